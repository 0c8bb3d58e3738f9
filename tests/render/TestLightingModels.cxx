// The lighting models on the GPU: the physics each must show (lit side bright, lights adding
// up, falloff, step-size invariance), and pictures of the seeds' scene for looking.
#include "RenderFixture.h"

#include <vtkCamera.h>
#include <vtkLightCollection.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace cloudvis;
using namespace cloudvis::test;

namespace
{
vtkSmartPointer<vtkCloudVolumeMapper> LitMapper(LightingModel model, double step = 0.03)
{
  auto mapper = vtkSmartPointer<vtkCloudVolumeMapper>::New();
  mapper->SetSampleDistance(step);
  mapper->JitterOff();
  LightingParameters lighting;
  lighting.Model = model;
  mapper->GetLightingProperty()->SetParameters(lighting);
  return mapper;
}

// Mean red radiance of the right half minus the left half of a render lit from +x or -x.
double RightMinusLeft(LightingModel model, double lightX)
{
  auto mapper = LitMapper(model);
  Scene scene(mapper, 64, 64);
  scene.SetInput(SparseCloud(48));
  SetRampMedium(scene.Property, 1.0, 0.6);
  AddDirectionalLight(scene.Renderer, lightX, 0.0, 0.0, 1.0);
  const Image image = scene.RenderFloat();
  Dump(image, std::string("lit-from-") + (lightX > 0 ? "right-" : "left-") +
      (model == LightingModel::March ? "march" : "derivative"));
  return MeanOver(image, 0, 32, 64) - MeanOver(image, 0, 0, 32);
}

class EveryLightModel : public ::testing::TestWithParam<LightingModel>
{
};
}

TEST_P(EveryLightModel, TheSideFacingTheLightIsBrighterAndMovingTheLightFlipsIt)
{
  EXPECT_GT(RightMinusLeft(GetParam(), 10.0), 0.002);
  EXPECT_LT(RightMinusLeft(GetParam(), -10.0), -0.002);
}

TEST_P(EveryLightModel, LightsAddUp)
{
  // With no ambient term the source is linear in the lights, and the transmittance does not
  // depend on them: the image of A and B together is the sum of the images of each.
  const auto render = [&](bool a, bool b) {
    auto mapper = LitMapper(GetParam());
    Scene scene(mapper, 48, 48);
    scene.SetInput(SparseCloud(48));
    SetRampMedium(scene.Property, 1.0, 0.6);
    if (a)
      AddDirectionalLight(scene.Renderer, 10.0, 5.0, 3.0, 0.7);
    if (b)
      AddPointLight(scene.Renderer, -2.5, 1.0, 2.0, 4.0, 1.0, 0.5, 0.8);
    return scene.RenderFloat();
  };
  const Image both = render(true, true), onlyA = render(true, false), onlyB = render(false, true);
  double largest = 0.0, brightest = 0.0;
  for (size_t i = 0; i < both.RGBA.size(); ++i)
  {
    if (i % 4 != 3)
    {
      largest = std::max(largest, double(std::abs(both.RGBA[i] - onlyA.RGBA[i] - onlyB.RGBA[i])));
      brightest = std::max(brightest, double(both.RGBA[i]));
    }
  }
  EXPECT_GT(brightest, 0.05);
  EXPECT_LT(largest, 1e-3 * std::max(1.0, brightest));
}

TEST_P(EveryLightModel, APointLightDimsWithDistance)
{
  const auto brightness = [&](double distance) {
    auto mapper = LitMapper(GetParam());
    Scene scene(mapper, 48, 48);
    scene.SetInput(SparseCloud(48));
    SetRampMedium(scene.Property, 1.0, 0.6);
    AddPointLight(scene.Renderer, 0.0, 0.0, distance, 9.0);
    return MeanOver(scene.RenderFloat(), 1, 0, 48);
  };
  EXPECT_GT(brightness(2.5), 1.5 * brightness(5.0));
}

