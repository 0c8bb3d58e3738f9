// A first render that shows the cloud (issue 34): a field file given alone has the default
// transfer function fitted to its values, a scene without one has it fitted when the default
// would show none of them, and a picture that would not show a field that is there is refused
// with what to set, while an empty field is rendered and said to be empty. The file is laid out
// as DALES writes a field dump (ql in kg/kg on time, zt, yt, xt, coordinates in metres). Given
// alone, its mixing ratios become liquid water contents with the standard atmosphere (up to
// 1.1 g/m^3); read as stored (field.quantity "density"), they are below 1.2e-3, where the
// default function, made for densities 0 .. 1, is transparent. Part of
// cloudvis-field-format-tests.
#include "FieldTestFiles.h" // Ncgen, CountCloud
#include "SupportImages.h"
#include "SupportRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace
{

using namespace cloudvis::support;
using cloudvis::test::CountCloud;
using cloudvis::test::Ncgen;
using json = nlohmann::json;

// A DALES field dump of 24 x 24 columns of 50 m and 16 levels of 25 m, one time step: two
// cumulus blobs of liquid water up to `peak` kg/kg above 200 m, `peak` 0 for a cloudless dump.
std::string DalesDump(const TemporaryDirectory& dir, const std::string& name, double peak)
{
  const int nx = 24, nz = 16;
  std::ostringstream cdl, ql, xs, zs;
  cdl << "netcdf fielddump {\ndimensions: time = UNLIMITED ; zt = " << nz << " ; yt = " << nx
      << " ; xt = " << nx << " ;\nvariables:\n"
      << "  double time(time) ; time:units = \"s\" ;\n"
      << "  float zt(zt) ; zt:units = \"m\" ; zt:long_name = \"Vertical position of cell centers\" "
         ";\n"
      << "  float yt(yt) ; yt:units = \"m\" ;\n  float xt(xt) ; xt:units = \"m\" ;\n"
      << "  float ql(time, zt, yt, xt) ; ql:units = \"kg/kg\" ;\n"
      << "    ql:long_name = \"Liquid water specific humidity\" ;\ndata:\n  time = 3600 ;\n";
  const double blobs[2][3] = { { 400.0, 500.0, 220.0 }, { 850.0, 700.0, 160.0 } };
  for (int k = 0; k < nz; ++k)
  {
    zs << (k ? ", " : "") << 25.0 * (k + 0.5);
    for (int j = 0; j < nx; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        const double x = 50.0 * (i + 0.5), y = 50.0 * (j + 0.5), h = 25.0 * (k + 0.5) - 200.0;
        double q = 0.0;
        for (const auto& b : blobs)
        {
          const double f = 1.0 - std::hypot(x - b[0], y - b[1], h - b[2] / 2) / b[2];
          q = std::max(q, h > 0.0 ? peak * f : 0.0);
        }
        ql << (k + j + i ? ", " : "") << q;
      }
    }
  }
  for (int i = 0; i < nx; ++i)
  {
    xs << (i ? ", " : "") << 50.0 * (i + 0.5);
  }
  cdl << "  zt = " << zs.str() << " ;\n  yt = " << xs.str() << " ;\n  xt = " << xs.str()
      << " ;\n  ql = " << ql.str() << " ;\n}\n";
  return Ncgen(dir, name, cdl.str(), 3);
}

