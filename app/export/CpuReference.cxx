#include "CpuReference.h"

#include "CloudMarchUniforms.h"
#include "Errors.h"
#include "ExportRender.h"
#include "SceneLighting.h"
#include "VtkMessageCapture.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkLightCollection.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{

void SetReferenceCamera(vtkCloudReferenceRenderer* reference, vtkCamera* camera)
{
  reference->SetCameraPosition(camera->GetPosition());
  reference->SetCameraFocalPoint(camera->GetFocalPoint());
  reference->SetCameraViewUp(camera->GetViewUp());
  reference->SetViewAngle(camera->GetViewAngle());
  reference->SetParallelProjection(camera->GetParallelProjection() != 0);
  reference->SetParallelScale(camera->GetParallelScale());
  reference->SetClippingRange(camera->GetClippingRange());
}

void SetUpReference(const Scene& scene, vtkImageData* field, vtkCloudReferenceRenderer* reference)
{
  const int width = scene.Render.Size[0];
  const int height = scene.Render.Size[1];
  // The camera exactly as RenderOffscreen's: ApplyCamera on a renderer of the image's aspect.
  // The renderer is never drawn and has no window, so it keeps the aspect it is given.
  vtkNew<vtkRenderer> renderer;
  renderer->SetAspect(double(width) / double(height), 1.0);
  ApplyCamera(scene.Camera, field->GetBounds(), renderer, scene.Source);
  reference->SetInputData(field);
  reference->SetImageSize(width, height);
  SetReferenceCamera(reference, renderer->GetActiveCamera());
  ConfigureReference(scene, reference);
}

void CheckSceneRenderable(const Scene& scene, vtkImageData* field, const std::string& input)
{
  const std::string geometryProblem = ValidateVolumeGeometry(field, nullptr);
  if (!geometryProblem.empty())
  {
    throw InputError(input + ": " + geometryProblem);
  }
  // What both renderers will be given (RendererSettingsOf), checked as both check it.
  const RendererSettings settings = RendererSettingsOf(scene);
  std::string tableProblem;
  const TransferTable table = TransferTableOf(settings.TransferFunction, 1.0, tableProblem);
  if (!tableProblem.empty())
  {
    throw InputError(scene.Source + ": " + tableProblem);
  }
  // The geometry and the parameters matter here, not the values; the scene does not set the
  // termination transmittance (every renderer's default).
  const MarchSetup setup = MakeMarchSetup(field,
    nullptr,
    DensityTexels(),
    &table,
    settings.SampleDistance,
    MarchSetup().TerminationTransmittance,
    settings.Lighting->GetParameters(),
    settings.Lights);
  MarchUniforms uniforms;
  const MarchProblem problem = SetUpMarch(setup, uniforms);
  switch (problem.Input)
  {
    case MarchInput::None:
      return;
    case MarchInput::Geometry:
      throw InputError(input + ": " + problem.Message);
    case MarchInput::TransferFunction:
      throw InputError(scene.Source + ": transfer_function: " + problem.Message);
    case MarchInput::Step:
      throw InputError(scene.Source + ": render.step: " + problem.Message);
    case MarchInput::Lighting:
      // The path tracer's parameters are the march's phase (render.march).
      throw InputError(scene.Source + ": " +
        (scene.Render.Lighting.Model == LightingModel::None ? std::string("render")
                                                            : std::string("render.") +
              LightingModelName(scene.Render.Lighting.Model == LightingModel::PathTrace
                  ? LightingModel::March
                  : scene.Render.Lighting.Model)) +
        ": " + problem.Message);
    case MarchInput::Light:
      throw InputError(
        scene.Source + ": lights[" + std::to_string(problem.Light) + "]: " + problem.Message);
  }
}

RenderedImage RenderCpuReference(const Scene& scene, vtkImageData* field, const std::string& input)
{
  CheckSceneRenderable(scene, field, input);
  const int width = scene.Render.Size[0];
  const int height = scene.Render.Size[1];

  VtkMessageCapture messages;
  // pathtrace: the CPU path tracer, render.spp paths per pixel; else the march's reference.
  vtkSmartPointer<vtkCloudReferenceRenderer> reference;
  if (scene.Render.Lighting.Model == LightingModel::PathTrace)
  {
    vtkNew<vtkCloudPathTracer> tracer;
    tracer->SetSamplesPerPixel(scene.Render.SamplesPerPixel);
    reference = tracer;
  }
  else
  {
    reference = vtkSmartPointer<vtkCloudReferenceRenderer>::New();
  }
  SetUpReference(scene, field, reference);
  reference->Update();

  vtkImageData* output = reference->GetOutput();
  auto* rgba = vtkFloatArray::SafeDownCast(output->GetPointData()->GetScalars());
  if (!messages.Messages().empty() || !rgba || rgba->GetNumberOfComponents() != 4 ||
    rgba->GetNumberOfTuples() != vtkIdType(width) * height)
  {
    throw InputError(input + ": CPU reference: " +
      (messages.Messages().empty() ? std::string("no image was produced") : messages.Messages()[0]));
  }

  const float* pixels = rgba->GetPointer(0);
  CheckFiniteImage(pixels, size_t(width) * size_t(height), input);
  CheckFieldShows(pixels, size_t(width) * size_t(height), field, scene, input);
  RenderedImage image;
  image.Width = width;
  image.Height = height;
  image.ExposureEV = ResolveExposureEV(scene.Render, pixels, size_t(width) * size_t(height));
  image.Display = scene.Render.Display;
  image.Radiance.assign(pixels, pixels + 4 * size_t(width) * size_t(height));
  image.RGB.resize(size_t(width) * size_t(height) * 3);
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
  {
    const float* p = pixels + 4 * i;
    const glm::vec3 shown =
      DisplayValueOf(glm::vec3(p[0], p[1], p[2]), p[3], image.ExposureEV, image.Display);
    for (int c = 0; c < 3; ++c)
    {
      const double value = shown[c] + (1.0 - p[3]) * scene.Background[c];
      image.RGB[3 * i + c] =
        static_cast<unsigned char>(std::lround(255.0 * std::min(1.0, std::max(0.0, value))));
    }
  }
  return image;
}

} // namespace cloudvis
