// The volumetric path tracer that is cloudvis's ground truth: an unbiased Monte Carlo estimate
// of the light a pixel receives from the same medium the lighting models approximate (extinction
// and albedo from the transfer table, the two-lobe Henyey-Greenstein phase, the same lights and
// ambient), with every order of scattering. The equations are in docs/lighting.md ("The path
// tracer"); vtkCloudPathTracer renders images with it.
//
// The path tracer is written once, for the CPU and the GPU, in shaders/transport/PathTrace.glsl
// (docs/transport.md): random numbers that are a pure function of (pixel, sample, dimension,
// seed) computed with 32-bit unsigned integer operations, the majorant walk through the
// occupancy bricks, free-flight and ratio tracking, phase sampling, next-event estimation and the
// paths. A pixel's samples therefore depend neither on threads nor on the order in which pixels
// are rendered, and the GPU draws the very same paths. The functions here are its C++ entry
// points: what the shader reads from uniforms and textures comes in MarchUniforms (SetUpMarch,
// CloudMarchUniforms.h) and PathTraceUniforms (CloudTransport.h), so the path tracer honours the
// field's whole geometry and computes in the same local frame as the march. Positions p are voxel
// index points; directions d are unit vectors of the local frame (whose axes are the world's).
#ifndef CloudPathTrace_h
#define CloudPathTrace_h

#include "CloudReferenceMarch.h"
#include "CloudTransport.h"
#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace cloudvis
{

// Each function below calls its one definition in shaders/transport/PathTrace.glsl, where it is
// documented, with the uniforms TransportOf fills from `u` and `pt`.

// Where a random number comes from: the pixel (j * width + i), the sample index within the
// pixel, the seed, and the dimension (the count of random numbers drawn so far), all 0 at first.
struct RandomStream : glsl::Transport::RandomStream
{
  RandomStream()
    : glsl::Transport::RandomStream()
  {
  }
};

// The 4-D PCG hash of Jarzynski and Olano ("Hash Functions for GPU Rendering", JCGT 2020).
CLOUDVISFILTERS_EXPORT glm::uvec4 Pcg4d(glm::uvec4 v);
// The next uniform number in [0, 1) of a stream; the dimension then advances.
CLOUDVISFILTERS_EXPORT float NextRandom(RandomStream& rng);

// The cosine of a scattering angle drawn from HG(g, mu) with xi in [0, 1).
CLOUDVISFILTERS_EXPORT float SampleHenyeyGreensteinCosine(float g, float xi);
// A new direction of travel after scattering along d, drawn from Phase(lighting, mu, 1) (the
// droplets: from the mean of its channels), and in `weight` the path's factor Phase / pdf.
CLOUDVISFILTERS_EXPORT glm::vec3 SamplePhaseDirection(
  const LightingParameters& lighting, glm::vec3 d, RandomStream& rng, glm::vec3& weight);

// Next-event estimation at scattering point p for light arriving along unit direction d.
CLOUDVISFILTERS_EXPORT glm::vec3 DirectLight(
  const MarchUniforms& u, const PathTraceUniforms& pt, glm::vec3 p, glm::vec3 d, RandomStream& rng);

// One sample of the pixel whose view ray runs from nearPoint to farPoint (in the local frame, as
// MarchRay's; vtkCloudReferenceRenderer::PixelRay gives them): one path's premultiplied radiance
// in rgb and one estimate of the pixel's opacity in a. A caller that traces many paths fills a
// TransportOf(u, pt) per thread and calls its TracePath.
CLOUDVISFILTERS_EXPORT glm::vec4 TracePath(const MarchUniforms& u,
  const PathTraceUniforms& pt,
  glm::vec3 nearPoint,
  glm::vec3 farPoint,
  RandomStream& rng);

} // namespace cloudvis

#endif
