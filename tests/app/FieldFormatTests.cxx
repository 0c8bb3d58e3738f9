// The field formats cloudvis reads and writes (FieldIO.h), on files made here by each format's own
// library or tools: NetCDF files by the netCDF C library, NRRD files by teem's `unu make`,
// MetaImage and raw files by VTK's writers, .pvti files by cloudvis and read back by VTK. Values
// are known (a function of the voxel index), so each read is checked voxel for voxel, or after
// resampling against the interpolation it promises; geometry (origin, spacing, direction) against
// what the file states; and the hostile cases (truncated files, wrong types, sizes far beyond
// memory, non-finite values) are refused with the numbers in the message. OpenVDB has its own
// file (OpenVdbTests.cxx), the only test that includes OpenVDB's headers.
#include "FieldTestFiles.h"
#include "KnownFieldFiles.h"

#include "CommandLine.h"
#include "FieldPieces.h"
#include "Scene.h"
#include "SceneField.h"
#include "SupportRun.h"

#include <gtest/gtest.h>
#include <netcdf.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkImageWriter.h>
#include <vtkMatrix3x3.h>
#include <vtkMetaImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedShortArray.h>
#include <vtkXMLPImageDataReader.h>
#include <vtkXMLPImageDataWriter.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace
{

using cloudvis::FieldReadOptions;
using cloudvis::FieldReport;
using namespace cloudvis::support;
using namespace cloudvis::test;

void ExpectVector(const double* actual, std::array<double, 3> expected, double tolerance = 1e-12)
{
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(actual[a], expected[a], tolerance) << "component " << a;
  }
}

// Column `a` of the field's direction matrix: the world direction of index axis a.
std::array<double, 3> Axis(vtkImageData* field, int a)
{
  vtkMatrix3x3* d = field->GetDirectionMatrix();
  return { { d->GetElement(0, a), d->GetElement(1, a), d->GetElement(2, a) } };
}

// ---- NetCDF, written by the netCDF C library ---------------------------------------------------

#define NC_OK(call) ASSERT_EQ((call), NC_NOERR) << nc_strerror(call)

struct NetCdfAxis
{
  std::string Name;
  std::vector<double> Coordinates;
  std::string Units;
};

// A file with a time axis (`times` steps, or none when 0), three spatial axes (slowest first:
// z, y, x) and float variables on (time, z, y, x), each filled by `value(variable, t, i, j, k)`.
void WriteNetCdf(const std::string& path,
  int mode,
  int times,
  const std::array<NetCdfAxis, 3>& axes,
  const std::vector<std::string>& variables,
  const std::function<float(std::size_t, int, int, int, int)>& value,
  const std::function<void(int file, int variable)>& define = {})
{
  int file = 0;
  NC_OK(nc_create(path.c_str(), mode | NC_CLOBBER, &file));
  std::vector<int> dims;
  int timeVariable = -1;
  if (times > 0)
  {
    int time = 0;
    NC_OK(nc_def_dim(file, "time", NC_UNLIMITED, &time));
    dims.push_back(time);
    NC_OK(nc_def_var(file, "time", NC_DOUBLE, 1, &time, &timeVariable));
    const std::string units = "seconds since 2020-06-01 00:00:00";
    NC_OK(nc_put_att_text(file, timeVariable, "units", units.size(), units.c_str()));
  }
  std::vector<int> coordinateVariables;
  for (const NetCdfAxis& axis : axes)
  {
    int dim = 0, variable = 0;
    NC_OK(nc_def_dim(file, axis.Name.c_str(), axis.Coordinates.size(), &dim));
    dims.push_back(dim);
    NC_OK(nc_def_var(file, axis.Name.c_str(), NC_DOUBLE, 1, &dim, &variable));
    NC_OK(nc_put_att_text(file, variable, "units", axis.Units.size(), axis.Units.c_str()));
    coordinateVariables.push_back(variable);
  }
  std::vector<int> ids;
  for (const std::string& name : variables)
  {
    int variable = 0;
    NC_OK(nc_def_var(file, name.c_str(), NC_FLOAT, int(dims.size()), dims.data(), &variable));
    const std::string units = "g m-3";
    NC_OK(nc_put_att_text(file, variable, "units", units.size(), units.c_str()));
    if (define)
    {
      define(file, variable);
    }
    ids.push_back(variable);
  }
  NC_OK(nc_enddef(file));
  for (int t = 0; t < times; ++t)
  {
    const std::size_t start = std::size_t(t), count = 1;
    const double seconds = 3600.0 * t;
    NC_OK(nc_put_vara_double(file, timeVariable, &start, &count, &seconds));
  }
  for (std::size_t a = 0; a < 3; ++a)
  {
    NC_OK(nc_put_var_double(file, coordinateVariables[a], axes[a].Coordinates.data()));
  }
  const int nz = int(axes[0].Coordinates.size()), ny = int(axes[1].Coordinates.size()),
            nx = int(axes[2].Coordinates.size());
  for (std::size_t v = 0; v < ids.size(); ++v)
  {
    for (int t = 0; t < std::max(times, 1); ++t)
    {
      std::vector<float> values;
      for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
          for (int i = 0; i < nx; ++i)
          {
            values.push_back(value(v, t, i, j, k));
          }
      const std::size_t start[4] = { std::size_t(t), 0, 0, 0 };
      const std::size_t count[4] = { 1, std::size_t(nz), std::size_t(ny), std::size_t(nx) };
      NC_OK(nc_put_vara_float(
        file, ids[v], times > 0 ? start : start + 1, times > 0 ? count : count + 1, values.data()));
    }
  }
  NC_OK(nc_close(file));
}

