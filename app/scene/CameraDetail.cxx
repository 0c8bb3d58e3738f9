// field.dimensions "auto" (CameraDetail.h): the nearest point of the cloud's region inside the
// view, the width a pixel spans there, and the lattice whose voxels are no wider.
#include "CameraDetail.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace cloudvis
{
namespace
{
// Rays per image side sampled for the nearest point: the region's nearest point in view lies on
// its boundary, where the entry distance varies smoothly between neighbouring rays.
constexpr int RaysPerSide = 65;

glm::dvec3 Vec(const std::array<double, 3>& a)
{
  return glm::dvec3(a[0], a[1], a[2]);
}

// Where the ray from `origin` along the unit `direction` enters the box (0 when it starts
// inside), or a negative number when it misses.
double EntryDistance(const glm::dvec3& origin,
  const glm::dvec3& direction,
  const std::array<double, 6>& box)
{
  double near = 0.0;
  double far = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    const double lo = box[size_t(2 * a)], hi = box[size_t(2 * a + 1)];
    if (direction[a] == 0.0)
    {
      if (origin[a] < lo || origin[a] > hi)
      {
        return -1.0;
      }
      continue;
    }
    double t0 = (lo - origin[a]) / direction[a];
    double t1 = (hi - origin[a]) / direction[a];
    if (t0 > t1)
    {
      std::swap(t0, t1);
    }
    near = std::max(near, t0);
    far = std::min(far, t1);
  }
  return near <= far ? near : -1.0;
}

// The lattice over `bounds` with every spacing at most `voxel`: bounds / (n - 1), n >= 2.
std::array<double, 3> CountsFor(const std::array<double, 6>& bounds, double voxel)
{
  std::array<double, 3> counts{};
  for (int a = 0; a < 3; ++a)
  {
    const double extent = bounds[size_t(2 * a + 1)] - bounds[size_t(2 * a)];
    counts[size_t(a)] = std::max(2.0, std::ceil(extent / voxel) + 1.0);
  }
  return counts;
}
} // namespace

std::optional<CameraDetail> ChooseCameraDetail(const CameraView& camera,
  const std::array<double, 6>& region,
  const std::array<double, 6>& bounds,
  std::uint64_t maximumVoxels)
{
  const glm::dvec3 eye = Vec(camera.Position);
  const glm::dvec3 forward = glm::normalize(Vec(camera.FocalPoint) - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, Vec(camera.ViewUp)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tanHalf = std::tan(0.5 * glm::radians(camera.ViewAngle));
  const double aspect = double(camera.Width) / double(camera.Height);
  // A pixel's angle at the image's centre; off axis, a ray at angle alpha to the view direction
  // sees its pixel cos^2(alpha) as wide across the ray.
  const double pixelAngle = 2.0 * tanHalf / double(camera.Height);

  double footprint = std::numeric_limits<double>::infinity();
  double nearest = std::numeric_limits<double>::infinity();
  const auto consider = [&](double x, double y) // image coordinates in [-1, 1]
  {
    const glm::dvec3 along = forward + x * tanHalf * aspect * right + y * tanHalf * up;
    const double length = glm::length(along);
    const double t = EntryDistance(eye, along / length, region);
    if (t < 0.0)
    {
      return;
    }
    const double cosine = 1.0 / length;
    footprint = std::min(footprint, t * cosine * cosine * pixelAngle);
    nearest = std::min(nearest, t);
  };
  for (int j = 0; j < RaysPerSide; ++j)
  {
    for (int i = 0; i < RaysPerSide; ++i)
    {
      consider(2.0 * i / (RaysPerSide - 1) - 1.0, 2.0 * j / (RaysPerSide - 1) - 1.0);
    }
  }
  // The region's point nearest the eye, when the view holds it, between the rays above.
  glm::dvec3 closest;
  for (int a = 0; a < 3; ++a)
  {
    closest[a] = std::clamp(eye[a], region[size_t(2 * a)], region[size_t(2 * a + 1)]);
  }
  const glm::dvec3 toClosest = closest - eye;
  const double depth = glm::dot(toClosest, forward);
  if (depth > 0.0)
  {
    const double x = glm::dot(toClosest, right) / (depth * tanHalf * aspect);
    const double y = glm::dot(toClosest, up) / (depth * tanHalf);
    if (std::abs(x) <= 1.0 && std::abs(y) <= 1.0)
    {
      consider(x, y);
    }
  }
  else if (glm::length(toClosest) == 0.0)
  {
    consider(0.0, 0.0); // inside the region: the nearest cloud may touch the lens
  }
  if (!std::isfinite(nearest))
  {
    return std::nullopt;
  }

  CameraDetail detail;
  detail.NearestCloud = nearest;
  detail.PixelFootprint = footprint;
  // The smallest voxel the cap allows, then the pixel's footprint if that is coarser.
  const auto voxelsOf = [](const std::array<double, 3>& n) { return n[0] * n[1] * n[2]; };
  constexpr double mostPerAxis = std::numeric_limits<int>::max();
  const auto fits = [&](const std::array<double, 3>& n) {
    return voxelsOf(n) <= double(maximumVoxels) && std::max({ n[0], n[1], n[2] }) <= mostPerAxis;
  };
  const double cap = double(maximumVoxels);
  double extentProduct = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    extentProduct *= bounds[size_t(2 * a + 1)] - bounds[size_t(2 * a)];
  }
  double voxel = std::max(footprint, std::cbrt(extentProduct / cap));
  std::array<double, 3> counts = CountsFor(bounds, voxel);
  // The +1 voxel per axis and the clamp to 2 make the first guess too fine: grow until it fits.
  while (!fits(counts))
  {
    voxel *= std::max({ 1.0 + 1e-6,
      std::cbrt(voxelsOf(counts) / cap),
      std::max({ counts[0], counts[1], counts[2] }) / mostPerAxis });
    counts = CountsFor(bounds, voxel);
  }
  detail.Capped = voxel > footprint;
  detail.Voxel = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    detail.Dimensions[size_t(a)] = int(counts[size_t(a)]);
    detail.Voxel = std::max(detail.Voxel,
      (bounds[size_t(2 * a + 1)] - bounds[size_t(2 * a)]) / (counts[size_t(a)] - 1.0));
  }
  return detail;
}

std::string DescribeCameraDetail(const CameraDetail& detail,
  const std::string& unit,
  std::uint64_t maximumVoxels)
{
  std::ostringstream words;
  words.precision(3);
  const std::array<int, 3>& d = detail.Dimensions;
  words << d[0] << " x " << d[1] << " x " << d[2] << " voxels of " << detail.Voxel << " " << unit
        << ": the nearest cloud in view is " << detail.NearestCloud << " " << unit
        << " away, where a pixel spans " << detail.PixelFootprint << " " << unit;
  if (detail.Capped)
  {
    words << "; field.max_voxels (" << maximumVoxels << ") capped them at ";
    if (detail.PixelFootprint > 0.0)
    {
      words << detail.Voxel / detail.PixelFootprint << " pixels there";
    }
    else
    {
      words << "the voxels it allows (the camera is inside the cloud's region)";
    }
  }
  return words.str();
}

} // namespace cloudvis
