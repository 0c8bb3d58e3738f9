// Detail matched to the camera: field.dimensions "auto" chooses a generated field's voxels so
// that one voxel projects to at most about one pixel on the nearest cloud the scene's camera
// sees, within field.max_voxels. The nearest cloud is bounded from below by the nearest point of
// the region that can hold cloud (the field's bounds; for the cloud model, its layer's heights)
// inside the view: the choice never leaves that cloud coarser than a pixel unless the cap says
// so. Pure geometry, fixed by the scene alone, so that pieces and MPI ranks choose alike.
#ifndef cloudvis_CameraDetail_h
#define cloudvis_CameraDetail_h

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace cloudvis
{

// A pinhole camera as the renderers place it: view_angle is vertical, in degrees, over an image
// of Width x Height pixels.
struct CameraView
{
  std::array<double, 3> Position{ { 0.0, 0.0, 1.0 } };
  std::array<double, 3> FocalPoint{ { 0.0, 0.0, 0.0 } };
  std::array<double, 3> ViewUp{ { 0.0, 1.0, 0.0 } };
  double ViewAngle = 30.0;
  int Width = 800;
  int Height = 600;
};

// What "auto" chose and why (info reports it).
struct CameraDetail
{
  std::array<int, 3> Dimensions{ { 2, 2, 2 } };
  // World units from the camera to the nearest point it sees of the region that can hold cloud.
  double NearestCloud = 0.0;
  // The width one pixel spans there, across the ray, in world units.
  double PixelFootprint = 0.0;
  // The largest spacing of the chosen lattice (bounds / (dimensions - 1)), world units.
  double Voxel = 0.0;
  // Whether MaximumVoxels made the voxel larger than the pixel's footprint.
  bool Capped = false;
};

// The smallest voxels a field over `bounds` [xmin, xmax, ymin, ymax, zmin, zmax] needs for the
// camera to see none larger than a pixel in `region` (a box within bounds that holds every
// cloud), as one isotropic spacing with the first and last voxels on the bounds; voxels grow
// together until there are at most maximumVoxels (>= 8: at least 2 along each axis). Empty when
// no ray of the view meets the region. The camera must have a direction and a view-up across
// it.
std::optional<CameraDetail> ChooseCameraDetail(const CameraView& camera,
  const std::array<double, 6>& region,
  const std::array<double, 6>& bounds,
  std::uint64_t maximumVoxels);

// What was chosen, in words for info ("480 x 120 x 480 voxels of 26.7 m: the nearest cloud in
// view is 770 m away, where a pixel spans 1.78 m; field.max_voxels (27648000) capped them at 15
// pixels there"); `unit` names the world unit ("m", or "world units").
std::string DescribeCameraDetail(const CameraDetail& detail,
  const std::string& unit,
  std::uint64_t maximumVoxels);

} // namespace cloudvis

#endif
