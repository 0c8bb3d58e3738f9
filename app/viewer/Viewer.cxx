// The viewer's window: its renderers, layout and rendering (what the keys do is in ViewerKeys.cxx,
// what s and w save in ViewerSaving.cxx, undo in ViewerHistory.cxx, the state in
// ViewerState.cxx). Renderers sharing the window: the 3D view, in the
// four-view layout the three slice views, the editor (bottom 25%), the orientation marker's, and
// in layer 1 over the views a non-interactive overlay with the texts. Texts live in their own
// renderer because the mapper restarts its accumulation whenever another prop of its renderer
// changes: a message must not cost the converged image.
//
// Rendering: nothing here renders directly. Input and changes ask for a frame (Request(): the
// interactor's RenderEvent, a function's ModifiedEvent, a key); the live loop (LiveLoop.h)
// renders once per batch of input and then refines progressively until the mapper has averaged
// MaximumAccumulatedFrames frames (render.accumulate) and has finished the multiple-scattering
// volume it recomputes a slice at a time (ScatteringVolumeSecondsPerFrame; the progress line says
// how far). During a drag the interactor asks for
// DesiredUpdateRate (the mapper lowers its resolution to keep up); when the drag ends it asks
// for StillUpdateRate, and the full-resolution image refines from there.
#include "ViewerInternals.h"

#include "AtomicFile.h"
#include "Background.h"
#include "Errors.h"
#include "ExportRender.h"
#include "FieldCoarsening.h"
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
#include <vtkDataArray.h>
#include <vtkOutlineFilter.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
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

// The mapper's time per frame for recomputing the multiple-scattering volume after a light moved
// or the transfer function changed: the frame then stays interactive (a 128^3 field's volume
// takes several of these on llvmpipe), and the march reads the last finished volume meanwhile.
constexpr double ScatteringVolumeSecondsPerFrame = 0.03;

// The mouse's button and wheel events: every gesture undo counts begins or ends with one.
constexpr unsigned long MouseButtonEvents[] = { vtkCommand::LeftButtonPressEvent,
  vtkCommand::LeftButtonReleaseEvent,
  vtkCommand::MiddleButtonPressEvent,
  vtkCommand::MiddleButtonReleaseEvent,
  vtkCommand::RightButtonPressEvent,
  vtkCommand::RightButtonReleaseEvent,
  vtkCommand::MouseWheelForwardEvent,
  vtkCommand::MouseWheelBackwardEvent };

} // namespace

void Viewer::Internals::ApplyLighting()
{
  ConfigureLighting(this->Current, this->Mapper);
}

// The function a session starts with is the one `render` starts with (FitTransferFunctionToField
// in Scene.h says how it meets the field's values); the message line says what happened, and
// that `f` fits the scene's own function when the values lie beyond it. The slices' window starts
// at the field's range (SliceColors) unless a saved scene's view section says otherwise.
std::string Viewer::Internals::FitTransferFunctionOnOpening(const std::array<double, 2>& range,
  const double bounds[6])
{
  const std::array<double, 2> span = TransferFunctionSpan(this->Current.TransferFunction);
  char text[256];
  const TransferFunctionFit fit =
    FitTransferFunctionToField(this->Current, range, this->Options.FieldFile, bounds);
  switch (fit)
  {
    case TransferFunctionFit::Kept:
      return "";
    case TransferFunctionFit::ValuesBeyondItsPoints:
      std::snprintf(text,
        sizeof(text),
        "the field's values [%.4g, %.4g] lie beyond the scene's transfer function [%.4g, %.4g]: "
        "f fits it to them",
        range[0],
        range[1],
        span[0],
        span[1]);
      return text;
    case TransferFunctionFit::FittedToValues:
    case TransferFunctionFit::GrownToValues:
      break;
  }
  std::snprintf(text,
    sizeof(text),
    "transfer function fitted to the field's values [%.4g, %.4g], as the slices' window%s; "
    "f fits again",
    range[0],
    range[1],
    this->Options.FieldFile                       ? ""
      : fit == TransferFunctionFit::GrownToValues ? " (they lie beyond the default function)"
                                                  : " (the default function shows none of them)");
  return text;
}

