// The CPU twin of the GPU march: shaders/CloudMarchFS.glsl (MarchRay is its main()) and the
// lighting models of shaders/CloudLighting{Common,None,Derivative,March}.glsl. Each function
// here has the name, the arguments and the order of operations of its GLSL counterpart, so the
// two can be read side by side; what the shader gets from uniforms and textures it gets from
// MarchUniforms (CloudMarchUniforms.h, where SetUpMarch computes them for both). Like the GPU it
// computes in the local frame of that header, never in world coordinates. The equations are in
// docs/lighting.md. Unlike the GPU this march never skips empty bricks (skipping does not change
// the sum, since empty bricks have sigma_t = 0), never jitters, and has no opaque geometry
// ending the rays. It computes in float, as the GPU does, and samples textures exactly (the
// GPU's linear filter weights have 8 fractional bits).
#ifndef CloudReferenceMarch_h
#define CloudReferenceMarch_h

#include "CloudLighting.h"
#include "CloudMarchUniforms.h"
#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

namespace cloudvis
{

// ---- CloudMarchFS.glsl ----

// Entry and exit distances of the ray o + t d through the box [lo, hi].
CLOUDVISFILTERS_EXPORT glm::vec2 IntersectBox(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi);

// Albedo in rgb and the extinction per local unit in a, at a density.
CLOUDVISFILTERS_EXPORT glm::vec4 Optical(const MarchUniforms& u, float density);

CLOUDVISFILTERS_EXPORT glm::vec3 LocalOfIndex(const MarchUniforms& u, glm::vec3 p);
CLOUDVISFILTERS_EXPORT glm::vec3 IndexOfLocal(const MarchUniforms& u, glm::vec3 x);
// LocalToIndex * w: a local displacement in index units.
CLOUDVISFILTERS_EXPORT glm::vec3 LocalToIndex(const MarchUniforms& u, glm::vec3 w);

// The march along one view ray from nearPoint (t = 0) to farPoint, both in the local frame:
// premultiplied radiance in rgb, opacity 1 - T in a. The GLSL computes the two points from the
// pixel with DCLocalMatrix.
CLOUDVISFILTERS_EXPORT glm::vec4 MarchRay(const MarchUniforms& u,
  glm::vec3 nearPoint,
  glm::vec3 farPoint);

// ---- CloudLightingCommon.glsl ----

// The density texture's GL_LINEAR, CLAMP_TO_EDGE fetch at (p + 0.5) / Dimensions, in the data's
// units: the trilinear interpolation of the normalized texels around index point p (the edge
// voxels repeated outside), times Density.Scale plus Density.Bias.
CLOUDVISFILTERS_EXPORT float DensityAt(const MarchUniforms& u, glm::vec3 p);
CLOUDVISFILTERS_EXPORT float ExtinctionAt(const MarchUniforms& u, glm::vec3 p);
CLOUDVISFILTERS_EXPORT bool InsideVolume(const MarchUniforms& u, glm::vec3 p);

// ---- CloudLightingNone.glsl, CloudLightingDerivative.glsl, CloudLightingMarch.glsl ----

// Optical depth from index point p toward a light, to where the light's ray leaves the volume
// or maxDistance (local), whichever is nearer: indexStep is the unit direction toward it in index
// units per local unit (LocalToIndex(u, l)), sigmaHere the extinction at p. Lighting.LightSteps
// segments growing by LightStepGrowth span that reach (the first at least Lighting.LightStep
// long, so a short reach takes fewer), each integrated by the trapezoid rule from the extinction
// at its ends. A p a hair outside the volume (a sample on a face, by rounding) starts on the face.
CLOUDVISFILTERS_EXPORT float LightOpticalDepth(const MarchUniforms& u,
  glm::vec3 p,
  float sigmaHere,
  glm::vec3 indexStep,
  float maxDistance);

// The source term S of each model at index point p (docs/lighting.md); d is the unit direction
// of the view ray. SourceTerm calls the one u.Lighting.Model names, as the mapper
// splices one of the three GLSL files into the march shader.
CLOUDVISFILTERS_EXPORT glm::vec3 SourceTermNone(const MarchUniforms& u,
  glm::vec3 p,
  float density,
  glm::vec3 albedo,
  glm::vec3 d);
CLOUDVISFILTERS_EXPORT glm::vec3 SourceTermDerivative(const MarchUniforms& u,
  glm::vec3 p,
  float density,
  glm::vec3 albedo,
  glm::vec3 d);
CLOUDVISFILTERS_EXPORT glm::vec3 SourceTermMarch(const MarchUniforms& u,
  glm::vec3 p,
  float density,
  glm::vec3 albedo,
  glm::vec3 d);
CLOUDVISFILTERS_EXPORT glm::vec3 SourceTerm(const MarchUniforms& u,
  glm::vec3 p,
  float density,
  glm::vec3 albedo,
  glm::vec3 d);

} // namespace cloudvis

#endif
