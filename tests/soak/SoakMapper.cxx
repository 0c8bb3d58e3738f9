// Soak test of vtkCloudVolumeMapper: 1,000 frames in one window while everything that makes the
// mapper reallocate or rebuild changes under it (lighting model and its parameters, transfer
// function, step, jitter, accumulation, resolution scale, empty-space skipping, window size, and
// every 250 frames the field itself). Resident memory (VmRSS) is read at frame 100, once every
// cache has been filled at least once, and at frame 1000; it must not grow by more than
// CLOUDVIS_SOAK_MAX_GROWTH percent (default 5) over those 900 frames, and every frame must
// render without a mapper error. Under the address sanitizer build LeakSanitizer checks at exit
// that everything allocated was released. The figures go to stdout (and docs/reliability.md).
#include "CloudLighting.h"
#include "SupportScene.h"
#include "vtkCloudDensitySource.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkVolumeProperty.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace
{

// AddressSanitizer keeps freed memory in its quarantine (256 MiB by default), so resident memory
// climbs by design there; under it the growth is reported, and LeakSanitizer judges at exit.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool UnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool UnderAddressSanitizer = true;
#else
constexpr bool UnderAddressSanitizer = false;
#endif
#else
constexpr bool UnderAddressSanitizer = false;
#endif

constexpr int Frames = 1000;
constexpr int FirstMeasuredFrame = 100;

// Resident set size of this process in KiB, from /proc/self/status.
long ResidentKiB()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.rfind("VmRSS:", 0) == 0)
    {
      std::istringstream in(line.substr(6));
      long kib = 0;
      in >> kib;
      return kib;
    }
  }
  return -1;
}

vtkSmartPointer<vtkImageData> MakeField(int size, unsigned seed)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(size, size, size);
  source->SetBounds(-2, 2, -2, 2, -2, 2);
  cloudvis::FieldDescription field;
  field.Noise.Seed = seed;
  field.Noise.Octaves = 3;
  source->SetField(field);
  source->Update();
  vtkSmartPointer<vtkImageData> image = source->GetOutput();
  return image;
}

// Frame-dependent transfer function: the number of points and their values change.
void SetTransferFunction(vtkVolumeProperty* property, int frame)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  vtkNew<vtkColorTransferFunction> color;
  const int points = 2 + frame % 5;
  for (int i = 0; i < points; ++i)
  {
    const double density = double(i) / (points - 1);
    opacity->AddPoint(density, density * (0.3 + 0.1 * (frame % 7)));
    color->AddRGBPoint(density, 0.5 + 0.5 * density, 0.6, 0.7 + 0.03 * (frame % 10));
  }
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetScalarOpacityUnitDistance(0.05 + 0.01 * (frame % 11));
}

} // namespace

int main()
{
  const char* growthText = std::getenv("CLOUDVIS_SOAK_MAX_GROWTH");
  const double maxGrowthPercent = growthText ? std::atof(growthText) : 5.0;

  // The render tests' off-screen scene (tests/support), under a headlight for the lighting
  // models to use.
  vtkNew<vtkCloudVolumeMapper> mapper;
  cloudvis::support::GpuScene scene(mapper, 64, 64);
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  vtkVolumeProperty* property = scene.Property;
  property->SetInterpolationTypeToLinear();
  renderer->CreateLight();

  long residentAt100 = 0;
  for (int frame = 1; frame <= Frames; ++frame)
  {
    if (frame % 250 == 1)
    {
      mapper->SetInputData(MakeField(24 + 8 * ((frame / 250) % 2), 7u + unsigned(frame)));
      renderer->ResetCamera();
    }
    if (frame % 10 == 0)
    {
      const int sizes[4][2] = { { 64, 64 }, { 96, 48 }, { 48, 80 }, { 72, 72 } };
      window->SetSize(sizes[(frame / 10) % 4][0], sizes[(frame / 10) % 4][1]);
    }
    cloudvis::LightingParameters lighting;
    lighting.Model = static_cast<cloudvis::LightingModel>(frame % 3);
    lighting.LightSteps = 2 + frame % 5;
    lighting.AmbientStrength = 0.1f * float(frame % 4);
    lighting.MultipleScattering = frame % 8 < 4 ? cloudvis::MultipleScatteringModel::Volume
                                                : cloudvis::MultipleScatteringModel::Octaves;
    lighting.MultipleScatteringOctaves = frame % 4;
    mapper->GetLightingProperty()->SetParameters(lighting);
    SetTransferFunction(property, frame);
    mapper->SetSampleDistance(frame % 2 ? 0.0 : 0.08);
    mapper->SetJitter(frame % 3 != 0);
    mapper->SetMaximumAccumulatedFrames(1 + frame % 4);
    mapper->SetResolutionScale(frame % 5 == 0 ? 0.5 : 1.0);
    mapper->SetEmptySpaceSkipping(frame % 7 != 0);
    renderer->GetActiveCamera()->Azimuth(1.0);

    window->Render();
    if (!mapper->GetLastError().empty())
    {
      std::cerr << "frame " << frame << ": " << mapper->GetLastError() << "\n";
      return 1;
    }
    if (frame == FirstMeasuredFrame)
    {
      residentAt100 = ResidentKiB();
    }
  }
  const long residentAt1000 = ResidentKiB();
  const double growth = 100.0 * double(residentAt1000 - residentAt100) / double(residentAt100);
  std::cout << "VmRSS at frame " << FirstMeasuredFrame << ": " << residentAt100 << " KiB\n"
            << "VmRSS at frame " << Frames << ": " << residentAt1000 << " KiB\n"
            << "growth: " << growth << "% (allowed: " << maxGrowthPercent << "%)\n";
  if (residentAt100 <= 0 || residentAt1000 <= 0)
  {
    std::cerr << "cannot read VmRSS from /proc/self/status\n";
    return 1;
  }
  if (UnderAddressSanitizer)
  {
    std::cout << "growth not checked under AddressSanitizer (quarantine); leaks are checked at exit\n";
    return 0;
  }
  if (growth >= maxGrowthPercent)
  {
    std::cerr << "resident memory grew by " << growth << "% over " << Frames - FirstMeasuredFrame
              << " frames, more than the " << maxGrowthPercent << "% allowed\n";
    return 1;
  }
  return 0;
}
