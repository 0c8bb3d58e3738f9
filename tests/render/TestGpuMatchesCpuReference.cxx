// The GPU mapper against the CPU reference of the same equations (vtkCloudReferenceRenderer),
// model by model: the same field, camera, transfer table, lights, ambient and step, jitter off,
// compared on the float images (premultiplied radiance and opacity) before any 8-bit rounding.
//
// Tolerances, per model and field: RMS over r, g, b below 1% and the largest difference below 5%
// of the brightest reference radiance; alpha within 1% RMS and 5% max of 1. What is left is not a
// difference in the equations but in arithmetic: the GPU's filtered texture fetches have 8-bit
// filter weights (trilinear density and the linear transfer-table lookup: up to 1/256 of the
// step between neighbouring texels, where the reference interpolates exactly), the GPU works in
// float with float matrices where the reference uses double matrices, so sample positions, and
// with them the sample lattice at a surface, differ by a few ulps. A sharp-edged field (the
// constant sphere) turns such a shift into an occasional whole sample more or less at the edge:
// that is what the 5% bounds, while the RMS bound catches any systematic difference.
//
// The point-light cases cover what a directional light cannot: per-sample light directions and
// the distance falloff (with only a directional light, a model that ignored positional lights
// would pass).
#include "CpuReference.h"
#include "RenderFixture.h"

#include "CloudTransferTable.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

using namespace cloudvis;
using namespace cloudvis::test;

namespace
{
constexpr int Size = 96;

struct Comparison
{
  double Brightest = 0.0;  // largest reference radiance over r, g, b
  double RmsColor = 0.0;   // over r, g, b and all pixels
  double MaxColor = 0.0;
  double RmsAlpha = 0.0;
  double MaxAlpha = 0.0;
};

Comparison Compare(const Image& gpu, const std::vector<float>& cpu)
{
  Comparison c;
  double sumColor = 0.0, sumAlpha = 0.0;
  for (size_t i = 0; i < cpu.size(); ++i)
  {
    const double d = std::abs(double(gpu.RGBA[i]) - double(cpu[i]));
    if (i % 4 == 3)
    {
      sumAlpha += d * d;
      c.MaxAlpha = std::max(c.MaxAlpha, d);
    }
    else
    {
      sumColor += d * d;
      c.MaxColor = std::max(c.MaxColor, d);
      c.Brightest = std::max(c.Brightest, double(cpu[i]));
    }
  }
  const double pixels = double(cpu.size() / 4);
  c.RmsColor = std::sqrt(sumColor / (3.0 * pixels));
  c.RmsAlpha = std::sqrt(sumAlpha / pixels);
  return c;
}

struct Case
{
  LightingModel Model;
  bool Cloud; // the article's cloud (perspective) or a constant sphere (parallel projection)
  bool PointLight = false; // a point light in front of the cloud instead of the sun
};

std::string NameOf(const Case& c)
{
  const char* model = c.Model == LightingModel::None ? "None"
    : c.Model == LightingModel::Derivative          ? "Derivative"
                                                     : "March";
  return std::string(model) + (c.Cloud ? "Cloud" : "Sphere") + (c.PointLight ? "PointLight" : "");
}

class GpuMatchesCpuReference : public ::testing::TestWithParam<Case>
{
};
}

