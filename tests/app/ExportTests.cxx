// Tests of export (docs/export.md): the cloudvis binary writes the files, which are read back with
// independent readers (OpenEXR's Imf::InputFile, vtkPNGReader; tests/support) and compared with
// the float render the mapper produced in this process for the same scene, so a test fails when a
// channel is missing, flipped, converted or rounded wrongly, when metadata is absent or does not
// reproduce the image, when an animation frame is not the still it claims to be, or when a
// refused command leaves a file behind. The scenes are small (<= 64^3 voxels, <= 160 x 120
// pixels, few frames) apart from one large-size render. Needs an X display (Xvfb under ctest).
#include "Animate.h"
#include "Compare.h"
#include "Errors.h"
#include "ExportRender.h"
#include "ImageWriters.h"
#include "NoiseTarget.h"
#include "OffscreenRender.h"
#include "Progress.h"
#include "Scene.h"
#include "SceneField.h"
#include "SceneJson.h"
#include "SupportImages.h"
#include "SupportRun.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace
{
using json = nlohmann::json;

using cloudvis::support::Exr;
using cloudvis::support::ReadExr;
using cloudvis::support::ReadPng;
using cloudvis::support::TemporaryDirectory;
using cloudvis::support::With;
using CliRun = cloudvis::support::CommandResult;
using Png = cloudvis::support::Image;

// The cloudvis binary of this build (tests/support).
CliRun Cloudvis(const std::vector<std::string>& arguments)
{
  return cloudvis::support::RunCloudvis(arguments);
}

// The small test scene: the fbm sphere at 32^3, 64 x 48 pixels, 2 accumulated frames.
const std::vector<std::string> Small = { "--set", "field.dimensions=32", "--set",
  "render.accumulate=2", "--size", "64x48" };
// `cloudvis render` of the small scene into `output`, with more options; fails the test when
// cloudvis does (call it inside ASSERT_NO_FATAL_FAILURE).
void RenderSmall(const std::string& output, const std::vector<std::string>& options = {})
{
  const CliRun run = Cloudvis(
    With(With(With({ "render", CLOUDVIS_SCENES "/fbm-sphere.json" }, options), { "-o", output }),
      Small));
  ASSERT_EQ(run.Status, 0) << run.Err;
}
cloudvis::Scene SmallScene()
{
  return cloudvis::LoadScene(CLOUDVIS_SCENES "/fbm-sphere.json",
    { "field.dimensions=32", "render.accumulate=2", "render.size=64,48" });
}

cloudvis::OffscreenRenderResult RenderFloat(const cloudvis::Scene& scene)
{
  cloudvis::RenderOptions options;
  options.FloatImage = true;
  return cloudvis::RenderOffscreen(scene, cloudvis::ProduceField(scene), "test", 0, options);
}

// ---- EXR ----------------------------------------------------------------------------------

TEST(Exr, ChannelsHoldTheFloatRender)
{
  TemporaryDirectory dir;
  const CliRun run = Cloudvis(With({ "render", CLOUDVIS_SCENES "/fbm-sphere.json", "-o",
    dir.File("r.exr") }, Small));
  ASSERT_EQ(run.Status, 0) << run.Err;
  EXPECT_EQ(run.Err, "") << "no progress bar when stderr is not a terminal";
  const Exr exr = ReadExr(dir.File("r.exr"));
  ASSERT_EQ(exr.Width, 64);
  ASSERT_EQ(exr.Height, 48);
  std::vector<std::string> names;
  for (const auto& channel : exr.Types)
  {
    names.push_back(channel.first);
    EXPECT_EQ(channel.second, Imf::FLOAT) << channel.first;
  }
  EXPECT_EQ(names,
    (std::vector<std::string>{ "A", "B", "G", "R", "Z", "samples", "transmittance" }));

  const cloudvis::Scene scene = SmallScene();
  const cloudvis::OffscreenRenderResult reference = RenderFloat(scene);
  const cloudvis::RenderedImage& image = reference.Image;
  // The cloud lies within the field's bounding sphere (radius 2 sqrt(3)) around the focal point.
  const double bounds[6] = { -2, 2, -2, 2, -2, 2 };
  const cloudvis::ResolvedCamera camera = cloudvis::ResolveCamera(scene, bounds);
  const double distance = std::sqrt(std::pow(camera.Position[0] - camera.FocalPoint[0], 2) +
    std::pow(camera.Position[1] - camera.FocalPoint[1], 2) +
    std::pow(camera.Position[2] - camera.FocalPoint[2], 2));
  const char* const rgba[] = { "R", "G", "B", "A" };
  int inside = 0, outside = 0;
  float brightest = 0.0f;
  for (int y = 0; y < 48; ++y)
  {
    for (int x = 0; x < 64; ++x)
    {
      const size_t p = size_t(y) * 64 + size_t(x);
      for (int c = 0; c < 4; ++c)
      {
        ASSERT_EQ(exr.At(rgba[c], x, y), image.Radiance[4 * p + c]) << rgba[c] << " " << x << "," << y;
      }
      const float a = exr.At("A", x, y);
      EXPECT_EQ(exr.At("transmittance", x, y), 1.0f - a);
      EXPECT_EQ(exr.At("samples", x, y), image.Auxiliary[4 * p]);
      brightest = std::max(brightest, exr.At("R", x, y));
      const float z = exr.At("Z", x, y);
      if (a == 0.0f)
      {
        EXPECT_TRUE(std::isinf(z) && z > 0) << x << "," << y << ": Z " << z;
        ++outside;
      }
      else if (a > 0.5f)
      {
        // A ray through a dense pixel passes 2% opacity before the focal point (the centre).
        EXPECT_TRUE(std::isfinite(z)) << x << "," << y;
        EXPECT_GT(z, distance - 2.0 * std::sqrt(3.0));
        EXPECT_LT(z, distance);
        ++inside;
      }
    }
  }
  EXPECT_GT(inside, 20);
  EXPECT_GT(outside, 100);
  // Lit by an orange sun plus a strong ambient, the cloud is brighter than 1 in places: the EXR
  // keeps what the 8-bit window clamps.
  EXPECT_GT(brightest, 1.0f);
}

TEST(Exr, PathTracedRenderAddsTheVarianceOfEachChannel)
{
  // render --lighting pathtrace: the variance layer holds the mapper's variance of each pixel's
  // means (the same paths: same seed and split), non-negative and non-zero where the cloud is.
  TemporaryDirectory dir;
  ASSERT_NO_FATAL_FAILURE(
    RenderSmall(dir.File("p.exr"), { "--lighting", "pathtrace", "--spp", "4" }));
  const Exr exr = ReadExr(dir.File("p.exr"));
  std::vector<std::string> names;
  for (const auto& channel : exr.Types)
  {
    names.push_back(channel.first);
  }
  EXPECT_EQ(names,
    (std::vector<std::string>{ "A", "B", "G", "R", "Z", "samples", "transmittance", "variance.A",
      "variance.B", "variance.G", "variance.R" }));

  cloudvis::Scene scene = SmallScene();
  scene.Render.Lighting.Model = cloudvis::LightingModel::PathTrace;
  scene.Render.SamplesPerPixel = 4;
  const cloudvis::RenderedImage image = RenderFloat(scene).Image;
  ASSERT_EQ(image.Variance.size(), image.Radiance.size());
  const char* const variance[] = { "variance.R", "variance.G", "variance.B", "variance.A" };
  int noisy = 0;
  for (int y = 0; y < 48; ++y)
  {
    for (int x = 0; x < 64; ++x)
    {
      const size_t p = size_t(y) * 64 + size_t(x);
      for (int c = 0; c < 4; ++c)
      {
        ASSERT_EQ(exr.At(variance[c], x, y), image.Variance[4 * p + c]) << x << "," << y;
        ASSERT_GE(image.Variance[4 * p + c], 0.0f);
      }
      noisy += exr.At("A", x, y) > 0.0f && exr.At("variance.R", x, y) > 0.0f;
    }
  }
  EXPECT_GT(noisy, 20);
}

TEST(Exr, HalfChannelsRoundTheFloatRender)
{
  TemporaryDirectory dir;
  ASSERT_NO_FATAL_FAILURE(RenderSmall(dir.File("h.exr"), { "--exr-half" }));
  const Exr exr = ReadExr(dir.File("h.exr"));
  for (const auto& channel : exr.Types)
  {
    EXPECT_EQ(channel.second, Imf::HALF) << channel.first;
  }
  const cloudvis::RenderedImage image = RenderFloat(SmallScene()).Image;
  for (int y = 0; y < 48; ++y)
  {
    for (int x = 0; x < 64; ++x)
    {
      const float r = image.Radiance[4 * (size_t(y) * 64 + size_t(x))];
      EXPECT_NEAR(exr.At("R", x, y), r, 1e-3 * std::fabs(r) + 1e-7);
    }
  }
  // The scene key says the same.
  const CliRun key = Cloudvis(With({ "render", CLOUDVIS_SCENES "/fbm-sphere.json", "--set",
    "render.exr_type=half", "-o", dir.File("k.exr") }, Small));
  ASSERT_EQ(key.Status, 0) << key.Err;
  EXPECT_EQ(ReadExr(dir.File("k.exr")).Types.at("R"), Imf::HALF);
}

TEST(Exr, HeaderCarriesTheSceneThatRendersTheSameImage)
{
  TemporaryDirectory dir;
  ASSERT_NO_FATAL_FAILURE(RenderSmall(dir.File("r.exr"), { "--set", "field.octaves=3" }));
  const Exr exr = ReadExr(dir.File("r.exr"));
  EXPECT_EQ(exr.Strings.at("cloudvis.version"), cloudvis::CloudvisVersion());
  EXPECT_NE(exr.Strings.at("cloudvis.command").find("cloudvis render "), std::string::npos);
  EXPECT_NE(exr.Strings.at("cloudvis.command").find("field.octaves=3"), std::string::npos);
  const json scene = json::parse(exr.Strings.at("cloudvis.scene"));
  EXPECT_EQ(scene["field"]["octaves"], 3);
  EXPECT_EQ(scene["render"]["size"], json::array({ 64, 48 }));
  EXPECT_TRUE(scene["camera"].contains("position")) << "the camera is resolved";
  EXPECT_TRUE(scene["render"].contains("step")) << "defaults are written";

  std::ofstream(dir.File("embedded.json")) << scene.dump(2);
  const CliRun again = Cloudvis({ "render", dir.File("embedded.json"), "-o", dir.File("again.exr") });
  ASSERT_EQ(again.Status, 0) << again.Err;
  const Exr second = ReadExr(dir.File("again.exr"));
  EXPECT_EQ(second.Channels.at("R"), exr.Channels.at("R"));
  EXPECT_EQ(second.Channels.at("A"), exr.Channels.at("A"));
  EXPECT_EQ(second.Channels.at("Z"), exr.Channels.at("Z"));
}

// ---- PNG ----------------------------------------------------------------------------------

TEST(Png, TextChunksNameTheSoftwareSceneAndCommand)
{
  TemporaryDirectory dir;
  const CliRun run =
    Cloudvis(With({ "render", CLOUDVIS_SCENES "/fbm-sphere.json", "-o", dir.File("r.png") }, Small));
  ASSERT_EQ(run.Status, 0) << run.Err;
  const Png png = ReadPng(dir.File("r.png"));
  EXPECT_EQ(png.Text.at("Software"), "cloudvis " + cloudvis::CloudvisVersion());
  EXPECT_EQ(png.Text.at("cloudvis.command").rfind("cloudvis render ", 0), 0u)
    << png.Text.at("cloudvis.command");
  const json scene = json::parse(png.Text.at("cloudvis.scene"));
  EXPECT_EQ(scene["field"]["dimensions"], json::array({ 32, 32, 32 }));
  EXPECT_EQ(scene["render"]["accumulate"], 2);
}

// Class "paths that are not UTF-8" (docs/reliability.md): nlohmann::json refused to dump such
// a path (type_error 316), so `info --json` and every export failed. Now the metadata holds the
// text escaped as \xNN, and stays valid JSON.
TEST(Metadata, TextThatIsNotUtf8IsEscapedInPngAndExr)
{
  TemporaryDirectory dir;
  const std::string field = dir.File("bad\xff\xfe.vti");
  const std::string escaped = dir.Path + "/bad\\xff\\xfe.vti";
  ASSERT_EQ(Cloudvis({ "generate", "--set", "field.dimensions=16", "-o", field }).Status, 0);
  const CliRun info = Cloudvis({ "info", field, "--json" });
  ASSERT_EQ(info.Status, 0) << info.Err;
  EXPECT_EQ(json::parse(info.Out)["field"], escaped);
  for (const std::string extension : { ".png", ".exr" })
  {
    SCOPED_TRACE(extension);
    const std::string image = dir.File("r" + extension);
    const CliRun run = Cloudvis({ "render",
      field,
      "-o",
      image,
      "--size",
      "32x24",
      "--set",
      "render.accumulate=1",
      "--set",
      "description=caf\xe9" }); // é in Latin-1
    ASSERT_EQ(run.Status, 0) << run.Err;
    const std::map<std::string, std::string> text =
      extension == ".png" ? ReadPng(image).Text : ReadExr(image).Strings;
    const json scene = json::parse(text.at("cloudvis.scene"));
    EXPECT_EQ(scene["field"]["file"], escaped);
    EXPECT_EQ(scene["description"], "caf\\xe9");
    EXPECT_NE(text.at("cloudvis.command").find("bad\\xff\\xfe.vti"), std::string::npos)
      << text.at("cloudvis.command");
  }
}

TEST(Png, SixteenBitIsTheSamePictureAsEightBit)
{
  TemporaryDirectory dir;
  ASSERT_EQ(Cloudvis(With({ "render", CLOUDVIS_SCENES "/fbm-sphere.json", "-o",
    dir.File("8.png") }, Small)).Status, 0);
  ASSERT_NO_FATAL_FAILURE(RenderSmall(dir.File("16.png"), { "--png-bits", "16" }));
  const Png eight = ReadPng(dir.File("8.png"));
  const Png sixteen = ReadPng(dir.File("16.png"));
  EXPECT_EQ(eight.Bits, 8);
  EXPECT_EQ(sixteen.Bits, 16) << "a 16-bit PNG";
  ASSERT_EQ(sixteen.Components, 3);
  ASSERT_EQ(sixteen.Values.size(), eight.Values.size());
  double worst = 0.0;
  bool finer = false;
  for (size_t i = 0; i < eight.Values.size(); ++i)
  {
    worst = std::max(worst, std::fabs(eight.Values[i] - sixteen.Values[i]));
    finer = finer || std::fabs(sixteen.Values[i] * 255.0 - std::round(sixteen.Values[i] * 255.0)) > 0.01;
  }
  // The window rounds the blend of the cloud over the background once; the 16-bit image is that
  // blend before rounding.
  EXPECT_LE(worst, 1.0 / 255.0 + 1e-9);
  EXPECT_TRUE(finer) << "some values fall between 8-bit steps";
}

TEST(Png, TransparentAlphaIsTheCloudsOpacity)
{
  TemporaryDirectory dir;
  ASSERT_NO_FATAL_FAILURE(RenderSmall(dir.File("t.png"), { "--transparent" }));
  const Png png = ReadPng(dir.File("t.png"));
  ASSERT_EQ(png.Components, 4);
  EXPECT_EQ(png.Bits, 8);
  for (const auto& corner : { std::make_pair(0, 0), std::make_pair(63, 47) })
  {
    EXPECT_EQ(png.At(corner.first, corner.second, 3), 0.0);
  }
  const cloudvis::RenderedImage image = RenderFloat(SmallScene()).Image;
  int thin = 0;
  for (int y = 0; y < 48; ++y)
  {
    for (int x = 0; x < 64; ++x)
    {
      const float* c = image.Radiance.data() + 4 * (size_t(y) * 64 + size_t(x));
      EXPECT_NEAR(png.At(x, y, 3), c[3], 0.5 / 255.0 + 1e-6);
      if (c[3] > 0.02f && c[3] < 0.5f)
      {
        ++thin;
        // Straight color: at thin edges the color is the cloud's, not darkened by its alpha.
        for (int k = 0; k < 3; ++k)
        {
          EXPECT_NEAR(png.At(x, y, k), std::min(1.0, double(c[k]) / c[3]), 0.5 / 255.0 + 1e-6);
        }
      }
    }
  }
  EXPECT_GT(thin, 5) << "the test covers thin edges";

  // Composited over the scene's background, the transparent PNG is the opaque one.
  ASSERT_EQ(Cloudvis(With({ "render", CLOUDVIS_SCENES "/fbm-sphere.json", "-o",
    dir.File("o.png") }, Small)).Status, 0);
  const Png opaque = ReadPng(dir.File("o.png"));
  const std::array<double, 3> background = cloudvis::DefaultScene().Background;
  double worst = 0.0;
  for (int y = 0; y < 48; ++y)
  {
    for (int x = 0; x < 64; ++x)
    {
      for (int k = 0; k < 3; ++k)
      {
        const float* c = image.Radiance.data() + 4 * (size_t(y) * 64 + size_t(x));
        if (c[0] > c[3] || c[1] > c[3] || c[2] > c[3])
        {
          continue; // brighter than its opacity: the straight color is clamped (docs/export.md)
        }
        const double a = png.At(x, y, 3);
        worst = std::max(worst,
          std::fabs(png.At(x, y, k) * a + (1.0 - a) * background[k] - opaque.At(x, y, k)));
      }
    }
  }
  EXPECT_LT(worst, 3.0 / 255.0);
}

// ---- exposure and the display curve (docs/export.md) ---------------------------------------

// The shipped cumulus (the demo's scene: filmic, automatic exposure) small enough for a test.
const std::vector<std::string> SmallCumulus = { "--set", "field.dimensions=96,72,96", "--set",
  "render.accumulate=4", "--size", "200x150" };

// The share of the cloud's pixels (at least half opaque in the EXR) that the PNG clips to white
// in some channel.
double ClippedCloudShare(const Png& png, const Exr& exr)
{
  int cloud = 0, clipped = 0;
  for (int y = 0; y < exr.Height; ++y)
  {
    for (int x = 0; x < exr.Width; ++x)
    {
      if (exr.At("A", x, y) < 0.5f)
      {
        continue;
      }
      ++cloud;
      clipped += png.At(x, y, 0) >= 1.0 || png.At(x, y, 1) >= 1.0 || png.At(x, y, 2) >= 1.0;
    }
  }
  EXPECT_GT(cloud, 1000) << "the cloud fills part of the picture";
  return cloud > 0 ? double(clipped) / double(cloud) : 1.0;
}

TEST(Display, FilmicCurveIsTheSameInTheWindowAndInTheWriters)
{
  // The 8-bit PNG is the window's pixels (the GPU's composite pass applies the curve), the
  // 16-bit one the float render through the C++ of the same shared source.
  TemporaryDirectory dir;
  const std::vector<std::string> filmic = { "--set", "render.display=filmic", "--exposure", "1.5" };
  ASSERT_NO_FATAL_FAILURE(RenderSmall(dir.File("8.png"), filmic));
  ASSERT_NO_FATAL_FAILURE(RenderSmall(dir.File("16.png"), With(filmic, { "--png-bits", "16" })));
  ASSERT_NO_FATAL_FAILURE(RenderSmall(dir.File("linear.png")));
  const Png eight = ReadPng(dir.File("8.png"));
  const Png sixteen = ReadPng(dir.File("16.png"));
  const Png linear = ReadPng(dir.File("linear.png"));
  ASSERT_EQ(eight.Values.size(), sixteen.Values.size());
  ASSERT_EQ(eight.Values.size(), linear.Values.size());
  double worst = 0.0, changed = 0.0;
  for (size_t i = 0; i < eight.Values.size(); ++i)
  {
    worst = std::max(worst, std::fabs(eight.Values[i] - sixteen.Values[i]));
    changed = std::max(changed, std::fabs(eight.Values[i] - linear.Values[i]));
  }
  EXPECT_LE(worst, 1.0 / 255.0 + 1e-9) << "one rounding of the blend apart";
  EXPECT_GT(changed, 20.0 / 255.0) << "the curve and the exposure change the picture";
  EXPECT_NE(eight.Text.at("cloudvis.display").find("filmic, exposure +1.50 EV"), std::string::npos)
    << eight.Text.at("cloudvis.display");
}

TEST(Display, ExposureScalesTheRadianceAndExrStaysLinear)
{
  // Over black, a linear PNG is the EXR's radiance times 2^EV, clamped and rounded.
  TemporaryDirectory dir;
  const std::vector<std::string> options = { "--set", "background=[0,0,0]", "--exposure", "-1" };
  ASSERT_NO_FATAL_FAILURE(RenderSmall(dir.File("r.png"), options));
  ASSERT_NO_FATAL_FAILURE(RenderSmall(dir.File("r.exr"), options));
  ASSERT_NO_FATAL_FAILURE(RenderSmall(dir.File("plain.exr")));
  const Png png = ReadPng(dir.File("r.png"));
  const Exr exr = ReadExr(dir.File("r.exr"));
  const Exr plain = ReadExr(dir.File("plain.exr"));
  EXPECT_FLOAT_EQ(exr.Floats.at("cloudvis.exposure_ev"), -1.0f);
  EXPECT_EQ(exr.Strings.at("cloudvis.display"), "linear");
  double worst = 0.0, brightest = 0.0;
  const char* const rgb[] = { "R", "G", "B" };
  for (int y = 0; y < exr.Height; ++y)
  {
    for (int x = 0; x < exr.Width; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_EQ(exr.At(rgb[c], x, y), plain.At(rgb[c], x, y)) << "EXR is not exposed";
        const double expected = std::round(255.0 * std::min(1.0, 0.5 * exr.At(rgb[c], x, y)));
        worst = std::max(worst, std::fabs(255.0 * png.At(x, y, c) - expected));
        brightest = std::max(brightest, expected);
      }
    }
  }
  EXPECT_LE(worst, 1.0);
  EXPECT_GT(brightest, 100.0) << "the test sees the cloud";
}

