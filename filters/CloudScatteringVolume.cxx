// The multiple-scattering volume on the CPU (CloudScatteringVolume.h): its inputs per grid, the
// solve from them, and the same over the pieces of a distributed field, where each piece computes
// the whole field's inputs for the cells it owns and every piece solves their sum.
#include "CloudScatteringVolume.h"

#include "CloudLightVolumes.h"
#include "CloudOpticalDepthGrid.h"
#include "CloudTransport.h"

#include <vtkImageData.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

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

namespace
{

// The field of u (its Dimensions and the lengths of IndexToLocal's axes).
ScatteringField ScatteringFieldOf(const MarchUniforms& u)
{
  ScatteringField field;
  field.Dimensions = u.Dimensions;
  field.VoxelSize = glm::vec3(glm::length(glm::vec3(u.IndexToLocal[0])),
    glm::length(glm::vec3(u.IndexToLocal[1])),
    glm::length(glm::vec3(u.IndexToLocal[2])));
  return field;
}
}

glm::vec3 ScatteringCellSize(const ScatteringField& field, glm::ivec3 size)
{
  const glm::vec3 spacing =
    glm::vec3(glm::max(field.Dimensions - 1, 1)) / glm::vec3(glm::max(size - 1, 1));
  return spacing * field.VoxelSize;
}

glm::vec3 ScatteringCellSize(const MarchUniforms& u, glm::ivec3 size)
{
  return ScatteringCellSize(ScatteringFieldOf(u), size);
}

namespace
{
// Points `transport` at grid `level` of `grids` (the one computed, and the coarser one's fluence).
void SetGrid(glsl::Transport& transport,
  const ScatteringField& field,
  const ScatteringGrid& grid,
  const ScatteringGrid& coarse)
{
  transport.Grid = &grid;
  transport.Coarse = &coarse;
  transport.ScatteringVolumeSize = glm::vec3(grid.Size);
  transport.ScatteringCoarseSize = glm::vec3(coarse.Size);
  transport.ScatteringCellSize = ScatteringCellSize(field, grid.Size);
}

// Sizes `grid`'s inputs (its first guess too when `start`) and runs texel(t, c, n) over its cells
// (n the cell's index), with this thread's copy of `transport`.
template<typename Texel>
void ForEachInput(const glsl::Transport& transport, ScatteringGrid& grid, bool start, Texel texel)
{
  const std::size_t cells = std::size_t(grid.Size.x) * grid.Size.y * grid.Size.z;
  grid.Medium.assign(cells, glm::vec4(0.0f));
  grid.Source.assign(cells, glm::vec4(0.0f));
  grid.Direction.assign(cells, glm::vec4(0.0f));
  grid.Fluence.assign(start ? cells : 0, glm::vec4(0.0f));
  vtkSMPTools::For(0,
    vtkIdType(grid.Size.z),
    [&](vtkIdType begin, vtkIdType end)
    {
      glsl::Transport t = transport;
      for (vtkIdType k = begin; k < end; ++k)
        for (int j = 0; j < grid.Size.y; ++j)
          for (int i = 0; i < grid.Size.x; ++i)
          {
            const glm::ivec3 c(i, j, int(k));
            texel(t, c, glsl::CellIndex(grid, c));
          }
    });
}

// The inputs for u's field, table, phase and lights (as ComputeScatteringVolume).
void ComputeScatteringInputs(const MarchUniforms& u, ScatteringInputs& inputs)
{
  glsl::Transport transport = TransportOf(u);
  const ScatteringField field = ScatteringFieldOf(u);
  const std::vector<glm::ivec3> grids = ScatteringGrids(u.Dimensions);
  inputs.assign(grids.size(), ScatteringGrid());
  const ScatteringGrid none;
  for (std::size_t level = 0; level < grids.size(); ++level)
  {
    ScatteringGrid& grid = inputs[level];
    grid.Size = grids[level];
    SetGrid(transport, field, grid, none);
    const bool start = level == 0;
    ForEachInput(transport,
      grid,
      start,
      [&grid, start](glsl::Transport& t, glm::ivec3 c, std::size_t n)
      {
        grid.Medium[n] = t.ScatteringMediumTexel(glm::vec3(c));
        t.ScatteringSourceTexel(glm::vec3(c), grid.Medium[n], grid.Source[n], grid.Direction[n]);
        if (start)
          grid.Fluence[n] = t.ScatteringStartTexel(glm::vec3(c), grid.Medium[n]);
      });
  }
}

// The relaxation and prolongation from given inputs, coarse to fine, and the finest grid's flux:
// `volume` is the finest grid with its Fluence and Flux. Deterministic: the same inputs give the
// same floats on any machine's CPU, whatever its threads.
void SolveScatteringVolume(const LightingParameters& lighting,
  const ScatteringField& field,
  ScatteringInputs inputs,
  ScatteringGrid& volume,
  const ScatteringSolve& solve)
{
  glsl::Transport transport = TransportOf(lighting);
  ScatteringGrid coarse;
  for (std::size_t level = 0; level < inputs.size(); ++level)
  {
    ScatteringGrid grid = std::move(inputs[level]);
    SetGrid(transport, field, grid, coarse);
    if (level > 0)
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
    if (level + 1 == inputs.size())
      ForEachCell(transport,
        grid.Size,
        grid.Flux,
        [](glsl::Transport& t, glm::ivec3 c) { return t.ScatteringFluxTexel(c); });
    coarse = std::move(grid);
  }
  volume = std::move(coarse);
}
} // namespace

