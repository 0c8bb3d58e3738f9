// What the three fuzz targets share: the bytes of one input written to a file of this process,
// for entry points that take a path (a scene file, a .vti), exactly as the command line would
// hand them over. The file lives in $TMPDIR (else /tmp), is named after the process so parallel
// fuzzing jobs do not meet, and is removed when the process exits.
#ifndef cloudvis_FuzzInput_h
#define cloudvis_FuzzInput_h

#include <cstddef>
#include <cstdint>
#include <string>

namespace cloudvis
{
namespace fuzz
{

// Writes `size` bytes to this process's input file with the given extension (".json", ".vti")
// and returns its path. Aborts when the file cannot be written: a fuzz run that cannot feed its
// input must stop, not report every input as harmless.
const std::string& WriteInputFile(const char* extension, const std::uint8_t* data, std::size_t size);

} // namespace fuzz
} // namespace cloudvis

// The libFuzzer entry point every target defines; FuzzReplay.cxx calls it on files.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

#endif