TEST(Display, AutoExposureMetersThePercentileOfTheCloudsLuminance)
{
  TemporaryDirectory dir;
  const CliRun run = Cloudvis(
    With({ "render", CLOUDVIS_SCENES "/cumulus.json", "-o", dir.File("c.exr") }, SmallCumulus));
  ASSERT_EQ(run.Status, 0) << run.Err;
  const Exr exr = ReadExr(dir.File("c.exr"));
  size_t cloud = 0;
  const double expected = cloudvis::support::AutoExposureOf(exr, cloud);
  ASSERT_GT(cloud, 1000u);
  EXPECT_NEAR(exr.Floats.at("cloudvis.exposure_ev"), expected, 1e-4);
  EXPECT_EQ(exr.Strings.at("cloudvis.display"), "filmic");
  EXPECT_NE(run.Out.find("filmic, exposure"), std::string::npos) << run.Out;
}

TEST(Display, DemoCumulusKeepsItsHighlights)
{
  // make demo's picture under its real sun: the filmic curve and the automatic exposure keep
  // the sunlit billows off white (docs/export.md measures the full-size demo); the linear
  // display of the same radiance clips a third of the cloud.
  TemporaryDirectory dir;
  for (const char* file : { "c.png", "c.exr" })
  {
    const CliRun run = Cloudvis(
      With({ "render", CLOUDVIS_SCENES "/cumulus.json", "-o", dir.File(file) }, SmallCumulus));
    ASSERT_EQ(run.Status, 0) << run.Err;
  }
  const CliRun run = Cloudvis(With({ "render", CLOUDVIS_SCENES "/cumulus.json", "-o",
    dir.File("linear.png"), "--set", "render.display=linear", "--exposure", "0" }, SmallCumulus));
  ASSERT_EQ(run.Status, 0) << run.Err;
  const Exr exr = ReadExr(dir.File("c.exr"));
  EXPECT_LT(ClippedCloudShare(ReadPng(dir.File("c.png")), exr), 0.01);
  EXPECT_GT(ClippedCloudShare(ReadPng(dir.File("linear.png")), exr), 0.1);
}

