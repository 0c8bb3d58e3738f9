// From linear radiance to display values: the exposure (in EV, fixed or chosen from the cloud's
// luminance) and the display curve (linear, or filmic with sRGB's encoding). The curve itself is
// written once for the GPU's composite pass and the C++ here, in
// shaders/display/DisplayTransform.glsl; this header is its C++ side and the automatic exposure,
// which both the exports and the viewer compute from a float image. docs/export.md, "Exposure
// and the display curve", gives the equations.
#ifndef CloudDisplayTransform_h
#define CloudDisplayTransform_h

#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <string>

namespace cloudvis
{

// render.display: the curve from exposed radiance to the display (the shared source's
// DisplayLinear and DisplayFilmic, which CloudDisplayTransform.cxx checks these against).
enum class DisplayCurve
{
  Linear = 0,
  Filmic = 1,
};

// The automatic exposure (render.exposure "auto") puts this percentile of the luminance of the
// cloud pixels' own colour (C / A, what the curve maps) at AutoExposureTarget before the curve: under the filmic curve that is a bright
// grey (display value 0.92, 236 of 255) with room left for the highlights (only pixels about 5
// times brighter clip to white), and the shading below it spread over the curve's middle (a
// target of 2 made the demo's cumulus a flat white with all of it above 0.76). A cloud pixel
// is one the cloud covers at least AutoExposureMinimumAlpha, or where no pixel is covered so
// much (a thin sheet), at least AutoExposureThinAlpha (one 8-bit level).
constexpr double AutoExposurePercentile = 0.99;
constexpr double AutoExposureTarget = 1.2;
constexpr double AutoExposureMinimumAlpha = 0.5;
constexpr float AutoExposureThinAlpha = 1.0f / 255.0f;
// The exposures render.exposure accepts, in EV (a factor of 2^-64 to 2^64).
constexpr double MaxExposureEV = 64.0;

struct AutoExposure
{
  bool Found = false;   // some pixel is a cloud pixel; else EV is 0
  double EV = 0.0;      // log2(AutoExposureTarget / luminance)
  double Luminance = 0; // the percentile's luminance (Rec. 709 weights of linear RGB)
  size_t CloudPixels = 0;
};

// The automatic exposure of a float image: `pixels` premultiplied linear RGBA values. An image
// without cloud pixels gets EV 0 (Found false), and one whose cloud pixels are all black EV 0
// too (Found true, Luminance 0).
CLOUDVISFILTERS_EXPORT AutoExposure ComputeAutoExposure(const float* rgba, size_t pixels);

// The premultiplied display value of one pixel's premultiplied radiance and opacity under
// `exposureEV` and `curve` (the shared source's DisplayValue), unclamped above for the linear
// curve (the caller quantizes).
CLOUDVISFILTERS_EXPORT glm::vec3 DisplayValueOf(
  const glm::vec3& radiance, float alpha, double exposureEV, DisplayCurve curve);

// "linear" or "filmic", as render.display names them.
CLOUDVISFILTERS_EXPORT std::string DisplayCurveName(DisplayCurve curve);

} // namespace cloudvis

#endif
