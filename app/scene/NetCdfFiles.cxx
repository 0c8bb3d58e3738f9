// The NetCDF reader: one variable at one time step of a file that follows the CF conventions, as
// large-eddy simulations of clouds write them (liquid water, ice, on regular or vertically
// stretched grids, with a time axis), read by VTK's vtkNetCDFCFReader. The netCDF C library (and
// HDF5 under it for netCDF-4 files) parses the file; the whole read, VTK's and the few attribute
// queries made here for the report, runs first in the isolated child (IsolatedRead.h).
//
// Geometry: the reader returns image data when every coordinate is evenly spaced (to 1% of the
// step, VTK's rule) and a rectilinear grid when one is not, as a stretched vertical coordinate
// is. A rectilinear grid is resampled here onto a regular lattice, linearly along each stretched
// axis, at the smallest spacing of that axis (so no level is skipped), with fewer points only
// when field.max_voxels would be exceeded; `info` reports how. Coordinates that decrease (pressure
// levels, latitudes from north to south) are turned around so that the spacing is positive.
// Curvilinear coordinates (2-D latitude and longitude) and data on cells are refused.
#include "FieldFormatReaders.h"

#include "Errors.h"
#include "InputFiles.h"
#include "IsolatedRead.h"
#include "VtkMessageCapture.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNetCDFCFReader.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkRectilinearGrid.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>
#include <vtk_netcdf.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cloudvis
{
namespace
{

// A text attribute of a variable ("" when absent or not text), through the netCDF C API.
class NetCdfAttributes
{
public:
  explicit NetCdfAttributes(const std::string& path)
  {
    if (nc_open(path.c_str(), NC_NOWRITE, &this->Id) != NC_NOERR)
    {
      this->Id = -1;
    }
  }
  ~NetCdfAttributes()
  {
    if (this->Id >= 0)
    {
      nc_close(this->Id);
    }
  }
  NetCdfAttributes(const NetCdfAttributes&) = delete;
  NetCdfAttributes& operator=(const NetCdfAttributes&) = delete;

  std::string Text(const std::string& variable, const char* attribute) const
  {
    int variableId = 0;
    nc_type type = NC_NAT;
    std::size_t length = 0;
    if (this->Id < 0 || nc_inq_varid(this->Id, variable.c_str(), &variableId) != NC_NOERR ||
      nc_inq_att(this->Id, variableId, attribute, &type, &length) != NC_NOERR || type != NC_CHAR ||
      length > 4096)
    {
      return "";
    }
    std::string text(length, '\0');
    if (nc_get_att_text(this->Id, variableId, attribute, &text[0]) != NC_NOERR)
    {
      return "";
    }
    return text.substr(0, text.find('\0'));
  }

  // Bytes per value of a variable's type, 0 when unknown.
  int ValueBytes(const std::string& variable) const
  {
    int variableId = 0;
    nc_type type = NC_NAT;
    std::size_t bytes = 0;
    if (this->Id < 0 || nc_inq_varid(this->Id, variable.c_str(), &variableId) != NC_NOERR ||
      nc_inq_vartype(this->Id, variableId, &type) != NC_NOERR ||
      nc_inq_type(this->Id, type, nullptr, &bytes) != NC_NOERR)
    {
      return 0;
    }
    return int(bytes);
  }

private:
  int Id = -1;
};

// The dimension names of a variable as vtkNetCDFReader lists them ("(z, y, x)", time left out),
// slowest first.
std::vector<std::string> DimensionNames(const std::string& encoded)
{
  std::vector<std::string> names;
  std::string inner = encoded.size() >= 2 ? encoded.substr(1, encoded.size() - 2) : "";
  std::istringstream in(inner);
  for (std::string name; std::getline(in, name, ',');)
  {
    const auto begin = name.find_first_not_of(' ');
    if (begin != std::string::npos)
    {
      names.push_back(name.substr(begin));
    }
  }
  return names;
}

struct Variable
{
  std::string Name;
  std::vector<std::string> Dimensions; // slowest first: (z, y, x)
};

// The variable field.array names, else "density", else the first with three spatial dimensions,
// else the first with two.
Variable ChooseVariable(const std::string& path,
  const std::vector<Variable>& variables,
  const std::string& wanted)
{
  std::string candidates;
  for (const Variable& v : variables)
  {
    if (v.Dimensions.size() >= 2 && v.Dimensions.size() <= 3)
    {
      candidates += (candidates.empty() ? "" : ", ") + v.Name;
    }
  }
  for (const Variable& v : variables)
  {
    if (v.Name == (wanted.empty() ? "density" : wanted))
    {
      if (v.Dimensions.size() < 2 || v.Dimensions.size() > 3)
      {
        Fail(path,
          "variable \"" + v.Name + "\" has " + std::to_string(v.Dimensions.size()) +
            " spatial dimensions; a density field needs 2 or 3 (variables that have: " +
            (candidates.empty() ? "none" : candidates) + ")");
      }
      return v;
    }
  }
  if (!wanted.empty())
  {
    Fail(path,
      "no variable named \"" + wanted + "\" (field.array); variables on 2 or 3 spatial " +
        "dimensions: " + (candidates.empty() ? "none" : candidates));
  }
  for (std::size_t spatial : { 3u, 2u })
  {
    for (const Variable& v : variables)
    {
      if (v.Dimensions.size() == spatial)
      {
        return v;
      }
    }
  }
  Fail(path, "no variable on 2 or 3 spatial dimensions: nothing to read as a density");
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
  double Origin = 0.0;  // of the regular output
  double Spacing = 1.0; // of the regular output
  double SmallestStep = 0.0, LargestStep = 0.0;
};

AxisSampling SampleAxis(const std::string& path, vtkDataArray* coordinates, const std::string& name)
{
  AxisSampling axis;
  const vtkIdType n = coordinates->GetNumberOfTuples();
  for (vtkIdType i = 0; i < n; ++i)
  {
    axis.Coordinates.push_back(coordinates->GetComponent(i, 0));
  }
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
  for (vtkIdType i = 1; i < n; ++i)
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
    axis.Points = int(std::ceil(length / axis.SmallestStep - 1e-9)) + 1;
    axis.Spacing = length / double(axis.Points - 1);
  }
  return axis;
}

// Resamples `values` (dimensions `in`, x fastest) along `axisIndex` from the file's coordinates
// onto the axis's regular lattice, linearly. Axes resampled one after the other give trilinear
// interpolation, the interpolation of a rectilinear grid.
std::vector<float> ResampleAlong(const std::vector<float>& values,
  std::array<int, 3>& dimensions,
  int axisIndex,
  const AxisSampling& axis)
{
  std::array<int, 3> out = dimensions;
  out[axisIndex] = axis.Points;
  std::vector<float> result(std::size_t(out[0]) * out[1] * out[2]);
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
  return result;
}

} // namespace

