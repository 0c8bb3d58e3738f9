// Files as LES models write their 3-D output (issue 34): DALES, MicroHH, SAM, PALM, UCLA-LES and
// WRF, each made by ncgen from CDL laid out as the model's documentation describes it (its
// dimension and coordinate names, staggered grids, units, variable names and order), holding
// the same two cumulus clouds. Each is read right: its cloud water chosen over the wind before
// it, on a lattice of 50 m columns and 25 m levels (PALM's first level, at the surface, is half a
// step; WRF's heights are its geopotential), as liquid water in g/m^3 with the same liquid water
// path; and `cloudvis render FILE` with no scene shows the cloud with no pixel clipped. Part of
// cloudvis-field-format-tests.
#include "FieldTestFiles.h"

#include "FieldUnits.h"
#include "SupportImages.h"
#include "SupportRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>
#include <sstream>

namespace
{

using namespace cloudvis::support;
using namespace cloudvis::test;
using json = nlohmann::json;

// The domain: 24 x 24 columns 50 m wide, 16 levels 25 m deep (cell centres at 12.5, 37.5, ...).
constexpr int Columns = 24, Levels = 16;
constexpr double Dx = 50.0, Dz = 25.0;

// Two cumulus blobs of liquid water up to 1.1 g/kg above 200 m, at (x, y, z) in metres.
double CloudWater(double x, double y, double z)
{
  const double blobs[2][3] = { { 400.0, 500.0, 220.0 }, { 850.0, 700.0, 160.0 } };
  const double h = z - 200.0;
  double q = 0.0;
  for (const auto& b : blobs)
  {
    const double f = 1.0 - std::hypot(x - b[0], y - b[1], h - b[2] / 2) / b[2];
    q = std::max(q, h > 0.0 ? 1.1e-3 * f : 0.0);
  }
  return q;
}

// CDL numbers, comma separated.
std::string List(int n, const std::function<double(int)>& value)
{
  std::ostringstream text;
  for (int i = 0; i < n; ++i)
  {
    text << (i ? ", " : "") << value(i);
  }
  return text.str();
}

// The values of a variable on dimensions whose spatial order is `order` (slowest first, each of
// 'x', 'y', 'z'), as `value(i, j, k)` gives them at column (i, j) and level k.
std::string Values(const std::string& order, const std::function<double(int, int, int)>& value)
{
  std::ostringstream text;
  int index[3] = { 0, 0, 0 }; // i, j, k
  const auto axisOf = [](char c) { return c == 'x' ? 0 : c == 'y' ? 1 : 2; };
  const int n[3] = { Columns, Columns, Levels };
  bool first = true;
  for (index[axisOf(order[0])] = 0; index[axisOf(order[0])] < n[axisOf(order[0])];
       ++index[axisOf(order[0])])
    for (index[axisOf(order[1])] = 0; index[axisOf(order[1])] < n[axisOf(order[1])];
         ++index[axisOf(order[1])])
      for (index[axisOf(order[2])] = 0; index[axisOf(order[2])] < n[axisOf(order[2])];
           ++index[axisOf(order[2])])
      {
        text << (first ? "" : ", ") << value(index[0], index[1], index[2]);
        first = false;
      }
  return text.str();
}

// The cloud water at cell centres in kg/kg, times `scale`.
std::function<double(int, int, int)> Cloud(double scale = 1.0)
{
  return [scale](int i, int j, int k)
  { return scale * CloudWater(Dx * (i + 0.5), Dx * (j + 0.5), Dz * (k + 0.5)); };
}

const std::string Centres = List(Columns, [](int i) { return Dx * (i + 0.5); });
const std::string Faces = List(Columns, [](int i) { return Dx * i; });
const std::string LevelCentres = List(Levels, [](int k) { return Dz * (k + 0.5); });
const std::string LevelFaces = List(Levels, [](int k) { return Dz * k; });

// DALES's field dump (fielddump.001.nc): coordinates xt, yt, zt at the cells' centres and xm,
// ym, zm at their faces; u on xm and w on zm before ql, all in kg/kg or m/s.
std::string Dales()
{
  return "netcdf fielddump {\ndimensions: time = UNLIMITED ; zt = 16 ; zm = 16 ; yt = 24 ; "
         "ym = 24 ; xt = 24 ; xm = 24 ;\nvariables:\n"
         "  double time(time) ; time:units = \"s\" ;\n"
         "  float zt(zt) ; zt:units = \"m\" ; zt:long_name = \"Vertical position of cell "
         "centers\" ;\n  float zm(zm) ; zm:units = \"m\" ;\n"
         "  float yt(yt) ; yt:units = \"m\" ;\n  float ym(ym) ; ym:units = \"m\" ;\n"
         "  float xt(xt) ; xt:units = \"m\" ;\n  float xm(xm) ; xm:units = \"m\" ;\n"
         "  float u(time, zt, yt, xm) ; u:units = \"m/s\" ; u:long_name = \"West-East velocity\" "
         ";\n"
         "  float w(time, zm, yt, xt) ; w:units = \"m/s\" ;\n"
         "  float thl(time, zt, yt, xt) ; thl:units = \"K\" ;\n"
         "  float ql(time, zt, yt, xt) ; ql:units = \"kg/kg\" ; ql:long_name = \"Liquid water "
         "mixing ratio\" ;\ndata:\n  time = 3600 ;\n  zt = " +
    LevelCentres + " ;\n  zm = " + LevelFaces + " ;\n  yt = " + Centres + " ;\n  ym = " + Faces +
    " ;\n  xt = " + Centres + " ;\n  xm = " + Faces + " ;\n  ql = " + Values("zyx", Cloud()) +
    " ;\n}\n";
}

// MicroHH's 3-D output as its scripts write NetCDF: x, y, z at centres, xh, yh, zh at faces,
// ql in kg kg-1.
std::string MicroHh()
{
  return "netcdf ql {\ndimensions: time = UNLIMITED ; z = 16 ; zh = 16 ; y = 24 ; yh = 24 ; "
         "x = 24 ; xh = 24 ;\nvariables:\n"
         "  double time(time) ; time:units = \"seconds since start\" ;\n"
         "  double z(z) ; z:units = \"m\" ;\n  double zh(zh) ; zh:units = \"m\" ;\n"
         "  double y(y) ; y:units = \"m\" ;\n  double yh(yh) ; yh:units = \"m\" ;\n"
         "  double x(x) ; x:units = \"m\" ;\n  double xh(xh) ; xh:units = \"m\" ;\n"
         "  float u(time, z, y, xh) ; u:units = \"m s-1\" ;\n"
         "  float ql(time, z, y, x) ; ql:units = \"kg kg-1\" ; ql:long_name = \"Liquid water "
         "specific humidity\" ;\ndata:\n  time = 7200 ;\n  z = " +
    LevelCentres + " ;\n  zh = " + LevelFaces + " ;\n  y = " + Centres + " ;\n  yh = " + Faces +
    " ;\n  x = " + Centres + " ;\n  xh = " + Faces + " ;\n  ql = " + Values("zyx", Cloud()) +
    " ;\n}\n";
}

// SAM's 3-D output (com3D2nc): x, y, z in m, the pressure profile p in mb, TABS in K, QV and
// QN (non-precipitating condensate) in g/kg, U and W before them.
std::string Sam()
{
  const auto standard = [](int k) { return *cloudvis::StandardAtmosphere(Dz * (k + 0.5)); };
  return "netcdf sam3d {\ndimensions: x = 24 ; y = 24 ; z = 16 ; time = UNLIMITED ;\n"
         "variables:\n  float x(x) ; x:units = \"m\" ;\n  float y(y) ; y:units = \"m\" ;\n"
         "  float z(z) ; z:units = \"m\" ; z:long_name = \"height\" ;\n"
         "  float time(time) ; time:units = \"d\" ;\n"
         "  float p(z) ; p:units = \"mb\" ; p:long_name = \"pressure\" ;\n"
         "  float U(time, z, y, x) ; U:units = \"m/s\" ;\n"
         "  float W(time, z, y, x) ; W:units = \"m/s\" ;\n"
         "  float TABS(time, z, y, x) ; TABS:units = \"K\" ;\n"
         "  float QV(time, z, y, x) ; QV:units = \"g/kg\" ;\n"
         "  float QN(time, z, y, x) ; QN:units = \"g/kg\" ; QN:long_name = \"Non-precipitating "
         "Condensate (Water+Ice)\" ;\ndata:\n  x = " +
    Centres + " ;\n  y = " + Centres + " ;\n  z = " + LevelCentres + " ;\n  time = 0.125 ;\n" +
    "  p = " + List(Levels, [&](int k) { return standard(k).Pressure / 100.0; }) + " ;\n" +
    "  TABS = " + Values("zyx", [&](int, int, int k) { return standard(k).Temperature; }) +
    " ;\n  QV = " + Values("zyx", [](int, int, int) { return 0.0; }) +
    " ;\n  QN = " + Values("zyx", Cloud(1000.0)) + " ;\n}\n";
}

// PALM's DATA_3D_NETCDF: zu_3d from the surface (0, then half a step, then whole steps), zw_3d,
// x and xu, y and yv in "meters", ql in kg/kg.
std::string Palm()
{
  const std::string zu = "0, " + LevelCentres;
  return "netcdf palm3d {\ndimensions: time = UNLIMITED ; zu_3d = 17 ; zw_3d = 17 ; y = 24 ; "
         "yv = 24 ; x = 24 ; xu = 24 ;\nvariables:\n"
         "  double time(time) ; time:units = \"seconds\" ;\n"
         "  double zu_3d(zu_3d) ; zu_3d:units = \"meters\" ;\n"
         "  double zw_3d(zw_3d) ; zw_3d:units = \"meters\" ;\n"
         "  double y(y) ; y:units = \"meters\" ;\n  double yv(yv) ; yv:units = \"meters\" ;\n"
         "  double x(x) ; x:units = \"meters\" ;\n  double xu(xu) ; xu:units = \"meters\" ;\n"
         "  float u(time, zu_3d, y, xu) ; u:units = \"m/s\" ;\n"
         "  float ql(time, zu_3d, y, x) ; ql:units = \"kg/kg\" ;\ndata:\n  time = 3600 ;\n"
         "  zu_3d = " +
    zu + " ;\n  zw_3d = " + LevelFaces + ", 400 ;\n  y = " + Centres + " ;\n  yv = " + Faces +
    " ;\n  x = " + Centres + " ;\n  xu = " + Faces +
    " ;\n  ql = " + List(Columns * Columns, [](int) { return 0.0; }) + ", " +
    Values("zyx", Cloud()) + " ;\n}\n";
}

// UCLA-LES's 3-D output: its arrays on (time, xt, yt, zt), z fastest, with xm, ym, zm at the
// faces; l is the liquid water mixing ratio in kg/kg.
std::string UclaLes()
{
  return "netcdf rico {\ndimensions: time = UNLIMITED ; zt = 16 ; zm = 16 ; xt = 24 ; xm = 24 ; "
         "yt = 24 ; ym = 24 ;\nvariables:\n  float time(time) ; time:units = \"s\" ;\n"
         "  float zt(zt) ; zt:units = \"m\" ;\n  float zm(zm) ; zm:units = \"m\" ;\n"
         "  float xt(xt) ; xt:units = \"m\" ;\n  float xm(xm) ; xm:units = \"m\" ;\n"
         "  float yt(yt) ; yt:units = \"m\" ;\n  float ym(ym) ; ym:units = \"m\" ;\n"
         "  float u(time, xm, yt, zt) ; u:units = \"m/s\" ;\n"
         "  float l(time, xt, yt, zt) ; l:longname = \"Liquid water mixing ratio\" ; "
         "l:units = \"kg/kg\" ;\ndata:\n  time = 3600 ;\n  zt = " +
    LevelCentres + " ;\n  zm = " + LevelFaces + " ;\n  xt = " + Centres + " ;\n  xm = " + Faces +
    " ;\n  yt = " + Centres + " ;\n  ym = " + Faces + " ;\n  l = " + Values("xyz", Cloud()) +
    " ;\n}\n";
}

// WRF's wrfout: no coordinate variables; DX and DY as global attributes; the heights are the
// geopotential PH (perturbation) + PHB (base) on the staggered levels, over g; QCLOUD in
// kg kg-1 on the mass grid, U on west_east_stag before it; T is WRF's perturbation potential
// temperature, P its perturbation pressure.
std::string Wrf()
{
  const double g = cloudvis::StandardGravity;
  const std::string stag = "Time, bottom_top_stag, south_north, west_east";
  std::ostringstream ph, phb;
  for (int k = 0; k <= Levels; ++k)
    for (int c = 0; c < Columns * Columns; ++c)
    {
      ph << (k + c ? ", " : "") << (c % 2 ? 0.5 : -0.5);
      phb << (k + c ? ", " : "") << g * Dz * k;
    }
  return "netcdf wrfout_d01 {\ndimensions: Time = UNLIMITED ; DateStrLen = 19 ; west_east = 24 "
         "; south_north = 24 ; bottom_top = 16 ; bottom_top_stag = 17 ; west_east_stag = 25 ;\n"
         "variables:\n  char Times(Time, DateStrLen) ;\n"
         "  float U(Time, bottom_top, south_north, west_east_stag) ; U:units = \"m s-1\" ;\n"
         "  float T(Time, bottom_top, south_north, west_east) ; T:units = \"K\" ; "
         "T:description = \"perturbation potential temperature (theta-t0)\" ;\n"
         "  float P(Time, bottom_top, south_north, west_east) ; P:units = \"Pa\" ;\n"
         "  float PH(" +
    stag + ") ; PH:units = \"m2 s-2\" ;\n  float PHB(" + stag +
    ") ; PHB:units = \"m2 s-2\" ;\n"
    "  float QCLOUD(Time, bottom_top, south_north, west_east) ; QCLOUD:units = \"kg kg-1\" ; "
    "QCLOUD:description = \"Cloud water mixing ratio\" ;\n"
    "  :DX = 50.f ; :DY = 50.f ; :TITLE = \" OUTPUT FROM WRF V4.4 MODEL\" ;\ndata:\n"
    "  Times = \"2020-01-01_01:00:00\" ;\n  PH = " +
    ph.str() + " ;\n  PHB = " + phb.str() + " ;\n  QCLOUD = " + Values("zyx", Cloud()) + " ;\n}\n";
}

struct Model
{
  const char* Name;
  std::string (*Cdl)();
  const char* Variable;
  double LowestLevel; // of the lattice, m
  double LevelStep;   // m
  // Of the liquid water path against the hand computation: float rounding, except where the
  // levels are resampled (PALM's half first step: linear between levels, 2.2% less).
  double PathTolerance;
};

void PrintTo(const Model& model, std::ostream* out)
{
  *out << model.Name;
}

class LesModel : public ::testing::TestWithParam<Model>
{
};

TEST_P(LesModel, IsReadRightAndRendersItsCloudWithNoScene)
{
  const Model& model = GetParam();
  TemporaryDirectory dir;
  const std::string path = Ncgen(dir, std::string(model.Name) + ".nc", model.Cdl(), 3);
  const auto info = RunCloudvis({ "info", path, "--json" });
  ASSERT_EQ(info.Status, 0) << info.Err;
  const json report = json::parse(info.Out);
  EXPECT_NE(
    report["source"]["variable"].get<std::string>().find("\"" + std::string(model.Variable) + "\""),
    std::string::npos)
    << report["source"];
  for (int a = 0; a < 3; ++a)
  {
    // WRF's heights are float geopotentials over g: 25 m to 1e-6.
    EXPECT_NEAR(report["spacing"][a].get<double>(), a < 2 ? Dx : model.LevelStep, 1e-4)
      << report["spacing"];
  }
  EXPECT_NEAR(report["origin"][2].get<double>(), model.LowestLevel, 1e-3);
  EXPECT_EQ(report["units"]["quantity"], "lwc");
  EXPECT_EQ(report["units"]["length_unit"], "m");
  EXPECT_EQ(report["units"]["up"], "z");
  // The same cloud in every file: its liquid water path with the standard atmosphere, 1.1 g/kg
  // at the cores, against DALES's cell-centred grid worked out the same way.
  double path0 = 0.0;
  for (int j = 0; j < Columns; ++j)
    for (int i = 0; i < Columns; ++i)
      for (int k = 0; k < Levels; ++k)
      {
        const double z = Dz * (k + 0.5);
        path0 += 1000.0 * Cloud()(i, j, k) * cloudvis::StandardAtmosphere(z)->Density * Dz;
      }
  const double lwp = report["clouds"]["mean_path"].get<double>();
  EXPECT_NEAR(lwp / (path0 / (Columns * Columns)), 1.0, model.PathTolerance) << lwp << " g/m^2";

  const auto run = RunCloudvis({ "render", path, "-o", dir.File("les.png"), "--size", "160x120" });
  ASSERT_EQ(run.Status, 0) << run.Err;
  const CloudPixels cloud = CountCloud(ReadPng(dir.File("les.png")));
  EXPECT_GT(cloud.Cloud, 400u) << "the two clouds cover a good part of the picture";
  EXPECT_EQ(cloud.Clipped, 0u);
}

INSTANTIATE_TEST_SUITE_P(Files,
  LesModel,
  ::testing::Values(Model{ "DALES", Dales, "ql", 12.5, Dz, 5e-6 },
    Model{ "MicroHH", MicroHh, "ql", 12.5, Dz, 5e-6 },
    Model{ "SAM", Sam, "QN", 12.5, Dz, 5e-6 },
    Model{ "PALM", Palm, "ql", 0.0, Dz / 2, 0.05 },
    Model{ "UCLA_LES", UclaLes, "l", 12.5, Dz, 5e-6 },
    Model{ "WRF", Wrf, "QCLOUD", 12.5, Dz, 5e-6 }),
  [](const ::testing::TestParamInfo<Model>& model) { return std::string(model.param.Name); });

} // namespace
