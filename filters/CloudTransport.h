// The CPU side of the shared light-transport source, shaders/transport/ (the GPU
// splices the same file into its shaders; docs/transport.md explains both). That file is included
// here inside the body of cloudvis::glsl::Transport: its uniforms become the struct's members,
// with the GLSL's names, and its functions the struct's member functions, so the C++ calls the
// very functions the shaders run. What the two languages spell differently is defined here:
// - the C++ prelude: INOUT(T) and OUT(T) are references, UNIFORM is empty, and glm's names
//   (vec3, mix, clamp, dot, exp...) are visible unqualified inside namespace cloudvis::glsl;
// - the accessors the shared file declares (DensityAt, TransferAt, EmptyBricksAround,
//   BrickExtinctionBounds, LightVolumeFetch, ExternalDepthFetch...), which read from memory what
//   the GLSL reads from textures: the GL_LINEAR fetches are computed exactly (the GPU's filter
//   weights have 8 fractional bits);
// - SourceTerm, which sums one model's light terms over the lights in a loop where the GPU's
//   program calls each light's term with a constant index (app/rendering/CloudMarchShader.cxx).
// A Transport (about a kilobyte) is filled from the uniforms SetUpMarch computes (TransportOf);
// it is per thread, since the path tracer counts its density reads in it, as the GLSL does in
// globals. The public entry points (MarchRay, TracePath, ComputeLightVolumes, HenyeyGreenstein...)
// are thin wrappers in CloudReferenceMarch.h, CloudPathTrace.h, CloudLightVolumes.h and
// CloudLighting.h.
#ifndef CloudTransport_h
#define CloudTransport_h

