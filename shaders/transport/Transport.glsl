// Light transport in cloudvis, written once for both renderers (docs/transport.md): the field's
// lookups, the lights, the phase functions and the multiple-scattering octaves, the light march and
// the light volumes, the source terms of the lighting models none, derivative and march, and the
// volumetric path tracer. The equations are in docs/lighting.md.
//
// This file is GLSL 1.50 and C++17 with glm at once. The GPU mapper splices it into its fragment
// shaders after shaders/transport/Prelude.glsl (app/rendering/CloudMarchShader.cxx); the CPU
// renderers include it inside the body of cloudvis::glsl::Transport (filters/CloudTransport.h),
// whose members carry the uniforms' names, so each function below is also a member function of
// that struct. What differs between the two languages is kept out of this file:
// - INOUT(T) and OUT(T) are GLSL's inout and out parameters, references in C++; UNIFORM is
//   GLSL's `uniform` and nothing in C++;
// - the accessors declared below read what the GPU keeps in textures: each language defines
//   them in its own file (shaders/transport/Accessors.glsl, filters/CloudTransport.h);
// - the constants (Pi, PhaseToRadiance, MAX_LIGHTS...) are C++ constants, substituted into the
//   GLSL by the mapper.
// Rules that keep it in the common subset: float literals carry the f suffix (C++ would make them
// double, which glm refuses to mix with float vectors); no swizzle beyond .x/.y/.z/.w (glm has
// none); no `const` local (GLSL 1.50 wants constant expressions there); no recursion; structs
// are built member by member.
//
// Frames and units: p is a point in voxel index space (voxel centres at integers); x a point of
// the local frame of filters/CloudMarchUniforms.h, where the lights are; l the unit direction
// toward a light, d the unit direction a ray travels (the view ray: from the eye into the scene),
// mu = dot(d, l); lengths in local units, sigma_t per local unit.

// ---- The field and its geometry (uniforms set by SetUpMarch, filters/CloudMarchUniforms.h) ----

UNIFORM vec3 Dimensions;   // voxels per axis
UNIFORM mat4 IndexToLocal;
UNIFORM mat3 LocalToIndex; // a local displacement in index units
UNIFORM float DensityScale; // density = filtered texel * DensityScale + DensityBias
UNIFORM float DensityBias;
UNIFORM float ExtinctionUnit; // the table's sigma_t (per world unit) times this: per local unit
UNIFORM vec3 BrickCount;      // occupancy bricks per axis
UNIFORM float BrickSize;      // voxels per brick edge
UNIFORM int SkipEmptySpace;   // 0: read every sample, empty bricks too

// ---- The accessors: what each language reads its own way ----

// The density at index point p in the data's units: the density texture's GL_LINEAR,
// CLAMP_TO_EDGE fetch at (p + 0.5) / Dimensions, scaled back.
float DensityAt(vec3 p);
// The transfer table at a density: albedo in rgb, sigma_t per world unit in a.
vec4 TransferAt(float density);
// How many bricks around brick `brick` are empty (the Chebyshev distance in bricks to occupied
// space; 0: it is occupied).
float EmptyBricksAround(vec3 brick);
// The brick's (minorant, majorant) of sigma_t per local unit (the path tracer's).
vec2 BrickExtinctionBounds(ivec3 brick);
// Light i's block of the light volumes at texel coordinate t (within [0, LightVolumeSize - 1]),
// linearly interpolated.
float LightVolumeFetch(int i, vec3 t);
// The multiple-scattering volume the march reads, its fluence and flux linearly interpolated at
// texel coordinate t (as LightVolumeFetch); shaders/transport/Scattering.glsl computes it.
vec4 ScatteringVolumeFetch(vec3 t);
vec4 ScatteringFluxFetch(vec3 t);
// Light i's block of the optical depths from outside the field at texel coordinate t (within
// [0, ExternalDepthSize - 1]), linearly interpolated.
float ExternalDepthFetch(int i, vec3 t);

// ---- The medium ----

