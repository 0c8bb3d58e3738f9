// What the fuzz targets share: the bytes of one input written to files of this process, for
// entry points that take a path (a scene file, a .vti, a .pvti and its pieces), exactly as the
// command line would hand them over. The files live in a directory of their own,
// $TMPDIR/cloudvis-fuzz-PID (else /tmp/...), so parallel fuzzing jobs do not meet and a .pvti can
// name its pieces relative to itself; the directory is removed when the process exits.
#ifndef cloudvis_FuzzInput_h
#define cloudvis_FuzzInput_h

#include <cstddef>
#include <cstdint>
#include <string>

namespace cloudvis
{
namespace fuzz
{

// Writes `size` bytes to the file `name` ("input.vti", "piece-1.vti") of this process's input
// directory and returns its path. Aborts when the file cannot be written: a fuzz run that cannot
// feed its input must stop, not report every input as harmless.
std::string WriteInputFile(const std::string& name, const std::uint8_t* data, std::size_t size);

// Removes the file `name` of the input directory, if it exists.
void RemoveInputFile(const std::string& name);

} // namespace fuzz
} // namespace cloudvis

// The libFuzzer entry point every target defines; FuzzReplay.cxx calls it on files.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

#endif
