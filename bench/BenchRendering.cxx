// Rendering speed: vtkCloudVolumeMapper against VTK's vtkGPUVolumeRayCastMapper in one run,
// on the same fields, transfer functions, camera and sample distance, 800x600, no shading,
// no jitter:
//   sparse  the article's cloud (unit sphere + 6 octaves of fBm) on 256^3 voxels over [-2, 2]^3
//   dense   6 octaves of fBm filling the whole 256^3 box
// Prints ms/frame of both, the ratio, the RMS difference of the two images (8-bit levels),
// cloudvis's useful-sample fraction (samples where the transfer function gives extinction /
// samples taken), its frame rate while interacting (automatic reduced resolution) and the GPU
// memory it takes; then the sparse field stored as float, unsigned short, unsigned char and half
// floats: the GPU memory of each, its frame time and its image against the float field's.
//
// Usage: cloudvis-bench-rendering [--size N] [--frames F] [--width W --height H]
// Environment, for narrower measurements:
//   CLOUDVIS_BENCH_LIGHTING_ONLY=1  only the lighting comparison
//   CLOUDVIS_BENCH_STORAGE_ONLY=1   only the storage comparison
//   CLOUDVIS_BENCH_OCCUPANCY=1      only the occupancy recomputation time per brick size
//   CLOUDVIS_BENCH_ONE_MODEL=0|1|2  only cloudvis with lighting none|derivative|march (one sun),
//                                   e.g. under `valgrind --tool=callgrind` with LP_NUM_THREADS=0
//                                   and VTK_SMP_BACKEND_IN_USE=Sequential for instruction counts;
//                           =vtk    only vtkGPUVolumeRayCastMapper, unlit, the same way
//   CLOUDVIS_BENCH_DENSE=1          that single run on the dense field instead of the sparse one
//   CLOUDVIS_BENCH_BRICK=N          the brick size of that run
#include "CloudFieldGeometry.h"
#include "CloudLightVolumes.h"
#include "CloudLighting.h"
#include "CloudTransferTable.h"
#include "SupportImages.h"
#include "SupportMappers.h"
#include "vtkCloudDensitySource.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudOccupancyFilter.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTimerLog.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <vector>

namespace
{
using cloudvis::support::GrabWindow;
using cloudvis::support::MatchedCloudMapper;
using cloudvis::support::MatchedVtkMapper;

struct Options
{
  int Size = 256;
  int Frames = 10;
  int Width = 800;
  int Height = 600;
};

vtkSmartPointer<vtkImageData> Field(int size, bool dense)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(size, size, size);
  cloudvis::FieldDescription field;
  if (dense)
  {
    field.Shapes[0].Type = cloudvis::ShapeType::Box;
    field.Shapes[0].HalfSize = glm::vec3(2.5f);
    field.DensityScale = 0.5;
  }
  source->SetField(field);
  source->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(source->GetOutput());
  return image;
}

// One window, renderer, volume; the camera frames the [-2, 2]^3 box from an oblique view.
struct View
{
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;

  // densityMax: the density the transfer function's last point sits at (1 for the float field;
  // the full scale of an integer type holding it).
  View(vtkVolumeMapper* mapper,
    vtkImageData* field,
    const Options& options,
    double densityMax = 1.0)
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(options.Width, options.Height);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(0.1, 0.12, 0.16);
    mapper->SetInputDataObject(field);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(0.05 * densityMax, 0.0);
    opacity->AddPoint(densityMax, 0.8);
    vtkNew<vtkColorTransferFunction> color;
    color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
    color->AddRGBPoint(densityMax, 0.8, 0.85, 1.0);
    this->Property->SetScalarOpacity(opacity);
    this->Property->SetColor(color);
    this->Property->SetScalarOpacityUnitDistance(0.1);
    this->Property->SetInterpolationTypeToLinear();
    this->Property->ShadeOff();
    this->Volume->SetMapper(mapper);
    this->Volume->SetProperty(this->Property);
    this->Renderer->AddVolume(this->Volume);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetPosition(4.0, 3.0, 7.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    camera->SetViewAngle(30.0);
    camera->SetClippingRange(0.5, 20.0);
  }

  // Mean milliseconds per frame over `frames` renders after one warm-up render.
  double MillisecondsPerFrame(int frames, const std::function<void()>& beforeEachFrame)
  {
    this->Window->Render();
    this->Window->WaitForCompletion();
    const double start = vtkTimerLog::GetUniversalTime();
    for (int f = 0; f < frames; ++f)
    {
      beforeEachFrame();
      this->Window->Render();
      this->Window->WaitForCompletion();
    }
    return 1000.0 * (vtkTimerLog::GetUniversalTime() - start) / frames;
  }
};