std::string Viewer::Internals::CornerText() const
{
  const std::string time = this->Time->Steps() ? this->Time->Label() : "";
  const std::string coarse = this->Coarsening > 1
    ? "3D view: the field coarsened " + std::to_string(this->Coarsening) + "x to fit the GPU"
    : "";
  return time + (time.empty() || coarse.empty() ? "" : "\n") + coarse;
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
  const auto render = [this]
  {
    const int before = this->Mapper->GetNumberOfAccumulatedFrames(this->View);
    this->Window->Render();
    this->MarchedFrames += this->Mapper->GetNumberOfAccumulatedFrames(this->View) != before ? 1 : 0;
  };
  // A field whose textures the GPU's memory refuses is drawn coarser (FieldCoarsening.h); the
  // slices and readouts keep it as it is.
  const int coarsening = RenderCoarsenedToFit(
    { this->Mapper.Get() }, this->Field, this->Coarsening, render, this->Coarsened);
  if (coarsening != this->Coarsening)
  {
    this->Coarsening = coarsening;
    this->Show(this->Coarsened, false);
    this->Status->SetCorner(this->CornerText());
  }
  if (preview)
  {
    this->Window->SetDesiredUpdateRate(this->Interactor->GetStillUpdateRate());
  }
  // Shown from the next frame on (the overlay's text is drawn with this one): the line lags a
  // frame, and a frame is asked for when it goes, so that it never stays after the work ends.
  const int done = this->Mapper->GetScatteringVolumeStepsDone();
  const int total = this->Mapper->GetScatteringVolumeStepCount();
  const std::string progress = total > 0
    ? "multiple scattering: converging (" + std::to_string(done) + "/" + std::to_string(total) + ")"
    : "";
  if (progress != this->Status->GetProgress())
  {
    this->Status->SetProgress(progress);
    if (progress.empty() && this->Loop)
    {
      this->Loop->Request();
    }
  }
  this->LastFrameWasPreview = preview;
  // The checks of a converged still, once each: whether the path tracer's walks ran whole, and
  // the automatic exposure, metered on the converged picture, never on the frames of a drag or
  // of a refinement, whose changing image would make it hunt. A new EV composites the still again
  // at once (the exposure does not modify the mapper: no march).
  if (!this->StillComplete())
  {
    this->ExposureMetered = false;
    this->PathsChecked = false;
  }
  else
  {
    if (!this->PathsChecked)
    {
      this->CheckPathsWhole();
    }
    if (this->Current.Render.AutoExposure && !this->ExposureMetered)
    {
      if (this->MeterExposure())
      {
        render();
      }
      if (this->AnnounceExposure)
      {
        this->AnnounceExposure = false;
        this->Show(this->ExposureText(), false);
        this->Loop->Request(); // the message is drawn by the next frame
      }
    }
  }
  ++this->FramesRendered;
  this->LastFrameAt = MonotonicSeconds();
  this->History.FrameDrawn(this->LastFrameAt);
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
      this->Mapper->GetNumberOfAccumulatedFrames(this->View) >= this->FramesToConverge() &&
      !this->Mapper->GetScatteringVolumeConverging() && this->Status->GetProgress().empty());
}

bool Viewer::Internals::StillComplete() const
{
  return this->Volume->GetVisibility() && this->Mapper->GetLastError().empty() &&
    this->Converged() && !this->Style->IsDragging() &&
    this->Window->GetDesiredUpdateRate() <= this->Interactor->GetStillUpdateRate();
}

void Viewer::Internals::CheckPathsWhole()
{
  this->PathsChecked = true;
  if (this->Current.Render.Lighting.Model != LightingModel::PathTrace)
  {
    return;
  }
  this->Window->MakeCurrent();
  const vtkIdType cut = this->Mapper->CountCutPathTracePixels(this->View);
  if (cut > 0)
  {
    int width = 0, height = 0;
    std::vector<float> rgba; // read for its size only, and only when paths were cut
    this->Mapper->ReadImage(this->View, rgba, width, height);
    this->Show(CutPathsProblem(this->Current.Source, cut, vtkIdType(width) * height), true);
    this->Loop->Request(); // the message is drawn by the next frame
  }
}

