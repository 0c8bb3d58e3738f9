// Read-backs for export. The depth conversion runs on the CPU over the read-back image: the
// mapper reports the distance from the near clipping plane (its rays start there), and adding the
// distance from the camera to the near plane along the same ray makes the value independent of
// the clipping range the renderer happened to choose.
#include "ExportRender.h"

#include "CloudFieldGeometry.h" // AvailableMemoryBytes, FormatBytes

#include "Errors.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkWindowToImageFilter.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cloudvis
{

RenderLimits QueryRenderLimits(vtkRenderWindow* window)
{
  auto* openGL = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!openGL)
  {
    return RenderLimits{ std::numeric_limits<int>::max(), std::numeric_limits<int>::max() };
  }
  openGL->Initialize();
  openGL->MakeCurrent();
  GLint texture = 0, renderbuffer = 0;
  GLint viewport[2] = { 0, 0 };
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  RenderLimits limits;
  limits.MaximumWidth = std::min({ int(texture), int(renderbuffer), int(viewport[0]) });
  limits.MaximumHeight = std::min({ int(texture), int(renderbuffer), int(viewport[1]) });
  // llvmpipe renders in host memory; on a GPU the read-back of an export still lands there.
  limits.AvailableBytes = double(AvailableMemoryBytes());
  return limits;
}

void CheckRenderSize(
  const std::array<int, 2>& size, const RenderLimits& limits, const std::string& source)
{
  if (size[0] > limits.MaximumWidth || size[1] > limits.MaximumHeight)
  {
    throw InputError(source + ": render.size: " + std::to_string(size[0]) + " x " +
      std::to_string(size[1]) + " pixels is beyond this GPU's limit of " +
      std::to_string(limits.MaximumWidth) + " x " + std::to_string(limits.MaximumHeight) +
      " pixels; choose a smaller size");
  }
  const double needed = double(size[0]) * double(size[1]) * RenderBytesPerPixel;
  if (limits.AvailableBytes > 0.0 && needed > limits.AvailableBytes)
  {
    throw InputError(source + ": render.size: " + std::to_string(size[0]) + " x " +
      std::to_string(size[1]) + " pixels needs " + FormatBytes(needed) +
      " of memory for its render targets but only " + FormatBytes(limits.AvailableBytes) +
      " is available; choose a smaller size");
  }
}

void ReadFloatImage(vtkCloudVolumeMapper* mapper, vtkRenderer* renderer, RenderedImage& image,
  const std::string& input)
{
  int width = 0, height = 0, auxWidth = 0, auxHeight = 0;
  if (!mapper->ReadImage(renderer, image.Radiance, width, height) ||
    !mapper->ReadAuxiliary(renderer, image.Auxiliary, auxWidth, auxHeight))
  {
    throw InputError(input + ": the renderer kept no float image to export");
  }
  if (width != image.Width || height != image.Height || auxWidth != width || auxHeight != height)
  {
    throw InputError(input + ": the float image is " + std::to_string(width) + " x " +
      std::to_string(height) + " pixels, not the window's " + std::to_string(image.Width) +
      " x " + std::to_string(image.Height) + "; render.resolution_scale must be 1 to export it");
  }
  CheckFiniteImage(image.Radiance.data(), size_t(width) * size_t(height), input);
  int varianceWidth = 0, varianceHeight = 0;
  if (!mapper->ReadVariance(renderer, image.Variance, varianceWidth, varianceHeight))
  {
    image.Variance.clear(); // not path traced
  }
  else if (varianceWidth != width || varianceHeight != height)
  {
    throw InputError(input + ": the variance image does not match the float image");
  }

  // Pixel centre (i, j) -> normalized device coordinates -> the world point on the near plane.
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkNew<vtkMatrix4x4> deviceToWorld;
  deviceToWorld->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(renderer->GetTiledAspectRatio(), -1.0, 1.0));
  deviceToWorld->Invert();
  double eye[3], direction[3];
  camera->GetPosition(eye);
  camera->GetDirectionOfProjection(direction);
  const bool parallel = camera->GetParallelProjection() != 0;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      float& depth = image.Auxiliary[4 * (size_t(j) * size_t(width) + size_t(i)) + 2];
      if (std::isinf(depth))
      {
        continue; // no cloud along this ray (in some accumulated frame)
      }
      const double device[4] = { 2.0 * (i + 0.5) / width - 1.0, 2.0 * (j + 0.5) / height - 1.0,
        -1.0, 1.0 };
      double world[4];
      deviceToWorld->MultiplyPoint(device, world);
      const double offset[3] = { world[0] / world[3] - eye[0], world[1] / world[3] - eye[1],
        world[2] / world[3] - eye[2] };
      const double toNear = parallel
        ? offset[0] * direction[0] + offset[1] * direction[1] + offset[2] * direction[2]
        : std::sqrt(offset[0] * offset[0] + offset[1] * offset[1] + offset[2] * offset[2]);
      depth = float(double(depth) + toNear);
    }
  }
}

void CheckFiniteImage(const float* rgba, size_t pixels, const std::string& input)
{
  size_t bad = 0;
  for (size_t i = 0; i < 4 * pixels; ++i)
  {
    bad += std::isfinite(rgba[i]) ? 0 : 1;
  }
  if (bad > 0)
  {
    throw InputError(input + ": the rendered image has " + std::to_string(bad) +
      " values that are NaN or infinite, so nothing was written; likely causes: a light, an "
      "extinction (unit distance) or a density beyond what float arithmetic holds "
      "(docs/reliability.md)");
  }
}

std::vector<float> ReadCheckedMapperImage(
  vtkCloudVolumeMapper* mapper, vtkRenderer* renderer, const std::string& input)
{
  std::vector<float> rgba;
  int width = 0, height = 0;
  if (!mapper->ReadImage(renderer, rgba, width, height))
  {
    throw InputError(input + ": the renderer kept no float image to check");
  }
  CheckFiniteImage(rgba.data(), size_t(width) * size_t(height), input);
  return rgba;
}

void CheckMapperImageFinite(vtkCloudVolumeMapper* mapper,
  vtkRenderer* renderer,
  const std::string& input)
{
  ReadCheckedMapperImage(mapper, renderer, input);
}

void ReadBackgroundImage(vtkRenderWindow* window, vtkVolume* volume, RenderedImage& image)
{
  volume->VisibilityOff();
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  volume->VisibilityOn();
  auto* data = vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
  if (data && data->GetNumberOfValues() == vtkIdType(image.RGB.size()))
  {
    image.BackgroundRGB.assign(data->GetPointer(0), data->GetPointer(0) + data->GetNumberOfValues());
  }
}

ResolvedCamera ResolveCamera(const Scene& scene, const double fieldBounds[6])
{
  vtkNew<vtkRenderer> renderer;
  ApplyCamera(scene.Camera, fieldBounds, renderer, scene.Source);
  ResolvedCamera resolved;
  renderer->GetActiveCamera()->GetPosition(resolved.Position.data());
  renderer->GetActiveCamera()->GetFocalPoint(resolved.FocalPoint.data());
  resolved.ViewUp = scene.Camera.ViewUp;
  return resolved;
}

std::string ResolvedSceneJson(const Scene& scene, vtkImageData* field)
{
  return SceneToJson(scene, ResolveCamera(scene, field->GetBounds())).dump(-1, ' ', true);
}

} // namespace cloudvis
