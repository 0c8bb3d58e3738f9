// The constants the shaders share with the C++, and the C++ entry points of the lighting
// functions, which are defined once for the CPU and the GPU in shaders/transport/
// (docs/transport.md); the equations are written out in docs/lighting.md. The models'
// parameters, the value a scene gives the renderers, are CloudLightingParameters.h's.
//
// Conventions: world units; l is the unit direction from a sample toward a light; d is the unit
// direction of the view ray (from the eye into the scene); mu = dot(d, l), so mu = 1 when the
// eye looks straight at the light through the sample (forward scattering).
#ifndef CloudLighting_h
#define CloudLighting_h

#include "CloudLightingParameters.h"
#include "cloudvisFiltersModule.h"

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

// The lighting functions' C++ entry points: each calls the one definition in
// shaders/transport/ (through cloudvis::glsl::Transport, CloudTransport.h), where
// they are documented, with the parameters' values as its uniforms.

// Henyey-Greenstein phase function: (1 / 4 pi) (1 - g^2) / (1 + g^2 - 2 g mu)^(3/2).
CLOUDVISFILTERS_EXPORT float HenyeyGreenstein(float g, float mu);

// The phase function of `p` at mu, per channel, its eccentricity scaled by `eccentricityScale`
// (c^n for octave n): the two lobes, or the droplets' table (scale 1) and their g's lobe.
CLOUDVISFILTERS_EXPORT glm::vec3 Phase(
  const LightingParameters& p, float mu, float eccentricityScale);

// The droplets' table of `p` (its effective radius and variance, the default wavelengths), from
// DropletPhase's cache, and its moments as the light transport takes them: the means over the
// channels of g (chi_1) and chi_2.
CLOUDVISFILTERS_EXPORT const DropletPhaseTable& DropletPhaseOf(const LightingParameters& p);
inline float DropletMeanCosineOf(const DropletPhaseTable& table)
{
  return (table.g.x + table.g.y + table.g.z) / 3.0f;
}
inline float DropletSecondMomentOf(const DropletPhaseTable& table)
{
  return (table.chi_2.x + table.chi_2.y + table.chi_2.z) / 3.0f;
}

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

// The multiple-scattering volume's flux limiter (shaders/transport/LightMarch.glsl): the largest
// |flux| / fluence it lets diffuse light stream at where the medium is thin. Marshak's half-space
// would be 1/2; 0.35 is the best of 1/2, 0.45, 0.41, 0.35 and 0.29 on the training cases of
// `cloudvis-bench-pathtrace fit` (docs/lighting.md, "The multiple-scattering volume").
constexpr float DiffuseEscapeSpeed = 0.35f;

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
  const bool droplets = p.Phase == PhaseModel::Droplets;
  for (int n = 0; n <= p.MultipleScatteringOctaves; ++n)
  {
    if (droplets)
    {
      // The table's largest value is its forward peak; the octaves' lobes have the table's g.
      const DropletPhaseTable& table = DropletPhaseOf(p);
      const glm::vec3 forward = table.Phase.front();
      sum += a *
        (n == 0 ? double(std::max(std::max(forward.x, forward.y), forward.z))
                : peakHG(DropletMeanCosineOf(table) * c));
    }
    else
    {
      sum += a * std::max(peakHG(p.PhaseG1 * c), peakHG(p.PhaseG2 * c));
    }
    a *= p.ScatteringFalloff;
    c *= p.EccentricityFalloff;
  }
  return std::max(1.0, 4.0 * 3.14159265358979323846 * sum);
}

} // namespace cloudvis

#endif
