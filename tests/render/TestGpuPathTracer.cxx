// The GPU path tracer (vtkCloudVolumeMapper's pathtrace model: shaders/transport/PathTrace.glsl
// compiled as GLSL) against the CPU one (vtkCloudPathTracer: the same source compiled as C++) and
// against closed forms. Both are Monte Carlo estimates with independent seeds, so they agree when
// their difference is within the combined standard error each reports (the GPU's from its
// second-moment target, ReadVariance): checked per channel on the mean over the cloud and on every
// 4 x 4 tile, with 4.5 standard errors as the gate (about one false alarm in 150,000 checks; the
// seeds are fixed, so the outcome is reproducible). Each check also requires the standard error to
// be small against the signal, so a loose estimate cannot pass by being noisy. The closed forms are
// the CPU tests' own (tests/unit/TestPathTracer.cxx): the opacity of a homogeneous slab seen
// obliquely, and the white furnace. A thick furnace checks that an image whose paths the GPU cut
// short is refused. Small images and sample counts: llvmpipe runs the shader on the CPU.
#include "SupportExpectations.h"
#include "SupportReference.h"
#include "SupportScene.h"

#include "CloudMarchUniforms.h"
#include "Errors.h"
#include "ExportRender.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkCamera.h>
#include <vtkLightCollection.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkVolume.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <string>

using namespace cloudvis;

namespace
{
constexpr double Sigmas = 4.5;
constexpr int Size = 24;

using namespace cloudvis::support;

// A path-traced off-screen scene of `field`, Size x Size pixels, lit by the test's lights only
// (no headlight).
struct GpuTrace
{
  vtkNew<vtkCloudVolumeMapper> Mapper;
  GpuScene View{ this->Mapper, Size, Size };

  GpuTrace(vtkImageData* field,
    vtkVolumeProperty* medium,
    const LightingParameters& lighting,
    int samplesPerFrame,
    int seed)
  {
    LightingParameters p = lighting;
    p.Model = LightingModel::PathTrace;
    this->Mapper->GetLightingProperty()->SetParameters(p);
    this->Mapper->SetPathTraceSamplesPerFrame(samplesPerFrame);
    this->Mapper->SetPathTraceSeed(seed);
    this->View.SetInput(field);
    this->View.Volume->SetProperty(medium);
    this->View.Renderer->AutomaticLightCreationOff();
  }

  // The parallel view SetParallelView gives the CPU renderers.
  void LookAt(glm::dvec3 focal, glm::dvec3 view, double scale)
  {
    SetParallelView(this->View.Renderer->GetActiveCamera(), focal, view, scale);
  }

  // Accumulates `frames` frames and reads the mean and its variance; every path must have run
  // whole unless `mayBeCut`.
  Image Render(int frames, bool mayBeCut = false)
  {
    this->Mapper->SetMaximumAccumulatedFrames(frames);
    const Image image = this->View.RenderPathTraced(frames);
    EXPECT_EQ(this->Mapper->GetLastError(), "");
    if (!mayBeCut)
    {
      EXPECT_EQ(this->CutPixels(), 0);
    }
    EXPECT_EQ(this->Mapper->GetNumberOfAccumulatedSamples(this->View.Renderer),
      frames * this->Mapper->GetPathTraceSamplesPerFrame());
    if (image.Values.empty())
    {
      ADD_FAILURE() << "the mapper kept no path-traced image";
    }
    return image;
  }

  vtkIdType CutPixels()
  {
    this->View.Window->MakeCurrent();
    return this->Mapper->CountCutPathTracePixels(this->View.Renderer);
  }
};

// ExpectNoDifference over 4 x 4 tiles at Sigmas, the standard error below `tightness` of
// `scale`, with the observed figures printed (the tolerances' margins, for docs and reports).
void ExpectAgreement(const Image& image,
  const std::function<double(std::size_t)>& difference,
  const std::function<double(std::size_t)>& variance,
  const std::function<bool(std::size_t)>& use,
  double scale,
  int minTiles,
  const std::string& what,
  double tightness = 0.02)
{
  const Estimate mean = MeanOverPixels(image, difference, variance, use);
  int tiles = 0;
  std::cout << what << ": mean difference " << mean.Mean << " +- " << mean.StandardError
            << " (scale " << scale << "), largest tile z "
            << LargestBlockZ(image, 4, difference, variance, use, tiles) << " over " << tiles
            << " tiles\n";
  ExpectNoDifference(image, 4, difference, variance, use, scale, minTiles, what, tightness, Sigmas);
}
}