bool Viewer::Internals::MeterExposure()
{
  this->ExposureMetered = true;
  ++this->ExposureMeterings;
  this->MeteredFrames = this->Mapper->GetNumberOfAccumulatedFrames(this->View);
  const double before = this->Mapper->GetExposureEV();
  try
  {
    this->Window->MakeCurrent();
    const std::vector<float> rgba =
      ReadCheckedMapperImage(this->Mapper, this->View, "automatic exposure");
    ConfigureDisplay(this->Mapper,
      this->Current.Render,
      ResolveExposureEV(this->Current.Render, rgba.data(), rgba.size() / 4));
  }
  catch (const std::exception& e)
  {
    this->Show(std::string(e.what()) + "; the exposure stays at " + ShowExposure(before), true);
  }
  return this->Mapper->GetExposureEV() != before;
}

bool Viewer::Internals::ApplyExposure()
{
  if (!this->Current.Render.AutoExposure)
  {
    ConfigureDisplay(this->Mapper, this->Current.Render, this->Current.Render.ExposureEV);
    return false;
  }
  // The metered EV stays until the next metering, which the still shown gets now.
  this->ExposureMetered = false;
  if (!this->StillComplete())
  {
    return false;
  }
  this->MeterExposure();
  return true;
}

std::string Viewer::Internals::ExposureText() const
{
  return "exposure " + ShowExposure(this->Mapper->GetExposureEV()) +
    (this->Current.Render.AutoExposure ? " (auto)" : "");
}

