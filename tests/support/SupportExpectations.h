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
inline void ExpectNoDifference(const Image& image, int blockSize, const PixelFunction& difference,
  const PixelFunction& variance, const PixelSelection& use, double scale, int minBlocks,
  const std::string& what, double tightness = 0.01, double sigmas = 4.0)
{
  const Estimate mean = MeanOverPixels(image, difference, variance, use);
  EXPECT_NEAR(mean.Mean, 0.0, sigmas * mean.StandardError) << what;
  EXPECT_LT(mean.StandardError, tightness * scale) << what;
  int blocks = 0;
  EXPECT_LT(LargestBlockZ(image, blockSize, difference, variance, use, blocks), sigmas) << what;
  EXPECT_GE(blocks, minBlocks) << what;
}

// Each member of `actual` is `expected`'s, named in the message when it is not.
inline void ExpectSameLighting(
  const LightingParameters& actual, const LightingParameters& expected, const std::string& what)
{
  EXPECT_EQ(actual.Model, expected.Model) << what << ": Model";
  EXPECT_EQ(actual.AmbientColor, expected.AmbientColor) << what << ": AmbientColor";
  EXPECT_EQ(actual.AmbientStrength, expected.AmbientStrength) << what << ": AmbientStrength";
  EXPECT_EQ(actual.DerivativeDistance, expected.DerivativeDistance) << what << ": DerivativeDistance";
  EXPECT_EQ(actual.LightSteps, expected.LightSteps) << what << ": LightSteps";
  EXPECT_EQ(actual.LightStep, expected.LightStep) << what << ": LightStep";
  EXPECT_EQ(actual.LightStepGrowth, expected.LightStepGrowth) << what << ": LightStepGrowth";
  EXPECT_EQ(actual.Transmittance, expected.Transmittance) << what << ": Transmittance";
  EXPECT_EQ(actual.PhaseG1, expected.PhaseG1) << what << ": PhaseG1";
  EXPECT_EQ(actual.PhaseG2, expected.PhaseG2) << what << ": PhaseG2";
  EXPECT_EQ(actual.PhaseLobeWeight, expected.PhaseLobeWeight) << what << ": PhaseLobeWeight";
  EXPECT_EQ(actual.MultipleScatteringOctaves, expected.MultipleScatteringOctaves)
    << what << ": MultipleScatteringOctaves";
  EXPECT_EQ(actual.ScatteringFalloff, expected.ScatteringFalloff) << what << ": ScatteringFalloff";
  EXPECT_EQ(actual.ExtinctionFalloff, expected.ExtinctionFalloff) << what << ": ExtinctionFalloff";
  EXPECT_EQ(actual.EccentricityFalloff, expected.EccentricityFalloff)
    << what << ": EccentricityFalloff";
  EXPECT_EQ(actual.PowderStrength, expected.PowderStrength) << what << ": PowderStrength";
}

} // namespace support
} // namespace cloudvis

#endif
