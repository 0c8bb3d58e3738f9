// The cloud model of real-time cloudscapes: a layer of air between a base and a top altitude, a
// coverage that says where clouds may be, a height profile per cloud type, a low-frequency shape
// noise that makes the cloud's mass and a high-frequency detail noise that erodes its edges
// (Schneider's Nubis, SIGGRAPH Advances 2015 and 2017; Hillaire, "Physically based sky,
// atmosphere and cloud rendering in Frostbite", SIGGRAPH 2016; Häggström, "Real-time rendering of
// volumetric clouds", 2018).
//
// With h the height fraction in the layer (altitude along y), c the coverage at the point, P the
// cloud type's height profile, S the shape noise and D the detail noise (both in [0, 1]):
//   base    = remap(S * P(h), 1 - c, 1, 0, 1) * c             coverage erodes the shape
//   D'      = mix(D, 1 - D, saturate(10 h))                   wispy under the base, billowy above
//   density = scale * saturate(remap(base, erosion * D', 1, 0, 1))
// where remap(v, lo, hi, a, b) = a + (v - lo) / (hi - lo) * (b - a). Erosion only ever removes
// density, at the edges where base is small, which keeps the silhouette crisp and the core solid;
// the result never exceeds `scale`.
//
// Coverage comes from the field's shapes (one cloud: c = coverage * saturate(-sdf / falloff)),
// from a procedural weather map (many clouds: a 2-D Perlin fBm thresholded at the coverage), or
// from a 2-D map read from a file (thresholded the same way); above the base a weather map may be
// broken up in 3-D (Breakup). A cumulonimbus on the shapes stands on its footprint, with an anvil
// streaming downwind and an overshooting dome (CloudTowerPlan.h); over a map it widens its
// coverage near the top. An altocumulus's coverage is cut into cloudlets by a Worley lattice. Wind moves the noises and the weather map with time; shear leans
// the clouds, displacing everything above the base by `shear` per unit of height.
//
// S and D are tileable noises baked once into small periodic volumes (64^3 texels each) and
// read with trilinear filtering, as the cited renderers do: one fetch per voxel instead of a
// dozen cellular evaluations, which is what lets a 512^3 cloudscape generate in seconds. The bake
// depends only on the seed, so every piece of a field reads the same volumes.
#ifndef CloudLayer_h
#define CloudLayer_h

#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkImageData;

namespace cloudvis
{

enum class CloudType
{
  Stratus,
  Stratocumulus,
  Cumulus,
  Cumulonimbus,
  Altocumulus, // a thin mid-level sheet of cloudlets on a cellular lattice
  Congestus,   // a towering cumulus: a flat base under a tall, narrowing tower
};

enum class CoverageSource
{
  Shapes, // the field's shapes: one cloud (or a few) where they are
  Noise,  // a procedural weather map: a 2-D Perlin fBm over x and z
  Map,    // a 2-D map of values in [0, 1] over the field's x and z bounds
};

// A weather map: Width x Height values in [0, 1], row-major with x along a row; the first value
// lies at (XMin, ZMin), the last at (XMax, ZMax), bilinear in between, the edge values beyond.
// vtkCloudDensitySource stretches it over the field's x and z bounds.
struct CoverageMap
{
  int Width = 0;
  int Height = 0;
  std::vector<float> Values;
  double XMin = 0.0, XMax = 1.0, ZMin = 0.0, ZMax = 1.0;

