// Checks that several test programs make, as GoogleTest expectations: the statistical check of
// a Monte Carlo image, and every member of two LightingParameters. Header only, so that the
// support libraries stay free of a test framework and only test programs include it.
#ifndef cloudvis_SupportExpectations_h
#define cloudvis_SupportExpectations_h

#include "CloudLighting.h"
#include "SupportImages.h"

#include <gtest/gtest.h>

#include <string>

namespace cloudvis
{
namespace support
{

// The checks of every comparison of a path-traced image: the mean of `difference` over the
// pixels `use` picks is 0 within `sigmas` standard errors, and so is each block's (a local error
// cannot hide in the mean: at least minBlocks blocks of blockSize x blockSize pixels count); and
// the standard error is below `tightness` (1%) of `scale`, so the check is tight.
inline void ExpectNoDifference(const Image& image,
  int blockSize,
  const PixelFunction& difference,
  const PixelFunction& variance,
  const PixelSelection& use,
  double scale,
  int minBlocks,
  const std::string& what,
  double tightness = 0.01,
  double sigmas = 4.0)
{
  const Estimate mean = MeanOverPixels(image, difference, variance, use);
  EXPECT_NEAR(mean.Mean, 0.0, sigmas * mean.StandardError) << what;
  EXPECT_LT(mean.StandardError, tightness * scale) << what;
  int blocks = 0;
  EXPECT_LT(LargestBlockZ(image, blockSize, difference, variance, use, blocks), sigmas) << what;
  EXPECT_GE(blocks, minBlocks) << what;
}

// Each member of `actual` is `expected`'s, named in the message when it is not.
inline void ExpectSameLighting(const LightingParameters& actual,
  const LightingParameters& expected,
  const std::string& what)
{
#define CLOUDVIS_EXPECT_SAME(member)                                                               \
  EXPECT_EQ(actual.member, expected.member) << what << ": " #member
  CLOUDVIS_EXPECT_SAME(Model);
  CLOUDVIS_EXPECT_SAME(AmbientColor);
  CLOUDVIS_EXPECT_SAME(AmbientStrength);
  CLOUDVIS_EXPECT_SAME(DerivativeDistance);
  CLOUDVIS_EXPECT_SAME(LightSteps);
  CLOUDVIS_EXPECT_SAME(LightStep);
  CLOUDVIS_EXPECT_SAME(LightStepGrowth);
  CLOUDVIS_EXPECT_SAME(Transmittance);
  CLOUDVIS_EXPECT_SAME(PhaseG1);
  CLOUDVIS_EXPECT_SAME(PhaseG2);
  CLOUDVIS_EXPECT_SAME(PhaseLobeWeight);
  CLOUDVIS_EXPECT_SAME(MultipleScattering);
  CLOUDVIS_EXPECT_SAME(MultipleScatteringOctaves);
  CLOUDVIS_EXPECT_SAME(ScatteringFalloff);
  CLOUDVIS_EXPECT_SAME(ExtinctionFalloff);
  CLOUDVIS_EXPECT_SAME(EccentricityFalloff);
  CLOUDVIS_EXPECT_SAME(PowderStrength);
#undef CLOUDVIS_EXPECT_SAME
}

} // namespace support
} // namespace cloudvis

#endif
