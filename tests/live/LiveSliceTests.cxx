// Live tests of what `cloudvis view` shows of a field's values, as ParaView and 3D Slicer users
// expect it: the transfer function fitted to the field's range on opening, the probe (a
// Control-click on a slice) and the readout under the pointer with the field's units, the
// slices' window/level (reset, auto, typed) and the slice views' zoom, pan and PageUp/PageDown.
// The real binary on its own Xvfb server, driven with real X input (LiveSession.h); every check
// reads the state the viewer writes or the window's pixels. Window 480 x 400: the 3D view is
// 480 x 300 above the editor's 480 x 100.
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

bool Logged(const json& state, const std::string& text)
{
  for (const json& message : state["messages"])
  {
    if (message.get<std::string>().find(text) != std::string::npos)
    {
      return true;
    }
  }
  return false;
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

// A scene's own function is kept when it covers the field's values, and grown to take them in
// when they lie beyond it (ParaView's "grow" rescale): [0, 1] becomes [0, 4.58], its shape kept.
TEST(LiveSlices, SceneFunctionIsKeptWhenItCoversTheFieldAndGrownWhenNot)
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
    const json& opacity = state["transfer_function"]["opacity"];
    ASSERT_EQ(opacity.size(), 3u);
    EXPECT_DOUBLE_EQ(opacity[0][0].get<double>(), 0.0);
    EXPECT_NEAR(opacity[1][0].get<double>(), 0.5 * FieldHigh, 1e-5);
    EXPECT_NEAR(opacity[2][0].get<double>(), FieldHigh, 1e-5);
    EXPECT_DOUBLE_EQ(opacity[1][1].get<double>(), 0.2);
    EXPECT_TRUE(Logged(state, "beyond the scene's function")) << state["messages"];
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

} // namespace
} // namespace live
} // namespace cloudvis