TEST(FirstRender, AnLesFileGivenAloneShowsItsCloud)
{
  TemporaryDirectory dir;
  const std::string file = DalesDump(dir, "fielddump.001.nc", 1.1e-3);
  const CommandResult run =
    RunCloudvis({ "render", file, "-o", dir.File("les.png"), "--size", "160x120" });
  ASSERT_EQ(run.Status, 0) << run.Err;
  EXPECT_NE(run.Out.find("transfer function: the default fitted to the field's values [0, 1.097]"),
    std::string::npos)
    << run.Out;
  const Image image = ReadPng(dir.File("les.png"));
  ASSERT_EQ(image.Width, 160);
  const cloudvis::test::CloudPixels cloud = CountCloud(image);
  EXPECT_GT(cloud.Cloud, 400u) << "the two clouds cover a good part of the picture";
  EXPECT_EQ(cloud.Clipped, 0u);
  // The picture's scene is the fitted one: its opacity points end at the field's maximum, and
  // the default's unit distance (0.1 for the default field's 4-unit box) grows with the box:
  // 1150 x 1150 x 375 m between the first and last voxels' centres.
  const json scene = json::parse(image.Text.at("cloudvis.scene"));
  EXPECT_NEAR(scene["transfer_function"]["opacity"].back()[0].get<double>(), 1.097, 1e-3);
  EXPECT_NEAR(scene["transfer_function"]["unit_distance"].get<double>(),
    0.1 * std::sqrt(2 * 1150.0 * 1150.0 + 375.0 * 375.0) / std::sqrt(48.0),
    1e-6);
}

TEST(FirstRender, ASceneWithoutATransferFunctionIsFittedWhereTheDefaultShowsNothing)
{
  TemporaryDirectory dir;
  const std::string file = DalesDump(dir, "fielddump.001.nc", 1.1e-3);
  // Its mixing ratios read as stored, not as the liquid water content they make with the air.
  const std::string scene = dir.Write(
    "les.json", json({ { "field", { { "file", file }, { "quantity", "density" } } } }).dump());
  const CommandResult run =
    RunCloudvis({ "render", scene, "-o", dir.File("les.png"), "--size", "160x120" });
  ASSERT_EQ(run.Status, 0) << run.Err;
  EXPECT_NE(run.Out.find("(the default's opacity is 0 over all of them)"), std::string::npos)
    << run.Out;
  EXPECT_GT(CountCloud(ReadPng(dir.File("les.png"))).Cloud, 400u);
}

TEST(FirstRender, APictureThatWouldNotShowTheFieldIsRefusedWithWhatToSet)
{
  TemporaryDirectory dir;
  const std::string file = DalesDump(dir, "fielddump.001.nc", 1.1e-3);
  // The scene's own function, over [0, 1]: kept, and transparent below 0.02.
  const json own = { { "field", { { "file", file }, { "quantity", "density" } } },
    { "transfer_function", { { "opacity", { { 0.0, 0.0 }, { 0.02, 0.0 }, { 1.0, 0.8 } } } } } };
  const std::string scene = dir.Write("own.json", own.dump());
  for (const char* command : { "render", "compare" })
  {
    SCOPED_TRACE(command);
    const CommandResult run =
      RunCloudvis({ command, scene, "-o", dir.File("out.png"), "--size", "160x120" });
    EXPECT_EQ(run.Status, 1);
    EXPECT_NE(run.Err.find("own.json: no pixel shows the field: the scene's transfer function "
                           "gives its values [0, 0.0009228"),
      std::string::npos)
      << run.Err;
    EXPECT_NE(run.Err.find("no opacity (its opacity is 0 up to density 0.02), so the picture "
                           "would be blank: move transfer_function.opacity's points into [0, "),
      std::string::npos)
      << run.Err;
    EXPECT_EQ(dir.Files(),
      (std::vector<std::string>{ "fielddump.001.nc", "fielddump.001.nc.cdl", "own.json" }));
  }
  const CommandResult cpu = RunCloudvis(
    { "render", scene, "-o", dir.File("out.png"), "--size", "40x30", "--cpu-reference" });
  EXPECT_EQ(cpu.Status, 1);
  EXPECT_NE(cpu.Err.find("no pixel shows the field"), std::string::npos) << cpu.Err;

  // A camera that looks away from a visible field, and one that looks past it.
  const CommandResult away = RunCloudvis({ "render",
    file,
    "-o",
    dir.File("out.png"),
    "--size",
    "160x120",
    "--set",
    "field.quantity=density",
    "--set",
    "camera.position=600,600,5000",
    "--set",
    "camera.focal_point=600,600,15000" });
  EXPECT_EQ(away.Status, 1);
  EXPECT_NE(away.Err.find("no pixel shows the field: it lies wholly outside the camera's view "
                          "(camera.position 600, 600, 5000 looking at camera.focal_point 600, "
                          "600, 15000)"),
    std::string::npos)
    << away.Err;
  const CommandResult past = RunCloudvis({ "render",
    file,
    "-o",
    dir.File("out.png"),
    "--size",
    "160x120",
    "--set",
    "field.quantity=density",
    "--set",
    "camera.position=600,-3000,1500",
    "--set",
    "camera.focal_point=600,0,1600" });
  EXPECT_EQ(past.Status, 1);
  EXPECT_NE(past.Err.find("no pixel shows the field (its values [0, 0.0009228"), std::string::npos)
    << past.Err;
  EXPECT_NE(past.Err.find("the camera may not look at it (camera.position, camera.focal_point)"),
    std::string::npos)
    << past.Err;
  EXPECT_EQ(dir.Files(),
    (std::vector<std::string>{ "fielddump.001.nc", "fielddump.001.nc.cdl", "own.json" }));
}

