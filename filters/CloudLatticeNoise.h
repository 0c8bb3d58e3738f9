// Lattice noise for cloud density fields: white, value and Perlin-gradient noise, evaluated at a
// point or shared along a row of voxels. CloudNoise.h sums any noise in fBm octaves.
//
// Every noise value is a pure function of the lattice point, the seed and the sample position,
// so a voxel's density never depends on threads or on which piece of the field is computed.
// The lattice is hashed with integer arithmetic (no permutation tables, no state). The point
// evaluations below interpolate in the order y, z, then x: the row evaluator in
// CloudDensityEvaluator.cxx shares the y/z work along a row of voxels and then does the same x
// step, so both give the same bits.
#ifndef CloudLatticeNoise_h
#define CloudLatticeNoise_h

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace cloudvis
{
namespace noise
{

inline std::uint32_t RotateLeft(std::uint32_t x, int r)
{
  return (x << r) | (x >> (32 - r));
}

// Hash of a lattice point and a seed, with xxHash32's primes and final avalanche. It absorbs z,
// then y, then x, so that a row along x can absorb its fixed y and z once (HashYZ) and finish
// each lattice column with one round (HashX).
constexpr std::uint32_t HashP2 = 2246822519u, HashP3 = 3266489917u, HashP4 = 668265263u,
                        HashP5 = 374761393u;
inline std::uint32_t HashRound(std::uint32_t h, std::int32_t coordinate)
{
  return RotateLeft(h + static_cast<std::uint32_t>(coordinate) * HashP3, 17) * HashP4;
}
inline std::uint32_t HashYZ(std::int32_t iy, std::int32_t iz, std::uint32_t seed)
{
  return HashRound(HashRound(seed + HashP5, iz), iy);
}
inline std::uint32_t HashX(std::uint32_t yzState, std::int32_t ix)
{
  std::uint32_t h = HashRound(yzState, ix);
  h ^= h >> 15;
  h *= HashP2;
  h ^= h >> 13;
  h *= HashP3;
  h ^= h >> 16;
  return h;
}
inline std::uint32_t Hash(std::int32_t ix, std::int32_t iy, std::int32_t iz, std::uint32_t seed)
{
  return HashX(HashYZ(iy, iz, seed), ix);
}

// The top 24 bits of a hash as a value in [-1, 1], both ends included.
inline float HashToSigned(std::uint32_t h)
{
  return static_cast<float>(h >> 8) * (2.0f / 16777215.0f) - 1.0f;
}

// Interpolation weights: the cubic of the write-ups for value noise, Perlin's quintic for
// gradient noise (continuous second derivative, so no visible lattice creases).
inline float FadeCubic(float t)
{
  return t * t * (3.0f - 2.0f * t);
}
inline float FadeQuintic(float t)
{
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}
inline float Lerp(float a, float b, float t)
{
  return a + (b - a) * t;
}

// Perlin's twelve cube-edge gradients (plus four repeats so a 4-bit index picks one), scaled to
// unit length.
struct Gradient
{
  float x, y, z;
};
inline const Gradient& GradientOf(std::uint32_t h)
{
  constexpr float s = 0.70710678f;
  static const Gradient table[16] = { { s, s, 0 },
    { -s, s, 0 },
    { s, -s, 0 },
    { -s, -s, 0 },
    { s, 0, s },
    { -s, 0, s },
    { s, 0, -s },
    { -s, 0, -s },
    { 0, s, s },
    { 0, -s, s },
    { 0, s, -s },
    { 0, -s, -s },
    { s, s, 0 },
    { -s, s, 0 },
    { 0, -s, s },
    { 0, -s, -s } };
  return table[h >> 28];
}
// With unit gradients 3D gradient noise stays within +-sqrt(3)/2; this maps it onto [-1, 1].
constexpr float PerlinScale = 1.15470054f; // 2 / sqrt(3)

// A lattice coordinate split into its cell index and the fraction inside the cell.
struct LatticeCoordinate
{
  std::int32_t Cell;
  float Fraction;
};
inline LatticeCoordinate Split(double x)
{
  // floor by truncation (std::floor is a library call without SSE4.1). Lattice coordinates stay
  // within +-2^30: ValidateFieldDescription bounds frequency times distance from the origin.
  std::int32_t cell = static_cast<std::int32_t>(x);
  cell -= x < static_cast<double>(cell);
  return { cell, static_cast<float>(x - static_cast<double>(cell)) };
}

// A cell index wrapped into [0, period), which makes a noise repeat every `period` cells
// (CloudCellularNoise.h); unchanged when period <= 0.
inline std::int32_t WrapCell(std::int32_t cell, std::int32_t period)
{
  if (period <= 0)
  {
    return cell;
  }
  const std::int32_t m = cell % period;
  return m < 0 ? m + period : m;
}

// What a row of fixed y and z shares for one octave: the lattice cells and fractions in y and z,
// their interpolation weights, and the hash states of the four (y, z) corners, whose cells are
// wrapped when the noise repeats every `period` cells.
struct RowCorners
{
  LatticeCoordinate Y, Z;
  float Uy, Uz;
  std::uint32_t State00, State10, State01, State11; // (dy, dz)
};
inline RowCorners CornersOfRow(double y,
  double z,
  std::uint32_t seed,
  float (*fade)(float),
  std::int32_t period = 0)
{
  const LatticeCoordinate ly = Split(y), lz = Split(z);
  const std::int32_t y0 = WrapCell(ly.Cell, period), y1 = WrapCell(ly.Cell + 1, period);
  const std::int32_t z0 = WrapCell(lz.Cell, period), z1 = WrapCell(lz.Cell + 1, period);
  return { ly,
    lz,
    fade(ly.Fraction),
    fade(lz.Fraction),
    HashYZ(y0, z0, seed),
    HashYZ(y1, z0, seed),
    HashYZ(y0, z1, seed),
    HashYZ(y1, z1, seed) };
}

// Value noise along y and z for one lattice column ix: the bilinear blend of its four corners.
inline float ValueColumn(std::int32_t ix, const RowCorners& r)
{
  const float v00 = HashToSigned(HashX(r.State00, ix));
  const float v10 = HashToSigned(HashX(r.State10, ix));
  const float v01 = HashToSigned(HashX(r.State01, ix));
  const float v11 = HashToSigned(HashX(r.State11, ix));
  return Lerp(Lerp(v00, v10, r.Uy), Lerp(v01, v11, r.Uy), r.Uz);
}

// Gradient noise along y and z for one lattice column ix. A corner contributes
// g.x * (fx - dx) + g.y * (fy - dy) + g.z * (fz - dz); the y/z part (Offset) and the x slope
// (Slope) are blended separately, so a row only needs fx per voxel.
struct PerlinColumnTerms
{
  float Offset;
  float Slope;
};
inline PerlinColumnTerms PerlinColumn(std::int32_t ix, const RowCorners& r)
{
  const Gradient& g00 = GradientOf(HashX(r.State00, ix));
  const Gradient& g10 = GradientOf(HashX(r.State10, ix));
  const Gradient& g01 = GradientOf(HashX(r.State01, ix));
  const Gradient& g11 = GradientOf(HashX(r.State11, ix));
  const float fy = r.Y.Fraction, fz = r.Z.Fraction, uy = r.Uy, uz = r.Uz;
  const float o00 = g00.y * fy + g00.z * fz;
  const float o10 = g10.y * (fy - 1.0f) + g10.z * fz;
  const float o01 = g01.y * fy + g01.z * (fz - 1.0f);
  const float o11 = g11.y * (fy - 1.0f) + g11.z * (fz - 1.0f);
  return { Lerp(Lerp(o00, o10, uy), Lerp(o01, o11, uy), uz),
    Lerp(Lerp(g00.x, g10.x, uy), Lerp(g01.x, g11.x, uy), uz) };
}

// The x step shared by the point and row evaluations.
inline float ValueAlongX(float column0, float column1, float fx)
{
  return Lerp(column0, column1, FadeCubic(fx));
}
inline float PerlinAlongX(const PerlinColumnTerms& c0, const PerlinColumnTerms& c1, float fx)
{
  const float n0 = c0.Offset + c0.Slope * fx;
  const float n1 = c1.Offset + c1.Slope * (fx - 1.0f);
  const float n = Lerp(n0, n1, FadeQuintic(fx)) * PerlinScale;
  return std::min(1.0f, std::max(-1.0f, n)); // branch-free: minss / maxss
}

// Point evaluations in lattice coordinates; each returns a value in [-1, 1].
inline float White(double x, double y, double z, std::uint32_t seed)
{
  return HashToSigned(Hash(Split(x).Cell, Split(y).Cell, Split(z).Cell, seed));
}
// Value and Perlin noise repeat every `period` cells when it is positive (the lattice's cells
// wrap, WrapCell), for the tileable noises of CloudCellularNoise.h.
inline float Value(double x, double y, double z, std::uint32_t seed, std::int32_t period = 0)
{
  const LatticeCoordinate lx = Split(x);
  const RowCorners r = CornersOfRow(y, z, seed, FadeCubic, period);
  return ValueAlongX(ValueColumn(WrapCell(lx.Cell, period), r),
    ValueColumn(WrapCell(lx.Cell + 1, period), r),
    lx.Fraction);
}
inline float Perlin(double x, double y, double z, std::uint32_t seed, std::int32_t period = 0)
{
  const LatticeCoordinate lx = Split(x);
  const RowCorners r = CornersOfRow(y, z, seed, FadeQuintic, period);
  return PerlinAlongX(PerlinColumn(WrapCell(lx.Cell, period), r),
    PerlinColumn(WrapCell(lx.Cell + 1, period), r),
    lx.Fraction);
}
} // namespace noise
} // namespace cloudvis

#endif
