// Live tests of what `cloudvis view` saves, driven with real X input (LiveSession.h): the
// screenshot of the layout (s) at a chosen size with its color legends. Window 480 x 400: the
// views are 480 x 300 above the editor's 480 x 100.
#include "LiveHelpers.h"
#include "LiveSession.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cloudvis
{
namespace live
{
namespace
{
using json = nlohmann::json;

const std::string Cloudvis = support::CloudvisBinary();

// The live tests' cloud (Arguments) with colors red at density 0 to blue at 1, so that the cloud's
// legend has colors nothing else in the window has.
std::vector<std::string> RedToBlueArguments(const std::vector<std::string>& extra)
{
  std::vector<std::string> arguments =
    Arguments({ "--set", "transfer_function.color=[[0,1,0,0],[1,0,0,1]]" });
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

// The mean color, in 8-bit levels, of the 7 x 7 pixels around the point at (fx, fy) of a
// rectangle x0, y0, x1, y1 of `image`.
std::array<double, 3> MeanAround(const support::Image& image,
  const std::array<double, 4>& rectangle,
  double fx,
  double fy)
{
  const int cx = int(std::lround(rectangle[0] + fx * (rectangle[2] - rectangle[0])));
  const int cy = int(std::lround(rectangle[1] + fy * (rectangle[3] - rectangle[1])));
  return MeanColorAround(image, cx, cy, 3);
}

// The pixels of `image` in the rectangle (fractions of its size) whose color is within `tolerance`
// levels of `color`.
int CountColor(const support::Image& image,
  const std::array<double, 4>& fractions,
  const std::array<double, 3>& color,
  double tolerance)
{
  int count = 0;
  for (int y = int(fractions[1] * image.Height); y < int(fractions[3] * image.Height); ++y)
  {
    for (int x = int(fractions[0] * image.Width); x < int(fractions[2] * image.Width); ++x)
    {
      const std::array<double, 3> pixel{
        { image.Level(x, y, 0), image.Level(x, y, 1), image.Level(x, y, 2) }
      };
      count += ColorDistance(pixel, color) <= tolerance ? 1 : 0;
    }
  }
  return count;
}

std::string LastSaved(const json& state, const std::string& extension)
{
  for (auto file = state["saved_files"].rbegin(); file != state["saved_files"].rend(); ++file)
  {
    const std::string path = file->get<std::string>();
    if (path.size() > extension.size() &&
      path.compare(path.size() - extension.size(), extension.size(), extension) == 0)
    {
      return path;
    }
  }
  return "";
}

// In four views, s saves every view of the layout at the size --screenshot-size asks for (twice
// the window's views here), without the editor: each view's region of the PNG holds what that
// view shows in the window, and the 3D view's region holds the cloud's legend (its red and blue)
// and the slices' color bar (blue-yellow's pale yellow). The EXR is the 3D view's float image.
// With the legends hidden (b), the next screenshot has none.
TEST(LiveExport, ScreenshotHoldsEveryViewAtTheChosenSizeWithLegends)
{
  LiveSession session(
    Cloudvis, RedToBlueArguments({ "--layout", "four", "--screenshot-size", "960x600" }));
  const json state = session.WaitUntilConverged();
  ASSERT_TRUE(state["legend_visible"].get<bool>());
  ASSERT_TRUE(state["color_bar_visible"].get<bool>());
  const support::Image window = session.Pixels({ { 0, 100, 480, 400 } }); // the views
  session.Key("s");
  const json saved = session.WaitFor(
    [](const json& s) { return s["saved_files"].size() == 2; }, "the screenshot", 120.0);
  const support::Image png = support::ReadPng(LastSaved(saved, ".png"));
  ASSERT_EQ(png.Width, 960);
  ASSERT_EQ(png.Height, 600);
  const support::Exr exr = support::ReadExr(LastSaved(saved, ".exr"));
  EXPECT_EQ(exr.Width, 480);
  EXPECT_EQ(exr.Height, 300);

  // Each slice view's region, at points off the crosshairs and captions, against the window's
  // view (the window's views start 100 pixels up, the PNG's at 0).
  for (const char* name : { "axial", "coronal", "sagittal" })
  {
    const json& v = state["viewports"][name];
    const std::array<double, 4> inWindow{ { v[0].get<double>(),
      v[1].get<double>() - 100.0,
      v[2].get<double>(),
      v[3].get<double>() - 100.0 } };
    const std::array<double, 4> inPng{
      { 2.0 * inWindow[0], 2.0 * inWindow[1], 2.0 * inWindow[2], 2.0 * inWindow[3] }
    };
    for (const auto& [fx, fy] : { std::pair{ 0.35, 0.4 }, std::pair{ 0.62, 0.6 } })
    {
      const auto shown = MeanAround(window, inWindow, fx, fy);
      const auto exported = MeanAround(png, inPng, fx, fy);
      EXPECT_LT(ColorDistance(shown, exported), 16.0)
        << name << " at (" << fx << ", " << fy << "): window " << shown[0] << " " << shown[1] << " "
        << shown[2] << ", screenshot " << exported[0] << " " << exported[1] << " " << exported[2];
    }
  }
  // The 3D view is the top right quarter; its legends at its right edge, the cloud's above the
  // slices'.
  const std::array<double, 4> legend{ { 0.5 + 0.5 * 0.8, 0.75, 1.0, 1.0 } };
  const std::array<double, 4> bar{ { 0.5 + 0.5 * 0.8, 0.5, 1.0, 0.75 } };
  EXPECT_GT(CountColor(png, legend, { { 255.0, 0.0, 0.0 } }, 40.0), 20) << "no red in the legend";
  EXPECT_GT(CountColor(png, legend, { { 0.0, 0.0, 255.0 } }, 40.0), 20) << "no blue in the legend";
  EXPECT_GT(CountColor(png, bar, { { 255.0, 237.0, 140.0 } }, 30.0), 20)
    << "no pale yellow in the slices' color bar";

  session.Key("b");
  session.WaitFor(
    [](const json& s) { return !s["legend_visible"].get<bool>(); }, "b to hide the legends");
  session.Key("s");
  const json again = session.WaitFor(
    [](const json& s) { return s["saved_files"].size() == 4; }, "the second screenshot", 120.0);
  const support::Image bare = support::ReadPng(LastSaved(again, ".png"));
  EXPECT_EQ(CountColor(bare, legend, { { 255.0, 0.0, 0.0 } }, 40.0), 0);
  EXPECT_EQ(CountColor(bare, bar, { { 255.0, 237.0, 140.0 } }, 30.0), 0);
}

} // namespace
} // namespace live
} // namespace cloudvis