// z 100 .. 200 by 50, y -5 .. 4 by 3, x 10 .. 18 by 2: evenly spaced, 3 x 4 x 5 points.
const std::array<NetCdfAxis, 3> EvenAxes = { { { "z", { 100, 150, 200 }, "m" },
  { "y", { -5, -2, 1, 4 }, "m" },
  { "x", { 10, 12, 14, 16, 18 }, "m" } } };

FieldReadOptions WithArray(const std::string& array, std::optional<int> step = std::nullopt)
{
  FieldReadOptions options;
  options.Array = array;
  options.TimeStep = step;
  return options;
}

TEST(NetCdf, ReadsTheChosenVariableAndTimeStepVoxelForVoxel)
{
  TemporaryDirectory dir;
  for (const int mode : { 0, NC_64BIT_OFFSET, NC_NETCDF4 })
  {
    SCOPED_TRACE("netCDF mode " + std::to_string(mode));
    const std::string path = dir.File("les-" + std::to_string(mode) + ".nc");
    WriteNetCdf(path,
      mode,
      2,
      EvenAxes,
      { "qv", "qc" },
      [](std::size_t v, int t, int i, int j, int k)
      { return float(Known(i, j, k) + 1000.0 * t + 5000.0 * double(v)); });
    FieldReport report;
    const auto field = cloudvis::ReadField(path, WithArray("qc", 1), &report);
    int d[3];
    field->GetDimensions(d);
    EXPECT_EQ(d[0], 5);
    EXPECT_EQ(d[1], 4);
    EXPECT_EQ(d[2], 3);
    ExpectVector(field->GetOrigin(), { { 10, -5, 100 } });
    ExpectVector(field->GetSpacing(), { { 2, 3, 50 } });
    ExpectKnownValues(field, 1000.0 + 5000.0);
    EXPECT_EQ(report.Format, "NetCDF (CF conventions)");
    EXPECT_NE(
      Detail(report, "variable").find("\"qc\" on (time, z, y, x), float"), std::string::npos);
    EXPECT_EQ(Detail(report, "units"), "g m-3");
    EXPECT_EQ(
      Detail(report, "time step"), "1 of 0 .. 1: t = 3600 seconds since 2020-06-01 00:00:00");
    EXPECT_EQ(Detail(report, "axis z"), "\"z\" (z by its name): 100 .. 200 m, 3 points");
    EXPECT_EQ(Detail(report, "resampled"), "no: the coordinates are evenly spaced");
  }
}

TEST(NetCdf, DefaultVariableIsDensityElseTheFirstOnThreeDimensions)
{
  TemporaryDirectory dir;
  const auto byVariable = [](std::size_t v, int, int i, int j, int k)
  { return float(Known(i, j, k) + 1000.0 * double(v)); };
  const std::string withDensity = dir.File("d.nc");
  WriteNetCdf(withDensity, 0, 0, EvenAxes, { "qc", "density" }, byVariable);
  ExpectKnownValues(cloudvis::ReadField(withDensity), 1000.0);
  const std::string without = dir.File("q.nc");
  WriteNetCdf(without, 0, 0, EvenAxes, { "qc", "qi" }, byVariable);
  FieldReport report;
  ExpectKnownValues(cloudvis::ReadField(without, {}, &report), 0.0);
  EXPECT_EQ(Detail(report, "time step"), "") << "a file without a time axis has no time step";
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(without, WithArray("ql")); })
              .find("no variable named \"ql\" (field.array); variables that can be read as "
                    "a density: qc, qi"),
    std::string::npos);
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(without, WithArray("qc", 1)); })
              .find("field.time_step: 1 is out of range: the file holds no time axis"),
    std::string::npos);
  // An LES file's cloud water is chosen over the wind and temperature before it: by its name,
  // and by its standard_name before any name.
  const std::string les = dir.File("les.nc");
  WriteNetCdf(les, 0, 0, EvenAxes, { "u", "thl", "ql", "qc" }, byVariable);
  ExpectKnownValues(cloudvis::ReadField(les), 2000.0);
  const std::string standard = dir.File("standard.nc");
  WriteNetCdf(standard,
    0,
    0,
    EvenAxes,
    { "u", "ql", "cloud" },
    byVariable,
    [](int file, int variable)
    {
      if (variable == 5) // the third data variable, after the three coordinates and two others
      {
        const std::string name = "mass_fraction_of_cloud_liquid_water_in_air";
        NC_OK(nc_put_att_text(file, variable, "standard_name", name.size(), name.c_str()));
      }
    });
  ExpectKnownValues(cloudvis::ReadField(standard), 2000.0);
}

TEST(NetCdf, TimeStepOutOfRangeNamesTheSteps)
{
  TemporaryDirectory dir;
  const std::string path = dir.File("t.nc");
  WriteNetCdf(path,
    0,
    3,
    EvenAxes,
    { "qc" },
    [](std::size_t, int t, int i, int j, int k) { return float(Known(i, j, k) + t); });
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path, WithArray("", 3)); })
              .find("field.time_step: 3 is out of range: the file holds 3 time steps (0 .. 2)"),
    std::string::npos);
  ExpectKnownValues(cloudvis::ReadField(path, WithArray("", 2)), 2.0);
}

