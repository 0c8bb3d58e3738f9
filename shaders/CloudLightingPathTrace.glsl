// Lighting model "pathtrace": the GPU twin of filters/CloudPathTrace.cxx, function for function
// and line for line (the equations are in docs/lighting.md, "The path tracer"). It is not a source
// term of the march: it brings its own main(), one fragment per pixel of the march target, which
// traces SamplesPerFrame paths through the pixel centre and writes their mean (premultiplied
// radiance and opacity 1 - T) to the color target and the mean of their squares to the moment
// target; the mapper's additive accumulation sums frames, so the readers get the mean and the
// second moment over every sample, hence the per-pixel variance.
//
// Random numbers are the CPU's: Pcg4d of (pixel, sample, dimension, seed) in 32-bit uint, which
// GLSL computes bit for bit as the C++ does. Sample k of frame f is sample SampleBase + k.
// Majorants and minorants per occupancy brick come from ExtinctionBoundsTexture (the occupancy
// filter's max_extinction and min_extinction per world unit, times ExtinctionUnit as Optical
// scales the table's); the empty distances from EmptyDistanceTexture.
// Constants shared with the C++ (RatioTrackingRouletteThreshold, NoCrossing,
// MaxTentativeCollisions, GaveUp, MaxWalkSteps) are substituted above this file by the mapper.
#define CLOUD_OWN_MAIN

uniform sampler3D ExtinctionBoundsTexture; // per brick: r = minorant, g = majorant
uniform int LightCount;
uniform int MaxBounces;
uniform int RouletteBounces;
uniform int PathTraceSeed;
uniform int SampleBase;
uniform int SamplesPerFrame;
uniform int MarchWidth;

float DensityReads = 0.0;       // density samples this pixel read, for the count target
float UsefulDensityReads = 0.0; // of which with a non-zero extinction

// ---- Random numbers ----

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

struct RandomStream
{
  uint Pixel;
  uint Sample;
  uint Seed;
  uint Dimension;
};

float NextRandom(inout RandomStream rng)
{
  uvec4 h = Pcg4d(uvec4(rng.Pixel, rng.Sample, rng.Dimension, rng.Seed));
  rng.Dimension += 1u;
  return float(h.x >> 8u) * (1.0 / 16777216.0);
}

// The extinction at p, counted for the count target.
float TrackedExtinctionAt(vec3 p)
{
  float sigma_t = ExtinctionAt(p);
  DensityReads += 1.0;
  UsefulDensityReads += sigma_t > 0.0 ? 1.0 : 0.0;
  return sigma_t;
}

// ---- The majorant walk ----

struct BrickWalk
{
  ivec3 Brick;
  ivec3 Step;
  vec3 TNext;
  vec3 TDelta;
};

BrickWalk BeginBrickWalk(vec3 p, vec3 direction, float t)
{
  vec3 q = p + t * direction;
  bvec3 parallel = equal(direction, vec3(0.0));
  vec3 safe = mix(direction, vec3(1.0), parallel);
  BrickWalk walk;
  walk.Brick = clamp(ivec3(floor(q / BrickSize)), ivec3(0), ivec3(BrickCount) - 1);
  walk.Step = ivec3(sign(direction));
  vec3 face = (vec3(walk.Brick) + step(0.0, direction)) * BrickSize;
  walk.TNext = mix(max(t + (face - q) / safe, vec3(t)), vec3(NoCrossing), parallel);
  walk.TDelta = mix(BrickSize / abs(safe), vec3(NoCrossing), parallel);
  return walk;
}

float BrickExit(BrickWalk walk)
{
  return min(min(walk.TNext.x, walk.TNext.y), walk.TNext.z);
}

bool AdvanceBrickWalk(inout BrickWalk walk)
{
  bvec3 crossed = lessThanEqual(walk.TNext, vec3(BrickExit(walk)));
  walk.Brick += ivec3(crossed) * walk.Step;
  walk.TNext += vec3(crossed) * walk.TDelta;
  return all(greaterThanEqual(walk.Brick, ivec3(0))) &&
    all(lessThan(walk.Brick, ivec3(BrickCount)));
}

vec2 BrickExtinctionBounds(ivec3 brick)
{
  return texelFetch(ExtinctionBoundsTexture, brick, 0).rg * ExtinctionUnit;
}

