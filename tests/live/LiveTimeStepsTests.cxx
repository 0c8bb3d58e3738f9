// Live tests of stepping through time (issue 34, part 3): `cloudvis view 'run/step_*.vti'` opens a
// numbered file series with its first step, names it in the window's top right, reads the next
// one ahead while the window is idle, and . and , step forward and back with the camera, slices and
// transfer function kept. A series being written is followed: a file that appears later is the next
// step, and a half-written one is an error message with the step shown kept, not a crash. The real
// binary on its own Xvfb, real X input (LiveSession.h); checks read the state file and the pixels.
#include "LiveHelpers.h"
#include "LiveSession.h"
#include "SupportFixtures.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace cloudvis
{
namespace live
{
namespace
{
using json = nlohmann::json;

const std::string Cloudvis = support::CloudvisBinary();

// A ball of `radius` voxels in `side`^3 as `path` (.vti), written as a model writes each step.
void WriteBall(const std::string& path, double radius, int side = 32)
{
  support::WriteImageData(support::LinearBall(side, radius), path);
}

// Pixels of the 3D view's centre block more than 24 levels from the background (taken at the
// view's left edge, away from the field's outline): how much of the cloud is seen.
size_t CloudPixels(LiveSession& session)
{
  const auto c = session.Center("3d");
  const std::array<double, 3> background = MeanColorAround(
    session.Pixels({ { c[0] - 230, c[1] - 10, c[0] - 210, c[1] + 10 } }), 10, 10, 5);
  const support::Image image =
    session.Pixels({ { c[0] - 100, c[1] - 100, c[0] + 100, c[1] + 100 } });
  size_t count = 0;
  for (int y = 0; y < image.Height; ++y)
    for (int x = 0; x < image.Width; ++x)
    {
      const std::array<double, 3> color = {
        image.Level(x, y, 0), image.Level(x, y, 1), image.Level(x, y, 2)
      };
      count += ColorDistance(color, background) > 24.0 ? 1 : 0;
    }
  return count;
}

json WaitForStep(LiveSession& session, int step, const std::string& file)
{
  return session.WaitFor(
    [&](const json& s)
    {
      return s["time_step"] == step &&
        s["time"].get<std::string>().find(file) != std::string::npos && s["converged"].get<bool>();
    },
    "time step " + std::to_string(step) + " (" + file + ") on screen");
}

TEST(LiveTimeSteps, PeriodAndCommaStepThroughAGrowingFileSeries)
{
  support::TemporaryDirectory run;
  for (int n = 1; n <= 3; ++n)
  {
    WriteBall(run.File("step_" + std::to_string(n) + ".vti"), 4.0 + 4.0 * n);
  }
  LiveSession session(
    Cloudvis, { run.File("step_*.vti"), "--set", "render.accumulate=4", "--size", "480x400" });
  const json start = WaitForStep(session, 0, "step_1.vti");
  EXPECT_EQ(start["time_steps"], 3);
  EXPECT_EQ(start["time"], "time step 0 of 0 .. 2: step_1.vti");
  session.WaitFor([](const json& s) { return s["read_ahead"] == 1; },
    "the next step to be read ahead while the window is idle");
  const size_t small = CloudPixels(session);

  session.Key("period");
  const json second = WaitForStep(session, 1, "step_2.vti");
  EXPECT_EQ(second["camera"], start["camera"]) << "the camera stays";
  EXPECT_EQ(second["transfer_function"], start["transfer_function"]) << "the function stays";
  session.WaitFor([](const json& s) { return s["read_ahead"] == 2; }, "step 2 read ahead");
  EXPECT_GT(small, 1000u) << "the ball of step 1 is seen";
  // Radius 12 against 8 voxels: 2.25 times the area, about 2.2 times the pixels here.
  EXPECT_GT(CloudPixels(session), small * 3 / 2) << "the ball of step 2 is larger";

  session.Key("period");
  WaitForStep(session, 2, "step_3.vti");
  session.Key("period");
  session.WaitFor([](const json& s) { return Said(s, "is the last: the folder holds no later"); },
    "the last step to say so");

  // The model writes the next step: the viewer finds it.
  WriteBall(run.File("step_4.vti"), 15.0);
  session.Key("period");
  const json fourth = WaitForStep(session, 3, "step_4.vti");
  EXPECT_EQ(fourth["time_steps"], 4);

  // A half-written file: refused in the message line, the step shown kept.
  {
    std::ifstream whole(run.File("step_4.vti"), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(whole)), {});
    std::ofstream(run.File("step_5.vti"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  session.Key("period");
  const json refused = session.WaitFor(
    [&](const json& s) { return Said(s, run.File("step_5.vti") + ": "); }, "step 5 refused");
  EXPECT_EQ(refused["time_step"], 3);
  EXPECT_EQ(session.WaitForExit(0.5), -1) << "the viewer still runs";

  session.Key("comma");
  WaitForStep(session, 2, "step_3.vti");
  // The scene saved names the series and the step shown.
  session.Key("w");
  const json saved = session.WaitFor(
    [](const json& s) { return !s["saved_files"].empty(); }, "the scene to be saved");
  std::ifstream sceneFile(saved["saved_files"].back().get<std::string>());
  const json scene = json::parse(sceneFile);
  EXPECT_EQ(scene["field"]["file"], run.File("step_*.vti"));
  EXPECT_EQ(scene["field"]["time_step"], 2);
}

TEST(LiveTimeSteps, AStepOnAnotherGridIsRefusedAndAFieldWithoutTimeSaysSo)
{
  support::TemporaryDirectory run;
  WriteBall(run.File("step_1.vti"), 8.0);
  WriteBall(run.File("step_2.vti"), 12.0, 24);
  LiveSession session(
    Cloudvis, { run.File("step_*.vti"), "--set", "render.accumulate=4", "--size", "480x400" });
  WaitForStep(session, 0, "step_1.vti");
  session.Key("period");
  const json refused = session.WaitFor(
    [](const json& s) { return Said(s, "is not the first step's"); }, "the other grid refused");
  EXPECT_EQ(refused["time_step"], 0);
  EXPECT_NE(refused["messages"].back().get<std::string>().find(
              run.File("step_2.vti") + " (step 1 of " + run.File("step_*.vti") + "): its grid"),
    std::string::npos)
    << refused["messages"].back();

  LiveSession generated(Cloudvis, Arguments());
  const json opened = generated.WaitUntilConverged();
  EXPECT_EQ(opened["time_steps"], 1);
  EXPECT_EQ(opened["time"], "");
  generated.Key("period");
  generated.WaitFor(
    [](const json& s) { return Said(s, "the field has one time step"); }, "no time to step");
}

// A series beyond the GPU memory the viewer may take: its 3D view draws each step coarsened
// (FieldCoarsening.h) and says so in the corner, and the slices keep the field as it is.
TEST(LiveTimeSteps, AFieldBeyondTheGpuMemoryIsDrawnCoarserAtEveryStep)
{
  support::TemporaryDirectory run;
  WriteBall(run.File("big_1.vti"), 40.0, 192);
  WriteBall(run.File("big_2.vti"), 60.0, 192);
  LiveSession session(Cloudvis,
    { run.File("big_*.vti"),
      "--set",
      "render.gpu_memory=16",
      "--set",
      "render.accumulate=4",
      "--size",
      "480x400" });
  const json start = WaitForStep(session, 0, "big_1.vti");
  EXPECT_NE(start["coarsened"].get<std::string>().find(
              "coarsened 2x (96 x 96 x 96 voxels drawn for 192 x 192 x 192)"),
    std::string::npos)
    << start["coarsened"];
  EXPECT_TRUE(Logged(start, "the field was coarsened 2x")) << "said in the message line";
  const size_t small = CloudPixels(session);
  EXPECT_GT(small, 1000u);
  session.Key("period");
  const json next = WaitForStep(session, 1, "big_2.vti");
  EXPECT_EQ(next["coarsened"], start["coarsened"]);
  EXPECT_GT(CloudPixels(session), small * 3 / 2) << "the next step is drawn, coarsened too";
}

} // namespace
} // namespace live
} // namespace cloudvis
