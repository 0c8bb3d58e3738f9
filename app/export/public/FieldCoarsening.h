// A field that fits in the host's memory but not in the GPU's, drawn rather than refused: averaged
// over 2 x 2 x 2 voxel blocks, and again (up to MaximumCoarsening per axis), until the mapper's
// textures fit the GPU memory it may take (render.gpu_memory, else what the driver reports
// free). `render`, `animate`, `compare` and the viewer's 3D view coarsen so, and say so (the
// commands' output line and the image's metadata "cloudvis.coarsened", the viewer's top-right
// corner), while statistics, slices and readouts keep the field as it is. docs/performance.md,
// "A field of 1 GiB", says what it costs.
#ifndef cloudvis_FieldCoarsening_h
#define cloudvis_FieldCoarsening_h

#include <vtkSmartPointer.h>

#include <functional>
#include <string>
#include <vector>

class vtkCloudVolumeMapper;
class vtkImageData;

namespace cloudvis
{

// The coarsest a field is drawn: 16 x 16 x 16 voxels averaged into one, 4096 times fewer.
constexpr int MaximumCoarsening = 16;

// `field` averaged over `factor` x `factor` x `factor` voxel blocks (the last, partial blocks of
// each axis dropped): the spacing `factor` times the field's, each voxel at the centre of its
// block, the direction kept. `factor` 1 returns `field` itself.
vtkSmartPointer<vtkImageData> CoarsenField(vtkImageData* field, int factor);

// Renders once with `render` (which draws the window and leaves the mappers' errors, if any);
// while a mapper refused an allocation for want of GPU memory, draws `field` coarsened 2x more
// (every mapper's input set to CoarsenField: `compare`'s panels draw one field) and renders
// again. Returns the factor drawn, from `factor` up (1: the field as it is), and sets `note` when
// it grew: "the field was coarsened 2x (512 x 512 x 128 voxels drawn for 1024 x 1024 x 256) to
// fit the GPU's memory: PROBLEM", PROBLEM the mappers' refusal. Once MaximumCoarsening does not
// fit either, the mappers' errors are left for the caller to report.
int RenderCoarsenedToFit(const std::vector<vtkCloudVolumeMapper*>& mappers,
  vtkImageData* field,
  int factor,
  const std::function<void()>& render,
  std::string& note);

} // namespace cloudvis

#endif
