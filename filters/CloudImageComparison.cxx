#include "CloudImageComparison.h"

#include <algorithm>
#include <cmath>

namespace cloudvis
{

namespace
{
bool InFootprint(const float* pixel)
{
  return pixel[3] > FootprintOpacity;
}
}

ImageNoise MeasureImageNoise(const float* rgba, const float* rgbaVariance, std::size_t pixels)
{
  ImageNoise noise;
  double sum = 0.0, variance = 0.0;
  for (std::size_t i = 0; i < pixels; ++i)
  {
    if (!InFootprint(rgba + 4 * i))
    {
      continue;
    }
    ++noise.Pixels;
    for (int c = 0; c < 3; ++c)
    {
      sum += rgba[4 * i + c];
      variance += rgbaVariance[4 * i + c];
    }
  }
  if (noise.Pixels > 0)
  {
    const double values = 3.0 * double(noise.Pixels);
    noise.MeanRadiance = sum / values;
    noise.RelativeStandardError =
      noise.MeanRadiance > 0.0 ? std::sqrt(variance / values) / noise.MeanRadiance : 0.0;
  }
  return noise;
}

ImageError CompareWithReference(
  const float* rgba, const float* referenceRgba, const float* referenceVariance, std::size_t pixels)
{
  ImageError error;
  double sum = 0.0, referenceSum = 0.0, squaredError = 0.0, variance = 0.0;
  double maxError = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < pixels; ++i)
  {
    if (!InFootprint(rgba + 4 * i) && !InFootprint(referenceRgba + 4 * i))
    {
      continue;
    }
    ++error.Pixels;
    for (int c = 0; c < 3; ++c)
    {
      const double x = rgba[4 * i + c], reference = referenceRgba[4 * i + c];
      sum += x;
      referenceSum += reference;
      squaredError += (x - reference) * (x - reference);
      variance += referenceVariance[4 * i + c];
      maxError = std::max(maxError, std::abs(x - reference));
      peak = std::max(peak, reference);
    }
  }
  if (error.Pixels == 0 || !(referenceSum > 0.0))
  {
    return error;
  }
  const double values = 3.0 * double(error.Pixels);
  const double referenceMean = referenceSum / values;
  error.RelativeRMSE = std::sqrt(squaredError / values) / referenceMean;
  error.NoiseCorrectedRelativeRMSE =
    std::sqrt(std::max(0.0, squaredError - variance) / values) / referenceMean;
  error.BiasRatio = sum / referenceSum;
  error.MaxErrorOverPeak = maxError / peak;
  error.ReferenceRelativeStandardError = std::sqrt(variance / values) / referenceMean;
  return error;
}

} // namespace cloudvis
