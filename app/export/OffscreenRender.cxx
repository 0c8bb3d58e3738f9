// The window is created per call and thrown away: a still is rendered once, and a fresh window
// keeps one render from inheriting another's GL state or accumulated frames. Every VTK message
// raised meanwhile is captured, so a failure reaches the user as one "cloudvis: error:" line built
// from the mapper's GetLastError().
#include "OffscreenRender.h"

#include "AtomicFile.h"
#include "Background.h"
#include "CpuReference.h"
#include "Display.h"
#include "Errors.h"
#include "ExportRender.h"
#include "FieldCoarsening.h"
#include "ImageWriters.h"
#include "OutOfMemory.h"
#include "SceneLighting.h"
#include "VtkMessageCapture.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace cloudvis
{
namespace
{

// After every Render(): the mapper's own report, in the user's terms.
} // namespace

void CheckMapper(
  vtkCloudVolumeMapper* mapper, const std::string& input, const VtkMessageCapture& messages)
{
  if (!mapper->GetLastError().empty())
  {
    // VTK's own words (a shader's compile log, say) were captured, not printed: pass them on.
    throw InputError(messages.WithVtkReason(input + ": " + mapper->GetLastError()));
  }
}

vtkSmartPointer<vtkVolumeProperty> MakeVolumeProperty(const TransferFunctionSpec& spec)
{
  const TransferFunctionSpec transferFunction = TabulatedTransferFunction(spec);
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const auto& point : transferFunction.Opacity)
  {
    opacity->AddPoint(point[0], point[1]);
  }
  vtkNew<vtkColorTransferFunction> color;
  for (const auto& point : transferFunction.Color)
  {
    color->AddRGBPoint(point[0], point[1], point[2], point[3]);
  }
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetScalarOpacityUnitDistance(transferFunction.UnitDistance);
  property->SetInterpolationTypeToLinear();
  property->ShadeOff();
  return property;
}

namespace
{

PathTraceFrames PathTraceFramesOf(int samplesPerPixel)
{
  // The most paths per frame that divides the count, up to 8: few frames (little per-frame
  // overhead) of bounded length, exactly samplesPerPixel paths in all.
  PathTraceFrames frames;
  for (int perFrame = 8; perFrame >= 1; --perFrame)
  {
    if (samplesPerPixel % perFrame == 0)
    {
      frames.SamplesPerFrame = perFrame;
      break;
    }
  }
  frames.Frames = samplesPerPixel / frames.SamplesPerFrame;
  return frames;
}
} // namespace

double ClippedCloudShare(const RenderedImage& image, const std::vector<float>& rgba)
{
  const size_t pixels = std::min(rgba.size() / 4, image.RGB.size() / 3);
  size_t cloud = 0, clipped = 0;
  for (size_t p = 0; p < pixels; ++p)
  {
    if (rgba[4 * p + 3] >= AutoExposureMinimumAlpha)
    {
      ++cloud;
      const unsigned char* c = image.RGB.data() + 3 * p;
      clipped += c[0] == 255 || c[1] == 255 || c[2] == 255;
    }
  }
  return cloud > 0 ? double(clipped) / double(cloud) : 0.0;
}

double ResolveExposureEV(const RenderSpec& render, const float* rgba, size_t pixels)
{
  return render.AutoExposure ? ComputeAutoExposure(rgba, pixels).EV : render.ExposureEV;
}

void ConfigureDisplay(vtkCloudVolumeMapper* mapper, const RenderSpec& render, double exposureEV)
{
  mapper->SetDisplayCurve(int(render.Display));
  mapper->SetExposureEV(exposureEV);
}

void ConfigureMapper(vtkCloudVolumeMapper* mapper, const RenderSpec& render)
{
  ConfigureDisplay(mapper, render, render.ExposureEV);
  mapper->SetJitter(render.Jitter);
  mapper->SetResolutionScale(render.ResolutionScale);
  mapper->SetMaximumAccumulatedFrames(render.Accumulate);
  mapper->SetEmptySpaceSkipping(render.SkipEmptySpace);
  mapper->SetMaximumGPUMemory(
    render.GpuMemoryMiB ? vtkTypeInt64(*render.GpuMemoryMiB * 1048576.0) : vtkTypeInt64(0));
  if (render.Lighting.Model == LightingModel::PathTrace)
  {
    const PathTraceFrames frames = PathTraceFramesOf(render.SamplesPerPixel);
    mapper->SetPathTraceSamplesPerFrame(frames.SamplesPerFrame);
    mapper->SetMaximumAccumulatedFrames(frames.Frames);
    // The majorant bricks of the CPU tracer's default: larger than the march's, they cut the
    // bricks a path walks through, 1.2-1.5x faster on llvmpipe (docs/performance.md).
    mapper->SetBrickSize(vtkNew<vtkCloudPathTracer>()->GetBrickSize());
  }
}

