// ViewerState as JSON: what `cloudvis view --state-file` writes after every frame and every batch
// of input, for tests and tools that drive the viewer with real input (docs/viewer.md).
#include "Viewer.h"

#include <cmath>

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
  json probed = json::array();
  for (double value : state.ProbedValue)
  {
    probed.push_back(Number(value));
  }
  return {
    { "frames_rendered", state.FramesRendered },
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
    { "first_light_position", state.FirstLightPosition },
    { "volume_visible", state.VolumeVisible },
    { "help_visible", state.HelpVisible },
    { "hint_visible", state.HintVisible },
    { "color_bar_visible", state.ColorBarVisible },
    { "message", state.Message },
    { "readout", state.Readout },
    { "slices",
      { { "visible", state.SliceVisible },
        { "index", state.SliceIndex },
        { "position", state.SlicePosition },
        { "probed_value", probed },
        { "window_level", state.SliceWindowLevel },
        { "colors", state.SliceColors },
        { "oblique_visible", state.ObliqueVisible } } },
    { "probe",
      { { "valid", state.ProbeValid },
        { "index", state.ProbeIndex },
        { "value", state.ProbeValue } } },
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
        { "selected_function", state.SelectedFunction },
        { "selected_point", state.SelectedPoint },
        { "info", state.EditorInfo },
        { "tooltips_visible", state.EditorTooltips },
        { "typing", state.Typing },
        { "undo_depth", state.UndoDepth },
        { "redo_depth", state.RedoDepth } } },
    { "preset", state.Preset },
    { "saved_files", state.SavedFiles },
    { "messages", state.Messages },
  };
}

} // namespace cloudvis
