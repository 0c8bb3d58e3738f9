// vtkCloudReferenceRenderer: scenes with known answers (a homogeneous sphere's opacity, a slab
// lit from behind), the behaviour each lighting model promises (the lit side is bright, lights
// add up, point lights fall off, the image converges as the steps shrink), the camera's
// agreement with vtkCamera, the image's orientation, input checks and determinism.
#include "CloudLighting.h"
#include "CloudMarchUniforms.h"
#include "CloudTransferTable.h"
#include "SupportExpectations.h"
#include "SupportFixtures.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolumeProperty.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

using namespace cloudvis;

using namespace cloudvis::support;

namespace
{
// A float field of n^3 voxels over the world box [lo, hi]^3, density(x, y, z) at each voxel.
vtkSmartPointer<vtkImageData> MakeField(
  int n, double lo, double hi, const std::function<double(double, double, double)>& density)
{
  return MakeBoxField({ n, n, n }, glm::dvec3(lo), glm::dvec3(hi), density);
}

// A renderer looking down -z at the origin, parallel projection framing [-1, 1]^2.
vtkSmartPointer<vtkCloudReferenceRenderer> FrontView(vtkImageData* field, int size = 32)
{
  auto renderer = vtkSmartPointer<vtkCloudReferenceRenderer>::New();
  renderer->SetInputData(field);
  renderer->SetImageSize(size, size);
  SetParallelView(renderer, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, -1.0), 1.0);
  renderer->SetVolumeProperty(LinearMedium(6.0f, glm::vec3(0.9f, 0.8f, 0.7f)));
  return renderer;
}

Image RenderWith(vtkCloudReferenceRenderer* renderer, const LightingParameters& lighting,
  const std::vector<Light>& lights)
{
  renderer->GetLightingProperty()->SetParameters(lighting);
  renderer->SetLights(MakeLights(lights));
  return Render(renderer);
}
}

namespace
{
// An off-centre ellipsoid, so that a rotation or a shift of the volume shows.
vtkSmartPointer<vtkImageData> Lopsided(int n = 24)
{
  return MakeField(n,
    -1.0,
    1.0,
    [](double x, double y, double z)
    {
      const double u = (x - 0.3) / 0.5, v = (y + 0.1) / 0.3, w = z / 0.4;
      return std::min(1.0, std::max(0.0, 2.0 * (1.0 - u * u - v * v - w * w)));
    });
}
}

TEST(ReferenceRenderer, HonoursTheExtentTheDirectionMatrixAndTheVolumeMatrix)
{
  // Each placement moves the volume and the camera alike: the picture must not change. (Before,
  // the reference refused a direction matrix and had no volume matrix.)
  auto field = Lopsided();
  const Image base = Render(FrontView(field, 32));
  ASSERT_GT(MeanRadiance(base), 0.01) << "an empty image proves nothing";

  // The same voxels indexed from -7, the origin moved back by 7 voxels.
  auto shifted = vtkSmartPointer<vtkImageData>::New();
  shifted->DeepCopy(field);
  const double* spacing = field->GetSpacing();
  shifted->SetOrigin(-1.0 + 7 * spacing[0], -1.0 + 7 * spacing[1], -1.0 + 7 * spacing[2]);
  shifted->SetExtent(-7, 16, -7, 16, -7, 16);
  EXPECT_LT(MaxDifference(Render(FrontView(shifted, 32)), base), 1e-6);

  // Rotated a quarter turn about z around its origin (-1, -1, -1) by the direction matrix, and
  // the camera with it: (x, y) -> (-y, x) about that point.
  auto rotated = vtkSmartPointer<vtkImageData>::New();
  rotated->DeepCopy(field);
  rotated->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1);
  auto turned = FrontView(rotated, 32);
  turned->SetCameraPosition(-2.0, 0.0, 5.0);
  turned->SetCameraFocalPoint(-2.0, 0.0, 0.0);
  turned->SetCameraViewUp(-1.0, 0.0, 0.0);
  EXPECT_LT(MaxDifference(Render(turned), base), 1e-5);

  // Moved and scaled by the volume's matrix: twice as large, so half the extinction per unit
  // length gives the same optical depths; the default step is one voxel, twice as long too.
  vtkNew<vtkMatrix4x4> matrix;
  matrix->SetElement(0, 0, 2.0);
  matrix->SetElement(1, 1, 2.0);
  matrix->SetElement(2, 2, 2.0);
  matrix->SetElement(0, 3, 5.0);
  matrix->SetElement(1, 3, -2.0);
  matrix->SetElement(2, 3, 1.0);
  auto placed = FrontView(field, 32);
  placed->SetVolumeMatrix(matrix);
  placed->SetVolumeProperty(LinearMedium(3.0f, glm::vec3(0.9f, 0.8f, 0.7f)));
  placed->SetCameraPosition(5.0, -2.0, 11.0);
  placed->SetCameraFocalPoint(5.0, -2.0, 1.0);
  placed->SetParallelScale(2.0);
  placed->SetClippingRange(2.0, 20.0);
  EXPECT_LT(MaxDifference(Render(placed), base), 1e-5);
  EXPECT_EQ(placed->GetVolumeMatrix()->GetElement(0, 3), 5.0);
}