void ApplyCamera(
  const CameraSpec& camera, const double bounds[6], vtkRenderer* renderer, const std::string& source)
{
  vtkCamera* active = renderer->GetActiveCamera();
  // ResetCamera keeps the view direction, puts the focal point at the centre of the bounds and
  // the camera where their bounding sphere fits a 30-degree view (it resets the view angle to
  // 30); the distance r / sin(angle / 2) is then rescaled to the scene's angle.
  active->SetFocalPoint(0.0, 0.0, 0.0);
  active->SetPosition(0.0, 0.0, 1.0);
  active->SetViewUp(0.0, 1.0, 0.0);
  renderer->ResetCamera(const_cast<double*>(bounds));
  const double halfAngle = 0.5 * vtkMath::RadiansFromDegrees(camera.ViewAngle);
  const double distance =
    active->GetDistance() * std::sin(vtkMath::RadiansFromDegrees(15.0)) / std::sin(halfAngle);
  active->SetViewAngle(camera.ViewAngle);
  double focal[3], position[3];
  active->GetFocalPoint(focal);
  if (camera.FocalPoint)
  {
    std::copy(camera.FocalPoint->begin(), camera.FocalPoint->end(), focal);
  }
  for (int a = 0; a < 3; ++a)
  {
    position[a] = focal[a] + distance * camera.DefaultDirection[size_t(a)];
  }
  if (camera.Position)
  {
    std::copy(camera.Position->begin(), camera.Position->end(), position);
  }
  if (camera.Orbit)
  {
    // On the sphere of the fitting distance (or the orbit's own) around the focal point, y up.
    const std::array<double, 3> orbit =
      OrbitPosition(*camera.Orbit, { { focal[0], focal[1], focal[2] } }, distance);
    std::copy(orbit.begin(), orbit.end(), position);
  }
  const double d[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] };
  const double* u = camera.ViewUp.data();
  const double dLength = std::hypot(d[0], d[1], d[2]);
  // VTK's camera squares its distance in double (vtkCamera::ComputeDistance, its view
  // transform), which overflows beyond about 1e154: the view it would make has no direction.
  constexpr double MaxCameraDistance = 1e150;
  if (!(dLength <= MaxCameraDistance))
  {
    std::ostringstream words;
    words << source << ": camera.position: " << dLength
          << " world units from the focal point (the field's centre when camera.focal_point is "
          << "absent); a camera may be at most " << MaxCameraDistance
          << " from it, as VTK's camera squares that distance in double";
    throw InputError(words.str());
  }
  if (dLength == 0.0)
  {
    throw InputError(source + ": camera.position: the camera position equals the focal point (" +
      "the field's centre when camera.focal_point is absent); the view has no direction");
  }
  const double cross[3] = { d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2],
    d[0] * u[1] - d[1] * u[0] };
  const double uLength = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  if (std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]) <=
    1e-9 * dLength * uLength)
  {
    throw InputError(source + ": camera.view_up: parallel to the view direction (from the " +
      "position to the focal point); choose a view-up across it");
  }
  active->SetFocalPoint(focal);
  active->SetPosition(position);
  active->SetViewUp(u[0], u[1], u[2]);
  active->OrthogonalizeViewUp();
  renderer->ResetCameraClippingRange(const_cast<double*>(bounds));
}

RenderedImage CaptureWindow(vtkRenderWindow* window, const std::string& input,
  const VtkMessageCapture& messages)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff(); // the accumulated frame is in the buffer already
  grab->Update();
  vtkImageData* pixels = grab->GetOutput();
  auto* data = vtkUnsignedCharArray::SafeDownCast(pixels->GetPointData()->GetScalars());
  int dimensions[3];
  pixels->GetDimensions(dimensions);
  const int* size = window->GetSize();
  if (!data || data->GetNumberOfComponents() != 3 || dimensions[0] != size[0] ||
    dimensions[1] != size[1])
  {
    throw InputError(
      messages.WithVtkReason(input + ": could not read the rendered image back from the window"));
  }
  RenderedImage image;
  image.Width = dimensions[0];
  image.Height = dimensions[1];
  image.RGB.assign(data->GetPointer(0), data->GetPointer(0) + data->GetNumberOfValues());
  return image;
}

