// A one-line progress bar on stderr for the long parts of a command (generating a field,
// accumulating frames, rendering an animation). It draws only on a terminal: when stderr is a
// file or a pipe (scripts, ctest) or the user passed --quiet, it writes nothing at all, so
// captured output is the same with or without it. The line is redrawn in place ("\r") when the
// shown percentage or label changes, and erased when the work is done, so what the command
// prints afterwards starts on a clean line.
#ifndef cloudvis_Progress_h
#define cloudvis_Progress_h

#include <ostream>
#include <string>

namespace cloudvis
{

class Progress
{
public:
  // Draws on `out` when `enabled`; see ForStderr for the usual choice.
  Progress(std::ostream& out, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // A bar on stderr, enabled when stderr is a terminal (isatty) and `quiet` is false.
  static bool StderrIsTerminal();

  // Shows "label [#####.....]  42%" for a fraction in [0, 1] (clamped).
  void Update(const std::string& label, double fraction);

  // Erases the bar (if one is shown); Update may start a new one.
  void Finish();

  bool Enabled() const { return this->IsEnabled; }

private:
  std::ostream& Out;
  bool IsEnabled;
  bool Shown = false;
  int LastPercent = -1;
  std::string LastLabel;
};

} // namespace cloudvis

#endif
