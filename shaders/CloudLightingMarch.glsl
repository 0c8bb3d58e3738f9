// Lighting model "march": for each light a nested march toward it sums the optical depth
// tau = sum sigma_t ds (segments growing by LightStepGrowth, stopping where the volume ends or
// at a point light); Beer-Lambert gives exp(-tau). A two-lobe Henyey-Greenstein phase and
// octaves of approximate multiple scattering weigh the light scattered toward the eye.
uniform int LightSteps;
uniform float LightStep; // first segment, world units
uniform float LightStepGrowth;
uniform float PhaseG1;
uniform float PhaseG2;
uniform float PhaseLobeWeight;
uniform int MultipleScatteringOctaves;
uniform float ScatteringFalloff;   // a
uniform float ExtinctionFalloff;   // b
uniform float EccentricityFalloff; // c
uniform float PowderStrength;

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

// Optical depth from p toward the light along l (world direction), up to maxDistance. Each
// segment is sampled at its midpoint; empty bricks are passed without reading the density.
float LightOpticalDepth(vec3 p, vec3 l, float maxDistance)
{
  vec3 indexStep = WorldToIndex * l; // index units per world unit
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

vec3 SourceTerm(vec3 p, float density, vec3 albedo, vec3 d)
{
  vec3 x = WorldOfIndex(p);
  vec3 light = Ambient;
  for (int i = 0; i < LightCount; ++i)
  {
    vec3 l;
    float lightDistance, falloff;
    SampleLight(i, x, l, lightDistance, falloff);
    float tau = LightOpticalDepth(p, l, lightDistance);
    light += LightRadiance[i] * falloff * ScatteredFraction(dot(d, l), tau);
  }
  return albedo * light;
}
