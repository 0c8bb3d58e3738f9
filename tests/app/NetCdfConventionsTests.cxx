// The CF conventions of NetCDF files as cloudvis reads them (NetCdfVariables.h), on files the
// netCDF tool ncgen makes from CDL text, so each fixture reads as the file it is: every numeric
// type in every file kind, every marking of missing values (refused with the count, or read as
// empty space with field.missing), the default variable in file order, dimensions placed on the
// axes they stand for whatever their order, a time axis without records, truncated and damaged
// netCDF-4 files, cells, curvilinear grids. Part of cloudvis-field-format-tests
// (FieldFormatTests.cxx has the files written by the netCDF C library).
#include "FieldTestFiles.h"

#include "Scene.h"
#include "SupportRun.h"

#include <gtest/gtest.h>
#include <vtkImageData.h>

#include <algorithm>
#include <cmath>

namespace
{

using cloudvis::FieldReadOptions;
using cloudvis::FieldReport;
using cloudvis::MissingValueRule;
using namespace cloudvis::support;
using namespace cloudvis::test;

// The value at world point (x, y, z) = (i, 10 j, 100 k) of the fixtures below.
double Known(int i, int j, int k)
{
  return i + 10.0 * j + 100.0 * k;
}

// Known(i, j, k) in CDL order for a variable on (z, y, x), 2 x 2 x 3.
const char* const KnownZyx = "0, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, 112";

// A file on z = 2, y = 2, x = 3 with coordinates z 0, 100; y 0, 10; x 0, 1, 2, the variables
// `declarations` (CDL) and their `data` (CDL).
std::string Grid(const std::string& declarations, const std::string& data)
{
  return "netcdf grid {\ndimensions: z = 2 ; y = 2 ; x = 3 ;\nvariables:\n"
         "  double z(z) ; double y(y) ; double x(x) ;\n" +
    declarations + "\ndata:\n  z = 0, 100 ; y = 0, 10 ; x = 0, 1, 2 ;\n" + data + "\n}\n";
}

// Every voxel of `field` (5-point slabs aside) is Known(i, j, k) * scale + offset, and the lattice
// is the fixture's: 3 x 2 x 2 from the origin, spacing 1, 10, 100.
void ExpectKnownGrid(vtkImageData* field, double scale = 1.0, double offset = 0.0)
{
  ASSERT_NE(field, nullptr);
  int d[3];
  field->GetDimensions(d);
  ASSERT_EQ(std::vector<int>(d, d + 3), (std::vector<int>{ 3, 2, 2 }));
  EXPECT_EQ(std::vector<double>(field->GetSpacing(), field->GetSpacing() + 3),
    (std::vector<double>{ 1, 10, 100 }));
  EXPECT_EQ(std::vector<double>(field->GetOrigin(), field->GetOrigin() + 3),
    (std::vector<double>{ 0, 0, 0 }));
  int wrong = 0;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i)
      {
        wrong += Density(field, i, j, k) == Known(i, j, k) * scale + offset ? 0 : 1;
      }
  EXPECT_EQ(wrong, 0) << "voxels whose value is not the one the file holds";
}

FieldReadOptions Options(const std::string& array,
  MissingValueRule missing = MissingValueRule::Refuse)
{
  FieldReadOptions options;
  options.Array = array;
  if (missing != MissingValueRule::Refuse)
  {
    options.Missing = missing;
  }
  return options;
}

// ---- types --------------------------------------------------------------------------------------