void Compare(const char* name, vtkImageData* field, const Options& options)
{
  const double step = 4.0 / (options.Size - 1); // one voxel

  auto vtkMapper = MatchedVtkMapper(step);
  View vtk(vtkMapper, field, options);
  const double vtkMs = vtk.MillisecondsPerFrame(options.Frames, [] {});

  auto cloudMapper = MatchedCloudMapper(step);
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
  const double rms =
    cloudvis::support::Compare(GrabWindow(cloud.Window), GrabWindow(vtk.Window)).RmsLevels();

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
    cloudvis::FormatBytes(double(cloudMapper->GetGPUMemoryBytes())).c_str(),
    cloudvis::FormatBytes(double(cloudMapper->GetDensityTextureBytes())).c_str());
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
  cloudvis::support::Image floatImage;
  for (const Storage& storage : { Storage{ "float", VTK_FLOAT, false },
         Storage{ "unsigned short", VTK_UNSIGNED_SHORT, false },
         Storage{ "unsigned char", VTK_UNSIGNED_CHAR, false },
         Storage{ "float, HalfFloatDensity", VTK_FLOAT, true } })
  {
    auto mapper = MatchedCloudMapper(step);
    mapper->SetHalfFloatDensity(storage.HalfFloat);
    const auto stored = storage.ScalarType == VTK_FLOAT
      ? vtkSmartPointer<vtkImageData>(field)
      : cloudvis::support::QuantizedField(field, storage.ScalarType);
    View view(mapper, stored, options, cloudvis::support::FullScale(storage.ScalarType));
    const double ms = view.MillisecondsPerFrame(options.Frames, [&] { mapper->Modified(); });
    if (!mapper->GetLastError().empty())
    {
      std::printf("  | %s | refused: %s |\n", storage.Name, mapper->GetLastError().c_str());
      continue;
    }
    const cloudvis::support::Image image = GrabWindow(view.Window);
    if (storage.ScalarType == VTK_FLOAT && !storage.HalfFloat)
    {
      floatImage = image;
    }
    const double rms = cloudvis::support::Compare(image, floatImage).RmsLevels();
    std::printf("  | %s | %s | %s | %s | %.1f | %.2f |\n",
      storage.Name,
      storage.HalfFloat                            ? "R16F"
        : storage.ScalarType == VTK_UNSIGNED_CHAR  ? "R8"
        : storage.ScalarType == VTK_UNSIGNED_SHORT ? "R16"
                                                   : "R32F",
      cloudvis::FormatBytes(double(mapper->GetDensityTextureBytes())).c_str(),
      cloudvis::FormatBytes(double(mapper->GetGPUMemoryBytes())).c_str(),
      ms,
      rms);
  }
}
}

// Issue 4's figures: the cost of each lighting model on the sparse cloud with one sun, against
// VTK's mapper with shading on; issue 12's: the march with light volumes against the nested
// march, and the volumes' recompute time.
void CompareLighting(vtkImageData* field, const Options& options)
{
  const double step = 4.0 / (options.Size - 1);
  const auto addSun = [](vtkRenderer* renderer)
  {
    vtkNew<vtkLight> sun;
    sun->SetLightTypeToSceneLight();
    sun->SetPositional(false);
    sun->SetPosition(6.0, 8.0, 4.0);
    sun->SetFocalPoint(0.0, 0.0, 0.0);
    sun->SetIntensity(1.0);
    renderer->AddLight(sun);
  };

  auto vtkMapper = MatchedVtkMapper(step);
  View vtk(vtkMapper, field, options);
  vtk.Property->ShadeOn();
  addSun(vtk.Renderer);
  const double vtkShadedMs = vtk.MillisecondsPerFrame(options.Frames, [] {});

  std::printf("lighting on the sparse field (%d^3, %dx%d, one light):\n",
    options.Size,
    options.Width,
    options.Height);
  // The march with its light volumes (the default: computed once here, since nothing they depend
  // on changes between frames), with the nested march at every sample (the quality setting), and
  // with the volumes while the light moves every frame: that frame minus the static one is the
  // volumes' recompute time.
  struct Setting
  {
    const char* Name;
    cloudvis::LightingModel Model;
    cloudvis::LightTransmittance Transmittance;
    bool MovingLight;
  };
  const Setting settings[] = {
    { "none", cloudvis::LightingModel::None, cloudvis::LightTransmittance::Volumes, false },
    { "derivative",
      cloudvis::LightingModel::Derivative,
      cloudvis::LightTransmittance::Volumes,
      false },
    { "march (light volumes)",
      cloudvis::LightingModel::March,
      cloudvis::LightTransmittance::Volumes,
      false },
    { "march (nested march)",
      cloudvis::LightingModel::March,
      cloudvis::LightTransmittance::Nested,
      false },
    { "march (light volumes, the light moving every frame)",
      cloudvis::LightingModel::March,
      cloudvis::LightTransmittance::Volumes,
      true },
  };
  double noneMs = 0.0, volumesMs = 0.0;
  for (const Setting& setting : settings)
  {
    auto mapper = MatchedCloudMapper(step);
    cloudvis::LightingParameters lighting;
    lighting.Model = setting.Model;
    lighting.Transmittance = setting.Transmittance;
    mapper->GetLightingProperty()->SetParameters(lighting);
    View cloud(mapper, field, options);
    addSun(cloud.Renderer);
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
    if (setting.Model == cloudvis::LightingModel::None)
    {
      noneMs = ms;
    }
    std::printf("  %-52s %8.1f ms/frame  (%.2f x none)\n", setting.Name, ms, ms / noneMs);
    if (setting.Model == cloudvis::LightingModel::March &&
      setting.Transmittance == cloudvis::LightTransmittance::Volumes && !setting.MovingLight)
    {
      volumesMs = ms;
      std::printf("  vtkGPUVolumeRayCastMapper shaded %8.1f ms/frame\n", vtkShadedMs);
      std::printf("  march (light volumes) vs VTK shaded speed-up ratio: %.2f\n", vtkShadedMs / ms);
      std::printf("  light volumes: %d^3 texels per light, %.1f MiB\n",
        cloudvis::LightVolumeSize(glm::ivec3(options.Size)).x,
        double(mapper->GetLightVolumeBytes()) / (1 << 20));
    }
    if (setting.Transmittance == cloudvis::LightTransmittance::Nested)
    {
      std::printf("  nested march / light volumes: %.2f\n", ms / volumesMs);
    }
    if (setting.MovingLight)
    {
      std::printf("  light volumes recompute: %.1f ms (moving-light frame minus static frame; "
                  "%d recomputes)\n",
        ms - volumesMs,
        mapper->GetLightVolumeComputeCount());
    }
  }
}

