// The lighting models' source terms: none, derivative and march.
// Part of the shared light transport, written once for both renderers: shaders/transport/
// Medium.glsl states the rules that keep it GLSL and C++ at once (docs/transport.md).

// ---- The lighting models' source terms ----
// The source term S of a sample at index point p, of density `density` and albedo `albedo`, seen
// along d is albedo * (Ambient + the sum of one term per light). The GPU's SourceTerm calls each
// light's term with a constant index, generated per program (CloudMarchShader.cxx); the CPU's
// loops over the lights (CloudTransport.h).

// Lighting model "none": emission-absorption. A sample emits its transfer-function color; no light
// reaches it from elsewhere.
vec3 SourceTermNone(vec3 p, float density, vec3 albedo, vec3 d)
{
  return albedo;
}

// Lighting model "derivative": for each light one more density sample a distance h toward it;
// diffuse = clamp((rho(p) - rho(p + h l)) / (h * density unit), 0, 1) is large where density falls
// toward the light, so the side of the cloud facing the light is bright. No shadowing, no phase.
UNIFORM float DerivativeDistance;   // h, local units
UNIFORM float DerivativeSlopeScale; // 1 / (h in world units * density unit), docs/lighting.md

// Positive where density falls toward the light. slopeScale is computed once in double, so the
// term depends neither on the field's density units nor on the march's frame.
float DerivativeDiffuse(float densityHere, float densityTowardLight, float slopeScale)
{
  return clamp((densityHere - densityTowardLight) * slopeScale, 0.0f, 1.0f);
}

// A directional light: the offset h l in index units is the same everywhere (precomputed).
vec3 DerivativeDirectionalTerm(int i, vec3 p, float density, vec3 albedo, vec3 d)
{
  float towardLight = DensityAt(p + LightIndexOffset[i]);
  return LightRadiance[i] * DerivativeDiffuse(density, towardLight, DerivativeSlopeScale);
}

vec3 DerivativePointTerm(int i, vec3 p, float density, vec3 albedo, vec3 d)
{
  vec3 l;
  float lightDistance, falloff;
  SampleLight(i, LocalOfIndex(p), l, lightDistance, falloff);
  float towardLight = DensityAt(p + LocalToIndex * (DerivativeDistance * l));
  return LightRadiance[i] * falloff * DerivativeDiffuse(density, towardLight, DerivativeSlopeScale);
}

// Lighting model "march": the optical depth tau toward each light, from the light volumes or a
// nested march (LightTransmittanceVolumes); Beer-Lambert gives exp(-tau). The two-lobe phase and
// the octaves weigh the light scattered toward the eye, times PhaseToRadiance (4 pi), so a light's
// color x intensity means the same in every model.

// A directional light: its direction in index units is the same everywhere (precomputed).
vec3 MarchDirectionalTerm(int i, vec3 p, float density, vec3 albedo, vec3 d)
{
  float tau = OpticalDepthToLight(
    i, p, Optical(density).w, LightDirection[i], DirectionalLightDistance);
  float mu = dot(d, LightDirection[i]);
  return LightRadiance[i] * PhaseToRadiance *
    (ScatteringVolumeOn != 0 ? BeamFraction(mu, tau, albedo) : ScatteredFraction(mu, tau, albedo));
}

vec3 MarchPointTerm(int i, vec3 p, float density, vec3 albedo, vec3 d)
{
  vec3 l;
  float lightDistance, falloff;
  SampleLight(i, LocalOfIndex(p), l, lightDistance, falloff);
  float tau = OpticalDepthToLight(i, p, Optical(density).w, l, lightDistance);
  float mu = dot(d, l);
  return LightRadiance[i] * falloff * PhaseToRadiance *
    (ScatteringVolumeOn != 0 ? BeamFraction(mu, tau, albedo) : ScatteredFraction(mu, tau, albedo));
}