// ---- size ---------------------------------------------------------------------------------

TEST(Size, LargeRenderIsCompleteAndMatchesASmallOne)
{
  TemporaryDirectory dir;
  const std::vector<std::string> scene = { "render", CLOUDVIS_SCENES "/fbm-sphere.json", "--set",
    "field.dimensions=32", "--set", "render.accumulate=1" };
  const CliRun large = Cloudvis(With(scene, { "--size", "2500x1800", "-o", dir.File("large.png") }));
  ASSERT_EQ(large.Status, 0) << large.Err;
  const CliRun small = Cloudvis(With(scene, { "--size", "250x180", "-o", dir.File("small.png") }));
  ASSERT_EQ(small.Status, 0) << small.Err;
  const Png big = ReadPng(dir.File("large.png"));
  const Png little = ReadPng(dir.File("small.png"));
  ASSERT_EQ(big.Width, 2500);
  ASSERT_EQ(big.Height, 1800);
  const std::array<double, 3> background = cloudvis::DefaultScene().Background;
  for (const auto& corner : { std::make_pair(0, 0), std::make_pair(2499, 0),
         std::make_pair(0, 1799), std::make_pair(2499, 1799) })
  {
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(big.At(corner.first, corner.second, k), background[k], 1.0 / 255.0);
    }
  }
  EXPECT_GT(big.At(1250, 900, 0), background[0] + 0.3) << "the cloud at the centre";
  // Box-filtered 10 x 10, the large image is the small one up to noise and edges.
  double sum = 0.0;
  for (int y = 0; y < 180; ++y)
  {
    for (int x = 0; x < 250; ++x)
    {
      for (int k = 0; k < 3; ++k)
      {
        double mean = 0.0;
        for (int j = 0; j < 10; ++j)
        {
          for (int i = 0; i < 10; ++i)
          {
            mean += big.At(10 * x + i, 10 * y + j, k);
          }
        }
        sum += std::fabs(mean / 100.0 - little.At(x, y, k));
      }
    }
  }
  EXPECT_LT(sum / (250.0 * 180.0 * 3.0), 0.01);
}

