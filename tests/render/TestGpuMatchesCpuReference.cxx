// The GPU mapper against the CPU reference of the same equations (vtkCloudReferenceRenderer):
// the same field, geometry, camera, transfer table, lights, ambient and step, jitter off,
// compared on the float images (premultiplied radiance and opacity) before any 8-bit rounding.
//
// Each case changes one thing a user relies on: the lighting model, a point light, the lighting
// parameters off their defaults (powder, both lobes and their weight, each multiple-scattering
// falloff, the octave count, the mapper's extinction scale), and where the volume is: a
// rotated image direction and vtkVolume orientation, a moved, scaled and user-transformed
// vtkVolume, an extent that does not start at 0, a volume 1e10 units from the origin and one
// 1e19 units wide; and how the field is stored (unsigned short and unsigned char texels, half
// floats). The reference is given the very objects the mapper renders with (the volume property,
// the lighting property, the renderer's lights), as a user would.
//
// The gate is over the pixels where either image shows cloud (opacity above 1e-4), relative to
// the brightest reference radiance, and a case fails on an empty image. What is left between
// the two is arithmetic, not equations: the GPU's texture filters have 8-bit weights (trilinear
// density and the transfer-table lookup; the CPU interpolates exactly) and its matrix products
// round differently, which moves a sample by a few ulps; where the density is sharp (the
// constant sphere's surface) that can add or drop a whole sample at the edge. Gates per platform,
// 3 to 5 times what was measured on llvmpipe (docs/reliability.md lists the figures).
#include "SupportReference.h"
#include "SupportScene.h"

#include "SupportMappers.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkMatrix4x4.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPointData.h>
#include <vtkTransform.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <string>

using namespace cloudvis;
using namespace cloudvis::support;