bool LeapEmptyBricks(vec3 p, vec3 direction, inout BrickWalk walk, inout float t)
{
  float emptyBricks = EmptyBricksAround(vec3(walk.Brick));
  if (emptyBricks < 2.0)
  {
    return false;
  }
  vec3 lo = (vec3(walk.Brick) - (emptyBricks - 1.0)) * BrickSize;
  vec3 hi = (vec3(walk.Brick) + emptyBricks) * BrickSize;
  float tLeap = IntersectBox(p, direction, lo, hi).y;
  if (!(tLeap > BrickExit(walk)))
  {
    return false;
  }
  t = tLeap;
  walk = BeginBrickWalk(p, direction, t);
  return true;
}

// ---- Tracking through the medium ----

// The C++ loop ends by itself (every turn advances the walk); MaxWalkSteps, far above the bricks
// any ray crosses, only keeps a GPU from hanging on a rounding accident.
bool NextOccupiedSegment(vec3 p, vec3 direction, float tEnd, inout BrickWalk walk, inout float t,
  out float tLeave, out vec2 bounds)
{
  tLeave = t;
  bounds = vec2(0.0);
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
    if (bounds.y > 0.0)
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

float SampleFreeFlight(vec3 p, vec3 direction, float tStart, float tEnd, inout RandomStream rng)
{
  BrickWalk walk = BeginBrickWalk(p, direction, tStart);
  float t = tStart, tLeave;
  vec2 bounds;
  int tentative = 0;
  while (NextOccupiedSegment(p, direction, tEnd, walk, t, tLeave, bounds))
  {
    for (;;)
    {
      t -= log(1.0 - NextRandom(rng)) / bounds.y;
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
        return t;
      }
    }
    t = tLeave;
  }
  return tEnd;
}

float RouletteTransmittance(float T, inout RandomStream rng)
{
  if (T >= RatioTrackingRouletteThreshold)
  {
    return T;
  }
  return NextRandom(rng) * RatioTrackingRouletteThreshold < T ? RatioTrackingRouletteThreshold
                                                              : 0.0;
}

float RatioTrackTransmittance(
  vec3 p, vec3 direction, float tStart, float tEnd, inout RandomStream rng)
{
  BrickWalk walk = BeginBrickWalk(p, direction, tStart);
  float T = 1.0;
  float t = tStart, tLeave;
  vec2 bounds;
  int tentative = 0;
  while (NextOccupiedSegment(p, direction, tEnd, walk, t, tLeave, bounds))
  {
    float control = bounds.x;
    float residual = bounds.y - bounds.x;
    T = RouletteTransmittance(T * exp(-control * (tLeave - t)), rng);
    if (T == 0.0)
    {
      return 0.0;
    }
    if (residual > 0.0)
    {
      for (;;)
      {
        t -= log(1.0 - NextRandom(rng)) / residual;
        if (t >= tLeave)
        {
          break;
        }
        if (++tentative > MaxTentativeCollisions)
        {
          return 0.0;
        }
        float sigma_t = TrackedExtinctionAt(p + t * direction);
        T = RouletteTransmittance(T * max(1.0 - (sigma_t - control) / residual, 0.0), rng);
        if (T == 0.0)
        {
          return 0.0;
        }
      }
    }
    t = tLeave;
  }
  return T;
}

// ---- Phase-function sampling ----

