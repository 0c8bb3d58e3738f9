// The NetCDF reader: one variable at one time step of a file that follows the CF conventions, as
// large-eddy simulations of clouds write them (liquid water, ice, on regular or vertically
// stretched grids, with a time axis). The netCDF C library (and HDF5 under it for netCDF-4 files)
// parses the file; cloudvis asks it for the variables, their attributes and the values of the
// chosen one in any numeric type, and applies the CF conventions itself (NetCdfVariables.h): the
// default variable, the time axis, which dimension is x, y and z, missing values, packing. The
// whole read runs in the isolated child (IsolatedRead.h).
//
// Geometry: the coordinate variables of the dimensions become the lattice, each dimension placed
// on the world axis it stands for whatever its position in the variable (a variable on (x, y, z)
// is transposed). A coordinate that is not evenly spaced (to 1e-3 of a step), as a stretched
// vertical coordinate is, is resampled here onto a regular lattice, linearly along each stretched
// axis, at the smallest spacing of that axis (so no level is skipped), with fewer points only
// when field.max_voxels would be exceeded; `info` reports how. Coordinates that decrease (pressure
// levels, latitudes from north to south) are turned around so that the spacing is positive.
// Curvilinear coordinates (2-D latitude and longitude) are refused.
//
// Missing values (CF's _FillValue, missing_value, valid_min, valid_max, valid_range) are refused
// with their count unless field.missing is "empty", which reads them as density 0: cloudvis does
// not guess what a missing density is.
#include "FieldFormatReaders.h"

#include "Errors.h"
#include "InputFiles.h"
#include "IsolatedRead.h"
#include "NetCdfAirDensity.h"
#include "NetCdfVariables.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>

namespace cloudvis
{
namespace
{

// ---- the superblock of a netCDF-4 (HDF5) file -------------------------------------------------

// The number of bytes a netCDF-4 file says it holds: the end-of-file address of its HDF5
// superblock (versions 0 to 3), plus the base address; 0 when the superblock is not one of these.
// HDF5 compares it with the file's size when it opens the file and refuses a shorter one, in its
// own words; cloudvis says the same first, with the numbers.
std::uint64_t Hdf5FileEnd(const std::string& superblock)
{
  if (superblock.size() < 9)
  {
    return 0;
  }
  const int version = static_cast<unsigned char>(superblock[8]);
  // Where the size of an address is, and where the base address begins.
  const std::size_t sizeAt = version <= 1 ? 13 : 9;
  const std::size_t baseAt = version == 0 ? 24 : version == 1 ? 28 : 12;
  if (version > 3 || superblock.size() <= sizeAt)
  {
    return 0;
  }
  const std::size_t addressBytes = static_cast<unsigned char>(superblock[sizeAt]);
  // Base address, then (versions 0 and 1) the free-space address or (2 and 3) the superblock
  // extension's, then the end-of-file address; little-endian.
  const std::size_t endAt = baseAt + 2 * addressBytes;
  if ((addressBytes != 2 && addressBytes != 4 && addressBytes != 8) ||
    superblock.size() < endAt + addressBytes)
  {
    return 0;
  }
  const auto address = [&superblock, addressBytes](std::size_t at)
  {
    std::uint64_t value = 0;
    for (std::size_t b = addressBytes; b-- > 0;)
    {
      value = (value << 8) | static_cast<unsigned char>(superblock[at + b]);
    }
    return value;
  };
  const std::uint64_t base = address(baseAt), end = address(endAt);
  return end > std::numeric_limits<std::uint64_t>::max() - base ? 0 : base + end;
}

// ---- the header of a classic file -------------------------------------------------------------

// A classic file (CDF-1, -2, -5) begins with a header that lists its dimensions, attributes and
// variables, each variable with the offset of its values. cloudvis reads it itself, before the
// netCDF library does, for two reasons. The library sizes its tables from the header's counts
// before it checks them against the file (found by the fuzzer: one variable claiming 2^31
// dimensions made it allocate 17 GB), so counts the header's bytes cannot hold are refused.
// And the library reads past the end of a truncated file without an error, handing back zeros,
// so a variable whose values for the time step end beyond the file is refused. (netCDF-4 files
// are HDF5 files, whose library refuses a truncated file itself.)
class ClassicHeader
{
public:
  // Reads the header from `bytes`, the first bytes of a file of `fileBytes`. Empty when it is
  // sound, or when it goes on beyond the bytes given (a header of more than 16 MiB is not
  // checked); else the problem.
  std::string Parse(const std::string& bytes, std::uint64_t fileBytes);

  // Where the values of `variable` at record `step` end; 0 when unknown.
  std::uint64_t EndOf(const std::string& variable, std::uint64_t step) const;

private:
  struct Var
  {
    std::string Name;
    std::uint64_t Begin = 0, Size = 0; // Size: of one record for a record variable
    bool Record = false;
  };
  struct Problem
  {
    std::string Text; // empty: the header goes on beyond the bytes read
  };

