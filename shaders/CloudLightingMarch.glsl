// Lighting model "march": for each light a nested march toward it sums the optical depth
// tau = sum sigma_t ds (segments growing by LightStepGrowth, stopping where the volume ends or
// at a point light); Beer-Lambert gives exp(-tau). The mapper calls one term per light with a
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

// A light's intensity means the same in every model (filters/CloudLighting.h): the phase,
// per steradian, is scaled so an isotropic, unshadowed sample scatters color x intensity.
const float PhaseToRadiance = 4.0 * Pi;

float Phase(float mu, float eccentricityScale)
{
  return PhaseLobeWeight * HenyeyGreenstein(PhaseG1 * eccentricityScale, mu) +
    (1.0 - PhaseLobeWeight) * HenyeyGreenstein(PhaseG2 * eccentricityScale, mu);
}

float ScatteredFraction(float mu, float tau)
{
  float sum = 0.0;
  float a = 1.0, b = 1.0, c = 1.0;
  for (int n = 0; n <= MultipleScatteringOctaves; ++n)
  {
    sum += a * Phase(mu, c) * exp(-b * tau);
    a *= ScatteringFalloff;
    b *= ExtinctionFalloff;
    c *= EccentricityFalloff;
  }
  float powder = 1.0 - PowderStrength * exp(-2.0 * tau); // non-physical, off by default
  return sum * powder;
}

// Optical depth from p toward a light, up to maxDistance (local). indexStep is the direction
// toward the light in index units per local unit. Each segment is sampled at its midpoint;
// empty bricks are passed without reading the density.
float LightOpticalDepth(vec3 p, vec3 indexStep, float maxDistance)
{
  float tau = 0.0;
  float start = 0.0;
  float segment = LightStep;
  for (int j = 0; j < LightSteps; ++j)
  {
    float s = start + 0.5 * segment;
    vec3 q = p + s * indexStep;
    if (s > maxDistance || !InsideVolume(q))
    {
      break;
    }
    if (SkipEmptySpace == 0 || !EmptyBrickAt(q))
    {
      tau += ExtinctionAt(q) * segment;
    }
    start += segment;
    segment *= LightStepGrowth;
  }
  return tau;
}

// A directional light: its direction in index units is the same everywhere (precomputed).
vec3 DirectionalLightTerm(int i, vec3 p, float density, vec3 d)
{
  float tau = LightOpticalDepth(p, LightIndexDirection[i], DirectionalLightDistance);
  return LightRadiance[i] * PhaseToRadiance * ScatteredFraction(dot(d, LightDirection[i]), tau);
}

vec3 PointLightTerm(int i, vec3 p, float density, vec3 d)
{
  vec3 l;
  float lightDistance, falloff;
  SampleLight(i, LocalOfIndex(p), l, lightDistance, falloff);
  float tau = LightOpticalDepth(p, LocalToIndex * l, lightDistance);
  return LightRadiance[i] * falloff * PhaseToRadiance * ScatteredFraction(dot(d, l), tau);
}
