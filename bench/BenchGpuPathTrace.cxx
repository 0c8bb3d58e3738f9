// The GPU path tracer (vtkCloudVolumeMapper's pathtrace model) against the CPU one
// (vtkCloudPathTracer) in one run, on the shipped scenes as `cloudvis render --lighting pathtrace`
// renders them (the app's scene reader, field, camera, transfer function, lights and ambient):
// per scene and renderer, the paths per second, the image's relative standard error (the RMS of
// the pixels' standard errors over the mean radiance of the cloud's footprint, MeasureImageNoise),
// and the time to 1% relative standard error at 800 x 600, extrapolated from the run (the error
// falls as 1 / sqrt(paths), the time grows with the paths and the pixels); and the GPU/CPU ratio.
//
// Usage: cloudvis-bench-gpu-pathtrace [--size WxH] [--spp N] [--cpu-size WxH] [SCENE.json ...]
//   --size      the GPU's image (default 800x600: the figure is measured, not extrapolated)
//   --spp       paths per pixel of both renderers (default 16)
//   --cpu-size  the CPU's image (default 200x150; its time is scaled to 800 x 600)
//   scenes      default data/scenes/fbm-sphere.json, two-lights.json, sphere.json
// Needs an X display (xvfb-run -a on a headless machine). The GPU is timed through RenderOffscreen
// (what `cloudvis render` runs) from the end of its first frame (shader compilation, uploads) to
// the image read back; at least 16 paths per pixel, so that some frames follow the first.
#include "CloudImageComparison.h"
#include "CpuReference.h"
#include "OffscreenRender.h"
#include "Scene.h"
#include "SceneField.h"
#include "vtkCloudPathTracer.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>
#include <vtkTimerLog.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

using namespace cloudvis;

namespace
{
struct Options
{
  int Width = 800, Height = 600;
  int CpuWidth = 200, CpuHeight = 150;
  int Samples = 16;
  std::vector<std::string> Scenes;
};

// One renderer's run: seconds for Samples paths per pixel and the image's noise.
struct Run
{
  double Seconds = 0.0;
  ImageNoise Noise;
  int Width = 0, Height = 0, Samples = 0;

  double PathsPerSecond() const { return double(Width) * Height * Samples / Seconds; }
  // Paths per pixel to reach 1% relative standard error, and the time that takes at 800 x 600.
  double SamplesToOnePercent() const
  {
    return Samples * std::pow(Noise.RelativeStandardError / 0.01, 2.0);
  }
  double SecondsToOnePercentAt800x600() const
  {
    return Seconds / Samples * SamplesToOnePercent() * (800.0 * 600.0) / (double(Width) * Height);
  }
};

Scene SceneAt(const std::string& path, int width, int height, int samples)
{
  Scene scene = LoadScene(path, {});
  scene.Render.Lighting.Model = LightingModel::PathTrace;
  scene.Render.Size = { { width, height } };
  scene.Render.SamplesPerPixel = samples;
  scene.Render.ResolutionScale = 1.0;
  return scene;
}

// `cloudvis render` itself (RenderOffscreen, float image kept for the variance), timed from the
// end of its first frame (shader compilation, uploads, occupancy) to the image read back: the
// paths of the frames after the first.
Run RunGpu(const Scene& scene, vtkImageData* field)
{
  double start = 0.0;
  int framesTimed = 0;
  RenderOptions options;
  options.FloatImage = true;
  options.OnFrame = [&](int frame, int frames)
  {
    if (frame == 1)
    {
      start = vtkTimerLog::GetUniversalTime();
    }
    framesTimed = frames - 1;
  };
  const OffscreenRenderResult result = RenderOffscreen(scene, field, scene.Source, 0, options);
  Run run;
  run.Seconds = vtkTimerLog::GetUniversalTime() - start;
  const RenderedImage& image = result.Image;
  if (framesTimed < 1 || image.Variance.empty())
  {
    throw std::runtime_error("the GPU path tracer needs at least two frames (spp above 8)");
  }
  run.Width = image.Width;
  run.Height = image.Height;
  run.Samples = result.AccumulatedSamples / result.AccumulatedFrames * framesTimed;
  run.Noise = MeasureImageNoise(
    image.Radiance.data(), image.Variance.data(), std::size_t(image.Width) * image.Height);
  // The noise is that of all the paths; the time, of the timed ones.
  run.Noise.RelativeStandardError *=
    std::sqrt(double(result.AccumulatedSamples) / double(run.Samples));
  return run;
}

Run RunCpu(const Scene& scene, vtkImageData* field)
{
  // The camera and settings as the GPU's (SetUpReference, as RenderCpuReference).
  const int width = scene.Render.Size[0], height = scene.Render.Size[1];
  vtkNew<vtkCloudPathTracer> tracer;
  SetUpReference(scene, field, tracer);
  tracer->SetSamplesPerPixel(scene.Render.SamplesPerPixel);
  const double start = vtkTimerLog::GetUniversalTime();
  tracer->Update();
  Run run;
  run.Seconds = vtkTimerLog::GetUniversalTime() - start;
  vtkPointData* data = tracer->GetOutput()->GetPointData();
  auto* rgba = vtkFloatArray::SafeDownCast(data->GetArray("rgba"));
  auto* variance = vtkFloatArray::SafeDownCast(data->GetArray("rgba_variance"));
  if (!rgba || !variance || rgba->GetNumberOfTuples() != vtkIdType(width) * height)
  {
    throw std::runtime_error("the CPU path tracer rendered nothing");
  }
  run.Width = width;
  run.Height = height;
  run.Samples = scene.Render.SamplesPerPixel;
  run.Noise =
    MeasureImageNoise(rgba->GetPointer(0), variance->GetPointer(0), std::size_t(width) * height);
  return run;
}

bool ParseSize(const char* text, int& width, int& height)
{
  return std::sscanf(text, "%dx%d", &width, &height) == 2 && width >= 16 && height >= 16;
}
}