bool Viewer::Internals::RefinementPending()
{
  if (this->Converged() || this->Style->IsDragging() ||
    this->Window->GetDesiredUpdateRate() > this->Interactor->GetStillUpdateRate())
  {
    return false;
  }
  if (this->Mapper->GetScatteringVolumeConverging())
  {
    return true; // each frame computes a slice of the volume, whatever it accumulates
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
  return this->LegendsVisible &&
    (this->FourViews || this->Slices->GetObliqueVisible() || this->Slices->GetSliceVisible(0) ||
      this->Slices->GetSliceVisible(1) || this->Slices->GetSliceVisible(2));
}

bool Viewer::Internals::LegendWanted() const
{
  return this->LegendsVisible && this->Volume->GetVisibility();
}

void Viewer::Internals::ApplyLayout()
{
  // A screenshot leaves the editor out, as ParaView's leaves its panels: the views fill it.
  const double top = 1.0, bottom = this->Exporting ? 0.0 : EditorHeight,
               middle = 0.5 * (top + bottom);
  this->Editor->SetDraw(!this->Exporting);
  this->Overlay->SetViewport(0.0, bottom, 1.0, top);
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
  // The legends and the texts, in the overlay's normalized coordinates; the readout right of the
  // marker, or under the slice views.
  const std::array<double, 4> overlayView = {
    { view[0], (view[1] - bottom) / (top - bottom), view[2], (view[3] - bottom) / (top - bottom) }
  };
  this->LegendArea = overlayView;
  this->PlaceLegends();
  // The readout above the orientation marker, or under the slice views.
  const double overlayHeight = std::max(1.0, (top - bottom) * size[1]);
  this->Status->Place(overlayView,
    this->FourViews ? std::array<double, 2>{ { 0.01, 0.01 } }
                    : std::array<double, 2>{
                        { overlayView[0] + 0.01, overlayView[1] + (side + 6.0) / overlayHeight } });
  this->Views2D->Update();
  this->Status->LayOut();
}

void Viewer::Internals::PlaceLegends()
{
  // At the 3D view's right edge, as ParaView places a scalar bar; with both shown, the cloud's
  // above the slices'.
  const std::array<double, 4>& area = this->LegendArea;
  const double width = area[2] - area[0], height = area[3] - area[1];
  const bool legend = this->LegendWanted(), colorBar = this->ColorBarWanted();
  const auto place = [&](vtkScalarBarActor* bar, double bottom, double top)
  {
    bar->SetPosition(area[0] + width * 0.8, area[1] + height * bottom);
    bar->SetPosition2(width * 0.14, height * (top - bottom));
  };
  place(this->Legend, colorBar ? 0.52 : 0.2, colorBar ? 0.92 : 0.75);
  place(this->Colors->GetColorBar(), legend ? 0.08 : 0.2, legend ? 0.48 : 0.75);
  // The help covers the view, and the legends would show through it (a screenshot hides the
  // help and keeps them).
  const bool covered = this->Status->GetHelpVisible() && !this->Exporting;
  this->Legend->SetVisibility(legend && !covered);
  this->Colors->GetColorBar()->SetVisibility(colorBar && !covered);
}

bool Viewer::Internals::SlicesShown() const
{
  return this->FourViews || this->Slices->GetSliceVisible(0) || this->Slices->GetSliceVisible(1) ||
    this->Slices->GetSliceVisible(2);
}

std::string Viewer::Internals::VoxelText(const char* label, const SliceProbe& voxel) const
{
  const ResolvedFieldUnits& units = this->Options.Units;
  const std::string length =
    units.Length == LengthUnit::None ? "" : " " + LengthUnitName(units.Length);
  const std::string unit = QuantityUnit(units.Quantity);
  const std::string unitSuffix = unit.empty() ? "" : " " + unit;
  char text[256];
  std::snprintf(text,
    sizeof(text),
    "%s (%.3g, %.3g, %.3g)%s  voxel [%d, %d, %d]  %s %.4g%s",
    label,
    voxel.Position[0],
    voxel.Position[1],
    voxel.Position[2],
    length.c_str(),
    voxel.Index[0],
    voxel.Index[1],
    voxel.Index[2],
    QuantityName(units.Quantity).c_str(),
    voxel.Value,
    unitSuffix.c_str());
  return text;
}

void Viewer::Internals::UpdateReadout()
{
  if (!this->SlicesShown())
  {
    // The probe belongs to the slices: it goes with them.
    this->Slices->ClearProbe();
    this->Hovered = SliceProbe();
  }
  std::string text;
  if (this->Hovered.Valid)
  {
    text = this->VoxelText("pointer", this->Hovered);
  }
  const SliceProbe& probe = this->Slices->GetProbe();
  if (probe.Valid)
  {
    text += (text.empty() ? "" : "\n") + this->VoxelText("probe", probe);
  }
  this->Status->SetReadout(text);
}

void Viewer::Internals::Hover(int x, int y)
{
  SliceProbe voxel;
  if (x >= 0 && this->SlicesShown())
  {
    voxel = this->FourViews ? this->Views2D->VoxelUnder(x, y) : SliceProbe();
    if (!voxel.Valid)
    {
      voxel = this->Slices->VoxelUnder(x, y);
    }
  }
  const bool same = voxel.Valid == this->Hovered.Valid &&
    (!voxel.Valid || voxel.Index == this->Hovered.Index); // the value follows (NaN != NaN)
  if (same)
  {
    return; // nothing to draw
  }
  this->Hovered = voxel;
  this->UpdateReadout();
  this->Request();
}

void Viewer::Internals::SlicesChanged()
{
  this->Views2D->Update();
  this->UpdateReadout();
  this->PlaceLegends(); // the color bar shown or hidden
  this->Request();
}

void Viewer::Internals::OpenViews(vtkImageData* field)
{
  vtkRenderWindow* window = this->Window;
  window->SetDisplayId(this->Display->Get());
  // As in RenderOffscreen: an observed ExitEvent turns VTK's abort() on a failed GL context into
  // an error the mapper reports.
  vtkNew<vtkCallbackCommand> onExit;
  window->AddObserver(vtkCommand::ExitEvent, onExit);
  window->SetMultiSamples(0);
  window->SetSize(this->Options.WindowSize[0], this->Options.WindowSize[1]);
  window->SetWindowName("cloudvis view");
  window->SetNumberOfLayers(2);

  ApplyBackground(this->Current, this->View);
  window->AddRenderer(this->View);
  this->Mapper->SetInputData(field);
  ConfigureMapper(this->Mapper, this->Current.Render);
  this->Mapper->SetScatteringVolumeSecondsPerFrame(ScatteringVolumeSecondsPerFrame);
  // Only the viewer interacts: exports never hold the reprojection's full-resolution history.
  this->Mapper->SetTemporalReprojection(this->Current.Render.Reprojection);
  this->ApplyLighting();
  double range[2];
  field->GetScalarRange(range);
  const std::string fitted =
    this->FitTransferFunctionOnOpening({ { range[0], range[1] } }, field->GetBounds());
  this->SceneTransferFunction = this->Current.TransferFunction; // what Shift+r goes back to
  this->Property = MakeVolumeProperty(this->Current.TransferFunction);
  this->Volume->SetMapper(this->Mapper);
  this->Volume->SetProperty(this->Property);
  // The slices are picked through the cloud: a picker that stopped at the volume (vtkCellPicker
  // picks volumes by their opacity) would never reach them.
  this->Volume->PickableOff();
  this->View->AddVolume(this->Volume);
  // The field's bounding box, as ParaView outlines a dataset.
  vtkNew<vtkOutlineFilter> outline;
  outline->SetInputData(field);
  vtkNew<vtkPolyDataMapper> outlineMapper;
  outlineMapper->SetInputConnection(outline->GetOutputPort());
  this->Outline->SetMapper(outlineMapper);
  this->Outline->GetProperty()->SetColor(0.75, 0.75, 0.8);
  this->Outline->GetProperty()->LightingOff();
  this->Outline->PickableOff();
  this->View->AddActor(this->Outline);
  ApplyCamera(this->Current.Camera, field->GetBounds(), this->View, this->Current.Source);

  this->Editor->SetViewport(0.0, 0.0, 1.0, EditorHeight);
  this->Editor->SetBackground(0.96, 0.96, 0.97);
  window->AddRenderer(this->Editor);

  this->Overlay->SetViewport(0.0, EditorHeight, 1.0, 1.0);
  this->Overlay->SetLayer(1);
  this->Overlay->InteractiveOff();
  window->AddRenderer(this->Overlay);
  this->Status = std::make_unique<StatusOverlay>(this->Overlay);
  this->Time = std::make_unique<ViewerTimeSteps>(this->Options.ReadTimeStep,
    this->Current.Field.Read.TimeStep.value_or(0),
    this->Options.Opened);
  if (this->Time->Steps())
  {
    this->Status->SetCorner(this->CornerText());
    // The next step is read while the first is looked at: the first . shows it at once.
    this->Time->ReadAheadLater(this->Time->Current() + 1,
      double(field->GetPointData()->GetScalars()->GetActualMemorySize()) * 1024.0);
  }
  if (!fitted.empty())
  {
    this->Show(fitted, false);
  }
}

void Viewer::Internals::ObserveInput(Viewer& owner)
{
  vtkRenderWindowInteractor* interactor = this->Interactor;
  interactor->SetRenderWindow(this->Window);
  interactor->SetDesiredUpdateRate(20.0);
  interactor->SetStillUpdateRate(0.001);
  // Styles and widgets render through the interactor: its RenderEvent becomes a request to the
  // live loop, which renders (LiveLoop.h).
  interactor->EnableRenderOff();
  this->Loop = std::make_unique<LiveLoop>(interactor,
    LiveLoop::Hooks{ [this] { this->RenderFrame(); },
      [this] { return this->RefinementPending(); },
      [this]
      {
        bool changed = false;
        const double next = this->Status->Tick(changed);
        if (changed)
        {
          this->Loop->Request();
        }
        return next;
      },
      [this, &owner]
      {
        this->SettleGesture();
        owner.WriteStateFile();
      },
      [this] { return this->Time->ReadAhead(); } });
  vtkNew<vtkCallbackCommand> requested;
  requested->SetClientData(this);
  requested->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*) { static_cast<Internals*>(data)->Request(); });
  interactor->AddObserver(vtkCommand::RenderEvent, requested);
  // A resized window lays its views out again: the marker stays square, the slice views fit
  // their slices, the texts wrap to the new width.
  vtkNew<vtkCallbackCommand> resized;
  resized->SetClientData(this);
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
  closed->SetClientData(&owner);
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
  handled->SetClientData(this);
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
  for (unsigned long event : MouseButtonEvents)
  {
    interactor->AddObserver(event, handled, -100.0);
  }
  for (unsigned long event :
    { vtkCommand::MouseMoveEvent, vtkCommand::KeyPressEvent, vtkCommand::KeyReleaseEvent })
  {
    interactor->AddObserver(event, handled, -100.0);
  }
  // Gestures for undo (ViewerHistory.h), seen before the widgets and the style act on them
  // (priority 100): a press begins one, a release lets it settle once the input is handled, a
  // wheel notch is one. A passive observer: the trackball grabs the interactor's focus during a
  // drag, and then only the focus and passive observers see the release.
  vtkNew<vtkCallbackCommand> gesture;
  gesture->PassiveObserverOn();
  gesture->SetClientData(this);
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
  for (unsigned long event : MouseButtonEvents)
  {
    interactor->AddObserver(event, gesture, 100.0);
  }
  this->Style->SetDefaultRenderer(this->View);
  interactor->SetInteractorStyle(this->Style);
}

