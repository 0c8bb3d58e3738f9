#include "CloudReferenceMarch.h"

#include "CloudLightVolumes.h"

#include <algorithm>
#include <cmath>

namespace cloudvis
{

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
  return glm::vec2(
    std::max(std::max(tNear.x, tNear.y), tNear.z), std::min(std::min(tFar.x, tFar.y), tFar.z));
}

glm::vec4 Optical(const MarchUniforms& u, float density)
{
  const glm::vec4 optical = u.Table->Lookup(density);
  return glm::vec4(glm::vec3(optical), optical.a * u.ExtinctionUnit);
}

glm::vec3 LocalOfIndex(const MarchUniforms& u, glm::vec3 p)
{
  return glm::vec3(u.IndexToLocal * glm::vec4(p, 1.0f));
}

glm::vec3 IndexOfLocal(const MarchUniforms& u, glm::vec3 x)
{
  return u.LocalToIndex * (x - glm::vec3(u.IndexToLocal[3]));
}

glm::vec3 LocalToIndex(const MarchUniforms& u, glm::vec3 w)
{
  return u.LocalToIndex * w;
}

glm::vec4 MarchRay(const MarchUniforms& u, glm::vec3 nearPoint, glm::vec3 farPoint)
{
  const glm::vec3 toFar = farPoint - nearPoint;
  const float rayLength = glm::length(toFar);
  const glm::vec3 d = toFar / rayLength;               // view direction, unit
  const glm::vec3 origin = IndexOfLocal(u, nearPoint); // index point at t = 0
  const glm::vec3 direction = LocalToIndex(u, d);      // index units per local unit

  const float tOpaque = rayLength; // no opaque geometry: the depth buffer holds the far plane
  const glm::vec2 tBox =
    IntersectBox(origin, direction, glm::vec3(0.0f), glm::vec3(u.Dimensions) - 1.0f);
  const float tEnter = std::max(tBox.x, 0.0f);
  const float tExit = std::min(std::min(tBox.y, tOpaque), rayLength);

  glm::vec3 radiance(0.0f);
  float T = 1.0f;
  if (tEnter < tExit)
  {
    // Samples are placed from the entry point, so their spacing keeps its precision however far
    // the camera is from the volume.
    const glm::vec3 entry = origin + tEnter * direction;
    const float span = tExit - tEnter;
    const float jitter = 0.0f;
    float k = 0.0f;
    for (int i = 0; i < u.MaximumSamples; ++i)
    {
      const float s = (k + jitter) * u.Step;
      if (s >= span)
      {
        break;
      }
      const glm::vec3 p = entry + s * direction;
      const float density = DensityAt(u, p);
      const glm::vec4 optical = Optical(u, density);
      const float sigma_t = optical.a;
      if (sigma_t > 0.0f)
      {
        const float stepT = std::exp(-sigma_t * u.Step);
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

float DensityAt(const MarchUniforms& u, glm::vec3 p)
{
  // GL_LINEAR at texture coordinate (p + 0.5) / n reads texels floor(p) and floor(p) + 1 with
  // weights from fract(p); CLAMP_TO_EDGE clamps each texel index to [0, n - 1]. The texels'
  // normalized values are interpolated, then scaled to the data's units, as the GLSL does.
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
  const auto texel = [&u](int x, int y, int z)
  {
    return NormalizedTexel(
      u.Density, (std::size_t(z) * u.Dimensions.y + y) * u.Dimensions.x + std::size_t(x));
  };
  const auto lerp = [](float a, float b, float w) { return a + w * (b - a); };
  const float c00 = lerp(texel(i0[0], i0[1], i0[2]), texel(i1[0], i0[1], i0[2]), f[0]);
  const float c10 = lerp(texel(i0[0], i1[1], i0[2]), texel(i1[0], i1[1], i0[2]), f[0]);
  const float c01 = lerp(texel(i0[0], i0[1], i1[2]), texel(i1[0], i0[1], i1[2]), f[0]);
  const float c11 = lerp(texel(i0[0], i1[1], i1[2]), texel(i1[0], i1[1], i1[2]), f[0]);
  const float filtered = lerp(lerp(c00, c10, f[1]), lerp(c01, c11, f[1]), f[2]);
  return filtered * u.Density.Scale + u.Density.Bias;
}

float ExtinctionAt(const MarchUniforms& u, glm::vec3 p)
{
  return Optical(u, DensityAt(u, p)).a;
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

namespace
{
// SourceTerm with one term per light, as the mapper's generated GLSL calls them.
template<typename DirectionalTerm, typename PointTerm>
glm::vec3 SumOverLights(const MarchUniforms& u,
  glm::vec3 albedo,
  DirectionalTerm directional,
  PointTerm point)
{
  glm::vec3 light = u.Ambient;
  for (const LocalLight& source : u.Lights)
  {
    light += source.Positional ? point(source) : directional(source);
  }
  return albedo * light;
}
}

glm::vec3 SourceTermDerivative(const MarchUniforms& u,
  glm::vec3 p,
  float density,
  glm::vec3 albedo,
  glm::vec3)
{
  const float h = u.Lighting.DerivativeDistance;
  return SumOverLights(
    u,
    albedo,
    [&](const LocalLight& source) { // DirectionalLightTerm: the offset h l is precomputed
      const float towardLight = DensityAt(u, p + source.IndexOffset);
      return source.Radiance * DerivativeDiffuse(density, towardLight, u.DerivativeSlopeScale);
    },
    [&](const LocalLight& source) { // PointLightTerm
      const LightSample s = SampleLight(source, LocalOfIndex(u, p));
      const float towardLight = DensityAt(u, p + LocalToIndex(u, h * s.Direction));
      return source.Radiance * s.Falloff *
        DerivativeDiffuse(density, towardLight, u.DerivativeSlopeScale);
    });
}

// ---- CloudLightingMarch.glsl ----

float LightOpticalDepth(const MarchUniforms& u,
  glm::vec3 p,
  float sigmaHere,
  glm::vec3 indexStep,
  float maxDistance)
{
  // A sample on a face may lie a hair outside by rounding: its light starts on the face, and
  // leaves a box LightBoxMargin larger, so a light running along the face still crosses it.
  const glm::vec3 last = glm::vec3(u.Dimensions) - 1.0f;
  const glm::vec3 start = glm::clamp(p, glm::vec3(0.0f), last);
  const float reach = std::min(
    IntersectBox(start, indexStep, glm::vec3(-LightBoxMargin), last + LightBoxMargin).y,
    maxDistance);
  float tau = 0.0f;
  if (reach > 0.0f)
  {
    const float growth = u.Lighting.LightStepGrowth;
    const float segments = growth == 1.0f
      ? float(u.Lighting.LightSteps)
      : (std::pow(growth, float(u.Lighting.LightSteps)) - 1.0f) / (growth - 1.0f);
    float segment = std::max(u.Lighting.LightStep, reach / segments);
    float s = 0.0f;
    float sigmaStart = sigmaHere;
    for (int j = 0; j < u.Lighting.LightSteps; ++j)
    {
      const float end = std::min(s + segment, reach);
      // The GPU passes empty bricks without reading them; their sigma_t is 0, so reading adds 0.
      const float sigmaEnd = ExtinctionAt(u, start + end * indexStep);
      tau += 0.5f * (sigmaStart + sigmaEnd) * (end - s);
      if (end >= reach)
      {
        break;
      }
      s = end;
      sigmaStart = sigmaEnd;
      segment *= growth;
    }
  }
  return tau;
}

glm::vec3 SourceTermMarch(
  const MarchUniforms& u, glm::vec3 p, float density, glm::vec3 albedo, glm::vec3 d)
{
  const float sigmaHere = Optical(u, density).a;
  const bool fromVolumes =
    u.Lighting.Transmittance == LightTransmittance::Volumes && u.LightDepths != nullptr;
  // The optical depth toward light `source`, along indexStep, up to maxDistance.
  const auto opticalDepth = [&](const LocalLight& source, glm::vec3 indexStep, float maxDistance)
  {
    return fromVolumes ? LightVolumeDepth(*u.LightDepths, u, int(&source - u.Lights.data()), p)
                       : LightOpticalDepth(u, p, sigmaHere, indexStep, maxDistance);
  };
  return SumOverLights(
    u,
    albedo,
    [&](const LocalLight& source) { // DirectionalLightTerm: l in index units is precomputed
      const float tau = opticalDepth(source, source.IndexDirection, DirectionalLightDistance);
      return source.Radiance * PhaseToRadiance *
        ScatteredFraction(u.Lighting, glm::dot(d, source.Direction), tau, albedo);
    },
    [&](const LocalLight& source) { // PointLightTerm
      const LightSample s = SampleLight(source, LocalOfIndex(u, p));
      const float tau = opticalDepth(source, LocalToIndex(u, s.Direction), s.Distance);
      return source.Radiance * s.Falloff * PhaseToRadiance *
        ScatteredFraction(u.Lighting, glm::dot(d, s.Direction), tau, albedo);
    });
}

glm::vec3 SourceTerm(const MarchUniforms& u,
  glm::vec3 p,
  float density,
  glm::vec3 albedo,
  glm::vec3 d)
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
