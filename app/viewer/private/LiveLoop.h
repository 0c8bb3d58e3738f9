// The viewer's event loop: the one place that decides when the window renders.
//
// Handlers of input never render themselves. Whatever changes the picture asks for a frame
// (Request(); VTK's styles and widgets do it through vtkRenderWindowInteractor::Render(), whose
// RenderEvent the viewer turns into a request because the interactor's own rendering is off).
// The loop then
//   1. handles every X event that is pending (all of them, so that a burst of key presses or
//      mouse motions costs one frame, not one frame each);
//   2. renders one frame if one was asked for;
//   3. else renders one step of progressive refinement if the image has not converged, but only
//      when no X event is waiting: a refinement frame yields to input;
//   4. else does the idle work there is (the next time step's read ahead), one piece at a time
//      and only when no X event is waiting;
//   5. else sleeps in select() on the X connection until an event arrives or a timed change
//      (a message fading) is due. A converged, idle viewer therefore uses no CPU.
// VTK's interactor timers are not run: nothing in the viewer moves by time, so a held mouse
// button can only move the camera by the motion it reports.
//
// Outside Run() (replaying a recording, tests calling the viewer directly) the viewer calls
// Flush() once an input event or a key has been handled, so a replayed event renders once, after
// everything it changed, as in the loop.
#ifndef cloudvis_LiveLoop_h
#define cloudvis_LiveLoop_h

#include <functional>

class vtkRenderWindowInteractor;

namespace cloudvis
{

class LiveLoop
{
public:
  struct Hooks
  {
    std::function<void()> RenderFrame;       // renders the window once
    std::function<bool()> RefinementPending; // the image would improve with another frame
    // Advances timed changes (a fading message) to now, requesting a frame when one changed;
    // returns the seconds until the next one, or a negative number when none is due.
    std::function<double()> Tick;
    std::function<void()> AfterWork; // after input was handled or a frame rendered
    // Work for an idle window; returns whether it did some (then the loop looks at input again
    // before doing more). May be empty.
    std::function<bool()> Idle;
  };

  LiveLoop(vtkRenderWindowInteractor* interactor, Hooks hooks);

  // Runs until the interactor's TerminateApp() (q, Esc, the window closed).
  void Run();

  // Asks for a frame: in Run(), once the pending input is handled; outside it, at Flush().
  void Request();

  // Renders now if a frame was asked for since the last one.
  void Flush();

  bool IsRunning() const { return this->Running; }

private:
  vtkRenderWindowInteractor* Interactor;
  Hooks Callbacks;
  bool Running = false;
  bool Requested = false;
};

} // namespace cloudvis

#endif