float SampleHenyeyGreensteinCosine(float g, float xi)
{
  if (abs(g) < 1e-3)
  {
    return 1.0 - 2.0 * xi;
  }
  float s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
  return clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

vec3 DirectionAround(vec3 axis, float mu, float phi)
{
  float signZ = axis.z >= 0.0 ? 1.0 : -1.0; // the C++'s `sign` (a GLSL built-in's name)
  float a = -1.0 / (signZ + axis.z);
  float b = axis.x * axis.y * a;
  vec3 b1 = vec3(1.0 + signZ * axis.x * axis.x * a, signZ * b, -signZ * axis.x);
  vec3 b2 = vec3(b, signZ + axis.y * axis.y * a, -axis.y);
  float sinTheta = sqrt(max(0.0, 1.0 - mu * mu));
  return normalize(sinTheta * cos(phi) * b1 + sinTheta * sin(phi) * b2 + mu * axis);
}

vec3 SamplePhaseDirection(vec3 d, inout RandomStream rng)
{
  float g = NextRandom(rng) < PhaseLobeWeight ? PhaseG1 : PhaseG2;
  float mu = SampleHenyeyGreensteinCosine(g, NextRandom(rng));
  float phi = 2.0 * Pi * NextRandom(rng);
  return DirectionAround(d, mu, phi);
}

// ---- Paths ----

vec3 DirectLight(vec3 p, vec3 d, inout RandomStream rng)
{
  vec3 x = LocalOfIndex(p);
  vec3 boxHigh = Dimensions - 1.0;
  vec3 light = vec3(0.0);
  for (int i = 0; i < LightCount; ++i)
  {
    vec3 l;
    float lightDistance, falloff;
    SampleLight(i, x, l, lightDistance, falloff);
    vec3 direction = LocalToIndex * l;
    float tEnd = min(IntersectBox(p, direction, vec3(0.0), boxHigh).y, lightDistance);
    float T = RatioTrackTransmittance(p, direction, 0.0, tEnd, rng);
    light += LightRadiance[i] * falloff * PhaseToRadiance * Phase(dot(d, l), 1.0) * T;
  }
  return light;
}

vec4 TracePath(vec3 nearPoint, vec3 farPoint, inout RandomStream rng)
{
  vec3 toFar = farPoint - nearPoint;
  float rayLength = length(toFar);
  vec3 d = toFar / rayLength;
  vec3 p = IndexOfLocal(nearPoint);
  vec3 direction = LocalToIndex * d;
  vec3 boxHigh = Dimensions - 1.0;
  vec2 tBox = IntersectBox(p, direction, vec3(0.0), boxHigh);
  float tStart = max(tBox.x, 0.0);
  float tEnd = min(tBox.y, rayLength);
  if (!(tStart < tEnd))
  {
    return vec4(0.0);
  }
  float T = RatioTrackTransmittance(p, direction, tStart, tEnd, rng);

  vec3 radiance = vec3(0.0);
  vec3 throughput = vec3(1.0);
  for (int bounce = 0; bounce <= MaxBounces; ++bounce)
  {
    float t = SampleFreeFlight(p, direction, tStart, tEnd, rng);
    if (t == GaveUp)
    {
      break;
    }
    if (t >= tEnd)
    {
      if (bounce > 0)
      {
        radiance += throughput * Ambient;
      }
      break;
    }
    if (bounce == MaxBounces)
    {
      break;
    }
    p += t * direction;
    throughput *= Optical(DensityAt(p)).rgb; // the albedo
    radiance += throughput * DirectLight(p, d, rng);
    if (bounce + 1 >= RouletteBounces)
    {
      float survival = min(max(max(throughput.r, throughput.g), throughput.b), 1.0);
      if (NextRandom(rng) >= survival)
      {
        break;
      }
      throughput /= survival;
    }
    d = SamplePhaseDirection(d, rng);
    direction = LocalToIndex * d;
    tStart = 0.0;
    tEnd = IntersectBox(p, direction, vec3(0.0), boxHigh).y;
  }
  return vec4(radiance, 1.0 - T);
}

void main()
{
  // The pixel centre's ray, as vtkCloudReferenceRenderer::PixelRay, ending at the opaque scene.
  vec2 ndc = texCoord * 2.0 - 1.0;
  vec3 nearPoint = LocalPoint(ndc, -1.0);
  float opaqueDepth = texture(DepthTexture, texCoord).r;
  vec3 farPoint = LocalPoint(ndc, opaqueDepth * 2.0 - 1.0);
  uint pixel = uint(gl_FragCoord.y) * uint(MarchWidth) + uint(gl_FragCoord.x);
  vec4 sum = vec4(0.0);
  vec4 squares = vec4(0.0);
  for (int k = 0; k < SamplesPerFrame; ++k)
  {
    RandomStream rng;
    rng.Pixel = pixel;
    rng.Sample = uint(SampleBase + k);
    rng.Seed = uint(PathTraceSeed);
    rng.Dimension = 0u;
    vec4 x = TracePath(nearPoint, farPoint, rng);
    sum += x;
    squares += x * x;
  }
  float n = float(SamplesPerFrame);
  gl_FragData[0] = sum / n;
  gl_FragData[1] = vec4(DensityReads / n, UsefulDensityReads / n, NoDepth, 1.0);
  gl_FragData[2] = squares / n;
}
