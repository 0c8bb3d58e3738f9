// The viewer's window and what its keys do. Renderers sharing the window: the 3D view, in the
// four-view layout the three slice views, the editor (bottom 25%), the orientation marker's, and
// in layer 1 over the views a non-interactive overlay with the texts. Texts live in their own
// renderer because the mapper restarts its accumulation whenever another prop of its renderer
// changes: a message must not cost the converged image.
//
// Rendering: nothing here renders directly. Input and changes ask for a frame (Request(): the
// interactor's RenderEvent, a function's ModifiedEvent, a key); the live loop (LiveLoop.h)
// renders once per batch of input and then refines progressively until the mapper has averaged
// MaximumAccumulatedFrames frames (render.accumulate). During a drag the interactor asks for
// DesiredUpdateRate (the mapper lowers its resolution to keep up); when the drag ends it asks
// for StillUpdateRate, and the full-resolution image refines from there.
#include "Viewer.h"

#include "AtomicFile.h"
#include "Background.h"
#include "Display.h"
#include "Errors.h"
#include "ExportRender.h"
#include "ImageWriters.h"
#include "KeyBindings.h"
#include "LiveLoop.h"
#include "OffscreenRender.h"
#include "Presets.h"
#include "SceneJson.h"
#include "SceneLighting.h"
#include "SliceColors.h"
#include "SlicePlanes.h"
#include "SliceViews.h"
#include "StatusOverlay.h"
#include "TransferFunctionEditor.h"
#include "ViewerFiles.h"
#include "vtkCloudViewerInteractorStyle.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkActor.h>
#include <vtkAxesActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkNew.h>
#include <vtkOrientationMarkerWidget.h>
#include <vtkOutlineFilter.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

namespace cloudvis
{
namespace
{
using json = nlohmann::json;

// The editor's share of the window, from the bottom; the views have the rest.
constexpr double EditorHeight = 0.25;
constexpr double ViewerPi = 3.14159265358979323846;
constexpr size_t KeptKeys = 64;

json Vec3Json(const glm::vec3& v)
{
  return json::array({ double(v.x), double(v.y), double(v.z) });
}

json LightToJson(const Light& light)
{
  json j = { { "type", light.Positional ? "point" : "directional" },
    { "position", Vec3Json(light.Position) },
    { "color", Vec3Json(light.Color) },
    { "intensity", double(light.Intensity) } };
  if (light.Positional)
  {
    j["attenuation"] = Vec3Json(light.Attenuation);
  }
  else
  {
    j["focal_point"] = Vec3Json(light.FocalPoint);
  }
  return j;
}

std::string Format(const char* format, double value)
{
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

const char* const AxisNames[3] = { "x", "y", "z" };
} // namespace

struct Viewer::Internals
{
  Scene Current; // lighting, lights, step and resolution as they are now; see CurrentScene()
  TransferFunctionSpec SceneTransferFunction; // what R goes back to
  vtkSmartPointer<vtkImageData> Field;
  ViewerOptions Options;
  std::ostream* Messages = &std::cerr;

  // Declared first: the display must outlive the window.
  std::unique_ptr<DisplayConnection> Display;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> View;
  vtkNew<vtkRenderer> Editor;
  vtkNew<vtkRenderer> Overlay;
  vtkNew<vtkRenderWindowInteractor> Interactor;
  vtkNew<vtkCloudViewerInteractorStyle> Style;
  vtkNew<vtkCloudVolumeMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkSmartPointer<vtkVolumeProperty> Property;
  vtkNew<vtkActor> Outline;
  vtkNew<vtkAxesActor> Axes;
  vtkNew<vtkOrientationMarkerWidget> Orientation;
  vtkNew<vtkInteractorEventRecorder> Recorder;
  std::unique_ptr<StatusOverlay> Status;
  std::unique_ptr<TransferFunctionEditor> Editing;
  std::unique_ptr<SliceColors> Colors;
  std::unique_ptr<SlicePlanes> Slices;
  std::unique_ptr<SliceViews> Views2D;
  std::unique_ptr<LiveLoop> Loop;

  bool FourViews = false;
  bool LightsChanged = false;
  bool Typing = false; // the keys type a point's values
  std::string Typed;
  int PresetIndex = -1;
  bool PreviewNext = false;         // the next frame answers a key that changed the cloud
  bool LastFrameWasPreview = false; // the image is not at full resolution yet
  // Where refinement stood when it last asked for a frame: the frames rendered then and the
  // frames the mapper had accumulated.
  std::pair<long, int> RefinementCheck{ std::numeric_limits<long>::max(), 0 };
  std::string Preset;
  std::vector<std::string> MessageLog;
  std::vector<std::string> SavedFiles;
  std::vector<HandledKey> Keys;
  long FramesRendered = 0;
  double LastFrameAt = -1.0;

