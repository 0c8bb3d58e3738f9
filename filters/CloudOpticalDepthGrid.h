// Light across the pieces of a distributed field (issue 25): under MPI each rank's renderer
// marches only its own piece, yet a cloud in one piece shadows a cloud in another. Each piece
// computes the optical depth it adds toward each light at the points of one world grid common to
// every rank (ComputePieceOpticalDepths); a sum over the ranks (the caller's MPI_Allreduce) minus
// a piece's own share is the optical depth that comes from outside that piece, which its march
// then adds wherever it uses an optical depth toward a light (OpticalDepthToLight in
// shaders/transport/LightMarch.glsl: the single-scattering beam, the light volumes' and the
// nested march's results, the multiple-scattering volume's source). docs/transport.md, "Optical
// depth from outside the field", states the units and the grid's convention. Nothing here needs
// MPI or OpenGL: the CPU reference and the GPU mapper read the same grid.
#ifndef CloudOpticalDepthGrid_h
#define CloudOpticalDepthGrid_h

#include "CloudMarchUniforms.h"
#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace cloudvis
{

// Optical depths toward each light at the points of a world-space, axis-aligned grid: point
// (i, j, k) at Origin + (i, j, k) * Spacing, corner-aligned (its first and last points sit on
// the box it spans; the whole field's bounds at about a quarter of its resolution is a good
// choice). Depths are dimensionless, sigma_t times length (the same tau as OpticalDepthToLight,
// whatever a piece's local frame), so the depths of pieces add. Lights are in the renderer's
// order (a mapper's: its SetLights, else its renderer's switched-on lights); Depths holds
// Size.x * Size.y * Size.z values per light, x fastest, light-major: light l's block starts at
// l * Size.x * Size.y * Size.z, as the GPU's texture stacks them along z.
struct OpticalDepthGrid
{
  double Origin[3] = { 0.0, 0.0, 0.0 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  int Size[3] = { 0, 0, 0 };
  int Lights = 0;
  std::vector<float> Depths;

  // An empty grid means no depths (it clears what a renderer was given).
  bool Empty() const { return this->Lights == 0 || this->Depths.empty(); }
  std::size_t PointCount() const
  {
    return std::size_t(this->Size[0]) * this->Size[1] * this->Size[2];
  }
  float& At(int light, int i, int j, int k)
  {
    return this
      ->Depths[((std::size_t(light) * this->Size[2] + k) * this->Size[1] + j) * this->Size[0] + i];
  }
};

// Empty when the grid's geometry is usable (Size >= 1 per axis, Spacing finite and > 0, Origin
// finite): what ComputePieceOpticalDepths needs. With `lights` >= 0 it also checks the depths:
// that many lights, Lights * PointCount finite values >= 0 (a renderer given external depths
// refuses others in these words).
CLOUDVISFILTERS_EXPORT std::string ValidateOpticalDepthGrid(const OpticalDepthGrid& grid,
  int lights = -1);

// The optical depth the volume of `setup` (a piece, or a whole field) adds along the ray from
// each grid point toward each of its lights: toward a directional light along its direction, to
// a positional light up to the light; only the part of the ray inside the volume's box counts,
// so a point outside the volume gets what the ray crosses of it on its way (and 0 when it misses
// the volume). The extinction is the march's (its table, its extinction scale, the density
// texels' interpolation). Integrated by the trapezoid rule at most half a voxel (in index units,
// the piece's own) per step, with the ray's ends on the box's faces. Fills grid.Lights and
// grid.Depths for the grid's Origin, Spacing and Size, with vtkSMPTools (each point's depth
// depends only on its index and the inputs: deterministic). Returns SetUpMarch's problem when
// the volume cannot be marched, or a problem of the grid's geometry (MarchInput::None); then
// the grid's depths are left empty.
CLOUDVISFILTERS_EXPORT MarchProblem ComputePieceOpticalDepths(const MarchSetup& setup,
  OpticalDepthGrid& grid);

// What comes from outside a piece, given the sum over all pieces (an MPI_Allreduce of their
// Depths) and the piece's own depths on the same grid: total - own per value, at least 0. In
// float, a sum of values >= 0 is never below any of its terms, so the clamp only guards sums
// made otherwise. Empty when the two grids differ in size or lights.
CLOUDVISFILTERS_EXPORT OpticalDepthGrid DepthsFromOutside(const OpticalDepthGrid& total,
  const OpticalDepthGrid& own);

// Makes the march of `u` (set up by SetUpMarch with `frame`) add `grid`'s depths (not owned: it
// must outlive u's use) to its optical depth toward each light; null clears them. Sets
// u.ExternalDepths and u.IndexToExternal, the map from the volume's index points to the grid's
// texel coordinates. The grid must hold u's lights (ValidateOpticalDepthGrid).
CLOUDVISFILTERS_EXPORT void SetExternalOpticalDepths(MarchUniforms& u,
  const LocalFrame& frame,
  const OpticalDepthGrid* grid);

} // namespace cloudvis

#endif
