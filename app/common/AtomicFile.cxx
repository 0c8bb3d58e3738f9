// POSIX implementation of the write-then-rename protocol: mkstemps creates a uniquely named
// temporary in the target's directory, rename(2) replaces the target atomically. The temporaries
// alive at any moment are also listed in a fixed table of slots that the signal handler reads: a
// handler may only call async-signal-safe functions (unlink, sigaction, raise) and must not
// touch std::string or the heap, so each slot is a char buffer guarded by a lock-free atomic
// state. The handler covers every signal whose default action ends the process and that can be
// caught; after removing the temporaries it restores the default action and raises the signal
// again, so the process ends exactly as it would have without cloudvis's handler. The
// temporaries of a group replaced together (TemporaryGroup) live in one hidden directory whose
// members the handler names from a pattern, so a group may hold any number of them. During an
// InterruptionHold the handler records an asynchronous signal instead, and the hold's end acts
// on it.
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
#include <fcntl.h>
#include <memory>
#include <ostream>
#include <pthread.h>
#include <streambuf>
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

// A group's directory and the pattern of its members' names (TemporaryGroup): members
// PREFIX<i>SUFFIX for i < Count, and EXTRA; registered like a slot.
struct GroupSlot
{
  std::atomic<int> State{ Free };
  char Directory[PATH_MAX] = {};
  char Prefix[NAME_MAX + 1] = {};
  char Suffix[NAME_MAX + 1] = {};
  char Extra[NAME_MAX + 1] = {};
  long Count = 0;
};
GroupSlot Groups[4];

// The hold (InterruptionHold): while HoldDepth > 0 an asynchronous signal is recorded in
// HeldSignal instead of acted on; whichever of the handler and the hold's end finds the depth 0
// afterwards takes the recorded signal (exchange) and acts on it, so none is lost or acted on
// twice, whatever thread the kernel gave it to.
std::atomic<int> HoldDepth{ 0 };
std::atomic<int> HeldSignal{ 0 };

// The signals whose default action ends the process (signal(7): "Term" and "Core") and that a
// handler can catch, apart from the real-time signals, which are added at run time. The first
// group is raised by the program's own faults (synchronously, in the faulting thread): returning
// from their handler would fault again, so they are never held.
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

// Appends `text` to `path` (of `capacity` bytes, NUL-terminated) without allocating; false
// when it does not fit.
bool AppendSafely(char* path, std::size_t capacity, const char* text)
{
  std::size_t length = 0;
  while (length < capacity && path[length])
  {
    ++length;
  }
  for (; *text; ++text, ++length)
  {
    if (length + 1 >= capacity)
    {
      return false;
    }
    path[length] = *text;
  }
  path[length] = '\0';
  return true;
}

// Removes a group's members and its directory, async-signal-safely: unlink and rmdir, names
// built in a buffer on the stack. A member another process creates meanwhile makes rmdir fail:
// then again, a few times; once the directory is gone, nothing can be created in it.
void RemoveGroup(const GroupSlot& group)
{
  for (int attempt = 0; attempt < 5; ++attempt)
  {
    char path[PATH_MAX];
    for (long i = -1; i < group.Count; ++i)
    {
      path[0] = '\0';
      bool fits =
        AppendSafely(path, sizeof(path), group.Directory) && AppendSafely(path, sizeof(path), "/");
      if (i < 0)
      {
        fits = fits && AppendSafely(path, sizeof(path), group.Extra);
      }
      else
      {
        char digits[24];
        int n = 0;
        for (long v = i; n == 0 || v > 0; v /= 10)
        {
          digits[n++] = char('0' + v % 10);
        }
        char number[24];
        for (int d = 0; d < n; ++d)
        {
          number[d] = digits[n - 1 - d];
        }
        number[n] = '\0';
        fits = fits && AppendSafely(path, sizeof(path), group.Prefix) &&
          AppendSafely(path, sizeof(path), number) &&
          AppendSafely(path, sizeof(path), group.Suffix);
      }
      if (fits)
      {
        ::unlink(path);
      }
    }
    if (::rmdir(group.Directory) == 0 || errno != ENOTEMPTY)
    {
      return;
    }
  }
}

