// Live tests of the scene `cloudvis view` saves (w): it brings back the layout, the slices,
// their window/level and colors and the legends, not only the cloud and the camera. Window
// 480 x 400: the views are 480 x 300 above the editor's 480 x 100.
#include "LiveSession.h"

#include <gtest/gtest.h>

#include <fstream>

namespace cloudvis
{
namespace live
{
namespace
{
using json = nlohmann::json;

const std::string Cloudvis = support::CloudvisBinary();

// The slices' part of a state that a saved scene must bring back, with the layout and legends.
void ExpectSameView(const json& expected, const json& restored)
{
  EXPECT_EQ(restored["four_views"], expected["four_views"]);
  EXPECT_EQ(restored["legend_visible"], expected["legend_visible"]);
  const json& e = expected["slices"];
  const json& r = restored["slices"];
  EXPECT_EQ(r["visible"], e["visible"]);
  EXPECT_EQ(r["index"], e["index"]);
  EXPECT_EQ(r["colors"], e["colors"]);
  EXPECT_EQ(r["oblique_visible"], e["oblique_visible"]);
  for (size_t i = 0; i < 2; ++i)
  {
    EXPECT_NEAR(r["window_level"][i].get<double>(), e["window_level"][i].get<double>(), 1e-9);
  }
  for (size_t i = 0; i < 3; ++i)
  {
    EXPECT_NEAR(r["oblique_origin"][i].get<double>(), e["oblique_origin"][i].get<double>(), 1e-9);
    EXPECT_NEAR(r["oblique_normal"][i].get<double>(), e["oblique_normal"][i].get<double>(), 1e-9);
  }
}

// Layout, slices, their position, window/level, colors and legends changed with the keyboard and
// the mouse, then w: the saved scene opened in a new viewer shows the same (the oblique plane
// too, placed by the first scene's view section), and --layout overrides the saved layout
// alone.
TEST(LiveScene, SavedSceneRestoresLayoutSlicesWindowLevelAndColors)
{
  LiveSession first(Cloudvis,
    { "--set",
      "field.dimensions=48",
      "--set",
      "render.accumulate=4",
      "--set",
      R"(view.oblique={"origin": [0.3, -0.2, 0.1], "normal": [0, 1, 1]})",
      "--size",
      "480x400" });
  const json opened = first.WaitUntilConverged();
  EXPECT_NEAR(opened["slices"]["oblique_origin"][0].get<double>(), 0.3, 1e-9)
    << "the scene's view.oblique was not applied";
  first.Keys({ "4", "x", "z", "o", "c", "c", "b" });
  first.WaitFor(
    [](const json& s)
    {
      return s["four_views"].get<bool>() && s["slices"]["visible"][0].get<bool>() &&
        s["slices"]["visible"][2].get<bool>() && s["slices"]["oblique_visible"].get<bool>() &&
        s["slices"]["colors"] == "viridis" && !s["legend_visible"].get<bool>() &&
        s["viewports"].contains("axial");
    },
    "the keys");
  // Two wheel notches step the axial slice; a right drag sets the window/level.
  const auto axial = first.Center("axial");
  const json before = first.State();
  first.Wheel(axial[0], axial[1], true);
  first.Wheel(axial[0], axial[1], true);
  first.Drag(3, { { axial[0] - 20, axial[1] + 10 } }, { { axial[0] + 30, axial[1] - 15 } });
  const json changed = first.WaitFor(
    [&](const json& s)
    {
      return s["slices"]["index"][2].get<int>() == before["slices"]["index"][2].get<int>() + 2 &&
        s["slices"]["window_level"] != before["slices"]["window_level"];
    },
    "the wheel and the right drag");
  first.Key("w");
  const json saved = first.WaitFor(
    [](const json& s) { return s["saved_files"].size() == 1; }, "w to save the scene");
  const std::string scene = saved["saved_files"][0].get<std::string>();
  json document;
  std::ifstream(scene) >> document;
  ASSERT_TRUE(document.contains("view")) << document.dump(2);
  EXPECT_EQ(document["view"]["slice_colors"], "viridis");
  EXPECT_EQ(document["view"]["layout"], "four");

  LiveSession second(Cloudvis, { scene, "--size", "480x400" });
  const json restored = second.WaitUntilConverged();
  ExpectSameView(saved, restored);
  EXPECT_EQ(restored["slices"]["index"][2].get<int>(), changed["slices"]["index"][2].get<int>());
  // What the scene held before the view section comes back too, and a scene opened as it was
  // saved has nothing unsaved.
  EXPECT_EQ(restored["transfer_function"], saved["transfer_function"]);
  for (size_t c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(restored["camera"]["position"][c].get<double>(),
      saved["camera"]["position"][c].get<double>(),
      1e-9);
  }
  EXPECT_FALSE(restored["unsaved_changes"].get<bool>());

  LiveSession third(Cloudvis, { scene, "--size", "480x400", "--layout", "3d" });
  const json overridden = third.WaitUntilConverged();
  EXPECT_FALSE(overridden["four_views"].get<bool>()) << "--layout did not override the scene";
  EXPECT_EQ(overridden["slices"]["visible"], saved["slices"]["visible"]);
  EXPECT_EQ(overridden["slices"]["colors"], "viridis");
}

} // namespace
} // namespace live
} // namespace cloudvis