namespace
{
constexpr int Size = 64;

struct Comparison
{
  double Brightest = 0.0; // largest reference radiance over r, g, b
  size_t CloudPixels = 0; // pixels where either image has opacity above 1e-4
  double RmsColor = 0.0;  // over r, g, b of the cloud pixels
  double MaxColor = 0.0;
  double MaxAlpha = 0.0;
};

Comparison CompareOverTheCloud(const Image& gpu, const Image& cpu)
{
  const Mask cloud = OpacityAbove(gpu, cpu, 1e-4f);
  const Difference color = Compare(gpu, cpu, 3, cloud);
  Comparison c;
  c.CloudPixels = color.Count / 3;
  c.RmsColor = color.Rms;
  c.MaxColor = color.Max;
  c.MaxAlpha = Compare(gpu, cpu, 1, cloud, 3).Max;
  c.Brightest = Largest(cpu, 3, cloud);
  return c;
}

// A similarity transform of the whole scene, world' = Offset + Scale * world: applied to the
// field's origin and spacing, the camera, the lights and the unit distance, it must not change
// the image (the march's local frame makes that hold in float).
struct Similarity
{
  double Scale = 1.0;
  double Offset = 0.0; // along each axis
  double Apply(double x) const { return this->Offset + this->Scale * x; }
};

struct Case
{
  std::string Name;
  LightingModel Model = LightingModel::March;
  bool Cloud = true;       // the article's cloud (perspective) or a constant sphere (parallel)
  bool PointLight = false; // a point light in front of the cloud instead of the sun
  bool SunToo = false;     // with PointLight: the sun as well, two lights of both kinds
  std::function<void(LightingParameters&)> Lighting = [](LightingParameters&) {};
  double ExtinctionScale = 1.0;
  // Where the volume is: the field's geometry and the vtkVolume's matrix (the camera keeps
  // looking at the volume's centre from the same side).
  std::function<void(vtkImageData*, vtkVolume*)> Place = [](vtkImageData*, vtkVolume*) {};
  Similarity World;
  // How the field is stored: its scalar type (the cloud quantized to unsigned char or short, the
  // transfer function scaled with it), and for a float field whether the mapper keeps it as half
  // floats. Storage the GPU reads with less precision than the reference raises the gates to
  // its own, from what it measures (on every platform: the loss is the storage's).
  int ScalarType = VTK_FLOAT;
  bool HalfFloat = false;
  double RmsGate = 0.0;
  double MaxGate = 0.0;
};

// The scene's radiance per pixel from both renderers.
struct Rendered
{
  Image Gpu;
  Image Cpu;
  std::string Renderer; // the GL renderer's name
};

Rendered RenderBoth(const Case& c)
{
  const double step = 0.05 * c.World.Scale;
  LightingParameters lighting;
  lighting.Model = c.Model;
  lighting.AmbientColor = glm::vec3(0.6f, 0.6f, 0.75f);
  lighting.AmbientStrength = 0.2f;
  c.Lighting(lighting);

  vtkNew<vtkCloudVolumeMapper> mapper;
  mapper->SetSampleDistance(step);
  mapper->JitterOff();
  mapper->GetLightingProperty()->SetParameters(lighting);
  mapper->SetExtinctionScale(c.ExtinctionScale);
  mapper->SetHalfFloatDensity(c.HalfFloat);
  GpuScene scene(mapper, Size, Size);
  const vtkSmartPointer<vtkImageData> field =
    support::QuantizedField(c.Cloud ? SparseCloud(40) : ConstantSphere(1.2, 40), c.ScalarType);
  const double* origin = field->GetOrigin();
  const double* spacing = field->GetSpacing();
  field->SetOrigin(c.World.Apply(origin[0]), c.World.Apply(origin[1]), c.World.Apply(origin[2]));
  field->SetSpacing(
    c.World.Scale * spacing[0], c.World.Scale * spacing[1], c.World.Scale * spacing[2]);
  c.Place(field, scene.Volume);
  scene.SetInput(field);
  if (c.Cloud)
  {
    SetRampMedium(scene.Property, support::FullScale(c.ScalarType), 0.6);
  }
  else
  {
    SetUniformMedium(scene.Property, 0.3, 0.1, 0.9, 0.8, 0.7);
  }
  scene.Property->SetScalarOpacityUnitDistance(
    c.World.Scale * scene.Property->GetScalarOpacityUnitDistance());

  double bounds[6];
  scene.Volume->GetBounds(bounds);
  const double centre[3] = {
    0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])
  };
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  const double distance = 6.0 * c.World.Scale;
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0], centre[1], centre[2] + distance);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetParallelProjection(!c.Cloud);
  camera->SetParallelScale(1.6 * c.World.Scale);
  camera->SetViewAngle(30.0);
  camera->SetClippingRange(0.1 * c.World.Scale, (2.0 * 6.0 + 10.0) * c.World.Scale);

  // One directional light (or a point light, brighter to make up for its falloff, or both), placed
  // by the similarity; a point light's inverse-square falloff is rescaled so that it lights alike.
  if (c.PointLight)
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetDiffuseColor(1.0, 0.9, 0.8);
    light->SetIntensity(0.8 * 9.0);
    light->SetPositional(true);
    light->SetConeAngle(180.0);
    light->SetPosition(centre[0], centre[1], centre[2] + 2.5 * c.World.Scale);
    light->SetFocalPoint(centre);
    light->SetAttenuationValues(0.0, 0.0, 1.0 / (c.World.Scale * c.World.Scale));
    scene.Renderer->AddLight(light);
  }
  if (!c.PointLight || c.SunToo)
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetDiffuseColor(1.0, 0.9, 0.8);
    light->SetIntensity(0.8);
    light->SetPosition(centre[0] + 6.0, centre[1] + 8.0, centre[2] + 4.0);
    light->SetFocalPoint(centre);
    scene.Renderer->AddLight(light);
  }

  Rendered r;
  r.Gpu = scene.RenderFloat();
  EXPECT_EQ(mapper->GetLastError(), "");
  r.Renderer = vtkOpenGLRenderWindow::SafeDownCast(scene.Window)->ReportCapabilities();

  // The reference, given the very objects the mapper was given: the field, the camera after the
  // render, the volume property and extinction scale (it builds the mapper's table), the
  // lighting property, the renderer's lights, the volume's matrix, the step.
  vtkNew<vtkCloudReferenceRenderer> reference;
  ConfigureReference(reference, scene);
  reference->Update();
  r.Cpu = ImageOf(reference->GetOutput());
  Dump(r.Gpu, "gpu-vs-cpu-" + c.Name + "-gpu");
  Dump(r.Cpu, "gpu-vs-cpu-" + c.Name + "-cpu");
  return r;
}

bool OnLlvmpipe(const std::string& capabilities)
{
  return capabilities.find("llvmpipe") != std::string::npos;
}

// The test's name in ctest's list, rather than the parameter's bytes.
void PrintTo(const Case& c, std::ostream* out)
{
  *out << c.Name;
}

class GpuMatchesCpuReference : public ::testing::TestWithParam<Case>
{
};