// Entry and exit distances of the ray o + t d through the box [lo, hi].
vec2 IntersectBox(vec3 o, vec3 d, vec3 lo, vec3 hi)
{
  // An axis-parallel ray gets a huge finite inverse rather than a division by zero.
  vec3 safe = mix(d, vec3(1e-30f), equal(d, vec3(0.0f)));
  vec3 inv = 1.0f / safe;
  vec3 t0 = (lo - o) * inv;
  vec3 t1 = (hi - o) * inv;
  vec3 tNear = min(t0, t1);
  vec3 tFar = max(t0, t1);
  return vec2(max(max(tNear.x, tNear.y), tNear.z), min(min(tFar.x, tFar.y), tFar.z));
}

// Albedo in rgb and the extinction per local unit in a, at a density.
vec4 Optical(float density)
{
  vec4 optical = TransferAt(density);
  return vec4(vec3(optical), optical.w * ExtinctionUnit);
}

float ExtinctionAt(vec3 p)
{
  return Optical(DensityAt(p)).w;
}

vec3 LocalOfIndex(vec3 p)
{
  return vec3(IndexToLocal * vec4(p, 1.0f));
}

vec3 IndexOfLocal(vec3 x)
{
  return LocalToIndex * (x - vec3(IndexToLocal[3]));
}

bool InsideVolume(vec3 p)
{
  return all(greaterThanEqual(p, vec3(0.0f))) && all(lessThanEqual(p, Dimensions - 1.0f));
}

// The brick around index point p.
vec3 BrickOf(vec3 p)
{
  return clamp(floor(p / BrickSize), vec3(0.0f), BrickCount - 1.0f);
}

bool EmptyBrickAt(vec3 p)
{
  return EmptyBricksAround(BrickOf(p)) > 0.0f;
}

// ---- The lights (cloudvis::LocalLight, packed into arrays by light) ----

UNIFORM int LightCount;
UNIFORM int LightPositional[MAX_LIGHTS];
UNIFORM vec3 LightPosition[MAX_LIGHTS];    // local; positional lights
UNIFORM vec3 LightDirection[MAX_LIGHTS];   // unit, toward the light; directional lights
UNIFORM vec3 LightRadiance[MAX_LIGHTS];    // color * intensity
UNIFORM vec3 LightAttenuation[MAX_LIGHTS]; // for local distances
// Per directional light, precomputed: its direction in index units per local unit, and the
// derivative model's offset h l in index units.
UNIFORM vec3 LightIndexDirection[MAX_LIGHTS];
UNIFORM vec3 LightIndexOffset[MAX_LIGHTS];
UNIFORM vec3 Ambient; // ambient color * strength

// Direction l toward light i from local point x, the local distance to it
// (DirectionalLightDistance for a directional light) and its distance falloff.
void SampleLight(int i, vec3 x, OUT(vec3) l, OUT(float) lightDistance, OUT(float) falloff)
{
  if (LightPositional[i] == 0)
  {
    l = LightDirection[i];
    lightDistance = DirectionalLightDistance;
    falloff = 1.0f;
    return;
  }
  vec3 toLight = LightPosition[i] - x;
  float r = length(toLight);
  lightDistance = r;
  l = toLight / max(r, 1e-20f);
  vec3 k = LightAttenuation[i];
  falloff = 1.0f / max(k.x + k.y * r + k.z * r * r, 1e-20f);
}

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

// ---- The path tracer (docs/lighting.md, "The path tracer") ----
// An unbiased Monte Carlo estimate of the light a pixel receives from the same medium, with every
// order of scattering: plain loops, float arithmetic, and random numbers that are a pure function
// of (pixel, sample, dimension, seed) in 32-bit unsigned integers, so the CPU and the GPU draw the
// very same paths. A ray is p + t * direction: p an index point, direction the index-space image
// of the unit local direction d (index units per local unit), t in local units.

UNIFORM int MaxBounces;      // scattering events a path may have (1: single scattering)
UNIFORM int RouletteBounces; // Russian roulette on the throughput from this many events on

