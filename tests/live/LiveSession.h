// Driving the real `cloudvis view` with real X input, for the live tests (LiveTests.cxx) and the
// viewer benchmark (bench/BenchViewer.cxx). A session starts a private Xvfb server (Xvfb picks a
// free display itself: -displayfd), runs the cloudvis binary on it with --state-file, and sends
// input through the XTEST extension, which the server delivers exactly like a mouse and a
// keyboard. What the viewer did is read back from its state file (ViewerStateJson, written
// atomically after every frame and every batch of input) and, for pixels, from the window itself
// as a support::Image (tests/support: the images, metrics, folders and runner every test shares;
// only the X server, the background viewer process and XTEST are this harness's own).
//
// Each session has its own server, so sessions running side by side (ctest -j2) never move each
// other's pointer. Nothing waits a fixed time to decide a result: WaitFor polls the state with a
// generous timeout, for loaded machines.
#ifndef cloudvis_LiveSession_h
#define cloudvis_LiveSession_h

#include "SupportImages.h"
#include "SupportRun.h"

#include <nlohmann/json.hpp>

#include <array>
#include <functional>
#include <string>
#include <sys/types.h>
#include <vector>

typedef struct _XDisplay Display;

namespace cloudvis
{
namespace live
{

// CLOCK_MONOTONIC seconds, the clock of the state file's times.
double Now();

class LiveSession
{
public:
  // Starts Xvfb and `cloudvis view ARGUMENTS --output-dir WORK --state-file WORK/state.json`,
  // WORK a fresh temporary folder. Without `stateFile` (a cloudvis from before --state-file
  // existed, for benchmarks) the window is found by its name and State() stays empty. Throws
  // std::runtime_error when either fails to start.
  LiveSession(const std::string& cloudvis,
    const std::vector<std::string>& arguments,
    bool stateFile = true);
  // Ends the viewer (SIGTERM if it still runs) and the server, and removes WORK.
  ~LiveSession();
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  // The last state the viewer wrote (an empty object before the first).
  nlohmann::json State() const;
  // Polls the state until `done` holds; throws std::runtime_error naming `what`, with the last
  // state and the viewer's stderr, after `timeout` seconds or when the viewer exits.
  nlohmann::json WaitFor(const std::function<bool(const nlohmann::json&)>& done,
    const std::string& what,
    double timeout = 90.0) const;
  // Waits for the window and a converged image.
  nlohmann::json WaitUntilConverged(double timeout = 90.0) const;

  // The viewer process's CPU time so far (user + system), in seconds.
  double CpuSeconds() const;
  pid_t Pid() const { return this->Viewer; }
  // Waits for the viewer to exit; returns its exit status (-1 on timeout).
  int WaitForExit(double timeout = 60.0);
  std::string Stderr() const;

  // Input, at window pixels counted from the bottom left as the state's viewports are. Each call
  // reaches the server before it returns (XSync).
  void Move(int x, int y);
  void Press(int button);
  void Release(int button);
  // Presses `button` at `from`, moves to `to` in `steps` equal steps, releases.
  void Drag(int button, std::array<int, 2> from, std::array<int, 2> to, int steps = 8);
  void Wheel(int x, int y, bool forward);
  // Resizes the viewer's window, as a window manager would.
  void Resize(int width, int height);
  // Asks the viewer's window to close, as a window manager's close button does: a
  // WM_PROTOCOLS client message carrying WM_DELETE_WINDOW.
  void Close();
  // A key by its X key symbol ("m", "Left", "Delete", "P"); `control` holds Control. Upper-case
  // letters are typed with Shift.
  void Key(const std::string& keySym, bool control = false);
  // Holds a modifier key down ("Control_L", "Shift_L") or lets it go, for clicks and drags made
  // with it.
  void Hold(const std::string& modifierKeySym, bool down);
  // Several keys sent at once, the server synchronised only after the last.
  void Keys(const std::vector<std::string>& keySyms);

  // The window's pixels in the rectangle x0, y0, x1, y1 of window pixels from the bottom left:
  // 8-bit RGB, rows from the bottom like the rectangle, so that Level(x - x0, y - y0, c) is the
  // window's pixel (x, y).
  support::Image Pixels(const std::array<int, 4>& rectangle);

  // The center of a viewport named in the state ("3d", "editor", "axial", ...).
  std::array<int, 2> Center(const std::string& viewport) const;

  // The viewer's X window (0 until it exists) and its size.
  unsigned long WindowId() const;
  std::array<int, 2> WindowSize() const;

  const std::string& WorkDirectory() const { return this->Work.Path; }
  // The server's display name (":N"), for other programs to run on it.
  const std::string& DisplayName() const { return this->DisplayNameText; }

private:
  std::array<int, 2> ToScreen(int x, int y) const;
  void SendKey(const std::string& keySym, bool control);
  void Focus();
  void Sync();

  support::TemporaryDirectory Work{ "cloudvis-live" };
  std::string StatePath;
  std::string DisplayNameText;
  pid_t Server = -1;
  pid_t Viewer = -1;
  Display* Connection = nullptr;
  bool UsesStateFile = true;
  bool Exited = false;
  int ExitStatus = -1;
};

} // namespace live
} // namespace cloudvis

#endif
