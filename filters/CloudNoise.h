// Lattice noise for cloud density fields: white, value and Perlin-gradient noise, and the
// octave schedule of fractional Brownian motion (fBm).
//
// Every noise value is a pure function of the lattice point, the seed and the sample position,
// so a voxel's density never depends on threads or on which piece of the field is computed.
// The lattice is hashed with integer arithmetic (no permutation tables, no state). The point
// evaluations below interpolate in the order y, z, then x: the row evaluator in
// CloudDensityEvaluator.cxx shares the y/z work along a row of voxels and then does the same x
// step, so both give the same bits.
#ifndef CloudNoise_h
#define CloudNoise_h

#include <cmath>
#include <cstdint>
#include <vector>

namespace cloudvis
{
namespace noise
{

enum class NoiseType
{
  None,   // no noise: fBm is 0
  White,  // an independent random value per lattice cell, no interpolation
  Value,  // random values on the lattice, interpolated with the cubic f*f*(3-2f)
  Perlin, // random gradients on the lattice, quintic interpolation (improved Perlin noise)
};

inline std::uint32_t RotateLeft(std::uint32_t x, int r)
{
  return (x << r) | (x >> (32 - r));
}

// Hash of a lattice point and a seed, with xxHash32's primes and final avalanche.
inline std::uint32_t Hash(std::int32_t ix, std::int32_t iy, std::int32_t iz, std::uint32_t seed)
{
  constexpr std::uint32_t P2 = 2246822519u, P3 = 3266489917u, P4 = 668265263u, P5 = 374761393u;
  std::uint32_t h = seed + P5;
  h = RotateLeft(h + static_cast<std::uint32_t>(ix) * P3, 17) * P4;
  h = RotateLeft(h + static_cast<std::uint32_t>(iy) * P3, 17) * P4;
  h = RotateLeft(h + static_cast<std::uint32_t>(iz) * P3, 17) * P4;
  h ^= h >> 15;
  h *= P2;
  h ^= h >> 13;
  h *= P3;
  h ^= h >> 16;
  return h;
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
  static const Gradient table[16] = { { s, s, 0 }, { -s, s, 0 }, { s, -s, 0 }, { -s, -s, 0 },
    { s, 0, s }, { -s, 0, s }, { s, 0, -s }, { -s, 0, -s }, { 0, s, s }, { 0, -s, s },
    { 0, s, -s }, { 0, -s, -s }, { s, s, 0 }, { -s, s, 0 }, { 0, -s, s }, { 0, -s, -s } };
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
  const double cell = std::floor(x);
  return { static_cast<std::int32_t>(static_cast<std::int64_t>(cell)),
    static_cast<float>(x - cell) };
}

// Value noise along y and z for one lattice column ix: the bilinear blend of its four corners.
inline float ValueColumn(
  std::int32_t ix, LatticeCoordinate y, LatticeCoordinate z, float uy, float uz, std::uint32_t seed)
{
  const float v00 = HashToSigned(Hash(ix, y.Cell, z.Cell, seed));
  const float v10 = HashToSigned(Hash(ix, y.Cell + 1, z.Cell, seed));
  const float v01 = HashToSigned(Hash(ix, y.Cell, z.Cell + 1, seed));
  const float v11 = HashToSigned(Hash(ix, y.Cell + 1, z.Cell + 1, seed));
  return Lerp(Lerp(v00, v10, uy), Lerp(v01, v11, uy), uz);
}

// Gradient noise along y and z for one lattice column ix. A corner contributes
// g.x * (fx - dx) + g.y * (fy - dy) + g.z * (fz - dz); the y/z part (Offset) and the x slope
// (Slope) are blended separately, so a row only needs fx per voxel.
struct PerlinColumnTerms
{
  float Offset;
  float Slope;
};
inline PerlinColumnTerms PerlinColumn(
  std::int32_t ix, LatticeCoordinate y, LatticeCoordinate z, float uy, float uz, std::uint32_t seed)
{
  const Gradient& g00 = GradientOf(Hash(ix, y.Cell, z.Cell, seed));
  const Gradient& g10 = GradientOf(Hash(ix, y.Cell + 1, z.Cell, seed));
  const Gradient& g01 = GradientOf(Hash(ix, y.Cell, z.Cell + 1, seed));
  const Gradient& g11 = GradientOf(Hash(ix, y.Cell + 1, z.Cell + 1, seed));
  const float fy = y.Fraction, fz = z.Fraction;
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
  return n < -1.0f ? -1.0f : (n > 1.0f ? 1.0f : n);
}

// Point evaluations in lattice coordinates; each returns a value in [-1, 1].
inline float White(double x, double y, double z, std::uint32_t seed)
{
  return HashToSigned(Hash(Split(x).Cell, Split(y).Cell, Split(z).Cell, seed));
}
inline float Value(double x, double y, double z, std::uint32_t seed)
{
  const LatticeCoordinate lx = Split(x), ly = Split(y), lz = Split(z);
  const float uy = FadeCubic(ly.Fraction), uz = FadeCubic(lz.Fraction);
  return ValueAlongX(ValueColumn(lx.Cell, ly, lz, uy, uz, seed),
    ValueColumn(lx.Cell + 1, ly, lz, uy, uz, seed), lx.Fraction);
}
inline float Perlin(double x, double y, double z, std::uint32_t seed)
{
  const LatticeCoordinate lx = Split(x), ly = Split(y), lz = Split(z);
  const float uy = FadeQuintic(ly.Fraction), uz = FadeQuintic(lz.Fraction);
  return PerlinAlongX(PerlinColumn(lx.Cell, ly, lz, uy, uz, seed),
    PerlinColumn(lx.Cell + 1, ly, lz, uy, uz, seed), lx.Fraction);
}
inline float Evaluate(NoiseType type, double x, double y, double z, std::uint32_t seed)
{
  switch (type)
  {
    case NoiseType::White:
      return White(x, y, z, seed);
    case NoiseType::Value:
      return Value(x, y, z, seed);
    case NoiseType::Perlin:
      return Perlin(x, y, z, seed);
    case NoiseType::None:
      break;
  }
  return 0.0f;
}

// fBm: octave o samples noise at frequency f_o with amplitude a_o, where
// f_0 = Frequency, f_{o+1} = f_o * (Lacunarity + o * LacunarityIncrement), a_o = Amplitude * Gain^o.
// The defaults are the article's cloud: 6 octaves, amplitude 0.5 halving, factor 2.02 growing
// by 0.21 per octave.
struct FbmParameters
{
  NoiseType Type = NoiseType::Value;
  int Octaves = 6;
  double Frequency = 1.0;
  double Lacunarity = 2.02;
  double LacunarityIncrement = 0.21;
  double Gain = 0.5;
  double Amplitude = 0.5;
  std::uint32_t Seed = 0;
};

struct Octave
{
  double Frequency;
  float Amplitude;
  std::uint32_t Seed;
};

inline std::vector<Octave> OctaveSchedule(const FbmParameters& p)
{
  std::vector<Octave> octaves;
  if (p.Type == NoiseType::None)
  {
    return octaves;
  }
  double frequency = p.Frequency, amplitude = p.Amplitude;
  for (int o = 0; o < p.Octaves; ++o)
  {
    // Each octave gets its own lattice so octaves never line up.
    octaves.push_back({ frequency, static_cast<float>(amplitude),
      p.Seed * 0x9E3779B1u + static_cast<std::uint32_t>(o) * 0x85EBCA77u });
    frequency *= p.Lacunarity + o * p.LacunarityIncrement;
    amplitude *= p.Gain;
  }
  return octaves;
}

// The largest |fBm| can be: the sum of the octave amplitudes, since each octave is in [-1, 1].
inline double FbmBound(const FbmParameters& p)
{
  double bound = 0.0;
  for (const Octave& o : OctaveSchedule(p))
  {
    bound += std::abs(o.Amplitude);
  }
  return bound;
}

// fBm at a point already in world units (x, y, z include any wind offset).
inline float Fbm(const FbmParameters& p, double x, double y, double z)
{
  float sum = 0.0f;
  for (const Octave& o : OctaveSchedule(p))
  {
    sum += o.Amplitude * Evaluate(p.Type, x * o.Frequency, y * o.Frequency, z * o.Frequency, o.Seed);
  }
  return sum;
}

} // namespace noise
} // namespace cloudvis

#endif
