// What the viewer's keys do: the actions of the key table (KeyBindings.h), the typed values of
// a transfer-function point, and the record of handled keys the state file reports.
#include "ViewerInternals.h"

#include "Errors.h"
#include "FieldCoarsening.h"
#include "FieldSeries.h"
#include "ImageWriters.h" // ShowExposure
#include "OffscreenRender.h"
#include "Presets.h"
#include "Scene.h"
#include "ViewerFiles.h"

#include "CloudMarchUniforms.h" // EffectiveSampleDistance

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cloudvis
{
namespace
{
constexpr double ViewerPi = 3.14159265358979323846;
constexpr size_t KeptKeys = 64;
// How long a first q (or close) waits for the second one that quits without saving: as long as
// its message (an error's) is shown in full.
constexpr double QuitConfirmSeconds = 2.0 * StatusOverlay::MessageSeconds;
const char* const AxisNames[3] = { "x", "y", "z" };

std::string Format(const char* format, double value)
{
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}
} // namespace

int Viewer::Internals::FirstDirectionalLight() const
{
  for (size_t i = 0; i < this->Current.Lights.size(); ++i)
  {
    if (!this->Current.Lights[i].Positional)
    {
      return int(i);
    }
  }
  return -1;
}

void Viewer::Internals::MoveLight(double azimuthDegrees, double elevationDegrees)
{
  const int index = this->FirstDirectionalLight();
  if (index < 0)
  {
    this->Show("the scene has no directional light to move", true);
    return;
  }
  Light& light = this->Current.Lights[size_t(index)];
  const glm::dvec3 d = light.Position - light.FocalPoint;
  const double r = glm::length(d);
  double azimuth = std::atan2(d.x, d.z) + azimuthDegrees * ViewerPi / 180.0;
  double elevation =
    std::asin(std::max(-1.0, std::min(1.0, d.y / r))) + elevationDegrees * ViewerPi / 180.0;
  elevation = std::max(-89.0 * ViewerPi / 180.0, std::min(89.0 * ViewerPi / 180.0, elevation));
  const glm::dvec3 moved(r * std::cos(elevation) * std::sin(azimuth),
    r * std::sin(elevation),
    r * std::cos(elevation) * std::cos(azimuth));
  light.Position = light.FocalPoint + moved;
  this->ApplyLighting();
  char text[128];
  std::snprintf(text,
    sizeof(text),
    "light %d: azimuth %.0f, elevation %.0f degrees",
    index,
    azimuth * 180.0 / ViewerPi,
    elevation * 180.0 / ViewerPi);
  this->Show(text, false);
}

void Viewer::Internals::StepExposure(double stops)
{
  // From the EV the window shows, the metered one included: a step is relative to the picture.
  RenderSpec& render = this->Current.Render;
  render.AutoExposure = false;
  this->AnnounceExposure = false;
  render.ExposureEV =
    std::max(-MaxExposureEV, std::min(MaxExposureEV, this->Mapper->GetExposureEV() + stops));
  this->ApplyExposure();
  this->Show(this->ExposureText(), false);
}

void Viewer::Internals::UseAutoExposure()
{
  this->Current.Render.AutoExposure = true;
  this->Current.Render.ExposureEV = 0.0; // as the scene reads "auto"
  this->AnnounceExposure = !this->ApplyExposure();
  if (!this->AnnounceExposure)
  {
    this->Show(this->ExposureText(), false);
    return;
  }
  this->Show("exposure: auto, metered when the picture has converged", false);
}

double Viewer::Internals::EffectiveStep() const
{
  // The mapper's own meaning of step 0, the voxel edge after the volume's placement.
  return EffectiveSampleDistance(
    GeometryOf(this->Field, this->Volume->GetMatrix()), this->Current.Render.Step);
}

void Viewer::Internals::LoadNextPreset()
{
  std::vector<std::string> names;
  try
  {
    names = ShippedPresetNames();
  }
  catch (const std::exception& e)
  {
    this->Show(e.what(), true);
    return;
  }
  if (names.empty())
  {
    this->Show("no presets in " + PresetDirectory(), true);
    return;
  }
  this->PresetIndex = (this->PresetIndex + 1) % int(names.size());
  const std::string& name = names[size_t(this->PresetIndex)];
  try
  {
    this->Editing->Apply(ReadNamedPreset(name));
    this->Preset = name;
    this->Show("preset " + name, false);
  }
  catch (const std::exception& e)
  {
    this->Show(std::string(e.what()) + "; the transfer function is unchanged", true);
  }
}

void Viewer::Internals::SavePreset()
{
  try
  {
    const std::string path =
      WritePreset(TransferFunctionOf(this->Property), this->Options.OutputDirectory);
    this->SavedFiles.push_back(path);
    this->Show("saved preset " + path, false);
  }
  catch (const std::exception& e)
  {
    this->Show(e.what(), true);
  }
}

void Viewer::Internals::TypeKey(const std::string& keySym, char keyCode)
{
  using Function = TransferFunctionEditor::Function;
  const Function function = this->Editing->GetSelectedFunction();
  // What is typed: the slices' window and level, or the selected point's values.
  const bool windowLevel = this->TypingWindowLevel;
  const std::string what = windowLevel
    ? std::string("window/level")
    : std::string(TransferFunctionEditor::FunctionName(function)) + " point " +
      std::to_string(this->Editing->GetSelectedPoint());
  if (keySym == "Escape")
  {
    this->Typing = false;
    this->Editing->SetEntry("");
    this->Show("typing cancelled; the " + std::string(windowLevel ? "window/level" : "point") +
        " is unchanged",
      false);
    return;
  }
  if (keySym == "Return" || keySym == "KP_Enter")
  {
    const std::string problem = windowLevel ? this->SetTypedWindowLevel()
                                            : this->Editing->SetSelectedPointValues(this->Typed);
    if (!problem.empty())
    {
      this->Show(problem + " (Esc cancels)", true);
      return;
    }
    this->Typing = false;
    this->Editing->SetEntry("");
    this->Show(windowLevel
        ? this->WindowLevelText("window/level typed")
        : what + ": " + this->Editing->GetSelectedPointValues() + " (Ctrl+z undoes)",
      false);
    return;
  }
  if (keySym == "BackSpace")
  {
    if (!this->Typed.empty())
    {
      this->Typed.pop_back();
    }
  }
  else if (keyCode != 0 && std::string("0123456789.-+eE ,").find(keyCode) != std::string::npos)
  {
    this->Typed += keyCode;
  }
  const auto now = this->Colors->GetWindowLevel();
  const std::string values = windowLevel ? Format("%.4g", now[0]) + " " + Format("%.4g", now[1])
                                         : this->Editing->GetSelectedPointValues();
  const char* fields = windowLevel  ? "window level"
    : function == Function::Opacity ? "density opacity"
                                    : "density r g b";
  this->Editing->SetEntry(what + " (now " + values + "), type " + fields + ": " + this->Typed +
    "_   Enter applies, Esc cancels");
}

std::string Viewer::Internals::WindowLevelText(const std::string& what) const
{
  const auto [window, level] = this->Colors->GetWindowLevel();
  return what + ": window " + Format("%.4g", window) + ", level " + Format("%.4g", level) +
    " (densities " + Format("%.4g", level - 0.5 * window) + " to " +
    Format("%.4g", level + 0.5 * window) + ")" +
    (this->Colors->IsWindowed() ? "" : "; the transfer function's colors are not windowed (c)");
}

std::string Viewer::Internals::SetTypedWindowLevel()
{
  const std::vector<double> numbers = ParseTypedNumbers(this->Typed);
  if (numbers.size() != 2)
  {
    return "type two numbers, the window and the level (for example 0.5 0.25)";
  }
  const std::string problem = WindowLevelProblem(numbers[0], numbers[1]);
  if (!problem.empty())
  {
    return problem + ", got " + Format("%.4g", numbers[0]) + " " + Format("%.4g", numbers[1]);
  }
  this->Colors->SetWindowLevel(numbers[0], numbers[1]);
  this->SlicesChanged();
  return "";
}

void Viewer::Internals::StartTypingWindowLevel()
{
  this->Typing = true;
  this->TypingWindowLevel = true;
  this->Typed.clear();
  this->TypeKey("", 0);
}

// As ParaView's "rescale to visible range" and Slicer's automatic window/level: the values the
// shown slices hold, without the extreme percent at either end (a few hot voxels would otherwise
// take the whole window), else their whole range.
void Viewer::Internals::AutoWindowLevel()
{
  std::vector<double> values;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (this->FourViews || this->Slices->GetSliceVisible(axis))
    {
      const std::vector<double> slice = this->Slices->GetSliceValues(axis);
      values.insert(values.end(), slice.begin(), slice.end());
    }
  }
  if (values.empty())
  {
    this->Show("no slice is shown (x, y, z or 4 show one): the window/level is unchanged", true);
    return;
  }
  const auto at = [&](double fraction)
  {
    const auto nth =
      values.begin() + std::ptrdiff_t(std::lround(fraction * double(values.size() - 1)));
    std::nth_element(values.begin(), nth, values.end());
    return *nth;
  };
  double low = at(0.01), high = at(0.99);
  if (!(high > low))
  {
    low = at(0.0);
    high = at(1.0);
  }
  if (!(high > low))
  {
    this->Show(
      "the shown slices hold one value, " + Format("%.4g", low) + ": the window/level is unchanged",
      true);
    return;
  }
  this->Colors->SetWindowLevel(high - low, 0.5 * (low + high));
  this->Show(
    this->WindowLevelText("window/level from the shown slices (1st to 99th percentile)"), false);
  this->SlicesChanged();
}

