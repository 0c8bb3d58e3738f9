// `cloudvis render --cpu-reference`: the scene rendered by vtkCloudReferenceRenderer, the CPU
// oracle of the GPU mapper's equations, instead of the GPU. Everything the image depends on comes
// from the same places as RenderOffscreen's: the camera ApplyCamera sets up, the field's whole
// geometry, and the settings of RendererSettingsOf (SceneLighting.h: the transfer function, from
// which the reference builds the mapper's table, the lighting, the lights, render.step). Both
// renderers refuse the same inputs (cloudvis::SetUpMarch); CheckSceneRenderable says so in scene
// keys. No
// jitter (one exact ray per pixel), no accumulation, and render.resolution_scale does not apply
// (the reference renders every pixel). No OpenGL, so no display is needed.
#ifndef cloudvis_CpuReference_h
#define cloudvis_CpuReference_h

#include "OffscreenRender.h"

#include <string>
#include <vector>

class vtkCamera;
class vtkCloudReferenceRenderer;
class vtkImageData;

namespace cloudvis
{

// Gives the reference renderer a vtkCamera's view: position, focal point, view up, view angle,
// parallel projection and scale, clipping range. With ImageSize equal to the viewport's size the
// two show the same view.
void SetReferenceCamera(vtkCloudReferenceRenderer* reference, vtkCamera* camera);

// Sets up `reference` (the march's reference or the path tracer) to draw `field` as
// RenderCpuReference draws the scene: render.size pixels, the camera ApplyCamera sets up on a
// renderer of that aspect, and ConfigureReference's settings (transfer function, lighting, lights,
// step). Does not render. bench/ measures the CPU renderers through it.
void SetUpReference(const Scene& scene, vtkImageData* field, vtkCloudReferenceRenderer* reference);

// Throws InputError unless both renderers can draw `field` as the scene says: what
// cloudvis::ValidateVolumeGeometry and cloudvis::SetUpMarch refuse (a geometry float arithmetic
// cannot hold, a step needing more samples per ray than the renderers take, an extinction or a
// light beyond float range), named by its scene key: "<scene>: render.step: <problem>". Every
// command that renders calls it once the field is known and before anything is drawn or written.
void CheckSceneRenderable(const Scene& scene, vtkImageData* field, const std::string& input);

// The reference's premultiplied RGBA (render.size pixels, rows bottom to top; kept in Radiance)
// through the display transform and composited over the scene's background,
// D(c, a) + (1 - a) * background, rounded to 8 bits. Throws InputError
// "<input>: CPU reference: <problem>" when the reference refuses the field or the parameters, and
// CheckFiniteImage's error when a pixel is not finite.
RenderedImage RenderCpuReference(const Scene& scene, vtkImageData* field, const std::string& input);

} // namespace cloudvis

#endif
