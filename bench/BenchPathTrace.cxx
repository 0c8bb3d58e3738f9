// The path tracer (vtkCloudPathTracer): how fast it converges on the shipped scenes, and how far
// each lighting model of the march is from it. Five commands:
//
//   speed  [--size WxH] [--spp N] [--bounces B] [--brick N] [SCENE.json ...]
//     Renders each scene (default: data/scenes/fbm-sphere.json, two-lights.json, sphere.json)
//     with N paths per pixel, prints paths per second, the image's relative standard error, and
//     the time to 1% relative standard error at 800 x 600 extrapolated from the run (the error
//     falls as 1 / sqrt(paths) and the time grows with the pixels); and, as the peer in the same
//     run, the time of the CPU march of the scene's lighting model (vtkCloudReferenceRenderer).
//   errors [--size WxH] [--spp N] [--bounces B] [--seed S]
//     The table of docs/lighting.md: each model (march, march without octaves, derivative)
//     against the path tracer on the fbm-sphere field and a dense field, lit from the side and
//     from behind, albedo 1 and 0.9, one directional light, no ambient.
//   bounces [--size WxH] [--spp N]
//     The light the bounce cap drops, on the fields of `errors` and two-lights.json at albedo 1.
//   defects [--size WxH] [--spp N]
//     Measures the march's defects one by one (docs/lighting.md, "What the march gets wrong"):
//     the light march's midpoint sampling and reach, the octaves per opacity, and bright
//     isolated pixels of a field that touches the box.
//   fit [--size WxH] [--spp N] [--bounces B] [--seed S] [--split first|stratified] [--voxels N]
//       [--max-octaves N] [--evaluations E] [--png DIR]
//     Fits the march's multiple-scattering octaves (N, a, b, c) and the derivative model's
//     distance h to the path tracer on a fixed case set with held-out cases (docs/lighting.md,
//     "Fitting the march to the path tracer"), and prints the errors before and after, per case
//     and per set, with the light volumes and with the nested light march.
//
// Scenes are read minimally (field, transfer_function, lights, ambient, camera position and view
// angle): enough for the shipped scenes, with a clear refusal of what it does not read.
#include "CloudImageComparison.h"
#include "CloudLightVolumes.h"
#include "CloudMarchUniforms.h"
#include "CloudReferenceMarch.h"
#include "vtkCloudDensitySource.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMath.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkTimerLog.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolumeProperty.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

using namespace cloudvis;
using json = nlohmann::json;

namespace
{

// ---- Scenes ----

struct BenchScene
{
  std::string Name;
  FieldDescription Field;
  glm::ivec3 Dimensions{ 128 };
  std::array<double, 6> Bounds{ { -2.0, 2.0, -2.0, 2.0, -2.0, 2.0 } };
  double Time = 0.0;
  std::vector<std::array<double, 2>> Opacity;
  std::vector<std::array<double, 4>> Color;
  double UnitDistance = 1.0;
  std::vector<Light> Lights;
  LightingParameters Lighting; // model, ambient
  std::optional<glm::dvec3> CameraPosition;
  double ViewAngle = 30.0;
};

[[noreturn]] void Fail(const std::string& message)
{
  throw std::runtime_error(message);
}

glm::vec3 Vec3(const json& v)
{
  return glm::vec3(v.at(0).get<float>(), v.at(1).get<float>(), v.at(2).get<float>());
}

// The subset of the scene format (docs/scene-format.md) the shipped scenes use; anything else
// is refused by name rather than silently ignored.
BenchScene ReadScene(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    Fail(path + ": cannot read the scene file");
  const json scene = json::parse(in, nullptr, false);
  if (scene.is_discarded())
    Fail(path + ": not valid JSON");
  const auto refuse =
    [&path](const json& object, const std::vector<std::string>& known, const std::string& section)
  {
    for (const auto& item : object.items())
      if (std::find(known.begin(), known.end(), item.key()) == known.end())
        Fail(path + ": " + section + item.key() + ": not read by this benchmark");
  };
  refuse(scene,
    { "description", "field", "transfer_function", "lights", "ambient", "camera", "background",
      "render" },
    "");
  BenchScene s;
  s.Name = path.substr(path.find_last_of('/') + 1);
  s.Lighting.AmbientColor = glm::vec3(0.6f, 0.6f, 0.75f); // the scene format's defaults
  s.Lighting.AmbientStrength = 0.2f;
  Light sun;
  sun.Position = glm::vec3(6.0f, 8.0f, 4.0f);
  s.Lights = { sun };

  const json& field = scene.at("field");
  refuse(field,
    { "dimensions",
      "bounds",
      "density_model",
      "density_scale",
      "falloff_width",
      "shape",
      "noise",
      "octaves",
      "lacunarity",
      "lacunarity_increment",
      "gain",
      "amplitude",
      "frequency",
      "seed",
      "wind",
      "time" },
    "field.");
  if (field.contains("dimensions"))
    s.Dimensions = glm::ivec3(field["dimensions"].get<int>());
  if (field.contains("bounds"))
    for (int i = 0; i < 6; ++i)
      s.Bounds[i] = field["bounds"].at(i).get<double>();
  FieldDescription& f = s.Field;
  const std::string model = field.value("density_model", "sdf_plus_fbm");
  if (model == "sdf_plus_fbm")
    f.Model = DensityModel::SdfPlusFbm;
  else if (model == "fbm_falloff")
    f.Model = DensityModel::FbmFalloff;
  else if (model == "constant")
    f.Model = DensityModel::Constant;
  else
    Fail(path + ": field.density_model " + model + ": not read by this benchmark");
  f.DensityScale = field.value("density_scale", 1.0);
  f.FalloffWidth = field.value("falloff_width", f.FalloffWidth);
  if (field.contains("shape"))
  {
    const json& shape = field["shape"];
    if (shape.value("type", "") != "sphere" || shape.size() != 2)
      Fail(path + ": field.shape: only {\"type\": \"sphere\", \"radius\": r} is read");
    f.Shapes[0].Radius = shape.at("radius").get<float>();
  }
  const std::string noise = field.value("noise", "value");
  if (noise == "none")
    f.Noise.Type = noise::NoiseType::None;
  else if (noise == "value")
    f.Noise.Type = noise::NoiseType::Value;
  else if (noise == "perlin")
    f.Noise.Type = noise::NoiseType::Perlin;
  else
    Fail(path + ": field.noise " + noise + ": not read by this benchmark");
  f.Noise.Octaves = field.value("octaves", f.Noise.Octaves);
  f.Noise.Lacunarity = field.value("lacunarity", f.Noise.Lacunarity);
  f.Noise.LacunarityIncrement = field.value("lacunarity_increment", f.Noise.LacunarityIncrement);
  f.Noise.Gain = field.value("gain", f.Noise.Gain);
  f.Noise.Amplitude = field.value("amplitude", f.Noise.Amplitude);
  f.Noise.Frequency = field.value("frequency", f.Noise.Frequency);
  f.Noise.Seed = field.value("seed", f.Noise.Seed);
  if (field.contains("wind"))
    f.Wind = glm::dvec3(Vec3(field["wind"]));
  s.Time = field.value("time", 0.0);

  const json& transfer = scene.at("transfer_function");
  refuse(transfer, { "opacity", "color", "unit_distance" }, "transfer_function.");
  for (const json& point : transfer.at("opacity"))
    s.Opacity.push_back({ point.at(0).get<double>(), point.at(1).get<double>() });
  for (const json& point : transfer.at("color"))
    s.Color.push_back({ point.at(0).get<double>(), point.at(1).get<double>(),
      point.at(2).get<double>(), point.at(3).get<double>() });
  s.UnitDistance = transfer.value("unit_distance", 1.0);

  if (scene.contains("lights"))
  {
    s.Lights.clear();
    for (const json& l : scene["lights"])
    {
      refuse(
        l, { "type", "position", "focal_point", "color", "intensity", "attenuation" }, "lights[].");
      Light light;
      light.Positional = l.at("type").get<std::string>() == "point";
      light.Position = Vec3(l.at("position"));
      if (l.contains("focal_point"))
        light.FocalPoint = Vec3(l["focal_point"]);
      if (l.contains("color"))
        light.Color = Vec3(l["color"]);
      light.Intensity = l.value("intensity", 1.0f);
      if (l.contains("attenuation"))
        light.Attenuation = Vec3(l["attenuation"]);
      s.Lights.push_back(light);
    }
  }
  if (scene.contains("ambient"))
  {
    s.Lighting.AmbientColor = Vec3(scene["ambient"].at("color"));
    s.Lighting.AmbientStrength = scene["ambient"].at("strength").get<float>();
  }
  if (scene.contains("camera"))
  {
    const json& camera = scene["camera"];
    refuse(camera, { "position", "view_angle" }, "camera.");
    if (camera.contains("position"))
      s.CameraPosition = glm::dvec3(Vec3(camera["position"]));
    s.ViewAngle = camera.value("view_angle", 30.0);
  }
  const std::string lighting =
    scene.contains("render") ? scene["render"].value("lighting", "none") : "none";
  s.Lighting.Model = lighting == "march" ? LightingModel::March
    : lighting == "derivative"           ? LightingModel::Derivative
                                         : LightingModel::None;
  return s;
}

vtkSmartPointer<vtkImageData> MakeField(const BenchScene& scene)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(scene.Dimensions.x, scene.Dimensions.y, scene.Dimensions.z);
  source->SetBounds(scene.Bounds.data());
  source->SetField(scene.Field);
  source->SetTime(scene.Time);
  const std::string problem = source->Validate();
  if (!problem.empty())
    Fail(scene.Name + ": field: " + problem);
  source->Update();
  auto field = vtkSmartPointer<vtkImageData>::New();
  field->ShallowCopy(source->GetOutput());
  return field;
}