void Viewer::Internals::StartTyping()
{
  if (this->Editing->GetSelectedPoint() < 0)
  {
    this->Show("no point is selected: click one in the editor first", true);
    return;
  }
  this->Typing = true;
  this->TypingWindowLevel = false;
  this->Typed.clear();
  this->TypeKey("", 0);
}

void Viewer::Internals::StepSlice(int step)
{
  const int* pointer = this->Interactor->GetEventPosition();
  int axis = this->FourViews ? this->Views2D->AxisAt(pointer[0], pointer[1]) : -1;
  if (axis < 0)
  {
    axis = this->Slices->AxisUnder(pointer[0], pointer[1]);
  }
  axis = axis < 0 ? this->ActiveAxis : axis;
  if (!this->FourViews && !this->Slices->GetSliceVisible(axis))
  {
    // A slice nobody sees would move unseen.
    this->Show(std::string("no slice to step: the slice across ") + AxisNames[axis] +
        " is hidden (x, y or z shows one, 4 the slice views)",
      false);
    return;
  }
  this->ActiveAxis = axis;
  this->Slices->SetSliceIndex(axis, this->Slices->GetSliceIndex(axis) + step);
  this->Show(std::string("slice across ") + AxisNames[axis] + ": " +
      std::to_string(this->Slices->GetSliceIndex(axis)) + " of " +
      std::to_string(this->Slices->GetNumberOfSlices(axis) - 1) + " (" + AxisNames[axis] + " = " +
      Format("%.3g", this->Slices->GetSlicePosition(axis)) + ")",
    false);
  this->SlicesChanged();
}