// The GPU's image `traced` of `gpu`'s scene, `paths` per pixel, against the CPU tracer's with as
// many, channel by channel over the cloud, with their standard errors below `tightness` of the
// mean.
void ExpectAgreesWithCpu(GpuTrace& gpu, const Image& traced, int paths, double tightness)
{
  ASSERT_EQ(traced.Width, Size);
  vtkNew<vtkCloudPathTracer> cpu;
  ConfigureReference(cpu, gpu.View);
  cpu->SetSamplesPerPixel(paths);
  cpu->SetSeed(0);
  const Image reference = Render(cpu);
  ASSERT_EQ(reference.Pixels(), traced.Pixels());

  const auto inCloud = [&](std::size_t p) { return reference.At(p, 3) > 0.0f; };
  for (int channel = 0; channel < 4; ++channel)
  {
    ExpectAgreement(
      traced,
      [&](std::size_t p) { return traced.At(p, channel) - reference.At(p, channel); },
      [&](std::size_t p)
      { return traced.VarianceAt(p, channel) + reference.VarianceAt(p, channel); },
      inCloud,
      MeanOf(reference, channel, inCloud),
      8,
      "channel " + std::to_string(channel),
      tightness);
  }
}

// A heterogeneous, optically thick sphere (optical diameter up to 12) with a coloured albedo,
// lit from the side by a directional light and a point light, in a dim environment, with every
// order of scattering: every estimator of the tracer takes part (free flight, ratio tracking
// with empty bricks leapt and homogeneous bricks integrated, the phase's sampling, roulette, NEE
// to each kind of light, the environment), traced with `phase` on the GPU and the CPU with
// `frames` x 8 paths per pixel, whose standard error must fall below `tightness` of the mean.
void ExpectGpuAgreesWithCpu(PhaseModel phase, int frames, double tightness)
{
  auto field = SoftSphere(24);
  auto medium = LinearMedium(8.0f, glm::vec3(0.9f, 0.8f, 0.7f));
  LightingParameters lighting = Ambient(glm::vec3(0.1f, 0.15f, 0.2f));
  lighting.Phase = phase;
  // Small droplets: a forward peak of about 20 per steradian rather than thousands, so that next-
  // event estimation toward the lights stays within the test's noise budget (the bow and the
  // glory are there at every size).
  lighting.DropletEffectiveRadius = 2.0f;
  GpuTrace gpu(field, medium, lighting, 8, 7);
  gpu.LookAt(glm::dvec3(0.0), glm::dvec3(0.3, -0.2, -1.0), 0.9);
  AddLight(gpu.View.Renderer, DirectionalLight(glm::dvec3(1.0, 0.5, 0.2), 1.5f));
  AddLight(gpu.View.Renderer, PointLight(glm::dvec3(-0.5, 1.5, 1.0), 2.0f));
  ExpectAgreesWithCpu(gpu, gpu.Render(frames), 8 * frames, tightness);
}

TEST(GpuPathTracer, AgreesWithTheCpuPathTracerWithinTheirStandardErrors)
{
  ExpectGpuAgreesWithCpu(PhaseModel::TwoLobe, 16, 0.02); // both lobes, 128 paths per pixel
}

TEST(GpuPathTracer, DropletPhaseAgreesWithTheCpuPathTracer)
{
  // The Mie table's texture, its evaluation at each event and its inverse-CDF sampling with the
  // channels' weights, in GLSL against the same source in C++.
  // Even small droplets' peak makes next-event estimation noisier than the lobes, though both
  // tracers guide next events toward the lights for this phase (LightGuidedNextEvent): 384 paths
  // per pixel leave a standard error of about 1.6% of the mean (1024 plain paths left 2%).
  ExpectGpuAgreesWithCpu(PhaseModel::Droplets, 48, 0.03);
}

