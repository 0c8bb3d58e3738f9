// Mixing ratios as LES codes write them become liquid water contents with the air's density
// (NetCdfAirDensity.h, issue 34): the ICAO standard atmosphere against the US Standard
// Atmosphere 1976's table, the liquid water path of a kg/kg field against the hydrostatic
// integral worked by hand, each source of the density (a profile in the file, pressure and
// temperature with the humidity, a number, a named variable), and each refusal. The files are
// made by ncgen from CDL. Part of cloudvis-field-format-tests.
#include "FieldTestFiles.h"

#include "FieldUnits.h"
#include "SupportRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vtkImageData.h>

#include <cmath>
#include <sstream>

namespace
{

using cloudvis::AirDensitySource;
using cloudvis::FieldQuantity;
using cloudvis::FieldReadOptions;
using cloudvis::FieldReport;
using namespace cloudvis::support;
using namespace cloudvis::test;

TEST(AirDensity, StandardAtmosphereMatchesTheTable)
{
  // US Standard Atmosphere 1976 (NOAA-S/T 76-1562), table I, at geometric heights: temperature
  // K, pressure Pa, density kg/m^3, each printed to 5 or 6 figures (a relative rounding of up
  // to 5e-5).
  struct Row
  {
    double Height, Temperature, Pressure, Density;
  };
  const Row table[] = { { -1000.0, 294.651, 113929.0, 1.34700 },
    { 0.0, 288.150, 101325.0, 1.22500 },
    { 1000.0, 281.651, 89874.6, 1.11164 },
    { 5000.0, 255.676, 54048.3, 0.736429 },
    { 11000.0, 216.774, 22699.9, 0.364801 },
    { 20000.0, 216.650, 5529.31, 0.0889097 },
    { 32000.0, 228.490, 889.063, 0.0135551 },
    { 50000.0, 270.650, 79.7790, 0.00102688 },
    { 80000.0, 198.639, 1.05243, 0.0000184580 } };
  for (const Row& row : table)
  {
    const auto air = cloudvis::StandardAtmosphere(row.Height);
    ASSERT_TRUE(air) << row.Height;
    EXPECT_NEAR(air->Temperature, row.Temperature, 2e-3) << row.Height;
    EXPECT_NEAR(air->Pressure / row.Pressure, 1.0, 1e-4) << row.Height;
    EXPECT_NEAR(air->Density / row.Density, 1.0, 1e-4) << row.Height;
  }
  EXPECT_FALSE(cloudvis::StandardAtmosphere(-6000.0));
  EXPECT_FALSE(cloudvis::StandardAtmosphere(90000.0));
  EXPECT_FALSE(cloudvis::StandardAtmosphere(std::nan("")));
}

// A field dump of 3 x 2 columns 50 m wide and `levels` levels 10 m deep from `bottom` m (cell
// centres at bottom + 5, + 15, ..., stored from the top down when `descending`), "ql" of `ratio`
// in `units` in every voxel, with the variables `declarations` and their `data` (CDL) added, and
// the vertical coordinate's `zAttributes`.
std::string Dump(const TemporaryDirectory& dir,
  const std::string& name,
  const std::string& units,
  double ratio,
  const std::string& declarations = "",
  const std::string& data = "",
  double bottom = 1000.0,
  int levels = 200,
  const std::string& zAttributes = "z:units = \"m\" ;",
  bool descending = false)
{
  std::ostringstream cdl, z, ql;
  for (int k = 0; k < levels; ++k)
  {
    z << (k ? ", " : "") << bottom + 5.0 + 10.0 * (descending ? levels - 1 - k : k);
    for (int c = 0; c < 6; ++c)
    {
      ql << (k + c ? ", " : "") << ratio;
    }
  }
  cdl << "netcdf dump {\ndimensions: z = " << levels << " ; y = 2 ; x = 3 ;\nvariables:\n"
      << "  double z(z) ; " << zAttributes << "\n  double y(y) ; y:units = \"m\" ;\n"
      << "  double x(x) ; x:units = \"m\" ;\n  float ql(z, y, x) ; ql:units = \"" << units
      << "\" ;\n"
      << declarations << "\ndata:\n  z = " << z.str() << " ;\n  y = 0, 50 ;\n  x = 0, 50, 100 ;\n"
      << "  ql = " << ql.str() << " ;\n"
      << data << "\n}\n";
  return Ncgen(dir, name, cdl.str());
}

// The pressure of the standard atmosphere's troposphere at geometric height h, by its closed form
// (US Standard Atmosphere 1976, eq. 33a): an independent copy for the hand computation.
double TroposphericPressure(double h)
{
  const double geopotential = 6356766.0 * h / (6356766.0 + h);
  return 101325.0 * std::pow(1.0 - 0.0065 * geopotential / 288.15, 9.80665 / (287.05287 * 0.0065));
}

TEST(AirDensity, LiquidWaterPathOfAMixingRatioIsTheHydrostaticIntegral)
{
  TemporaryDirectory dir;
  // 1 g/kg of liquid water from 1 to 3 km: LWP = 1 g/kg x the air's mass per m^2 in the layer,
  // which hydrostatic balance makes the pressure difference over gravity, (p(1 km) - p(3 km)) / g,
  // with g at the layer's middle (gravity falls as (r / (r + h))^2 with height h, 6e-4 at 2 km).
  const std::string path = Dump(dir, "q.nc", "kg/kg", 1e-3);
  const double gravity = 9.80665 * std::pow(6356766.0 / (6356766.0 + 2000.0), 2);
  const double byHand =
    1.0 * (TroposphericPressure(1000.0) - TroposphericPressure(3000.0)) / gravity;
  const auto run = RunCloudvis({ "info", path, "--json" });
  ASSERT_EQ(run.Status, 0) << run.Err;
  const auto info = nlohmann::json::parse(run.Out);
  const double lwp = info["clouds"]["mean_cloudy_path"].get<double>();
  EXPECT_NEAR(lwp / byHand, 1.0, 1e-4) << lwp << " g/m^2 against " << byHand;
  // g/kg is a thousandth of kg/kg.
  const auto grams =
    nlohmann::json::parse(RunCloudvis({ "info", Dump(dir, "g.nc", "g kg-1", 1.0), "--json" }).Out);
  EXPECT_NEAR(grams["clouds"]["mean_cloudy_path"].get<double>() / byHand, 1.0, 1e-4);
  // info says where the density came from and what it was.
  const std::string text = RunCloudvis({ "info", path }).Out;
  EXPECT_NE(text.find("quantity     lwc (liquid water content: a mixing ratio in kg/kg times the "
                      "air's density)"),
    std::string::npos)
    << text;
  EXPECT_NE(text.find("air density  1.11111 .. 0.909722 kg/m^3 (bottom .. top): the ICAO "
                      "standard atmosphere at the heights of z, 1005 .. 2995 m"),
    std::string::npos)
    << text;
}

// The field's value at voxel (i, j, k).
double LwcAt(vtkImageData* field, int i, int j, int k)
{
  return Density(field, i, j, k);
}

TEST(AirDensity, TheFilesProfileComesBeforeTheStandardAtmosphere)
{
  TemporaryDirectory dir;
  // DALES's rhof: the base state's density on the full levels, a profile along z.
  std::ostringstream rho;
  for (int k = 0; k < 4; ++k)
  {
    rho << (k ? ", " : "") << 1.0 - 0.1 * k;
  }
  const std::string path = Dump(dir,
    "p.nc",
    "kg/kg",
    2e-3,
    "  float rhof(z) ; rhof:units = \"kg/m3\" ;",
    "  rhof = " + rho.str() + " ;",
    0.0,
    4);
  FieldReport report;
  auto field = cloudvis::ReadField(path, {}, &report);
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_NEAR(LwcAt(field, 2, 1, k), 2.0 * (1.0 - 0.1 * k), 1e-6) << k;
  }
  EXPECT_EQ(report.Resolved.Quantity, FieldQuantity::Lwc);
  EXPECT_EQ(Detail(report, "air density"),
    "1 .. 0.7 kg/m^3 (bottom .. top): variable \"rhof\" (a profile along \"z\")");
  // Stored from the top down, the profile is turned around with the field: its first value is the
  // top's.
  const std::string reversed = Dump(dir,
    "r.nc",
    "kg/kg",
    2e-3,
    "  float rhof(z) ; rhof:units = \"kg/m3\" ;",
    "  rhof = " + rho.str() + " ;",
    0.0,
    4,
    "z:units = \"m\" ;",
    true);
  field = cloudvis::ReadField(reversed, {}, &report);
  EXPECT_NEAR(LwcAt(field, 0, 0, 0), 2.0 * 0.7, 1e-6);
  EXPECT_NEAR(LwcAt(field, 0, 0, 3), 2.0 * 1.0, 1e-6);
}