// Density samples this pixel read, and of those the ones with a non-zero extinction (the GPU's
// count target; per thread on the CPU).
float DensityReads = 0.0f;
float UsefulDensityReads = 0.0f;

// Random numbers. The 4-D PCG hash of Jarzynski and Olano ("Hash Functions for GPU Rendering",
// JCGT 2020): an LCG step per component and two rounds of cross-multiplication, in uint
// arithmetic modulo 2^32.
uvec4 Pcg4d(uvec4 v)
{
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  return v;
}

// Where a random number comes from: the pixel (j * width + i), the sample index within the
// pixel, the seed, and the dimension: the count of random numbers this sample has drawn so far.
struct RandomStream
{
  uint Pixel;
  uint Sample;
  uint Seed;
  uint Dimension;
};

// The next uniform number in [0, 1) of a stream: the top 24 bits of
// Pcg4d(pixel, sample, dimension, seed).x, exact in float; the dimension then advances.
float NextRandom(INOUT(RandomStream) rng)
{
  uvec4 h = Pcg4d(uvec4(rng.Pixel, rng.Sample, rng.Dimension, rng.Seed));
  rng.Dimension += 1u;
  return float(h.x >> 8u) * (1.0f / 16777216.0f);
}

// The extinction at p, counted.
float TrackedExtinctionAt(vec3 p)
{
  float sigma_t = ExtinctionAt(p);
  DensityReads += 1.0f;
  UsefulDensityReads += sigma_t > 0.0f ? 1.0f : 0.0f;
  return sigma_t;
}

// The majorant walk: a 3-D DDA through the occupancy bricks along a ray.
struct BrickWalk
{
  ivec3 Brick; // the brick the walk is in
  ivec3 Step;  // -1, 0 or +1 per axis: the direction's sign
  vec3 TNext;  // ray parameter at which the walk crosses the next face, per axis
  vec3 TDelta; // ray parameter across one brick, per axis
};

// The walk along p + t * direction from parameter t (p + t direction inside the volume, up to
// rounding: the brick is clamped to the grid).
BrickWalk BeginBrickWalk(vec3 p, vec3 direction, float t)
{
  vec3 q = p + t * direction;
  bvec3 parallel = equal(direction, vec3(0.0f)); // never crosses that axis
  vec3 safe = mix(direction, vec3(1.0f), parallel);
  BrickWalk walk;
  walk.Brick = clamp(ivec3(floor(q / BrickSize)), ivec3(0), ivec3(BrickCount) - 1);
  walk.Step = ivec3(sign(direction));
  // The face ahead along each axis: the brick's upper face when moving up, its lower one else.
  // Not before t: q may lie a rounding error outside the (clamped) brick.
  vec3 face = (vec3(walk.Brick) + step(0.0f, direction)) * BrickSize;
  walk.TNext = mix(max(t + (face - q) / safe, vec3(t)), vec3(NoCrossing), parallel);
  walk.TDelta = mix(BrickSize / abs(safe), vec3(NoCrossing), parallel);
  return walk;
}

// Where the walk leaves its brick.
float BrickExit(BrickWalk walk)
{
  return min(min(walk.TNext.x, walk.TNext.y), walk.TNext.z);
}

// Into the next brick; false when it has left the grid.
bool AdvanceBrickWalk(INOUT(BrickWalk) walk)
{
  // Every axis whose face is crossed first moves on (two or three at an edge or a corner).
  bvec3 crossed = lessThanEqual(walk.TNext, vec3(BrickExit(walk)));
  walk.Brick += ivec3(crossed) * walk.Step;
  walk.TNext += vec3(crossed) * walk.TDelta;
  return all(greaterThanEqual(walk.Brick, ivec3(0))) &&
    all(lessThan(walk.Brick, ivec3(BrickCount)));
}

