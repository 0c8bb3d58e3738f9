// The X display cloudvis renders through: VTK 9.1 on this platform has no EGL or OSMesa, so
// every window, on screen or off, needs an X server (Xvfb when headless).
#ifndef cloudvis_Display_h
#define cloudvis_Display_h

#include <string>

namespace cloudvis
{

// Throws InputError unless an X display can be opened: VTK 9.1 on this platform renders through
// X only. The message says how to run headless, quoting `commandLine` ("cloudvis render ...")
// after "xvfb-run -a".
void RequireDisplay(const std::string& commandLine);

// A connection to the X display named by $DISPLAY, open for the object's lifetime; fails like
// RequireDisplay. A refused connection is retried for a moment, because a busy Xvfb refuses some
// (seen on the 2-core build machines). Hand Get() to vtkRenderWindow::SetDisplayId and keep this
// object alive longer than the window: VTK then never opens its own connection, whose failure
// makes it abort() the process.
class DisplayConnection
{
public:
  explicit DisplayConnection(const std::string& commandLine);
  ~DisplayConnection();
  DisplayConnection(const DisplayConnection&) = delete;
  DisplayConnection& operator=(const DisplayConnection&) = delete;

  void* Get() const { return this->Display; } // an Xlib Display*

private:
  void* Display = nullptr;
};

} // namespace cloudvis

#endif
