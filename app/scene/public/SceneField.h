// From a validated scene to the density field it describes: either the procedural source
// configured from the scene's "field" section (for pipelines that want to connect to it, such
// as the renderer to come) or the finished vtkImageData (for export and statistics).
#ifndef cloudvis_SceneField_h
#define cloudvis_SceneField_h

#include "Scene.h"

#include <vtkSmartPointer.h>

#include <cstdint>
#include <functional>

class vtkCloudDensitySource;
class vtkImageData;

namespace cloudvis
{

// The most points a coverage map (field.cloud.coverage_map) may have: 16384 x 16384, the
// largest 2-D texture today's GPUs take, 1 GiB as the map's floats. The map spans the field's x
// and z bounds, whose voxels (at most field.max_voxels' default of 1024^3 in all) sample it far
// more coarsely. An image's header, or a field file once read, that claims more is refused.
constexpr std::uint64_t MaximumCoverageMapPixels = std::uint64_t(16384) * 16384;

// Reads field.cloud.coverage_map's file into field.Description.Layer.Map when the field will use
// it (the cloud model, its coverage from a map) and it is not read yet: the scene's reader calls
// it once, so that validation and generation share one read. Throws InputError naming the file.
void LoadCoverageMap(FieldSpec& field);

// A source set up with the field's dimensions, bounds, description and time. The field must be
// procedural (not FromFile()). A coverage map LoadCoverageMap has not read yet is read here.
vtkSmartPointer<vtkCloudDensitySource> MakeDensitySource(const FieldSpec& field);

// Empty when the source would accept the field, else the problem in the filters' words (the
// same checks vtkCloudDensitySource::Validate applies before generating). The memory the field
// needs is not among them: it is checked for what is generated, the whole field in ProduceField,
// each piece when a .pvti is generated in pieces.
std::string ValidateProceduralField(const FieldSpec& field);

// The field of a scene: read from field.file (with field.format, array, time_step, ...), or
// generated. Throws InputError on failure. `progress`, when given, is called with the
// generation's fraction done, 0 .. 1; `report`, when given, receives what was read (FieldIO.h),
// with the units the field has (FieldReport::Resolved). The scene is finished with the field:
// its units decided, from the scene's keys and what a field file declares (ResolveFieldValues),
// and what depends on them set (ResolveFieldOptics, Scene.h: the droplets' extinction and phase).
// Render with the scene as this leaves it.
vtkSmartPointer<vtkImageData> ProduceField(Scene& scene,
  const std::function<void(double fraction)>& progress = {},
  FieldReport* report = nullptr);
// The same field for a caller that only needs its values (generate, statistics, tests): the
// scene's copy is finished and dropped. A scene over a field file with droplets tabulated
// without ProduceField(Scene&) is refused (TabulatedTransferFunction).
vtkSmartPointer<vtkImageData> ProduceField(const Scene& scene,
  const std::function<void(double fraction)>& progress = {},
  FieldReport* report = nullptr);

// Refuses time steps a field file does not hold, before any work on them: `read`, the report of
// the first step read, says how many it holds. Throws InputError naming the file (`scene`'s
// field.file) and the last step; `what` names what asked for them ("--time-steps").
void CheckTimeSteps(const Scene& scene,
  const std::vector<int>& steps,
  const FieldReport& read,
  const std::string& what);

} // namespace cloudvis

#endif