// The scene's transfer function as the app gives it to every renderer (MakeVolumeProperty in
// app/export), or with every color replaced by the gray `albedo` when that is >= 0.
vtkSmartPointer<vtkVolumeProperty> MakeMedium(const BenchScene& scene, float albedo = -1.0f)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const auto& p : scene.Opacity)
    opacity->AddPoint(p[0], p[1]);
  vtkNew<vtkColorTransferFunction> color;
  for (const auto& p : scene.Color)
    color->AddRGBPoint(p[0],
      albedo >= 0.0f ? albedo : p[1],
      albedo >= 0.0f ? albedo : p[2],
      albedo >= 0.0f ? albedo : p[3]);
  auto medium = vtkSmartPointer<vtkVolumeProperty>::New();
  medium->SetScalarOpacity(opacity);
  medium->SetColor(color);
  medium->SetScalarOpacityUnitDistance(scene.UnitDistance);
  return medium;
}

// The table every renderer builds from it.
TransferTable TableOf(vtkVolumeProperty* medium)
{
  std::string problem;
  TransferTable table = TransferTableOf(medium, 1.0, problem);
  if (!problem.empty())
    Fail(problem);
  return table;
}

// The app's camera (render/OffscreenRender.cxx ApplyCamera) for the scene's keys read here: the
// bounds' centre seen along -z from the distance that fits them, or from camera.position.
void SetSceneCamera(vtkCloudReferenceRenderer* renderer, const BenchScene& scene,
  vtkImageData* field, int width, int height)
{
  vtkNew<vtkRenderer> fit;
  fit->SetAspect(double(width) / double(height), 1.0);
  vtkCamera* camera = fit->GetActiveCamera();
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetPosition(0.0, 0.0, 1.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  double bounds[6];
  field->GetBounds(bounds);
  fit->ResetCamera(bounds);
  const double distance = camera->GetDistance() * std::sin(vtkMath::RadiansFromDegrees(15.0)) /
    std::sin(0.5 * vtkMath::RadiansFromDegrees(scene.ViewAngle));
  camera->SetViewAngle(scene.ViewAngle);
  double focal[3];
  camera->GetFocalPoint(focal);
  const glm::dvec3 position =
    scene.CameraPosition.value_or(glm::dvec3(focal[0], focal[1], focal[2] + distance));
  camera->SetPosition(position.x, position.y, position.z);
  camera->OrthogonalizeViewUp();
  fit->ResetCameraClippingRange(bounds);
  renderer->SetImageSize(width, height);
  renderer->SetCameraPosition(camera->GetPosition());
  renderer->SetCameraFocalPoint(camera->GetFocalPoint());
  renderer->SetCameraViewUp(camera->GetViewUp());
  renderer->SetViewAngle(camera->GetViewAngle());
  renderer->SetClippingRange(camera->GetClippingRange());
}

// ---- Rendering ----

struct Rendered
{
  std::vector<float> RGBA;
  std::vector<float> Variance; // path tracer only
  double Seconds = 0.0;
};

Rendered Run(vtkCloudReferenceRenderer* renderer)
{
  const double start = vtkTimerLog::GetUniversalTime();
  renderer->Modified();
  renderer->Update();
  Rendered result;
  result.Seconds = vtkTimerLog::GetUniversalTime() - start;
  vtkPointData* pd = renderer->GetOutput()->GetPointData();
  auto* rgba = vtkFloatArray::SafeDownCast(pd->GetArray("rgba"));
  if (!rgba)
    Fail("the renderer produced no image");
  result.RGBA.assign(rgba->GetPointer(0), rgba->GetPointer(0) + rgba->GetNumberOfValues());
  if (auto* variance = vtkFloatArray::SafeDownCast(pd->GetArray("rgba_variance")))
    result.Variance.assign(
      variance->GetPointer(0), variance->GetPointer(0) + variance->GetNumberOfValues());
  for (float v : result.RGBA)
    if (!std::isfinite(v))
      Fail("the renderer produced a non-finite pixel");
  return result;
}

// An image composited over black, clamped to [0, 1], as an 8-bit PNG (to look at).
void WritePng(const std::string& directory, const std::string& name, const std::vector<float>& rgba,
  int width, int height)
{
  if (directory.empty())
    return;
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, height, 1);
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetNumberOfComponents(3);
  bytes->SetNumberOfTuples(vtkIdType(width) * height);
  for (vtkIdType p = 0; p < vtkIdType(width) * height; ++p)
    for (int c = 0; c < 3; ++c)
      bytes->SetValue(3 * p + c,
        static_cast<unsigned char>(std::lround(255.0f * std::clamp(rgba[4 * p + c], 0.0f, 1.0f))));
  image->GetPointData()->SetScalars(bytes);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  const std::string path = directory + "/" + name + ".png";
  writer->SetFileName(path.c_str());
  writer->Write();
}

struct Options
{
  std::string PngDirectory; // --png: where to write the images, for a look
  int Width = 200, Height = 150;
  int Samples = 16;
  int Bounces = 1024;
  int BrickSize = 8;
  unsigned Seed = 0;
  int FitDimensions = 64;  // fit: the fields' voxels along each axis (0: the scenes' own)
  int FitMaxOctaves = 6;   // fit: octave counts 1..this are fitted
  int FitEvaluations = 60; // fit: the most objective evaluations per octave count
  std::string FitSplit = "stratified"; // fit: which fields are held out
  std::vector<std::string> Scenes;
};

// A march of the scene's field through its camera at the benchmark's size, with this transfer
// function, lighting and lights.
vtkSmartPointer<vtkCloudReferenceRenderer> NewMarch(const BenchScene& scene,
  vtkImageData* field,
  vtkVolumeProperty* medium,
  const LightingParameters& lighting,
  const std::vector<Light>& lights,
  const Options& options)
{
  auto march = vtkSmartPointer<vtkCloudReferenceRenderer>::New();
  march->SetInputData(field);
  SetSceneCamera(march, scene, field, options.Width, options.Height);
  march->SetVolumeProperty(medium);
  march->GetLightingProperty()->SetParameters(lighting);
  march->SetLights(MakeLights(lights));
  return march;
}

// The same as a path tracer with the benchmark's paths per pixel, brick size and seed.
vtkSmartPointer<vtkCloudPathTracer> NewTracer(const BenchScene& scene,
  vtkImageData* field,
  vtkVolumeProperty* medium,
  const std::vector<Light>& lights,
  int maxBounces,
  const Options& options)
{
  auto tracer = vtkSmartPointer<vtkCloudPathTracer>::New();
  tracer->SetInputData(field);
  SetSceneCamera(tracer, scene, field, options.Width, options.Height);
  tracer->SetVolumeProperty(medium);
  tracer->GetLightingProperty()->SetParameters(scene.Lighting);
  tracer->SetLights(MakeLights(lights));
  tracer->SetSamplesPerPixel(options.Samples);
  tracer->SetMaxBounces(maxBounces);
  tracer->SetBrickSize(options.BrickSize);
  tracer->SetSeed(options.Seed);
  return tracer;
}

// ---- speed ----

