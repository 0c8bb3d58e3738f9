// Tests of the scene language's presets, backgrounds and camera orbit: that each shipped preset
// loads and draws, that a scene's own keys win over a preset's, that a ParaView preset's points
// land on the volume property where its file puts them, that every kind of bad preset is refused
// with a message naming the file and the problem; that a gradient and the article's sky put the
// colors the formulas give on the right pixels (the sky against an independent computation of each
// pixel's ray); that an orbit places the camera where its formula says. Render tests need an X
// display (Xvfb under `make test`).
#include "Background.h"
#include "Errors.h"
#include "OffscreenRender.h"
#include "Presets.h"
#include "Scene.h"
#include "SceneField.h"
#include "SupportBaselines.h"
#include "SupportRun.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkRenderer.h>
#include <vtkVolumeProperty.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <unistd.h>

namespace
{
using json = nlohmann::json;
using Color = std::array<double, 3>;

// A directory for scene and preset files, removed with them afterwards.
struct Folder : cloudvis::support::TemporaryDirectory
{
  Folder()
    : TemporaryDirectory("cloudvis-scene-language")
  {
  }
};

// The message LoadScene throws for a scene, or "" when it loads.
std::string LoadError(const std::string& path, const std::vector<std::string>& assignments = {})
{
  try
  {
    cloudvis::LoadScene(path, assignments);
  }
  catch (const cloudvis::InputError& e)
  {
    return e.what();
  }
  return "";
}

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

// A small scene that renders in a moment; `assignments` as with --set.
cloudvis::Scene SmallScene(std::vector<std::string> assignments = {})
{
  assignments.insert(assignments.begin(),
    { "field.dimensions=24", "render.size=[48,36]", "render.accumulate=1", "render.jitter=false" });
  return cloudvis::LoadScene("", assignments);
}

cloudvis::RenderedImage Render(const cloudvis::Scene& scene)
{
  const vtkSmartPointer<vtkImageData> field = cloudvis::ProduceField(scene);
  return cloudvis::RenderOffscreen(scene, field, "test").Image;
}

Color PixelColor(const cloudvis::RenderedImage& image, int x, int y)
{
  const unsigned char* p = image.Pixel(x, y);
  return { { p[0] / 255.0, p[1] / 255.0, p[2] / 255.0 } };
}

void ExpectColorNear(const Color& actual, const Color& expected, double tolerance, const std::string& what)
{
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(actual[c], expected[c], tolerance) << what << ", channel " << c;
  }
}

// ---- presets --------------------------------------------------------------------------------

TEST(Presets, ShippedPresetsAreListed)
{
  const std::vector<std::string> names = cloudvis::ShippedPresetNames();
  for (const char* name : { "cloud-white", "cloud-dusk", "density-heat", "thin-haze", "paraview-example" })
  {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  }
}

TEST(Presets, EachShippedPresetLoadsAndRenders)
{
  const cloudvis::Scene plain = SmallScene({ "background=[0,0,0]" });
  const cloudvis::RenderedImage reference = Render(plain);
  for (const std::string& name : cloudvis::ShippedPresetNames())
  {
    SCOPED_TRACE(name);
    const cloudvis::Scene scene =
      SmallScene({ "background=[0,0,0]", "transfer_function.preset=" + name });
    EXPECT_FALSE(scene.TransferFunction.Opacity.empty());
    const cloudvis::RenderedImage image = Render(scene);
    ASSERT_EQ(image.Width, 48);
    ASSERT_EQ(image.Height, 36);
    // The cloud shows in the middle, the background at the corner.
    ExpectColorNear(PixelColor(image, 0, 0), { { 0, 0, 0 } }, 0.5 / 255.0, "corner");
    const Color centre = PixelColor(image, 24, 18);
    EXPECT_GT(centre[0] + centre[1] + centre[2], 0.05) << "the cloud is drawn";
    if (name != "cloud-white")
    {
      EXPECT_NE(image.RGB, reference.RGB) << "a preset other than the default look changes the image";
    }
  }
}

TEST(Presets, CloudWhiteIsTheDefaultLook)
{
  const cloudvis::Scene scene = cloudvis::LoadScene("", { "transfer_function.preset=cloud-white" });
  const cloudvis::TransferFunctionSpec defaults;
  EXPECT_EQ(scene.TransferFunction.Opacity, defaults.Opacity);
  EXPECT_EQ(scene.TransferFunction.Color, defaults.Color);
  EXPECT_EQ(scene.TransferFunction.UnitDistance, defaults.UnitDistance);
}

