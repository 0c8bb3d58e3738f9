// The march's default multiple scattering, the multiple-scattering volume, against the path
// tracer on held-out cases of `cloudvis-bench-pathtrace fit` (docs/lighting.md, "The
// multiple-scattering volume"): cases no constant of the volume was chosen on, each rendered as
// the bench renders it (a shipped scene with --set assignments on 64^3 voxels, one white
// directional light, a uniform gray albedo, no ambient, 64 x 48 pixels, the path tracer with 1024
// (unless the case says) paths per pixel and seed 0). Each gate sits at about 1.5 times the error
// measured by `cloudvis-bench-pathtrace fit --size 64x48 --spp 1024 --multiple-scattering volume`,
// and the octaves, the model the volume replaced, miss every one of them.
#include "CloudImageComparison.h"
#include "CpuReference.h"
#include "Scene.h"
#include "SceneField.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace cloudvis;

struct HeldOutCase
{
  const char* Name;
  const char* SceneFile;
  std::vector<std::string> Assignments;
  glm::vec3 TowardLight;
  float Albedo;
  double MeasuredError;        // the volume's noise-corrected relative RMSE, measured
  double MeasuredOctavesError; // the octaves', measured
  int PathsPerPixel = 1024;    // the reference's
};

void PrintTo(const HeldOutCase& c, std::ostream* out)
{
  *out << c.Name;
}

// The scene as the bench's case: 64^3 voxels, no ambient, one light, a gray albedo, 64 x 48.
Scene CaseScene(const HeldOutCase& c)
{
  std::vector<std::string> assignments = c.Assignments;
  assignments.push_back("ambient.strength=0");
  assignments.push_back("field.dimensions=64");
  Scene scene = LoadScene(std::string(CLOUDVIS_SCENES) + "/" + c.SceneFile, assignments);
  Light light;
  light.Position = glm::dvec3(10.0f * c.TowardLight);
  scene.Lights = { light };
  for (auto& point : scene.TransferFunction.Color)
    point[1] = point[2] = point[3] = c.Albedo;
  scene.Render.Size = { { 64, 48 } };
  return scene;
}

std::vector<float> Rgba(vtkCloudReferenceRenderer* renderer, std::vector<float>* variance)
{
  renderer->Update();
  vtkPointData* pd = renderer->GetOutput()->GetPointData();
  auto* rgba = vtkFloatArray::SafeDownCast(pd->GetArray("rgba"));
  EXPECT_NE(rgba, nullptr);
  if (!rgba)
    return {};
  if (variance)
  {
    auto* v = vtkFloatArray::SafeDownCast(pd->GetArray("rgba_variance"));
    EXPECT_NE(v, nullptr);
    if (v)
      variance->assign(v->GetPointer(0), v->GetPointer(0) + v->GetNumberOfValues());
  }
  return { rgba->GetPointer(0), rgba->GetPointer(0) + rgba->GetNumberOfValues() };
}

class MultipleScatteringVolume : public testing::TestWithParam<HeldOutCase>
{
};

TEST_P(MultipleScatteringVolume, StaysWithinItsMeasuredErrorOfThePathTracer)
{
  const HeldOutCase& c = GetParam();
  const Scene scene = CaseScene(c);
  vtkSmartPointer<vtkImageData> field = ProduceField(scene);

  vtkNew<vtkCloudPathTracer> tracer;
  SetUpReference(scene, field, tracer);
  tracer->SetSamplesPerPixel(c.PathsPerPixel);
  tracer->SetMaxBounces(PathTraceBounceCap); // the bench's
  tracer->SetSeed(0);
  std::vector<float> variance;
  const std::vector<float> reference = Rgba(tracer, &variance);

  const auto errorOf = [&](MultipleScatteringModel model)
  {
    vtkNew<vtkCloudReferenceRenderer> march;
    SetUpReference(scene, field, march);
    LightingParameters lighting = scene.Render.Lighting;
    lighting.Model = LightingModel::March;
    lighting.MultipleScattering = model;
    march->GetLightingProperty()->SetParameters(lighting);
    const std::vector<float> image = Rgba(march, nullptr);
    return CompareWithReference(
      image.data(), reference.data(), variance.data(), reference.size() / 4);
  };
  const ImageError volume = errorOf(MultipleScatteringModel::Volume);
  const ImageError octaves = errorOf(MultipleScatteringModel::Octaves);
  std::cout << c.Name << ": volume " << volume.NoiseCorrectedRelativeRMSE << " (bias "
            << volume.BiasRatio << "), octaves " << octaves.NoiseCorrectedRelativeRMSE
            << ", reference's standard error " << volume.ReferenceRelativeStandardError << "\n";
  const double gate = 1.5 * c.MeasuredError;
  EXPECT_LT(volume.NoiseCorrectedRelativeRMSE, gate)
    << "measured " << c.MeasuredError << "; bias " << volume.BiasRatio;
  EXPECT_GT(volume.NoiseCorrectedRelativeRMSE, c.MeasuredError / 1.5)
    << "far better than measured: the measurement in docs/lighting.md is stale";
  EXPECT_GT(octaves.NoiseCorrectedRelativeRMSE, gate)
    << "the octaves (measured " << c.MeasuredOctavesError << ") must miss the volume's gate";
}

// Held out by `fit --split stratified` (the split the volume's constant was chosen on): two
// held-out fields and a training field lit from above, a direction and an albedo no training case
// has. Errors from docs/lighting.md's table.
INSTANTIATE_TEST_SUITE_P(HeldOut,
  MultipleScatteringVolume,
  testing::Values(HeldOutCase{ "PerlinFalloffSideLit",
                    "perlin-falloff.json",
                    {},
                    { 1, 0, 0 },
                    0.9f,
                    0.084,
                    0.793 },
    HeldOutCase{ "SparseSideLit",
      "fbm-sphere.json",
      { "field.shape.radius=0.5" },
      { 1, 0, 0 },
      0.9f,
      0.137,
      0.483 },
    HeldOutCase{ "SphereFromAbove", "sphere.json", {}, { 0, 1, 0 }, 0.9f, 0.058, 0.473 },
    HeldOutCase{ "DenseFromAbove",
      "fbm-sphere.json",
      { "field.shape.radius=1.8", "transfer_function.unit_distance=0.5" },
      { 0, 1, 0 },
      0.9f,
      0.114,
      0.319 }),
  [](const testing::TestParamInfo<HeldOutCase>& held) { return std::string(held.param.Name); });

// Held out by `fit --cases real` (issue 38's real regime, docs/lighting.md, "The real regime"):
// the shipped cumulus five times denser (optical diameter near 500) under a low sun at albedo
// 0.999, a light and an albedo no training case of that set has. The volume is far from the
// path tracer here; the gate keeps the surface depth of its solve (SurfaceDepth in
// shaders/transport/Scattering.glsl), without which a thick cell holds the light its surface
// sends back and the error was 170% (2.6 times this one; 67.0% before the bounce cap rose from
// 1024 to PathTraceBounceCap, whose reference keeps the deep walks' light). 256 paths per pixel:
// its reference's standard error, 14%, is far below the error the gate measures.
INSTANTIATE_TEST_SUITE_P(RealRegime,
  MultipleScatteringVolume,
  testing::Values(HeldOutCase{ "ThickCumulusLowSun",
    "cumulus.json",
    { "transfer_function.unit_distance=0.01" },
    { 0.9f, 0.27f, -0.35f },
    0.999f,
    0.663,
    1.256,
    256 }),
  [](const testing::TestParamInfo<HeldOutCase>& held) { return std::string(held.param.Name); });

} // namespace