TEST(ReferenceRenderer, CameraMatchesVtkCamera)
{
  vtkNew<vtkImageData> field;
  for (bool parallel : { false, true })
  {
    vtkNew<vtkCloudReferenceRenderer> renderer;
    renderer->SetImageSize(64, 48);
    renderer->SetCameraPosition(1.0, 2.0, 3.0);
    renderer->SetCameraFocalPoint(0.2, -0.1, 0.4);
    renderer->SetCameraViewUp(0.1, 1.0, 0.2);
    renderer->SetViewAngle(40.0);
    renderer->SetParallelProjection(parallel);
    renderer->SetParallelScale(0.7);
    renderer->SetClippingRange(0.5, 20.0);
    vtkNew<vtkCamera> camera;
    camera->SetPosition(1.0, 2.0, 3.0);
    camera->SetFocalPoint(0.2, -0.1, 0.4);
    camera->SetViewUp(0.1, 1.0, 0.2);
    camera->SetViewAngle(40.0);
    camera->SetParallelProjection(parallel);
    camera->SetParallelScale(0.7);
    camera->SetClippingRange(0.5, 20.0);

    vtkNew<vtkMatrix4x4> expected;
    vtkMatrix4x4::Invert(camera->GetCompositeProjectionTransformMatrix(64.0 / 48.0, -1.0, 1.0),
      expected);
    vtkNew<vtkMatrix4x4> actual;
    ASSERT_TRUE(renderer->GetDeviceToWorldMatrix(actual));
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(actual->GetElement(r, c), expected->GetElement(r, c),
          1e-9 * (1.0 + std::abs(expected->GetElement(r, c))))
          << (parallel ? "parallel" : "perspective") << " element " << r << ", " << c;
  }
}

TEST(ReferenceRenderer, RowZeroIsTheBottomAndColumnZeroTheLeft)
{
  // A blob at the upper right of the view appears at high i and high j.
  auto field = MakeField(24, -1.0, 1.0, [](double x, double y, double z) {
    const double r = std::sqrt((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5) + z * z);
    return std::max(0.0, 1.0 - r / 0.3);
  });
  auto renderer = FrontView(field, 16);
  const Image image = Render(renderer);
  double quadrant[2][2] = { { 0, 0 }, { 0, 0 } };
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i)
      quadrant[i / 8][j / 8] += image.At(i, j, 3);
  EXPECT_GT(quadrant[1][1], 0.5);
  EXPECT_EQ(quadrant[0][0], 0.0);
  EXPECT_EQ(quadrant[0][1], 0.0);
  EXPECT_EQ(quadrant[1][0], 0.0);
}

TEST(ReferenceRenderer, OutputHasTheImageSize)
{
  auto renderer = FrontView(SoftSphere(12));
  renderer->SetImageSize(7, 5);
  const Image image = Render(renderer);
  EXPECT_EQ(image.Width, 7);
  EXPECT_EQ(image.Height, 5);
  int dims[3];
  renderer->GetOutput()->GetDimensions(dims);
  EXPECT_EQ(dims[2], 1);
  EXPECT_EQ(image.Values.size(), std::size_t(7 * 5 * 4));
  EXPECT_EQ(renderer->GetOutput()->GetPointData()->GetScalars()->GetNumberOfComponents(), 4);
}

TEST(ReferenceRenderer, HomogeneousSphereHasTheOpacityOfItsDiameter)
{
  // Voxels within 15.6 voxels of the centre (23.5, 23.5, 23.5) hold density 1. Along the central
  // ray that is voxels 8..39; the trilinear ramps add half a voxel at each end, so the chord is
  // 2r with r = 16 voxels.
  const int n = 48;
  const double spacing = 1.0 / (n - 1);
  const double radius = 15.6 * spacing;
  auto field = MakeField(n, 0.0, 1.0, [=](double x, double y, double z) {
    const double dx = x - 0.5, dy = y - 0.5, dz = z - 0.5;
    return dx * dx + dy * dy + dz * dz <= radius * radius ? 1.0 : 0.0;
  });
  const double chord = 2.0 * 16.0 * spacing;
  const float sigma_t = static_cast<float>(1.2 / chord);
  const glm::vec3 albedo(0.9f, 0.8f, 0.7f);
  vtkNew<vtkCloudReferenceRenderer> renderer;
  renderer->SetInputData(field);
  renderer->SetImageSize(15, 15); // odd: the centre pixel's ray goes through the centre
  SetParallelView(renderer, glm::dvec3(0.5), glm::dvec3(0.0, 0.0, -1.0), 0.5);
  renderer->SetVolumeProperty(LinearMedium(sigma_t, albedo));
  const Image image = Render(renderer);

  const float alpha = 1.0f - std::exp(-1.2f);
  const auto centre = [&](int c) { return float(image.At(7, 7, c)); };
  EXPECT_NEAR(centre(3), alpha, 0.01f * alpha);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(centre(c), albedo[c] * centre(3), 1e-5f); // S = c: radiance = c (1 - T)
  }
  for (int corner : { 0, 14 })
  {
    for (int c = 0; c < 4; ++c)
    {
      EXPECT_EQ(image.At(corner, corner, c), 0.0f);
      EXPECT_EQ(image.At(corner, 14 - corner, c), 0.0f);
    }
  }
}