// In an empty brick whose empty block reaches beyond it, moves the walk (at ray parameter t) to
// where the ray leaves the block, and returns true; else leaves both alone.
bool LeapEmptyBricks(vec3 p, vec3 direction, INOUT(BrickWalk) walk, INOUT(float) t)
{
  float emptyBricks = EmptyBricksAround(vec3(walk.Brick));
  if (emptyBricks < 2.0f)
  {
    return false; // occupied, or next to an occupied brick: the walk steps one brick
  }
  vec3 lo = (vec3(walk.Brick) - (emptyBricks - 1.0f)) * BrickSize;
  vec3 hi = (vec3(walk.Brick) + emptyBricks) * BrickSize;
  float tLeap = IntersectBox(p, direction, lo, hi).y;
  if (!(tLeap > BrickExit(walk)))
  {
    return false; // rounding: no further than the next face
  }
  t = tLeap;
  walk = BeginBrickWalk(p, direction, t);
  return true;
}

// Moves the walk (at ray parameter t) on to the next occupied brick, leaping over blocks of empty
// ones, and gives the part [t, tLeave] of the ray inside it (tLeave <= tEnd) and its (minorant,
// majorant); false when the ray reaches tEnd or leaves the grid first. A tracking loop handles
// [t, tLeave] and sets t = tLeave before the next call. Every turn advances the walk, so the loop
// ends by itself; MaxWalkSteps, far above the bricks any ray crosses, only keeps a GPU from hanging
// on a rounding accident.
bool NextOccupiedSegment(vec3 p, vec3 direction, float tEnd, INOUT(BrickWalk) walk,
  INOUT(float) t, OUT(float) tLeave, OUT(vec2) bounds)
{
  tLeave = t;
  bounds = vec2(0.0f);
  for (int guard = 0; guard < MaxWalkSteps && t < tEnd; ++guard)
  {
    if (t >= BrickExit(walk))
    {
      if (!AdvanceBrickWalk(walk))
      {
        return false;
      }
      continue;
    }
    bounds = BrickExtinctionBounds(walk.Brick);
    if (bounds.y > 0.0f)
    {
      tLeave = min(BrickExit(walk), tEnd);
      return true;
    }
    if (!LeapEmptyBricks(p, direction, walk, t))
    {
      t = min(BrickExit(walk), tEnd);
    }
  }
  return false;
}

// Delta tracking: samples the distance to the next real collision along p + t * direction
// between tStart and tEnd, with tentative collisions at rate majorant per brick (empty bricks are
// crossed without a sample), each accepted with probability sigma_t / majorant (without reading
// the density when the random number falls below minorant / majorant). Returns the collision's t,
// or tEnd when the ray leaves the segment without one (probability: the transmittance of the
// segment), or GaveUp after MaxTentativeCollisions.
float SampleFreeFlight(vec3 p, vec3 direction, float tStart, float tEnd, INOUT(RandomStream) rng)
{
  BrickWalk walk = BeginBrickWalk(p, direction, tStart);
  float t = tStart, tLeave;
  vec2 bounds;
  int tentative = 0;
  while (NextOccupiedSegment(p, direction, tEnd, walk, t, tLeave, bounds))
  {
    // Tentative collisions at rate majorant; exponential distances are memoryless, so the next
    // brick starts afresh from its face.
    for (;;)
    {
      t -= log(1.0f - NextRandom(rng)) / bounds.y;
      if (t >= tLeave)
      {
        break;
      }
      if (++tentative > MaxTentativeCollisions)
      {
        return GaveUp;
      }
      float threshold = NextRandom(rng) * bounds.y;
      if (threshold < bounds.x || threshold < TrackedExtinctionAt(p + t * direction))
      {
        return t; // a real collision
      }
    }
    t = tLeave;
  }
  return tEnd; // no collision before the end of the segment
}

// Ratio tracking's Russian roulette: T unchanged above the threshold, else the threshold or 0.
float RouletteTransmittance(float T, INOUT(RandomStream) rng)
{
  if (T >= RatioTrackingRouletteThreshold)
  {
    return T;
  }
  return NextRandom(rng) * RatioTrackingRouletteThreshold < T ? RatioTrackingRouletteThreshold
                                                              : 0.0f;
}

