// Every file cloudvis writes (fields now, PNG and EXR renders later) goes through
// WriteFileAtomically: the content is written to a temporary file next to the target (same
// directory, hence same filesystem) and renamed over the target only once it is complete. A
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
#ifndef cloudvis_AtomicFile_h
#define cloudvis_AtomicFile_h

#include <functional>
#include <string>

namespace cloudvis
{

// Throws InputError unless `target` can be written: its directory must exist and be writable,
// and the target itself must not be a directory. Called before any expensive work, so a bad -o
// fails in milliseconds rather than after the field has been generated.
void CheckOutputTarget(const std::string& target);

// Calls write(temporaryPath), which must create the complete file at that path and throw on
// failure, then renames the temporary over `target`. On any failure the temporary is removed,
// the target is left as it was, and the exception propagates (OS failures as InputError naming
// the target). The temporary keeps the target's extension, for writers that look at it.
void WriteFileAtomically(
  const std::string& target, const std::function<void(const std::string& temporaryPath)>& write);

// Installs the signal handler that removes registered temporaries (see above); called by
// WriteFileAtomically, idempotent, and safe to call earlier (at start-up).
void InstallInterruptCleanup();

// For a child made by fork(): its copy of the table of temporaries names its parent's files,
// which a signal ending the child must not remove. Async-signal-safe, as a child of a
// multi-threaded parent requires.
void ForgetTemporariesInChild();

} // namespace cloudvis

#endif
