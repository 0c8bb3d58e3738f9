// One pass over the voxels for range, mean and occupancy, a second for the histogram (its bins
// need the range). Sums are accumulated in double so the mean of a large field stays accurate.
#include "FieldStatistics.h"

#include "Utf8.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
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
  // The image's own bounds would follow its extent; ours always start at index 0 of the lattice,
  // which is what a scene's "bounds" describes.
  int extent[6];
  field->GetExtent(extent);
  for (int a = 0; a < 3; ++a)
  {
    s.Origin[a] += extent[2 * a] * s.Spacing[a];
    s.Bounds[2 * a] = s.Origin[a];
    s.Bounds[2 * a + 1] = s.Origin[a] + (s.Dimensions[a] - 1) * s.Spacing[a];
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

double HistogramEdge(const FieldStatistics& s, size_t bin)
{
  return s.Minimum + (s.Maximum - s.Minimum) * double(bin) / double(s.Histogram.size());
}

void PrintFieldStatistics(std::ostream& out, const FieldStatistics& s, const std::string& name)
{
  const auto triple = [](const auto& v, const char* separator)
  {
    std::ostringstream text;
    text << v[0] << separator << v[1] << separator << v[2];
    return text.str();
  };
  out << std::setprecision(6);
  out << "field        " << name << "\n";
  out << "dimensions   " << triple(s.Dimensions, " x ") << " (" << s.Voxels << " voxels)\n";
  out << "spacing      " << triple(s.Spacing, " ") << "\n";
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

nlohmann::json FieldStatisticsToJson(const FieldStatistics& s, const std::string& name)
{
  nlohmann::json edges = nlohmann::json::array();
  for (size_t b = 0; b <= s.Histogram.size(); ++b)
  {
    edges.push_back(HistogramEdge(s, b));
  }
  return {
    { "field", EscapeInvalidUtf8(name) }, // a path: any bytes
    { "dimensions", s.Dimensions },
    { "voxels", s.Voxels },
    { "spacing", s.Spacing },
    { "origin", s.Origin },
    { "bounds", s.Bounds },
    { "range", { s.Minimum, s.Maximum } },
    { "mean", s.Mean },
    { "non_empty_voxels", s.NonEmptyVoxels },
    { "non_empty_fraction", s.NonEmptyFraction },
    { "histogram",
      { { "bins", s.Histogram.size() }, { "edges", edges }, { "counts", s.Histogram } } },
  };
}

} // namespace cloudvis
