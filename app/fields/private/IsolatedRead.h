// The second of the layers that stand between a hostile field file and the cloudvis process
// (VtkXmlImageFiles.cxx describes all three): the libraries that parse field files (VTK's XML
// readers, the netCDF and HDF5 C libraries, OpenVDB) trust the file, and crafted headers make
// them crash, loop or allocate without bound. Every reader that hands a file to such a library
// therefore runs in a forked child under an address-space and a time limit (NRRD, MetaImage and
// raw files are parsed and decoded by cloudvis itself, in its own process, every size checked
// before it is allocated: StoredValues.cxx), and the child sends what it read (the image:
// geometry and point arrays; the array to use; the report) back through a pipe. A crash, a hang or a runaway allocation ends the child, not cloudvis, and becomes an
// InputError; the library never parses the file in the cloudvis process, and the file is read
// once.
#ifndef cloudvis_IsolatedRead_h
#define cloudvis_IsolatedRead_h

#include "FieldIO.h" // FieldFileContents

#include <cstdint>
#include <functional>
#include <string>

namespace cloudvis
{

// Runs `read` in a forked child limited to the memory this process may still take and to
// 60 s + 1 s per 10 MiB of `fileBytes` (the environment variable CLOUDVIS_READ_SECONDS replaces
// the 60 s: the fuzz targets set it below libFuzzer's own time limit), and returns what it
// returned. Throws InputError: the child's own (an ordinary refusal, in the reader's words), or
// naming `path` and `parser` ("VTK's reader", "OpenVDB's reader") when the child crashed, ran out
// of time or ran out of memory. Without fork() (or when it fails) `read` runs here.
FieldFileContents ReadInIsolation(const std::string& path,
  std::uint64_t fileBytes,
  const std::string& parser,
  const std::function<FieldFileContents()>& read);

// True inside the child of ReadInIsolation. The child has a thread pool of its own (TBB's
// workers are ended before the fork), but its limits are tight and its results are copied, so
// code that chooses between serial and threaded loops runs serial there; and the memory checks
// count the copy the parent receives.
bool InIsolatedRead();

// In the child: what the file needs to be read, as a reader computed it from the file's
// dimensions before allocating ("a field of 1024 x 1024 x 3072 voxels", in bytes; the largest
// noted counts). When the child then runs out of memory, the parent's message says it, beside
// what was available. Nothing outside the child.
void NoteReadNeeds(const std::string& what, double bytes);

} // namespace cloudvis

#endif
