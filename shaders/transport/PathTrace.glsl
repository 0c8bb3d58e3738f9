// The volumetric path tracer.
// Part of the shared light transport, written once for both renderers: shaders/transport/
// Medium.glsl states the rules that keep it GLSL and C++ at once (docs/transport.md).

// ---- The path tracer (docs/lighting.md, "The path tracer") ----
// An unbiased Monte Carlo estimate of the light a pixel receives from the same medium, with every
// order of scattering: plain loops, float arithmetic, and random numbers that are a pure function
// of (pixel, sample, dimension, seed) in 32-bit unsigned integers, so the CPU and the GPU draw the
// very same paths. A ray is p + t * direction: p an index point, direction the index-space image
// of the unit local direction d (index units per local unit), t in local units.

UNIFORM int MaxBounces;      // scattering events a path may have (1: single scattering)
UNIFORM int RouletteBounces; // Russian roulette on the throughput from this many events on
// 1: each scattering event also estimates the next event's light along a second direction,
// drawn toward the lights (LightGuidedNextEvent); 0: the plain estimator.
UNIFORM int LightGuidedNextEvents;

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

// The density, per steradian, with which SamplePhaseDirection draws a direction at cosine mu to
// its axis: the phase itself for the two lobes, the channels' mean phase for the droplets.
float PhaseSamplingDensity(float mu)
{
  vec3 p = Phase(mu, 1.0f);
  return PhaseType == PhaseDroplets ? (p.x + p.y + p.z) / 3.0f : p.x;
}

// The density, per steradian, of the guided directions: the phase's sampling density around each
// light's direction toLight[i], mixed by the lights' shares.
float GuidedDensity(vec3 w, vec3 toLight[MAX_LIGHTS], float share[MAX_LIGHTS])
{
  float density = 0.0f;
  for (int i = 0; i < LightCount; ++i)
  {
    density += share[i] * PhaseSamplingDensity(dot(toLight[i], w));
  }
  return density;
}

// The light that reaches the next scattering event straight from the lights, estimated along two
// directions out of the event at index point p (the path arrived along d): the walk's own,
// walkDirection, drawn from the phase, and a guided one, drawn with the phase's own shape around
// the direction of a light chosen by its luminance. The two are weighed by the balance heuristic
// of multiple importance sampling (Veach 1997): the guided direction's estimate is added to the
// radiance here (`throughput` is the path's at this event), and the weight of the walk's own
// next-event estimate at its next event is returned.
// Why: the plain estimate of that light is the phase toward the light at an event the walk
// reached by the phase from here, so a forward peak (the droplets' reaches thousands per
// steradian) makes it spike on the rare walks that turn toward the light. The guided direction
// finds that lobe by construction, and the weights bound each estimate by the smaller of the two
// densities. docs/lighting.md, "The estimators", gives the measured gain.
float LightGuidedNextEvent(vec3 p, vec3 d, vec3 walkDirection, vec3 throughput,
  INOUT(RandomStream) rng, INOUT(vec3) radiance)
{
  // Each light's direction from here, and its share of the guided directions: the luminance
  // (Rec. 709) of its radiance arriving here before any extinction, over all the lights'.
  vec3 x = LocalOfIndex(p);
  vec3 toLight[MAX_LIGHTS];
  float share[MAX_LIGHTS];
  float total = 0.0f;
  for (int i = 0; i < LightCount; ++i)
  {
    float lightDistance, falloff;
    SampleLight(i, x, toLight[i], lightDistance, falloff);
    share[i] = dot(LightRadiance[i] * falloff, vec3(0.2126f, 0.7152f, 0.0722f));
    total += share[i];
  }
  if (!(total > 0.0f))
  {
    return 1.0f; // no light to guide toward: the walk's estimate alone
  }
  // A light by its share, then a direction around it.
  float u = NextRandom(rng) * total;
  int chosen = LightCount - 1;
  for (int i = 0; i < LightCount - 1; ++i)
  {
    u -= share[i];
    if (u < 0.0f)
    {
      chosen = i;
      break;
    }
  }
  for (int i = 0; i < LightCount; ++i)
  {
    share[i] /= total;
  }
  vec3 unusedWeight;
  vec3 guided = SamplePhaseDirection(toLight[chosen], rng, unusedWeight);
  vec3 direction = LocalToIndex * guided;
  float tEnd = IntersectBox(p, direction, vec3(0.0f), Dimensions - 1.0f).y;
  float t = SampleFreeFlight(p, direction, 0.0f, tEnd, rng);
  if (t != GaveUp && t < tEnd)
  {
    vec3 q = p + t * direction;
    float mu = dot(d, guided);
    float densities = PhaseSamplingDensity(mu) + GuidedDensity(guided, toLight, share);
    radiance += throughput * (Phase(mu, 1.0f) / densities) * vec3(Optical(DensityAt(q))) *
      DirectLight(q, guided, rng);
  }
  float walkDensity = PhaseSamplingDensity(dot(d, walkDirection));
  return walkDensity / (walkDensity + GuidedDensity(walkDirection, toLight, share));
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
  float nextEventWeight = 1.0f; // the multiple-importance weight of the next next-event estimate
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
    radiance += throughput * nextEventWeight * DirectLight(p, d, rng);
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
    vec3 walkDirection = SamplePhaseDirection(d, rng, phaseWeight);
    nextEventWeight = LightGuidedNextEvents != 0 && bounce + 1 < MaxBounces
      ? LightGuidedNextEvent(p, d, walkDirection, throughput, rng, radiance)
      : 1.0f;
    d = walkDirection;
    throughput *= phaseWeight;
    direction = LocalToIndex * d;
    tStart = 0.0f;
    tEnd = IntersectBox(p, direction, vec3(0.0f), boxHigh).y;
  }
  return vec4(radiance, 1.0f - T);
}
