// The CPU's march: MarchRay is the C++ of shaders/CloudMarchFS.glsl's main(), with the name, the
// arguments and the order of operations of the GLSL, and it calls the lighting models' source
// terms and the medium's lookups from their one definition in shaders/transport/
// (through CloudTransport.h); the other functions here are C++ entry points to that source. What
// the shader gets from uniforms and textures it gets from MarchUniforms (CloudMarchUniforms.h,
// where SetUpMarch computes them for both). Like the GPU it computes in the local frame of that
// header, never in world coordinates. The equations are in docs/lighting.md. Unlike the GPU this
// march never skips empty bricks (skipping does not change the sum, since empty bricks have
// sigma_t = 0), never jitters, and has no opaque geometry ending the rays. It computes in float, as
// the GPU does, and samples textures exactly (the GPU's linear filter weights have 8 fractional
// bits).
#ifndef CloudReferenceMarch_h
#define CloudReferenceMarch_h

#include "CloudLighting.h"
#include "CloudMarchUniforms.h"
#include "CloudTransport.h"
#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

namespace cloudvis
{

// ---- The shared source's medium (Medium.glsl) ----

// Entry and exit distances of the ray o + t d through the box [lo, hi].
CLOUDVISFILTERS_EXPORT glm::vec2 IntersectBox(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi);

CLOUDVISFILTERS_EXPORT glm::vec3 LocalOfIndex(const MarchUniforms& u, glm::vec3 p);
CLOUDVISFILTERS_EXPORT glm::vec3 IndexOfLocal(const MarchUniforms& u, glm::vec3 x);
// LocalToIndex * w: a local displacement in index units.
CLOUDVISFILTERS_EXPORT glm::vec3 LocalToIndex(const MarchUniforms& u, glm::vec3 w);

// The density in the data's units at index point p: the density texture's GL_LINEAR,
// CLAMP_TO_EDGE fetch at (p + 0.5) / Dimensions, computed exactly (the trilinear interpolation
// of the normalized texels around p, the edge voxels repeated outside), times Density.Scale plus
// Density.Bias.
CLOUDVISFILTERS_EXPORT float DensityAt(const MarchUniforms& u, glm::vec3 p);
CLOUDVISFILTERS_EXPORT float ExtinctionAt(const MarchUniforms& u, glm::vec3 p);
CLOUDVISFILTERS_EXPORT bool InsideVolume(const MarchUniforms& u, glm::vec3 p);

// ---- The march: CloudMarchFS.glsl's main() ----

// The march along one view ray from nearPoint (t = 0) to farPoint, both in the local frame:
// premultiplied radiance in rgb, opacity 1 - T in a. The GLSL computes the two points from the
// pixel with DCLocalMatrix.
CLOUDVISFILTERS_EXPORT glm::vec4 MarchRay(const MarchUniforms& u,
  glm::vec3 nearPoint,
  glm::vec3 farPoint);
// The same with the shared source's uniforms filled once (TransportOf(u)), for a caller that
// marches many rays: one `transport` per thread.
CLOUDVISFILTERS_EXPORT glm::vec4 MarchRay(glsl::Transport& transport,
  glm::vec3 nearPoint,
  glm::vec3 farPoint);

// Optical depth from index point p toward a light, to where the light's ray leaves the volume
// or maxDistance (local), whichever is nearer: indexStep is the unit direction toward it in index
// units per local unit (LocalToIndex(u, l)), sigmaHere the extinction at p (Medium.glsl's
// LightOpticalDepth, with u.Lighting's light steps).
CLOUDVISFILTERS_EXPORT float LightOpticalDepth(const MarchUniforms& u,
  glm::vec3 p,
  float sigmaHere,
  glm::vec3 indexStep,
  float maxDistance);

} // namespace cloudvis

#endif