  std::uint64_t Left() const { return this->Bytes->size() - this->At; }
  std::uint64_t Number(int bytes)
  {
    if (std::uint64_t(bytes) > this->Left())
    {
      throw Problem{};
    }
    std::uint64_t value = 0;
    for (int b = 0; b < bytes; ++b)
    {
      value = (value << 8) | static_cast<unsigned char>((*this->Bytes)[this->At++]);
    }
    return value;
  }
  std::uint64_t Count() { return this->Number(this->Version == 5 ? 8 : 4); }
  // A count of list entries, each taking at least `entryBytes` of the header.
  std::uint64_t ListCount(const char* what, std::uint64_t entryBytes)
  {
    const std::uint64_t count = this->Count();
    if (count > this->Left() / entryBytes && this->Bytes->size() >= this->FileBytes)
    {
      throw Problem{ "the header lists " + std::to_string(count) + " " + what +
        ", more than its remaining " + std::to_string(this->Left()) + " bytes can hold" };
    }
    return count;
  }
  void Skip(std::uint64_t bytes)
  {
    const std::uint64_t padded = (bytes + 3) / 4 * 4;
    if (bytes > this->Left() || padded > this->Left())
    {
      throw Problem{};
    }
    this->At += std::size_t(padded);
  }
  std::string Name()
  {
    const std::uint64_t length = this->Count();
    if (length > this->Left())
    {
      throw Problem{};
    }
    const std::string name = this->Bytes->substr(this->At, std::size_t(length));
    this->Skip(length);
    return name;
  }
  static std::uint64_t TypeBytes(std::uint64_t type)
  {
    // NC_BYTE, CHAR, SHORT, INT, FLOAT, DOUBLE, UBYTE, USHORT, UINT, INT64, UINT64
    static const std::uint64_t sizes[] = { 0, 1, 1, 2, 4, 4, 8, 1, 2, 4, 8, 8 };
    return type < 12 ? sizes[type] : 0;
  }
  void SkipAttributes()
  {
    this->Number(4); // NC_ATTRIBUTE, or ABSENT
    for (std::uint64_t a = 0, n = this->ListCount("attributes", 12); a < n; ++a)
    {
      this->Name();
      const std::uint64_t type = this->Number(4);
      if (TypeBytes(type) == 0)
      {
        throw Problem{ "an attribute has the unknown type " + std::to_string(type) };
      }
      const std::uint64_t values = this->Count();
      if (values > this->Left() / TypeBytes(type))
      {
        throw Problem{};
      }
      this->Skip(values * TypeBytes(type));
    }
  }

