// From a validated scene and its field to pixels: the one place that maps a Scene's
// transfer_function, camera, background and render sections onto VTK's window, renderer, camera,
// vtkVolumeProperty and vtkCloudVolumeMapper. `render` uses all of it; `compare` will call
// RenderOffscreen once per lighting model on the same field; the interactive viewer will build
// its own window and use the configuration pieces (MakeVolumeProperty, ConfigureMapper,
// ApplyCamera) so that what it shows is what `render` writes.
#ifndef cloudvis_OffscreenRender_h
#define cloudvis_OffscreenRender_h

#include "Scene.h"

#include <vtkSmartPointer.h>

#include <functional>
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

// 8-bit RGB pixels as the window showed them, rows from bottom to top (VTK's order).
struct RenderedImage
{
  int Width = 0;
  int Height = 0;
  std::vector<unsigned char> RGB; // Width * Height * 3

  // Kept only when RenderOptions::FloatImage asks for them (exports: ImageWriters.h), same size
  // and row order: the mapper's premultiplied linear RGBA (alpha = 1 - transmittance); per pixel
  // samples taken, useful samples, the cloud's distance from the camera and 1 (ExportRender.h);
  // and the window's pixels without the cloud.
  std::vector<float> Radiance;
  std::vector<float> Auxiliary;
  std::vector<unsigned char> BackgroundRGB;

  const unsigned char* Pixel(int x, int y) const
  {
    return this->RGB.data() + 3 * (size_t(y) * size_t(this->Width) + size_t(x));
  }
};

struct OffscreenRenderResult
{
  RenderedImage Image;
  int AccumulatedFrames = 0;             // frames the mapper averaged into Image
  std::vector<double> FrameMilliseconds; // wall clock of each benchmark frame, in order
};

// Throws InputError unless an X display can be opened: VTK 9.1 on this platform renders through
// X only. The message says how to run headless, quoting `commandLine` ("cloudvis render ...")
// after "xvfb-run -a".
void RequireDisplay(const std::string& commandLine);

// A connection to the X display named by $DISPLAY, open for the object's lifetime; fails like
// RequireDisplay. A refused connection is retried for a moment, because a busy Xvfb refuses some
// (seen on the 2-core build machines). Hand Get() to vtkRenderWindow::SetDisplayId and keep this
// object alive longer than the window: VTK then never opens its own connection, whose failure
// makes it abort() the process.
class DisplayConnection
{
public:
  explicit DisplayConnection(const std::string& commandLine);
  ~DisplayConnection();
  DisplayConnection(const DisplayConnection&) = delete;
  DisplayConnection& operator=(const DisplayConnection&) = delete;

  void* Get() const { return this->Display; } // an Xlib Display*

private:
  void* Display = nullptr;
};

// The volume property of a transfer function: piecewise-linear opacity per unit distance and
// color, linear interpolation of the density, no VTK shading (lighting is the mapper's).
vtkSmartPointer<vtkVolumeProperty> MakeVolumeProperty(const TransferFunctionSpec& transferFunction);

// Sets the mapper's step, jitter, resolution scale, accumulation and empty-space skipping (and
// the lighting model; ConfigureLighting in SceneLighting.h adds the lights and parameters) from
// the render section.
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
struct RenderOptions
{
  bool FloatImage = false; // keep RenderedImage's float image, auxiliary channels and background
  std::function<void(int frame, int frames)> OnFrame; // after each accumulated frame (progress)
};
OffscreenRenderResult RenderOffscreen(const Scene& scene, vtkImageData* field,
  const std::string& input, int benchmarkFrames = 0, const RenderOptions& options = {});

// The image formats the renderer writes, as lower-case extensions with the dot (".png").
// Throws InputError naming `input` with the mapper's last error, if any, and what VTK said.
void CheckMapper(
  vtkCloudVolumeMapper* mapper, const std::string& input, const VtkMessageCapture& messages);

// The window's pixels after the last render, as RenderedImage (8-bit RGB, bottom to top); throws
// InputError naming `input` (and what VTK said, from `messages`) if they cannot be read.
RenderedImage CaptureWindow(
  vtkRenderWindow* window, const std::string& input, const VtkMessageCapture& messages);

std::vector<std::string> SupportedImageExtensions();

// Throws InputError unless `path` ends in a supported extension (the message lists them) and can
// be written (CheckOutputTarget). Called before any rendering.
void CheckImageOutput(const std::string& path);

// Writes the image in the format its extension names, atomically (WriteFileAtomically).
void WriteImage(const RenderedImage& image, const std::string& path);
// The same with export options and metadata (io/ImageWriters.h).
struct ImageExportOptions;
void WriteImage(
  const RenderedImage& image, const std::string& path, const ImageExportOptions& options);

} // namespace cloudvis

#endif