// A z-up domain is seen from the side, z up, with the sun above, not from straight above with
// the sun at its side: the default camera and lights turn with the file's up axis, and a scene's
// own camera is kept.
TEST(FirstRender, AZUpFileIsSeenFromTheSideWithTheSunAbove)
{
  TemporaryDirectory dir;
  const std::string file = DalesDump(dir, "fielddump.001.nc", 1.1e-3);
  const CommandResult run = RunCloudvis(
    { "render", file, "-o", dir.File("les.png"), "--size", "160x120", "--lighting", "march" });
  ASSERT_EQ(run.Status, 0) << run.Err;
  const Image image = ReadPng(dir.File("les.png"));
  const json scene = json::parse(image.Text.at("cloudvis.scene"));
  EXPECT_EQ(scene["camera"]["view_up"], json({ 0.0, 0.0, 1.0 }));
  const json& position = scene["camera"]["position"];
  const json& focal = scene["camera"]["focal_point"];
  EXPECT_LT(position[1].get<double>(), focal[1].get<double>() - 1000.0) << scene["camera"];
  EXPECT_NEAR(position[2].get<double>(), focal[2].get<double>(), 1e-6) << scene["camera"];
  EXPECT_EQ(scene["lights"][0]["position"], json({ 6.0, -4.0, 8.0 }));
  // Lit from above: the cloud's upper half is brighter than its lower half.
  double upper = 0.0, lower = 0.0;
  for (int y = 0; y < image.Height; ++y)
  {
    for (int x = 0; x < image.Width; ++x)
    {
      (y >= image.Height / 2 ? upper : lower) += image.Radiance(x, y) - image.Radiance(0, 0);
    }
  }
  EXPECT_GT(upper, 1.2 * lower) << "rows count from the bottom";

  const CommandResult own = RunCloudvis({ "render",
    file,
    "-o",
    dir.File("own.png"),
    "--size",
    "40x30",
    "--set",
    "camera.position=600,600,5000" });
  ASSERT_EQ(own.Status, 0) << own.Err;
  const json ownScene = json::parse(ReadPng(dir.File("own.png")).Text.at("cloudvis.scene"));
  EXPECT_EQ(ownScene["camera"]["view_up"], json({ 0.0, 1.0, 0.0 }));
}

TEST(FirstRender, AnEmptyFieldIsRenderedAndSaidToBeEmpty)
{
  TemporaryDirectory dir;
  const std::string file = DalesDump(dir, "clear.nc", 0.0);
  const CommandResult run =
    RunCloudvis({ "render", file, "-o", dir.File("clear.png"), "--size", "40x30" });
  ASSERT_EQ(run.Status, 0) << run.Err;
  EXPECT_NE(
    run.Out.find("the field is empty (no value above 0): the picture shows the background alone"),
    std::string::npos)
    << run.Out;
  EXPECT_EQ(CountCloud(ReadPng(dir.File("clear.png"))).Cloud, 0u);
}

} // namespace