TEST(ReferenceRenderer, SlabLitFromBehindMatchesSingleScattering)
{
  // A homogeneous slab of thickness L seen along -z, a directional light straight behind it
  // (mu = 1), single scattering: T(t) sigma_t 4 pi E P exp(-sigma_t (L - t)) is constant along
  // the ray, so L_out = 4 pi E P(1) sigma_t L exp(-sigma_t L) and alpha = 1 - exp(-sigma_t L).
  auto field = MakeField(33, 0.0, 1.0, [](double, double, double) { return 1.0; });
  const float sigma_t = 1.5f, L = 1.0f;
  vtkNew<vtkCloudReferenceRenderer> renderer;
  renderer->SetInputData(field);
  renderer->SetImageSize(1, 1);
  SetParallelView(renderer, glm::dvec3(0.5), glm::dvec3(0.0, 0.0, -1.0), 0.5);
  renderer->SetVolumeProperty(LinearMedium(sigma_t));
  renderer->SetSampleDistance(1.0 / 256.0);
  LightingParameters p = ModelOnly(LightingModel::March);
  p.MultipleScattering = MultipleScatteringModel::Octaves; // single scattering alone
  p.MultipleScatteringOctaves = 0;
  p.PhaseLobeWeight = 1.0f;
  p.PhaseG1 = 0.5f;
  p.LightStep = 1.0f / 64.0f;
  p.LightStepGrowth = 1.0f;
  p.LightSteps = 64;
  p.Transmittance = LightTransmittance::Nested;
  Light behind;
  behind.Position = glm::vec3(0.5f, 0.5f, -10.0f);
  behind.FocalPoint = glm::vec3(0.5f);
  const Image image = RenderWith(renderer, p, { behind });
  const float expected =
    PhaseToRadiance * HenyeyGreenstein(0.5f, 1.0f) * sigma_t * L * std::exp(-sigma_t * L);
  EXPECT_NEAR(image.At(0, 0, 0), expected, 0.01f * expected);
  EXPECT_NEAR(image.At(0, 0, 3), 1.0f - std::exp(-sigma_t * L), 0.01f);
}

TEST(ReferenceRenderer, LitSideIsBrighterForDerivativeAndMarch)
{
  auto renderer = FrontView(SoftSphere(40));
  for (LightingModel model : { LightingModel::Derivative, LightingModel::March })
  {
    const Image fromRight =
      RenderWith(renderer, ModelOnly(model), { DirectionalLight({ 1, 0, 0 }) });
    EXPECT_GT(
      MeanRadiance(fromRight, Columns(16, 32)), 1.5 * MeanRadiance(fromRight, Columns(0, 16)))
      << int(model);
    const Image fromLeft =
      RenderWith(renderer, ModelOnly(model), { DirectionalLight({ -1, 0, 0 }) });
    EXPECT_GT(MeanRadiance(fromLeft, Columns(0, 16)), 1.5 * MeanRadiance(fromLeft, Columns(16, 32)))
      << int(model);
    EXPECT_GT(MeanRadiance(fromLeft), 0.0);
  }
}

TEST(ReferenceRenderer, LightsAddUp)
{
  auto renderer = FrontView(SoftSphere(40), 24);
  const Light a = DirectionalLight({ 1, 0.5f, 0.2f }, 0.8f, { 1.0f, 0.6f, 0.3f });
  const Light b = PointLight({ -0.5f, 1.5f, 1.0f }, 3.0f);
  // The derivative and the march with the octaves are linear in the lights: exactly additive.
  // The multiple-scattering volume's flux limiter is not (its diffusion coefficient depends on
  // the fluence's own gradient), so two lights' diffuse light adds up only nearly: measured
  // 3.5% of the image's largest value at worst.
  LightingParameters octaves = ModelOnly(LightingModel::March);
  octaves.MultipleScattering = MultipleScatteringModel::Octaves;
  const struct
  {
    LightingParameters Parameters;
    double Tolerance; // of the image's largest value
  } settings[] = { { ModelOnly(LightingModel::Derivative), 3e-5 },
    { octaves, 3e-5 },
    { ModelOnly(LightingModel::March), 0.05 } };
  for (const auto& setting : settings)
  {
    const LightingParameters& p = setting.Parameters; // ambient strength 0
    const Image both = RenderWith(renderer, p, { a, b });
    const Image onlyA = RenderWith(renderer, p, { a });
    const Image onlyB = RenderWith(renderer, p, { b });
    ASSERT_EQ(both.Values.size(), onlyA.Values.size());
    const double largest = *std::max_element(both.Values.begin(), both.Values.end());
    double worst = 0.0;
    for (std::size_t v = 0; v < both.Values.size(); ++v)
    {
      if (v % 4 == 3)
      {
        EXPECT_EQ(both.Values[v], onlyA.Values[v]); // opacity does not depend on the lights
        continue;
      }
      worst = std::max(worst, std::abs(both.Values[v] - (onlyA.Values[v] + onlyB.Values[v])));
    }
    EXPECT_LT(worst, setting.Tolerance * largest)
      << LightingModelName(p.Model) << ", " << MultipleScatteringModelName(p.MultipleScattering)
      << ": worst " << worst / largest << " of the largest value";
    EXPECT_GT(largest, 0.05f);
    EXPECT_GT(MeanRadiance(onlyB), 0.0);
  }
}