  // Renders the window. A preview (asked for by a key that changes the cloud, in the live loop)
  // renders at the interactor's DesiredUpdateRate, so the mapper marches at a resolution that
  // keeps up with it, and leaves the full-resolution image to the refinement that follows.
  void RenderFrame()
  {
    const double start = MonotonicSeconds();
    const bool preview = this->PreviewNext && !this->Style->IsDragging() &&
      this->Window->GetDesiredUpdateRate() <= this->Interactor->GetStillUpdateRate();
    this->PreviewNext = false;
    if (preview)
    {
      this->Window->SetDesiredUpdateRate(this->Interactor->GetDesiredUpdateRate());
    }
    this->Window->Render();
    if (preview)
    {
      this->Window->SetDesiredUpdateRate(this->Interactor->GetStillUpdateRate());
    }
    this->LastFrameWasPreview = preview;
    ++this->FramesRendered;
    this->LastFrameAt = MonotonicSeconds();
    for (HandledKey& key : this->Keys)
    {
      if (key.ShownAt < 0.0 && key.HandledAt <= start)
      {
        key.ShownAt = this->LastFrameAt;
      }
    }
  }

  void Request()
  {
    this->RefinementCheck = { std::numeric_limits<long>::max(), 0 };
    this->Loop->Request();
  }

  int FramesToConverge() const
  {
    return this->Current.Render.Jitter ? this->Mapper->GetMaximumAccumulatedFrames() : 1;
  }

  bool Converged() const
  {
    return !this->Volume->GetVisibility() || !this->Mapper->GetLastError().empty() ||
      (!this->LastFrameWasPreview &&
        this->Mapper->GetNumberOfAccumulatedFrames(this->View) >= this->FramesToConverge());
  }

  // Another frame would improve the image: it has not converged, nothing is being dragged, and
  // the last refinement frame did accumulate (a guard: something that restarted the accumulation
  // on every frame would otherwise keep the loop rendering forever).
  bool RefinementPending()
  {
    if (this->Converged() || this->Style->IsDragging() ||
      this->Window->GetDesiredUpdateRate() > this->Interactor->GetStillUpdateRate())
    {
      return false;
    }
    const int accumulated = this->Mapper->GetNumberOfAccumulatedFrames(this->View);
    if (!this->LastFrameWasPreview && this->FramesRendered > this->RefinementCheck.first &&
      accumulated <= this->RefinementCheck.second)
    {
      return false;
    }
    this->RefinementCheck = { this->FramesRendered, accumulated };
    return true;
  }

  void Show(const std::string& text, bool error)
  {
    this->MessageLog.push_back(text);
    this->Status->ShowMessage(text, error);
    *this->Messages << (error ? "cloudvis: error: " : "cloudvis view: ") << text << std::endl;
  }

  void ApplyLighting() { ConfigureLighting(this->Current, this->View, this->Mapper); }

  std::array<int, 4> PixelViewport(vtkRenderer* renderer) const
  {
    const int* size = const_cast<vtkRenderWindow*>(this->Window.Get())->GetSize();
    double v[4];
    renderer->GetViewport(v);
    return { { int(std::lround(v[0] * size[0])),
      int(std::lround(v[1] * size[1])),
      int(std::lround(v[2] * size[0])),
      int(std::lround(v[3] * size[1])) } };
  }

  std::array<int, 2> ViewSize() const
  {
    int size[2];
    const_cast<vtkRenderer*>(this->View.Get())->GetTiledSize(&size[0], &size[1]);
    return { { size[0], size[1] } };
  }

  bool ColorBarWanted() const
  {
    return this->FourViews || this->Slices->GetObliqueVisible() ||
      this->Slices->GetSliceVisible(0) || this->Slices->GetSliceVisible(1) ||
      this->Slices->GetSliceVisible(2);
  }

  // Places the renderers for the layout: the 3D view alone above the editor, or the four views
  // as 3D Slicer's "four-up" places them (axial top left, 3D top right, sagittal bottom left,
  // coronal bottom right).
  void ApplyLayout()
  {
    const double top = 1.0, bottom = EditorHeight, middle = 0.5 * (top + bottom);
    std::array<double, 4> view{ { 0.0, bottom, 1.0, top } };
    const std::array<std::array<double, 4>, 3> slices = { { { { 0.0, middle, 0.5, top } },
      { { 0.5, bottom, 1.0, middle } },
      { { 0.0, bottom, 0.5, middle } } } };
    if (this->FourViews)
    {
      view = { { 0.5, middle, 1.0, top } };
    }
    this->View->SetViewport(view.data());
    for (int v = 0; v < SliceViews::Count; ++v)
    {
      vtkRenderer* renderer = this->Views2D->GetRenderer(v);
      renderer->SetViewport(slices[size_t(v)].data());
      if (this->FourViews && !this->Window->HasRenderer(renderer))
      {
        this->Window->AddRenderer(renderer);
      }
      else if (!this->FourViews && this->Window->HasRenderer(renderer))
      {
        this->Window->RemoveRenderer(renderer);
      }
    }
    // The orientation marker in the 3D view's bottom left corner, square in pixels. The widget
    // computes its renderer's place when it is enabled, and only then.
    const int* size = this->Window->GetSize();
    const double width = (view[2] - view[0]) * size[0], height = (view[3] - view[1]) * size[1];
    const double side = 0.2 * std::min(width, height);
    this->Orientation->SetEnabled(0);
    this->Orientation->SetViewport(
      0.0, 0.0, side / std::max(1.0, width), side / std::max(1.0, height));
    this->Orientation->SetCurrentRenderer(this->View);
    this->Orientation->SetEnabled(1);
    if (this->Orientation->GetInteractive())
    {
      this->Orientation->SetInteractive(0); // a marker, not a handle (only settable once enabled)
    }
    // The color bar at the 3D view's right edge and the texts, in the overlay's normalized
    // coordinates; the readout right of the marker, or under the slice views.
    const std::array<double, 4> overlayView = {
      { view[0], (view[1] - bottom) / (top - bottom), view[2], (view[3] - bottom) / (top - bottom) }
    };
    const double ow = overlayView[2] - overlayView[0], oh = overlayView[3] - overlayView[1];
    vtkScalarBarActor* bar = this->Colors->GetColorBar();
    bar->SetPosition(overlayView[0] + ow * 0.84, overlayView[1] + oh * 0.2);
    bar->SetPosition2(ow * 0.1, oh * 0.55);
    bar->SetVisibility(this->ColorBarWanted());
    // The readout above the orientation marker, or under the slice views.
    const double overlayHeight = std::max(1.0, (top - bottom) * size[1]);
    this->Status->Place(overlayView,
      this->FourViews ? std::array<double, 2>{ { 0.01, 0.01 } }
                      : std::array<double, 2>{ { overlayView[0] + 0.01,
                          overlayView[1] + (side + 6.0) / overlayHeight } });
    this->Views2D->Update();
    this->Status->LayOut();
  }

