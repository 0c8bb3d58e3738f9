// What the lighting models share (twins of filters/CloudLighting.h and CloudReferenceMarch.h):
// the lights, the phase function, and density and extinction lookups at any point of the volume.
// p is a point in voxel index space; LocalOfIndex(p) gives it in the local frame, where the
// lights are (cloudvis::LocalLight), and LocalToIndex turns a local displacement into index units.

// MAX_LIGHTS is cloudvis::LightingLimits::MaxLights (filters/CloudLighting.h), the one limit the
// scene reader, the mapper and the CPU renderers all enforce, substituted at the top of
// CloudMarchFS.glsl with Pi and DirectionalLightDistance.
uniform int LightPositional[MAX_LIGHTS];
uniform vec3 LightPosition[MAX_LIGHTS];  // local; positional lights
uniform vec3 LightDirection[MAX_LIGHTS]; // unit, toward the light; directional lights
uniform vec3 LightRadiance[MAX_LIGHTS];  // color * intensity
uniform vec3 LightAttenuation[MAX_LIGHTS]; // for local distances
// Per directional light, precomputed: its direction in index units per local unit, and the
// derivative model's offset h l in index units.
uniform vec3 LightIndexDirection[MAX_LIGHTS];
uniform vec3 LightIndexOffset[MAX_LIGHTS];
uniform vec3 Ambient; // ambient color * strength

// The density in the data's units: the native texels, filtered, scaled back.
float DensityAt(vec3 p)
{
  return texture(DensityTexture, (p + 0.5) / Dimensions).r * DensityScale + DensityBias;
}

float ExtinctionAt(vec3 p)
{
  return Optical(DensityAt(p)).a;
}

bool InsideVolume(vec3 p)
{
  return all(greaterThanEqual(p, vec3(0.0))) && all(lessThanEqual(p, Dimensions - 1.0));
}

// Direction toward light i from local point x, the local distance to it and its falloff.
void SampleLight(int i, vec3 x, out vec3 l, out float lightDistance, out float falloff)
{
  if (LightPositional[i] == 0)
  {
    l = LightDirection[i];
    lightDistance = DirectionalLightDistance;
    falloff = 1.0;
    return;
  }
  vec3 toLight = LightPosition[i] - x;
  float r = length(toLight);
  lightDistance = r;
  l = toLight / max(r, 1e-20);
  vec3 k = LightAttenuation[i];
  falloff = 1.0 / max(k.x + k.y * r + k.z * r * r, 1e-20);
}

float HenyeyGreenstein(float g, float mu)
{
  float g2 = g * g;
  float denominator = 1.0 + g2 - 2.0 * g * mu;
  return (1.0 - g2) / (4.0 * Pi * denominator * sqrt(denominator));
}
