#include "CloudTowerPlan.h"

#include "CloudLayer.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{

namespace
{
// Grid nodes per side, heights sampled for the footprint, and steps along the anvil's sweep:
// at the shipped cumulonimbus a footprint node is about 60 m, under half a voxel.
constexpr int TowerNodes = 192;
constexpr int TowerHeights = 64;
constexpr int AnvilNodes = 320;
constexpr int SweepSteps = 96;
constexpr double Pi = 3.14159265358979323846;
}

void ShapeBounds(const Shape& s, glm::dvec3& low, glm::dvec3& high)
{
  double radius = 0.0;
  switch (s.Type)
  {
    case ShapeType::Sphere:
      radius = s.Radius;
      break;
    case ShapeType::Box:
      radius = glm::length(glm::dvec3(s.HalfSize));
      break;
    case ShapeType::Torus:
      radius = double(s.MajorRadius) + s.MinorRadius;
      break;
    case ShapeType::Cross:
      radius = glm::length(glm::dvec3(s.ArmLength, s.ArmWidth, s.ArmWidth));
      break;
    case ShapeType::Capsule:
      radius =
        std::max(glm::length(glm::dvec3(s.EndA)), glm::length(glm::dvec3(s.EndB))) + s.Radius;
      break;
  }
  radius *= s.Scale;
  low = glm::dvec3(s.Center) - radius;
  high = glm::dvec3(s.Center) + radius;
}

float CloudTowerPlan::Grid::At(double x, double z) const
{
  const double u = (x - this->Low.x) / this->Cell, v = (z - this->Low.y) / this->Cell;
  const double last = this->Size - 1;
  const double cu = std::min(std::max(u, 0.0), last), cv = std::min(std::max(v, 0.0), last);
  const int i = std::min(static_cast<int>(cu), this->Size - 2);
  const int k = std::min(static_cast<int>(cv), this->Size - 2);
  const float fu = static_cast<float>(cu - i), fv = static_cast<float>(cv - k);
  const float* row0 = this->Values.data() + static_cast<size_t>(k) * this->Size;
  const float* row1 = row0 + this->Size;
  const float a = row0[i] + (row0[i + 1] - row0[i]) * fu;
  const float b = row1[i] + (row1[i + 1] - row1[i]) * fu;
  const float inside = a + (b - a) * fv;
  if (!this->Distances)
  {
    return inside;
  }
  const double outside = std::hypot(u - cu, v - cv) * this->Cell;
  return inside + static_cast<float>(outside);
}

CloudTowerPlan::CloudTowerPlan(const std::function<float(glm::vec3)>& sdf,
  glm::dvec3 low,
  glm::dvec3 high,
  const CloudLayer& layer)
{
  // The footprint: a square grid over the shapes' x and z bounds.
  const double side = std::max(high.x - low.x, high.z - low.z);
  this->Tower.Size = TowerNodes;
  this->Tower.Cell = side / (TowerNodes - 1);
  this->Tower.Low = glm::dvec2(low.x, low.z);
  this->Tower.Values.assign(static_cast<size_t>(TowerNodes) * TowerNodes, 0.0f);
  const double dy = (high.y - low.y) / (TowerHeights - 1);
  vtkSMPTools::For(0,
    TowerNodes,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType k = begin; k < end; ++k)
      {
        for (int i = 0; i < TowerNodes; ++i)
        {
          const double x = this->Tower.Low.x + i * this->Tower.Cell;
          const double z = this->Tower.Low.y + k * this->Tower.Cell;
          float least = sdf(glm::vec3(glm::dvec3(x, low.y, z)));
          for (int j = 1; j < TowerHeights; ++j)
          {
            least = std::min(least, sdf(glm::vec3(glm::dvec3(x, low.y + j * dy, z))));
          }
          this->Tower.Values[static_cast<size_t>(k) * TowerNodes + i] = least;
        }
      }
    });

  // The axis: the footprint's centroid and equivalent radius.
  double area = 0.0;
  glm::dvec2 moment(0.0);
  for (int k = 0; k < TowerNodes; ++k)
  {
    for (int i = 0; i < TowerNodes; ++i)
    {
      if (this->Tower.Values[static_cast<size_t>(k) * TowerNodes + i] < 0.0f)
      {
        area += 1.0;
        moment += glm::dvec2(i, k);
      }
    }
  }
  const double cellArea = this->Tower.Cell * this->Tower.Cell;
  this->AxisPoint = area > 0.0 ? this->Tower.Low + moment / area * this->Tower.Cell
                               : 0.5 * (glm::dvec2(low.x, low.z) + glm::dvec2(high.x, high.z));
  this->AxisRadius = std::sqrt(area * cellArea / Pi);

  // The anvil: the footprint swept downwind, over a grid that holds the sweep and its fan.
  const glm::dvec2 w = glm::normalize(glm::dvec2(layer.AnvilDirection[0], layer.AnvilDirection[1]));
  const double reach = layer.Anvil * layer.AnvilReach;
  const double overhang = layer.Anvil * (layer.Top - layer.Base) * AnvilOverhang;
  const double margin = reach * FanSlope + overhang + this->Tower.Cell;
  glm::dvec2 lo = glm::min(glm::dvec2(low.x, low.z), glm::dvec2(low.x, low.z) + reach * w);
  glm::dvec2 hi = glm::max(glm::dvec2(high.x, high.z), glm::dvec2(high.x, high.z) + reach * w);
  lo -= margin;
  hi += margin;
  const double anvilSide = std::max(hi.x - lo.x, hi.y - lo.y);
  for (Grid* g : { &this->Anvil, &this->AnvilAlong })
  {
    g->Size = AnvilNodes;
    g->Cell = anvilSide / (AnvilNodes - 1);
    g->Low = lo;
    g->Values.assign(static_cast<size_t>(AnvilNodes) * AnvilNodes, 0.0f);
  }
  this->AnvilAlong.Distances = false;
  vtkSMPTools::For(0,
    AnvilNodes,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType k = begin; k < end; ++k)
      {
        for (int i = 0; i < AnvilNodes; ++i)
        {
          const glm::dvec2 p = lo + glm::dvec2(i, k) * this->Anvil.Cell;
          float least = this->Tower.At(p.x, p.y);
          float along = 0.0f;
          for (int n = 1; reach > 0.0 && n <= SweepSteps; ++n)
          {
            const double s = double(n) / SweepSteps;
            const glm::dvec2 q = p - s * reach * w;
            const float d = this->Tower.At(q.x, q.y) - static_cast<float>(s * reach * FanSlope);
            if (d < least)
            {
              least = d;
              along = static_cast<float>(s);
            }
          }
          const size_t at = static_cast<size_t>(k) * AnvilNodes + i;
          this->Anvil.Values[at] = least - static_cast<float>(overhang);
          this->AnvilAlong.Values[at] = along;
        }
      }
    });
}

} // namespace cloudvis
