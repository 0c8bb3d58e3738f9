#include "CloudLayer.h"

#include "CloudNoise.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>
#include <vtkType.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <future>
#include <map>
#include <mutex>
#include <sstream>

namespace cloudvis
{

namespace
{
using noise::Saturate;
float SmoothStep(float edge0, float edge1, float v)
{
  const float t = Saturate((v - edge0) / (edge1 - edge0));
  return t * t * (3.0f - 2.0f * t);
}
}

float HeightProfile(CloudType type, float h)
{
  if (!(h > 0.0f && h < 1.0f))
  {
    return 0.0f;
  }
  // (base ramp end, top ramp start) per type: a thin sheet, rolls, a flat base under a rounded
  // top, a tower that holds its width up to the anvil, rounded cloudlets, and a tall tower that
  // narrows over its top third.
  switch (type)
  {
    case CloudType::Stratus:
      return SmoothStep(0.0f, 0.1f, h) * (1.0f - SmoothStep(0.6f, 1.0f, h));
    case CloudType::Stratocumulus:
      return SmoothStep(0.0f, 0.12f, h) * (1.0f - SmoothStep(0.45f, 1.0f, h));
    case CloudType::Cumulus:
      return SmoothStep(0.0f, 0.04f, h) * (1.0f - SmoothStep(0.5f, 1.0f, h));
    case CloudType::Cumulonimbus:
      return SmoothStep(0.0f, 0.03f, h) * (1.0f - SmoothStep(0.96f, 1.0f, h));
    case CloudType::Altocumulus:
      return SmoothStep(0.0f, 0.25f, h) * (1.0f - SmoothStep(0.4f, 1.0f, h));
    case CloudType::Congestus:
      return SmoothStep(0.0f, 0.03f, h) * (1.0f - SmoothStep(0.7f, 1.0f, h));
  }
  return 0.0f;
}

std::string ValidateCloudLayer(const CloudLayer& l)
{
  std::ostringstream error;
  // Each check names its parameter (as the scene's field.cloud keys and the source's setters do)
  // and the value it got.
  const auto require = [&error](bool ok, const char* what, double value, const char* allowed)
  {
    if (!ok && error.str().empty())
    {
      error << "cloud " << what << " must be " << allowed << ", got " << value;
    }
  };
  const auto unit = [](double v) { return v >= 0.0 && v <= 1.0; };
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  require(std::isfinite(l.Base), "base", l.Base, "a finite number");
  require(std::isfinite(l.Top), "top", l.Top, "a finite number");
  if (error.str().empty() && !(l.Base < l.Top && std::isfinite(l.Top - l.Base)))
  {
    error << "the cloud base (" << l.Base << ") must lie below the top (" << l.Top
          << "), by a finite depth";
  }
  require(unit(l.Coverage), "coverage", l.Coverage, "in [0, 1]");
  require(unit(l.Erosion), "erosion", l.Erosion, "in [0, 1]");
  require(unit(l.Curl), "curl", l.Curl, "in [0, 1]");
  require(unit(l.Anvil), "anvil", l.Anvil, "in [0, 1]");
  require(unit(l.Breakup), "breakup", l.Breakup, "in [0, 1]");
  require(unit(l.Rain), "rain", l.Rain, "in [0, 1]");
  require(positive(l.MapScale), "map scale", l.MapScale, "a positive number");
  require(positive(l.ShapeScale), "shape scale", l.ShapeScale, "a positive number");
  require(positive(l.DetailScale), "detail scale", l.DetailScale, "a positive number");
  require(l.MapOctaves >= 1 && l.MapOctaves <= noise::MaxOctaves,
    "map octaves",
    l.MapOctaves,
    "between 1 and 12");
  require(unit(l.MapGain), "map gain", l.MapGain, "in [0, 1]");
  require(std::isfinite(l.Shear[0]), "shear x", l.Shear[0], "a finite number");
  require(std::isfinite(l.Shear[1]), "shear z", l.Shear[1], "a finite number");
  require(std::isfinite(l.AnvilDirection[0]),
    "anvil direction x",
    l.AnvilDirection[0],
    "a finite number");
  require(std::isfinite(l.AnvilDirection[1]),
    "anvil direction z",
    l.AnvilDirection[1],
    "a finite number");
  if (error.str().empty() && l.AnvilDirection[0] == 0.0 && l.AnvilDirection[1] == 0.0)
  {
    error << "cloud anvil direction must not be [0, 0]: it is the direction the anvil streams in";
  }
  require(std::isfinite(l.AnvilReach) && l.AnvilReach >= 0.0,
    "anvil reach",
    l.AnvilReach,
    "a finite number >= 0");
  require(std::isfinite(l.Overshoot) && l.Overshoot >= 0.0,
    "overshoot",
    l.Overshoot,
    "a finite number >= 0");
  const bool tower = l.Type == CloudType::Cumulonimbus && l.Source == CoverageSource::Shapes;
  const char* towerKey = l.Rain > 0.0 ? "rain"
    : l.Overshoot > 0.0               ? "overshoot"
    : l.AnvilReach > 0.0              ? "anvil reach"
                                      : nullptr;
  if (error.str().empty() && !tower && towerKey)
  {
    error << "cloud " << towerKey
          << " needs a tower to stand on: the cumulonimbus type with its coverage from the shapes "
             "(coverage_map \"shapes\")";
  }
  if (!error.str().empty() || l.Source != CoverageSource::Map)
  {
    return error.str();
  }
  if (!l.Map)
  {
    error << "the coverage comes from a map, but no map is set (SetCoverageMap, or a file as "
             "field.cloud.coverage_map)";
  }
  else if (l.Map->Width < 1 || l.Map->Height < 1 ||
    l.Map->Values.size() != static_cast<size_t>(l.Map->Width) * l.Map->Height)
  {
    error << "the coverage map holds " << l.Map->Values.size() << " values for " << l.Map->Width
          << " x " << l.Map->Height << " points";
  }
  else
  {
    const auto outside = std::find_if(l.Map->Values.begin(),
      l.Map->Values.end(),
      [](float v) { return !(v >= 0.0f && v <= 1.0f); });
    if (outside != l.Map->Values.end())
    {
      error << "coverage map value " << *outside << " at point "
            << (outside - l.Map->Values.begin()) << " is outside [0, 1]";
    }
  }
  return error.str();
}

float CoverageMap::Sample(double x, double z) const
{
  const auto place = [](double v, double lo, double hi, int n, int& i, float& t)
  {
    const double u = n > 1 ? std::min(std::max((v - lo) / (hi - lo), 0.0), 1.0) * (n - 1) : 0.0;
    i = std::min(static_cast<int>(u), std::max(n - 2, 0));
    t = static_cast<float>(u - i);
  };
  int i, j;
  float tx, tz;
  place(x, this->XMin, this->XMax, this->Width, i, tx);
  place(z, this->ZMin, this->ZMax, this->Height, j, tz);
  const int i1 = std::min(i + 1, this->Width - 1), j1 = std::min(j + 1, this->Height - 1);
  const float* v = this->Values.data();
  const float a = v[j * this->Width + i] + (v[j * this->Width + i1] - v[j * this->Width + i]) * tx;
  const float b =
    v[j1 * this->Width + i] + (v[j1 * this->Width + i1] - v[j1 * this->Width + i]) * tx;
  return a + (b - a) * tz;
}

std::shared_ptr<const CoverageMap> CoverageMapOfImage(vtkImageData* image, std::string& problem)
{
  int dimensions[3];
  image->GetDimensions(dimensions);
  std::vector<int> axes;
  for (int a = 0; a < 3; ++a)
  {
    if (dimensions[a] > 1)
    {
      axes.push_back(a);
    }
  }
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars && image->GetPointData()->GetNumberOfArrays() > 0)
  {
    scalars = image->GetPointData()->GetArray(0);
  }
  if (axes.size() > 2 || dimensions[0] < 1 || dimensions[1] < 1 || dimensions[2] < 1)
  {
    problem = "a coverage map must be a 2-D image, got " + std::to_string(dimensions[0]) + " x " +
      std::to_string(dimensions[1]) + " x " + std::to_string(dimensions[2]) + " points";
    return nullptr;
  }
  if (!scalars || scalars->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    problem = "the coverage map has no point values";
    return nullptr;
  }
  auto map = std::make_shared<CoverageMap>();
  map->Width = axes.empty() ? 1 : dimensions[axes[0]];
  map->Height = axes.size() < 2 ? 1 : dimensions[axes[1]];
  const int type = scalars->GetDataType();
  const bool integer = type != VTK_FLOAT && type != VTK_DOUBLE;
  const double divisor = integer ? scalars->GetDataTypeMax() : 1.0;
  map->Values.resize(static_cast<size_t>(scalars->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
  {
    const double v = scalars->GetComponent(i, 0) / divisor;
    if (!(v >= 0.0 && v <= 1.0))
    {
      problem = "coverage map value " + std::to_string(scalars->GetComponent(i, 0)) + " at point " +
        std::to_string(i) + " is outside [0, 1]";
      return nullptr;
    }
    map->Values[static_cast<size_t>(i)] = static_cast<float>(v);
  }
  return map;
}

float TiledVolume::Sample(glm::dvec3 u) const
{
  const int n = this->Size;
  int cell[3];
  float t[3];
  for (int a = 0; a < 3; ++a)
  {
    // Texel centres at (i + 0.5) / n of the tile, wrapped.
    const noise::LatticeCoordinate c = noise::Split(u[a] * n - 0.5);
    cell[a] = noise::WrapCell(c.Cell, n);
    t[a] = c.Fraction;
  }
  const int x0 = cell[0], x1 = x0 + 1 == n ? 0 : x0 + 1;
  const int y0 = cell[1], y1 = y0 + 1 == n ? 0 : y0 + 1;
  const int z0 = cell[2], z1 = z0 + 1 == n ? 0 : z0 + 1;
  const float* v = this->Texels.data();
  const auto at = [&](int x, int y, int z) { return v[(static_cast<size_t>(z) * n + y) * n + x]; };
  const auto lerp = [](float a, float b, float s) { return a + (b - a) * s; };
  const float c00 = lerp(at(x0, y0, z0), at(x1, y0, z0), t[0]);
  const float c10 = lerp(at(x0, y1, z0), at(x1, y1, z0), t[0]);
  const float c01 = lerp(at(x0, y0, z1), at(x1, y0, z1), t[0]);
  const float c11 = lerp(at(x0, y1, z1), at(x1, y1, z1), t[0]);
  return lerp(lerp(c00, c10, t[1]), lerp(c01, c11, t[1]), t[2]);
}

namespace
{
// Fills a size^3 volume with f(u) at the texel centres, u in tiles.
template<typename F>
TiledVolume Bake(int size, F f)
{
  TiledVolume volume;
  volume.Size = size;
  volume.Texels.resize(static_cast<size_t>(size) * size * size);
  vtkSMPTools::For(0,
    size * size,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType row = begin; row < end; ++row)
      {
        const int y = static_cast<int>(row % size), z = static_cast<int>(row / size);
        for (int x = 0; x < size; ++x)
        {
          const glm::dvec3 u((x + 0.5) / size, (y + 0.5) / size, (z + 0.5) / size);
          volume.Texels[static_cast<size_t>(row) * size + x] = f(u);
        }
      }
    });
  return volume;
}

// Lattice cells per tile of the baked noises: the shape's Perlin-Worley has 4 (so a tile holds a
// few cloud masses), the detail's Worley fBm 4, 8 and 16, the curl's Perlin potentials 4.
constexpr int ShapeCells = 4, DetailCells = 4, CurlCells = 4;
constexpr int ShapeTexels = 64, DetailTexels = 64, CurlTexels = 32;

CloudNoiseVolumes BakeVolumes(std::uint32_t seed)
{
  using namespace noise;
  CloudNoiseVolumes v;
  v.Shape = Bake(ShapeTexels,
    [seed](glm::dvec3 u)
    {
      const glm::dvec3 p = u * double(ShapeCells);
      // Schneider's base shape: Perlin-Worley dilated by a lower-contrast Worley fBm.
      const float perlinWorley = PerlinWorley(p.x, p.y, p.z, seed, ShapeCells);
      const float worley = InvertedWorleyFbm(p.x, p.y, p.z, seed + 0x5BD1E995u, ShapeCells);
      return Saturate(Remap(perlinWorley, worley - 1.0f, 1.0f, 0.0f, 1.0f));
    });
  v.Detail = Bake(DetailTexels,
    [seed](glm::dvec3 u)
    {
      const glm::dvec3 p = u * double(DetailCells);
      return InvertedWorleyFbm(p.x, p.y, p.z, seed + 0x1B873593u, DetailCells);
    });
  for (int c = 0; c < 3; ++c)
  {
    v.Curl[c] = Bake(CurlTexels,
      [seed, c](glm::dvec3 u)
      {
        const glm::dvec3 p = u * double(CurlCells);
        return CurlNoise(p.x, p.y, p.z, seed + 0xCC9E2D51u, CurlCells)[c];
      });
  }
  return v;
}
}

