// One pass over the voxels for range, mean and occupancy, a second for the histogram (its bins
// need the range). Sums are accumulated in double so the mean of a large field stays accurate.
#include "FieldStatistics.h"

#include "CloudMarchUniforms.h" // GeometryOf
#include "Utf8.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkPointData.h>

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace cloudvis
{

FieldStatistics ComputeFieldStatistics(vtkImageData* field, int bins)
{
  FieldStatistics s;
  field->GetDimensions(s.Dimensions.data());
  field->GetSpacing(s.Spacing.data());
  field->GetOrigin(s.Origin.data());
  for (int i = 0; i < 9; ++i)
  {
    s.Direction[std::size_t(i)] = field->GetDirectionMatrix()->GetData()[i];
  }
  // Where the renderers put the voxels: the first voxel of the extent (origin, direction and
  // spacing applied), and the world box around the (possibly rotated) lattice.
  const VolumeGeometry geometry = GeometryOf(field, nullptr);
  const glm::dvec3 first(geometry.IndexToWorld[3]);
  s.Origin = { { first.x, first.y, first.z } };
  for (int a = 0; a < 3; ++a)
  {
    s.Bounds[2 * a] = s.Bounds[2 * a + 1] = first[a];
  }
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 index((corner & 1) ? s.Dimensions[0] - 1 : 0,
      (corner & 2) ? s.Dimensions[1] - 1 : 0,
      (corner & 4) ? s.Dimensions[2] - 1 : 0);
    const glm::dvec3 world(geometry.IndexToWorld * glm::dvec4(index, 1.0));
    for (int a = 0; a < 3; ++a)
    {
      s.Bounds[2 * a] = std::min(s.Bounds[2 * a], world[a]);
      s.Bounds[2 * a + 1] = std::max(s.Bounds[2 * a + 1], world[a]);
    }
  }
  s.Histogram.assign(static_cast<size_t>(std::max(bins, 1)), 0);
  vtkDataArray* values = field->GetPointData()->GetScalars();
  const vtkIdType n = values ? values->GetNumberOfTuples() : 0;
  s.Voxels = static_cast<std::uint64_t>(n);
  if (n == 0)
  {
    return s;
  }
  double sum = 0.0;
  s.Minimum = s.Maximum = values->GetComponent(0, 0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double v = values->GetComponent(i, 0);
    s.Minimum = std::min(s.Minimum, v);
    s.Maximum = std::max(s.Maximum, v);
    sum += v;
    s.NonEmptyVoxels += v > 0.0 ? 1 : 0;
  }
  s.Mean = sum / double(n);
  s.NonEmptyFraction = double(s.NonEmptyVoxels) / double(n);
  const double width = (s.Maximum - s.Minimum) / double(s.Histogram.size());
  const size_t last = s.Histogram.size() - 1;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double v = values->GetComponent(i, 0);
    const size_t bin = width > 0.0 ? static_cast<size_t>((v - s.Minimum) / width) : 0;
    ++s.Histogram[std::min(bin, last)];
  }
  return s;
}

namespace
{

// The lower edge of histogram bin `bin` (bin == bins gives the upper edge of the last one).
double HistogramEdge(const FieldStatistics& s, size_t bin)
{
  return s.Minimum + (s.Maximum - s.Minimum) * double(bin) / double(s.Histogram.size());
}

bool IsIdentity(const std::array<double, 9>& direction)
{
  for (std::size_t i = 0; i < 9; ++i)
  {
    if (direction[i] != (i % 4 == 0 ? 1.0 : 0.0))
    {
      return false;
    }
  }
  return true;
}

// A report label as a JSON key: "time step" -> "time_step".
std::string JsonKey(std::string label)
{
  std::replace(label.begin(), label.end(), ' ', '_');
  return label;
}

} // namespace