// The message of the InputError CheckRenderSize throws ("" when it throws none).
std::string SizeRefusal(int width, int height, const cloudvis::RenderLimits& limits)
{
  try
  {
    cloudvis::CheckRenderSize({ { width, height } }, limits, "s.json");
  }
  catch (const cloudvis::InputError& e)
  {
    return e.what();
  }
  return "";
}

TEST(Size, BeyondTheGpuLimitIsRefusedWithTheLimit)
{
  cloudvis::RenderLimits limits{ 4096, 2048 };
  EXPECT_EQ(SizeRefusal(4096, 2048, limits), "");
  EXPECT_EQ(SizeRefusal(4097, 100, limits), "s.json: render.size: 4097 x 100 pixels is beyond "
                                            "this GPU's limit of 4096 x 2048 pixels; choose a "
                                            "smaller size");
  // Render targets that would not fit in the memory available are refused with their size.
  const cloudvis::RenderLimits small{ 4096, 2048, 64.0 * 1024 * 1024 };
  EXPECT_EQ(SizeRefusal(800, 600, small), "");
  EXPECT_EQ(SizeRefusal(4000, 2000, small), "s.json: render.size: 4000 x 2000 pixels needs 580 "
                                            "MiB of memory for its render targets but only 64 MiB "
                                            "is available; choose a smaller size");
  // This GPU renders what the scene accepts up to the large test above, at least.
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(16, 16);
  const cloudvis::RenderLimits real = cloudvis::QueryRenderLimits(window);
  EXPECT_GE(real.MaximumWidth, 4096);
  EXPECT_GE(real.MaximumHeight, 4096);
}