void Viewer::Internals::StepTime(int direction)
{
  ViewerTimeSteps& time = *this->Time;
  if (!time.Steps())
  {
    this->Show("the field has one time step; , and . step through a NetCDF file's time axis or a "
               "numbered file series (cloudvis view 'run/les_*.nc')",
      false);
    return;
  }
  const int step = time.Current() + direction;
  // A series may have grown since it was listed: a step past its last is asked of the folder.
  if (step < 0 || (step >= time.Count() && !time.Series()))
  {
    this->Show(time.Label() + (step < 0 ? " is the first" : " is the last"), false);
    return;
  }
  FieldStep next;
  try
  {
    if (step >= time.Count() &&
      FindFileSeries(
        this->Current.Field.File, this->Current.Field.Read.SeriesGaps == SeriesGapRule::Skip)
          .Files.size() <= std::size_t(step))
    {
      this->Show(time.Label() + " is the last: the folder holds no later file yet", false);
      return;
    }
    next = time.Take(step);
    CheckSameGrid(
      TimeStepName(this->Current.Field.File, step, next.Report), this->Field, next.Field);
  }
  catch (const InputError& error)
  {
    this->Show(error.what(), true);
    return;
  }
  // The new values in the shown image: the mapper, the slices and their views follow its MTime,
  // and keep their places, the camera and the function.
  this->Field->GetPointData()->SetScalars(next.Field->GetPointData()->GetScalars());
  this->Field->Modified();
  if (this->Coarsening > 1)
  {
    this->Mapper->SetInputData(CoarsenField(this->Field, this->Coarsening));
  }
  this->Current.Field.Read.TimeStep = step;
  time.SetShown(step, next.Report);
  this->Editing->SetField(this->Field);
  this->Status->SetCorner(this->CornerText());
  this->Show(time.Label(), false);
  this->SlicesChanged();
  time.ReadAheadLater(step + direction,
    double(this->Field->GetPointData()->GetScalars()->GetActualMemorySize()) * 1024.0);
}

