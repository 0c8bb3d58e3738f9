// `cloudvis render --cpu-reference`: the scene rendered by vtkCloudReferenceRenderer, the CPU
// oracle of the GPU mapper's equations, instead of the GPU. Everything the image depends on comes
// from the same places as RenderOffscreen's: the camera ApplyCamera sets up, the transfer table
// the mapper would build (BuildTransferTable over the field's scalar range), the scene's lights,
// LightingOf(scene) and render.step. No jitter (one exact ray per pixel), no accumulation, and
// render.resolution_scale does not apply (the reference renders every pixel). No OpenGL, so no
// display is needed.
#ifndef cloudvis_CpuReference_h
#define cloudvis_CpuReference_h

#include "CloudTransferTable.h"
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

// The transfer table the GPU mapper builds for this transfer function and field: 1024 entries
// over the field's scalar range (a constant field gets the range [v, v + 1], as on the GPU).
TransferTable SceneTransferTable(const TransferFunctionSpec& transferFunction, vtkImageData* field);

// The reference's premultiplied RGBA (render.size pixels, rows bottom to top) composited over the
// scene's background, c + (1 - a) * background, rounded to 8 bits. Throws InputError
// "<input>: CPU reference: <problem>" when the reference refuses the field or the parameters.
RenderedImage RenderCpuReference(const Scene& scene, vtkImageData* field, const std::string& input);

} // namespace cloudvis

#endif