TEST(GpuPathTracer, SlabOpacityIsOneMinusExpOfMinusSigmaTimesPath)
{
  // tests/unit/TestPathTracer.cxx's slab: optical thickness sigma_t L, L = 9 / 16, seen at
  // cosine 0.8 to its normal: every pixel's opacity is 1 - exp(-sigma_t L / 0.8); no light, so
  // nothing is scattered toward the eye.
  const double thickness = 9.0 / 16.0;
  const float sigma_t = 2.5f;
  auto slab = MakeBoxField({ 17, 17, 33 },
    { -2.0, -2.0, -1.0 },
    { 2.0, 2.0, 1.0 },
    [](double, double, double z) { return std::abs(z) <= 0.25 + 1e-9 ? 1.0 : 0.0; });
  GpuTrace gpu(slab, LinearMedium(sigma_t), LightingParameters(), 4, 3);
  gpu.LookAt(glm::dvec3(0.0), glm::dvec3(-0.6, 0.0, -0.8), 0.5);
  const Image image = gpu.Render(4);
  const double alpha = 1.0 - std::exp(-sigma_t * thickness / 0.8);
  const auto all = [](std::size_t) { return true; };
  ExpectAgreement(
    image,
    [&](std::size_t p) { return image.At(p, 3) - alpha; },
    [&](std::size_t p) { return image.VarianceAt(p, 3); },
    all,
    alpha,
    30,
    "opacity");
  // The pixels are independent estimates of one value: their scatter checks the variance the
  // mapper reports from its moment target (the sample variance of N pixels has a relative
  // standard error of sqrt(2 / (N - 1))).
  double scatter = 0.0, reported = 0.0;
  for (std::size_t p = 0; p < image.Pixels(); ++p)
  {
    ASSERT_EQ(image.At(p, 0), 0.0f) << "no light, no ambient: nothing is scattered";
    scatter += (image.At(p, 3) - alpha) * (image.At(p, 3) - alpha);
    reported += image.VarianceAt(p, 3);
  }
  const double pixels = double(image.Pixels());
  const double ratio = (scatter / pixels) / (reported / pixels);
  std::cout << "scatter over reported variance: " << ratio << "\n";
  EXPECT_NEAR(ratio, 1.0, Sigmas * std::sqrt(2.0 / (pixels - 1.0)));
}

TEST(GpuPathTracer, WhiteFurnaceMediumVanishesIntoTheEnvironment)
{
  // Albedo 1, no light, a uniform environment A: every path that enters leaves with A, so
  // rgb = A alpha at every pixel, through every order of scattering of a thick sphere.
  const glm::vec3 environment(0.5f, 1.0f, 2.0f);
  GpuTrace gpu(SoftSphere(24), LinearMedium(8.0f), Ambient(environment), 8, 5);
  gpu.LookAt(glm::dvec3(0.0), glm::dvec3(0.3, -0.2, -1.0), 0.8);
  const Image image = gpu.Render(8);
  const auto inCloud = [&](std::size_t p) { return image.At(p, 3) > 0.0f; };
  for (int channel = 0; channel < 3; ++channel)
  {
    ExpectAgreement(
      image,
      [&](std::size_t p) { return image.At(p, channel) - environment[channel] * image.At(p, 3); },
      [&](std::size_t p)
      {
        return image.VarianceAt(p, channel) +
          environment[channel] * environment[channel] * image.VarianceAt(p, 3);
      },
      inCloud,
      MeanOf(image, channel, inCloud),
      8,
      "channel " + std::to_string(channel));
  }
}

TEST(GpuPathTracer, AThickConservativeCloudIsTracedWholeOrRefused)
{
  // The white furnace on a sphere as thick as a real cloud (optical diameter near 240, albedo
  // 1): its walks take about (optical depth)^2 events, more loop turns than a software
  // rasterizer lets a fragment run (llvmpipe ends them all after 65535, without an error), which
  // leaves the image too dark. Either every path ran whole and the image agrees with the CPU
  // tracer, or the mapper counts the pixels cut short and the image is refused, saying why.
  GpuTrace gpu(SoftSphere(24), LinearMedium(200.0f), Ambient(glm::vec3(1.0f)), 8, 5);
  gpu.LookAt(glm::dvec3(0.0), glm::dvec3(0.3, -0.2, -1.0), 0.8);
  const Image traced = gpu.Render(2, true);
  const vtkIdType cut = gpu.CutPixels();
  ASSERT_GE(cut, 0);
  if (cut == 0)
  {
    ExpectAgreesWithCpu(gpu, traced, 16, 0.02);
    return;
  }
  std::cout << cut << " of " << traced.Pixels() << " pixels cut short: refused\n";
  try
  {
    ReadCheckedMapperImage(gpu.Mapper, gpu.View.Renderer, "thick.json");
    ADD_FAILURE() << "an image whose paths were cut short was not refused";
  }
  catch (const InputError& error)
  {
    const std::string expected = "thick.json: the GPU ended the path tracer's walks early on " +
      std::to_string(cut) + " of " + std::to_string(traced.Pixels()) + " pixels";
    EXPECT_EQ(std::string(error.what()).substr(0, expected.size()), expected);
  }
}
