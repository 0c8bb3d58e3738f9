// The viewer's window and its keys. Three renderers share the window: the 3D view (top 75%),
// the editor (bottom 25%) and, in layer 1 over the 3D view, a non-interactive overlay with the
// help and message texts. Text lives in its own renderer because the mapper restarts its
// accumulation whenever another prop of its renderer changes: a message must not cost the
// converged image.
//
// Progressive refinement: while the event loop runs, a repeating timer re-renders until the
// mapper has averaged MaximumAccumulatedFrames frames (render.accumulate), and renders once when
// a transfer function changed. During a camera drag the interactor asks for DesiredUpdateRate
// (the mapper lowers its resolution to keep up); when the drag ends it asks for StillUpdateRate,
// and the full-resolution image refines from there.
#include "Viewer.h"

#include "AtomicFile.h"
#include "Background.h"
#include "Display.h"
#include "Errors.h"
#include "ExportRender.h"
#include "FieldIO.h"
#include "ImageWriters.h"
#include "InputFiles.h"
#include "OffscreenRender.h"
#include "Presets.h"
#include "SceneField.h"
#include "SceneJson.h"
#include "SceneLighting.h"
#include "SlicePlanes.h"
#include "TransferFunctionEditor.h"
#include "Utf8.h"
#include "vtkCloudViewerInteractorStyle.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace cloudvis
{
namespace
{
using json = nlohmann::json;

// The 3D view's share of the window, from the top; the editor has the rest.
constexpr double EditorHeight = 0.25;
constexpr double ViewerPi = 3.14159265358979323846;

const char* const HelpText =
  "mouse, 3D view: left drag rotate, middle drag pan, right drag / wheel zoom\n"
  "mouse, slices: left cursor + value, middle drag move, right drag window/level\n"
  "mouse, editor: click add point, drag move, Delete remove\n"
  "x y z  toggle the slice across x, y, z      o  toggle the oblique slice\n"
  "m  lighting model (none, derivative, march)  arrows  move the first light\n"
  "+ -  step size larger / smaller            [ ]  resolution scale down / up\n"
  "p  next preset   P  save the transfer function as a preset\n"
  "l  histogram log / linear   f  fit the transfer function to the data\n"
  "s  screenshot (PNG + EXR)   w  save the scene (JSON)   r  reset the camera\n"
  "h  this help   q / Esc  quit";

bool Exists(const std::string& path)
{
  struct stat info;
  return ::stat(path.c_str(), &info) == 0;
}

std::string JoinPath(const std::string& directory, const std::string& name)
{
  if (directory.empty() || directory == ".")
  {
    return name;
  }
  return directory + (directory.back() == '/' ? "" : "/") + name;
}

// DIR/PREFIXNNN with the first NNN (001, 002, ...) for which no file with any of `extensions`
// exists yet.
std::string NextFreeBase(const std::string& directory, const std::string& prefix,
  const std::vector<std::string>& extensions)
{
  for (int n = 1; n < 100000; ++n)
  {
    char number[16];
    std::snprintf(number, sizeof(number), "%03d", n);
    const std::string base = JoinPath(directory, prefix + number);
    if (std::none_of(extensions.begin(), extensions.end(),
          [&](const std::string& e) { return Exists(base + e); }))
    {
      return base;
    }
  }
  throw InputError(JoinPath(directory, prefix) + "NNN: every number is taken");
}

json Vec3Json(const glm::dvec3& v)
{
  return json::array({ v.x, v.y, v.z });
}

json LightToJson(const Light& light)
{
  json j = { { "type", light.Positional ? "point" : "directional" },
    { "position", Vec3Json(light.Position) }, { "color", Vec3Json(light.Color) },
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

} // namespace

struct Viewer::Internals
{
  Scene Current; // lighting, lights, step and resolution as they are now; see CurrentScene()
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
  vtkNew<vtkTextActor> Help;
  vtkNew<vtkTextActor> Message;
  vtkNew<vtkInteractorEventRecorder> Recorder;
  std::unique_ptr<TransferFunctionEditor> Editing;
  std::unique_ptr<SlicePlanes> Slices;

  bool LightsChanged = false;
  bool NeedsRender = false;
  bool Rendering = false;
  int PresetIndex = -1;
  std::string Preset;
  std::vector<std::string> MessageLog;
  std::vector<std::string> SavedFiles;

  void Render()
  {
    this->NeedsRender = false;
    this->Window->Render();
  }

  void Show(const std::string& message, bool error)
  {
    // Messages quote paths and user text, which may hold bytes that are not UTF-8.
    const std::string text = EscapeInvalidUtf8(message);
    this->MessageLog.push_back(text);
    this->Message->SetInput(text.c_str());
    this->Message->GetTextProperty()->SetColor(error ? 1.0 : 0.85, error ? 0.45 : 0.95, error ? 0.4 : 0.85);
    this->Message->VisibilityOn();
    *this->Messages << (error ? "cloudvis: error: " : "cloudvis view: ") << text << std::endl;
  }

  int FramesToConverge() const
  {
    return this->Current.Render.Jitter ? this->Mapper->GetMaximumAccumulatedFrames() : 1;
  }

  void ApplyLighting() { ConfigureLighting(this->Current, this->View, this->Mapper); }

  // The 3D view alone, converged (render.accumulate frames) and without the overlay texts.
  RenderedImage Capture(bool floatImage)
  {
    this->Window->SetDesiredUpdateRate(this->Interactor->GetStillUpdateRate());
    const bool help = this->Help->GetVisibility() != 0;
    const bool message = this->Message->GetVisibility() != 0;
    this->Help->VisibilityOff();
    this->Message->VisibilityOff();
    const int frames = this->FramesToConverge();
    this->Render();
    for (int i = 0; i < frames + 1 && this->Mapper->GetNumberOfAccumulatedFrames(this->View) < frames; ++i)
    {
      this->Render();
    }
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(this->Window);
    grab->SetViewport(this->View->GetViewport());
    grab->SetInputBufferTypeToRGB();
    grab->ReadFrontBufferOff();
    grab->ShouldRerenderOff();
    grab->Update();
    RenderedImage image;
    vtkImageData* pixels = grab->GetOutput();
    auto* data = vtkUnsignedCharArray::SafeDownCast(pixels->GetPointData()->GetScalars());
    int dimensions[3];
    pixels->GetDimensions(dimensions);
    this->Help->SetVisibility(help);
    this->Message->SetVisibility(message);
    if (!data || data->GetNumberOfComponents() != 3)
    {
      throw InputError("screenshot: could not read the image back from the window");
    }
    image.Width = dimensions[0];
    image.Height = dimensions[1];
    image.RGB.assign(data->GetPointer(0), data->GetPointer(0) + data->GetNumberOfValues());
    if (floatImage)
    {
      this->Window->MakeCurrent();
      ReadFloatImage(this->Mapper, this->View, image, "screenshot");
    }
    return image;
  }

  std::array<int, 2> ViewSize() const
  {
    int size[2];
    const_cast<vtkRenderer*>(this->View.Get())->GetTiledSize(&size[0], &size[1]);
    return { { size[0], size[1] } };
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
    const glm::dvec3 d = light.Position - light.FocalPoint;
    const double r = glm::length(d);
    double azimuth = std::atan2(d.x, d.z) + azimuthDegrees * ViewerPi / 180.0;
    double elevation = std::asin(std::max(-1.0, std::min(1.0, d.y / r))) + elevationDegrees * ViewerPi / 180.0;
    elevation = std::max(-89.0 * ViewerPi / 180.0, std::min(89.0 * ViewerPi / 180.0, elevation));
    const glm::dvec3 moved(r * std::cos(elevation) * std::sin(azimuth), r * std::sin(elevation),
      r * std::cos(elevation) * std::cos(azimuth));
    light.Position = light.FocalPoint + moved;
    this->LightsChanged = true;
    this->ApplyLighting();
    char text[128];
    std::snprintf(text, sizeof(text), "light %d: azimuth %.0f, elevation %.0f degrees", index,
      azimuth * 180.0 / ViewerPi, elevation * 180.0 / ViewerPi);
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
      // Through the scene's own reader: a preset is checked exactly as transfer_function.preset.
      const json document = { { "transfer_function", { { "preset", name } } } };
      const Scene loaded = SceneFromDocument(document, "preset " + name, "");
      SetTransferFunction(this->Property, loaded.TransferFunction);
      this->Editing->UpdateRange();
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
        NextFreeBase(this->Options.OutputDirectory, "cloudvis-preset-", { ".json" }) + ".json";
      CheckOutputTarget(path);
      const TransferFunctionSpec spec = TransferFunctionOf(this->Property);
      const auto slash = path.find_last_of('/');
      const std::string stem =
        path.substr(slash == std::string::npos ? 0 : slash + 1, path.size() - 5 - (slash == std::string::npos ? 0 : slash + 1));
      const json preset = { { "name", stem },
        { "description", "saved by cloudvis view" }, { "opacity", spec.Opacity },
        { "color", spec.Color }, { "unit_distance", spec.UnitDistance } };
      WriteFileAtomically(path, [&](const std::string& temporary) {
        std::ofstream out(temporary);
        out << preset.dump(2) << "\n";
        out.close();
        if (!out)
        {
          throw InputError(path + ": cannot write the preset");
        }
      });
      this->SavedFiles.push_back(path);
      this->Show("saved preset " + path, false);
    }
    catch (const std::exception& e)
    {
      this->Show(e.what(), true);
    }
  }
};

Viewer::Viewer(
  const Scene& scene, vtkSmartPointer<vtkImageData> field, const ViewerOptions& options)
  : Internal(new Internals)
{
  Internals& in = *this->Internal;
  in.Current = scene;
  in.Field = field;
  in.Options = options;
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

  in.View->SetViewport(0.0, EditorHeight, 1.0, 1.0);
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
  ApplyCamera(in.Current.Camera, field->GetBounds(), in.View, in.Current.Source);

  in.Editor->SetViewport(0.0, 0.0, 1.0, EditorHeight);
  in.Editor->SetBackground(0.96, 0.96, 0.97);
  window->AddRenderer(in.Editor);

  in.Overlay->SetViewport(0.0, EditorHeight, 1.0, 1.0);
  in.Overlay->SetLayer(1);
  in.Overlay->InteractiveOff();
  window->AddRenderer(in.Overlay);
  in.Help->SetInput(HelpText);
  in.Help->GetTextProperty()->SetFontSize(11);
  in.Help->GetTextProperty()->SetFontFamilyToCourier();
  in.Help->GetTextProperty()->SetColor(1.0, 1.0, 0.85);
  in.Help->GetTextProperty()->SetBackgroundColor(0.0, 0.0, 0.0);
  in.Help->GetTextProperty()->SetBackgroundOpacity(0.6);
  in.Help->GetTextProperty()->SetVerticalJustificationToTop();
  in.Help->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  in.Help->SetPosition(0.01, 0.92);
  in.Help->VisibilityOff();
  in.Overlay->AddActor2D(in.Help);
  in.Message->GetTextProperty()->SetFontSize(14);
  in.Message->GetTextProperty()->SetVerticalJustificationToTop();
  in.Message->GetTextProperty()->SetBackgroundColor(0.0, 0.0, 0.0);
  in.Message->GetTextProperty()->SetBackgroundOpacity(0.5);
  in.Message->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  in.Message->SetPosition(0.01, 0.99);
  in.Message->VisibilityOff();
  in.Overlay->AddActor2D(in.Message);

  vtkRenderWindowInteractor* interactor = in.Interactor;
  interactor->SetRenderWindow(window);
  interactor->SetDesiredUpdateRate(20.0);
  interactor->SetStillUpdateRate(0.001);
  in.Style->SetDefaultRenderer(in.View);
  interactor->SetInteractorStyle(in.Style);

  in.Editing = std::make_unique<TransferFunctionEditor>(in.Property, field, in.Editor);
  in.Style->SetEditor(in.Editor, in.Editing->GetScene());
  in.Style->KeyHandler = [this](const std::string& keySym, char keyCode) { this->PressKey(keySym, keyCode); };
  in.Style->ChartDragHandler = [&in](bool dragging)
  {
    in.Window->SetDesiredUpdateRate(
      dragging ? in.Interactor->GetDesiredUpdateRate() : in.Interactor->GetStillUpdateRate());
    if (!dragging)
    {
      in.Render();
    }
  };

  // A changed function re-renders the 3D view: at once outside the event loop's timer, else on
  // its next tick (a drag changes the function several times per mouse move).
  vtkNew<vtkCallbackCommand> changed;
  changed->SetClientData(&in);
  changed->SetCallback([](vtkObject*, unsigned long, void* data, void*)
    { static_cast<Internals*>(data)->NeedsRender = true; });
  in.Property->GetScalarOpacity()->AddObserver(vtkCommand::ModifiedEvent, changed);
  in.Property->GetRGBTransferFunction()->AddObserver(vtkCommand::ModifiedEvent, changed);

  interactor->Initialize();
  in.Slices = std::make_unique<SlicePlanes>(field, in.View, interactor);
  in.Render();
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
  in.Slices.reset();
  in.Style->KeyHandler = nullptr;
  in.Style->ChartDragHandler = nullptr;
  in.Style->SetEditor(nullptr, nullptr);
  in.Editing.reset();
  in.Window->Finalize();
}

void Viewer::PlayFile(const std::string& path)
{
  this->PlayString(RegularInputFile(path, "recording").ReadAll(MaximumRecordingBytes));
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
  if (in.NeedsRender)
  {
    in.Render();
  }
}

void Viewer::Start()
{
  Internals& in = *this->Internal;
  vtkNew<vtkCallbackCommand> tick;
  tick->SetClientData(&in);
  tick->SetCallback([](vtkObject*, unsigned long, void* data, void*) {
    auto& viewer = *static_cast<Internals*>(data);
    const bool still = viewer.Style->GetState() == VTKIS_NONE &&
      viewer.Window->GetDesiredUpdateRate() <= viewer.Interactor->GetStillUpdateRate();
    if (viewer.NeedsRender ||
      (still && viewer.Mapper->GetNumberOfAccumulatedFrames(viewer.View) < viewer.FramesToConverge()))
    {
      viewer.Render();
    }
  });
  const unsigned long observer = in.Interactor->AddObserver(vtkCommand::TimerEvent, tick);
  const int timer = in.Interactor->CreateRepeatingTimer(30);
  in.Interactor->Start();
  in.Interactor->DestroyTimer(timer);
  in.Interactor->RemoveObserver(observer);
}

void Viewer::PressKey(const std::string& keySym, char keyCode)
{
  Internals& in = *this->Internal;
  const auto is = [&](const char* sym, char code)
  { return keySym == sym || (keySym.empty() && code != 0 && keyCode == code); };
  bool render = true;
  if (is("x", 'x') || is("y", 'y') || is("z", 'z'))
  {
    const int axis = keySym.empty() ? keyCode - 'x' : keySym[0] - 'x';
    in.Slices->SetSliceVisible(axis, !in.Slices->GetSliceVisible(axis));
  }
  else if (is("o", 'o'))
  {
    in.Slices->SetObliqueVisible(!in.Slices->GetObliqueVisible());
  }
  else if (is("l", 'l'))
  {
    in.Editing->SetLogHistogram(!in.Editing->GetLogHistogram());
    in.Show(std::string("histogram: ") + (in.Editing->GetLogHistogram() ? "log" : "linear"), false);
  }
  else if (is("f", 'f'))
  {
    in.Editing->FitToData();
    const auto range = in.Editing->GetRange();
    std::ostringstream text;
    text << "transfer function fitted to the data: [" << range[0] << ", " << range[1] << "]";
    in.Show(text.str(), false);
  }
  else if (is("p", 'p'))
  {
    in.LoadNextPreset();
  }
  else if (is("P", 'P'))
  {
    in.SavePreset();
  }
  else if (is("m", 'm'))
  {
    const std::vector<std::string> names = LightingModelNames();
    const std::string current = LightingModelName(in.Current.Render.Lighting);
    const auto found = std::find(names.begin(), names.end(), current);
    const size_t next = found == names.end() ? 0 : size_t(found - names.begin() + 1) % names.size();
    in.Current.Render.Lighting = *FindLightingModel(names[next]);
    in.ApplyLighting();
    in.Show("lighting: " + names[next], false);
  }
  else if (keySym == "Left" || keySym == "Right")
  {
    in.MoveLight(keySym == "Left" ? -10.0 : 10.0, 0.0);
  }
  else if (keySym == "Up" || keySym == "Down")
  {
    in.MoveLight(0.0, keySym == "Up" ? 10.0 : -10.0);
  }
  else if (is("plus", '+') || is("equal", '=') || is("KP_Add", '+') || is("minus", '-') ||
    is("KP_Subtract", '-'))
  {
    const bool larger = keySym == "plus" || keySym == "equal" || keySym == "KP_Add" ||
      (keySym.empty() && keyCode != '-');
    in.Current.Render.Step = in.EffectiveStep() * (larger ? 1.25 : 0.8);
    in.Mapper->SetSampleDistance(in.Current.Render.Step);
    in.Show("step: " + std::to_string(in.Current.Render.Step), false);
  }
  else if (is("bracketleft", '[') || is("bracketright", ']'))
  {
    const bool up = keySym == "bracketright" || (keySym.empty() && keyCode == ']');
    in.Current.Render.ResolutionScale =
      std::max(0.25, std::min(1.0, in.Current.Render.ResolutionScale + (up ? 0.125 : -0.125)));
    in.Mapper->SetResolutionScale(in.Current.Render.ResolutionScale);
    in.Show("resolution scale: " + std::to_string(in.Current.Render.ResolutionScale), false);
  }
  else if (is("h", 'h'))
  {
    in.Help->SetVisibility(!in.Help->GetVisibility());
  }
  else if (is("s", 's'))
  {
    this->SaveScreenshot();
  }
  else if (is("w", 'w'))
  {
    this->SaveSceneFile();
  }
  else if (is("r", 'r'))
  {
    ApplyCamera(in.Current.Camera, in.Field->GetBounds(), in.View, in.Current.Source);
  }
  else if (is("q", 'q') || keySym == "Escape")
  {
    in.Interactor->TerminateApp();
    render = false;
  }
  else
  {
    render = false; // not a viewer key (Delete went to the editor)
  }
  if (render || in.NeedsRender)
  {
    in.Render();
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
  }
  state.ObliqueVisible = in.Slices->GetObliqueVisible();
  state.ObliqueOrigin = in.Slices->GetObliqueOrigin();
  state.ObliqueNormal = in.Slices->GetObliqueNormal();
  state.ObliqueCutPoints = in.Slices->GetObliqueCutPoints();
  state.TransferFunction = TransferFunctionOf(in.Property);
  state.Step = in.Current.Render.Step;
  state.ResolutionScale = in.Current.Render.ResolutionScale;
  state.HelpVisible = in.Help->GetVisibility() != 0;
  state.LogHistogram = in.Editing->GetLogHistogram();
  state.EditorRange = in.Editing->GetRange();
  const int light = in.FirstDirectionalLight();
  if (light >= 0)
  {
    const glm::dvec3& p = in.Current.Lights[size_t(light)].Position;
    state.FirstLightPosition = { { p.x, p.y, p.z } };
  }
  state.Preset = in.Preset;
  state.Messages = in.MessageLog;
  state.SavedFiles = in.SavedFiles;
  state.AccumulatedFrames = in.Mapper->GetNumberOfAccumulatedFrames(in.View);
  state.ViewSize = in.ViewSize();
  return state;
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
    if (scene.BackgroundStyle.Type == BackgroundType::Sky && scene.Document.contains("background") &&
      scene.Document["background"].is_object() && !scene.Document["background"].contains("sun"))
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
  const std::string text = this->CurrentSceneJson().dump(2) + "\n";
  WriteFileAtomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary);
    out << text;
    out.close();
    if (!out)
    {
      throw InputError(path + ": cannot write the scene");
    }
  });
}

void Viewer::SaveScreenshot()
{
  Internals& in = *this->Internal;
  try
  {
    const std::string base =
      NextFreeBase(in.Options.OutputDirectory, "cloudvis-screenshot-", { ".png", ".exr" });
    const std::string png = base + ".png", exr = base + ".exr";
    CheckImageOutput(png);
    CheckImageOutput(exr);
    const bool floatImage = in.Current.Render.ResolutionScale >= 1.0;
    const RenderedImage image = in.Capture(floatImage);
    ImageExportOptions options;
    options.SceneJson = this->CurrentSceneJson().dump(-1, ' ', true);
    options.CommandLine = in.Options.CommandLine;
    WriteImage(image, png, options);
    in.SavedFiles.push_back(png);
    if (!floatImage)
    {
      in.Show("saved " + png + "; no EXR: the float image needs resolution scale 1 (press ])", true);
      return;
    }
    WriteImage(image, exr, options);
    in.SavedFiles.push_back(exr);
    in.Show("saved " + png + " and " + exr, false);
  }
  catch (const std::exception& e)
  {
    in.Show(e.what(), true);
  }
}

void Viewer::SaveWindowImage(const std::string& path)
{
  Internals& in = *this->Internal;
  in.Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(in.Window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->Write();
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
