// Live tests of the multiple-scattering volume in the viewer (issue 21): turning the light or
// editing the transfer function recomputes the volume a slice of work per frame, the progress line
// says "multiple scattering: converging (k/n)" while it does, input is handled meanwhile, and the
// picture converges: the line goes, the state says converged, and the image is the one a viewer
// opened on the new light shows; a screenshot taken meanwhile saves that converged picture. The
// real binary on its own Xvfb, real X input (LiveSession.h).
#include "LiveHelpers.h"
#include "LiveSession.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace cloudvis
{
namespace live
{
namespace
{
using json = nlohmann::json;

const std::string Cloudvis = support::CloudvisBinary();
const std::string Converging = "multiple scattering: converging (";

// The march on a 96^3 cloud: its volume's finest grid is 25^3, several frames of work.
std::vector<std::string> MarchArguments()
{
  return Arguments({ "--set", "render.lighting=march", "--set", "field.dimensions=96" });
}

// The same viewer opened with its one light where `state`'s first light is.
std::vector<std::string> ArgumentsWithTheLightOf(const json& state)
{
  const json light = state["first_light_position"];
  const auto exact = [](const json& v)
  {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v.get<double>());
    return std::string(text);
  };
  std::vector<std::string> arguments = MarchArguments();
  arguments.push_back("--set");
  arguments.push_back("lights=[{\"type\":\"directional\",\"position\":[" + exact(light[0]) + "," +
    exact(light[1]) + "," + exact(light[2]) + "]}]");
  return arguments;
}

// Takes a screenshot (s) and returns the PNG it saved.
support::Image Screenshot(LiveSession& session)
{
  const size_t before = session.State()["saved_files"].size();
  session.Key("s");
  const json saved = session.WaitFor(
    [&](const json& s) { return s["saved_files"].size() >= before + 2; }, "the screenshot", 90.0);
  for (const json& file : saved["saved_files"])
  {
    const std::string path = file.get<std::string>();
    if (path.size() > 4 && path.compare(path.size() - 4, 4, ".png") == 0)
    {
      return support::ReadPng(path);
    }
  }
  throw std::runtime_error("the screenshot saved no PNG");
}

// The progress line's k and n, or {-1, -1} when it says nothing.
std::array<int, 2> Progress(const json& state)
{
  const std::string line = state["progress"].get<std::string>();
  std::array<int, 2> progress{ { -1, -1 } };
  if (line.rfind(Converging, 0) == 0)
  {
    std::sscanf(line.c_str() + Converging.size(), "%d/%d", &progress[0], &progress[1]);
  }
  return progress;
}

// After a change: the line shows, counts up over frames, and goes once the picture converged.
// Returns the converged state.
json ExpectProgressThenConvergence(LiveSession& session, const std::string& change)
{
  const json first = session.WaitFor(
    [](const json& s) { return Progress(s)[0] >= 0; }, "the progress line after " + change, 60.0);
  const std::array<int, 2> k = Progress(first);
  EXPECT_GT(k[1], 100) << "every pass of the volume counts";
  EXPECT_LT(k[0], k[1]);
  EXPECT_FALSE(first["converged"].get<bool>()) << "converged while the volume is computed";
  const json later =
    session.WaitFor([&](const json& s) { return Progress(s)[0] > k[0] || Progress(s)[0] < 0; },
      "the progress to advance after " + change,
      60.0);
  EXPECT_GT(later["frames_rendered"].get<long>(), first["frames_rendered"].get<long>())
    << "the work is spread over frames";
  const json converged =
    session.WaitFor([](const json& s) { return s["converged"].get<bool>() && Progress(s)[0] < 0; },
      "the picture to converge after " + change,
      90.0);
  EXPECT_EQ(converged["progress"], "");
  return converged;
}
}

TEST(LiveScattering, TurningTheLightRecomputesTheVolumeOverFramesThenConverges)
{
  LiveSession session(Cloudvis, MarchArguments());
  const json opened = session.WaitUntilConverged();
  EXPECT_EQ(opened["progress"], "") << "the first volume is computed whole";
  session.Key("Right"); // the light turns 10 degrees
  const json first = session.WaitFor([](const json& s) { return Progress(s)[0] >= 0; },
    "the progress line after the light turned",
    60.0);
  // Input is handled while the volume converges: the next key turns the light on, and its
  // frame comes (a new computation starts from the beginning).
  const size_t keys = first["keys"].size();
  session.Key("Right");
  const json handled = session.WaitFor([&](const json& s)
    { return s["keys"].size() > keys && !s["keys"].back()["shown_at"].is_null(); },
    "the second key's frame while the volume converges",
    30.0);
  EXPECT_NE(handled["first_light_position"], opened["first_light_position"]);
  const json converged = ExpectProgressThenConvergence(session, "the light turned twice");
  EXPECT_EQ(converged["first_light_position"], handled["first_light_position"]);

  // The converged picture is the one a viewer opened with the light where it is now computes
  // whole: the same passes, the same volume. Compared on the cloud in the middle of the 3D view,
  // away from the texts (the key's message at the top left, which the new viewer does not show).
  const auto view = converged["viewports"]["3d"];
  const int width = view[2].get<int>() - view[0].get<int>();
  const int height = view[3].get<int>() - view[1].get<int>();
  const std::array<int, 4> rectangle{ { view[0].get<int>() + width / 4,
    view[1].get<int>() + height / 6,
    view[2].get<int>() - width / 4,
    view[3].get<int>() - height / 4 } };
  const support::Image progressive = session.Pixels(rectangle);
  LiveSession fresh(Cloudvis, ArgumentsWithTheLightOf(converged));
  fresh.WaitUntilConverged();
  if (const char* dump = std::getenv("CLOUDVIS_LIVE_DUMP"))
  {
    support::WritePng(progressive, std::string(dump) + "-progressive.png");
    support::WritePng(fresh.Pixels(rectangle), std::string(dump) + "-fresh.png");
  }
  EXPECT_LE(support::MaxDifference(progressive, fresh.Pixels(rectangle)), 2.0 / 255.0);
}

TEST(LiveScattering, EditingTheTransferFunctionRecomputesTheVolumeOverFrames)
{
  LiveSession session(Cloudvis, MarchArguments());
  const json start = session.WaitUntilConverged();
  const size_t inner = SelectInnerOpacityPoint(session, start);
  session.WaitUntilConverged();
  const auto point = Pixel(start["editor"]["opacity_point_pixels"][inner]);
  session.Drag(1, point, { { point[0], point[1] - 15 } }); // less opaque there
  const json converged = ExpectProgressThenConvergence(session, "the opacity point moved");
  EXPECT_NE(converged["transfer_function"]["opacity"], start["transfer_function"]["opacity"]);
}

TEST(LiveScattering, AScreenshotWhileTheVolumeConvergesSavesTheConvergedPicture)
{
  // The capture finishes the volume before its frames: the file is what a viewer opened on the
  // new light saves, not the old multiple scattering under the new light.
  LiveSession session(Cloudvis, MarchArguments());
  session.WaitUntilConverged();
  session.Key("Right");
  const json converging = session.WaitFor([](const json& s) { return Progress(s)[0] >= 0; },
    "the progress line after the light turned",
    60.0);
  const support::Image taken = Screenshot(session);
  LiveSession fresh(Cloudvis, ArgumentsWithTheLightOf(converging));
  fresh.WaitUntilConverged();
  const support::Image expected = Screenshot(fresh);
  ASSERT_EQ(taken.Width, expected.Width);
  EXPECT_LE(support::MaxDifference(taken, expected), 2.0 / 255.0);
}

} // namespace live
} // namespace cloudvis