// A vertical coordinate stretched upwards, as large-eddy simulations use: the field is resampled
// linearly onto levels as far apart as the closest two of the file, which keeps the file's
// levels (they are multiples of the smallest step) and interpolates between them.
TEST(NetCdf, StretchedVerticalCoordinateIsResampledLinearlyAtTheSmallestStep)
{
  TemporaryDirectory dir;
  const std::vector<double> levels = { 0, 10, 30, 70, 150 };
  const std::array<NetCdfAxis, 3> axes = {
    { { "height", levels, "m" }, { "y", { 0, 100 }, "m" }, { "x", { 0, 100, 200 }, "m" } }
  };
  // Quadratic in height, so interpolation between the levels is visible.
  const auto value = [&levels](int i, int j, int k)
  { return float(levels[std::size_t(k)] * levels[std::size_t(k)] + i + 10.0 * j); };
  const std::string path = dir.File("stretched.nc");
  WriteNetCdf(path,
    0,
    0,
    axes,
    { "ql" },
    [&](std::size_t, int, int i, int j, int k) { return value(i, j, k); });
  FieldReport report;
  const auto field = cloudvis::ReadField(path, {}, &report);
  int d[3];
  field->GetDimensions(d);
  ASSERT_EQ(d[2], 16) << "150 m at the smallest step, 10 m: 16 levels";
  EXPECT_EQ(d[0], 3);
  EXPECT_EQ(d[1], 2);
  ExpectVector(field->GetSpacing(), { { 100, 100, 10 } });
  ExpectVector(field->GetOrigin(), { { 0, 0, 0 } });
  double largestError = 0.0;
  for (int k = 0; k < d[2]; ++k)
  {
    const double z = 10.0 * k;
    std::size_t l = 0;
    while (l + 2 < levels.size() && levels[l + 1] < z)
    {
      ++l;
    }
    const double w = (z - levels[l]) / (levels[l + 1] - levels[l]);
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
      {
        const double expected = (1 - w) * value(i, j, int(l)) + w * value(i, j, int(l) + 1);
        largestError = std::max(largestError, std::fabs(Density(field, i, j, k) - expected));
      }
  }
  // The levels and weights here (steps of 10 between levels 0, 10, 30, 70, 150) make every
  // interpolated value a float exactly; observed error 0.
  EXPECT_LT(largestError, 1e-6);
  EXPECT_EQ(Detail(report, "axis z"),
    "\"height\" (z by its name): 0 .. 150 m, 5 points, stretched (steps 10 .. 80)");
  EXPECT_EQ(Detail(report, "resampled"),
    "z: linearly onto 16 regular points 10 apart (the smallest step of the file)");

  // With fewer voxels allowed the levels are coarser, and the report says why.
  FieldReadOptions capped;
  capped.MaximumVoxels = 60;
  const auto coarse = cloudvis::ReadField(path, capped, &report);
  coarse->GetDimensions(d);
  EXPECT_LE(d[0] * d[1] * d[2], 60);
  EXPECT_GE(d[2], 5);
  EXPECT_NE(Detail(report, "resampled")
              .find("coarser than the smallest step, 10, which would "
                    "need 16 points: field.max_voxels"),
    std::string::npos);
  EXPECT_EQ(Density(coarse, 2, 1, d[2] - 1), value(2, 1, 4)) << "the top level stays the file's";
}

// One tiny step (1e-12 of a 2 m column) asks for 2e12 points at the smallest step, beyond an
// int: the count is kept exact, reported, and field.max_voxels coarsens the lattice from it.
TEST(NetCdf, OneTinyStepIsCountedBeyondIntAndCoarsened)
{
  TemporaryDirectory dir;
  const std::array<NetCdfAxis, 3> axes = { { { "height", { 0, 1e-12, 1, 2 }, "m" },
    { "y", { 0, 100 }, "m" },
    { "x", { 0, 100, 200 }, "m" } } };
  const std::string path = dir.File("tiny.nc");
  WriteNetCdf(path,
    0,
    0,
    axes,
    { "ql" },
    [](std::size_t, int, int i, int j, int k) { return float(Known(i, j, k)); });
  FieldReadOptions capped;
  capped.MaximumVoxels = 600;
  FieldReport report;
  const auto field = cloudvis::ReadField(path, capped, &report);
  int d[3];
  field->GetDimensions(d);
  EXPECT_EQ(d[0], 3);
  EXPECT_EQ(d[1], 2);
  EXPECT_GE(d[2], 4);
  EXPECT_LE(d[0] * d[1] * d[2], 600);
  const std::string resampled = Detail(report, "resampled");
  const std::string need = "which would need ";
  const std::size_t at = resampled.find(need);
  ASSERT_NE(at, std::string::npos) << resampled;
  const double points = std::stod(resampled.substr(at + need.size()));
  EXPECT_NEAR(points, 2e12, 2.0) << resampled;
  EXPECT_EQ(Density(field, 2, 1, d[2] - 1), Known(2, 1, 3)) << "the top level stays the file's";
}

