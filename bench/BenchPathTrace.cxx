// The path tracer (vtkCloudPathTracer): how fast it converges on the shipped scenes, and how far
// each lighting model of the march is from it. Three commands:
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
//   defects
//     Measures the march's known defects one by one (docs/lighting.md, "What the march gets
//     wrong").
//
// Scenes are read minimally (field, transfer_function, lights, ambient, camera position and view
// angle): enough for the shipped scenes, with a clear refusal of what it does not read.
#include "CloudImageComparison.h"
#include "CloudReferenceMarch.h"
#include "vtkCloudDensitySource.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkTimerLog.h>
#include <vtkUnsignedCharArray.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
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
    { "dimensions", "bounds", "density_model", "density_scale", "shape", "noise", "octaves",
      "lacunarity", "lacunarity_increment", "gain", "amplitude", "frequency", "seed", "wind",
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
  else if (model == "constant")
    f.Model = DensityModel::Constant;
  else
    Fail(path + ": field.density_model " + model + ": not read by this benchmark");
  f.DensityScale = field.value("density_scale", 1.0);
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

// The table the app builds (render/CpuReference.cxx): over the field's density range.
TransferTable MakeTable(const BenchScene& scene, vtkImageData* field)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const auto& p : scene.Opacity)
    opacity->AddPoint(p[0], p[1]);
  vtkNew<vtkColorTransferFunction> color;
  for (const auto& p : scene.Color)
    color->AddRGBPoint(p[0], p[1], p[2], p[3]);
  double range[2] = { 0.0, 1.0 };
  field->GetPointData()->GetScalars()->GetRange(range, 0);
  if (!(range[1] > range[0]))
    range[1] = range[0] + 1.0;
  return BuildTransferTable(color, opacity, scene.UnitDistance, range, 1024);
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
  std::vector<std::string> Scenes;
};

// ---- speed ----

