#include "CloudReferenceMarch.h"

#include <algorithm>
#include <cmath>

namespace cloudvis
{

// ---- The shared source's medium ----

glm::vec2 IntersectBox(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi)
{
  return glsl::Transport{}.IntersectBox(o, d, lo, hi);
}

glm::vec3 LocalOfIndex(const MarchUniforms& u, glm::vec3 p)
{
  return TransportOf(u).LocalOfIndex(p);
}

glm::vec3 IndexOfLocal(const MarchUniforms& u, glm::vec3 x)
{
  return TransportOf(u).IndexOfLocal(x);
}

glm::vec3 LocalToIndex(const MarchUniforms& u, glm::vec3 w)
{
  return u.LocalToIndex * w;
}

float DensityAt(const MarchUniforms& u, glm::vec3 p)
{
  return TransportOf(u).DensityAt(p);
}

float ExtinctionAt(const MarchUniforms& u, glm::vec3 p)
{
  return TransportOf(u).ExtinctionAt(p);
}

bool InsideVolume(const MarchUniforms& u, glm::vec3 p)
{
  return TransportOf(u).InsideVolume(p);
}

float LightOpticalDepth(const MarchUniforms& u,
  glm::vec3 p,
  float sigmaHere,
  glm::vec3 indexStep,
  float maxDistance)
{
  return TransportOf(u).LightOpticalDepth(p, sigmaHere, indexStep, maxDistance);
}

// ---- The march: CloudMarchFS.glsl's main() ----

glm::vec4 MarchRay(const MarchUniforms& u, glm::vec3 nearPoint, glm::vec3 farPoint)
{
  glsl::Transport transport = TransportOf(u);
  return MarchRay(transport, nearPoint, farPoint);
}

glm::vec4 MarchRay(glsl::Transport& transport, glm::vec3 nearPoint, glm::vec3 farPoint)
{
  const MarchUniforms& u = *transport.March;
  const glm::vec3 toFar = farPoint - nearPoint;
  const float rayLength = glm::length(toFar);
  const glm::vec3 d = toFar / rayLength;                      // view direction, unit
  const glm::vec3 origin = transport.IndexOfLocal(nearPoint); // index point at t = 0
  const glm::vec3 direction = u.LocalToIndex * d;             // index units per local unit

  const float tOpaque = rayLength; // no opaque geometry: the depth buffer holds the far plane
  const glm::vec2 tBox =
    transport.IntersectBox(origin, direction, glm::vec3(0.0f), glm::vec3(u.Dimensions) - 1.0f);
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
      const float density = transport.DensityAt(p);
      const glm::vec4 optical = transport.Optical(density);
      const float sigma_t = optical.a;
      if (sigma_t > 0.0f)
      {
        const float stepT = std::exp(-sigma_t * u.Step);
        // In-scattering integrated over the step: S * (1 - exp(-sigma_t dt)), exact for S
        // constant over the step, so the sum does not depend on the step size.
        radiance += T * transport.SourceTerm(p, density, glm::vec3(optical), d) * (1.0f - stepT);
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

} // namespace cloudvis