INSTANTIATE_TEST_SUITE_P(Models, EveryLightModel,
  ::testing::Values(LightingModel::Derivative, LightingModel::March),
  [](const ::testing::TestParamInfo<LightingModel>& parameter) {
    return parameter.param == LightingModel::March ? "March" : "Derivative";
  });

TEST(LightMarch, HalvingBothStepsChangesTheMeanRadianceByUnderTwoPercent)
{
  const auto mean = [](double step, double lightStep, int lightSteps) {
    auto mapper = LitMapper(LightingModel::March, step);
    LightingParameters lighting = mapper->GetLightingProperty()->GetParameters();
    lighting.LightStep = float(lightStep);
    lighting.LightSteps = lightSteps;
    lighting.LightStepGrowth = 1.0f;
    mapper->GetLightingProperty()->SetParameters(lighting);
    Scene scene(mapper, 64, 64);
    scene.SetInput(SparseCloud(64));
    SetRampMedium(scene.Property, 1.0, 0.6);
    AddDirectionalLight(scene.Renderer, 5.0, 5.0, 2.0, 3.0);
    const Image image = scene.RenderFloat();
    return MeanOver(image, 0, 0, 64) + MeanOver(image, 1, 0, 64) + MeanOver(image, 2, 0, 64);
  };
  const double coarse = mean(0.04, 0.08, 12), fine = mean(0.02, 0.04, 24);
  EXPECT_GT(coarse, 0.01);
  EXPECT_LT(std::abs(coarse - fine) / fine, 0.02);
}

TEST(LightingPictures, TheSeedsCloudUnderASunAndAPinkPointLight)
{
  // Not an assertion of looks, but of the scene being lit at all; the pictures are dumped. The
  // cloud must differ from the background by several levels over much of the middle: an empty
  // window (the background alone, whose red is 0.35) fails.
  for (LightingModel model : { LightingModel::None, LightingModel::Derivative, LightingModel::March })
  {
    auto mapper = LitMapper(model, 0.02);
    LightingParameters lighting = mapper->GetLightingProperty()->GetParameters();
    lighting.AmbientColor = glm::vec3(0.60f, 0.60f, 0.75f);
    lighting.AmbientStrength = model == LightingModel::Derivative ? 1.1f : 0.3f;
    mapper->GetLightingProperty()->SetParameters(lighting);
    Scene scene(mapper, 160, 160);
    scene.SetInput(SparseCloud(96));
    scene.Renderer->SetBackground(0.35, 0.45, 0.65);
    SetRampMedium(scene.Property, 1.0, 0.6);
    vtkNew<vtkColorTransferFunction> white;
    white->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
    scene.Property->SetColor(white);
    AddDirectionalLight(scene.Renderer, 6.0, 8.0, 4.0, model == LightingModel::March ? 1.6 : 0.8,
      1.0, model == LightingModel::Derivative ? 0.6 : 1.0, model == LightingModel::Derivative ? 0.3 : 1.0);
    AddPointLight(scene.Renderer, -2.2, -0.5, 1.5, 2.0,
      1.0, 0.4, 0.7);
    const Image image = scene.Render();
    Dump(image, std::string("seed-") +
        (model == LightingModel::None ? "none" : model == LightingModel::March ? "march" : "derivative"));
    int cloudPixels = 0;
    for (int y = 0; y < image.Height; ++y)
      for (int x = 0; x < image.Width; ++x)
        cloudPixels += std::abs(image.At(x, y, 0) - 0.35f) + std::abs(image.At(x, y, 1) - 0.45f) +
            std::abs(image.At(x, y, 2) - 0.65f) >
          6.0f / 255.0f;
    EXPECT_GT(cloudPixels, image.Width * image.Height / 8) << "model " << int(model);
    EXPECT_GT(MeanOver(image, 0, 40, 120), 0.4) << "lit: brighter than the background's 0.35";
  }
}
