// Every file cloudvis writes (fields now, PNG and EXR renders later) goes through
// WriteFileAtomically: the content is written to a temporary file next to the target (same
// directory, hence same filesystem) and renamed over the target only once it is complete. A
// reader therefore never sees a half-written file, and a failed or interrupted export leaves the
// previous target untouched and no temporary behind. "Interrupted" includes SIGINT and SIGTERM:
// while a temporary exists its path is registered where a signal handler can reach it without
// allocating or locking; the handlers (installed on the first write, unless the signal is
// ignored or already handled by someone else) unlink the registered temporaries and end the
// process with _exit(128 + signal), 130 for SIGINT and 143 for SIGTERM.
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

// Installs the SIGINT and SIGTERM handlers that remove registered temporaries (see above); called
// by WriteFileAtomically, idempotent, and safe to call earlier (at start-up) so that a signal that
// arrives before the first write also exits with 128 + signal.
void InstallInterruptCleanup();

} // namespace cloudvis

#endif