// Residual ratio tracking: an unbiased estimate of the transmittance exp(-integral of sigma_t)
// from tStart to tEnd. Per brick, the minorant is a control extinction integrated exactly, and
// the rest is ratio-tracked: the product of (1 - (sigma_t - minorant) / (majorant - minorant))
// over tentative collisions at rate majorant - minorant. A homogeneous brick costs no density
// read and adds no noise. Russian roulette below RatioTrackingRouletteThreshold.
float RatioTrackTransmittance(
  vec3 p, vec3 direction, float tStart, float tEnd, INOUT(RandomStream) rng)
{
  BrickWalk walk = BeginBrickWalk(p, direction, tStart);
  float T = 1.0f;
  float t = tStart, tLeave;
  vec2 bounds;
  int tentative = 0;
  while (NextOccupiedSegment(p, direction, tEnd, walk, t, tLeave, bounds))
  {
    float control = bounds.x;
    float residual = bounds.y - bounds.x;
    T = RouletteTransmittance(T * exp(-control * (tLeave - t)), rng);
    if (T == 0.0f)
    {
      return 0.0f;
    }
    if (residual > 0.0f)
    {
      for (;;)
      {
        t -= log(1.0f - NextRandom(rng)) / residual;
        if (t >= tLeave)
        {
          break;
        }
        if (++tentative > MaxTentativeCollisions)
        {
          return 0.0f;
        }
        // The bounds hold up to the rounding of a sample position: clamp at 0.
        float sigma_t = TrackedExtinctionAt(p + t * direction);
        T = RouletteTransmittance(T * max(1.0f - (sigma_t - control) / residual, 0.0f), rng);
        if (T == 0.0f)
        {
          return 0.0f;
        }
      }
    }
    t = tLeave;
  }
  return T;
}

