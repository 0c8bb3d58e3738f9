// Implementation of LiveSession.h: processes by fork/exec, input by XTEST, pixels by XGetImage.
#include "LiveSession.h"

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XTest.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <thread>
#include <time.h>
#include <unistd.h>

namespace cloudvis
{
namespace live
{
namespace
{
void Pause(double seconds)
{
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

// fork + exec with `environment` added, stdout and stderr to `log` (if given), `keepOpen` left
// open in the child. Returns the child's pid.
pid_t Spawn(const std::vector<std::string>& command,
  const std::vector<std::string>& environment,
  const std::string& log,
  int keepOpen = -1)
{
  const pid_t pid = fork();
  if (pid < 0)
  {
    throw std::runtime_error("fork failed: " + std::string(std::strerror(errno)));
  }
  if (pid == 0)
  {
    for (const std::string& variable : environment)
    {
      putenv(const_cast<char*>(variable.c_str()));
    }
    if (!log.empty())
    {
      const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd >= 0)
      {
        dup2(fd, 1);
        dup2(fd, 2);
        close(fd);
      }
    }
    for (int fd = 3; fd < 256; ++fd)
    {
      if (fd != keepOpen)
      {
        close(fd);
      }
    }
    std::vector<char*> argv;
    for (const std::string& argument : command)
    {
      argv.push_back(const_cast<char*>(argument.c_str()));
    }
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

void Stop(pid_t pid)
{
  if (pid <= 0)
  {
    return;
  }
  kill(pid, SIGTERM);
  for (int i = 0; i < 200; ++i)
  {
    if (waitpid(pid, nullptr, WNOHANG) == pid)
    {
      return;
    }
    Pause(0.025);
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
}
} // namespace

double Now()
{
  timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

LiveSession::LiveSession(const std::string& cloudvis,
  const std::vector<std::string>& arguments,
  bool stateFile)
  : StatePath(this->Work.File("state.json"))
  , UsesStateFile(stateFile)
{
  const std::string& work = this->Work.Path;
  // A private server: Xvfb writes the display number it chose to the pipe once it accepts
  // connections.
  int ready[2];
  if (pipe(ready) != 0)
  {
    throw std::runtime_error("pipe failed");
  }
  this->Server = Spawn({ "Xvfb",
                         "-displayfd",
                         std::to_string(ready[1]),
                         "-screen",
                         "0",
                         "1280x1024x24",
                         "-nolisten",
                         "tcp",
                         "-noreset" },
    {},
    work + "/xvfb.log",
    ready[1]);
  close(ready[1]);
  std::string number;
  char c;
  while (read(ready[0], &c, 1) == 1 && c != '\n')
  {
    number += c;
  }
  close(ready[0]);
  if (number.empty())
  {
    throw std::runtime_error("Xvfb did not start: " + support::ReadText(work + "/xvfb.log"));
  }
  const std::string display = ":" + number;
  this->DisplayNameText = display;
  this->Connection = XOpenDisplay(display.c_str());
  int event, error, major, minor;
  if (!this->Connection || !XTestQueryExtension(this->Connection, &event, &error, &major, &minor))
  {
    throw std::runtime_error("cannot use XTEST on the display " + display);
  }
  std::vector<std::string> command = { cloudvis, "view" };
  command.insert(command.end(), arguments.begin(), arguments.end());
  command.insert(command.end(), { "--output-dir", work });
  if (stateFile)
  {
    command.insert(command.end(), { "--state-file", this->StatePath });
  }
  this->Viewer = Spawn(command, { "DISPLAY=" + display }, work + "/viewer.log");
}

LiveSession::~LiveSession()
{
  if (!this->Exited)
  {
    Stop(this->Viewer);
  }
  if (this->Connection)
  {
    XCloseDisplay(this->Connection);
  }
  Stop(this->Server);
}

nlohmann::json LiveSession::State() const
{
  const std::string text = support::ReadText(this->StatePath);
  if (text.empty())
  {
    return nlohmann::json::object();
  }
  return nlohmann::json::parse(text, nullptr, false);
}

std::string LiveSession::Stderr() const
{
  return support::ReadText(this->Work.File("viewer.log"));
}

nlohmann::json LiveSession::WaitFor(const std::function<bool(const nlohmann::json&)>& done,
  const std::string& what,
  double timeout) const
{
  const double end = Now() + timeout;
  nlohmann::json state;
  for (;;)
  {
    state = this->State();
    if (state.is_object() && !state.empty() && done(state))
    {
      return state;
    }
    int status = 0;
    const bool exited = this->Exited || waitpid(this->Viewer, &status, WNOHANG) == this->Viewer;
    if (exited || Now() > end)
    {
      throw std::runtime_error("waiting for " + what +
        (exited ? ": the viewer exited" : ": timed out after " + std::to_string(timeout) + " s") +
        "\nlast state: " + state.dump() + "\nviewer output:\n" + this->Stderr());
    }
    Pause(0.05);
  }
}

nlohmann::json LiveSession::WaitUntilConverged(double timeout) const
{
  return this->WaitFor([](const nlohmann::json& s)
    { return s.value("converged", false) && s.value("frames_rendered", 0) > 0; },
    "a converged image",
    timeout);
}

double LiveSession::CpuSeconds() const
{
  const std::string stat = support::ReadText("/proc/" + std::to_string(this->Viewer) + "/stat");
  const size_t close = stat.rfind(')');
  if (close == std::string::npos)
  {
    return 0.0;
  }
  std::istringstream fields(stat.substr(close + 2));
  std::string field;
  double user = 0.0, system = 0.0;
  // After the command: state (field 3) ... utime is field 14, stime field 15.
  for (int index = 3; index <= 15 && fields >> field; ++index)
  {
    if (index == 14)
    {
      user = std::stod(field);
    }
    if (index == 15)
    {
      system = std::stod(field);
    }
  }
  return (user + system) / double(sysconf(_SC_CLK_TCK));
}

int LiveSession::WaitForExit(double timeout)
{
  const double end = Now() + timeout;
  while (!this->Exited && Now() < end)
  {
    int status = 0;
    if (waitpid(this->Viewer, &status, WNOHANG) == this->Viewer)
    {
      this->Exited = true;
      this->ExitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    else
    {
      Pause(0.02);
    }
  }
  return this->Exited ? this->ExitStatus : -1;
}

namespace
{
// The first window named `name` under `parent`, depth first; 0 for none.
Window FindWindow(Display* display, Window parent, const char* name)
{
  char* title = nullptr;
  if (XFetchName(display, parent, &title) && title)
  {
    const bool found = std::strcmp(title, name) == 0;
    XFree(title);
    if (found)
    {
      return parent;
    }
  }
  Window root, up, *children = nullptr;
  unsigned int count = 0;
  Window found = 0;
  if (XQueryTree(display, parent, &root, &up, &children, &count))
  {
    for (unsigned int i = 0; i < count && !found; ++i)
    {
      found = FindWindow(display, children[i], name);
    }
    if (children)
    {
      XFree(children);
    }
  }
  return found;
}
} // namespace

unsigned long LiveSession::WindowId() const
{
  if (this->UsesStateFile)
  {
    const nlohmann::json state = this->State();
    return state.contains("window") ? state["window"]["id"].get<unsigned long>() : 0;
  }
  return FindWindow(this->Connection, DefaultRootWindow(this->Connection), "cloudvis view");
}

std::array<int, 2> LiveSession::WindowSize() const
{
  XWindowAttributes attributes;
  if (!this->WindowId() || !XGetWindowAttributes(this->Connection, this->WindowId(), &attributes))
  {
    return { { 0, 0 } };
  }
  return { { attributes.width, attributes.height } };
}

std::array<int, 2> LiveSession::ToScreen(int x, int y) const
{
  const Window window = this->WindowId();
  const int height = this->WindowSize()[1];
  int rootX = 0, rootY = 0;
  Window child;
  XTranslateCoordinates(
    this->Connection, window, DefaultRootWindow(this->Connection), 0, 0, &rootX, &rootY, &child);
  return { { rootX + x, rootY + (height - 1 - y) } };
}

void LiveSession::Focus()
{
  // Keys go to the focused window: the viewer's, wherever the pointer is.
  const Window window = this->WindowId();
  XSetInputFocus(this->Connection, window, RevertToPointerRoot, CurrentTime);
}

void LiveSession::Sync()
{
  XSync(this->Connection, False);
}

void LiveSession::Move(int x, int y)
{
  const auto screen = this->ToScreen(x, y);
  XTestFakeMotionEvent(this->Connection, -1, screen[0], screen[1], CurrentTime);
  this->Sync();
}

void LiveSession::Press(int button)
{
  XTestFakeButtonEvent(this->Connection, unsigned(button), True, CurrentTime);
  this->Sync();
}

void LiveSession::Release(int button)
{
  XTestFakeButtonEvent(this->Connection, unsigned(button), False, CurrentTime);
  this->Sync();
}

void LiveSession::Drag(int button, std::array<int, 2> from, std::array<int, 2> to, int steps)
{
  this->Move(from[0], from[1]);
  this->Press(button);
  for (int i = 1; i <= steps; ++i)
  {
    this->Move(from[0] + (to[0] - from[0]) * i / steps, from[1] + (to[1] - from[1]) * i / steps);
  }
  this->Release(button);
}

void LiveSession::Resize(int width, int height)
{
  XResizeWindow(this->Connection, this->WindowId(), unsigned(width), unsigned(height));
  this->Sync();
}

void LiveSession::Close()
{
  XEvent event{};
  event.xclient.type = ClientMessage;
  event.xclient.window = this->WindowId();
  event.xclient.message_type = XInternAtom(this->Connection, "WM_PROTOCOLS", False);
  event.xclient.format = 32;
  event.xclient.data.l[0] = long(XInternAtom(this->Connection, "WM_DELETE_WINDOW", False));
  event.xclient.data.l[1] = CurrentTime;
  XSendEvent(this->Connection, this->WindowId(), False, NoEventMask, &event);
  this->Sync();
}

void LiveSession::Wheel(int x, int y, bool forward)
{
  this->Move(x, y);
  this->Press(forward ? 4 : 5);
  this->Release(forward ? 4 : 5);
}

void LiveSession::Keys(const std::vector<std::string>& keySyms)
{
  this->Focus();
  for (const std::string& keySym : keySyms)
  {
    this->SendKey(keySym, false);
  }
  this->Sync();
}

void LiveSession::Key(const std::string& keySym, bool control)
{
  this->Focus();
  this->SendKey(keySym, control);
  this->Sync();
}

void LiveSession::Hold(const std::string& modifierKeySym, bool down)
{
  const KeyCode code = XKeysymToKeycode(this->Connection, XStringToKeysym(modifierKeySym.c_str()));
  if (code == 0)
  {
    throw std::runtime_error("no key for the key symbol " + modifierKeySym);
  }
  this->Focus();
  XTestFakeKeyEvent(this->Connection, code, down ? True : False, CurrentTime);
  this->Sync();
}

void LiveSession::SendKey(const std::string& keySym, bool control)
{
  const KeySym symbol = XStringToKeysym(keySym.c_str());
  const KeyCode code = XKeysymToKeycode(this->Connection, symbol);
  if (symbol == NoSymbol || code == 0)
  {
    throw std::runtime_error("no key for the key symbol " + keySym);
  }
  const bool shift = keySym.size() == 1 && keySym[0] >= 'A' && keySym[0] <= 'Z';
  std::vector<KeyCode> modifiers;
  if (control)
  {
    modifiers.push_back(XKeysymToKeycode(this->Connection, XStringToKeysym("Control_L")));
  }
  if (shift)
  {
    modifiers.push_back(XKeysymToKeycode(this->Connection, XStringToKeysym("Shift_L")));
  }
  for (KeyCode modifier : modifiers)
  {
    XTestFakeKeyEvent(this->Connection, modifier, True, CurrentTime);
  }
  XTestFakeKeyEvent(this->Connection, code, True, CurrentTime);
  XTestFakeKeyEvent(this->Connection, code, False, CurrentTime);
  for (KeyCode modifier : modifiers)
  {
    XTestFakeKeyEvent(this->Connection, modifier, False, CurrentTime);
  }
}

support::Image LiveSession::Pixels(const std::array<int, 4>& rectangle)
{
  const Window window = this->WindowId();
  const int height = this->WindowSize()[1];
  const int width = rectangle[2] - rectangle[0], rows = rectangle[3] - rectangle[1];
  XImage* image = XGetImage(this->Connection,
    window,
    rectangle[0],
    height - rectangle[3],
    unsigned(width),
    unsigned(rows),
    AllPlanes,
    ZPixmap);
  if (!image)
  {
    throw std::runtime_error("XGetImage failed");
  }
  support::Image pixels;
  pixels.Width = width;
  pixels.Height = rows;
  pixels.Components = 3;
  pixels.Bits = 8;
  pixels.Values.reserve(size_t(width) * size_t(rows) * 3);
  // XGetImage's rows run from the top; the Image's from the bottom.
  for (int y = rows - 1; y >= 0; --y)
  {
    for (int x = 0; x < width; ++x)
    {
      const unsigned long pixel = XGetPixel(image, x, y);
      pixels.Values.push_back(double((pixel & image->red_mask) >> 16) / 255.0);
      pixels.Values.push_back(double((pixel & image->green_mask) >> 8) / 255.0);
      pixels.Values.push_back(double(pixel & image->blue_mask) / 255.0);
    }
  }
  XDestroyImage(image);
  return pixels;
}

std::array<int, 2> LiveSession::Center(const std::string& viewport) const
{
  const nlohmann::json box = this->State()["viewports"][viewport];
  return { { (box[0].get<int>() + box[2].get<int>()) / 2,
    (box[1].get<int>() + box[3].get<int>()) / 2 } };
}

} // namespace live
} // namespace cloudvis