  void UpdateReadout()
  {
    const SliceProbe& probe = this->Slices->GetProbe();
    if (!probe.Valid)
    {
      this->Status->SetReadout("");
      return;
    }
    char text[192];
    std::snprintf(text,
      sizeof(text),
      "probe (%.3g, %.3g, %.3g)  voxel [%d, %d, %d]  density %.4g",
      probe.Position[0],
      probe.Position[1],
      probe.Position[2],
      probe.Index[0],
      probe.Index[1],
      probe.Index[2],
      probe.Value);
    this->Status->SetReadout(text);
  }

  // The slices moved, probed or changed their colors (from a plane, a slice view or a key).
  void SlicesChanged()
  {
    this->Views2D->Update();
    this->UpdateReadout();
    this->Colors->GetColorBar()->SetVisibility(this->ColorBarWanted());
    this->Request();
  }

  // The 3D view alone, converged (render.accumulate frames), without the viewer's own
  // decorations (texts, outline, orientation marker), so that `render` draws the same picture.
  RenderedImage Capture(bool floatImage)
  {
    this->Window->SetDesiredUpdateRate(this->Interactor->GetStillUpdateRate());
    const auto texts = this->Status->HideAll();
    this->Outline->VisibilityOff();
    this->Axes->VisibilityOff();
    const bool colorBar = this->Colors->GetColorBar()->GetVisibility() != 0;
    this->Colors->GetColorBar()->VisibilityOff();
    struct Decorations
    {
      Internals& In;
      std::array<bool, 5> Texts;
      bool ColorBar;
      ~Decorations()
      {
        this->In.Status->Restore(this->Texts);
        this->In.Outline->VisibilityOn();
        this->In.Axes->VisibilityOn();
        this->In.Colors->GetColorBar()->SetVisibility(this->ColorBar);
      }
    } restore{ *this, texts, colorBar };
    const int frames = this->FramesToConverge();
    this->RenderFrame();
    for (int i = 0;
         i < frames + 1 && this->Mapper->GetNumberOfAccumulatedFrames(this->View) < frames;
         ++i)
    {
      this->RenderFrame();
    }
    RenderedImage image;
    try
    {
      double viewport[4];
      this->View->GetViewport(viewport);
      image = GrabWindow(this->Window, viewport);
    }
    catch (const InputError&)
    {
      throw InputError("screenshot: could not read the image back from the window");
    }
    if (floatImage)
    {
      this->Window->MakeCurrent();
      ReadFloatImage(this->Mapper, this->View, image, "screenshot");
    }
    return image;
  }

  // The first directional light, or -1.
  int FirstDirectionalLight() const
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