int Speed(const Options& options)
{
  std::vector<std::string> files = options.Scenes;
  if (files.empty())
    files = { "data/scenes/fbm-sphere.json", "data/scenes/two-lights.json",
      "data/scenes/sphere.json" };
  std::vector<BenchScene> scenes;
  for (const std::string& file : files)
    scenes.push_back(ReadScene(file)); // every scene checked before anything is printed
  std::printf("%d x %d, %d paths per pixel, bounce cap %d, bricks of %d voxels, vtkSMPTools %s "
              "with %d threads\n\n",
    options.Width, options.Height, options.Samples, options.Bounces, options.BrickSize,
    vtkSMPTools::GetBackend(), vtkSMPTools::GetEstimatedNumberOfThreads());
  std::printf("| scene | path tracer | paths/s (all pixels) | paths/s (cloud pixels) | relative "
              "standard error | time to 1%% at 800x600 | CPU march (%s) | one path per pixel "
              "costs |\n|---|---|---|---|---|---|---|---|\n",
    "scene's model");
  for (const BenchScene& scene : scenes)
  {
    const vtkSmartPointer<vtkImageData> field = MakeField(scene);
    const auto medium = MakeMedium(scene);

    const Rendered traced =
      Run(NewTracer(scene, field, medium, scene.Lights, options.Bounces, options));
    const Rendered marched =
      Run(NewMarch(scene, field, medium, scene.Lighting, scene.Lights, options));

    WritePng(
      options.PngDirectory, scene.Name + "-pathtrace", traced.RGBA, options.Width, options.Height);
    WritePng(
      options.PngDirectory, scene.Name + "-march", marched.RGBA, options.Width, options.Height);
    const std::size_t pixels = std::size_t(options.Width) * options.Height;
    const ImageNoise noise = MeasureImageNoise(traced.RGBA.data(), traced.Variance.data(), pixels);
    const double paths = double(pixels) * options.Samples;
    const double samplesNeeded =
      options.Samples * std::pow(noise.RelativeStandardError / 0.01, 2.0);
    const double seconds800x600 =
      traced.Seconds / options.Samples * samplesNeeded * (800.0 * 600.0) / double(pixels);
    std::printf("| %s | %.2f s | %.0f | %.0f | %.2f%% | %.0f s (%.0f paths per pixel) | %.3f s | "
                "%.1f march images |\n",
      scene.Name.c_str(), traced.Seconds, paths / traced.Seconds,
      double(noise.Pixels) * options.Samples / traced.Seconds, 100.0 * noise.RelativeStandardError,
      seconds800x600, samplesNeeded, marched.Seconds,
      traced.Seconds / options.Samples / marched.Seconds);
    std::fflush(stdout);
  }
  std::printf("\n(time to 1%%: extrapolated from this run, the error falling as 1 / sqrt(paths) "
              "and the time growing with the pixels; the footprint is the pixels of opacity > "
              "%.2f)\n",
    double(FootprintOpacity));
  return 0;
}

// ---- errors ----

// The fields of the table: the fbm-sphere scene's, and a dense one (a sphere of radius 1.8
// filling the same box, the same noise, extinction up to 3.2 per unit length).
struct ErrorField
{
  const char* Name;
  BenchScene Scene;
};

std::vector<ErrorField> ErrorFields()
{
  BenchScene fbm = ReadScene("data/scenes/fbm-sphere.json");
  BenchScene dense = fbm;
  dense.Name = "dense";
  dense.Field.Shapes[0].Radius = 1.8f;
  dense.UnitDistance = 0.5;
  for (BenchScene* s : { &fbm, &dense })
    s->Lighting.AmbientStrength = 0.0f;
  return { { "fbm-sphere", fbm }, { "dense", dense } };
}

struct ErrorModel
{
  const char* Name;
  LightingModel Model;
  int Octaves;
  bool UniformLightSteps; // 64 uniform light steps spanning the volume's diagonal
  bool SingleScattering;  // compared with the path tracer restricted to one bounce
  bool AlbedoOneOnly;     // single scattering scales with the albedo: one albedo says it all
  bool Nested;            // the nested light march rather than the light volumes
};

// The mean of r, g, b over the footprint of an image.
double MeanRadiance(const Rendered& image)
{
  return MeasureImageNoise(image.RGBA.data(), image.RGBA.data(), image.RGBA.size() / 4)
    .MeanRadiance;
}