  float Sample(double x, double z) const;
};

// The map of a 2-D image (one of its dimensions 1): its first two axes of more than one point
// become x and z, its first point-data component the values. Integer values are divided by their
// type's maximum (an 8-bit image's 255 is coverage 1); floating-point values must lie in [0, 1].
// Null, with the problem in `problem`, for an image that is not 2-D, has no scalars, or holds a
// value outside [0, 1] or NaN.
CLOUDVISFILTERS_EXPORT std::shared_ptr<const CoverageMap> CoverageMapOfImage(vtkImageData* image,
  std::string& problem);

struct CloudLayer
{
  CloudType Type = CloudType::Cumulus;
  double Base = -1.0;    // altitude (y, world units) of the cloud base
  double Top = 1.0;      // and of the top; Base < Top
  double Coverage = 0.6; // in [0, 1]
  CoverageSource Source = CoverageSource::Shapes;
  std::shared_ptr<const CoverageMap> Map; // Source == Map
  // The procedural weather map: the size of its largest features (world units), its octaves and
  // the gain between them. The gain sets how rough the cloud outlines seen from above are (a 2-D
  // fBm's Hurst exponent is -log2(gain)): the area-perimeter dimension of the thresholded map's
  // islands measures 1.27 at gain 0.6, 1.34 at 0.7 and 1.41 at 0.8 (6 octaves, 35% coverage),
  // against the 1.35 Lovejoy measured for real clouds.
  double MapScale = 4.0;
  int MapOctaves = 6;
  double MapGain = 0.6;
  double ShapeScale = 2.0;  // world length over which the shape noise repeats
  double DetailScale = 0.5; // and the detail noise
  double Erosion = 0.4;     // in [0, 1]: how deep the detail noise eats into the edges
  // Curl-noise turbulence of the detail noise, 0 .. 1: the detail is read at points displaced by
  // 0.25 * Curl * (1 - h) detail tiles times the curl noise (whose components are of order 1 to 3).
  double Curl = 0.0;
  // How far a 3-D noise moves a weather map's value above the base, 0 .. 1 (a noise or map
  // coverage only): the clouds' sides break up instead of rising as the map's outlines.
  double Breakup = 0.0;
  // The cumulonimbus's anvil (CloudTowerPlan.h): its strength, 0 .. 1 (0: no anvil); the
  // direction [x, z] of the upper wind it streams along (any length but 0); how far it reaches
  // downwind from the tower (world units, >= 0; times Anvil); and the height of the overshooting
  // dome above Top on the tower's axis (world units, >= 0; 0: none).
  double Anvil = 0.0;
  std::array<double, 2> AnvilDirection{ { 1.0, 0.0 } };
  double AnvilReach = 0.0;
  double Overshoot = 0.0;
  // The cumulonimbus's rain shaft under its base (shapes coverage only): its density at the heart
  // of its streaks, as a fraction of the field's density scale, 0 .. 1 (0: none).
  double Rain = 0.0;
  std::array<double, 2> Shear{ { 0.0, 0.0 } }; // x and z displacement per unit of height above base
};

// The height profile of a cloud type at height fraction h in [0, 1]: 0 below the base and above
// the top, up to 1 in between.
CLOUDVISFILTERS_EXPORT float HeightProfile(CloudType type, float h);

// Empty when the layer can be evaluated, else what is wrong with it.
CLOUDVISFILTERS_EXPORT std::string ValidateCloudLayer(const CloudLayer& layer);

// A tileable noise baked into a periodic cube of Size^3 texels, read with trilinear filtering:
// Sample(u) at u in tiles (1 tile = the cube; any real u, it wraps).
struct CLOUDVISFILTERS_EXPORT TiledVolume
{
  int Size = 0;
  std::vector<float> Texels; // x fastest
  float Sample(glm::dvec3 u) const;
};

// The baked noises of a seed: the shape (Perlin-Worley remapped by an inverted Worley fBm), the
// detail (inverted Worley fBm) and the curl field (three components). Computed once per seed and
// shared (a small process-wide cache), since the bake costs a few tenths of a second.
struct CloudNoiseVolumes
{
  TiledVolume Shape;
  TiledVolume Detail;
  TiledVolume Curl[3];
};
CLOUDVISFILTERS_EXPORT std::shared_ptr<const CloudNoiseVolumes> BakeCloudNoise(std::uint32_t seed);

// The most lattice cells per world unit that the layer's noises sample: the baked volumes' texels
// per tile over their scales, and the procedural weather map's highest octave. A coordinate
// times this must stay within the 32-bit lattice cells (ValidateNoiseRange).
CLOUDVISFILTERS_EXPORT double CloudLatticeDensity(const CloudLayer& layer);

// The Perlin fBm of the procedural weather map at (x, z) in world units and `height` above the
// layer's base, in [0, 1]. Its octaves wider than the layer is deep are 2-D (they place the
// clouds); the finer ones, the clouds' own eddies, turn with height as fast as they vary across,
// so that a cloud's sides are not its outline drawn straight up. At the base it is the 2-D map,
// and above it never exceeds the base's value, so that every cloud keeps a flat base.
CLOUDVISFILTERS_EXPORT float WeatherNoise(const CloudLayer& layer,
  std::uint32_t seed,
  double x,
  double z,
  double height);

} // namespace cloudvis

#endif