  const std::string* Bytes = nullptr;
  std::uint64_t FileBytes = 0;
  std::size_t At = 0;
  int Version = 1;
  std::vector<Var> Variables;
  std::uint64_t RecordBytes = 0;
};

std::string ClassicHeader::Parse(const std::string& bytes, std::uint64_t fileBytes)
{
  this->Bytes = &bytes;
  this->FileBytes = fileBytes;
  this->Variables.clear();
  try
  {
    this->At = 3;
    this->Version = int(this->Number(1));
    this->Count(); // the number of records: the time step is checked against the file's times
    std::vector<std::uint64_t> lengths;
    this->Number(4); // NC_DIMENSION, or ABSENT
    for (std::uint64_t d = 0, n = this->ListCount("dimensions", 8); d < n; ++d)
    {
      this->Name();
      lengths.push_back(this->Count());
    }
    this->SkipAttributes(); // global attributes
    this->Number(4);        // NC_VARIABLE, or ABSENT
    for (std::uint64_t v = 0, n = this->ListCount("variables", 24); v < n; ++v)
    {
      Var var;
      var.Name = this->Name();
      std::uint64_t values = 1;
      const std::uint64_t dims = this->Count();
      if (dims > 1024) // NC_MAX_VAR_DIMS
      {
        throw Problem{ "variable \"" + var.Name + "\" has " + std::to_string(dims) +
          " dimensions; netCDF allows 1024" };
      }
      for (std::uint64_t d = 0; d < dims; ++d)
      {
        const std::uint64_t id = this->Count();
        if (id >= lengths.size())
        {
          throw Problem{ "variable \"" + var.Name + "\" names dimension " + std::to_string(id) +
            " of " + std::to_string(lengths.size()) };
        }
        var.Record = var.Record || (d == 0 && lengths[id] == 0);
        values *= lengths[id] == 0 ? 1 : lengths[id];
      }
      this->SkipAttributes();
      var.Size = values * TypeBytes(this->Number(4));
      this->Count(); // vsize, which large variables overflow
      var.Begin = this->Number(this->Version == 1 ? 4 : 8);
      this->Variables.push_back(var);
    }
  }
  catch (const Problem& problem)
  {
    this->Variables.clear();
    if (!problem.Text.empty())
    {
      return problem.Text;
    }
    return bytes.size() >= fileBytes ? "the header ends before the lists it announces do" : "";
  }
  // One record holds every record variable's values, each padded to 4 bytes unless it is the
  // only one.
  const auto recordVariables = std::count_if(
    this->Variables.begin(), this->Variables.end(), [](const Var& v) { return v.Record; });
  this->RecordBytes = 0;
  for (const Var& v : this->Variables)
  {
    this->RecordBytes += v.Record ? (recordVariables == 1 ? v.Size : (v.Size + 3) / 4 * 4) : 0;
  }
  return "";
}

std::uint64_t ClassicHeader::EndOf(const std::string& variable, std::uint64_t step) const
{
  for (const Var& v : this->Variables)
  {
    if (v.Name == variable)
    {
      return v.Begin + (v.Record ? step * this->RecordBytes : 0) + v.Size;
    }
  }
  return 0;
}

// ---- resampling a rectilinear grid -------------------------------------------------------------

// One axis of the output lattice and how it maps onto the file's coordinates.
struct AxisSampling
{
  std::vector<double> Coordinates; // the file's, increasing
  bool Reversed = false;           // the file's coordinates decrease
  bool Stretched = false;
  int Points = 0;       // of the regular output
  double FinestPoints = 0.0; // stretched: at the smallest step, beyond int if one step is tiny
  double Origin = 0.0;  // of the regular output
  double Spacing = 1.0; // of the regular output
  double SmallestStep = 0.0, LargestStep = 0.0;
};

AxisSampling SampleAxis(const std::string& path,
  std::vector<double> coordinates,
  const std::string& name)
{
  AxisSampling axis;
  axis.Coordinates = std::move(coordinates);
  const std::size_t n = axis.Coordinates.size();
  if (n > 1 && axis.Coordinates.back() < axis.Coordinates.front())
  {
    std::reverse(axis.Coordinates.begin(), axis.Coordinates.end());
    axis.Reversed = true;
  }
  axis.Points = int(n);
  axis.Origin = axis.Coordinates.front();
  if (n == 1)
  {
    return axis;
  }
  axis.SmallestStep = std::numeric_limits<double>::max();
  for (std::size_t i = 1; i < n; ++i)
  {
    const double step = axis.Coordinates[i] - axis.Coordinates[i - 1];
    if (!(step > 0.0) || !std::isfinite(step))
    {
      Fail(
        path, "the coordinates of dimension \"" + name + "\" do not increase or decrease steadily");
    }
    axis.SmallestStep = std::min(axis.SmallestStep, step);
    axis.LargestStep = std::max(axis.LargestStep, step);
  }
  const double length = axis.Coordinates.back() - axis.Coordinates.front();
  axis.Spacing = length / double(n - 1);
  // Even to 1e-3 of a step (coordinates stored as float are that exact): then the lattice is the
  // file's own, and nothing is interpolated.
  axis.Stretched = axis.LargestStep - axis.SmallestStep > 1e-3 * axis.Spacing;
  if (axis.Stretched)
  {
    // The smallest step, rounded down so that the first and last coordinates are lattice points.
    // Counted in double: one tiny step asks for more points than an int holds, and
    // field.max_voxels coarsens the lattice from there (Points is set then).
    axis.FinestPoints = std::ceil(length / axis.SmallestStep - 1e-9) + 1.0;
    if (!std::isfinite(axis.FinestPoints))
    {
      Fail(path,
        "the coordinates of dimension \"" + name + "\" span " + Number(length) +
          " with a smallest step of " + Number(axis.SmallestStep) +
          ": a regular lattice at that step would need more points than can be counted");
    }
    axis.Spacing = length / (axis.FinestPoints - 1.0);
  }
  return axis;
}

// `count` floats, uninitialised. The values are read and resampled into the array the field
// will hold, so that no lattice is copied at the end (CheckFieldSize counts each one alive).
vtkSmartPointer<vtkFloatArray> NewFloats(std::size_t count)
{
  auto values = vtkSmartPointer<vtkFloatArray>::New();
  values->SetNumberOfTuples(vtkIdType(count));
  if (std::size_t(values->GetNumberOfValues()) != count)
  {
    throw std::bad_alloc(); // VTK reports a failed allocation only on its error stream
  }
  return values;
}

// Resamples `in` (dimensions `dimensions`, x fastest) along `axisIndex` from the file's
// coordinates onto the axis's regular lattice, linearly. Axes resampled one after the other give
// trilinear interpolation, the interpolation of a rectilinear grid.
vtkSmartPointer<vtkFloatArray> ResampleAlong(vtkFloatArray* in,
  std::array<int, 3>& dimensions,
  int axisIndex,
  const AxisSampling& axis)
{
  std::array<int, 3> out = dimensions;
  out[axisIndex] = axis.Points;
  vtkSmartPointer<vtkFloatArray> resampled = NewFloats(std::size_t(out[0]) * out[1] * out[2]);
  const float* values = in->GetPointer(0);
  float* result = resampled->GetPointer(0);
  // For each output point along the axis: the file's interval and the weight of its upper end.
  std::vector<int> lower(std::size_t(axis.Points));
  std::vector<double> weight(std::size_t(axis.Points));
  std::size_t interval = 0;
  for (int p = 0; p < axis.Points; ++p)
  {
    const double at = axis.Origin + p * axis.Spacing;
    while (interval + 2 < axis.Coordinates.size() && axis.Coordinates[interval + 1] < at)
    {
      ++interval;
    }
    const double a = axis.Coordinates[interval], b = axis.Coordinates[interval + 1];
    lower[std::size_t(p)] = int(interval);
    weight[std::size_t(p)] = std::clamp((at - a) / (b - a), 0.0, 1.0);
  }
  const std::size_t strideIn = axisIndex == 0 ? 1
    : axisIndex == 1                          ? std::size_t(dimensions[0])
                                              : std::size_t(dimensions[0]) * dimensions[1];
  for (int k = 0; k < out[2]; ++k)
  {
    for (int j = 0; j < out[1]; ++j)
    {
      for (int i = 0; i < out[0]; ++i)
      {
        const int index[3] = { i, j, k };
        const int p = index[axisIndex];
        // The input point with this point's other indices and index `lower` along the axis.
        std::size_t base = 0, outIndex = 0;
        std::size_t strideAll = 1, strideAllOut = 1;
        for (int a = 0; a < 3; ++a)
        {
          const int along = a == axisIndex ? lower[std::size_t(p)] : index[a];
          base += std::size_t(along) * strideAll;
          outIndex += std::size_t(index[a]) * strideAllOut;
          strideAll *= std::size_t(dimensions[a]);
          strideAllOut *= std::size_t(out[a]);
        }
        const double w = weight[std::size_t(p)];
        const double below = values[base];
        const double above = w > 0.0 ? double(values[base + strideIn]) : below;
        result[outIndex] = float(below + w * (above - below));
      }
    }
  }
  dimensions = out;
  return resampled;
}

// ---- the values ---------------------------------------------------------------------------------

// "1 missing value", "12 missing values".
std::string Values(std::uint64_t count, const std::string& kind = "")
{
  return std::to_string(count) + " " + kind + (count == 1 ? "value" : "values");
}

// How the values of the chosen variable are read: its layout, time step and missing values, and
// the axes of the lattice they go to.
struct ValueSource
{
  const netcdf::File& File;
  const netcdf::Variable& Variable;
  const netcdf::Layout& Layout;
  std::size_t Step = 0;
  bool MissingIsEmpty = false;
  std::size_t SlabSlices = 1; // of its slowest spatial dimension, read at a time
};

// The values of the variable at the time step as floats, x fastest, each axis in the order of its
// increasing coordinate, so that a variable on (x, y, z) or on decreasing coordinates lands on
// the lattice as it lies in the world. The file is read in slabs of whole chunks along its
// slowest spatial dimension, as doubles (the library converts every numeric type exactly, and
// int64 and uint64 nearly), which are compared with the missing-value markers as stored, then
// unpacked. Missing values become 0 and are counted in `missing`.
vtkSmartPointer<vtkFloatArray> ReadValues(const ValueSource& source,
  const std::array<AxisSampling, 3>& axes,
  netcdf::MissingValues& missing)
{
  const std::string& path = source.File.Path();
  const std::array<std::size_t, 3> lattice{
    { axes[0].Coordinates.size(), axes[1].Coordinates.size(), axes[2].Coordinates.size() }
  };
  const std::array<std::ptrdiff_t, 3> latticeStride{
    { 1, std::ptrdiff_t(lattice[0]), std::ptrdiff_t(lattice[0] * lattice[1]) }
  };
  // The spatial dimensions in file order (a 2-D variable's third is a placeholder of one point),
  // with the step in the lattice that one step along each makes.
  const std::size_t dimensions = source.Variable.Dimensions.size();
  std::array<int, 3> position{ { -1, -1, -1 } };
  std::array<std::size_t, 3> length{ { 1, 1, 1 } };
  std::array<std::ptrdiff_t, 3> stride{ { 0, 0, 0 } };
  std::ptrdiff_t first = 0; // the lattice index of the file's first value
  int s = 0;
  for (int p = 0; p < int(dimensions); ++p)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (source.Layout.Space[std::size_t(a)].Position == p)
      {
        position[std::size_t(s)] = p;
        length[std::size_t(s)] = lattice[std::size_t(a)];
        stride[std::size_t(s)] = axes[std::size_t(a)].Reversed ? -latticeStride[std::size_t(a)]
                                                               : latticeStride[std::size_t(a)];
        first += axes[std::size_t(a)].Reversed
          ? std::ptrdiff_t(lattice[std::size_t(a)] - 1) * latticeStride[std::size_t(a)]
          : 0;
        ++s;
      }
    }
  }
  std::vector<std::size_t> start(dimensions, 0), count(dimensions, 1);
  for (int a = 0; a < s; ++a)
  {
    count[std::size_t(position[std::size_t(a)])] = length[std::size_t(a)];
  }
  if (source.Layout.Time.Position >= 0)
  {
    start[std::size_t(source.Layout.Time.Position)] = source.Step;
  }
  const netcdf::Packing packing = netcdf::PackingOf(source.File, source.Variable);
  vtkSmartPointer<vtkFloatArray> read = NewFloats(lattice[0] * lattice[1] * lattice[2]);
  float* values = read->GetPointer(0);
  std::vector<double> slab(std::min(source.SlabSlices, length[0]) * length[1] * length[2]);
  std::uint64_t beyond = 0;
  for (std::size_t from = 0; from < length[0]; from += source.SlabSlices)
  {
    const std::size_t slices = std::min(source.SlabSlices, length[0] - from);
    start[std::size_t(position[0])] = from;
    count[std::size_t(position[0])] = slices;
    source.File.Read(source.Variable, start, count, slab.data());
    const double* stored = slab.data();
    for (std::size_t i0 = from; i0 < from + slices; ++i0)
      for (std::size_t i1 = 0; i1 < length[1]; ++i1)
        for (std::size_t i2 = 0; i2 < length[2]; ++i2)
        {
          const double packed = *stored++;
          float& value = values[std::size_t(first + std::ptrdiff_t(i0) * stride[0] +
            std::ptrdiff_t(i1) * stride[1] + std::ptrdiff_t(i2) * stride[2])];
          if (missing.Match(packed) >= 0)
          {
            value = 0.0f;
            continue;
          }
          const double unpacked = packed * packing.Scale + packing.Offset;
          beyond += BeyondFloat(unpacked) ? 1 : 0;
          value = float(unpacked); // NaN and infinity stay, for ReadField to count and refuse
        }
  }
  RefuseBeyondFloat(path, "\"" + source.Variable.Name + "\"", beyond);
  if (missing.Count() > 0 && !source.MissingIsEmpty)
  {
    Fail(path,
      "variable \"" + source.Variable.Name + "\" holds " + Values(missing.Count(), "missing ") +
        " (" + missing.Describe() +
        "): cloudvis does not guess what a missing density is; field.missing = \"empty\" reads "
        "them as empty space (density 0)");
  }
  return read;
}

