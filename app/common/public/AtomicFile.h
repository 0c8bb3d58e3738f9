// Every file cloudvis writes (fields, PNG and EXR renders, saved scenes) goes through
// WriteStreamAtomically: the content is written to a temporary file next to the target (same
// directory, hence same filesystem) and renamed over the target only once it is complete.
// Complete means checked: every write(2), the final flush, fsync, the file's size against the
// bytes written, and close; any failure (a full disk) refuses the output with the OS reason
// ("x.vdb: cannot write the field as OpenVDB: No space left on device") and leaves the target
// as it was. There is no way to write by name: a library writing by name may not check its own
// writes (OpenVDB's io::File does not), so every writer writes to the stream.
// A target that is a symbolic link is written through: the file at the end of the link's chain
// is replaced (in its own directory), the link stays a link. A new file gets the mode an
// ordinary new file would (0666 less the umask), a replaced one keeps its own. A
// reader therefore never sees a half-written file, and a failed or interrupted export leaves the
// previous target untouched and no temporary behind. "Interrupted" means any signal whose
// default action ends the process and that can be caught (SIGHUP, SIGINT, SIGQUIT, SIGPIPE,
// SIGTERM, SIGUSR1, SIGALRM, SIGXFSZ, the real-time signals, and the fault signals SIGSEGV,
// SIGABRT, ...): while a temporary exists its path is registered where a signal handler can
// reach it without allocating or locking; the handler (installed on the first write, for each
// signal that is neither ignored nor already handled by someone else) unlinks the registered
// temporaries, restores the default action and raises the signal again, so the process ends by
// that signal (a shell reports 128 + signal: 129 for SIGHUP, 130 for SIGINT, 143 for SIGTERM).
// The temporary's name stays within the directory's file-name limit whatever the target's.
// Files replaced together (the pieces of a .pvti and the .pvti) are written into a
// TemporaryGroup and renamed by their owner once all are written, with interruptions held
// (InterruptionHold) so that no signal cuts the renames in two.
#ifndef cloudvis_AtomicFile_h
#define cloudvis_AtomicFile_h

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace cloudvis
{

// Throws InputError unless `target` can be written: its directory must exist and be writable,
// and the target itself must not be a directory. Called before any expensive work, so a bad -o
// fails in milliseconds rather than after the field has been generated.
void CheckOutputTarget(const std::string& target);

// The file a write to `target` replaces: `target`, or the end of its chain of symbolic links.
std::string OutputFileBehindLinks(const std::string& target);

// Calls write(out) with a stream onto a new temporary, checks the file as above, and renames it
// over `target` (behind its links). `what` completes the message "TARGET: cannot write WHAT:
// REASON" ("the field as OpenVDB"). The writer may seek (tellp, seekp). When the writer throws
// after a write failed, the OS reason is reported instead of the writer's message.
void WriteStreamAtomically(const std::string& target,
  const std::string& what,
  const std::function<void(std::ostream& out)>& write);

// The same checked writing onto a new file at `path` (a TemporaryGroup member) that its owner
// renames over `target` later; the file gets `target`'s final mode. Messages name `target`.
void WriteNewFileChecked(const std::string& path,
  const std::string& target,
  const std::string& what,
  const std::function<void(std::ostream& out)>& write);

// Holds back the asynchronous terminating signals (SIGINT, SIGTERM, SIGHUP, ..., not the fault
// signals) of the whole process while it lives, whichever thread the kernel delivers them to: a
// signal arriving meanwhile is recorded, not acted on, and when the last hold ends it is acted
// on as above (temporaries removed, the process ended by it). For the steps that must not be
// cut in two: creating and registering a temporary, renaming a group's members. Holds nest.
class InterruptionHold
{
public:
  InterruptionHold();
  ~InterruptionHold();
  InterruptionHold(const InterruptionHold&) = delete;
  InterruptionHold& operator=(const InterruptionHold&) = delete;
};

// The temporaries of a group of files replaced together, possibly by several processes (the
// pieces of a .pvti and the .pvti), in one hidden directory beside `target` (the group's main
// file): DIRECTORY/.NAME.tmp-TAG. Every process of an MPI job passes the same TAG (the run id),
// so all use one directory, which exactly one of them creates (`create`); the others never do,
// so once a signal has removed it no process can create it again. Its members are named
// PREFIX<i>SUFFIX for i < count, and EXTRA. A signal ending any process that holds the group
// removes every member and the directory (the handler builds the names from this pattern): once the
// directory is gone no process can create a file in it, so a process that mpirun kills with
// SIGKILL, whose handler never runs, leaves nothing behind either. The destructor removes the
// members this process made and then, when it is empty, the directory.
class TemporaryGroup
{
public:
  TemporaryGroup(const std::string& target,
    const std::string& tag,
    bool create,
    const std::string& prefix,
    const std::string& suffix,
    long count,
    const std::string& extra);
  ~TemporaryGroup();
  TemporaryGroup(const TemporaryGroup&) = delete;
  TemporaryGroup& operator=(const TemporaryGroup&) = delete;
  // The path of member `name` (one of the pattern's), which this process will write.
  std::string Member(const std::string& name);
  // Renames member `name` over `target`; throws InputError naming the target when it cannot.
  void Commit(const std::string& name, const std::string& target);

private:
  std::string Directory;
  std::vector<std::string> Created;
  void* Registration = nullptr; // the signal handler's entry
};

// Installs the signal handler that removes registered temporaries (see above); called by
// WriteStreamAtomically, idempotent, and safe to call earlier (at start-up).
void InstallInterruptCleanup();

// For a child made by fork(): its copy of the table of temporaries names its parent's files,
// which a signal ending the child must not remove; and it inherits no hold. Async-signal-safe,
// as a child of a multi-threaded parent requires.
void ForgetTemporariesInChild();

} // namespace cloudvis

#endif
