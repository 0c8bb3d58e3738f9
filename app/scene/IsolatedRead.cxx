// The forked, resource-limited first read of a field file (IsolatedRead.h says why). The child's
// exit status says how its read ended; a signal or another status is a failure the parent
// reports without reading the file itself.
#include "IsolatedRead.h"

#include "AtomicFile.h"
#include "Errors.h"

#include "CloudFieldGeometry.h" // AvailableMemoryBytes, FormatBytes

#include <oneapi/tbb/global_control.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <new>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace cloudvis
{
namespace
{

// How the child ends; any other exit status, or a signal, is a failure.
constexpr int ChildReadCleanly = 0;
constexpr int ChildRefused = 3; // an ordinary error: the parent reads and reports it
constexpr int ChildOutOfMemory = 4;

bool InChild = false;

[[noreturn]] void Fail(const std::string& path, const std::string& problem)
{
  throw InputError(path + ": " + problem);
}

// In the child: the memory limit, then the read.
[[noreturn]] void RunChild(unsigned seconds, const std::function<void()>& read)
{
  InChild = true;
  // The temporaries of an export in progress are the parent's: a signal ending the child (the
  // alarm below) must not remove them.
  ForgetTemporariesInChild();
#if !defined(__SANITIZE_ADDRESS__)
  // The child may use what the process already maps plus the memory still available, so a
  // header claiming more fails here as an allocation, not in the parent as an OOM kill.
  // (AddressSanitizer reserves terabytes of shadow memory, so its builds skip the limit.)
  std::uint64_t mapped = 0;
  std::ifstream status("/proc/self/status");
  for (std::string key; status >> key;)
  {
    if (key == "VmSize:")
    {
      status >> mapped;
      mapped *= 1024u;
      break;
    }
  }
  const std::uint64_t available = AvailableMemoryBytes();
  if (mapped > 0 && available > 0)
  {
    const rlimit memory{ rlim_t(mapped + available), rlim_t(mapped + available) };
    ::setrlimit(RLIMIT_AS, &memory);
  }
#endif
  ::alarm(seconds);
  int code = ChildReadCleanly;
  try
  {
    read();
  }
  catch (const std::bad_alloc&)
  {
    code = ChildOutOfMemory;
  }
  catch (...)
  {
    code = ChildRefused;
  }
  ::_exit(code);
}

} // namespace

bool InIsolatedRead()
{
  return InChild;
}

void ProbeReadInIsolation(const std::string& path,
  std::uint64_t fileBytes,
  const std::string& parser,
  const std::function<void()>& read)
{
  const unsigned seconds = 60u + unsigned(fileBytes / (10u << 20)); // 60 s + 1 s per 10 MiB
  // A child inherits TBB's thread pool without its threads, and the first parallel loop it runs
  // (OpenVDB frees a tree with one) waits for them forever. So the pool's threads are ended
  // first; TBB starts new ones when this process next needs them.
  {
    oneapi::tbb::task_scheduler_handle scheduler{ oneapi::tbb::attach{} };
    // False when another part of the process holds the pool (none of cloudvis does): then the
    // child's time limit is what ends a wait.
    oneapi::tbb::finalize(scheduler, std::nothrow);
  }
  const pid_t child = ::fork();
  if (child < 0)
  {
    return; // no isolation to be had: read directly, behind the other checks alone
  }
  if (child == 0)
  {
    RunChild(seconds, read);
  }
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR)
  {
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == ChildReadCleanly || code == ChildRefused)
  {
    return; // read it here; an ordinary error is then reported in its own words
  }
  if (code == ChildOutOfMemory)
  {
    Fail(path,
      parser + " ran out of memory on this file: it claims more than the " +
        FormatBytes(double(AvailableMemoryBytes())) + " available");
  }
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
  {
    Fail(path,
      parser + " took longer than " + std::to_string(seconds) +
        " s on this file without finishing: it is malformed");
  }
  if (WIFSIGNALED(status))
  {
    Fail(path,
      parser + " crashed on this file (" + std::string(strsignal(WTERMSIG(status))) +
        "): it is malformed");
  }
  // Another status: a sanitizer (in sanitized builds) caught the library doing something fatal.
  Fail(path,
    parser + " failed on this file (exit status " + std::to_string(code) + "): it is malformed");
}

} // namespace cloudvis