// "1 of 0 .. 3: t = 3600 seconds since 2020-06-01" for the report, with the number of steps and
// the step's time in `report`, and the refusals of a time axis without records and of a step
// beyond it.
std::string TimeStep(const netcdf::File& file,
  const netcdf::Variable& chosen,
  const netcdf::Layout& layout,
  const FieldReadOptions& options,
  FieldReport& report)
{
  const int step = options.TimeStep.value_or(0);
  if (layout.Time.Position < 0)
  {
    if (step > 0)
    {
      Fail(file.Path(),
        "field.time_step: " + std::to_string(step) +
          " is out of range: the file holds no time axis (one step, 0)");
    }
    return "";
  }
  const std::string name = file.DimensionOf(layout.Time.Dimension).Name;
  const std::size_t steps = file.DimensionOf(layout.Time.Dimension).Length;
  if (steps == 0)
  {
    Fail(file.Path(),
      "variable \"" + chosen.Name + "\" holds no values: its time axis \"" + name +
        "\" has no records");
  }
  if (std::size_t(step) >= steps)
  {
    Fail(file.Path(),
      "field.time_step: " + std::to_string(step) + " is out of range: the file holds " +
        std::to_string(steps) + " time steps (0 .. " + std::to_string(steps - 1) + ")");
  }
  report.TimeSteps = steps;
  std::string text = std::to_string(step) + " of 0 .. " + std::to_string(steps - 1);
  if (const netcdf::Variable* times = file.CoordinateOf(layout.Time.Dimension))
  {
    const std::string units = file.Text(*times, "units");
    report.Times = file.Coordinates(*times);
    report.Time = report.Times[std::size_t(step)];
    report.TimeUnits = units;
    text += ": t = " + Number(report.Time) + (units.empty() ? "" : " " + units);
  }
  return text + (options.TimeStep ? "" : " (the first; field.time_step picks another)");
}

} // namespace

