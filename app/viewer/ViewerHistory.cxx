// Implementation of ViewerHistory.h, and the viewer's side of it: the undoable state read from
// and put back into the window, the gestures that make steps, the undo and redo keys.
#include "ViewerHistory.h"

#include "ViewerInternals.h"
#include "Words.h"

#include <vtkCamera.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{
namespace
{
// Equal but for rounding: VTK renormalizes the view up now and then (a difference of 1e-16 is no
// camera move to undo).
bool Near(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  for (size_t i = 0; i < 3; ++i)
  {
    if (std::abs(a[i] - b[i]) > 1e-9 * std::max({ 1.0, std::abs(a[i]), std::abs(b[i]) }))
    {
      return false;
    }
  }
  return true;
}

// What differs between two states, for messages: "camera", "lighting", "exposure", "transfer
// function", "slices", joined by ", " (empty when nothing does).
std::string UndoableDifference(const UndoableState& a, const UndoableState& b)
{
  std::vector<std::string> parts;
  if (!Near(a.Position, b.Position) || !Near(a.FocalPoint, b.FocalPoint) ||
    !Near(a.ViewUp, b.ViewUp) || a.ViewAngle != b.ViewAngle)
  {
    parts.push_back("camera");
  }
  if (a.Lighting != b.Lighting || a.Lights != b.Lights || a.Step != b.Step ||
    a.ResolutionScale != b.ResolutionScale)
  {
    parts.push_back("lighting");
  }
  if (a.AutoExposure != b.AutoExposure || a.ExposureEV != b.ExposureEV)
  {
    parts.push_back("exposure");
  }
  if (!SameTransferFunction(a.TransferFunction, b.TransferFunction))
  {
    parts.push_back("transfer function");
  }
  if (a.SliceVisible != b.SliceVisible || a.SliceIndex != b.SliceIndex ||
    a.ObliqueVisible != b.ObliqueVisible || a.WindowLevel != b.WindowLevel)
  {
    parts.push_back("slices");
  }
  return Join(parts);
}
} // namespace

void UndoHistory::Record(const UndoableState& before,
  const UndoableState& now,
  bool wheel,
  double at)
{
  if (UndoableDifference(before, now).empty())
  {
    return;
  }
  const bool burst = wheel && this->LastWasWheel && at - this->LastWheelAt < WheelBurstSeconds &&
    !this->Undone.empty();
  if (!burst)
  {
    this->Undone.push_back(before);
  }
  this->Redone.clear();
  this->LastWasWheel = wheel;
  this->LastWheelAt = wheel ? at : -1e300;
}

void UndoHistory::FrameDrawn(double at)
{
  if (this->LastWasWheel)
  {
    this->LastWheelAt = at;
  }
}

bool UndoHistory::Undo(const UndoableState& now, UndoableState& restore)
{
  if (this->Undone.empty())
  {
    return false;
  }
  restore = this->Undone.back();
  this->Undone.pop_back();
  this->Redone.push_back(now);
  this->LastWasWheel = false;
  return true;
}

bool UndoHistory::Redo(const UndoableState& now, UndoableState& restore)
{
  if (this->Redone.empty())
  {
    return false;
  }
  restore = this->Redone.back();
  this->Redone.pop_back();
  this->Undone.push_back(now);
  this->LastWasWheel = false;
  return true;
}

