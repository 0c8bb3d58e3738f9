// The event loop of LiveLoop.h. It replaces vtkRenderWindowInteractor::Start(), whose X loop
// dispatches one event, then fires the interactor's timers, then one event... : with a repeating
// refinement timer that rendered on every tick, input waited behind frames, a held trackball drag
// kept turning (vtkInteractorStyle::OnTimer repeats the last motion while a button is down) and
// the loop never slept.
#include "LiveLoop.h"

#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>

#include <X11/Xlib.h>

#include <cerrno>
#include <cmath>
#include <sys/select.h>

namespace cloudvis
{

LiveLoop::LiveLoop(vtkRenderWindowInteractor* interactor, Hooks hooks)
  : Interactor(interactor)
  , Callbacks(std::move(hooks))
{
}

void LiveLoop::Request()
{
  this->Requested = true;
}

void LiveLoop::Flush()
{
  if (this->Requested)
  {
    this->Requested = false;
    this->Callbacks.RenderFrame();
  }
}

void LiveLoop::Run()
{
  auto* display = static_cast<Display*>(this->Interactor->GetRenderWindow()->GetGenericDisplayId());
  if (!display)
  {
    return;
  }
  const int connection = ConnectionNumber(display);
  this->Running = true;
  this->Interactor->SetDone(false);
  while (!this->Interactor->GetDone())
  {
    const bool input = XPending(display) > 0;
    this->Interactor->ProcessEvents(); // every pending event; handlers only Request()
    if (this->Interactor->GetDone())
    {
      break;
    }
    const double nextChange = this->Callbacks.Tick();
    if (this->Requested)
    {
      this->Requested = false;
      this->Callbacks.RenderFrame();
      this->Callbacks.AfterWork();
      continue;
    }
    if (input)
    {
      this->Callbacks.AfterWork();
    }
    if (this->Callbacks.RefinementPending())
    {
      if (XPending(display) == 0)
      {
        this->Callbacks.RenderFrame();
        this->Callbacks.AfterWork();
      }
      continue;
    }
    if (this->Callbacks.Idle && XPending(display) == 0 && this->Callbacks.Idle())
    {
      this->Callbacks.AfterWork();
      continue;
    }
    // Idle: sleep until the X server has something for us or a timed change is due. XPending
    // above has flushed our output and emptied the connection into Xlib's queue, which is empty.
    fd_set readable;
    FD_ZERO(&readable);
    FD_SET(connection, &readable);
    timeval timeout{};
    timeval* wait = nullptr;
    if (nextChange >= 0.0)
    {
      timeout.tv_sec = long(nextChange);
      timeout.tv_usec = long((nextChange - std::floor(nextChange)) * 1e6);
      wait = &timeout;
    }
    if (XPending(display) == 0)
    {
      select(connection + 1, &readable, nullptr, nullptr, wait);
    }
  }
  this->Running = false;
}

} // namespace cloudvis
