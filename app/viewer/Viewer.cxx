// The viewer's window: its renderers, layout, rendering and files (what the keys do is in
// ViewerKeys.cxx, the state in ViewerState.cxx). Renderers sharing the window: the 3D view, in the
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
#include "ViewerInternals.h"

#include "AtomicFile.h"
#include "Background.h"
#include "Errors.h"
#include "ExportRender.h"
#include "ImageWriters.h"
#include "InputFiles.h"
#include "OffscreenRender.h"
#include "SceneJson.h"
#include "SceneLighting.h"
#include "Utf8.h"
#include "ViewerFiles.h"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkOutlineFilter.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkScalarBarActor.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{
namespace
{
// The editor's share of the window, from the bottom; the views have the rest.
constexpr double EditorHeight = 0.25;

} // namespace

void Viewer::Internals::ApplyLighting()
{
  ConfigureLighting(this->Current, this->View, this->Mapper);
}

void Viewer::Internals::RenderFrame()
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

void Viewer::Internals::Request()
{
  this->RefinementCheck = { std::numeric_limits<long>::max(), 0 };
  this->Loop->Request();
}

int Viewer::Internals::FramesToConverge() const
{
  return this->Current.Render.Jitter ? this->Mapper->GetMaximumAccumulatedFrames() : 1;
}

bool Viewer::Internals::Converged() const
{
  return !this->Volume->GetVisibility() || !this->Mapper->GetLastError().empty() ||
    (!this->LastFrameWasPreview &&
      this->Mapper->GetNumberOfAccumulatedFrames(this->View) >= this->FramesToConverge());
}

bool Viewer::Internals::RefinementPending()
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
  // A preview frame (a key's quick answer at interactive resolution) accumulates apart: the
  // full-resolution refinement after it starts over at one frame. Counting the preview's frame
  // as the one to beat took that first refinement frame for an accumulation that restarts every
  // frame, and refinement stalled until something else asked for a frame (the message's fading,
  // 4 s later).
  this->RefinementCheck = { this->FramesRendered, this->LastFrameWasPreview ? 0 : accumulated };
  return true;
}

void Viewer::Internals::Show(const std::string& message, bool error)
{
  // Messages quote paths and user text, which may hold bytes that are not UTF-8.
  const std::string text = EscapeInvalidUtf8(message);
  this->MessageLog.push_back(text);
  this->Status->ShowMessage(text, error);
  *this->Messages << (error ? "cloudvis: error: " : "cloudvis view: ") << text << std::endl;
}

std::array<int, 4> Viewer::Internals::PixelViewport(vtkRenderer* renderer) const
{
  const int* size = const_cast<vtkRenderWindow*>(this->Window.Get())->GetSize();
  double v[4];
  renderer->GetViewport(v);
  return { { int(std::lround(v[0] * size[0])),
    int(std::lround(v[1] * size[1])),
    int(std::lround(v[2] * size[0])),
    int(std::lround(v[3] * size[1])) } };
}

std::array<int, 2> Viewer::Internals::ViewSize() const
{
  int size[2];
  const_cast<vtkRenderer*>(this->View.Get())->GetTiledSize(&size[0], &size[1]);
  return { { size[0], size[1] } };
}

bool Viewer::Internals::ColorBarWanted() const
{
  return this->FourViews || this->Slices->GetObliqueVisible() || this->Slices->GetSliceVisible(0) ||
    this->Slices->GetSliceVisible(1) || this->Slices->GetSliceVisible(2);
}

void Viewer::Internals::ApplyLayout()
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
                    : std::array<double, 2>{
                        { overlayView[0] + 0.01, overlayView[1] + (side + 6.0) / overlayHeight } });
  this->Views2D->Update();
  this->Status->LayOut();
}

void Viewer::Internals::UpdateReadout()
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

void Viewer::Internals::SlicesChanged()
{
  this->Views2D->Update();
  this->UpdateReadout();
  this->Colors->GetColorBar()->SetVisibility(this->ColorBarWanted());
  this->Request();
}

