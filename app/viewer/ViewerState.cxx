// The viewer's state (Viewer::State) and as JSON: what `cloudvis view --state-file` writes after
// every frame and every batch of input, for tests and tools that drive the viewer with real input
// (docs/viewer.md).
#include "ViewerInternals.h"

#include "Utf8.h"
#include "ViewerFiles.h"

#include <vtkCamera.h>
#include <vtkScalarBarActor.h>

#include <cmath>
#include <cstdint>

namespace cloudvis
{
namespace
{
using json = nlohmann::json;

// NaN is not JSON: unprobed values become null.
json Number(double value)
{
  return std::isfinite(value) ? json(value) : json(nullptr);
}
} // namespace

json ViewerStateJson(const ViewerState& state)
{
  json keys = json::array();
  for (const HandledKey& key : state.Keys)
  {
    keys.push_back({ { "key", key.KeySym },
      { "handled_at", key.HandledAt },
      { "shown_at", Number(key.ShownAt) } });
  }
  json viewports = json::object();
  for (const auto& [name, pixels] : state.Viewports)
  {
    viewports[name] = pixels;
  }
  json sliceViews = json::object();
  for (int v = 0; v < SliceViews::Count; ++v)
  {
    sliceViews[SliceViews::Name(v)] = { { "zoom", state.SliceViewZoom[size_t(v)] },
      { "pan", state.SliceViewPan[size_t(v)] } };
  }
  json probed = json::array();
  for (double value : state.ProbedValue)
  {
    probed.push_back(Number(value));
  }
  // Saved files' paths (from --output-dir) may hold bytes that are not UTF-8, which dump() refuses.
  return WithValidUtf8({
    { "frames_rendered", state.FramesRendered },
    { "marched_frames", state.MarchedFrames },
    { "last_frame_at", state.LastFrameAt },
    { "converged", state.Converged },
    { "accumulated_frames", state.AccumulatedFrames },
    { "keys", keys },
    { "window", { { "id", state.WindowId }, { "size", state.WindowSize } } },
    { "viewports", viewports },
    { "four_views", state.FourViews },
    { "camera",
      { { "position", state.CameraPosition },
        { "focal_point", state.CameraFocalPoint },
        { "view_up", state.CameraViewUp } } },
    { "lighting", LightingModelName(state.Lighting) },
    { "step", state.Step },
    { "resolution_scale", state.ResolutionScale },
    { "exposure",
      { { "ev", state.ExposureEV },
        { "auto", state.AutoExposure },
        { "display", state.Display },
        { "meterings", state.ExposureMeterings },
        { "metered_frames", state.MeteredFrames } } },
    { "first_light_position", state.FirstLightPosition },
    { "volume_visible", state.VolumeVisible },
    { "help_visible", state.HelpVisible },
    { "help_page", state.HelpPage },
    { "help_boxes", state.HelpBoxes },
    { "help_font_size", state.HelpFontSize },
    { "unsaved_changes", state.UnsavedChanges },
    { "hint_visible", state.HintVisible },
    { "color_bar_visible", state.ColorBarVisible },
    { "legend_visible", state.LegendVisible },
    { "message", state.Message },
    { "readout", state.Readout },
    { "progress", state.Progress },
    { "time_step", state.TimeStep },
    { "time_steps", state.TimeSteps },
    { "time", state.Time },
    { "read_ahead", state.ReadAhead },
    { "coarsened", state.Coarsened },
    { "slices",
      { { "visible", state.SliceVisible },
        { "index", state.SliceIndex },
        { "position", state.SlicePosition },
        { "probed_value", probed },
        { "window_level", state.SliceWindowLevel },
        { "colors", state.SliceColors },
        { "oblique_visible", state.ObliqueVisible },
        { "oblique_origin", state.ObliqueOrigin },
        { "oblique_normal", state.ObliqueNormal } } },
    { "probe",
      { { "valid", state.ProbeValid },
        { "index", state.ProbeIndex },
        { "value", state.ProbeValue } } },
    { "slice_views", sliceViews },
    { "hover",
      { { "valid", state.HoverValid },
        { "index", state.HoverIndex },
        { "value", state.HoverValue } } },
    { "transfer_function",
      { { "opacity", state.TransferFunction.Opacity },
        { "color", state.TransferFunction.Color },
        { "unit_distance", state.TransferFunction.UnitDistance } } },
    { "editor",
      { { "range", state.EditorRange },
        { "log_histogram", state.LogHistogram },
        { "opacity_point_pixels", state.OpacityPointPixels },
        { "color_point_pixels", state.ColorPointPixels },
        { "color_strip_pixels", state.ColorStripPixels },
        { "palette_visible", state.PaletteVisible },
        { "palette_pixels", state.PalettePixels },
        { "selected_function", state.SelectedFunction },
        { "selected_point", state.SelectedPoint },
        { "info", state.EditorInfo },
        { "tooltips_visible", state.EditorTooltips },
        { "hover_tooltip", state.HoverTooltip },
        { "drag_tooltip", state.DragTooltip },
        { "typing", state.Typing },
        { "undo_depth", state.UndoDepth },
        { "redo_depth", state.RedoDepth } } },
    { "preset", state.Preset },
    { "saved_files", state.SavedFiles },
    { "messages", state.Messages },
  });
}

ViewerState Viewer::State() const
{
  const Internals& in = *this->Internal;
  ViewerState state;
  state.Lighting = in.Current.Render.Lighting.Model;
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
  state.HelpPage = in.Status->GetHelpPageName();
  state.HelpBoxes = in.Status->GetHelpBoxes();
  state.HelpFontSize = in.Status->GetHelpFontSize();
  state.UnsavedChanges = in.UnsavedChanges(*this);
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

  state.FramesRendered = in.FramesRendered;
  state.MarchedFrames = in.MarchedFrames;
  state.ExposureEV = in.Mapper->GetExposureEV();
  state.AutoExposure = in.Current.Render.AutoExposure;
  state.Display = DisplayCurveName(in.Current.Render.Display);
  state.ExposureMeterings = in.ExposureMeterings;
  state.MeteredFrames = in.MeteredFrames;
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
  state.LegendVisible = in.Legend->GetVisibility() != 0;
  state.Message = in.Status->GetMessage();
  state.Readout = in.Status->GetReadout();
  state.Progress = in.Status->GetProgress();
  state.TimeStep = in.Time->Current();
  state.TimeSteps = in.Time->Count();
  state.Time = in.Time->Steps() ? in.Time->Label() : "";
  state.Coarsened = in.Coarsened;
  state.ReadAhead = in.Time->ReadAheadStep();
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
  for (int v = 0; v < SliceViews::Count; ++v)
  {
    state.SliceViewZoom[size_t(v)] = in.Views2D->GetZoom(v);
    state.SliceViewPan[size_t(v)] = in.Views2D->GetPan(v);
  }
  state.HoverValid = in.Hovered.Valid;
  state.HoverIndex = in.Hovered.Index;
  state.HoverValue = in.Hovered.Value;
  using Function = TransferFunctionEditor::Function;
  state.OpacityPointPixels = in.Editing->GetPointPixels(Function::Opacity);
  state.ColorPointPixels = in.Editing->GetPointPixels(Function::Color);
  state.ColorStripPixels = in.Editing->GetColorStripPixels();
  state.PaletteVisible = in.Editing->GetPaletteVisible();
  state.PalettePixels = in.Editing->GetPalettePixels();
  state.SelectedFunction = TransferFunctionEditor::FunctionName(in.Editing->GetSelectedFunction());
  state.SelectedPoint = in.Editing->GetSelectedPoint();
  state.EditorInfo = in.Editing->GetInfoText();
  state.EditorTooltips = in.Editing->GetTooltipsVisible();
  state.HoverTooltip = in.Editing->GetHoverTooltip();
  state.DragTooltip = in.Editing->GetDragTooltip();
  state.Typing = in.Typing;
  state.UndoDepth = in.History.GetUndoDepth();
  state.RedoDepth = in.History.GetRedoDepth();
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
    *in.Messages << "cloudvis: error: " << EscapeInvalidUtf8(e.what()) << std::endl;
  }
}

} // namespace cloudvis