void Viewer::Internals::ConnectEditor(Viewer& owner, vtkImageData* field)
{
  this->Editing = std::make_unique<TransferFunctionEditor>(this->Property, field, this->Editor);
  this->Style->SetEditor(this->Editor, this->Editing->GetScene());
  this->Style->EditorLeft = [this]
  {
    this->Editing->PointerLeft();
    this->Request();
  };
  this->Style->KeyHandler = [&owner](const std::string& keySym, char keyCode, bool control)
  { owner.PressKey(keySym, keyCode, control); };
  this->Style->DragHandler = [this](bool dragging)
  {
    this->Window->SetDesiredUpdateRate(
      dragging ? this->Interactor->GetDesiredUpdateRate() : this->Interactor->GetStillUpdateRate());
    if (dragging)
    {
      this->Editing->BeginDrag();
    }
    else
    {
      this->Editing->EndDrag();
    }
    this->Request();
  };

  // A changed function re-renders the 3D view (and the slices colored by it); a drag changes the
  // function several times per mouse move, and the requests become one frame.
  vtkNew<vtkCallbackCommand> changed;
  changed->SetClientData(this);
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
  this->Property->GetScalarOpacity()->AddObserver(vtkCommand::ModifiedEvent, changed);
  this->Property->GetRGBTransferFunction()->AddObserver(vtkCommand::ModifiedEvent, changed);
}