void ComputeScatteringVolume(const MarchUniforms& u,
  ScatteringGrid& volume,
  const ScatteringSolve& solve)
{
  ScatteringInputs inputs;
  ComputeScatteringInputs(u, inputs);
  SolveScatteringVolume(u.Lighting, ScatteringFieldOf(u), std::move(inputs), volume, solve);
}

// ---- Across the pieces of a distributed field ----

namespace
{
// The whole field's ScatteringField in the frame a renderer of the whole would march in.
ScatteringField WholeScatteringField(const VolumeGeometry& whole)
{
  const glm::mat4 indexToLocal(MakeLocalFrame(whole).IndexToLocal);
  ScatteringField field;
  field.Dimensions = whole.Dimensions;
  field.VoxelSize = glm::vec3(glm::length(glm::vec3(indexToLocal[0])),
    glm::length(glm::vec3(indexToLocal[1])),
    glm::length(glm::vec3(indexToLocal[2])));
  return field;
}

MarchProblem GeometryProblem(std::string message)
{
  MarchProblem problem;
  problem.Input = MarchInput::Geometry;
  problem.Message = std::move(message);
  return problem;
}
}

VolumeGeometry WholeFieldGeometry(vtkImageData* piece,
  vtkMatrix4x4* volumeMatrix,
  const int wholeExtent[6])
{
  VolumeGeometry whole = GeometryOf(piece, volumeMatrix);
  const int* extent = piece->GetExtent();
  glm::dvec3 shift(0.0);
  for (int a = 0; a < 3; ++a)
  {
    whole.Dimensions[a] = wholeExtent[2 * a + 1] - wholeExtent[2 * a] + 1;
    shift[a] = double(wholeExtent[2 * a] - extent[2 * a]);
  }
  whole.IndexToWorld = whole.IndexToWorld * glm::translate(glm::dmat4(1.0), shift);
  return whole;
}