TEST(NetCdf, DecreasingCoordinatesAreTurnedAround)
{
  TemporaryDirectory dir;
  std::array<NetCdfAxis, 3> axes = EvenAxes;
  axes[1].Coordinates = { 4, 1, -2, -5 }; // y from north to south
  const std::string path = dir.File("south.nc");
  WriteNetCdf(path,
    0,
    0,
    axes,
    { "qc" },
    [](std::size_t, int, int i, int j, int k) { return float(Known(i, j, k)); });
  FieldReport report;
  const auto field = cloudvis::ReadField(path, {}, &report);
  ExpectVector(field->GetOrigin(), { { 10, -5, 100 } });
  ExpectVector(field->GetSpacing(), { { 2, 3, 50 } });
  // The file's row j = 3 (y = -5) is the field's row 0.
  EXPECT_EQ(Density(field, 1, 0, 2), Known(1, 3, 2));
  EXPECT_EQ(Density(field, 1, 3, 2), Known(1, 0, 2));
  EXPECT_NE(
    Detail(report, "axis y").find("decreasing in the file (turned around)"), std::string::npos);
}

TEST(NetCdf, FillValuesAreRefusedWithTheirCount)
{
  TemporaryDirectory dir;
  const std::string path = dir.File("gaps.nc");
  const float fill = -999.0f;
  WriteNetCdf(
    path,
    0,
    0,
    EvenAxes,
    { "qc" },
    [fill](std::size_t, int, int i, int j, int k)
    { return i == 0 && j == 0 ? fill : float(Known(i, j, k)); },
    [fill](int file, int variable)
    { nc_put_att_float(file, variable, "_FillValue", NC_FLOAT, 1, &fill); });
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("variable \"qc\" holds 3 missing values (_FillValue -999)"),
    std::string::npos);
}

// A netCDF-4 file states its dimensions; its values live in chunks that may never have been
// written. A few kilobytes can so claim 4096^3 values: refused with the size, before anything of
// that size is allocated (the test would run out of memory otherwise).
TEST(NetCdf, HugeDeclaredSizesAreRefusedBeforeAllocation)
{
  TemporaryDirectory dir;
  const std::string path = dir.File("huge.nc");
  int file = 0, dims[3], variable = 0;
  NC_OK(nc_create(path.c_str(), NC_NETCDF4 | NC_CLOBBER, &file));
  for (int a = 0; a < 3; ++a)
  {
    NC_OK(nc_def_dim(file, std::string(1, "zyx"[a]).c_str(), 4096, &dims[a]));
  }
  NC_OK(nc_def_var(file, "qc", NC_FLOAT, 3, dims, &variable));
  NC_OK(nc_close(file));
  ASSERT_LT(ReadText(path).size(), 100000u);
  const std::string message = ErrorOf([&] { cloudvis::ReadField(path); });
  EXPECT_NE(message.find("a field of 4096 x 4096 x 4096 voxels (6.87195e+10 voxels, 256 GiB as "
                         "float) is more than field.max_voxels allows (1073741824)"),
    std::string::npos)
    << message;
}

TEST(NetCdf, TruncatedAndForeignFilesAreRefused)
{
  TemporaryDirectory dir;
  const std::string path = dir.File("cut.nc");
  WriteNetCdf(path,
    0,
    0,
    EvenAxes,
    { "qc" },
    [](std::size_t, int, int i, int j, int k) { return float(Known(i, j, k)); });
  // The netCDF library itself would read zeros past the end.
  const std::size_t size = ReadText(path).size();
  Truncate(path, size - 100);
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find(": the values of \"qc\" end at byte " + std::to_string(size) +
                " but the file holds " + std::to_string(size - 100) + ": it is truncated"),
    std::string::npos);
  // Record variables: each time step is a record holding every variable's values. Cut into the
  // last record, the last step of "qc" is refused and the first still reads.
  const std::string records = dir.File("records.nc");
  WriteNetCdf(records,
    0,
    2,
    EvenAxes,
    { "qc", "qv" },
    [](std::size_t v, int t, int i, int j, int k)
    { return float(Known(i, j, k) + 1000.0 * t + 5000.0 * double(v)); });
  const std::size_t recordsSize = ReadText(records).size();
  Truncate(records, recordsSize - 60 * 4 - 8); // all of the last "qv", and 8 bytes of "qc"
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(records, WithArray("qc", 1)); })
              .find("the values of \"qc\" end at byte " + std::to_string(recordsSize - 60 * 4) +
                " but the file holds " + std::to_string(recordsSize - 60 * 4 - 8)),
    std::string::npos);
  ExpectKnownValues(cloudvis::ReadField(records, WithArray("qc", 0)), 0.0);
  WriteText(dir.File("text.nc"), "netcdf is text\n");
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(dir.File("text.nc")); })
              .find("not a NetCDF file (it starts with neither \"CDF\" nor the HDF5 signature)"),
    std::string::npos);
}

// ---- NRRD, written by teem's own tool ----------------------------------------------------------