// Every numeric type of netCDF in every file kind that has it, converted to float. VTK's reader,
// used before, knew the classic types only ("Unknown netCDF variable type 7" for ubyte).
TEST(NetCdfConventions, EveryNumericTypeIsReadInEveryFileKind)
{
  TemporaryDirectory dir;
  const std::vector<std::string> classicTypes = { "byte", "short", "int", "float", "double" };
  const std::vector<std::string> extendedTypes = { "ubyte", "ushort", "uint", "int64", "uint64" };
  for (const int kind : { 1, 2, 3, 4, 5 })
  {
    std::vector<std::string> types = classicTypes;
    if (kind == 3 || kind == 5) // netCDF-4 and CDF-5 have the unsigned and 64-bit types
    {
      types.insert(types.end(), extendedTypes.begin(), extendedTypes.end());
    }
    if (kind == 5) // ncgen 4.9.0 declares a CDF-5 int64 variable as int
    {
      types.erase(std::find(types.begin(), types.end(), "int64"));
    }
    std::string declarations, data;
    for (const std::string& type : types)
    {
      declarations += "  " + type + " v_" + type + "(z, y, x) ;\n";
      data += "  v_" + type + " = " + KnownZyx + " ;\n";
    }
    const std::string path =
      Ncgen(dir, "types-" + std::to_string(kind) + ".nc", Grid(declarations, data), kind);
    for (const std::string& type : types)
    {
      SCOPED_TRACE("ncgen -k " + std::to_string(kind) + ", " + type);
      FieldReport report;
      ExpectKnownGrid(cloudvis::ReadField(path, Options("v_" + type), &report));
      EXPECT_NE(Detail(report, "variable")
                  .find("\"v_" + type + "\" on (z, y, x), " + type +
                    (type == "float" ? "" : ", converted to float")),
        std::string::npos)
        << Detail(report, "variable");
    }
  }
}

// ---- missing values -----------------------------------------------------------------------------

// Each CF marking of missing values, alone and together, on plain and packed variables. VTK's
// reader, used before, replaced _FillValue of float and double variables only: missing_value,
// valid_*, the default fill value and the _FillValue of packed integers read as densities.
TEST(NetCdfConventions, MissingValuesInEveryMarkingAreRefusedWithTheirCountAndMarking)
{
  TemporaryDirectory dir;
  struct Case
  {
    std::string Declaration, Data, Expected;
  };
  const std::vector<Case> cases = {
    { "float qc(z, y, x) ; qc:_FillValue = -999.f ;",
      "qc = -999, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, -999 ;",
      "holds 2 missing values (_FillValue -999)" },
    { "float qc(z, y, x) ; qc:missing_value = -999.f ;",
      "qc = -999, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, 112 ;",
      "holds 1 missing value (missing_value -999)" },
    // A double written for a float variable means the float nearest to it.
    { "float qc(z, y, x) ; qc:missing_value = -999.9 ;",
      "qc = -999.9, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, 112 ;",
      "holds 1 missing value (missing_value -999.9)" },
    { "float qc(z, y, x) ; qc:missing_value = -999.f, -888.f ; qc:_FillValue = -1.f ;",
      "qc = -999, -888, -888, -1, 11, 12, 100, 101, 102, 110, 111, 112 ;",
      "holds 4 missing values (1 _FillValue -1, 1 missing_value -999, 2 missing_value -888)" },
    { "short qc(z, y, x) ; qc:_FillValue = -32767s ; qc:scale_factor = 0.5 ; "
      "qc:add_offset = 1.0 ;",
      "qc = _, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, 112 ;",
      "holds 1 missing value (_FillValue -32767)" },
    { "float qc(z, y, x) ; qc:valid_min = 0.f ;",
      "qc = -5, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, 112 ;",
      "holds 1 missing value (below valid_min 0)" },
    { "float qc(z, y, x) ; qc:valid_max = 100.f ;",
      "qc = 0, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, 112 ;",
      "holds 5 missing values (above valid_max 100)" },
    // valid_range is in packed units: packed 0 .. 100 is 1 .. 51 unpacked.
    { "short qc(z, y, x) ; qc:valid_range = 0s, 100s ; qc:scale_factor = 0.5 ; "
      "qc:add_offset = 1.0 ;",
      "qc = -1, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, 112 ;",
      "holds 6 missing values (outside valid_range [0, 100])" },
    { "float qc(z, y, x) ; qc:_FillValue = NaNf ;",
      "qc = NaN, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, 112 ;",
      "holds 1 missing value (_FillValue nan)" },
    // Without _FillValue, a value never written holds the type's default fill value.
    { "float qc(z, y, x) ;",
      "qc = _, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, 112 ;",
      "holds 1 missing value (the default fill value 9.96921e+36)" },
  };
  for (std::size_t c = 0; c < cases.size(); ++c)
  {
    SCOPED_TRACE(cases[c].Declaration);
    const std::string path =
      Ncgen(dir, "missing-" + std::to_string(c) + ".nc", Grid(cases[c].Declaration, cases[c].Data));
    const std::string message = ErrorOf([&] { cloudvis::ReadField(path); });
    EXPECT_NE(message.find(path + ": variable \"qc\" " + cases[c].Expected), std::string::npos)
      << message;
    EXPECT_NE(message.find("field.missing = \"empty\" reads them as empty space (density 0)"),
      std::string::npos)
      << message;
  }
  // A byte variable's default fill value (-127) is a legal value: not taken as missing.
  const std::string bytes = Ncgen(dir,
    "bytes.nc",
    Grid("byte qc(z, y, x) ;", "qc = -127, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, 112 ;"));
  EXPECT_EQ(Density(cloudvis::ReadField(bytes), 0, 0, 0), -127.0);
}

