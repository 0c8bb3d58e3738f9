// Optical depth toward a light: the light march, the light volumes, the multiple-scattering
// volume the march reads, and the optical depths from outside the field.
// Part of the shared light transport, written once for both renderers: shaders/transport/
// Medium.glsl states the rules that keep it GLSL and C++ at once (docs/transport.md).

// ---- The light march: optical depth toward a light ----

UNIFORM int LightSteps;
UNIFORM float LightStep; // the first segment, local units
UNIFORM float LightStepGrowth;

// Optical depth from index point p toward a light, to where the light's ray leaves the volume or
// maxDistance (local), whichever is nearer. indexStep is the direction toward the light in index
// units per local unit; sigmaHere the extinction at p. LightSteps segments growing by
// LightStepGrowth span that reach (the first at least LightStep long; fewer where the reach is
// short), each integrated by the trapezoid rule from the extinction at its ends, so no stretch of
// the way goes uncounted and a segment is not one read of the field. Empty bricks are not read
// when SkipEmptySpace is on (their sigma_t is 0: reading them adds 0).
float LightOpticalDepth(vec3 p, float sigmaHere, vec3 indexStep, float maxDistance)
{
  // A sample on a face may lie a hair outside by rounding: its light starts on the face, and
  // leaves a box LightBoxMargin larger, so a light running along the face still crosses it.
  vec3 start = clamp(p, vec3(0.0f), Dimensions - 1.0f);
  float reach = min(
    IntersectBox(start, indexStep, vec3(-LightBoxMargin), Dimensions - 1.0f + LightBoxMargin).y,
    maxDistance);
  float tau = 0.0f;
  if (reach > 0.0f)
  {
    float growth = LightStepGrowth;
    float segments = growth == 1.0f ? float(LightSteps)
                                    : (pow(growth, float(LightSteps)) - 1.0f) / (growth - 1.0f);
    float segment = max(LightStep, reach / segments);
    float s = 0.0f;
    float sigmaStart = sigmaHere;
    for (int j = 0; j < LightSteps; ++j)
    {
      float end = min(s + segment, reach);
      vec3 q = start + end * indexStep;
      float sigmaEnd = 0.0f;
      if (SkipEmptySpace == 0 || !EmptyBrickAt(q))
      {
        sigmaEnd = ExtinctionAt(q);
      }
      tau += 0.5f * (sigmaStart + sigmaEnd) * (end - s);
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

// ---- The light volumes (issue 12): the optical depth toward each light on a grid ----

// 1: the march model reads the optical depth from the light volumes (filters/CloudLightVolumes.h),
// one block per light stacked along z; 0: it marches toward each light. A constant of the GPU's
// march programs, as PhaseType is (MarchSwitches, app/rendering/CloudMarchShader.h); a uniform of
// the volume passes and a member on the CPU, as are the other switches below.
#ifndef LightTransmittanceVolumes
UNIFORM int LightTransmittanceVolumes;
#endif
UNIFORM vec3 LightVolumeSize;    // texels per axis of one light's block
UNIFORM float LightVolumeCount;  // blocks stacked along z

// The optical depth toward light i from the texel at `texel` of its block: the light march from
// the field's index point there. The grid is corner-aligned: its first and last texels sit on the
// field's first and last voxels.
float LightVolumeTexel(int i, vec3 texel)
{
  vec3 p = texel * ((Dimensions - 1.0f) / max(LightVolumeSize - 1.0f, vec3(1.0f)));
  vec3 l;
  float lightDistance, falloff;
  SampleLight(i, LocalOfIndex(p), l, lightDistance, falloff);
  vec3 indexStep = LightPositional[i] != 0 ? LocalToIndex * l : LightIndexDirection[i];
  return LightOpticalDepth(p, ExtinctionAt(p), indexStep, lightDistance);
}

// The optical depth toward light i at index point p from its block: p clamped to the volume, at
// its place in the corner-aligned grid (within [0, size - 1] texels, so the interpolation never
// reads another light's block).
float LightVolumeDepth(int i, vec3 p)
{
  vec3 t = clamp(p, vec3(0.0f), Dimensions - 1.0f) *
    ((LightVolumeSize - 1.0f) / max(Dimensions - 1.0f, vec3(1.0f)));
  return LightVolumeFetch(i, t);
}

// ---- The multiple-scattering volume (issue 21, docs/lighting.md "The multiple-scattering volume") ----
// Light scattered at least once, on a coarse grid, for the march to read with two fetches per
// sample (fluence and flux). The phase is split as in delta-Eddington: a fraction f (its second
// moment) stays in the light's beam, so the beam's extinction is sigma_t (1 - albedo f), and the
// rest scatters with the reduced eccentricity g* = (g - f) / (1 - f). The beam's scattered share,
// E (exp(-tau (1 - albedo f)) - exp(-tau)), is added to single scattering at every sample with the
// phase toward the eye (BeamFraction); the diffuse rest is the fluence phi of a flux-limited
// diffusion equation
//   -div(D (grad phi - 3 Q1)) + sigma_a phi = Q0,
//   D = 1 / sqrt(9 sigma_tr^2 + |grad phi - 3 Q1|^2 / (DiffuseEscapeSpeed phi)^2)
// with sigma_tr = sigma_t (1 - albedo g), the source Q0 what the beams lose across a cell and
// scatter out of themselves, its first moment Q1 = g* Q0 times the beams' direction, and
// Marshak's vacuum condition on the grid's faces. It is solved per colour channel by red-black
// Gauss-Seidel on the cells, coarse to fine: the solver's texel functions are in
// shaders/transport/Scattering.glsl, its order of passes in filters/CloudScatteringVolume.h.

#ifndef ScatteringVolumeOn
UNIFORM int ScatteringVolumeOn;        // 1: the march's orders >= 2 are the volume's (no octaves)
#endif
UNIFORM vec3 ScatteringVolumeSize;     // texels per axis of the grid computed or read

// The phase's first moment g and the delta-Eddington forward fraction f (its second moment, at
// most g: a phase that scatters backward keeps no beam).
float PhaseMeanCosine()
{
  if (PhaseType == PhaseDroplets)
  {
    return DropletMeanCosine;
  }
  return PhaseLobeWeight * PhaseG1 + (1.0f - PhaseLobeWeight) * PhaseG2;
}

float PhaseForwardFraction()
{
  float second = PhaseType == PhaseDroplets
    ? DropletSecondMoment
    : PhaseLobeWeight * PhaseG1 * PhaseG1 + (1.0f - PhaseLobeWeight) * PhaseG2 * PhaseG2;
  return min(second, max(PhaseMeanCosine(), 0.0f));
}

// The beam's share of a light's scattered light at a sample: the phase toward the eye times the
// beam's transmittance exp(-tau (1 - albedo f)), which holds the unscattered light (single
// scattering, exp(-tau)) and the light the forward fraction f kept in the beam.
vec3 BeamFraction(float mu, float tau, vec3 albedo)
{
  vec3 beam = exp(-tau * (vec3(1.0f) - albedo * PhaseForwardFraction()));
  float powder = 1.0f - PowderStrength * exp(-2.0f * tau);
  return beam * (Phase(mu, 1.0f) * powder);
}

// ---- Optical depth from outside the field (issue 25, filters/CloudOpticalDepthGrid.h) ----
// What other pieces of a distributed field add toward each light: a world grid of depths (tau,
// as this file's), one block per light stacked along z as the light volumes are, which
// OpticalDepthToLight adds to the field's own. Read where the grid is, through IndexToExternal
// (an affine map: the grid is the same on every piece, so a point on a face two pieces share
// reads the same depth in both, and no resampling blurs it twice).

#ifndef ExternalOpticalDepths
UNIFORM int ExternalOpticalDepths;  // 1: added; 0: nothing read (a field on its own)
#endif
UNIFORM vec3 ExternalDepthSize;     // grid points per axis of one light's block
UNIFORM float ExternalDepthCount;   // blocks stacked along z
UNIFORM mat4 IndexToExternal;       // an index point to the grid's texel coordinates

float ExternalOpticalDepth(int i, vec3 p)
{
  vec3 t = clamp(vec3(IndexToExternal * vec4(p, 1.0f)), vec3(0.0f), ExternalDepthSize - 1.0f);
  return ExternalDepthFetch(i, t);
}

// The optical depth toward light i at index point p, where the extinction is sigmaHere, the
// light lies along l at lightDistance: the field's own from the light volumes, or marched, plus
// what lies outside the field when it is given.
float OpticalDepthToLight(int i, vec3 p, float sigmaHere, vec3 l, float lightDistance)
{
  float outside = ExternalOpticalDepths != 0 ? ExternalOpticalDepth(i, p) : 0.0f;
  if (LightTransmittanceVolumes != 0)
  {
    return outside + LightVolumeDepth(i, p);
  }
  vec3 indexStep = LightPositional[i] != 0 ? LocalToIndex * l : LightIndexDirection[i];
  return outside + LightOpticalDepth(p, sigmaHere, indexStep, lightDistance);
}

// The volume the march reads is the field's own, or one solved over the whole of a distributed
// field that this field is a piece of (filters/CloudScatteringVolume.h, SolveScatteringVolume):
// then ScatteringVolumeSize is the whole field's finest grid and IndexToScattering (affine) maps
// this piece's index points to its texel coordinates, so pieces read one volume where they meet.
#ifndef ExternalScatteringVolume
UNIFORM int ExternalScatteringVolume; // 1: read through IndexToScattering; 0: the field's own
#endif
UNIFORM mat4 IndexToScattering;

// The light scattered toward the eye at index point p by the volume's diffuse light, per unit
// albedo: its first-order (P1) radiance (phi + 3 F . w) / 4 pi weighed by the phase, which gives
// phi (1 - 3 g (F / phi) . d) / 4 pi (the flux over the fluence F / phi is stored by luminance).
vec3 MultipleScatteringTerm(vec3 p, vec3 d)
{
  vec3 t = ExternalScatteringVolume != 0
    ? clamp(vec3(IndexToScattering * vec4(p, 1.0f)), vec3(0.0f), ScatteringVolumeSize - 1.0f)
    : clamp(p, vec3(0.0f), Dimensions - 1.0f) *
      ((ScatteringVolumeSize - 1.0f) / max(Dimensions - 1.0f, vec3(1.0f)));
  vec4 fluence = ScatteringVolumeFetch(t);
  vec4 flux = ScatteringFluxFetch(t);
  float anisotropy = 1.0f - 3.0f * PhaseMeanCosine() * dot(vec3(flux.x, flux.y, flux.z), d);
  return vec3(fluence.x, fluence.y, fluence.z) * (max(anisotropy, 0.0f) / PhaseToRadiance);
}

