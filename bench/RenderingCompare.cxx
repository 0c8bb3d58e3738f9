// cloudvis-bench-rendering's measures of one field size (BenchRendering.cxx): the default run
// (both fields against VTK's mapper, the lighting models, the texel formats) and its parts run
// alone (`lighting`, `storage`, `one`, `occupancy`), for narrower measurements such as
// instruction counts under callgrind.
#include "CloudFieldGeometry.h"
#include "CloudLightVolumes.h"
#include "CloudScatteringVolume.h"
#include "CloudTransferTable.h"
#include "RenderingBench.h"
#include "Scene.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudOccupancyFilter.h"

#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkPiecewiseFunction.h>
#include <vtkTimerLog.h>

#include <algorithm>
#include <cstdio>

namespace cloudvis
{
namespace bench
{

namespace
{
void Compare(const char* name, vtkImageData* field, const Options& options)
{
  const double step = 4.0 / (options.Size - 1); // one voxel

  auto vtkMapper = VtkMapper(step);
  View vtk(vtkMapper, field, options);
  const double vtkMs = vtk.MillisecondsPerFrame(options.Frames, [] {});

  auto cloudMapper = CloudMapper(step);
  View cloud(cloudMapper, field, options);
  // Modified() makes the mapper march again although the view is unchanged.
  const double cloudMs =
    cloud.MillisecondsPerFrame(options.Frames, [&] { cloudMapper->Modified(); });

  cloudMapper->CollectStatisticsOn();
  cloudMapper->Modified();
  cloud.Window->Render();
  const auto& statistics = cloudMapper->GetLastFrameStatistics();
  const double useful = statistics.UsefulSamples / std::max(1.0, statistics.SamplesTaken);
  cloudMapper->CollectStatisticsOff();
  const double rms = RmsLevels(cloud.Pixels(), vtk.Pixels());

  // While interacting the mapper lowers its resolution to keep 20 frames per second.
  cloud.Window->SetDesiredUpdateRate(20.0);
  cloud.MillisecondsPerFrame(3, [&] { cloud.Renderer->GetActiveCamera()->Azimuth(1.0); });
  const double interactiveMs = cloud.MillisecondsPerFrame(
    options.Frames, [&] { cloud.Renderer->GetActiveCamera()->Azimuth(1.0); });

  std::printf("%s field (%d^3, %dx%d, step %.4f):\n",
    name,
    options.Size,
    options.Width,
    options.Height,
    step);
  std::printf("  vtkGPUVolumeRayCastMapper  %8.1f ms/frame\n", vtkMs);
  std::printf("  vtkCloudVolumeMapper       %8.1f ms/frame\n", cloudMs);
  std::printf("  %s speed-up ratio: %.2f\n", name, vtkMs / cloudMs);
  std::printf("  image difference: %.2f RMS 8-bit levels\n", rms);
  std::printf("  useful-sample fraction: %.1f%% (occupied bricks %.1f%%)\n",
    100.0 * useful,
    100.0 * statistics.OccupiedBrickFraction);
  std::printf(
    "  interactive: %.1f ms/frame = %.1f frames/s\n", interactiveMs, 1000.0 / interactiveMs);
  std::printf("  cloudvis GPU memory: %s (density texture %s)\n",
    FormatBytes(double(cloudMapper->GetGPUMemoryBytes())).c_str(),
    FormatBytes(double(cloudMapper->GetDensityTextureBytes())).c_str());
}

// The sparse field stored in each of the mapper's texel formats (QuantizedField: densities in
// [0, 1] as integers of the type's full scale, the transfer function scaled with them).
void CompareStorage(vtkImageData* field, const Options& options)
{
  struct Storage
  {
    const char* Name;
    int ScalarType;
    bool HalfFloat;
  };
  const double step = 4.0 / (options.Size - 1);
  std::printf("storage of the sparse field (%d^3, %dx%d, step %.4f):\n",
    options.Size,
    options.Width,
    options.Height,
    step);
  std::printf("  | field | texels | density texture | all textures and targets | ms/frame | "
              "RMS vs float (8-bit levels) |\n  |---|---|---|---|---|---|\n");
  RenderedImage floatImage;
  for (const Storage& storage : { Storage{ "float", VTK_FLOAT, false },
         Storage{ "unsigned short", VTK_UNSIGNED_SHORT, false },
         Storage{ "unsigned char", VTK_UNSIGNED_CHAR, false },
         Storage{ "float, HalfFloatDensity", VTK_FLOAT, true } })
  {
    auto mapper = CloudMapper(step);
    mapper->SetHalfFloatDensity(storage.HalfFloat);
    const auto stored = storage.ScalarType == VTK_FLOAT ? vtkSmartPointer<vtkImageData>(field)
                                                        : Quantized(field, storage.ScalarType);
    View view(mapper, stored, options, FullScale(storage.ScalarType));
    const double ms = view.MillisecondsPerFrame(options.Frames, [&] { mapper->Modified(); });
    if (!mapper->GetLastError().empty())
    {
      std::printf("  | %s | refused: %s |\n", storage.Name, mapper->GetLastError().c_str());
      continue;
    }
    const RenderedImage image = view.Pixels();
    if (storage.ScalarType == VTK_FLOAT && !storage.HalfFloat)
    {
      floatImage = image;
    }
    const double rms = RmsLevels(image, floatImage);
    std::printf("  | %s | %s | %s | %s | %.1f | %.2f |\n",
      storage.Name,
      storage.HalfFloat                            ? "R16F"
        : storage.ScalarType == VTK_UNSIGNED_CHAR  ? "R8"
        : storage.ScalarType == VTK_UNSIGNED_SHORT ? "R16"
                                                   : "R32F",
      FormatBytes(double(mapper->GetDensityTextureBytes())).c_str(),
      FormatBytes(double(mapper->GetGPUMemoryBytes())).c_str(),
      ms,
      rms);
  }
}

// Issue 4's figures: the cost of each lighting model on the sparse cloud with one sun, against
// VTK's mapper with shading on; issue 12's: the march with light volumes against the nested
// march, and the volumes' recompute time; issue 21's: the multiple-scattering volume's.
void CompareLighting(vtkImageData* field, const Options& options)
{
  const double step = 4.0 / (options.Size - 1);

  auto vtkMapper = VtkMapper(step);
  View vtk(vtkMapper, field, options);
  vtk.Property->ShadeOn();
  SetLights(vtk.Renderer, 1);
  const double vtkShadedMs = vtk.MillisecondsPerFrame(options.Frames, [] {});

  std::printf("lighting on the sparse field (%d^3, %dx%d, one light):\n",
    options.Size,
    options.Width,
    options.Height);
  // The march with its light volumes and its multiple-scattering volume (the default: computed
  // once here, since nothing they depend on changes between frames), with the octaves instead of
  // the multiple-scattering volume, with the nested march at every sample (the quality setting),
  // and both while the light moves every frame: that frame minus the static one is what
  // recomputing the volumes costs (the light volumes alone with the octaves).
  const struct
  {
    const char* Name;
    const char* Lighting; // MeasuredLighting's name
    bool MovingLight;
  } settings[] = {
    { "none", "none", false },
    { "derivative", "derivative", false },
    { "march (light volumes, multiple-scattering volume)", "march", false },
    { "march (light volumes, octaves)", "octaves", false },
    { "march (nested march, multiple-scattering volume)", "nested", false },
    { "march (multiple-scattering volume, the light moving)", "march", true },
    { "march (octaves, the light moving every frame)", "octaves", true },
  };
  double noneMs = 0.0, volumesMs = 0.0, octavesMs = 0.0, movingMs = 0.0;
  for (const auto& setting : settings)
  {
    auto mapper = CloudMapper(step);
    const LightingParameters lighting = *MeasuredLighting(setting.Lighting);
    mapper->GetLightingProperty()->SetParameters(lighting);
    View cloud(mapper, field, options);
    SetLights(cloud.Renderer, 1);
    vtkLight* sun = vtkLight::SafeDownCast(cloud.Renderer->GetLights()->GetItemAsObject(0));
    int frame = 0;
    const double ms = cloud.MillisecondsPerFrame(options.Frames,
      [&]
      {
        mapper->Modified();
        if (setting.MovingLight)
        {
          sun->SetPosition(6.0, 8.0, 4.0 + 0.01 * ++frame);
        }
      });
    if (lighting.Model == LightingModel::None)
    {
      noneMs = ms;
    }
    std::printf("  %-52s %8.1f ms/frame  (%.2f x none)\n", setting.Name, ms, ms / noneMs);
    const bool octaves = lighting.MultipleScattering == MultipleScatteringModel::Octaves;
    if (lighting.Model == LightingModel::March && octaves && !setting.MovingLight)
    {
      octavesMs = ms;
      std::printf("  march with the multiple-scattering volume / with the octaves: %.2f\n",
        volumesMs / ms);
    }
    if (lighting.Model == LightingModel::March &&
      lighting.Transmittance == LightTransmittance::Volumes && !setting.MovingLight && !octaves)
    {
      volumesMs = ms;
      std::printf("  vtkGPUVolumeRayCastMapper shaded %8.1f ms/frame\n", vtkShadedMs);
      std::printf("  march (light volumes) vs VTK shaded speed-up ratio: %.2f\n", vtkShadedMs / ms);
      std::printf("  light volumes: %d^3 texels per light, %.1f MiB\n",
        LightVolumeSize(glm::ivec3(options.Size)).x,
        double(mapper->GetLightVolumeBytes()) / (1 << 20));
    }
    if (lighting.Transmittance == LightTransmittance::Nested)
    {
      std::printf("  nested march / light volumes: %.2f\n", ms / volumesMs);
    }
    if (UsesScatteringVolume(lighting))
    {
      // The mapper's own time for its last computation of the volume (a frame's statistics).
      mapper->CollectStatisticsOn();
      mapper->Modified();
      cloud.Window->Render();
      const double recomputeMs = mapper->GetLastFrameStatistics().ScatteringVolumeMilliseconds;
      mapper->CollectStatisticsOff();
      std::printf("  multiple-scattering volume: %d^3 texels, %.1f MiB, recompute %.1f ms "
                  "(%d computes)\n",
        ScatteringVolumeSize(glm::ivec3(options.Size)).x,
        double(mapper->GetScatteringVolumeBytes()) / (1 << 20),
        recomputeMs,
        mapper->GetScatteringVolumeComputeCount());
    }
    if (setting.MovingLight && !octaves)
    {
      movingMs = ms;
    }
    if (setting.MovingLight && octaves)
    {
      // The octaves recompute the light volumes alone; the volume's frame recomputes both.
      const double lightVolumesMs = ms - octavesMs, bothMs = movingMs - volumesMs;
      std::printf("  recompute when the light moves: light volumes %.1f ms, multiple-scattering "
                  "volume %.1f ms (moving-light frame minus static frame; %d recomputes)\n",
        lightVolumesMs,
        bothMs - lightVolumesMs,
        mapper->GetLightVolumeComputeCount());
    }
  }
}

} // namespace

int Default(const Options& options, bool lightingOnly)
{
  const auto sparse = Field(options.Size, false);
  if (!lightingOnly)
  {
    Compare("sparse", sparse, options);
    Compare("dense", Field(options.Size, true), options);
  }
  CompareLighting(sparse, options);
  if (!lightingOnly)
  {
    CompareStorage(sparse, options);
  }
  return 0;
}

int Storage(const Options& options)
{
  CompareStorage(Field(options.Size, false), options);
  return 0;
}

// The occupancy recomputation time per brick size, on the sparse field with the views' transfer
// function.
int Occupancy(const Options& options)
{
  const auto sparse = Field(options.Size, false);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(0.05, 0.0);
  opacity->AddPoint(1.0, 0.8);
  for (int brick : { 2, 3, 4, 8 })
  {
    vtkNew<vtkCloudOccupancyFilter> occupancy;
    occupancy->SetInputData(sparse);
    occupancy->SetBrickSize(brick);
    // The table the mapper builds: over the transfer function's points.
    occupancy->SetTransferTable(TabulateTransferFunction(nullptr, opacity, 0.1));
    const double start = vtkTimerLog::GetUniversalTime();
    occupancy->Update();
    std::printf(
      "occupancy brick %d: %.1f ms\n", brick, 1000.0 * (vtkTimerLog::GetUniversalTime() - start));
  }
  return 0;
}

// One mapper alone: cloudvis with one lighting model and the sun (brickSize > 0: that brick
// size), or VTK's mapper unlit ("vtk"); its ms/frame and, for cloudvis, the useful-sample fraction.
int OneModel(const Options& options, const std::string& model, bool dense, int brickSize)
{
  const auto field = Field(options.Size, dense);
  if (model == "vtk")
  {
    auto vtkMapper = VtkMapper(4.0 / (options.Size - 1));
    View vtk(vtkMapper, field, options);
    std::printf("%.1f ms\n", vtk.MillisecondsPerFrame(options.Frames, [] {}));
    return 0;
  }
  auto mapper = CloudMapper(4.0 / (options.Size - 1));
  if (brickSize > 0)
    mapper->SetBrickSize(brickSize);
  mapper->GetLightingProperty()->SetParameters(*MeasuredLighting(model));
  View cloud(mapper, field, options);
  SetLights(cloud.Renderer, 1);
  std::printf("%.1f ms\n", cloud.MillisecondsPerFrame(options.Frames, [&] { mapper->Modified(); }));
  mapper->CollectStatisticsOn();
  mapper->Modified();
  cloud.Window->Render();
  const vtkCloudVolumeMapper::FrameStatistics& st = mapper->GetLastFrameStatistics();
  std::printf("useful-sample fraction %.1f%% of %.3g samples\n",
    100.0 * st.UsefulSamples / st.SamplesTaken,
    st.SamplesTaken);
  return 0;
}

} // namespace bench
} // namespace cloudvis