// CF makes scale_factor and add_offset one number each, _FillValue, valid_min and valid_max one
// number, valid_range two, and missing_value one or several, all numbers. Before, an attribute
// of another type was skipped (a text missing_value "-999" left -999 to be read as water, a text
// scale_factor left the values 100 times too large), a second scale_factor value was dropped and
// a scale of 0 made every value add_offset, all without a word.
TEST(NetCdfConventions, AttributesOfTheWrongTypeOrShapeAreRefused)
{
  TemporaryDirectory dir;
  struct Case
  {
    std::string Declaration, Expected;
    int Kind = 1;
  };
  const std::vector<Case> cases = {
    { "float qc(z, y, x) ; qc:missing_value = \"-999\" ;",
      "attribute missing_value is text (\"-999\"), not a number: as a missing-value marker it "
      "must be numeric (CF), and read as text it would be ignored" },
    { "short qc(z, y, x) ; qc:scale_factor = \"0.01\" ;",
      "attribute scale_factor is text (\"0.01\"), not a number: as the packing's scale it must "
      "be numeric (CF)" },
    { "short qc(z, y, x) ; qc:scale_factor = 0.5, 2.0 ;",
      "attribute scale_factor has 2 values, 1 expected: as the packing's scale (CF) it is one "
      "number" },
    { "short qc(z, y, x) ; qc:scale_factor = 0. ;",
      "attribute scale_factor is 0: unpacked, every value would be add_offset" },
    { "short qc(z, y, x) ; qc:add_offset = 1.0, 2.0 ;", "attribute add_offset has 2 values" },
    { "float qc(z, y, x) ; qc:valid_range = 0.f ;",
      "attribute valid_range has 1 value, 2 expected: as the range of valid values (CF) it holds "
      "that many" },
    { "float qc(z, y, x) ; qc:valid_min = 0.f, 1.f ;",
      "attribute valid_min has 2 values, 1 expected" },
    { "float qc(z, y, x) ; string qc:missing_value = \"-999\" ;",
      "attribute missing_value is a string, not a number",
      3 },
    { "float qc(z, y, x) ; qc:effective_radius = \"ten\" ;",
      "attribute effective_radius is text (\"ten\"), not a number" },
    { "float qc(z, y, x) ; qc:effective_radius = 0.f ;",
      "attribute effective_radius must be a number of micrometres in [0.001, 1000000], got 0" },
  };
  for (std::size_t c = 0; c < cases.size(); ++c)
  {
    SCOPED_TRACE(cases[c].Declaration);
    const std::string path = Ncgen(dir,
      "attribute-" + std::to_string(c) + ".nc",
      Grid(cases[c].Declaration, std::string("qc = ") + KnownZyx + " ;"),
      cases[c].Kind);
    const std::string message = ErrorOf([&] { cloudvis::ReadField(path); });
    EXPECT_NE(message.find(path + ": variable \"qc\": " + cases[c].Expected), std::string::npos)
      << message;
  }
  // CF allows several missing values: each marks values missing (checked above), and a packed
  // variable's one-number scale and offset are applied.
  const std::string packed = Ncgen(dir,
    "packed-ok.nc",
    Grid("short qc(z, y, x) ; qc:scale_factor = 0.5 ; qc:add_offset = 1.0 ; "
         "qc:missing_value = -1s, -2s ;",
      std::string("qc = ") + KnownZyx + " ;"));
  ExpectKnownGrid(cloudvis::ReadField(packed), 0.5, 1.0);
}

