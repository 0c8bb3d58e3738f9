// How far an image is from a reference image with a per-pixel variance (the path tracer's), and
// how noisy that reference is: the figures docs/lighting.md tabulates for each lighting model
// against the ground truth. Images are premultiplied RGBA floats, 4 per pixel, as the
// renderers write them; the statistics run over r, g and b of the pixels where either image
// has an opacity above a threshold (the cloud's footprint), so the empty background does not
// dilute them.
#ifndef CloudImageComparison_h
#define CloudImageComparison_h

#include "cloudvisFiltersModule.h"

#include <cstddef>

namespace cloudvis
{

// The footprint: pixels whose opacity (in either image) is above this.
constexpr float FootprintOpacity = 0.01f;

struct ImageNoise
{
  std::size_t Pixels = 0;    // in the footprint
  double MeanRadiance = 0.0; // mean of r, g, b over the footprint
  // The RMS over the footprint's r, g, b of the standard error of each pixel's mean, relative
  // to MeanRadiance: the image's noise level.
  double RelativeStandardError = 0.0;
};

// The noise level of an image with per-pixel variances of its means (vtkCloudPathTracer's
// "rgba" and "rgba_variance").
CLOUDVISFILTERS_EXPORT ImageNoise MeasureImageNoise(
  const float* rgba, const float* rgbaVariance, std::size_t pixels);

struct ImageError
{
  std::size_t Pixels = 0; // in the footprint of either image
  // sqrt(mean (x - x_ref)^2) / mean(x_ref): the error, noise of the reference included.
  double RelativeRMSE = 0.0;
  // The same with the reference's variance subtracted from the mean squared error (0 when the
  // difference is all noise): the error the reference's noise does not explain.
  double NoiseCorrectedRelativeRMSE = 0.0;
  double BiasRatio = 0.0;                      // mean(x) / mean(x_ref): above 1 too bright
  double MaxErrorOverPeak = 0.0;               // max |x - x_ref| / max x_ref
  double ReferenceRelativeStandardError = 0.0; // the reference's noise level (MeasureImageNoise)
};

CLOUDVISFILTERS_EXPORT ImageError CompareWithReference(const float* rgba,
  const float* referenceRgba, const float* referenceVariance, std::size_t pixels);

} // namespace cloudvis

#endif