int Errors(const Options& options)
{
  const ErrorModel models[] = {
    { "march (defaults: light volumes, 3 octaves)", LightingModel::March, 3, false, false, false,
      false },
    { "march, nested light march (6 growing steps), 3 octaves", LightingModel::March, 3, false,
      false, false, true },
    { "march, no octaves", LightingModel::March, 0, false, false, false, false },
    { "derivative", LightingModel::Derivative, 0, false, false, false, false },
    { "single scattering: march, no octaves (light volumes)", LightingModel::March, 0, false, true,
      true, false },
    { "single scattering: march, no octaves, nested light march", LightingModel::March, 0, false,
      true, true, true },
    { "single scattering: march, no octaves, 64 uniform light steps", LightingModel::March, 0, true,
      true, true, true },
  };
  const struct
  {
    const char* Name;
    glm::vec3 TowardLight;
  } lightings[] = { { "side-lit", { 1.0f, 0.0f, 0.0f } },
    { "backlit", glm::normalize(glm::vec3(0.2f, 0.3f, -1.0f)) } };
  std::printf("%d x %d, path tracer %d paths per pixel, bounce cap %d\n\n", options.Width,
    options.Height, options.Samples, options.Bounces);
  std::printf("| field | light | albedo | model | relative RMSE | noise-corrected | bias (ratio "
              "of means) | max error / peak | reference's relative standard error |\n"
              "|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> albedoRatios, settingDifferences;
  for (const ErrorField& errorField : ErrorFields())
  {
    const BenchScene& scene = errorField.Scene;
    const vtkSmartPointer<vtkImageData> field = MakeField(scene);
    double bounds[6];
    field->GetBounds(bounds);
    const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
      (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
    for (const auto& lit : lightings)
    {
      Light light;
      light.Position = 10.0f * lit.TowardLight;
      double fullMean[2] = { 0.0, 0.0 };
      double marchMean[2] = { 0.0, 0.0 }; // march with its defaults (models[0])
      for (float albedo : { 1.0f, 0.9f })
      {
        const auto medium = MakeMedium(scene, albedo);
        const std::string label = std::string(errorField.Name) + "-" + lit.Name + "-albedo" +
          (albedo == 1.0f ? "1" : "0.9");
        std::vector<Rendered> references(2); // every order of scattering, single scattering
        Rendered volumesImage;                // march with its defaults: the light volumes
        for (const ErrorModel& model : models)
        {
          if (model.AlbedoOneOnly && albedo != 1.0f)
            continue;
          Rendered& reference = references[model.SingleScattering ? 1 : 0];
          if (reference.RGBA.empty())
          {
            reference = Run(NewTracer(scene,
              field,
              medium,
              { light },
              model.SingleScattering ? 1 : options.Bounces,
              options));
            WritePng(options.PngDirectory,
              label + (model.SingleScattering ? "-pathtrace1" : "-pathtrace"), reference.RGBA,
              options.Width, options.Height);
          }
          LightingParameters lighting = scene.Lighting;
          lighting.Model = model.Model;
          lighting.MultipleScatteringOctaves = model.Octaves;
          lighting.Transmittance =
            model.Nested ? LightTransmittance::Nested : LightTransmittance::Volumes;
          if (model.UniformLightSteps)
          {
            lighting.LightSteps = 64;
            lighting.LightStepGrowth = 1.0f;
            lighting.LightStep = float(diagonal / 64.0);
          }
          const Rendered image = Run(NewMarch(scene, field, medium, lighting, { light }, options));
          WritePng(options.PngDirectory,
            label + "-" + (model.Model == LightingModel::Derivative ? "derivative" : "march") +
              std::to_string(model.Octaves) + (model.UniformLightSteps ? "u" : "") +
              (model.Nested ? "n" : ""),
            image.RGBA, options.Width, options.Height);
          if (&model == &models[0])
          {
            marchMean[albedo == 1.0f ? 0 : 1] = MeanRadiance(image);
            volumesImage = image;
          }
          if (&model == &models[1]) // the two settings against each other, noise-free
          {
            const std::vector<float> exact(image.RGBA.size(), 0.0f);
            const ImageError d = CompareWithReference(volumesImage.RGBA.data(), image.RGBA.data(),
              exact.data(), std::size_t(options.Width) * options.Height);
            char line[200];
            std::snprintf(line, sizeof(line), "| %s | %s | %.1f | %.2f%% | %.4f | %.2f%% |",
              errorField.Name, lit.Name, double(albedo), 100.0 * d.RelativeRMSE, d.BiasRatio,
              100.0 * d.MaxErrorOverPeak);
            settingDifferences.push_back(line);
          }
          const ImageError e = CompareWithReference(image.RGBA.data(), reference.RGBA.data(),
            reference.Variance.data(), std::size_t(options.Width) * options.Height);
          std::printf("| %s | %s | %.1f | %s | %.1f%% | %.1f%% | %.3f | %.1f%% | %.2f%% |\n",
            errorField.Name, lit.Name, double(albedo), model.Name, 100.0 * e.RelativeRMSE,
            100.0 * e.NoiseCorrectedRelativeRMSE, e.BiasRatio, 100.0 * e.MaxErrorOverPeak,
            100.0 * e.ReferenceRelativeStandardError);
          std::fflush(stdout);
        }
        fullMean[albedo == 1.0f ? 0 : 1] = MeanRadiance(references[0]);
      }
      char line[200];
      std::snprintf(line,
        sizeof(line),
        "| %s | %s | %.3f | %.3f |",
        errorField.Name,
        lit.Name,
        fullMean[1] / fullMean[0],
        marchMean[1] / marchMean[0]);
      albedoRatios.push_back(line);
    }
  }
  std::printf("\nImage at albedo 0.9 over image at albedo 1 (means over the footprint):\n\n"
              "| field | light | path tracer | march (defaults) |\n|---|---|---|---|\n");
  for (const std::string& line : albedoRatios)
    std::printf("%s\n", line.c_str());
  std::printf("\nmarch (defaults) with light volumes against the nested light march (the "
              "nested image as the reference):\n\n| field | light | albedo | relative RMSE | "
              "bias | max error / peak |\n|---|---|---|---|---|---|\n");
  for (const std::string& line : settingDifferences)
    std::printf("%s\n", line.c_str());
  return 0;
}

// ---- bounces ----

// The light the bounce cap drops: the same paths (same seed) with the cap and with no cap in
// practice (2^24) differ only by the paths that reach the cap, so the difference of the image
// means (of the green channel, over all pixels) is that loss, nearly free of noise.
int Bounces(const Options& options)
{
  std::printf("%d x %d, %d paths per pixel; loss = 1 - mean(cap) / mean(no cap)\n\n", options.Width,
    options.Height, options.Samples);
  std::printf("| scene | cap | image mean | loss | relative standard error of the image mean | "
              "time |\n"
              "|---|---|---|---|---|---|\n");
  std::vector<ErrorField> fields = ErrorFields();
  fields.push_back({ "two-lights", ReadScene("data/scenes/two-lights.json") });
  for (ErrorField& errorField : fields)
  {
    BenchScene& scene = errorField.Scene;
    const vtkSmartPointer<vtkImageData> field = MakeField(scene);
    const auto medium = MakeMedium(scene, 1.0f); // the longest paths
    Light sun;
    sun.Position = glm::vec3(10.0f, 0.0f, 0.0f);
    double uncapped = 0.0;
    for (int cap : { 1 << 24, 8, 16, 32, 64, 128, 1024 })
    {
      const Rendered image = Run(NewTracer(scene,
        field,
        medium,
        scene.Name == "two-lights.json" ? scene.Lights : std::vector<Light>{ sun },
        cap,
        options));
      // The green channel's mean over all pixels, and its standard error (pixels independent).
      double mean = 0.0, variance = 0.0;
      const std::size_t pixels = image.RGBA.size() / 4;
      for (std::size_t p = 0; p < pixels; ++p)
      {
        mean += image.RGBA[4 * p + 1] / double(pixels);
        variance += image.Variance[4 * p + 1] / (double(pixels) * double(pixels));
      }
      if (cap == (1 << 24))
        uncapped = mean;
      std::printf("| %s | %d | %.5f | %.2e | %.2e | %.1f s |\n", errorField.Name, cap, mean,
        1.0 - mean / uncapped, std::sqrt(variance) / mean, image.Seconds);
      std::fflush(stdout);
    }
  }
  return 0;
}

// ---- defects ----

// The uniforms the CPU march gets for a field (as vtkCloudReferenceRenderer builds them for a
// float field with an identity direction matrix, which is what the benchmark generates).
// The march's uniforms for the field and table with the default lighting, as the renderers set
// them up (SetUpMarch), and the local frame they are in.
MarchUniforms UniformsOf(vtkImageData* field, const TransferTable& table, LocalFrame& frame)
{
  MarchSetup setup;
  setup.Geometry = GeometryOf(field, nullptr);
  setup.Table = &table;
  MarchUniforms u;
  const MarchProblem problem = SetUpMarch(setup, u, &frame);
  if (problem)
    Fail("the field cannot be marched: " + problem.Message);
  u.Density = DensityTexelsOf(field->GetPointData()->GetScalars());
  return u;
}

// The optical depth from index point p along the direction l over [s0, s1] (local units), by
// the midpoint rule with steps of 1/16 of the smallest voxel: the exact integral to 1e-4.
double OpticalDepth(
  const MarchUniforms& u, const LocalFrame& frame, glm::vec3 p, glm::vec3 l, double s0, double s1)
{
  const double ds = frame.SmallestVoxelEdge / frame.Unit / 16.0;
  const glm::vec3 indexStep = LocalToIndex(u, l);
  double tau = 0.0;
  for (double s = s0 + 0.5 * ds; s < s1; s += ds)
  {
    const glm::vec3 q = p + float(s) * indexStep;
    if (InsideVolume(u, q))
      tau += ExtinctionAt(u, q) * std::min(ds, s1 - (s - 0.5 * ds));
  }
  return tau;
}

struct Percentiles
{
  std::vector<double> Values;
  std::string Format(const char* unit = "") const
  {
    std::vector<double> v = this->Values;
    if (v.empty())
      return "-";
    std::sort(v.begin(), v.end());
    double mean = 0.0;
    for (double x : v)
      mean += x;
    mean /= double(v.size());
    char text[160];
    std::snprintf(text, sizeof(text), "mean %.4f%s, 5%% %.4f, median %.4f, 95%% %.4f, max %.4f",
      mean, unit, v[v.size() / 20], v[v.size() / 2], v[v.size() * 19 / 20], v.back());
    return text;
  }
};

// The light march's transmittance at sample points of the cloud against the exact one over the
// same way (to the volume's exit): what its segments and their quadrature make of the field.
void LightMarchErrors(const char* name, vtkImageData* field, const TransferTable& table)
{
  LocalFrame frame;
  const MarchUniforms u = UniformsOf(field, table, frame);
  const LightingParameters& l = u.Lighting;                  // lengths in local units
  const double voxel = frame.SmallestVoxelEdge / frame.Unit; // local units
  std::printf("\n%s: %d light steps growing %.2f to the volume's exit, the first at least %.4f "
              "(%.1f voxels; the volume's diagonal is %.2f)\n",
    name,
    l.LightSteps,
    double(l.LightStepGrowth),
    l.LightStep * frame.Unit,
    l.LightStep / voxel,
    frame.LongestChord * frame.Unit);
  for (const glm::vec3 toward : { glm::vec3(1, 0, 0), glm::normalize(glm::vec3(0.2f, 0.3f, -1)) })
  {
    Percentiles ratio;
    int samples = 0;
    for (int k = 2; k < u.Dimensions.z - 2; k += 3)
      for (int j = 2; j < u.Dimensions.y - 2; j += 3)
        for (int i = 2; i < u.Dimensions.x - 2; i += 3)
        {
          // Off the lattice, as view samples are.
          const glm::vec3 p(i + 0.37f, j + 0.61f, k + 0.23f);
          const float sigma = ExtinctionAt(u, p);
          if (!(sigma > 0.0f))
            continue;
          ++samples;
          const glm::vec3 indexStep = LocalToIndex(u, toward);
          const float tauMarch = LightOpticalDepth(u, p, sigma, indexStep, 1e30f);
          const glm::vec2 exit =
            IntersectBox(p, indexStep, glm::vec3(0.0f), glm::vec3(u.Dimensions - 1));
          const double tauExact = OpticalDepth(u, frame, p, toward, 0.0, exit.y);
          ratio.Values.push_back(std::exp(tauExact - tauMarch));
        }
    std::printf("  light toward (%.2f, %.2f, %.2f), %d cloud samples: transmittance / exact to "
                "the exit: %s\n",
      double(toward.x),
      double(toward.y),
      double(toward.z),
      samples,
      ratio.Format().c_str());
  }
}

// Where a model's image is too bright or too dark: the ratio of its mean to the path tracer's
// over pixels binned by the path tracer's opacity (thin edges to dense cores).
void OpacityBins(const char* label, const Rendered& image, const Rendered& reference)
{
  const double edges[] = { 0.01, 0.3, 0.7, 0.95, 0.99, 1.01 };
  std::printf("  %s:", label);
  for (int b = 0; b + 1 < int(sizeof(edges) / sizeof(edges[0])); ++b)
  {
    double sum = 0.0, referenceSum = 0.0;
    int pixels = 0;
    for (std::size_t p = 0; p < image.RGBA.size() / 4; ++p)
    {
      const float alpha = reference.RGBA[4 * p + 3];
      if (alpha >= edges[b] && alpha < edges[b + 1])
      {
        ++pixels;
        for (int c = 0; c < 3; ++c)
        {
          sum += image.RGBA[4 * p + c];
          referenceSum += reference.RGBA[4 * p + c];
        }
      }
    }
    if (pixels > 0)
      std::printf(" opacity [%.2f, %.2f): %.2f (%d px);", edges[b], std::min(edges[b + 1], 1.0),
        sum / referenceSum, pixels);
  }
  std::printf("\n");
}

// Pixels more than `factor` times brighter than the median of their 8 neighbours.
std::vector<int> Outliers(const Rendered& image, int width, int height, double factor)
{
  std::vector<int> outliers;
  const auto luminance = [&](int i, int j)
  {
    const float* p = &image.RGBA[(std::size_t(j) * width + i) * 4];
    return double(p[0] + p[1] + p[2]);
  };
  for (int j = 1; j + 1 < height; ++j)
    for (int i = 1; i + 1 < width; ++i)
    {
      std::vector<double> around;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          if (di || dj)
            around.push_back(luminance(i + di, j + dj));
      std::nth_element(around.begin(), around.begin() + 4, around.end());
      if (luminance(i, j) > factor * around[4] && luminance(i, j) > 1e-3)
        outliers.push_back(j * width + i);
    }
  return outliers;
}

int Defects(const Options& options)
{
  std::printf("The march's defects, measured (%d x %d images, path tracer %d paths per pixel).\n",
    options.Width, options.Height, options.Samples);
  for (const ErrorField& errorField : ErrorFields())
  {
    const BenchScene& scene = errorField.Scene;
    const vtkSmartPointer<vtkImageData> field = MakeField(scene);
    const TransferTable table = TableOf(MakeMedium(scene));
    LightMarchErrors(errorField.Name, field, table);

    // The octaves against the path tracer, per opacity bin, side-lit, albedo 1 and 0.9.
    Light side;
    side.Position = glm::vec3(10.0f, 0.0f, 0.0f);
    for (float albedo : { 1.0f, 0.9f })
    {
      const auto gray = MakeMedium(scene, albedo);
      const Rendered reference =
        Run(NewTracer(scene, field, gray, { side }, options.Bounces, options));
      LightingParameters lighting = scene.Lighting;
      lighting.Model = LightingModel::March;
      auto march = NewMarch(scene, field, gray, lighting, { side }, options);
      char label[120];
      std::snprintf(label, sizeof(label), "side-lit, albedo %.1f, march (defaults) / path tracer",
        double(albedo));
      OpacityBins(label, Run(march), reference);
      lighting.LightSteps = 12; // twice the segments, over the same way to the exit
      march->GetLightingProperty()->SetParameters(lighting);
      std::snprintf(label, sizeof(label),
        "side-lit, albedo %.1f, march with 12 growing light "
        "steps / path tracer",
        double(albedo));
      OpacityBins(label, Run(march), reference);
    }
  }

  // A field that fills its box (the fbm sphere with radius 2.5 in [-2, 2]^3), lit from the side
  // along the box's front face: view rays enter through that face, and their first sample lies
  // on it. Where rounding puts it a hair outside, the light march finds no midpoint inside and
  // the sample is lit unshadowed.
  BenchScene filling = ReadScene("data/scenes/fbm-sphere.json");
  filling.Field.Shapes[0].Radius = 2.5f;
  filling.Lighting.AmbientStrength = 0.0f;
  const vtkSmartPointer<vtkImageData> field = MakeField(filling);
  const auto medium = MakeMedium(filling, 1.0f);
  const TransferTable table = TableOf(medium);
  LocalFrame frame;
  const MarchUniforms u = UniformsOf(field, table, frame);
  Light side;
  side.Position = glm::vec3(10.0f, 0.0f, 0.0f);
  std::printf("\nbox-filling field (radius 2.5), side-lit along the front face, albedo 1, "
              "march (defaults), pixels of opacity > 0.5:\n");
  for (double step : { 0.0, 0.005 })
  {
    LightingParameters lighting = filling.Lighting;
    lighting.Model = LightingModel::March;
    auto march = NewMarch(filling, field, medium, lighting, { side }, options);
    march->SetSampleDistance(step);
    const Rendered image = Run(march);
    glm::dmat4 viewToDevice;
    glm::dmat3 worldToView;
    glm::dvec3 eye;
    if (!march->GetCamera(viewToDevice, worldToView, eye))
      Fail("unusable camera");
    const glm::dmat4 deviceToLocal = DeviceToLocal(frame, viewToDevice, worldToView, eye);
    // Whether the first sample of a pixel's ray lies outside the volume (InsideVolume false):
    // the ray set-up of MarchRay, repeated to see that sample.
    const auto firstSampleOutside = [&](int pixel)
    {
      glm::dvec3 nearPoint, farPoint;
      vtkCloudReferenceRenderer::PixelRay(deviceToLocal, pixel % options.Width,
        pixel / options.Width, options.Width, options.Height, nearPoint, farPoint);
      const glm::vec3 toFar = glm::vec3(farPoint) - glm::vec3(nearPoint);
      const glm::vec3 origin = IndexOfLocal(u, glm::vec3(nearPoint));
      const glm::vec3 direction = LocalToIndex(u, toFar / glm::length(toFar));
      const glm::vec2 tBox =
        IntersectBox(origin, direction, glm::vec3(0.0f), glm::vec3(u.Dimensions) - 1.0f);
      return !InsideVolume(u, origin + std::max(tBox.x, 0.0f) * direction);
    };
    std::vector<int> isOutlier(std::size_t(options.Width) * options.Height, 0);
    for (int pixel : Outliers(image, options.Width, options.Height, 3.0))
      isOutlier[pixel] = 1;
    int dense = 0, outside = 0, outliers = 0, outlierOutside = 0;
    double radiance[2] = { 0.0, 0.0 };
    for (int pixel = 0; pixel < options.Width * options.Height; ++pixel)
    {
      if (image.RGBA[4 * pixel + 3] < 0.5f)
        continue;
      const bool out = firstSampleOutside(pixel);
      ++dense;
      outside += out;
      outliers += isOutlier[pixel];
      outlierOutside += isOutlier[pixel] && out;
      radiance[out] += image.RGBA[4 * pixel];
    }
    std::printf("  step %s: %d of %d pixels have their first sample outside by rounding, and are "
                "on average %.1fx brighter than the others; %d pixels are > 3x the median of "
                "their neighbours, %d of them with the first sample outside\n",
      step > 0.0 ? "0.005" : "default (1 voxel)", outside, dense,
      (radiance[1] / std::max(outside, 1)) / (radiance[0] / std::max(dense - outside, 1)), outliers,
      outlierOutside);
  }
  return 0;
}

// ---- fit ----

// The fit of the march's multiple-scattering octaves (N, a, b, c) and of the derivative model's
// distance h to the path tracer (docs/lighting.md, "Fitting the march to the path tracer").
//
// The case set is fixed here: seven fields, each lit by one white directional light from four
// directions, with a uniform gray albedo of 1, 0.9 or 0.7 over the field's own transfer-function
// opacity, no ambient. Fields: fbm-sphere, perlin-falloff and sphere (shipped scenes; the last
// optically thin), dense (the `errors` table's), fbm-box (fBm on a box filling most of the
// volume), thick-sphere (sphere.json 8 times denser) and sparse (the fbm noise on a sphere of
// radius 0.5: wisps).
//
// The split (--split): a case is held out when its field is one of the split's held-out fields,
// or when it is lit from above (a direction no training case has) at albedo 0.9 (an albedo no
// training case has). Training cases are lit from the side, behind and in front at albedo 1 and
// 0.7; held-out fields from the side, behind and above at albedo 1 and 0.9.
//   "first": held-out fields perlin-falloff, sphere, sparse. Chosen before any fit; it turned out
//     to hold out every optically thin field, so the training set had none (docs/lighting.md).
//   "stratified" (the default): held-out fields fbm-box, perlin-falloff, sparse; the training
//     set has a field of each kind the held-out set has (thin: sphere; fbm noise: fbm-sphere;
//     dense: dense). Chosen after the "first" split's fit, before its own.
struct FitField
{
  std::string Name;
  BenchScene Scene;
  bool HeldOut = false;
};

std::vector<FitField> FitFields(const std::string& split)
{
  const BenchScene fbm = ReadScene("data/scenes/fbm-sphere.json");
  BenchScene dense = fbm; // the `errors` table's dense field: a sphere that touches the box
  dense.Field.Shapes[0].Radius = 1.8f;
  dense.UnitDistance = 0.5;
  BenchScene box = fbm; // fBm on a box filling most of the volume, extinction up to 6.4
  box.Field.Shapes[0].Type = ShapeType::Box;
  box.Field.Shapes[0].HalfSize = glm::vec3(1.5f, 1.0f, 1.5f);
  box.UnitDistance = 0.25;
  BenchScene sphere = ReadScene("data/scenes/sphere.json"); // optical radius 0.51
  BenchScene thick = sphere; // the same sphere 8 times denser: optical radius 4.1
  thick.Field.DensityScale = 8.0;
  thick.Opacity = { { 0.0, 0.0 }, { 8.0, 0.4 } };
  BenchScene sparse = fbm; // wisps: the fbm noise on a sphere of radius 0.5
  sparse.Field.Shapes[0].Radius = 0.5f;
  std::vector<FitField> fields = { { "fbm-sphere", fbm },
    { "dense", dense },
    { "fbm-box", box },
    { "thick-sphere", thick },
    { "perlin-falloff", ReadScene("data/scenes/perlin-falloff.json") },
    { "sphere", sphere },
    { "sparse", sparse } };
  std::vector<std::string> heldOut;
  if (split == "first")
    heldOut = { "perlin-falloff", "sphere", "sparse" };
  else if (split == "stratified")
    heldOut = { "fbm-box", "perlin-falloff", "sparse" };
  else
    Fail("--split " + split + ": not a split (first, stratified)");
  for (FitField& f : fields)
  {
    f.Scene.Name = f.Name;
    f.Scene.Lighting.AmbientStrength = 0.0f;
    f.HeldOut = std::find(heldOut.begin(), heldOut.end(), f.Name) != heldOut.end();
  }
  return fields;
}

struct FitLight
{
  const char* Name;
  glm::vec3 TowardLight; // the eye looks along -z
};

const FitLight FitLights[] = { { "side", { 1.0f, 0.0f, 0.0f } },
  { "back", glm::normalize(glm::vec3(0.2f, 0.3f, -1.0f)) },
  { "front", glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f)) },
  { "above", { 0.0f, 1.0f, 0.0f } } };
