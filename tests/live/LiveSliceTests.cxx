// Live tests of what `cloudvis view` shows of a field's values, as ParaView and 3D Slicer users
// expect it: the transfer function fitted to the field's range on opening, the probe (a
// Control-click on a slice) and the readout under the pointer with the field's units, the
// slices' window/level (reset, auto, typed) and the slice views' zoom, pan and PageUp/PageDown.
// The real binary on its own Xvfb server, driven with real X input (LiveSession.h); every check
// reads the state the viewer writes or the window's pixels. Window 480 x 400: the 3D view is
// 480 x 300 above the editor's 480 x 100.
#include "LiveHelpers.h"
#include "LiveSession.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataWriter.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{
namespace live
{
namespace
{
using json = nlohmann::json;

const std::string Cloudvis = support::CloudvisBinary();

// A field that does not fit the default transfer function's [0, 1]: 25^3 voxels of spacing 0.1,
// 1 at the corners rising to 4.58 at the centre voxel (a Gaussian bump of 5 voxels, shifted and
// scaled to give exactly these two values).
constexpr int FieldSide = 25;
constexpr double FieldLow = 1.0;
constexpr double FieldHigh = 4.58;

std::string WriteBumpField(const std::string& path)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(FieldSide, FieldSide, FieldSide);
  image->SetSpacing(0.1, 0.1, 0.1);
  vtkNew<vtkFloatArray> density;
  density->SetName("density");
  density->SetNumberOfTuples(vtkIdType(FieldSide) * FieldSide * FieldSide);
  const int c = FieldSide / 2;
  const double corner = std::exp(-3.0 * c * c / (2.0 * 25.0));
  vtkIdType id = 0;
  for (int k = 0; k < FieldSide; ++k)
  {
    for (int j = 0; j < FieldSide; ++j)
    {
      for (int i = 0; i < FieldSide; ++i)
      {
        const double r2 = double((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c));
        const double bump = (std::exp(-r2 / (2.0 * 25.0)) - corner) / (1.0 - corner);
        density->SetValue(id++, float(FieldLow + (FieldHigh - FieldLow) * bump));
      }
    }
  }
  image->GetPointData()->SetScalars(density);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  if (writer->Write() != 1)
  {
    throw std::runtime_error("could not write " + path);
  }
  return path;
}

std::vector<std::string> Window(const std::vector<std::string>& extra = {})
{
  std::vector<std::string> arguments = { "--set", "render.accumulate=4", "--size", "480x400" };
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

// The densities a state's transfer function spans, opacity and color points together.
std::array<double, 2> Span(const json& state)
{
  const json& function = state["transfer_function"];
  return { { std::min(
               function["opacity"][0][0].get<double>(), function["color"][0][0].get<double>()),
    std::max(
      function["opacity"].back()[0].get<double>(), function["color"].back()[0].get<double>()) } };
}

// A .vti opened directly gets its transfer function and the slices' window fitted to its values,
// [1, 4.58], and says so: the cloud is the bump, not the opaque block the default [0, 1] function
// makes of values beyond 1 (everything at least 1 has the function's top opacity, 0.8 per 0.1).
TEST(LiveSlices, FieldFileOpensFittedToItsValues)
{
  const support::TemporaryDirectory files("cloudvis-live-fit");
  LiveSession session(Cloudvis, Window({ WriteBumpField(files.File("bump.vti")) }));
  const json state = session.WaitUntilConverged();
  const auto span = Span(state);
  EXPECT_NEAR(span[0], FieldLow, 1e-5);
  EXPECT_NEAR(span[1], FieldHigh, 1e-5);
  EXPECT_NEAR(state["slices"]["window_level"][0].get<double>(), FieldHigh - FieldLow, 1e-5);
  EXPECT_NEAR(state["slices"]["window_level"][1].get<double>(), 0.5 * (FieldHigh + FieldLow), 1e-5);
  EXPECT_TRUE(Logged(state, "fitted to the field's values [1, 4.58], as the slices' window"))
    << state["messages"];
  EXPECT_EQ(state["editor"]["undo_depth"], 0) << "the fit on opening is no edit to undo";
  EXPECT_FALSE(state["unsaved_changes"].get<bool>()) << "the fit on opening is no edit to save";
  // Near the front face's corner (the field fills the middle two thirds of the view's height)
  // the rays pass the bump by and the values stay near 1: the background shows, where the
  // unfitted function drew white.
  const auto center = session.Center("3d");
  const int off = 85;
  const auto corner = session.Pixels(
    { { center[0] + off, center[1] + off, center[0] + off + 6, center[1] + off + 6 } });
  double mean = 0.0;
  for (int y = 0; y < 6; ++y)
  {
    for (int x = 0; x < 6; ++x)
    {
      mean += corner.Level(x, y, 0) / 36.0;
    }
  }
  EXPECT_LT(mean, 60.0) << "an opaque block where the field is near its minimum";
}

// A scene's own function is kept as it was written or saved, as ParaView loads a saved state's
// colour maps; when the field's values lie beyond it the message says that f fits it. A scene
// without a function of its own has the default one grown to take the values in (ParaView's
// "grow" rescale): [0, 1] becomes [0, 4.58], its shape kept.
TEST(LiveSlices, SceneFunctionIsKeptAndTheDefaultOneGrown)
{
  const support::TemporaryDirectory files("cloudvis-live-grow");
  const std::string field = WriteBumpField(files.File("bump.vti"));
  const auto scene = [&](const std::string& name, double top)
  {
    return files.Write(name,
      json({ { "field", { { "file", field } } },
             { "transfer_function",
               { { "opacity", { { 0.0, 0.0 }, { 0.5 * top, 0.2 }, { top, 0.5 } } },
                 { "color", { { 0.0, 0.5, 0.5, 0.5 }, { top, 1.0, 1.0, 1.0 } } } } } })
        .dump());
  };
  {
    LiveSession session(Cloudvis, Window({ scene("covers.json", 5.0) }));
    const json state = session.WaitUntilConverged();
    EXPECT_EQ(
      state["transfer_function"]["opacity"], json({ { 0.0, 0.0 }, { 2.5, 0.2 }, { 5.0, 0.5 } }));
    EXPECT_FALSE(Logged(state, "fitted")) << state["messages"];
  }
  {
    LiveSession session(Cloudvis, Window({ scene("short.json", 1.0) }));
    const json state = session.WaitUntilConverged();
    EXPECT_EQ(
      state["transfer_function"]["opacity"], json({ { 0.0, 0.0 }, { 0.5, 0.2 }, { 1.0, 0.5 } }));
    EXPECT_TRUE(Logged(state, "lie beyond the scene's transfer function")) << state["messages"];
    EXPECT_FALSE(state["unsaved_changes"].get<bool>());
  }
  {
    // No transfer_function: the default one, whose points end at 1, grows to the field's top.
    const std::string plain =
      files.Write("plain.json", json({ { "field", { { "file", field } } } }).dump());
    LiveSession session(Cloudvis, Window({ plain }));
    const json state = session.WaitUntilConverged();
    const json& opacity = state["transfer_function"]["opacity"];
    ASSERT_GE(opacity.size(), 2u);
    EXPECT_DOUBLE_EQ(opacity.front()[0].get<double>(), 0.0);
    EXPECT_NEAR(opacity.back()[0].get<double>(), FieldHigh, 1e-5);
    EXPECT_TRUE(Logged(state, "beyond the default function")) << state["messages"];
    EXPECT_FALSE(state["unsaved_changes"].get<bool>()) << "the fit is where the session starts";
  }
}

// The default cloud on 48^3 voxels as liquid water content on a grid in kilometres, converging
// in 4 frames, with the slice across z (it faces the default camera).
std::vector<std::string> CloudWithUnits()
{
  return Window({ "--set",
    "field.dimensions=48",
    "--set",
    "field.quantity=lwc",
    "--set",
    "field.length_unit=km" });
}

json ShowZSlice(LiveSession& session)
{
  session.WaitUntilConverged();
  session.Key("z");
  return session.WaitFor([](const json& s)
    { return s["slices"]["visible"][2].get<bool>() && s["converged"].get<bool>(); },
    "the z slice to show");
}

void ControlClick(LiveSession& session, int x, int y)
{
  session.Move(x, y);
  session.Hold("Control_L", true);
  session.Press(1);
  session.Release(1);
  session.Hold("Control_L", false);
}

// A left drag that starts on a slice facing the camera turns the camera (in ParaView and Slicer
// a left drag in the 3D view always does), and probes nothing.
TEST(LiveSlices, LeftDragOnASliceTurnsTheCamera)
{
  LiveSession session(Cloudvis, CloudWithUnits());
  const json shown = ShowZSlice(session);
  const auto center = session.Center("3d");
  session.Drag(1, { { center[0] + 40, center[1] + 30 } }, { { center[0] + 90, center[1] + 30 } });
  const json turned = session.WaitFor([&](const json& s)
    { return s["camera"] != shown["camera"] && s["converged"].get<bool>(); },
    "the left drag to turn the camera");
  EXPECT_FALSE(turned["probe"]["valid"].get<bool>()) << "the drag probed the slice";
}

// Control+click on a slice in the 3D view probes the voxel and moves the other two slices (the
// crosshairs of the slice views) through it; the readout gives the position in the field's
// length unit and the value as its quantity with its unit.
TEST(LiveSlices, ControlClickProbesMovesTheCrosshairsAndShowsUnits)
{
  LiveSession session(Cloudvis, CloudWithUnits());
  const json shown = ShowZSlice(session);
  const auto center = session.Center("3d");
  ControlClick(session, center[0] + 60, center[1] + 40);
  const json probed = session.WaitFor(
    [](const json& s) { return s["probe"]["valid"].get<bool>(); }, "the Control+click to probe");
  EXPECT_EQ(probed["camera"], shown["camera"]) << "the Control+click turned the camera";
  EXPECT_EQ(probed["probe"]["index"][2], shown["slices"]["index"][2]);
  EXPECT_GT(probed["probe"]["index"][0].get<int>(), shown["slices"]["index"][0].get<int>());
  EXPECT_GT(probed["probe"]["index"][1].get<int>(), shown["slices"]["index"][1].get<int>());
  EXPECT_EQ(probed["slices"]["index"][0], probed["probe"]["index"][0]) << "crosshair x";
  EXPECT_EQ(probed["slices"]["index"][1], probed["probe"]["index"][1]) << "crosshair y";
  const std::string readout = probed["readout"].get<std::string>();
  const std::string probeLine = readout.substr(readout.find("probe ("));
  EXPECT_NE(probeLine.find(") km  voxel ["), std::string::npos) << readout;
  EXPECT_NE(probeLine.find("  lwc "), std::string::npos) << readout;
  EXPECT_NE(probeLine.find(" g/m^3"), std::string::npos) << readout;
}

// The readout follows the pointer over a slice without a click (Slicer's data probe), goes when
// the pointer leaves the slices, and the whole readout goes when the slices are hidden.
TEST(LiveSlices, ReadoutFollowsThePointerAndGoesWithTheSlices)
{
  LiveSession session(Cloudvis, CloudWithUnits());
  ShowZSlice(session);
  const auto center = session.Center("3d");
  session.Move(center[0] + 50, center[1] + 30);
  const json first = session.WaitFor(
    [](const json& s) { return s["hover"]["valid"].get<bool>(); }, "the pointer's readout");
  EXPECT_EQ(first["readout"].get<std::string>().rfind("pointer (", 0), 0u) << first["readout"];
  EXPECT_FALSE(first["probe"]["valid"].get<bool>()) << "hovering probed";
  session.Move(center[0] + 70, center[1] + 45);
  const json second =
    session.WaitFor([&](const json& s) { return s["hover"]["index"] != first["hover"]["index"]; },
      "the pointer's readout to follow it");
  EXPECT_GT(second["hover"]["index"][0].get<int>(), first["hover"]["index"][0].get<int>());
  EXPECT_NE(second["readout"], first["readout"]);
  session.Move(5, 5 + session.State()["viewports"]["3d"][1].get<int>()); // off the field
  session.WaitFor([](const json& s) { return !s["hover"]["valid"].get<bool>(); },
    "the pointer's readout to go off the slice");
  ControlClick(session, center[0] + 60, center[1] + 40);
  session.WaitFor([](const json& s) { return s["probe"]["valid"].get<bool>(); }, "the probe");
  session.Key("z");
  const json hidden = session.WaitFor(
    [](const json& s) { return !s["slices"]["visible"][2].get<bool>(); }, "the slice to hide");
  EXPECT_EQ(hidden["readout"], "") << "the readout stayed without the slices";
  EXPECT_FALSE(hidden["probe"]["valid"].get<bool>());
}

// The values of the bump field's slice across z at its centre, as the automatic window sees
// them: the 1st and 99th percentiles, picked as the viewer picks them.
std::array<double, 2> CentreSlicePercentiles()
{
  std::vector<double> values;
  const int c = FieldSide / 2;
  const double corner = std::exp(-3.0 * c * c / (2.0 * 25.0));
  for (int j = 0; j < FieldSide; ++j)
  {
    for (int i = 0; i < FieldSide; ++i)
    {
      const double r2 = double((i - c) * (i - c) + (j - c) * (j - c));
      const double bump = (std::exp(-r2 / (2.0 * 25.0)) - corner) / (1.0 - corner);
      values.push_back(double(float(FieldLow + (FieldHigh - FieldLow) * bump)));
    }
  }
  std::sort(values.begin(), values.end());
  const auto at = [&](double f)
  { return values[size_t(std::lround(f * double(values.size() - 1)))]; };
  return { { at(0.01), at(0.99) } };
}

void Type(LiveSession& session, const std::string& text)
{
  std::vector<std::string> keys;
  for (const char c : text)
  {
    keys.push_back(c == ' ' ? "space"
        : c == '.'          ? "period"
        : c == '-'          ? "minus"
                            : std::string(1, c));
  }
  keys.push_back("Return");
  session.Keys(keys);
}

// a takes the window/level from the shown slice's values (1st to 99th percentile), Shift+a goes
// back to the field's range, Shift+l types them; bad typed values change nothing and say why.
TEST(LiveSlices, WindowLevelAutoResetAndTyped)
{
  const support::TemporaryDirectory files("cloudvis-live-window");
  LiveSession session(Cloudvis, Window({ WriteBumpField(files.File("bump.vti")) }));
  session.WaitUntilConverged();
  session.Key("a");
  session.WaitFor([](const json& s)
    { return Said(s, "no slice is shown"); },
    "a without a slice to say so");
  session.Key("z");
  session.WaitFor(
    [](const json& s) { return s["slices"]["visible"][2].get<bool>(); }, "the z slice");
  session.Key("a");
  const auto [low, high] = CentreSlicePercentiles();
  const json automatic = session.WaitFor([](const json& s)
    { return Said(s, "from the shown slices"); },
    "the automatic window");
  EXPECT_NEAR(automatic["slices"]["window_level"][0].get<double>(), high - low, 1e-5);
  EXPECT_NEAR(automatic["slices"]["window_level"][1].get<double>(), 0.5 * (high + low), 1e-5);
  ASSERT_GT(FieldHigh - FieldLow - (high - low), 0.1) << "the test cannot tell auto from reset";

  session.Key("A");
  const json reset = session.WaitFor([](const json& s)
    { return Said(s, "reset to the field's range"); },
    "Shift+a to reset the window");
  EXPECT_NEAR(reset["slices"]["window_level"][0].get<double>(), FieldHigh - FieldLow, 1e-5);
  EXPECT_NEAR(reset["slices"]["window_level"][1].get<double>(), 0.5 * (FieldHigh + FieldLow), 1e-5);

  session.Key("L");
  Type(session, "0 2");
  const json refused = session.WaitFor(
    [](const json& s) { return Said(s, "the window (the first number) must be greater than 0"); },
    "a window of 0 to be refused");
  EXPECT_TRUE(refused["editor"]["typing"].get<bool>());
  EXPECT_EQ(refused["slices"]["window_level"], reset["slices"]["window_level"]);
  session.Keys(
    { "BackSpace", "BackSpace", "BackSpace", "1", "period", "5", "space", "2", "Return" });
  const json typed = session.WaitFor(
    [](const json& s) { return !s["editor"]["typing"].get<bool>(); }, "the typed window");
  EXPECT_EQ(typed["slices"]["window_level"], json::array({ 1.5, 2.0 }));
  EXPECT_TRUE(Said(typed, "densities 1.25 to 2.75"))
    << typed["messages"];
}

// The transfer function's colors on a slice are the color strip's at every density, whatever the
// window: with the cloud-dusk preset and a window over [0.3, 0.7], empty space (density 0) keeps
// the function's purple at 0 (it showed the salmon of 0.3, the window's low end).
TEST(LiveSlices, TransferFunctionColorsOnSlicesIgnoreTheWindow)
{
  LiveSession session(Cloudvis, Window({ "--set", "field.dimensions=48", "--layout", "four" }));
  session.WaitUntilConverged();
  session.Keys({ "p", "c", "c", "c" });
  session.WaitFor([](const json& s)
    { return s["preset"] == "cloud-dusk" && s["slices"]["colors"] == "transfer function"; },
    "the cloud-dusk preset and its colors on the slices");
  session.Key("L");
  Type(session, "0.4 0.5");
  const json windowed = session.WaitFor(
    [](const json& s) {
      return s["slices"]["window_level"] == json::array({ 0.4, 0.5 }) && s["converged"].get<bool>();
    },
    "the typed window");
  EXPECT_TRUE(Said(windowed, "colors are not windowed"))
    << windowed["messages"];
  // The axial slice's bottom right corner, empty space: the slice fills 1/1.15 of the view's
  // height around its centre.
  const json& axial = windowed["viewports"]["axial"];
  const int side = int((axial[3].get<int>() - axial[1].get<int>()) / 1.15);
  const auto center = session.Center("axial");
  const int x = center[0] + int(0.42 * side), y = center[1] - int(0.42 * side);
  const auto pixel = session.Pixels({ { x, y, x + 1, y + 1 } });
  const double purple[3] = { 0.42, 0.36, 0.52 }; // cloud-dusk's color at density 0
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(pixel.Level(0, 0, c), 255.0 * purple[c], 3.0) << "channel " << c;
  }
}

// In the four views, Control + wheel zooms the slice view under the pointer (about the pointer:
// the voxel there stays under it), Shift + left drag pans it without probing, PageUp and
// PageDown step the slice under the pointer, and r fits the views again.
TEST(LiveSlices, SliceViewsZoomPanAndPageThroughSlices)
{
  LiveSession session(Cloudvis, Window({ "--set", "field.dimensions=48", "--layout", "four" }));
  const json start = session.WaitUntilConverged();
  const auto axial = session.Center("axial");
  const json& view = start["viewports"]["axial"];
  const int left = view[0].get<int>() + 2;
  const auto edge = [&] { return session.Pixels({ { left, axial[1], left + 1, axial[1] + 1 } }); };
  ASSERT_NEAR(edge().Level(0, 0, 2), 25.5, 2.0) << "the fitted slice reaches the view's edge";

  const std::array<int, 2> at{ { axial[0] + 30, axial[1] + 20 } };
  session.Move(at[0], at[1]);
  const json before =
    session.WaitFor([](const json& s) { return s["hover"]["valid"].get<bool>(); }, "the pointer");
  session.Hold("Control_L", true);
  for (int i = 0; i < 3; ++i)
  {
    session.Wheel(at[0], at[1], true);
  }
  session.Hold("Control_L", false);
  const json zoomed = session.WaitFor([](const json& s)
    { return s["slice_views"]["axial"]["zoom"].get<double>() > 1.9 && s["converged"].get<bool>(); },
    "Control + wheel to zoom the axial view");
  EXPECT_NEAR(zoomed["slice_views"]["axial"]["zoom"].get<double>(), 1.25 * 1.25 * 1.25, 1e-9);
  EXPECT_EQ(zoomed["slices"]["index"], start["slices"]["index"]) << "the wheel stepped a slice";
  EXPECT_EQ(zoomed["slice_views"]["coronal"]["zoom"], 1.0) << "another view zoomed";
  EXPECT_GT(std::abs(edge().Level(0, 0, 2) - 25.5), 5.0) << "the slice did not grow to the edge";
  session.Move(at[0] + 1, at[1]);
  session.Move(at[0], at[1]);
  const json still = session.WaitFor(
    [&](const json& s) { return s["hover"]["valid"].get<bool>(); }, "the pointer after the zoom");
  for (int c = 0; c < 2; ++c)
  {
    EXPECT_LE(
      std::abs(still["hover"]["index"][c].get<int>() - before["hover"]["index"][c].get<int>()), 1)
      << "the voxel under the pointer moved away (axis " << c << ")";
  }

  session.Hold("Shift_L", true);
  session.Drag(1, at, { { at[0] + 40, at[1] } });
  session.Hold("Shift_L", false);
  // The slice follows the pointer: 40 pixels right moves the view's centre left by 40 pixels'
  // worth of world units (the view's height in pixels spans 2 x the parallel scale, 2.3 for
  // the default field's 4 x 4 slice and the 15 % margin).
  const double height = double(view[3].get<int>() - view[1].get<int>());
  const double worldPerPixel = 4.0 * 1.15 / height / (1.25 * 1.25 * 1.25);
  const auto moved = [&](const json& s)
  {
    return s["slice_views"]["axial"]["pan"][0].get<double>() -
      zoomed["slice_views"]["axial"]["pan"][0].get<double>();
  };
  const json panned = session.WaitFor([&](const json& s)
    { return std::abs(moved(s) + 40.0 * worldPerPixel) < 2.0 * worldPerPixel; },
    "Shift + left drag to pan the view by the drag");
  EXPECT_NEAR(panned["slice_views"]["axial"]["pan"][1].get<double>(),
    zoomed["slice_views"]["axial"]["pan"][1].get<double>(),
    1e-9);
  EXPECT_FALSE(panned["probe"]["valid"].get<bool>()) << "the pan probed";

  const auto sagittal = session.Center("sagittal");
  session.Move(sagittal[0], sagittal[1]);
  const int x = panned["slices"]["index"][0].get<int>();
  session.Key("Prior");
  session.WaitFor([&](const json& s) { return s["slices"]["index"][0].get<int>() == x + 1; },
    "PageUp over the sagittal view to step x up");
  session.Keys({ "Next", "Next" });
  const json paged =
    session.WaitFor([&](const json& s) { return s["slices"]["index"][0].get<int>() == x - 1; },
      "PageDown twice to step x down");
  EXPECT_EQ(paged["slices"]["index"][2], panned["slices"]["index"][2]) << "PageUp moved z";

  session.Key("r");
  const json reset = session.WaitFor(
    [](const json& s) { return s["slice_views"]["axial"]["zoom"] == 1.0; }, "r to fit the views");
  EXPECT_EQ(reset["slice_views"]["axial"]["pan"], json::array({ 0.0, 0.0 }));
}

} // namespace
} // namespace live
} // namespace cloudvis
