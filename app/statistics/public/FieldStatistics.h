// Summary numbers of a density field, as `cloudvis info` prints them: lattice geometry, value
// range, mean, how much of the box the cloud occupies, and a histogram. Computed once into a
// plain struct so the text report, the JSON report (whose key names are a stable interface,
// documented in docs/command-line.md) and tests all read the same values.
#ifndef cloudvis_FieldStatistics_h
#define cloudvis_FieldStatistics_h

#include "FieldIO.h" // FieldReport

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

class vtkImageData;

namespace cloudvis
{

struct FieldStatistics
{
  std::array<int, 3> Dimensions{};
  std::array<double, 3> Spacing{};
  std::array<double, 3> Origin{}; // the world position of the extent's first voxel
  // The lattice's axes in world space, row-major (column a is the direction of index axis a).
  std::array<double, 9> Direction{ { 1, 0, 0, 0, 1, 0, 0, 0, 1 } };
  std::array<double, 6> Bounds{}; // the world box around the voxels (direction matrix applied)
  std::uint64_t Voxels = 0;
  double Minimum = 0.0;
  double Maximum = 0.0;
  double Mean = 0.0;
  std::uint64_t NonEmptyVoxels = 0; // density > 0
  double NonEmptyFraction = 0.0;
  // Equal-width bins over [Minimum, Maximum]; the last bin includes Maximum. When all values are
  // equal every voxel is counted in the first bin.
  std::vector<std::uint64_t> Histogram;
};

// Statistics of the active point scalars (component 0) of a field.
FieldStatistics ComputeFieldStatistics(vtkImageData* field, int bins = 16);

// Human-readable report, the histogram drawn as text bars. `name` is the file or scene shown;
// `source`, when given, what its reader found (format, grid or variable, units, time step,
// resampling), printed after the name.
void PrintFieldStatistics(std::ostream& out,
  const FieldStatistics& statistics,
  const std::string& name,
  const FieldReport* source = nullptr);

// The same as a JSON object with stable keys; `source` becomes the object "source" (its format
// under "format", each detail under its label with spaces as underscores).
nlohmann::json FieldStatisticsToJson(const FieldStatistics& statistics,
  const std::string& name,
  const FieldReport* source = nullptr);

} // namespace cloudvis

#endif