TEST_P(GpuMatchesCpuReference, WithinTolerance)
{
  const Case& c = GetParam();
  const double step = 0.05;
  LightingParameters lighting;
  lighting.Model = c.Model;
  lighting.AmbientColor = glm::vec3(0.6f, 0.6f, 0.75f);
  lighting.AmbientStrength = 0.2f;
  // One directional light (or a point light, brighter to make up for its falloff).
  Light sun;
  sun.Positional = false;
  sun.Position = glm::vec3(6.0f, 8.0f, 4.0f);
  sun.FocalPoint = glm::vec3(0.0f);
  sun.Color = glm::vec3(1.0f, 0.9f, 0.8f);
  sun.Intensity = 0.8f;
  if (c.PointLight)
  {
    sun.Positional = true;
    sun.Position = glm::vec3(0.0f, 0.0f, 2.5f);
    sun.Intensity *= 9.0f;
  }

  vtkNew<vtkCloudVolumeMapper> mapper;
  mapper->SetSampleDistance(step);
  mapper->JitterOff();
  mapper->SetLighting(lighting);
  test::Scene scene(mapper, Size, Size);
  const vtkSmartPointer<vtkImageData> field = c.Cloud ? SparseCloud(48) : ConstantSphere(1.2, 40);
  scene.SetInput(field);
  if (c.Cloud)
  {
    SetRampMedium(scene.Property, 1.0, 0.6);
    scene.LookAlongMinusZ(6.0, false);
  }
  else
  {
    SetUniformMedium(scene.Property, 0.3, 0.1, 0.9, 0.8, 0.7);
    scene.LookAlongMinusZ(6.0, true, 1.6);
  }
  if (c.PointLight)
  {
    AddPointLight(scene.Renderer, sun.Position.x, sun.Position.y, sun.Position.z, sun.Intensity,
      sun.Color.r, sun.Color.g, sun.Color.b);
  }
  else
  {
    AddDirectionalLight(scene.Renderer, sun.Position.x, sun.Position.y, sun.Position.z,
      sun.Intensity, sun.Color.r, sun.Color.g, sun.Color.b);
  }
  const Image gpu = scene.RenderFloat();
  ASSERT_EQ(gpu.Width, Size);
  ASSERT_EQ(gpu.Height, Size);

  // The reference, given what the mapper was given: the camera after the render (whatever the
  // renderer did to it), the table the mapper builds (1024 entries over the scalar range).
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  vtkNew<vtkCloudReferenceRenderer> reference;
  reference->SetInputData(field);
  reference->SetImageSize(Size, Size);
  SetReferenceCamera(reference, camera); // as render --cpu-reference does
  double range[2];
  field->GetPointData()->GetScalars()->GetRange(range, 0);
  vtkVolumeProperty* property = scene.Property;
  reference->SetTransferTable(BuildTransferTable(property->GetRGBTransferFunction(0),
    property->GetScalarOpacity(0), property->GetScalarOpacityUnitDistance(0), range, 1024));
  reference->SetLighting(lighting);
  reference->SetLights({ sun });
  reference->SetSampleDistance(step);
  reference->Update();
  auto* rgba = vtkFloatArray::SafeDownCast(reference->GetOutput()->GetPointData()->GetScalars());
  ASSERT_NE(rgba, nullptr);
  const std::vector<float> cpu(rgba->GetPointer(0), rgba->GetPointer(0) + 4 * Size * Size);

  Image cpuImage;
  cpuImage.Width = cpuImage.Height = Size;
  cpuImage.RGBA = cpu;
  Dump(gpu, "gpu-vs-cpu-" + NameOf(c) + "-gpu");
  Dump(cpuImage, "gpu-vs-cpu-" + NameOf(c) + "-cpu");

  const Comparison d = Compare(gpu, cpu);
  std::cout << NameOf(c) << ": brightest " << d.Brightest << ", color RMS " << d.RmsColor
            << " (" << 100.0 * d.RmsColor / d.Brightest << "%), max " << d.MaxColor << " ("
            << 100.0 * d.MaxColor / d.Brightest << "%); alpha RMS " << d.RmsAlpha << ", max "
            << d.MaxAlpha << "\n";
  RecordProperty("RelativeRms", std::to_string(d.RmsColor / d.Brightest));
  RecordProperty("RelativeMax", std::to_string(d.MaxColor / d.Brightest));
  ASSERT_GT(d.Brightest, 0.05) << "the scene must show something to compare";
  EXPECT_LT(d.RmsColor, 0.01 * d.Brightest);
  EXPECT_LT(d.MaxColor, 0.05 * d.Brightest);
  EXPECT_LT(d.RmsAlpha, 0.01);
  EXPECT_LT(d.MaxAlpha, 0.05);
}

INSTANTIATE_TEST_SUITE_P(Models, GpuMatchesCpuReference,
  ::testing::Values(Case{ LightingModel::None, true }, Case{ LightingModel::Derivative, true },
    Case{ LightingModel::March, true }, Case{ LightingModel::None, false },
    Case{ LightingModel::Derivative, false }, Case{ LightingModel::March, false },
    Case{ LightingModel::Derivative, true, true }, Case{ LightingModel::March, true, true }),
  [](const ::testing::TestParamInfo<Case>& parameter) { return NameOf(parameter.param); });