void Viewer::Internals::ToggleSlice(int axis)
{
  const bool visible = !this->Slices->GetSliceVisible(axis);
  this->Slices->SetSliceVisible(axis, visible);
  this->ActiveAxis = visible ? axis : this->ActiveAxis;
  this->Show(std::string("slice across ") + AxisNames[axis] + ": " +
      (visible ? "shown at " + std::string(AxisNames[axis]) + " = " +
            Format("%.3g", this->Slices->GetSlicePosition(axis))
               : std::string("hidden")),
    false);
  this->SlicesChanged();
}

std::string Viewer::Internals::EditsOf(const Viewer& viewer) const
{
  // The scene `w` would save, view section (layout, slices, window/level, colors) included.
  nlohmann::json edits = viewer.CurrentSceneJson();
  edits["render"].erase("size");
  return edits.dump();
}

bool Viewer::Internals::UnsavedChanges(const Viewer& viewer) const
{
  return !this->Options.SceneSavedOnExit && this->EditsOf(viewer) != this->SavedEdits;
}

void Viewer::Internals::Quit(const Viewer& viewer, bool fromWindowManager)
{
  const double now = MonotonicSeconds();
  if (!this->UnsavedChanges(viewer) || now - this->QuitAskedAt <= QuitConfirmSeconds)
  {
    this->Interactor->TerminateApp();
    return;
  }
  this->QuitAskedAt = now;
  this->Show(fromWindowManager
      ? "unsaved changes: w saves the scene, closing again (or q) quits without saving"
      : "unsaved changes: w saves the scene, q again quits without saving",
    true);
}

bool Viewer::Internals::ActOnSlices(ViewerAction action, int variant)
{
  using A = ViewerAction;
  switch (action)
  {
    case A::ToggleSlice:
      this->ToggleSlice(variant);
      return true;
    case A::ToggleOblique:
      this->Slices->SetObliqueVisible(!this->Slices->GetObliqueVisible());
      this->Show(
        std::string("oblique slice: ") + (this->Slices->GetObliqueVisible() ? "shown" : "hidden"),
        false);
      this->SlicesChanged();
      return true;
    case A::StepSlice:
      this->StepSlice(variant == 0 ? 1 : -1);
      return true;
    case A::StepTime:
      this->StepTime(variant == 0 ? -1 : 1);
      return true;
    case A::AutoWindowLevel:
      this->AutoWindowLevel();
      return true;
    case A::ResetWindowLevel:
      this->Colors->ResetWindowLevel();
      this->Show(this->WindowLevelText("window/level reset to the field's range"), false);
      this->SlicesChanged();
      return true;
    case A::TypeWindowLevel:
      this->StartTypingWindowLevel();
      return true;
    case A::CycleSliceColors:
      this->Colors->NextColormap();
      this->Show("slice colors: " + this->Colors->GetColormap(), false);
      this->SlicesChanged();
      return true;
    default:
      return false;
  }
}

