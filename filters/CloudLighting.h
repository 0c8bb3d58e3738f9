// The lighting models' parameters, the constants the shaders share with the C++, and the C++ entry
// points of the lighting functions, which are defined once for the CPU and the GPU in
// shaders/transport/Transport.glsl (docs/transport.md); the equations are written out in
// docs/lighting.md.
//
// Conventions: world units; l is the unit direction from a sample toward a light; d is the unit
// direction of the view ray (from the eye into the scene); mu = dot(d, l), so mu = 1 when the
// eye looks straight at the light through the sample (forward scattering).
#ifndef CloudLighting_h
#define CloudLighting_h

#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace cloudvis
{

enum class LightingModel
{
  None,       // emission-absorption: a sample emits its transfer-function color
  Derivative, // directional derivative toward each light, one extra density sample per light
  March,      // nested march toward each light: Beer-Lambert shadowing and a phase function
  PathTrace,  // Monte Carlo volumetric path tracing: every order of scattering (CloudPathTrace.h)
};

// A light in the world, as a scene or a vtkLight gives it (the mapper converts vtkLights into
// these). Positions are double, like VTK's: a light beside a volume far from the origin keeps
// its place, and a directional light may sit at any distance along its direction.
struct Light
{
  bool Positional = false; // false: directional, from Position toward FocalPoint
  glm::dvec3 Position{ 0.0, 10.0, 10.0 };
  glm::dvec3 FocalPoint{ 0.0 };
  glm::vec3 Color{ 1.0f };
  float Intensity = 1.0f;
  glm::vec3 Attenuation{ 0.0f, 0.0f, 1.0f }; // positional: 1 / (a0 + a1 r + a2 r^2), world r
};

// The unit direction toward a directional light, computed in double (so a sun placed at 1e300
// keeps its direction); the zero vector when its position equals its focal point.
inline glm::dvec3 DirectionTowardLight(const Light& light)
{
  const glm::dvec3 d = light.Position - light.FocalPoint;
  // Scaled first: the squared length of a vector beyond 1e154 overflows even in double.
  const double largest = std::max({ std::abs(d.x), std::abs(d.y), std::abs(d.z) });
  return largest > 0.0 && std::isfinite(largest) ? glm::normalize(d / largest) : glm::dvec3(0.0);
}

// A light as the march computes with it: in the march's local frame (CloudMarchUniforms.h),
// whose lengths are world lengths divided by the frame's unit. The uniforms of the GLSL's lights.
struct LocalLight
{
  bool Positional = false;
  glm::vec3 Position{ 0.0f };    // local coordinates; positional lights
  glm::vec3 Direction{ 0.0f };   // unit, toward the light; directional lights
  glm::vec3 Radiance{ 0.0f };    // color * intensity
  glm::vec3 Attenuation{ 0.0f }; // (a0, a1 unit, a2 unit^2): the falloff of a local distance
  // Directional lights, the same at every sample (SetUpMarch computes them once, in float, for
  // both renderers): Direction in index units per local unit, and the derivative model's offset
  // h Direction in index units.
  glm::vec3 IndexDirection{ 0.0f };
  glm::vec3 IndexOffset{ 0.0f };
};

// How the march finds the optical depth toward a light at a sample (docs/lighting.md).
enum class LightTransmittance
{
  Volumes, // read from per-light optical-depth volumes computed when the inputs change
  Nested,  // a march toward each light at every sample (the quality setting)
};

struct LightingParameters
{
  LightingModel Model = LightingModel::None;
  glm::vec3 AmbientColor{ 1.0f };
  float AmbientStrength = 0.0f;

  // derivative: the finite-difference distance h toward the light, world units; 0 means 4
  // voxel spacings (the smallest spacing of the field).
  float DerivativeDistance = 0.0f;

  // march: LightSteps segments toward each light spanning the way to the volume's exit (or a
  // point light), each LightStepGrowth times longer than the one before (1: uniform steps), the
  // first at least LightStep long (0 means 2 voxel spacings).
  int LightSteps = 6;
  float LightStep = 0.0f;
  float LightStepGrowth = 1.6f;
  // Where the optical depth comes from: the volumes (fast; their march has uniform steps of the
  // view's step) or the nested march above at every sample.
  LightTransmittance Transmittance = LightTransmittance::Volumes;
  // Henyey-Greenstein phase, two lobes: w * HG(g1) + (1 - w) * HG(g2). w = 1 is one lobe.
  float PhaseG1 = 0.6f;
  float PhaseG2 = -0.3f;
  float PhaseLobeWeight = 0.8f;
  // Approximate multiple scattering: octaves n = 1..N added to single scattering (n = 0), each
  // scaling scattering by a^n, extinction toward the light by b^n, eccentricity by c^n. The
  // values are fitted to the path tracer (`cloudvis-bench-pathtrace fit`, docs/lighting.md
  // "Fitting the march to the path tracer"); until that fit they were 3 and 0.5, 0.5, 0.5.
  int MultipleScatteringOctaves = 3;
  float ScatteringFalloff = 0.41f;   // a
  float ExtinctionFalloff = 0.26f;   // b
  float EccentricityFalloff = 0.46f; // c
  // Non-physical "powder" darkening of thin regions (an artistic term): 0 disables.
  float PowderStrength = 0.0f;
};

// The limits ValidateLightingParameters puts on LightingParameters, and the number of lights
// the renderers take; the scene schema states the same ones from here.
struct LightingLimits
{
  // The GLSL's MAX_LIGHTS (the mapper substitutes it into shaders/transport/Transport.glsl). The
  // GPU mapper and the CPU renderers refuse more (SetUpMarch), and so does a scene's lights
  // section.
  static constexpr int MaxLights = 8;
  static constexpr int MinLightSteps = 1;
  static constexpr int MaxLightSteps = 64;
  static constexpr float MinLightStepGrowth = 1.0f;
  static constexpr float MaxLightStepGrowth = 4.0f;
  static constexpr int MaxMultipleScatteringOctaves = 8;
};

// Empty when the parameters are usable, else the problem, in words.
inline std::string ValidateLightingParameters(const LightingParameters& p)
{
  using L = LightingLimits;
  const auto finite3 = [](glm::vec3 v)
  { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite3(p.AmbientColor) || !std::isfinite(p.AmbientStrength) || p.AmbientStrength < 0.0f)
    return "ambient color and strength must be finite, strength >= 0";
  if (!std::isfinite(p.DerivativeDistance) || p.DerivativeDistance < 0.0f)
    return "the derivative distance must be >= 0 (0: automatic)";
  if (p.LightSteps < L::MinLightSteps || p.LightSteps > L::MaxLightSteps)
    return "light-march steps must be between " + std::to_string(L::MinLightSteps) + " and " +
      std::to_string(L::MaxLightSteps);
  if (!std::isfinite(p.LightStep) || p.LightStep < 0.0f)
    return "the light-march step must be >= 0 (0: automatic)";
  if (!std::isfinite(p.LightStepGrowth) || p.LightStepGrowth < L::MinLightStepGrowth ||
    p.LightStepGrowth > L::MaxLightStepGrowth)
    return "the light-march step growth must be between " +
      std::to_string(int(L::MinLightStepGrowth)) + " and " +
      std::to_string(int(L::MaxLightStepGrowth));
  if (!(std::abs(p.PhaseG1) < 1.0f) || !(std::abs(p.PhaseG2) < 1.0f))
    return "phase eccentricities g must be in (-1, 1)";
  if (!(p.PhaseLobeWeight >= 0.0f && p.PhaseLobeWeight <= 1.0f))
    return "the phase lobe weight must be in [0, 1]";
  if (p.MultipleScatteringOctaves < 0 ||
    p.MultipleScatteringOctaves > L::MaxMultipleScatteringOctaves)
    return "multiple-scattering octaves must be between 0 and " +
      std::to_string(L::MaxMultipleScatteringOctaves);
  for (float f : { p.ScatteringFalloff, p.ExtinctionFalloff, p.EccentricityFalloff })
    if (!(f >= 0.0f && f <= 1.0f))
      return "multiple-scattering falloffs must be in [0, 1]";
  if (!(p.PowderStrength >= 0.0f && p.PowderStrength <= 1.0f))
    return "the powder strength must be in [0, 1]";
  return {};
}

constexpr float Pi = 3.14159265358979f;

// The march weighs a light with a phase function, a density per steradian (1 / 4 pi when
// isotropic). Multiplying by 4 pi makes a light's color x intensity mean the same in every
// model: what an unshadowed sample of albedo 1 sends toward the eye when it scatters
// isotropically (the derivative model: a face lit head-on, D = 1).
constexpr float PhaseToRadiance = 4.0f * Pi;

// The lighting functions' C++ entry points: each calls the one definition in
// shaders/transport/Transport.glsl (through cloudvis::glsl::Transport, CloudTransport.h), where
// they are documented, with the parameters' values as its uniforms.

// Henyey-Greenstein phase function: (1 / 4 pi) (1 - g^2) / (1 + g^2 - 2 g mu)^(3/2).
CLOUDVISFILTERS_EXPORT float HenyeyGreenstein(float g, float mu);

// The two-lobe phase with both eccentricities scaled by `eccentricityScale` (c^n for octave n).
CLOUDVISFILTERS_EXPORT float Phase(const LightingParameters& p, float mu, float eccentricityScale);

// Light scattered toward the eye at a sample from one light whose optical depth to the sample
// is tau: single scattering plus the multiple-scattering octaves (docs/lighting.md), per channel.
CLOUDVISFILTERS_EXPORT glm::vec3 ScatteredFraction(const LightingParameters& p,
  float mu,
  float tau,
  glm::vec3 albedo);

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
CLOUDVISFILTERS_EXPORT LightSample SampleLight(const LocalLight& light, glm::vec3 x);

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
