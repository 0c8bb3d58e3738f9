// Light without re-marching (issue 12): per light, the optical depth toward it at the texels of
// a grid over the volume, computed once when the field, the transfer function, the extinction
// scale, the step or the lights change, and read by the march (one trilinear lookup per sample
// per light) instead of a nested march toward each light. A texel's value (LightVolumeTexel) and
// the march's lookup (LightVolumeDepth) are defined once in shaders/transport/LightMarch.glsl; the
// GPU computes the grid in a pass of its own (app/rendering/CloudLightVolumeTexture.cxx,
// shaders/CloudLightVolumeFS.glsl) and the CPU here, with the same functions. docs/lighting.md
// states the equations; the quality setting LightingParameters::Transmittance chooses between
// the light volumes and the nested march.
//
// The grid: half the field's resolution per axis (LightVolumeDivisor), corner-aligned (its first
// and last texels sit on the field's first and last voxels, so no sample lies beyond its texels),
// one block of texels per light stacked along z in one 3-D texture (GLSL 1.50 cannot index an
// array of samplers with a light's index).
#ifndef CloudLightVolumes_h
#define CloudLightVolumes_h

#include "CloudMarchUniforms.h"
#include "CloudTransport.h" // LightVolumes
#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

namespace cloudvis
{

// The grid's texels per axis are (n - 1) / LightVolumeDivisor + 1, rounded up, for n voxels.
constexpr int LightVolumeDivisor = 2;

// Texels per axis of one light's block.
CLOUDVISFILTERS_EXPORT glm::ivec3 LightVolumeSize(glm::ivec3 fieldDimensions);

// The uniforms the volume pass marches with: those of the view (`u`), with the light march made
// uniform at the view's step (u.Step), as many segments as the volume's longest ray needs.
CLOUDVISFILTERS_EXPORT MarchUniforms LightVolumeMarch(const MarchUniforms& u);

// Computes them for u.Lights (with vtkSMPTools: a texel's value depends only on its index).
CLOUDVISFILTERS_EXPORT void ComputeLightVolumes(const MarchUniforms& u, LightVolumes& volumes);

// The optical depth toward light `light` at index point p: the trilinear interpolation of its
// block at p's place in the grid (p clamped to the volume), as the GPU's GL_LINEAR fetch.
CLOUDVISFILTERS_EXPORT float LightVolumeDepth(const LightVolumes& volumes,
  const MarchUniforms& u,
  int light,
  glm::vec3 p);

} // namespace cloudvis

#endif