TEST(AirDensity, PressureAndTemperatureGiveTheIdealGasWithTheVirtualTemperature)
{
  TemporaryDirectory dir;
  // SAM's 3-D output has p (hPa, a profile), TABS (K) and QV (g/kg): the profile and the
  // volumes combine into a volume of densities.
  const std::string path = Dump(dir,
    "pt.nc",
    "g/kg",
    1.0,
    "  float p(z) ; p:units = \"hPa\" ;\n  float TABS(z, y, x) ; TABS:units = \"K\" ;\n"
    "  float QV(z, y, x) ; QV:units = \"g/kg\" ;",
    "  p = 900, 800 ;\n  TABS = 280, 280, 280, 280, 280, 280, 270, 270, 270, 270, 270, 270 ;\n"
    "  QV = 10, 10, 10, 10, 10, 10, 0, 0, 0, 0, 0, 0 ;",
    1000.0,
    2);
  FieldReport report;
  auto field = cloudvis::ReadField(path, {}, &report);
  const double R = cloudvis::DryAirGasConstant;
  EXPECT_EQ(report.Resolved.Quantity, FieldQuantity::Lwc);
  EXPECT_NEAR(LwcAt(field, 1, 1, 0), 90000.0 / (R * 280.0 * (1.0 + 0.608 * 0.01)), 1e-5);
  EXPECT_NEAR(LwcAt(field, 1, 1, 1), 80000.0 / (R * 270.0), 1e-5);
  EXPECT_EQ(Detail(report, "air density"),
    "1.0322 .. 1.11299 kg/m^3: ideal gas from pressure \"p\" (a profile along \"z\") and "
    "temperature \"TABS\" (3-D), virtual temperature with humidity \"QV\"");

  const std::string volumes = Dump(dir,
    "pt3.nc",
    "g/kg",
    1.0,
    "  float p(z, y, x) ; p:units = \"hPa\" ;\n  float TABS(z, y, x) ; TABS:units = \"K\" ;\n"
    "  float QV(z, y, x) ; QV:units = \"g/kg\" ;",
    "  p = 900, 900, 900, 900, 900, 900, 800, 800, 800, 800, 800, 800 ;\n"
    "  TABS = 280, 280, 280, 280, 280, 280, 270, 270, 270, 270, 270, 270 ;\n"
    "  QV = 10, 10, 10, 10, 10, 10, 0, 0, 0, 0, 0, 0 ;",
    1000.0,
    2);
  field = cloudvis::ReadField(volumes, {}, &report);
  EXPECT_NEAR(LwcAt(field, 1, 1, 0), 90000.0 / (R * 280.0 * (1.0 + 0.608 * 0.01)), 1e-5);
  EXPECT_NEAR(LwcAt(field, 1, 1, 1), 80000.0 / (R * 270.0), 1e-5);
  EXPECT_EQ(Detail(report, "air density"),
    "1.0322 .. 1.11299 kg/m^3: ideal gas from pressure \"p\" (3-D) and temperature \"TABS\" "
    "(3-D), virtual temperature with humidity \"QV\"");
  // Without the humidity, the temperature itself.
  const std::string dry = Dump(dir,
    "dry.nc",
    "g/kg",
    1.0,
    "  float p(z) ; p:units = \"Pa\" ;\n  float T(z) ; T:units = \"degC\" ;",
    "  p = 90000, 80000 ;\n  T = 6.85, -3.15 ;",
    1000.0,
    2);
  field = cloudvis::ReadField(dry, {}, &report);
  EXPECT_NEAR(LwcAt(field, 0, 0, 0), 90000.0 / (R * 280.0), 1e-5);
  EXPECT_NE(Detail(report, "air density")
              .find("not the virtual temperature: the file holds no "
                    "humidity"),
    std::string::npos);
}