  void MoveLight(double azimuthDegrees, double elevationDegrees)
  {
    const int index = this->FirstDirectionalLight();
    if (index < 0)
    {
      this->Show("the scene has no directional light to move", true);
      return;
    }
    Light& light = this->Current.Lights[size_t(index)];
    const glm::dvec3 d = glm::dvec3(light.Position) - glm::dvec3(light.FocalPoint);
    const double r = glm::length(d);
    double azimuth = std::atan2(d.x, d.z) + azimuthDegrees * ViewerPi / 180.0;
    double elevation =
      std::asin(std::max(-1.0, std::min(1.0, d.y / r))) + elevationDegrees * ViewerPi / 180.0;
    elevation = std::max(-89.0 * ViewerPi / 180.0, std::min(89.0 * ViewerPi / 180.0, elevation));
    const glm::dvec3 moved(r * std::cos(elevation) * std::sin(azimuth),
      r * std::sin(elevation),
      r * std::cos(elevation) * std::cos(azimuth));
    light.Position = glm::vec3(glm::dvec3(light.FocalPoint) + moved);
    this->LightsChanged = true;
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

  double EffectiveStep() const
  {
    if (this->Current.Render.Step > 0.0)
    {
      return this->Current.Render.Step;
    }
    const double* spacing = this->Field->GetSpacing();
    return std::min({ spacing[0], spacing[1], spacing[2] });
  }

  void LoadNextPreset()
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

  void SavePreset()
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

  // A key while typing a point's values: characters of numbers, BackSpace, Enter, Esc.
  void TypeKey(const std::string& keySym, char keyCode)
  {
    using Function = TransferFunctionEditor::Function;
    const Function function = this->Editing->GetSelectedFunction();
    const std::string what = std::string(TransferFunctionEditor::FunctionName(function)) +
      " point " + std::to_string(this->Editing->GetSelectedPoint());
    if (keySym == "Escape")
    {
      this->Typing = false;
      this->Editing->SetEntry("");
      this->Show("typing cancelled; the point is unchanged", false);
      return;
    }
    if (keySym == "Return" || keySym == "KP_Enter")
    {
      const std::string problem = this->Editing->SetSelectedPointValues(this->Typed);
      if (!problem.empty())
      {
        this->Show(problem + " (Esc cancels)", true);
        return;
      }
      this->Typing = false;
      this->Editing->SetEntry("");
      this->Show(what + ": " + this->Editing->GetSelectedPointValues() + " (Ctrl+z undoes)", false);
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
    this->Editing->SetEntry(what + " (now " + this->Editing->GetSelectedPointValues() + "), type " +
      (function == Function::Opacity ? "density opacity" : "density r g b") + ": " + this->Typed +
      "_   Enter applies, Esc cancels");
  }

  void StartTyping()
  {
    if (this->Editing->GetSelectedPoint() < 0)
    {
      this->Show("no point is selected: click one in the editor first", true);
      return;
    }
    this->Typing = true;
    this->Typed.clear();
    this->TypeKey("", 0);
  }

  void ToggleSlice(int axis)
  {
    const bool visible = !this->Slices->GetSliceVisible(axis);
    this->Slices->SetSliceVisible(axis, visible);
    this->Show(std::string("slice across ") + AxisNames[axis] + ": " +
        (visible ? "shown at " + std::string(AxisNames[axis]) + " = " +
              Format("%.3g", this->Slices->GetSlicePosition(axis))
                 : std::string("hidden")),
      false);
    this->SlicesChanged();
  }

  void Act(ViewerAction action, int variant, Viewer& viewer)
  {
    using A = ViewerAction;
    switch (action)
    {
      case A::ToggleSlice:
        this->ToggleSlice(variant);
        break;
      case A::ToggleOblique:
        this->Slices->SetObliqueVisible(!this->Slices->GetObliqueVisible());
        this->Show(
          std::string("oblique slice: ") + (this->Slices->GetObliqueVisible() ? "shown" : "hidden"),
          false);
        this->SlicesChanged();
        break;
      case A::CycleSliceColors:
        this->Colors->NextColormap();
        this->Show("slice colors: " + this->Colors->GetColormap(), false);
        this->SlicesChanged();
        break;
      case A::ToggleLayout:
        this->FourViews = !this->FourViews;
        this->ApplyLayout();
        this->Show(
          this->FourViews ? "four views: 3D, axial, coronal, sagittal" : "the 3D view alone",
          false);
        break;
      case A::ToggleVolume:
        this->Volume->SetVisibility(!this->Volume->GetVisibility());
        this->Show(
          this->Volume->GetVisibility() ? "cloud shown" : "cloud hidden (v shows it)", false);
        break;
      case A::CycleLighting:
      {
        const std::vector<std::string> names = LightingModelNames();
        const std::string current = LightingModelName(this->Current.Render.Lighting);
        const auto found = std::find(names.begin(), names.end(), current);
        const size_t next =
          found == names.end() ? 0 : size_t(found - names.begin() + 1) % names.size();
        this->Current.Render.Lighting = *FindLightingModel(names[next]);
        this->ApplyLighting();
        this->Show("lighting: " + names[next], false);
        break;
      }
      case A::MoveLightAzimuth:
        this->MoveLight(variant == 0 ? -10.0 : 10.0, 0.0);
        break;
      case A::MoveLightElevation:
        this->MoveLight(0.0, variant == 0 ? 10.0 : -10.0);
        break;
      case A::StepLarger:
      case A::StepSmaller:
        this->Current.Render.Step = this->EffectiveStep() * (action == A::StepLarger ? 1.25 : 0.8);
        this->Mapper->SetSampleDistance(this->Current.Render.Step);
        this->Show("step: " + Format("%.3g", this->Current.Render.Step), false);
        break;
      case A::ResolutionDown:
      case A::ResolutionUp:
        this->Current.Render.ResolutionScale = std::max(0.25,
          std::min(1.0,
            this->Current.Render.ResolutionScale + (action == A::ResolutionUp ? 0.125 : -0.125)));
        this->Mapper->SetResolutionScale(this->Current.Render.ResolutionScale);
        this->Show(
          "resolution scale: " + Format("%.3g", this->Current.Render.ResolutionScale), false);
        break;
      case A::NextPreset:
        this->LoadNextPreset();
        break;
      case A::SavePreset:
        this->SavePreset();
        break;
      case A::HistogramScale:
        this->Editing->SetLogHistogram(!this->Editing->GetLogHistogram());
        this->Show(
          std::string("histogram: ") + (this->Editing->GetLogHistogram() ? "log" : "linear"),
          false);
        break;
      case A::FitTransferFunction:
      {
        this->Editing->FitToData();
        const auto range = this->Editing->GetRange();
        this->Show("transfer function fitted to the data: [" + Format("%.4g", range[0]) + ", " +
            Format("%.4g", range[1]) + "]",
          false);
        break;
      }
      case A::ResetTransferFunction:
        this->Editing->Apply(this->SceneTransferFunction);
        this->Preset.clear();
        this->Show("transfer function reset to the scene's (Ctrl+z undoes)", false);
        break;
      case A::Undo:
        this->Show(this->Editing->Undo() ? "undone" : "nothing to undo", false);
        break;
      case A::Redo:
        this->Show(this->Editing->Redo() ? "redone" : "nothing to redo", false);
        break;
      case A::DeletePoint:
      {
        const std::string problem = this->Editing->DeleteSelectedPoint();
        this->Show(problem.empty() ? "point removed (Ctrl+z undoes)" : problem, !problem.empty());
        break;
      }
      case A::TypePointValues:
        this->StartTyping();
        break;
      case A::Screenshot:
        viewer.SaveScreenshot();
        break;
      case A::SaveScene:
        viewer.SaveSceneFile();
        break;
      case A::ResetCamera:
        ApplyCamera(
          this->Current.Camera, this->Field->GetBounds(), this->View, this->Current.Source);
        break;
      case A::Help:
        this->Status->SetHelpVisible(!this->Status->GetHelpVisible());
        break;
      case A::Quit:
        this->Interactor->TerminateApp();
        break;
    }
  }
};

Viewer::Viewer(const Scene& scene,
  vtkSmartPointer<vtkImageData> field,
  const ViewerOptions& options)
  : Internal(new Internals)
{
  Internals& in = *this->Internal;
  in.Current = scene;
  in.SceneTransferFunction = scene.TransferFunction;
  in.Field = field;
  in.Options = options;
  in.FourViews = options.FourViews;
  in.Messages = options.Messages ? options.Messages : &std::cerr;
  in.Display = std::make_unique<DisplayConnection>("cloudvis view ...");

  vtkRenderWindow* window = in.Window;
  window->SetDisplayId(in.Display->Get());
  // As in RenderOffscreen: an observed ExitEvent turns VTK's abort() on a failed GL context into
  // an error the mapper reports.
  vtkNew<vtkCallbackCommand> onExit;
  window->AddObserver(vtkCommand::ExitEvent, onExit);
  window->SetMultiSamples(0);
  window->SetSize(options.WindowSize[0], options.WindowSize[1]);
  window->SetWindowName("cloudvis view");
  window->SetNumberOfLayers(2);

  ApplyBackground(in.Current, in.View);
  window->AddRenderer(in.View);
  in.Mapper->SetInputData(field);
  ConfigureMapper(in.Mapper, in.Current.Render);
  in.ApplyLighting();
  in.Property = MakeVolumeProperty(in.Current.TransferFunction);
  in.Volume->SetMapper(in.Mapper);
  in.Volume->SetProperty(in.Property);
  // The slices are picked through the cloud: a picker that stopped at the volume (vtkCellPicker
  // picks volumes by their opacity) would never reach them.
  in.Volume->PickableOff();
  in.View->AddVolume(in.Volume);
  // The field's bounding box, as ParaView outlines a dataset.
  vtkNew<vtkOutlineFilter> outline;
  outline->SetInputData(field);
  vtkNew<vtkPolyDataMapper> outlineMapper;
  outlineMapper->SetInputConnection(outline->GetOutputPort());
  in.Outline->SetMapper(outlineMapper);
  in.Outline->GetProperty()->SetColor(0.75, 0.75, 0.8);
  in.Outline->GetProperty()->LightingOff();
  in.Outline->PickableOff();
  in.View->AddActor(in.Outline);
  ApplyCamera(in.Current.Camera, field->GetBounds(), in.View, in.Current.Source);

  in.Editor->SetViewport(0.0, 0.0, 1.0, EditorHeight);
  in.Editor->SetBackground(0.96, 0.96, 0.97);
  window->AddRenderer(in.Editor);

  in.Overlay->SetViewport(0.0, EditorHeight, 1.0, 1.0);
  in.Overlay->SetLayer(1);
  in.Overlay->InteractiveOff();
  window->AddRenderer(in.Overlay);
  in.Status = std::make_unique<StatusOverlay>(in.Overlay);

  vtkRenderWindowInteractor* interactor = in.Interactor;
  interactor->SetRenderWindow(window);
  interactor->SetDesiredUpdateRate(20.0);
  interactor->SetStillUpdateRate(0.001);
  // Styles and widgets render through the interactor: its RenderEvent becomes a request to the
  // live loop, which renders (LiveLoop.h).
  interactor->EnableRenderOff();
  in.Loop = std::make_unique<LiveLoop>(interactor,
    LiveLoop::Hooks{ [&in] { in.RenderFrame(); },
      [&in] { return in.RefinementPending(); },
      [&in]
      {
        bool changed = false;
        const double next = in.Status->Tick(changed);
        if (changed)
        {
          in.Loop->Request();
        }
        return next;
      },
      [this] { this->WriteStateFile(); } });
  vtkNew<vtkCallbackCommand> requested;
  requested->SetClientData(&in);
  requested->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*) { static_cast<Internals*>(data)->Request(); });
  interactor->AddObserver(vtkCommand::RenderEvent, requested);
  // Outside the loop (playback), an input event renders once it has been handled by everyone:
  // this observer comes after the style's and the widgets'.
  vtkNew<vtkCallbackCommand> handled;
  handled->SetClientData(&in);
  handled->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*)
    {
      auto& viewer = *static_cast<Internals*>(data);
      if (!viewer.Loop->IsRunning())
      {
        viewer.Loop->Flush();
      }
    });
  for (unsigned long event : { vtkCommand::MouseMoveEvent,
         vtkCommand::LeftButtonPressEvent,
         vtkCommand::LeftButtonReleaseEvent,
         vtkCommand::MiddleButtonPressEvent,
         vtkCommand::MiddleButtonReleaseEvent,
         vtkCommand::RightButtonPressEvent,
         vtkCommand::RightButtonReleaseEvent,
         vtkCommand::MouseWheelForwardEvent,
         vtkCommand::MouseWheelBackwardEvent,
         vtkCommand::KeyPressEvent,
         vtkCommand::KeyReleaseEvent })
  {
    interactor->AddObserver(event, handled, -100.0);
  }
  in.Style->SetDefaultRenderer(in.View);
  interactor->SetInteractorStyle(in.Style);