namespace
{
// What cloudvis checks of a file itself before the netCDF library opens it (ClassicHeader,
// Hdf5FileEnd): the file's size, whether it is a classic file, and a classic file's header.
struct CheckedFile
{
  std::uint64_t Bytes = 0;
  bool Classic = false; // CDF-1, -2 and -5 files hold every value uncompressed
  ClassicHeader Header;
};

CheckedFile CheckBeforeTheLibrary(const std::string& path)
{
  CheckedFile checked;
  const RegularInputFile file(path, "field");
  checked.Bytes = file.Size();
  const std::string magic = file.ReadAt(0, 8);
  checked.Classic = magic.size() >= 4 && magic.compare(0, 3, "CDF") == 0 &&
    (magic[3] == 1 || magic[3] == 2 || magic[3] == 5);
  if (!checked.Classic && magic != "\x89HDF\r\n\x1a\n")
  {
    Fail(path, "not a NetCDF file (it starts with neither \"CDF\" nor the HDF5 signature)");
  }
  if (checked.Classic)
  {
    // Its first 16 MiB, more than any header needs.
    const std::string headerBytes =
      file.ReadAt(0, std::size_t(std::min<std::uint64_t>(checked.Bytes, 16u << 20)));
    const std::string problem = checked.Header.Parse(headerBytes, checked.Bytes);
    if (!problem.empty())
    {
      Fail(path, "malformed NetCDF header: " + problem);
    }
  }
  else if (const std::uint64_t end = Hdf5FileEnd(file.ReadAt(0, 64)); end > checked.Bytes)
  {
    Fail(path,
      "the netCDF-4 (HDF5) file says it holds " + std::to_string(end) + " bytes but holds " +
        std::to_string(checked.Bytes) + ": it is truncated");
  }
  return checked;
}

// The chosen variable in the open file, at the time step the options choose.
struct ChosenVariable
{
  const netcdf::File& File;
  const netcdf::Variable& Variable;
  const netcdf::Layout Layout;
  const FieldReadOptions& Options;
  std::size_t Step() const { return std::size_t(this->Options.TimeStep.value_or(0)); }
};

// The lattice of the file: each axis's dimension and name, its coordinates (the indices without
// a coordinate variable; one point at 0 for the axis a 2-D variable lacks) and how the
// coordinates a file implies came about.
struct FileLattice
{
  std::array<AxisSampling, 3> Axes;
  std::array<double, 3> Dimensions{ { 1.0, 1.0, 1.0 } };
  std::array<std::string, 3> Names;
  std::array<std::string, 3> Implied;
};

FileLattice LatticeOf(const ChosenVariable& v)
{
  const std::string& path = v.File.Path();
  FileLattice lattice;
  for (std::size_t a = 0; a < 3; ++a)
  {
    const netcdf::Layout::Axis& axis = v.Layout.Space[a];
    std::vector<double> coordinates{ 0.0 };
    if (axis.Position >= 0)
    {
      const netcdf::Dimension& dimension = v.File.DimensionOf(axis.Dimension);
      lattice.Names[a] = dimension.Name;
      if (dimension.Length == 0)
      {
        Fail(path,
          "variable \"" + v.Variable.Name + "\" holds no values: its dimension \"" +
            dimension.Name + "\" has length 0");
      }
      lattice.Dimensions[a] = double(dimension.Length);
      // Before any coordinates are read: a chunked coordinate may claim any length too.
      CheckFieldSize(path, lattice.Dimensions, 4.0, v.Options.MaximumVoxels);
      const netcdf::Variable* c = v.File.CoordinateOf(axis.Dimension);
      const auto impliedAxis =
        c ? std::nullopt : netcdf::ImpliedCoordinates(v.File, axis.Dimension, v.Step());
      if (impliedAxis)
      {
        coordinates = impliedAxis->Coordinates;
        lattice.Implied[a] = impliedAxis->How;
      }
      else if (!c)
      {
        coordinates.resize(dimension.Length);
        for (std::size_t i = 0; i < coordinates.size(); ++i)
        {
          coordinates[i] = double(i);
        }
      }
      else
      {
        coordinates = v.File.Coordinates(*c);
      }
    }
    lattice.Axes[a] = SampleAxis(path, coordinates, lattice.Names[a]);
  }
  return lattice;
}

// The slices of the slowest spatial dimension read at a time: whole chunks of it (a chunk is
// then decompressed once), else about 8 MiB of doubles; the field's size checked with them.
std::size_t SlabSlices(const ChosenVariable& v, const FileLattice& lattice)
{
  const std::array<double, 3>& d = lattice.Dimensions;
  int slowest = -1;
  for (std::size_t a = 0; a < 3; ++a)
  {
    const int p = v.Layout.Space[a].Position;
    slowest = p >= 0 && (slowest < 0 || p < v.Layout.Space[std::size_t(slowest)].Position)
      ? int(a)
      : slowest;
  }
  const double slice = d[0] * d[1] * d[2] / d[std::size_t(slowest)];
  const std::size_t chunk =
    v.File.ChunkLength(v.Variable, v.Layout.Space[std::size_t(slowest)].Position);
  const std::size_t slabSlices =
    chunk > 0 ? chunk : std::size_t(std::max(1.0, std::floor((8u << 20) / 8.0 / slice)));
  CheckFieldSize(v.File.Path(),
    d,
    4.0,
    v.Options.MaximumVoxels,
    8.0 * slice * double(std::min<std::size_t>(slabSlices, std::size_t(d[std::size_t(slowest)]))));
  return slabSlices;
}

// The report's lines on the variable read: its name, dimensions, type and packing, its units.
void ReportVariable(const ChosenVariable& v, FieldReport& report)
{
  const netcdf::File& file = v.File;
  const std::string units = file.Text(v.Variable, "units");
  const std::string longName = file.Text(v.Variable, "long_name");
  const netcdf::Packing packing = netcdf::PackingOf(file, v.Variable);
  std::string dimensionsText;
  for (const int d : v.Variable.Dimensions)
  {
    dimensionsText += (dimensionsText.empty() ? "" : ", ") + file.DimensionOf(d).Name;
  }
  const std::string type = netcdf::TypeName(v.Variable.Type);
  report.Add("variable",
    "\"" + v.Variable.Name + "\"" + (longName.empty() ? "" : " (" + longName + ")") + " on (" +
      dimensionsText + "), " + type +
      (packing.Packed ? ", packed (scale_factor " + Number(packing.Scale) + ", add_offset " +
            Number(packing.Offset) + "), unpacked to float"
          : type == "float" ? ""
                            : ", converted to float"));
  report.Add("units", units.empty() ? "not stated" : units);
  DeclareQuantityOfUnits(units, "the variable's", report);
}

// Another variable on the field's dimensions (the air's density), read as the field's values
// were. Its missing values are refused, not read as empty space: field.missing is the field's,
// and the air is needed at every voxel.
vtkSmartPointer<vtkFloatArray> ReadOnTheFieldsLattice(const ChosenVariable& v,
  const FileLattice& lattice,
  std::size_t slabSlices,
  const netcdf::Variable& other)
{
  const std::string& path = v.File.Path();
  const netcdf::Layout otherLayout = netcdf::LayoutOf(v.File, other);
  for (std::size_t a = 0; a < 3; ++a)
  {
    if (otherLayout.Space[a].Dimension != v.Layout.Space[a].Dimension)
    {
      Fail(path,
        "variable \"" + other.Name + "\" is on the dimensions of \"" + v.Variable.Name +
          "\" but they do not stand for the same axes");
    }
  }
  netcdf::MissingValues otherMissing(v.File, other);
  const ValueSource values{ v.File, other, otherLayout, v.Step(), true, slabSlices };
  vtkSmartPointer<vtkFloatArray> air = ReadValues(values, lattice.Axes, otherMissing);
  if (otherMissing.Count() > 0)
  {
    Fail(path,
      "variable \"" + other.Name + "\" holds " + Values(otherMissing.Count(), "missing ") + " (" +
        otherMissing.Describe() + "): the air's density is needed at every voxel of \"" +
        v.Variable.Name +
        "\"; field.air_density \"standard\" or a number in kg/m^3 gives it another way");
  }
  return air;
}

// The points of each axis once the stretched ones are resampled: at their smallest step, coarser
// where field.max_voxels requires it; the field's size checked with the resampling's peak (each
// stretched axis is resampled from one lattice into the next, both alive at once). `finest`:
// the points each axis would have at its smallest step.
std::array<double, 3> ResampledPoints(const std::string& path,
  const FileLattice& lattice,
  const FieldReadOptions& options,
  std::array<double, 3>& finest)
{
  const std::array<AxisSampling, 3>& axes = lattice.Axes;
  for (int a = 0; a < 3; ++a)
  {
    finest[a] = axes[a].Stretched ? axes[a].FinestPoints : double(axes[a].Points);
  }
  std::array<double, 3> resampled = finest;
  while (resampled[0] * resampled[1] * resampled[2] > double(options.MaximumVoxels))
  {
    int widest = -1;
    double ratio = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      const double r = resampled[a] / lattice.Dimensions[a];
      if (axes[a].Stretched && r > ratio)
      {
        widest = a;
        ratio = r;
      }
    }
    if (widest < 0)
    {
      break; // nothing left to coarsen: CheckFieldSize below says the field is too large
    }
    resampled[widest] = std::max(lattice.Dimensions[widest], std::floor(resampled[widest] * 0.9));
  }
  const auto voxels = [](const std::array<double, 3>& d) { return d[0] * d[1] * d[2]; };
  std::array<double, 3> before = lattice.Dimensions;
  double peak = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    if (axes[a].Stretched)
    {
      std::array<double, 3> after = before;
      after[a] = resampled[a];
      peak = std::max(peak, voxels(before) + voxels(after));
      before = after;
    }
  }
  // The 4 bytes per voxel count the final lattice; the peak beyond it is counted too.
  CheckFieldSize(
    path, resampled, 4.0, options.MaximumVoxels, 4.0 * std::max(0.0, peak - voxels(resampled)));
  return resampled;
}