MarchProblem ComputePieceScatteringInputs(const MarchSetup& setup,
  const OpticalDepthGrid* external,
  const VolumeGeometry& whole,
  ScatteringInputs& inputs)
{
  inputs.clear();
  MarchUniforms u;
  LocalFrame frame;
  MarchProblem problem = SetUpMarch(setup, u, &frame);
  if (problem)
  {
    return problem;
  }
  // The piece's voxels are the whole field's, moved by whole voxels: its index points are the
  // whole's less `offset`, exactly, so every piece judges a cell's owner on the same floats.
  const glm::dmat4 pieceToWhole = glm::inverse(whole.IndexToWorld) * setup.Geometry.IndexToWorld;
  glm::ivec3 offset(0);
  for (int a = 0; a < 3; ++a)
  {
    for (int r = 0; r < 3; ++r)
    {
      if (std::abs(pieceToWhole[a][r] - (a == r ? 1.0 : 0.0)) > 1e-6)
      {
        return GeometryProblem("the piece's voxels are not the whole field's: its spacing or "
                               "direction differs");
      }
    }
    offset[a] = int(std::lround(pieceToWhole[3][a]));
    if (std::abs(pieceToWhole[3][a] - offset[a]) > 1e-6 || offset[a] < 0 ||
      offset[a] + setup.Geometry.Dimensions[a] > whole.Dimensions[a])
    {
      return GeometryProblem("the piece's voxels are not a sub-grid of the whole field's extent");
    }
  }
  if (external)
  {
    problem.Message = ValidateOpticalDepthGrid(*external, int(u.Lights.size()));
    if (problem)
    {
      return problem;
    }
    SetExternalOpticalDepths(u, frame, external);
  }
  // The source reads the light volumes when the march does, as the piece's own volume would.
  LightVolumes lightVolumes;
  if (u.Lighting.Model == LightingModel::March &&
    u.Lighting.Transmittance == LightTransmittance::Volumes)
  {
    ComputeLightVolumes(u, lightVolumes);
    u.LightDepths = &lightVolumes;
  }

  glsl::Transport transport = TransportOf(u);
  const ScatteringField field = WholeScatteringField(whole);
  // Whole-field local units per piece-local unit (a power of two, 1 when the voxels are the same).
  const float perPiece = float(frame.Unit / MakeLocalFrame(whole).Unit);
  const glm::vec3 wholeLast = glm::vec3(whole.Dimensions) - 1.0f;
  const glm::ivec3 pieceLast = setup.Geometry.Dimensions - 1;
  const std::vector<glm::ivec3> grids = ScatteringGrids(whole.Dimensions);
  inputs.assign(grids.size(), ScatteringGrid());
  for (std::size_t level = 0; level < grids.size(); ++level)
  {
    ScatteringGrid& grid = inputs[level];
    grid.Size = grids[level];
    transport.ScatteringVolumeSize = glm::vec3(grid.Size);
    transport.ScatteringCellSize = ScatteringCellSize(field, grid.Size) / perPiece;
    // As IndexOfGridTexel and ScatteringMediumTexel compute them for the whole field.
    const glm::vec3 spacing = wholeLast / glm::max(glm::vec3(grid.Size) - 1.0f, glm::vec3(1.0f));
    const glm::vec3 quarter = 0.25f * spacing;
    const bool start = level == 0;
    ForEachInput(transport,
      grid,
      start,
      [&](glsl::Transport& t, glm::ivec3 c, std::size_t n)
      {
        const glm::vec3 p = glm::vec3(c) * spacing - glm::vec3(offset);
        for (int a = 0; a < 3; ++a)
        {
          const bool endsWhole = offset[a] + pieceLast[a] == whole.Dimensions[a] - 1;
          if (p[a] < 0.0f || p[a] > float(pieceLast[a]) ||
            (p[a] == float(pieceLast[a]) && !endsWhole))
          {
            return; // another piece's cell, or no piece's
          }
        }
        const glm::vec4 medium = t.ScatteringMediumAround(p, quarter);
        glm::vec4 source, direction;
        t.ScatteringSourceAt(p, medium, source, direction);
        grid.Medium[n] = glm::vec4(glm::vec3(medium), medium.w / perPiece);
        grid.Source[n] = source / perPiece;
        grid.Direction[n] = direction;
        if (start)
          grid.Fluence[n] = t.ScatteringStartAt(p, medium);
      });
  }
  return {};
}