RenderedImage Viewer::Internals::Capture(bool floatImage)
{
  this->Window->SetDesiredUpdateRate(this->Interactor->GetStillUpdateRate());
  const auto texts = this->Status->HideAll();
  this->Outline->VisibilityOff();
  this->Axes->VisibilityOff();
  const bool colorBar = this->Colors->GetColorBar()->GetVisibility() != 0;
  this->Colors->GetColorBar()->VisibilityOff();
  // The frames of the capture stay in the back buffer: the window keeps showing what it showed
  // (the "saving" notice) until the capture is done.
  this->Window->SwapBuffersOff();
  struct Decorations
  {
    Internals& In;
    std::array<bool, 5> Texts;
    bool ColorBar;
    ~Decorations()
    {
      this->In.Window->SwapBuffersOn();
      this->In.Status->Restore(this->Texts);
      this->In.Outline->VisibilityOn();
      this->In.Axes->VisibilityOn();
      this->In.Colors->GetColorBar()->SetVisibility(this->ColorBar);
    }
  } restore{ *this, texts, colorBar };
  const int frames = this->FramesToConverge();
  this->RenderFrame();
  for (int i = 0; i < frames + 1 && this->Mapper->GetNumberOfAccumulatedFrames(this->View) < frames;
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
  // Only the viewer interacts: exports never hold the reprojection's full-resolution history.
  in.Mapper->SetTemporalReprojection(in.Current.Render.Reprojection);
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
      [this]
      {
        this->Internal->SettleGesture();
        this->WriteStateFile();
      } });
  vtkNew<vtkCallbackCommand> requested;
  requested->SetClientData(&in);
  requested->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*) { static_cast<Internals*>(data)->Request(); });
  interactor->AddObserver(vtkCommand::RenderEvent, requested);
  // A resized window lays its views out again: the marker stays square, the slice views fit
  // their slices, the texts wrap to the new width.
  vtkNew<vtkCallbackCommand> resized;
  resized->SetClientData(&in);
  resized->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*)
    {
      auto& viewer = *static_cast<Internals*>(data);
      if (viewer.Views2D)
      {
        viewer.ApplyLayout();
        viewer.Request();
      }
    });
  interactor->AddObserver(vtkCommand::ConfigureEvent, resized);
  // The window manager's close button (WM_DELETE_WINDOW): VTK's X interactor invokes ExitEvent
  // when someone observes it (else it terminates at once), so closing asks like q does.
  vtkNew<vtkCallbackCommand> closed;
  closed->SetClientData(this);
  closed->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*)
    {
      auto& viewer = *static_cast<Viewer*>(data);
      viewer.Internal->Quit(viewer, true);
      viewer.Internal->Request();
    });
  interactor->AddObserver(vtkCommand::ExitEvent, closed);
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
        viewer.SettleGesture();
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
  // Gestures for undo (ViewerHistory.h), seen before the widgets and the style act on them
  // (priority 100): a press begins one, a release lets it settle once the input is handled, a
  // wheel notch is one. A passive observer: the trackball grabs the interactor's focus during a
  // drag, and then only the focus and passive observers see the release.
  vtkNew<vtkCallbackCommand> gesture;
  gesture->PassiveObserverOn();
  gesture->SetClientData(&in);
  gesture->SetCallback(
    [](vtkObject*, unsigned long event, void* data, void*)
    {
      auto& viewer = *static_cast<Internals*>(data);
      switch (event)
      {
        case vtkCommand::LeftButtonPressEvent:
        case vtkCommand::MiddleButtonPressEvent:
        case vtkCommand::RightButtonPressEvent:
          viewer.BeginGesture(false);
          ++viewer.ButtonsDown;
          break;
        case vtkCommand::MouseWheelForwardEvent:
        case vtkCommand::MouseWheelBackwardEvent:
          viewer.BeginGesture(true);
          break;
        default: // a release
          viewer.ButtonsDown = std::max(0, viewer.ButtonsDown - 1);
          break;
      }
    });
  for (unsigned long event : { vtkCommand::LeftButtonPressEvent,
         vtkCommand::LeftButtonReleaseEvent,
         vtkCommand::MiddleButtonPressEvent,
         vtkCommand::MiddleButtonReleaseEvent,
         vtkCommand::RightButtonPressEvent,
         vtkCommand::RightButtonReleaseEvent,
         vtkCommand::MouseWheelForwardEvent,
         vtkCommand::MouseWheelBackwardEvent })
  {
    interactor->AddObserver(event, gesture, 100.0);
  }
  in.Style->SetDefaultRenderer(in.View);
  interactor->SetInteractorStyle(in.Style);

  in.Editing = std::make_unique<TransferFunctionEditor>(in.Property, field, in.Editor);
  in.Style->SetEditor(in.Editor, in.Editing->GetScene());
  in.Style->EditorLeft = [&in]
  {
    in.Editing->PointerLeft();
    in.Request();
  };
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

  in.SavedEdits = in.EditsOf(*this);

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
  in.Style->EditorLeft = nullptr;
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
  in.SettleGesture();
  in.Loop->Flush();
  this->WriteStateFile();
}

void Viewer::Start()
{
  Internals& in = *this->Internal;
  this->WriteStateFile();
  in.Loop->Run();
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
  // The capture renders render.accumulate frames without the decorations (seconds for a large
  // view): say so on screen, and in the state, before the work starts.
  in.Show("saving a screenshot ...", false);
  in.RenderFrame();
  this->WriteStateFile();
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
    in.SavedEdits = in.EditsOf(*this);
    in.SavedFiles.push_back(path);
    in.Show("saved " + path + " (cloudvis render " + path + " -o IMAGE.png)", false);
  }
  catch (const std::exception& e)
  {
    in.Show(e.what(), true);
  }
}

} // namespace cloudvis