// The lattice is rotated (i along +y, j along -x), and its first axis (5 voxels) is one VTK's
// reader would take for vector components: geometry and values are the file's anyway.
TEST(Nrrd, ReadsARotatedLatticeVoxelForVoxel)
{
  TemporaryDirectory dir;
  const std::string raw = WriteKnownRaw(dir);
  const std::string path = dir.File("rotated.nrrd");
  RunTool(Unu(raw, path, "-e raw -spc RAS -orig '(1,2,3)' -dirs '(0,0.5,0) (-1,0,0) (0,0,2)'"));
  FieldReport report;
  const auto field = cloudvis::ReadField(path, {}, &report);
  int d[3];
  field->GetDimensions(d);
  EXPECT_EQ(d[0], 5);
  EXPECT_EQ(d[1], 4);
  EXPECT_EQ(d[2], 3);
  ExpectKnownValues(field);
  ExpectVector(field->GetSpacing(), { { 0.5, 1, 2 } });
  ExpectVector(field->GetOrigin(), { { 1, 2, 3 } });
  const auto i = Axis(field, 0), j = Axis(field, 1), k = Axis(field, 2);
  ExpectVector(i.data(), { { 0, 1, 0 } });
  ExpectVector(j.data(), { { -1, 0, 0 } });
  ExpectVector(k.data(), { { 0, 0, 1 } });
  double world[3];
  field->TransformIndexToPhysicalPoint(4, 3, 2, world);
  ExpectVector(world, { { 1 - 3.0, 2 + 4 * 0.5, 3 + 2 * 2.0 } });
  EXPECT_EQ(report.Format, "NRRD");
  EXPECT_EQ(Detail(report, "values"), "float");
}

// teem allows spaces inside a vector ("(0, 0.5, 0)"): split on them, the directions were
// ignored and the lattice read as the identity (exit 0, wrong geometry). A vector that cannot be
// read is refused, not ignored.
TEST(Nrrd, SpaceDirectionsWithSpacesAreReadAndBrokenOnesRefused)
{
  TemporaryDirectory dir;
  const std::string raw = WriteKnownRaw(dir);
  const std::string path = dir.File("spaced.nrrd");
  RunTool(Unu(raw, path, "-e raw -spc RAS -dirs '(0,0.5,0) (-1,0,0) (0,0,2)'"));
  const std::string good = ReadText(path);
  const std::string line = "space directions: (0,0.5,0) (-1,0,0) (0,0,2)";
  ASSERT_NE(good.find(line), std::string::npos) << good;
  const auto with = [&](const std::string& directions)
  { return std::string(good).replace(good.find(line), line.size(), directions); };
  WriteText(path, with("space directions: ( 0, 0.5, 0 ) (-1, 0, 0)\t(0,  0, 2)"));
  const auto field = cloudvis::ReadField(path);
  ExpectKnownValues(field);
  ExpectVector(field->GetSpacing(), { { 0.5, 1, 2 } });
  ExpectVector(Axis(field, 0).data(), { { 0, 1, 0 } });
  ExpectVector(Axis(field, 1).data(), { { -1, 0, 0 } });
  WriteText(path, with("space directions: (0, 0.5, 0) (-1, 0, 0)"));
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("spaced.nrrd: the NRRD \"space directions\" gives 2 vectors (or \"none\") "
                    "for 3 axes"),
    std::string::npos);
  WriteText(path, with("space directions: (0, 0.5, 0) (-1, 0, 0) (0, 0, 2"));
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("the NRRD \"space directions\" opens a vector it does not close"),
    std::string::npos);
  WriteText(path, with("space directions: (0, 0.5, 0) (-1, 0, 0) (0, zero, 2)"));
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("the NRRD \"space directions\" of axis 2 is not a vector of three numbers "
                    "(\"(0, zero, 2)\")"),
    std::string::npos);
}

TEST(Nrrd, GzipEncodingAndDetachedHeadersAreRead)
{
  TemporaryDirectory dir;
  const std::string raw = WriteKnownRaw(dir);
  RunTool(Unu(raw, dir.File("zipped.nrrd"), "-e gzip -sp 1 1 1"));
  ExpectKnownValues(cloudvis::ReadField(dir.File("zipped.nrrd")));
  // A detached header names its data file (relative to the header).
  RunTool("cd '" + dir.Path + "' && " + Unu("known.raw", "detached.nhdr", "-h -e raw -sp 1 1 1"));
  FieldReport report;
  ExpectKnownValues(cloudvis::ReadField(dir.File("detached.nhdr"), {}, &report));
  EXPECT_EQ(Detail(report, "data file"), dir.File("known.raw"));
}

TEST(Nrrd, HostileHeadersAreRefused)
{
  TemporaryDirectory dir;
  const std::string raw = WriteKnownRaw(dir);
  const std::string path = dir.File("f.nrrd");
  RunTool(Unu(raw, path, "-e raw -sp 1 1 1"));
  const std::string good = ReadText(path);
  const auto replaced = [&good](const std::string& from, const std::string& to)
  {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  // Truncated: the data is 240 bytes.
  Truncate(path, good.size() - 40);
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("an image of 60 float values needs 240 bytes of data after "),
    std::string::npos);
  // Sizes far beyond memory, in a file of a few hundred bytes.
  WriteText(path, replaced("sizes: 5 4 3", "sizes: 50000 40000 30000"));
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("a field of 50000 x 40000 x 30000 voxels (6e+13 voxels, 218 TiB as float)"),
    std::string::npos);
  // A sheared lattice, and values of several components per voxel.
  WriteText(
    path, replaced("spacings: 1 1 1", "space: RAS\nspace directions: (1,0,0) (0.5,1,0) (0,0,1)"));
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("the image's direction matrix is not a rotation: its axes must be "
                    "perpendicular unit vectors (axes 0 and 1 have a dot product of "),
    std::string::npos);
  WriteText(path,
    replaced("dimension: 3\n", "dimension: 4\n")
      .replace(good.find("sizes: 5 4 3"), 12, "sizes: 1 5 4 3"));
  ExpectKnownValues(cloudvis::ReadField(path)) /* one component per voxel is a scalar */;
  WriteText(path,
    replaced("dimension: 3\n", "dimension: 4\n")
      .replace(good.find("sizes: 5 4 3"), 12, "sizes: 5 1 4 3"));
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("the NRRD image has 5 values per voxel; a density field needs 1"),
    std::string::npos);
}