TEST(AirDensity, ANumberOrANamedVariable)
{
  TemporaryDirectory dir;
  const std::string path = Dump(dir,
    "n.nc",
    "kg kg-1",
    1e-3,
    "  float density2(z) ; density2:units = \"g m-3\" ;",
    "  density2 = 500, 400 ;",
    0.0,
    2);
  FieldReadOptions options;
  options.AirDensity = { AirDensitySource::Kind::Number, 0.5, "" };
  FieldReport report;
  auto field = cloudvis::ReadField(path, options, &report);
  EXPECT_NEAR(LwcAt(field, 0, 0, 1), 0.5, 1e-6);
  EXPECT_EQ(Detail(report, "air density"), "0.5 kg/m^3: field.air_density");
  options.AirDensity = { AirDensitySource::Kind::Variable, 0.0, "density2" };
  field = cloudvis::ReadField(path, options, &report);
  EXPECT_NEAR(LwcAt(field, 0, 0, 1), 0.4, 1e-6);
  // Without a source in the file, "auto" is the standard atmosphere at 5 and 15 m.
  field = cloudvis::ReadField(path, {}, &report);
  EXPECT_NEAR(LwcAt(field, 0, 0, 0), cloudvis::StandardAtmosphere(5.0)->Density, 1e-6);
  // Read as a density, the values stay the file's.
  options = {};
  options.Units.Quantity = FieldQuantity::Density;
  field = cloudvis::ReadField(path, options, &report);
  EXPECT_FLOAT_EQ(float(LwcAt(field, 0, 0, 0)), 1e-3f);
  EXPECT_EQ(Detail(report, "quantity"),
    "density: a mixing ratio in kg kg-1, kept as stored (the scene's field.quantity \"density\")");
  // The scene's key, as a user writes it.
  const auto run = RunCloudvis({ "info", path, "--set", "field.air_density=variable:density2" });
  EXPECT_NE(run.Out.find("air density  0.5 .. 0.4 kg/m^3 (bottom .. top): variable \"density2\""),
    std::string::npos)
    << run.Out << run.Err;
}

