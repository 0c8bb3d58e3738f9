// Committed baseline images for the pictures a user relies on, in the manner of VTK's
// vtkRegressionTestImage and F3D's TestSDKHelpers: a test renders at a small fixed size with
// fixed seeds and no jitter, and compares with tests/baselines/NAME.png (or an alternate,
// NAME_1.png, NAME_2.png ..., for a platform that draws it differently but rightly).
//
//   - no baseline: the image is written to the output folder and the check fails, saying where
//     the image is and how to make it the baseline;
//   - a difference beyond the tolerance: the image and a difference image (NAME.png,
//     NAME-difference.png, |a - b| x 10) are written to the output folder (the build's
//     tests/baseline-output) and the check fails with the figures and the paths;
//   - CLOUDVIS_REGENERATE_BASELINES=1 in the environment: the image becomes the baseline (written
//     into the source tree) and the check passes. tests/baselines/regenerate.sh does this for every
//     baseline test, on purpose only: look at the new images before committing them.
#ifndef cloudvis_SupportBaselines_h
#define cloudvis_SupportBaselines_h

#include "SupportImages.h"

#include <string>

namespace cloudvis
{
namespace support
{

// How far an image may be from its baseline, in 8-bit levels over the RGB channels. The
// defaults were measured on the two-light scene at 128 x 96 (march, no jitter): a rerender, or
// llvmpipe on one thread, gives the same bytes; the CPU reference, another implementation of the
// same equations, differs by 0.26 levels RMS and 1 at most, so another correct platform stays
// within 0.5 RMS and 4 at most; a 5% change of the ambient strength (0.63 RMS) or of the phase
// eccentricity g1 (1.5 RMS, 7 at most) does not.
struct Tolerance
{
  double RmsLevels = 0.5;
  double MaxLevels = 4.0;
};

struct BaselineCheck
{
  bool Passed = false;
  std::string Message; // what was compared and, on failure, where the images are
  explicit operator bool() const { return this->Passed; }
};

BaselineCheck CompareWithBaseline(const Image& image,
  const std::string& name,
  const Tolerance& tolerance = {});

} // namespace support
} // namespace cloudvis

#endif
