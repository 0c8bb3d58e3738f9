// The volumetric path tracer that is cloudvis's ground truth: an unbiased Monte Carlo estimate
// of the light a pixel receives from the same medium the lighting models approximate (extinction
// and albedo from the transfer table, the two-lobe Henyey-Greenstein phase, the same lights and
// ambient), with every order of scattering. The equations are in docs/lighting.md ("The path
// tracer"); vtkCloudPathTracer renders images with it.
//
// Written to be twinned by a GLSL 1.50 fragment shader, function for function and line for line:
// free functions with the shader's arguments (what the shader reads from uniforms and textures
// comes in MarchUniforms and PathTraceUniforms), plain loops (no recursion, no callbacks, no
// virtual calls), float arithmetic, and random numbers that are a pure function of
// (pixel, sample, dimension, seed) computed with 32-bit unsigned integer operations that GLSL
// reproduces bit for bit. A pixel's samples therefore depend neither on threads nor on the order
// in which pixels are rendered, and the GPU can draw the very same paths.
//
// The field is reached only through the accessors of CloudReferenceMarch.h (DensityAt,
// ExtinctionAt, LocalOfIndex, IndexOfLocal, LocalToIndex, IntersectBox...) and the uniforms
// SetUpMarch computes (CloudMarchUniforms.h), so the path tracer honours the field's whole
// geometry (extent, origin, spacing, direction matrix, the volume's matrix) exactly as the march
// does, and computes in the same local frame around the volume. Positions p are voxel index
// points; directions d are unit vectors of the local frame (whose axes are the world's), and
// `direction` their index-space image (index units per local unit), so a ray is
// p + t * direction with t in local units and sigma_t per local unit, as in the march.
#ifndef CloudPathTrace_h
#define CloudPathTrace_h

