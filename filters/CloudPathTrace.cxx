#include "CloudPathTrace.h"

#include <algorithm>
#include <cmath>

namespace cloudvis
{

// ---- Random numbers ----

glm::uvec4 Pcg4d(glm::uvec4 v)
{
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  return v;
}

float NextRandom(RandomStream& rng)
{
  const glm::uvec4 h = Pcg4d(glm::uvec4(rng.Pixel, rng.Sample, rng.Dimension, rng.Seed));
  rng.Dimension += 1u;
  return float(h.x >> 8u) * (1.0f / 16777216.0f);
}

// ---- The majorant walk ----

BrickWalk BeginBrickWalk(const PathTraceUniforms& pt, glm::vec3 p, glm::vec3 direction, float t)
{
  const glm::vec3 q = p + t * direction;
  const glm::bvec3 parallel = glm::equal(direction, glm::vec3(0.0f)); // never crosses that axis
  const glm::vec3 safe = glm::mix(direction, glm::vec3(1.0f), parallel);
  BrickWalk walk;
  walk.Brick =
    glm::clamp(glm::ivec3(glm::floor(q / pt.BrickSize)), glm::ivec3(0), pt.BrickCount - 1);
  walk.Step = glm::ivec3(glm::sign(direction));
  // The face ahead along each axis: the brick's upper face when moving up, its lower one else.
  // Not before t: q may lie a rounding error outside the (clamped) brick.
  const glm::vec3 face = (glm::vec3(walk.Brick) + glm::step(0.0f, direction)) * pt.BrickSize;
  walk.TNext =
    glm::mix(glm::max(t + (face - q) / safe, glm::vec3(t)), glm::vec3(NoCrossing), parallel);
  walk.TDelta = glm::mix(pt.BrickSize / glm::abs(safe), glm::vec3(NoCrossing), parallel);
  return walk;
}

float BrickExit(const BrickWalk& walk)
{
  return std::min(std::min(walk.TNext.x, walk.TNext.y), walk.TNext.z);
}

bool AdvanceBrickWalk(const PathTraceUniforms& pt, BrickWalk& walk)
{
  // Every axis whose face is crossed first moves on (two or three at an edge or a corner).
  const glm::bvec3 crossed = glm::lessThanEqual(walk.TNext, glm::vec3(BrickExit(walk)));
  walk.Brick += glm::ivec3(crossed) * walk.Step;
  walk.TNext += glm::vec3(crossed) * walk.TDelta;
  return glm::all(glm::greaterThanEqual(walk.Brick, glm::ivec3(0))) &&
    glm::all(glm::lessThan(walk.Brick, pt.BrickCount));
}

glm::vec2 BrickExtinctionBounds(const PathTraceUniforms& pt, glm::ivec3 brick)
{
  const std::size_t index =
    (std::size_t(brick.z) * pt.BrickCount.y + brick.y) * pt.BrickCount.x + brick.x;
  return glm::vec2(pt.BrickMinorant[index], pt.BrickMajorant[index]);
}

float EmptyBricksAround(const PathTraceUniforms& pt, glm::ivec3 brick)
{
  const std::size_t index =
    (std::size_t(brick.z) * pt.BrickCount.y + brick.y) * pt.BrickCount.x + brick.x;
  return float(pt.BrickEmptyDistance[index]);
}

bool LeapEmptyBricks(
  const PathTraceUniforms& pt, glm::vec3 p, glm::vec3 direction, BrickWalk& walk, float& t)
{
  const float emptyBricks = EmptyBricksAround(pt, walk.Brick);
  if (emptyBricks < 2.0f)
  {
    return false; // occupied, or next to an occupied brick: the walk steps one brick
  }
  const glm::vec3 lo = (glm::vec3(walk.Brick) - (emptyBricks - 1.0f)) * pt.BrickSize;
  const glm::vec3 hi = (glm::vec3(walk.Brick) + emptyBricks) * pt.BrickSize;
  const float tLeap = IntersectBox(p, direction, lo, hi).y;
  if (!(tLeap > BrickExit(walk)))
  {
    return false; // rounding: no further than the next face
  }
  t = tLeap;
  walk = BeginBrickWalk(pt, p, direction, t);
  return true;
}

// ---- Tracking through the medium ----

bool NextOccupiedSegment(const PathTraceUniforms& pt, glm::vec3 p, glm::vec3 direction, float tEnd,
  BrickWalk& walk, float& t, float& tLeave, glm::vec2& bounds)
{
  while (t < tEnd)
  {
    if (t >= BrickExit(walk))
    {
      if (!AdvanceBrickWalk(pt, walk))
      {
        return false;
      }
      continue;
    }
    bounds = BrickExtinctionBounds(pt, walk.Brick);
    if (bounds.y > 0.0f)
    {
      tLeave = std::min(BrickExit(walk), tEnd);
      return true;
    }
    if (!LeapEmptyBricks(pt, p, direction, walk, t))
    {
      t = std::min(BrickExit(walk), tEnd);
    }
  }
  return false;
}

float SampleFreeFlight(const MarchUniforms& u, const PathTraceUniforms& pt, glm::vec3 p,
  glm::vec3 direction, float tStart, float tEnd, RandomStream& rng)
{
  BrickWalk walk = BeginBrickWalk(pt, p, direction, tStart);
  float t = tStart, tLeave;
  glm::vec2 bounds;
  int tentative = 0;
  while (NextOccupiedSegment(pt, p, direction, tEnd, walk, t, tLeave, bounds))
  {
    // Tentative collisions at rate majorant; exponential distances are memoryless, so the next
    // brick starts afresh from its face.
    for (;;)
    {
      t -= std::log(1.0f - NextRandom(rng)) / bounds.y;
      if (t >= tLeave)
      {
        break;
      }
      if (++tentative > MaxTentativeCollisions)
      {
        return GaveUp;
      }
      const float threshold = NextRandom(rng) * bounds.y;
      if (threshold < bounds.x || threshold < ExtinctionAt(u, p + t * direction))
      {
        return t; // a real collision
      }
    }
    t = tLeave;
  }
  return tEnd; // no collision before the end of the segment
}

float RouletteTransmittance(float T, RandomStream& rng)
{
  if (T >= RatioTrackingRouletteThreshold)
  {
    return T;
  }
  return NextRandom(rng) * RatioTrackingRouletteThreshold < T ? RatioTrackingRouletteThreshold
                                                              : 0.0f;
}

float RatioTrackTransmittance(const MarchUniforms& u, const PathTraceUniforms& pt, glm::vec3 p,
  glm::vec3 direction, float tStart, float tEnd, RandomStream& rng)
{
  BrickWalk walk = BeginBrickWalk(pt, p, direction, tStart);
  float T = 1.0f;
  float t = tStart, tLeave;
  glm::vec2 bounds;
  int tentative = 0;
  while (NextOccupiedSegment(pt, p, direction, tEnd, walk, t, tLeave, bounds))
  {
    const float control = bounds.x;
    const float residual = bounds.y - bounds.x;
    T = RouletteTransmittance(T * std::exp(-control * (tLeave - t)), rng);
    if (T == 0.0f)
    {
      return 0.0f;
    }
    if (residual > 0.0f)
    {
      for (;;)
      {
        t -= std::log(1.0f - NextRandom(rng)) / residual;
        if (t >= tLeave)
        {
          break;
        }
        if (++tentative > MaxTentativeCollisions)
        {
          return 0.0f;
        }
        // The bounds hold up to the rounding of a sample position: clamp at 0.
        const float sigma_t = ExtinctionAt(u, p + t * direction);
        T = RouletteTransmittance(T * std::max(1.0f - (sigma_t - control) / residual, 0.0f), rng);
        if (T == 0.0f)
        {
          return 0.0f;
        }
      }
    }
    t = tLeave;
  }
  return T;
}

// ---- Phase-function sampling ----

float SampleHenyeyGreensteinCosine(float g, float xi)
{
  if (std::abs(g) < 1e-3f)
  {
    return 1.0f - 2.0f * xi;
  }
  const float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * xi);
  return glm::clamp((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}

glm::vec3 DirectionAround(glm::vec3 axis, float mu, float phi)
{
  // An orthonormal basis around the axis without a division by a small number (Duff et al.,
  // "Building an Orthonormal Basis, Revisited", JCGT 2017).
  const float sign = axis.z >= 0.0f ? 1.0f : -1.0f;
  const float a = -1.0f / (sign + axis.z);
  const float b = axis.x * axis.y * a;
  const glm::vec3 b1(1.0f + sign * axis.x * axis.x * a, sign * b, -sign * axis.x);
  const glm::vec3 b2(b, sign + axis.y * axis.y * a, -axis.y);
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - mu * mu));
  return glm::normalize(sinTheta * std::cos(phi) * b1 + sinTheta * std::sin(phi) * b2 + mu * axis);
}

