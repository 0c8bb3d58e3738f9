// The netCDF C API and the CF conventions as the NetCDF reader uses them (NetCdfVariables.h).
// cloudvis reads the variable itself rather than through VTK's vtkNetCDFCFReader: the library
// converts every numeric type (VTK 9.1's reader knows the classic types only and refused ubyte
// and int64), lists variables in file order (VTK sorts them by name), and the CF rules that turn
// stored numbers into densities (missing values in every marking, packing, which dimension is
// which axis) are applied here, in one place, where VTK applied some of them to some types.
#include "NetCdfVariables.h"

#include "FieldFormatReaders.h"

#include <vtkFloatArray.h>
#include <vtk_netcdf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <sstream>

namespace cloudvis
{
namespace netcdf
{

// ---- the file -----------------------------------------------------------------------------------

File::File(const std::string& path)
  : Name(path)
{
  int status = nc_open(path.c_str(), NC_NOWRITE, &this->Id);
  if (status != NC_NOERR)
  {
    this->Id = -1;
    this->Fail(status, "open it");
  }
  // A constructor that throws runs no destructor: whatever fails from here on (the library, or
  // memory), the file is closed before the error leaves.
  try
  {
    int dimensions = 0, variables = 0, unlimited = -1;
    status = nc_inq(this->Id, &dimensions, &variables, nullptr, &unlimited);
    std::vector<int> ids(std::size_t(std::max(dimensions, 0)));
    if (status == NC_NOERR && dimensions > 0)
    {
      status = nc_inq_dimids(this->Id, &dimensions, ids.data(), 0);
    }
    for (std::size_t d = 0; status == NC_NOERR && d < ids.size(); ++d)
    {
      char name[NC_MAX_NAME + 1] = {};
      Dimension dimension;
      status = nc_inq_dim(this->Id, ids[d], name, &dimension.Length);
      dimension.Name = name;
      dimension.Unlimited = ids[d] == unlimited;
      this->Dimensions.emplace_back(ids[d], dimension);
    }
    // nc_inq_varids lists the variables in the order the file defines them.
    ids.assign(std::size_t(std::max(variables, 0)), 0);
    if (status == NC_NOERR && variables > 0)
    {
      status = nc_inq_varids(this->Id, &variables, ids.data());
    }
    for (std::size_t v = 0; status == NC_NOERR && v < ids.size(); ++v)
    {
      char name[NC_MAX_NAME + 1] = {};
      int count = 0;
      Variable variable;
      variable.Id = ids[v];
      status = nc_inq_varndims(this->Id, ids[v], &count);
      if (status == NC_NOERR && (count < 0 || count > NC_MAX_VAR_DIMS))
      {
        status = NC_EMAXDIMS; // the library's own limit, which nc_inq_var would write beyond
      }
      variable.Dimensions.assign(std::size_t(std::clamp(count, 0, NC_MAX_VAR_DIMS)), 0);
      if (status == NC_NOERR)
      {
        status = nc_inq_var(
          this->Id, ids[v], name, &variable.Type, nullptr, variable.Dimensions.data(), nullptr);
      }
      variable.Name = name;
      this->All.push_back(variable);
    }
    if (status != NC_NOERR)
    {
      this->Fail(status, "list its dimensions and variables");
    }
  }
  catch (...)
  {
    nc_close(this->Id);
    throw;
  }
}

File::~File()
{
  if (this->Id >= 0)
  {
    nc_close(this->Id);
  }
}

void File::Fail(int status, const std::string& doing) const
{
  const std::string library = std::string(" (the netCDF library: ") + nc_strerror(status) + ")";
  switch (status)
  {
    // The HDF5 layer of a netCDF-4 file: the structures it found do not hold together.
    case NC_EHDFERR:
    case NC_EFILEMETA:
    case NC_EDIMMETA:
    case NC_EATTMETA:
    case NC_EVARMETA:
    case NC_ETRUNC:
    case NC_EIO:
      cloudvis::Fail(
        this->Name, "cannot " + doing + ": the file is damaged or truncated" + library);
    case NC_ENOTNC:
      cloudvis::Fail(this->Name, "not a NetCDF file the netCDF library can read" + library);
    case NC_EFILTER:
    case NC_ENOFILTER:
      cloudvis::Fail(this->Name,
        "cannot " + doing + ": the values are compressed with a filter this netCDF library " +
          "does not have" + library);
    case NC_ENOMEM:
      cloudvis::Fail(this->Name, "cannot " + doing + ": not enough memory" + library);
    default:
      // What the library refuses when it opens a file (sizes beyond the format's, counts that
      // do not fit) is in the file.
      cloudvis::Fail(
        this->Name, "cannot " + doing + (this->Id < 0 ? ": the file is malformed" : "") + library);
  }
}

const Variable* File::Find(const std::string& name) const
{
  for (const Variable& v : this->All)
  {
    if (v.Name == name)
    {
      return &v;
    }
  }
  return nullptr;
}

const Dimension& File::DimensionOf(int id) const
{
  for (const auto& d : this->Dimensions)
  {
    if (d.first == id)
    {
      return d.second;
    }
  }
  // A variable of the root group uses dimensions of the root group (or of none, netCDF-4 groups
  // aside, which CF files do not use for the data read here).
  cloudvis::Fail(this->Name,
    "a variable uses dimension " + std::to_string(id) + ", which is not one of the root group's");
}

const Variable* File::CoordinateOf(int dimension) const
{
  const Variable* v = this->Find(this->DimensionOf(dimension).Name);
  return v && v->Dimensions.size() == 1 && v->Dimensions[0] == dimension && IsNumeric(v->Type)
    ? v
    : nullptr;
}

std::string File::Text(const Variable& variable, const char* attribute) const
{
  nc_type type = NC_NAT;
  std::size_t length = 0;
  if (nc_inq_att(this->Id, variable.Id, attribute, &type, &length) != NC_NOERR || type != NC_CHAR ||
    length > 4096)
  {
    return "";
  }
  std::string text(length, '\0');
  if (length > 0 && nc_get_att_text(this->Id, variable.Id, attribute, &text[0]) != NC_NOERR)
  {
    return "";
  }
  return text.substr(0, text.find('\0'));
}

std::vector<double> File::Numbers(const Variable& variable, const char* attribute) const
{
  nc_type type = NC_NAT;
  std::size_t length = 0;
  if (nc_inq_att(this->Id, variable.Id, attribute, &type, &length) != NC_NOERR ||
    !IsNumeric(type) || length == 0 || length > 4096)
  {
    return {};
  }
  std::vector<double> values(length);
  return nc_get_att_double(this->Id, variable.Id, attribute, values.data()) == NC_NOERR
    ? values
    : std::vector<double>{};
}

std::vector<double> File::CheckedNumbers(const Variable& variable,
  const char* attribute,
  std::size_t least,
  std::size_t most,
  const std::string& meaning) const
{
  nc_type type = NC_NAT;
  std::size_t length = 0;
  if (nc_inq_att(this->Id, variable.Id, attribute, &type, &length) != NC_NOERR)
  {
    return {};
  }
  const std::string where = "variable \"" + variable.Name + "\": attribute " + attribute;
  if (!IsNumeric(type))
  {
    const std::string text = type == NC_CHAR ? this->Text(variable, attribute) : "";
    cloudvis::Fail(this->Name,
      where + " is " +
        (type == NC_CHAR ? "text (\"" + text.substr(0, 64) + "\")" : WithArticle(TypeName(type))) +
        ", not a number: as " + meaning +
        " it must be numeric (CF), and read as text it would "
        "be ignored");
  }
  if (length < least || length > most)
  {
    cloudvis::Fail(this->Name,
      where + " has " + std::to_string(length) + (length == 1 ? " value" : " values") + ", " +
        (least == most ? std::to_string(least)
                       : std::to_string(least) + " to " + std::to_string(most)) +
        " expected: as " + meaning + " (CF) " +
        (least == most && least == 1 ? "it is one number" : "it holds that many"));
  }
  std::vector<double> values(length);
  if (nc_get_att_double(this->Id, variable.Id, attribute, values.data()) != NC_NOERR)
  {
    cloudvis::Fail(this->Name, "cannot read " + where);
  }
  return values;
}

bool File::Has(const Variable& variable, const char* attribute) const
{
  return nc_inq_attid(this->Id, variable.Id, attribute, nullptr) == NC_NOERR;
}

void File::Read(const Variable& variable,
  const std::vector<std::size_t>& start,
  const std::vector<std::size_t>& count,
  double* values) const
{
  // NC_ERANGE cannot happen: every numeric type fits a double.
  const int status = nc_get_vara_double(this->Id, variable.Id, start.data(), count.data(), values);
  if (status != NC_NOERR)
  {
    this->Fail(status, "read the values of \"" + variable.Name + "\"");
  }
}

std::vector<double> File::Coordinates(const Variable& variable) const
{
  std::vector<double> values(this->DimensionOf(variable.Dimensions.at(0)).Length);
  if (!values.empty())
  {
    this->Read(variable, { 0 }, { values.size() }, values.data());
  }
  const Packing packing = PackingOf(*this, variable);
  for (double& value : values)
  {
    value = value * packing.Scale + packing.Offset;
  }
  return values;
}

std::size_t File::ChunkLength(const Variable& variable, int position) const
{
  int storage = NC_CONTIGUOUS;
  std::vector<std::size_t> chunks(variable.Dimensions.size());
  if (chunks.empty() ||
    nc_inq_var_chunking(this->Id, variable.Id, &storage, chunks.data()) != NC_NOERR ||
    storage != NC_CHUNKED)
  {
    return 0;
  }
  return chunks[std::size_t(position)];
}

bool IsNumeric(int type)
{
  switch (type)
  {
    case NC_BYTE:
    case NC_UBYTE:
    case NC_SHORT:
    case NC_USHORT:
    case NC_INT:
    case NC_UINT:
    case NC_INT64:
    case NC_UINT64:
    case NC_FLOAT:
    case NC_DOUBLE:
      return true;
    default:
      return false;
  }
}

std::string TypeName(int type)
{
  static const char* const names[] = { "",
    "byte",
    "char",
    "short",
    "int",
    "float",
    "double",
    "ubyte",
    "ushort",
    "uint",
    "int64",
    "uint64",
    "string" };
  return type > 0 && type <= NC_STRING ? names[type]
                                       : "a user-defined type (compound, enum, opaque or vlen)";
}

// ---- roles of dimensions ------------------------------------------------------------------------

namespace
{

std::string Lower(std::string text)
{
  std::transform(
    text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

bool StartsWith(const std::string& text, const std::string& prefix)
{
  return text.compare(0, prefix.size(), prefix) == 0;
}

bool OneOf(const std::string& text, std::initializer_list<const char*> words)
{
  return std::any_of(words.begin(), words.end(), [&text](const char* w) { return text == w; });
}

struct Identified
{
  Role Is = Role::Unknown;
  std::string How;
};

Role RoleOfUnits(const std::string& units)
{
  const std::string u = Lower(units);
  if (u.find(" since ") != std::string::npos)
  {
    return Role::Time;
  }
  // CF 4.1 and 4.2: the spellings of degrees east and north.
  if (OneOf(u, { "degrees_east", "degree_east", "degree_e", "degrees_e", "degreee", "degreese" }))
  {
    return Role::X;
  }
  if (OneOf(u, { "degrees_north", "degree_north", "degree_n", "degrees_n", "degreen", "degreesn" }))
  {
    return Role::Y;
  }
  // CF 4.3: a pressure is a vertical coordinate.
  if (OneOf(u, { "pa", "hpa", "kpa", "mbar", "millibar", "bar", "decibar", "dbar", "atm", "mb" }))
  {
    return Role::Z;
  }
  return Role::Unknown;
}

Role RoleOfStandardName(const std::string& name)
{
  if (name == "time")
  {
    return Role::Time;
  }
  if (OneOf(name, { "longitude", "grid_longitude", "projection_x_coordinate" }))
  {
    return Role::X;
  }
  if (OneOf(name, { "latitude", "grid_latitude", "projection_y_coordinate" }))
  {
    return Role::Y;
  }
  if (OneOf(name, { "altitude", "height", "depth", "air_pressure", "model_level_number" }) ||
    StartsWith(name, "height_above") || StartsWith(name, "atmosphere_") ||
    StartsWith(name, "ocean_"))
  {
    return Role::Z;
  }
  return Role::Unknown;
}

// Names of dimensions in the files of atmospheric models: CF's usual ones, WRF's (west_east,
// south_north, bottom_top and their _stag), and the staggered names of LES codes (xt, xm, zt, zm
// in UCLA-LES, DALES and MicroHH).
Role RoleOfName(const std::string& dimension)
{
  const std::string n = Lower(dimension);
  if (OneOf(n, { "time", "t", "times" }))
  {
    return Role::Time;
  }
  if (OneOf(n, { "x", "xt", "xm", "xc", "xh", "xu", "xf", "nx", "lon" }) || StartsWith(n, "x_") ||
    StartsWith(n, "lon") || StartsWith(n, "west_east"))
  {
    return Role::X;
  }
  if (OneOf(n, { "y", "yt", "ym", "yc", "yh", "yv", "yf", "ny", "lat" }) || StartsWith(n, "y_") ||
    StartsWith(n, "lat") || StartsWith(n, "south_north"))
  {
    return Role::Y;
  }
  if (OneOf(n,
        { "z",
          "zt",
          "zm",
          "zc",
          "zh",
          "zw",
          "zf",
          "zu",
          "nz",
          "alt",
          "p",
          "pres",
          "plev",
          "sigma",
          "depth" }) ||
    StartsWith(n, "z_") || StartsWith(n, "zu_") || StartsWith(n, "zw_") || // PALM: zu_3d, zw_3d
    StartsWith(n, "lev") || StartsWith(n, "height") || StartsWith(n, "altitude") ||
    StartsWith(n, "pressure") || StartsWith(n, "bottom_top"))
  {
    return Role::Z;
  }
  return Role::Unknown;
}

Identified Identify(const File& file, int dimension)
{
  if (const Variable* c = file.CoordinateOf(dimension))
  {
    const std::string axis = Lower(file.Text(*c, "axis"));
    const Role byAxis = axis == "x" ? Role::X
      : axis == "y"                 ? Role::Y
      : axis == "z"                 ? Role::Z
      : axis == "t"                 ? Role::Time
                                    : Role::Unknown;
    if (byAxis != Role::Unknown)
    {
      return { byAxis, "its coordinate's axis attribute \"" + file.Text(*c, "axis") + "\"" };
    }
    const std::string standardName = file.Text(*c, "standard_name");
    if (const Role r = RoleOfStandardName(Lower(standardName)); r != Role::Unknown)
    {
      return { r, "its coordinate's standard_name \"" + standardName + "\"" };
    }
    const std::string units = file.Text(*c, "units");
    if (const Role r = RoleOfUnits(units); r != Role::Unknown)
    {
      return { r, "its coordinate's units \"" + units + "\"" };
    }
    const std::string positive = Lower(file.Text(*c, "positive"));
    if (positive == "up" || positive == "down")
    {
      return { Role::Z, "its coordinate's positive attribute \"" + positive + "\"" };
    }
  }
  if (const Role r = RoleOfName(file.DimensionOf(dimension).Name); r != Role::Unknown)
  {
    return { r, "its name" };
  }
  return {};
}

const char* const AxisNames[] = { "x", "y", "z" };

} // namespace

Layout LayoutOf(const File& file, const Variable& variable)
{
  Layout layout;
  const auto problem = [&layout](const std::string& text)
  {
    if (layout.Problem.empty())
    {
      layout.Problem = text;
    }
  };
  if (!IsNumeric(variable.Type))
  {
    problem("is of type " + TypeName(variable.Type) + ", not numbers");
  }
  const int n = int(variable.Dimensions.size());
  std::vector<Identified> roles;
  for (int p = 0; p < n; ++p)
  {
    roles.push_back(Identify(file, variable.Dimensions[std::size_t(p)]));
    if (roles.back().Is == Role::Unknown && p == 0 && n > 2 &&
      file.DimensionOf(variable.Dimensions[0]).Unlimited)
    {
      roles.back() = { Role::Time, "it is the record (unlimited) dimension" };
    }
  }
  std::vector<int> unknown; // positions of spatial dimensions nothing identifies, fastest first
  for (int p = n - 1; p >= 0; --p)
  {
    const Identified& role = roles[std::size_t(p)];
    const Layout::Axis axis{ p, variable.Dimensions[std::size_t(p)], role.How };
    const std::string name = "\"" + file.DimensionOf(axis.Dimension).Name + "\"";
    if (role.Is == Role::Time)
    {
      if (layout.Time.Position >= 0)
      {
        problem("has two time dimensions, " + name + " and \"" +
          file.DimensionOf(layout.Time.Dimension).Name + "\"");
      }
      layout.Time = axis;
      continue;
    }
    ++layout.SpatialDimensions;
    if (role.Is == Role::Unknown)
    {
      unknown.push_back(p);
      continue;
    }
    Layout::Axis& slot = layout.Space[std::size_t(int(role.Is) - int(Role::X))];
    if (slot.Position >= 0)
    {
      problem("has two dimensions that are its " +
        std::string(AxisNames[int(role.Is) - int(Role::X)]) + " axis: " + name + " (by " +
        role.How + ") and \"" + file.DimensionOf(slot.Dimension).Name + "\" (by " + slot.How + ")");
    }
    slot = axis;
  }
  if (layout.SpatialDimensions < 2 || layout.SpatialDimensions > 3)
  {
    problem("has " + std::to_string(layout.SpatialDimensions) +
      " spatial dimensions; a density field needs 2 or 3");
    return layout;
  }
  // The others by position: CF orders dimensions T, Z, Y, X, so the fastest free one is x.
  for (const int p : unknown)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (layout.Space[std::size_t(a)].Position < 0)
      {
        layout.Space[std::size_t(a)] = { p,
          variable.Dimensions[std::size_t(p)],
          "position (nothing in the file names it; dimensions are taken as ordered z, y, x)" };
        break;
      }
    }
  }
  // Auxiliary coordinates of two or more of its dimensions (2-D latitude and longitude) make
  // the grid curvilinear: its points are not where a lattice puts them.
  std::istringstream names(file.Text(variable, "coordinates"));
  for (std::string name; names >> name;)
  {
    const Variable* auxiliary = file.Find(name);
    if (auxiliary && auxiliary->Dimensions.size() >= 2)
    {
      problem("is on curvilinear coordinates (\"" + name + "\" of its `coordinates` attribute " +
        "has " + std::to_string(auxiliary->Dimensions.size()) +
        " dimensions): cloudvis reads regular and rectilinear grids only");
    }
  }
  return layout;
}

namespace
{

// The CF standard names and the names of LES codes (DALES, MicroHH, PALM, SAM, WRF, UCLA-LES) of
// the cloud's liquid water, likeliest first.
const std::vector<std::string>& CloudWaterStandardNames()
{
  static const std::vector<std::string> names = { "mass_fraction_of_cloud_liquid_water_in_air",
    "cloud_liquid_water_mixing_ratio",
    "mass_concentration_of_cloud_liquid_water_in_air" };
  return names;
}

const std::vector<std::string>& CloudWaterNames()
{
  // DALES, MicroHH, PALM: ql; many codes: qc, qcl; SAM: QN (liquid and ice); WRF: QCLOUD;
  // UCLA-LES: l; and liquid water contents.
  static const std::vector<std::string> names = {
    "ql", "qc", "qcl", "QN", "QCLOUD", "QC", "l", "lwc", "LWC"
  };
  return names;
}
} // namespace

const Variable& ChooseVariable(const File& file, const std::string& wanted)
{
  // Variables that describe others: coordinates (named as their dimension), auxiliary
  // coordinates (in a `coordinates` attribute) and cell bounds (`bounds`, `climatology`).
  std::vector<std::string> describing;
  for (const Variable& v : file.Variables())
  {
    if (v.Dimensions.size() == 1 && file.DimensionOf(v.Dimensions[0]).Name == v.Name)
    {
      describing.push_back(v.Name);
    }
    for (const char* attribute : { "coordinates", "bounds", "climatology" })
    {
      std::istringstream names(file.Text(v, attribute));
      for (std::string name; names >> name;)
      {
        describing.push_back(name);
      }
    }
  }
  std::string candidates, problems;
  const Variable* first = nullptr;
  const Variable* cloudWater = nullptr;
  int cloudWaterRank = 0; // a lower rank is the likelier cloud water: standard names, then names
  for (const Variable& v : file.Variables())
  {
    if (std::find(describing.begin(), describing.end(), v.Name) != describing.end())
    {
      continue;
    }
    const std::string problem = LayoutOf(file, v).Problem;
    if (problem.empty())
    {
      candidates += (candidates.empty() ? "" : ", ") + v.Name;
      first = first ? first : &v;
      const std::string standard = file.Text(v, "standard_name");
      const auto& standards = CloudWaterStandardNames();
      const auto& names = CloudWaterNames();
      const auto byStandard = std::find(standards.begin(), standards.end(), standard);
      const auto byName = std::find(names.begin(), names.end(), v.Name);
      const int rank = byStandard != standards.end() ? int(byStandard - standards.begin()) + 1
        : byName != names.end() ? int(standards.size() + (byName - names.begin())) + 1
                                : 0;
      if (rank > 0 && (!cloudWater || rank < cloudWaterRank))
      {
        cloudWater = &v;
        cloudWaterRank = rank;
      }
    }
    else if (v.Dimensions.size() >= 2)
    {
      problems += "; variable \"" + v.Name + "\" " + problem;
    }
  }
  const std::string readable = candidates.empty() ? "none" : candidates;
  if (const Variable* named = file.Find(wanted.empty() ? "density" : wanted))
  {
    const Layout layout = LayoutOf(file, *named);
    if (!layout.Problem.empty())
    {
      cloudvis::Fail(file.Path(),
        "variable \"" + named->Name + "\"" + (wanted.empty() ? "" : " (field.array)") + " " +
          layout.Problem + " (variables that can be read as a density: " + readable + ")");
    }
    return *named;
  }
  if (!wanted.empty())
  {
    cloudvis::Fail(file.Path(),
      "no variable named \"" + wanted +
        "\" (field.array); variables that can be read as a density: " + readable);
  }
  if (!first)
  {
    cloudvis::Fail(file.Path(),
      "no variable can be read as a density (numbers on 2 or 3 spatial dimensions)" + problems);
  }
  return cloudWater ? *cloudWater : *first;
}

// ---- missing values and packing ---------------------------------------------------------------

MissingValues::MissingValues(const File& file, const Variable& variable)
  : Float(variable.Type == NC_FLOAT)
{
  const auto equal = [this](const std::string& text, double value) {
    this->Markers.push_back({ text + " " + Number(value), value });
  };
  // CF: _FillValue, valid_min and valid_max are single numbers, valid_range two, and
  // missing_value one or several (each marks values missing), all numbers compared with the
  // stored values; of any other type or length they would mark nothing, so they are refused.
  const char* marker = "a missing-value marker";
  const std::vector<double> fill = file.CheckedNumbers(variable, "_FillValue", 1, 1, marker);
  if (!fill.empty())
  {
    equal("_FillValue", fill[0]);
  }
  else if (variable.Type != NC_BYTE && variable.Type != NC_UBYTE && IsNumeric(variable.Type))
  {
    static const double defaults[] = { 0,
      0,
      0,
      NC_FILL_SHORT,
      NC_FILL_INT,
      NC_FILL_FLOAT,
      NC_FILL_DOUBLE,
      0,
      NC_FILL_USHORT,
      NC_FILL_UINT,
      double(NC_FILL_INT64),
      double(NC_FILL_UINT64) };
    equal("the default fill value", defaults[variable.Type]);
  }
  for (const double value : file.CheckedNumbers(variable, "missing_value", 1, 4096, marker))
  {
    equal("missing_value", value);
  }
  const auto range = [this](const std::string& text, double low, double high)
  {
    Marker m;
    m.Text = text;
    m.Low = low;
    m.High = high;
    m.Range = true;
    this->Markers.push_back(m);
  };
  const std::vector<double> validRange =
    file.CheckedNumbers(variable, "valid_range", 2, 2, "the range of valid values");
  const std::vector<double> low =
    file.CheckedNumbers(variable, "valid_min", 1, 1, "the smallest valid value");
  const std::vector<double> high =
    file.CheckedNumbers(variable, "valid_max", 1, 1, "the largest valid value");
  if (validRange.size() == 2)
  {
    range("outside valid_range [" + Number(validRange[0]) + ", " + Number(validRange[1]) + "]",
      validRange[0],
      validRange[1]);
  }
  if (!low.empty())
  {
    range("below valid_min " + Number(low[0]), low[0], std::numeric_limits<double>::infinity());
  }
  if (!high.empty())
  {
    range("above valid_max " + Number(high[0]), -std::numeric_limits<double>::infinity(), high[0]);
  }
  // A float variable's values are floats: a marker written as a double (missing_value = -999.9)
  // means the float nearest to it, as the value stored for it is.
  for (Marker& m : this->Markers)
  {
    const auto asStored = [this](double v) { return this->Float ? double(float(v)) : v; };
    m.Value = asStored(m.Value);
    m.Low = std::isinf(m.Low) ? m.Low : asStored(m.Low);
    m.High = std::isinf(m.High) ? m.High : asStored(m.High);
  }
}

int MissingValues::Match(double packed)
{
  for (std::size_t i = 0; i < this->Markers.size(); ++i)
  {
    Marker& m = this->Markers[i];
    const bool missing = m.Range
      ? (packed < m.Low || packed > m.High)
      : (packed == m.Value || (std::isnan(packed) && std::isnan(m.Value)));
    if (missing)
    {
      ++m.Count;
      return int(i);
    }
  }
  return -1;
}

std::uint64_t MissingValues::Count() const
{
  std::uint64_t count = 0;
  for (const Marker& m : this->Markers)
  {
    count += m.Count;
  }
  return count;
}

std::string MissingValues::Describe() const
{
  std::vector<const Marker*> found;
  for (const Marker& m : this->Markers)
  {
    if (m.Count > 0)
    {
      found.push_back(&m);
    }
  }
  if (found.size() == 1)
  {
    return found[0]->Text;
  }
  std::string text;
  for (const Marker* m : found)
  {
    text += (text.empty() ? "" : ", ") + std::to_string(m->Count) + " " + m->Text;
  }
  return text;
}

Packing PackingOf(const File& file, const Variable& variable)
{
  Packing packing;
  // CF: each one number (of the unpacked type); a scale of 0 (or not finite) would turn every
  // value into add_offset.
  const std::vector<double> scale =
    file.CheckedNumbers(variable, "scale_factor", 1, 1, "the packing's scale");
  const std::vector<double> offset =
    file.CheckedNumbers(variable, "add_offset", 1, 1, "the packing's offset");
  const std::string where = "variable \"" + variable.Name + "\": attribute ";
  if (!scale.empty() && !(std::isfinite(scale[0]) && scale[0] != 0.0))
  {
    cloudvis::Fail(file.Path(),
      where + "scale_factor is " + Number(scale[0]) +
        ": unpacked, every value would be add_offset (or not a number); a packing's scale is a "
        "finite number other than 0");
  }
  if (!offset.empty() && !std::isfinite(offset[0]))
  {
    cloudvis::Fail(file.Path(),
      where + "add_offset is " + Number(offset[0]) + ": a packing's offset is a finite number");
  }
  packing.Scale = scale.empty() ? 1.0 : scale[0];
  packing.Offset = offset.empty() ? 0.0 : offset[0];
  packing.Packed = !scale.empty() || !offset.empty();
  return packing;
}

void DeclareDroplets(const File& file, const Variable& variable, FieldReport& report)
{
  using Declare =
    void (*)(const std::string&, const std::string&, const std::string&, double, FieldReport&);
  const struct
  {
    const char* Attribute;
    const char* Meaning;
    Declare Check;
  } attributes[] = {
    { "effective_radius",
      "the droplets' effective radius in micrometres",
      cloudvis::DeclareEffectiveRadius },
    { "droplet_number",
      "the droplets' number concentration per cm^3",
      cloudvis::DeclareDropletNumber },
  };
  for (const auto& a : attributes)
  {
    const std::vector<double> value = file.CheckedNumbers(variable, a.Attribute, 1, 1, a.Meaning);
    if (!value.empty())
    {
      a.Check(file.Path(),
        "variable \"" + variable.Name + "\": attribute " + a.Attribute,
        std::string("the variable's ") + a.Attribute,
        value[0],
        report);
    }
  }
}

std::optional<ImpliedAxis> ImpliedCoordinates(const File& file,
  int dimension,
  std::size_t step,
  bool read)
{
  const Dimension& d = file.DimensionOf(dimension);
  const Variable global; // Id NC_GLOBAL: the file's own attributes
  if (d.Name == "west_east" || d.Name == "south_north")
  {
    const char* attribute = d.Name == "west_east" ? "DX" : "DY";
    const std::vector<double> spacing = file.Numbers(global, attribute);
    if (spacing.size() != 1 || !(spacing[0] > 0.0) || !std::isfinite(spacing[0]))
    {
      return std::nullopt;
    }
    ImpliedAxis axis{
      {}, "m", std::string("WRF's ") + attribute + " " + Number(spacing[0]) + " m"
    };
    for (std::size_t i = 0; read && i < d.Length; ++i)
    {
      axis.Coordinates.push_back(spacing[0] * double(i));
    }
    return axis;
  }
  const Variable* ph = file.Find("PH");
  const Variable* phb = file.Find("PHB");
  if (d.Name != "bottom_top" || !ph || !phb || ph->Dimensions != phb->Dimensions)
  {
    return std::nullopt;
  }
  // PH and PHB on (Time, bottom_top_stag, south_north, west_east), one level more than d.
  int stag = -1;
  std::vector<std::size_t> start(ph->Dimensions.size(), 0), count(ph->Dimensions.size(), 1);
  std::size_t columns = 1;
  for (std::size_t p = 0; p < ph->Dimensions.size(); ++p)
  {
    const Dimension& pd = file.DimensionOf(ph->Dimensions[p]);
    if (pd.Name == "bottom_top_stag" && pd.Length == d.Length + 1)
    {
      stag = int(p);
    }
    else if (pd.Name == "Time" || pd.Name == "time")
    {
      start[p] = step;
      if (step >= pd.Length)
      {
        return std::nullopt;
      }
    }
    else
    {
      count[p] = pd.Length;
      columns *= pd.Length;
    }
  }
  if (stag < 0 || columns == 0)
  {
    return std::nullopt;
  }
  ImpliedAxis axis{ {},
    "m",
    "WRF's (PH + PHB) / g, the domain's mean at each level, halfway between the staggered "
    "levels" };
  if (!read)
  {
    return axis;
  }
  std::vector<double> staggered, perturbation(columns), base(columns);
  for (std::size_t k = 0; k <= d.Length; ++k)
  {
    start[std::size_t(stag)] = k;
    file.Read(*ph, start, count, perturbation.data());
    file.Read(*phb, start, count, base.data());
    double sum = 0.0;
    for (std::size_t c = 0; c < columns; ++c)
    {
      sum += perturbation[c] + base[c];
    }
    staggered.push_back(sum / double(columns) / StandardGravity);
  }
  for (std::size_t k = 0; k < d.Length; ++k)
  {
    axis.Coordinates.push_back(0.5 * (staggered[k] + staggered[k + 1]));
  }
  return axis;
}

std::string CoordinateUnits(const File& file, int dimension)
{
  if (const Variable* coordinate = file.CoordinateOf(dimension))
  {
    return file.Text(*coordinate, "units");
  }
  const auto implied = ImpliedCoordinates(file, dimension, 0, false);
  return implied ? implied->Units : "";
}

std::string WhyZIsNotAHeight(const File& file, const Layout& layout)
{
  const Layout::Axis& z = layout.Space[2];
  if (z.Position < 0)
  {
    return "the variable has no vertical dimension";
  }
  const std::string name = file.DimensionOf(z.Dimension).Name;
  if (z.How.find("position") != std::string::npos)
  {
    return "no dimension is identified as vertical (z is \"" + name + "\" by its position)";
  }
  const Variable* coordinate = file.CoordinateOf(z.Dimension);
  const std::string units = CoordinateUnits(file, z.Dimension);
  const std::string positive = coordinate ? file.Text(*coordinate, "positive") : "";
  const bool height = LengthUnitFromText(units) || units.empty();
  if (positive == "down" || !height)
  {
    return "the vertical axis is not a height (units \"" + units + "\", positive \"" + positive +
      "\")";
  }
  return "";
}

// The length unit the spatial axes' coordinates share (m or km), and the vertical axis: z, where
// the file identifies one (not by position) whose coordinate is not a pressure or positive down.
void DeclareLengthAndUp(const File& file, const Layout& layout, FieldReport& report)
{
  std::optional<LengthUnit> shared;
  bool agree = true;
  for (const Layout::Axis& axis : layout.Space)
  {
    if (axis.Position < 0)
    {
      continue;
    }
    const auto unit = LengthUnitFromText(CoordinateUnits(file, axis.Dimension));
    agree = agree && unit && (!shared || *shared == *unit);
    shared = unit;
  }
  if (agree && shared)
  {
    report.Units.Length = shared;
    report.Add("length unit", LengthUnitName(*shared) + " (the axes' coordinates)");
  }
  const Layout::Axis& z = layout.Space[2];
  if (z.Position < 0 || z.How.find("position") != std::string::npos)
  {
    return;
  }
  const std::string why = WhyZIsNotAHeight(file, layout);
  if (!why.empty())
  {
    report.Add("up", "not declared: " + why + "; field.up says which axis is up");
    return;
  }
  report.Units.Up = 2;
  report.Add("up", "z (the file's vertical axis)");
}

} // namespace netcdf
} // namespace cloudvis