void Viewer::Internals::AddSlicesAndLegends(vtkImageData* field)
{
  double range[2];
  field->GetScalarRange(range);
  this->Colors = std::make_unique<SliceColors>(
    std::array<double, 2>{ { range[0], range[1] } }, this->Property->GetRGBTransferFunction());
  this->Overlay->AddActor2D(this->Colors->GetColorBar());
  // The legend reads the volume's own color function: every edit shows in it.
  this->Legend->SetLookupTable(this->Property->GetRGBTransferFunction());
  // Both legends name the field's quantity and its unit, as the readout does: "lwc (g/m^3)".
  const std::string unit = QuantityUnit(this->Options.Units.Quantity);
  const std::string quantity =
    QuantityName(this->Options.Units.Quantity) + (unit.empty() ? "" : " (" + unit + ")");
  StyleColorBar(this->Legend, quantity);
  this->Overlay->AddActor2D(this->Legend);
  this->Slices =
    std::make_unique<SlicePlanes>(field, this->View, this->Interactor.Get(), *this->Colors);
  this->Slices->Changed = [this] { this->SlicesChanged(); };
  this->Views2D = std::make_unique<SliceViews>(field, *this->Slices, *this->Colors);
  this->Views2D->Changed = [this] { this->SlicesChanged(); };
  this->Style->SliceViewMouse =
    [this](vtkCloudViewerInteractorStyle::MouseAction action, int button, int x, int y)
  {
    return this->Views2D->Mouse(action,
      button,
      x,
      y,
      this->Interactor->GetControlKey() != 0,
      this->Interactor->GetShiftKey() != 0);
  };
  this->Style->HoverHandler = [this](int x, int y) { this->Hover(x, y); };
  this->Colors->GetColorBar()->SetTitle(("slices: " + quantity).c_str());

  this->Orientation->SetOrientationMarker(this->Axes);
  this->Orientation->SetInteractor(this->Interactor.Get());
}

Viewer::Viewer(const Scene& scene,
  vtkSmartPointer<vtkImageData> field,
  const ViewerOptions& options)
  : Internal(new Internals)
{
  Internals& in = *this->Internal;
  in.Current = scene;
  in.Field = field;
  in.Options = options;
  in.Messages = options.Messages ? options.Messages : &std::cerr;
  in.Display = std::make_unique<DisplayConnection>("cloudvis view ...");
  in.OpenViews(field);
  in.ObserveInput(*this);
  in.ConnectEditor(*this, field);
  in.Interactor->Initialize();
  in.AddSlicesAndLegends(field);
  vtkRenderWindowInteractor* interactor = in.Interactor;
  in.Orientation->SetOrientationMarker(in.Axes);
  in.Orientation->SetInteractor(interactor);
  // The layout, slices and their colors as the scene's view section (--layout included) says;
  // a scene without one gets the defaults (ViewSpec).
  in.ApplyView(scene.View.value_or(ViewSpec{}));

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
  in.Style->HoverHandler = nullptr;
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

} // namespace cloudvis