// The cosine mu of a scattering angle drawn from HG(g, mu) by inverting its distribution with xi
// in [0, 1): mu = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g xi))^2) / (2 g); uniform for |g| < 1e-3.
float SampleHenyeyGreensteinCosine(float g, float xi)
{
  if (abs(g) < 1e-3f)
  {
    return 1.0f - 2.0f * xi;
  }
  float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * xi);
  return clamp((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}

// The unit vector at cosine mu to the unit vector axis, at azimuth phi around it.
vec3 DirectionAround(vec3 axis, float mu, float phi)
{
  // An orthonormal basis around the axis without a division by a small number (Duff et al.,
  // "Building an Orthonormal Basis, Revisited", JCGT 2017).
  float signZ = axis.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (signZ + axis.z);
  float b = axis.x * axis.y * a;
  vec3 b1 = vec3(1.0f + signZ * axis.x * axis.x * a, signZ * b, -signZ * axis.x);
  vec3 b2 = vec3(b, signZ + axis.y * axis.y * a, -axis.y);
  float sinTheta = sqrt(max(0.0f, 1.0f - mu * mu));
  return normalize(sinTheta * cos(phi) * b1 + sinTheta * sin(phi) * b2 + mu * axis);
}

// A new direction of travel after scattering light travelling along d, and the path's weight
// Phase / pdf for it. Two lobes: a lobe (the first with probability PhaseLobeWeight), then its HG
// cosine, then a uniform azimuth; the density is exactly the phase, so the weight is 1. Droplets:
// a channel chosen uniformly, then its tabulated cosine, so the density is the channels' mean
// phase and the weight each channel's phase over that mean (at most 3; near 1 but at the
// cloudbow and the glory, where the colours part).
vec3 SamplePhaseDirection(vec3 d, INOUT(RandomStream) rng, OUT(vec3) weight)
{
  float mu;
  weight = vec3(1.0f);
  if (PhaseType == PhaseDroplets)
  {
    int c = min(int(3.0f * NextRandom(rng)), 2);
    mu = SampleDropletCosine(c, NextRandom(rng));
    vec3 p = DropletPhaseAt(mu);
    weight = p * (3.0f / max(p.x + p.y + p.z, 1e-30f));
  }
  else
  {
    float g = NextRandom(rng) < PhaseLobeWeight ? PhaseG1 : PhaseG2;
    mu = SampleHenyeyGreensteinCosine(g, NextRandom(rng));
  }
  float phi = 2.0f * Pi * NextRandom(rng);
  return DirectionAround(d, mu, phi);
}

// Next-event estimation at a scattering point p for light arriving along the unit direction d:
// the sum over lights of E_i f_i 4 pi Phase(dot(d, l_i)) T_i, with T_i ratio-tracked to the light
// (a point light) or out of the volume (a directional light).
vec3 DirectLight(vec3 p, vec3 d, INOUT(RandomStream) rng)
{
  vec3 x = LocalOfIndex(p);
  vec3 boxHigh = Dimensions - 1.0f;
  vec3 light = vec3(0.0f);
  for (int i = 0; i < LightCount; ++i)
  {
    vec3 l;
    float lightDistance, falloff;
    SampleLight(i, x, l, lightDistance, falloff);
    vec3 direction = LocalToIndex * l;
    float tEnd = min(IntersectBox(p, direction, vec3(0.0f), boxHigh).y, lightDistance);
    float T = RatioTrackTransmittance(p, direction, 0.0f, tEnd, rng);
    light += LightRadiance[i] * falloff * PhaseToRadiance * Phase(dot(d, l), 1.0f) * T;
  }
  return light;
}

// One sample of the pixel whose view ray runs from nearPoint to farPoint (local frame): the
// radiance of one path in rgb (premultiplied: the background is composited later, so a ray that
// crosses the medium without scattering brings nothing) and one estimate of the pixel's opacity
// 1 - T in a (T ratio-tracked along the view ray). A path that leaves the volume after scattering
// brings the ambient radiance (a uniform environment).
vec4 TracePath(vec3 nearPoint, vec3 farPoint, INOUT(RandomStream) rng)
{
  // The view ray as the march sets it up.
  vec3 toFar = farPoint - nearPoint;
  float rayLength = length(toFar);
  vec3 d = toFar / rayLength;        // direction of travel, unit
  vec3 p = IndexOfLocal(nearPoint);  // index point at t = 0
  vec3 direction = LocalToIndex * d; // index units per local unit
  vec3 boxHigh = Dimensions - 1.0f;
  vec2 tBox = IntersectBox(p, direction, vec3(0.0f), boxHigh);
  float tStart = max(tBox.x, 0.0f);
  float tEnd = min(tBox.y, rayLength);
  if (!(tStart < tEnd))
  {
    return vec4(0.0f);
  }
  float T = RatioTrackTransmittance(p, direction, tStart, tEnd, rng);

  vec3 radiance = vec3(0.0f);
  vec3 throughput = vec3(1.0f);
  // bounce: the scattering events of the path so far.
  for (int bounce = 0; bounce <= MaxBounces; ++bounce)
  {
    float t = SampleFreeFlight(p, direction, tStart, tEnd, rng);
    if (t == GaveUp)
    {
      break; // an extinction too large for float: the path ends with what it has
    }
    if (t >= tEnd)
    {
      // Out of the volume: into the uniform environment (the view ray itself brings nothing).
      if (bounce > 0)
      {
        radiance += throughput * Ambient;
      }
      break;
    }
    if (bounce == MaxBounces)
    {
      break; // one scattering event more than allowed
    }
    p += t * direction;
    throughput *= vec3(Optical(DensityAt(p))); // the albedo
    radiance += throughput * DirectLight(p, d, rng);
    if (bounce + 1 >= RouletteBounces)
    {
      float survival = min(max(max(throughput.x, throughput.y), throughput.z), 1.0f);
      if (NextRandom(rng) >= survival)
      {
        break;
      }
      throughput /= survival;
    }
    vec3 phaseWeight;
    d = SamplePhaseDirection(d, rng, phaseWeight);
    throughput *= phaseWeight;
    direction = LocalToIndex * d;
    tStart = 0.0f;
    tEnd = IntersectBox(p, direction, vec3(0.0f), boxHigh).y;
  }
  return vec4(radiance, 1.0f - T);
}