TEST(AirDensity, WithoutAHeightAutoKeepsTheRatiosAndSaysWhy)
{
  TemporaryDirectory dir;
  const std::string path =
    Dump(dir, "d.nc", "kg/kg", 1e-3, "", "", 0.0, 2, "z:units = \"m\" ; z:positive = \"down\" ;");
  FieldReport report;
  auto field = cloudvis::ReadField(path, {}, &report);
  EXPECT_EQ(report.Resolved.Quantity, FieldQuantity::Density);
  EXPECT_FLOAT_EQ(float(LwcAt(field, 0, 0, 0)), 1e-3f);
  EXPECT_EQ(Detail(report, "quantity"),
    "density: a mixing ratio in kg/kg, not converted to a liquid water content: that needs the "
    "air's density, and none was found (the file holds no air density; no pressure and "
    "temperature; no standard atmosphere: the vertical axis is not a height (units \"m\", "
    "positive \"down\") (field.up says which axis is up)); field.air_density \"standard\", a "
    "number in kg/m^3 or \"variable:NAME\" gives one");
  // Declared a liquid water content, it is refused.
  FieldReadOptions lwc;
  lwc.Units.Quantity = FieldQuantity::Lwc;
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path, lwc); })
              .find(path +
                ": variable \"ql\" holds a mixing ratio in kg/kg: a liquid water "
                "content (field.quantity \"lwc\") needs the air's density"),
    std::string::npos);
  // field.up and field.length_unit make the standard atmosphere possible.
  lwc.Units.Up = 2;
  field = cloudvis::ReadField(path, lwc, &report);
  EXPECT_NEAR(LwcAt(field, 0, 0, 1), cloudvis::StandardAtmosphere(15.0)->Density, 1e-6);
}