TEST(ReferenceRenderer, PointLightFallsOffWithDistance)
{
  auto renderer = FrontView(SoftSphere(40), 24);
  for (LightingModel model : { LightingModel::Derivative, LightingModel::March })
  {
    const double nearer =
      MeanRadiance(RenderWith(renderer, ModelOnly(model), { PointLight({ 0, 0, 2 }) }));
    const double farther =
      MeanRadiance(RenderWith(renderer, ModelOnly(model), { PointLight({ 0, 0, 4 }) }));
    EXPECT_GT(nearer, 0.0);
    EXPECT_LT(farther, 0.5 * nearer) << int(model);
  }
}

TEST(ReferenceRenderer, AmbientLightsEveryVisibleSample)
{
  auto renderer = FrontView(SoftSphere(40), 24);
  for (LightingModel model : { LightingModel::Derivative, LightingModel::March })
  {
    LightingParameters p = ModelOnly(model);
    p.AmbientColor = glm::vec3(0.5f, 1.0f, 1.0f);
    p.AmbientStrength = 2.0f;
    // No lights: S = c A, radiance = c A (1 - T), as emission-absorption with color c A.
    const Image image = RenderWith(renderer, p, {});
    const auto centre = [&](int c) { return float(image.At(12, 12, c)); };
    EXPECT_NEAR(centre(0), 0.9f * 1.0f * centre(3), 1e-5f) << int(model);
    EXPECT_NEAR(centre(1), 0.8f * 2.0f * centre(3), 1e-5f) << int(model);
  }
}

TEST(ReferenceRenderer, MarchConvergesAsStepsShrink)
{
  // Halving the view step and the light step while doubling the light steps (uniform segments,
  // so the light march covers the same distance) hardly changes the image.
  auto field = SoftSphere(40);
  const double spacing = field->GetSpacing()[0];
  auto renderer = FrontView(field, 32);
  renderer->SetVolumeProperty(LinearMedium(3.0f));
  LightingParameters p = ModelOnly(LightingModel::March);
  p.LightStepGrowth = 1.0f;
  p.Transmittance = LightTransmittance::Nested;
  const std::vector<Light> lights = { DirectionalLight({ 1, 1, 0.5f }) };

  renderer->SetSampleDistance(spacing);
  p.LightStep = float(2.0 * spacing);
  p.LightSteps = 12;
  const double coarse = MeanRadiance(RenderWith(renderer, p, lights));
  renderer->SetSampleDistance(0.5 * spacing);
  p.LightStep = float(spacing);
  p.LightSteps = 24;
  const double fine = MeanRadiance(RenderWith(renderer, p, lights));
  EXPECT_GT(coarse, 0.0);
  EXPECT_NEAR(fine, coarse, 0.02 * coarse);
}

TEST(ReferenceRenderer, ZeroDistancesMeanFourAndTwoVoxels)
{
  // The derivative distance 0 is 4 smallest spacings and the first light step 0 is 2.
  auto field = SoftSphere(24);
  field->SetSpacing(2.0 / 23.0, 1.5 / 23.0, 2.0 / 23.0);
  const float smallest = float(1.5 / 23.0);
  auto renderer = FrontView(field, 16);
  const std::vector<Light> lights = { DirectionalLight({ 1, 0.3f, 0 }) };
  LightingParameters automatic = ModelOnly(LightingModel::Derivative);
  LightingParameters explicitly = automatic;
  explicitly.DerivativeDistance = 4.0f * smallest;
  const Image a = RenderWith(renderer, automatic, lights);
  EXPECT_EQ(a.Values, RenderWith(renderer, explicitly, lights).Values);
  explicitly.DerivativeDistance = 8.0f * smallest;
  EXPECT_NE(a.Values, RenderWith(renderer, explicitly, lights).Values);

  automatic.Model = explicitly.Model = LightingModel::March;
  // The light step shapes the nested march (the light volumes march at the view's step).
  automatic.Transmittance = explicitly.Transmittance = LightTransmittance::Nested;
  explicitly.LightStep = 2.0f * smallest;
  const Image m = RenderWith(renderer, automatic, lights);
  EXPECT_EQ(m.Values, RenderWith(renderer, explicitly, lights).Values);
  explicitly.LightStep = 3.0f * smallest;
  EXPECT_NE(m.Values, RenderWith(renderer, explicitly, lights).Values);
}