int Speed(const Options& options)
{
  std::vector<std::string> scenes = options.Scenes;
  if (scenes.empty())
    scenes = { "data/scenes/fbm-sphere.json", "data/scenes/two-lights.json",
      "data/scenes/sphere.json" };
  std::printf("%d x %d, %d paths per pixel, bounce cap %d, bricks of %d voxels, vtkSMPTools %s "
              "with %d threads\n\n",
    options.Width, options.Height, options.Samples, options.Bounces, options.BrickSize,
    vtkSMPTools::GetBackend(), vtkSMPTools::GetEstimatedNumberOfThreads());
  std::printf("| scene | path tracer | paths/s (all pixels) | paths/s (cloud pixels) | relative "
              "standard error | time to 1%% at 800x600 | CPU march (%s) | one path per pixel "
              "costs |\n|---|---|---|---|---|---|---|---|\n",
    "scene's model");
  for (const std::string& path : scenes)
  {
    const BenchScene scene = ReadScene(path);
    const vtkSmartPointer<vtkImageData> field = MakeField(scene);
    const TransferTable table = MakeTable(scene, field);

    vtkNew<vtkCloudPathTracer> tracer;
    tracer->SetInputData(field);
    SetSceneCamera(tracer, scene, field, options.Width, options.Height);
    tracer->SetTransferTable(table);
    tracer->SetLighting(scene.Lighting);
    tracer->SetLights(scene.Lights);
    tracer->SetSamplesPerPixel(options.Samples);
    tracer->SetMaxBounces(options.Bounces);
    tracer->SetBrickSize(options.BrickSize);
    tracer->SetSeed(options.Seed);
    const Rendered traced = Run(tracer);

    vtkNew<vtkCloudReferenceRenderer> march;
    march->SetInputData(field);
    SetSceneCamera(march, scene, field, options.Width, options.Height);
    march->SetTransferTable(table);
    march->SetLighting(scene.Lighting);
    march->SetLights(scene.Lights);
    const Rendered marched = Run(march);

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
  {
    s->Dimensions = glm::ivec3(96);
    s->Lighting.AmbientStrength = 0.0f;
  }
  return { { "fbm-sphere", fbm }, { "dense", dense } };
}

struct ErrorModel
{
  const char* Name;
  LightingModel Model;
  int Octaves;
  int Bounces; // of the path tracer it is compared with
};

int Errors(const Options& options)
{
  const ErrorModel models[] = {
    { "march (defaults: 6 growing light steps, 3 octaves)", LightingModel::March, 3,
      options.Bounces },
    { "march, no octaves", LightingModel::March, 0, options.Bounces },
    { "derivative", LightingModel::Derivative, 0, options.Bounces },
    { "march, no octaves vs single scattering", LightingModel::March, 0, 1 },
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
  for (const ErrorField& errorField : ErrorFields())
  {
    const BenchScene& scene = errorField.Scene;
    const vtkSmartPointer<vtkImageData> field = MakeField(scene);
    const TransferTable baseTable = MakeTable(scene, field);
    for (const auto& lit : lightings)
    {
      Light light;
      light.Position = 10.0f * lit.TowardLight;
      for (float albedo : { 1.0f, 0.9f })
      {
        TransferTable table = baseTable;
        for (int e = 0; e < table.Size; ++e)
          for (int c = 0; c < 3; ++c)
            table.RGBA[4 * e + c] = albedo;
        std::vector<Rendered> references(2); // full, single scattering
        for (const ErrorModel& model : models)
        {
          Rendered& reference = references[model.Bounces == 1 ? 1 : 0];
          if (reference.RGBA.empty())
          {
            vtkNew<vtkCloudPathTracer> tracer;
            tracer->SetInputData(field);
            SetSceneCamera(tracer, scene, field, options.Width, options.Height);
            tracer->SetTransferTable(table);
            tracer->SetLighting(scene.Lighting);
            tracer->SetLights({ light });
            tracer->SetSamplesPerPixel(options.Samples);
            tracer->SetMaxBounces(model.Bounces);
            tracer->SetSeed(options.Seed);
            reference = Run(tracer);
          }
          vtkNew<vtkCloudReferenceRenderer> renderer;
          renderer->SetInputData(field);
          SetSceneCamera(renderer, scene, field, options.Width, options.Height);
          renderer->SetTransferTable(table);
          LightingParameters lighting = scene.Lighting;
          lighting.Model = model.Model;
          lighting.MultipleScatteringOctaves = model.Octaves;
          renderer->SetLighting(lighting);
          renderer->SetLights({ light });
          const Rendered image = Run(renderer);
          const ImageError e = CompareWithReference(image.RGBA.data(), reference.RGBA.data(),
            reference.Variance.data(), std::size_t(options.Width) * options.Height);
          std::printf("| %s | %s | %.1f | %s | %.1f%% | %.1f%% | %.3f | %.1f%% | %.2f%% |\n",
            errorField.Name, lit.Name, double(albedo), model.Name, 100.0 * e.RelativeRMSE,
            100.0 * e.NoiseCorrectedRelativeRMSE, e.BiasRatio, 100.0 * e.MaxErrorOverPeak,
            100.0 * e.ReferenceRelativeStandardError);
          std::fflush(stdout);
        }
      }
    }
  }
  return 0;
}

int Usage(const char* program)
{
  std::fprintf(stderr,
    "usage: %s speed [--size WxH] [--spp N] [--bounces B] [--brick N] [--seed S] [--png DIR] "
    "[SCENE.json ...]\n"
    "       %s errors [--size WxH] [--spp N] [--bounces B] [--seed S] [--png DIR]\n",
    program, program);
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
    else if (arg == "--seed" && hasValue)
      options.Seed = unsigned(std::strtoul(argv[++i], nullptr, 10));
    else if (arg.rfind("--", 0) == 0)
      return Usage(argv[0]);
    else
      options.Scenes.push_back(arg);
  }
  if (options.Samples < 2 || options.Bounces < 1)
    return Usage(argv[0]);
  try
  {
    if (command == "speed")
      return Speed(options);
    if (command == "errors")
      return Errors(options);
    return Usage(argv[0]);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "cloudvis-bench-pathtrace: %s\n", e.what());
    return 1;
  }
}
