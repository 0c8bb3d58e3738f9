// What the renderers' unit tests share (TestPathTracer.cxx, TestReferenceRenderer.cxx): fields
// on a box from a density function, linear transfer tables and the volume properties that give
// them, lights, a parallel view, the
// rendered image with its per-pixel variance, means with their standard errors, and counting
// an algorithm's errors. Statistical checks take their tolerance from the variance the path
// tracer reports, so they are as tight as the noise allows.
#ifndef RendererTestSupport_h
#define RendererTestSupport_h

#include "CloudLighting.h"
#include "CloudTransferTable.h"
#include "vtkCloudPathTracer.h"

#include <vtkCallbackCommand.h>
#include <vtkColorTransferFunction.h>
#include <vtkCommand.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkVolumeProperty.h>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace cloudvis
{
namespace test
{

// A float field of dims voxels spanning the world box [lo, hi], density(x, y, z) at each voxel.
inline vtkSmartPointer<vtkImageData> MakeBoxField(glm::ivec3 dims, glm::dvec3 lo, glm::dvec3 hi,
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

// sigma_t rising linearly from 0 at density 0 to sigma_t at density 1 (so a trilinear sample's
// extinction is exactly sigma_t times its density), one albedo.
inline TransferTable LinearTable(float sigma_t, glm::vec3 albedo = glm::vec3(1.0f))
{
  TransferTable table;
  table.Size = 2;
  table.RGBA = { albedo.r, albedo.g, albedo.b, 0.0f, albedo.r, albedo.g, albedo.b, sigma_t };
  return table;
}

// The transfer function whose table (cloudvis::TransferTableOf, TransferTableSize entries over
// [0, densityMax]) is LinearTable's: sigma_t * density / densityMax at every entry, one albedo.
// The opacity per unit distance u is 1 - exp(-sigma_t u d / densityMax), given at each entry's
// density, with u = 1 / sigma_t so that it stays below VTK's opacity of 1.
inline vtkSmartPointer<vtkVolumeProperty> LinearMedium(float sigma_t,
  glm::vec3 albedo = glm::vec3(1.0f),
  double densityMax = 1.0)
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

// No light but the ambient, a uniform environment of this radiance.
inline LightingParameters Ambient(glm::vec3 radiance)
{
  LightingParameters lighting;
  lighting.AmbientColor = radiance;
  lighting.AmbientStrength = 1.0f;
  return lighting;
}

// A sphere of radius 0.6 with a soft edge 0.3 wide in [-1, 1]^3: optically thick at its core.
inline vtkSmartPointer<vtkImageData> SoftSphere(int n = 32)
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

inline Light DirectionalLight(glm::vec3 towardLight, float intensity = 1.0f)
{
  Light light;
  light.Position = glm::dvec3(10.0f * towardLight);
  light.FocalPoint = glm::dvec3(0.0);
  light.Intensity = intensity;
  return light;
}

inline Light PointLight(glm::vec3 position, float intensity = 1.0f)
{
  Light light;
  light.Positional = true;
  light.Position = glm::dvec3(position);
  light.Intensity = intensity;
  light.Attenuation = glm::vec3(0.0f, 0.0f, 1.0f); // inverse square
  return light;
}

// A parallel view of the region [-scale, scale]^2 around `focal` (world), looking along `view`.
inline void SetParallelView(
  vtkCloudReferenceRenderer* renderer, glm::dvec3 focal, glm::dvec3 view, double scale)
{
  const glm::dvec3 position = focal - 5.0 * glm::normalize(view);
  renderer->SetCameraPosition(position.x, position.y, position.z);
  renderer->SetCameraFocalPoint(focal.x, focal.y, focal.z);
  renderer->SetCameraViewUp(0.0, 1.0, 0.0);
  renderer->ParallelProjectionOn();
  renderer->SetParallelScale(scale);
  renderer->SetClippingRange(1.0, 10.0);
}

// An image and, for path-traced ones, the variance of each pixel's mean.
struct Image
{
  int Width = 0, Height = 0;
  std::vector<float> RGBA;
  std::vector<float> Variance;

  std::size_t Pixels() const { return std::size_t(this->Width) * this->Height; }
  float At(std::size_t pixel, int c) const { return this->RGBA[4 * pixel + c]; }
  float VarianceAt(std::size_t pixel, int c) const { return this->Variance[4 * pixel + c]; }
};

inline Image Render(vtkCloudReferenceRenderer* renderer)
{
  renderer->Modified();
  renderer->Update();
  vtkImageData* output = renderer->GetOutput();
  Image image;
  int dims[3];
  output->GetDimensions(dims);
  image.Width = dims[0];
  image.Height = dims[1];
  const auto copy = [output](const char* name, std::vector<float>& to)
  {
    if (auto* array = vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray(name)))
    {
      to.assign(array->GetPointer(0), array->GetPointer(0) + array->GetNumberOfValues());
    }
  };
  copy("rgba", image.RGBA);
  copy("rgba_variance", image.Variance);
  return image;
}

// How many errors an algorithm reports when it updates.
inline int CountErrors(vtkAlgorithm* algorithm)
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

// A mean and the standard error of it.
struct Estimate
{
  double Mean = 0.0;
  double StandardError = 0.0;
};

// The mean over pixels (where `use` says so) of f(pixel), each pixel's f having the variance
// v(pixel), the pixels independent.
inline Estimate MeanOverPixels(
  const Image& image, const std::function<double(std::size_t)>& f,
  const std::function<double(std::size_t)>& v,
  const std::function<bool(std::size_t)>& use = [](std::size_t) { return true; })
{
  double sum = 0.0, variance = 0.0;
  int n = 0;
  for (std::size_t p = 0; p < image.Pixels(); ++p)
  {
    if (use(p))
    {
      sum += f(p);
      variance += v(p);
      ++n;
    }
  }
  return { sum / n, std::sqrt(variance) / n };
}

// The largest |z| over blocks of blockSize x blockSize pixels (where `use` picks at least half
// of a block's pixels) of the block's mean difference over its standard error. A block pools
// thousands of paths, so its mean is close to normal and its variance estimate reliable even
// where single pixels depend on rare events (a path that hits a thin edge, or fails to).
inline double LargestBlockZ(const Image& image, int blockSize,
  const std::function<double(std::size_t)>& difference,
  const std::function<double(std::size_t)>& variance, const std::function<bool(std::size_t)>& use,
  int& blocks)
{
  double largest = 0.0;
  blocks = 0;
  for (int bj = 0; bj + blockSize <= image.Height; bj += blockSize)
  {
    for (int bi = 0; bi + blockSize <= image.Width; bi += blockSize)
    {
      double sum = 0.0, v = 0.0;
      int used = 0;
      for (int j = bj; j < bj + blockSize; ++j)
      {
        for (int i = bi; i < bi + blockSize; ++i)
        {
          const std::size_t p = std::size_t(j) * image.Width + i;
          if (use(p))
          {
            sum += difference(p);
            v += variance(p);
            ++used;
          }
        }
      }
      if (2 * used >= blockSize * blockSize && v > 0.0)
      {
        largest = std::max(largest, std::abs(sum) / std::sqrt(v));
        ++blocks;
      }
    }
  }
  return largest;
}

// The checks of every image comparison: the mean of `difference` over the pixels `use` picks is
// 0 within `sigmas` standard errors, and so is each block's (a local error cannot hide in the
// mean: at least minBlocks blocks of 3 x 3 or more pixels count); and the standard error is
// below `tightness` (1%) of `scale`, so the check is tight.
inline void ExpectNoDifference(const Image& image, int blockSize,
  const std::function<double(std::size_t)>& difference,
  const std::function<double(std::size_t)>& variance, const std::function<bool(std::size_t)>& use,
  double scale, int minBlocks, const std::string& what, double tightness = 0.01,
  double sigmas = 4.0)
{
  const Estimate mean = MeanOverPixels(image, difference, variance, use);
  EXPECT_NEAR(mean.Mean, 0.0, sigmas * mean.StandardError) << what;
  EXPECT_LT(mean.StandardError, tightness * scale) << what;
  int blocks = 0;
  EXPECT_LT(LargestBlockZ(image, blockSize, difference, variance, use, blocks), sigmas) << what;
  EXPECT_GE(blocks, minBlocks) << what;
}

} // namespace test
} // namespace cloudvis

#endif
