// Every field VTK can hand the mapper renders right or is refused (issue 10): one test per class
// of input that used to give a plausible but wrong picture. Rendering right is checked against a
// known answer (the same field placed otherwise, the field without its outliers); refusing means
// an error that names the problem, and nothing drawn. The GPU against the CPU reference and
// against VTK's own mapper for the same classes are in TestGpuMatchesCpuReference.cxx and
// TestCloudVolumeMapper.cxx.
#include "SupportScene.h"

#include "CloudMarchUniforms.h"

#include <vtkCamera.h>
#include <vtkFloatArray.h>
#include <vtkLight.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

using namespace cloudvis;
using namespace cloudvis::support;

namespace
{
// Renders `field` after `setup` has changed the scene; returns the mapper's error, and checks
// that nothing but the black background was drawn when there is one.
std::string ErrorOf(
  vtkImageData* field,
  double step,
  const std::function<void(GpuScene&, vtkCloudVolumeMapper*)>& setup = [](GpuScene&,
                                                                         vtkCloudVolumeMapper*) {})
{
  auto mapper = CloudMapper(step);
  GpuScene scene(mapper, 32, 32);
  scene.SetInput(field);
  SetRampMedium(scene.Property, 1.0, 0.6);
  setup(scene, mapper);
  const Image image = scene.Render();
  if (!mapper->GetLastError().empty())
  {
    EXPECT_EQ(Largest(image, 3), 0.0) << "nothing may be drawn from refused input";
  }
  return mapper->GetLastError();
}

bool Mentions(const std::string& error, const std::string& words)
{
  return error.find(words) != std::string::npos;
}

LightingParameters March()
{
  LightingParameters p;
  p.Model = LightingModel::March;
  return p;
}
}

TEST(TrustworthyImages, AStepTooSmallForTheSampleCapIsRefusedWithTheSmallestAllowed)
{
  // [-2, 2]^3: the longest ray is the diagonal, 4 sqrt(3); 65536 samples allow a step of 1.06e-4.
  auto field = SparseCloud(16);
  for (double step : { 1e-9, 1e-5, 1.0e-4 })
  {
    const std::string error = ErrorOf(field, step);
    EXPECT_TRUE(Mentions(error, "samples along the volume's longest ray")) << error;
    EXPECT_TRUE(Mentions(error, "use a step of at least 0.000105")) << error;
  }
  EXPECT_EQ(ErrorOf(field, 1.1e-4), "") << "a step just above the limit renders";
}

TEST(TrustworthyImages, MoreThanEightLightsAreRefusedNotDropped)
{
  auto field = SparseCloud(16);
  const auto lights = [](int count)
  {
    return [count](GpuScene& scene, vtkCloudVolumeMapper* mapper)
    {
      mapper->GetLightingProperty()->SetParameters(March());
      for (int i = 0; i < count; ++i)
      {
        AddLight(scene.Renderer, PointLight(glm::dvec3(i, 1.0, 3.0)));
      }
    };
  };
  EXPECT_TRUE(Mentions(ErrorOf(field, 0.05, lights(9)), "9 lights; the renderers take at most 8"));
  EXPECT_EQ(ErrorOf(field, 0.05, lights(8)), "");
}

