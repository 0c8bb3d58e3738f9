// The second of the layers that stand between a hostile field file and the cloudvis process
// (VtkXmlImageFiles.cxx describes all three): the libraries that parse field files (VTK's
// readers, the netCDF and HDF5 libraries under VTK's NetCDF reader, MetaIO, OpenVDB) trust the
// file, and crafted headers make them crash, loop or allocate without bound. Every reader therefore
// runs its own read function first in a forked child under an address-space and a time limit; a
// crash, a hang or a runaway allocation ends the child, not cloudvis, and becomes an InputError.
// Only a file the child read to the end (or refused with an ordinary error) is then read in this
// process, by the same function. The cost is reading a field twice.
#ifndef cloudvis_IsolatedRead_h
#define cloudvis_IsolatedRead_h

#include <cstdint>
#include <functional>
#include <string>

namespace cloudvis
{

// Runs `read` in a forked child limited to the memory this process may still take and to
// 60 s + 1 s per 10 MiB of `fileBytes`. Returns when the child returned from `read` or threw
// (then the caller runs `read` itself and gets the same error in its own words); throws
// InputError naming `path` and `parser` ("VTK's reader", "OpenVDB") when the child crashed, ran
// out of time or ran out of memory. Without fork() (or when it fails) it returns at once: the
// caller's own size checks then stand alone.
void ProbeReadInIsolation(const std::string& path,
  std::uint64_t fileBytes,
  const std::string& parser,
  const std::function<void()>& read);

// True inside the child of ProbeReadInIsolation. The child has a thread pool of its own (TBB's
// workers are ended before the fork), but its limits are tight and its work thrown away, so code
// that chooses between serial and threaded loops runs serial there.
bool InIsolatedRead();

} // namespace cloudvis

#endif
