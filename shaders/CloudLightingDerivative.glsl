// Lighting model "derivative": for each light one more density sample a distance h toward it;
// diffuse = clamp((rho(p) - rho(p + h l)) / (h * density unit), 0, 1) is large where density
// falls toward the light, so the side of the cloud facing the light is bright. No shadowing, no
// phase. The mapper calls one term per light with a constant index (see LightingSource).
uniform float DerivativeDistance;   // h, local units
uniform float DerivativeSlopeScale; // 1 / (h in world units * density unit)

float DerivativeDiffuse(float densityHere, float densityTowardLight, float slopeScale)
{
  return clamp((densityHere - densityTowardLight) * slopeScale, 0.0, 1.0);
}

// A directional light: the offset h l in index units is the same everywhere (precomputed).
vec3 DirectionalLightTerm(int i, vec3 p, float density, vec3 albedo, vec3 d)
{
  float towardLight = DensityAt(p + LightIndexOffset[i]);
  return LightRadiance[i] * DerivativeDiffuse(density, towardLight, DerivativeSlopeScale);
}

vec3 PointLightTerm(int i, vec3 p, float density, vec3 albedo, vec3 d)
{
  vec3 l;
  float lightDistance, falloff;
  SampleLight(i, LocalOfIndex(p), l, lightDistance, falloff);
  float towardLight = DensityAt(p + LocalToIndex * (DerivativeDistance * l));
  return LightRadiance[i] * falloff * DerivativeDiffuse(density, towardLight, DerivativeSlopeScale);
}
