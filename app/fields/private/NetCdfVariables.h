// What the NetCDF reader (NetCdfFiles.cxx) asks of a file, through the netCDF C API, and what the
// CF conventions make of the answers: the variables in file order with their dimensions, types
// and attributes; which variable is the density by default; which dimension of a variable is its
// time axis and which is its x, y and z (and by what evidence); which values the variable marks
// as missing (_FillValue, missing_value, valid_min, valid_max, valid_range) and how it is packed
// (scale_factor, add_offset). Every library error becomes an InputError naming the file, in
// words: a netCDF-4 file that HDF5 cannot read is "damaged or truncated", not "HDF error". Only
// the root group is read (CF files keep their variables there).
#ifndef cloudvis_NetCdfVariables_h
#define cloudvis_NetCdfVariables_h

#include "FieldIO.h" // FieldReport

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

class vtkFloatArray;

namespace cloudvis
{
namespace netcdf
{

struct Dimension
{
  std::string Name;
  std::size_t Length = 0;
  bool Unlimited = false;
};

struct Variable
{
  int Id = -1;
  std::string Name;
  int Type = 0;                // nc_type
  std::vector<int> Dimensions; // ids, slowest first as the file lists them
};

// An open file (closed when this goes), read-only.
class File
{
public:
  // Throws InputError naming `path` when the library cannot open it.
  explicit File(const std::string& path);
  ~File();
  File(const File&) = delete;
  File& operator=(const File&) = delete;

  const std::string& Path() const { return this->Name; }
  // The variables of the root group in the order the file defines them.
  const std::vector<Variable>& Variables() const { return this->All; }
  const Variable* Find(const std::string& name) const;
  const Dimension& DimensionOf(int id) const;
  // The coordinate variable of a dimension (CF: one-dimensional, numeric, named as the dimension);
  // nullptr when there is none.
  const Variable* CoordinateOf(int dimension) const;

  // A text attribute, "" when absent or not text.
  std::string Text(const Variable& variable, const char* attribute) const;
  // A numeric attribute's values; empty when absent or not numeric.
  std::vector<double> Numbers(const Variable& variable, const char* attribute) const;
  // A numeric attribute's values, which the CF rules read as numbers: empty when absent; an
  // attribute of another type (text, a string), or with fewer than `least` or more than `most`
  // values, is refused naming the file, the variable, the attribute, its type and length
  // (`meaning` says what the attribute is for: "a missing-value marker").
  std::vector<double> CheckedNumbers(const Variable& variable,
    const char* attribute,
    std::size_t least,
    std::size_t most,
    const std::string& meaning) const;
  bool Has(const Variable& variable, const char* attribute) const;

  // The values of `variable` in the box `start`, `count` (one entry per dimension), whatever the
  // variable's numeric type, converted to double by the library, `values` holding the product of
  // `count`. Throws InputError in words when the library cannot read them.
  void Read(const Variable& variable,
    const std::vector<std::size_t>& start,
    const std::vector<std::size_t>& count,
    double* values) const;
  // The values of a coordinate variable, unpacked (scale_factor, add_offset).
  std::vector<double> Coordinates(const Variable& variable) const;
  // The length of a chunk along the variable's dimension at `position`; 0 when the variable is
  // not chunked (classic files, contiguous netCDF-4 variables).
  std::size_t ChunkLength(const Variable& variable, int position) const;

private:
  [[noreturn]] void Fail(int status, const std::string& doing) const;

