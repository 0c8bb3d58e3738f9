// Live tests of the transfer-function editor's colors, driven with real X input (LiveSession.h):
// the color points drawn in their own colors, and the palette that gives the selected color
// point a color at a click. Window 480 x 400: the editor is the bottom 480 x 100.
#include "LiveHelpers.h"
#include "LiveSession.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

namespace cloudvis
{
namespace live
{
namespace
{
using json = nlohmann::json;

const std::string Cloudvis = support::CloudvisBinary();

// The window's color at a pixel, in 8-bit levels.
std::array<double, 3> ColorAt(LiveSession& session, const std::array<int, 2>& p)
{
  const support::Image image = session.Pixels({ { p[0], p[1], p[0] + 1, p[1] + 1 } });
  return { { image.Level(0, 0, 0), image.Level(0, 0, 1), image.Level(0, 0, 2) } };
}

// A color point's color in 8-bit levels.
std::array<double, 3> PointColor(const json& state, size_t i)
{
  const json& p = state["transfer_function"]["color"][i];
  return { { 255.0 * p[1].get<double>(), 255.0 * p[2].get<double>(), 255.0 * p[3].get<double>() } };
}

// The mean color, in 8-bit levels, of the 3 x 3 pixels at a color point's centre: the marker's
// fill (the strip under a marker has the point's color too, but VTK's gray fill hides it).
std::array<double, 3> MarkerColor(LiveSession& session, const json& state, size_t i)
{
  const auto centre = Pixel(state["editor"]["color_point_pixels"][i]);
  const support::Image image =
    session.Pixels({ { centre[0] - 1, centre[1] - 1, centre[0] + 2, centre[1] + 2 } });
  return MeanColorAround(image, 1, 1, 1);
}

// Three color points, red, green and blue. Each marker is drawn in its point's color. A click on
// the green point selects it and shows the palette; a click on a swatch gives the point the
// swatch's color (what the window shows there), keeps its density, and is one undo step that
// Ctrl+z takes back.
TEST(LiveEditor, ColorPointsShowTheirColorsAndThePaletteSetsOne)
{
  LiveSession session(Cloudvis,
    { "--set",
      "field.dimensions=48",
      "--set",
      "render.accumulate=4",
      "--set",
      "transfer_function.color=[[0,1,0,0],[0.5,0,1,0],[1,0,0,1]]",
      "--size",
      "480x400" });
  const json state = session.WaitUntilConverged();
  ASSERT_EQ(state["editor"]["color_point_pixels"].size(), 3u);
  if (const char* dump = std::getenv("CLOUDVIS_LIVE_DUMP"))
  {
    support::WritePng(session.Pixels({ { 0, 0, 480, 100 } }), dump);
  }
  for (size_t i = 0; i < 3; ++i)
  {
    const std::array<double, 3> marker = MarkerColor(session, state, i);
    EXPECT_LT(ColorDistance(marker, PointColor(state, i)), 40.0)
      << "color point " << i << " is drawn " << marker[0] << " " << marker[1] << " " << marker[2];
  }

  const json& green = state["editor"]["color_point_pixels"][1];
  const auto point = Pixel(green);
  session.Move(point[0], point[1]);
  session.Press(1);
  session.Release(1);
  const json selected = session.WaitFor(
    [](const json& s)
    {
      return s["editor"]["selected_function"] == "color" &&
        s["editor"]["selected_point"].get<int>() == 1 && s["editor"]["palette_visible"].get<bool>();
    },
    "the green point to be selected, with the palette");
  EXPECT_EQ(selected["transfer_function"], state["transfer_function"]) << "the click moved it";

  // The palette's top row is hues; a swatch a third of the way along is in the greens-to-blues,
  // but read its color from the window: what the user sees is what the point must get.
  const json& rect = selected["editor"]["palette_pixels"];
  const double x0 = rect[0].get<double>(), x1 = rect[2].get<double>();
  const double y1 = rect[3].get<double>();
  const auto swatch = Pixel(json::array({ x0 + 2.0 + 7.0 * 12.0 + 5.5, y1 - 2.0 - 5.5 })); // column 7, row 0
  ASSERT_LT(swatch[0], x1);
  const std::array<double, 3> shown = ColorAt(session, swatch);
  const int undo = selected["editor"]["undo_depth"].get<int>();
  session.Move(swatch[0], swatch[1]);
  session.Press(1);
  session.Release(1);
  const json picked = session.WaitFor(
    [&](const json& s)
    {
      return s["transfer_function"]["color"][1] != state["transfer_function"]["color"][1] &&
        !s["editor"]["tooltips_visible"].get<bool>();
    },
    "the swatch to color the point");
  EXPECT_LT(ColorDistance(PointColor(picked, 1), shown), 1.5)
    << "the point did not get the swatch's color " << shown[0] << " " << shown[1] << " " << shown[2]
    << ": " << picked["transfer_function"]["color"][1].dump();
  EXPECT_GT(ColorDistance(shown, PointColor(state, 1)), 50.0) << "the swatch was the point's color";
  EXPECT_EQ(picked["transfer_function"]["color"][1][0], 0.5) << "the density moved";
  EXPECT_EQ(picked["transfer_function"]["opacity"], state["transfer_function"]["opacity"])
    << "the click reached the opacity chart under the palette";
  EXPECT_EQ(picked["editor"]["undo_depth"].get<int>(), undo + 1);
  EXPECT_EQ(picked["editor"]["selected_point"].get<int>(), 1) << "the point lost its selection";

  session.Key("z", true);
  const json undone = session.WaitFor([&](const json& s)
    { return s["transfer_function"] == state["transfer_function"]; },
    "Ctrl+z to take the color back");
  EXPECT_EQ(undone["editor"]["undo_depth"].get<int>(), undo);
}

} // namespace
} // namespace live
} // namespace cloudvis