glm::vec3 SamplePhaseDirection(const LightingParameters& lighting, glm::vec3 d, RandomStream& rng)
{
  const float g = NextRandom(rng) < lighting.PhaseLobeWeight ? lighting.PhaseG1 : lighting.PhaseG2;
  const float mu = SampleHenyeyGreensteinCosine(g, NextRandom(rng));
  const float phi = 2.0f * Pi * NextRandom(rng);
  return DirectionAround(d, mu, phi);
}

// ---- Paths ----

glm::vec3 DirectLight(
  const MarchUniforms& u, const PathTraceUniforms& pt, glm::vec3 p, glm::vec3 d, RandomStream& rng)
{
  const glm::vec3 x = LocalOfIndex(u, p);
  const glm::vec3 boxHigh = glm::vec3(u.Dimensions) - 1.0f;
  glm::vec3 light(0.0f);
  for (const LocalLight& source : u.Lights)
  {
    const LightSample s = SampleLight(source, x);
    const glm::vec3 direction = LocalToIndex(u, s.Direction);
    const float tEnd = std::min(IntersectBox(p, direction, glm::vec3(0.0f), boxHigh).y, s.Distance);
    const float T = RatioTrackTransmittance(u, pt, p, direction, 0.0f, tEnd, rng);
    light += source.Radiance * s.Falloff * PhaseToRadiance *
      Phase(u.Lighting, glm::dot(d, s.Direction), 1.0f) * T;
  }
  return light;
}

