#include "CloudLightVolumes.h"

#include "CloudReferenceMarch.h"

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

namespace
{
// Index units of the field per texel of the grid and its inverse, per axis (0 on an axis of one
// voxel, never a division by 0).
glm::vec3 IndexPerTexel(glm::ivec3 dimensions, glm::ivec3 size)
{
  return glm::vec3(dimensions - 1) / glm::vec3(glm::max(size - 1, 1));
}
glm::vec3 TexelPerIndex(glm::ivec3 dimensions, glm::ivec3 size)
{
  return glm::vec3(size - 1) / glm::vec3(glm::max(dimensions - 1, 1));
}
}

float LightVolumeTexel(const MarchUniforms& u, int light, glm::ivec3 texel, glm::ivec3 size)
{
  const glm::vec3 p = glm::vec3(texel) * IndexPerTexel(u.Dimensions, size);
  const LocalLight& source = u.Lights[std::size_t(light)];
  const LightSample s = SampleLight(source, LocalOfIndex(u, p));
  const glm::vec3 indexStep =
    source.Positional ? LocalToIndex(u, s.Direction) : source.IndexDirection;
  return LightOpticalDepth(u, p, ExtinctionAt(u, p), indexStep, s.Distance);
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
    for (vtkIdType slice = begin; slice < end; ++slice)
    {
      const int light = int(slice / size.z);
      const int k = int(slice % size.z);
      for (int j = 0; j < size.y; ++j)
        for (int i = 0; i < size.x; ++i)
          depth[(std::size_t(slice) * size.y + j) * size.x + i] =
            LightVolumeTexel(march, light, glm::ivec3(i, j, k), size);
    }
  };
  vtkSMPTools::For(0, slices, computeSlices);
}

float LightVolumeDepth(const LightVolumes& volumes, const MarchUniforms& u, int light, glm::vec3 p)
{
  // The GLSL's texture coordinate, in texels of the block: p clamped to the volume and scaled;
  // the corner alignment keeps it within [0, size - 1], so the interpolation never reads another
  // light's block.
  const glm::vec3 t = glm::clamp(p, glm::vec3(0.0f), glm::vec3(u.Dimensions - 1)) *
    TexelPerIndex(u.Dimensions, volumes.Size);
  const glm::ivec3 size = volumes.Size;
  int i0[3], i1[3];
  float f[3];
  for (int a = 0; a < 3; ++a)
  {
    const float fl = std::floor(t[a]);
    f[a] = t[a] - fl;
    i0[a] = std::min(std::max(int(fl), 0), size[a] - 1);
    i1[a] = std::min(i0[a] + 1, size[a] - 1);
  }
  const std::size_t block = std::size_t(light) * size.z;
  const auto texel = [&](int x, int y, int z)
  { return volumes.Depth[((block + std::size_t(z)) * size.y + y) * size.x + std::size_t(x)]; };
  const auto lerp = [](float a, float b, float w) { return a + w * (b - a); };
  const float c00 = lerp(texel(i0[0], i0[1], i0[2]), texel(i1[0], i0[1], i0[2]), f[0]);
  const float c10 = lerp(texel(i0[0], i1[1], i0[2]), texel(i1[0], i1[1], i0[2]), f[0]);
  const float c01 = lerp(texel(i0[0], i0[1], i1[2]), texel(i1[0], i0[1], i1[2]), f[0]);
  const float c11 = lerp(texel(i0[0], i1[1], i1[2]), texel(i1[0], i1[1], i1[2]), f[0]);
  return lerp(lerp(c00, c10, f[1]), lerp(c01, c11, f[1]), f[2]);
}

} // namespace cloudvis