// ---- animate ------------------------------------------------------------------------------

TEST(Animate, TurntableWritesNumberedFramesStartingWithThePlainRender)
{
  TemporaryDirectory dir;
  const CliRun run = Cloudvis(With({ "animate", CLOUDVIS_SCENES "/fbm-sphere.json", "-o",
    dir.File("frames/"), "--frames", "4", "--turntable" }, Small));
  ASSERT_EQ(run.Status, 0) << run.Err;
  EXPECT_EQ(run.Err, "");
  EXPECT_NE(run.Out.find("wrote 4 frames to " + dir.File("frames") +
              "/ (frame_0000.png .. frame_0003.png, 64 x 48 pixels)"),
    std::string::npos) << run.Out;
  EXPECT_EQ(dir.Files("/frames"), (std::vector<std::string>{ "frame_0000.png", "frame_0001.png",
                                    "frame_0002.png", "frame_0003.png" }));
  ASSERT_EQ(Cloudvis(With({ "render", CLOUDVIS_SCENES "/fbm-sphere.json", "-o",
    dir.File("plain.png") }, Small)).Status, 0);
  const Png plain = ReadPng(dir.File("plain.png"));
  const Png first = ReadPng(dir.File("frames/frame_0000.png"));
  const Png last = ReadPng(dir.File("frames/frame_0003.png"));
  EXPECT_EQ(first.Values, plain.Values) << "frame 0 is the scene's own view";
  EXPECT_GT(cloudvis::support::Compare(first, last).Mean, 0.005) << "the camera moved";
  // Frame 2 is the half turn: the camera stands opposite, as its metadata says.
  const json half = json::parse(ReadPng(dir.File("frames/frame_0002.png")).Text.at("cloudvis.scene"));
  const json start = json::parse(first.Text.at("cloudvis.scene"));
  for (int a : { 0, 2 })
  {
    const double focal = start["camera"]["focal_point"][a];
    EXPECT_NEAR(double(half["camera"]["position"][a]) - focal,
      -(double(start["camera"]["position"][a]) - focal), 1e-9);
  }
  // ... and rendering that metadata gives the frame.
  std::ofstream(dir.File("half.json")) << half.dump();
  ASSERT_EQ(Cloudvis({ "render", dir.File("half.json"), "-o", dir.File("half.png") }).Status, 0);
  EXPECT_EQ(ReadPng(dir.File("half.png")).Values, ReadPng(dir.File("frames/frame_0002.png")).Values);
}

