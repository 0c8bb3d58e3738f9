// The physical units of a field (FieldUnits.h): combining the scene's and the file's, names,
// and the droplet law.
#include "FieldUnits.h"

#include <algorithm>
#include <cctype>

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

// Lower case, without spaces, '^', '*' and '.', so "g m-3", "g/m^3", "g.m**-3" compare.
std::string Compact(const std::string& text)
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

} // namespace

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
  return r;
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
  const std::string u = Compact(units);
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
  const std::string u = Compact(units);
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

} // namespace cloudvis