// The netCDF library's (or the reader's) allocation beyond the memory the read may use: the
// message says what the file needs by its dimensions and what the read could use. Before, it
// said "it claims more than the 22.5 GiB available" for a file that needed 12 GiB.
TEST(NetCdfConventions, RunningOutOfMemorySaysWhatTheFileNeeds)
{
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's shadow memory needs more address space than ulimit -v";
#else
  TemporaryDirectory dir;
  // 800^3 floats, never written: a compressed netCDF-4 file of a few KiB that needs about
  // 6 GiB to read, read under an address-space limit of about 1 GB.
  const std::string path = Ncgen(dir,
    "big.nc",
    "netcdf big {\ndimensions: z = 800 ; y = 800 ; x = 800 ;\nvariables:\n"
    "  float ql(z, y, x) ; ql:_DeflateLevel = 1 ; ql:_ChunkSizes = 20, 800, 800 ;\n}\n",
    3);
  const std::string command = "ulimit -v 1000000 && '" + CloudvisBinary() + "' info '" + path +
    "' --set field.missing=empty 2>'" + dir.File("err.txt") + "'";
  EXPECT_NE(std::system(command.c_str()), 0);
  const std::string message = ReadText(dir.File("err.txt"));
  EXPECT_NE(message.find(path +
              ": the netCDF library ran out of memory on this file: a field of "
              "800 x 800 x 800 voxels needs about 5."),
    std::string::npos)
    << message;
  EXPECT_NE(message.find("GiB to read (by its dimensions), more than the "), std::string::npos)
    << message;
  EXPECT_NE(message.find("MiB the read may use (the address-space limit)"), std::string::npos)
    << message;
#endif
}

TEST(NetCdfConventions, FieldMissingEmptyReadsMissingValuesAsEmptySpace)
{
  TemporaryDirectory dir;
  const std::string path = Ncgen(dir,
    "packed.nc",
    Grid("short qc(z, y, x) ; qc:_FillValue = -32767s ; qc:scale_factor = 0.5 ; "
         "qc:add_offset = 1.0 ;",
      std::string("qc = _, 1, 2, 10, 11, 12, 100, 101, 102, 110, 111, _ ;")));
  FieldReport report;
  const auto field = cloudvis::ReadField(path, Options("", MissingValueRule::Empty), &report);
  int wrong = 0;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i)
      {
        const bool missing = (i + j + k == 0) || (i == 2 && j == 1 && k == 1);
        wrong += Density(field, i, j, k) == (missing ? 0.0 : Known(i, j, k) * 0.5 + 1.0) ? 0 : 1;
      }
  EXPECT_EQ(wrong, 0) << "voxels other than the unpacked value or, where missing, 0";
  EXPECT_EQ(Detail(report, "missing"),
    "2 values, read as empty space (field.missing); marked by _FillValue -32767");
  EXPECT_NE(Detail(report, "variable")
              .find("short, packed (scale_factor 0.5, add_offset 1), unpacked to float"),
    std::string::npos)
    << Detail(report, "variable");

  // Through a scene, and refused for a format that marks nothing as missing.
  const cloudvis::Scene scene =
    cloudvis::LoadScene("", { "field.file=" + path, "field.missing=empty" });
  EXPECT_EQ(scene.Field.Read.Missing, MissingValueRule::Empty);
  EXPECT_NE(ErrorOf(
              [] {
                cloudvis::LoadScene("", { "field.file=f.vti", "field.missing=empty" });
              })
              .find("field.missing: applies to NetCDF files only; a vti file (VTK XML image "
                    "data) marks no values as missing"),
    std::string::npos);
}

