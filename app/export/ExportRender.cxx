// Read-backs for export. The depth conversion runs on the CPU over the read-back image: the
// mapper reports the distance from the near clipping plane (its rays start there), and adding the
// distance from the camera to the near plane along the same ray makes the value independent of
// the clipping range the renderer happened to choose.
#include "ExportRender.h"

#include "CloudFieldGeometry.h" // AvailableMemoryBytes, FormatBytes

#include "Errors.h"
#include "VtkMessageCapture.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
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
#include <cstdio>
#include <limits>
#include <sstream>

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

namespace
{

// Whether the field holds no value above 0: its picture is the background alone, which is
// right, and the commands say so in words (as for a function that HidesEveryValue, Scene.h).
bool FieldIsEmpty(vtkImageData* field)
{
  vtkDataArray* values = field->GetPointData()->GetScalars();
  return !values || values->GetNumberOfTuples() == 0 || !(values->GetRange(0)[1] > 0.0);
}
}

std::string FitTransferFunctionNote(Scene& scene, vtkImageData* field, bool fieldFileAlone)
{
  if (FieldIsEmpty(field))
  {
    return "the field is empty (no value above 0): the picture shows the background alone\n";
  }
  if (HidesEveryValue(scene.TransferFunction))
  {
    return "transfer function: its opacity is 0 everywhere, so the picture shows the background "
           "alone\n";
  }
  double range[2];
  field->GetPointData()->GetScalars()->GetRange(range, 0);
  const std::array<double, 2> span = TransferFunctionSpan(scene.TransferFunction);
  char text[320];
  switch (FitTransferFunctionToField(
    scene, { { range[0], range[1] } }, fieldFileAlone, field->GetBounds()))
  {
    case TransferFunctionFit::Kept:
      return "";
    case TransferFunctionFit::FittedToValues:
      std::snprintf(text,
        sizeof(text),
        "transfer function: the default fitted to the field's values [%.4g, %.4g] (%s)\n",
        range[0],
        range[1],
        fieldFileAlone ? "a field file has none of its own"
                       : "the default's opacity is 0 over all of them");
      return text;
    case TransferFunctionFit::GrownToValues:
      std::snprintf(text,
        sizeof(text),
        "transfer function: the default grown to take in the field's values [%.4g, %.4g]\n",
        range[0],
        range[1]);
      return text;
    case TransferFunctionFit::ValuesBeyondItsPoints:
      std::snprintf(text,
        sizeof(text),
        "transfer function: the scene's, kept; the field's values [%.4g, %.4g] lie beyond its "
        "points [%.4g, %.4g]\n",
        range[0],
        range[1],
        span[0],
        span[1]);
      return text;
  }
  return "";
}

namespace
{
// The opacity the transfer function's points give `density` (piecewise linear, held beyond the
// ends, as vtkPiecewiseFunction does).
double OpacityAt(const TransferFunctionSpec& function, double density)
{
  const auto& points = function.Opacity;
  if (density <= points.front()[0])
  {
    return points.front()[1];
  }
  for (size_t i = 1; i < points.size(); ++i)
  {
    if (density <= points[i][0])
    {
      const double span = points[i][0] - points[i - 1][0];
      const double t = span > 0.0 ? (density - points[i - 1][0]) / span : 1.0;
      return points[i - 1][1] + t * (points[i][1] - points[i - 1][1]);
    }
  }
  return points.back()[1];
}

std::string Number(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", value);
  return text;
}
} // namespace

void CheckFieldShows(const float* rgba,
  size_t pixels,
  vtkImageData* field,
  const Scene& scene,
  const std::string& input)
{
  for (size_t p = 0; p < pixels; ++p)
  {
    if (rgba[4 * p + 3] >= VisibleAlpha)
    {
      return;
    }
  }
  if (FieldIsEmpty(field) || HidesEveryValue(scene.TransferFunction))
  {
    return;
  }
  double range[2];
  field->GetPointData()->GetScalars()->GetRange(range, 0);
  const std::string values = "its values [" + Number(range[0]) + ", " + Number(range[1]) + "]";
  const TransferFunctionSpec& function = scene.TransferFunction;
  if (function.Extinction == TransferFunctionSpec::ExtinctionRule::Opacity)
  {
    double most = 0.0;
    for (const auto& point : function.Opacity)
    {
      if (point[0] >= range[0] && point[0] <= range[1])
      {
        most = std::max(most, point[1]);
      }
    }
    most = std::max({ most, OpacityAt(function, range[0]), OpacityAt(function, range[1]) });
    if (!(most > 0.0))
    {
      throw InputError(input + ": no pixel shows the field: the scene's transfer function gives " +
        values + " no opacity (its opacity is 0 up to density " +
        Number(OpacityRisesAbove(function)) +
        "), so the picture would be blank: move transfer_function.opacity's points into [" +
        Number(range[0]) + ", " + Number(range[1]) +
        "], or leave transfer_function out of the scene to have the default fitted to them");
    }
  }
  throw InputError(input + ": no pixel shows the field (" + values +
    "), so the picture would be blank: the camera may not look at it (camera.position, " +
    "camera.focal_point), or it is too thin to show at this transfer function (raise " +
    "transfer_function.opacity or lower transfer_function.unit_distance)");
}

std::string NothingRenderedProblem(vtkRenderer* renderer,
  vtkVolume* volume,
  const VtkMessageCapture& messages,
  const std::string& input)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  double planes[24];
  camera->GetFrustumPlanes(renderer->GetTiledAspectRatio(), planes);
  const double* b = volume->GetBounds();
  bool outside = false;
  for (int p = 0; p < 6 && !outside; ++p)
  {
    // Inside is where a x + b y + c z + d >= 0 for every plane: outside one, the box is unseen.
    outside = true;
    for (int corner = 0; corner < 8; ++corner)
    {
      const double x = b[corner & 1], y = b[2 + ((corner >> 1) & 1)];
      const double z = b[4 + ((corner >> 2) & 1)];
      outside = outside &&
        planes[4 * p] * x + planes[4 * p + 1] * y + planes[4 * p + 2] * z + planes[4 * p + 3] < 0.0;
    }
  }
  if (outside && messages.Messages().empty())
  {
    const double* position = camera->GetPosition();
    const double* focal = camera->GetFocalPoint();
    char text[256];
    std::snprintf(text,
      sizeof(text),
      "no pixel shows the field: it lies wholly outside the camera's view (camera.position "
      "%.6g, %.6g, %.6g looking at camera.focal_point %.6g, %.6g, %.6g)",
      position[0],
      position[1],
      position[2],
      focal[0],
      focal[1],
      focal[2]);
    return input + ": " + text;
  }
  return messages.WithVtkReason(input + ": nothing was rendered");
}

std::string CutPathsProblem(const std::string& input, vtkIdType cut, vtkIdType pixels)
{
  std::ostringstream words;
  words << input << ": the GPU ended the path tracer's walks early on " << cut << " of " << pixels
        << " pixels, so the image lacks their light (a software rasterizer such as llvmpipe "
           "stops a shader's loops after 65535 turns in all, fewer than the walks of an "
           "optically thick cloud take); trace it on the CPU (render --cpu-reference) or on a "
           "hardware GPU";
  return words.str();
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
  const vtkIdType cut = mapper->CountCutPathTracePixels(renderer);
  if (cut > 0)
  {
    throw InputError(CutPathsProblem(input, cut, vtkIdType(width) * height));
  }
  return rgba;
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
