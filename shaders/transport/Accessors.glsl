// The GPU's accessors of the shared light-transport source (shaders/transport/Transport.glsl
// declares them): what the GLSL reads from textures, the one place where the GPU has code of its
// own. Their C++ definitions, which read the same values from memory, are in
// filters/CloudTransport.h.

uniform sampler3D DensityTexture;  // the field's native texels (R8, R16, R32F or R16F)
uniform sampler1D TransferTexture; // rgb albedo, a = sigma_t per world unit
uniform vec2 TableRange;           // density at the first and last table entries
uniform float TableSize;
uniform sampler3D EmptyDistanceTexture; // Chebyshev distance in bricks to occupied space, /255
uniform sampler3D ExtinctionBoundsTexture; // the path tracer's, per brick: r = minorant, g = majorant
uniform sampler3D LightVolumeTexture; // the light volumes, one block per light stacked along z

float DensityAt(vec3 p)
{
  return texture(DensityTexture, (p + 0.5) / Dimensions).r * DensityScale + DensityBias;
}

float TableCoordinate(float density)
{
  float u = clamp((density - TableRange.x) / (TableRange.y - TableRange.x), 0.0, 1.0);
  return (u * (TableSize - 1.0) + 0.5) / TableSize; // texel centres, as TransferTable::Lookup
}

vec4 TransferAt(float density)
{
  return texture(TransferTexture, TableCoordinate(density));
}

float EmptyBricksAround(vec3 brick)
{
  return floor(texelFetch(EmptyDistanceTexture, ivec3(brick), 0).r * 255.0 + 0.5);
}

// The occupancy filter's bounds are per world unit; ExtinctionUnit makes them per local unit, as
// Optical scales the table's.
vec2 BrickExtinctionBounds(ivec3 brick)
{
  return texelFetch(ExtinctionBoundsTexture, brick, 0).rg * ExtinctionUnit;
}

float LightVolumeFetch(int i, vec3 t)
{
  t.z += float(i) * LightVolumeSize.z;
  return texture(LightVolumeTexture,
    (t + 0.5) / vec3(LightVolumeSize.xy, LightVolumeSize.z * LightVolumeCount)).r;
}

// The multiple-scattering grids (filters/CloudScatteringVolume.h): the one being computed, read
// per cell, the next coarser one's fluence and the finished volume the march reads, interpolated.
uniform sampler3D ScatteringMediumTexture;
uniform sampler3D ScatteringSourceTexture;
uniform sampler3D ScatteringDirectionTexture;
uniform sampler3D ScatteringFluenceTexture;
uniform sampler3D CoarseFluenceTexture;
uniform sampler3D ScatteringVolumeTexture;
uniform sampler3D ScatteringFluxTexture;

vec4 ScatteringMediumAt(ivec3 c)
{
  return texelFetch(ScatteringMediumTexture, c, 0);
}

vec4 ScatteringSourceAt(ivec3 c)
{
  return texelFetch(ScatteringSourceTexture, c, 0);
}

vec4 ScatteringDirectionAt(ivec3 c)
{
  return texelFetch(ScatteringDirectionTexture, c, 0);
}

vec4 ScatteringFluenceAt(ivec3 c)
{
  return texelFetch(ScatteringFluenceTexture, c, 0);
}

vec4 CoarseFluenceFetch(vec3 t)
{
  return texture(CoarseFluenceTexture, (t + 0.5) / ScatteringCoarseSize);
}

vec4 ScatteringVolumeFetch(vec3 t)
{
  return texture(ScatteringVolumeTexture, (t + 0.5) / ScatteringVolumeSize);
}

vec4 ScatteringFluxFetch(vec3 t)
{
  return texture(ScatteringFluxTexture, (t + 0.5) / ScatteringVolumeSize);
}
