// `cloudvis-bench-pathtrace speed`: how fast the path tracer (vtkCloudPathTracer) converges on
// scenes, and, as its peer in the same run, the time of the CPU march of the scene's lighting
// model (vtkCloudReferenceRenderer; the march for a pathtrace scene, whose parameters the path
// tracer takes).
#include "CloudImageComparison.h"
#include "PathTraceBench.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkImageData.h>
#include <vtkSMPTools.h>

#include <cmath>
#include <cstdio>

namespace cloudvis
{
namespace bench
{

int Speed(const Options& options)
{
  std::vector<std::string> files = options.Scenes;
  if (files.empty())
    files = {
      "data/scenes/fbm-sphere.json", "data/scenes/two-lights.json", "data/scenes/sphere.json"
    };
  std::vector<BenchScene> scenes;
  for (const std::string& file : files)
    scenes.push_back(ReadBenchScene(file)); // every scene checked before anything is printed
  std::printf("%d x %d, %d paths per pixel, bounce cap %d, bricks of %d voxels, vtkSMPTools %s "
              "with %d threads\n\n",
    options.Width,
    options.Height,
    options.Samples,
    options.Bounces,
    options.BrickSize,
    vtkSMPTools::GetBackend(),
    vtkSMPTools::GetEstimatedNumberOfThreads());
  std::printf("| scene | path tracer | paths/s (all pixels) | paths/s (cloud pixels) | relative "
              "standard error | time to 1%% at 800x600 | CPU march (%s) | one path per pixel "
              "costs |\n|---|---|---|---|---|---|---|---|\n",
    "scene's model");
  for (const BenchScene& scene : scenes)
  {
    const vtkSmartPointer<vtkImageData> field = FieldOf(scene.Spec);
    LightingParameters lighting = scene.Spec.Render.Lighting;
    if (lighting.Model == LightingModel::PathTrace)
      lighting.Model = LightingModel::March;

    const Rendered traced = Run(NewTracer(scene.Spec, field, options.Bounces, options));
    const Rendered marched = Run(NewMarch(scene.Spec, field, lighting, options));

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
      scene.Name.c_str(),
      traced.Seconds,
      paths / traced.Seconds,
      double(noise.Pixels) * options.Samples / traced.Seconds,
      100.0 * noise.RelativeStandardError,
      seconds800x600,
      samplesNeeded,
      marched.Seconds,
      traced.Seconds / options.Samples / marched.Seconds);
    std::fflush(stdout);
  }
  std::printf("\n(time to 1%%: extrapolated from this run, the error falling as 1 / sqrt(paths) "
              "and the time growing with the pixels; the footprint is the pixels of opacity > "
              "%.2f)\n",
    double(FootprintOpacity));
  return 0;
}

} // namespace bench
} // namespace cloudvis