// Rotation by `degrees` about `axis` as a direction matrix.
void SetRotatedDirection(vtkImageData* field, double degrees, double x, double y, double z)
{
  vtkNew<vtkTransform> rotation;
  rotation->RotateWXYZ(degrees, x, y, z);
  double m[9];
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 3; ++col)
      m[3 * r + col] = rotation->GetMatrix()->GetElement(r, col);
  field->SetDirectionMatrix(m);
}
}

TEST_P(GpuMatchesCpuReference, WithinTolerance)
{
  const Case& c = GetParam();
  const Rendered r = RenderBoth(c);
  ASSERT_EQ(r.Gpu.Width, Size);
  ASSERT_EQ(r.Gpu.Height, Size);
  ASSERT_EQ(r.Cpu.Values.size(), size_t(4 * Size * Size)) << "the reference rendered nothing";

  const Comparison d = CompareOverTheCloud(r.Gpu, r.Cpu);
  std::cout << c.Name << ": " << d.CloudPixels << " cloud pixels, brightest " << d.Brightest
            << ", color RMS " << d.RmsColor / d.Brightest << " of it, max "
            << d.MaxColor / d.Brightest << "; alpha max " << d.MaxAlpha << "\n";
  RecordProperty("RelativeRms", std::to_string(d.RmsColor / d.Brightest));
  RecordProperty("RelativeMax", std::to_string(d.MaxColor / d.Brightest));
  // Not an empty window: the cloud covers a good part of the image, and is bright.
  ASSERT_GT(d.CloudPixels, Size * Size / 10) << "the scene must show a cloud to compare";
  ASSERT_GT(d.Brightest, 0.05) << "the scene must show a cloud to compare";
  // Measured on llvmpipe over all cases: RMS 0.06e-6 .. 3.5e-6 and max 0.5e-6 .. 2.1e-5 of the
  // peak, alpha max up to 2.3e-5. Elsewhere (not measured yet) ten times looser, and the constant
  // sphere's max at 5%: another GPU's rounding may add or drop a whole sample on its surface.
  const bool llvmpipe = OnLlvmpipe(r.Renderer);
  const double rmsGate = std::max(c.RmsGate, llvmpipe ? 1e-5 : 1e-4);
  const double maxGate = std::max(c.MaxGate, llvmpipe ? 1e-4 : c.Cloud ? 1e-3 : 0.05);
  EXPECT_LT(d.RmsColor, rmsGate * d.Brightest);
  EXPECT_LT(d.MaxColor, maxGate * d.Brightest);
  EXPECT_LT(d.MaxAlpha, maxGate);
}