TEST(AirDensity, SourcesThatCannotBeUsedAreRefused)
{
  TemporaryDirectory dir;
  const auto refusal = [](const std::string& path, const FieldReadOptions& options)
  { return ErrorOf([&] { cloudvis::ReadField(path, options); }); };
  const std::string plain = Dump(dir, "plain.nc", "kg/kg", 1e-3, "", "", 0.0, 2);
  FieldReadOptions named;
  named.AirDensity = { AirDensitySource::Kind::Variable, 0.0, "rho" };
  EXPECT_EQ(refusal(plain, named), plain + ": field.air_density: no variable named \"rho\"");

  const auto withRho =
    [&](const std::string& name, const std::string& declaration, const std::string& data)
  { return Dump(dir, name, "kg/kg", 1e-3, declaration, data, 0.0, 2); };
  const std::string kelvin =
    withRho("kelvin.nc", "  float rho(z) ; rho:units = \"K\" ;", "  rho = 1, 1 ;");
  EXPECT_EQ(refusal(kelvin, {}),
    kelvin +
      ": the air density variable \"rho\" has units \"K\", not a density (kg m-3); "
      "field.air_density \"standard\" or a number in kg/m^3 gives the density another way");
  const std::string negative =
    withRho("negative.nc", "  float rho(z) ; rho:units = \"kg m-3\" ;", "  rho = 1, -1 ;");
  EXPECT_EQ(refusal(negative, {}),
    negative +
      ": the air density variable \"rho\": its values span -1 .. 1 kg/m^3, beyond the "
      "1e-06 .. 10 of air; field.air_density \"standard\" or a number in kg/m^3 gives "
      "the density another way");
  const std::string sideways =
    withRho("sideways.nc", "  float rho(y) ; rho:units = \"kg m-3\" ;", "  rho = 1, 1 ;");
  EXPECT_NE(refusal(sideways, {})
              .find("the air density variable \"rho\": it is on (y): neither "
                    "the field's dimensions (z, y, x) nor a profile along its "
                    "vertical one \"z\""),
    std::string::npos)
    << refusal(sideways, {});
  const std::string gaps = withRho("gaps.nc",
    "  float rho(z) ; rho:units = \"kg m-3\" ; rho:_FillValue = -1.f ;",
    "  rho = 1, -1 ;");
  EXPECT_NE(refusal(gaps, {}).find("it marks values as missing (_FillValue -1)"), std::string::npos)
    << refusal(gaps, {});
  const std::string holes = withRho("holes.nc",
    "  float rho(z, y, x) ; rho:units = \"kg m-3\" ; rho:_FillValue = -1.f ;",
    "  rho = 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, -1 ;");
  EXPECT_EQ(refusal(holes, {}),
    holes +
      ": variable \"rho\" holds 1 missing value (_FillValue -1): the air's density is "
      "needed at every voxel of \"ql\"; field.air_density \"standard\" or a number in "
      "kg/m^3 gives it another way");

  FieldReadOptions standard;
  standard.AirDensity = { AirDensitySource::Kind::Standard, 0.0, "" };
  const std::string high = Dump(dir, "high.nc", "kg/kg", 1e-3, "", "", 90000.0, 2);
  EXPECT_EQ(refusal(high, standard),
    high +
      ": field.air_density \"standard\": the heights of z reach 90005 m, beyond the "
      "standard atmosphere's -5000 .. 86000 m");
  const std::string lwc = Dump(dir, "lwc.nc", "g m-3", 0.5, "", "", 0.0, 2);
  EXPECT_EQ(refusal(lwc, standard),
    lwc +
      ": field.air_density: variable \"ql\" is not a mixing ratio (its units are \"g m-3\"): "
      "the air's density turns mixing ratios (kg/kg, g/kg) into liquid water contents");
  standard.Units.Quantity = FieldQuantity::Density;
  EXPECT_EQ(refusal(plain, standard),
    plain +
      ": field.air_density: the scene reads variable \"ql\" as a density (field.quantity "
      "\"density\"), which keeps its mixing ratios as stored");
  // Another format has no mixing ratios; the key's values are checked as the scene is read.
  ASSERT_EQ(
    RunCloudvis({ "generate", "--set", "field.dimensions=8", "-o", dir.File("f.vti") }).Status, 0);
  const auto vti =
    RunCloudvis({ "info", dir.File("f.vti"), "--set", "field.air_density=standard" });
  EXPECT_EQ(vti.Status, 1);
  EXPECT_NE(vti.Err.find("field.air_density: applies to NetCDF files only"), std::string::npos)
    << vti.Err;
  const auto bad = RunCloudvis({ "info", plain, "--set", "field.air_density=1e3" });
  EXPECT_EQ(bad.Status, 1);
  EXPECT_NE(bad.Err.find("field.air_density: expected \"auto\", \"standard\", a number of kg/m^3 "
                         "in [1e-06, 10] or \"variable:NAME\", got number 1000.0"),
    std::string::npos)
    << bad.Err;
}

} // namespace
