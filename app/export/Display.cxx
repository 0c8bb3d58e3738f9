// Kept in its own file because Xlib.h defines macros (None, Status, Bool) that collide with
// ordinary C++ names elsewhere in the renderer.
#include "Display.h"

#include "Errors.h"

#include <X11/Xlib.h>

#include <chrono>
#include <cstdlib>
#include <thread>

namespace cloudvis
{

DisplayConnection::DisplayConnection(const std::string& commandLine)
{
  const char* name = std::getenv("DISPLAY");
  const std::string headless =
    "; to render without a screen, run it under Xvfb: xvfb-run -a " + commandLine;
  if (!name || !*name)
  {
    throw InputError("cloudvis needs an X display to render, and $DISPLAY is not set" + headless);
  }
  // A busy Xvfb refuses a connection now and then; a server that is not there refuses all of
  // them, for about a second in total here.
  for (int attempt = 0; attempt < 12 && !this->Display; ++attempt)
  {
    if (attempt > 0)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(10 * attempt));
    }
    this->Display = XOpenDisplay(name);
  }
  if (!this->Display)
  {
    throw InputError(std::string("cloudvis needs an X display to render, and cannot open \"") +
      name + "\" ($DISPLAY)" + headless);
  }
}

DisplayConnection::~DisplayConnection()
{
  if (this->Display)
  {
    XCloseDisplay(static_cast<::Display*>(this->Display));
  }
}

void RequireDisplay(const std::string& commandLine)
{
  const DisplayConnection check(commandLine);
}

} // namespace cloudvis
