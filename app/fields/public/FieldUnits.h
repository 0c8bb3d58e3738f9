// What a field's values and lengths mean in physical terms. Most cloudvis fields are
// dimensionless densities on a lattice in world units; a scientist's field (LES output, say) is
// liquid water content in g/m^3 on a grid in metres or kilometres, with one vertical axis. The
// scene's field section may say so (field.quantity, field.length_unit, field.up,
// field.effective_radius, field.droplet_number) and so may a field file (a NetCDF variable's and
// axes' `units`, a CF vertical axis, OpenVDB grid metadata): ResolveFieldUnits combines the two,
// the scene winning, and remembers where each value came from so that `cloudvis info` can report
// both. The droplet laws that turn liquid water into effective radius and extinction live here
// too, so the transfer function and the statistics use one copy of them, and so do the mixing
// ratios LES codes write and the standard atmosphere that makes them liquid water contents.
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

// The value above which a field's voxel is cloud (the default threshold of the cloud mask): any
// density > 0 for a plain density field; for liquid water content the usual LES threshold,
// 0.01 g/m^3.
double DefaultCloudThreshold(FieldQuantity quantity);

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
  std::optional<double> DropletNumber;   // droplets per cm^3 of an lwc field
};

// The units a field has once scene and file are combined, and where each came from: "scene",
// "file" or "default".
struct ResolvedFieldUnits
{
  FieldQuantity Quantity = FieldQuantity::Density;
  LengthUnit Length = LengthUnit::None;
  int Up = 1; // y: cloudvis's generated fields and cameras have y up
  double EffectiveRadius = 10.0;
  // Droplets per cm^3; 0 when none is given, and then every droplet has EffectiveRadius. Given,
  // the effective radius grows with the liquid water, r_e = EffectiveRadiusOfDroplets(LWC, N),
  // and EffectiveRadius is r_e at CloudMeanLwc, the mean content of the cloud's voxels (those
  // above info's cloud threshold): the one r_e the droplets' phase takes.
  double DropletNumber = 0.0;
  double CloudMeanLwc = 0.0;
  std::string QuantityFrom = "default", LengthFrom = "default", UpFrom = "default",
              EffectiveRadiusFrom = "default", DropletNumberFrom = "default";
  // What the file declared, where the scene overrode it with something else (for the report).
  FieldUnits Overridden;
};

// The defaults of ResolvedFieldUnits, for the scene reference.
constexpr double DefaultEffectiveRadius = 10.0; // micrometres, a typical cumulus droplet

// The density of liquid water, g/m^3.
constexpr double WaterDensity = 1e6;

// The droplet numbers field.droplet_number and a file may give, per cm^3 (clean maritime air
// holds 10 to 100, polluted continental air up to a few thousand).
constexpr double DropletNumberMin = 1.0, DropletNumberMax = 1e5;

// The ratio k = (r_v / r_e)^3 of the volume-mean radius to the effective radius cubed, of
// maritime stratocumulus (Martin, Johnson and Spice 1994, J. Atmos. Sci. 51, 1823; continental
// clouds have about 0.67).
constexpr double DropletSpectrumK = 0.8;

// The effective radius in micrometres of `numberPerCubicCentimetre` droplets holding `lwc` g/m^3:
// r_e = (3 LWC / (4 pi rho_w k N))^(1/3) (Martin et al. 1994). 1 g/m^3 in 100 droplets per cm^3
// gives 14.4 um.
double EffectiveRadiusOfDroplets(double lwc, double numberPerCubicCentimetre);

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

// A `units` text as the parsers above compare it: lower case, without spaces, '^', '*' and '.',
// so that "g m-3", "g/m^3" and "g.m**-3" read "gm-3", "g/m3" and "gm-3".
std::string CompactUnits(const std::string& units);

// ---- mixing ratios and the air's density ----------------------------------------------------

// The grams of water per kilogram of air that one unit of a mixing ratio is: 1000 for "kg/kg"
// ("kg kg-1", "kg kg**-1"), 1 for "g/kg" ("g kg-1"), and 1000 for "1" or no units where the CF
// standard_name says the variable is a mixing ratio or mass fraction of cloud liquid water.
// Empty for any other units. LES codes write liquid water as such a ratio; times the air's
// density in kg/m^3 it is a liquid water content in g/m^3.
std::optional<double> MixingRatioGramsPerKilogram(const std::string& units,
  const std::string& standardName);

// Where the air's density comes from when a field of mixing ratios becomes a liquid water content
// (the scene's field.air_density): found in the file or else the standard atmosphere ("auto"),
// the standard atmosphere from the heights, one number, or the file's variable of that name.
struct AirDensitySource
{
  enum class Kind
  {
    Auto,
    Standard,
    Number,
    Variable,
  };
  Kind From = Kind::Auto;
  double KilogramsPerCubicMetre = 0.0; // Number
  std::string Variable;                // Variable
  bool operator==(const AirDensitySource& o) const
  {
    return this->From == o.From && this->KilogramsPerCubicMetre == o.KilogramsPerCubicMetre &&
      this->Variable == o.Variable;
  }
};

// The densities a number of field.air_density, or an air density a file holds, may have, kg/m^3:
// from thin stratospheric air to well beyond the densest air at the surface.
constexpr double AirDensityMin = 1e-6, AirDensityMax = 10.0;

// The gas constant of dry air, J/(kg K), and standard gravity, m/s^2 (US Standard Atmosphere 1976).
constexpr double DryAirGasConstant = 287.05287;
constexpr double StandardGravity = 9.80665;

// The air at a height, of the ICAO standard atmosphere (identical to the US Standard Atmosphere
// 1976 up to 86 km): temperature in K, pressure in Pa, density in kg/m^3. The height is geometric,
// in metres above sea level, turned into geopotential height for the layers' lapse rates; the
// pressure is hydrostatic. Empty outside [StandardAtmosphereBottom, StandardAtmosphereTop].
struct AirState
{
  double Temperature = 0.0, Pressure = 0.0, Density = 0.0;
};
constexpr double StandardAtmosphereBottom = -5000.0, StandardAtmosphereTop = 86000.0;
std::optional<AirState> StandardAtmosphere(double heightMetres);

} // namespace cloudvis

#endif