TEST(ReferenceRenderer, UnsignedCharFieldRendersLikeTheFloatField)
{
  auto field = SoftSphere(24);
  auto bytes = vtkSmartPointer<vtkImageData>::New();
  bytes->CopyStructure(field);
  vtkNew<vtkUnsignedCharArray> scalars;
  auto* source = vtkFloatArray::SafeDownCast(field->GetPointData()->GetScalars());
  scalars->SetNumberOfTuples(source->GetNumberOfTuples());
  for (vtkIdType v = 0; v < source->GetNumberOfTuples(); ++v)
  {
    const float quantised = std::round(source->GetValue(v) * 255.0f);
    scalars->SetValue(v, static_cast<unsigned char>(quantised));
    source->SetValue(v, quantised / 255.0f);
  }
  bytes->GetPointData()->SetScalars(scalars);
  auto floatRenderer = FrontView(field, 16);
  auto byteRenderer = FrontView(bytes, 16);
  byteRenderer->SetVolumeProperty(LinearMedium(6.0f, glm::vec3(0.9f, 0.8f, 0.7f), 255.0));
  const std::vector<Light> lights = { DirectionalLight({ 1, 0, 0 }) };
  const Image a = RenderWith(floatRenderer, ModelOnly(LightingModel::March), lights);
  const Image b = RenderWith(byteRenderer, ModelOnly(LightingModel::March), lights);
  ASSERT_EQ(a.Values.size(), b.Values.size());
  for (std::size_t v = 0; v < a.Values.size(); ++v)
  {
    EXPECT_NEAR(a.Values[v], b.Values[v], 1e-4f) << v;
  }
}

TEST(ReferenceRenderer, RefusesBadInput)
{
  auto sphere = SoftSphere(12);

  auto noTable = FrontView(sphere, 8);
  noTable->SetVolumeProperty(nullptr);
  EXPECT_EQ(CountErrors(noTable), 1);

  auto vectors = vtkSmartPointer<vtkImageData>::New();
  vectors->CopyStructure(sphere);
  vtkNew<vtkFloatArray> threeComponents;
  threeComponents->SetNumberOfComponents(3);
  threeComponents->SetNumberOfTuples(sphere->GetNumberOfPoints());
  threeComponents->Fill(0.0);
  vectors->GetPointData()->SetScalars(threeComponents);
  EXPECT_EQ(CountErrors(FrontView(vectors, 8)), 1);

  // A rotated image is drawn (ReferenceRenderer.HonoursTheImageGeometry...); a flattened one
  // cannot be.
  auto flattened = vtkSmartPointer<vtkImageData>::New();
  flattened->DeepCopy(sphere);
  flattened->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 1, 1, 0);
  EXPECT_EQ(CountErrors(FrontView(flattened, 8)), 1);

  auto emptyImage = FrontView(sphere, 8);
  emptyImage->SetImageSize(0, 8);
  EXPECT_GE(CountErrors(emptyImage), 1);

  auto negativeStep = FrontView(sphere, 8);
  negativeStep->SetSampleDistance(-0.1);
  EXPECT_EQ(CountErrors(negativeStep), 1);

  auto tinyStep = FrontView(sphere, 8); // beyond the 65536 samples a ray may take
  tinyStep->SetSampleDistance(1e-9);
  EXPECT_EQ(CountErrors(tinyStep), 1);

  auto noSpacing = vtkSmartPointer<vtkImageData>::New();
  noSpacing->DeepCopy(sphere);
  noSpacing->SetSpacing(0.1, std::nan(""), 0.1);
  EXPECT_EQ(CountErrors(FrontView(noSpacing, 8)), 1);

  auto notANumber = vtkSmartPointer<vtkImageData>::New();
  notANumber->DeepCopy(sphere);
  notANumber->GetPointData()->GetScalars()->SetComponent(7, 0, std::nan(""));
  EXPECT_EQ(CountErrors(FrontView(notANumber, 8)), 1);

  auto badLighting = FrontView(sphere, 8);
  LightingParameters p = ModelOnly(LightingModel::March);
  p.PhaseG1 = 1.5f;
  badLighting->GetLightingProperty()->SetParameters(p);
  EXPECT_EQ(CountErrors(badLighting), 1);

  auto tooManyLights = FrontView(sphere, 8);
  tooManyLights->SetLights(MakeLights(std::vector<Light>(9, DirectionalLight({ 1, 0, 0 }))));
  EXPECT_EQ(CountErrors(tooManyLights), 1);

  auto blindCamera = FrontView(sphere, 8);
  blindCamera->SetCameraFocalPoint(0.0, 0.0, 5.0);
  EXPECT_EQ(CountErrors(blindCamera), 1);

  // And a good one runs silently.
  EXPECT_EQ(CountErrors(FrontView(sphere, 8)), 0);
}