double CloudLatticeDensity(const CloudLayer& layer)
{
  double density = std::max(double(ShapeTexels) / layer.ShapeScale,
    double(std::max(DetailTexels, CurlTexels)) / layer.DetailScale);
  if (layer.Source == CoverageSource::Noise)
  {
    density = std::max(density, std::ldexp(1.0, layer.MapOctaves - 1) / layer.MapScale);
  }
  return density;
}

std::shared_ptr<const CloudNoiseVolumes> BakeCloudNoise(std::uint32_t seed)
{
  // The last few seeds' volumes, so an animation or a field generated in pieces bakes once. The
  // bake runs outside the lock (it is parallel itself): a second caller of the same seed waits on
  // the first one's future, callers of other seeds go on.
  using Volumes = std::shared_ptr<const CloudNoiseVolumes>;
  static std::mutex mutex;
  static std::map<std::uint32_t, std::shared_future<Volumes>> cache;
  static std::deque<std::uint32_t> order; // oldest first
  std::promise<Volumes> promise;
  std::shared_future<Volumes> baking;
  bool bakesHere = false;
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto found = cache.find(seed);
    if (found != cache.end())
    {
      baking = found->second;
    }
    else
    {
      if (order.size() >= 4)
      {
        cache.erase(order.front());
        order.pop_front();
      }
      baking = promise.get_future().share();
      cache.emplace(seed, baking);
      order.push_back(seed);
      bakesHere = true;
    }
  }
  if (!bakesHere)
  {
    return baking.get();
  }
  try
  {
    auto volumes = std::make_shared<const CloudNoiseVolumes>(BakeVolumes(seed));
    promise.set_value(volumes);
    return volumes;
  }
  catch (...)
  {
    // A failed bake (out of memory) is not cached: waiting callers get the error, later ones
    // try again.
    promise.set_exception(std::current_exception());
    std::lock_guard<std::mutex> lock(mutex);
    cache.erase(seed);
    order.erase(std::remove(order.begin(), order.end(), seed), order.end());
    throw;
  }
}