const float FitAlbedos[] = { 1.0f, 0.9f, 0.7f };

// The split, as a rule on (field, light, albedo): every combination is one of training, held
// out, or not used (to bound the running time).
enum class FitRole
{
  Training,
  HeldOut,
  Unused,
};

FitRole RoleOf(const FitField& field, const FitLight& light, float albedo)
{
  const bool above = std::strcmp(light.Name, "above") == 0;
  if (!field.HeldOut)
  {
    if (above)
      return albedo == 0.9f ? FitRole::HeldOut : FitRole::Unused;
    return albedo == 0.9f ? FitRole::Unused : FitRole::Training;
  }
  return std::strcmp(light.Name, "front") == 0 || albedo == 0.7f ? FitRole::Unused
                                                                 : FitRole::HeldOut;
}

// The march of one case with its light volumes computed once: the octaves (N, a, b, c) change
// only how the optical depth toward the light becomes scattered light, not the optical depth, so
// a fit that changes nothing else need not recompute the volumes at each evaluation (nor does the
// GPU: docs/lighting.md, "Light volumes"). It marches each pixel as vtkCloudReferenceRenderer
// does (Fit checks that the two images are identical at the defaults).
struct PreparedMarch
{
  TransferTable Table;
  MarchUniforms Uniforms;
  LightVolumes Volumes;
  glm::dmat4 DeviceToLocal;
  int Width = 0, Height = 0;

