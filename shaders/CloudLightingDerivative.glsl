// Lighting model "derivative": for each light one more density sample a distance h toward it;
// diffuse = clamp((rho(p) - rho(p + h l)) / h, 0, 1) is large where density falls toward the
// light, so the side of the cloud facing the light is bright. No shadowing, no phase.
uniform float DerivativeDistance; // h, world units

float DerivativeDiffuse(float densityHere, float densityTowardLight, float h, float densityRange)
{
  return clamp((densityHere - densityTowardLight) / (h * densityRange), 0.0, 1.0);
}

vec3 SourceTerm(vec3 p, float density, vec3 albedo, vec3 d)
{
  vec3 x = WorldOfIndex(p);
  vec3 light = Ambient;
  for (int i = 0; i < LightCount; ++i)
  {
    vec3 l;
    float lightDistance, falloff;
    SampleLight(i, x, l, lightDistance, falloff);
    float towardLight = DensityAt(p + WorldToIndex * (DerivativeDistance * l));
    light += LightRadiance[i] * falloff *
      DerivativeDiffuse(density, towardLight, DerivativeDistance, TableRange.y - TableRange.x);
  }
  return albedo * light;
}