int main(int argc, char* argv[])
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const bool hasValue = i + 1 < argc;
    if (!std::strcmp(argv[i], "--size") && hasValue)
    {
      if (!ParseSize(argv[++i], options.Width, options.Height))
      {
        std::fprintf(stderr, "--size expects WxH, each at least 16\n");
        return 2;
      }
    }
    else if (!std::strcmp(argv[i], "--cpu-size") && hasValue)
    {
      if (!ParseSize(argv[++i], options.CpuWidth, options.CpuHeight))
      {
        std::fprintf(stderr, "--cpu-size expects WxH, each at least 16\n");
        return 2;
      }
    }
    else if (!std::strcmp(argv[i], "--spp") && hasValue)
    {
      options.Samples = std::atoi(argv[++i]);
      if (options.Samples < 16)
      {
        std::fprintf(stderr, "--spp expects an integer of at least 16\n");
        return 2;
      }
    }
    else if (argv[i][0] == '-')
    {
      std::fprintf(stderr,
        "usage: cloudvis-bench-gpu-pathtrace [--size WxH] [--spp N] [--cpu-size WxH] "
        "[SCENE.json ...]\n");
      return 2;
    }
    else
    {
      options.Scenes.push_back(argv[i]);
    }
  }
  if (options.Scenes.empty())
  {
    options.Scenes = {
      "data/scenes/fbm-sphere.json", "data/scenes/two-lights.json", "data/scenes/sphere.json"
    };
  }
  try
  {
    std::printf("GPU %d x %d, CPU %d x %d (vtkSMPTools %s, %d threads), %d paths per pixel\n\n",
      options.Width,
      options.Height,
      options.CpuWidth,
      options.CpuHeight,
      vtkSMPTools::GetBackend(),
      vtkSMPTools::GetEstimatedNumberOfThreads(),
      options.Samples);
    std::printf(
      "| scene | GPU paths/s | CPU paths/s | GPU / CPU | relative standard error "
      "(GPU, CPU) | time to 1%% at 800x600, GPU | CPU |\n|---|---|---|---|---|---|---|\n");
    for (const std::string& path : options.Scenes)
    {
      const Scene gpuScene = SceneAt(path, options.Width, options.Height, options.Samples);
      const Scene cpuScene = SceneAt(path, options.CpuWidth, options.CpuHeight, options.Samples);
      const vtkSmartPointer<vtkImageData> field = ProduceField(gpuScene);
      const Run gpu = RunGpu(gpuScene, field);
      const Run cpu = RunCpu(cpuScene, field);
      std::string name = path.substr(path.find_last_of('/') + 1);
      std::printf("| %s | %.3g | %.3g | %.2f | %.2f%%, %.2f%% | %.0f s (%.0f paths per pixel) | "
                  "%.0f s (%.0f) |\n",
        name.c_str(),
        gpu.PathsPerSecond(),
        cpu.PathsPerSecond(),
        gpu.PathsPerSecond() / cpu.PathsPerSecond(),
        100.0 * gpu.Noise.RelativeStandardError,
        100.0 * cpu.Noise.RelativeStandardError,
        gpu.SecondsToOnePercentAt800x600(),
        gpu.SamplesToOnePercent(),
        cpu.SecondsToOnePercentAt800x600(),
        cpu.SamplesToOnePercent());
      std::fflush(stdout);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "cloudvis-bench-gpu-pathtrace: %s\n", e.what());
    return 1;
  }
  return 0;
}
