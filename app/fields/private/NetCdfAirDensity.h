// A field of mixing ratios made a liquid water content, as the NetCDF reader reads it: LES codes
// write the cloud's liquid water in kg/kg or g/kg, and LWC (g/m^3) = ratio (g/kg) x the air's
// density (kg/m^3). Where the density comes from is the scene's field.air_density
// (AirDensitySource, FieldUnits.h); "auto", the default, takes the first of
//   1. a variable of the file holding it: by standard_name "air_density", else by a name LES codes
//      use (rho, rhof, rhobf, rhoref, ...), on the field's spatial dimensions or a profile along
//      its vertical one;
//   2. pressure and temperature (ideal gas: rho = p / (R_d T_v), with the virtual temperature
//      T_v = T (1 + 0.608 q_v) where the file holds the vapour's mixing ratio or specific
//      humidity), by standard_name, else by name;
//   3. the ICAO standard atmosphere at the heights of the vertical axis, when it is a height in
//      metres or kilometres.
// The report names the source and the densities used. A source the scene asks for that the file
// cannot give, an air density variable of the wrong units or shape, missing values, and densities
// that are not positive are refused, naming the file and the variable.
#ifndef cloudvis_NetCdfAirDensity_h
#define cloudvis_NetCdfAirDensity_h

#include "FieldIO.h"
#include "NetCdfVariables.h"

#include <vtkSmartPointer.h>

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

class vtkFloatArray;

namespace cloudvis
{
namespace netcdf
{

// The field being read, as the sources of the air's density need it: its lattice in the file's
// coordinates (before any resampling), x fastest, each axis increasing.
struct FieldLattice
{
  const File& Source;
  const Variable& Chosen;
  const Layout& Axes;
  std::size_t Step = 0; // the time step read
  // Each axis's coordinates, increasing, in the file's units (its indices where it has none).
  std::array<std::vector<double>, 3> Coordinates;
  bool ZReversed = false; // the file stores z decreasing
  // Reads a variable whose spatial dimensions are the field's onto the lattice, as the field's
  // values were read (missing values refused, packing undone).
  std::function<vtkSmartPointer<vtkFloatArray>(const Variable&)> ReadVolume;
};

// When the chosen variable's units (with its standard_name) are a mixing ratio: its values
// `values`, on `lattice`, become a liquid water content in g/m^3, in place, with the air's density
// from options.AirDensity, and report.Units.Quantity becomes lwc; each step is said in the report
// ("quantity", "air density", "converted"). Not when the scene reads the field as a density
// (field.quantity "density"), nor under "auto" when the file gives no density and its vertical
// axis is not a height (the report says why, and what sets one; a scene that declares
// field.quantity "lwc" is refused then). Throws InputError naming the file otherwise (see above).
// Returns whether the units were a mixing ratio.
bool ConvertMixingRatio(const FieldLattice& lattice,
  const FieldReadOptions& options,
  vtkFloatArray* values,
  FieldReport& report);

} // namespace netcdf
} // namespace cloudvis

#endif
