#include "CloudPathTrace.h"

namespace cloudvis
{

glm::uvec4 Pcg4d(glm::uvec4 v)
{
  return glsl::Transport{}.Pcg4d(v);
}

float NextRandom(RandomStream& rng)
{
  return glsl::Transport{}.NextRandom(rng);
}

float SampleHenyeyGreensteinCosine(float g, float xi)
{
  return glsl::Transport{}.SampleHenyeyGreensteinCosine(g, xi);
}

glm::vec3 SamplePhaseDirection(
  const LightingParameters& lighting, glm::vec3 d, RandomStream& rng, glm::vec3& weight)
{
  return TransportOf(lighting).SamplePhaseDirection(d, rng, weight);
}

glm::vec3 DirectLight(
  const MarchUniforms& u, const PathTraceUniforms& pt, glm::vec3 p, glm::vec3 d, RandomStream& rng)
{
  return TransportOf(u, pt).DirectLight(p, d, rng);
}

glm::vec4 TracePath(const MarchUniforms& u,
  const PathTraceUniforms& pt,
  glm::vec3 nearPoint,
  glm::vec3 farPoint,
  RandomStream& rng)
{
  return TransportOf(u, pt).TracePath(nearPoint, farPoint, rng);
}

} // namespace cloudvis