float WeatherNoise(const CloudLayer& layer, std::uint32_t seed, double x, double z, double height)
{
  const double depth = layer.Top - layer.Base;
  double frequency = 1.0 / layer.MapScale, amplitude = 1.0, variance = 0.0;
  double atHeight = 0.0, atBase = 0.0; // the sums at `height` and at the base
  for (int o = 0; o < layer.MapOctaves; ++o)
  {
    // A slice of 3-D Perlin noise off the lattice's planes (where gradient noise is 0), its own
    // seed per octave, that moves through the lattice with height as fast as across for the
    // octaves at most half the layer's depth wide, not at all for those as wide as the layer is
    // deep or wider, and in between linearly in depth / wavelength.
    const std::uint32_t octaveSeed = seed * 0x9E3779B1u + 0x7F4A7C15u * o;
    const double turning = std::clamp(depth * frequency - 1.0, 0.0, 1.0);
    const double flat = noise::Perlin(x * frequency, 0.5, z * frequency, octaveSeed);
    atBase += amplitude * flat;
    atHeight += amplitude *
      (turning > 0.0 && height != 0.0
          ? noise::Perlin(
              x * frequency, 0.5 + turning * height * frequency, z * frequency, octaveSeed)
          : flat);
    variance += amplitude * amplitude;
    frequency *= 2.0;
    amplitude *= layer.MapGain;
  }
  // The turning octaves only ever remove coverage from the base's: every cloud keeps its flat
  // base.
  const double sum = std::min(atHeight, atBase);
  // Perlin noise is close to normal with a standard deviation of 0.24 (measured over this slice),
  // so the sum is too, with the octaves' variances added. Its normal distribution function makes
  // the map uniform on [0, 1]: a coverage threshold c then leaves about c of the sky under clouds.
  constexpr double perlinDeviation = 0.24;
  const double score = sum / (perlinDeviation * std::sqrt(variance));
  return static_cast<float>(0.5 * (1.0 + std::erf(score / std::sqrt(2.0))));
}

} // namespace cloudvis
