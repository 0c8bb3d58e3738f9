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
//        cloudvis-bench-rendering matrix [--fields sparse,dense] [--sizes 256,512,1024]
//          [--images 800x600,1920x1080,3840x2160] [--models none,derivative,march,nested]
//          [--lights 1,2] [--frames F] [--interactive-frames F] [--type uchar|ushort|float]
//          [--no-vtk]
// The matrix mode (issue 12) runs every combination of the lists in one run, both mappers on the
// same field (unsigned char by default, so that 1024^3 takes 1 GiB), and prints one markdown
// table row per combination (cloudvis ms, VTK ms, their ratio, the cost against `none`, the
// resolution scale the mapper settles at while interacting, the GPU memory of both), then the
// issue's targets met or not. Its default is the full matrix; on a software renderer (llvmpipe)
// without subset options, 128^3 and 256^3 at 800x600. What the GPU or the host cannot hold is
// reported as refused with the size needed.
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
//   CLOUDVIS_BENCH_REPROJECTION=1   only temporal reprojection: an orbit of interactive frames
//                                   with and without it, timed and compared with still renders
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
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <string>
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

// The bench's two fields on size^3 voxels over [-2, 2]^3: the article's sparse cloud, or fBm
// filling the box (`dense`). Generated in slabs of z so that a field stored as bytes never has
// its float densities in memory all at once (a 1024^3 float field is 4 GiB); integer types hold
// round(clamp(density, 0, 1) * FullScale), as support::QuantizedField makes them.
vtkSmartPointer<vtkImageData> Field(int size, bool dense, int scalarType = VTK_FLOAT)
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
  source->UpdateInformation();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(size, size, size);
  vtkSmartPointer<vtkDataArray> values =
    vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(scalarType));
  values->SetNumberOfTuples(vtkIdType(size) * size * size);
  constexpr int SlabDepth = 32;
  for (int z0 = 0; z0 < size; z0 += SlabDepth)
  {
    const int extent[6] = { 0, size - 1, 0, size - 1, z0, std::min(size, z0 + SlabDepth) - 1 };
    source->UpdateExtent(extent);
    vtkImageData* slab = source->GetOutput();
    if (z0 == 0)
    {
      image->SetOrigin(slab->GetOrigin());
      image->SetSpacing(slab->GetSpacing());
      values->SetName(slab->GetPointData()->GetScalars()->GetName());
    }
    const auto converted = cloudvis::support::QuantizedField(slab, scalarType);
    vtkDataArray* slabValues = converted->GetPointData()->GetScalars();
    std::memcpy(values->GetVoidPointer(vtkIdType(z0) * size * size),
      slabValues->GetVoidPointer(0),
      std::size_t(slabValues->GetNumberOfTuples()) * slabValues->GetDataTypeSize());
  }
  image->GetPointData()->SetScalars(values);
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

// The sun every lit measure uses (the lighting comparison, the matrix, one model alone): a
// directional scene light of intensity 1 from (6, 8, 4) toward the origin.
void AddSun(vtkRenderer* renderer)
{
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(6.0, 8.0, 4.0);
  sun->SetFocalPoint(0.0, 0.0, 0.0);
  sun->SetIntensity(1.0);
  renderer->AddLight(sun);
}