TEST(Presets, SceneKeysOverrideThePresets)
{
  Folder folder;
  folder.Write("warm.json", R"({"name": "warm", "opacity": [[0, 0], [1, 0.4]],
    "color": [[0, 1, 0.5, 0], [1, 1, 1, 0.5]], "unit_distance": 0.25})");
  // The preset key is written after the overriding key: the order in the file does not matter.
  const std::string scene = folder.Write("scene.json", R"({"transfer_function":
    {"opacity": [[0, 0], [0.5, 0.9]], "preset": "warm.json"}})");
  const cloudvis::Scene loaded = cloudvis::LoadScene(scene, {});
  using P2 = std::array<double, 2>;
  using P4 = std::array<double, 4>;
  EXPECT_EQ(loaded.TransferFunction.Opacity, (std::vector<P2>{ { 0, 0 }, { 0.5, 0.9 } }))
    << "the scene's opacity wins";
  EXPECT_EQ(loaded.TransferFunction.Color, (std::vector<P4>{ { 0, 1, 0.5, 0 }, { 1, 1, 1, 0.5 } }))
    << "the preset's color stays";
  EXPECT_EQ(loaded.TransferFunction.UnitDistance, 0.25);
  // --set overrides too, and a preset without unit_distance keeps the default.
  folder.Write("colors.json", R"({"color": [[0, 0, 0, 1]]})");
  const cloudvis::Scene set = cloudvis::LoadScene(scene,
    { "transfer_function.preset=colors.json", "transfer_function.unit_distance=0.5" });
  EXPECT_EQ(set.TransferFunction.Color, (std::vector<P4>{ { 0, 0, 0, 1 } }));
  EXPECT_EQ(set.TransferFunction.UnitDistance, 0.5);
  EXPECT_EQ(set.TransferFunction.Opacity, (std::vector<P2>{ { 0, 0 }, { 0.5, 0.9 } }));
  const cloudvis::Scene onlyColors = cloudvis::LoadScene("", { "transfer_function.preset=" + folder.Path + "/colors.json" });
  EXPECT_EQ(onlyColors.TransferFunction.Opacity, cloudvis::TransferFunctionSpec{}.Opacity)
    << "what a preset leaves out keeps the default";
  EXPECT_EQ(onlyColors.TransferFunction.UnitDistance, 0.1);
}

const char* const TwoParaViewPresets = R"([
  {"Name": "first", "ColorSpace": "RGB",
   "RGBPoints": [0.0, 0.0, 0.0, 1.0,  0.5, 0.0, 1.0, 0.0,  2.0, 1.0, 0.0, 0.0],
   "Points": [0.1, 0.0, 0.5, 0.0,  1.0, 0.8, 0.5, 0.0,  3.0, 0.2, 0.5, 0.0]},
  {"Name": "second", "ColorSpace": "Diverging", "RGBPoints": [-1, 1, 1, 1, 1, 0, 0, 0]}
])";