// The report's line on axis `a`: its dimension, coordinates and how they were found.
std::string DescribeAxis(const ChosenVariable& v, const FileLattice& lattice, int a)
{
  const AxisSampling& axis = lattice.Axes[std::size_t(a)];
  const netcdf::Layout::Axis& identified = v.Layout.Space[std::size_t(a)];
  const netcdf::Variable* coordinate =
    identified.Position >= 0 ? v.File.CoordinateOf(identified.Dimension) : nullptr;
  const std::string coordinateUnits =
    identified.Position >= 0 ? netcdf::CoordinateUnits(v.File, identified.Dimension) : "";
  const std::string& implied = lattice.Implied[std::size_t(a)];
  std::string text = (identified.Position < 0 ? std::string("(none)")
                                              : "\"" + lattice.Names[std::size_t(a)] + "\" (" +
                           "xyz"[a] + " by " + identified.How + ")") +
    ": " + Number(axis.Coordinates.front()) + " .. " + Number(axis.Coordinates.back()) +
    (coordinateUnits.empty() ? "" : " " + coordinateUnits) + ", " +
    std::to_string(axis.Coordinates.size()) + " points" +
    (identified.Position < 0 || coordinate ? ""
        : implied.empty()                  ? " (no coordinate variable: its indices)"
                                           : " (no coordinate variable: " + implied + ")");
  if (axis.Reversed)
  {
    text += ", decreasing in the file (turned around)";
  }
  return text;
}