// Issue 4's figures: the cost of each lighting model on the sparse cloud with one sun, against
// VTK's mapper with shading on; issue 12's: the march with light volumes against the nested
// march, and the volumes' recompute time.
void CompareLighting(vtkImageData* field, const Options& options)
{
  const double step = 4.0 / (options.Size - 1);

  auto vtkMapper = MatchedVtkMapper(step);
  View vtk(vtkMapper, field, options);
  vtk.Property->ShadeOn();
  AddSun(vtk.Renderer);
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
    AddSun(cloud.Renderer);
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

// Issue 12's interaction item: the sparse cloud after a still frame, orbiting 1 degree per
// interactive frame (desired update rate 20, so the mapper lowers its scale to keep 20 frames per
// second), with and without TemporalReprojection. Each interactive frame is compared with the
// still render of its view by a second mapper (jitter on, 16 frames accumulated: converged);
// prints ms/frame, the march's scale and the RMS error (8-bit levels) of both, and their ratios.
// The transfer function is the render tests' contrasted one (opacity 0.9 per 0.1 at density 0.5,
// orange to blue), whose detail the reduced resolution loses; the default one is nearly uniform
// white, which any resolution shows alike.
void CompareReprojection(vtkImageData* field, const Options& options)
{
  const auto contrast = [](vtkVolumeProperty* property)
  {
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(0.5, 0.9);
    vtkNew<vtkColorTransferFunction> color;
    color->AddRGBPoint(0.0, 0.9, 0.5, 0.2);
    color->AddRGBPoint(0.5, 0.3, 0.6, 1.0);
    property->SetScalarOpacity(opacity);
    property->SetColor(color);
  };
  const double step = 4.0 / (options.Size - 1);
  const int orbit = std::max(options.Frames, 2);
  std::printf("temporal reprojection on the sparse field (%d^3, %dx%d, step %.4f, %d interactive "
              "frames orbiting 1 degree each):\n",
    options.Size,
    options.Width,
    options.Height,
    step,
    orbit);
  const auto converged = [&](int frame)
  {
    auto mapper = MatchedCloudMapper(step);
    mapper->JitterOn();
    mapper->SetMaximumAccumulatedFrames(16);
    View still(mapper, field, options);
    contrast(still.Property);
    still.Renderer->GetActiveCamera()->Azimuth(double(frame));
    for (int f = 0; f < 16; ++f)
    {
      still.Window->Render();
    }
    return GrabWindow(still.Window);
  };
  std::vector<cloudvis::support::Image> truth;
  for (int frame = 1; frame <= orbit; ++frame)
  {
    truth.push_back(converged(frame));
  }
  double results[2][2] = {}; // [reprojection][ms, error]
  for (const bool reprojection : { false, true })
  {
    auto mapper = MatchedCloudMapper(step);
    mapper->JitterOn();
    mapper->SetMaximumAccumulatedFrames(16);
    mapper->SetTemporalReprojection(reprojection);
    View cloud(mapper, field, options);
    contrast(cloud.Property);
    for (int f = 0; f < 16; ++f)
    {
      cloud.Window->Render(); // the converged still frame the interaction starts from
    }
    cloud.Window->SetDesiredUpdateRate(20.0);
    double seconds = 0.0, squaredError = 0.0;
    int scaledWidth = 0;
    for (int frame = 1; frame <= orbit; ++frame)
    {
      cloud.Renderer->GetActiveCamera()->Azimuth(1.0);
      const double start = vtkTimerLog::GetUniversalTime();
      cloud.Window->Render();
      cloud.Window->WaitForCompletion();
      seconds += vtkTimerLog::GetUniversalTime() - start;
      const cloudvis::support::Image shown = GrabWindow(cloud.Window);
      const double rms = cloudvis::support::Compare(shown, truth[frame - 1]).RmsLevels();
      if (const char* dump = std::getenv("CLOUDVIS_BENCH_DUMP"))
      {
        const std::string name = std::string(dump) + "/frame" + std::to_string(frame);
        cloudvis::support::WritePng(shown, name + (reprojection ? "-reprojected.png" : "-low.png"));
        cloudvis::support::WritePng(truth[frame - 1], name + "-truth.png");
      }
      squaredError += rms * rms;
      if (frame == 1 || frame == orbit)
      {
        std::printf("  %s, interactive frame %d: RMS error %.2f levels\n",
          reprojection ? "with reprojection" : "without reprojection",
          frame,
          rms);
      }
      std::vector<float> rgba;
      int height = 0;
      mapper->ReadImage(cloud.Renderer, rgba, scaledWidth, height);
    }
    const double ms = 1000.0 * seconds / orbit;
    const double error = std::sqrt(squaredError / orbit);
    results[reprojection][0] = ms;
    results[reprojection][1] = error;
    std::printf("  %-22s %8.1f ms/frame  march %4d px wide  RMS error vs converged %.2f levels\n",
      reprojection ? "with reprojection" : "without reprojection",
      ms,
      scaledWidth,
      error);
  }
  std::printf(
    "  reprojection frame-time ratio (with / without): %.2f\n", results[1][0] / results[0][0]);
  std::printf("  reprojection error ratio (with / without): %.2f\n", results[1][1] / results[0][1]);
}

// ---------------------------------------------------------------------------------------------
// The matrix (issue 12): fields x sizes x image sizes x lighting models x light counts, cloudvis
// against VTK's mapper (unlit for `none`, shaded with the same lights for the lit models) in one
// run; frame times to the GPU's completion, the resolution the mapper settles at while
// interacting, and the GPU memory of both. The path-traced model is measured by
// cloudvis-bench-gpu-pathtrace, not here.
namespace matrix
{
struct Model
{
  const char* Name;
  cloudvis::LightingModel Lighting;
  cloudvis::LightTransmittance Transmittance;
};
const Model Models[] = {
  { "none", cloudvis::LightingModel::None, cloudvis::LightTransmittance::Volumes },
  { "derivative", cloudvis::LightingModel::Derivative, cloudvis::LightTransmittance::Volumes },
  { "march", cloudvis::LightingModel::March, cloudvis::LightTransmittance::Volumes },
  { "nested", cloudvis::LightingModel::March, cloudvis::LightTransmittance::Nested },
};

struct ImageSize
{
  int Width, Height;
};

struct Settings
{
  std::vector<std::string> Fields = { "sparse", "dense" };
  std::vector<int> Sizes = { 256, 512, 1024 };
  std::vector<ImageSize> Images = { { 800, 600 }, { 1920, 1080 }, { 3840, 2160 } };
  std::vector<std::string> Models = { "none", "derivative", "march", "nested" };
  std::vector<int> Lights = { 1, 2 };
  int Frames = 10;
  int InteractiveFrames = 10;
  int ScalarType = VTK_UNSIGNED_CHAR;
  bool Vtk = true;
};

// One measured row of the table.
struct Row
{
  std::string Field;
  int Size = 0;
  ImageSize Image{};
  std::string Model;
  int Lights = 0; // 0: the model uses none
  double CloudMs = -1.0;
  double VtkMs = -1.0;
  double NoneMs = -1.0; // cloudvis unlit on the same field and image
  double InteractiveScale = -1.0;
  double InteractiveMs = -1.0;
  long long CloudBytes = -1;
  long long CloudDriverBytes = -1; // the driver's free-memory delta over the first render
  long long VtkBytes = -1;
  bool VtkBytesMeasured = false;
  std::string Refused;
};

std::vector<std::string> SplitList(const std::string& text)
{
  std::vector<std::string> items;
  std::size_t begin = 0;
  while (begin <= text.size())
  {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    if (end > begin)
    {
      items.push_back(text.substr(begin, end - begin));
    }
    begin = end + 1;
  }
  return items;
}

// A positive integer, or -1.
int PositiveInteger(const std::string& text)
{
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  return end && *end == '\0' && value > 0 && value < (1L << 30) ? int(value) : -1;
}

// The lights of the matrix: the sun of the lighting comparison, and for two a warm point light
// below and to the left (as in data/scenes/two-lights.json), for both mappers.
void SetLights(vtkRenderer* renderer, int count)
{
  renderer->RemoveAllLights();
  if (count >= 1)
  {
    AddSun(renderer);
  }
  if (count >= 2)
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetFocalPoint(0.0, 0.0, 0.0);
    light->SetPositional(true);
    light->SetConeAngle(180.0);
    light->SetPosition(-2.2, -0.5, 1.5);
    light->SetDiffuseColor(1.0, 0.4, 0.7);
    light->SetIntensity(1.5);
    light->SetAttenuationValues(0.0, 0.0, 1.0);
    renderer->AddLight(light);
  }
}

// The driver's free video memory before and after `render`, when it reports it (-1 otherwise).
long long DriverBytesUsedBy(vtkRenderWindow* window, const std::function<void()>& render)
{
  const long long before = vtkCloudVolumeMapper::GetFreeGPUMemoryBytes(window);
  render();
  window->WaitForCompletion();
  const long long after = vtkCloudVolumeMapper::GetFreeGPUMemoryBytes(window);
  return before >= 0 && after >= 0 ? before - after : -1;
}

std::string Ms(double ms)
{
  char text[32];
  std::snprintf(text, sizeof text, ms < 0.0 ? "-" : "%.1f", ms);
  return ms < 0.0 ? "-" : text;
}

std::string Bytes(long long bytes)
{
  return bytes < 0 ? "-" : cloudvis::FormatBytes(double(bytes));
}

void PrintHeader()
{
  std::printf("| field | voxels | image | model | lights | cloudvis ms | VTK ms | VTK / cloudvis "
              "| x none | interactive: scale, ms | cloudvis GPU memory (driver delta) | VTK GPU "
              "memory |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
}

void PrintRow(const Row& row)
{
  const std::string image = row.Image.Width > 0
    ? std::to_string(row.Image.Width) + "x" + std::to_string(row.Image.Height)
    : "-";
  std::printf("| %s | %d^3 | %s | %s | %s |",
    row.Field.c_str(),
    row.Size,
    image.c_str(),
    row.Model.c_str(),
    row.Lights ? std::to_string(row.Lights).c_str() : "-");
  if (!row.Refused.empty())
  {
    std::printf(" %s |||||||\n", row.Refused.c_str());
    std::fflush(stdout);
    return;
  }
  char ratioText[32] = "-";
  if (row.CloudMs > 0.0 && row.VtkMs > 0.0)
  {
    std::snprintf(ratioText, sizeof ratioText, "**%.2f**", row.VtkMs / row.CloudMs);
  }
  char noneText[32] = "-";
  if (row.NoneMs > 0.0)
  {
    std::snprintf(noneText, sizeof noneText, "%.2f", row.CloudMs / row.NoneMs);
  }
  char interactive[64] = "-";
  if (row.InteractiveScale > 0.0)
  {
    std::snprintf(interactive,
      sizeof interactive,
      "%.2f (%dx%d), %.1f",
      row.InteractiveScale,
      int(std::lround(row.InteractiveScale * row.Image.Width)),
      int(std::lround(row.InteractiveScale * row.Image.Height)),
      row.InteractiveMs);
  }
  std::printf(" %s | %s | %s | %s | %s | %s (%s) | %s%s |\n",
    Ms(row.CloudMs).c_str(),
    Ms(row.VtkMs).c_str(),
    ratioText,
    noneText,
    interactive,
    Bytes(row.CloudBytes).c_str(),
    Bytes(row.CloudDriverBytes).c_str(),
    Bytes(row.VtkBytes).c_str(),
    row.VtkBytes < 0 ? "" : (row.VtkBytesMeasured ? " (driver delta)" : " (estimate)"));
  std::fflush(stdout);
}

// VTK's mapper on one field and image: unlit, then shaded with each light count. Its memory is
// the driver's free-memory delta over its first render where the driver reports free memory,
// else an estimate: the field's 3-D texture in its native texels (VTK 9.1 uploads unsigned char
// as R8, unsigned short as R16, float as R32F), the largest part by far.
struct VtkResults
{
  double UnlitMs = -1.0;
  std::map<int, double> ShadedMs; // per light count
  long long Bytes = -1;
  bool Measured = false;
  std::string Refused;
};

VtkResults MeasureVtk(vtkImageData* field,
  const Options& options,
  const Settings& settings,
  double densityMax)
{
  VtkResults results;
  const int size = field->GetDimensions()[0];
  auto mapper = MatchedVtkMapper(4.0 / (size - 1));
  View view(mapper, field, options, densityMax);
  view.Volume->VisibilityOff(); // the context and the window's buffers first
  view.Window->Render();
  GLint largest = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &largest);
  const long long textureBytes =
    (long long)size * size * size * vtkAbstractArray::GetDataTypeSize(field->GetScalarType());
  const long long free = vtkCloudVolumeMapper::GetFreeGPUMemoryBytes(view.Window);
  if (size > largest || (free >= 0 && textureBytes > free))
  {
    results.Refused = "refused: VTK's mapper needs a 3-D texture of " + std::to_string(size) +
      "^3 texels, " + cloudvis::FormatBytes(double(textureBytes)) + " (the GPU allows " +
      std::to_string(largest) + " per axis" +
      (free >= 0 ? ", reports " + cloudvis::FormatBytes(double(free)) + " free" : "") + ")";
    return results;
  }
  view.Volume->VisibilityOn();
  const long long delta = DriverBytesUsedBy(view.Window, [&] { view.Window->Render(); });
  results.Measured = delta >= 0;
  results.Bytes = results.Measured ? delta : textureBytes;
  const bool anyUnlit =
    std::find(settings.Models.begin(), settings.Models.end(), "none") != settings.Models.end();
  if (anyUnlit)
  {
    results.UnlitMs = view.MillisecondsPerFrame(settings.Frames, [] {});
  }
  if (settings.Models.size() > (anyUnlit ? 1u : 0u))
  {
    view.Property->ShadeOn();
    for (int lights : settings.Lights)
    {
      SetLights(view.Renderer, lights);
      results.ShadedMs[lights] = view.MillisecondsPerFrame(settings.Frames, [] {});
    }
  }
  return results;
}

// cloudvis on one field and image, for every model and light count asked for.
void MeasureCloud(const std::string& fieldName,
  vtkImageData* field,
  const Options& options,
  const Settings& settings,
  double densityMax,
  const VtkResults& vtk,
  std::vector<Row>& rows)
{
  const int size = field->GetDimensions()[0];
  auto mapper = MatchedCloudMapper(4.0 / (size - 1));
  View view(mapper, field, options, densityMax);
  vtkCamera* camera = view.Renderer->GetActiveCamera();
  double noneMs = -1.0;
  bool first = true;
  for (const Model& model : Models)
  {
    if (std::find(settings.Models.begin(), settings.Models.end(), model.Name) ==
      settings.Models.end())
    {
      continue;
    }
    const bool lit = model.Lighting != cloudvis::LightingModel::None;
    for (int lights : lit ? settings.Lights : std::vector<int>{ 0 })
    {
      Row row;
      row.Field = fieldName;
      row.Size = size;
      row.Image = { options.Width, options.Height };
      row.Model = model.Name;
      row.Lights = lights;
      cloudvis::LightingParameters lighting;
      lighting.Model = model.Lighting;
      lighting.Transmittance = model.Transmittance;
      mapper->GetLightingProperty()->SetParameters(lighting);
      SetLights(view.Renderer, lights);
      if (first)
      {
        view.Volume->VisibilityOff();
        view.Window->Render();
        view.Volume->VisibilityOn();
        row.CloudDriverBytes = DriverBytesUsedBy(view.Window, [&] { view.Window->Render(); });
        first = false;
      }
      else
      {
        view.Window->Render();
      }
      if (!mapper->GetLastError().empty())
      {
        row.Refused = "refused by cloudvis: " + mapper->GetLastError();
        PrintRow(row);
        rows.push_back(row);
        if (mapper->GetGPUMemoryBytes() == 0 || mapper->GetDensityTextureBytes() == 0)
        {
          return; // the field itself does not fit: no other model will
        }
        continue;
      }
      row.CloudMs = view.MillisecondsPerFrame(settings.Frames, [&] { mapper->Modified(); });
      row.CloudBytes = mapper->GetGPUMemoryBytes();
      row.VtkMs = lit ? (vtk.ShadedMs.count(lights) ? vtk.ShadedMs.at(lights) : -1.0) : vtk.UnlitMs;
      row.VtkBytes = vtk.Bytes;
      row.VtkBytesMeasured = vtk.Measured;
      if (!lit)
      {
        noneMs = row.CloudMs;
      }
      row.NoneMs = noneMs;

      // Interacting: the window's desired update rate above 1, the camera turning each frame; the
      // mapper lowers its resolution scale to keep InteractiveFrameRate. A few frames to settle,
      // then the measured ones, then one more that reads back the march's size.
      double position[3];
      camera->GetPosition(position);
      view.Window->SetDesiredUpdateRate(20.0);
      const auto turn = [&] { camera->Azimuth(1.0); };
      view.MillisecondsPerFrame(5, turn);
      row.InteractiveMs = view.MillisecondsPerFrame(settings.InteractiveFrames, turn);
      mapper->CollectStatisticsOn();
      turn();
      view.Window->Render();
      mapper->CollectStatisticsOff();
      row.InteractiveScale = double(mapper->GetLastFrameStatistics().Width) / options.Width;
      view.Window->SetDesiredUpdateRate(0.0001); // vtkRenderWindow's still rate
      camera->SetPosition(position);
      camera->SetViewUp(0.0, 1.0, 0.0);
      PrintRow(row);
      rows.push_back(row);
    }
  }
}

// Each of the targets, met or not for the rows that measure it.
void PrintTargets(const std::vector<Row>& rows)
{
  std::printf("\nTargets (issue 12; they are GPU targets: on a software renderer the verdicts are "
              "indicative only):\n");
  const auto verdict = [](bool met) { return met ? "met" : "NOT met"; };
  bool any = false;
  for (const Row& row : rows)
  {
    const bool hd = row.Image.Width == 1920 && row.Image.Height == 1080;
    if (row.Refused.empty() && row.Model == "none" && hd && (row.Size == 256 || row.Size == 512) &&
      row.VtkMs > 0.0)
    {
      const double wanted = row.Field == "sparse" ? 5.0 : 1.3;
      const double ratio = row.VtkMs / row.CloudMs;
      std::printf("- unlit %s %d^3 at 1920x1080: %.2fx VTK (target at least %.1fx): %s\n",
        row.Field.c_str(),
        row.Size,
        ratio,
        wanted,
        verdict(ratio >= wanted));
      any = true;
    }
  }
  if (!any)
  {
    std::printf("- unlit against VTK at 1920x1080, 256^3 and 512^3: not measured in this run\n");
  }
  any = false;
  for (const Row& row : rows)
  {
    if (row.Refused.empty() && row.Model == "march" && row.Lights == 2 && row.NoneMs > 0.0)
    {
      const double cost = row.CloudMs / row.NoneMs;
      std::printf("- march (light volumes), two lights, %s %d^3 at %dx%d: %.2fx none (target at "
                  "most 1.5x): %s\n",
        row.Field.c_str(),
        row.Size,
        row.Image.Width,
        row.Image.Height,
        cost,
        verdict(cost <= 1.5));
      any = true;
    }
  }
  if (!any)
  {
    std::printf("- march with two lights against none: not measured in this run\n");
  }
  any = false;
  for (const Row& row : rows)
  {
    if (row.Refused.empty() && row.Model == "march" && row.Lights == 2 && row.Size == 512 &&
      row.Field == "sparse" && row.Image.Width == 1920 && row.Image.Height == 1080)
    {
      const double fps = 1000.0 / row.CloudMs;
      std::printf("- two lights, march, sparse 512^3 at 1920x1080: %.1f frames/s (target at "
                  "least 60): %s\n",
        fps,
        verdict(fps >= 60.0));
      any = true;
    }
  }
  if (!any)
  {
    std::printf("- two lights at 512^3, 1920x1080, 60 frames/s: not measured in this run\n");
  }
}

int Run(int argc, char* argv[])
{
  Settings settings;
  bool chosen = false; // any of the subset options given
  const char* usage = "usage: cloudvis-bench-rendering matrix [--fields sparse,dense] [--sizes "
                      "256,512,1024] [--images 800x600,1920x1080,3840x2160] [--models "
                      "none,derivative,march,nested] [--lights 1,2] [--frames F] "
                      "[--interactive-frames F] [--type uchar|ushort|float] [--no-vtk]\n";
  for (int i = 2; i < argc; ++i)
  {
    const std::string option = argv[i];
    if (option == "--no-vtk")
    {
      settings.Vtk = false;
      continue;
    }
    if (i + 1 >= argc)
    {
      std::fprintf(stderr, "%s: %s needs a value\n%s", argv[0], option.c_str(), usage);
      return 2;
    }
    const std::string value = argv[++i];
    const std::vector<std::string> items = SplitList(value);
    bool valid = !items.empty();
    if (option == "--fields")
    {
      settings.Fields = items;
      for (const std::string& item : items)
        valid = valid && (item == "sparse" || item == "dense");
      chosen = true;
    }
    else if (option == "--sizes" || option == "--lights")
    {
      std::vector<int>& list = option == "--sizes" ? settings.Sizes : settings.Lights;
      list.clear();
      for (const std::string& item : items)
      {
        const int n = PositiveInteger(item);
        valid = valid && n > 0 && (option == "--sizes" ? n >= 8 : n <= 2);
        list.push_back(n);
      }
      chosen = true;
    }
    else if (option == "--images")
    {
      settings.Images.clear();
      for (const std::string& item : items)
      {
        ImageSize image{ 0, 0 };
        char end = 0;
        valid = valid &&
          std::sscanf(item.c_str(), "%dx%d%c", &image.Width, &image.Height, &end) == 2 &&
          image.Width >= 16 && image.Height >= 16 && image.Width <= 16384 && image.Height <= 16384;
        settings.Images.push_back(image);
      }
      chosen = true;
    }
    else if (option == "--models")
    {
      settings.Models = items;
      for (const std::string& item : items)
      {
        valid = valid &&
          std::any_of(
            std::begin(Models), std::end(Models), [&](const Model& m) { return item == m.Name; });
      }
      chosen = true;
    }
    else if (option == "--frames" || option == "--interactive-frames")
    {
      (option == "--frames" ? settings.Frames : settings.InteractiveFrames) =
        PositiveInteger(value);
      valid = PositiveInteger(value) > 0;
    }
    else if (option == "--type")
    {
      settings.ScalarType = value == "uchar" ? VTK_UNSIGNED_CHAR
        : value == "ushort"                  ? VTK_UNSIGNED_SHORT
        : value == "float"                   ? VTK_FLOAT
                                             : -1;
      valid = settings.ScalarType >= 0;
    }
    else
    {
      std::fprintf(stderr, "%s: unknown option %s\n%s", argv[0], option.c_str(), usage);
      return 2;
    }
    if (!valid)
    {
      std::fprintf(stderr,
        "%s: invalid value \"%s\" for %s\n%s",
        argv[0],
        value.c_str(),
        option.c_str(),
        usage);
      return 2;
    }
  }

  // What renders: a software renderer gets a small default matrix (the full one takes hours).
  std::string renderer, version;
  {
    vtkNew<vtkRenderWindow> probe;
    probe->SetOffScreenRendering(1);
    probe->SetSize(16, 16);
    probe->Render();
    renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  }
  const bool software = renderer.find("llvmpipe") != std::string::npos ||
    renderer.find("softpipe") != std::string::npos;
  std::printf("renderer: %s, OpenGL %s\n", renderer.c_str(), version.c_str());
  if (software && !chosen)
  {
    settings.Sizes = { 128, 256 };
    settings.Images = { { 800, 600 } };
    settings.Frames = std::min(settings.Frames, 3);
    std::printf("a software renderer and no --sizes/--images/--fields/--models/--lights given: "
                "the llvmpipe subset (128^3 and 256^3, 800x600, 3 frames); the full matrix is "
                "the default on a GPU\n");
  }
  std::printf("fields stored as %s; %d frames per measure (after one warm-up), %d interactive; "
              "ms/frame to the GPU's completion (glFinish); the path-traced model is measured "
              "by cloudvis-bench-gpu-pathtrace\n\n",
    vtkImageScalarTypeNameMacro(settings.ScalarType),
    settings.Frames,
    settings.InteractiveFrames);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  PrintHeader();

  std::vector<Row> rows;
  const double densityMax = cloudvis::support::FullScale(settings.ScalarType);
  for (int size : settings.Sizes)
  {
    for (const std::string& fieldName : settings.Fields)
    {
      // The field once in host memory, and a copy in the driver's (llvmpipe's textures are host
      // memory too; a GPU driver may stage it).
      const long long fieldBytes =
        (long long)size * size * size * vtkAbstractArray::GetDataTypeSize(settings.ScalarType);
      const long long needed = 2 * fieldBytes + 32LL * size * size * 4;
      const long long available = static_cast<long long>(cloudvis::AvailableMemoryBytes());
      if (available > 0 && needed > available)
      {
        Row row;
        row.Field = fieldName;
        row.Size = size;
        row.Model = "all";
        row.Refused = "skipped: the " +
          std::string(vtkImageScalarTypeNameMacro(settings.ScalarType)) + " field needs about " +
          cloudvis::FormatBytes(double(needed)) + " of host memory, " +
          cloudvis::FormatBytes(double(available)) + " available";
        PrintRow(row);
        rows.push_back(row);
        continue;
      }
      const auto field = Field(size, fieldName == "dense", settings.ScalarType);
      for (const ImageSize& image : settings.Images)
      {
        Options options;
        options.Size = size;
        options.Width = image.Width;
        options.Height = image.Height;
        VtkResults vtk;
        if (settings.Vtk)
        {
          vtk = MeasureVtk(field, options, settings, densityMax);
          if (!vtk.Refused.empty())
          {
            Row row;
            row.Field = fieldName;
            row.Size = size;
            row.Image = image;
            row.Model = "VTK";
            row.Refused = vtk.Refused;
            PrintRow(row);
            rows.push_back(row);
          }
        }
        MeasureCloud(fieldName, field, options, settings, densityMax, vtk, rows);
      }
    }
  }
  PrintTargets(rows);
  return 0;
}
} // namespace matrix

int main(int argc, char* argv[])
{
  if (argc > 1 && !std::strcmp(argv[1], "matrix"))
  {
    return matrix::Run(argc, argv);
  }
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
    AddSun(cloud.Renderer);
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
  if (std::getenv("CLOUDVIS_BENCH_REPROJECTION"))
  {
    CompareReprojection(sparse, options);
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
