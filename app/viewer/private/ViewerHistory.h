// The viewer's one undo history, as ParaView's undo stack: a step is what the user could change
// and take back, as it was before a change (UndoableState: the transfer function, the camera, the
// lighting model, lights, step and resolution scale, the exposure, and the slices' visibility,
// places and window/level). The viewer records a step around each gesture that changed
// something: a key, a mouse drag from press to release (a camera turn, a point dragged, a slice
// moved), and a burst of wheel notches (those less than WheelBurstSeconds apart make one step).
// Undo puts a step back whole and keeps the present state for redo; a new step clears the redo
// side.
#ifndef cloudvis_ViewerHistory_h
#define cloudvis_ViewerHistory_h

#include "Scene.h"

#include <array>
#include <string>
#include <vector>

namespace cloudvis
{

struct UndoableState
{
  TransferFunctionSpec TransferFunction;
  // The 3D view's camera.
  std::array<double, 3> Position{ { 0.0, 0.0, 0.0 } };
  std::array<double, 3> FocalPoint{ { 0.0, 0.0, 0.0 } };
  std::array<double, 3> ViewUp{ { 0.0, 1.0, 0.0 } };
  double ViewAngle = 30.0;
  // Lighting.
  LightingModel Lighting = LightingModel::None;
  std::vector<Light> Lights;
  double Step = 0.0;
  double ResolutionScale = 1.0;
  // The exposure: render.exposure's EV, or automatic (then EV is 0, as the scene reads "auto":
  // a metering is no step of the user's).
  bool AutoExposure = false;
  double ExposureEV = 0.0;
  // Slices.
  std::array<bool, 3> SliceVisible{ { false, false, false } };
  std::array<int, 3> SliceIndex{ { 0, 0, 0 } };
  bool ObliqueVisible = false;
  std::array<double, 2> WindowLevel{ { 1.0, 0.5 } };
};

class UndoHistory
{
public:
  // Wheel notches closer than this make one step.
  static constexpr double WheelBurstSeconds = 0.6;

  // A gesture changed the state from `before` to `now` (nothing is recorded when they are equal).
  // A wheel gesture within WheelBurstSeconds of the last one, recorded as the last step, joins
  // that step (which keeps the state before the burst). `at`: seconds on any steady clock.
  void Record(const UndoableState& before, const UndoableState& now, bool wheel, double at);
  // A frame was drawn, ending at `at`: the time the viewer spent drawing after a notch is no
  // pause of the user's, so a burst's notches stay one step however slow the frames between them.
  void FrameDrawn(double at);

  // The state to restore for undo (redo), given the present one; false when there is none.
  bool Undo(const UndoableState& now, UndoableState& restore);
  bool Redo(const UndoableState& now, UndoableState& restore);

  int GetUndoDepth() const { return int(this->Undone.size()); }
  int GetRedoDepth() const { return int(this->Redone.size()); }

private:
  std::vector<UndoableState> Undone; // the states before each step, the last step last
  std::vector<UndoableState> Redone;
  bool LastWasWheel = false;
  double LastWheelAt = -1e300;
};

} // namespace cloudvis

#endif
