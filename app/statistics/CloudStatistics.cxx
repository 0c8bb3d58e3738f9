// Cloud statistics of a field (CloudStatistics.h): one pass over the voxels fills the per-level
// and per-column sums, the projected mask is then labelled into clouds, and the two fits run on
// the clouds. Sums are accumulated in double.
#include "CloudStatistics.h"

#include "CloudMarchUniforms.h" // GeometryOf

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace cloudvis
{

namespace
{
// "1 cloud", "3 clouds".
std::string Clouds(std::size_t n)
{
  return std::to_string(n) + (n == 1 ? " cloud" : " clouds");
}
} // namespace

std::vector<Cloud> CloudsOfMask(const std::vector<std::uint8_t>& mask, int width, int height)
{
  std::vector<Cloud> clouds;
  std::vector<std::uint8_t> visited(mask.size(), 0);
  std::vector<std::int64_t> stack;
  const auto cloudy = [&](int x, int y) { return mask[std::size_t(y) * width + x] != 0; };
  for (std::int64_t start = 0; start < std::int64_t(mask.size()); ++start)
  {
    if (!mask[std::size_t(start)] || visited[std::size_t(start)])
    {
      continue;
    }
    Cloud cloud;
    visited[std::size_t(start)] = 1;
    stack.push_back(start);
    while (!stack.empty())
    {
      const std::int64_t p = stack.back();
      stack.pop_back();
      const int x = int(p % width), y = int(p / width);
      ++cloud.Area;
      const int neighbours[4][2] = { { x - 1, y }, { x + 1, y }, { x, y - 1 }, { x, y + 1 } };
      for (const auto& n : neighbours)
      {
        if (n[0] < 0 || n[0] >= width || n[1] < 0 || n[1] >= height)
        {
          cloud.TouchesEdge = true; // the edge on the border is not counted
        }
        else if (!cloudy(n[0], n[1]))
        {
          ++cloud.Perimeter;
        }
        else
        {
          const std::int64_t q = std::int64_t(n[1]) * width + n[0];
          if (!visited[std::size_t(q)])
          {
            visited[std::size_t(q)] = 1;
            stack.push_back(q);
          }
        }
      }
    }
    clouds.push_back(cloud);
  }
  return clouds;
}

PowerLawFit FitAreaPerimeter(const std::vector<Cloud>& clouds)
{
  PowerLawFit fit;
  std::vector<double> x, y;
  for (const Cloud& c : clouds)
  {
    if (!c.TouchesEdge && c.Area >= MinimumFitArea)
    {
      x.push_back(std::log(double(c.Area)));
      y.push_back(std::log(double(c.Perimeter)));
    }
  }
  fit.Count = x.size();
  if (x.size() < MinimumFitClouds)
  {
    fit.Problem = Clouds(x.size()) + " of at least " + std::to_string(MinimumFitArea) +
      " pixels inside the border, fewer than the " + std::to_string(MinimumFitClouds) +
      " a fit needs";
    return fit;
  }
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  fit.RangeMin = std::exp(*lo);
  fit.RangeMax = std::exp(*hi);
  if (*hi - *lo < std::log(10.0))
  {
    fit.Problem = "the clouds' areas span less than a factor of 10";
    return fit;
  }
  const double n = double(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  const double slope = sxy / sxx;
  double residuals = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    const double r = y[i] - (my + slope * (x[i] - mx));
    residuals += r * r;
  }
  fit.Fitted = true;
  fit.Value = 2.0 * slope; // log P = (D / 2) log A + c
  fit.StandardError = 2.0 * std::sqrt(residuals / std::max(n - 2.0, 1.0) / sxx);
  return fit;
}

PowerLawFit FitPowerLaw(const std::vector<double>& unsorted)
{
  PowerLawFit fit;
  std::vector<double> s = unsorted;
  std::sort(s.begin(), s.end());
  const std::size_t n = s.size();
  if (n < MinimumFitClouds)
  {
    fit.Count = n;
    fit.Problem = Clouds(n) + " of at least " + std::to_string(MinimumFitArea) +
      " pixels, fewer than the " + std::to_string(MinimumFitClouds) + " a fit needs";
    return fit;
  }
  // Candidate lower bounds: the distinct sizes with enough clouds at or above them, at most
  // about 200 of them evenly spread (the search is quadratic).
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i + MinimumFitClouds <= n; ++i)
  {
    if (i == 0 || s[i] != s[i - 1])
    {
      candidates.push_back(i);
    }
  }
  const std::size_t stride = std::max<std::size_t>(1, candidates.size() / 200);
  double bestDistance = std::numeric_limits<double>::max();
  for (std::size_t c = 0; c < candidates.size(); c += stride)
  {
    const std::size_t first = candidates[c];
    const double sMin = s[first];
    const double m = double(n - first);
    double logSum = 0.0;
    for (std::size_t i = first; i < n; ++i)
    {
      logSum += std::log(s[i] / sMin);
    }
    if (!(logSum > 0.0))
    {
      continue; // all equal: no law to fit
    }
    const double b = 1.0 + m / logSum;
    // Kolmogorov-Smirnov distance between the tail's empirical CDF and the fitted one.
    double distance = 0.0;
    for (std::size_t i = first; i < n; ++i)
    {
      const double model = 1.0 - std::pow(s[i] / sMin, 1.0 - b);
      const double below = double(i - first) / m, at = double(i - first + 1) / m;
      distance = std::max({ distance, std::abs(model - below), std::abs(model - at) });
    }
    if (distance < bestDistance)
    {
      bestDistance = distance;
      fit.Fitted = true;
      fit.Value = b;
      fit.StandardError = (b - 1.0) / std::sqrt(m);
      fit.RangeMin = sMin;
      fit.RangeMax = s.back();
      fit.Count = n - first;
      fit.Distance = distance;
      fit.Consistent = distance < 1.36 / std::sqrt(m);
    }
  }
  if (!fit.Fitted)
  {
    fit.Count = n;
    fit.Problem = "the clouds all have the same size";
  }
  return fit;
}

