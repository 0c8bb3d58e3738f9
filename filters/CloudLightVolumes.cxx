#include "CloudLightVolumes.h"

#include "CloudTransport.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{

glm::ivec3 LightVolumeSize(glm::ivec3 n)
{
  return (glm::max(n, 1) - 1 + (LightVolumeDivisor - 1)) / LightVolumeDivisor + 1;
}

MarchUniforms LightVolumeMarch(const MarchUniforms& u)
{
  MarchUniforms march = u;
  march.Lighting.LightSteps = u.LongestRaySamples + 1;
  march.Lighting.LightStep = u.Step;
  march.Lighting.LightStepGrowth = 1.0f;
  return march;
}

void ComputeLightVolumes(const MarchUniforms& u, LightVolumes& volumes)
{
  const MarchUniforms march = LightVolumeMarch(u);
  const glm::ivec3 size = LightVolumeSize(u.Dimensions);
  volumes.Size = size;
  volumes.Lights = int(u.Lights.size());
  volumes.Depth.assign(std::size_t(size.x) * size.y * size.z * volumes.Lights, 0.0f);
  float* depth = volumes.Depth.data();
  const vtkIdType slices = vtkIdType(size.z) * volumes.Lights;
  const auto computeSlices = [&](vtkIdType begin, vtkIdType end)
  {
    // This thread's uniforms of the light-volume pass (the GPU's are LightVolumeMarch's too).
    glsl::Transport transport = TransportOf(march);
    transport.LightVolumeSize = glm::vec3(size);
    for (vtkIdType slice = begin; slice < end; ++slice)
    {
      const int light = int(slice / size.z);
      const int k = int(slice % size.z);
      for (int j = 0; j < size.y; ++j)
        for (int i = 0; i < size.x; ++i)
          depth[(std::size_t(slice) * size.y + j) * size.x + i] =
            transport.LightVolumeTexel(light, glm::vec3(i, j, k));
    }
  };
  vtkSMPTools::For(0, slices, computeSlices);
}

float LightVolumeDepth(const LightVolumes& volumes, const MarchUniforms& u, int light, glm::vec3 p)
{
  glsl::Transport transport = TransportOf(u);
  transport.Volumes = &volumes;
  transport.LightVolumeSize = glm::vec3(volumes.Size);
  transport.LightVolumeCount = float(volumes.Lights);
  return transport.LightVolumeDepth(light, p);
}

} // namespace cloudvis
