#include "CloudReferenceMarch.h"

#include <algorithm>
#include <cmath>

namespace cloudvis
{

LightingParameters ResolveLighting(const LightingParameters& p, double smallestSpacing)
{
  // In double and then rounded, as the mapper computes the uniforms.
  LightingParameters resolved = p;
  resolved.DerivativeDistance =
    p.DerivativeDistance > 0.0f ? p.DerivativeDistance : float(4.0 * smallestSpacing);
  resolved.LightStep = p.LightStep > 0.0f ? p.LightStep : float(2.0 * smallestSpacing);
  return resolved;
}

// ---- CloudMarchFS.glsl ----

glm::vec2 IntersectBox(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi)
{
  // An axis-parallel ray gets a huge finite inverse rather than a division by zero.
  const glm::vec3 safe = glm::mix(d, glm::vec3(1e-30f), glm::equal(d, glm::vec3(0.0f)));
  const glm::vec3 inv = 1.0f / safe;
  const glm::vec3 t0 = (lo - o) * inv;
  const glm::vec3 t1 = (hi - o) * inv;
  const glm::vec3 tNear = glm::min(t0, t1);
  const glm::vec3 tFar = glm::max(t0, t1);
  return glm::vec2(std::max(std::max(tNear.x, tNear.y), tNear.z),
    std::min(std::min(tFar.x, tFar.y), tFar.z));
}

glm::vec4 MarchRay(const MarchUniforms& u, const glm::dvec3& nearWorld, const glm::dvec3& farWorld)
{
  // The GLSL maps both plane points to index space with DCIndexMatrix; with an identity
  // direction matrix that is (world - IndexOrigin) / Spacing.
  const auto indexOf = [&u](const glm::dvec3& w) {
    return (w - glm::dvec3(u.IndexOrigin)) / glm::dvec3(u.Spacing);
  };
  const float rayLength = static_cast<float>(glm::length(farWorld - nearWorld));
  const glm::vec3 origin(indexOf(nearWorld));
  const glm::vec3 d(glm::normalize(farWorld - nearWorld)); // view direction, world
  // index units per world unit
  const glm::vec3 direction = (glm::vec3(indexOf(farWorld)) - origin) / rayLength;

  const float tOpaque = rayLength; // no opaque geometry: the depth buffer holds the far plane
  const glm::vec2 tBox =
    IntersectBox(origin, direction, glm::vec3(0.0f), glm::vec3(u.Dimensions) - 1.0f);
  const float tEnter = std::max(tBox.x, 0.0f);
  const float tExit = std::min(std::min(tBox.y, tOpaque), rayLength);

  glm::vec3 radiance(0.0f);
  float T = 1.0f;
  if (tEnter < tExit)
  {
    const float jitter = 0.0f;
    float k = 0.0f;
    for (int i = 0; i < u.MaximumIterations; ++i)
    {
      const float t = tEnter + (k + jitter) * u.StepWorld;
      if (t >= tExit)
      {
        break;
      }
      const glm::vec3 p = origin + t * direction;
      const float density = DensityAt(u, p);
      const glm::vec4 optical = u.Table->Lookup(density);
      const float sigma_t = optical.a;
      if (sigma_t > 0.0f)
      {
        const float stepT = std::exp(-sigma_t * u.StepWorld);
        // In-scattering integrated over the step: S * (1 - exp(-sigma_t dt)), exact for S
        // constant over the step, so the sum does not depend on the step size.
        radiance += T * SourceTerm(u, p, density, glm::vec3(optical), d) * (1.0f - stepT);
        T *= stepT;
        if (T < u.TerminationTransmittance)
        {
          break;
        }
      }
      k += 1.0f;
    }
  }
  return glm::vec4(radiance, 1.0f - T); // premultiplied: alpha is the opacity
}

// ---- CloudLightingCommon.glsl ----

glm::vec3 WorldOfIndex(const MarchUniforms& u, glm::vec3 p)
{
  return u.IndexOrigin + u.Spacing * p;
}

glm::vec3 WorldToIndex(const MarchUniforms& u, glm::vec3 w)
{
  return w / u.Spacing;
}

float DensityAt(const MarchUniforms& u, glm::vec3 p)
{
  // GL_LINEAR at texture coordinate (p + 0.5) / n reads texels floor(p) and floor(p) + 1 with
  // weights from fract(p); CLAMP_TO_EDGE clamps each texel index to [0, n - 1].
  int i0[3], i1[3];
  float f[3];
  for (int a = 0; a < 3; ++a)
  {
    const float fl = std::floor(p[a]);
    f[a] = p[a] - fl;
    const int n = u.Dimensions[a];
    const float lo = std::min(std::max(fl, 0.0f), float(n - 1));
    const float hi = std::min(std::max(fl + 1.0f, 0.0f), float(n - 1));
    i0[a] = static_cast<int>(lo);
    i1[a] = static_cast<int>(hi);
  }
  const auto voxel = [&u](int x, int y, int z) {
    return u.Density[(std::size_t(z) * u.Dimensions.y + y) * u.Dimensions.x + x];
  };
  const auto lerp = [](float a, float b, float w) { return a + w * (b - a); };
  const float c00 = lerp(voxel(i0[0], i0[1], i0[2]), voxel(i1[0], i0[1], i0[2]), f[0]);
  const float c10 = lerp(voxel(i0[0], i1[1], i0[2]), voxel(i1[0], i1[1], i0[2]), f[0]);
  const float c01 = lerp(voxel(i0[0], i0[1], i1[2]), voxel(i1[0], i0[1], i1[2]), f[0]);
  const float c11 = lerp(voxel(i0[0], i1[1], i1[2]), voxel(i1[0], i1[1], i1[2]), f[0]);
  return lerp(lerp(c00, c10, f[1]), lerp(c01, c11, f[1]), f[2]);
}

float ExtinctionAt(const MarchUniforms& u, glm::vec3 p)
{
  return u.Table->Lookup(DensityAt(u, p)).a;
}

bool InsideVolume(const MarchUniforms& u, glm::vec3 p)
{
  return glm::all(glm::greaterThanEqual(p, glm::vec3(0.0f))) &&
    glm::all(glm::lessThanEqual(p, glm::vec3(u.Dimensions) - 1.0f));
}

// ---- CloudLightingNone.glsl ----

glm::vec3 SourceTermNone(const MarchUniforms&, glm::vec3, float, glm::vec3 albedo, glm::vec3)
{
  return albedo;
}

// ---- CloudLightingDerivative.glsl ----

glm::vec3 SourceTermDerivative(
  const MarchUniforms& u, glm::vec3 p, float density, glm::vec3 albedo, glm::vec3)
{
  const float h = u.Lighting.DerivativeDistance;
  const glm::vec3 x = WorldOfIndex(u, p);
  glm::vec3 light = u.Ambient;
  for (const Light& source : u.Lights)
  {
    const LightSample s = SampleLight(source, x);
    const float towardLight = DensityAt(u, p + WorldToIndex(u, h * s.Direction));
    light += source.Color * source.Intensity * s.Falloff *
      DerivativeDiffuse(density, towardLight, h, float(u.Table->Range[1] - u.Table->Range[0]));
  }
  return albedo * light;
}

// ---- CloudLightingMarch.glsl ----

float LightOpticalDepth(const MarchUniforms& u, glm::vec3 p, glm::vec3 l, float maxDistance)
{
  const glm::vec3 indexStep = WorldToIndex(u, l); // index units per world unit
  float tau = 0.0f;
  float start = 0.0f;
  float segment = u.Lighting.LightStep;
  for (int j = 0; j < u.Lighting.LightSteps; ++j)
  {
    const float s = start + 0.5f * segment;
    const glm::vec3 q = p + s * indexStep;
    if (s > maxDistance || !InsideVolume(u, q))
    {
      break;
    }
    // The GPU passes empty bricks without reading them; their sigma_t is 0, so reading adds 0.
    tau += ExtinctionAt(u, q) * segment;
    start += segment;
    segment *= u.Lighting.LightStepGrowth;
  }
  return tau;
}

glm::vec3 SourceTermMarch(
  const MarchUniforms& u, glm::vec3 p, float /*density*/, glm::vec3 albedo, glm::vec3 d)
{
  const glm::vec3 x = WorldOfIndex(u, p);
  glm::vec3 light = u.Ambient;
  for (const Light& source : u.Lights)
  {
    const LightSample s = SampleLight(source, x);
    const float tau = LightOpticalDepth(u, p, s.Direction, s.Distance);
    light += source.Color * source.Intensity * s.Falloff * PhaseToRadiance *
      ScatteredFraction(u.Lighting, glm::dot(d, s.Direction), tau);
  }
  return albedo * light;
}

glm::vec3 SourceTerm(
  const MarchUniforms& u, glm::vec3 p, float density, glm::vec3 albedo, glm::vec3 d)
{
  switch (u.Lighting.Model)
  {
    case LightingModel::Derivative:
      return SourceTermDerivative(u, p, density, albedo, d);
    case LightingModel::March:
      return SourceTermMarch(u, p, density, albedo, d);
    case LightingModel::None:
    default:
      return SourceTermNone(u, p, density, albedo, d);
  }
}

} // namespace cloudvis