#include "CloudDropletOptics.h"
#include "CloudLighting.h"
#include "CloudMarchUniforms.h"
#include "CloudOpticalDepthGrid.h"
#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace cloudvis
{

// ---- What the accessors read besides the march's uniforms ----

// The CPU's light volumes (CloudLightVolumes.h): every light's block of optical depths, as the
// GPU's texture holds them: Size.x * Size.y * (Size.z * lights) floats, x fastest, light i's block
// from z = i * Size.z.
struct LightVolumes
{
  glm::ivec3 Size{ 0 };
  int Lights = 0;
  std::vector<float> Depth;
};

// The CPU's multiple-scattering grid (CloudScatteringVolume.h) as the GPU's textures hold it:
// per cell, x fastest, Size.x * Size.y * Size.z texels each. Medium: albedo in rgb, sigma_t per
// local unit in a; Source: the diffuse source Q0 in rgb; Direction: the beams' mean direction of
// travel in xyz; Fluence: the diffuse fluence in rgb.
struct ScatteringGrid
{
  glm::ivec3 Size{ 0 };
  std::vector<glm::vec4> Medium, Source, Direction, Fluence, Flux;
};

// What the path tracer reads besides the march's uniforms.

struct CLOUDVISFILTERS_EXPORT PathTraceUniforms
{
  // The bounds of sigma_t per occupancy brick: the largest (the majorant, vtkCloudOccupancyFilter's
  // "max_extinction") and the smallest (the minorant, "min_extinction") any trilinear sample in
  // the brick can have, per local unit (the filter's values per world unit times the march's
  // ExtinctionUnit, as Optical scales the table's); BrickCount.x * .y * .z values each, x
  // fastest. Brick b covers index points [b * BrickSize, (b + 1) * BrickSize) along each axis.
  const float* BrickMajorant = nullptr;
  const float* BrickMinorant = nullptr;
  // Per brick, the Chebyshev distance in bricks to the nearest occupied one ("empty_distance"):
  // a walk in an empty brick at distance k leaps out of the (2k - 1)^3 empty block around it.
  const unsigned char* BrickEmptyDistance = nullptr;
  glm::ivec3 BrickCount{ 0 };
  float BrickSize = 1.0f;
  // Scattering events a path may have (1: single scattering); the path ends at the next one.
  int MaxBounces = 1;
  // Russian roulette from this many scattering events on, with the survival probability the
  // largest component of the throughput (so an albedo-1 path is never killed by it).
  int RouletteBounces = 3;
  // 1: each scattering event also estimates the next event's direct light along a direction
  // drawn toward the lights, weighed with the walk's own by multiple importance sampling
  // (LightGuidedNextEvent in shaders/transport/PathTrace.glsl); 0: the plain estimator.
  int LightGuidedNextEvents = 0;
};

// Whether the path tracer guides next events toward the lights unless told otherwise: for the
// droplets' phase, whose forward peak (thousands per steradian) makes the plain estimator's
// noise explode on thick clouds; not for the two lobes, whose peak is low enough that the extra
// shadow ray costs as much as it saves (docs/lighting.md, "The estimators").
inline bool GuidesNextEventsByDefault(const LightingParameters& p)
{
  return p.Phase == PhaseModel::Droplets;
}

// The edge of the majorant bricks, in cells, that renders path-trace with by default
// (vtkCloudPathTracer's BrickSize, and the app's GPU mapper for the pathtrace model): the fastest
// on the shipped scenes (docs/performance.md).
constexpr int PathTraceBrickSize = 8;

// Ratio tracking plays Russian roulette once its running transmittance falls below this: a
// path in deep shadow stops early, unbiased (it survives with probability T / threshold and
// then carries the threshold).
constexpr float RatioTrackingRouletteThreshold = 0.1f;

// The ray parameter of the faces a walk never crosses (its direction is parallel to them).
constexpr float NoCrossing = 1e30f;

// A bound on the tentative collisions of one tracking call. Real media stay far below it (the
// shipped scenes need at most a few hundred: majorant minus minorant times the length); an
// extinction so large that float t cannot advance (a majorant above ~1e7 / t) would otherwise
// loop forever. Beyond it, free flight gives up (GaveUp) and ends the path, and ratio tracking
// returns a transmittance of 0: the ray is treated as opaque.
constexpr int MaxTentativeCollisions = 1 << 16;
constexpr float GaveUp = -1.0f;

// A bound on the turns of one search for the next occupied brick, far above the bricks any ray
// crosses (3 x 2^16 / 2 for the largest field the mapper takes): the walk ends by itself; this only
// keeps a GPU from hanging should rounding ever stall it.
constexpr int MaxWalkSteps = 1 << 18;

namespace glsl
{
using namespace glm;
using uint = glm::uint;

// The C++ prelude of the shared source (shaders/transport/Prelude.glsl is the GLSL's).
#define INOUT(T) T&
#define OUT(T) T&
#define UNIFORM
#define MAX_LIGHTS LightingLimits::MaxLights

struct Transport
{
// The shared source leaves some parameters unused (a model's term takes every term's arguments).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include "../shaders/transport/DropletPhase.glsl"
#include "../shaders/transport/LightMarch.glsl"
#include "../shaders/transport/LightingModels.glsl"
#include "../shaders/transport/Medium.glsl"
#include "../shaders/transport/PathTrace.glsl"
#include "../shaders/transport/Phase.glsl"
#include "../shaders/transport/Scattering.glsl"
#pragma GCC diagnostic pop

  // ---- C++ only ----

  // Where the accessors read: the march's uniforms (the field's texels, the transfer table), and
  // when set the path tracer's brick bounds and the CPU's light volumes.
  const MarchUniforms* March = nullptr;
  const PathTraceUniforms* PathTrace = nullptr;
  const LightVolumes* Volumes = nullptr;
  // The optical depths from outside the field (CloudOpticalDepthGrid.h), when given.
  const OpticalDepthGrid* External = nullptr;
  // The multiple-scattering grid being computed, the next coarser one (its Fluence), and the one
  // the march reads.
  const ScatteringGrid* Grid = nullptr;
  const ScatteringGrid* Coarse = nullptr;
  const ScatteringGrid* Scattering = nullptr;
  // The droplets' phase table (PhaseType PhaseDroplets).
  const DropletPhaseTable* DropletTable = nullptr;
  LightingModel Model = LightingModel::None;

  // The source term of Model at index point p: the GLSL's SourceTerm, which the mapper generates
  // per program with one call per light (CloudMarchShader.cxx), as a loop over the lights.
  vec3 SourceTerm(vec3 p, float density, vec3 albedo, vec3 d)
  {
    if (this->Model != LightingModel::Derivative && this->Model != LightingModel::March)
    {
      return SourceTermNone(p, density, albedo, d);
    }
    vec3 light = Ambient;
    for (int i = 0; i < LightCount; ++i)
    {
      const bool point = LightPositional[i] != 0;
      if (this->Model == LightingModel::Derivative)
      {
        light += point ? DerivativePointTerm(i, p, density, albedo, d)
                       : DerivativeDirectionalTerm(i, p, density, albedo, d);
      }
      else
      {
        light += point ? MarchPointTerm(i, p, density, albedo, d)
                       : MarchDirectionalTerm(i, p, density, albedo, d);
      }
    }
    if (this->Model == LightingModel::March && ScatteringVolumeOn != 0)
    {
      light += MultipleScatteringTerm(p, d);
    }
    return albedo * light;
  }
};

#undef INOUT
#undef OUT
#undef UNIFORM
#undef MAX_LIGHTS

// ---- The C++ accessors ----

namespace fetch
{
// GL_LINEAR with CLAMP_TO_EDGE at texel coordinate t of a grid of n texels (x fastest), read by
// `texel(i, j, k)`: the texels floor(t) and floor(t) + 1 on each axis, clamped to [0, n - 1],
// weighted by fract(t), computed exactly.
template<typename Texel>
float Trilinear(glm::vec3 t, glm::ivec3 n, Texel texel)
{
  int i0[3] = {}, i1[3] = {}; // (initialised: GCC cannot see that the loop sets every element)
  float f[3] = {};
  for (int a = 0; a < 3; ++a)
  {
    const float fl = std::floor(t[a]);
    f[a] = t[a] - fl;
    const float last = float(n[a] - 1);
    i0[a] = static_cast<int>(std::min(std::max(fl, 0.0f), last));
    i1[a] = static_cast<int>(std::min(std::max(fl + 1.0f, 0.0f), last));
  }
  const auto lerp = [](float a, float b, float w) { return a + w * (b - a); };
  const float c00 = lerp(texel(i0[0], i0[1], i0[2]), texel(i1[0], i0[1], i0[2]), f[0]);
  const float c10 = lerp(texel(i0[0], i1[1], i0[2]), texel(i1[0], i1[1], i0[2]), f[0]);
  const float c01 = lerp(texel(i0[0], i0[1], i1[2]), texel(i1[0], i0[1], i1[2]), f[0]);
  const float c11 = lerp(texel(i0[0], i1[1], i1[2]), texel(i1[0], i1[1], i1[2]), f[0]);
  return lerp(lerp(c00, c10, f[1]), lerp(c01, c11, f[1]), f[2]);
}

inline std::size_t BrickIndex(const PathTraceUniforms& pt, glm::ivec3 brick)
{
  return (std::size_t(brick.z) * pt.BrickCount.y + brick.y) * pt.BrickCount.x + brick.x;
}
}

// The density texture's fetch at (p + 0.5) / Dimensions is texel coordinate p: the normalized
// texels are interpolated, then scaled to the data's units, as the GLSL does.
inline float Transport::DensityAt(vec3 p)
{
  const MarchUniforms& u = *this->March;
  const float filtered = fetch::Trilinear(p,
    u.Dimensions,
    [&u](int x, int y, int z)
    {
      return NormalizedTexel(
        u.Density, (std::size_t(z) * u.Dimensions.y + y) * u.Dimensions.x + std::size_t(x));
    });
  return filtered * DensityScale + DensityBias;
}

inline vec4 Transport::TransferAt(float density)
{
  return this->March->Table->Lookup(density);
}

inline vec3 Transport::DropletPhaseNode(int i)
{
  return this->DropletTable->Phase[std::size_t(i)];
}

inline vec3 Transport::DropletCdfNode(int i)
{
  return this->DropletTable->CDF[std::size_t(i)];
}

// No occupancy without the path tracer's bricks: the CPU march reads every sample.
inline float Transport::EmptyBricksAround(vec3 brick)
{
  const PathTraceUniforms* pt = this->PathTrace;
  return pt && pt->BrickEmptyDistance
    ? float(pt->BrickEmptyDistance[fetch::BrickIndex(*pt, ivec3(brick))])
    : 0.0f;
}

inline vec2 Transport::BrickExtinctionBounds(ivec3 brick)
{
  const std::size_t index = fetch::BrickIndex(*this->PathTrace, brick);
  return vec2(this->PathTrace->BrickMinorant[index], this->PathTrace->BrickMajorant[index]);
}

// The corner alignment keeps t within [0, size - 1], so the interpolation never reads another
// light's block.
inline float Transport::LightVolumeFetch(int i, vec3 t)
{
  const LightVolumes& volumes = *this->Volumes;
  const ivec3 size = volumes.Size;
  const std::size_t block = std::size_t(i) * size.z;
  return fetch::Trilinear(t,
    size,
    [&](int x, int y, int z)
    { return volumes.Depth[((block + std::size_t(z)) * size.y + y) * size.x + std::size_t(x)]; });
}

// As LightVolumeFetch: t within [0, size - 1] keeps to light i's block.
inline float Transport::ExternalDepthFetch(int i, vec3 t)
{
  const OpticalDepthGrid& grid = *this->External;
  const ivec3 size(grid.Size[0], grid.Size[1], grid.Size[2]);
  const std::size_t block = std::size_t(i) * size.z;
  return fetch::Trilinear(t,
    size,
    [&](int x, int y, int z)
    { return grid.Depths[((block + std::size_t(z)) * size.y + y) * size.x + std::size_t(x)]; });
}

inline std::size_t CellIndex(const ScatteringGrid& grid, ivec3 c)
{
  return (std::size_t(c.z) * grid.Size.y + c.y) * grid.Size.x + std::size_t(c.x);
}

inline vec4 Transport::ScatteringMediumAt(ivec3 c)
{
  return this->Grid->Medium[CellIndex(*this->Grid, c)];
}

inline vec4 Transport::ScatteringSourceAt(ivec3 c)
{
  return this->Grid->Source[CellIndex(*this->Grid, c)];
}

inline vec4 Transport::ScatteringDirectionAt(ivec3 c)
{
  return this->Grid->Direction[CellIndex(*this->Grid, c)];
}

inline vec4 Transport::ScatteringFluenceAt(ivec3 c)
{
  return this->Grid->Fluence[CellIndex(*this->Grid, c)];
}

namespace fetch
{
// GL_LINEAR of one of a grid's textures at texel coordinate t, per component.
inline vec4 GridTrilinear(const ScatteringGrid& grid, const std::vector<vec4>& texels, vec3 t)
{
  vec4 result;
  for (int channel = 0; channel < 4; ++channel)
  {
    result[channel] = Trilinear(t,
      grid.Size,
      [&](int x, int y, int z) { return texels[CellIndex(grid, ivec3(x, y, z))][channel]; });
  }
  return result;
}

inline vec4 FluenceTrilinear(const ScatteringGrid& grid, vec3 t)
{
  return GridTrilinear(grid, grid.Fluence, t);
}
}

inline vec4 Transport::CoarseFluenceFetch(vec3 t)
{
  return fetch::FluenceTrilinear(*this->Coarse, t);
}

inline vec4 Transport::ScatteringVolumeFetch(vec3 t)
{
  return fetch::FluenceTrilinear(*this->Scattering, t);
}

inline vec4 Transport::ScatteringFluxFetch(vec3 t)
{
  return fetch::GridTrilinear(*this->Scattering, this->Scattering->Flux, t);
}

} // namespace glsl

// The shared source's uniforms for the march's uniforms `u`, as the mapper uploads them
// (CloudMarchShader.cxx): the field, the lights, the lighting parameters and model, and the light
// volumes when u.LightDepths is set and the march reads them, the optical depths from outside
// the field when u.ExternalDepths is set. No occupancy: the CPU march reads
// every sample (SkipEmptySpace 0).
CLOUDVISFILTERS_EXPORT glsl::Transport TransportOf(const MarchUniforms& u);
// The same with the path tracer's bricks and bounces (`pt` must outlive the result).
CLOUDVISFILTERS_EXPORT glsl::Transport TransportOf(const MarchUniforms& u,
  const PathTraceUniforms& pt);
// Only the phase function's and the octaves' uniforms, from lighting parameters.
CLOUDVISFILTERS_EXPORT glsl::Transport TransportOf(const LightingParameters& p);

} // namespace cloudvis

#endif