  in.Editing = std::make_unique<TransferFunctionEditor>(in.Property, field, in.Editor);
  in.Style->SetEditor(in.Editor, in.Editing->GetScene());
  in.Style->KeyHandler = [this](const std::string& keySym, char keyCode, bool control)
  { this->PressKey(keySym, keyCode, control); };
  in.Style->DragHandler = [&in](bool dragging)
  {
    in.Window->SetDesiredUpdateRate(
      dragging ? in.Interactor->GetDesiredUpdateRate() : in.Interactor->GetStillUpdateRate());
    if (dragging)
    {
      in.Editing->BeginDrag();
    }
    else
    {
      in.Editing->EndDrag();
    }
    in.Request();
  };

  // A changed function re-renders the 3D view (and the slices colored by it); a drag changes the
  // function several times per mouse move, and the requests become one frame.
  vtkNew<vtkCallbackCommand> changed;
  changed->SetClientData(&in);
  changed->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*)
    {
      auto& viewer = *static_cast<Internals*>(data);
      if (viewer.Colors && viewer.Colors->GetColormap() == "transfer function")
      {
        viewer.Colors->Update();
      }
      if (viewer.Loop->IsRunning())
      {
        viewer.Request();
      }
    });
  in.Property->GetScalarOpacity()->AddObserver(vtkCommand::ModifiedEvent, changed);
  in.Property->GetRGBTransferFunction()->AddObserver(vtkCommand::ModifiedEvent, changed);

  interactor->Initialize();
  double range[2];
  field->GetScalarRange(range);
  in.Colors = std::make_unique<SliceColors>(
    std::array<double, 2>{ { range[0], range[1] } }, in.Property->GetRGBTransferFunction());
  in.Overlay->AddActor2D(in.Colors->GetColorBar());
  in.Slices = std::make_unique<SlicePlanes>(field, in.View, interactor, *in.Colors);
  in.Slices->Changed = [&in] { in.SlicesChanged(); };
  in.Views2D = std::make_unique<SliceViews>(field, *in.Slices, *in.Colors);
  in.Views2D->Changed = [&in] { in.SlicesChanged(); };
  in.Style->SliceViewMouse =
    [&in](vtkCloudViewerInteractorStyle::MouseAction action, int button, int x, int y)
  { return in.Views2D->Mouse(action, button, x, y); };

  in.Orientation->SetOrientationMarker(in.Axes);
  in.Orientation->SetInteractor(interactor);
  in.ApplyLayout();

  in.RenderFrame();
  if (!in.Mapper->GetLastError().empty())
  {
    throw InputError(scene.Source + ": " + in.Mapper->GetLastError());
  }

  if (!options.RecordFile.empty())
  {
    in.Recorder->SetInteractor(interactor);
    in.Recorder->KeyPressActivationOff();
    in.Recorder->SetFileName(options.RecordFile.c_str());
    in.Recorder->On();
    in.Recorder->Record();
  }
}

