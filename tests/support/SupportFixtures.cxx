// The renderer tests' fields, media, lights, view and CPU images (SupportFixtures.h).
#include "SupportFixtures.h"

#include "CloudMarchUniforms.h"

#include "vtkCloudDensitySource.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkCommand.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace cloudvis
{
namespace support
{
namespace
{
vtkSmartPointer<vtkImageData> Generate(const FieldDescription& field, int size, double extent)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(size, size, size);
  source->SetBounds(-extent, extent, -extent, extent, -extent, extent);
  source->SetField(field);
  source->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(source->GetOutput());
  return image;
}

}

vtkSmartPointer<vtkImageData> MakeBoxField(glm::ivec3 dims,
  glm::dvec3 lo,
  glm::dvec3 hi,
  const std::function<double(double, double, double)>& density)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims.x, dims.y, dims.z);
  const glm::dvec3 spacing = (hi - lo) / glm::dvec3(dims - 1);
  image->SetOrigin(lo.x, lo.y, lo.z);
  image->SetSpacing(spacing.x, spacing.y, spacing.z);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("density");
  scalars->SetNumberOfTuples(vtkIdType(dims.x) * dims.y * dims.z);
  vtkIdType v = 0;
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i)
        scalars->SetValue(
          v++, float(density(lo.x + i * spacing.x, lo.y + j * spacing.y, lo.z + k * spacing.z)));
  image->GetPointData()->SetScalars(scalars);
  return image;
}

vtkSmartPointer<vtkImageData> LinearBall(int side, double radius)
{
  const double voxel = double(side - 1);
  return MakeBoxField({ side, side, side },
    glm::dvec3(0.0),
    glm::dvec3(1.0),
    [=](double x, double y, double z)
    {
      const double r = voxel * glm::length(glm::dvec3(x, y, z) - glm::dvec3(0.5));
      return std::max(0.0, 1.0 - r / radius);
    });
}

void WriteImageData(vtkImageData* image, const std::string& path)
{
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName((path + ".part").c_str());
  writer->SetInputData(image);
  if (writer->Write() != 1 || std::rename((path + ".part").c_str(), path.c_str()) != 0)
  {
    throw std::runtime_error("could not write " + path);
  }
}

vtkSmartPointer<vtkImageData> SoftSphere(int n)
{
  return MakeBoxField({ n, n, n },
    glm::dvec3(-1.0),
    glm::dvec3(1.0),
    [](double x, double y, double z)
    {
      const double r = std::sqrt(x * x + y * y + z * z);
      return std::min(1.0, std::max(0.0, (0.75 - r) / 0.3));
    });
}

vtkSmartPointer<vtkImageData> ConstantSphere(double radius, int size)
{
  FieldDescription field;
  field.Model = DensityModel::Constant;
  field.Shapes[0].Radius = float(radius);
  return Generate(field, size, 2.0);
}

vtkSmartPointer<vtkImageData> ConstantBox(double halfSize, int size, double extent)
{
  FieldDescription field;
  field.Model = DensityModel::Constant;
  field.Shapes[0].Type = ShapeType::Box;
  field.Shapes[0].HalfSize = glm::vec3(float(halfSize));
  return Generate(field, size, extent);
}

vtkSmartPointer<vtkImageData> SparseCloud(int size)
{
  FieldDescription field; // the article's cloud: unit sphere + 6 octaves
  return Generate(field, size, 2.0);
}

vtkSmartPointer<vtkImageData> DenseCloud(int size)
{
  FieldDescription field;
  field.Shapes[0].Type = ShapeType::Box;
  field.Shapes[0].HalfSize = glm::vec3(2.5f);
  field.DensityScale = 0.5;
  return Generate(field, size, 2.0);
}

TransferTable LinearTable(float sigma_t, glm::vec3 albedo)
{
  TransferTable table;
  table.Size = 2;
  table.RGBA = { albedo.r, albedo.g, albedo.b, 0.0f, albedo.r, albedo.g, albedo.b, sigma_t };
  return table;
}

vtkSmartPointer<vtkVolumeProperty> LinearMedium(float sigma_t, glm::vec3 albedo, double densityMax)
{
  const double unitDistance = 1.0 / double(sigma_t);
  vtkNew<vtkPiecewiseFunction> opacity;
  const int entries = TransferTableSize;
  for (int i = 0; i < entries; ++i)
  {
    const double density = densityMax * (double(i) / (entries - 1));
    opacity->AddPoint(density, -std::expm1(-double(sigma_t) * unitDistance * density / densityMax));
  }
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, albedo.r, albedo.g, albedo.b);
  color->AddRGBPoint(densityMax, albedo.r, albedo.g, albedo.b);
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetScalarOpacityUnitDistance(unitDistance);
  return property;
}

void SetUniformMedium(vtkVolumeProperty* property,
  double opacity,
  double unitDistance,
  double r,
  double g,
  double b)
{
  vtkNew<vtkPiecewiseFunction> o;
  o->AddPoint(0.0, 0.0);
  o->AddPoint(0.49, 0.0);
  o->AddPoint(0.51, opacity);
  o->AddPoint(1.0, opacity);
  vtkNew<vtkColorTransferFunction> c;
  c->AddRGBPoint(0.0, r, g, b);
  c->AddRGBPoint(1.0, r, g, b);
  property->SetScalarOpacity(o);
  property->SetColor(c);
  property->SetScalarOpacityUnitDistance(unitDistance);
  property->SetInterpolationTypeToLinear();
  property->ShadeOff();
}

