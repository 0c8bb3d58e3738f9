// Field generation speed: vtkCloudDensitySource against vtkSampleFunction over a sum of six
// vtkPerlinNoise functions (frequency x2.02 and amplitude x0.5 per octave), the way a VTK user
// would build the same fBm field. Both fill the same 256^3 lattice over the same bounds with
// 6 octaves of gradient noise at every voxel, on all cores (vtkSMPTools), in one run.
//
// Then the cloud model against issue 22's target: the field of data/scenes/cloudscape-above.json,
// read through the app's scene reader and generated as `cloudvis generate` does, at 512^3 (the
// first generation, which bakes the cloud noise volumes, and the best of the repeats), checked
// against "at most 30 s". And, for information (VTK has no peer for them), the rate of the
// cellular noises in 6-octave fBm at every voxel.
//
// Usage: cloudvis-bench-generation [--size N] [--repeat R] [--cloudscape-size N] [--noise-size N]
//                                  [--scene PATH]
#include "Errors.h"
#include "Scene.h"
#include "SceneField.h"
#include "vtkCloudDensitySource.h"

#include <vtkImplicitSum.h>
#include <vtkNew.h>
#include <vtkPerlinNoise.h>
#include <vtkSMPTools.h>
#include <vtkSampleFunction.h>
#include <vtkTimerLog.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <string>

namespace
{
constexpr int Octaves = 6;
constexpr double Bounds[6] = { -2.0, 2.0, -2.0, 2.0, -2.0, 2.0 };

// Best wall-clock time of `repeat` runs, in seconds.
double BestOf(int repeat, const std::function<void()>& run)
{
  double best = std::numeric_limits<double>::max();
  for (int r = 0; r < repeat; ++r)
  {
    const double start = vtkTimerLog::GetUniversalTime();
    run();
    best = std::min(best, vtkTimerLog::GetUniversalTime() - start);
  }
  return best;
}

// Wall-clock seconds of one run.
double TimeOf(const std::function<void()>& run)
{
  const double start = vtkTimerLog::GetUniversalTime();
  run();
  return vtkTimerLog::GetUniversalTime() - start;
}

// A size^3 lattice of a 6-octave fBm of `type` over a box that fills the bounds, so that every
// voxel evaluates every octave (no voxel is skipped as empty); the frequency grows x2.02 per
// octave, as the VTK peer's.
void SetUpFbmEverywhere(vtkCloudDensitySource* source, cloudvis::noise::NoiseType type, int size)
{
  source->SetDimensions(size, size, size);
  source->SetBounds(const_cast<double*>(Bounds));
  cloudvis::FieldDescription field;
  field.Shapes[0].Type = cloudvis::ShapeType::Box;
  field.Shapes[0].HalfSize = glm::vec3(2.5f);
  field.Noise.Type = type;
  field.Noise.Octaves = Octaves;
  field.Noise.LacunarityIncrement = 0.0;
  source->SetField(field);
}

// The per-voxel rate of a 6-octave fBm of `type` at every voxel of a size^3 lattice (a box that
// fills the bounds, as above), in Mvoxel/s.
double FbmRate(cloudvis::noise::NoiseType type, int size, int repeat)
{
  vtkNew<vtkCloudDensitySource> source;
  SetUpFbmEverywhere(source, type, size);
  const double seconds = BestOf(repeat,
    [&]
    {
      source->Modified();
      source->Update();
    });
  return double(size) * size * size / seconds * 1e-6;
}
}

