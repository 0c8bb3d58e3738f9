// Light transport in cloudvis, written once for both renderers (docs/transport.md), in five files
// spliced in this order (GPU) or included (CPU): Medium.glsl (the field's lookups and the lights),
// Phase.glsl (the phase functions and the multiple-scattering octaves), LightMarch.glsl (optical
// depth toward a light: the light march, the light volumes, the depths from outside the field, and
// the multiple-scattering volume's reading), LightingModels.glsl (the source terms of the lighting
// models none, derivative and march) and PathTrace.glsl (the volumetric path tracer). The equations
// are in docs/lighting.md.
//
// These files are GLSL 1.50 and C++17 with glm at once. The GPU mapper splices them into its
// fragment shaders after shaders/transport/Prelude.glsl (app/rendering/CloudMarchShader.cxx); the
// CPU renderers include them inside the body of cloudvis::glsl::Transport
// (filters/CloudTransport.h), whose members carry the uniforms' names, so each of their functions
// is also a member function of that struct. What differs between the two languages is kept out
// of them:
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

