#include "CloudScatteringVolume.h"

#include "CloudTransport.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{

namespace
{
// Runs texel(transport, cell) over every cell of `grid`'s size, writing `out`, with this
// thread's copy of `transport`.
template<typename Texel>
void ForEachCell(const glsl::Transport& transport,
  glm::ivec3 size,
  std::vector<glm::vec4>& out,
  Texel texel)
{
  out.resize(std::size_t(size.x) * size.y * size.z);
  vtkSMPTools::For(0,
    vtkIdType(size.z),
    [&](vtkIdType begin, vtkIdType end)
    {
      glsl::Transport t = transport;
      for (vtkIdType k = begin; k < end; ++k)
        for (int j = 0; j < size.y; ++j)
          for (int i = 0; i < size.x; ++i)
            out[(std::size_t(k) * size.y + j) * size.x + std::size_t(i)] =
              texel(t, glm::ivec3(i, j, int(k)));
    });
}
}

glm::ivec3 ScatteringVolumeSize(glm::ivec3 n)
{
  return (glm::max(n, 1) - 1 + (ScatteringVolumeDivisor - 1)) / ScatteringVolumeDivisor + 1;
}

std::vector<glm::ivec3> ScatteringGrids(glm::ivec3 fieldDimensions)
{
  std::vector<glm::ivec3> grids = { ScatteringVolumeSize(fieldDimensions) };
  while (std::min({ grids.back().x, grids.back().y, grids.back().z }) > 5)
  {
    grids.push_back(grids.back() / 2 + 1); // half the cells, (n - 1) / 2 rounded up
  }
  std::reverse(grids.begin(), grids.end());
  return grids;
}

glm::vec3 ScatteringCellSize(const MarchUniforms& u, glm::ivec3 size)
{
  const glm::vec3 spacing =
    glm::vec3(glm::max(u.Dimensions - 1, 1)) / glm::vec3(glm::max(size - 1, 1));
  return spacing *
    glm::vec3(glm::length(glm::vec3(u.IndexToLocal[0])),
      glm::length(glm::vec3(u.IndexToLocal[1])),
      glm::length(glm::vec3(u.IndexToLocal[2])));
}

void ComputeScatteringVolume(const MarchUniforms& u,
  ScatteringGrid& volume,
  const ScatteringSolve& solve)
{
  glsl::Transport transport = TransportOf(u);
  ScatteringGrid coarse;
  const std::vector<glm::ivec3> grids = ScatteringGrids(u.Dimensions);
  for (std::size_t level = 0; level < grids.size(); ++level)
  {
    ScatteringGrid grid;
    grid.Size = grids[level];
    transport.Grid = &grid;
    transport.Coarse = &coarse;
    transport.ScatteringVolumeSize = glm::vec3(grid.Size);
    transport.ScatteringCoarseSize = glm::vec3(coarse.Size);
    transport.ScatteringCellSize = ScatteringCellSize(u, grid.Size);
    ForEachCell(transport,
      grid.Size,
      grid.Medium,
      [](glsl::Transport& t, glm::ivec3 c) { return t.ScatteringMediumTexel(glm::vec3(c)); });
    std::vector<glm::vec4> directions(grid.Medium.size());
    ForEachCell(transport,
      grid.Size,
      grid.Source,
      [&](glsl::Transport& t, glm::ivec3 c)
      {
        glm::vec4 source, direction;
        const std::size_t i = glsl::CellIndex(grid, c);
        t.ScatteringSourceTexel(glm::vec3(c), grid.Medium[i], source, direction);
        directions[i] = direction;
        return source;
      });
    grid.Direction = std::move(directions);
    if (level == 0)
      ForEachCell(transport,
        grid.Size,
        grid.Fluence,
        [&](glsl::Transport& t, glm::ivec3 c)
        { return t.ScatteringStartTexel(glm::vec3(c), grid.Medium[glsl::CellIndex(grid, c)]); });
    else
      ForEachCell(transport,
        grid.Size,
        grid.Fluence,
        [](glsl::Transport& t, glm::ivec3 c) { return t.ScatteringProlongTexel(glm::vec3(c)); });
    const int sweeps = level == 0 ? solve.CoarsestSweeps : solve.SweepsPerGrid;
    std::vector<glm::vec4> next;
    for (int sweep = 0; sweep < sweeps; ++sweep)
      for (int parity = 0; parity < 2; ++parity)
      {
        ForEachCell(transport,
          grid.Size,
          next,
          [parity](glsl::Transport& t, glm::ivec3 c) { return t.ScatteringRelaxTexel(c, parity); });
        grid.Fluence.swap(next);
      }
    if (level + 1 == grids.size())
      ForEachCell(transport,
        grid.Size,
        grid.Flux,
        [](glsl::Transport& t, glm::ivec3 c) { return t.ScatteringFluxTexel(c); });
    coarse = std::move(grid);
  }
  volume = std::move(coarse);
}

} // namespace cloudvis
