// Multiple scattering without paths (issue 21): the light that has scattered at least once, on a
// grid at a quarter of the field's resolution, computed when the field, the transfer function, the
// phase or the lights change, and read by the march once per sample. The equations (a
// delta-Eddington split of the phase and flux-limited diffusion of the diffuse rest) and their
// texel functions are defined once in shaders/transport/Transport.glsl ("The multiple-scattering
// volume"); the GPU runs them in passes of its own (app/rendering/), the CPU here, with the same
// functions and the same order of passes. docs/lighting.md states the model and its error.
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

// Whether a march with these parameters reads the volume (the march model, with its multiple
// scattering from the volume rather than the octaves).
inline bool UsesScatteringVolume(const LightingParameters& p)
{
  return p.Model == LightingModel::March && p.MultipleScattering == MultipleScatteringModel::Volume;
}

// The finest grid's size for a field of these dimensions, and every grid's from the coarsest
// (the first with at most 5 texels along its shortest axis, or the finest when it is that small)
// to the finest: 5^3, 9^3, 17^3 and 33^3 for 128^3 voxels.
CLOUDVISFILTERS_EXPORT glm::ivec3 ScatteringVolumeSize(glm::ivec3 fieldDimensions);
CLOUDVISFILTERS_EXPORT std::vector<glm::ivec3> ScatteringGrids(glm::ivec3 fieldDimensions);

// The local length of a cell per axis on a grid of `size` texels.
CLOUDVISFILTERS_EXPORT glm::vec3 ScatteringCellSize(const MarchUniforms& u, glm::ivec3 size);

// Computes the volume for u's field, table, phase and lights (u.LightDepths when the march reads
// light volumes), with vtkSMPTools: a texel's value depends only on the previous pass's.
CLOUDVISFILTERS_EXPORT void ComputeScatteringVolume(const MarchUniforms& u,
  ScatteringGrid& volume,
  const ScatteringSolve& solve = ScatteringSolve());

} // namespace cloudvis

#endif
