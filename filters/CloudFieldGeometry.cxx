#include "CloudFieldGeometry.h"

#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkInformationIntegerVectorKey.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace cloudvis
{

void LatticeFromBounds(
  const int dimensions[3], const double bounds[6], double origin[3], double spacing[3])
{
  for (int a = 0; a < 3; ++a)
  {
    const double lo = bounds[2 * a], hi = bounds[2 * a + 1];
    if (dimensions[a] > 1)
    {
      origin[a] = lo;
      spacing[a] = (hi - lo) / (dimensions[a] - 1);
    }
    else
    {
      // A single layer sits in the middle of the bounds.
      origin[a] = 0.5 * (lo + hi);
      spacing[a] = hi > lo ? hi - lo : 1.0;
    }
  }
}

std::uint64_t AvailableMemoryBytes()
{
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
  {
    if (key == "MemAvailable:")
    {
      return kib * 1024u;
    }
  }
  const long pages = sysconf(_SC_AVPHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
  return pages > 0 && pageSize > 0 ? std::uint64_t(pages) * std::uint64_t(pageSize) : 0u;
}

std::string ValidateDensityScalars(vtkDataArray* scalars)
{
  if (!scalars)
  {
    return "the input has no scalar array to use as density";
  }
  const std::string name = std::string("the scalar array \"") +
    (scalars->GetName() ? scalars->GetName() : "") + "\"";
  if (scalars->GetNumberOfComponents() != 1)
  {
    return name + " has " + std::to_string(scalars->GetNumberOfComponents()) +
      " components; a density has exactly 1";
  }
  const int type = scalars->GetDataType();
  if (type != VTK_FLOAT && type != VTK_UNSIGNED_CHAR && type != VTK_UNSIGNED_SHORT)
  {
    return name + " is of type " + scalars->GetDataTypeAsString() +
      "; a density is float, unsigned char or unsigned short";
  }
  return {};
}

std::string ValidateDensityValues(vtkDataArray* scalars)
{
  if (scalars->GetDataType() != VTK_FLOAT)
  {
    return {}; // integers are always finite
  }
  const float* values = static_cast<const float*>(scalars->GetVoidPointer(0));
  const vtkIdType n = scalars->GetNumberOfTuples();
  vtkIdType nonFinite = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    nonFinite += std::isfinite(values[i]) ? 0 : 1;
  }
  if (nonFinite == 0)
  {
    return {};
  }
  return std::string("the scalar array \"") + (scalars->GetName() ? scalars->GetName() : "") +
    "\" holds " + std::to_string(nonFinite) + " values that are NaN or infinite";
}

std::string FormatBytes(double bytes)
{
  static const char* units[] = { "bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB" };
  int u = 0;
  while (bytes >= 1024.0 && u < 6)
  {
    bytes /= 1024.0;
    ++u;
  }
  std::ostringstream out;
  out.precision(u == 0 ? 0 : 3);
  out << bytes << ' ' << units[u];
  return out.str();
}

std::string ValidateFieldGeometry(const int dimensions[3], const double bounds[6])
{
  static const char* axes = "xyz";
  std::ostringstream error;
  for (int a = 0; a < 3; ++a)
  {
    if (dimensions[a] < 1)
    {
      error << "dimensions must be at least 1 along each axis, got " << dimensions[a] << " along "
            << axes[a];
      return error.str();
    }
    const double lo = bounds[2 * a], hi = bounds[2 * a + 1];
    if (!std::isfinite(lo) || !std::isfinite(hi))
    {
      error << "bounds along " << axes[a] << " must be finite numbers";
      return error.str();
    }
    if (!(lo < hi))
    {
      error << "bounds along " << axes[a] << " must increase (min < max), got [" << lo << ", "
            << hi << "]";
      return error.str();
    }
  }
  return {};
}

std::string ValidateExtentMemory(const int extent[6], int bytesPerVoxel)
{
  // Counted in 64 bits and the product in double: a large extent overflows int; an empty one
  // counts 0.
  long long counts[3];
  double voxels = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    counts[a] = std::max(0LL, (long long)extent[2 * a + 1] - extent[2 * a] + 1);
    voxels *= double(counts[a]);
  }
  const double needed = voxels * bytesPerVoxel;
  const std::uint64_t available = AvailableMemoryBytes();
  if (available > 0 && needed > static_cast<double>(available))
  {
    std::ostringstream error;
    error << "a field of " << counts[0] << " x " << counts[1] << " x " << counts[2]
          << " voxels needs " << FormatBytes(needed) << " but only "
          << FormatBytes(double(available)) << " of memory is available";
    return error.str();
  }
  return {};
}

std::string PipelineExtent(vtkInformation* info, vtkInformationIntegerVectorKey* key, int extent[6])
{
  if (!info || !info->Has(key) || info->Length(key) != 6)
  {
    return std::string("no ") + key->GetName() +
      " in the pipeline information: the input's source failed or has not run";
  }
  info->Get(key, extent);
  return {};
}

std::string RequestWholeExtent(vtkInformation* inputInfo)
{
  int wholeExtent[6];
  std::string problem =
    PipelineExtent(inputInfo, vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent);
  if (problem.empty())
  {
    inputInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), wholeExtent, 6);
  }
  return problem;
}

std::string ValidateSubExtent(const int extent[6], const int whole[6])
{
  // An empty request is legal (a streaming piece with nothing in it): nothing is filled.
  for (int a = 0; a < 3; ++a)
  {
    if (extent[2 * a] > extent[2 * a + 1])
    {
      return {};
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    if (extent[2 * a] < whole[2 * a] || extent[2 * a + 1] > whole[2 * a + 1])
    {
      std::ostringstream error;
      error << "the extent asked for, [" << extent[0] << ", " << extent[1] << ", " << extent[2]
            << ", " << extent[3] << ", " << extent[4] << ", " << extent[5]
            << "], leaves the whole extent [" << whole[0] << ", " << whole[1] << ", " << whole[2]
            << ", " << whole[3] << ", " << whole[4] << ", " << whole[5] << "]";
      return error.str();
    }
  }
  return {};
}

} // namespace cloudvis