// ---- MetaImage, written by VTK's writer --------------------------------------------------------

TEST(MetaImage, ReadsWhatVtkWroteVoxelForVoxel)
{
  TemporaryDirectory dir;
  for (const bool compressed : { false, true })
  {
    for (const int type : { VTK_FLOAT, VTK_UNSIGNED_SHORT, VTK_SHORT, VTK_DOUBLE })
    {
      const std::string path = dir.File(std::string(compressed ? "z" : "u") + std::to_string(type) +
        (compressed ? ".mhd" : ".mha"));
      SCOPED_TRACE(path);
      WriteMetaImage(path, type, compressed);
      FieldReport report;
      const auto field = cloudvis::ReadField(path, {}, &report);
      ExpectKnownValues(field);
      ExpectVector(field->GetSpacing(), { { 0.5, 1, 2 } });
      ExpectVector(field->GetOrigin(), { { 1, 2, 3 } });
      EXPECT_EQ(report.Format, "MetaImage");
      EXPECT_EQ(Detail(report, "values").find(type == VTK_FLOAT ? "MET_FLOAT" : "MET_"), 0u);
    }
  }
}

TEST(MetaImage, TransformMatrixAndSignedSpacingBecomeTheDirection)
{
  TemporaryDirectory dir;
  const std::string path = WriteMetaImage(dir.File("f.mha"), VTK_FLOAT, false);
  std::string text = ReadText(path);
  // As ITK writes a rotated image: each axis's direction in turn (i along +y, j along -x).
  text.replace(
    text.find("TransformMatrix = 1 0 0 0 1 0 0 0 1"), 35, "TransformMatrix = 0 1 0 -1 0 0 0 0 1");
  text.replace(text.find("ElementSpacing = 0.5 1 2"), 24, "ElementSpacing = 0.5 1 -2");
  WriteText(path, text);
  const auto field = cloudvis::ReadField(path);
  ExpectKnownValues(field);
  ExpectVector(field->GetSpacing(), { { 0.5, 1, 2 } });
  const auto i = Axis(field, 0), j = Axis(field, 1), k = Axis(field, 2);
  ExpectVector(i.data(), { { 0, 1, 0 } });
  ExpectVector(j.data(), { { -1, 0, 0 } });
  ExpectVector(k.data(), { { 0, 0, -1 } }) /* the negative spacing */;
}

TEST(MetaImage, TruncatedAndHugeHeadersAreRefused)
{
  TemporaryDirectory dir;
  const std::string path = WriteMetaImage(dir.File("f.mha"), VTK_FLOAT, false);
  const std::string good = ReadText(path);
  Truncate(path, good.size() - 4);
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("an image of 60 MET_FLOAT values needs 240 bytes of data"),
    std::string::npos);
  std::string huge = good;
  huge.replace(huge.find("DimSize = 5 4 3"), 15, "DimSize = 90000 90000 90000");
  WriteText(path, huge);
  EXPECT_NE(
    ErrorOf([&] { cloudvis::ReadField(path); }).find("a field of 90000 x 90000 x 90000 voxels"),
    std::string::npos);
}

// ---- raw volumes, written by VTK's raw writer ------------------------------------------------

FieldReadOptions RawOptions(const std::string& type,
  bool bigEndian = false,
  std::uint64_t header = 0)
{
  FieldReadOptions options;
  options.Raw.Dimensions = { { 5, 4, 3 } };
  options.Raw.Type = type;
  options.Raw.BigEndian = bigEndian;
  options.Raw.Spacing = { { 0.5, 1.0, 2.0 } };
  options.Raw.Origin = { { 1.0, 2.0, 3.0 } };
  options.Raw.HeaderBytes = header;
  return options;
}

std::string WriteRawWithVtk(const std::string& path, int type)
{
  vtkNew<vtkImageWriter> writer;
  writer->SetInputData(KnownImage(type));
  writer->SetFileName(path.c_str());
  writer->SetFileDimensionality(3);
  writer->Write();
  return path;
}

TEST(Raw, ReadsEveryTypeInEitherByteOrder)
{
  TemporaryDirectory dir;
  const std::pair<const char*, int> types[] = { { "uint8", VTK_UNSIGNED_CHAR },
    { "uint16", VTK_UNSIGNED_SHORT },
    { "int16", VTK_SHORT },
    { "uint32", VTK_UNSIGNED_INT },
    { "int32", VTK_INT },
    { "float32", VTK_FLOAT },
    { "float64", VTK_DOUBLE } };
  for (const auto& type : types)
  {
    SCOPED_TRACE(type.first);
    const std::string path =
      WriteRawWithVtk(dir.File(std::string(type.first) + ".raw"), type.second);
    FieldReport report;
    const auto field = cloudvis::ReadField(path, RawOptions(type.first), &report);
    // vtkImageWriter stores the rows from the top (y flipped); uint8 holds Known() modulo 256.
    if (type.second == VTK_UNSIGNED_CHAR)
    {
      EXPECT_EQ(Density(field, 4, 0, 2), double(std::uint8_t(Known(4, 3, 2))));
    }
    else
    {
      ExpectKnownValues(field, 0.0, true);
    }
    ExpectVector(field->GetSpacing(), { { 0.5, 1, 2 } });
    ExpectVector(field->GetOrigin(), { { 1, 2, 3 } });
    // The same bytes reversed value by value, with a header before them: big-endian.
    const std::string bytes = ReadText(path);
    const std::size_t size = bytes.size() / 60;
    std::string swapped = "HEADER";
    for (std::size_t v = 0; v < 60; ++v)
    {
      swapped.append(std::string(bytes.rbegin() + std::ptrdiff_t(bytes.size() - (v + 1) * size),
        bytes.rbegin() + std::ptrdiff_t(bytes.size() - v * size)));
    }
    WriteText(dir.File("big.raw"), swapped);
    const auto big = cloudvis::ReadField(dir.File("big.raw"), RawOptions(type.first, true, 6));
    EXPECT_EQ(Density(big, 4, 3, 2), Density(field, 4, 3, 2));
    EXPECT_EQ(Density(big, 1, 2, 1), Density(field, 1, 2, 1));
  }
}

