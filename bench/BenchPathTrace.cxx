// The path tracer (vtkCloudPathTracer): how fast it converges on the shipped scenes, and how far
// each lighting model of the march is from it. Six commands:
//
//   speed  [--size WxH] [--spp N] [--bounces B] [--brick N] [SCENE.json ...]
//     Renders each scene (default: data/scenes/fbm-sphere.json, two-lights.json, sphere.json)
//     with N paths per pixel, prints paths per second, the image's relative standard error, and
//     the time to 1% relative standard error at 800 x 600 extrapolated from the run (the error
//     falls as 1 / sqrt(paths) and the time grows with the pixels); and, as the peer in the same
//     run, the time of the CPU march of the scene's lighting model (vtkCloudReferenceRenderer).
//   estimators [--size WxH] [--spp N] [--bounces B] [--seed S] [--png DIR] [SCENE.json ...]
//     The next-event estimators, plain and light-guided, in one run on the thick cumulus of issue
//     38 (two lobes and droplets) and the shipped cumulus, or on the scenes given, each with three
//     seeds: time, noise, the image means' spread, the time to 2% at 400 x 300 and the ratio of the
//     times to equal noise (docs/lighting.md, "The estimators").
//   errors [--size WxH] [--spp N] [--bounces B] [--seed S]
//     The table of docs/lighting.md: each model (march, march without octaves, derivative)
//     against the path tracer on the fbm-sphere field and a dense field, lit from the side and
//     from behind, albedo 1 and 0.9, one directional light, no ambient.
//   bounces [--size WxH] [--spp N]
//     The light the bounce cap drops, on the fields of `errors` and two-lights.json at albedo 1.
//   defects [--size WxH] [--spp N]
//     Measures the march's defects one by one (docs/lighting.md, "What the march gets wrong"):
//     the light march's midpoint sampling and reach, the octaves per opacity, and bright
//     isolated pixels of a field that touches the box.
//   fit [--size WxH] [--spp N] [--bounces B] [--seed S] [--cases standard|real]
//       [--split first|stratified] [--voxels N]
//       [--max-octaves N] [--evaluations E] [--png DIR] [--reference-cache DIR]
//       [--multiple-scattering octaves|volume]
//     Fits the march's multiple-scattering octaves (N, a, b, c) and the derivative model's
//     distance h to the path tracer on a fixed case set with held-out cases (docs/lighting.md,
//     "Fitting the march to the path tracer"), and prints the errors before and after, per case
//     and per set, with the light volumes and with the nested light march. --cases real takes
//     the real regime of issue 38 instead (optically thick clouds at albedos near 1, with a split
//     of its own: docs/lighting.md, "The real regime"). With
//     --multiple-scattering volume it fits nothing: it prints the octaves' and the
//     multiple-scattering volume's errors per case, and the volume's computation time
//     (docs/lighting.md, "The multiple-scattering volume"). --reference-cache keeps the path
//     tracer's references in DIR, keyed by case and options, and reads them back next time.
//
// Scenes are read by the scene library as `cloudvis render` reads them (any scene it renders), and
// rendered by the CPU renderers set up as `cloudvis render --cpu-reference` sets them up; each
// command varies a scene only through its keys (PathTraceBench.h). One file per command:
// PathTraceSpeed.cxx, PathTraceEstimators.cxx, PathTraceErrors.cxx (errors, bounces),
// PathTraceDefects.cxx, PathTraceFit.cxx.
#include "CloudLightingParameters.h"
#include "PathTraceBench.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

using namespace cloudvis::bench;

namespace
{
int Usage(const char* program, std::FILE* out = stderr)
{
  std::fprintf(out,
    "usage: %s speed [--size WxH] [--spp N] [--bounces B] [--brick N] [--seed S] [--png DIR] "
    "[SCENE.json ...]\n"
    "       %s estimators [--size WxH] [--spp N] [--bounces B] [--seed S] [--png DIR] "
    "[SCENE.json ...]\n"
    "       %s errors [--size WxH] [--spp N] [--bounces B] [--seed S] [--png DIR]\n"
    "       %s bounces [--size WxH] [--spp N] [--seed S]\n"
    "       %s defects [--size WxH] [--spp N] [--bounces B]\n"
    "       %s fit [--size WxH] [--spp N] [--bounces B] [--seed S] [--cases standard|real] "
    "[--split first|stratified] "
    "[--voxels N] [--max-octaves N] [--evaluations E] [--png DIR] [--reference-cache DIR] "
    "[--multiple-scattering octaves|volume]\n",
    program,
    program,
    program,
    program,
    program,
    program);
  return out == stderr ? 2 : 0;
}
}

int main(int argc, char* argv[])
{
  if (argc < 2)
    return Usage(argv[0]);
  const std::string command = argv[1];
  if (command == "--help" || command == "-h")
    return Usage(argv[0], stdout);
  Options options;
  for (int i = 2; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--size" && hasValue)
    {
      if (std::sscanf(argv[++i], "%dx%d", &options.Width, &options.Height) != 2 ||
        options.Width < 1 || options.Height < 1)
        return Usage(argv[0]);
    }
    else if (arg == "--spp" && hasValue)
      options.Samples = std::atoi(argv[++i]);
    else if (arg == "--bounces" && hasValue)
      options.Bounces = std::atoi(argv[++i]);
    else if (arg == "--png" && hasValue)
      options.PngDirectory = argv[++i];
    else if (arg == "--brick" && hasValue)
      options.BrickSize = std::atoi(argv[++i]);
    else if (arg == "--cases" && hasValue)
      options.FitCases = argv[++i];
    else if (arg == "--split" && hasValue)
      options.FitSplit = argv[++i];
    else if (arg == "--reference-cache" && hasValue)
      options.ReferenceCache = argv[++i];
    else if (arg == "--multiple-scattering" && hasValue)
      options.MultipleScattering = argv[++i];
    else if (arg == "--voxels" && hasValue)
      options.FitDimensions = std::atoi(argv[++i]);
    else if (arg == "--max-octaves" && hasValue)
      options.FitMaxOctaves = std::atoi(argv[++i]);
    else if (arg == "--evaluations" && hasValue)
      options.FitEvaluations = std::atoi(argv[++i]);
    else if (arg == "--seed" && hasValue)
      options.Seed = unsigned(std::strtoul(argv[++i], nullptr, 10));
    else if (arg.rfind("--", 0) == 0)
      return Usage(argv[0]);
    else
      options.Scenes.push_back(arg);
  }
  if (options.Samples < 2 || options.Bounces < 1 || options.FitDimensions == 1 ||
    options.FitDimensions < 0 || options.FitMaxOctaves < 1 ||
    options.FitMaxOctaves > cloudvis::LightingLimits::MaxMultipleScatteringOctaves ||
    options.FitEvaluations < 1 ||
    (options.FitSplit != "first" && options.FitSplit != "stratified") ||
    (options.FitCases != "standard" && options.FitCases != "real") ||
    (options.MultipleScattering != "octaves" && options.MultipleScattering != "volume"))
    return Usage(argv[0]);
  try
  {
    if (command == "speed")
      return Speed(options);
    if (command == "estimators")
      return Estimators(options);
    if (command == "errors")
      return Errors(options);
    if (command == "bounces")
      return Bounces(options);
    if (command == "defects")
      return Defects(options);
    if (command == "fit")
      return Fit(options);
    return Usage(argv[0]);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "cloudvis-bench-pathtrace: %s\n", e.what());
    return 1;
  }
}