TEST(Presets, ParaViewPointsLandOnTheVolumeProperty)
{
  Folder folder;
  folder.Write("paraview.json", TwoParaViewPresets);
  const std::string scene = folder.Write("scene.json", R"({"transfer_function": {"preset": "paraview.json"}})");
  const cloudvis::Scene loaded = cloudvis::LoadScene(scene, {});
  const vtkSmartPointer<vtkVolumeProperty> property = cloudvis::MakeVolumeProperty(loaded.TransferFunction);
  vtkColorTransferFunction* color = property->GetRGBTransferFunction();
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity();
  ASSERT_EQ(color->GetSize(), 3) << "one color node per RGBPoints quadruple";
  ASSERT_EQ(opacity->GetSize(), 3) << "one opacity node per Points quadruple";
  const auto expectColor = [&](double x, const Color& expected)
  {
    double rgb[3];
    color->GetColor(x, rgb);
    ExpectColorNear({ { rgb[0], rgb[1], rgb[2] } }, expected, 1e-6, "color at " + std::to_string(x));
  };
  expectColor(0.0, { { 0, 0, 1 } });
  expectColor(0.25, { { 0, 0.5, 0.5 } }); // linear between the first two
  expectColor(0.5, { { 0, 1, 0 } });
  expectColor(2.0, { { 1, 0, 0 } });
  expectColor(5.0, { { 1, 0, 0 } }); // holds beyond the last point
  EXPECT_NEAR(opacity->GetValue(0.1), 0.0, 1e-9);
  EXPECT_NEAR(opacity->GetValue(0.55), 0.4, 1e-9) << "midpoint and sharpness are ignored: linear";
  EXPECT_NEAR(opacity->GetValue(1.0), 0.8, 1e-9);
  EXPECT_NEAR(opacity->GetValue(3.0), 0.2, 1e-9);

  // preset_name picks another preset of the file; without Points the opacity stays the default.
  const cloudvis::Scene second = cloudvis::LoadScene(scene, { "transfer_function.preset_name=second" });
  using P4 = std::array<double, 4>;
  EXPECT_EQ(second.TransferFunction.Color, (std::vector<P4>{ { -1, 1, 1, 1 }, { 1, 0, 0, 0 } }));
  EXPECT_EQ(second.TransferFunction.Opacity, cloudvis::TransferFunctionSpec{}.Opacity);
}

TEST(Presets, ShippedParaViewExampleLoadsByNameAndByPath)
{
  const cloudvis::Scene byName = cloudvis::LoadScene("", { "transfer_function.preset=paraview-example" });
  const cloudvis::Scene byPath = cloudvis::LoadScene("",
    { "transfer_function.preset=" + cloudvis::PresetDirectory() + "/paraview-example.json",
      "transfer_function.preset_name=cloudvis ember" });
  EXPECT_EQ(byName.TransferFunction.Color.size(), 4u);
  EXPECT_EQ(byName.TransferFunction.Opacity.size(), 4u);
  EXPECT_EQ(byName.TransferFunction.Color.front(), (std::array<double, 4>{ 0.0, 0.05, 0.1, 0.3 }));
  EXPECT_NE(byPath.TransferFunction.Color, byName.TransferFunction.Color);
}

struct BadPreset
{
  const char* What;
  const char* Content; // the file bad.json; nullptr: no file
  const char* Reference;
  std::vector<std::string> Expected; // parts of the message
  const char* PresetName = nullptr;
};