void SetRampMedium(vtkVolumeProperty* property, double max, double opacity)
{
  vtkNew<vtkPiecewiseFunction> o;
  o->AddPoint(0.0, 0.0);
  o->AddPoint(max, opacity);
  vtkNew<vtkColorTransferFunction> c;
  c->AddRGBPoint(0.0, 0.9, 0.5, 0.2);
  c->AddRGBPoint(max, 0.3, 0.6, 1.0);
  property->SetScalarOpacity(o);
  property->SetColor(c);
  property->SetScalarOpacityUnitDistance(0.1);
  property->SetInterpolationTypeToLinear();
  property->ShadeOff();
}

LightingParameters Ambient(glm::vec3 radiance)
{
  LightingParameters lighting;
  lighting.AmbientColor = radiance;
  lighting.AmbientStrength = 1.0f;
  return lighting;
}

LightingParameters ModelOnly(LightingModel model)
{
  LightingParameters lighting;
  lighting.Model = model;
  return lighting;
}

LightingParameters EveryLightingParameterChanged()
{
  // Each default moved by a step that keeps it within LightingLimits.
  const LightingParameters d;
  LightingParameters p;
  p.Model = LightingModel::March;
  p.Transmittance = LightTransmittance::Nested;
  p.AmbientColor = d.AmbientColor - glm::vec3(0.9f, 0.8f, 0.7f);
  p.AmbientStrength = d.AmbientStrength + 0.4f;
  p.DerivativeDistance = d.DerivativeDistance + 0.5f;
  p.LightSteps = d.LightSteps + 3;
  p.LightStep = d.LightStep + 0.06f;
  p.LightStepGrowth = d.LightStepGrowth - 0.3f;
  p.PhaseG1 = d.PhaseG1 + 0.1f;
  p.PhaseG2 = d.PhaseG2 + 0.1f;
  p.PhaseLobeWeight = d.PhaseLobeWeight - 0.2f;
  p.MultipleScattering = d.MultipleScattering == MultipleScatteringModel::Volume
    ? MultipleScatteringModel::Octaves
    : MultipleScatteringModel::Volume;
  p.MultipleScatteringOctaves = d.MultipleScatteringOctaves + 2;
  p.ScatteringFalloff = d.ScatteringFalloff + 0.04f;
  p.ExtinctionFalloff = d.ExtinctionFalloff + 0.09f;
  p.EccentricityFalloff = d.EccentricityFalloff - 0.21f;
  p.PowderStrength = d.PowderStrength + 0.15f;
  return p;
}

Light DirectionalLight(glm::dvec3 towardLight, float intensity, glm::vec3 color)
{
  Light light;
  light.Position = towardLight;
  light.FocalPoint = glm::dvec3(0.0);
  light.Color = color;
  light.Intensity = intensity;
  return light;
}

Light PointLight(glm::dvec3 position, float intensity, glm::vec3 color)
{
  Light light;
  light.Positional = true;
  light.Position = position;
  light.Color = color;
  light.Intensity = intensity;
  light.Attenuation = glm::vec3(0.0f, 0.0f, 1.0f); // inverse square
  return light;
}

void AddLight(vtkRenderer* renderer, const Light& light)
{
  renderer->AddLight(MakeLight(light));
}

void SetParallelView(vtkCamera* camera, glm::dvec3 focal, glm::dvec3 view, double scale)
{
  const glm::dvec3 position = focal - 5.0 * glm::normalize(view);
  camera->SetPosition(position.x, position.y, position.z);
  camera->SetFocalPoint(focal.x, focal.y, focal.z);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(scale);
  camera->SetClippingRange(1.0, 10.0);
}

void SetParallelView(vtkCloudReferenceRenderer* renderer,
  glm::dvec3 focal,
  glm::dvec3 view,
  double scale)
{
  vtkNew<vtkCamera> camera;
  SetParallelView(camera, focal, view, scale);
  renderer->SetCameraPosition(camera->GetPosition());
  renderer->SetCameraFocalPoint(camera->GetFocalPoint());
  renderer->SetCameraViewUp(camera->GetViewUp());
  renderer->SetParallelProjection(true);
  renderer->SetParallelScale(camera->GetParallelScale());
  renderer->SetClippingRange(camera->GetClippingRange());
}

Image ImageOf(vtkImageData* output)
{
  int dims[3];
  output->GetDimensions(dims);
  const auto floats = [output](const char* name)
  {
    std::vector<float> values;
    if (auto* array = vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray(name)))
    {
      values.assign(array->GetPointer(0), array->GetPointer(0) + array->GetNumberOfValues());
    }
    return values;
  };
  return FromRgba(floats("rgba"), dims[0], dims[1], floats("rgba_variance"));
}

Image Render(vtkCloudReferenceRenderer* renderer)
{
  renderer->Modified();
  renderer->Update();
  return ImageOf(renderer->GetOutput());
}

ImageError CompareWithReference(const Image& image, const Image& reference)
{
  const std::vector<float> rgba(image.Values.begin(), image.Values.end()),
    referenceRgba(reference.Values.begin(), reference.Values.end()),
    referenceVariance(reference.Variance.begin(), reference.Variance.end());
  if (rgba.size() != referenceRgba.size() || referenceVariance.size() != referenceRgba.size())
  {
    return ImageError{};
  }
  return cloudvis::CompareWithReference(
    rgba.data(), referenceRgba.data(), referenceVariance.data(), reference.Pixels());
}

int CountErrors(vtkAlgorithm* algorithm)
{
  int errors = 0;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void*) { ++*static_cast<int*>(clientData); });
  const unsigned long tag = algorithm->AddObserver(vtkCommand::ErrorEvent, onError);
  algorithm->Modified();
  algorithm->Update();
  algorithm->RemoveObserver(tag);
  return errors;
}

} // namespace support
} // namespace cloudvis
