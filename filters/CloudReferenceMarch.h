// The CPU twin of the GPU march: shaders/CloudMarchFS.glsl (MarchRay is its main()) and the
// lighting models of shaders/CloudLighting{Common,None,Derivative,March}.glsl. Each function
// here has the name, the arguments and the order of operations of its GLSL counterpart, so the
// two can be read side by side; what the shader gets from uniforms and textures it gets from
// MarchUniforms. The equations are in docs/lighting.md. Unlike the GPU this march never skips
// empty bricks (skipping does not change the sum, since empty bricks have sigma_t = 0), never
// jitters, and has no opaque geometry ending the rays. It computes in float, as the GPU does,
// and samples textures exactly (the GPU's linear filter weights have 8 fractional bits).
#ifndef CloudReferenceMarch_h
#define CloudReferenceMarch_h

#include "CloudLighting.h"
#include "CloudTransferTable.h"
#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <vector>

namespace cloudvis
{

// What the march shader reads from its uniforms and textures.
struct CLOUDVISFILTERS_EXPORT MarchUniforms
{
  // DensityTexture: Dimensions.x * .y * .z values, x fastest, in the input's scalar units.
  const float* Density = nullptr;
  glm::ivec3 Dimensions{ 0 };
  // IndexToWorld: world = IndexOrigin + Spacing * p for an index point p (identity direction).
  glm::vec3 IndexOrigin{ 0.0f };
  glm::vec3 Spacing{ 1.0f };
  // TransferTexture: albedo and sigma_t per density.
  const TransferTable* Table = nullptr;
  float StepWorld = 1.0f; // world units between samples along a view ray, > 0
  float TerminationTransmittance = 1.0f / 255.0f;
  // A bound on the samples of a ray, against a step too small for float t to advance; the
  // mapper's is the volume's diagonal over the step plus a margin.
  int MaximumIterations = 1;

  // The lighting model and its parameters, with the automatic distances already resolved:
  // Lighting.DerivativeDistance and Lighting.LightStep are > 0 here (see ResolveLighting).
  LightingParameters Lighting;
  std::vector<Light> Lights;
  glm::vec3 Ambient{ 0.0f }; // AmbientColor * AmbientStrength
};

// The lighting parameters as the shader's uniforms get them: a DerivativeDistance of 0 becomes
// 4 * smallestSpacing and a LightStep of 0 becomes 2 * smallestSpacing (world units).
CLOUDVISFILTERS_EXPORT LightingParameters ResolveLighting(
  const LightingParameters& p, double smallestSpacing);

// ---- CloudMarchFS.glsl ----

// Entry and exit distances of the ray o + t d through the box [lo, hi].
CLOUDVISFILTERS_EXPORT glm::vec2 IntersectBox(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi);

// The march along one view ray from nearWorld (t = 0) to farWorld: premultiplied radiance in
// rgb, opacity 1 - T in a. The GLSL computes the two points from the pixel with DCWCMatrix.
CLOUDVISFILTERS_EXPORT glm::vec4 MarchRay(
  const MarchUniforms& u, const glm::dvec3& nearWorld, const glm::dvec3& farWorld);

// ---- CloudLightingCommon.glsl ----

CLOUDVISFILTERS_EXPORT glm::vec3 WorldOfIndex(const MarchUniforms& u, glm::vec3 p);
// WorldToIndex * w: a world displacement in index units.
CLOUDVISFILTERS_EXPORT glm::vec3 WorldToIndex(const MarchUniforms& u, glm::vec3 w);
// The density texture's GL_LINEAR, CLAMP_TO_EDGE fetch at (p + 0.5) / Dimensions: trilinear
// between the lattice voxels around index point p, the edge voxels repeated outside.
CLOUDVISFILTERS_EXPORT float DensityAt(const MarchUniforms& u, glm::vec3 p);
CLOUDVISFILTERS_EXPORT float ExtinctionAt(const MarchUniforms& u, glm::vec3 p);
CLOUDVISFILTERS_EXPORT bool InsideVolume(const MarchUniforms& u, glm::vec3 p);

// ---- CloudLightingNone.glsl, CloudLightingDerivative.glsl, CloudLightingMarch.glsl ----

// Optical depth from index point p toward the light along l (world direction, unit), up to
// maxDistance (world): segments from 0, the first Lighting.LightStep long, each next
// LightStepGrowth times longer, sampled at their midpoints; stops at the first midpoint outside
// the volume or beyond maxDistance, or after LightSteps segments.
CLOUDVISFILTERS_EXPORT float LightOpticalDepth(
  const MarchUniforms& u, glm::vec3 p, glm::vec3 l, float maxDistance);

// The source term S of each model at index point p (docs/lighting.md); d is the unit world
// direction of the view ray. SourceTerm calls the one u.Lighting.Model names, as the mapper
// splices one of the three GLSL files into the march shader.
CLOUDVISFILTERS_EXPORT glm::vec3 SourceTermNone(
  const MarchUniforms& u, glm::vec3 p, float density, glm::vec3 albedo, glm::vec3 d);
CLOUDVISFILTERS_EXPORT glm::vec3 SourceTermDerivative(
  const MarchUniforms& u, glm::vec3 p, float density, glm::vec3 albedo, glm::vec3 d);
CLOUDVISFILTERS_EXPORT glm::vec3 SourceTermMarch(
  const MarchUniforms& u, glm::vec3 p, float density, glm::vec3 albedo, glm::vec3 d);
CLOUDVISFILTERS_EXPORT glm::vec3 SourceTerm(
  const MarchUniforms& u, glm::vec3 p, float density, glm::vec3 albedo, glm::vec3 d);

} // namespace cloudvis

#endif