glm::vec4 TracePath(const MarchUniforms& u,
  const PathTraceUniforms& pt,
  glm::vec3 nearPoint,
  glm::vec3 farPoint,
  RandomStream& rng)
{
  // The view ray as MarchRay sets it up.
  const glm::vec3 toFar = farPoint - nearPoint;
  const float rayLength = glm::length(toFar);
  glm::vec3 d = toFar / rayLength;          // direction of travel, unit
  glm::vec3 p = IndexOfLocal(u, nearPoint); // index point at t = 0
  glm::vec3 direction = LocalToIndex(u, d); // index units per local unit
  const glm::vec3 boxHigh = glm::vec3(u.Dimensions) - 1.0f;
  const glm::vec2 tBox = IntersectBox(p, direction, glm::vec3(0.0f), boxHigh);
  float tStart = std::max(tBox.x, 0.0f);
  float tEnd = std::min(tBox.y, rayLength);
  if (!(tStart < tEnd))
  {
    return glm::vec4(0.0f);
  }
  const float T = RatioTrackTransmittance(u, pt, p, direction, tStart, tEnd, rng);

  glm::vec3 radiance(0.0f);
  glm::vec3 throughput(1.0f);
  // bounce: the scattering events of the path so far.
  for (int bounce = 0; bounce <= pt.MaxBounces; ++bounce)
  {
    const float t = SampleFreeFlight(u, pt, p, direction, tStart, tEnd, rng);
    if (t == GaveUp)
    {
      break; // an extinction too large for float: the path ends with what it has
    }
    if (t >= tEnd)
    {
      // Out of the volume: into the uniform environment (the view ray itself brings nothing:
      // the background is composited behind the premultiplied image).
      if (bounce > 0)
      {
        radiance += throughput * u.Ambient;
      }
      break;
    }
    if (bounce == pt.MaxBounces)
    {
      break; // one scattering event more than allowed
    }
    p += t * direction;
    throughput *= glm::vec3(u.Table->Lookup(DensityAt(u, p))); // the albedo
    radiance += throughput * DirectLight(u, pt, p, d, rng);
    if (bounce + 1 >= pt.RouletteBounces)
    {
      const float survival =
        std::min(std::max(std::max(throughput.r, throughput.g), throughput.b), 1.0f);
      if (NextRandom(rng) >= survival)
      {
        break;
      }
      throughput /= survival;
    }
    d = SamplePhaseDirection(u.Lighting, d, rng);
    direction = LocalToIndex(u, d);
    tStart = 0.0f;
    tEnd = IntersectBox(p, direction, glm::vec3(0.0f), boxHigh).y;
  }
  return glm::vec4(radiance, 1.0f - T);
}

} // namespace cloudvis