bool Viewer::Internals::ActOnView(ViewerAction action)
{
  using A = ViewerAction;
  switch (action)
  {
    case A::ToggleLayout:
      this->FourViews = !this->FourViews;
      this->ApplyLayout();
      this->UpdateReadout();
      this->Show(
        this->FourViews ? "four views: 3D, axial, coronal, sagittal" : "the 3D view alone", false);
      return true;
    case A::ToggleVolume:
      this->Volume->SetVisibility(!this->Volume->GetVisibility());
      this->Show(
        this->Volume->GetVisibility() ? "cloud shown" : "cloud hidden (v shows it)", false);
      this->PlaceLegends(); // the cloud's legend goes with the cloud
      return true;
    case A::ToggleLegends:
      this->LegendsVisible = !this->LegendsVisible;
      this->PlaceLegends();
      this->Show(
        std::string("color legends: ") + (this->LegendsVisible ? "shown" : "hidden"), false);
      return true;
    case A::ResetCamera:
      ApplyCamera(this->Current.Camera, this->Field->GetBounds(), this->View, this->Current.Source);
      this->Views2D->ResetZoom();
      return true;
    case A::Help:
      // The pages in turn (keys, the mouse in 3D, in the slice views and the editor), then none.
      this->Status->SetHelpPage(this->Status->GetHelpPage() + 1);
      this->PlaceLegends(); // hidden under the help
      return true;
    case A::Close:
      if (this->Status->GetHelpVisible())
      {
        this->Status->SetHelpPage(-1);
        this->PlaceLegends(); // back from under the help
      }
      else
      {
        this->Show("nothing to close (Esc closes the help and cancels typing; q quits)", false);
      }
      return true;
    default:
      return false;
  }
}

bool Viewer::Internals::ActOnRendering(ViewerAction action, int variant)
{
  using A = ViewerAction;
  switch (action)
  {
    case A::CycleLighting:
    {
      // The interactive models: the path tracer takes seconds per clean frame, so `m` passes it
      // by (a scene with render.lighting "pathtrace" still opens with it, converging in place).
      std::vector<std::string> names = LightingModelNames();
      names.erase(
        std::remove(names.begin(), names.end(), LightingModelName(LightingModel::PathTrace)),
        names.end());
      const std::string current = LightingModelName(this->Current.Render.Lighting.Model);
      const auto found = std::find(names.begin(), names.end(), current);
      const size_t next =
        found == names.end() ? 0 : size_t(found - names.begin() + 1) % names.size();
      this->Current.Render.Lighting.Model = *FindLightingModel(names[next]);
      this->ApplyLighting();
      this->Show("lighting: " + names[next], false);
      return true;
    }
    case A::MoveLightAzimuth:
      this->MoveLight(variant == 0 ? -10.0 : 10.0, 0.0);
      return true;
    case A::MoveLightElevation:
      this->MoveLight(0.0, variant == 0 ? 10.0 : -10.0);
      return true;
    case A::StepLarger:
    case A::StepSmaller:
      this->Current.Render.Step = this->EffectiveStep() * (action == A::StepLarger ? 1.25 : 0.8);
      this->Mapper->SetSampleDistance(this->Current.Render.Step);
      this->Show("step: " + Format("%.3g", this->Current.Render.Step), false);
      return true;
    case A::ResolutionDown:
    case A::ResolutionUp:
      this->Current.Render.ResolutionScale = std::max(0.25,
        std::min(1.0,
          this->Current.Render.ResolutionScale + (action == A::ResolutionUp ? 0.125 : -0.125)));
      this->Mapper->SetResolutionScale(this->Current.Render.ResolutionScale);
      this->Show(
        "resolution scale: " + Format("%.3g", this->Current.Render.ResolutionScale), false);
      return true;
    case A::StepExposure:
      this->StepExposure(variant == 0 ? -0.5 : 0.5);
      return true;
    case A::AutoExposure:
      this->UseAutoExposure();
      return true;
    default:
      return false;
  }
}