#include "CloudReferenceMarch.h"
#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace cloudvis
{

// ---- Random numbers ----

// Where a random number comes from: the pixel (j * width + i), the sample index within the
// pixel, the seed, and the dimension: the count of random numbers this sample has drawn so far.
struct RandomStream
{
  std::uint32_t Pixel = 0;
  std::uint32_t Sample = 0;
  std::uint32_t Seed = 0;
  std::uint32_t Dimension = 0;
};

// The 4-D PCG hash of Jarzynski and Olano ("Hash Functions for GPU Rendering", JCGT 2020):
// an LCG step per component and two rounds of cross-multiplication, in uint arithmetic modulo
// 2^32, which GLSL's uint reproduces exactly.
CLOUDVISFILTERS_EXPORT glm::uvec4 Pcg4d(glm::uvec4 v);

// The next uniform number in [0, 1) of a stream: the top 24 bits of
// Pcg4d(pixel, sample, dimension, seed).x, exact in float; the dimension then advances.
CLOUDVISFILTERS_EXPORT float NextRandom(RandomStream& rng);

// ---- What the path-trace shader reads besides the march's uniforms ----

struct CLOUDVISFILTERS_EXPORT PathTraceUniforms
{
  // The bounds of sigma_t per occupancy brick: the largest (the majorant, vtkCloudOccupancyFilter's
  // "max_extinction") and the smallest (the minorant, "min_extinction") any trilinear sample in
  // the brick can have, per local unit (the filter's values per world unit times the march's
  // ExtinctionUnit, as Optical scales the table's); BrickCount.x * .y * .z values each, x
  // fastest. Brick b covers index points [b * BrickSize, (b + 1) * BrickSize) along each axis.
  const float* BrickMajorant = nullptr;
  const float* BrickMinorant = nullptr;
  // Per brick, the Chebyshev distance in bricks to the nearest occupied one ("empty_distance"):
  // a walk in an empty brick at distance k leaps out of the (2k - 1)^3 empty block around it.
  const unsigned char* BrickEmptyDistance = nullptr;
  glm::ivec3 BrickCount{ 0 };
  float BrickSize = 1.0f;
  // Scattering events a path may have (1: single scattering); the path ends at the next one.
  int MaxBounces = 1;
  // Russian roulette from this many scattering events on, with the survival probability the
  // largest component of the throughput (so an albedo-1 path is never killed by it).
  int RouletteBounces = 3;
};

// The edge of the majorant bricks, in cells, that renders path-trace with by default
// (vtkCloudPathTracer's BrickSize, and the app's GPU mapper for the pathtrace model): the fastest
// on the shipped scenes (docs/performance.md).
constexpr int PathTraceBrickSize = 8;

// Ratio tracking plays Russian roulette once its running transmittance falls below this: a
// path in deep shadow stops early, unbiased (it survives with probability T / threshold and
// then carries the threshold).
constexpr float RatioTrackingRouletteThreshold = 0.1f;

// That roulette: T unchanged above the threshold, else the threshold or 0.
CLOUDVISFILTERS_EXPORT float RouletteTransmittance(float T, RandomStream& rng);

// The ray parameter of the faces a walk never crosses (its direction is parallel to them).
constexpr float NoCrossing = 1e30f;

// A bound on the tentative collisions of one tracking call. Real media stay far below it (the
// shipped scenes need at most a few hundred: majorant minus minorant times the length); an
// extinction so large that float t cannot advance (a majorant above ~1e7 / t) would otherwise
// loop forever. Beyond it, free flight gives up (GaveUp) and ends the path, and ratio tracking
// returns a transmittance of 0: the ray is treated as opaque.
constexpr int MaxTentativeCollisions = 1 << 16;
constexpr float GaveUp = -1.0f;

// ---- The majorant walk: a 3-D DDA through the bricks along a ray ----

struct BrickWalk
{
  glm::ivec3 Brick; // the brick the walk is in
  glm::ivec3 Step;  // -1, 0 or +1 per axis: the direction's sign
  glm::vec3 TNext;  // ray parameter at which the walk crosses the next face, per axis
  glm::vec3 TDelta; // ray parameter across one brick, per axis
};

// The walk along p + t * direction from parameter t (p + t direction inside the volume, up to
// rounding: the brick is clamped to the grid).
CLOUDVISFILTERS_EXPORT BrickWalk BeginBrickWalk(
  const PathTraceUniforms& pt, glm::vec3 p, glm::vec3 direction, float t);
// Where the walk leaves its brick.
CLOUDVISFILTERS_EXPORT float BrickExit(const BrickWalk& walk);
// Into the next brick; false when it has left the grid.
CLOUDVISFILTERS_EXPORT bool AdvanceBrickWalk(const PathTraceUniforms& pt, BrickWalk& walk);
// How many bricks around this one are empty (0: it is occupied), as the march shader reads it.
CLOUDVISFILTERS_EXPORT float EmptyBricksAround(const PathTraceUniforms& pt, glm::ivec3 brick);
// In an empty brick whose empty block reaches beyond it, moves the walk (at ray parameter t)
// to where the ray leaves the block, and returns true; else leaves both alone.
CLOUDVISFILTERS_EXPORT bool LeapEmptyBricks(
  const PathTraceUniforms& pt, glm::vec3 p, glm::vec3 direction, BrickWalk& walk, float& t);
// Moves the walk (at ray parameter t) on to the next occupied brick, leaping over blocks of
// empty ones, and gives the part [t, tLeave] of the ray inside it (tLeave <= tEnd) and its
// (minorant, majorant); false when the ray reaches tEnd or leaves the grid first. A tracking
// loop handles [t, tLeave] and sets t = tLeave before the next call.
CLOUDVISFILTERS_EXPORT bool NextOccupiedSegment(const PathTraceUniforms& pt, glm::vec3 p,
  glm::vec3 direction, float tEnd, BrickWalk& walk, float& t, float& tLeave, glm::vec2& bounds);
// The brick's (minorant, majorant) of sigma_t.
CLOUDVISFILTERS_EXPORT glm::vec2 BrickExtinctionBounds(
  const PathTraceUniforms& pt, glm::ivec3 brick);

// ---- Tracking through the medium ----

// Delta tracking: samples the distance to the next real collision along p + t * direction
// between tStart and tEnd, with tentative collisions at rate majorant per brick (empty bricks
// are crossed without a sample), each accepted with probability sigma_t / majorant (without
// reading the density when the random number falls below minorant / majorant). Returns the
// collision's t, or tEnd when the ray leaves the segment without one (probability: the
// transmittance of the segment), or GaveUp after MaxTentativeCollisions.
CLOUDVISFILTERS_EXPORT float SampleFreeFlight(const MarchUniforms& u, const PathTraceUniforms& pt,
  glm::vec3 p, glm::vec3 direction, float tStart, float tEnd, RandomStream& rng);

// Residual ratio tracking: an unbiased estimate of the transmittance exp(-integral of sigma_t)
// from tStart to tEnd. Per brick, the minorant is a control extinction integrated exactly, and
// the rest is ratio-tracked: the product of (1 - (sigma_t - minorant) / (majorant - minorant))
// over tentative collisions at rate majorant - minorant. A homogeneous brick costs no density
// read and adds no noise. Russian roulette below RatioTrackingRouletteThreshold.
CLOUDVISFILTERS_EXPORT float RatioTrackTransmittance(const MarchUniforms& u,
  const PathTraceUniforms& pt, glm::vec3 p, glm::vec3 direction, float tStart, float tEnd,
  RandomStream& rng);

// ---- Phase-function sampling ----

// The cosine mu of a scattering angle drawn from HG(g, mu) by inverting its distribution with
// xi in [0, 1): mu = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g xi))^2) / (2 g); uniform for |g| < 1e-3.
CLOUDVISFILTERS_EXPORT float SampleHenyeyGreensteinCosine(float g, float xi);

// The unit vector at cosine mu to the unit vector axis, at azimuth phi around it.
CLOUDVISFILTERS_EXPORT glm::vec3 DirectionAround(glm::vec3 axis, float mu, float phi);

// A new direction of travel after scattering light travelling along d: a lobe (the first with
// probability PhaseLobeWeight), then its HG cosine, then a uniform azimuth. Its density is
// exactly Phase(lighting, dot(d, new), 1), so a path's weight needs no phase / pdf factor.
CLOUDVISFILTERS_EXPORT glm::vec3 SamplePhaseDirection(
  const LightingParameters& lighting, glm::vec3 d, RandomStream& rng);

// ---- Paths ----

// Next-event estimation at a scattering point p for light arriving along the unit (local)
// direction d: sum over lights of E_i f_i 4 pi Phase(dot(d, l_i)) T_i, with T_i ratio-tracked
// to the light (a point light) or out of the volume (a directional light). The 4 pi is the
// march's PhaseToRadiance: a light's color x intensity is what an unshadowed isotropic sample of
// albedo 1 sends toward the eye in every model.
CLOUDVISFILTERS_EXPORT glm::vec3 DirectLight(
  const MarchUniforms& u, const PathTraceUniforms& pt, glm::vec3 p, glm::vec3 d, RandomStream& rng);

// One sample of the pixel whose view ray runs from nearPoint to farPoint (in the local frame, as
// MarchRay's; vtkCloudReferenceRenderer::PixelRay gives them): the radiance of one
// path in rgb (premultiplied: the background is composited later, as for the other renderers,
// so a ray that crosses the medium without scattering brings nothing) and one estimate of the
// pixel's opacity 1 - T in a (T ratio-tracked along the view ray). A path that leaves the volume
// after scattering brings the ambient radiance (u.Ambient: a uniform environment).
CLOUDVISFILTERS_EXPORT glm::vec4 TracePath(const MarchUniforms& u,
  const PathTraceUniforms& pt,
  glm::vec3 nearPoint,
  glm::vec3 farPoint,
  RandomStream& rng);

} // namespace cloudvis

#endif