UndoableState Viewer::Internals::Undoable() const
{
  UndoableState state;
  state.TransferFunction = TransferFunctionOf(this->Property);
  vtkCamera* camera = const_cast<vtkRenderer*>(this->View.Get())->GetActiveCamera();
  camera->GetPosition(state.Position.data());
  camera->GetFocalPoint(state.FocalPoint.data());
  camera->GetViewUp(state.ViewUp.data());
  state.ViewAngle = camera->GetViewAngle();
  state.Lighting = this->Current.Render.Lighting.Model;
  state.Lights = this->Current.Lights;
  state.Step = this->Current.Render.Step;
  state.ResolutionScale = this->Current.Render.ResolutionScale;
  state.AutoExposure = this->Current.Render.AutoExposure;
  state.ExposureEV = state.AutoExposure ? 0.0 : this->Current.Render.ExposureEV;
  for (int axis = 0; axis < 3; ++axis)
  {
    state.SliceVisible[size_t(axis)] = this->Slices->GetSliceVisible(axis);
    state.SliceIndex[size_t(axis)] = this->Slices->GetSliceIndex(axis);
  }
  state.ObliqueVisible = this->Slices->GetObliqueVisible();
  state.WindowLevel = this->Colors->GetWindowLevel();
  return state;
}

void Viewer::Internals::RestoreUndoable(const UndoableState& state)
{
  const UndoableState now = this->Undoable();
  if (!SameTransferFunction(now.TransferFunction, state.TransferFunction))
  {
    this->Editing->Apply(state.TransferFunction);
  }
  vtkCamera* camera = this->View->GetActiveCamera();
  camera->SetPosition(state.Position.data());
  camera->SetFocalPoint(state.FocalPoint.data());
  camera->SetViewUp(state.ViewUp.data());
  camera->SetViewAngle(state.ViewAngle);
  this->View->ResetCameraClippingRange();
  this->Current.Render.Lighting.Model = state.Lighting;
  this->Current.Lights = state.Lights;
  this->Current.Render.Step = state.Step;
  this->Current.Render.ResolutionScale = state.ResolutionScale;
  this->Mapper->SetResolutionScale(state.ResolutionScale);
  this->ApplyLighting(); // the model, lights and step
  if (now.AutoExposure != state.AutoExposure || now.ExposureEV != state.ExposureEV)
  {
    this->Current.Render.AutoExposure = state.AutoExposure;
    this->Current.Render.ExposureEV = state.ExposureEV;
    this->ApplyExposure(); // automatic again: metered now, or when the picture converges
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    if (now.SliceIndex[size_t(axis)] != state.SliceIndex[size_t(axis)])
    {
      this->Slices->SetSliceIndex(axis, state.SliceIndex[size_t(axis)]);
    }
    if (now.SliceVisible[size_t(axis)] != state.SliceVisible[size_t(axis)])
    {
      this->Slices->SetSliceVisible(axis, state.SliceVisible[size_t(axis)]);
    }
  }
  if (now.ObliqueVisible != state.ObliqueVisible)
  {
    this->Slices->SetObliqueVisible(state.ObliqueVisible);
  }
  if (now.WindowLevel != state.WindowLevel)
  {
    this->Colors->SetWindowLevel(state.WindowLevel[0], state.WindowLevel[1]);
  }
  this->SlicesChanged();
}

void Viewer::Internals::BeginGesture(bool wheel)
{
  if (this->InGesture && this->ButtonsDown > 0)
  {
    return; // a key or another button during a drag: part of the drag's step
  }
  this->SettleGesture();
  this->GestureStart = this->Undoable();
  this->InGesture = true;
  this->WheelGesture = wheel;
}

void Viewer::Internals::SettleGesture()
{
  if (!this->InGesture || this->ButtonsDown > 0)
  {
    return;
  }
  this->InGesture = false;
  this->History.Record(
    this->GestureStart, this->Undoable(), this->WheelGesture, MonotonicSeconds());
}

void Viewer::Internals::UndoStep(bool redo)
{
  this->SettleGesture();
  const UndoableState now = this->Undoable();
  UndoableState restore;
  if (!(redo ? this->History.Redo(now, restore) : this->History.Undo(now, restore)))
  {
    this->Show(redo ? "nothing to redo" : "nothing to undo", false);
    return;
  }
  const std::string what = UndoableDifference(now, restore);
  this->RestoreUndoable(restore);
  this->Show(std::string(redo ? "redone: " : "undone: ") + what, false);
}

} // namespace cloudvis
