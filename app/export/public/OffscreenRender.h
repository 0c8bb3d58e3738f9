// From a validated scene and its field to pixels: the one place that maps a Scene's
// transfer_function, camera, background and render sections onto VTK's window, renderer, camera,
// vtkVolumeProperty and vtkCloudVolumeMapper. `render` uses all of it; `compare` will call
// RenderOffscreen once per lighting model on the same field; the interactive viewer will build
// its own window and use the configuration pieces (MakeVolumeProperty, ConfigureMapper,
// ApplyCamera) so that what it shows is what `render` writes.
#ifndef cloudvis_OffscreenRender_h
#define cloudvis_OffscreenRender_h

#include "NoiseTarget.h"
#include "RenderedImage.h"
#include "Scene.h"

#include <vtkSmartPointer.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

class vtkCloudVolumeMapper;
class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;
class vtkVolumeProperty;

namespace cloudvis
{
class VtkMessageCapture;

struct OffscreenRenderResult
{
  RenderedImage Image;
  int AccumulatedFrames = 0;             // frames the mapper averaged into Image
  int AccumulatedSamples = 0;            // samples per pixel in them (pathtrace: paths)
  std::vector<double> FrameMilliseconds; // wall clock of each benchmark frame, in order
  // Of the cloud's pixels (at least AutoExposureMinimumAlpha opaque), the share that Image
  // shows white in some channel: what the display transform failed to keep (0 without cloud).
  double ClippedCloudShare = 0.0;
  std::optional<NoiseReport> Noise;      // with RenderOptions::TargetNoise: how it went
};

// The share of the cloud's pixels (premultiplied RGBA `rgba`, at least AutoExposureMinimumAlpha
// opaque) that `image` shows at 255 in some channel; 0 when there is no such pixel.
double ClippedCloudShare(const RenderedImage& image, const std::vector<float>& rgba);

// The volume property of a transfer function: piecewise-linear opacity per unit distance and
// color, linear interpolation of the density, no VTK shading (lighting is the mapper's).
vtkSmartPointer<vtkVolumeProperty> MakeVolumeProperty(const TransferFunctionSpec& transferFunction);

// How the GPU mapper splits a pathtrace still of samplesPerPixel paths into accumulated frames.
struct PathTraceFrames
{
  int SamplesPerFrame = 1;
  int Frames = 1;
};
// The exposure (EV) a render's display values use: render.exposure, or with "auto" the one
// ComputeAutoExposure (filters/CloudDisplayTransform.h) chooses from the cloud's float image,
// `pixels` premultiplied RGBA values.
double ResolveExposureEV(const RenderSpec& render, const float* rgba, size_t pixels);

// Sets the mapper's display transform: render.display and the exposure `exposureEV`.
void ConfigureDisplay(vtkCloudVolumeMapper* mapper, const RenderSpec& render, double exposureEV);

// Sets what only the GPU mapper has from the render section: jitter, resolution scale, the
// display transform (with the scene's exposure; "auto" is resolved after the render),
// accumulation (for pathtrace: render.spp paths, PathTraceFramesOf, and the path tracer's bricks,
// cloudvis::PathTraceBrickSize) and empty-space skipping.
// What every renderer takes (the step, the lighting, the
// lights) comes from ConfigureLighting (SceneLighting.h).
void ConfigureMapper(vtkCloudVolumeMapper* mapper, const RenderSpec& render);

// Sets the renderer's active camera from the camera section, filling absent keys for a field
// with these bounds (xmin, xmax, ymin, ymax, zmin, zmax): the focal point is the centre, the
// position looks along -z from the distance vtkRenderer::ResetCamera picks to fit the bounds.
// Throws InputError (prefixed by `source`) when view_up is parallel to the view direction.
void ApplyCamera(
  const CameraSpec& camera, const double bounds[6], vtkRenderer* renderer, const std::string& source);

// Renders `field` as the scene describes, off screen: render.size pixels, the scene's background,
// render.accumulate frames averaged (one when jitter is off: every frame would be the same),
// then captures the window. With benchmarkFrames > 0, renders that many more frames afterwards,
// forcing a full march each time, and times each up to the GPU's completion. `input` names the
// field in errors. Throws InputError "<input>: <problem>" when the mapper reports an error (a
// field it cannot draw, an invalid transfer function, a GPU failure) or when nothing was drawn,
// and before drawing when render.size is beyond the GPU's limit (ExportRender.h).
//
// With TargetNoise (the path tracer only), the still accumulates until that noise rather than
// render.spp paths (AccumulateToNoiseTarget); the result's Noise says whether it was reached, and
// the image is the one measured either way: refusing it is the caller's choice.
struct RenderOptions
{
  bool FloatImage = false; // keep RenderedImage's float image, auxiliary channels and background
  // After each accumulated frame (progress); with a noise target `frames` is the latest estimate.
  std::function<void(int frame, int frames)> OnFrame;
  std::optional<NoiseTarget> TargetNoise;
};
OffscreenRenderResult RenderOffscreen(const Scene& scene, vtkImageData* field,
  const std::string& input, int benchmarkFrames = 0, const RenderOptions& options = {});

// Throws InputError naming `input` with the mapper's last error, if any, and what VTK said.
void CheckMapper(
  vtkCloudVolumeMapper* mapper, const std::string& input, const VtkMessageCapture& messages);

// The window's pixels after the last render, as RenderedImage (8-bit RGB, bottom to top); throws
// InputError naming `input` (and what VTK said, from `messages`) if they cannot be read.
RenderedImage CaptureWindow(
  vtkRenderWindow* window, const std::string& input, const VtkMessageCapture& messages);

} // namespace cloudvis

#endif