  PreparedMarch(vtkCloudReferenceRenderer* renderer, vtkImageData* field)
  {
    std::string tableProblem;
    this->Table =
      TransferTableOf(renderer->GetVolumeProperty(), renderer->GetExtinctionScale(), tableProblem);
    if (!tableProblem.empty())
      Fail(tableProblem);
    const MarchSetup setup = MakeMarchSetup(field,
      renderer->GetVolumeMatrix(),
      DensityTexelsOf(field->GetPointData()->GetScalars()),
      &this->Table,
      renderer->GetSampleDistance(),
      renderer->GetTerminationTransmittance(),
      renderer->GetLightingProperty(),
      renderer->GetLights());
    LocalFrame frame;
    const MarchProblem problem = SetUpMarch(setup, this->Uniforms, &frame);
    if (problem)
      Fail("the field cannot be marched: " + problem.Message);
    if (this->Uniforms.Lighting.Transmittance != LightTransmittance::Volumes)
      Fail("a prepared march reads light volumes");
    ComputeLightVolumes(this->Uniforms, this->Volumes);
    this->Uniforms.LightDepths = &this->Volumes;
    glm::dmat4 viewToDevice;
    glm::dmat3 worldToView;
    glm::dvec3 eye;
    if (!renderer->GetCamera(viewToDevice, worldToView, eye))
      Fail("unusable camera");
    this->DeviceToLocal = cloudvis::DeviceToLocal(frame, viewToDevice, worldToView, eye);
    const int* size = renderer->GetImageSize();
    this->Width = size[0];
    this->Height = size[1];
  }

  // The image with these octaves (the other lighting parameters as prepared).
  std::vector<float> Render(const LightingParameters& octaves)
  {
    this->Uniforms.Lighting.MultipleScatteringOctaves = octaves.MultipleScatteringOctaves;
    this->Uniforms.Lighting.ScatteringFalloff = octaves.ScatteringFalloff;
    this->Uniforms.Lighting.ExtinctionFalloff = octaves.ExtinctionFalloff;
    this->Uniforms.Lighting.EccentricityFalloff = octaves.EccentricityFalloff;
    std::vector<float> rgba(std::size_t(this->Width) * this->Height * 4);
    vtkSMPTools::For(0,
      this->Height,
      [&](int begin, int end)
      {
        for (int j = begin; j < end; ++j)
          for (int i = 0; i < this->Width; ++i)
          {
            glm::dvec3 nearPoint, farPoint;
            vtkCloudReferenceRenderer::PixelRay(
              this->DeviceToLocal, i, j, this->Width, this->Height, nearPoint, farPoint);
            const glm::vec4 color =
              MarchRay(this->Uniforms, glm::vec3(nearPoint), glm::vec3(farPoint));
            std::copy(&color.r, &color.r + 4, &rgba[(std::size_t(j) * this->Width + i) * 4]);
          }
      });
    return rgba;
  }
};

struct FitCase
{
  std::string Name;
  bool HeldOut = false;
  Rendered Reference;
  vtkSmartPointer<vtkCloudReferenceRenderer> March; // its lighting is set per evaluation
  std::unique_ptr<PreparedMarch> Octaves;           // the same march, for the octaves' fit
  double ReferenceSeconds = 0.0;
  double VoxelEdge = 0.0; // the field's smallest voxel edge, world units
};

// The errors of the march with these lighting parameters on each case (of one set only when
// `only` is given: the objective renders the training cases alone). With `octavesOnly` the
// prepared marches render, with `lighting`'s octaves and the rest as prepared.
std::vector<ImageError> FitErrors(std::vector<FitCase>& cases,
  const std::function<LightingParameters(const FitCase&)>& lightingOf,
  bool octavesOnly = false,
  std::optional<bool> onlyHeldOut = std::nullopt)
{
  std::vector<ImageError> errors(cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i)
  {
    FitCase& c = cases[i];
    if (onlyHeldOut && c.HeldOut != *onlyHeldOut)
      continue;
    const LightingParameters lighting = lightingOf(c);
    std::vector<float> image;
    if (octavesOnly)
      image = c.Octaves->Render(lighting);
    else
    {
      c.March->GetLightingProperty()->SetParameters(lighting);
      image = Run(c.March).RGBA;
    }
    errors[i] = CompareWithReference(
      image.data(), c.Reference.RGBA.data(), c.Reference.Variance.data(), image.size() / 4);
  }
  return errors;
}

// The same lighting for every case.
std::vector<ImageError> FitErrors(std::vector<FitCase>& cases,
  const LightingParameters& lighting,
  bool octavesOnly = false,
  std::optional<bool> onlyHeldOut = std::nullopt)
{
  return FitErrors(
    cases, [&lighting](const FitCase&) { return lighting; }, octavesOnly, onlyHeldOut);
}

// The objective: the mean over the training cases of the noise-corrected relative RMSE (each
// case counts the same, whatever its brightness; the reference's noise, which no parameter can
// explain, is taken out).
double MeanError(const std::vector<FitCase>& cases,
  const std::vector<ImageError>& errors,
  bool heldOut)
{
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (cases[i].HeldOut == heldOut)
    {
      sum += errors[i].NoiseCorrectedRelativeRMSE;
      ++n;
    }
  return n ? sum / n : 0.0;
}

// Nelder-Mead in a box: points are clamped into [lower, upper] before they are evaluated, the
// simplex starts at `start` with edges of `step`, and stops when its values differ by less than
// `tolerance` or after `maxEvaluations`.
template<std::size_t D>
std::pair<std::array<double, D>, double> NelderMead(
  const std::function<double(const std::array<double, D>&)>& f,
  std::array<double, D> start,
  const std::array<double, D>& step,
  const std::array<double, D>& lower,
  const std::array<double, D>& upper,
  double tolerance,
  int maxEvaluations)
{
  using Point = std::array<double, D>;
  const auto clamp = [&](Point p)
  {
    for (std::size_t i = 0; i < D; ++i)
      p[i] = std::clamp(p[i], lower[i], upper[i]);
    return p;
  };
  int evaluations = 0;
  const auto value = [&](const Point& p)
  {
    ++evaluations;
    return f(p);
  };
  std::vector<std::pair<Point, double>> simplex;
  start = clamp(start);
  simplex.push_back({ start, value(start) });
  for (std::size_t i = 0; i < D; ++i)
  {
    Point p = start;
    p[i] += (p[i] + step[i] <= upper[i]) ? step[i] : -step[i];
    p = clamp(p);
    simplex.push_back({ p, value(p) });
  }
  const auto combine = [&](const Point& centroid, const Point& p, double t)
  {
    Point q;
    for (std::size_t i = 0; i < D; ++i)
      q[i] = centroid[i] + t * (p[i] - centroid[i]);
    return clamp(q);
  };
  while (evaluations < maxEvaluations)
  {
    std::sort(simplex.begin(),
      simplex.end(),
      [](const auto& x, const auto& y) { return x.second < y.second; });
    if (simplex.back().second - simplex.front().second < tolerance)
      break;
    Point centroid{};
    for (std::size_t k = 0; k < D; ++k)
      for (std::size_t i = 0; i < D; ++i)
        centroid[i] += simplex[k].first[i] / double(D);
    auto& worst = simplex.back();
    const Point reflected = combine(centroid, worst.first, -1.0);
    const double fr = value(reflected);
    if (fr < simplex.front().second)
    {
      const Point expanded = combine(centroid, worst.first, -2.0);
      const double fe = value(expanded);
      worst = fe < fr ? std::make_pair(expanded, fe) : std::make_pair(reflected, fr);
    }
    else if (fr < simplex[D - 1].second)
      worst = { reflected, fr };
    else
    {
      const Point contracted = combine(centroid, worst.first, fr < worst.second ? -0.5 : 0.5);
      const double fc = value(contracted);
      if (fc < std::min(fr, worst.second))
        worst = { contracted, fc };
      else // shrink toward the best
        for (std::size_t k = 1; k <= D; ++k)
        {
          simplex[k].first = combine(simplex[0].first, simplex[k].first, 0.5);
          simplex[k].second = value(simplex[k].first);
        }
    }
  }
  std::sort(simplex.begin(),
    simplex.end(),
    [](const auto& x, const auto& y) { return x.second < y.second; });
  return { simplex.front().first, simplex.front().second };
}

