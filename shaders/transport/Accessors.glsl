// The GPU's accessors of the shared light-transport source (shaders/transport/Medium.glsl
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
uniform sampler3D ExternalDepthTexture; // depths from outside the field, blocks as the above
uniform sampler2D DropletPhaseTexture; // the droplets' table: row 0 its phase, row 1 its CDF

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

vec3 DropletPhaseNode(int i)
{
  return texelFetch(DropletPhaseTexture, ivec2(i, 0), 0).rgb;
}

vec3 DropletCdfNode(int i)
{
  return texelFetch(DropletPhaseTexture, ivec2(i, 1), 0).rgb;
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

float ExternalDepthFetch(int i, vec3 t)
{
  t.z += float(i) * ExternalDepthSize.z;
  return texture(ExternalDepthTexture,
    (t + 0.5) / vec3(ExternalDepthSize.xy, ExternalDepthSize.z * ExternalDepthCount)).r;
}

// The multiple-scattering grids (filters/CloudScatteringVolume.h): the one being computed, read
// per cell, and the next coarser one's fluence, interpolated, are 2-D atlases of their layers
// (layer k's tile is column k % columns, row k / columns: a pass over an atlas is spread among
// llvmpipe's threads, which share a draw by 64 x 64 tiles of its target, where a grid's layer is
// one); the finished volume the march reads (the finest grid's fluence and flux) is 3-D,
// interpolated by the texture unit.
uniform sampler2D ScatteringMediumTexture;
uniform sampler2D ScatteringSourceTexture;
uniform sampler2D ScatteringDirectionTexture;
uniform sampler2D ScatteringFluenceTexture;
uniform sampler2D CoarseFluenceTexture;
uniform float ScatteringAtlasColumns; // layers per row of the computed grid's atlases
uniform float CoarseAtlasColumns;     // and of the coarser grid's
uniform sampler3D ScatteringVolumeTexture;
uniform sampler3D ScatteringFluxTexture;

// Cell c's texel in the atlas of a grid of `size` texels, and the cell of an atlas texel.
ivec2 AtlasTexel(ivec3 c, vec3 size, float columns)
{
  int n = int(columns);
  return ivec2(c.x + (c.z % n) * int(size.x), c.y + (c.z / n) * int(size.y));
}

ivec3 AtlasCell(ivec2 texel, vec3 size, float columns)
{
  ivec2 tile = texel / ivec2(size.xy);
  return ivec3(texel - tile * ivec2(size.xy), tile.y * int(columns) + tile.x);
}

vec4 ScatteringMediumAt(ivec3 c)
{
  return texelFetch(
    ScatteringMediumTexture, AtlasTexel(c, ScatteringVolumeSize, ScatteringAtlasColumns), 0);
}

vec4 ScatteringSourceAt(ivec3 c)
{
  return texelFetch(
    ScatteringSourceTexture, AtlasTexel(c, ScatteringVolumeSize, ScatteringAtlasColumns), 0);
}

vec4 ScatteringDirectionAt(ivec3 c)
{
  return texelFetch(
    ScatteringDirectionTexture, AtlasTexel(c, ScatteringVolumeSize, ScatteringAtlasColumns), 0);
}

vec4 ScatteringFluenceAt(ivec3 c)
{
  return texelFetch(
    ScatteringFluenceTexture, AtlasTexel(c, ScatteringVolumeSize, ScatteringAtlasColumns), 0);
}

// GL_LINEAR with CLAMP_TO_EDGE of layer `layer` at texel coordinate xy, within its tile: the
// coordinate clamped to the tile's first and last texel centres reads what clamped indices read.
vec4 AtlasBilinear(sampler2D atlas, vec2 xy, int layer, vec3 size, float columns)
{
  int n = int(columns);
  vec2 tile = vec2(float(layer % n), float(layer / n)) * size.xy;
  return texture(
    atlas, (tile + clamp(xy, vec2(0.0), size.xy - 1.0) + 0.5) / vec2(textureSize(atlas, 0)));
}

// Trilinear as the CPU's fetch::Trilinear: the layers floor(t.z) and the next, clamped, weighted by
// fract(t.z).
vec4 CoarseFluenceFetch(vec3 t)
{
  float z0 = floor(t.z);
  int l0 = int(clamp(z0, 0.0, ScatteringCoarseSize.z - 1.0));
  int l1 = int(clamp(z0 + 1.0, 0.0, ScatteringCoarseSize.z - 1.0));
  return mix(
    AtlasBilinear(CoarseFluenceTexture, t.xy, l0, ScatteringCoarseSize, CoarseAtlasColumns),
    AtlasBilinear(CoarseFluenceTexture, t.xy, l1, ScatteringCoarseSize, CoarseAtlasColumns),
    t.z - z0);
}

vec4 ScatteringVolumeFetch(vec3 t)
{
  return texture(ScatteringVolumeTexture, (t + 0.5) / ScatteringVolumeSize);
}

vec4 ScatteringFluxFetch(vec3 t)
{
  return texture(ScatteringFluxTexture, (t + 0.5) / ScatteringVolumeSize);
}
