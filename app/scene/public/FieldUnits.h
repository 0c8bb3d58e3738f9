// What a field's values and lengths mean in physical terms. Most cloudvis fields are
// dimensionless densities on a lattice in world units; a scientist's field (LES output, say) is
// liquid water content in g/m^3 on a grid in metres or kilometres, with one vertical axis. The
// scene's field section may say so (field.quantity, field.length_unit, field.up,
// field.effective_radius) and so may a field file (a NetCDF variable's and axes' `units`, a CF
// vertical axis, OpenVDB grid metadata): ResolveFieldUnits combines the two, the scene winning,
// and remembers where each value came from so that `cloudvis info` can report both. The droplet
// law that turns liquid water into extinction lives here too, so the transfer function and the
// statistics use one copy of it.
#ifndef cloudvis_FieldUnits_h
#define cloudvis_FieldUnits_h

#include <optional>
#include <string>

namespace cloudvis
{

// What a field's values are.
enum class FieldQuantity
{
  Density, // dimensionless, the transfer function says what it looks like (the default)
  Lwc,     // liquid water content, g/m^3
};

// How long one world unit (the unit of bounds, spacing and origin) is.
enum class LengthUnit
{
  None,      // unknown: world units only (the default)
  Metre,     // m
  Kilometre, // km
};

// Units as the scene or a file declares them; an absent member was not declared.
struct FieldUnits
{
  std::optional<FieldQuantity> Quantity;
  std::optional<LengthUnit> Length;
  std::optional<int> Up;                 // the vertical axis: 0 = x, 1 = y, 2 = z
  std::optional<double> EffectiveRadius; // micrometres, of the droplets of an lwc field
};

// The units a field has once scene and file are combined, and where each came from: "scene",
// "file" or "default".
struct ResolvedFieldUnits
{
  FieldQuantity Quantity = FieldQuantity::Density;
  LengthUnit Length = LengthUnit::None;
  int Up = 1; // y: cloudvis's generated fields and cameras have y up
  double EffectiveRadius = 10.0;
  std::string QuantityFrom = "default", LengthFrom = "default", UpFrom = "default",
              EffectiveRadiusFrom = "default";
  // What the file declared, where the scene overrode it with something else (for the report).
  FieldUnits Overridden;
};

// The defaults of ResolvedFieldUnits, for the scene reference.
constexpr double DefaultEffectiveRadius = 10.0; // micrometres, a typical cumulus droplet

// The density of liquid water, g/m^3.
constexpr double WaterDensity = 1e6;

// The scene's units where given, else the file's, else the defaults.
ResolvedFieldUnits ResolveFieldUnits(const FieldUnits& scene, const FieldUnits& file);

// Metres per world unit: 1 for m, 1000 for km, 0 when the length unit is unknown.
double MetresPerUnit(LengthUnit unit);

// The extinction of cloud droplets, per metre: sigma = 3 LWC / (2 rho_w r_e) for a liquid water
// content in g/m^3 and an effective radius in micrometres (the geometric-optics limit, extinction
// efficiency 2). LWC 1 g/m^3 with r_e = 10 um gives 0.15 per metre.
double DropletExtinctionPerMetre(double lwc, double effectiveRadiusMicrometres);

// Names as scene files and reports write them: "density", "lwc"; "none", "m", "km"; "x", "y", "z".
std::string QuantityName(FieldQuantity quantity);
std::string LengthUnitName(LengthUnit unit);
std::string AxisName(int axis);
// The unit of a quantity's values ("g/m^3", or "" for density).
std::string QuantityUnit(FieldQuantity quantity);

// A quantity from a `units` text a file gives ("g m-3", "g/m3", "kg m-3", "kg/m^3"...): the
// quantity and the factor that turns the file's values into its unit (1000 for kg/m^3 -> g/m^3).
// Empty when the text is not a liquid water content (a mixing ratio kg/kg is not: it needs the
// air's density).
struct DeclaredQuantity
{
  FieldQuantity Quantity = FieldQuantity::Density;
  double Scale = 1.0;
};
std::optional<DeclaredQuantity> QuantityFromUnits(const std::string& units);

// A length unit from a `units` text ("m", "metre", "meters", "km", "kilometres"...).
std::optional<LengthUnit> LengthUnitFromText(const std::string& units);

} // namespace cloudvis

#endif
