// Filling the shared light-transport source's uniforms on the CPU (CloudTransport.h), and the
// lighting functions' C++ entry points that CloudLighting.h declares.
#include "CloudTransport.h"

#include "CloudLighting.h"
#include "CloudScatteringVolume.h"

namespace cloudvis
{
namespace
{
void SetPhase(glsl::Transport& t, const LightingParameters& p)
{
  t.PhaseType = int(p.Phase);
  if (p.Phase == PhaseModel::Droplets)
  {
    const DropletPhaseTable& table = DropletPhaseOf(p);
    t.DropletTable = &table;
    t.DropletMeanCosine = DropletMeanCosineOf(table);
    t.DropletSecondMoment = DropletSecondMomentOf(table);
  }
  t.PhaseG1 = p.PhaseG1;
  t.PhaseG2 = p.PhaseG2;
  t.PhaseLobeWeight = p.PhaseLobeWeight;
  t.MultipleScatteringOctaves = p.MultipleScatteringOctaves;
  t.ScatteringFalloff = p.ScatteringFalloff;
  t.ExtinctionFalloff = p.ExtinctionFalloff;
  t.EccentricityFalloff = p.EccentricityFalloff;
  t.PowderStrength = p.PowderStrength;
}

void SetLight(glsl::Transport& t, int i, const LocalLight& light)
{
  t.LightPositional[i] = light.Positional ? 1 : 0;
  t.LightPosition[i] = light.Position;
  t.LightDirection[i] = light.Direction;
  t.LightRadiance[i] = light.Radiance;
  t.LightAttenuation[i] = light.Attenuation;
  t.LightIndexDirection[i] = light.IndexDirection;
  t.LightIndexOffset[i] = light.IndexOffset;
}
}

glsl::Transport TransportOf(const LightingParameters& p)
{
  glsl::Transport t{};
  SetPhase(t, p);
  return t;
}

glsl::Transport TransportOf(const MarchUniforms& u)
{
  glsl::Transport t{};
  t.March = &u;
  t.Model = u.Lighting.Model;
  t.Dimensions = glm::vec3(u.Dimensions);
  t.IndexToLocal = u.IndexToLocal;
  t.LocalToIndex = u.LocalToIndex;
  t.DensityScale = u.Density.Scale;
  t.DensityBias = u.Density.Bias;
  t.ExtinctionUnit = u.ExtinctionUnit;
  t.SkipEmptySpace = 0;

  t.LightCount = int(u.Lights.size());
  for (int i = 0; i < t.LightCount; ++i)
  {
    SetLight(t, i, u.Lights[std::size_t(i)]);
  }
  t.Ambient = u.Ambient;

  const LightingParameters& p = u.Lighting;
  SetPhase(t, p);
  t.LightSteps = p.LightSteps;
  t.LightStep = p.LightStep;
  t.LightStepGrowth = p.LightStepGrowth;
  t.DerivativeDistance = p.DerivativeDistance;
  t.DerivativeSlopeScale = u.DerivativeSlopeScale;
  if (p.Transmittance == LightTransmittance::Volumes && u.LightDepths != nullptr)
  {
    t.Volumes = u.LightDepths;
    t.LightTransmittanceVolumes = 1;
    t.LightVolumeSize = glm::vec3(u.LightDepths->Size);
    t.LightVolumeCount = float(u.LightDepths->Lights);
  }
  if (u.ExternalDepths != nullptr && !u.ExternalDepths->Empty())
  {
    const OpticalDepthGrid& grid = *u.ExternalDepths;
    t.External = &grid;
    t.ExternalOpticalDepths = 1;
    t.ExternalDepthSize = glm::vec3(grid.Size[0], grid.Size[1], grid.Size[2]);
    t.ExternalDepthCount = float(grid.Lights);
    t.IndexToExternal = u.IndexToExternal;
  }
  if ((u.MultipleScattering != nullptr || u.ScatteringVolumeTextures) &&
    p.Model == LightingModel::March)
  {
    t.Scattering = u.MultipleScattering;
    t.ScatteringVolumeOn = 1;
    t.ScatteringVolumeSize = glm::vec3(ScatteringVolumeSize(u.Dimensions));
  }
  if (u.ExternalScattering != nullptr && !u.ExternalScattering->Empty() && UsesScatteringVolume(p))
  {
    // A whole field's volume, on the GPU bound in place of the field's own.
    t.Scattering = &u.ExternalScattering->Volume;
    t.ScatteringVolumeOn = 1;
    t.ScatteringVolumeSize = glm::vec3(u.ExternalScattering->Volume.Size);
    t.ExternalScatteringVolume = 1;
    t.IndexToScattering = u.IndexToScattering;
  }
  return t;
}

glsl::Transport TransportOf(const MarchUniforms& u, const PathTraceUniforms& pt)
{
  glsl::Transport t = TransportOf(u);
  t.PathTrace = &pt;
  t.BrickCount = glm::vec3(pt.BrickCount);
  t.BrickSize = pt.BrickSize;
  t.MaxBounces = pt.MaxBounces;
  t.RouletteBounces = pt.RouletteBounces;
  t.LightGuidedNextEvents = pt.LightGuidedNextEvents;
  return t;
}

// ---- CloudLighting.h ----

float HenyeyGreenstein(float g, float mu)
{
  return glsl::Transport{}.HenyeyGreenstein(g, mu);
}

glm::vec3 Phase(const LightingParameters& p, float mu, float eccentricityScale)
{
  return TransportOf(p).Phase(mu, eccentricityScale);
}

const DropletPhaseTable& DropletPhaseOf(const LightingParameters& p)
{
  return DropletPhase(p.DropletEffectiveRadius, p.DropletEffectiveVariance);
}

glm::vec3 ScatteredFraction(const LightingParameters& p, float mu, float tau, glm::vec3 albedo)
{
  return TransportOf(p).ScatteredFraction(mu, tau, albedo);
}

LightSample SampleLight(const LocalLight& light, glm::vec3 x)
{
  glsl::Transport t{};
  SetLight(t, 0, light);
  LightSample s;
  t.SampleLight(0, x, s.Direction, s.Distance, s.Falloff);
  return s;
}

} // namespace cloudvis
