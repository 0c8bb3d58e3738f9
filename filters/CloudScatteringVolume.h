// Multiple scattering without paths (issue 21): the light that has scattered at least once, on a
// grid at a quarter of the field's resolution, computed when the field, the transfer function, the
// phase or the lights change, and read by the march once per sample. The equations (a
// delta-Eddington split of the phase and flux-limited diffusion of the diffuse rest) and their
// texel functions are defined once in shaders/transport/Scattering.glsl (LightMarch.glsl's "The
// multiple-scattering volume" gives the equations); the GPU runs them in passes of its own
// (app/rendering/), the CPU here, with the same functions and the same order of passes.
// docs/lighting.md states the model and its error.
//
// The solve, per grid from the coarsest to the finest: the cells' medium and diffuse source, a
// first guess (zero on the coarsest grid, the coarser grid's solution on the others), then
// red-black over-relaxation sweeps. Grids are corner-aligned (their first and last texels sit on
// the field's first and last voxels), each twice as fine as the one before.
#ifndef CloudScatteringVolume_h
#define CloudScatteringVolume_h

#include "CloudMarchUniforms.h"
#include "CloudTransport.h" // ScatteringGrid
#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <vector>

class vtkImageData;
class vtkMatrix4x4;

namespace cloudvis
{

// The finest grid's texels per axis are (n - 1) / ScatteringVolumeDivisor + 1, rounded up, for n
// voxels.
constexpr int ScatteringVolumeDivisor = 4;

// How the diffusion is solved: red-black Gauss-Seidel sweeps on the coarsest grid and on each
// finer one (docs/lighting.md: 24 per grid come within 0.6 points of the converged error).
struct ScatteringSolve
{
  int CoarsestSweeps = 64;
  int SweepsPerGrid = 24;
};

// The finest grid's size for a field of these dimensions, and every grid's from the coarsest
// (the first with at most 5 texels along its shortest axis, or the finest when it is that small)
// to the finest: 5^3, 9^3, 17^3 and 33^3 for 128^3 voxels.
CLOUDVISFILTERS_EXPORT glm::ivec3 ScatteringVolumeSize(glm::ivec3 fieldDimensions);
CLOUDVISFILTERS_EXPORT std::vector<glm::ivec3> ScatteringGrids(glm::ivec3 fieldDimensions);

// The field a volume is solved over, as the solve needs it: its voxels per axis and the local
// length of a voxel's edge along each index axis.
struct ScatteringField
{
  glm::ivec3 Dimensions{ 0 };
  glm::vec3 VoxelSize{ 1.0f };
};

// The local length of a cell per axis on a grid of `size` texels.
CLOUDVISFILTERS_EXPORT glm::vec3 ScatteringCellSize(const ScatteringField& field, glm::ivec3 size);
CLOUDVISFILTERS_EXPORT glm::vec3 ScatteringCellSize(const MarchUniforms& u, glm::ivec3 size);

// What the solve starts from, per grid from the coarsest (ScatteringGrids of the field's
// dimensions): every cell's Medium, Source and Direction, and on the coarsest grid the first
// guess in Fluence. Everything that reads the field and the lights is here; the solve reads only
// these and the phase.
using ScatteringInputs = std::vector<ScatteringGrid>;

// Computes the volume for u's field, table, phase and lights (u.LightDepths when the march reads
// light volumes), with vtkSMPTools: a texel's value depends only on the previous pass's. The
// inputs (every cell's medium, source and direction, and the coarsest grid's first guess), then
// the solve (relaxation and prolongation, coarse to fine, then the finest grid's flux),
// deterministic: the same inputs give the same floats on any machine's CPU, whatever its threads.
CLOUDVISFILTERS_EXPORT void ComputeScatteringVolume(const MarchUniforms& u,
  ScatteringGrid& volume,
  const ScatteringSolve& solve = ScatteringSolve());

// ---- Across the pieces of a distributed field (issue 25) ----
// Diffuse light crosses the pieces' faces only if the diffusion is solved over the whole field.
// Each piece computes the inputs of the whole field's grids for the cells it owns
// (ComputePieceScatteringInputs: zero elsewhere), a sum over the pieces (an MPI_Allreduce of
// PackScatteringInputs) gives every piece the whole field's inputs, each solves them
// (SolveWholeFieldScattering, identical everywhere) and its march reads the result through a world
// map (SetExternalScatteringVolume). docs/transport.md, "The multiple-scattering volume over the
// whole field".

// A multiple-scattering volume over a whole field: where its voxels lie (Dimensions, the map from
// index points to world points) and its finest grid's Fluence and Flux. Empty: none.
struct WholeFieldScattering
{
  VolumeGeometry Field;
  ScatteringGrid Volume;
  bool Empty() const { return this->Volume.Fluence.empty(); }
};

// The whole field of `piece` placed by `volumeMatrix` (null: identity): the piece's image with
// `wholeExtent` for its extent (the pieces of one image share its origin, spacing and direction).
CLOUDVISFILTERS_EXPORT VolumeGeometry WholeFieldGeometry(vtkImageData* piece,
  vtkMatrix4x4* volumeMatrix,
  const int wholeExtent[6]);

// The inputs of the whole field's grids (ScatteringGrids of whole.Dimensions over whole's box)
// that the piece of `setup` owns, lit with `external` (the exchanged optical depths from the
// other pieces; null: none): a cell is the piece's when its centre's whole-field index is within
// [first, last) of the piece's points along each axis, or [first, last] where the piece ends with
// the whole field, so each cell has one owner, cells on the faces pieces share included. Other
// cells are 0 (as are those of no piece). A cell's samples near a face read the piece's clamped
// edge where they would read the neighbour's (docs/transport.md gives the difference measured).
// Media and sources are per local unit of whole's frame. Returns SetUpMarch's problem, or one of
// the geometry when the piece's voxels are not a sub-grid of whole's.
CLOUDVISFILTERS_EXPORT MarchProblem ComputePieceScatteringInputs(const MarchSetup& setup,
  const OpticalDepthGrid* external,
  const VolumeGeometry& whole,
  ScatteringInputs& inputs);

// Every grid's inputs as one array of floats and back (the sum over ranks reduces it): the
// Medium, Source and Direction of each grid from the coarsest, then the coarsest's Fluence.
// UnpackScatteringInputs sizes `inputs` for `whole` and returns false when `values` has another
// length.
// ScatteringInputValues is the array's length for a whole field of these dimensions.
CLOUDVISFILTERS_EXPORT std::size_t ScatteringInputValues(glm::ivec3 wholeDimensions);
CLOUDVISFILTERS_EXPORT std::vector<float> PackScatteringInputs(const ScatteringInputs& inputs);
CLOUDVISFILTERS_EXPORT bool UnpackScatteringInputs(const std::vector<float>& values,
  const VolumeGeometry& whole,
  ScatteringInputs& inputs);

// The volume solved over the whole field from the summed inputs.
CLOUDVISFILTERS_EXPORT WholeFieldScattering SolveWholeFieldScattering(
  const LightingParameters& lighting,
  const VolumeGeometry& whole,
  ScatteringInputs inputs,
  const ScatteringSolve& solve = ScatteringSolve());

// Makes the march of u (set up by SetUpMarch with `frame`) read `volume` (not owned: it must
// outlive u's use) instead of a volume of its own field; null or empty clears it. Sets
// u.ExternalScattering and u.IndexToScattering, the map from u's index points to the volume's
// texel coordinates.
CLOUDVISFILTERS_EXPORT void SetExternalScatteringVolume(MarchUniforms& u,
  const LocalFrame& frame,
  const WholeFieldScattering* volume);

} // namespace cloudvis

#endif