Viewer::~Viewer()
{
  Internals& in = *this->Internal;
  if (!in.Options.RecordFile.empty())
  {
    in.Recorder->Stop();
    in.Recorder->Off();
  }
  in.Orientation->SetEnabled(0);
  in.Style->SliceViewMouse = nullptr;
  in.Views2D.reset();
  in.Slices.reset();
  in.Style->KeyHandler = nullptr;
  in.Style->DragHandler = nullptr;
  in.Style->SetEditor(nullptr, nullptr);
  in.Editing.reset();
  in.Window->Finalize();
}

void Viewer::PlayFile(const std::string& path)
{
  std::ifstream file(path);
  if (!file)
  {
    throw InputError(path + ": cannot read the recording");
  }
  std::stringstream text;
  text << file.rdbuf();
  this->PlayString(text.str());
}

void Viewer::PlayString(const std::string& events)
{
  Internals& in = *this->Internal;
  vtkNew<vtkInteractorEventRecorder> player;
  player->SetInteractor(in.Interactor);
  player->KeyPressActivationOff();
  player->ReadFromInputStringOn();
  player->SetInputString(events.c_str());
  player->Play();
  player->Stop();
  in.Loop->Flush();
  this->WriteStateFile();
}

void Viewer::Start()
{
  Internals& in = *this->Internal;
  this->WriteStateFile();
  in.Loop->Run();
}

