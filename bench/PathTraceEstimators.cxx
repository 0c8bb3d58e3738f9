// `cloudvis-bench-pathtrace estimators`: the path tracer's next-event estimators against each
// other in one run (vtkCloudPathTracer's NextEventEstimator): the plain one, and the light-guided
// one, which also estimates each next event's direct light along a direction drawn toward the
// lights (shaders/transport/PathTrace.glsl, LightGuidedNextEvent). On the case of issue 38, a
// thick cumulus (the shipped one: optical diameter near 100) at albedo 0.99 without ambient, with
// the two lobes and with the droplets' phase, and on the shipped cumulus as it is; or on the scenes
// given. Each is traced with several seeds, because a forward peak gives the plain estimator a
// heavy tail: one seed's standard error understates it, and the spread of the image's mean over
// the seeds shows it.
#include "CloudImageComparison.h"
#include "PathTraceBench.h"
#include "vtkCloudPathTracer.h"

#include <vtkImageData.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cloudvis
{
namespace bench
{

namespace
{
constexpr int Seeds = 3;

// One estimator over the seeds: the total time, the mean of the squared relative standard errors
// (the noise per image), and the image means.
struct EstimatorRun
{
  double Seconds = 0.0;
  double SquaredError = 0.0;
  double Means[Seeds] = {};
};

EstimatorRun RunEstimator(const BenchScene& scene,
  vtkImageData* field,
  int estimator,
  const Options& options)
{
  EstimatorRun run;
  for (int s = 0; s < Seeds; ++s)
  {
    Options seeded = options;
    seeded.Seed = options.Seed + unsigned(s);
    const vtkSmartPointer<vtkCloudPathTracer> tracer =
      NewTracer(scene.Spec, field, options.Bounces, seeded);
    tracer->SetNextEventEstimator(estimator);
    const Rendered traced = Run(tracer);
    const ImageNoise noise = MeasureImageNoise(
      traced.RGBA.data(), traced.Variance.data(), std::size_t(options.Width) * options.Height);
    run.Seconds += traced.Seconds;
    run.SquaredError += noise.RelativeStandardError * noise.RelativeStandardError / Seeds;
    run.Means[s] = noise.MeanRadiance;
    WritePng(options.PngDirectory,
      scene.Name + (estimator == vtkCloudPathTracer::Plain ? "-plain-" : "-guided-") +
        std::to_string(s),
      traced.RGBA,
      options.Width,
      options.Height);
  }
  return run;
}

// The relative spread (largest minus smallest over their mean) of a run's image means.
double MeanSpread(const EstimatorRun& run)
{
  const auto [low, high] = std::minmax_element(run.Means, run.Means + Seeds);
  double sum = 0.0;
  for (double m : run.Means)
    sum += m;
  return sum > 0.0 ? (*high - *low) / (sum / Seeds) : 0.0;
}

void PrintRow(const char* estimator, const EstimatorRun& run, const Options& options)
{
  const double error = std::sqrt(run.SquaredError);
  // The time to 2% at 400 x 300, the error falling as 1 / sqrt(paths) and the time growing with
  // the pixels.
  const double seconds = run.Seconds / Seeds * std::pow(error / 0.02, 2.0) * (400.0 * 300.0) /
    (double(options.Width) * options.Height);
  std::printf("| | %s | %.2f s | %.2f%% | %.4f, %.4f, %.4f (spread %.1f%%) | %.0f s |",
    estimator,
    run.Seconds / Seeds,
    100.0 * error,
    run.Means[0],
    run.Means[1],
    run.Means[2],
    100.0 * MeanSpread(run),
    seconds);
}
}

int Estimators(const Options& options)
{
  std::vector<BenchScene> scenes;
  if (options.Scenes.empty())
  {
    const std::string cumulus = "data/scenes/cumulus.json";
    const std::vector<std::string> thick = { "ambient.strength=0",
      "transfer_function.color=[[0, 0.99, 0.99, 0.99], [1, 0.99, 0.99, 0.99]]",
      "render.lighting=pathtrace" };
    scenes.push_back(ReadBenchScene(cumulus, thick));
    scenes.back().Name = "thick-cumulus-0.99-two-lobes";
    std::vector<std::string> droplets = thick;
    droplets.push_back("render.march.phase=droplets");
    scenes.push_back(ReadBenchScene(cumulus, droplets));
    scenes.back().Name = "thick-cumulus-0.99-droplets";
    scenes.push_back(ReadBenchScene(cumulus, { "render.lighting=pathtrace" }));
    scenes.back().Name = "cumulus-as-shipped";
  }
  for (const std::string& file : options.Scenes)
    scenes.push_back(ReadBenchScene(file));
  std::printf("%d x %d, %d paths per pixel, %d seeds from %u, bounce cap %d, vtkSMPTools %s with "
              "%d threads\n\n",
    options.Width,
    options.Height,
    options.Samples,
    Seeds,
    options.Seed,
    options.Bounces,
    vtkSMPTools::GetBackend(),
    vtkSMPTools::GetEstimatedNumberOfThreads());
  std::printf("| case | estimator | time per image | relative standard error | image mean per "
              "seed | time to 2%% at 400x300 | time to equal noise, plain over light-guided "
              "|\n|---|---|---|---|---|---|---|\n");
  for (const BenchScene& scene : scenes)
  {
    const vtkSmartPointer<vtkImageData> field = FieldOf(scene.Spec);
    const EstimatorRun plain = RunEstimator(scene, field, vtkCloudPathTracer::Plain, options);
    const EstimatorRun guided =
      RunEstimator(scene, field, vtkCloudPathTracer::LightGuided, options);
    std::printf("| %s | | | | | | |\n", scene.Name.c_str());
    PrintRow("plain", plain, options);
    std::printf(" |\n");
    PrintRow("light-guided", guided, options);
    std::printf(" **%.2f** |\n",
      (plain.Seconds * plain.SquaredError) / (guided.Seconds * guided.SquaredError));
    std::fflush(stdout);
  }
  std::printf("\n(relative standard error: the root of the seeds' mean squared error over the "
              "footprint, pixels of opacity > %.2f; the default estimator is light-guided for "
              "the droplets' phase, plain for the two lobes)\n",
    double(FootprintOpacity));
  return 0;
}

} // namespace bench
} // namespace cloudvis