TEST(Animate, TimeFramesAreTheSceneAtEachTime)
{
  TemporaryDirectory dir;
  const CliRun run = Cloudvis(With({ "animate", CLOUDVIS_SCENES "/fbm-sphere.json", "-o",
    dir.File("t"), "--frames", "3", "--time", "0:6", "--format", "exr" }, Small));
  ASSERT_EQ(run.Status, 0) << run.Err;
  EXPECT_EQ(dir.Files("/t"),
    (std::vector<std::string>{ "frame_0000.exr", "frame_0001.exr", "frame_0002.exr" }));
  std::vector<Exr> frames;
  for (const std::string& name : dir.Files("/t"))
  {
    frames.push_back(ReadExr(dir.File("t/" + name)));
  }
  EXPECT_NE(frames[0].Channels.at("A"), frames[1].Channels.at("A"));
  EXPECT_NE(frames[1].Channels.at("A"), frames[2].Channels.at("A"));
  EXPECT_NE(frames[0].Channels.at("A"), frames[2].Channels.at("A"));
  EXPECT_EQ(json::parse(frames[1].Strings.at("cloudvis.scene"))["field"]["time"], 3.0);
  // Frame 1 is the still of the scene at t = 3.
  const CliRun still = Cloudvis(With({ "render", CLOUDVIS_SCENES "/fbm-sphere.json", "--set",
    "field.time=3", "-o", dir.File("t3.exr") }, Small));
  ASSERT_EQ(still.Status, 0) << still.Err;
  const Exr t3 = ReadExr(dir.File("t3.exr"));
  EXPECT_EQ(t3.Channels.at("R"), frames[1].Channels.at("R"));
  EXPECT_EQ(t3.Channels.at("A"), frames[1].Channels.at("A"));
}

