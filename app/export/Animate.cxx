// A fresh window per frame (RenderOffscreen): window creation costs tens of milliseconds against
// seconds of marching per accumulated still, and keeps each frame identical to `cloudvis render`
// of the scene it embeds. The turntable works on the resolved camera (ResolveCamera), so every
// frame's metadata states its camera explicitly; frame 0 keeps the scene's own camera.
#include "Animate.h"

#include "AtomicFile.h"
#include "Errors.h"
#include "ExportRender.h"
#include "FieldSeries.h"
#include "OffscreenRender.h"
#include "SceneField.h"

#include <vtkImageData.h>
#include <vtkNew.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <optional>
#include <sys/stat.h>
#include <unistd.h>

namespace cloudvis
{
namespace
{

// Rotates p about the axis through `center` along the unit vector k by `angle` radians
// (Rodrigues' formula).
std::array<double, 3> Rotate(const std::array<double, 3>& p, const std::array<double, 3>& center,
  const std::array<double, 3>& k, double angle)
{
  const double v[3] = { p[0] - center[0], p[1] - center[1], p[2] - center[2] };
  const double c = std::cos(angle), s = std::sin(angle);
  const double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
  const double kxv[3] = { k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2],
    k[0] * v[1] - k[1] * v[0] };
  std::array<double, 3> r;
  for (int a = 0; a < 3; ++a)
  {
    r[a] = center[a] + v[a] * c + kxv[a] * s + k[a] * kv * (1.0 - c);
  }
  return r;
}

// The scene of frame `index`, and the camera it is rendered with.
Scene FrameScene(const Scene& scene, const AnimationRequest& request, int index,
  const ResolvedCamera& start)
{
  Scene frame = scene;
  if (!request.TimeSteps.empty())
  {
    frame.Field.Read.TimeStep = request.TimeSteps[std::size_t(index)];
    return frame;
  }
  if (!request.Turntable)
  {
    frame.Field.Time = FrameTime(request, index);
    return frame;
  }
  if (index == 0)
  {
    return frame;
  }
  const std::array<double, 3>& u = scene.Camera.ViewUp;
  const double length = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const std::array<double, 3> axis{ { u[0] / length, u[1] / length, u[2] / length } };
  const double angle = 2.0 * M_PI * double(index) / double(request.Frames);
  CameraSpec camera;
  camera.Position = Rotate(start.Position, start.FocalPoint, axis, angle);
  camera.FocalPoint = start.FocalPoint;
  camera.ViewUp = scene.Camera.ViewUp;
  camera.ViewAngle = scene.Camera.ViewAngle;
  frame.Camera = camera;
  return frame;
}

} // namespace

std::string FrameFileName(const AnimationRequest& request, int index)
{
  const int digits = std::max(4, int(std::to_string(std::max(request.Frames - 1, 0)).size()));
  std::string number = std::to_string(index);
  number.insert(0, size_t(std::max(0, digits - int(number.size()))), '0');
  return request.Directory + "/frame_" + number + request.Extension;
}

double FrameTime(const AnimationRequest& request, int index)
{
  if (request.Frames <= 1 || index <= 0)
  {
    return request.TimeBegin;
  }
  if (index >= request.Frames - 1)
  {
    return request.TimeEnd;
  }
  return request.TimeBegin +
    double(index) * (request.TimeEnd - request.TimeBegin) / double(request.Frames - 1);
}

void CheckAnimationDirectory(const std::string& directory)
{
  struct stat info;
  if (::stat(directory.c_str(), &info) != 0)
  {
    // Missing: its parent must take a new directory (the same check as for a new file).
    CheckOutputTarget(directory);
    return;
  }
  if (!S_ISDIR(info.st_mode))
  {
    throw InputError(directory + ": cannot write frames: it exists and is not a directory");
  }
  if (::access(directory.c_str(), W_OK | X_OK) != 0)
  {
    throw InputError(directory + ": cannot write frames: the directory is not writable (" +
      std::strerror(errno) + ")");
  }
}

int RenderAnimation(const Scene& scene, const std::string& input, const AnimationRequest& request,
  const std::function<void(const std::string& label, double fraction)>& progress,
  std::string* transferFunctionNote)
{
  const int n = request.Frames;
  auto report = [&](int index, const char* stage, double within)
  {
    if (progress)
    {
      progress("frame " + std::to_string(index + 1) + "/" + std::to_string(n) + " " + stage,
        (double(index) + within) / double(n));
    }
  };
  vtkSmartPointer<vtkImageData> field;
  // A turntable's scene, finished with the field it shows (the droplets' optics) once produced.
  Scene turning = scene;
  ResolvedCamera start;
  // An automatic exposure is metered on the first frame and kept, and so is the transfer
  // function fitted to the first frame's field: a sequence must not flicker.
  std::optional<double> exposureEV;
  std::optional<TransferFunctionSpec> fitted;
  vtkNew<vtkImageData> grid; // frame 0's lattice, which every time step must have
  int written = 0;
  for (int index = 0; index < n; ++index)
  {
    try
    {
      // Generation counts for the first half of a frame that needs it, accumulation the rest.
      const bool generate = !field || !request.Turntable;
      const double generationShare = generate && !scene.Field.FromFile() ? 0.5 : 0.0;
      Scene frame = request.Turntable ? turning : FrameScene(scene, request, index, start);
      if (generate)
      {
        FieldReport read;
        field = ProduceField(
          frame, [&](double f) { report(index, "generating", generationShare * f); }, &read);
        if (index == 0)
        {
          CheckTimeSteps(scene, request.TimeSteps, read, "--time-steps");
          grid->CopyStructure(field);
        }
        else if (!request.TimeSteps.empty())
        {
          CheckSameGrid(TimeStepName(scene.Field.File, frame.Field.Read.TimeStep.value_or(0), read),
            grid,
            field);
        }
      }
      if (!fitted)
      {
        const std::string note = FitTransferFunctionNote(frame, field, request.FieldFileAlone);
        fitted = frame.TransferFunction;
        if (transferFunctionNote)
        {
          *transferFunctionNote = note;
        }
      }
      frame.TransferFunction = *fitted;
      if (request.Turntable)
      {
        if (index == 0)
        {
          turning = frame; // finished with its field (ProduceField), for every frame
          start = ResolveCamera(turning, field->GetBounds());
        }
        frame = FrameScene(turning, request, index, start);
      }
      if (exposureEV)
      {
        frame.Render.AutoExposure = false;
        frame.Render.ExposureEV = *exposureEV;
      }
      RenderOptions options;
      options.FloatImage = NeedsFloatImage(FrameFileName(request, index), request.Export);
      options.OnFrame = [&](int f, int frames)
      { report(index, "rendering", generationShare + (1.0 - generationShare) * f / frames); };
      const OffscreenRenderResult result = RenderOffscreen(frame, field, input, 0, options);
      exposureEV = result.Image.ExposureEV;
      ImageExportOptions exportOptions = request.Export;
      exportOptions.SceneJson = ResolvedSceneJson(frame, field);
      if (index == 0 && ::mkdir(request.Directory.c_str(), 0777) != 0 && errno != EEXIST)
      {
        throw InputError(request.Directory + ": cannot create the directory (" +
          std::strerror(errno) + ")");
      }
      WriteImage(result.Image, FrameFileName(request, index), exportOptions);
      ++written;
    }
    catch (const InputError& e)
    {
      if (written == 0)
      {
        throw;
      }
      throw InputError(std::string(e.what()) + " (frame " + std::to_string(index) + "; frames 0 .. " +
        std::to_string(written - 1) + " were written)");
    }
  }
  return written;
}

} // namespace cloudvis
