// Noise and fBm: range, continuity, the difference between white and value noise, the fBm
// bound and the octave schedule of the write-ups.
#include "CloudNoise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace cloudvis::noise;

namespace
{
// Random points spread over many lattice cells, including negative coordinates.
std::vector<std::array<double, 3>> SamplePoints(int count, double extent = 50.0)
{
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> u(-extent, extent);
  std::vector<std::array<double, 3>> points(count);
  for (auto& p : points)
  {
    p = { u(rng), u(rng), u(rng) };
  }
  return points;
}
}

class NoiseOfEveryType : public ::testing::TestWithParam<NoiseType>
{
};

TEST_P(NoiseOfEveryType, StaysWithinMinusOneToOneAndUsesTheRange)
{
  float lo = 1.0f, hi = -1.0f;
  for (const auto& p : SamplePoints(200000))
  {
    const float n = Evaluate(GetParam(), p[0], p[1], p[2], 7u);
    ASSERT_GE(n, -1.0f);
    ASSERT_LE(n, 1.0f);
    lo = std::min(lo, n);
    hi = std::max(hi, n);
  }
  // A noise squeezed into a small part of the range would make pale clouds.
  EXPECT_LT(lo, -0.6f);
  EXPECT_GT(hi, 0.6f);
}

TEST_P(NoiseOfEveryType, TheSeedChangesThePattern)
{
  int different = 0;
  for (const auto& p : SamplePoints(1000))
  {
    different += Evaluate(GetParam(), p[0], p[1], p[2], 1u) != Evaluate(GetParam(), p[0], p[1], p[2], 2u);
  }
  EXPECT_GT(different, 950);
}

INSTANTIATE_TEST_SUITE_P(AllTypes, NoiseOfEveryType,
  ::testing::Values(NoiseType::White, NoiseType::Value, NoiseType::Perlin),
  [](const ::testing::TestParamInfo<NoiseType>& parameter) {
    return parameter.param == NoiseType::White
      ? "White"
      : (parameter.param == NoiseType::Value ? "Value" : "Perlin");
  });

TEST(Noise, ValueAndPerlinNoiseAreContinuous)
{
  // A step of 1e-3 lattice cells changes a continuous noise by at most a few times the
  // step times its largest slope (about 1.5 for the cubic, 1.9 for the quintic, per axis).
  const double h = 1e-3;
  for (NoiseType type : { NoiseType::Value, NoiseType::Perlin })
  {
    float largest = 0.0f;
    for (const auto& p : SamplePoints(50000))
    {
      const float a = Evaluate(type, p[0], p[1], p[2], 3u);
      const float b = Evaluate(type, p[0] + h, p[1] + h, p[2] + h, 3u);
      largest = std::max(largest, std::abs(a - b));
    }
    EXPECT_LT(largest, 0.03f) << "noise type " << int(type);
  }
}

TEST(Noise, WhiteNoiseJumpsWhereValueNoiseIsSmooth)
{
  // Across a lattice cell boundary white noise jumps to an unrelated value; value noise,
  // sampled the same way, changes by almost nothing.
  double whiteJump = 0.0, valueJump = 0.0;
  int n = 0;
  for (int ix = -20; ix < 20; ++ix)
  {
    for (int iy = -20; iy < 20; ++iy)
    {
      const double x = ix, y = iy + 0.5, z = 0.25;
      whiteJump += std::abs(White(x - 1e-4, y, z, 5u) - White(x + 1e-4, y, z, 5u));
      valueJump += std::abs(Value(x - 1e-4, y, z, 5u) - Value(x + 1e-4, y, z, 5u));
      ++n;
    }
  }
  // Two independent uniform values in [-1, 1] differ by 2/3 on average.
  EXPECT_GT(whiteJump / n, 0.5);
  EXPECT_LT(valueJump / n, 1e-3);
}

TEST(Noise, ValueNoiseEqualsTheLatticeValueAtLatticePoints)
{
  for (int i = -5; i < 5; ++i)
  {
    EXPECT_FLOAT_EQ(Value(i, 2 * i, -i, 9u), HashToSigned(Hash(i, 2 * i, -i, 9u)));
  }
}

TEST(Fbm, TheOctaveScheduleIsTheArticles)
{
  FbmParameters p; // defaults: 6 octaves, amplitude 0.5 halving, factor 2.02 growing by 0.21
  const std::vector<Octave> octaves = OctaveSchedule(p);
  ASSERT_EQ(octaves.size(), 6u);
  double frequency = 1.0, factor = 2.02, amplitude = 0.5;
  for (const Octave& o : octaves)
  {
    EXPECT_NEAR(o.Frequency, frequency, 1e-12);
    EXPECT_FLOAT_EQ(o.Amplitude, float(amplitude));
    frequency *= factor;
    factor += 0.21;
    amplitude *= 0.5;
  }
  EXPECT_NEAR(FbmBound(p), 0.5 + 0.25 + 0.125 + 0.0625 + 0.03125 + 0.015625, 1e-7);
}

TEST(Fbm, StaysWithinTheSumOfItsAmplitudes)
{
  for (NoiseType type : { NoiseType::White, NoiseType::Value, NoiseType::Perlin })
  {
    FbmParameters p;
    p.Type = type;
    p.Octaves = 8;
    p.Amplitude = 0.7;
    p.Gain = 0.6;
    const double bound = FbmBound(p);
    double largest = 0.0;
    for (const auto& q : SamplePoints(20000, 5.0))
    {
      const double f = Fbm(p, q[0], q[1], q[2]);
      largest = std::max(largest, std::abs(f));
      ASSERT_LE(std::abs(f), bound + 1e-5);
    }
    EXPECT_GT(largest, 0.3 * bound) << "noise type " << int(type);
  }
}

TEST(Fbm, NoNoiseGivesZero)
{
  FbmParameters p;
  p.Type = NoiseType::None;
  EXPECT_EQ(FbmBound(p), 0.0);
  EXPECT_EQ(Fbm(p, 0.3, 0.2, 0.1), 0.0f);
}