TEST(Presets, BadPresetsAreRefusedNamingTheFileAndTheProblem)
{
  const std::vector<BadPreset> cases = {
    { "unknown name", nullptr, "nope",
      { "scene.json: transfer_function.preset: unknown preset \"nope\"; shipped presets: ",
        "cloud-dusk, cloud-white, density-heat" } },
    { "a name that is a path", nullptr, "../presets",
      { "transfer_function.preset: ", "../presets: cannot read preset file" } },
    { "missing file", nullptr, "missing.json",
      { "transfer_function.preset: ", "missing.json: cannot read preset file: No such file" } },
    { "malformed JSON", "{\n  \"opacity\": [[0, 0],\n  ]\n}", "bad.json",
      { "transfer_function.preset: ", "bad.json:3:3: malformed JSON at line 3, column 3" } },
    { "not an object", "42", "bad.json", { "bad.json: a preset must be a JSON object" } },
    { "no points", R"({"name": "empty"})", "bad.json", { "bad.json: the preset has no points" } },
    { "empty list", R"({"opacity": []})", "bad.json", { "bad.json: opacity: the list is empty" } },
    { "decreasing density", R"({"opacity": [[0.5, 0], [0.2, 1]]})", "bad.json",
      { "bad.json: opacity[1][0]: densities must increase strictly from point to point: 0.2 follows 0.5" } },
    { "color out of range", R"({"color": [[0, 1.5, 0, 0]]})", "bad.json",
      { "bad.json: color[0][1]: value 1.5 is out of range: allowed [0, 1]" } },
    { "unknown key", R"({"colour": [[0, 1, 1, 1]], "opacity": [[0, 0]]})", "bad.json",
      { "bad.json: colour: unknown key; allowed keys: name, description, opacity, color, unit_distance" } },
    { "ParaView: no presets", "[]", "bad.json", { "bad.json: the ParaView preset list is empty" } },
    { "ParaView: no RGBPoints", R"([{"Name": "x", "Points": [0, 0, 0.5, 0]}])", "bad.json",
      { "bad.json: [0]: no RGBPoints" } },
    { "ParaView: no points", R"([{"Name": "x", "RGBPoints": []}])", "bad.json",
      { "bad.json: [0].RGBPoints: the list is empty; it has no points" } },
    { "ParaView: not quadruples", R"([{"Name": "x", "RGBPoints": [0, 1, 1]}])", "bad.json",
      { "bad.json: [0].RGBPoints: has 3 numbers, not a multiple of 4" } },
    { "ParaView: decreasing x", R"([{"Name": "x", "RGBPoints": [1, 0, 0, 0, 0.5, 1, 1, 1]}])", "bad.json",
      { "bad.json: [0].RGBPoints[4]: x values must increase strictly from point to point: 0.5 follows 1" } },
    { "ParaView: color out of range", R"([{"Name": "x", "RGBPoints": [0, 0, 2, 0]}])", "bad.json",
      { "bad.json: [0].RGBPoints[2]: value 2 is out of range: allowed [0, 1]" } },
    { "ParaView: opacity out of range",
      R"([{"Name": "x", "RGBPoints": [0, 0, 0, 0], "Points": [0, -0.5, 0.5, 0]}])", "bad.json",
      { "bad.json: [0].Points[1]: value -0.5 is out of range: allowed [0, 1]" } },
    { "ParaView: not a number", R"([{"Name": "x", "RGBPoints": [0, "red", 0, 0]}])", "bad.json",
      { "bad.json: [0].RGBPoints[1]: expected a number" } },
    { "ParaView: unknown preset_name", TwoParaViewPresets, "bad.json",
      { "bad.json: no ParaView preset named \"third\"; the file has \"first\", \"second\"" }, "third" },
    { "preset_name on a cloudvis preset", R"({"opacity": [[0, 0]]})", "bad.json",
      { "bad.json: is a cloudvis preset, not a ParaView file" }, "x" },
  };
  for (const BadPreset& bad : cases)
  {
    SCOPED_TRACE(bad.What);
    Folder folder;
    if (bad.Content)
    {
      folder.Write("bad.json", bad.Content);
    }
    json tf = { { "preset", bad.Reference } };
    if (bad.PresetName)
    {
      tf["preset_name"] = bad.PresetName;
    }
    const std::string scene = folder.Write("scene.json", json{ { "transfer_function", tf } }.dump());
    const std::string message = LoadError(scene);
    ASSERT_FALSE(message.empty()) << "accepted";
    EXPECT_TRUE(Contains(message, "transfer_function.preset: ")) << message;
    for (const std::string& part : bad.Expected)
    {
      EXPECT_TRUE(Contains(message, part)) << message << "\n  expected: " << part;
    }
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

TEST(Presets, PresetKeysOfTheWrongTypeAreRefused)
{
  EXPECT_TRUE(Contains(LoadError("", { "transfer_function.preset=3" }),
    "transfer_function.preset: expected a preset name or the path of a .json file, got number 3"));
  EXPECT_TRUE(Contains(LoadError("", { "transfer_function.preset_name=first" }),
    "transfer_function.preset_name: applies only with transfer_function.preset"));
  EXPECT_TRUE(Contains(LoadError("", { "transfer_function.preset=nope" }), "(set with --set)"));
}

// ---- backgrounds: parsing -------------------------------------------------------------------

TEST(Background, KindsParse)
{
  const cloudvis::Scene array = cloudvis::LoadScene("", { "background=[0.1,0.2,0.3]" });
  EXPECT_EQ(array.BackgroundStyle.Type, cloudvis::BackgroundType::Solid);
  EXPECT_EQ(array.Background, (Color{ 0.1, 0.2, 0.3 }));
  const cloudvis::Scene solid = cloudvis::LoadScene("", { R"(background={"type":"solid","color":[1,0,0.5]})" });
  EXPECT_EQ(solid.BackgroundStyle.Type, cloudvis::BackgroundType::Solid);
  EXPECT_EQ(solid.Background, (Color{ 1, 0, 0.5 }));
  const cloudvis::Scene gradient =
    cloudvis::LoadScene("", { R"(background={"type":"gradient","top":[0,0,1],"bottom":[1,1,0]})" });
  EXPECT_EQ(gradient.BackgroundStyle.Type, cloudvis::BackgroundType::Gradient);
  EXPECT_EQ(gradient.BackgroundStyle.Top, (Color{ 0, 0, 1 }));
  EXPECT_EQ(gradient.Background, (Color{ 1, 1, 0 }));
  const cloudvis::Scene sky = cloudvis::LoadScene("", { R"(background={"type":"sky","sun":[0,2,0]})" });
  EXPECT_EQ(sky.BackgroundStyle.Type, cloudvis::BackgroundType::Sky);
  EXPECT_EQ(sky.BackgroundStyle.Sun, (Color{ 0, 1, 0 })) << "normalized";
}

TEST(Background, SkySunDefaultsToTheFirstDirectionalLightElseTheArticles)
{
  const cloudvis::Scene plain = cloudvis::LoadScene("", { R"(background={"type":"sky"})" });
  ASSERT_TRUE(plain.BackgroundStyle.Sun.has_value());
  const double n = std::sqrt(0.25 + 0.36 + 0.36);
  ExpectColorNear(*plain.BackgroundStyle.Sun, { { 0.5 / n, 0.6 / n, 0.6 / n } }, 1e-12, "no lights key");

  Folder folder;
  // A point light first (skipped), then a directional one; the background comes before the lights.
  const std::string scene = folder.Write("scene.json", R"({"background": {"type": "sky"},
    "lights": [{"type": "point", "position": [0, 5, 0]},
               {"type": "directional", "position": [0, 0, 3], "focal_point": [0, 0, 0]}]})");
  const std::string message = LoadError(scene);
  if (!message.empty())
  {
    GTEST_SKIP() << "the lights section has another form here: " << message;
  }
  const cloudvis::Scene lit = cloudvis::LoadScene(scene, {});
  ASSERT_TRUE(lit.BackgroundStyle.Sun.has_value());
  ExpectColorNear(*lit.BackgroundStyle.Sun, { { 0, 0, 1 } }, 1e-6, "the directional light");
}

TEST(Background, BadValuesAreRefused)
{
  const std::vector<std::pair<std::string, std::string>> cases = {
    { R"(background={"type":"cloudy"})", "background.type: unknown name \"cloudy\"; allowed: solid, gradient, sky" },
    { R"(background={"color":[1,1,1]})", "background.type: missing; one of solid, gradient, sky" },
    { R"(background={"type":"gradient","top":[1,1,1]})", "background.bottom: missing; a gradient background needs top, bottom" },
    { R"(background={"type":"solid"})", "background.color: missing; a solid background needs color" },
    { R"(background={"type":"solid","color":[1,1,1],"top":[0,0,0]})", "background.top: not a key of a solid background; allowed keys: type, color" },
    { R"(background={"type":"sky","color":[1,1,1]})", "background.color: not a key of a sky background; allowed keys: type, sun" },
    { R"(background={"type":"gradient","top":[1,1.5,1],"bottom":[0,0,0]})", "background.top[1]: value 1.5 is out of range: allowed [0, 1]" },
    { R"(background={"type":"solid","color":[-1,0,0]})", "background.color[0]: value -1 is out of range: allowed [0, 1]" },
    { R"(background={"type":"sky","sun":[0,0,0]})", "background.sun: the direction toward the sun must not be zero" },
    { R"(background="blue")", "background: expected [r, g, b] or an object with a \"type\"" },
    { "background=[1,1,2]", "background[2]: value 2 is out of range: allowed [0, 1]" },
  };
  for (const auto& c : cases)
  {
    const std::string message = LoadError("", { c.first });
    EXPECT_TRUE(Contains(message, "default scene: " + c.second)) << c.first << "\n  got: " << message;
  }
}

// ---- backgrounds: the sky's formula and its pixels --------------------------------------------

TEST(Background, SkyColorFollowsTheArticlesFormula)
{
  const Color sun{ { 0, 0, 1 } };
  // At the horizon, away from the sun: the base color.
  ExpectColorNear(cloudvis::SkyColor({ { 1, 0, 0 } }, sun), { { 0.7, 0.7, 0.9 } }, 1e-12, "horizon");
  // Looking up 30 degrees: minus 0.8 * (0.9, 0.75, 0.9) * 0.5.
  const double y = 0.5, h = std::sqrt(0.75);
  ExpectColorNear(cloudvis::SkyColor({ { h, y, 0 } }, sun), { { 0.34, 0.4, 0.54 } }, 1e-12, "up");
  // Toward the sun at the horizon: plus 0.5 * (1, 0.5, 0.3), clamped to 1.
  ExpectColorNear(cloudvis::SkyColor({ { 0, 0, 1 } }, sun), { { 1.0, 0.95, 1.0 } }, 1e-12, "sun");
  // 60 degrees from the sun: cos^10 = 2^-10.
  const double glow = std::pow(0.5, 10.0) * 0.5;
  ExpectColorNear(cloudvis::SkyColor({ { h, 0, 0.5 } }, sun),
    { { 0.7 + glow, 0.7 + 0.5 * glow, 0.9 + 0.3 * glow } }, 1e-12, "glow");
  // Straight up the gradient goes below zero in red: clamped.
  EXPECT_EQ(cloudvis::SkyColor({ { 0, 1, 0 } }, sun)[0], 0.0);
}

// The ray through the centre of pixel (i, j) from the camera's own frame, independently of the
// matrices MakeSkyImage inverts.
Color PixelRay(vtkCamera* camera, int i, int j, int width, int height)
{
  double forward[3], up[3], right[3];
  camera->GetDirectionOfProjection(forward);
  camera->GetViewUp(up);
  vtkMath::Cross(forward, up, right);
  const double t = std::tan(0.5 * vtkMath::RadiansFromDegrees(camera->GetViewAngle()));
  const double x = (2.0 * (i + 0.5) / width - 1.0) * t * width / height;
  const double y = (2.0 * (j + 0.5) / height - 1.0) * t;
  Color ray;
  for (int c = 0; c < 3; ++c)
  {
    ray[c] = forward[c] + x * right[c] + y * up[c];
  }
  const double length = std::sqrt(ray[0] * ray[0] + ray[1] * ray[1] + ray[2] * ray[2]);
  return { { ray[0] / length, ray[1] / length, ray[2] / length } };
}

TEST(Background, SkyImageIsTheFormulaAlongEachPixelsRay)
{
  vtkNew<vtkCamera> camera;
  camera->SetPosition(1, 0.5, 6);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(60);
  camera->OrthogonalizeViewUp();
  const int width = 64, height = 48;
  const Color sun = PixelRay(camera, 48, 30, width, height); // a sun in view
  const vtkSmartPointer<vtkImageData> image = cloudvis::MakeSkyImage(camera, width, height, sun);
  int dimensions[3];
  image->GetDimensions(dimensions);
  ASSERT_EQ(dimensions[0], width);
  ASSERT_EQ(dimensions[1], height);
  const auto pixel = [&](int i, int j)
  {
    const auto* p = static_cast<unsigned char*>(image->GetScalarPointer(i, j, 0));
    return Color{ { p[0] / 255.0, p[1] / 255.0, p[2] / 255.0 } };
  };
  for (int j = 0; j < height; j += 7)
  {
    for (int i = 0; i < width; i += 9)
    {
      ExpectColorNear(pixel(i, j), cloudvis::SkyColor(PixelRay(camera, i, j, width, height), sun),
        0.5 / 255.0 + 1e-9, "pixel " + std::to_string(i) + "," + std::to_string(j));
    }
  }
  // Looking up (top row) is darker and bluer than the middle, which is nearer the horizon.
  const Color up = pixel(10, height - 1), level = pixel(10, height / 2);
  EXPECT_LT(up[0] + up[1] + up[2], level[0] + level[1] + level[2]);
  EXPECT_GT(up[2] / std::max(up[0], 1e-3), level[2] / level[0]);
  // Toward the sun it is warmer (more red than blue) than the same row far from it.
  const Color toward = pixel(48, 30), away = pixel(2, 30);
  EXPECT_GT(toward[0] - toward[2], away[0] - away[2] + 0.05);
}

TEST(Background, GradientAndSkyReachTheRenderedPixels)
{
  // Nothing opaque in the field: every pixel is background.
  const std::string clear = "transfer_function.opacity=[[0,0]]";
  const cloudvis::RenderedImage gradient =
    Render(SmallScene({ clear, R"(background={"type":"gradient","top":[0,0,1],"bottom":[1,0.5,0]})" }));
  const int w = gradient.Width, h = gradient.Height;
  const Color top = PixelColor(gradient, w / 2, h - 1), bottom = PixelColor(gradient, 0, 0);
  ExpectColorNear(top, { { 0, 0, 1 } }, 0.05, "top row");
  ExpectColorNear(bottom, { { 1, 0.5, 0 } }, 0.05, "bottom row");
  const Color middle = PixelColor(gradient, w / 2, h / 2);
  ExpectColorNear(middle, { { 0.5, 0.25, 0.5 } }, 0.05, "halfway");

  const cloudvis::RenderedImage solid =
    Render(SmallScene({ clear, R"(background={"type":"solid","color":[0.2,0.4,0.6]})" }));
  ExpectColorNear(PixelColor(solid, w / 3, h / 3), { { 0.2, 0.4, 0.6 } }, 1.0 / 255.0, "solid");

  // The sky: what MakeSkyImage computes for the scene's camera is what the window shows.
  const cloudvis::Scene skyScene = SmallScene({ clear, R"(background={"type":"sky","sun":[0,0.2,1]})" });
  const cloudvis::RenderedImage sky = Render(skyScene);
  vtkNew<vtkRenderer> renderer;
  const vtkSmartPointer<vtkImageData> field = cloudvis::ProduceField(skyScene);
  cloudvis::ApplyCamera(skyScene.Camera, field->GetBounds(), renderer, "test");
  const vtkSmartPointer<vtkImageData> expected = cloudvis::MakeSkyImage(
    renderer->GetActiveCamera(), w, h, cloudvis::SkySunDirection(skyScene.BackgroundStyle));
  for (int j = 0; j < h; j += 5)
  {
    for (int i = 0; i < w; i += 5)
    {
      const auto* e = static_cast<unsigned char*>(expected->GetScalarPointer(i, j, 0));
      const unsigned char* p = sky.Pixel(i, j);
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(int(p[c]), int(e[c]), 1) << "pixel " << i << "," << j << " channel " << c;
      }
    }
  }
  // The camera looks along -z and this sun is toward +z, behind it: no glow in view, and the
  // vertical gradient makes the top darker than the bottom.
  const Color skyTop = PixelColor(sky, w / 2, h - 1), skyBottom = PixelColor(sky, w / 2, 0);
  EXPECT_LT(skyTop[0] + skyTop[1] + skyTop[2], skyBottom[0] + skyBottom[1] + skyBottom[2]);

  // With a cloud, it composites over the sky: the centre differs, a corner does not.
  const cloudvis::RenderedImage cloudy = Render(SmallScene({ R"(background={"type":"sky","sun":[0,0.2,1]})" }));
  EXPECT_NE(std::vector<unsigned char>(cloudy.Pixel(w / 2, h / 2), cloudy.Pixel(w / 2, h / 2) + 3),
    std::vector<unsigned char>(sky.Pixel(w / 2, h / 2), sky.Pixel(w / 2, h / 2) + 3));
  EXPECT_EQ(std::vector<unsigned char>(cloudy.Pixel(0, 0), cloudy.Pixel(0, 0) + 3),
    std::vector<unsigned char>(sky.Pixel(0, 0), sky.Pixel(0, 0) + 3));
}