// Called by the handler, and by the end of a hold that recorded a signal.
void RemoveTemporariesAndReraise(int signal)
{
  for (Slot& slot : Slots)
  {
    if (slot.State.load() == Registered)
    {
      ::unlink(slot.Path);
    }
  }
  for (GroupSlot& group : Groups)
  {
    if (group.State.load() == Registered)
    {
      RemoveGroup(group);
    }
  }
  // End as the default action would: the parent sees "killed by signal" (a shell's $? is
  // 128 + signal), and a core-dumping signal still dumps core. The signal is blocked while its
  // handler runs, so it is unblocked for the raise to take effect at once. pthread_sigmask, not
  // sigprocmask: both are async-signal-safe (signal-safety(7): pthread_sigmask since POSIX.1-2008
  // TC1), but sigprocmask is unspecified in a multi-threaded process (VTK's and MPI's threads),
  // and the mask to change is this thread's, which the kernel blocked the signal in.
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

bool IsFaultSignal(int signal)
{
  for (int fault : FaultSignals)
  {
    if (signal == fault)
    {
      return true;
    }
  }
  return false;
}

extern "C" void OnTerminatingSignal(int signal)
{
  if (!IsFaultSignal(signal) && HoldDepth.load() > 0)
  {
    int none = 0;
    HeldSignal.compare_exchange_strong(none, signal); // the first signal held is acted on
    if (HoldDepth.load() > 0)
    {
      return;
    }
    // The hold ended meanwhile, perhaps before the signal was recorded: act unless it did.
    signal = HeldSignal.exchange(0);
    if (signal == 0)
    {
      return;
    }
  }
  RemoveTemporariesAndReraise(signal);
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
// extension for writers that look at it (a group's directory takes the group's TAG for XXXXXX,
// and no extension). The temporary's name must fit the directory's file-name
// limit (pathconf _PC_NAME_MAX, 255 bytes on most file systems) however long the target's name
// is, so NAME is shortened as far as needed (at a UTF-8 character boundary), and EXT is dropped
// when it alone would not fit; XXXXXX keeps the name unique.
struct TemporaryName
{
  std::string Pattern;
  int SuffixLength; // the characters after XXXXXX
};
TemporaryName TemporaryNameFor(const std::string& directory,
  const std::string& name,
  const std::string& tag = "XXXXXX",
  bool keepExtension = true)
{
  const long limit = ::pathconf(directory.c_str(), _PC_NAME_MAX);
  const std::size_t nameMax = limit > 0 ? std::size_t(limit) : std::size_t(NAME_MAX);
  const std::string marker = ".tmp-" + tag;
  const auto dot = name.find_last_of('.');
  std::string extension =
    dot == std::string::npos || dot == 0 || !keepExtension ? "" : name.substr(dot);
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

// The file a write to `target` replaces: `target` itself, or, when it is a symbolic link, the
// file at the end of its chain of links (which need not exist yet: a dangling link names the
// file to create). An output is written through links, as editors and `sed -i
// --follow-symlinks` do, so the link stays a link and the file it names gets the content.
std::string FileBehindLinks(const std::string& target)
{
  std::string path = target;
  for (int depth = 0; depth < 40; ++depth) // Linux's own limit (MAXSYMLINKS)
  {
    struct stat info;
    if (::lstat(path.c_str(), &info) != 0 || !S_ISLNK(info.st_mode))
    {
      return path;
    }
    std::vector<char> link(std::size_t(info.st_size > 0 ? info.st_size : PATH_MAX) + 1);
    const ssize_t length = ::readlink(path.c_str(), link.data(), link.size());
    if (length < 0 || std::size_t(length) >= link.size())
    {
      throw InputError(target + ": cannot read the symbolic link " + path + " (" +
        (length < 0 ? SystemReason() : "it changed while being read") + ")");
    }
    const std::string next(link.data(), std::size_t(length));
    path = next[0] == '/' ? next : DirectoryOf(path) + "/" + next;
  }
  throw InputError(target + ": cannot write: too many levels of symbolic links");
}

// The stream buffer of a file being written (CheckedOutput): a buffer flushed with write(2),
// every call checked and retried after a short write or EINTR, and seekable (OpenVDB and VTK go
// back to fill in offsets). The first failure is kept with its errno; from then on nothing more
// is written, and the stream the writer holds goes bad, so a writer that checks its stream stops
// and one that does not (OpenVDB's) cannot leave a file that looks whole: Finish reports it.
class CheckedBuffer : public std::streambuf
{
public:
  explicit CheckedBuffer(int fd)
    : Descriptor(fd)
    , Buffer(std::size_t(1) << 20)
  {
    this->setp(this->Buffer.data(), this->Buffer.data() + this->Buffer.size());
  }
  CheckedBuffer(const CheckedBuffer&) = delete;
  CheckedBuffer& operator=(const CheckedBuffer&) = delete;

  int Error = 0;          // the errno of the first failure, 0 while there is none
  std::string FailedCall; // the call that failed: "write", "seek"
  off_t End = 0;          // the end of the data written so far (what the file's size must be)

protected:
  int_type overflow(int_type c) override
  {
    if (!this->Drain())
    {
      return traits_type::eof();
    }
    if (!traits_type::eq_int_type(c, traits_type::eof()))
    {
      *this->pptr() = traits_type::to_char_type(c);
      this->pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return this->Drain() ? 0 : -1; }
  pos_type seekoff(off_type offset, std::ios_base::seekdir way, std::ios_base::openmode) override
  {
    if (way == std::ios_base::cur && offset == 0 && this->Error == 0)
    {
      return pos_type(this->Position + (this->pptr() - this->pbase())); // tellp: no flush
    }
    if (!this->Drain())
    {
      return pos_type(off_type(-1));
    }
    const int whence = way == std::ios_base::beg ? SEEK_SET
      : way == std::ios_base::cur                ? SEEK_CUR
                                                 : SEEK_END;
    const off_t at = ::lseek(this->Descriptor, off_t(offset), whence);
    if (at < 0)
    {
      this->Fail("seek");
      return pos_type(off_type(-1));
    }
    this->Position = at;
    return pos_type(at);
  }
  pos_type seekpos(pos_type position, std::ios_base::openmode which) override
  {
    return this->seekoff(off_type(position), std::ios_base::beg, which);
  }

private:
  // Writes out the buffer; false once anything has failed.
  bool Drain()
  {
    const char* at = this->pbase();
    const char* end = this->pptr();
    while (this->Error == 0 && at < end)
    {
      const ssize_t written = ::write(this->Descriptor, at, std::size_t(end - at));
      if (written < 0 && errno == EINTR)
      {
        continue;
      }
      if (written <= 0)
      {
        if (written == 0)
        {
          errno = ENOSPC; // write(2) returns 0 for a non-empty request only when nothing fits
        }
        this->Fail("write");
        break;
      }
      at += written;
      this->Position += written;
      this->End = std::max(this->End, this->Position);
    }
    this->setp(this->Buffer.data(), this->Buffer.data() + this->Buffer.size());
    return this->Error == 0;
  }
  void Fail(const char* call)
  {
    if (this->Error == 0)
    {
      this->Error = errno != 0 ? errno : EIO;
      this->FailedCall = call;
    }
  }

  int Descriptor;
  std::vector<char> Buffer;
  off_t Position = 0; // the file offset of the buffer's first byte
};

// Writes a file through a CheckedBuffer and finishes it: the final flush, fsync (so that a
// write-back error the kernel reports late, as NFS and quotas do, is seen before the rename),
// the file's size against the bytes written, and close, each checked. Every failure is an
// InputError "TARGET: cannot write WHAT: REASON" naming the OS reason (strerror).
void WriteChecked(int fd,
  const std::string& target,
  const std::string& what,
  const std::function<void(std::ostream& out)>& write)
{
  struct Closer
  {
    int& Fd;
    ~Closer()
    {
      if (this->Fd >= 0)
      {
        ::close(this->Fd);
      }
    }
  } closer{ fd };
  const auto fail = [&](const std::string& reason)
  { throw InputError(target + ": cannot write " + what + ": " + reason); };
  CheckedBuffer buffer(fd);
  std::ostream out(&buffer);
  const auto osFailure = [&]
  {
    return buffer.Error == 0 ? std::string()
                             : std::strerror(buffer.Error) +
        (buffer.FailedCall == "write" ? std::string() : " (" + buffer.FailedCall + ")");
  };
  try
  {
    write(out);
  }
  catch (const std::bad_alloc&)
  {
    throw;
  }
  catch (const std::exception&)
  {
    // The writer's own complaint ("cannot write the field") is the consequence; the OS reason,
    // when there is one, is the cause.
    if (buffer.Error != 0)
    {
      fail(osFailure());
    }
    throw;
  }
  out.flush();
  if (buffer.Error != 0)
  {
    fail(osFailure());
  }
  if (!out)
  {
    fail("the writer's stream failed");
  }
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) // EINVAL: fsync is not offered
  {
    fail(SystemReason() + " (fsync)");
  }
  struct stat written;
  if (::fstat(fd, &written) != 0)
  {
    fail(SystemReason() + " (fstat)");
  }
  if (written.st_size != buffer.End)
  {
    fail("the file holds " + std::to_string(written.st_size) + " bytes of the " +
      std::to_string(buffer.End) + " written");
  }
  const int closing = fd;
  fd = -1;
  if (::close(closing) != 0)
  {
    fail(SystemReason() + " (close)");
  }
}

// A new temporary beside `file` (the file to replace), registered for removal; its descriptor
// is left open in `fd` with the final mode already set.
std::unique_ptr<TemporaryFile> CreateTemporary(const std::string& target,
  const std::string& file,
  int& fd)
{
  const std::string directory = DirectoryOf(file);
  const TemporaryName name = TemporaryNameFor(directory, FileNameOf(file));
  std::vector<char> buffer(name.Pattern.begin(), name.Pattern.end());
  buffer.push_back('\0');
  InstallInterruptCleanup();
  std::unique_ptr<TemporaryFile> created;
  {
    // Held process-wide, whichever thread the kernel gives a signal to.
    const InterruptionHold noSignalUntilRegistered;
    fd = ::mkstemps(buffer.data(), name.SuffixLength);
    if (fd < 0)
    {
      throw InputError(
        target + ": cannot create a temporary file in " + directory + " (" + SystemReason() + ")");
    }
    created = std::make_unique<TemporaryFile>(buffer.data());
  }
  if (::fchmod(fd, FinalMode(file)) != 0)
  {
    const std::string reason = SystemReason();
    ::close(fd);
    fd = -1;
    throw InputError(target + ": cannot set permissions of the temporary file " +
      created->GetPath() + " (" + reason + ")");
  }
  return created;
}

void Replace(TemporaryFile& temporary, const std::string& target, const std::string& file)
{
  if (::rename(temporary.GetPath().c_str(), file.c_str()) != 0)
  {
    throw InputError(target + ": cannot replace the target" +
      (file == target ? "" : " " + file + " it links to") + " (" + SystemReason() + ")");
  }
  temporary.Release();
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
    action.sa_handler = OnTerminatingSignal;
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
  for (GroupSlot& group : Groups)
  {
    group.State.store(Free);
  }
  HoldDepth.store(0);
  HeldSignal.store(0);
}

InterruptionHold::InterruptionHold()
{
  InstallInterruptCleanup();
  HoldDepth.fetch_add(1);
}

InterruptionHold::~InterruptionHold()
{
  if (HoldDepth.fetch_sub(1) == 1)
  {
    if (const int signal = HeldSignal.exchange(0))
    {
      RemoveTemporariesAndReraise(signal);
    }
  }
}

TemporaryGroup::TemporaryGroup(const std::string& target,
  const std::string& tag,
  bool create,
  const std::string& prefix,
  const std::string& suffix,
  long count,
  const std::string& extra)
{
  CheckOutputTarget(target);
  const std::string directory = DirectoryOf(target);
  this->Directory = TemporaryNameFor(directory, FileNameOf(target), tag, false).Pattern;
  if (this->Directory.size() >= PATH_MAX || prefix.size() > NAME_MAX || suffix.size() > NAME_MAX ||
    extra.size() > NAME_MAX)
  {
    throw InputError(target + ": the path of its temporary directory is too long");
  }
  // Between mkdir and the registration a signal would leave the directory behind.
  const InterruptionHold noSignalUntilRegistered;
  if (create && ::mkdir(this->Directory.c_str(), 0700) != 0)
  {
    throw InputError(target + ": cannot create the temporary directory " + this->Directory + " (" +
      SystemReason() + ")");
  }
  for (GroupSlot& group : Groups)
  {
    int expected = Free;
    if (group.State.compare_exchange_strong(expected, Claimed))
    {
      std::memcpy(group.Directory, this->Directory.c_str(), this->Directory.size() + 1);
      std::memcpy(group.Prefix, prefix.c_str(), prefix.size() + 1);
      std::memcpy(group.Suffix, suffix.c_str(), suffix.size() + 1);
      std::memcpy(group.Extra, extra.c_str(), extra.size() + 1);
      group.Count = count;
      group.State.store(Registered); // publishes it to the handler
      this->Registration = &group;
      break;
    }
  }
  if (!this->Registration)
  {
    if (create)
    {
      ::rmdir(this->Directory.c_str());
    }
    throw InputError(target + ": too many groups of files are being written at once");
  }
}

TemporaryGroup::~TemporaryGroup()
{
  for (const std::string& member : this->Created)
  {
    std::remove(member.c_str());
  }
  ::rmdir(
    this->Directory.c_str()); // fails while another process's members remain: the last removes it
  static_cast<GroupSlot*>(this->Registration)->State.store(Free);
}

std::string TemporaryGroup::Member(const std::string& name)
{
  const std::string path = this->Directory + "/" + name;
  this->Created.push_back(path);
  return path;
}

void TemporaryGroup::Commit(const std::string& name, const std::string& target)
{
  const std::string member = this->Directory + "/" + name;
  if (::rename(member.c_str(), FileBehindLinks(target).c_str()) != 0)
  {
    throw InputError(
      target + ": cannot replace the target with " + member + " (" + SystemReason() + ")");
  }
}

void CheckOutputTarget(const std::string& requested)
{
  if (requested.empty())
  {
    throw InputError("the output path is empty");
  }
  // The checks apply to the file that will be replaced: behind the links, if any.
  const std::string target = FileBehindLinks(requested);
  const std::string named = target == requested ? requested : requested + " (" + target + ")";
  const std::string directory = DirectoryOf(target);
  struct stat info;
  if (::stat(directory.c_str(), &info) != 0)
  {
    throw InputError(named + ": cannot write: directory " + directory + " does not exist (" +
      SystemReason() + ")");
  }
  if (!S_ISDIR(info.st_mode))
  {
    throw InputError(named + ": cannot write: " + directory + " is not a directory");
  }
  if (::access(directory.c_str(), W_OK | X_OK) != 0)
  {
    throw InputError(named + ": cannot write: directory " + directory + " is not writable (" +
      SystemReason() + ")");
  }
  if (::stat(target.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
  {
    throw InputError(named + ": cannot write: it is a directory");
  }
}

std::string OutputFileBehindLinks(const std::string& target)
{
  return FileBehindLinks(target);
}

void WriteStreamAtomically(const std::string& target,
  const std::string& what,
  const std::function<void(std::ostream& out)>& write)
{
  CheckOutputTarget(target);
  const std::string file = FileBehindLinks(target);
  int fd = -1;
  const std::unique_ptr<TemporaryFile> temporary = CreateTemporary(target, file, fd);
  WriteChecked(fd, target, what, write);
  Replace(*temporary, target, file);
}

void WriteNewFileChecked(const std::string& path,
  const std::string& target,
  const std::string& what,
  const std::function<void(std::ostream& out)>& write)
{
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0)
  {
    throw InputError(target + ": cannot create " + path + " (" + SystemReason() + ")");
  }
  if (::fchmod(fd, FinalMode(FileBehindLinks(target))) != 0)
  {
    const std::string reason = SystemReason();
    ::close(fd);
    throw InputError(target + ": cannot set permissions of " + path + " (" + reason + ")");
  }
  WriteChecked(fd, target, what, write);
}

} // namespace cloudvis
