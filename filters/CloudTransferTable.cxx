#include "CloudTransferTable.h"

#include <vtkColorTransferFunction.h>
#include <vtkPiecewiseFunction.h>
#include <vtkScalarsToColors.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cloudvis
{

namespace
{
// Opacity 1 would be an infinite extinction; this keeps sigma_t finite (about 9.2 / u) while
// still letting one unit of travel absorb all but 1e-4 of the light.
constexpr double MaxOpacity = 1.0 - 1e-4;

// Texel-space position of a density, x in [0, size - 1]: where Lookup, MaxExtinction and
// MinExtinction agree on which entries a density touches.
double TablePosition(const TransferTable& table, double density)
{
  const double width = table.Range[1] - table.Range[0];
  if (!(width > 0.0) || std::isnan(density))
  {
    return 0.0;
  }
  const double t = std::min(std::max((density - table.Range[0]) / width, 0.0), 1.0);
  return t * (table.Size - 1);
}

// The entries first .. last that a linear lookup of any density between the two can touch.
void EntriesTouched(
  const TransferTable& table, double densityMin, double densityMax, int& first, int& last)
{
  double x0 = TablePosition(table, densityMin);
  double x1 = TablePosition(table, densityMax);
  if (x1 < x0)
  {
    std::swap(x0, x1);
  }
  first = std::min(static_cast<int>(x0), table.Size - 1);
  // ceil, not floor + 1: a density exactly on an entry gives its neighbour weight 0, and a ramp
  // that starts at density 0 must leave a field of zeros transparent. The GPU computes the
  // position in float and quantises the weights to 8 bits, so where it lands a hair past the
  // entry the neighbour's weight rounds to 0 as well.
  last = std::min(static_cast<int>(std::ceil(x1)), table.Size - 1);
}

bool InUnitInterval(double v)
{
  return v >= 0.0 && v <= 1.0; // false for NaN
}
}

glm::vec4 TransferTable::Lookup(double density) const
{
  if (this->Size < 1 || this->RGBA.size() < std::size_t(this->Size) * 4)
  {
    return glm::vec4(0.0f);
  }
  const double x = TablePosition(*this, density);
  const int i0 = std::min(static_cast<int>(x), this->Size - 1);
  const int i1 = std::min(i0 + 1, this->Size - 1);
  const float f = static_cast<float>(x - i0);
  const float* a = &this->RGBA[std::size_t(i0) * 4];
  const float* b = &this->RGBA[std::size_t(i1) * 4];
  return glm::vec4(a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]),
    a[3] + f * (b[3] - a[3]));
}

float TransferTable::MaxExtinction(double densityMin, double densityMax) const
{
  if (this->Size < 1 || this->RGBA.size() < std::size_t(this->Size) * 4)
  {
    return 0.0f;
  }
  int first, last;
  EntriesTouched(*this, densityMin, densityMax, first, last);
  float sigma_t = 0.0f;
  for (int i = first; i <= last; ++i)
  {
    sigma_t = std::max(sigma_t, this->RGBA[std::size_t(i) * 4 + 3]);
  }
  return sigma_t;
}

float TransferTable::MinExtinction(double densityMin, double densityMax) const
{
  if (this->Size < 1 || this->RGBA.size() < std::size_t(this->Size) * 4)
  {
    return 0.0f;
  }
  int first, last;
  EntriesTouched(*this, densityMin, densityMax, first, last);
  float sigma_t = this->RGBA[std::size_t(first) * 4 + 3];
  for (int i = first + 1; i <= last; ++i)
  {
    sigma_t = std::min(sigma_t, this->RGBA[std::size_t(i) * 4 + 3]);
  }
  return sigma_t;
}

bool TransferTable::operator==(const TransferTable& other) const
{
  return this->Range[0] == other.Range[0] && this->Range[1] == other.Range[1] &&
    this->Size == other.Size && this->RGBA == other.RGBA;
}

void WidenEmptyRange(double range[2])
{
  if (!(range[1] > range[0]))
  {
    range[1] = range[0] + 1.0;
  }
}

double Extinction(double opacity, double unitDistance, double extinctionScale)
{
  const double a = std::min(std::max(opacity, 0.0), MaxOpacity);
  return -std::log1p(-a) / unitDistance * extinctionScale;
}

double MinUnitDistance()
{
  return Extinction(1.0, 1.0) / FloatMax;
}

TransferTable BuildTransferTable(vtkScalarsToColors* color, vtkPiecewiseFunction* opacity,
  double unitDistance, const double range[2], int size, double extinctionScale)
{
  TransferTable table;
  const bool valid = size >= 1 && std::isfinite(unitDistance) && unitDistance > 0.0 &&
    std::isfinite(extinctionScale) && extinctionScale >= 0.0 && std::isfinite(range[0]) &&
    std::isfinite(range[1]) && range[0] <= range[1];
  if (!valid)
  {
    return table;
  }
  table.Range[0] = range[0];
  table.Range[1] = range[1];
  table.Size = size;
  table.RGBA.resize(std::size_t(size) * 4);
  for (int i = 0; i < size; ++i)
  {
    const double density =
      size > 1 ? range[0] + (range[1] - range[0]) * (double(i) / (size - 1)) : range[0];
    double rgb[3] = { 1.0, 1.0, 1.0 };
    if (color)
    {
      color->GetColor(density, rgb);
    }
    const double sigma_t =
      Extinction(opacity ? opacity->GetValue(density) : 0.0, unitDistance, extinctionScale);
    float* entry = &table.RGBA[std::size_t(i) * 4];
    entry[0] = static_cast<float>(rgb[0]);
    entry[1] = static_cast<float>(rgb[1]);
    entry[2] = static_cast<float>(rgb[2]);
    entry[3] = static_cast<float>(sigma_t);
  }
  return table;
}

