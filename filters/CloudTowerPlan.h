// The horizontal plan of a cumulonimbus whose coverage comes from the field's shapes: the
// tower's footprint and the anvil's, as signed distances on 2-D grids over x and z (docs/
// scene-format.md, "Cumulonimbus").
//
// - The footprint: the least signed distance of the shapes over all heights, d_T(x, z) =
//   min_y sdf(x, y, z). Read at every height of the tower, it keeps the tower as wide at the top
//   as at its widest level: a cluster of spheres no longer narrows into a waist between them.
// - The anvil: the footprint swept downwind along the unit direction w of the upper wind, out to
//   the reach R, and fanning out sideways as it goes (at FanSlope per unit of distance), less a
//   short overhang u all round:
//     d_A(x, z) = min over s in [0, 1] of ( d_T((x, z) - s R w) - s R FanSlope ) - u,
//   with s_A(x, z) the s of that minimum: how far down the anvil the point lies (0 over the
//   tower, 1 at its far end), which thins the anvil downwind.
// - The axis: the centroid of the footprint, and its radius sqrt(area / pi); the overshooting
//   dome stands on them.
//
// Both grids cover the shapes' bounds (and the sweep's), fixed by the field's description
// alone, so every piece of a field reads the very same grids: pieces stay bit-identical.
#ifndef CloudTowerPlan_h
#define CloudTowerPlan_h

#include "CloudShapes.h"

#include <glm/glm.hpp>

#include <functional>
#include <vector>

namespace cloudvis
{

struct CloudLayer;

class CloudTowerPlan
{
public:
  // How much the anvil widens per unit of its length downwind (each side): about 20 degrees.
  static constexpr double FanSlope = 0.35;
  // The overhang all round the tower at the anvil's level, as a fraction of the layer's depth
  // (times `anvil`): upwind, this is all the anvil reaches.
  static constexpr double AnvilOverhang = 0.1;

  // The plan of the shapes whose signed distance is `sdf`, which lie within the bounding box
  // [low, high] (world units), for the layer's anvil (direction, reach, overhang).
  CloudTowerPlan(const std::function<float(glm::vec3)>& sdf,
    glm::dvec3 low,
    glm::dvec3 high,
    const CloudLayer& layer);

  // d_T at (x, z): negative inside the footprint.
  float TowerDistance(double x, double z) const { return this->Tower.At(x, z); }
  // d_A and s_A at (x, z).
  float AnvilDistance(double x, double z) const { return this->Anvil.At(x, z); }
  float AnvilFraction(double x, double z) const { return this->AnvilAlong.At(x, z); }

  glm::dvec2 Axis() const { return this->AxisPoint; }
  double Radius() const { return this->AxisRadius; }

private:
  // A Size x Size grid of values over [Low, Low + Size * Cell) in x and z, bilinear between its
  // nodes. Beyond it: the nearest node's value plus the distance to the grid, which keeps a
  // distance growing outward.
  struct Grid
  {
    int Size = 0;
    glm::dvec2 Low{ 0.0 };
    double Cell = 1.0;
    std::vector<float> Values; // x fastest
    bool Distances = true;     // add the distance beyond the grid (false: clamp only)
    float At(double x, double z) const;
  };

  Grid Tower;
  Grid Anvil;
  Grid AnvilAlong;
  glm::dvec2 AxisPoint{ 0.0 };
  double AxisRadius = 0.0;
};

// The bounding box of a shape (its bounding sphere's, rotated or not), world units.
void ShapeBounds(const Shape& shape, glm::dvec3& low, glm::dvec3& high);

} // namespace cloudvis

#endif
