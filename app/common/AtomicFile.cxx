// POSIX implementation of the write-then-rename protocol: mkstemps creates a uniquely named
// temporary in the target's directory, rename(2) replaces the target atomically. The temporaries
// alive at any moment are also listed in a fixed table of slots that the SIGINT/SIGTERM handler
// reads: a handler may only call async-signal-safe functions (unlink, _exit) and must not touch
// std::string or the heap, so each slot is a char buffer guarded by a lock-free atomic state.
#include "AtomicFile.h"

#include "Errors.h"

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace cloudvis
{
namespace
{

std::string DirectoryOf(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos)
  {
    return ".";
  }
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string SystemReason()
{
  return std::strerror(errno);
}

// ---- temporaries the signal handler removes -----------------------------------------------
// A slot is Free, being Claimed by a thread that is copying a path in, or Registered (the
// handler unlinks its path). More temporaries alive at once than slots (several threads
// exporting concurrently) are simply not registered: their cleanup on a signal is lost, nothing
// else.
constexpr int SlotCount = 8;
enum SlotState : int
{
  Free,
  Claimed,
  Registered
};
struct Slot
{
  std::atomic<int> State{ Free };
  char Path[PATH_MAX] = {};
};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");
Slot Slots[SlotCount];

extern "C" void RemoveTemporariesAndExit(int signal)
{
  for (Slot& slot : Slots)
  {
    if (slot.State.load() == Registered)
    {
      ::unlink(slot.Path);
    }
  }
  ::_exit(128 + signal);
}

// Returns the slot now holding `path`, or -1 when none is free or the path does not fit.
int RegisterTemporary(const char* path)
{
  const size_t length = std::strlen(path);
  if (length >= PATH_MAX)
  {
    return -1;
  }
  for (int i = 0; i < SlotCount; ++i)
  {
    int expected = Free;
    if (Slots[i].State.compare_exchange_strong(expected, Claimed))
    {
      std::memcpy(Slots[i].Path, path, length + 1);
      Slots[i].State.store(Registered); // publishes the path to the handler
      return i;
    }
  }
  return -1;
}

void UnregisterTemporary(int slot)
{
  if (slot >= 0)
  {
    Slots[slot].State.store(Free);
  }
}

// Blocks SIGINT and SIGTERM in this thread for its lifetime: between mkstemps creating the
// temporary and its registration, a signal would otherwise leave it behind.
class ScopedInterruptBlock
{
public:
  ScopedInterruptBlock()
  {
    sigset_t block;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &block, &this->Previous);
  }
  ~ScopedInterruptBlock() { pthread_sigmask(SIG_SETMASK, &this->Previous, nullptr); }
  ScopedInterruptBlock(const ScopedInterruptBlock&) = delete;
  ScopedInterruptBlock& operator=(const ScopedInterruptBlock&) = delete;

private:
  sigset_t Previous;
};

// Removes the temporary unless it has been renamed: covers exceptions from the writer as well as
// our own failures. Registered for the signal handler while it exists.
class TemporaryFile
{
public:
  explicit TemporaryFile(std::string path)
    : Path(std::move(path))
    , SlotIndex(RegisterTemporary(this->Path.c_str()))
  {
  }
  ~TemporaryFile()
  {
    if (!this->Path.empty())
    {
      std::remove(this->Path.c_str());
    }
    // After the removal: a signal in between unlinks a name that is already gone, harmlessly.
    UnregisterTemporary(this->SlotIndex);
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  // Called once the temporary has been renamed over the target: nothing left to remove.
  void Release()
  {
    this->Path.clear();
    UnregisterTemporary(this->SlotIndex);
    this->SlotIndex = -1;
  }
  const std::string& GetPath() const { return this->Path; }

private:
  std::string Path;
  int SlotIndex;
};

// mkstemps creates files readable only by their owner; a finished output should get the
// permissions an ordinary new file would (or keep those of the file it replaces).
mode_t FinalMode(const std::string& target)
{
  struct stat existing;
  if (::stat(target.c_str(), &existing) == 0)
  {
    return existing.st_mode & 07777;
  }
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

} // namespace

void InstallInterruptCleanup()
{
  static const bool installed = []
  {
    struct sigaction action;
    std::memset(&action, 0, sizeof(action));
    action.sa_handler = RemoveTemporariesAndExit;
    sigemptyset(&action.sa_mask);
    // One handler at a time: a SIGTERM arriving during the SIGINT cleanup waits for it.
    sigaddset(&action.sa_mask, SIGINT);
    sigaddset(&action.sa_mask, SIGTERM);
    for (int signal : { SIGINT, SIGTERM })
    {
      struct sigaction previous;
      // A signal that is ignored (nohup, a background job of a non-interactive shell) stays
      // ignored, and one that someone else handles keeps its handler.
      if (::sigaction(signal, nullptr, &previous) == 0 && previous.sa_handler == SIG_DFL &&
        !(previous.sa_flags & SA_SIGINFO))
      {
        ::sigaction(signal, &action, nullptr);
      }
    }
    return true;
  }();
  (void)installed;
}

void CheckOutputTarget(const std::string& target)
{
  if (target.empty())
  {
    throw InputError("the output path is empty");
  }
  const std::string directory = DirectoryOf(target);
  struct stat info;
  if (::stat(directory.c_str(), &info) != 0)
  {
    throw InputError(target + ": cannot write: directory " + directory + " does not exist (" +
      SystemReason() + ")");
  }
  if (!S_ISDIR(info.st_mode))
  {
    throw InputError(target + ": cannot write: " + directory + " is not a directory");
  }
  if (::access(directory.c_str(), W_OK | X_OK) != 0)
  {
    throw InputError(
      target + ": cannot write: directory " + directory + " is not writable (" + SystemReason() + ")");
  }
  if (::stat(target.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
  {
    throw InputError(target + ": cannot write: it is a directory");
  }
}

void WriteFileAtomically(
  const std::string& target, const std::function<void(const std::string& temporaryPath)>& write)
{
  CheckOutputTarget(target);
  const std::string directory = DirectoryOf(target);
  const auto slash = target.find_last_of('/');
  const std::string name = slash == std::string::npos ? target : target.substr(slash + 1);
  const auto dot = name.find_last_of('.');
  const std::string extension = dot == std::string::npos || dot == 0 ? "" : name.substr(dot);
  // Hidden, and named after the target, so a leftover from a killed process is recognisable.
  std::string pattern = directory + "/." + name + ".tmp-XXXXXX" + extension;
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  InstallInterruptCleanup();
  int fd = -1;
  std::unique_ptr<TemporaryFile> created;
  {
    ScopedInterruptBlock noInterruptUntilRegistered;
    fd = ::mkstemps(buffer.data(), static_cast<int>(extension.size()));
    if (fd < 0)
    {
      throw InputError(target + ": cannot create a temporary file in " + directory + " (" +
        SystemReason() + ")");
    }
    created = std::make_unique<TemporaryFile>(buffer.data());
  }
  TemporaryFile& temporary = *created;
  const mode_t mode = FinalMode(target);
  const bool modeSet = ::fchmod(fd, mode) == 0;
  ::close(fd);
  if (!modeSet)
  {
    throw InputError(target + ": cannot set permissions of the temporary file " +
      temporary.GetPath() + " (" + SystemReason() + ")");
  }

  write(temporary.GetPath());

  struct stat written;
  if (::stat(temporary.GetPath().c_str(), &written) != 0)
  {
    throw InputError(target + ": the writer left no file behind (" + SystemReason() + ")");
  }
  if (::rename(temporary.GetPath().c_str(), target.c_str()) != 0)
  {
    throw InputError(target + ": cannot replace the target (" + SystemReason() + ")");
  }
  temporary.Release();
}

} // namespace cloudvis