// The stretched axes resampled onto their regular lattices (ResampledPoints), `density` with
// them, and the report's lines on every axis and on the resampling.
void ResampleStretchedAxes(const ChosenVariable& v,
  FileLattice& lattice,
  vtkSmartPointer<vtkFloatArray>& density,
  std::array<int, 3>& dims,
  FieldReport& report)
{
  std::array<double, 3> finest{};
  const std::array<double, 3> resampled =
    ResampledPoints(v.File.Path(), lattice, v.Options, finest);
  std::vector<std::string> resampling;
  for (int a = 0; a < 3; ++a)
  {
    AxisSampling& axis = lattice.Axes[std::size_t(a)];
    std::string text = DescribeAxis(v, lattice, a);
    if (axis.Stretched)
    {
      axis.Points = int(resampled[a]);
      axis.Spacing = (axis.Coordinates.back() - axis.Coordinates.front()) / double(axis.Points - 1);
      text +=
        ", stretched (steps " + Number(axis.SmallestStep) + " .. " + Number(axis.LargestStep) + ")";
      resampling.push_back(std::string(1, "xyz"[a]) + ": linearly onto " +
        std::to_string(axis.Points) + " regular points " + Number(axis.Spacing) + " apart" +
        (double(axis.Points) == finest[a] ? " (the smallest step of the file)"
                                          : " (coarser than the smallest step, " +
              Number(axis.SmallestStep) + ", which would need " +
              (finest[a] < 1e15 ? std::to_string(std::uint64_t(finest[a])) : Number(finest[a])) +
              " points: field.max_voxels)"));
      density = ResampleAlong(density, dims, a, axis);
    }
    report.Add("axis " + std::string(1, "xyz"[a]), text);
  }
  netcdf::DeclareLengthAndUp(v.File, v.Layout, report);
  if (resampling.empty())
  {
    resampling.push_back("no: the coordinates are evenly spaced");
  }
  for (const std::string& line : resampling)
  {
    report.Add("resampled", line);
  }
}