// ---- the default variable -----------------------------------------------------------------------

// The first data variable in the order of the file, not of the alphabet (VTK's), and never one
// that cannot be read as a density (a bounds variable, a char variable): those made a file with a
// good float variable fail.
TEST(NetCdfConventions, TheDefaultVariableIsTheFirstDataVariableInFileOrder)
{
  TemporaryDirectory dir;
  const std::string order = Ncgen(dir,
    "order.nc",
    Grid("float qv(z, y, x) ; float aaa(z, y, x) ;",
      std::string("qv = ") + KnownZyx + " ;\n aaa = 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1 ;"));
  FieldReport report;
  ExpectKnownGrid(cloudvis::ReadField(order, {}, &report));
  EXPECT_NE(Detail(report, "variable").find("\"qv\""), std::string::npos);

  const std::string cdl = "netcdf unreadable {\n"
                          "dimensions: z = 2 ; y = 2 ; x = 3 ; nv = 2 ;\n"
                          "variables:\n"
                          "  double z(z) ; double y(y) ; double x(x) ; x:bounds = \"x_bnds\" ;\n"
                          "  double x_bnds(x, nv) ;\n"
                          "  char label(z, y, x) ;\n"
                          "  float qv(z, y, x) ;\n"
                          "data:\n  z = 0, 100 ; y = 0, 10 ; x = 0, 1, 2 ;\n"
                          "  x_bnds = -0.5, 0.5, 0.5, 1.5, 1.5, 2.5 ;\n"
                          "  label = \"abcdefghijkl\" ;\n"
                          "  qv = " +
    std::string(KnownZyx) + " ;\n}\n";
  const std::string unreadable = Ncgen(dir, "unreadable.nc", cdl);
  ExpectKnownGrid(cloudvis::ReadField(unreadable, {}, &report));
  EXPECT_NE(Detail(report, "variable").find("\"qv\""), std::string::npos);
  // Chosen by name, such a variable is refused in words, with the ones that can be read.
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(unreadable, Options("label")); })
              .find("variable \"label\" (field.array) is of type char, not numbers (variables "
                    "that can be read as a density: qv)"),
    std::string::npos);

  // "density" by name still wins.
  const std::string withDensity = Ncgen(dir,
    "density.nc",
    Grid("float qv(z, y, x) ; float density(z, y, x) ;",
      std::string("density = ") + KnownZyx + " ;\n qv = 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1 ;"));
  ExpectKnownGrid(cloudvis::ReadField(withDensity));
}

// ---- axes ---------------------------------------------------------------------------------------

// Values of a variable on (x, y, z), CDL order (z fastest), that are Known(i, j, k) in the world.
const char* const KnownXyz = "0, 100, 10, 110, 1, 101, 11, 111, 2, 102, 12, 112";