namespace
{
std::vector<Case> Cases()
{
  std::vector<Case> cases;
  for (LightingModel model :
    { LightingModel::None, LightingModel::Derivative, LightingModel::March })
  {
    const std::string name = model == LightingModel::None ? "None"
      : model == LightingModel::Derivative                ? "Derivative"
                                                          : "March";
    Case cloud;
    cloud.Name = name + "Cloud";
    cloud.Model = model;
    cases.push_back(cloud);
    Case sphere = cloud;
    sphere.Name = name + "Sphere";
    sphere.Cloud = false;
    cases.push_back(sphere);
    if (model != LightingModel::None)
    {
      Case point = cloud;
      point.Name = name + "CloudPointLight";
      point.PointLight = true;
      cases.push_back(point);
    }
  }
  // Every lighting parameter off its default at least once.
  Case lobes;
  lobes.Name = "MarchTwoLobesPowder";
  lobes.Lighting = [](LightingParameters& p)
  {
    p.PhaseG1 = 0.85f;
    p.PhaseG2 = -0.5f;
    p.PhaseLobeWeight = 0.55f;
    p.PowderStrength = 0.7f;
  };
  cases.push_back(lobes);
  // The droplets' Mie table (the texture and the shared evaluation), with the sun in front so
  // that the forward peak and the bow both fall on the cloud, and their moments in the volume.
  Case droplets;
  droplets.Name = "MarchDropletPhase";
  droplets.Lighting = [](LightingParameters& p)
  {
    p.Phase = PhaseModel::Droplets;
    p.DropletEffectiveRadius = 8.0f;
  };
  cases.push_back(droplets);
  Case dropletPoint = droplets;
  dropletPoint.Name = "MarchDropletPhasePointLight";
  dropletPoint.PointLight = true;
  cases.push_back(dropletPoint);
  Case octaves;
  octaves.Name = "MarchOctavesAndFalloffs";
  octaves.Lighting = [](LightingParameters& p)
  {
    p.MultipleScattering = MultipleScatteringModel::Octaves;
    p.MultipleScatteringOctaves = 6;
    p.ScatteringFalloff = 0.7f;
    p.ExtinctionFalloff = 0.3f;
    p.EccentricityFalloff = 0.8f;
    p.LightSteps = 9;
    p.LightStepGrowth = 1.3f;
    p.Transmittance = LightTransmittance::Nested; // where the light steps count
  };
  cases.push_back(octaves);
  // The quality setting: a nested march toward each light at every sample (every other march
  // case reads the light volumes, the default).
  for (const bool point : { false, true })
  {
    Case nested;
    nested.Name = point ? "MarchCloudPointLightNested" : "MarchCloudNested";
    nested.PointLight = point;
    nested.Lighting = [](LightingParameters& p) { p.Transmittance = LightTransmittance::Nested; };
    cases.push_back(nested);
  }
  // The multiple-scattering volume (every march case above reads it) from a point light and the
  // sun together, with the light volumes and with the nested march toward the lights: its source
  // sums both kinds, and the cloud's albedo (the ramp's colours) is below 1 in every channel.
  for (const bool nested : { false, true })
  {
    Case both;
    both.Name = nested ? "MarchSunAndPointLightNested" : "MarchSunAndPointLight";
    both.PointLight = true;
    both.SunToo = true;
    if (nested)
    {
      both.Lighting = [](LightingParameters& p) { p.Transmittance = LightTransmittance::Nested; };
    }
    cases.push_back(both);
  }
  Case singleScattering;
  singleScattering.Name = "MarchSingleScatteringExtinctionScale";
  singleScattering.Lighting = [](LightingParameters& p)
  {
    p.MultipleScattering = MultipleScatteringModel::Octaves;
    p.MultipleScatteringOctaves = 0;
  };
  singleScattering.ExtinctionScale = 2.5;
  cases.push_back(singleScattering);
  Case derivativeDistance;
  derivativeDistance.Name = "DerivativeDistanceAndExtinctionScale";
  derivativeDistance.Model = LightingModel::Derivative;
  derivativeDistance.Lighting = [](LightingParameters& p) { p.DerivativeDistance = 0.2f; };
  derivativeDistance.ExtinctionScale = 0.4;
  cases.push_back(derivativeDistance);

  // Where the volume is.
  Case rotated;
  rotated.Name = "RotatedDirectionAndVolume";
  rotated.Place = [](vtkImageData* field, vtkVolume* volume)
  {
    SetRotatedDirection(field, 35.0, 1.0, 2.0, 0.5);
    volume->RotateWXYZ(-50.0, 0.3, 1.0, 0.2);
  };
  cases.push_back(rotated);
  Case moved;
  moved.Name = "MovedScaledVolume";
  moved.Model = LightingModel::Derivative;
  moved.Place = [](vtkImageData*, vtkVolume* volume)
  {
    volume->SetOrigin(0.5, 0.0, 0.0);
    volume->SetPosition(3.0, -1.0, 2.0);
    volume->SetScale(1.3, 0.7, 1.1);
    vtkNew<vtkTransform> user;
    user->Translate(0.0, 0.4, 0.0);
    user->RotateZ(20.0);
    volume->SetUserTransform(user);
  };
  cases.push_back(moved);
  Case extent;
  extent.Name = "ExtentStartingAtMinus10";
  extent.Place = [](vtkImageData* field, vtkVolume*)
  {
    const double* origin = field->GetOrigin();
    const double* spacing = field->GetSpacing();
    int e[6];
    field->GetExtent(e);
    // The same voxels in the same place, indexed from -10 (as vtkRTAnalyticSource's).
    field->SetOrigin(
      origin[0] + 10 * spacing[0], origin[1] + 10 * spacing[1], origin[2] + 10 * spacing[2]);
    field->SetExtent(e[0] - 10, e[1] - 10, e[2] - 10, e[3] - 10, e[4] - 10, e[5] - 10);
  };
  cases.push_back(extent);
  Case far;
  far.Name = "FarFromTheOrigin";
  far.World.Offset = 1e10;
  far.PointLight = true;
  cases.push_back(far);
  // The field in the types the mapper uploads natively, the march lighting the cloud.
  const auto stored = [&](const char* name, int type, bool half, double rms, double max)
  {
    Case c;
    c.Name = name;
    c.ScalarType = type;
    c.HalfFloat = half;
    c.RmsGate = rms;
    c.MaxGate = max;
    cases.push_back(c);
  };
  // Unsigned short texels (R16) filter like floats: the common gates (measured on llvmpipe: RMS
  // 1.9e-6, max 1.5e-5 of the peak, alpha 1.3e-5).
  stored("UnsignedShortCloud", VTK_UNSIGNED_SHORT, false, 0.0, 0.0);
  // Unsigned char texels (R8): llvmpipe filters them in 8-bit fixed point (the interpolated
  // value comes back rounded to a multiple of 1/255: measured on R8, R16, R32F and R16F
  // textures, only R8 does it), so its density is off the exact interpolation by up to about a
  // byte level, where the CPU's is exact. Measured: RMS 8.7e-4, max 5.5e-3 of the peak, alpha
  // 5.1e-3; gates 3.5x that.
  stored("UnsignedCharCloud", VTK_UNSIGNED_CHAR, false, 3e-3, 2e-2);
  // Half floats (R16F) round each voxel to 11 significant bits before anything is filtered, and
  // the CPU reference reads the full floats: this measures the precision half floats give up.
  // Measured: RMS 1.05e-5, max 7.3e-5 of the peak, alpha 7.3e-5; gates about 4x that.
  stored("HalfFloatCloud", VTK_FLOAT, true, 4e-5, 3e-4);

  Case huge;
  huge.Name = "HugeField";
  huge.World.Scale = 1e19; // a field 4e19 units wide: its squared lengths overflow float
  huge.PointLight = true;
  cases.push_back(huge);
  return cases;
}
}

