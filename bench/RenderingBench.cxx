// The fields, views, mappers and lights every command of cloudvis-bench-rendering uses
// (RenderingBench.h).
#include "RenderingBench.h"

#include "OffscreenRender.h"
#include "Scene.h"
#include "VtkMessageCapture.h"
#include "vtkCloudDensitySource.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkTimerLog.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace cloudvis
{
namespace bench
{

double FullScale(int scalarType)
{
  return scalarType == VTK_UNSIGNED_CHAR ? 255.0 : scalarType == VTK_UNSIGNED_SHORT ? 65535.0 : 1.0;
}

vtkSmartPointer<vtkImageData> Quantized(vtkImageData* field, int scalarType)
{
  vtkDataArray* densities = field->GetPointData()->GetScalars();
  auto values = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(scalarType));
  values->SetName(densities->GetName());
  values->SetNumberOfTuples(densities->GetNumberOfTuples());
  const double scale = FullScale(scalarType);
  const bool integer = scalarType != VTK_FLOAT;
  for (vtkIdType i = 0; i < densities->GetNumberOfTuples(); ++i)
  {
    const double density = densities->GetComponent(i, 0);
    values->SetComponent(
      i, 0, integer ? std::round(std::clamp(density, 0.0, 1.0) * scale) : density);
  }
  auto stored = vtkSmartPointer<vtkImageData>::New();
  stored->CopyStructure(field);
  stored->GetPointData()->SetScalars(values);
  return stored;
}

// Generated in slabs of z so that a field stored as bytes never has its float densities in memory
// all at once (a 1024^3 float field is 4 GiB).
vtkSmartPointer<vtkImageData> Field(int size, bool dense, int scalarType)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(size, size, size);
  FieldDescription field;
  if (dense)
  {
    field.Shapes[0].Type = ShapeType::Box;
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
    const auto converted = Quantized(slab, scalarType);
    vtkDataArray* slabValues = converted->GetPointData()->GetScalars();
    std::memcpy(values->GetVoidPointer(vtkIdType(z0) * size * size),
      slabValues->GetVoidPointer(0),
      std::size_t(slabValues->GetNumberOfTuples()) * slabValues->GetDataTypeSize());
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

vtkSmartPointer<vtkCloudVolumeMapper> CloudMapper(double step)
{
  // The app's set-up (ConfigureMapper) for a render section without jitter or accumulation; the
  // step is every renderer's (ConfigureLighting's in the app).
  RenderSpec render;
  render.Jitter = false;
  render.Accumulate = 1;
  auto mapper = vtkSmartPointer<vtkCloudVolumeMapper>::New();
  ConfigureMapper(mapper, render);
  mapper->SetSampleDistance(step);
  return mapper;
}

vtkSmartPointer<vtkGPUVolumeRayCastMapper> VtkMapper(double step)
{
  auto peer = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
  peer->SetBlendModeToComposite();
  peer->SetUseJittering(0);
  peer->AutoAdjustSampleDistancesOff();
  peer->LockSampleDistanceToInputSpacingOff();
  peer->SetSampleDistance(step);
  return peer;
}

View::View(vtkVolumeMapper* mapper, vtkImageData* field, const Options& options, double densityMax)
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

double View::MillisecondsPerFrame(int frames, const std::function<void()>& beforeEachFrame)
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

RenderedImage View::Pixels()
{
  const VtkMessageCapture messages;
  return CaptureWindow(this->Window, "cloudvis-bench-rendering", messages);
}

double RmsLevels(const RenderedImage& a, const RenderedImage& b)
{
  if (a.Width != b.Width || a.Height != b.Height || a.RGB.empty())
  {
    return std::numeric_limits<double>::infinity();
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < a.RGB.size(); ++i)
  {
    const double d = double(a.RGB[i]) - double(b.RGB[i]);
    sum += d * d;
  }
  return std::sqrt(sum / double(a.RGB.size()));
}

void SetLights(vtkRenderer* renderer, int count)
{
  renderer->RemoveAllLights();
  if (count >= 1)
  {
    vtkNew<vtkLight> sun;
    sun->SetLightTypeToSceneLight();
    sun->SetPositional(false);
    sun->SetPosition(6.0, 8.0, 4.0);
    sun->SetFocalPoint(0.0, 0.0, 0.0);
    sun->SetIntensity(1.0);
    renderer->AddLight(sun);
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

std::optional<LightingParameters> MeasuredLighting(const std::string& name)
{
  LightingParameters lighting;
  if (name == "nested")
  {
    lighting.Model = LightingModel::March;
    lighting.Transmittance = LightTransmittance::Nested;
    return lighting;
  }
  if (name == "octaves")
  {
    lighting.Model = LightingModel::March;
    lighting.MultipleScattering = MultipleScatteringModel::Octaves;
    return lighting;
  }
  const std::optional<LightingModel> model = FindLightingModel(name);
  if (!model || *model == LightingModel::PathTrace)
  {
    return std::nullopt;
  }
  lighting.Model = *model;
  return lighting;
}

} // namespace bench
} // namespace cloudvis