FieldFileContents ReadNetCdfFile(const std::string& path, const FieldReadOptions& options)
{
  std::uint64_t fileBytes = 0;
  bool classic = false;    // CDF-1, -2 and -5 files hold every value uncompressed
  std::string headerBytes; // of a classic file: its first 16 MiB, more than any header needs
  ClassicHeader header;
  {
    const RegularInputFile file(path, "field");
    fileBytes = file.Size();
    const std::string magic = file.ReadAt(0, 8);
    classic = magic.size() >= 4 && magic.compare(0, 3, "CDF") == 0 &&
      (magic[3] == 1 || magic[3] == 2 || magic[3] == 5);
    if (!classic && magic != "\x89HDF\r\n\x1a\n")
    {
      Fail(path, "not a NetCDF file (it starts with neither \"CDF\" nor the HDF5 signature)");
    }
    if (classic)
    {
      headerBytes = file.ReadAt(0, std::size_t(std::min<std::uint64_t>(fileBytes, 16u << 20)));
      const std::string problem = header.Parse(headerBytes, fileBytes);
      if (!problem.empty())
      {
        Fail(path, "malformed NetCDF header: " + problem);
      }
    }
  }

  const auto read = [&]() -> FieldFileContents
  {
    VtkMessageCapture messages;
    const auto failWithVtk = [&](const std::string& problem)
    {
      const std::string summary = messages.Summary();
      Fail(path, problem + (summary.empty() ? "" : " (VTK: " + summary + ")"));
    };
    vtkNew<vtkNetCDFCFReader> reader;
    reader->SetFileName(path.c_str());
    // Cartesian lattices as the file's coordinates state them: no projection of latitude and
    // longitude onto a sphere, no vertical exaggeration.
    reader->SphericalCoordinatesOff();
    reader->SetVerticalScale(1.0);
    reader->SetVerticalBias(0.0);
    // Missing values become NaN, which ReadField then counts and refuses.
    reader->ReplaceFillValueWithNanOn();
    // The coordinates themselves: VTK makes image data of coordinates even to 1% of a step, which
    // would move points by up to that much; the evenness is judged below, more strictly.
    reader->SetOutputTypeToRectilinear();
    if (!reader->UpdateMetaData() || !messages.Messages().empty())
    {
      failWithVtk("cannot read NetCDF");
    }
    std::vector<Variable> variables;
    vtkStringArray* dimensions = reader->GetVariableDimensions();
    for (int i = 0; i < reader->GetNumberOfVariableArrays(); ++i)
    {
      variables.push_back({ reader->GetVariableArrayName(i),
        i < dimensions->GetNumberOfValues() ? DimensionNames(dimensions->GetValue(i))
                                            : std::vector<std::string>{} });
    }
    const Variable chosen = ChooseVariable(path, variables, options.Array);
    for (const Variable& v : variables)
    {
      reader->SetVariableArrayStatus(v.Name.c_str(), v.Name == chosen.Name ? 1 : 0);
    }
    reader->UpdateInformation();
    vtkInformation* information = reader->GetOutputInformation(0);
    if (reader->GetErrorCode() != 0 || !messages.Messages().empty() || !information ||
      !information->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    {
      failWithVtk("cannot read the variable \"" + chosen.Name + "\"");
    }
    int extent[6];
    information->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
    const std::array<double, 3> fileDimensions{ { double(extent[1]) - extent[0] + 1.0,
      double(extent[3]) - extent[2] + 1.0,
      double(extent[5]) - extent[4] + 1.0 } };
    const NetCdfAttributes attributes(path);
    const int valueBytes = attributes.ValueBytes(chosen.Name);
    // VTK's array of the file's type, a double copy when the variable is packed (scale_factor,
    // add_offset), then the float copy made here.
    CheckFieldSize(
      path, fileDimensions, std::max(valueBytes, 1) + 8.0 + 4.0, options.MaximumVoxels);
    // The time step: field.time_step indexes the file's times (0 when not given).
    FieldFileContents contents;
    const int steps = information->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS())
      ? information->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS())
      : 0;
    const int step = options.TimeStep.value_or(0);
    if (options.TimeStep && step >= std::max(steps, 1))
    {
      Fail(path,
        "field.time_step: " + std::to_string(step) + " is out of range: the file holds " +
          (steps == 0
              ? std::string("no time axis (one step, 0)")
              : std::to_string(steps) + " time steps (0 .. " + std::to_string(steps - 1) + ")"));
    }
    if (classic)
    {
      const std::uint64_t end = header.EndOf(chosen.Name, std::uint64_t(step));
      if (end > fileBytes)
      {
        Fail(path,
          "the values of \"" + chosen.Name + "\" end at byte " + std::to_string(end) +
            " but the file holds " + std::to_string(fileBytes) + ": it is truncated");
      }
    }
    if (steps > 0)
    {
      const double* times = information->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
      reader->UpdateTimeStep(times[step]);
      const char* units = reader->GetTimeUnits();
      contents.Report.Add("time step",
        std::to_string(step) + " of 0 .. " + std::to_string(steps - 1) +
          ": t = " + Number(times[step]) + (units && *units ? " " + std::string(units) : "") +
          (options.TimeStep ? "" : " (the first; field.time_step picks another)"));
    }
    else
    {
      reader->Update();
    }
    if (reader->GetErrorCode() != 0 || !messages.Messages().empty())
    {
      failWithVtk("cannot read the variable \"" + chosen.Name + "\"");
    }

    vtkDataSet* output = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
    vtkDataArray* values = output ? output->GetPointData()->GetArray(chosen.Name.c_str()) : nullptr;
    if (!values)
    {
      if (output && output->GetCellData()->GetArray(chosen.Name.c_str()))
      {
        Fail(path,
          "the variable \"" + chosen.Name +
            "\" is given on cells (its coordinates have "
            "bounds): cloudvis reads values on points only");
      }
      Fail(path,
        "the variable \"" + chosen.Name + "\" is on curvilinear coordinates (" +
          (output ? output->GetClassName() : "no data") +
          "): cloudvis reads regular and rectilinear grids only");
    }
    const std::string units = reader->QueryArrayUnits(chosen.Name.c_str());
    const std::string longName = attributes.Text(chosen.Name, "long_name");
    std::string dimensionsText;
    for (const std::string& d : chosen.Dimensions)
    {
      dimensionsText += (dimensionsText.empty() ? "" : ", ") + d;
    }
    contents.Report.Details.insert(contents.Report.Details.begin(),
      { "variable",
        "\"" + chosen.Name + "\"" + (longName.empty() ? "" : " (" + longName + ")") + " on (" +
          dimensionsText + "), " + TypeInWords(values->GetDataType()) +
          (values->GetDataType() == VTK_FLOAT ? "" : ", converted to float") });
    contents.Report.Details.insert(
      contents.Report.Details.begin() + 1, { "units", units.empty() ? "not stated" : units });

    // The axes, x fastest: NetCDF lists dimensions slowest first.
    const auto dimensionName = [&chosen](int axis) -> std::string
    {
      const int n = int(chosen.Dimensions.size());
      return axis < n ? chosen.Dimensions[std::size_t(n - 1 - axis)] : "";
    };
    std::array<AxisSampling, 3> axes;
    vtkRectilinearGrid* grid = vtkRectilinearGrid::SafeDownCast(output);
    if (!grid)
    {
      Fail(path,
        "the variable \"" + chosen.Name + "\" is on curvilinear coordinates (" +
          output->GetClassName() + "): cloudvis reads regular and rectilinear grids only");
    }
    for (int a = 0; a < 3; ++a)
    {
      vtkDataArray* coordinates = a == 0 ? grid->GetXCoordinates()
        : a == 1                         ? grid->GetYCoordinates()
                                         : grid->GetZCoordinates();
      if (!coordinates || coordinates->GetNumberOfTuples() != vtkIdType(fileDimensions[a]))
      {
        Fail(path, "VTK's reader returned no coordinates for axis " + std::string(1, "xyz"[a]));
      }
      axes[a] = SampleAxis(path, coordinates, dimensionName(a));
    }

    // The values, float, x fastest, with decreasing axes turned around.
    std::array<int, 3> dims{
      { int(fileDimensions[0]), int(fileDimensions[1]), int(fileDimensions[2]) }
    };
    vtkSmartPointer<vtkFloatArray> floats = ToFloat(path, values, chosen.Name);
    std::vector<float> data(
      floats->GetPointer(0), floats->GetPointer(0) + floats->GetNumberOfValues());
    floats = nullptr;
    if (axes[0].Reversed || axes[1].Reversed || axes[2].Reversed)
    {
      std::vector<float> turned(data.size());
      for (int k = 0; k < dims[2]; ++k)
        for (int j = 0; j < dims[1]; ++j)
          for (int i = 0; i < dims[0]; ++i)
          {
            const int si = axes[0].Reversed ? dims[0] - 1 - i : i;
            const int sj = axes[1].Reversed ? dims[1] - 1 - j : j;
            const int sk = axes[2].Reversed ? dims[2] - 1 - k : k;
            turned[(std::size_t(k) * dims[1] + j) * dims[0] + i] =
              data[(std::size_t(sk) * dims[1] + sj) * dims[0] + si];
          }
      data.swap(turned);
    }

    // Stretched axes: their regular lattice, coarser if field.max_voxels requires it.
    std::array<double, 3> resampled{
      { double(axes[0].Points), double(axes[1].Points), double(axes[2].Points) }
    };
    std::array<int, 3> finest{ { axes[0].Points, axes[1].Points, axes[2].Points } };
    while (resampled[0] * resampled[1] * resampled[2] > double(options.MaximumVoxels))
    {
      int widest = -1;
      double ratio = 1.0;
      for (int a = 0; a < 3; ++a)
      {
        const double r = resampled[a] / fileDimensions[a];
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
      resampled[widest] = std::max(fileDimensions[widest], std::floor(resampled[widest] * 0.9));
    }
    CheckFieldSize(path, resampled, 4.0, options.MaximumVoxels);
    std::vector<std::string> resampling;
    for (int a = 0; a < 3; ++a)
    {
      AxisSampling& axis = axes[a];
      const std::string name = dimensionName(a);
      const std::string coordinateUnits = name.empty() ? "" : attributes.Text(name, "units");
      std::string text = (name.empty() ? std::string("(none)") : "\"" + name + "\"") + ": " +
        Number(axis.Coordinates.front()) + " .. " + Number(axis.Coordinates.back()) +
        (coordinateUnits.empty() ? "" : " " + coordinateUnits) + ", " +
        std::to_string(axis.Coordinates.size()) + " points";
      if (axis.Reversed)
      {
        text += ", decreasing in the file (turned around)";
      }
      if (axis.Stretched)
      {
        axis.Points = int(resampled[a]);
        axis.Spacing =
          (axis.Coordinates.back() - axis.Coordinates.front()) / double(axis.Points - 1);
        text += ", stretched (steps " + Number(axis.SmallestStep) + " .. " +
          Number(axis.LargestStep) + ")";
        resampling.push_back(std::string(1, "xyz"[a]) + ": linearly onto " +
          std::to_string(axis.Points) + " regular points " + Number(axis.Spacing) + " apart" +
          (axis.Points == finest[a]
              ? " (the smallest step of the file)"
              : " (coarser than the smallest step, " + Number(axis.SmallestStep) +
                ", which would need " + std::to_string(finest[a]) + " points: field.max_voxels)"));
        data = ResampleAlong(data, dims, a, axis);
      }
      contents.Report.Add("axis " + std::string(1, "xyz"[a]), text);
    }
    if (resampling.empty())
    {
      resampling.push_back("no: the coordinates are evenly spaced");
    }
    for (const std::string& line : resampling)
    {
      contents.Report.Add("resampled", line);
    }

    auto field = vtkSmartPointer<vtkImageData>::New();
    field->SetExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1);
    field->SetOrigin(axes[0].Origin, axes[1].Origin, axes[2].Origin);
    field->SetSpacing(axes[0].Spacing, axes[1].Spacing, axes[2].Spacing);
    vtkNew<vtkFloatArray> density;
    density->SetName(chosen.Name.c_str());
    density->SetNumberOfTuples(vtkIdType(data.size()));
    std::copy(data.begin(), data.end(), density->GetPointer(0));
    field->GetPointData()->SetScalars(density);
    contents.Image = field;
    contents.Array = chosen.Name;
    return contents;
  };
  return ReadInIsolation(path, fileBytes, "VTK's NetCDF reader", read);
}

} // namespace cloudvis