TEST(ReferenceRenderer, ReportsProgressAndStopsWhenAborted)
{
  auto renderer = FrontView(SoftSphere(24), 32);
  std::vector<double> progress;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&progress);
  onProgress->SetCallback([](vtkObject* caller, unsigned long, void* clientData, void* data) {
    auto* seen = static_cast<std::vector<double>*>(clientData);
    seen->push_back(*static_cast<double*>(data));
    if (seen->back() > 0.2)
    {
      static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
    }
  });
  const Image full = Render(renderer);
  renderer->AddObserver(vtkCommand::ProgressEvent, onProgress);
  const Image aborted = Render(renderer);
  ASSERT_GE(progress.size(), 2u);
  EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));
  EXPECT_LT(progress.back(), 0.5);
  // The rows below the abort are rendered, the top ones (where the sphere also is) are not.
  EXPECT_GT(full.Radiance(16, 6), 0.0f);
  EXPECT_EQ(aborted.Radiance(16, 6), full.Radiance(16, 6));
  EXPECT_GT(full.Radiance(16, 24), 0.0f);
  EXPECT_EQ(aborted.Radiance(16, 24), 0.0f);
}

TEST(ReferenceRenderer, SequentialStdThreadAndTbbBackendsGiveTheSameImage)
{
  auto renderer = FrontView(SoftSphere(24), 24);
  renderer->GetLightingProperty()->SetParameters(ModelOnly(LightingModel::March));
  renderer->SetLights(MakeLights({ DirectionalLight({ 1, 1, 0 }), PointLight({ 0, -1.5f, 1 }) }));
  const std::string original = vtkSMPTools::GetBackend();
  std::vector<Image> images;
  for (const char* backend : { "Sequential", "STDThread", "TBB" })
  {
    ASSERT_TRUE(vtkSMPTools::SetBackend(backend)) << backend;
    images.push_back(Render(renderer));
  }
  vtkSMPTools::SetBackend(original.c_str());
  EXPECT_EQ(images[1].Values, images[0].Values);
  EXPECT_EQ(images[2].Values, images[0].Values);
}

// Every parameter reaches the renderer through VTK objects (what Python can pass): the lights as
// vtkLights, where a switched-off one does not light and a change to one re-renders; the lighting
// property and the volume property, whose changes re-render too, as VTK's pipeline promises.
TEST(ReferenceRenderer, TakesItsParametersAsVtkObjectsAndFollowsTheirChanges)
{
  auto renderer = FrontView(SoftSphere(40), 16);
  vtkNew<vtkCloudLightingProperty> lighting;
  lighting->SetModelToDerivative();
  renderer->SetLightingProperty(lighting);
  EXPECT_EQ(renderer->GetLightingProperty(), lighting.Get());
  const auto update = [&]()
  {
    renderer->Update(); // no Modified(): the renderer must see the objects' changes itself
    return ImageOf(renderer->GetOutput());
  };
  const double unlit = MeanRadiance(update());
  EXPECT_EQ(unlit, 0.0); // no lights, no ambient

  const vtkSmartPointer<vtkLight> sun = MakeLight(DirectionalLight({ 1, 0, 0 }));
  renderer->GetLights()->AddItem(sun);
  const double lit = MeanRadiance(update());
  EXPECT_GT(lit, 0.01);
  sun->SetIntensity(2.0);
  EXPECT_NEAR(MeanRadiance(update()), 2.0 * lit, 1e-5 * lit);
  sun->SwitchOff();
  EXPECT_EQ(MeanRadiance(update()), 0.0);
  sun->SwitchOn();

  lighting->SetAmbientStrength(1.0f);
  const double withAmbient = MeanRadiance(update());
  EXPECT_GT(withAmbient, 2.0 * lit + 0.01);
  renderer->GetVolumeProperty()->GetScalarOpacity()->RemoveAllPoints();
  renderer->GetVolumeProperty()->GetScalarOpacity()->AddPoint(0.0, 0.0);
  renderer->GetVolumeProperty()->GetScalarOpacity()->AddPoint(1.0, 0.0);
  EXPECT_EQ(MeanRadiance(update()), 0.0) << "a transparent medium shows nothing";

  renderer->SetLightingProperty(nullptr); // back to a default property: model none
  EXPECT_NE(renderer->GetLightingProperty(), nullptr);
  EXPECT_EQ(renderer->GetLightingProperty()->GetModel(), vtkCloudLightingProperty::NoLighting);
  renderer->SetLights(nullptr);
  EXPECT_EQ(renderer->GetLights()->GetNumberOfItems(), 0);
}