TEST(TrustworthyImages, LightsAndExtinctionsBeyondFloatRangeAreRefused)
{
  auto field = SparseCloud(16);
  const std::string bright = ErrorOf(field,
    0.05,
    [](GpuScene& scene, vtkCloudVolumeMapper* mapper)
    {
      mapper->GetLightingProperty()->SetParameters(March());
      AddLight(scene.Renderer, DirectionalLight(glm::dvec3(6.0, 8.0, 4.0), 1e38));
    });
  EXPECT_TRUE(Mentions(bright, "light 0 (color x intensity 1e+38)")) << bright;
  EXPECT_TRUE(Mentions(bright, "lower its intensity")) << bright;

  const std::string far = ErrorOf(field,
    0.05,
    [](GpuScene& scene, vtkCloudVolumeMapper* mapper)
    {
      mapper->GetLightingProperty()->SetParameters(March());
      AddLight(scene.Renderer, PointLight(glm::dvec3(1e30, 0.0, 0.0)));
    });
  EXPECT_TRUE(Mentions(far, "too far for float arithmetic")) << far;

  const std::string thin = ErrorOf(field,
    0.05,
    [](GpuScene& scene, vtkCloudVolumeMapper*)
    { scene.Property->SetScalarOpacityUnitDistance(1e-45); });
  EXPECT_TRUE(Mentions(thin, "raise the unit distance")) << thin;

  // The same light is harmless under "none", which does not use lights.
  EXPECT_EQ(ErrorOf(field,
              0.05,
              [](GpuScene& scene, vtkCloudVolumeMapper*)
              { AddLight(scene.Renderer, DirectionalLight(glm::dvec3(6.0, 8.0, 4.0), 1e38)); }),
    "");
}

TEST(TrustworthyImages, ADirectionalLightFarAlongItsDirectionLightsAlike)
{
  // A sun's position only gives its direction: at 1e300 (beyond float) it is the same sun.
  const auto render = [](double distance)
  {
    auto mapper = CloudMapper(0.05);
    mapper->GetLightingProperty()->SetParameters(March());
    GpuScene scene(mapper, 48, 48);
    scene.ShowSparseCloud(32);
    AddLight(
      scene.Renderer, DirectionalLight(glm::dvec3(0.6 * distance, 0.8 * distance, 0.4 * distance)));
    const Image image = scene.RenderFloat();
    EXPECT_EQ(mapper->GetLastError(), "");
    return image;
  };
  const Image near = render(10.0), far = render(1e300);
  ASSERT_GT(MeanOver(near, 0, Columns(0, 48)), 0.01) << "an empty window proves nothing";
  EXPECT_EQ(MaxDifference(near, far), 0.0);
}

TEST(TrustworthyImages, NonFiniteDensitiesAreRefused)
{
  for (float bad :
    { std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity() })
  {
    auto field = SparseCloud(16);
    vtkFloatArray::SafeDownCast(field->GetPointData()->GetScalars())->SetValue(100, bad);
    const std::string error = ErrorOf(field, 0.05);
    EXPECT_TRUE(Mentions(error, "holds 1 values that are NaN or infinite")) << error;
  }
}

TEST(TrustworthyImages, AFlatOrNonFiniteGeometryIsRefused)
{
  const auto refused = [](const std::function<void(vtkImageData*, vtkVolume*)>& change)
  {
    auto field = SparseCloud(16);
    return ErrorOf(
      field, 0.05, [&](GpuScene& scene, vtkCloudVolumeMapper*) { change(field, scene.Volume); });
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(Mentions(refused([](vtkImageData* f, vtkVolume*) { f->SetSpacing(0.1, 0.0, 0.1); }),
    "the image's spacing (0.1, 0, 0.1) must be three positive finite numbers"));
  EXPECT_TRUE(Mentions(refused([](vtkImageData* f, vtkVolume*) { f->SetSpacing(0.1, -0.1, 0.1); }),
    "the image's spacing (0.1, -0.1, 0.1)"));
  // With a NaN in its geometry the volume's bounds are NaN and VTK's renderer culls it before
  // the mapper is asked to draw: nothing is drawn, and the shared check (which the CPU reference
  // and the application call first) names the problem.
  for (const auto& change : std::vector<std::function<void(vtkImageData*)>>{ [&](vtkImageData* f)
         { f->SetSpacing(nan, 0.1, 0.1); },
         [&](vtkImageData* f) { f->SetOrigin(0.0, nan, 0.0); } })
  {
    auto field = SparseCloud(16);
    change(field);
    const std::string problem = ValidateVolumeGeometry(field, nullptr);
    EXPECT_TRUE(Mentions(problem, "must be three") && Mentions(problem, "nan")) << problem;
    auto mapper = CloudMapper(0.05);
    GpuScene scene(mapper, 32, 32);
    scene.SetInput(field);
    SetRampMedium(scene.Property, 1.0, 0.6);
    const Image image = scene.Render();
    EXPECT_EQ(MeanOver(image, 0, Columns(0, 32)) + MeanOver(image, 1, Columns(0, 32)) +
        MeanOver(image, 2, Columns(0, 32)),
      0.0)
      << "nothing drawn";
  }
  EXPECT_TRUE(Mentions(
    refused([](vtkImageData* f, vtkVolume*) { f->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 1, 1, 0); }),
    "the image's direction matrix is singular"));
  EXPECT_TRUE(Mentions(refused([](vtkImageData*, vtkVolume* v) { v->SetScale(1.0, 0.0, 1.0); }),
    "the volume's matrix is singular"));
  // Voxels 1e40 times longer along one axis than another: no float frame holds both.
  EXPECT_TRUE(
    Mentions(refused([](vtkImageData* f, vtkVolume*) { f->SetSpacing(1e-20, 1e20, 1.0); }),
      "differ too much for float arithmetic"));
}