bool TransferFunctionRange(vtkPiecewiseFunction* opacity,
  vtkScalarsToColors* color,
  double range[2])
{
  if (!opacity || opacity->GetSize() == 0)
  {
    return false;
  }
  double node[4];
  opacity->GetNodeValue(0, node);
  range[0] = range[1] = node[0];
  const auto include = [range](double density)
  {
    range[0] = std::min(range[0], density);
    range[1] = std::max(range[1], density);
  };
  opacity->GetNodeValue(opacity->GetSize() - 1, node);
  include(node[0]);
  // A vtkColorTransferFunction's range is that of its points; any other vtkScalarsToColors
  // gives its own.
  if (color)
  {
    include(color->GetRange()[0]);
    include(color->GetRange()[1]);
  }
  WidenEmptyRange(range);
  return true;
}

TransferTable TabulateTransferFunction(vtkScalarsToColors* color,
  vtkPiecewiseFunction* opacity,
  double unitDistance,
  int size,
  double extinctionScale)
{
  double range[2];
  if (!TransferFunctionRange(opacity, color, range))
  {
    return TransferTable();
  }
  return BuildTransferTable(color, opacity, unitDistance, range, size, extinctionScale);
}

std::string ValidateTransferFunction(vtkPiecewiseFunction* opacity, vtkScalarsToColors* color)
{
  std::ostringstream problem;
  if (!opacity)
  {
    return "no opacity transfer function";
  }
  const int points = opacity->GetSize();
  if (points == 0)
  {
    return "the opacity transfer function has no points";
  }
  double previous = 0.0;
  for (int i = 0; i < points; ++i)
  {
    double node[4]; // x, opacity, midpoint, sharpness
    opacity->GetNodeValue(i, node);
    if (std::isnan(node[0]) || std::isnan(node[1]))
    {
      problem << "opacity point " << i << " is not a number";
      return problem.str();
    }
    if (i > 0 && node[0] < previous)
    {
      problem << "opacity point " << i << " lies at density " << node[0]
              << ", before the previous point at " << previous
              << ": densities must not decrease";
      return problem.str();
    }
    previous = node[0];
    if (!InUnitInterval(node[1]))
    {
      problem << "opacity " << node[1] << " at density " << node[0] << " is outside [0, 1]";
      return problem.str();
    }
    if (!InUnitInterval(node[2]) || !InUnitInterval(node[3]))
    {
      problem << "opacity point " << i << " has midpoint " << node[2] << " and sharpness "
              << node[3] << ": both must lie in [0, 1]";
      return problem.str();
    }
  }
  if (!color)
  {
    return "";
  }

  // Sample the color where a renderer will read it: across its own range and at every opacity
  // point (where the visible part of the volume is).
  std::vector<double> densities;
  const double* colorRange = color->GetRange();
  constexpr int Samples = 257;
  for (int i = 0; i < Samples; ++i)
  {
    densities.push_back(colorRange[0] + (colorRange[1] - colorRange[0]) * i / (Samples - 1));
  }
  for (int i = 0; i < points; ++i)
  {
    double node[4];
    opacity->GetNodeValue(i, node);
    densities.push_back(node[0]);
  }
  for (double density : densities)
  {
    double rgb[3];
    color->GetColor(density, rgb);
    if (!InUnitInterval(rgb[0]) || !InUnitInterval(rgb[1]) || !InUnitInterval(rgb[2]))
    {
      problem << "the color at density " << density << " is (" << rgb[0] << ", " << rgb[1] << ", "
              << rgb[2] << "): each component must be a number in [0, 1]";
      return problem.str();
    }
  }
  return "";
}

TransferTable TransferTableOf(vtkVolumeProperty* property,
  double extinctionScale,
  std::string& problem)
{
  problem.clear();
  if (!property)
  {
    problem = "transfer function: no volume property";
    return TransferTable();
  }
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  vtkColorTransferFunction* color = property->GetRGBTransferFunction(0);
  const std::string invalid = ValidateTransferFunction(opacity, color);
  if (!invalid.empty())
  {
    problem = "transfer function: " + invalid;
    return TransferTable();
  }
  TransferTable table = TabulateTransferFunction(
    color, opacity, property->GetScalarOpacityUnitDistance(0), TransferTableSize, extinctionScale);
  if (table.Size < 1)
  {
    problem = "transfer function: the unit distance must be a positive finite number";
  }
  return table;
}

} // namespace cloudvis