  std::string Name;
  int Id = -1;
  std::vector<Variable> All;
  std::vector<std::pair<int, Dimension>> Dimensions;
};

// Whether values of the type read as numbers (every integer and floating-point type of netCDF-3
// and -4; not char, string, or the user-defined types of netCDF-4); and the type in CDL's words
// ("ubyte", "int64").
bool IsNumeric(int type);
std::string TypeName(int type);

// A dimension's meaning for a variable.
enum class Role
{
  Unknown,
  X,
  Y,
  Z,
  Time
};

// What a variable's dimensions mean: at most one time axis, and x, y and z for the others. Each
// dimension's role comes from its coordinate variable's `axis` attribute, else its standard_name,
// else its units (degrees_east, degrees_north, a pressure, a time "since" a date) or `positive`
// attribute, else the dimension's name (x, lon..., y, lat..., z, lev..., height, altitude, time,
// and the names of WRF and common LES codes); a dimension that none of them identifies takes a
// spatial axis left free by position (the fastest x, then y, then z), and an unidentified leading
// record (unlimited) dimension is the time axis.
struct Layout
{
  struct Axis
  {
    int Position = -1;  // in the variable's dimension list
    int Dimension = -1; // its id
    std::string How;    // "its name", "its coordinate's axis attribute \"Z\"", ...
  };
  Axis Time;                 // Position -1: no time axis
  std::array<Axis, 3> Space; // x, y, z; Position -1: the variable has no such dimension
  int SpatialDimensions = 0;
  std::string Problem; // why the variable cannot be a density field; empty when it can
};
Layout LayoutOf(const File& file, const Variable& variable);

// The variable `wanted` names (field.array); when empty, the one named "density", else the
// cloud's liquid water among the data variables (not coordinate, auxiliary coordinate or bounds
// variables) that can be a density (numeric, on 2 or 3 spatial dimensions): by the first of
// the CF standard names of liquid water, else the first of the LES codes' names for it (ql, qc,
// QCLOUD, ...), so that an LES file's wind and temperature are passed over; else the first of
// them in file order. Throws InputError naming
// the file and, for a refused choice, why it cannot be read and which variables can.
const Variable& ChooseVariable(const File& file, const std::string& wanted);

// The CF markers of missing values of a variable, compared with its packed values: _FillValue
// (or, without one, the netCDF default fill value of the type, which is what never-written values
// hold; not for byte types, whose default fill is a legal value), missing_value (one or several),
// and values outside valid_min, valid_max or valid_range. A NaN marker matches NaN.
class MissingValues
{
public:
  MissingValues(const File& file, const Variable& variable);

  // The index of the first marker `packed` matches, or -1 when it is a value. Counts it.
  int Match(double packed);
  // The number of values matched so far.
  std::uint64_t Count() const;
  // "_FillValue -999" or "3 _FillValue -999, 9 below valid_min 0": the markers that matched.
  std::string Describe() const;

private:
  struct Marker
  {
    std::string Text;
    double Value = 0.0;                                    // for an equality
    double Low = -std::numeric_limits<double>::infinity(); // for a range: values below are missing
    double High = std::numeric_limits<double>::infinity(); // values above are missing
    bool Range = false;
    std::uint64_t Count = 0;
  };
  std::vector<Marker> Markers;
  bool Float = false; // the variable is float: markers compare as floats
};

// scale_factor and add_offset (1 and 0 when absent): value = packed * Scale + Offset.
struct Packing
{
  double Scale = 1.0;
  double Offset = 0.0;
  bool Packed = false;
};
Packing PackingOf(const File& file, const Variable& variable);

// The droplets a variable declares, into FieldReport::Units: the numeric attributes
// `effective_radius` (one value in micrometres in [0.001, 1000000]) and `droplet_number` (one
// value per cm^3 in [DropletNumberMin, DropletNumberMax]), each refused out of range.
void DeclareDroplets(const File& file, const Variable& variable, FieldReport& report);

// What the file declares of its physical units (FieldReport::Units), each with a line in the
// report, beyond the quantity of the variable's `units` (DeclareQuantityOfUnits,
// FieldFormatReaders.h; a mixing ratio is ConvertMixingRatio's, NetCdfAirDensity.h): the length
// unit the spatial axes' coordinates share and the vertical axis (z, where the file identifies a
// height axis).
void DeclareLengthAndUp(const File& file, const Layout& layout, FieldReport& report);

// Coordinates a file implies for a dimension without a coordinate variable, as WRF writes its
// grid: west_east and south_north at the global attributes DX and DY (metres) apart from 0, and
// bottom_top at the heights of its mass levels, halfway between the staggered levels'
// geopotential heights (PH + PHB) / g averaged over the domain at time step `step` (terrain-
// following levels are read as flat). Empty when the file implies none; with `read` false, only
// whether it would (Coordinates left empty).
struct ImpliedAxis
{
  std::vector<double> Coordinates;
  std::string Units; // "m"
  std::string How;   // "WRF's DX", for the report
};
std::optional<ImpliedAxis> ImpliedCoordinates(const File& file,
  int dimension,
  std::size_t step,
  bool read = true);

// The units of a dimension's coordinates: its coordinate variable's `units`, else those of the
// coordinates the file implies, else "".
std::string CoordinateUnits(const File& file, int dimension);

// Why the z axis of a variable's layout is not a height (empty when it is): the variable has none,
// no dimension is identified as vertical (z is its third by position), or its coordinate is a
// pressure, or positive down.
std::string WhyZIsNotAHeight(const File& file, const Layout& layout);

} // namespace netcdf
} // namespace cloudvis

#endif