// A variable declared (x, y, z) rather than (z, y, x) keeps its world axes (VTK's reader took the
// last dimension for x whatever it was); each dimension is placed by the strongest evidence the
// file gives, and `info` says which.
TEST(NetCdfConventions, DimensionsGoToTheAxesTheyStandFor)
{
  TemporaryDirectory dir;
  struct Case
  {
    std::string Dimensions;         // CDL: the three dimensions and their coordinate variables
    std::string Variable;           // the variable's dimensions
    std::array<std::string, 3> How; // "axis x" .. "axis z" reports begin so
  };
  const std::vector<Case> cases = {
    { "dimensions: x = 3 ; y = 2 ; z = 2 ;\nvariables: double x(x) ; double y(y) ; double z(z) ;",
      "(x, y, z)",
      { "\"x\" (x by its name): 0 .. 2, 3 points",
        "\"y\" (y by its name): 0 .. 10, 2 points",
        "\"z\" (z by its name): 0 .. 100, 2 points" } },
    { "dimensions: p = 3 ; q = 2 ; r = 2 ;\nvariables: double p(p) ; p:axis = \"X\" ;"
      " double q(q) ; q:axis = \"Y\" ; double r(r) ; r:axis = \"Z\" ;",
      "(p, q, r)",
      { "\"p\" (x by its coordinate's axis attribute \"X\")",
        "\"q\" (y by its coordinate's axis attribute \"Y\")",
        "\"r\" (z by its coordinate's axis attribute \"Z\")" } },
    { "dimensions: e = 3 ; n = 2 ; h = 2 ;\nvariables: double e(e) ; e:units = \"degrees_east\" ;"
      " double n(n) ; n:units = \"degrees_north\" ; double h(h) ; h:standard_name = "
      "\"altitude\" ;",
      "(e, n, h)",
      { "\"e\" (x by its coordinate's units \"degrees_east\")",
        "\"n\" (y by its coordinate's units \"degrees_north\")",
        "\"h\" (z by its coordinate's standard_name \"altitude\")" } },
    // Nothing names the dimensions: CF's order (z, y, x) by position.
    { "dimensions: c = 2 ; b = 2 ; a = 3 ;\nvariables: double c(c) ; double b(b) ; double a(a) ;",
      "(c, b, a)",
      { "\"a\" (x by position", "\"b\" (y by position", "\"c\" (z by position" } },
  };
  for (std::size_t c = 0; c < cases.size(); ++c)
  {
    SCOPED_TRACE(cases[c].Variable);
    const Case& test = cases[c];
    // The coordinates are 0 1 2, 0 10 and 0 100 along x, y and z, whatever the dimensions' names.
    const std::string names[3] = {
      test.Variable.substr(1, 1), test.Variable.substr(4, 1), test.Variable.substr(7, 1)
    };
    const bool zyx = c == 3;
    const std::string x = zyx ? names[2] : names[0], z = zyx ? names[0] : names[2];
    const std::string cdl = "netcdf axes {\n" + test.Dimensions + "\n float qc" + test.Variable +
      " ;\ndata:\n " + x + " = 0, 1, 2 ; " + names[1] + " = 0, 10 ; " + z +
      " = 0, 100 ;\n qc = " + (zyx ? KnownZyx : KnownXyz) + " ;\n}\n";
    const std::string path = Ncgen(dir, "axes-" + std::to_string(c) + ".nc", cdl);
    FieldReport report;
    ExpectKnownGrid(cloudvis::ReadField(path, {}, &report));
    for (int a = 0; a < 3; ++a)
    {
      const std::string line = Detail(report, std::string("axis ") + "xyz"[a]);
      EXPECT_EQ(line.find(test.How[std::size_t(a)]), 0u) << line;
    }
  }
  // Two dimensions that say they are the same axis: refused, naming both and why.
  const std::string twice = Ncgen(dir,
    "twice.nc",
    "netcdf twice {\ndimensions: lon = 3 ; x = 2 ; z = 2 ;\nvariables: float qc(z, x, lon) ;\n}\n");
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(twice); })
              .find("variable \"qc\" has two dimensions that are its x axis: \"x\" (by its name) "
                    "and \"lon\" (by its name)"),
    std::string::npos);
}

// ---- time, truncation, damage, cells, curvilinear grids -----------------------------------------