// Golden-section search of a unimodal f on [a, b], to a bracket of `tolerance`.
std::pair<double, double> GoldenSection(const std::function<double(double)>& f,
  double a,
  double b,
  double tolerance)
{
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - r * (b - a), x2 = a + r * (b - a);
  double f1 = f(x1), f2 = f(x2);
  while (b - a > tolerance)
  {
    if (f1 < f2)
    {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - r * (b - a);
      f1 = f(x1);
    }
    else
    {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + r * (b - a);
      f2 = f(x2);
    }
  }
  return f1 < f2 ? std::make_pair(x1, f1) : std::make_pair(x2, f2);
}

// A case's name as a file name: "dense, side, albedo 1.0" -> "dense,_side,_albedo_1.0".
std::string FileLabel(std::string name)
{
  std::replace(name.begin(), name.end(), ' ', '_');
  return name;
}

// The per-case table of two settings' errors, and the aggregates of each set.
void PrintBeforeAfter(const char* title,
  const std::vector<FitCase>& cases,
  const std::vector<ImageError>& before,
  const std::vector<ImageError>& after)
{
  std::printf("\n%s\n\n| case | set | relative RMSE before | after | noise-corrected before | "
              "after | bias before | after | reference's standard error |\n"
              "|---|---|---|---|---|---|---|---|---|\n",
    title);
  for (bool heldOut : { false, true })
    for (std::size_t i = 0; i < cases.size(); ++i)
      if (cases[i].HeldOut == heldOut)
        std::printf("| %s | %s | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.3f | %.3f | %.2f%% |\n",
          cases[i].Name.c_str(),
          heldOut ? "held out" : "training",
          100.0 * before[i].RelativeRMSE,
          100.0 * after[i].RelativeRMSE,
          100.0 * before[i].NoiseCorrectedRelativeRMSE,
          100.0 * after[i].NoiseCorrectedRelativeRMSE,
          before[i].BiasRatio,
          after[i].BiasRatio,
          100.0 * before[i].ReferenceRelativeStandardError);
  for (bool heldOut : { false, true })
  {
    double worstBefore = 0.0, worstAfter = 0.0;
    for (std::size_t i = 0; i < cases.size(); ++i)
      if (cases[i].HeldOut == heldOut)
      {
        worstBefore = std::max(worstBefore, before[i].NoiseCorrectedRelativeRMSE);
        worstAfter = std::max(worstAfter, after[i].NoiseCorrectedRelativeRMSE);
      }
    std::printf("| **mean, %s** | | | | %.1f%% | %.1f%% | | | |\n"
                "| **worst, %s** | | | | %.1f%% | %.1f%% | | | |\n",
      heldOut ? "held out" : "training",
      100.0 * MeanError(cases, before, heldOut),
      100.0 * MeanError(cases, after, heldOut),
      heldOut ? "held out" : "training",
      100.0 * worstBefore,
      100.0 * worstAfter);
  }
  std::fflush(stdout);
}

