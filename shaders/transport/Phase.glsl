// The phase functions and the multiple-scattering octaves.
// Part of the shared light transport, written once for both renderers: shaders/transport/
// Medium.glsl states the rules that keep it GLSL and C++ at once (docs/transport.md).

// ---- Phase functions and the multiple-scattering octaves ----

// The phase function: PhaseTwoLobe, Henyey-Greenstein with two lobes, w * HG(g1) + (1 - w) *
// HG(g2) (w = 1 is one lobe), or PhaseDroplets, the Mie phase of cloud droplets tabulated per
// channel (shaders/transport/DropletPhase.glsl), whose first moment g and second moment chi_2
// (means over the channels) stand in for the lobes' where the light transport needs moments.
// PhaseType is a constant of each GPU program (the mapper defines it, so a program holds one
// phase's code); the CPU's is a member.
#ifndef PhaseType
UNIFORM int PhaseType;
#endif
UNIFORM float PhaseG1;
UNIFORM float PhaseG2;
UNIFORM float PhaseLobeWeight;
UNIFORM float DropletMeanCosine;
UNIFORM float DropletSecondMoment;
// Octaves n = 1..N added to single scattering (n = 0), each scaling scattering by a^n,
// extinction toward the light by b^n, eccentricity by c^n.
UNIFORM int MultipleScatteringOctaves;
UNIFORM float ScatteringFalloff;   // a
UNIFORM float ExtinctionFalloff;   // b
UNIFORM float EccentricityFalloff; // c
UNIFORM float PowderStrength;      // non-physical darkening of thin regions; 0: off

// Henyey-Greenstein phase function: (1 / 4 pi) (1 - g^2) / (1 + g^2 - 2 g mu)^(3/2).
// Integrates to 1 over the sphere; g > 0 scatters forward.
float HenyeyGreenstein(float g, float mu)
{
  float g2 = g * g;
  float denominator = 1.0f + g2 - 2.0f * g * mu;
  return (1.0f - g2) / (4.0f * Pi * denominator * sqrt(denominator));
}

// The phase function at mu per channel, with its eccentricity scaled by `eccentricityScale` (c^n
// for octave n): the two lobes' both, or for the droplets a Henyey-Greenstein lobe of their g
// (scale 1 is the table itself).
vec3 Phase(float mu, float eccentricityScale)
{
  if (PhaseType == PhaseDroplets)
  {
    if (eccentricityScale == 1.0f)
    {
      return DropletPhaseAt(mu);
    }
    return vec3(HenyeyGreenstein(DropletMeanCosine * eccentricityScale, mu));
  }
  return vec3(PhaseLobeWeight * HenyeyGreenstein(PhaseG1 * eccentricityScale, mu) +
    (1.0f - PhaseLobeWeight) * HenyeyGreenstein(PhaseG2 * eccentricityScale, mu));
}

// Light scattered toward the eye at a sample from one light whose optical depth to the sample is
// tau: single scattering plus the octaves, per channel. Octave n stands for light scattered
// n + 1 times, so it carries the albedo n more times than single scattering (the caller
// multiplies by the albedo once): physics' albedo^(n+1).
vec3 ScatteredFraction(float mu, float tau, vec3 albedo)
{
  vec3 sum = vec3(0.0f);
  vec3 a = vec3(1.0f);
  float b = 1.0f, c = 1.0f;
  for (int n = 0; n <= MultipleScatteringOctaves; ++n)
  {
    sum += a * (Phase(mu, c) * exp(-b * tau));
    a *= ScatteringFalloff * albedo;
    b *= ExtinctionFalloff;
    c *= EccentricityFalloff;
  }
  // Labelled non-physical: darkens where little material lies toward the light.
  float powder = 1.0f - PowderStrength * exp(-2.0f * tau);
  return sum * powder;
}

