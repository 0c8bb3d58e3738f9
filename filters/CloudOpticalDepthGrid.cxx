// A piece's optical depth toward its lights over a common world grid, and the map by which a
// march reads such a grid (CloudOpticalDepthGrid.h). The extinction is the shared source's
// (ExtinctionAt, CloudTransport.h), so a piece's depths are in the units its march computes.
#include "CloudOpticalDepthGrid.h"

#include "CloudTransport.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace cloudvis
{
namespace
{
// The longest trapezoid step of a piece's depth, in the piece's voxels (index units). The march's
// own light volumes step a whole view step (about a voxel); half of it keeps the trapezoid's
// error, which falls as the step squared, a quarter of theirs, for 2 extinction reads per voxel
// crossed: a 33^3 grid over a 128^3 field in about a second on two cores.
constexpr float PieceDepthStep = 0.5f;

std::string Text(double value)
{
  return std::to_string(value);
}

// The optical depth the volume adds along p + t indexStep (t in local units) from t = 0 to
// maxDistance, counting only where the ray is inside the volume's box [0, Dimensions - 1]: the
// trapezoid rule on at most PieceDepthStep voxels per step between the box's faces.
float DepthInsideBox(glsl::Transport& transport,
  glm::vec3 p,
  glm::vec3 indexStep,
  float maxDistance)
{
  const glm::vec3 last = transport.Dimensions - 1.0f;
  const glm::vec2 box = transport.IntersectBox(p, indexStep, glm::vec3(0.0f), last);
  const float t0 = std::max(box.x, 0.0f);
  const float t1 = std::min(box.y, maxDistance);
  if (!(t1 > t0))
  {
    return 0.0f;
  }
  const float voxels = (t1 - t0) * glm::length(indexStep);
  const int steps = std::max(1, int(std::ceil(voxels / PieceDepthStep)));
  const float dt = (t1 - t0) / float(steps);
  // The ends lie on the faces up to rounding: clamped into the box.
  const auto extinction = [&](float t)
  { return transport.ExtinctionAt(glm::clamp(p + t * indexStep, glm::vec3(0.0f), last)); };
  float tau = 0.0f;
  float sigmaStart = extinction(t0);
  for (int s = 1; s <= steps; ++s)
  {
    const float sigmaEnd = extinction(s == steps ? t1 : t0 + float(s) * dt);
    tau += 0.5f * (sigmaStart + sigmaEnd) * dt;
    sigmaStart = sigmaEnd;
  }
  return tau;
}
}

std::string ValidateOpticalDepthGrid(const OpticalDepthGrid& grid, int lights)
{
  for (int a = 0; a < 3; ++a)
  {
    if (grid.Size[a] < 1)
    {
      return "the optical-depth grid needs at least 1 point per axis, not " +
        std::to_string(grid.Size[a]);
    }
    if (!(std::isfinite(grid.Spacing[a]) && grid.Spacing[a] > 0.0))
    {
      return "the optical-depth grid's spacing must be finite and > 0, not " +
        Text(grid.Spacing[a]);
    }
    if (!std::isfinite(grid.Origin[a]))
    {
      return "the optical-depth grid's origin must be finite";
    }
  }
  if (lights < 0)
  {
    return {};
  }
  if (grid.Lights != lights)
  {
    return "the optical depths from outside the field are for " + std::to_string(grid.Lights) +
      " lights; the cloud is lit by " + std::to_string(lights);
  }
  if (grid.Depths.size() != grid.PointCount() * std::size_t(grid.Lights))
  {
    return "the optical-depth grid holds " + std::to_string(grid.Depths.size()) +
      " depths, not size x lights = " + std::to_string(grid.PointCount() * grid.Lights);
  }
  for (float depth : grid.Depths)
  {
    if (!(std::isfinite(depth) && depth >= 0.0f))
    {
      return "the optical-depth grid holds a depth that is not finite and >= 0: " + Text(depth);
    }
  }
  return {};
}

MarchProblem ComputePieceOpticalDepths(const MarchSetup& setup, OpticalDepthGrid& grid)
{
  grid.Lights = 0;
  grid.Depths.clear();
  MarchProblem problem;
  problem.Message = ValidateOpticalDepthGrid(grid);
  if (problem)
  {
    return problem;
  }
  MarchUniforms u;
  LocalFrame frame;
  problem = SetUpMarch(setup, u, &frame);
  if (problem)
  {
    return problem;
  }

  grid.Lights = int(u.Lights.size());
  grid.Depths.assign(grid.PointCount() * std::size_t(grid.Lights), 0.0f);
  const vtkIdType slices = vtkIdType(grid.Size[2]) * grid.Lights;
  const auto computeSlices = [&](vtkIdType begin, vtkIdType end)
  {
    glsl::Transport transport = TransportOf(u); // per thread, as the light volumes'
    for (vtkIdType slice = begin; slice < end; ++slice)
    {
      const int light = int(slice / grid.Size[2]);
      const int k = int(slice % grid.Size[2]);
      for (int j = 0; j < grid.Size[1]; ++j)
        for (int i = 0; i < grid.Size[0]; ++i)
        {
          const glm::dvec3 world(grid.Origin[0] + i * grid.Spacing[0],
            grid.Origin[1] + j * grid.Spacing[1],
            grid.Origin[2] + k * grid.Spacing[2]);
          const glm::dvec3 local = frame.ToLocal(world);
          const glm::vec3 p(frame.LocalToIndex * glm::dvec4(local, 1.0));
          glm::vec3 l;
          float lightDistance, falloff;
          transport.SampleLight(light, glm::vec3(local), l, lightDistance, falloff);
          const glm::vec3 indexStep = transport.LightPositional[light] != 0
            ? transport.LocalToIndex * l
            : transport.LightIndexDirection[light];
          grid.At(light, i, j, k) = DepthInsideBox(transport, p, indexStep, lightDistance);
        }
    }
  };
  vtkSMPTools::For(0, slices, computeSlices);
  return {};
}

OpticalDepthGrid DepthsFromOutside(const OpticalDepthGrid& total, const OpticalDepthGrid& own)
{
  const bool same = total.Lights == own.Lights && total.Depths.size() == own.Depths.size() &&
    std::equal(total.Size, total.Size + 3, own.Size);
  if (!same)
  {
    return {};
  }
  OpticalDepthGrid outside = total;
  for (std::size_t v = 0; v < outside.Depths.size(); ++v)
  {
    outside.Depths[v] = std::max(total.Depths[v] - own.Depths[v], 0.0f);
  }
  return outside;
}

void SetExternalOpticalDepths(MarchUniforms& u,
  const LocalFrame& frame,
  const OpticalDepthGrid* grid)
{
  u.ExternalDepths = grid && !grid->Empty() ? grid : nullptr;
  u.IndexToExternal = glm::mat4(1.0f);
  if (!u.ExternalDepths)
  {
    return;
  }
  // Local to world is Anchor + Unit x, world to texel (world - Origin) / Spacing: composed in
  // double, so a field far from the world's origin keeps its place on the grid.
  glm::dmat4 localToTexel(1.0);
  for (int a = 0; a < 3; ++a)
  {
    localToTexel[a][a] = frame.Unit / grid->Spacing[a];
    localToTexel[3][a] = (frame.Anchor[a] - grid->Origin[a]) / grid->Spacing[a];
  }
  u.IndexToExternal = glm::mat4(localToTexel * frame.IndexToLocal);
}

} // namespace cloudvis
