// The scenes and renderers every command of cloudvis-bench-pathtrace uses (PathTraceBench.h).
#include "PathTraceBench.h"

#include "CloudImageComparison.h"
#include "CpuReference.h"
#include "ImageWriters.h"
#include "SceneField.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkTimerLog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cloudvis
{
namespace bench
{

void Fail(const std::string& message)
{
  throw std::runtime_error(message);
}

BenchScene ReadBenchScene(const std::string& path, const std::vector<std::string>& assignments)
{
  return { path.substr(path.find_last_of('/') + 1), LoadScene(path, assignments) };
}

Scene Relit(const Scene& scene, const std::vector<Light>& lights, float albedo)
{
  Scene relit = scene;
  relit.Lights = lights;
  if (albedo >= 0.0f)
  {
    for (auto& point : relit.TransferFunction.Color)
    {
      point[1] = point[2] = point[3] = albedo;
    }
  }
  return relit;
}

Light LightToward(glm::vec3 towardLight)
{
  Light light;
  light.Position = glm::dvec3(10.0f * towardLight);
  return light;
}

vtkSmartPointer<vtkImageData> FieldOf(const Scene& scene)
{
  return ProduceField(scene);
}

namespace
{
// The scene at the benchmark's image size, set up on `renderer` as the app sets up its CPU
// reference.
void SetUp(const Scene& scene,
  vtkImageData* field,
  const Options& options,
  vtkCloudReferenceRenderer* renderer)
{
  Scene sized = scene;
  sized.Render.Size = { { options.Width, options.Height } };
  SetUpReference(sized, field, renderer);
}
}

vtkSmartPointer<vtkCloudReferenceRenderer> NewMarch(const Scene& scene,
  vtkImageData* field,
  const LightingParameters& lighting,
  const Options& options)
{
  auto march = vtkSmartPointer<vtkCloudReferenceRenderer>::New();
  SetUp(scene, field, options, march);
  march->GetLightingProperty()->SetParameters(lighting);
  return march;
}

vtkSmartPointer<vtkCloudPathTracer> NewTracer(const Scene& scene,
  vtkImageData* field,
  int maxBounces,
  const Options& options)
{
  auto tracer = vtkSmartPointer<vtkCloudPathTracer>::New();
  SetUp(scene, field, options, tracer);
  tracer->SetSamplesPerPixel(options.Samples);
  tracer->SetMaxBounces(maxBounces);
  tracer->SetBrickSize(options.BrickSize);
  tracer->SetSeed(options.Seed);
  return tracer;
}

Rendered Run(vtkCloudReferenceRenderer* renderer)
{
  const double start = vtkTimerLog::GetUniversalTime();
  renderer->Modified();
  renderer->Update();
  Rendered result;
  result.Seconds = vtkTimerLog::GetUniversalTime() - start;
  vtkPointData* pd = renderer->GetOutput()->GetPointData();
  auto* rgba = vtkFloatArray::SafeDownCast(pd->GetArray("rgba"));
  if (!rgba)
    Fail("the renderer produced no image");
  result.RGBA.assign(rgba->GetPointer(0), rgba->GetPointer(0) + rgba->GetNumberOfValues());
  if (auto* variance = vtkFloatArray::SafeDownCast(pd->GetArray("rgba_variance")))
    result.Variance.assign(
      variance->GetPointer(0), variance->GetPointer(0) + variance->GetNumberOfValues());
  for (float v : result.RGBA)
    if (!std::isfinite(v))
      Fail("the renderer produced a non-finite pixel");
  return result;
}

double MeanRadiance(const Rendered& image)
{
  return MeasureImageNoise(image.RGBA.data(), image.RGBA.data(), image.RGBA.size() / 4)
    .MeanRadiance;
}

void WritePng(const std::string& directory,
  const std::string& name,
  const std::vector<float>& rgba,
  int width,
  int height)
{
  if (directory.empty())
    return;
  RenderedImage image;
  image.Width = width;
  image.Height = height;
  image.RGB.resize(std::size_t(width) * height * 3);
  for (std::size_t p = 0; p < std::size_t(width) * height; ++p)
    for (int c = 0; c < 3; ++c)
      image.RGB[3 * p + c] =
        static_cast<unsigned char>(std::lround(255.0f * std::clamp(rgba[4 * p + c], 0.0f, 1.0f)));
  WriteImage(image, directory + "/" + name + ".png");
}

std::vector<BenchScene> ErrorFields()
{
  BenchScene fbm = ReadBenchScene("data/scenes/fbm-sphere.json", { "ambient.strength=0" });
  BenchScene dense = ReadBenchScene("data/scenes/fbm-sphere.json",
    { "ambient.strength=0", "field.shape.radius=1.8", "transfer_function.unit_distance=0.5" });
  fbm.Name = "fbm-sphere";
  dense.Name = "dense";
  return { fbm, dense };
}

} // namespace bench
} // namespace cloudvis