TEST(LightingProperty, DefaultsAreThoseOfLightingParameters)
{
  vtkNew<vtkCloudLightingProperty> property;
  ExpectSameLighting(property->GetParameters(), LightingParameters(), "defaults");
  // The values the class documentation states.
  EXPECT_EQ(property->GetModel(), vtkCloudLightingProperty::NoLighting);
  EXPECT_EQ(property->GetLightSteps(), 6);
  EXPECT_EQ(property->GetLightStepGrowth(), 1.6f);
  EXPECT_EQ(property->GetPhaseG1(), 0.6f);
  EXPECT_EQ(property->GetPhaseG2(), -0.3f);
  EXPECT_EQ(property->GetPhaseLobeWeight(), 0.8f);
  EXPECT_EQ(property->GetMultipleScattering(), vtkCloudLightingProperty::ScatteringVolume);
  EXPECT_EQ(property->GetMultipleScatteringOctaves(), 3);
  EXPECT_EQ(property->GetAmbientStrength(), 0.0f);
  EXPECT_EQ(property->GetAmbientColor()[0], 1.0f);
}

TEST(LightingProperty, EverySetterReachesTheParametersAndOnlyChangesModify)
{
  const LightingParameters v = EveryLightingParameterChanged();
  ASSERT_EQ(v.Model, LightingModel::March);
  ASSERT_EQ(v.Transmittance, LightTransmittance::Nested);
  vtkNew<vtkCloudLightingProperty> property;
  property->SetModelToMarch();
  property->SetAmbientColor(v.AmbientColor.r, v.AmbientColor.g, v.AmbientColor.b);
  property->SetAmbientStrength(v.AmbientStrength);
  property->SetDerivativeDistance(v.DerivativeDistance);
  property->SetLightSteps(v.LightSteps);
  property->SetLightStep(v.LightStep);
  property->SetLightStepGrowth(v.LightStepGrowth);
  property->SetPhaseG1(v.PhaseG1);
  property->SetPhaseG2(v.PhaseG2);
  property->SetPhaseLobeWeight(v.PhaseLobeWeight);
  property->SetMultipleScattering(int(v.MultipleScattering));
  property->SetMultipleScatteringOctaves(v.MultipleScatteringOctaves);
  property->SetScatteringFalloff(v.ScatteringFalloff);
  property->SetExtinctionFalloff(v.ExtinctionFalloff);
  property->SetEccentricityFalloff(v.EccentricityFalloff);
  property->SetPowderStrength(v.PowderStrength);
  property->SetTransmittanceToNestedMarch();
  const LightingParameters p = property->GetParameters();
  ExpectSameLighting(p, v, "setters");

  vtkNew<vtkCloudLightingProperty> copy;
  copy->DeepCopy(property);
  ExpectSameLighting(copy->GetParameters(), v, "deep copy");
  const vtkMTimeType time = copy->GetMTime();
  copy->SetParameters(p); // the same values
  EXPECT_EQ(copy->GetMTime(), time);
  copy->SetPhaseG1(0.1f);
  EXPECT_GT(copy->GetMTime(), time);
}

// One table names the models: the property's names and values are the table's, in its order,
// and a name finds its model back.
TEST(LightingProperty, ModelNamesAndValuesAreTheOneTables)
{
  vtkNew<vtkCloudLightingProperty> property;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < LightingModelTable().size(); ++i)
  {
    const LightingModelEntry& entry = LightingModelTable()[i];
    EXPECT_EQ(int(entry.Model), int(i)) << "in the enumeration's order";
    property->SetModel(int(entry.Model));
    EXPECT_STREQ(property->GetModelAsString(), entry.Name);
    EXPECT_EQ(property->GetParameters().Model, entry.Model);
    EXPECT_EQ(FindLightingModel(entry.Name), entry.Model);
    EXPECT_STREQ(LightingModelName(entry.Model), entry.Name);
    names.emplace_back(entry.Name);
  }
  EXPECT_EQ(names, LightingModelNames());
  EXPECT_EQ(names, (std::vector<std::string>{ "none", "derivative", "march", "pathtrace" }))
    << "the names scene files and --lighting take";
  EXPECT_FALSE(FindLightingModel("lit"));
  property->SetModel(99);
  EXPECT_EQ(property->GetModel(), vtkCloudLightingProperty::PathTraceLighting) << "clamped";
  property->SetModel(-3);
  EXPECT_EQ(property->GetModel(), vtkCloudLightingProperty::NoLighting);
  property->SetTransmittance(7);
  EXPECT_EQ(property->GetParameters().Transmittance, LightTransmittance::Nested);
}