std::size_t ScatteringInputValues(glm::ivec3 wholeDimensions)
{
  // Three vec4 per cell of every grid, and the coarsest grid's first guess.
  const std::vector<glm::ivec3> grids = ScatteringGrids(wholeDimensions);
  std::size_t values = 0;
  for (const glm::ivec3& size : grids)
    values += 12 * std::size_t(size.x) * size.y * size.z;
  return values + 4 * std::size_t(grids.front().x) * grids.front().y * grids.front().z;
}

std::vector<float> PackScatteringInputs(const ScatteringInputs& inputs)
{
  std::vector<float> values;
  const auto append = [&values](const std::vector<glm::vec4>& texels)
  {
    for (const glm::vec4& texel : texels)
      values.insert(values.end(), { texel.x, texel.y, texel.z, texel.w });
  };
  for (const ScatteringGrid& grid : inputs)
  {
    append(grid.Medium);
    append(grid.Source);
    append(grid.Direction);
  }
  if (!inputs.empty())
    append(inputs.front().Fluence);
  return values;
}

bool UnpackScatteringInputs(const std::vector<float>& values,
  const VolumeGeometry& whole,
  ScatteringInputs& inputs)
{
  if (values.size() != ScatteringInputValues(whole.Dimensions))
    return false;
  const std::vector<glm::ivec3> grids = ScatteringGrids(whole.Dimensions);
  inputs.assign(grids.size(), ScatteringGrid());
  std::size_t next = 0;
  const auto take = [&](std::vector<glm::vec4>& texels, glm::ivec3 size)
  {
    texels.resize(std::size_t(size.x) * size.y * size.z);
    for (glm::vec4& texel : texels)
    {
      texel = glm::vec4(values[next], values[next + 1], values[next + 2], values[next + 3]);
      next += 4;
    }
  };
  for (std::size_t level = 0; level < grids.size(); ++level)
  {
    ScatteringGrid& grid = inputs[level];
    grid.Size = grids[level];
    take(grid.Medium, grid.Size);
    take(grid.Source, grid.Size);
    take(grid.Direction, grid.Size);
  }
  take(inputs.front().Fluence, grids.front());
  return true;
}

WholeFieldScattering SolveWholeFieldScattering(const LightingParameters& lighting,
  const VolumeGeometry& whole,
  ScatteringInputs inputs,
  const ScatteringSolve& solve)
{
  WholeFieldScattering result;
  result.Field = whole;
  SolveScatteringVolume(
    lighting, WholeScatteringField(whole), std::move(inputs), result.Volume, solve);
  // The march reads the fluence and the flux alone.
  for (auto* texels : { &result.Volume.Medium, &result.Volume.Source, &result.Volume.Direction })
    std::vector<glm::vec4>().swap(*texels);
  return result;
}

void SetExternalScatteringVolume(MarchUniforms& u,
  const LocalFrame& frame,
  const WholeFieldScattering* volume)
{
  u.ExternalScattering = volume && !volume->Empty() ? volume : nullptr;
  u.IndexToScattering = glm::mat4(1.0f);
  if (!u.ExternalScattering)
  {
    return;
  }
  // The piece's index point to the world, to the whole field's index point, to its grid's texel
  // coordinate (corner-aligned), composed in double.
  glm::dmat4 localToWorld(frame.Unit);
  localToWorld[3] = glm::dvec4(frame.Anchor, 1.0);
  glm::dmat4 wholeIndexToTexel(1.0);
  for (int a = 0; a < 3; ++a)
  {
    wholeIndexToTexel[a][a] =
      double(volume->Volume.Size[a] - 1) / double(std::max(volume->Field.Dimensions[a] - 1, 1));
  }
  u.IndexToScattering = glm::mat4(wholeIndexToTexel * glm::inverse(volume->Field.IndexToWorld) *
    localToWorld * frame.IndexToLocal);
}

} // namespace cloudvis
