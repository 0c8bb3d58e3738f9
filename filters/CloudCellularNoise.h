// Tileable lattice noises and the cellular noises of real-time clouds: Worley (F1 cellular) noise,
// Perlin-Worley and curl noise.
//
// Worley noise puts one feature point in every lattice cell, at a position hashed from the cell,
// and measures F1, the distance to the nearest one (Worley, "A cellular texture basis function",
// SIGGRAPH 1996). Inverted, 1 - F1 is round and bright around each feature point; summed in
// octaves it gives the billows of a cumulus (Schneider, "The real-time volumetric cloudscapes of
// Horizon Zero Dawn", SIGGRAPH 2015). Perlin-Worley remaps Perlin noise by an inverted Worley fBm,
// which keeps Perlin's connected shapes and adds Worley's puffs. Curl noise is the curl of three
// Perlin potentials: a divergence-free vector field that displaces sampling positions like
// turbulence does (Bridson et al., "Curl-noise for procedural fluid flow", SIGGRAPH 2007).
//
// Tiling: with a period P > 0 the lattice cells are wrapped modulo P before they are hashed, so the
// noise repeats every P lattice units along each axis, to the bit wherever x and x + P are exact.
// P = 0 never repeats, and then white, value and Perlin noise are exactly CloudNoise.h's.
// Every value here is a pure function of the coordinates, the seed and the period.
#ifndef CloudCellularNoise_h
#define CloudCellularNoise_h

#include "CloudLatticeNoise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace cloudvis
{
namespace noise
{

inline std::uint32_t TiledHash(std::int32_t ix,
  std::int32_t iy,
  std::int32_t iz,
  std::uint32_t seed,
  std::int32_t period)
{
  return Hash(WrapCell(ix, period), WrapCell(iy, period), WrapCell(iz, period), seed);
}

// The feature point of a cell, as an offset from the cell's lower corner in [0, 1)^3: ten bits of
// the cell's hash per axis, at the centres of 1024 slots.
struct FeatureOffset
{
  float X, Y, Z;
};
inline FeatureOffset FeatureOf(std::uint32_t h)
{
  constexpr float slot = 1.0f / 1024.0f;
  return { (static_cast<float>(h & 0x3FFu) + 0.5f) * slot,
    (static_cast<float>((h >> 10) & 0x3FFu) + 0.5f) * slot,
    (static_cast<float>((h >> 20) & 0x3FFu) + 0.5f) * slot };
}

// F1: the distance from (x, y, z) to the nearest feature point, in lattice units. The nearest
// point lies in the 3x3x3 cells around the sample whenever it is at most 1 away (a cell two steps
// off is at least 1 away); in the rare case it is farther, the 5x5x5 cells are searched, so the
// answer is exact.
inline float WorleyF1(double x, double y, double z, std::uint32_t seed, std::int32_t period = 0)
{
  const LatticeCoordinate lx = Split(x), ly = Split(y), lz = Split(z);
  const auto nearestSquared = [&](int reach)
  {
    float best = 1e30f;
    for (int dz = -reach; dz <= reach; ++dz)
    {
      for (int dy = -reach; dy <= reach; ++dy)
      {
        for (int dx = -reach; dx <= reach; ++dx)
        {
          const FeatureOffset f =
            FeatureOf(TiledHash(lx.Cell + dx, ly.Cell + dy, lz.Cell + dz, seed, period));
          const float ex = static_cast<float>(dx) + f.X - lx.Fraction;
          const float ey = static_cast<float>(dy) + f.Y - ly.Fraction;
          const float ez = static_cast<float>(dz) + f.Z - lz.Fraction;
          best = std::min(best, ex * ex + ey * ey + ez * ez);
        }
      }
    }
    return best;
  };
  float best = nearestSquared(1);
  if (best > 1.0f)
  {
    best = nearestSquared(2);
  }
  return std::sqrt(best);
}

// Tileable white noise (Value and Perlin take their period themselves, CloudLatticeNoise.h); with
// period 0 it is White().
inline float TiledWhite(double x, double y, double z, std::uint32_t seed, std::int32_t period)
{
  return HashToSigned(TiledHash(Split(x).Cell, Split(y).Cell, Split(z).Cell, seed, period));
}

// Inverted Worley fBm in [0, 1]: 1 - F1 at lattice frequencies 1, 2 and 4 (periods P, 2P, 4P)
// weighted 0.625, 0.25 and 0.125, as in Schneider's cloud noise. Each octave has its own seed.
inline float InvertedWorleyFbm(double x,
  double y,
  double z,
  std::uint32_t seed,
  std::int32_t period)
{
  constexpr float weights[3] = { 0.625f, 0.25f, 0.125f };
  float sum = 0.0f;
  for (int o = 0; o < 3; ++o)
  {
    const double f = static_cast<double>(1 << o);
    const float f1 = WorleyF1(
      x * f, y * f, z * f, seed + 0x68E31DA4u * static_cast<std::uint32_t>(o), period * (1 << o));
    sum += weights[o] * (1.0f - std::min(1.0f, f1));
  }
  return sum;
}

// remap(v, lo, hi, a, b): v's place between lo and hi, carried onto a .. b (not clamped).
inline float Remap(float v, float lo, float hi, float a, float b)
{
  return a + (v - lo) / (hi - lo) * (b - a);
}

// v clamped to [0, 1]; NaN becomes 0 (std::max returns its first argument when they do not
// compare).
inline float Saturate(float v)
{
  return std::min(1.0f, std::max(0.0f, v));
}

// Perlin-Worley in [0, 1]: Perlin noise (mapped onto [0, 1]) remapped from [W - 1, 1] to [0, 1],
// where W is the inverted Worley fBm: where W is high (near feature points) the noise is lifted
// into a puff, elsewhere it keeps Perlin's shape.
inline float PerlinWorley(double x, double y, double z, std::uint32_t seed, std::int32_t period)
{
  const float perlin = 0.5f + 0.5f * Perlin(x, y, z, seed, period);
  const float worley = InvertedWorleyFbm(x, y, z, seed ^ 0x27D4EB2Fu, period);
  return std::min(1.0f, std::max(0.0f, Remap(perlin, worley - 1.0f, 1.0f, 0.0f, 1.0f)));
}

// Curl noise: the curl of the potential (Perlin_s, Perlin_s+1, Perlin_s+2) at (x, y, z), by central
// differences of half-width Step lattice units. A divergence-free field (to the differences'
// accuracy) whose components are of order 1..3.
inline std::array<float, 3> CurlNoise(double x,
  double y,
  double z,
  std::uint32_t seed,
  std::int32_t period)
{
  constexpr double step = 1.0 / 64.0;
  const auto psi = [&](int c, double px, double py, double pz)
  { return Perlin(px, py, pz, seed + static_cast<std::uint32_t>(c), period); };
  const auto d = [&](int c, int axis)
  {
    const double e[3] = { axis == 0 ? step : 0.0, axis == 1 ? step : 0.0, axis == 2 ? step : 0.0 };
    return static_cast<float>(
      (psi(c, x + e[0], y + e[1], z + e[2]) - psi(c, x - e[0], y - e[1], z - e[2])) / (2.0 * step));
  };
  return { d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1) };
}

} // namespace noise
} // namespace cloudvis

#endif