INSTANTIATE_TEST_SUITE_P(Cases,
  GpuMatchesCpuReference,
  ::testing::ValuesIn(Cases()),
  [](const ::testing::TestParamInfo<Case>& parameter) { return parameter.param.Name; });

// A scene moved far from the origin, or scaled up or down enormously (camera, lights and unit
// distance with it), is the same scene: each renderer must draw it as it draws the scene at the
// origin. Before the march computed in its local frame, the GPU drew the first two blank.
TEST(GpuMatchesCpuReference, FarAwayAndHugeFieldsRenderLikeTheSameFieldAtTheOrigin)
{
  Case base;
  base.Name = "AtTheOrigin";
  base.PointLight = true;
  const Rendered atOrigin = RenderBoth(base);
  const bool llvmpipe = OnLlvmpipe(atOrigin.Renderer);
  for (const Similarity world : { Similarity{ 1.0, 1e10 },
         Similarity{ 1e19, 0.0 },
         Similarity{ std::ldexp(1.0, 60), 0.0 },
         Similarity{ 1e-12, -3e-9 } })
  {
    Case moved = base;
    moved.World = world;
    moved.Name = "Scale" + std::to_string(world.Scale) + "Offset" + std::to_string(world.Offset);
    const Rendered r = RenderBoth(moved);
    const Comparison gpu = CompareOverTheCloud(r.Gpu, atOrigin.Gpu);
    const Comparison reference = CompareOverTheCloud(r.Cpu, atOrigin.Cpu);
    std::cout << "scale " << world.Scale << ", offset " << world.Offset
              << ": GPU vs GPU at the origin, max " << gpu.MaxColor / gpu.Brightest << " RMS "
              << gpu.RmsColor / gpu.Brightest << " of the peak; CPU vs CPU max "
              << reference.MaxColor / reference.Brightest << " RMS "
              << reference.RmsColor / reference.Brightest << "\n";
    ASSERT_GT(gpu.CloudPixels, Size * Size / 10) << "an empty window proves nothing";
    ASSERT_GT(gpu.Brightest, 0.05);
    // Measured on llvmpipe: 0 for the offset and the power-of-two scale (the same floats),
    // up to 2.9e-5 (GPU) and 3.3e-6 (CPU) of the peak for the others, where the scaled spacing
    // rounds differently.
    EXPECT_LT(gpu.MaxColor, (llvmpipe ? 1e-4 : 1e-3) * gpu.Brightest);
    EXPECT_LT(reference.MaxColor, 1e-5 * reference.Brightest);
    if (world.Scale == std::ldexp(1.0, 60) || world.Scale == 1.0)
    {
      EXPECT_EQ(gpu.MaxColor, 0.0) << "a power-of-two scale and an exact offset change no float";
      EXPECT_EQ(reference.MaxColor, 0.0);
    }
  }
}