int Fit(const Options& options)
{
  const double fitStart = vtkTimerLog::GetUniversalTime();
  std::printf("%d x %d, path tracer %d paths per pixel, bounce cap %d, seed %u; fields on %s "
              "voxels; split %s\n",
    options.Width,
    options.Height,
    options.Samples,
    options.Bounces,
    options.Seed,
    options.FitDimensions > 0 ? std::to_string(options.FitDimensions).append("^3").c_str()
                              : "their own",
    options.FitSplit.c_str());
  // The references, once per case.
  std::vector<FitCase> cases;
  std::vector<vtkSmartPointer<vtkImageData>> fields; // kept alive for the marches
  for (FitField& fitField : FitFields(options.FitSplit))
  {
    BenchScene& scene = fitField.Scene;
    if (options.FitDimensions > 0)
      scene.Dimensions = glm::ivec3(options.FitDimensions);
    fields.push_back(MakeField(scene));
    vtkImageData* field = fields.back();
    for (const FitLight& light : FitLights)
      for (float albedo : FitAlbedos)
      {
        const FitRole role = RoleOf(fitField, light, albedo);
        if (role == FitRole::Unused)
          continue;
        Light sun;
        sun.Position = 10.0f * light.TowardLight;
        const auto medium = MakeMedium(scene, albedo);
        FitCase c;
        char name[120];
        std::snprintf(name,
          sizeof(name),
          "%s, %s, albedo %.1f",
          fitField.Name.c_str(),
          light.Name,
          double(albedo));
        c.Name = name;
        c.HeldOut = role == FitRole::HeldOut;
        c.Reference = Run(NewTracer(scene, field, medium, { sun }, options.Bounces, options));
        c.ReferenceSeconds = c.Reference.Seconds;
        const double* spacing = field->GetSpacing();
        c.VoxelEdge = std::min({ spacing[0], spacing[1], spacing[2] });
        LightingParameters lighting = scene.Lighting;
        lighting.Model = LightingModel::March;
        c.March = NewMarch(scene, field, medium, lighting, { sun }, options);
        c.Octaves = std::make_unique<PreparedMarch>(c.March, field);
        if (Run(c.March).RGBA != c.Octaves->Render(lighting))
          Fail(c.Name + ": the prepared march differs from vtkCloudReferenceRenderer's");
        WritePng(options.PngDirectory,
          FileLabel(c.Name) + "-pathtrace",
          c.Reference.RGBA,
          options.Width,
          options.Height);
        cases.push_back(std::move(c));
      }
  }
  double referenceSeconds = 0.0;
  for (const FitCase& c : cases)
    referenceSeconds += c.ReferenceSeconds;
  std::printf("%zu cases (%d held out); the references took %.0f s\n",
    cases.size(),
    int(std::count_if(cases.begin(), cases.end(), [](const FitCase& c) { return c.HeldOut; })),
    referenceSeconds);

  // The octaves: for each N, Nelder-Mead over (a, b, c) in [0, 1]^3 from the old defaults.
  // "Before": the octaves' values until this fit (the rest: the shipped defaults, light volumes).
  LightingParameters base;
  base.Model = LightingModel::March;
  base.MultipleScatteringOctaves = 3;
  base.ScatteringFalloff = base.ExtinctionFalloff = base.EccentricityFalloff = 0.5f;
  const std::vector<ImageError> before = FitErrors(cases, base);
  std::printf("\nbefore the fit (N %d, a %.3f, b %.3f, c %.3f): training %.2f%%, held out "
              "%.2f%%\n",
    base.MultipleScatteringOctaves,
    double(base.ScatteringFalloff),
    double(base.ExtinctionFalloff),
    double(base.EccentricityFalloff),
    100.0 * MeanError(cases, before, false),
    100.0 * MeanError(cases, before, true));
  std::printf("\nOctave counts 1 to %d: the best of a 4^3 grid over (a, b, c) starts Nelder-Mead "
              "(at most %d evaluations after it), bounded to [0, 1]^3.\n",
    options.FitMaxOctaves,
    options.FitEvaluations);
  std::printf("\n| octaves N | a | b | c | training mean | held-out mean | evaluations | time |\n"
              "|---|---|---|---|---|---|---|---|\n");
  std::vector<std::pair<LightingParameters, double>> fits; // per N, with its training mean
  for (int octaves = 1; octaves <= options.FitMaxOctaves; ++octaves)
  {
    const double nStart = vtkTimerLog::GetUniversalTime();
    int evaluations = 0;
    const auto withParameters = [&](const std::array<double, 3>& x)
    {
      LightingParameters p = base;
      p.MultipleScatteringOctaves = octaves;
      p.ScatteringFalloff = float(x[0]);
      p.ExtinctionFalloff = float(x[1]);
      p.EccentricityFalloff = float(x[2]);
      return p;
    };
    const auto objective = [&](const std::array<double, 3>& x)
    {
      ++evaluations;
      return MeanError(cases, FitErrors(cases, withParameters(x), true, false), false);
    };
    // Coarse to fine: the best of a 4^3 grid over the box starts the simplex (the objective
    // has more than one valley: less scattering can be traded against less extinction).
    std::array<double, 3> start{ 0.5, 0.5, 0.5 };
    double startValue = objective(start);
    for (double a : { 0.2, 0.4, 0.6, 0.8 })
      for (double b : { 0.2, 0.4, 0.6, 0.8 })
        for (double c : { 0.2, 0.4, 0.6, 0.8 })
        {
          const double value = objective({ a, b, c });
          if (value < startValue)
          {
            startValue = value;
            start = { a, b, c };
          }
        }
    const auto [x, training] = NelderMead<3>(objective,
      start,
      { 0.1, 0.1, 0.1 },
      { 0.0, 0.0, 0.0 },
      { 1.0, 1.0, 1.0 },
      1e-4,
      options.FitEvaluations);
    const LightingParameters fitted = withParameters(x);
    const double heldOut = MeanError(cases, FitErrors(cases, fitted, true, true), true);
    std::printf("| %d | %.3f | %.3f | %.3f | %.2f%% | %.2f%% | %d | %.0f s |\n",
      octaves,
      x[0],
      x[1],
      x[2],
      100.0 * training,
      100.0 * heldOut,
      evaluations,
      vtkTimerLog::GetUniversalTime() - nStart);
    std::fflush(stdout);
    fits.push_back({ fitted, training });
  }
  // The fewest octaves within half a point of the best training mean: each octave costs the
  // march two phase evaluations and an exponential per light at every sample, and beyond 3
  // octaves the training mean falls by tenths of a point, less than it moves between splits.
  double bestTraining = 1e30;
  for (const auto& fit : fits)
    bestTraining = std::min(bestTraining, fit.second);
  LightingParameters best = base;
  for (const auto& fit : fits)
    if (fit.second <= bestTraining + 0.005)
    {
      best = fit.first;
      break;
    }
  // Rounded to two decimals, as the defaults are written.
  for (float* f : { &best.ScatteringFalloff, &best.ExtinctionFalloff, &best.EccentricityFalloff })
    *f = std::round(*f * 100.0f) / 100.0f;
  std::printf("\nchosen (the fewest octaves within 0.5 points of the best training mean, "
              "rounded): N %d, a %.2f, b %.2f, c %.2f\n",
    best.MultipleScatteringOctaves,
    double(best.ScatteringFalloff),
    double(best.ExtinctionFalloff),
    double(best.EccentricityFalloff));
  const LightingParameters shipped;
  std::printf(
    "the shipped defaults (filters/CloudLighting.h) are N %d, a %.2f, b %.2f, c %.2f: %s\n",
    shipped.MultipleScatteringOctaves,
    double(shipped.ScatteringFalloff),
    double(shipped.ExtinctionFalloff),
    double(shipped.EccentricityFalloff),
    shipped.MultipleScatteringOctaves == best.MultipleScatteringOctaves &&
        shipped.ScatteringFalloff == best.ScatteringFalloff &&
        shipped.ExtinctionFalloff == best.ExtinctionFalloff &&
        shipped.EccentricityFalloff == best.EccentricityFalloff
      ? "the fit's"
      : "not the fit's");
  const std::vector<ImageError> after = FitErrors(cases, best);
  PrintBeforeAfter(
    "march, light volumes (the default): before the fit, and fitted", cases, before, after);
  if (!options.PngDirectory.empty())
    for (FitCase& c : cases)
      for (const auto& [lighting, suffix] :
        { std::make_pair(best, "-march-fitted"), std::make_pair(base, "-march-before") })
      {
        c.March->GetLightingProperty()->SetParameters(lighting);
        WritePng(options.PngDirectory,
          FileLabel(c.Name) + suffix,
          Run(c.March).RGBA,
          options.Width,
          options.Height);
      }

  // The check with the nested light march.
  LightingParameters baseNested = base, bestNested = best;
  baseNested.Transmittance = bestNested.Transmittance = LightTransmittance::Nested;
  PrintBeforeAfter("march, nested light march: before the fit, and fitted",
    cases,
    FitErrors(cases, baseNested),
    FitErrors(cases, bestNested));

  // The derivative model: h in voxel spacings of each field (as its default, 4, is stated),
  // golden-section search of log2(h) over [1/2, 64] voxels: its one length; the model has no
  // other constant a fit could set (its slope scale is 1 / (h rho_unit)).
  const auto derivativeAt = [](double log2Voxels)
  {
    return [log2Voxels](const FitCase& c)
    {
      LightingParameters p;
      p.Model = LightingModel::Derivative;
      p.DerivativeDistance = float(std::exp2(log2Voxels) * c.VoxelEdge);
      return p;
    };
  };
  const std::vector<ImageError> derivativeBefore = FitErrors(cases, derivativeAt(2.0));
  const auto [log2h, derivativeTraining] = GoldenSection([&](double x)
    { return MeanError(cases, FitErrors(cases, derivativeAt(x), false, false), false); },
    -1.0,
    6.0,
    0.05);
  std::printf("\nderivative: h = %.2f voxels gives training %.2f%% (4 voxels: %.2f%%)\n",
    std::exp2(log2h),
    100.0 * derivativeTraining,
    100.0 * MeanError(cases, derivativeBefore, false));
  PrintBeforeAfter("derivative: h = 4 voxels before, fitted after",
    cases,
    derivativeBefore,
    FitErrors(cases, derivativeAt(log2h)));

  std::printf("\nthe whole fit took %.0f s (references %.0f s)\n",
    vtkTimerLog::GetUniversalTime() - fitStart,
    referenceSeconds);
  return 0;
}

int Usage(const char* program)
{
  std::fprintf(stderr,
    "usage: %s speed [--size WxH] [--spp N] [--bounces B] [--brick N] [--seed S] [--png DIR] "
    "[SCENE.json ...]\n"
    "       %s errors [--size WxH] [--spp N] [--bounces B] [--seed S] [--png DIR]\n"
    "       %s bounces [--size WxH] [--spp N] [--seed S]\n"
    "       %s defects [--size WxH] [--spp N] [--bounces B]\n"
    "       %s fit [--size WxH] [--spp N] [--bounces B] [--seed S] [--split first|stratified] "
    "[--voxels N] [--max-octaves N] [--evaluations E] [--png DIR]\n",
    program,
    program,
    program,
    program,
    program);
  return 2;
}
}

int main(int argc, char* argv[])
{
  if (argc < 2)
    return Usage(argv[0]);
  const std::string command = argv[1];
  Options options;
  for (int i = 2; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--size" && hasValue)
    {
      if (std::sscanf(argv[++i], "%dx%d", &options.Width, &options.Height) != 2 ||
        options.Width < 1 || options.Height < 1)
        return Usage(argv[0]);
    }
    else if (arg == "--spp" && hasValue)
      options.Samples = std::atoi(argv[++i]);
    else if (arg == "--bounces" && hasValue)
      options.Bounces = std::atoi(argv[++i]);
    else if (arg == "--png" && hasValue)
      options.PngDirectory = argv[++i];
    else if (arg == "--brick" && hasValue)
      options.BrickSize = std::atoi(argv[++i]);
    else if (arg == "--split" && hasValue)
      options.FitSplit = argv[++i];
    else if (arg == "--voxels" && hasValue)
      options.FitDimensions = std::atoi(argv[++i]);
    else if (arg == "--max-octaves" && hasValue)
      options.FitMaxOctaves = std::atoi(argv[++i]);
    else if (arg == "--evaluations" && hasValue)
      options.FitEvaluations = std::atoi(argv[++i]);
    else if (arg == "--seed" && hasValue)
      options.Seed = unsigned(std::strtoul(argv[++i], nullptr, 10));
    else if (arg.rfind("--", 0) == 0)
      return Usage(argv[0]);
    else
      options.Scenes.push_back(arg);
  }
  if (options.Samples < 2 || options.Bounces < 1 || options.FitDimensions == 1 ||
    options.FitDimensions < 0 || options.FitMaxOctaves < 1 ||
    options.FitMaxOctaves > LightingLimits::MaxMultipleScatteringOctaves ||
    options.FitEvaluations < 1 ||
    (options.FitSplit != "first" && options.FitSplit != "stratified"))
    return Usage(argv[0]);
  try
  {
    if (command == "speed")
      return Speed(options);
    if (command == "errors")
      return Errors(options);
    if (command == "bounces")
      return Bounces(options);
    if (command == "defects")
      return Defects(options);
    if (command == "fit")
      return Fit(options);
    return Usage(argv[0]);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "cloudvis-bench-pathtrace: %s\n", e.what());
    return 1;
  }
}
