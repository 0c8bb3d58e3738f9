// A field that fits in the host's memory but not in the GPU's (issue 34, part 4) is drawn, not
// refused: `render` (and `compare`, for all its panels) averages it over 2 x 2 x 2 voxels (and again) until the mapper's textures fit
// render.gpu_memory, says so on its output and in the PNG's metadata, and draws the same cloud.
// What no coarsening fits is refused with the mapper's reason. The field is a ball written as a
// .vti, as users bring theirs. Part of cloudvis-field-format-tests.
#include "FieldTestFiles.h"

#include "SupportFixtures.h"
#include "SupportImages.h"
#include "SupportRun.h"

#include <gtest/gtest.h>

namespace
{

using namespace cloudvis::support;
using namespace cloudvis::test;

TEST(Coarsening, AFieldBeyondTheGpuMemoryIsDrawnCoarserAndSaysSo)
{
  TemporaryDirectory dir;
  // 27 MiB of floats: a ball of 67 voxels' radius in 192^3.
  const std::string field = dir.File("ball.vti");
  WriteImageData(LinearBall(192, 67.0), field);
  const std::vector<std::string> common = { "render",
    field,
    "--size",
    "160x120",
    "--set",
    "render.accumulate=1",
    "--set",
    "render.jitter=false" };
  auto full = common, coarse = common;
  full.insert(full.end(), { "-o", dir.File("full.png") });
  coarse.insert(coarse.end(), { "-o", dir.File("coarse.png"), "--set", "render.gpu_memory=16" });
  const auto asItIs = RunCloudvis(full);
  ASSERT_EQ(asItIs.Status, 0) << asItIs.Err;
  EXPECT_EQ(asItIs.Out.find("coarsened"), std::string::npos) << asItIs.Out;
  const auto fitted = RunCloudvis(coarse);
  ASSERT_EQ(fitted.Status, 0) << fitted.Err;
  const std::string said =
    "the field was coarsened 2x (96 x 96 x 96 voxels drawn for 192 x 192 x 192) to fit the "
    "GPU's memory: the density texture (192 x 192 x 192 voxels of R32F) needs 27 MiB";
  EXPECT_NE(fitted.Out.find(said), std::string::npos) << fitted.Out;
  const Image a = ReadPng(dir.File("full.png")), b = ReadPng(dir.File("coarse.png"));
  EXPECT_EQ(b.Text.count("cloudvis.coarsened"), 1u);
  EXPECT_EQ(b.Text.at("cloudvis.coarsened").rfind(said, 0), 0u);
  EXPECT_EQ(a.Text.count("cloudvis.coarsened"), 0u);
  // The same ball, in the same place: only the voxels' size differs.
  EXPECT_GT(CountCloud(b).Cloud, 1000u);
  EXPECT_LT(RmsDifference(a, b), 1.0) << "0.1 levels observed";

  // compare's panels draw one field: coarsened for all of them alike.
  const auto compared = RunCloudvis({ "compare",
    field,
    "--lighting",
    "none,derivative",
    "--size",
    "160x120",
    "-o",
    dir.File("compare.png"),
    "--set",
    "render.gpu_memory=16" });
  ASSERT_EQ(compared.Status, 0) << compared.Err;
  EXPECT_NE(compared.Out.find(said), std::string::npos) << compared.Out;
  EXPECT_EQ(ReadPng(dir.File("compare.png")).Text.count("cloudvis.coarsened"), 1u);

  // A picture whose targets alone exceed the memory: no coarsening helps, and it is refused.
  const std::vector<std::string> huge = { "render",
    field,
    "-o",
    dir.File("huge.png"),
    "--size",
    "4096x4096",
    "--set",
    "render.gpu_memory=16" };
  const auto refused = RunCloudvis(huge);
  EXPECT_EQ(refused.Status, 1);
  EXPECT_NE(refused.Err.find("more than its GPU memory limit of 16 MiB"), std::string::npos)
    << refused.Err;
  EXPECT_NE(refused.Err.find("(even with the field coarsened 16x)"),
    std::string::npos)
    << refused.Err;
  EXPECT_EQ(dir.Files(),
    (std::vector<std::string>{ "ball.vti", "coarse.png", "compare.png", "full.png" }));
}

} // namespace