int main(int argc, char* argv[])
{
  Options options;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const int value = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--size"))
      options.Size = value;
    else if (!std::strcmp(argv[i], "--frames"))
      options.Frames = value;
    else if (!std::strcmp(argv[i], "--width"))
      options.Width = value;
    else if (!std::strcmp(argv[i], "--height"))
      options.Height = value;
  }
  if (options.Size < 8 || options.Frames < 1 || options.Width < 16 || options.Height < 16)
  {
    std::fprintf(
      stderr, "usage: %s [--size N>=8] [--frames F>=1] [--width W --height H]\n", argv[0]);
    return 2;
  }
  const auto sparse = Field(options.Size, false);
  if (std::getenv("CLOUDVIS_BENCH_OCCUPANCY"))
  {
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
      occupancy->SetTransferTable(cloudvis::TabulateTransferFunction(nullptr, opacity, 0.1));
      const double start = vtkTimerLog::GetUniversalTime();
      occupancy->Update();
      std::printf(
        "occupancy brick %d: %.1f ms\n", brick, 1000.0 * (vtkTimerLog::GetUniversalTime() - start));
    }
    return 0;
  }
  if (const char* only = std::getenv("CLOUDVIS_BENCH_ONE_MODEL"))
  {
    const auto field = std::getenv("CLOUDVIS_BENCH_DENSE") ? Field(options.Size, true) : sparse;
    if (!std::strcmp(only, "vtk"))
    {
      auto vtkMapper = MatchedVtkMapper(4.0 / (options.Size - 1));
      View vtk(vtkMapper, field, options);
      std::printf("%.1f ms\n", vtk.MillisecondsPerFrame(options.Frames, [] {}));
      return 0;
    }
    auto mapper = MatchedCloudMapper(4.0 / (options.Size - 1));
    if (const char* brick = std::getenv("CLOUDVIS_BENCH_BRICK"))
      mapper->SetBrickSize(std::atoi(brick));
    cloudvis::LightingParameters lighting;
    lighting.Model = cloudvis::LightingModel(std::atoi(only));
    mapper->GetLightingProperty()->SetParameters(lighting);
    View cloud(mapper, field, options);
    vtkNew<vtkLight> sun;
    sun->SetPosition(6.0, 8.0, 4.0);
    sun->SetFocalPoint(0.0, 0.0, 0.0);
    cloud.Renderer->AddLight(sun);
    std::printf(
      "%.1f ms\n", cloud.MillisecondsPerFrame(options.Frames, [&] { mapper->Modified(); }));
    mapper->CollectStatisticsOn();
    mapper->Modified();
    cloud.Window->Render();
    const vtkCloudVolumeMapper::FrameStatistics& st = mapper->GetLastFrameStatistics();
    std::printf("useful-sample fraction %.1f%% of %.3g samples\n",
      100.0 * st.UsefulSamples / st.SamplesTaken,
      st.SamplesTaken);
    return 0;
  }
  if (std::getenv("CLOUDVIS_BENCH_STORAGE_ONLY"))
  {
    CompareStorage(sparse, options);
    return 0;
  }
  if (!std::getenv("CLOUDVIS_BENCH_LIGHTING_ONLY"))
  {
    Compare("sparse", sparse, options);
    Compare("dense", Field(options.Size, true), options);
  }
  CompareLighting(sparse, options);
  if (!std::getenv("CLOUDVIS_BENCH_LIGHTING_ONLY"))
  {
    CompareStorage(sparse, options);
  }
  return 0;
}