int main(int argc, char* argv[])
{
  int size = 256, repeat = 3, cloudscapeSize = 512, noiseSize = 128;
  std::string scenePath = CLOUDVIS_SCENES "/cloudscape-above.json";
  bool usage = argc % 2 == 0;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    if (!std::strcmp(argv[i], "--size"))
      size = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--repeat"))
      repeat = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--cloudscape-size"))
      cloudscapeSize = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--noise-size"))
      noiseSize = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--scene"))
      scenePath = argv[i + 1];
    else
      usage = true;
  }
  if (usage || size < 2 || repeat < 1 || cloudscapeSize < 2 || noiseSize < 2)
  {
    std::fprintf(stderr,
      "usage: %s [--size N>=2] [--repeat R>=1] [--cloudscape-size N>=2] [--noise-size N>=2] "
      "[--scene PATH]\n",
      argv[0]);
    return 2;
  }
  const double voxels = double(size) * size * size;

  // cloudvis: the article's cloud density over a box that fills the bounds.
  vtkNew<vtkCloudDensitySource> cloud;
  SetUpFbmEverywhere(cloud, cloudvis::noise::NoiseType::Perlin, size);
  const double cloudSeconds = BestOf(repeat, [&] {
    cloud->Modified();
    cloud->Update();
  });

  // The VTK peer.
  vtkNew<vtkImplicitSum> sum;
  sum->NormalizeByWeightOff();
  double frequency = 1.0, amplitude = 0.5;
  for (int o = 0; o < Octaves; ++o)
  {
    vtkNew<vtkPerlinNoise> octave;
    octave->SetFrequency(frequency, frequency, frequency);
    octave->SetAmplitude(amplitude);
    sum->AddFunction(octave, 1.0);
    frequency *= 2.02;
    amplitude *= 0.5;
  }
  vtkNew<vtkSampleFunction> sampler;
  sampler->SetImplicitFunction(sum);
  sampler->SetSampleDimensions(size, size, size);
  sampler->SetModelBounds(Bounds);
  sampler->SetOutputScalarTypeToFloat();
  sampler->ComputeNormalsOff();
  const double vtkSeconds = BestOf(std::max(1, repeat - 1), [&] {
    sampler->Modified();
    sampler->Update();
  });

  std::printf("field: %d^3 voxels, %d octaves of gradient noise, SMP backend %s, %d threads\n",
    size, Octaves, vtkSMPTools::GetBackend(), vtkSMPTools::GetEstimatedNumberOfThreads());
  std::printf("vtkCloudDensitySource:                 %8.3f s  %8.1f Mvoxel/s\n", cloudSeconds,
    voxels / cloudSeconds * 1e-6);
  std::printf("vtkSampleFunction + 6 vtkPerlinNoise:  %8.3f s  %8.1f Mvoxel/s\n", vtkSeconds,
    voxels / vtkSeconds * 1e-6);
  std::printf("generation speed-up ratio: %.1f (target >= 10: %s)\n",
    vtkSeconds / cloudSeconds,
    vtkSeconds / cloudSeconds >= 10.0 ? "met" : "NOT met");

  // The cloudscape, exactly as `cloudvis generate SCENE --set field.dimensions=N` makes it.
  cloudvis::Scene scene;
  try
  {
    scene =
      cloudvis::LoadScene(scenePath, { "field.dimensions=" + std::to_string(cloudscapeSize) });
  }
  catch (const std::exception& error)
  {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
  vtkSmartPointer<vtkCloudDensitySource> cloudscape = cloudvis::MakeDensitySource(scene.Field);
  const std::string problem = cloudscape->Validate();
  if (!problem.empty())
  {
    std::fprintf(stderr, "%s: %s\n", scenePath.c_str(), problem.c_str());
    return 1;
  }
  // The first generation bakes the seed's noise volumes (once per process, as in `cloudvis
  // generate`); the repeats reuse them.
  const double firstSeconds = TimeOf([&] { cloudscape->Update(); });
  const double cloudscapeSeconds = std::min(firstSeconds,
    BestOf(std::max(1, repeat - 1),
      [&]
      {
        cloudscape->Modified();
        cloudscape->Update();
      }));
  const double cloudscapeVoxels = double(cloudscapeSize) * cloudscapeSize * cloudscapeSize;
  std::printf("\ncloudscape: %s at %d^3 voxels\n", scenePath.c_str(), cloudscapeSize);
  // Issue 22's target is for 512^3; other sizes are reported without it.
  const std::string target = cloudscapeSize != 512 ? "(the target, <= 30 s, is for 512^3)"
    : firstSeconds <= 30.0                         ? "target <= 30 s: met"
                                                   : "target <= 30 s: NOT met";
  std::printf("first generation (bakes the noise volumes): %8.3f s  %8.1f Mvoxel/s  %s\n",
    firstSeconds,
    cloudscapeVoxels / firstSeconds * 1e-6,
    target.c_str());
  // The bake alone, for a seed not baked yet in this process.
  const double bakeSeconds =
    TimeOf([&] { cloudvis::BakeCloudNoise(scene.Field.Description.Noise.Seed + 1u); });
  std::printf("of which the bake of the noise volumes (once per seed): %.3f s\n", bakeSeconds);
  std::printf("best of %d:                                %8.3f s  %8.1f Mvoxel/s\n",
    repeat,
    cloudscapeSeconds,
    cloudscapeVoxels / cloudscapeSeconds * 1e-6);

  std::printf(
    "\ncellular noises, %d-octave fBm at every voxel of %d^3 (no VTK peer):\n", Octaves, noiseSize);
  for (const auto& [type, name] :
    { std::pair{ cloudvis::noise::NoiseType::Perlin, "perlin (for scale)" },
      std::pair{ cloudvis::noise::NoiseType::Worley, "worley" },
      std::pair{ cloudvis::noise::NoiseType::InvertedWorley, "inverted_worley" },
      std::pair{ cloudvis::noise::NoiseType::PerlinWorley, "perlin_worley" } })
  {
    std::printf("  %-20s %8.2f Mvoxel/s\n", name, FbmRate(type, noiseSize, repeat));
  }
  return 0;
}