// The picture at the top of the user guide, small: the article's cloud under the article's sky,
// against its committed baseline (tests/baselines/sky.png; tests/support/SupportBaselines.h).
TEST(Baseline, SkyScene)
{
  const Folder folder;
  const std::string png = folder.File("sky.png");
  const cloudvis::support::CommandResult run = cloudvis::support::RunCloudvis({ "render",
    CLOUDVIS_SCENES "/sky.json", "--size", "128x96", "--set", "field.dimensions=32", "--set",
    "render.jitter=false", "--set", "render.accumulate=1", "-o", png });
  ASSERT_EQ(run.Status, 0) << run.Err;
  const cloudvis::support::BaselineCheck check =
    cloudvis::support::CompareWithBaseline(cloudvis::support::ReadPng(png), "sky");
  EXPECT_TRUE(check) << check.Message;
}

// ---- camera orbit ---------------------------------------------------------------------------

TEST(Orbit, PositionFollowsTheFormula)
{
  const double bounds[6] = { -1, 3, -2, 2, 0, 2 };
  const double focal[3] = { 1, 0, 1 };
  vtkNew<vtkRenderer> renderer;
  cloudvis::CameraSpec spec;
  spec.Orbit = cloudvis::OrbitSpec{ 30.0, 20.0, 7.0 };
  cloudvis::ApplyCamera(spec, bounds, renderer, "s");
  vtkCamera* camera = renderer->GetActiveCamera();
  const double az = vtkMath::RadiansFromDegrees(30.0), el = vtkMath::RadiansFromDegrees(20.0);
  const double expected[3] = { focal[0] + 7 * std::cos(el) * std::sin(az), focal[1] + 7 * std::sin(el),
    focal[2] + 7 * std::cos(el) * std::cos(az) };
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(camera->GetPosition()[c], expected[c], 1e-9) << c;
    EXPECT_NEAR(camera->GetFocalPoint()[c], focal[c], 1e-9) << c;
  }
  EXPECT_GT(camera->GetViewUp()[1], 0.9) << "y stays up";

  // Without a distance: the default camera's distance; azimuth 0, elevation 0 is the default view.
  cloudvis::ApplyCamera(cloudvis::CameraSpec{}, bounds, renderer, "s");
  const double defaultZ = camera->GetPosition()[2];
  spec.Orbit = cloudvis::OrbitSpec{};
  cloudvis::ApplyCamera(spec, bounds, renderer, "s");
  EXPECT_NEAR(camera->GetPosition()[0], focal[0], 1e-9);
  EXPECT_NEAR(camera->GetPosition()[2], defaultZ, 1e-9);
  spec.Orbit = cloudvis::OrbitSpec{ 90.0, 0.0, std::nullopt };
  cloudvis::ApplyCamera(spec, bounds, renderer, "s");
  EXPECT_NEAR(camera->GetPosition()[0] - focal[0], defaultZ - focal[2], 1e-9) << "azimuth 90 looks from +x";
  EXPECT_NEAR(camera->GetPosition()[2], focal[2], 1e-9);

  // Around camera.focal_point when given.
  spec.FocalPoint = std::array<double, 3>{ { 5, 5, 5 } };
  spec.Orbit = cloudvis::OrbitSpec{ 0.0, 90.0 - 1e-6, 2.0 };
  cloudvis::ApplyCamera(spec, bounds, renderer, "s");
  EXPECT_NEAR(camera->GetPosition()[1], 7.0, 1e-6) << "looking almost straight down";
}