// A time axis with no records holds no values: the variable is refused as such (VTK's reader
// crashed on it).
TEST(NetCdfConventions, ATimeAxisWithoutRecordsIsRefusedInWords)
{
  TemporaryDirectory dir;
  const std::string path = Ncgen(dir,
    "records.nc",
    "netcdf records {\ndimensions: time = UNLIMITED ; z = 2 ; y = 2 ; x = 3 ;\n"
    "variables:\n double time(time) ; time:units = \"seconds since 2020-01-01\" ;\n"
    " float qc(time, z, y, x) ;\n}\n");
  const std::string message = ErrorOf([&] { cloudvis::ReadField(path); });
  EXPECT_NE(
    message.find(path + ": variable \"qc\" holds no values: its time axis \"time\" has no records"),
    std::string::npos)
    << message;
}

// A netCDF-4 file is an HDF5 file: cut short, it is refused as truncated with the sizes (the
// library said "HDF error"); damaged inside, as damaged.
TEST(NetCdfConventions, ATruncatedOrDamagedNetCdf4FileIsRefusedAsSuch)
{
  TemporaryDirectory dir;
  const std::string path =
    Ncgen(dir, "whole.nc", Grid("float qc(z, y, x) ;", std::string("qc = ") + KnownZyx + " ;"), 3);
  ExpectKnownGrid(cloudvis::ReadField(path));
  const std::string bytes = ReadText(path);
  for (const std::size_t kept : { bytes.size() - 1, bytes.size() / 2, std::size_t(200) })
  {
    WriteText(dir.File("cut.nc"), bytes.substr(0, kept));
    const std::string message = ErrorOf([&] { cloudvis::ReadField(dir.File("cut.nc")); });
    EXPECT_NE(
      message.find("the netCDF-4 (HDF5) file says it holds " + std::to_string(bytes.size()) +
        " bytes but holds " + std::to_string(kept) + ": it is truncated"),
      std::string::npos)
      << message;
  }
  // Past the superblock, every byte overwritten: what HDF5 finds there does not hold together.
  WriteText(dir.File("damaged.nc"), bytes.substr(0, 96) + std::string(bytes.size() - 96, '\x55'));
  const std::string message = ErrorOf([&] { cloudvis::ReadField(dir.File("damaged.nc")); });
  EXPECT_NE(message.find("the file is damaged or truncated"), std::string::npos) << message;
}

// Values on cells (coordinates with bounds) are read at their coordinates, the cells' centres
// (VTK's reader made cell data of them, which cloudvis refused); 2-D latitude and longitude make
// a curvilinear grid, refused.
TEST(NetCdfConventions, CellsAreReadAtTheirCentresAndCurvilinearGridsRefused)
{
  TemporaryDirectory dir;
  const std::string cells = Ncgen(dir,
    "cells.nc",
    "netcdf cells {\ndimensions: z = 2 ; y = 2 ; x = 3 ; nv = 2 ;\nvariables:\n"
    " double z(z) ; double y(y) ; double x(x) ; x:bounds = \"x_bnds\" ;\n"
    " double x_bnds(x, nv) ; float qc(z, y, x) ;\n"
    "data:\n z = 0, 100 ; y = 0, 10 ; x = 0, 1, 2 ;\n x_bnds = -0.5, 0.5, 0.5, 1.5, 1.5, 2.5 ;\n"
    " qc = " +
      std::string(KnownZyx) + " ;\n}\n");
  ExpectKnownGrid(cloudvis::ReadField(cells));
  const std::string curvilinear = Ncgen(dir,
    "curvilinear.nc",
    "netcdf curvilinear {\ndimensions: y = 2 ; x = 3 ;\nvariables:\n"
    " float lat(y, x) ; float lon(y, x) ; float qc(y, x) ; qc:coordinates = \"lat lon\" ;\n}\n");
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(curvilinear); })
              .find("variable \"qc\" is on curvilinear coordinates (\"lat\" of its `coordinates` "
                    "attribute has 2 dimensions): cloudvis reads regular and rectilinear grids "
                    "only"),
    std::string::npos);
}

} // namespace
