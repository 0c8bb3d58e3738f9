// Live tests of the viewer's exposure (render.exposure, docs/viewer.md "Exposure"): e and E step
// it by half a stop without marching the cloud again, Ctrl+e meters it automatically as `render`
// does (the 99th percentile of the cloud's luminance at 1.2), once per converged still and never
// during a drag, and undo, the saved scene and the screenshot carry it. The real binary on its own
// Xvfb, real X input (LiveSession.h); checks read the state file, the window's pixels and the
// files the viewer wrote.
#include "LiveHelpers.h"
#include "LiveSession.h"

#include "CloudDisplayTransform.h" // AutoExposureTarget, AutoExposurePercentile

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace cloudvis
{
namespace live
{
namespace
{
using json = nlohmann::json;

const std::string Cloudvis = support::CloudvisBinary();

// An EV as the viewer's messages and the PNG's metadata write it: "+1.25 EV".
std::string ShowEv(double ev)
{
  char text[32];
  std::snprintf(text, sizeof text, "%+.2f EV", ev);
  return text;
}

double Ev(const json& state)
{
  return state["exposure"]["ev"].get<double>();
}

bool Auto(const json& state)
{
  return state["exposure"]["auto"].get<bool>();
}

long Meterings(const json& state)
{
  return state["exposure"]["meterings"].get<long>();
}

// The keys pressed since `before` have all been drawn and the picture is still.
bool ShownAndStill(const json& state, const json& before, size_t keys)
{
  if (state["keys"].size() < before["keys"].size() + keys || !state["converged"].get<bool>())
  {
    return false;
  }
  for (const json& key : state["keys"])
  {
    if (key["shown_at"].is_null())
    {
      return false;
    }
  }
  return true;
}

// The scene the last w saved.
json LastSavedScene(const json& state)
{
  std::ifstream in(state["saved_files"].back().get<std::string>());
  return json::parse(in);
}

// The 3D view's middle half, where the cloud is and the legend and the orientation marker are
// not.
std::array<int, 4> MiddleOfTheView(const json& state)
{
  const json& v = state["viewports"]["3d"];
  const int x0 = v[0], y0 = v[1], x1 = v[2], y1 = v[3];
  return { { x0 + (x1 - x0) / 4, y0 + (y1 - y0) / 4, x1 - (x1 - x0) / 4, y1 - (y1 - y0) / 4 } };
}

// Under the linear curve over a black background the window's pixel is the cloud's radiance times
// 2^EV: a stop up doubles every unclipped pixel of the cloud. Two presses of E composite the
// converged still again under +1 EV, marching no frame; undo takes a half stop back and the saved
// scene holds the number.
TEST(LiveExposure, ShiftERaisesTheExposureWithoutMarching)
{
  LiveSession session(
    Cloudvis, Arguments({ "--set", "background=[0,0,0]", "--set", "render.display=linear" }));
  const json start = session.WaitUntilConverged();
  ASSERT_EQ(Ev(start), 0.0);
  ASSERT_FALSE(Auto(start));
  ASSERT_EQ(start["exposure"]["display"], "linear");
  const std::array<int, 4> middle = MiddleOfTheView(start);
  const support::Image before = session.Pixels(middle);

  session.Keys({ "E", "E" });
  const json raised =
    session.WaitFor([&](const json& s) { return ShownAndStill(s, start, 2) && Ev(s) == 1.0; },
      "two E to raise the exposure to +1 EV");
  EXPECT_TRUE(Said(raised, "exposure +1.00 EV")) << raised["messages"].back();
  EXPECT_EQ(raised["marched_frames"], start["marched_frames"])
    << "the exposure marched the cloud again (" << start["marched_frames"] << " -> "
    << raised["marched_frames"] << " frames)";
  EXPECT_EQ(raised["accumulated_frames"], start["accumulated_frames"]);
  const support::Image after = session.Pixels(middle);

  // The median ratio of the cloud's pixels dim enough not to clip at +1 EV (the outline drawn
  // behind the cloud does not scale, and is a few of them).
  std::vector<double> ratios;
  for (int y = 0; y < before.Height; ++y)
  {
    for (int x = 0; x < before.Width; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double level = before.Level(x, y, c);
        if (level >= 16.0 && level <= 110.0)
        {
          ratios.push_back(after.Level(x, y, c) / before.Level(x, y, c));
        }
      }
    }
  }
  ASSERT_GT(ratios.size(), 500u) << "the test does not see the cloud";
  std::nth_element(
    ratios.begin(), ratios.begin() + std::ptrdiff_t(ratios.size() / 2), ratios.end());
  EXPECT_NEAR(ratios[ratios.size() / 2], 2.0, 0.06) << "+1 EV does not double the cloud's pixels";

  session.Key("w");
  const json saved =
    session.WaitFor([](const json& s) { return s["saved_files"].size() == 1; }, "w to save");
  EXPECT_EQ(LastSavedScene(saved)["render"]["exposure"], 1.0);

  session.Key("z", true);
  const json undone =
    session.WaitFor([](const json& s) { return Ev(s) == 0.5; }, "Ctrl+z to take back half a stop");
  EXPECT_TRUE(Said(undone, "undone: exposure")) << undone["messages"].back();
}

// The shipped cumulus (filmic, render.exposure "auto"), small.
std::vector<std::string> SmallCumulus()
{
  return { CLOUDVIS_SCENES "/cumulus.json",
    "--set",
    "field.dimensions=48,36,48",
    "--set",
    "render.accumulate=4",
    "--size",
    "480x400" };
}

// The EV the automatic exposure gives a float image (tests/support), with enough cloud to meter.
double AutoExposureOf(const support::Exr& exr)
{
  size_t cloud = 0;
  const double ev = support::AutoExposureOf(exr, cloud);
  EXPECT_GT(cloud, 1000u) << "the screenshot holds little cloud";
  return ev;
}

// A scene with render.exposure "auto" is metered when its still has converged, once: the EV is
// the one `render` would choose for the picture (checked against the screenshot's float image,
// which records the window's exposure), frames that follow meter nothing, a drag meters nothing
// until its still converges. E leaves auto from the metered EV, Ctrl+e comes back to it, and the
// saved scene says "auto" again.
TEST(LiveExposure, AutoExposureMetersEachStillOnce)
{
  LiveSession session(Cloudvis, SmallCumulus());
  const json start = session.WaitFor([](const json& s)
    { return !s.empty() && s["converged"].get<bool>() && Meterings(s) > 0; },
    "the cumulus to converge and be metered");
  ASSERT_TRUE(Auto(start));
  ASSERT_EQ(start["exposure"]["display"], "filmic");
  EXPECT_EQ(Meterings(start), 1);
  EXPECT_EQ(start["exposure"]["metered_frames"], 4) << "metered before the still converged";
  const double metered = Ev(start);
  EXPECT_TRUE(std::isfinite(metered));
  EXPECT_NE(metered, 0.0) << "the shipped cumulus under its real sun needs some exposure";

  // The screenshot is the window's picture: its files record the metered EV, and the EV is the
  // one its float image asks for.
  session.Key("s");
  const json shot = session.WaitFor([](const json& s)
    { return s["saved_files"].size() == 2 && s["converged"].get<bool>(); },
    "the screenshot");
  const support::Exr exr = support::ReadExr(shot["saved_files"][1].get<std::string>());
  EXPECT_FLOAT_EQ(exr.Floats.at("cloudvis.exposure_ev"), float(metered));
  EXPECT_EQ(exr.Strings.at("cloudvis.display"), "filmic");
  EXPECT_NEAR(AutoExposureOf(exr), metered, 1e-4) << "not the EV `render` gives the picture";
  const support::Image png = support::ReadPng(shot["saved_files"][0].get<std::string>());
  EXPECT_NE(
    png.Text.at("cloudvis.display").find("filmic, exposure " + ShowEv(metered)), std::string::npos)
    << png.Text.at("cloudvis.display");

  // A drag meters nothing while it lasts; its still is metered once, and the frames after it
  // (the editor's tooltips) meter nothing.
  const json idle = session.WaitFor([&](const json& s)
    { return s["converged"].get<bool>() && Meterings(s) >= Meterings(shot); },
    "the window's still after the screenshot");
  const long beforeDrag = Meterings(idle);
  const auto center = session.Center("3d");
  session.Move(center[0], center[1]);
  session.Press(1);
  for (int step = 1; step <= 6; ++step)
  {
    session.Move(center[0] + 8 * step, center[1]);
    Pause(0.05);
  }
  const json dragging = session.WaitFor([&](const json& s)
    { return s["camera"]["position"] != idle["camera"]["position"]; },
    "the drag to turn the camera");
  session.Release(1);
  EXPECT_EQ(Meterings(dragging), beforeDrag) << "metered during the drag";
  const json turned = session.WaitFor([&](const json& s)
    { return s["converged"].get<bool>() && Meterings(s) > beforeDrag; },
    "the turned still to be metered");
  EXPECT_EQ(Meterings(turned), beforeDrag + 1)
    << "metered " << Meterings(turned) - beforeDrag << " times for one still";
  EXPECT_EQ(turned["exposure"]["metered_frames"], 4) << "metered before the still converged";
  EXPECT_GE(turned["marched_frames"].get<long>() - idle["marched_frames"].get<long>(), 4)
    << "the drag and the refinement after it marched fewer frames than one still has";
  const auto editor = session.Center("editor");
  for (int step = 0; step < 6; ++step)
  {
    session.Move(editor[0] - 60 + 20 * step, editor[1]);
  }
  const json after = session.WaitFor([&](const json& s)
    { return s["frames_rendered"] > turned["frames_rendered"].get<long>() + 1; },
    "frames after the still");
  EXPECT_EQ(Meterings(after), Meterings(turned)) << "the exposure hunts: metered a still again";
  EXPECT_EQ(Ev(after), Ev(turned));

  const double now = Ev(after);
  session.Key("E");
  const json manual = session.WaitFor([](const json& s) { return !Auto(s); }, "E to leave auto");
  EXPECT_DOUBLE_EQ(Ev(manual), now + 0.5);
  EXPECT_TRUE(Said(manual, "exposure " + ShowEv(now + 0.5))) << manual["messages"].back();
  session.Key("e", true);
  const json back = session.WaitFor([](const json& s) { return Auto(s); }, "Ctrl+e for auto");
  EXPECT_DOUBLE_EQ(Ev(back), now) << "the same still meters to the same EV";
  EXPECT_TRUE(Said(back, "exposure " + ShowEv(now) + " (auto)")) << back["messages"].back();
  session.Key("w");
  const json saved =
    session.WaitFor([](const json& s) { return s["saved_files"].size() == 3; }, "w to save");
  EXPECT_EQ(LastSavedScene(saved)["render"]["exposure"], "auto");
}

} // namespace
} // namespace live
} // namespace cloudvis
