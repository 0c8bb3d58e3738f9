// What is drawn behind the cloud: the scene's background section on a vtkRenderer. A solid color
// and a vertical gradient are VTK's own backgrounds; the sky of the article is a textured
// background computed on the CPU from the camera, one texel per pixel, so the mapper composites
// the cloud over it exactly as over a plain color (sky * (1 - alpha) + cloud). The sky follows
// the camera: it is recomputed at the start of every render whose camera or viewport size
// changed, so an interactive view can use it too.
#ifndef cloudvis_Background_h
#define cloudvis_Background_h

#include "Scene.h"

#include <vtkSmartPointer.h>

#include <array>

class vtkCamera;
class vtkImageData;
class vtkRenderer;

namespace cloudvis
{

// The article's sky for a unit view ray and a unit direction toward the sun, in [0, 1] per channel:
//   (0.7, 0.7, 0.9) - 0.8 * (0.9, 0.75, 0.9) * ray.y + 0.5 * (1.0, 0.5, 0.3) * max(dot(sun, ray), 0)^10
// clamped to [0, 1] (the gradient goes below 0 near the zenith and the glow above 1 near the sun).
std::array<double, 3> SkyColor(const std::array<double, 3>& ray, const std::array<double, 3>& sun);

// The unit direction toward the sun a sky uses: background.Sun, resolved when the scene was read
// (background.sun, else the first directional light of a "lights" section), else
// normalize(BackgroundSpec::DefaultSun).
std::array<double, 3> SkySunDirection(const BackgroundSpec& background);

// The sky as seen by `camera` in a viewport of width x height pixels: 8-bit RGB, rows from bottom
// to top, the ray of pixel (i, j) through its centre, found with the inverse of the camera's
// view-projection matrix.
vtkSmartPointer<vtkImageData> MakeSkyImage(
  vtkCamera* camera, int width, int height, const std::array<double, 3>& sun);

// Sets the renderer's background from the scene: Scene::Background for a solid color, VTK's
// gradient background (Background at the bottom, BackgroundStyle.Top at the top) for a gradient,
// and for a sky a textured background kept up to date by an observer of the renderer's
// StartEvent. Call it once per renderer; calling it again replaces the previous setting.
void ApplyBackground(const Scene& scene, vtkRenderer* renderer);

} // namespace cloudvis

#endif
