// Live tests of `cloudvis view`: the real binary on its own Xvfb server, driven with real X input
// (XTEST) while its event loop runs (LiveSession.h), for what recorded sessions cannot see: time
// passing with a button held, CPU use when idle, input arriving while frames render, and the
// mouse on the editor's points and the slices as a person uses it. Every check reads the state
// the viewer writes (--state-file) or the window's pixels, polling with generous timeouts.
// Window 480 x 400: the 3D view is 480 x 300 above the editor's 480 x 100.
#include "LiveHelpers.h"
#include "LiveSession.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <set>
#include <thread>

namespace cloudvis
{
namespace live
{
namespace
{
using json = nlohmann::json;

const std::string Cloudvis = support::CloudvisBinary();

std::array<double, 3> Vector(const json& value)
{
  return { { value[0].get<double>(), value[1].get<double>(), value[2].get<double>() } };
}

// The angle in degrees between the camera's directions from its focal point in two states.
double CameraTurn(const json& a, const json& b)
{
  const auto direction = [](const json& state)
  {
    const auto p = Vector(state["camera"]["position"]);
    const auto f = Vector(state["camera"]["focal_point"]);
    std::array<double, 3> d{ { p[0] - f[0], p[1] - f[1], p[2] - f[2] } };
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (double& c : d)
    {
      c /= length;
    }
    return d;
  };
  const auto u = direction(a), v = direction(b);
  const double cosine = std::min(1.0, u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
  return std::acos(cosine) * 180.0 / 3.14159265358979323846;
}

// A drag held still for three seconds turns the camera by the drag alone: VTK's trackball turns
// 20 / (view width) degrees per pixel times its motion factor 10, so 40 pixels across a 480-pixel
// view turn it 16.7 degrees. (The old loop's timer turned it on and on while the button was held.)
TEST(Live, HeldDragTurnsTheCameraOnlyByTheDrag)
{
  LiveSession session(Cloudvis, Arguments());
  const json before = session.WaitUntilConverged();
  const auto center = session.Center("3d");
  session.Move(center[0] - 20, center[1]);
  session.Press(1);
  for (int i = 1; i <= 8; ++i)
  {
    session.Move(center[0] - 20 + 5 * i, center[1]);
  }
  Pause(3.0); // the button held still: the scenario, not a check
  session.Release(1);
  const json after = session.WaitFor([&](const json& s)
    { return s["converged"].get<bool>() && s["camera"] != before["camera"]; },
    "the camera to turn and the image to converge");
  const double width =
    before["viewports"]["3d"][2].get<double>() - before["viewports"]["3d"][0].get<double>();
  EXPECT_NEAR(CameraTurn(before, after), 40.0 * 20.0 / width * 10.0, 0.01);
}

// A live session recorded with --record (a drag held still, a key) replays with --play to the
// camera the live session ended with: time passing leaves nothing in the camera that the
// recorded events do not hold.
TEST(Live, RecordedLiveSessionReplaysToTheSameCamera)
{
  const support::TemporaryDirectory files("cloudvis-live-record");
  LiveSession session(Cloudvis,
    Arguments(
      { "--record", files.File("session.log"), "--save-scene-on-exit", files.File("live.json") }));
  const json before = session.WaitUntilConverged();
  const auto center = session.Center("3d");
  session.Move(center[0] - 20, center[1] - 10);
  session.Press(1);
  for (int i = 1; i <= 6; ++i)
  {
    session.Move(center[0] - 20 + 6 * i, center[1] - 10 + 3 * i);
  }
  Pause(2.0); // held still
  session.Release(1);
  session.Key("m");
  session.WaitFor([&](const json& s) { return s["lighting"] == "derivative"; }, "the key");
  session.Key("q");
  ASSERT_EQ(session.WaitForExit(), 0) << session.Stderr();
  const support::CommandResult replayed = support::RunCloudvis(support::With({ "view" },
                                                                 Arguments({ "--play",
                                                                   files.File("session.log"),
                                                                   "--save-scene-on-exit",
                                                                   files.File("replay.json") })),
    { "DISPLAY=" + session.DisplayName() });
  ASSERT_EQ(replayed.Status, 0) << replayed.Err;
  const json live = json::parse(support::ReadText(files.File("live.json")));
  const json replay = json::parse(support::ReadText(files.File("replay.json")));
  EXPECT_NE(live["camera"]["position"], before["camera"]["position"]) << "the drag turned nothing";
  EXPECT_EQ(replay["render"]["lighting"], "derivative");
  for (const char* key : { "position", "focal_point", "view_up" })
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(
        replay["camera"][key][c].get<double>(), live["camera"][key][c].get<double>(), 1e-9)
        << key << "[" << c << "]";
    }
  }
}

// Converged and left alone, the viewer renders nothing and uses (almost) no CPU.
TEST(Live, IdleViewerUsesNoCpuOnceConverged)
{
  LiveSession session(Cloudvis, Arguments());
  const json converged = session.WaitUntilConverged();
  const double cpu = session.CpuSeconds();
  Pause(5.0); // the idle period measured
  const json later = session.State();
  const double used = session.CpuSeconds() - cpu;
  EXPECT_EQ(later["frames_rendered"], converged["frames_rendered"]) << "frames while idle";
  EXPECT_LT(used, 0.1) << "CPU seconds used in 5 idle seconds";
}

// Five keys sent at once are all handled, in order, and the frames do not come between them:
// at most one frame is rendered between the first key and the last (the old loop rendered after
// each key, so five keys waited behind four frames).
TEST(Live, RapidKeysAreHandledInOrderWithoutAFrameEach)
{
  LiveSession session(Cloudvis, Arguments());
  const json before = session.WaitUntilConverged();
  const std::vector<std::string> keys = { "Right", "Right", "m", "Up", "m" };
  session.Keys(keys);
  const json after = session.WaitFor([&](const json& s)
    { return s["keys"].size() == keys.size() && !s["keys"].back()["shown_at"].is_null(); },
    "five keys handled and shown");
  std::vector<std::string> handled;
  std::set<double> frames;
  for (const json& key : after["keys"])
  {
    handled.push_back(key["key"].get<std::string>());
    frames.insert(key["shown_at"].get<double>());
  }
  EXPECT_EQ(handled, keys);
  EXPECT_LE(frames.size(), 2u) << after["keys"].dump();
  EXPECT_EQ(after["lighting"], "march");
  EXPECT_NE(after["first_light_position"], before["first_light_position"]);
}

// Every kind of transfer-function point moves in the directions that mean something: the top
// end point of the opacity curve down and up, an inner opacity point right, left and up, an inner
// color point right, the top end color point left. The value tooltip goes with the drag.
TEST(Live, EditorPointsOfEveryKindMove)
{
  LiveSession session(Cloudvis, Arguments());
  json state = session.WaitUntilConverged();
  const auto dragged = [&](const char* function, size_t index, int dx, int dy, const char* what)
  {
    const json start = session.State();
    const std::string pixels = std::string(function) + "_point_pixels";
    const auto from = Pixel(start["editor"][pixels][index]);
    session.Drag(1, from, { { from[0] + dx, from[1] + dy } }, 6);
    return session.WaitFor(
      [&](const json& s)
      {
        return s["transfer_function"] != start["transfer_function"] &&
          !s["editor"]["tooltips_visible"].get<bool>();
      },
      what);
  };
  const auto opacity = [](const json& s, size_t i, int c)
  { return s["transfer_function"]["opacity"][i][c].get<double>(); };
  const auto color = [](const json& s, size_t i)
  { return s["transfer_function"]["color"][i][0].get<double>(); };

  const size_t last = state["transfer_function"]["opacity"].size() - 1;
  json moved = dragged("opacity", last, 0, -20, "the top end opacity point to move down");
  EXPECT_LT(opacity(moved, last, 1), opacity(state, last, 1));
  EXPECT_DOUBLE_EQ(opacity(moved, last, 0), opacity(state, last, 0));
  json up = dragged("opacity", last, 0, 10, "the top end opacity point to move up");
  EXPECT_GT(opacity(up, last, 1), opacity(moved, last, 1));

  const size_t inner = last - 1;
  json right = dragged("opacity", inner, 30, 0, "an inner opacity point to move right");
  EXPECT_GT(opacity(right, inner, 0), opacity(up, inner, 0));
  json left = dragged("opacity", inner, -15, 0, "an inner opacity point to move left");
  EXPECT_LT(opacity(left, inner, 0), opacity(right, inner, 0));
  json raised = dragged("opacity", inner, 0, 15, "an inner opacity point to move up");
  EXPECT_GT(opacity(raised, inner, 1), opacity(left, inner, 1));

  json colorRight = dragged("color", 1, 30, 0, "an inner color point to move right");
  EXPECT_GT(color(colorRight, 1), color(raised, 1));
  const size_t lastColor = raised["transfer_function"]["color"].size() - 1;
  json colorLeft = dragged("color", lastColor, -20, 0, "the top end color point to move left");
  EXPECT_LT(color(colorLeft, lastColor), color(colorRight, lastColor));
  EXPECT_EQ(colorLeft["editor"]["undo_depth"].get<int>(), 7);
}

// Delete removes the point clicked last, not an end point; Ctrl+z brings it back, Ctrl+y
// removes it again.
TEST(Live, DeleteRemovesTheSelectedPointAndUndoRestoresIt)
{
  LiveSession session(Cloudvis, Arguments());
  const json start = session.WaitUntilConverged();
  const size_t count = start["transfer_function"]["opacity"].size();
  const auto point = Pixel(start["editor"]["opacity_point_pixels"][count - 2]);
  session.Move(point[0], point[1]);
  session.Press(1);
  session.Release(1);
  session.WaitFor([&](const json& s) { return s["editor"]["selected_point"] == int(count - 2); },
    "the point to be selected");
  session.Key("Delete");
  const json removed = session.WaitFor([&](const json& s)
    { return s["transfer_function"]["opacity"].size() == count - 1; },
    "Delete to remove the point");
  EXPECT_EQ(removed["transfer_function"]["opacity"][count - 2],
    start["transfer_function"]["opacity"][count - 1]);
  session.Key("z", true);
  const json undone = session.WaitFor([&](const json& s)
    { return s["transfer_function"]["opacity"].size() == count; },
    "Ctrl+z to bring it back");
  EXPECT_EQ(undone["transfer_function"]["opacity"], start["transfer_function"]["opacity"]);
  session.Key("y", true);
  session.WaitFor([&](const json& s)
    { return s["transfer_function"]["opacity"].size() == count - 1; },
    "Ctrl+y to remove it again");
  // An end point stays, and says why.
  const auto end = Pixel(session.State()["editor"]["opacity_point_pixels"][0]);
  session.Move(end[0], end[1]);
  session.Press(1);
  session.Release(1);
  session.WaitFor([&](const json& s) { return s["editor"]["selected_point"] == 0; },
    "the first point to be selected");
  session.Key("Delete");
  const json kept = session.WaitFor([&](const json& s)
    { return s["message"].get<std::string>().find("end points") != std::string::npos; },
    "Delete on an end point to be refused");
  EXPECT_EQ(kept["transfer_function"]["opacity"].size(), count - 1);
}

// Typed values set the selected point; bad text changes nothing and says what is wrong.
TEST(Live, TypedValuesSetTheSelectedPoint)
{
  LiveSession session(Cloudvis, Arguments());
  const json start = session.WaitUntilConverged();
  const size_t inner = SelectInnerOpacityPoint(session, start);
  session.Keys({ "Return", "5", "space", "0", "Return" });
  session.WaitFor([&](const json& s)
    { return s["message"].get<std::string>().find("density must lie") != std::string::npos; },
    "a density outside the neighbours to be refused");
  EXPECT_EQ(session.State()["transfer_function"], start["transfer_function"]);
  session.Keys({ "BackSpace",
    "BackSpace",
    "BackSpace",
    "0",
    "period",
    "4",
    "space",
    "0",
    "period",
    "2",
    "5",
    "Return" });
  const json typed = session.WaitFor(
    [&](const json& s) { return !s["editor"]["typing"].get<bool>(); }, "typing to end");
  EXPECT_EQ(typed["transfer_function"]["opacity"][inner], json::array({ 0.4, 0.25 }));
}

// A right drag on a slice changes the window/level of the slices, and the slice image with it.
TEST(Live, SliceWindowLevelChangesTheSliceImage)
{
  LiveSession session(Cloudvis, Arguments());
  session.WaitUntilConverged();
  session.Key("z");
  const json shown = session.WaitFor([](const json& s)
    { return s["slices"]["visible"][2].get<bool>() && s["converged"].get<bool>(); },
    "the z slice to show");
  const auto center = session.Center("3d");
  // Near the slice's corner, where the cloud does not cover it.
  const std::array<int, 4> corner = {
    { center[0] + 55, center[1] + 50, center[0] + 75, center[1] + 70 }
  };
  const auto before = session.Pixels(corner);
  session.Drag(3, { { center[0] + 65, center[1] + 60 } }, { { center[0] + 125, center[1] + 30 } });
  const json after = session.WaitFor(
    [&](const json& s)
    {
      return s["slices"]["window_level"] != shown["slices"]["window_level"] &&
        s["converged"].get<bool>();
    },
    "the window/level to change");
  EXPECT_GT(after["slices"]["window_level"][0].get<double>(),
    shown["slices"]["window_level"][0].get<double>());
  EXPECT_GT(support::Compare(before, session.Pixels(corner)).MeanLevels(), 5.0)
    << "the slice image did not change";
}

// The z slice faces the default camera: a middle drag still moves it (up: toward the viewer),
// and a Control+left click probes a voxel whose readout stays after the button is released.
TEST(Live, SliceFacingTheCameraMovesAndItsProbeStays)
{
  LiveSession session(Cloudvis, Arguments());
  session.WaitUntilConverged();
  session.Key("z");
  const json shown = session.WaitFor(
    [](const json& s) { return s["slices"]["visible"][2].get<bool>(); }, "the z slice to show");
  const int index = shown["slices"]["index"][2].get<int>();
  const auto center = session.Center("3d");
  session.Drag(2, { { center[0] + 60, center[1] + 40 } }, { { center[0] + 60, center[1] + 80 } });
  const json moved =
    session.WaitFor([&](const json& s) { return s["slices"]["index"][2].get<int>() != index; },
      "the middle drag to move the slice");
  EXPECT_GT(moved["slices"]["index"][2].get<int>(), index);
  session.Move(center[0] + 60, center[1] + 40);
  session.Hold("Control_L", true);
  session.Press(1);
  session.Release(1);
  session.Hold("Control_L", false);
  const json probed =
    session.WaitFor([](const json& s) { return s["probe"]["valid"].get<bool>(); }, "the probe");
  // The slice's index from the same state as the probe: `moved` is the first state after the
  // slice left its place, while the rest of the drag may still be on its way (under the
  // sanitizers the slice went on from 34 to 35 after it, and the probe rightly said 35).
  EXPECT_GE(probed["slices"]["index"][2].get<int>(), moved["slices"]["index"][2].get<int>());
  EXPECT_EQ(probed["probe"]["index"][2], probed["slices"]["index"][2])
    << "the probe must read the slice where it is now";
  const std::string readout = probed["readout"].get<std::string>();
  const std::string probeLine = readout.substr(readout.find("probe ("));
  EXPECT_NE(probeLine.find("density"), std::string::npos) << readout;
  session.Move(center[0], center[1] - 60); // elsewhere, no button
  // Once the viewer has seen the pointer move (the voxel under it changed), the probe's line is
  // still there.
  const json away = session.WaitFor([&](const json& s)
    { return !s["hover"]["valid"].get<bool>() || s["hover"]["index"] != probed["probe"]["index"]; },
    "the pointer to move away from the probed voxel");
  EXPECT_NE(away["readout"].get<std::string>().find(probeLine), std::string::npos)
    << "the probe's readout did not stay";
}

// The four-view layout: the wheel over the axial view steps its slice one voxel per notch, a
// click moves the other two slices (the crosshair) through the voxel clicked.
TEST(Live, FourViewsWheelStepsAndClickMovesTheCrosshair)
{
  LiveSession session(Cloudvis, Arguments());
  session.WaitUntilConverged();
  session.Key("4");
  const json four = session.WaitFor([](const json& s)
    { return s["four_views"].get<bool>() && s["viewports"].contains("axial"); },
    "the four views");
  const auto axial = session.Center("axial");
  const int z = four["slices"]["index"][2].get<int>();
  for (int i = 0; i < 3; ++i)
  {
    session.Wheel(axial[0], axial[1], true);
  }
  session.WaitFor([&](const json& s) { return s["slices"]["index"][2].get<int>() == z + 3; },
    "three wheel notches to step the axial slice by three");
  session.Move(axial[0] + 30, axial[1] + 20);
  session.Press(1);
  session.Release(1);
  const json clicked = session.WaitFor(
    [](const json& s) { return s["probe"]["valid"].get<bool>(); }, "the click to probe");
  EXPECT_GT(clicked["slices"]["index"][0].get<int>(), four["slices"]["index"][0].get<int>());
  EXPECT_GT(clicked["slices"]["index"][1].get<int>(), four["slices"]["index"][1].get<int>());
  EXPECT_EQ(clicked["probe"]["index"][0], clicked["slices"]["index"][0]);
  EXPECT_EQ(clicked["probe"]["index"][1], clicked["slices"]["index"][1]);
  EXPECT_EQ(clicked["probe"]["index"][2].get<int>(), z + 3);
}

// A resized window lays its views out again: the views and the editor share the new size as
// before, and a slice view made tall and narrow still fits its whole slice (background on both
// sides), where a camera fitted to the old shape would cut the slice at the view's edges.
TEST(Live, ResizedWindowLaysItsViewsOutAgain)
{
  LiveSession session(Cloudvis, Arguments({ "--layout", "four" }));
  session.WaitUntilConverged();
  session.Resize(480, 900);
  const json resized = session.WaitFor(
    [](const json& s) {
      return s["window"]["size"] == json::array({ 480, 900 }) && s["converged"].get<bool>();
    },
    "the window to take its new size");
  EXPECT_EQ(resized["viewports"]["3d"], json::array({ 240, 563, 480, 900 }));
  EXPECT_EQ(resized["viewports"]["axial"], json::array({ 0, 563, 240, 900 }));
  EXPECT_EQ(resized["viewports"]["editor"], json::array({ 0, 0, 480, 225 }));
  const json strip = resized["editor"]["color_strip_pixels"];
  EXPECT_NEAR(strip[2].get<double>(), 480.0 - 14.0, 0.5) << "the editor did not follow";
  // The axial view's left and right edges at its middle height: its background.
  const auto center = session.Center("axial");
  for (const int x : { 2, 237 })
  {
    const auto pixel = session.Pixels({ { x, center[1], x + 1, center[1] + 1 } });
    EXPECT_NEAR(pixel.Level(0, 0, 2), 25.5, 2.0)
      << "x " << x << ": the slice reaches the view's edge";
  }
}

// A message fades away by itself; the hint line goes once the help has been shown.
TEST(Live, MessagesFadeAndTheHintGoesAfterTheHelp)
{
  LiveSession session(Cloudvis, Arguments());
  const json start = session.WaitUntilConverged();
  EXPECT_TRUE(start["hint_visible"].get<bool>());
  session.Key("m");
  session.WaitFor(
    [](const json& s) { return s["message"] == "lighting: derivative"; }, "the message");
  session.WaitFor([](const json& s) { return s["message"] == ""; }, "the message to fade", 60.0);
  session.Key("h");
  session.WaitFor([](const json& s) { return s["help_page"] == "keys"; }, "the help");
  session.Key("h");
  session.WaitFor([](const json& s) { return s["help_page"] == "mouse-3d"; }, "its mouse page");
  session.Key("h");
  session.WaitFor(
    [](const json& s) { return s["help_page"] == "mouse-2d"; }, "its second mouse page");
  session.Key("h");
  const json after = session.WaitFor(
    [](const json& s) { return !s["help_visible"].get<bool>(); }, "the help to hide");
  EXPECT_FALSE(after["hint_visible"].get<bool>());
}

// An optically thick sphere at albedo 1 (optical diameter near 2500) opened path-traced (`m`
// passes the path tracer by): its walks are far longer than the loop budget a software
// rasterizer gives a fragment (llvmpipe's 65535 turns), so there the GPU cuts them short. `render`
// refuses such an image; the viewer keeps showing it but says so as an error once the still has
// converged. Where the GPU runs the walks whole, neither complains.
TEST(Live, APathTracedStillCutShortByTheGpuIsSaid)
{
  support::TemporaryDirectory work;
  const std::string scene = work.Write("thick.json", R"({
    "field": { "dimensions": 48, "bounds": [-2, 2, -2, 2, -2, 2], "density_model": "constant",
               "shape": { "type": "sphere", "radius": 1 }, "noise": "none" },
    "transfer_function": { "opacity": [[0, 0], [1, 0.05]], "color": [[0, 1, 1, 1], [1, 1, 1, 1]],
                           "unit_distance": 0.0002 },
    "render": { "lighting": "pathtrace", "spp": 2, "resolution_scale": 0.25 },
    "camera": { "position": [0, 0, 7], "view_angle": 30 } })");
  const support::CommandResult rendered =
    support::RunCloudvis({ "render", scene, "--size", "480x300", "-o", work.File("thick.png") });
  const std::string cut = "the GPU ended the path tracer's walks early";
  const bool refused = rendered.Err.find(cut) != std::string::npos;
  ASSERT_TRUE(refused ? rendered.Status == 1 : rendered.Status == 0) << rendered.Err;

  LiveSession session(Cloudvis, { scene, "--size", "480x400" });
  const json traced = session.WaitUntilConverged();
  ASSERT_EQ(traced["lighting"], "pathtrace");
  if (refused)
  {
    EXPECT_EQ(work.Files(), std::vector<std::string>{ "thick.json" }) << "the refusal left a file";
    const json said = session.WaitFor(
      [&](const json& s) { return Said(s, cut); }, "the viewer to say the walks were cut");
    EXPECT_TRUE(Said(said, "thick.json: ")) << said["messages"].back();
  }
  else
  {
    EXPECT_FALSE(Logged(traced, cut));
  }
}

} // namespace
} // namespace live
} // namespace cloudvis