// The read itself, in the isolated child: the variable chosen, its lattice, its values (in air
// density units when a mixing ratio is converted), the stretched axes resampled, the report.
FieldFileContents ReadChosenVariable(const std::string& path,
  const FieldReadOptions& options,
  const CheckedFile& checked)
{
  const netcdf::File file(path);
  const netcdf::Variable& chosen = netcdf::ChooseVariable(file, options.Array);
  const ChosenVariable v{ file, chosen, netcdf::LayoutOf(file, chosen), options };
  FieldFileContents contents;
  const std::string step = TimeStep(file, chosen, v.Layout, options, contents.Report);
  if (checked.Classic)
  {
    const std::uint64_t end = checked.Header.EndOf(chosen.Name, std::uint64_t(v.Step()));
    if (end > checked.Bytes)
    {
      Fail(path,
        "the values of \"" + chosen.Name + "\" end at byte " + std::to_string(end) +
          " but the file holds " + std::to_string(checked.Bytes) + ": it is truncated");
    }
  }
  FileLattice lattice = LatticeOf(v);
  const std::size_t slabSlices = SlabSlices(v, lattice);
  netcdf::MissingValues missing(file, chosen);
  const ValueSource source{ file,
    chosen,
    v.Layout,
    v.Step(),
    options.Missing.value_or(MissingValueRule::Refuse) == MissingValueRule::Empty,
    slabSlices };
  vtkSmartPointer<vtkFloatArray> density = ReadValues(source, lattice.Axes, missing);

  ReportVariable(v, contents.Report);
  const std::array<AxisSampling, 3>& axes = lattice.Axes;
  const netcdf::FieldLattice onLattice{ file,
    chosen,
    v.Layout,
    v.Step(),
    { { axes[0].Coordinates, axes[1].Coordinates, axes[2].Coordinates } },
    axes[2].Reversed,
    [&](const netcdf::Variable& other)
    { return ReadOnTheFieldsLattice(v, lattice, slabSlices, other); } };
  netcdf::ConvertMixingRatio(onLattice, options, density, contents.Report);
  netcdf::DeclareDroplets(file, chosen, contents.Report);
  if (!step.empty())
  {
    contents.Report.Add("time step", step);
  }
  if (missing.Count() > 0)
  {
    contents.Report.Add("missing",
      Values(missing.Count()) + ", read as empty space (field.missing); marked by " +
        missing.Describe());
  }

  const std::array<double, 3>& d = lattice.Dimensions;
  std::array<int, 3> dims{ { int(d[0]), int(d[1]), int(d[2]) } };
  ResampleStretchedAxes(v, lattice, density, dims, contents.Report);
  auto field = vtkSmartPointer<vtkImageData>::New();
  field->SetExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1);
  field->SetOrigin(axes[0].Origin, axes[1].Origin, axes[2].Origin);
  field->SetSpacing(axes[0].Spacing, axes[1].Spacing, axes[2].Spacing);
  density->SetName(chosen.Name.c_str());
  field->GetPointData()->SetScalars(density);
  contents.Image = field;
  contents.Array = chosen.Name;
  return contents;
}
} // namespace

FieldFileContents ReadNetCdfFile(const std::string& path, const FieldReadOptions& options)
{
  const CheckedFile checked = CheckBeforeTheLibrary(path);
  return ReadInIsolation(path,
    checked.Bytes,
    "the netCDF library",
    [&]() { return ReadChosenVariable(path, options, checked); });
}

} // namespace cloudvis