TEST(Orbit, SceneKeysParseAndAreChecked)
{
  const cloudvis::Scene scene =
    cloudvis::LoadScene("", { R"(camera.orbit={"azimuth":-45,"elevation":10,"distance":6})" });
  ASSERT_TRUE(scene.Camera.Orbit.has_value());
  EXPECT_EQ(scene.Camera.Orbit->Azimuth, -45.0);
  EXPECT_EQ(scene.Camera.Orbit->Elevation, 10.0);
  EXPECT_EQ(scene.Camera.Orbit->Distance, 6.0);
  const cloudvis::Scene partial = cloudvis::LoadScene("", { R"(camera.orbit={"azimuth":10})" });
  EXPECT_EQ(partial.Camera.Orbit->Elevation, 0.0);
  EXPECT_FALSE(partial.Camera.Orbit->Distance.has_value());

  EXPECT_TRUE(Contains(LoadError("", { "camera.position=0,0,5", R"(camera.orbit={"azimuth":10})" }),
    "default scene: camera.orbit: cannot be combined with camera.position"));
  EXPECT_TRUE(Contains(LoadError("", { R"(camera.orbit={"elevation":90})" }),
    "camera.orbit.elevation: value 90 is out of range: allowed (-90, 90)"));
  EXPECT_TRUE(Contains(LoadError("", { R"(camera.orbit={"elevation":-95})" }),
    "camera.orbit.elevation: value -95 is out of range: allowed (-90, 90)"));
  EXPECT_TRUE(Contains(LoadError("", { R"(camera.orbit={"distance":0})" }),
    "camera.orbit.distance: value 0 is out of range: allowed > 0"));
  EXPECT_TRUE(Contains(LoadError("", { R"(camera.orbit={"radius":3})" }),
    "camera.orbit.radius: unknown key; allowed keys: azimuth, elevation, distance"));
  EXPECT_TRUE(Contains(LoadError("", { "camera.orbit=30" }), "camera.orbit: expected an object"));
}

} // namespace
