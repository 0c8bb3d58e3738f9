// Lighting model "march": for each light a nested march toward it sums the optical depth
// tau = integral sigma_t ds (segments growing by LightStepGrowth, spanning the way to where the
// volume ends or to a point light); Beer-Lambert gives exp(-tau). The mapper calls one term per light with a
// constant index (see LightingSource). A two-lobe Henyey-Greenstein phase and
// octaves of approximate multiple scattering weigh the light scattered toward the eye.
uniform int LightSteps;
uniform float LightStep; // first segment, local units
uniform float LightStepGrowth;
uniform float PhaseG1;
uniform float PhaseG2;
uniform float PhaseLobeWeight;
uniform int MultipleScatteringOctaves;
uniform float ScatteringFalloff;   // a
uniform float ExtinctionFalloff;   // b
uniform float EccentricityFalloff; // c
uniform float PowderStrength;
// Issue 12: 1 reads the optical depth from the light volumes (filters/CloudLightVolumes.h), one
// block per light stacked along z in LightVolumeTexture; 0 marches toward each light.
uniform int LightTransmittanceVolumes;
uniform sampler3D LightVolumeTexture;
uniform vec3 LightVolumeSize; // texels per axis of one light's block
uniform float LightVolumeCount; // blocks stacked along z

// A light's intensity means the same in every model (filters/CloudLighting.h): the phase,
// per steradian, is scaled so an isotropic, unshadowed sample scatters color x intensity.
const float PhaseToRadiance = 4.0 * Pi;

float Phase(float mu, float eccentricityScale)
{
  return PhaseLobeWeight * HenyeyGreenstein(PhaseG1 * eccentricityScale, mu) +
    (1.0 - PhaseLobeWeight) * HenyeyGreenstein(PhaseG2 * eccentricityScale, mu);
}

// Octave n stands for light scattered n + 1 times, so it carries the albedo n more times than
// single scattering (the caller multiplies by the albedo once): physics' albedo^(n+1).
vec3 ScatteredFraction(float mu, float tau, vec3 albedo)
{
  vec3 sum = vec3(0.0);
  vec3 a = vec3(1.0);
  float b = 1.0, c = 1.0;
  for (int n = 0; n <= MultipleScatteringOctaves; ++n)
  {
    sum += a * (Phase(mu, c) * exp(-b * tau));
    a *= ScatteringFalloff * albedo;
    b *= ExtinctionFalloff;
    c *= EccentricityFalloff;
  }
  float powder = 1.0 - PowderStrength * exp(-2.0 * tau); // non-physical, off by default
  return sum * powder;
}

// Optical depth from p toward a light, to where the light's ray leaves the volume or reaches
// the light (maxDistance, local). indexStep is the direction toward the light in index units per
// local unit; sigmaHere the extinction at p. LightSteps segments growing by LightStepGrowth span
// that reach (the first at least LightStep long; fewer where the reach is short), each
// integrated by the trapezoid rule from its ends, so no stretch of the way goes uncounted and a
// segment is not one read of the field. Empty bricks are not read (their sigma_t is 0).
float LightOpticalDepth(vec3 p, float sigmaHere, vec3 indexStep, float maxDistance)
{
  // A sample on a face may lie a hair outside by rounding: its light starts on the face, and
  // leaves a box LightBoxMargin larger, so a light running along the face still crosses it.
  vec3 start = clamp(p, vec3(0.0), Dimensions - 1.0);
  float reach = min(
    IntersectBox(start, indexStep, vec3(-LightBoxMargin), Dimensions - 1.0 + LightBoxMargin).y,
    maxDistance);
  float tau = 0.0;
  if (reach > 0.0)
  {
    float growth = LightStepGrowth;
    float segments = growth == 1.0 ? float(LightSteps) : (pow(growth, float(LightSteps)) - 1.0) / (growth - 1.0);
    float segment = max(LightStep, reach / segments);
    float s = 0.0;
    float sigmaStart = sigmaHere;
    for (int j = 0; j < LightSteps; ++j)
    {
      float end = min(s + segment, reach);
      vec3 q = start + end * indexStep;
      float sigmaEnd = 0.0;
      if (SkipEmptySpace == 0 || !EmptyBrickAt(q))
      {
        sigmaEnd = ExtinctionAt(q);
      }
      tau += 0.5 * (sigmaStart + sigmaEnd) * (end - s);
      if (end >= reach)
      {
        break;
      }
      s = end;
      sigmaStart = sigmaEnd;
      segment *= growth;
    }
  }
  return tau;
}

// The optical depth toward light i at index point p from its block of the light volumes: p
// clamped to the volume, at its place in the corner-aligned grid (within [0, size - 1] texels, so
// the linear filter never reads another light's block). The twin of cloudvis::LightVolumeDepth.
float LightVolumeDepth(int i, vec3 p)
{
  vec3 t = clamp(p, vec3(0.0), Dimensions - 1.0) * ((LightVolumeSize - 1.0) / max(Dimensions - 1.0, vec3(1.0)));
  t.z += float(i) * LightVolumeSize.z;
  return texture(LightVolumeTexture, (t + 0.5) / vec3(LightVolumeSize.xy, LightVolumeSize.z * LightVolumeCount)).r;
}

// A directional light: its direction in index units is the same everywhere (precomputed).
vec3 DirectionalLightTerm(int i, vec3 p, float density, vec3 albedo, vec3 d)
{
  float tau = LightTransmittanceVolumes != 0
    ? LightVolumeDepth(i, p)
    : LightOpticalDepth(p, Optical(density).a, LightIndexDirection[i], DirectionalLightDistance);
  return LightRadiance[i] * PhaseToRadiance * ScatteredFraction(dot(d, LightDirection[i]), tau, albedo);
}

vec3 PointLightTerm(int i, vec3 p, float density, vec3 albedo, vec3 d)
{
  vec3 l;
  float lightDistance, falloff;
  SampleLight(i, LocalOfIndex(p), l, lightDistance, falloff);
  float tau = LightTransmittanceVolumes != 0
    ? LightVolumeDepth(i, p)
    : LightOpticalDepth(p, Optical(density).a, LocalToIndex * l, lightDistance);
  return LightRadiance[i] * falloff * PhaseToRadiance * ScatteredFraction(dot(d, l), tau, albedo);
}
