// POSIX implementation of the write-then-rename protocol: mkstemps creates a uniquely named
// temporary in the target's directory, rename(2) replaces the target atomically. The temporaries
// alive at any moment are also listed in a fixed table of slots that the signal handler reads: a
// handler may only call async-signal-safe functions (unlink, sigaction, raise) and must not
// touch std::string or the heap, so each slot is a char buffer guarded by a lock-free atomic
// state. The handler covers every signal whose default action ends the process and that can be
// caught; after removing the temporaries it restores the default action and raises the signal
// again, so the process ends exactly as it would have without cloudvis's handler.
#include "AtomicFile.h"

#include "Errors.h"
#include "FileNames.h"

#include <algorithm>
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

// The signals whose default action ends the process (signal(7): "Term" and "Core") and that a
// handler can catch, apart from the real-time signals, which are added at run time. The first
// group is raised by the program's own faults (synchronously, in the faulting thread); blocking
// them is undefined, so ScopedSignalBlock leaves them alone.
constexpr int FaultSignals[] = { SIGILL, SIGTRAP, SIGABRT, SIGBUS, SIGFPE, SIGSEGV, SIGSYS };
constexpr int AsynchronousSignals[] = {
  SIGHUP,
  SIGINT,
  SIGQUIT,
  SIGUSR1,
  SIGUSR2,
  SIGPIPE,
  SIGALRM,
  SIGTERM,
  SIGXCPU,
  SIGXFSZ,
  SIGVTALRM,
  SIGPROF,
  SIGIO,
#ifdef SIGSTKFLT
  SIGSTKFLT,
#endif
#ifdef SIGPWR
  SIGPWR,
#endif
};

// The asynchronous signals and the real-time ones (SIGRTMIN..SIGRTMAX: the C library keeps a
// few below SIGRTMIN for itself, and SIGRTMIN is a function call there, hence at run time).
sigset_t AsynchronousSignalSet()
{
  sigset_t set;
  sigemptyset(&set);
  for (int signal : AsynchronousSignals)
  {
    sigaddset(&set, signal);
  }
  for (int signal = SIGRTMIN; signal <= SIGRTMAX; ++signal)
  {
    sigaddset(&set, signal);
  }
  return set;
}

extern "C" void RemoveTemporariesAndReraise(int signal)
{
  for (Slot& slot : Slots)
  {
    if (slot.State.load() == Registered)
    {
      ::unlink(slot.Path);
    }
  }
  // End as the default action would: the parent sees "killed by signal" (a shell's $? is
  // 128 + signal), and a core-dumping signal still dumps core. The signal is blocked while its
  // handler runs, so it is unblocked for the raise to take effect at once.
  struct sigaction defaultAction;
  std::memset(&defaultAction, 0, sizeof(defaultAction));
  defaultAction.sa_handler = SIG_DFL;
  sigemptyset(&defaultAction.sa_mask);
  ::sigaction(signal, &defaultAction, nullptr);
  sigset_t only;
  sigemptyset(&only);
  sigaddset(&only, signal);
  ::pthread_sigmask(SIG_UNBLOCK, &only, nullptr);
  ::raise(signal);
  ::_exit(128 + signal); // not reached: every signal handled here ends the process by default
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

// Blocks the asynchronous signals in this thread for its lifetime: between mkstemps creating the
// temporary and its registration, a signal would otherwise leave it behind.
class ScopedSignalBlock
{
public:
  ScopedSignalBlock()
  {
    const sigset_t block = AsynchronousSignalSet();
    pthread_sigmask(SIG_BLOCK, &block, &this->Previous);
  }
  ~ScopedSignalBlock() { pthread_sigmask(SIG_SETMASK, &this->Previous, nullptr); }
  ScopedSignalBlock(const ScopedSignalBlock&) = delete;
  ScopedSignalBlock& operator=(const ScopedSignalBlock&) = delete;

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

// The mkstemps pattern of a target's temporary: DIRECTORY/.NAME.tmp-XXXXXX.EXT, hidden, and named
// after the target so that a leftover from a killed process is recognisable, with the target's
// extension for writers that look at it. The temporary's name must fit the directory's file-name
// limit (pathconf _PC_NAME_MAX, 255 bytes on most file systems) however long the target's name
// is, so NAME is shortened as far as needed (at a UTF-8 character boundary), and EXT is dropped
// when it alone would not fit; XXXXXX keeps the name unique.
struct TemporaryName
{
  std::string Pattern;
  int SuffixLength; // the characters after XXXXXX
};
TemporaryName TemporaryNameFor(const std::string& directory, const std::string& name)
{
  const long limit = ::pathconf(directory.c_str(), _PC_NAME_MAX);
  const std::size_t nameMax = limit > 0 ? std::size_t(limit) : std::size_t(NAME_MAX);
  const std::string marker = ".tmp-XXXXXX";
  const auto dot = name.find_last_of('.');
  std::string extension = dot == std::string::npos || dot == 0 ? "" : name.substr(dot);
  if (1 + marker.size() + extension.size() > nameMax)
  {
    extension.clear();
  }
  const std::size_t fixed = 1 + marker.size() + extension.size();
  std::size_t kept = std::min(name.size(), nameMax > fixed ? nameMax - fixed : 0);
  // Not in the middle of a multi-byte character: back off over continuation bytes.
  while (kept > 0 && kept < name.size() && (static_cast<unsigned char>(name[kept]) & 0xC0) == 0x80)
  {
    --kept;
  }
  return { directory + "/." + name.substr(0, kept) + marker + extension, int(extension.size()) };
}

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
    std::vector<int> signals(std::begin(FaultSignals), std::end(FaultSignals));
    signals.insert(signals.end(), std::begin(AsynchronousSignals), std::end(AsynchronousSignals));
    for (int signal = SIGRTMIN; signal <= SIGRTMAX; ++signal)
    {
      signals.push_back(signal);
    }
    struct sigaction action;
    std::memset(&action, 0, sizeof(action));
    action.sa_handler = RemoveTemporariesAndReraise;
    // One cleanup at a time: another signal arriving during it waits, and is moot once the
    // process ends.
    action.sa_mask = AsynchronousSignalSet();
    for (int signal : signals)
    {
      struct sigaction previous;
      // A signal that is ignored (nohup, a background job of a non-interactive shell) stays
      // ignored, and one that someone else handles (a sanitizer's SIGSEGV handler, libFuzzer's)
      // keeps its handler.
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

void ForgetTemporariesInChild()
{
  for (Slot& slot : Slots)
  {
    slot.State.store(Free);
  }
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
  const TemporaryName name = TemporaryNameFor(directory, FileNameOf(target));
  std::vector<char> buffer(name.Pattern.begin(), name.Pattern.end());
  buffer.push_back('\0');
  InstallInterruptCleanup();
  int fd = -1;
  std::unique_ptr<TemporaryFile> created;
  {
    ScopedSignalBlock noSignalUntilRegistered;
    fd = ::mkstemps(buffer.data(), name.SuffixLength);
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