TEST(Animate, FrameNamesAndTimes)
{
  cloudvis::AnimationRequest request;
  request.Directory = "d";
  request.Frames = 10;
  EXPECT_EQ(cloudvis::FrameFileName(request, 9), "d/frame_0009.png");
  request.Frames = 12345;
  request.Extension = ".exr";
  EXPECT_EQ(cloudvis::FrameFileName(request, 7), "d/frame_00007.exr");
  request.Frames = 5;
  request.TimeBegin = 1.0;
  request.TimeEnd = 3.0;
  EXPECT_EQ(cloudvis::FrameTime(request, 0), 1.0);
  EXPECT_EQ(cloudvis::FrameTime(request, 2), 2.0);
  EXPECT_EQ(cloudvis::FrameTime(request, 4), 3.0);
  request.Frames = 1;
  EXPECT_EQ(cloudvis::FrameTime(request, 0), 1.0);
}

TEST(Animate, FailurePartWayKeepsTheFramesWrittenAndNoPartialFrame)
{
  TemporaryDirectory dir;
  // Frame 1 cannot be written: its name is taken by a directory.
  ASSERT_EQ(::mkdir(dir.File("f").c_str(), 0777), 0);
  ASSERT_EQ(::mkdir(dir.File("f/frame_0001.png").c_str(), 0777), 0);
  const CliRun run = Cloudvis(With({ "animate", CLOUDVIS_SCENES "/fbm-sphere.json", "-o",
    dir.File("f"), "--frames", "3", "--turntable" }, Small));
  EXPECT_EQ(run.Status, 1);
  EXPECT_NE(run.Err.find("frame_0001.png: cannot write: it is a directory"), std::string::npos)
    << run.Err;
  EXPECT_NE(run.Err.find("frames 0 .. 0 were written"), std::string::npos) << run.Err;
  EXPECT_EQ(dir.Files("/f"), (std::vector<std::string>{ "frame_0000.png", "frame_0001.png" }));
  EXPECT_TRUE(dir.Files("/f/frame_0001.png").empty());
}

// ---- noise target (docs/lighting.md, "A noise target") -------------------------------------

// The path tracer on the two-lights field at 24^3, 32 x 24 pixels: 10% takes a few readings of
// the noise (about 250 paths), 20% one or two. The automatic exposure renders the window once
// more after the accumulation, which must composite the image measured, not trace a new one.
cloudvis::Scene NoiseScene()
{
  return cloudvis::LoadScene(CLOUDVIS_SCENES "/two-lights.json",
    { "field.dimensions=24", "render.size=32,24", "render.lighting=pathtrace",
      "render.exposure=auto" });
}

cloudvis::NoiseTarget Target(double relativeStandardError)
{
  cloudvis::NoiseTarget target;
  target.RelativeStandardError = relativeStandardError;
  target.TimeLimit = 120.0; // far beyond what it takes: a loose target must be reached
  return target;
}

TEST(NoiseTarget, RenderStopsAtTheTargetWithTheImageItMeasured)
{
  // The still's own float image and variance (what an EXR holds) give the noise reported: the
  // image is the one measured, at or below the target, and it stopped there rather than running
  // on (one reading past the target at most halves the noise under 1 / sqrt(paths)).
  cloudvis::RenderOptions options;
  options.FloatImage = true;
  options.TargetNoise = Target(0.1);
  const cloudvis::Scene scene = NoiseScene();
  const cloudvis::OffscreenRenderResult result =
    cloudvis::RenderOffscreen(scene, cloudvis::ProduceField(scene), "test", 0, options);
  ASSERT_TRUE(result.Noise);
  const cloudvis::NoiseReport& report = *result.Noise;
  EXPECT_TRUE(report.Reached());
  EXPECT_LE(report.Noise.RelativeStandardError, 0.1);
  EXPECT_GT(report.Noise.RelativeStandardError, 0.05);
  EXPECT_GT(report.Samples, cloudvis::FirstNoiseCheckFrames * cloudvis::NoiseTargetSamplesPerFrame)
    << "10% takes more than the first reading here";
  EXPECT_EQ(result.AccumulatedSamples, report.Samples);
  const cloudvis::RenderedImage& image = result.Image;
  ASSERT_EQ(image.Variance.size(), image.Radiance.size());
  const cloudvis::ImageNoise own = cloudvis::MeasureImageNoise(
    image.Radiance.data(), image.Variance.data(), image.Radiance.size() / 4);
  EXPECT_GT(own.Pixels, 100u);
  EXPECT_DOUBLE_EQ(own.RelativeStandardError, report.Noise.RelativeStandardError);
}

