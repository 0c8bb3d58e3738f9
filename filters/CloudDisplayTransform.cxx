// The C++ side of the shared display transform, and the automatic exposure: a percentile of the
// cloud pixels' luminance (CloudDisplayTransform.h).
#include "CloudDisplayTransform.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace cloudvis
{

// The shared source's functions, in C++ (DisplayValue, FilmicCurve, SrgbEncode).
namespace display
{
using namespace glm;
#include "../shaders/display/DisplayTransform.glsl"
}
static_assert(int(DisplayCurve::Linear) == display::DisplayLinear &&
    int(DisplayCurve::Filmic) == display::DisplayFilmic,
  "render.display's curves are the shared source's");

glm::vec3 DisplayValueOf(
  const glm::vec3& radiance, float alpha, double exposureEV, DisplayCurve curve)
{
  return display::DisplayValue(radiance, alpha, float(std::exp2(exposureEV)), int(curve));
}

AutoExposure ComputeAutoExposure(const float* rgba, size_t pixels)
{
  // The curve maps the cloud's own colour C / A (DisplayValue), so that is what is metered; over
  // the pixels the cloud covers well, or for a thin cloud that covers none so well, over every
  // pixel it shows in at all.
  std::vector<float> luminance;
  for (const float minimumAlpha : { float(AutoExposureMinimumAlpha), AutoExposureThinAlpha })
  {
    for (size_t i = 0; i < pixels; ++i)
    {
      const float* p = rgba + 4 * i;
      if (p[3] >= minimumAlpha)
      {
        luminance.push_back((0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]) / p[3]);
      }
    }
    if (!luminance.empty())
    {
      break;
    }
  }
  AutoExposure result;
  result.CloudPixels = luminance.size();
  if (luminance.empty())
  {
    return result;
  }
  result.Found = true;
  const size_t rank = std::min(luminance.size() - 1,
    size_t(std::floor(AutoExposurePercentile * double(luminance.size() - 1) + 0.5)));
  std::nth_element(luminance.begin(), luminance.begin() + long(rank), luminance.end());
  result.Luminance = double(luminance[rank]);
  if (result.Luminance > 0.0)
  {
    result.EV = std::clamp(
      std::log2(AutoExposureTarget / result.Luminance), -MaxExposureEV, MaxExposureEV);
  }
  return result;
}

std::string DisplayCurveName(DisplayCurve curve)
{
  return curve == DisplayCurve::Filmic ? "filmic" : "linear";
}

} // namespace cloudvis
