// Mixing ratios made liquid water contents with the air's density (NetCdfAirDensity.h).
#include "NetCdfAirDensity.h"

#include "FieldFormatReaders.h" // Fail, Number
#include "FieldUnits.h"

#include <vtkFloatArray.h>

#include <algorithm>
#include <cmath>
#include <new>
#include <optional>

namespace cloudvis
{
namespace netcdf
{
namespace
{

// A quantity of the air over the field's lattice: one value per voxel (Volume), or one per level
// along the lattice axis `Axis` (Profile; a constant is a profile of one level).
struct AirValues
{
  std::vector<double> Profile;
  int Axis = 2;
  vtkSmartPointer<vtkFloatArray> Volume;
  std::string Shape; // "a profile along \"zt\"", "3-D", "one value"

  std::size_t Size() const
  {
    return this->Volume ? std::size_t(this->Volume->GetNumberOfValues()) : this->Profile.size();
  }
  // The value at voxel `index` of a lattice of `points`, x fastest.
  double At(std::size_t index, const std::array<std::size_t, 3>& points) const
  {
    if (this->Volume)
    {
      return double(this->Volume->GetValue(vtkIdType(index)));
    }
    if (this->Profile.size() == 1)
    {
      return this->Profile[0];
    }
    const std::size_t stride = this->Axis == 0 ? 1
      : this->Axis == 1                        ? points[0]
                                               : points[0] * points[1];
    return this->Profile[(index / stride) % points[std::size_t(this->Axis)]];
  }
  // Each value v becomes f(v, other's value at the same place). When one of the two is a volume
  // (SAM's pressure profile and its 3-D temperature), so is the result.
  template<typename F>
  void Combine(const AirValues& other, const std::array<std::size_t, 3>& points, F f)
  {
    const bool alike = bool(this->Volume) == bool(other.Volume) &&
      (this->Volume || (this->Axis == other.Axis && this->Profile.size() == other.Profile.size()));
    if (alike && !this->Volume)
    {
      for (std::size_t i = 0; i < this->Profile.size(); ++i)
      {
        this->Profile[i] = f(this->Profile[i], other.Profile[i]);
      }
      return;
    }
    vtkSmartPointer<vtkFloatArray> result = this->Volume;
    if (!result)
    {
      result = vtkSmartPointer<vtkFloatArray>::New();
      const std::size_t voxels = points[0] * points[1] * points[2];
      result->SetNumberOfValues(vtkIdType(voxels));
      if (std::size_t(result->GetNumberOfValues()) != voxels)
      {
        throw std::bad_alloc(); // VTK reports a failed allocation only on its error stream
      }
    }
    for (std::size_t i = 0; i < std::size_t(result->GetNumberOfValues()); ++i)
    {
      result->SetValue(vtkIdType(i), float(f(this->At(i, points), other.At(i, points))));
    }
    this->Volume = result;
    this->Profile.clear();
    this->Shape = "3-D";
  }
  std::array<double, 2> Range() const
  {
    std::array<double, 2> range{ { INFINITY, -INFINITY } };
    for (std::size_t i = 0; i < this->Size(); ++i)
    {
      const double v =
        this->Volume ? double(this->Volume->GetValue(vtkIdType(i))) : this->Profile[i];
      range = { { std::min(range[0], v), std::max(range[1], v) } };
    }
    return range;
  }
  // "1.22 .. 1.13 kg/m^3" (from the lowest level to the highest for a profile).
  std::string Describe(const std::string& unit) const
  {
    if (this->Volume)
    {
      const std::array<double, 2> r = this->Range();
      return Number(r[0]) + " .. " + Number(r[1]) + " " + unit;
    }
    if (this->Profile.size() == 1 || this->Profile.front() == this->Profile.back())
    {
      return Number(this->Profile.front()) + " " + unit;
    }
    return Number(this->Profile.front()) + " .. " + Number(this->Profile.back()) + " " + unit +
      " (bottom .. top)";
  }
};

// How a variable's values become the unit cloudvis computes in: value * Scale + Offset.
struct UnitConversion
{
  double Scale = 1.0, Offset = 0.0;
};

std::optional<UnitConversion> DensityUnits(const std::string& units)
{
  const std::string u = CompactUnits(units);
  if (u.empty() || u == "kgm-3" || u == "kg/m3")
  {
    return UnitConversion{};
  }
  if (u == "gm-3" || u == "g/m3")
  {
    return UnitConversion{ 1e-3 };
  }
  return std::nullopt;
}

std::optional<UnitConversion> PressureUnits(const std::string& units)
{
  const std::string u = CompactUnits(units);
  if (u == "pa" || u == "pascal" || u == "pascals")
  {
    return UnitConversion{};
  }
  if (u == "hpa" || u == "mb" || u == "mbar" || u == "millibar" || u == "millibars")
  {
    return UnitConversion{ 100.0 };
  }
  if (u == "kpa")
  {
    return UnitConversion{ 1000.0 };
  }
  return std::nullopt;
}

std::optional<UnitConversion> TemperatureUnits(const std::string& units)
{
  const std::string u = CompactUnits(units);
  for (const char* kelvin : { "k", "kelvin", "degk", "degreek", "degrees_k", "degree_kelvin" })
  {
    if (u == kelvin)
    {
      return UnitConversion{};
    }
  }
  for (const char* celsius :
    { "degc", "c", "celsius", "degreec", "degree_c", "degrees_c", "degree_celsius" })
  {
    if (u == celsius)
    {
      return UnitConversion{ 1.0, 273.15 };
    }
  }
  return std::nullopt;
}

std::optional<UnitConversion> HumidityUnits(const std::string& units, const std::string& standard)
{
  if (const auto grams = MixingRatioGramsPerKilogram(units, ""))
  {
    return UnitConversion{ *grams / 1000.0 };
  }
  const std::string u = CompactUnits(units);
  const bool byName = standard == "specific_humidity" || standard == "humidity_mixing_ratio";
  return byName && (u.empty() || u == "1") ? std::optional<UnitConversion>(UnitConversion{})
                                           : std::nullopt;
}

// The first variable whose standard_name is one of `standards`, else whose name is one of
// `names`.
const Variable* FindAirVariable(const File& file,
  const std::vector<std::string>& standards,
  const std::vector<std::string>& names)
{
  for (const std::string& standard : standards)
  {
    for (const Variable& v : file.Variables())
    {
      if (file.Text(v, "standard_name") == standard)
      {
        return &v;
      }
    }
  }
  for (const std::string& name : names)
  {
    if (const Variable* v = file.Find(name))
    {
      return v;
    }
  }
  return nullptr;
}

std::string DimensionsOf(const File& file, const Variable& v)
{
  std::string text;
  for (const int d : v.Dimensions)
  {
    text += (text.empty() ? "" : ", ") + file.DimensionOf(d).Name;
  }
  return "(" + text + ")";
}

// The values of `v` over the lattice, in the unit `conversion` turns them into: one value for a
// variable without spatial dimensions, a profile for one on the field's vertical dimension alone,
// a volume for one on the field's spatial dimensions (each with the field's time step where it
// has the field's time axis). Empty with `problem` said otherwise, and for missing values.
std::optional<AirValues> ReadAirValues(const FieldLattice& lattice,
  const Variable& v,
  const UnitConversion& conversion,
  std::string& problem)
{
  const File& file = lattice.Source;
  const Layout& field = lattice.Axes;
  std::vector<int> spatial;
  int timePosition = -1;
  for (std::size_t p = 0; p < v.Dimensions.size(); ++p)
  {
    if (field.Time.Position >= 0 && v.Dimensions[p] == field.Time.Dimension)
    {
      timePosition = int(p);
    }
    else
    {
      spatial.push_back(v.Dimensions[p]);
    }
  }
  if (!IsNumeric(v.Type))
  {
    problem = "it holds " + TypeName(v.Type) + " values, not numbers";
    return std::nullopt;
  }
  std::vector<int> fieldSpatial;
  for (const Layout::Axis& a : field.Space)
  {
    if (a.Position >= 0)
    {
      fieldSpatial.push_back(a.Dimension);
    }
  }
  AirValues values;
  const int z = field.Space[2].Position >= 0 ? field.Space[2].Dimension : -1;
  if (spatial.empty() || (spatial.size() == 1 && spatial[0] == z))
  {
    const std::size_t levels = spatial.empty() ? 1 : lattice.Coordinates[2].size();
    std::vector<std::size_t> start(v.Dimensions.size(), 0), count(v.Dimensions.size(), 1);
    for (std::size_t p = 0; p < v.Dimensions.size(); ++p)
    {
      if (int(p) == timePosition)
      {
        start[p] = lattice.Step;
      }
      else
      {
        count[p] = levels;
      }
    }
    values.Profile.resize(levels);
    file.Read(v, start, count, values.Profile.data());
    MissingValues missing(file, v);
    const Packing packing = PackingOf(file, v);
    for (double& value : values.Profile)
    {
      if (missing.Match(value) >= 0)
      {
        problem = "it marks values as missing (" + missing.Describe() + ")";
        return std::nullopt;
      }
      value = (value * packing.Scale + packing.Offset) * conversion.Scale + conversion.Offset;
    }
    if (lattice.ZReversed && !spatial.empty())
    {
      std::reverse(values.Profile.begin(), values.Profile.end());
    }
    values.Shape =
      spatial.empty() ? "one value" : "a profile along \"" + file.DimensionOf(z).Name + "\"";
    return values;
  }
  std::vector<int> sortedSpatial = spatial, sortedField = fieldSpatial;
  std::sort(sortedSpatial.begin(), sortedSpatial.end());
  std::sort(sortedField.begin(), sortedField.end());
  if (sortedSpatial != sortedField)
  {
    problem = "it is on " + DimensionsOf(file, v) + ": neither the field's dimensions " +
      DimensionsOf(file, lattice.Chosen) + " nor a profile along its vertical one" +
      (z >= 0 ? " \"" + file.DimensionOf(z).Name + "\"" : std::string());
    return std::nullopt;
  }
  values.Volume = lattice.ReadVolume(v);
  float* stored = values.Volume->GetPointer(0);
  for (vtkIdType i = 0; i < values.Volume->GetNumberOfValues(); ++i)
  {
    stored[i] = float(double(stored[i]) * conversion.Scale + conversion.Offset);
  }
  values.Shape = "3-D";
  return values;
}

// Whether every value lies in [low, high]; else `problem` says which does not.
bool Within(const AirValues& values,
  double low,
  double high,
  const std::string& what,
  std::string& problem)
{
  const std::array<double, 2> r = values.Range();
  if (r[0] >= low && r[1] <= high)
  {
    return true;
  }
  problem = "its values span " + Number(r[0]) + " .. " + Number(r[1]) + " " + what +
    ", beyond the " + Number(low) + " .. " + Number(high) + " of air";
  return false;
}

// What field.air_density "auto" found, for the report and for the refusal when nothing is found.
struct Search
{
  std::optional<AirValues> Density;
  std::string Source;  // what the density is: "variable \"rhof\" (a profile along \"zt\")"
  std::string Missing; // why no source gave one
};

void AppendWhy(std::string& list, const std::string& why)
{
  list += (list.empty() ? "" : "; ") + why;
}

// An air density variable: read and checked, or refused (it is meant to be one, by its
// standard_name or name, or because the scene names it).
AirValues ReadDensityVariable(const FieldLattice& lattice, const Variable& v)
{
  const std::string path = lattice.Source.Path();
  const std::string units = lattice.Source.Text(v, "units");
  const std::string what = "the air density variable \"" + v.Name + "\"";
  const auto conversion = DensityUnits(units);
  if (!conversion)
  {
    Fail(path,
      what + " has units \"" + units +
        "\", not a density (kg m-3); field.air_density \"standard\" or a number in kg/m^3 "
        "gives the density another way");
  }
  std::string problem;
  std::optional<AirValues> values = ReadAirValues(lattice, v, *conversion, problem);
  if (values && !Within(*values, AirDensityMin, AirDensityMax, "kg/m^3", problem))
  {
    values.reset();
  }
  if (!values)
  {
    Fail(path,
      what + ": " + problem +
        "; field.air_density \"standard\" or a number in kg/m^3 gives the density another way");
  }
  return *values;
}

// Ideal gas from the file's pressure and temperature (and humidity, for the virtual
// temperature); empty with `why` said when the file does not hold them as the air's.
std::optional<AirValues> DensityFromPressureAndTemperature(const FieldLattice& lattice,
  std::string& source,
  std::string& why)
{
  const File& file = lattice.Source;
  const Variable* p =
    FindAirVariable(file, { "air_pressure" }, { "p", "pres", "pressure", "PRES" });
  const Variable* t =
    FindAirVariable(file, { "air_temperature" }, { "T", "t", "temp", "ta", "TABS", "tabs" });
  if (!p || !t)
  {
    why = "no pressure and temperature";
    return std::nullopt;
  }
  std::string problem;
  const auto pressureUnits = PressureUnits(file.Text(*p, "units"));
  const auto temperatureUnits = TemperatureUnits(file.Text(*t, "units"));
  std::optional<AirValues> pressure, temperature;
  if (!pressureUnits)
  {
    problem = "\"" + p->Name + "\" has units \"" + file.Text(*p, "units") + "\", not a pressure";
  }
  else if (!temperatureUnits)
  {
    problem = "\"" + t->Name + "\" has units \"" + file.Text(*t, "units") +
      "\", not an absolute temperature";
  }
  else if (!(pressure = ReadAirValues(lattice, *p, *pressureUnits, problem)) ||
    !Within(*pressure, 1.0, 2e5, "Pa", problem))
  {
    problem = "pressure \"" + p->Name + "\": " + problem;
  }
  else if (!(temperature = ReadAirValues(lattice, *t, *temperatureUnits, problem)) ||
    !Within(*temperature, 100.0, 400.0, "K", problem))
  {
    problem = "temperature \"" + t->Name + "\": " + problem;
  }
  if (!problem.empty())
  {
    why = "pressure and temperature not used (" + problem + ")";
    return std::nullopt;
  }
  const std::array<std::size_t, 3> points{
    { lattice.Coordinates[0].size(), lattice.Coordinates[1].size(), lattice.Coordinates[2].size() }
  };
  source = "ideal gas from pressure \"" + p->Name + "\" (" + pressure->Shape +
    ") and temperature \"" + t->Name + "\" (" + temperature->Shape + ")";
  AirValues density = *pressure;
  pressure.reset();
  density.Combine(
    *temperature, points, [](double pa, double k) { return pa / (DryAirGasConstant * k); });
  temperature.reset();
  const Variable* q = FindAirVariable(
    file, { "specific_humidity", "humidity_mixing_ratio" }, { "qv", "QV", "QVAPOR", "q", "sphum" });
  if (!q)
  {
    source += ", not the virtual temperature: the file holds no humidity";
    return density;
  }
  const auto humidityUnits = HumidityUnits(file.Text(*q, "units"), file.Text(*q, "standard_name"));
  std::optional<AirValues> humidity;
  if (!humidityUnits)
  {
    problem = "its units \"" + file.Text(*q, "units") + "\" are not a mixing ratio";
  }
  else if ((humidity = ReadAirValues(lattice, *q, *humidityUnits, problem)))
  {
    Within(*humidity, -1e-3, 0.1, "kg/kg", problem);
  }
  if (!problem.empty())
  {
    source +=
      ", not the virtual temperature: humidity \"" + q->Name + "\" not used (" + problem + ")";
    return density;
  }
  density.Combine(*humidity,
    points,
    [](double rho, double qv) { return rho / (1.0 + 0.608 * std::max(qv, 0.0)); });
  source += ", virtual temperature with humidity \"" + q->Name + "\"";
  return density;
}

// The lattice axis that is up and metres per unit along it, for the standard atmosphere; empty
// with `why` said when the field's vertical is not a height in known units.
std::optional<std::pair<int, double>> HeightAxis(const FieldLattice& lattice,
  const FieldReadOptions& options,
  std::string& why)
{
  const File& file = lattice.Source;
  int up = 2;
  if (options.Units.Up)
  {
    up = *options.Units.Up;
  }
  else if (const std::string notHeight = WhyZIsNotAHeight(file, lattice.Axes); !notHeight.empty())
  {
    why = notHeight + " (field.up says which axis is up)";
    return std::nullopt;
  }
  double metres = 0.0;
  if (options.Units.Length)
  {
    metres = MetresPerUnit(*options.Units.Length);
  }
  else if (const Layout::Axis& axis = lattice.Axes.Space[std::size_t(up)]; axis.Position >= 0)
  {
    const auto unit = LengthUnitFromText(CoordinateUnits(file, axis.Dimension));
    metres = unit ? MetresPerUnit(*unit) : 0.0;
  }
  if (!(metres > 0.0))
  {
    why = "the vertical axis " + AxisName(up) +
      " has no length unit (field.length_unit says how long a unit is)";
    return std::nullopt;
  }
  return std::make_pair(up, metres);
}

// The standard atmosphere at the heights of the up axis, read as above sea level; empty with
// `why` said when they are not heights, or beyond the standard's range.
std::optional<AirValues> StandardDensity(const FieldLattice& lattice,
  const FieldReadOptions& options,
  std::string& source,
  std::string& why)
{
  const auto axis = HeightAxis(lattice, options, why);
  if (!axis)
  {
    return std::nullopt;
  }
  const std::vector<double>& heights = lattice.Coordinates[std::size_t(axis->first)];
  AirValues density;
  density.Axis = axis->first;
  density.Shape = "a profile along " + AxisName(axis->first);
  for (const double h : heights)
  {
    const std::optional<AirState> air = StandardAtmosphere(h * axis->second);
    if (!air)
    {
      why = "the heights of " + AxisName(axis->first) + " reach " + Number(h * axis->second) +
        " m, beyond the standard atmosphere's " + Number(StandardAtmosphereBottom) + " .. " +
        Number(StandardAtmosphereTop) + " m";
      return std::nullopt;
    }
    density.Profile.push_back(air->Density);
  }
  source = "the ICAO standard atmosphere at the heights of " + AxisName(axis->first) + ", " +
    Number(heights.front() * axis->second) + " .. " + Number(heights.back() * axis->second) +
    " m, read as above sea level";
  return density;
}

} // namespace

bool ConvertMixingRatio(const FieldLattice& lattice,
  const FieldReadOptions& options,
  vtkFloatArray* values,
  FieldReport& report)
{
  const File& file = lattice.Source;
  const std::string& path = file.Path();
  const std::string units = file.Text(lattice.Chosen, "units");
  const std::optional<double> grams =
    MixingRatioGramsPerKilogram(units, file.Text(lattice.Chosen, "standard_name"));
  const AirDensitySource& asked = options.AirDensity;
  const bool explicitSource = asked.From != AirDensitySource::Kind::Auto;
  const std::string variable = "variable \"" + lattice.Chosen.Name + "\"";
  if (!grams)
  {
    if (explicitSource)
    {
      Fail(path,
        "field.air_density: " + variable + " is not a mixing ratio (its units are \"" + units +
          "\"): the air's density turns mixing ratios (kg/kg, g/kg) into liquid water contents");
    }
    return false;
  }
  const std::string ratio = "a mixing ratio in " + units;
  if (options.Units.Quantity == FieldQuantity::Density)
  {
    if (explicitSource)
    {
      Fail(path,
        "field.air_density: the scene reads " + variable +
          " as a density (field.quantity \"density\"), which keeps its mixing ratios as stored");
    }
    report.Add("quantity",
      "density: " + ratio + ", kept as stored (the scene's field.quantity \"density\")");
    return true;
  }

  std::optional<AirValues> density;
  std::string source, missing;
  switch (asked.From)
  {
    case AirDensitySource::Kind::Number:
      density = AirValues{ { asked.KilogramsPerCubicMetre }, 2, nullptr, "one value" };
      source = "field.air_density";
      break;
    case AirDensitySource::Kind::Variable:
    {
      const Variable* v = file.Find(asked.Variable);
      if (!v)
      {
        Fail(path, "field.air_density: no variable named \"" + asked.Variable + "\"");
      }
      density = ReadDensityVariable(lattice, *v);
      source = "variable \"" + v->Name + "\" (" + density->Shape + ", field.air_density)";
      break;
    }
    case AirDensitySource::Kind::Standard:
      density = StandardDensity(lattice, options, source, missing);
      if (!density)
      {
        Fail(path, "field.air_density \"standard\": " + missing);
      }
      break;
    case AirDensitySource::Kind::Auto:
    {
      std::string why;
      if (const Variable* v = FindAirVariable(file,
            { "air_density" },
            { "air_density", "rho", "rhof", "rhobf", "rho_air", "rhoref", "rhoa", "RHO", "dens" }))
      {
        density = ReadDensityVariable(lattice, *v);
        source = "variable \"" + v->Name + "\" (" + density->Shape + ")";
        break;
      }
      AppendWhy(missing, "the file holds no air density");
      if ((density = DensityFromPressureAndTemperature(lattice, source, why)))
      {
        break;
      }
      AppendWhy(missing, why);
      if ((density = StandardDensity(lattice, options, source, why)))
      {
        source += " (" + missing + ")";
        break;
      }
      AppendWhy(missing, "no standard atmosphere: " + why);
      break;
    }
  }
  if (!density)
  {
    const std::string give =
      "field.air_density \"standard\", a number in kg/m^3 or \"variable:NAME\" gives one";
    if (options.Units.Quantity == FieldQuantity::Lwc)
    {
      Fail(path,
        variable + " holds " + ratio +
          ": a liquid water content (field.quantity \"lwc\") needs the air's density, and "
          "none was found (" +
          missing + "); " + give);
    }
    report.Add("quantity",
      "density: " + ratio +
        ", not converted to a liquid water content: that needs the air's "
        "density, and none was found (" +
        missing + "); " + give);
    return true;
  }
  const std::array<std::size_t, 3> points{
    { lattice.Coordinates[0].size(), lattice.Coordinates[1].size(), lattice.Coordinates[2].size() }
  };
  float* v = values->GetPointer(0);
  std::size_t i = 0;
  for (std::size_t k = 0; k < points[2]; ++k)
    for (std::size_t j = 0; j < points[1]; ++j)
      for (std::size_t n = 0; n < points[0]; ++n, ++i)
      {
        const std::array<std::size_t, 3> at{ { n, j, k } };
        const double rho = density->Volume ? double(density->Volume->GetValue(vtkIdType(i)))
          : density->Profile.size() == 1   ? density->Profile[0]
                                           : density->Profile[at[std::size_t(density->Axis)]];
        v[i] = float(double(v[i]) * *grams * rho);
      }
  values->Modified();
  report.Units.Quantity = FieldQuantity::Lwc;
  report.Add("quantity", "lwc (liquid water content: " + ratio + " times the air's density)");
  report.Add("air density", density->Describe("kg/m^3") + ": " + source);
  report.Add("converted",
    "from " + units + " to g/m^3 (x " + Number(*grams) + " g/kg per unit x the air density)");
  return true;
}

} // namespace netcdf
} // namespace cloudvis
