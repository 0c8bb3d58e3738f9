// The functions the lighting models share, on the CPU (their parameters, the value a scene gives
// the renderers, are CloudLightingParameters.h's). Each function has
// a GLSL twin of the same name in shaders/CloudLightingCommon.glsl, .../CloudLightingDerivative
// .glsl and .../CloudLightingMarch.glsl; the equations are written out in docs/lighting.md.
//
// Conventions: world units; l is the unit direction from a sample toward a light; d is the unit
// direction of the view ray (from the eye into the scene); mu = dot(d, l), so mu = 1 when the
// eye looks straight at the light through the sample (forward scattering).
#ifndef CloudLighting_h
#define CloudLighting_h

#include "CloudLightingParameters.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace cloudvis
{

constexpr float Pi = 3.14159265358979f;

// The march weighs a light with a phase function, a density per steradian (1 / 4 pi when
// isotropic). Multiplying by 4 pi makes a light's color x intensity mean the same in every
// model: what an unshadowed sample of albedo 1 sends toward the eye when it scatters
// isotropically (the derivative model: a face lit head-on, D = 1).
constexpr float PhaseToRadiance = 4.0f * Pi;

// Henyey-Greenstein phase function: (1 / 4 pi) (1 - g^2) / (1 + g^2 - 2 g mu)^(3/2).
// Integrates to 1 over the sphere; g > 0 scatters forward.
inline float HenyeyGreenstein(float g, float mu)
{
  const float g2 = g * g;
  const float denominator = 1.0f + g2 - 2.0f * g * mu;
  return (1.0f - g2) / (4.0f * Pi * denominator * std::sqrt(denominator));
}

// The two-lobe phase with both eccentricities scaled by `eccentricityScale` (c^n for octave n).
inline float Phase(const LightingParameters& p, float mu, float eccentricityScale)
{
  return p.PhaseLobeWeight * HenyeyGreenstein(p.PhaseG1 * eccentricityScale, mu) +
    (1.0f - p.PhaseLobeWeight) * HenyeyGreenstein(p.PhaseG2 * eccentricityScale, mu);
}

// Directional derivative toward a light: positive where density falls toward the light, so the
// side of a cloud facing the light is bright. slopeScale is 1 / (h * density unit), h in world
// units and the density unit the transfer function's span (docs/lighting.md), computed once in
// double: the term does not depend on the field's density units nor on the march's frame.
inline float DerivativeDiffuse(float densityHere, float densityTowardLight, float slopeScale)
{
  return glm::clamp((densityHere - densityTowardLight) * slopeScale, 0.0f, 1.0f);
}

// Light scattered toward the eye at a sample from one light whose optical depth to the sample
// is tau: single scattering plus the multiple-scattering octaves (docs/lighting.md), per channel.
// Octave n stands for light scattered n + 1 times, so it carries the albedo n more times than
// single scattering (the caller multiplies by the albedo once): physics' albedo^(n+1).
inline glm::vec3 ScatteredFraction(const LightingParameters& p,
  float mu,
  float tau,
  glm::vec3 albedo)
{
  glm::vec3 sum(0.0f);
  glm::vec3 a(1.0f);
  float b = 1.0f, c = 1.0f;
  for (int n = 0; n <= p.MultipleScatteringOctaves; ++n)
  {
    sum += a * (Phase(p, mu, c) * std::exp(-b * tau));
    a *= p.ScatteringFalloff * albedo;
    b *= p.ExtinctionFalloff;
    c *= p.EccentricityFalloff;
  }
  // Labelled non-physical: darkens where little material lies toward the light.
  const float powder = 1.0f - p.PowderStrength * std::exp(-2.0f * tau);
  return sum * powder;
}

// The light march leaves a box this much larger (index units) than the volume's [0, n - 1]: a
// sample on a face, with the light running along that face, would otherwise leave the box at
// once (at 1e-3 voxels the reach grows by at most 0.002 voxels elsewhere).
constexpr float LightBoxMargin = 1e-3f;

// How far a directional light is, in local units: beyond any light march (the GLSL receives it
// by substitution).
constexpr float DirectionalLightDistance = 1e30f;

// Where a light is seen from a point x of the march's local frame: unit direction toward it, the
// local distance to it (DirectionalLightDistance for directional lights) and its distance
// falloff.
struct LightSample
{
  glm::vec3 Direction;
  float Distance;
  float Falloff;
};
inline LightSample SampleLight(const LocalLight& light, glm::vec3 x)
{
  if (!light.Positional)
  {
    return { light.Direction, DirectionalLightDistance, 1.0f };
  }
  const glm::vec3 toLight = light.Position - x;
  const float r = glm::length(toLight);
  const glm::vec3 k = light.Attenuation;
  return { toLight / std::max(r, 1e-20f), r, 1.0f / std::max(k.x + k.y * r + k.z * r * r, 1e-20f) };
}

// The most radiance per unit of a light's color x intensity that one sample can send toward the
// eye, over the derivative model (D <= 1) and the march (4 pi times the scattered fraction at its
// peak: every octave's largest phase value, no shadowing), for a falloff of 1. Renderers check
// their lights against it so that no light can overflow float arithmetic (CloudMarchUniforms.h).
inline double PeakRadiancePerLightRadiance(const LightingParameters& p)
{
  const auto peakHG = [](double g) { // at mu = sign(g): (1 + |g|) / (4 pi (1 - |g|)^2)
    const double a = std::abs(g);
    return (1.0 + a) / (4.0 * 3.14159265358979323846 * (1.0 - a) * (1.0 - a));
  };
  double sum = 0.0, a = 1.0, c = 1.0;
  for (int n = 0; n <= p.MultipleScatteringOctaves; ++n)
  {
    sum += a * std::max(peakHG(p.PhaseG1 * c), peakHG(p.PhaseG2 * c));
    a *= p.ScatteringFalloff;
    c *= p.EccentricityFalloff;
  }
  return std::max(1.0, 4.0 * 3.14159265358979323846 * sum);
}

} // namespace cloudvis

#endif