OffscreenRenderResult RenderOffscreen(const Scene& scene, vtkImageData* field,
  const std::string& input, int benchmarkFrames, const RenderOptions& options)
{
  CheckSceneRenderable(scene, field, input);
  const MemoryUse memory("rendering " + input + " at " + std::to_string(scene.Render.Size[0]) +
      " x " + std::to_string(scene.Render.Size[1]) + " pixels",
    double(scene.Render.Size[0]) * double(scene.Render.Size[1]) * RenderBytesPerPixel +
      4.0 * double(field->GetNumberOfPoints()));
  // One connection, opened (and retried) here and handed to the window: VTK opening its own
  // aborts the process when the server refuses it.
  const DisplayConnection display("cloudvis ...");
  VtkMessageCapture messages;

  vtkNew<vtkRenderWindow> window;
  window->SetDisplayId(display.Get());
  // VTK calls abort() when it cannot create the GL context unless someone observes ExitEvent;
  // observing it turns that into "nothing was rendered", reported below with VTK's reason.
  vtkNew<vtkCallbackCommand> onExit;
  window->AddObserver(vtkCommand::ExitEvent, onExit);
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(scene.Render.Size[0], scene.Render.Size[1]);
  vtkNew<vtkRenderer> renderer;
  ApplyBackground(scene, renderer);
  window->AddRenderer(renderer);

  vtkNew<vtkCloudVolumeMapper> mapper;
  mapper->SetInputData(field);
  ConfigureMapper(mapper, scene.Render);
  ConfigureLighting(scene, mapper);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(MakeVolumeProperty(scene.TransferFunction));
  renderer->AddVolume(volume);
  ApplyCamera(scene.Camera, field->GetBounds(), renderer, scene.Source);

  // Before anything is drawn: the GPU's limit, stated in the message (ExportRender.h).
  CheckRenderSize(scene.Render.Size, QueryRenderLimits(window), scene.Source);

  OffscreenRenderResult result;
  int coarsening = 1; // the field drawn averaged over this many voxels along each axis
  std::string coarsened;
  const auto renderChecked = [&]()
  {
    coarsening = RenderCoarsenedToFit(
      { mapper.Get() }, field, coarsening, [&] { window->Render(); }, coarsened);
    if (coarsening > 1 && mapper->GetLastErrorIsGpuMemory())
    {
      throw InputError(input + ": " + mapper->GetLastError() + " (even with the field coarsened " +
        std::to_string(coarsening) + "x)");
    }
    CheckMapper(mapper, input, messages);
  };
  if (options.TargetNoise)
  {
    if (scene.Render.Lighting.Model != LightingModel::PathTrace)
    {
      throw InputError(input + ": a noise target needs the path tracer (render.lighting " +
        LightingModelName(LightingModel::PathTrace) + "), not " +
        LightingModelName(scene.Render.Lighting.Model));
    }
    ConfigureNoiseTarget(mapper);
    result.Noise = AccumulateToNoiseTarget(
      *options.TargetNoise, window, mapper, renderer, renderChecked, input, options.OnFrame);
  }
  else
  {
    // Without jitter every frame marches the same samples: one is the converged still. The path
    // tracer's frames are all different.
    const int frames = scene.Render.Lighting.Model == LightingModel::PathTrace
      ? mapper->GetMaximumAccumulatedFrames()
      : (scene.Render.Jitter ? scene.Render.Accumulate : 1);
    // So that a render after the last frame (the automatic exposure's) composites the still
    // again rather than marching one more frame.
    mapper->SetMaximumAccumulatedFrames(frames);
    for (int frame = 0; frame < frames; ++frame)
    {
      renderChecked();
      if (options.OnFrame)
      {
        options.OnFrame(frame + 1, frames);
      }
    }
  }
  result.AccumulatedFrames = mapper->GetNumberOfAccumulatedFrames(renderer);
  result.AccumulatedSamples = mapper->GetNumberOfAccumulatedSamples(renderer);
  if (result.AccumulatedFrames == 0)
  {
    throw InputError(NothingRenderedProblem(renderer, volume, messages, input));
  }

  // Checked for NaN and infinity before anything is made of it.
  const std::vector<float> rgba = ReadCheckedMapperImage(mapper, renderer, input);
  CheckFieldShows(rgba.data(), rgba.size() / 4, field, scene, input);
  const double exposureEV = ResolveExposureEV(scene.Render, rgba.data(), rgba.size() / 4);
  if (exposureEV != mapper->GetExposureEV())
  {
    ConfigureDisplay(mapper, scene.Render, exposureEV);
    window->Render(); // the converged still, composited again under the chosen exposure
    CheckMapper(mapper, input, messages);
  }
  result.Image = CaptureWindow(window, input, messages);
  result.Image.ExposureEV = exposureEV;
  result.Image.Display = scene.Render.Display;
  result.Image.Coarsened = coarsened;
  if (rgba.size() / 4 == result.Image.RGB.size() / 3)
  {
    result.ClippedCloudShare = ClippedCloudShare(result.Image, rgba);
  }
  if (options.FloatImage)
  {
    ReadFloatImage(mapper, renderer, result.Image, input);
    ReadBackgroundImage(window, volume, result.Image);
  }

  for (int frame = 0; frame < benchmarkFrames; ++frame)
  {
    mapper->Modified(); // else the mapper shows the converged still without marching
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    window->WaitForCompletion();
    const auto end = std::chrono::steady_clock::now();
    CheckMapper(mapper, input, messages);
    result.FrameMilliseconds.push_back(
      std::chrono::duration<double, std::milli>(end - start).count());
  }
  return result;
}

} // namespace cloudvis
