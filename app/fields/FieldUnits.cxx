// The physical units of a field (FieldUnits.h): combining the scene's and the file's, names,
// and the droplet law.
#include "FieldUnits.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>

namespace cloudvis
{

namespace
{

// Picks the scene's value, else the file's, else keeps the default; records where it came from
// and what the file said when the scene overrode it with something else.
template<typename T>
void Pick(const std::optional<T>& scene,
  const std::optional<T>& file,
  T& value,
  std::string& from,
  std::optional<T>& overridden)
{
  if (scene)
  {
    value = *scene;
    from = "scene";
    if (file && *file != *scene)
    {
      overridden = file;
    }
  }
  else if (file)
  {
    value = *file;
    from = "file";
  }
}

} // namespace

std::string CompactUnits(const std::string& text)
{
  std::string compact;
  for (const char c : text)
  {
    if (!std::isspace(static_cast<unsigned char>(c)) && c != '^' && c != '*' && c != '.')
    {
      compact += char(std::tolower(static_cast<unsigned char>(c)));
    }
  }
  return compact;
}

ResolvedFieldUnits ResolveFieldUnits(const FieldUnits& scene, const FieldUnits& file)
{
  ResolvedFieldUnits r;
  Pick(scene.Quantity, file.Quantity, r.Quantity, r.QuantityFrom, r.Overridden.Quantity);
  Pick(scene.Length, file.Length, r.Length, r.LengthFrom, r.Overridden.Length);
  Pick(scene.Up, file.Up, r.Up, r.UpFrom, r.Overridden.Up);
  Pick(scene.EffectiveRadius,
    file.EffectiveRadius,
    r.EffectiveRadius,
    r.EffectiveRadiusFrom,
    r.Overridden.EffectiveRadius);
  // The scene's droplet number, else the file's; the scene's effective radius wins over the
  // file's number as over its radius.
  if (scene.DropletNumber)
  {
    r.DropletNumber = *scene.DropletNumber;
    r.DropletNumberFrom = "scene";
    if (file.DropletNumber && *file.DropletNumber != *scene.DropletNumber)
    {
      r.Overridden.DropletNumber = file.DropletNumber;
    }
  }
  else if (file.DropletNumber && !scene.EffectiveRadius)
  {
    r.DropletNumber = *file.DropletNumber;
    r.DropletNumberFrom = "file";
  }
  else
  {
    r.Overridden.DropletNumber = file.DropletNumber;
  }
  return r;
}

double DefaultCloudThreshold(FieldQuantity quantity)
{
  return quantity == FieldQuantity::Lwc ? 0.01 : 0.0;
}

double MetresPerUnit(LengthUnit unit)
{
  switch (unit)
  {
    case LengthUnit::Metre:
      return 1.0;
    case LengthUnit::Kilometre:
      return 1000.0;
    case LengthUnit::None:
      break;
  }
  return 0.0;
}

double DropletExtinctionPerMetre(double lwc, double effectiveRadiusMicrometres)
{
  return 3.0 * lwc / (2.0 * WaterDensity * effectiveRadiusMicrometres * 1e-6);
}

double EffectiveRadiusOfDroplets(double lwc, double numberPerCubicCentimetre)
{
  const double perCubicMetre = numberPerCubicCentimetre * 1e6;
  const double pi = std::acos(-1.0);
  const double cubed = 3.0 * lwc / (4.0 * pi * WaterDensity * DropletSpectrumK * perCubicMetre);
  return std::cbrt(cubed) * 1e6;
}

std::string QuantityName(FieldQuantity quantity)
{
  return quantity == FieldQuantity::Lwc ? "lwc" : "density";
}

std::string LengthUnitName(LengthUnit unit)
{
  switch (unit)
  {
    case LengthUnit::Metre:
      return "m";
    case LengthUnit::Kilometre:
      return "km";
    case LengthUnit::None:
      break;
  }
  return "none";
}

std::string AxisName(int axis)
{
  return std::string(1, char('x' + std::clamp(axis, 0, 2)));
}

std::string QuantityUnit(FieldQuantity quantity)
{
  return quantity == FieldQuantity::Lwc ? "g/m^3" : "";
}

std::optional<DeclaredQuantity> QuantityFromUnits(const std::string& units)
{
  const std::string u = CompactUnits(units);
  for (const char* gram : { "gm-3", "g/m3" })
  {
    if (u == gram)
    {
      return DeclaredQuantity{ FieldQuantity::Lwc, 1.0 };
    }
  }
  for (const char* kilogram : { "kgm-3", "kg/m3" })
  {
    if (u == kilogram)
    {
      return DeclaredQuantity{ FieldQuantity::Lwc, 1000.0 };
    }
  }
  return std::nullopt;
}

std::optional<LengthUnit> LengthUnitFromText(const std::string& units)
{
  const std::string u = CompactUnits(units);
  for (const char* metre : { "m", "metre", "metres", "meter", "meters" })
  {
    if (u == metre)
    {
      return LengthUnit::Metre;
    }
  }
  for (const char* kilometre : { "km", "kilometre", "kilometres", "kilometer", "kilometers" })
  {
    if (u == kilometre)
    {
      return LengthUnit::Kilometre;
    }
  }
  return std::nullopt;
}

std::optional<double> MixingRatioGramsPerKilogram(const std::string& units,
  const std::string& standardName)
{
  const std::string u = CompactUnits(units);
  for (const char* kilogram : { "kg/kg", "kgkg-1" })
  {
    if (u == kilogram)
    {
      return 1000.0;
    }
  }
  for (const char* gram : { "g/kg", "gkg-1" })
  {
    if (u == gram)
    {
      return 1.0;
    }
  }
  const bool ratioByName = standardName == "cloud_liquid_water_mixing_ratio" ||
    standardName == "mass_fraction_of_cloud_liquid_water_in_air";
  if (ratioByName && (u.empty() || u == "1"))
  {
    return 1000.0;
  }
  return std::nullopt;
}

std::optional<AirState> StandardAtmosphere(double heightMetres)
{
  if (!(heightMetres >= StandardAtmosphereBottom && heightMetres <= StandardAtmosphereTop))
  {
    return std::nullopt;
  }
  // The layers: geopotential base height (m) and lapse rate (K/m); the base temperature and
  // pressure of each follow from the sea-level values.
  struct Layer
  {
    double Base, Lapse;
  };
  static constexpr std::array<Layer, 7> layers{ { { 0.0, -0.0065 },
    { 11000.0, 0.0 },
    { 20000.0, 0.001 },
    { 32000.0, 0.0028 },
    { 47000.0, 0.0 },
    { 51000.0, -0.0028 },
    { 71000.0, -0.002 } } };
  constexpr double earthRadius = 6356766.0; // m, the standard's for geopotential height
  const double geopotential = earthRadius * heightMetres / (earthRadius + heightMetres);
  // Pressure across a layer from its base, at temperature t0 there, over geopotential dh.
  const auto across = [](double p0, double t0, double lapse, double dh)
  {
    const double g = StandardGravity / DryAirGasConstant;
    return lapse == 0.0 ? p0 * std::exp(-g * dh / t0)
                        : p0 * std::pow((t0 + lapse * dh) / t0, -g / lapse);
  };
  double temperature = 288.15, pressure = 101325.0;
  std::size_t l = 0;
  while (l + 1 < layers.size() && geopotential >= layers[l + 1].Base)
  {
    const double dh = layers[l + 1].Base - layers[l].Base;
    pressure = across(pressure, temperature, layers[l].Lapse, dh);
    temperature += layers[l].Lapse * dh;
    ++l;
  }
  const double dh = geopotential - layers[l].Base; // below 0 m: the troposphere's, continued
  AirState air;
  air.Pressure = across(pressure, temperature, layers[l].Lapse, dh);
  air.Temperature = temperature + layers[l].Lapse * dh;
  air.Density = air.Pressure / (DryAirGasConstant * air.Temperature);
  return air;
}

} // namespace cloudvis