TEST(TrustworthyImages, AnOutlierVoxelDoesNotChangeTheRestOfTheCloud)
{
  // The transfer table spans the transfer function (0 .. 1), not the data: a voxel of 1e4, or
  // two of +-3.4e38, at a corner of the field change the picture at that corner only (where the
  // voxel is drawn with the function's end values), nowhere else. With the octaves, whose light
  // at a sample depends only on the medium along its rays: the multiple-scattering volume spreads
  // any change of the medium (that corner voxel drawn as the densest) over the whole cloud's
  // diffuse light, a little, as light does.
  const auto render = [](const std::function<void(vtkFloatArray*)>& change)
  {
    auto mapper = CloudMapper(0.03);
    LightingParameters octaves = March();
    octaves.MultipleScattering = MultipleScatteringModel::Octaves;
    mapper->GetLightingProperty()->SetParameters(octaves);
    GpuScene scene(mapper, 96, 96);
    auto field = SparseCloud(48);
    change(vtkFloatArray::SafeDownCast(field->GetPointData()->GetScalars()));
    scene.SetInput(field);
    SetRampMedium(scene.Property, 1.0, 0.6);
    AddLight(scene.Renderer, DirectionalLight(glm::dvec3(6.0, 8.0, 4.0)));
    const Image image = scene.RenderFloat();
    EXPECT_EQ(mapper->GetLastError(), "");
    return image;
  };
  const Image plain = render([](vtkFloatArray*) {});
  ASSERT_GT(MeanOver(plain, 3, Columns(0, 96)), 0.02) << "an empty window proves nothing";
  for (const auto& outliers : std::vector<std::function<void(vtkFloatArray*)>>{ [](vtkFloatArray* d)
         { d->SetValue(0, 1e4f); },
         [](vtkFloatArray* d)
         {
           d->SetValue(0, 3.4e38f);
           d->SetValue(1, -3.4e38f);
         } })
  {
    const Image changed = render(outliers);
    // The corner voxel (-2, -2, -2) is seen at about pixel (6, 6) of the parallel view of
    // [-2.2, 2.2]^2.
    double largest = 0.0;
    for (int y = 0; y < 96; ++y)
      for (int x = 0; x < 96; ++x)
        if (x > 16 || y > 16)
          for (int c = 0; c < 4; ++c)
          {
            const double d = std::abs(double(changed.At(x, y, c)) - double(plain.At(x, y, c)));
            largest = std::isnan(d) ? INFINITY : std::max(largest, d);
          }
    EXPECT_EQ(largest, 0.0);
  }
}