bool Viewer::Internals::ActOnTransferFunction(ViewerAction action)
{
  using A = ViewerAction;
  switch (action)
  {
    case A::NextPreset:
      this->LoadNextPreset();
      return true;
    case A::SavePreset:
      this->SavePreset();
      return true;
    case A::HistogramScale:
      this->Editing->SetLogHistogram(!this->Editing->GetLogHistogram());
      this->Show(
        std::string("histogram: ") + (this->Editing->GetLogHistogram() ? "log" : "linear"), false);
      return true;
    case A::FitTransferFunction:
    {
      this->Editing->FitToData();
      const auto range = this->Editing->GetRange();
      this->Show("transfer function fitted to the data: [" + Format("%.4g", range[0]) + ", " +
          Format("%.4g", range[1]) + "]",
        false);
      return true;
    }
    case A::ResetTransferFunction:
      this->Editing->Apply(this->SceneTransferFunction);
      this->Preset.clear();
      this->Show("transfer function reset to the scene's (Ctrl+z undoes)", false);
      return true;
    case A::Undo:
    case A::Redo:
      this->UndoStep(action == A::Redo);
      return true;
    case A::DeletePoint:
    {
      const std::string problem = this->Editing->DeleteSelectedPoint();
      this->Show(problem.empty() ? "point removed (Ctrl+z undoes)" : problem, !problem.empty());
      return true;
    }
    case A::TypePointValues:
      this->StartTyping();
      return true;
    default:
      return false;
  }
}

bool Viewer::Internals::ActOnSession(ViewerAction action, Viewer& viewer)
{
  using A = ViewerAction;
  switch (action)
  {
    case A::Screenshot:
      viewer.SaveScreenshot();
      return true;
    case A::SaveScene:
      viewer.SaveSceneFile();
      return true;
    case A::Quit:
      this->Quit(viewer, false);
      return true;

    default:
      return false;
  }
}

void Viewer::Internals::Act(ViewerAction action, int variant, Viewer& viewer)
{
  // Each family of actions takes the actions it knows and leaves the others. (Their switches
  // have defaults, so the compiler no longer names an action none of them takes: this does.)
  if (!(this->ActOnSlices(action, variant) || this->ActOnView(action) ||
        this->ActOnRendering(action, variant) || this->ActOnTransferFunction(action) ||
        this->ActOnSession(action, viewer)))
  {
    this->Show("this key's action (" + std::to_string(int(action)) + ") does nothing yet", true);
  }
}

void Viewer::PressKey(const std::string& keySym, char keyCode, bool control)
{
  Internals& in = *this->Internal;
  const double handled = MonotonicSeconds();
  const std::string sym = keySym.empty() ? KeySymOfCharacter(keyCode) : keySym;
  // A key is a gesture of its own (undo and redo aside, which walk the history).
  const KeyMatch match = in.Typing ? KeyMatch{} : FindKeyBinding(keySym, keyCode, control);
  const bool walksHistory = match.Binding &&
    (match.Binding->Action == ViewerAction::Undo || match.Binding->Action == ViewerAction::Redo);
  if (!in.Typing && !match.Binding)
  {
    return; // not a viewer key
  }
  if (!walksHistory)
  {
    in.BeginGesture(false);
  }
  if (in.Typing)
  {
    in.TypeKey(sym, keyCode);
  }
  else
  {
    if (match.Binding->Action != ViewerAction::Quit)
    {
      in.QuitAskedAt = -1e300; // q, another key, q: the second q asks again
    }
    in.Act(match.Binding->Action, match.Variant, *this);
    // A preview only in the live loop: replayed sessions and tests see full-resolution frames.
    in.PreviewNext = in.PreviewNext || (match.Binding->RedrawsCloud && in.Loop->IsRunning());
  }
  in.SettleGesture();
  in.Keys.push_back({ sym, handled, -1.0 });
  if (in.Keys.size() > KeptKeys)
  {
    in.Keys.erase(in.Keys.begin());
  }
  if (!in.Interactor->GetDone())
  {
    in.Request();
    if (!in.Loop->IsRunning())
    {
      in.Loop->Flush();
    }
  }
}

} // namespace cloudvis
