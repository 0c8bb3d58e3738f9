// The pieces of RenderOffscreen that exports need beyond the window's 8-bit pixels: the GPU's
// size limit, checked before anything is drawn; the mapper's float image and auxiliary channels
// with the cloud's depth turned into a distance from the camera; the background alone (for
// compositing the float image at 16 bits); and the camera the renderer placed, for the scene
// metadata and for the turntable.
#ifndef cloudvis_ExportRender_h
#define cloudvis_ExportRender_h

#include "OffscreenRender.h"
#include "SceneJson.h"

#include <vtkType.h>

#include <array>
#include <string>
#include <vector>

class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;
class vtkVolume;

namespace cloudvis
{

class VtkMessageCapture;

// The largest image the GPU can render into in one piece: the smallest of GL_MAX_TEXTURE_SIZE
// (the mapper's float targets), GL_MAX_RENDERBUFFER_SIZE (the window's off-screen framebuffer)
// and GL_MAX_VIEWPORT_DIMS, per axis.
struct RenderLimits
{
  int MaximumWidth = 0;
  int MaximumHeight = 0;
  double AvailableBytes = 0.0; // memory the render targets may take; 0 when unknown
};

// Memory one pixel of a render takes at the most: the mapper's two RGBA32F targets and float
// depth (36 bytes), the window's color and depth (8) and the float read-back of an export
// (radiance and auxiliary channels, 32).
constexpr double RenderBytesPerPixel = 76.0;

// Initialises `window` (at its current size) and reads the limits from its GL context.
RenderLimits QueryRenderLimits(vtkRenderWindow* window);

// Throws InputError "<source>: render.size: W x H pixels is beyond this GPU's limit of MW x MH
// pixels" when `size` exceeds `limits`, or "... needs N of memory but only M is available" when
// its render targets would not fit.
void CheckRenderSize(
  const std::array<int, 2>& size, const RenderLimits& limits, const std::string& source);

// Fills image.Radiance and image.Auxiliary from the mapper's last accumulated frame, rows bottom
// to top like image.RGB. Auxiliary channel 2 becomes the distance along each pixel's ray from
// the camera position (for a parallel projection: from the plane through the camera position
// across the view direction) to where the cloud's opacity first passes 2%; +infinity where it
// never does in some accumulated frame. Throws InputError (naming `input`) when the mapper has
// no image or its image is not the window's size (render.resolution_scale below 1), and
// CheckFiniteImage's error when a pixel is not finite.
void ReadFloatImage(vtkCloudVolumeMapper* mapper, vtkRenderer* renderer, RenderedImage& image,
  const std::string& input);

// Throws InputError "<input>: the rendered image has N pixels that are NaN or infinite ..." (with
// the likely causes) unless every value of the premultiplied RGBA floats is finite. Every path
// that writes a picture checks its float image with it first: a non-finite pixel would reach
// the file as a silently wrong color.
void CheckFiniteImage(const float* rgba, size_t pixels, const std::string& input);

// A pixel shows the field when it is at least this opaque: one 8-bit level of the cloud over the
// background.
constexpr double VisibleAlpha = 1.0 / 255.0;

// Fits `scene`'s transfer function to `field`'s values (FitTransferFunctionToField in Scene.h)
// and says what was done, or that the field is empty, as a line for a command's output ("" when
// nothing was done). render, compare and animate call it once the field is produced.
std::string FitTransferFunctionNote(Scene& scene, vtkImageData* field, bool fieldFileAlone);

// Throws InputError naming `input` when no pixel of the premultiplied RGBA floats (`pixels` of
// them) is VisibleAlpha opaque although the field holds values above 0 and the transfer function
// means to show some (HidesEveryValue is false): a blank picture of a field that is there is
// refused, never written. The message says why and what to set: a
// transfer function whose opacity is 0 over all the field's values (with the values and where
// the opacity starts), or else the camera or a cloud too thin to show.
void CheckFieldShows(const float* rgba,
  size_t pixels,
  vtkImageData* field,
  const Scene& scene,
  const std::string& input);

// What a render that drew no frame says: "INPUT: nothing was rendered", with VTK's words when it
// said any, or, when the volume's box lies wholly outside the camera's view frustum (the mapper
// then draws nothing at all), that no pixel shows the field and where the camera looks.
std::string NothingRenderedProblem(vtkRenderer* renderer,
  vtkVolume* volume,
  const VtkMessageCapture& messages,
  const std::string& input);

// What a path-traced image of `pixels` pixels says when the GPU cut the walks of `cut` of them
// short (vtkCloudVolumeMapper::CountCutPathTracePixels): "INPUT: the GPU ended the path
// tracer's walks early on CUT of PIXELS pixels, ...", with what to do instead.
std::string CutPathsProblem(const std::string& input, vtkIdType cut, vtkIdType pixels);

// The mapper's float image of `renderer` (premultiplied RGBA), checked with CheckFiniteImage;
// throws InputError naming `input` when the mapper kept none, or when the GPU cut a path-traced
// image's walks short (vtkCloudVolumeMapper::CountCutPathTracePixels).
std::vector<float> ReadCheckedMapperImage(
  vtkCloudVolumeMapper* mapper, vtkRenderer* renderer, const std::string& input);

// Renders the window once more with `volume` hidden and fills image.BackgroundRGB with what is
// left (the background as the renderer draws it, display values); shows the volume again.
void ReadBackgroundImage(vtkRenderWindow* window, vtkVolume* volume, RenderedImage& image);

// The camera ApplyCamera places for the scene and a field with these bounds.
ResolvedCamera ResolveCamera(const Scene& scene, const double fieldBounds[6]);

// The resolved scene of `scene` rendered over `field` (SceneToJson with the placed camera), as
// exports embed it: compact JSON, ASCII only (non-ASCII characters escaped, as PNG text needs).
std::string ResolvedSceneJson(const Scene& scene, vtkImageData* field);

} // namespace cloudvis

#endif