namespace
{

// The values as floats: the array itself when it is one, else a copy of component 0.
struct FloatValues
{
  std::vector<float> Copy;
  const float* Data = nullptr;
};

FloatValues ValuesOf(vtkDataArray* array)
{
  FloatValues values;
  if (auto* floats = vtkFloatArray::SafeDownCast(array))
  {
    if (floats->GetNumberOfComponents() == 1)
    {
      values.Data = floats->GetPointer(0);
      return values;
    }
  }
  values.Copy.resize(std::size_t(array->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    values.Copy[std::size_t(i)] = float(array->GetComponent(i, 0));
  }
  values.Data = values.Copy.data();
  return values;
}

// Log-spaced bins over the sizes, four per decade, on round edges (10^(k/4)).
void SizeHistogram(const std::vector<double>& sizes, CloudStatistics& s)
{
  if (sizes.empty())
  {
    return;
  }
  const auto [lo, hi] = std::minmax_element(sizes.begin(), sizes.end());
  const int first = int(std::floor(std::log10(*lo) * 4.0 + 1e-9));
  const int last = int(std::floor(std::log10(*hi) * 4.0 + 1e-9)) + 1;
  for (int k = first; k <= last; ++k)
  {
    s.SizeBinEdges.push_back(std::pow(10.0, k / 4.0));
  }
  s.SizeCounts.assign(s.SizeBinEdges.size() - 1, 0);
  for (const double size : sizes)
  {
    const int bin = int(std::floor(std::log10(size) * 4.0 + 1e-9)) - first;
    ++s.SizeCounts[std::size_t(std::clamp(bin, 0, int(s.SizeCounts.size()) - 1))];
  }
}

// The vertical integral in PathUnit's unit: metres when the length unit is known.
double PathScale(const ResolvedFieldUnits& u)
{
  return u.Length == LengthUnit::None ? 1.0 : MetresPerUnit(u.Length);
}

// The lattice's vertical: the index axis whose world direction is the field's up, and the world
// heights of its levels from the lowest. Any lattice whose axes are world axes, reversed or
// permuted by its direction matrix, has one; a tilted lattice has no vertical columns.
struct VerticalAxis
{
  int Index = 2;                // the index axis along up
  int Horizontal[2] = { 0, 1 }; // the other two, in order
  double Lowest = 0.0;          // world height of the lowest level
  double Step = 1.0;            // world units between levels (positive)
  bool Downward = false;        // index 0 is the highest level
  double PixelSize = 1.0;       // sqrt of a column's world area
  std::string Problem;
};

VerticalAxis VerticalAxisOf(vtkImageData* field, int up)
{
  VerticalAxis v;
  const VolumeGeometry geometry = GeometryOf(field, nullptr);
  const glm::dmat4& m = geometry.IndexToWorld;
  for (int i = 0; i < 3; ++i)
  {
    if (std::abs(m[i][up]) > std::abs(m[v.Index][up]))
    {
      v.Index = i;
    }
  }
  for (int i = 0; i < 3; ++i)
  {
    const glm::dvec3 axis(m[i]);
    const double along = std::abs(axis[up]);
    const double across =
      i == v.Index ? std::sqrt(std::max(0.0, glm::dot(axis, axis) - along * along)) : along;
    if (!(across <= 1e-6 * glm::length(axis)))
    {
      v.Problem = "the lattice is tilted against up (" + AxisName(up) +
        ") by its direction matrix, so it has no vertical columns; the cloud statistics need "
        "one lattice axis along up";
      return v;
    }
  }
  v.Horizontal[0] = v.Index == 0 ? 1 : 0;
  v.Horizontal[1] = v.Index == 2 ? 1 : 2;
  const double step = m[v.Index][up];
  const int levels = geometry.Dimensions[v.Index];
  v.Step = std::abs(step);
  v.Downward = step < 0.0;
  v.Lowest = m[3][up] + (v.Downward ? step * (levels - 1) : 0.0);
  // Each square root first: a pixel of 1e200 x 1e200 has a size, though not an area, in double.
  v.PixelSize = std::sqrt(glm::length(glm::dvec3(m[v.Horizontal[0]]))) *
    std::sqrt(glm::length(glm::dvec3(m[v.Horizontal[1]])));
  const double top = v.Lowest + v.Step * (levels - 1);
  // The whole mask's area, the largest any cloud can have.
  const double area = v.PixelSize * v.PixelSize * double(geometry.Dimensions[v.Horizontal[0]]) *
    double(geometry.Dimensions[v.Horizontal[1]]);
  if (!std::isfinite(top) || !std::isfinite(area) ||
    !(v.PixelSize * v.PixelSize >= std::numeric_limits<double>::min()))
  {
    std::ostringstream problem;
    problem << std::setprecision(6) << "the lattice's voxels (" << v.Step
            << " world units along up, " << v.PixelSize
            << " across) give heights or areas beyond the range of a double, so no statistics in "
               "world units can be given";
    v.Problem = problem.str();
  }
  return v;
}

} // namespace

std::string PathUnit(const ResolvedFieldUnits& u)
{
  if (u.Quantity == FieldQuantity::Lwc)
  {
    return u.Length == LengthUnit::None ? "g/m^3 x world units" : "g/m^2";
  }
  return u.Length == LengthUnit::None ? "density x world units"
                                      : "density x " + LengthUnitName(LengthUnit::Metre);
}

CloudStatistics ComputeCloudStatistics(vtkImageData* field,
  const ResolvedFieldUnits& units,
  double threshold)
{
  CloudStatistics s;
  s.Units = units;
  s.Threshold = std::isnan(threshold) ? DefaultCloudThreshold(units.Quantity) : threshold;
  int dims[3];
  field->GetDimensions(dims);
  vtkDataArray* array = field->GetPointData()->GetScalars();
  const std::int64_t voxels = std::int64_t(dims[0]) * dims[1] * dims[2];
  if (!array || array->GetNumberOfTuples() != voxels || voxels == 0)
  {
    return s;
  }
  const VerticalAxis vertical = VerticalAxisOf(field, std::clamp(units.Up, 0, 2));
  if (!vertical.Problem.empty())
  {
    s.Problem = vertical.Problem;
    return s;
  }
  const FloatValues values = ValuesOf(array);
  const int up = vertical.Index, a = vertical.Horizontal[0], b = vertical.Horizontal[1];
  const int width = dims[a], height = dims[b], levels = dims[up];
  s.Columns = std::uint64_t(width) * std::uint64_t(height);
  std::vector<double> path(s.Columns, 0.0);
  std::vector<std::uint8_t> mask(s.Columns, 0);
  std::vector<std::uint64_t> cloudyPerLevel(std::size_t(levels), 0); // from the lowest
  std::int64_t v = 0;
  int ijk[3];
  for (ijk[2] = 0; ijk[2] < dims[2]; ++ijk[2])
  {
    for (ijk[1] = 0; ijk[1] < dims[1]; ++ijk[1])
    {
      for (ijk[0] = 0; ijk[0] < dims[0]; ++ijk[0], ++v)
      {
        const float value = values.Data[v];
        const std::size_t column = std::size_t(ijk[a]) + std::size_t(width) * std::size_t(ijk[b]);
        path[column] += value;
        if (value > s.Threshold)
        {
          mask[column] = 1;
          ++cloudyPerLevel[std::size_t(vertical.Downward ? levels - 1 - ijk[up] : ijk[up])];
        }
      }
    }
  }
  const double levelVoxels = double(s.Columns);
  for (int k = 0; k < levels; ++k)
  {
    const double h = vertical.Lowest + vertical.Step * k;
    s.LevelHeights.push_back(h);
    s.CloudFractionPerLevel.push_back(double(cloudyPerLevel[std::size_t(k)]) / levelVoxels);
    if (cloudyPerLevel[std::size_t(k)] > 0)
    {
      s.CloudBase = s.HasCloud ? s.CloudBase : h;
      s.CloudTop = h;
      s.HasCloud = true;
    }
  }
  // Each voxel stands for a cell of its spacing along up: a slab of n cloudy voxels of value c
  // integrates to n c dz.
  const double pathScale = vertical.Step * PathScale(units);
  double sum = 0.0, cloudySum = 0.0;
  for (std::size_t c = 0; c < s.Columns; ++c)
  {
    sum += path[c];
    if (mask[c])
    {
      ++s.CloudyColumns;
      cloudySum += path[c];
    }
  }
  s.ProjectedCloudFraction = double(s.CloudyColumns) / double(s.Columns);
  s.MeanPath = sum * pathScale / double(s.Columns);
  s.MeanCloudyPath = s.CloudyColumns ? cloudySum * pathScale / double(s.CloudyColumns) : 0.0;
  if (!std::isfinite(s.MeanPath))
  {
    CloudStatistics refused;
    refused.Units = s.Units;
    refused.Threshold = s.Threshold;
    refused.Problem = "the vertical integral of the values exceeds the range of a double";
    return refused;
  }

  const std::vector<Cloud> clouds = CloudsOfMask(mask, width, height);
  s.Clouds = clouds.size();
  s.PixelSize = vertical.PixelSize;
  std::vector<double> sizes, fitSizes;
  for (const Cloud& cloud : clouds)
  {
    s.CloudsTouchingEdge += cloud.TouchesEdge ? 1 : 0;
    const double size = std::sqrt(double(cloud.Area)) * s.PixelSize;
    sizes.push_back(size);
    if (cloud.Area >= MinimumFitArea)
    {
      fitSizes.push_back(size);
    }
  }
  SizeHistogram(sizes, s);
  s.SizeDistribution = FitPowerLaw(fitSizes);
  s.FractalDimension = FitAreaPerimeter(clouds);
  // The dimension's fit range as areas in world units, like the sizes.
  s.FractalDimension.RangeMin *= s.PixelSize * s.PixelSize;
  s.FractalDimension.RangeMax *= s.PixelSize * s.PixelSize;
  return s;
}

namespace
{

// "500 (500 m)" or "0.5 (500 m)" or "12" without units: a height in world units and metres.
std::string Length(double worldUnits, const ResolvedFieldUnits& u)
{
  std::ostringstream text;
  text << std::setprecision(6) << worldUnits;
  if (u.Length != LengthUnit::None)
  {
    text << " (" << worldUnits * MetresPerUnit(u.Length) << " m)";
  }
  return text.str();
}

void PrintFit(std::ostream& out,
  const char* label,
  const PowerLawFit& fit,
  const char* what,
  const char* range)
{
  out << std::left << std::setw(13) << label << std::right;
  if (!fit.Fitted)
  {
    out << "no fit: " << fit.Problem << "\n";
    return;
  }
  out << what << " " << std::setprecision(4) << fit.Value << " +/- " << fit.StandardError
      << " over " << fit.Count << " clouds, " << range << " [" << fit.RangeMin << ", "
      << fit.RangeMax << "]";
  if (fit.Distance > 0.0)
  {
    out << ", KS distance " << std::setprecision(3) << fit.Distance
        << (fit.Consistent ? " (consistent with the law)" : " (NOT consistent with the law)");
  }
  out << "\n";
}

std::string From(const std::string& from)
{
  return from == "default" ? "" : " (" + from + ")";
}

} // namespace

void PrintCloudStatistics(std::ostream& out, const CloudStatistics& s)
{
  const ResolvedFieldUnits& u = s.Units;
  out << std::setprecision(6);
  out << "quantity     " << QuantityName(u.Quantity)
      << (u.Quantity == FieldQuantity::Lwc ? " (liquid water content, g/m^3)" : "")
      << From(u.QuantityFrom) << "\n";
  out << "length unit  " << LengthUnitName(u.Length) << From(u.LengthFrom) << "\n";
  out << "up           " << AxisName(u.Up) << From(u.UpFrom) << "\n";
  if (u.Quantity == FieldQuantity::Lwc && u.DropletNumber > 0.0)
  {
    const double radius = EffectiveRadiusOfDroplets(1.0, u.DropletNumber);
    out << "droplets     " << u.DropletNumber << " per cm^3" << From(u.DropletNumberFrom)
        << ": r_e = (3 LWC / (4 pi rho_w k N))^(1/3), " << radius << " um at 1 g/m^3; extinction "
        << DropletExtinctionPerMetre(1.0, radius) << " /m at 1 g/m^3, as LWC^(2/3)\n";
    if (u.CloudMeanLwc > 0.0)
    {
      out << "             r_e " << u.EffectiveRadius << " um at the cloud's mean "
          << u.CloudMeanLwc << " g/m^3 (the droplets' phase's)\n";
    }
  }
  else if (u.Quantity == FieldQuantity::Lwc)
  {
    out << "droplets     effective radius " << u.EffectiveRadius << " um"
        << From(u.EffectiveRadiusFrom) << ": extinction "
        << DropletExtinctionPerMetre(1.0, u.EffectiveRadius) << " /m per g/m^3\n";
  }
  const FieldUnits& o = u.Overridden;
  if (o.Quantity || o.Length || o.Up || o.EffectiveRadius || o.DropletNumber)
  {
    out << "file says    ";
    if (o.Quantity)
      out << "quantity " << QuantityName(*o.Quantity) << " ";
    if (o.Length)
      out << "length unit " << LengthUnitName(*o.Length) << " ";
    if (o.Up)
      out << "up " << AxisName(*o.Up) << " ";
    if (o.EffectiveRadius)
      out << "effective radius " << *o.EffectiveRadius << " um ";
    if (o.DropletNumber)
      out << "droplet number " << *o.DropletNumber << " per cm^3 ";
    out << "(the scene's keys win)\n";
  }
  if (!s.Problem.empty())
  {
    out << "clouds       no statistics: " << s.Problem << "\n";
    return;
  }
  const std::string unit = QuantityUnit(u.Quantity);
  out << "cloud mask   value > " << s.Threshold << (unit.empty() ? "" : " " + unit) << "\n";
  out << "cloud cover  " << 100.0 * s.ProjectedCloudFraction << "% projected along "
      << AxisName(u.Up) << " (" << s.CloudyColumns << " of " << s.Columns << " columns)\n";
  if (!s.HasCloud)
  {
    out << "cloud levels none\n";
  }
  else
  {
    out << "cloud base   " << Length(s.CloudBase, u) << "\n";
    out << "cloud top    " << Length(s.CloudTop, u) << "\n";
    // A compact profile: at most 12 of the levels between base and top.
    std::vector<std::size_t> cloudy;
    for (std::size_t k = 0; k < s.LevelHeights.size(); ++k)
    {
      if (s.LevelHeights[k] >= s.CloudBase && s.LevelHeights[k] <= s.CloudTop)
      {
        cloudy.push_back(k);
      }
    }
    const std::size_t stride = (cloudy.size() + 11) / 12;
    out << "cloud fraction per level (" << cloudy.size() << " levels from base to top"
        << (stride > 1 ? ", one in " + std::to_string(stride) + " shown" : std::string()) << ")\n";
    for (std::size_t i = 0; i < cloudy.size(); i += stride)
    {
      const std::size_t k = cloudy[i];
      out << "  " << std::left << std::setw(24) << Length(s.LevelHeights[k], u) << std::right
          << std::setw(10) << 100.0 * s.CloudFractionPerLevel[k] << "%\n";
    }
  }
  const std::string pathName = u.Quantity == FieldQuantity::Lwc ? "LWP          " : "column path  ";
  out << pathName << "mean " << s.MeanPath << ", over cloudy columns " << s.MeanCloudyPath << " "
      << PathUnit(u) << "\n";
  out << "clouds       " << s.Clouds << " in the projected mask (4-connected), "
      << s.CloudsTouchingEdge << " touching its border\n";
  PrintFit(out, "size law", s.SizeDistribution, "n(s) ~ s^-b, b =", "sizes sqrt(area)");
  PrintFit(out, "fractal dim", s.FractalDimension, "area-perimeter D =", "areas");
}

nlohmann::json UnitsToJson(const ResolvedFieldUnits& u)
{
  nlohmann::json json = {
    { "quantity", QuantityName(u.Quantity) },
    { "value_unit", QuantityUnit(u.Quantity) },
    { "length_unit", LengthUnitName(u.Length) },
    { "up", AxisName(u.Up) },
    { "effective_radius", u.EffectiveRadius },
    { "droplet_number", u.DropletNumber },
    { "cloud_mean_lwc", u.CloudMeanLwc },
    { "from",
      { { "quantity", u.QuantityFrom },
        { "length_unit", u.LengthFrom },
        { "up", u.UpFrom },
        { "effective_radius", u.EffectiveRadiusFrom },
        { "droplet_number", u.DropletNumberFrom } } },
  };
  nlohmann::json file = nlohmann::json::object();
  const FieldUnits& o = u.Overridden;
  if (o.Quantity)
    file["quantity"] = QuantityName(*o.Quantity);
  if (o.Length)
    file["length_unit"] = LengthUnitName(*o.Length);
  if (o.Up)
    file["up"] = AxisName(*o.Up);
  if (o.EffectiveRadius)
    file["effective_radius"] = *o.EffectiveRadius;
  if (o.DropletNumber)
    file["droplet_number"] = *o.DropletNumber;
  json["overridden_file_values"] = file;
  return json;
}

namespace
{

nlohmann::json FitToJson(const PowerLawFit& fit, const char* value)
{
  if (!fit.Fitted)
  {
    return { { "fitted", false }, { "problem", fit.Problem }, { "count", fit.Count } };
  }
  nlohmann::json json = { { "fitted", true },
    { value, fit.Value },
    { "standard_error", fit.StandardError },
    { "range", { fit.RangeMin, fit.RangeMax } },
    { "count", fit.Count } };
  if (fit.Distance > 0.0)
  {
    json["ks_distance"] = fit.Distance;
    json["consistent"] = fit.Consistent;
  }
  return json;
}

} // namespace

nlohmann::json CloudStatisticsToJson(const CloudStatistics& s)
{
  if (!s.Problem.empty())
  {
    return { { "threshold", s.Threshold }, { "problem", s.Problem } };
  }
  nlohmann::json json = {
    { "threshold", s.Threshold },
    { "connectivity", s.Connectivity },
    { "columns", s.Columns },
    { "cloudy_columns", s.CloudyColumns },
    { "projected_cloud_fraction", s.ProjectedCloudFraction },
    { "level_heights", s.LevelHeights },
    { "cloud_fraction_per_level", s.CloudFractionPerLevel },
    { "cloud_base", s.HasCloud ? nlohmann::json(s.CloudBase) : nlohmann::json() },
    { "cloud_top", s.HasCloud ? nlohmann::json(s.CloudTop) : nlohmann::json() },
    { "path_unit", PathUnit(s.Units) },
    { "mean_path", s.MeanPath },
    { "mean_cloudy_path", s.MeanCloudyPath },
    { "clouds", s.Clouds },
    { "clouds_touching_edge", s.CloudsTouchingEdge },
    { "size_histogram", { { "edges", s.SizeBinEdges }, { "counts", s.SizeCounts } } },
    { "size_distribution", FitToJson(s.SizeDistribution, "exponent") },
    { "fractal_dimension", FitToJson(s.FractalDimension, "dimension") },
  };
  if (s.HasCloud && s.Units.Length != LengthUnit::None)
  {
    json["cloud_base_m"] = s.CloudBase * MetresPerUnit(s.Units.Length);
    json["cloud_top_m"] = s.CloudTop * MetresPerUnit(s.Units.Length);
  }
  return json;
}

} // namespace cloudvis