TEST(NoiseTarget, CompareKeepsTheReferenceItMeasuredWhileTheModelsAccumulate)
{
  // 20% is reached within the models' 16 frames: the reference must stop there and stay, so
  // that the errors are measured against the image whose noise was reported.
  cloudvis::Scene scene = NoiseScene();
  scene.Render.Accumulate = 16;
  cloudvis::ReferencePaths reference;
  reference.Target = Target(0.2);
  const cloudvis::ComparisonResult result = cloudvis::RenderComparison(scene,
    cloudvis::ProduceField(scene), "test",
    { { cloudvis::LightingModel::March, std::nullopt } }, std::nullopt, 1, reference);
  ASSERT_TRUE(result.ReferenceTarget);
  EXPECT_TRUE(result.ReferenceTarget->Reached());
  EXPECT_LE(result.ReferenceTarget->Frames, 16);
  EXPECT_EQ(result.AccumulatedFrames, 16);
  EXPECT_EQ(result.ReferenceSamples, result.ReferenceTarget->Samples);
  EXPECT_LE(result.ReferenceNoise.RelativeStandardError, 0.2);
  EXPECT_DOUBLE_EQ(
    result.ReferenceNoise.RelativeStandardError, result.ReferenceTarget->Noise.RelativeStandardError);
}

TEST(NoiseTarget, ReadingsFollowTheSquareRootLawAtMostDoubling)
{
  // Twice the target's noise needs four times the paths: capped at double the frames.
  EXPECT_EQ(cloudvis::NextNoiseCheck(8, 0.04, 0.02), 16);
  // Just above the target: 5% past the law's count, and at least one frame more.
  EXPECT_EQ(cloudvis::NextNoiseCheck(100, 0.021, 0.02), 116);
  EXPECT_EQ(cloudvis::NextNoiseCheck(8, 0.02000001, 0.02), 9);
  EXPECT_EQ(cloudvis::NextNoiseCheck(60000, 1.0, 0.02), cloudvis::MaximumNoiseTargetFrames);
}

// ---- progress -----------------------------------------------------------------------------

TEST(Progress, DrawsOnlyWhenEnabledAndErasesItself)
{
  std::ostringstream quiet;
  {
    cloudvis::Progress progress(quiet, false);
    progress.Update("rendering", 0.5);
  }
  EXPECT_EQ(quiet.str(), "");
  std::ostringstream shown;
  {
    cloudvis::Progress progress(shown, true);
    progress.Update("rendering", 0.5);
    progress.Update("rendering", 0.501); // the same percentage: not redrawn
    progress.Update("rendering", 1.0);
  }
  EXPECT_EQ(shown.str(), "\rrendering [###############...............]  50%\033[K"
                         "\rrendering [##############################] 100%\033[K\r\033[K");
}

// ---- the resolved scene -------------------------------------------------------------------

TEST(SceneJson, EveryShippedSceneRoundTrips)
{
  DIR* scenes = ::opendir(CLOUDVIS_SCENES);
  ASSERT_NE(scenes, nullptr);
  int count = 0;
  while (dirent* entry = ::readdir(scenes))
  {
    const std::string name = entry->d_name;
    if (name.size() < 5 || name.substr(name.size() - 5) != ".json")
    {
      continue;
    }
    const cloudvis::Scene scene = cloudvis::LoadScene(std::string(CLOUDVIS_SCENES "/") + name, {});
    const double bounds[6] = { -2, 2, -2, 2, -2, 2 };
    const cloudvis::ResolvedCamera camera = cloudvis::ResolveCamera(scene, bounds);
    const json first = cloudvis::SceneToJson(scene, camera);
    const cloudvis::Scene again = cloudvis::SceneFromDocument(first, name, CLOUDVIS_SCENES);
    EXPECT_EQ(cloudvis::SceneToJson(again, cloudvis::ResolveCamera(again, bounds)), first) << name;
    ++count;
  }
  ::closedir(scenes);
  EXPECT_GT(count, 5);
}

TEST(SceneJson, EveryNameReadsBackToItsValue)
{
  cloudvis::Scene scene;
  const cloudvis::ResolvedCamera camera;
  for (const char* model : { "sdf_plus_fbm", "fbm_falloff", "constant" })
  {
    for (const char* noise : { "none", "white", "value", "perlin" })
    {
      for (const char* shape : { "sphere", "box", "torus", "cross", "capsule" })
      {
        for (const char* blend : { "union", "smooth_union" })
        {
          const json document = { { "field", { { "density_model", model }, { "noise", noise },
            { "shape", { { "type", shape } } }, { "blend", blend } } } };
          const cloudvis::Scene read = cloudvis::SceneFromDocument(document, "d", "");
          const json written = cloudvis::SceneToJson(read, camera);
          EXPECT_EQ(written["field"]["density_model"], model);
          EXPECT_EQ(written["field"]["noise"], noise);
          EXPECT_EQ(written["field"]["shape"][0]["type"], shape);
          EXPECT_EQ(written["field"]["blend"], blend);
        }
      }
    }
  }
  for (const std::string& lighting : cloudvis::LightingModelNames())
  {
    const json document = { { "render", { { "lighting", lighting } } } };
    EXPECT_EQ(cloudvis::SceneToJson(cloudvis::SceneFromDocument(document, "d", ""), camera)
                ["render"]["lighting"],
      lighting);
  }
}

} // namespace