TEST(Raw, AFileOfAnotherSizeIsRefusedBeforeAllocation)
{
  TemporaryDirectory dir;
  const std::string path = WriteRawWithVtk(dir.File("f.raw"), VTK_FLOAT);
  FieldReadOptions options = RawOptions("float32");
  options.Raw.Dimensions = { { 1000, 1000, 250 } };
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path, options); })
              .find("a raw volume of 1000 x 1000 x 250 float32 little-endian values is "
                    "1000000000 bytes, but the file holds 240: check field.raw.dimensions, "
                    "type and header_bytes"),
    std::string::npos);
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path, RawOptions("float64")); })
              .find("is 480 bytes, but the file holds 240"),
    std::string::npos);
  options.Raw.Dimensions = { { 100000, 100000, 100000 } };
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path, options); })
              .find("a field of 100000 x 100000 x 100000 voxels (1e+15 voxels, 3.55 PiB as float)"),
    std::string::npos);
}

TEST(Raw, ValuesBeyondFloatAndNonFiniteValuesAreRefusedWithTheirCount)
{
  TemporaryDirectory dir;
  std::vector<double> values(60, 1.0);
  values[3] = 1e300;
  values[7] = -1e300;
  values[11] = std::numeric_limits<double>::quiet_NaN();
  WriteText(dir.File("d.raw"), std::string(reinterpret_cast<const char*>(values.data()), 480));
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(dir.File("d.raw"), RawOptions("float64")); })
              .find("holds 2 values beyond the range of float"),
    std::string::npos);
  values[3] = values[7] = std::numeric_limits<double>::infinity();
  WriteText(dir.File("d.raw"), std::string(reinterpret_cast<const char*>(values.data()), 480));
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(dir.File("d.raw"), RawOptions("float64")); })
              .find("holds 3 values that are NaN or infinite"),
    std::string::npos);
}

// ---- read options that do not suit the format, as the scene reports them ----------------------

TEST(FieldReadOptions, OptionsThatDoNotSuitTheFormatAreRefusedByKey)
{
  const auto problem = [](const std::vector<std::string>& assignments)
  { return ErrorOf([&] { cloudvis::LoadScene("", assignments); }); };
  EXPECT_NE(problem({ "field.file=f.raw", "field.array=qc", "field.raw.dimensions=4" })
              .find("field.array: a raw file (raw volume) holds one array"),
    std::string::npos);
  EXPECT_NE(problem({ "field.file=f.vti", "field.time_step=2" })
              .find("field.time_step: a vti file (VTK XML image data) holds one time step"),
    std::string::npos);
  EXPECT_NE(problem({ "field.file=f.vdb", "field.raw.dimensions=4" })
              .find("field.raw: applies to raw files only"),
    std::string::npos);
  EXPECT_NE(
    problem({ "field.file=f.raw" }).find("field.raw.dimensions: missing"), std::string::npos);
  EXPECT_NE(problem({ "field.file=f.dat" }).find("field.file: \"f.dat\" is not a field file"),
    std::string::npos);
  EXPECT_NE(problem({ "field.file=f.dat", "field.format=grib" })
              .find("field.format: unknown name \"grib\"; allowed: vti, pvti, vdb, netcdf, "
                    "nrrd, metaimage, raw"),
    std::string::npos);
  EXPECT_NE(problem({ "field.array=qc" })
              .find("field.array: says how a field file is read; give field.file too"),
    std::string::npos);
  EXPECT_NE(problem({ "field.file=f.vti", "field.octaves=3" })
              .find("field.file: cannot be combined with field.octaves"),
    std::string::npos);
  // A name without a known extension is read as the format field.format names.
  const cloudvis::Scene scene = cloudvis::LoadScene("",
    { "field.file=f.dat",
      "field.format=raw",
      "field.raw.dimensions=4,5,6",
      "field.raw.type=uint16",
      "field.raw.byte_order=big" });
  EXPECT_EQ(scene.Field.Read.Format, "raw");
  EXPECT_EQ(scene.Field.Read.Raw.Dimensions, (std::array<int, 3>{ { 4, 5, 6 } }));
  EXPECT_EQ(scene.Field.Read.Raw.Type, "uint16");
  EXPECT_TRUE(scene.Field.Read.Raw.BigEndian);
}

// ---- .pvti written by cloudvis ----------------------------------------------------------------

