// The noises of a cloud density field by name, and fractional Brownian motion (fBm): a noise summed
// in octaves of rising frequency and falling amplitude. The lattice noises are in
// CloudLatticeNoise.h, the cellular ones and tiling in CloudCellularNoise.h.
#ifndef CloudNoise_h
#define CloudNoise_h

#include "CloudCellularNoise.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace cloudvis
{
namespace noise
{

enum class NoiseType
{
  None,           // no noise: fBm is 0
  White,          // an independent random value per lattice cell, no interpolation
  Value,          // random values on the lattice, interpolated with the cubic f*f*(3-2f)
  Perlin,         // random gradients on the lattice, quintic interpolation (improved Perlin noise)
  Worley,         // F1 cellular noise: 2 F1 - 1, dark at the feature points
  InvertedWorley, // 1 - 2 F1: round puffs around the feature points
  PerlinWorley,   // Perlin remapped by an inverted Worley fBm (CloudCellularNoise.h)
};

// True for the noises that have no row evaluation of their own: each voxel of a row is evaluated
// as a point.
inline bool IsCellular(NoiseType type)
{
  return type == NoiseType::Worley || type == NoiseType::InvertedWorley ||
    type == NoiseType::PerlinWorley;
}

// One noise at lattice coordinates (x, y, z), in [-1, 1]; it repeats every `period` lattice units
// when period > 0 (CloudCellularNoise.h).
inline float Evaluate(NoiseType type,
  double x,
  double y,
  double z,
  std::uint32_t seed,
  std::int32_t period = 0)
{
  switch (type)
  {
    case NoiseType::White:
      return TiledWhite(x, y, z, seed, period);
    case NoiseType::Value:
      return Value(x, y, z, seed, period);
    case NoiseType::Perlin:
      return Perlin(x, y, z, seed, period);
    case NoiseType::Worley:
      return std::min(1.0f, 2.0f * WorleyF1(x, y, z, seed, period) - 1.0f);
    case NoiseType::InvertedWorley:
      return std::max(-1.0f, 1.0f - 2.0f * WorleyF1(x, y, z, seed, period));
    case NoiseType::PerlinWorley:
      return 2.0f * PerlinWorley(x, y, z, seed, period) - 1.0f;
    case NoiseType::None:
      break;
  }
  return 0.0f;
}

// The limits ValidateFieldDescription (CloudDensityEvaluator.h) puts on FbmParameters; the
// scene schema states the same ones from here.
constexpr int MaxOctaves = 12;
constexpr double MaxFrequency = 1e6;

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
  // When > 0, the first octave repeats every Period lattice cells, i.e. every Period / Frequency
  // world units, and so does the whole fBm: octave o's period is Period times its frequency
  // ratio, which ValidateFieldDescription requires to be a whole number (an integer lacunarity,
  // no increment). 0: no repeat.
  std::int32_t Period = 0;
};

struct Octave
{
  double Frequency;
  float Amplitude;
  std::uint32_t Seed;
  std::int32_t Period; // lattice cells, 0 for none
};

// The largest period an octave may have, so that cells stay within the lattice's int32 range.
constexpr std::int64_t MaxPeriod = 1 << 24;

inline std::vector<Octave> OctaveSchedule(const FbmParameters& p)
{
  std::vector<Octave> octaves;
  if (p.Type == NoiseType::None)
  {
    return octaves;
  }
  double frequency = p.Frequency, amplitude = p.Amplitude;
  std::int64_t period = p.Period;
  for (int o = 0; o < p.Octaves; ++o)
  {
    // Each octave gets its own lattice so octaves never line up.
    octaves.push_back({ frequency,
      static_cast<float>(amplitude),
      p.Seed * 0x9E3779B1u + static_cast<std::uint32_t>(o) * 0x85EBCA77u,
      static_cast<std::int32_t>(std::min(period, MaxPeriod)) });
    const double factor = p.Lacunarity + o * p.LacunarityIncrement;
    frequency *= factor;
    amplitude *= p.Gain;
    period = static_cast<std::int64_t>(std::llround(static_cast<double>(period) * factor));
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
    sum += o.Amplitude *
      Evaluate(p.Type, x * o.Frequency, y * o.Frequency, z * o.Frequency, o.Seed, o.Period);
  }
  return sum;
}

} // namespace noise
} // namespace cloudvis

#endif