// The march's two ways of adding multiple scattering have one table of names too: the property's
// values and names are the table's, a name finds its model back, the setters modify only on a
// change, and a value outside the enumeration is refused by the validation, not rendered.
TEST(LightingProperty, MultipleScatteringNamesAndValuesAreTheOneTable)
{
  vtkNew<vtkCloudLightingProperty> property;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < MultipleScatteringModelTable().size(); ++i)
  {
    const MultipleScatteringModelEntry& entry = MultipleScatteringModelTable()[i];
    EXPECT_EQ(int(entry.Model), int(i)) << "in the enumeration's order";
    property->SetMultipleScattering(int(entry.Model));
    EXPECT_STREQ(property->GetMultipleScatteringAsString(), entry.Name);
    EXPECT_EQ(property->GetParameters().MultipleScattering, entry.Model);
    EXPECT_EQ(FindMultipleScatteringModel(entry.Name), entry.Model);
    EXPECT_STREQ(MultipleScatteringModelName(entry.Model), entry.Name);
    names.emplace_back(entry.Name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{ "volume", "octaves" }))
    << "the names scene files and compare's march:NAME take";
  EXPECT_FALSE(FindMultipleScatteringModel("diffusion"));
  EXPECT_STREQ(MultipleScatteringModelName(MultipleScatteringModel(7)), "unknown");

  property->SetMultipleScatteringToVolume();
  EXPECT_EQ(property->GetMultipleScattering(), vtkCloudLightingProperty::ScatteringVolume);
  const vtkMTimeType time = property->GetMTime();
  property->SetMultipleScatteringToVolume();
  EXPECT_EQ(property->GetMTime(), time) << "the same value";
  property->SetMultipleScatteringToOctaves();
  EXPECT_EQ(property->GetParameters().MultipleScattering, MultipleScatteringModel::Octaves);
  EXPECT_GT(property->GetMTime(), time);
  property->SetMultipleScattering(9);
  EXPECT_EQ(property->GetMultipleScattering(), vtkCloudLightingProperty::ScatteringOctaves)
    << "clamped";
  property->SetMultipleScattering(-2);
  EXPECT_EQ(property->GetMultipleScattering(), vtkCloudLightingProperty::ScatteringVolume);

  LightingParameters p;
  for (const MultipleScatteringModelEntry& entry : MultipleScatteringModelTable())
  {
    p.MultipleScattering = entry.Model;
    EXPECT_EQ(ValidateLightingParameters(p), "") << entry.Name;
  }
  p.MultipleScattering = MultipleScatteringModel(7); // a C++ caller's cast
  EXPECT_EQ(ValidateLightingParameters(p),
    "the multiple scattering must be volume or octaves, got the value 7");
  LightingParameters other = p;
  other.MultipleScattering = MultipleScatteringModel::Volume;
  EXPECT_FALSE(other == p) << "operator== sees the choice";
}

// A scene's lights reach a CPU renderer as cloudvis::Lights and light the cloud exactly as the
// same lights made vtkLights do; a light collection set afterwards takes their place.
TEST(ReferenceRenderer, CloudLightsLightAsTheirVtkLightsAndGiveWayToACollection)
{
  auto renderer = FrontView(SoftSphere(24), 24);
  renderer->GetLightingProperty()->SetParameters(ModelOnly(LightingModel::Derivative));
  const std::vector<Light> lights = { DirectionalLight({ 1, 1, 0 }), PointLight({ 0, -1.5f, 1 }) };
  renderer->SetLights(lights);
  ASSERT_NE(renderer->GetCloudLights(), nullptr);
  EXPECT_TRUE(renderer->GetLightList() == lights);
  const Image asLights = Render(renderer);
  EXPECT_GT(MeanRadiance(asLights), 0.01);

  renderer->SetLights(MakeLights(lights));
  EXPECT_EQ(renderer->GetCloudLights(), nullptr);
  EXPECT_EQ(Render(renderer).Values, asLights.Values);

  renderer->SetLights(lights);
  EXPECT_EQ(Render(renderer).Values, asLights.Values);
  renderer->SetLights(vtkSmartPointer<vtkLightCollection>::New()); // no vtkLights, no ambient
  EXPECT_EQ(renderer->GetCloudLights(), nullptr);
  EXPECT_EQ(MeanRadiance(Render(renderer)), 0.0);
}

// Not a test: how long a 128 x 128 render of a 64^3 field takes per model, for the report.
// Run with --gtest_also_run_disabled_tests --gtest_filter='*Timing*'.
TEST(ReferenceRenderer, DISABLED_Timing128x128Of64Cubed)
{
  auto renderer = FrontView(SoftSphere(64), 128);
  renderer->ParallelProjectionOff();
  renderer->SetCameraPosition(0.0, 0.0, 4.0);
  const char* names[] = { "none", "derivative", "march" };
  for (LightingModel model :
    { LightingModel::None, LightingModel::Derivative, LightingModel::March })
  {
    LightingParameters p = ModelOnly(model);
    p.AmbientStrength = 0.2f;
    renderer->GetLightingProperty()->SetParameters(p);
    renderer->SetLights(MakeLights({ DirectionalLight({ 1, 1, 0.5f }) }));
    const auto start = std::chrono::steady_clock::now();
    renderer->Modified();
    renderer->Update();
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "128x128 of 64^3, " << names[int(model)] << ": " << seconds * 1000.0 << " ms"
              << std::endl;
  }
}