void PrintFieldStatistics(std::ostream& out,
  const FieldStatistics& s,
  const std::string& name,
  const FieldReport* source)
{
  const auto triple = [](const auto& v, const char* separator)
  {
    std::ostringstream text;
    text << v[0] << separator << v[1] << separator << v[2];
    return text.str();
  };
  out << std::setprecision(6);
  out << "field        " << name << "\n";
  if (source)
  {
    out << "format       " << source->Format << "\n";
    for (const auto& detail : source->Details)
    {
      out << std::left << std::setw(12) << detail.first << std::right << " " << detail.second
          << "\n";
    }
  }
  out << "dimensions   " << triple(s.Dimensions, " x ") << " (" << s.Voxels << " voxels)\n";
  out << "spacing      " << triple(s.Spacing, " ") << "\n";
  out << "origin       " << triple(s.Origin, " ") << " (the first voxel)\n";
  if (IsIdentity(s.Direction))
  {
    out << "direction    identity (the lattice's axes are x, y, z)\n";
  }
  else
  {
    const auto& d = s.Direction;
    out << "direction    axes i (" << d[0] << " " << d[3] << " " << d[6] << "), j (" << d[1] << " "
        << d[4] << " " << d[7] << "), k (" << d[2] << " " << d[5] << " " << d[8] << ")\n";
  }
  out << "bounds       [" << s.Bounds[0] << ", " << s.Bounds[1] << "] x [" << s.Bounds[2] << ", "
      << s.Bounds[3] << "] x [" << s.Bounds[4] << ", " << s.Bounds[5] << "]\n";
  out << "range        [" << s.Minimum << ", " << s.Maximum << "]\n";
  out << "mean         " << s.Mean << "\n";
  out << "non-empty    " << s.NonEmptyVoxels << " voxels, " << 100.0 * s.NonEmptyFraction
      << "% (density > 0)\n";
  out << "histogram    " << s.Histogram.size() << " bins over [" << s.Minimum << ", " << s.Maximum
      << "]\n";
  const std::uint64_t largest = *std::max_element(s.Histogram.begin(), s.Histogram.end());
  constexpr int barWidth = 40;
  for (size_t b = 0; b < s.Histogram.size(); ++b)
  {
    std::ostringstream range;
    range << std::setprecision(4) << "[" << HistogramEdge(s, b) << ", " << HistogramEdge(s, b + 1)
          << (b + 1 == s.Histogram.size() ? "]" : ")");
    // A bar of at least one mark for any non-empty bin, so rare values stay visible.
    const int bar = largest == 0 || s.Histogram[b] == 0
      ? 0
      : std::max(1, static_cast<int>(barWidth * double(s.Histogram[b]) / double(largest) + 0.5));
    out << "  " << std::left << std::setw(22) << range.str() << std::right << std::setw(12)
        << s.Histogram[b] << " " << std::string(static_cast<size_t>(bar), '#') << "\n";
  }
}

nlohmann::json FieldStatisticsToJson(const FieldStatistics& s,
  const std::string& name,
  const FieldReport* source)
{
  nlohmann::json edges = nlohmann::json::array();
  for (size_t b = 0; b <= s.Histogram.size(); ++b)
  {
    edges.push_back(HistogramEdge(s, b));
  }
  nlohmann::json json = {
    { "field", EscapeInvalidUtf8(name) }, // a path: any bytes
    { "dimensions", s.Dimensions },
    { "voxels", s.Voxels },
    { "spacing", s.Spacing },
    { "origin", s.Origin },
    { "direction", s.Direction },
    { "bounds", s.Bounds },
    { "range", { s.Minimum, s.Maximum } },
    { "mean", s.Mean },
    { "non_empty_voxels", s.NonEmptyVoxels },
    { "non_empty_fraction", s.NonEmptyFraction },
    { "histogram",
      { { "bins", s.Histogram.size() }, { "edges", edges }, { "counts", s.Histogram } } },
  };
  if (source)
  {
    // Names of grids, variables and paths in the details: any bytes.
    nlohmann::json details = { { "format", source->Format } };
    for (const auto& detail : source->Details)
    {
      // A label given more than once (one "resampled" line per axis) becomes a list.
      nlohmann::json& entry = details[JsonKey(detail.first)];
      const std::string text = EscapeInvalidUtf8(detail.second);
      if (entry.is_null())
      {
        entry = text;
      }
      else
      {
        if (!entry.is_array())
        {
          entry = nlohmann::json::array({ entry });
        }
        entry.push_back(text);
      }
    }
    json["source"] = details;
  }
  return json;
}

} // namespace cloudvis