void Viewer::PressKey(const std::string& keySym, char keyCode, bool control)
{
  Internals& in = *this->Internal;
  const double handled = MonotonicSeconds();
  const std::string sym = keySym.empty() ? KeySymOfCharacter(keyCode) : keySym;
  if (in.Typing)
  {
    in.TypeKey(sym, keyCode);
  }
  else
  {
    const KeyMatch match = FindKeyBinding(keySym, keyCode, control);
    if (!match.Binding)
    {
      return; // not a viewer key
    }
    in.Act(match.Binding->Action, match.Variant, *this);
    // A preview only in the live loop: replayed sessions and tests see full-resolution frames.
    in.PreviewNext = in.PreviewNext || (match.Binding->RedrawsCloud && in.Loop->IsRunning());
  }
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

ViewerState Viewer::State() const
{
  const Internals& in = *this->Internal;
  ViewerState state;
  state.Lighting = in.Current.Render.Lighting;
  for (int axis = 0; axis < 3; ++axis)
  {
    state.SliceVisible[size_t(axis)] = in.Slices->GetSliceVisible(axis);
    state.SlicePosition[size_t(axis)] = in.Slices->GetSlicePosition(axis);
    state.ProbedValue[size_t(axis)] = in.Slices->GetProbedValue(axis);
    state.SliceIndex[size_t(axis)] = in.Slices->GetSliceIndex(axis);
  }
  state.ObliqueVisible = in.Slices->GetObliqueVisible();
  state.ObliqueOrigin = in.Slices->GetObliqueOrigin();
  state.ObliqueNormal = in.Slices->GetObliqueNormal();
  state.ObliqueCutPoints = in.Slices->GetObliqueCutPoints();
  state.TransferFunction = TransferFunctionOf(in.Property);
  state.Step = in.Current.Render.Step;
  state.ResolutionScale = in.Current.Render.ResolutionScale;
  state.HelpVisible = in.Status->GetHelpVisible();
  state.LogHistogram = in.Editing->GetLogHistogram();
  state.EditorRange = in.Editing->GetRange();
  const int light = in.FirstDirectionalLight();
  if (light >= 0)
  {
    const glm::vec3& p = in.Current.Lights[size_t(light)].Position;
    state.FirstLightPosition = { { p.x, p.y, p.z } };
  }
  state.Preset = in.Preset;
  state.Messages = in.MessageLog;
  state.SavedFiles = in.SavedFiles;
  state.AccumulatedFrames = in.Mapper->GetNumberOfAccumulatedFrames(in.View);
  state.ViewSize = in.ViewSize();

  state.FramesRendered = in.FramesRendered;
  state.LastFrameAt = in.LastFrameAt;
  state.Converged = in.Converged();
  state.Keys = in.Keys;
  vtkCamera* camera = const_cast<vtkRenderer*>(in.View.Get())->GetActiveCamera();
  camera->GetPosition(state.CameraPosition.data());
  camera->GetFocalPoint(state.CameraFocalPoint.data());
  camera->GetViewUp(state.CameraViewUp.data());
  state.FourViews = in.FourViews;
  state.VolumeVisible = in.Volume->GetVisibility() != 0;
  state.HintVisible = in.Status->GetHintVisible();
  state.ColorBarVisible = in.Colors->GetColorBar()->GetVisibility() != 0;
  state.Message = in.Status->GetMessage();
  state.Readout = in.Status->GetReadout();
  state.WindowId = static_cast<unsigned long>(reinterpret_cast<uintptr_t>(
    const_cast<vtkRenderWindow*>(in.Window.Get())->GetGenericWindowId()));
  const int* size = const_cast<vtkRenderWindow*>(in.Window.Get())->GetSize();
  state.WindowSize = { { size[0], size[1] } };
  state.Viewports.push_back({ "3d", in.PixelViewport(in.View) });
  state.Viewports.push_back({ "editor", in.PixelViewport(in.Editor) });
  if (in.FourViews)
  {
    for (int v = 0; v < SliceViews::Count; ++v)
    {
      if (!in.Views2D->GetRenderer(v)->GetRenderWindow())
      {
        continue; // not drawn
      }
      state.Viewports.push_back(
        { SliceViews::Name(v), in.PixelViewport(in.Views2D->GetRenderer(v)) });
    }
  }
  state.SliceWindowLevel = in.Colors->GetWindowLevel();
  state.SliceColors = in.Colors->GetColormap();
  const SliceProbe& probe = in.Slices->GetProbe();
  state.ProbeValid = probe.Valid;
  state.ProbeIndex = probe.Index;
  state.ProbeValue = probe.Value;
  using Function = TransferFunctionEditor::Function;
  state.OpacityPointPixels = in.Editing->GetPointPixels(Function::Opacity);
  state.ColorPointPixels = in.Editing->GetPointPixels(Function::Color);
  state.ColorStripPixels = in.Editing->GetColorStripPixels();
  state.SelectedFunction = TransferFunctionEditor::FunctionName(in.Editing->GetSelectedFunction());
  state.SelectedPoint = in.Editing->GetSelectedPoint();
  state.EditorInfo = in.Editing->GetInfoText();
  state.EditorTooltips = in.Editing->GetTooltipsVisible();
  state.Typing = in.Typing;
  state.UndoDepth = in.Editing->GetUndoDepth();
  state.RedoDepth = in.Editing->GetRedoDepth();
  return state;
}

void Viewer::WriteStateFile() const
{
  const Internals& in = *this->Internal;
  if (in.Options.StateFile.empty())
  {
    return;
  }
  try
  {
    WriteTextFile(in.Options.StateFile, ViewerStateJson(this->State()).dump() + "\n", "the state");
  }
  catch (const std::exception& e)
  {
    *in.Messages << "cloudvis: error: " << e.what() << std::endl;
  }
}

Scene Viewer::CurrentScene() const
{
  const Internals& in = *this->Internal;
  Scene scene = in.Current;
  scene.TransferFunction = TransferFunctionOf(in.Property);
  scene.Render.Size = in.ViewSize();
  vtkCamera* camera = const_cast<vtkRenderer*>(in.View.Get())->GetActiveCamera();
  std::array<double, 3> position, focal, up;
  camera->GetPosition(position.data());
  camera->GetFocalPoint(focal.data());
  camera->GetViewUp(up.data());
  scene.Camera.Position = position;
  scene.Camera.FocalPoint = focal;
  scene.Camera.ViewUp = up;
  scene.Camera.Orbit.reset();
  scene.Camera.ViewAngle = camera->GetViewAngle();
  if (in.LightsChanged)
  {
    // SceneToJson keeps the document's lights: write the moved ones there.
    json lights = json::array();
    for (const Light& light : scene.Lights)
    {
      lights.push_back(LightToJson(light));
    }
    if (!scene.Document.is_object())
    {
      scene.Document = json::object();
    }
    scene.Document["lights"] = lights;
    // A sky without background.sun follows the first light when the scene is read again: keep
    // the sun it has now.
    if (scene.BackgroundStyle.Type == BackgroundType::Sky &&
      scene.Document.contains("background") && scene.Document["background"].is_object() &&
      !scene.Document["background"].contains("sun"))
    {
      const auto sun = SkySunDirection(scene.BackgroundStyle);
      scene.Document["background"]["sun"] = { sun[0], sun[1], sun[2] };
    }
  }
  return scene;
}

nlohmann::json Viewer::CurrentSceneJson() const
{
  const Scene scene = this->CurrentScene();
  ResolvedCamera camera;
  camera.Position = *scene.Camera.Position;
  camera.FocalPoint = *scene.Camera.FocalPoint;
  camera.ViewUp = scene.Camera.ViewUp;
  return SceneToJson(scene, camera);
}

void Viewer::SaveScene(const std::string& path) const
{
  WriteTextFile(path, this->CurrentSceneJson().dump(2) + "\n", "the scene");
}

void Viewer::SaveScreenshot()
{
  Internals& in = *this->Internal;
  try
  {
    const bool floatImage = in.Current.Render.ResolutionScale >= 1.0;
    const std::vector<std::string> paths = WriteScreenshot(
      in.Options.OutputDirectory,
      floatImage,
      [&] { return in.Capture(floatImage); },
      this->CurrentSceneJson().dump(-1, ' ', true),
      in.Options.CommandLine);
    in.SavedFiles.insert(in.SavedFiles.end(), paths.begin(), paths.end());
    if (!floatImage)
    {
      in.Show(
        "saved " + paths[0] + "; no EXR: the float image needs resolution scale 1 (press ])", true);
      return;
    }
    in.Show("saved " + paths[0] + " and " + paths[1], false);
  }
  catch (const std::exception& e)
  {
    in.Show(e.what(), true);
  }
}

void Viewer::SaveWindowImage(const std::string& path)
{
  Internals& in = *this->Internal;
  in.RenderFrame();
  const RenderedImage image = GrabWindow(in.Window);
  WriteImage(image, path);
}

void Viewer::SaveSceneFile()
{
  Internals& in = *this->Internal;
  try
  {
    const std::string path =
      NextFreeBase(in.Options.OutputDirectory, "cloudvis-view-", { ".json" }) + ".json";
    CheckOutputTarget(path);
    this->SaveScene(path);
    in.SavedFiles.push_back(path);
    in.Show("saved " + path + " (cloudvis render " + path + " -o IMAGE.png)", false);
  }
  catch (const std::exception& e)
  {
    in.Show(e.what(), true);
  }
}

} // namespace cloudvis