TEST(ParallelFiles, PiecesWrittenByCloudvisReadBackByCloudvisAndVtk)
{
  TemporaryDirectory dir;
  const auto field = RotatedField();
  for (const int pieces : { 1, 2, 5 })
  {
    SCOPED_TRACE(std::to_string(pieces) + " pieces");
    const std::string path = dir.File("p" + std::to_string(pieces) + ".pvti");
    cloudvis::WriteFieldPieces(field, path, pieces);
    for (int p = 0; p < pieces; ++p)
    {
      EXPECT_TRUE(std::filesystem::exists(cloudvis::PieceFileName(path, p)));
    }
    ExpectSameField(field, cloudvis::ReadField(path));
    // VTK's own reader assembles the same values (VTK 9.1 keeps no direction for .pvti).
    vtkNew<vtkXMLPImageDataReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkDataArray* read = reader->GetOutput()->GetPointData()->GetArray("density");
    ASSERT_NE(read, nullptr);
    ASSERT_EQ(read->GetNumberOfTuples(), field->GetNumberOfPoints());
    EXPECT_EQ(read->GetRange()[1], field->GetPointData()->GetScalars()->GetRange()[1]);
    EXPECT_EQ(reader->GetOutput()->GetOrigin()[1], field->GetOrigin()[1]);
  }
  EXPECT_NE(ErrorOf([&] { cloudvis::WriteFieldPieces(field, dir.File("many.pvti"), 10000); })
              .find("cannot be split into 10000 pieces"),
    std::string::npos);
}

// VTK 9.1's own parallel writer leaves the Direction out of the .pvti and writes it in each piece:
// the field read back takes its first piece's, so a rotated lattice stays rotated.
TEST(ParallelFiles, PiecesWrittenByVtkKeepTheDirectionOfTheirPieces)
{
  TemporaryDirectory dir;
  const auto field = RotatedField();
  const std::string path = dir.File("vtk.pvti");
  vtkNew<vtkXMLPImageDataWriter> writer;
  writer->SetInputData(field);
  writer->SetFileName(path.c_str());
  writer->SetNumberOfPieces(3);
  writer->SetStartPiece(0);
  writer->SetEndPiece(2);
  ASSERT_EQ(writer->Write(), 1);
  ASSERT_EQ(ReadText(path).find("Direction"), std::string::npos)
    << "VTK's writer now states the direction in the .pvti: this test no longer tests the pieces'";
  ExpectSameField(field, cloudvis::ReadField(path));
}

// Pieces that share points must agree there: VTK's reader takes each point from one piece and
// never reads the other's, so a conflict was resolved silently by the pieces' order. Pieces are
// named as their files are, from 0.
TEST(ParallelFiles, OverlappingPiecesMustHoldEqualValuesWhereTheyOverlap)
{
  TemporaryDirectory dir;
  const auto field = RotatedField();
  const std::string path = dir.File("p.pvti");
  cloudvis::WriteFieldPieces(field, path, 2);
  ExpectSameField(field, cloudvis::ReadField(path)) /* a shared plane of equal values */;
  // Piece 1 (x from 7 to 12) with another value at the first point of the plane x = 7 it shares
  // with piece 0.
  const cloudvis::Extent second =
    cloudvis::PieceExtent(cloudvis::LatticeOf(field).WholeExtent, 1, 2);
  ASSERT_EQ(second[0], 7);
  const auto piece = cloudvis::ExtractPiece(field, second);
  int first[3] = { 7, -3, 1 };
  piece->GetPointData()->GetScalars()->SetComponent(piece->ComputePointId(first), 0, 999.0);
  // Written with the run the .pvti records, so the pieces are of one run and only disagree.
  cloudvis::WriteVtkXmlImageFile(
    piece, dir.File("p_1.vti"), dir.File("p_1.vti"), RecordedRun(path));
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("p.pvti: piece 0 (p_0.vti) and piece 1 (p_1.vti) overlap and disagree: at "
                    "point (7, -3, 1) \"density\" is 107 in piece 0 and 999 in piece 1"),
    std::string::npos);
  std::filesystem::remove(dir.File("p_1.vti"));
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("p.pvti: piece 1 (p_1.vti): cannot read field piece"),
    std::string::npos);
}

// `generate -o f.pvti --pieces N` generates each piece by itself (vtkCloudDensitySource fills
// exactly the extent asked for): the pieces assemble into the field generated whole, bit for bit.
TEST(ParallelFiles, GeneratedPiecesEqualTheWholeFieldBitForBit)
{
  TemporaryDirectory dir;
  std::ostringstream out, err;
  const std::vector<std::string> set = {
    "--set", "field.dimensions=21,17,9", "--set", "field.noise=perlin"
  };
  std::vector<std::string> whole = { "cloudvis", "generate", "-o", dir.File("whole.vti") };
  whole.insert(whole.end(), set.begin(), set.end());
  ASSERT_EQ(cloudvis::RunCommandLine(whole, out, err), 0) << err.str();
  for (const char* pieces : { "1", "4", "7" })
  {
    std::vector<std::string> split = {
      "cloudvis", "generate", "-o", dir.File("split.pvti"), "--pieces", pieces
    };
    split.insert(split.end(), set.begin(), set.end());
    ASSERT_EQ(cloudvis::RunCommandLine(split, out, err), 0) << err.str();
    EXPECT_NE(out.str().find(std::string("voxels in ") + pieces + " piece"), std::string::npos);
    ExpectSameField(
      cloudvis::ReadField(dir.File("whole.vti")), cloudvis::ReadField(dir.File("split.pvti")));
  }
}

} // namespace
