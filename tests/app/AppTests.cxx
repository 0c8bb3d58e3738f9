// Library-level tests of the application layers: what the command-line tests cannot judge by regex. A
// generated file must equal, bit for bit, vtkCloudDensitySource configured by hand with the same
// parameters (which also checks that every scene key lands on the right member); statistics
// must match analytic answers; overrides and atomic writes must behave as documented; rendered
// PNGs must have the requested size, the background where there is no cloud and the cloud where
// there is one. The Render tests need an X display (Xvfb under `make test`).
#include "AtomicFile.h"
#include "CommandLine.h"
#include "Errors.h"
#include "ExportRender.h"
#include "FieldIO.h"
#include "FieldStatistics.h"
#include "FieldTestFiles.h"
#include "FileNames.h"
#include "InputFiles.h"
#include "OffscreenRender.h"
#include "Scene.h"
#include "SceneField.h"
#include "SceneJson.h"
#include "SupportImages.h"
#include "SupportRun.h"
#include "Utf8.h"
#include "VtkWrittenFields.h"
#include "vtkCloudDensitySource.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkCamera.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkXMLImageDataReader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <stdexcept>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
using json = nlohmann::json;

using cloudvis::support::ReadText;
using cloudvis::support::TemporaryDirectory;
using cloudvis::support::WriteText;

// Runs the cloudvis binary; fails the test on a non-zero status.
std::string RunCloudvis(const std::vector<std::string>& arguments)
{
  const cloudvis::support::CommandResult run = cloudvis::support::RunCloudvis(arguments);
  EXPECT_EQ(run.Status, 0) << run.Err;
  return run.Out;
}

vtkSmartPointer<vtkImageData> ReadBack(const std::string& path)
{
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkImageData> image = reader->GetOutput();
  return image;
}

void ExpectBitIdentical(vtkImageData* expected, vtkImageData* actual)
{
  int de[3], da[3];
  expected->GetDimensions(de);
  actual->GetDimensions(da);
  ASSERT_EQ(std::vector<int>(de, de + 3), std::vector<int>(da, da + 3));
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_EQ(expected->GetOrigin()[a], actual->GetOrigin()[a]);
    EXPECT_EQ(expected->GetSpacing()[a], actual->GetSpacing()[a]);
  }
  auto* e = vtkFloatArray::SafeDownCast(expected->GetPointData()->GetArray("density"));
  auto* a = vtkFloatArray::SafeDownCast(actual->GetPointData()->GetArray("density"));
  ASSERT_NE(e, nullptr);
  ASSERT_NE(a, nullptr) << "the written file has no float array \"density\"";
  ASSERT_EQ(e->GetNumberOfValues(), a->GetNumberOfValues());
  EXPECT_EQ(0, std::memcmp(e->GetPointer(0), a->GetPointer(0), sizeof(float) * e->GetNumberOfValues()));
}

vtkSmartPointer<vtkImageData> Generate(vtkCloudDensitySource* source)
{
  source->Update();
  vtkSmartPointer<vtkImageData> image = source->GetOutput();
  return image;
}

// The field file `path` is, bit for bit, what vtkCloudDensitySource makes of these settings.
void ExpectSourceField(const std::string& path, const std::array<int, 3>& dimensions,
  const std::array<double, 6>& bounds, const cloudvis::FieldDescription& field, double time)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(dimensions.data());
  source->SetBounds(bounds.data());
  source->SetField(field);
  source->SetTime(time);
  ExpectBitIdentical(Generate(source), ReadBack(path));
}

// ---- generate: files equal the source's output --------------------------------------------

TEST(Generate, DefaultSceneEqualsSourceDefaults)
{
  TemporaryDirectory dir;
  RunCloudvis({ "generate", "--set", "field.dimensions=40", "-o", dir.File("f.vti") });
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(40, 40, 40);
  ExpectBitIdentical(Generate(source), ReadBack(dir.File("f.vti")));
}

TEST(Generate, EveryKeyReachesTheSource)
{
  TemporaryDirectory dir;
  WriteText(dir.File("scene.json"), R"({
    "description": "every procedural key away from its default",
    "field": {
      "dimensions": [20, 24, 28], "bounds": [-1, 2, -3, 1, -2, 2.5],
      "density_model": "fbm_falloff", "density_scale": 2.5, "falloff_width": 0.4,
      "shape": [ { "type": "box", "center": [0.2, -0.3, 0.1], "rotation": [10, 20, 30],
                   "scale": 1.2, "half_size": [0.5, 0.7, 0.3] },
                 { "type": "capsule", "end_a": [-1, 0, 0], "end_b": [1, 0.5, 0], "radius": 0.4 },
                 "torus" ],
      "blend": "smooth_union", "blend_radius": 0.3,
      "noise": "perlin", "octaves": 3, "frequency": 1.7, "lacunarity": 2.5,
      "lacunarity_increment": 0.1, "gain": 0.6, "amplitude": 0.8, "seed": 4000000000,
      "wind": [0.1, 0.2, -0.3], "time": 1.25 } })");
  RunCloudvis({ "generate", dir.File("scene.json"), "-o", dir.File("f.vti") });

  cloudvis::FieldDescription field;
  field.Model = cloudvis::DensityModel::FbmFalloff;
  field.DensityScale = 2.5;
  field.FalloffWidth = 0.4;
  cloudvis::Shape box;
  box.Type = cloudvis::ShapeType::Box;
  box.Center = glm::vec3(0.2f, -0.3f, 0.1f);
  box.RotationDegrees = glm::vec3(10, 20, 30);
  box.Scale = 1.2f;
  box.HalfSize = glm::vec3(0.5f, 0.7f, 0.3f);
  cloudvis::Shape capsule;
  capsule.Type = cloudvis::ShapeType::Capsule;
  capsule.EndA = glm::vec3(-1, 0, 0);
  capsule.EndB = glm::vec3(1, 0.5f, 0);
  capsule.Radius = 0.4f;
  cloudvis::Shape torus;
  torus.Type = cloudvis::ShapeType::Torus;
  field.Shapes = { box, capsule, torus };
  field.Blend = cloudvis::ShapeBlend::SmoothUnion;
  field.BlendRadius = 0.3;
  field.Noise.Type = cloudvis::noise::NoiseType::Perlin;
  field.Noise.Octaves = 3;
  field.Noise.Frequency = 1.7;
  field.Noise.Lacunarity = 2.5;
  field.Noise.LacunarityIncrement = 0.1;
  field.Noise.Gain = 0.6;
  field.Noise.Amplitude = 0.8;
  field.Noise.Seed = 4000000000u;
  field.Wind = glm::dvec3(0.1, 0.2, -0.3);
  ExpectSourceField(dir.File("f.vti"), { { 20, 24, 28 } }, { { -1, 2, -3, 1, -2, 2.5 } }, field, 1.25);
}

TEST(Generate, MorphSceneEqualsSourceMorph)
{
  TemporaryDirectory dir;
  RunCloudvis({ "generate", CLOUDVIS_SCENES "/morph.json", "--set", "field.dimensions=24", "--set",
    "field.time=4.5", "-o", dir.File("f.vti") });
  cloudvis::FieldDescription field;
  field.Morph = true;
  ExpectSourceField(
    dir.File("f.vti"), { { 24, 24, 24 } }, { { -3.5, 3.5, -3.5, 3.5, -3.5, 3.5 } }, field, 4.5);
}

TEST(Generate, LeavesOnlyTheTarget)
{
  TemporaryDirectory dir;
  RunCloudvis({ "generate", "--set", "field.dimensions=8", "-o", dir.File("f.vti") });
  EXPECT_EQ(dir.Files(), std::vector<std::string>{ "f.vti" });
}

// ---- info: statistics with known answers ----------------------------------------------------

json InfoJson(const std::vector<std::string>& arguments)
{
  std::vector<std::string> all{ "info" };
  all.insert(all.end(), arguments.begin(), arguments.end());
  all.push_back("--json");
  return json::parse(RunCloudvis(all));
}

TEST(Info, ConstantSphereMatchesItsVolume)
{
  const double scale = 2.5;
  const json info = InfoJson({ CLOUDVIS_SCENES "/sphere.json", "--set", "field.dimensions=64",
    "--set", "field.density_scale=" + std::to_string(scale) });
  EXPECT_EQ(info["range"][0].get<double>(), 0.0);
  EXPECT_EQ(info["range"][1].get<double>(), scale);
  // Exactly the lattice points inside the unit sphere are non-empty (counted here independently
  // of the density code; a handful of points right on the surface may round either way) ...
  const int n = 64;
  std::uint64_t inside = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
      {
        const double x = -2.0 + 4.0 * i / (n - 1), y = -2.0 + 4.0 * j / (n - 1),
                     z = -2.0 + 4.0 * k / (n - 1);
        inside += x * x + y * y + z * z < 1.0 ? 1 : 0;
      }
  const double fraction = info["non_empty_fraction"].get<double>();
  EXPECT_NEAR(fraction, double(inside) / (n * n * n), 1e-5);
  // ... and their share is close to the sphere's volume fraction (4/3 pi) / 64 of the box; at
  // 64^3 the lattice count falls about 5% short of it.
  const double volumeFraction = 4.0 / 3.0 * M_PI / 64.0;
  EXPECT_NEAR(fraction, volumeFraction, 0.06 * volumeFraction);
  // Constant density: the mean is the scale times the occupied fraction, and every voxel falls
  // in the first (empty) or last (full) histogram bin.
  EXPECT_NEAR(info["mean"].get<double>(), scale * fraction, 1e-9);
  const auto counts = info["histogram"]["counts"].get<std::vector<std::uint64_t>>();
  ASSERT_EQ(counts.size(), 16u);
  EXPECT_EQ(counts.back(), info["non_empty_voxels"].get<std::uint64_t>());
  EXPECT_EQ(counts.front() + counts.back(), 64u * 64u * 64u);
  EXPECT_EQ(info["histogram"]["edges"].size(), 17u);
  EXPECT_EQ(info["bounds"], json({ -2.0, 2.0, -2.0, 2.0, -2.0, 2.0 }));
  EXPECT_NEAR(info["spacing"][0].get<double>(), 4.0 / 63.0, 1e-12);
}

TEST(Info, UnsignedCharFieldIsConvertedToFloat)
{
  vtkSmartPointer<vtkImageData> field = cloudvis::ReadField(CLOUDVIS_TEST_DATA "/uchar-field.vti");
  auto* density = vtkFloatArray::SafeDownCast(field->GetPointData()->GetScalars());
  ASSERT_NE(density, nullptr);
  EXPECT_STREQ(density->GetName(), "density");
  EXPECT_EQ(density->GetValue(7), 40.0f);
  const cloudvis::FieldStatistics s = cloudvis::ComputeFieldStatistics(field);
  EXPECT_EQ(s.Mean, 12.5);
  EXPECT_EQ(s.NonEmptyVoxels, 4u);
  EXPECT_EQ(s.Histogram.front(), 4u);
  EXPECT_EQ(s.Histogram.back(), 1u); // 40, the maximum, belongs to the last bin
}

TEST(Info, OverridesChangeTheField)
{
  const json base = InfoJson({ CLOUDVIS_SCENES "/fbm-sphere.json", "--set", "field.dimensions=16" });
  const json other = InfoJson({ CLOUDVIS_SCENES "/fbm-sphere.json", "--set", "field.dimensions=16",
    "--set", "field.seed=7" });
  EXPECT_NE(base["mean"], other["mean"]);
  const json box = InfoJson({ CLOUDVIS_SCENES "/fbm-sphere.json", "--set", "field.dimensions=20,10,5" });
  EXPECT_EQ(box["dimensions"], json({ 20, 10, 5 }));
}

// ---- --set value parsing ------------------------------------------------------------------

TEST(Overrides, ValueParsing)
{
  using cloudvis::ParseOverrideValue;
  EXPECT_EQ(ParseOverrideValue("k", "6"), json(6));
  EXPECT_EQ(ParseOverrideValue("k", "\"perlin\""), json("perlin"));
  EXPECT_EQ(ParseOverrideValue("k", "perlin"), json("perlin"));
  EXPECT_EQ(ParseOverrideValue("k", "128,128,128"), json({ 128, 128, 128 }));
  EXPECT_EQ(ParseOverrideValue("k", "0.5, -0.1,-0.5"), json({ 0.5, -0.1, -0.5 }));
  EXPECT_EQ(ParseOverrideValue("k", "[1, 2]"), json({ 1, 2 }));
  EXPECT_EQ(ParseOverrideValue("k", "1,two"), json("1,two"));
  EXPECT_EQ(ParseOverrideValue("k", ""), json(""));
  for (const char* bad : { "nan", "inf", "-inf", "NaN", "Infinity", "1,nan,2", "1e999" })
  {
    EXPECT_THROW(ParseOverrideValue("k", bad), cloudvis::InputError) << bad;
  }
}

TEST(Overrides, CreateIntermediateObjectsAndRefuseNonObjects)
{
  json document = json::object();
  cloudvis::ApplyOverride(document, "field.shape=box");
  EXPECT_EQ(document, json::parse(R"({"field": {"shape": "box"}})"));
  cloudvis::ApplyOverride(document, "field.shape=torus");
  EXPECT_EQ(document["field"]["shape"], "torus");
  EXPECT_THROW(cloudvis::ApplyOverride(document, "field.shape.radius=2"), cloudvis::InputError);
  EXPECT_THROW(cloudvis::ApplyOverride(document, "field.shape"), cloudvis::UsageError);
  EXPECT_THROW(cloudvis::ApplyOverride(document, "=3"), cloudvis::UsageError);
  EXPECT_THROW(cloudvis::ApplyOverride(document, "field..x=3"), cloudvis::UsageError);
}

// ---- scenes ---------------------------------------------------------------------------------

TEST(Scene, DefaultIsTheSourceDefault)
{
  const cloudvis::Scene scene = cloudvis::LoadScene("", {});
  vtkNew<vtkCloudDensitySource> source;
  EXPECT_EQ(scene.Field.Dimensions, (std::array<int, 3>{ source->GetDimensions()[0],
                                      source->GetDimensions()[1], source->GetDimensions()[2] }));
  EXPECT_EQ(scene.Field.Description.Noise.Octaves, source->GetField().Noise.Octaves);
  EXPECT_FALSE(scene.Field.FromFile());
}

TEST(Scene, FilePathsAreRelativeToTheScene)
{
  const cloudvis::Scene scene = cloudvis::LoadScene(CLOUDVIS_TEST_DATA "/uchar-scene.json", {});
  EXPECT_EQ(scene.Field.File, CLOUDVIS_TEST_DATA "/uchar-field.vti");
  EXPECT_EQ(cloudvis::LoadScene("", { "field.file=/abs/f.vti" }).Field.File, "/abs/f.vti");
}

TEST(Scene, MorphAndShapeLists)
{
  EXPECT_TRUE(cloudvis::LoadScene("", { "field.shape=morph" }).Field.Description.Morph);
  EXPECT_TRUE(cloudvis::LoadScene("", { "field.shape=[\"morph\"]" }).Field.Description.Morph);
  const cloudvis::Scene two = cloudvis::LoadScene("", { "field.shape=[\"box\",\"cross\"]" });
  ASSERT_EQ(two.Field.Description.Shapes.size(), 2u);
  EXPECT_EQ(two.Field.Description.Shapes[1].Type, cloudvis::ShapeType::Cross);
}

TEST(Scene, EveryShippedSceneHasADescription)
{
  for (const char* name : { "sphere", "fbm-sphere", "octave-sweep-1", "octave-sweep-2",
         "octave-sweep-3", "octave-sweep-4", "white-noise", "value-noise", "perlin-falloff",
         "morph", "two-lights" })
  {
    const cloudvis::Scene scene =
      cloudvis::LoadScene(std::string(CLOUDVIS_SCENES "/") + name + ".json", {});
    EXPECT_FALSE(scene.Description.empty()) << name;
    EXPECT_LE(scene.Field.Dimensions[0], 128) << name;
  }
  const auto octaves = [](int n)
  {
    return cloudvis::LoadScene(CLOUDVIS_SCENES "/octave-sweep-" + std::to_string(n) + ".json", {})
      .Field.Description.Noise.Octaves;
  };
  for (int n = 1; n <= 4; ++n)
  {
    EXPECT_EQ(octaves(n), n);
  }
}

// ---- out of memory --------------------------------------------------------------------------

// A std::bad_alloc ends a command with the step that ran out of memory, its size and what the
// process could have had, not a bare "out of memory" (issue 36): here generation under an
// address-space limit of about 3 GB for a field of 8 GiB.
TEST(OutOfMemory, NamesTheStepItsSizeAndTheLimit)
{
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's shadow memory needs more address space than ulimit -v";
#else
  TemporaryDirectory dir;
  const std::string command = "cd '" + dir.Path + "' && ulimit -v 3000000 && '" +
    cloudvis::support::CloudvisBinary() +
    "' generate --set field.dimensions=2048,2048,512 -o big.vti 2> err.txt";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string message = ReadText(dir.File("err.txt"));
  EXPECT_NE(message.find("cloudvis: error: out of memory while generating a field of 2048 x 2048 x "
                         "512 voxels (default scene), which needs about 8 GiB; "),
    std::string::npos)
    << message;
  EXPECT_NE(
    message.find("of memory is available, and the address-space limit (ulimit -v) is 2.86 GiB"),
    std::string::npos)
    << message;
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << "one line: " << message;
  EXPECT_EQ(dir.Files(), std::vector<std::string>{ "err.txt" });
#endif
}

// ---- atomic writes --------------------------------------------------------------------------

// The temporary a write in progress has made in `dir`: its one hidden file.
std::string TemporaryIn(const TemporaryDirectory& dir)
{
  std::string temporary;
  for (const std::string& name : dir.Files())
  {
    if (name[0] == '.')
    {
      EXPECT_TRUE(temporary.empty()) << "a second temporary " << name;
      temporary = dir.File(name);
    }
  }
  return temporary;
}

TEST(AtomicFile, FailureLeavesTargetUntouchedAndNoTemporary)
{
  TemporaryDirectory dir;
  const std::string target = dir.File("f.vti");
  WriteText(target, "previous");
  std::string temporary;
  EXPECT_THROW(cloudvis::WriteStreamAtomically(target,
                 "the test's text",
                 [&](std::ostream& out)
                 {
                   out << "half a fi" << std::flush;
                   temporary = TemporaryIn(dir);
                   throw cloudvis::InputError("disk full");
                 }),
    cloudvis::InputError);
  EXPECT_EQ(temporary.rfind(dir.Path + "/", 0), 0u) << "temporary not in the target's directory";
  EXPECT_EQ(ReadText(temporary), "") << "the temporary is still there";
  EXPECT_EQ(ReadText(target), "previous");
  EXPECT_EQ(dir.Files(), std::vector<std::string>{ "f.vti" });
}

TEST(AtomicFile, SuccessReplacesTargetWithOrdinaryPermissions)
{
  TemporaryDirectory dir;
  const std::string target = dir.File("f.vti");
  WriteText(target, "previous");
  ::chmod(target.c_str(), 0640);
  const auto writeText = [](const char* text)
  { return [text](std::ostream& out) { out << text; }; };
  cloudvis::WriteStreamAtomically(target, "the test's text", writeText("new"));
  EXPECT_EQ(ReadText(target), "new");
  EXPECT_EQ(dir.Files(), std::vector<std::string>{ "f.vti" });
  struct stat info;
  ASSERT_EQ(::stat(target.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0640u) << "a replaced file keeps its permissions";

  const std::string fresh = dir.File("g.vti");
  cloudvis::WriteStreamAtomically(fresh, "the test's text", writeText("x"));
  ASSERT_EQ(::stat(fresh.c_str(), &info), 0);
  const mode_t mask = ::umask(0);
  ::umask(mask);
  EXPECT_EQ(info.st_mode & 0777, 0666u & ~mask) << "a new file gets the umask's permissions";
}

TEST(AtomicFile, RefusesMissingDirectoryBeforeWriting)
{
  bool called = false;
  EXPECT_THROW(
    cloudvis::WriteStreamAtomically(
      "/nonexistent-dir/f.vti", "the test's text", [&called](std::ostream&) { called = true; }),
    cloudvis::InputError);
  EXPECT_FALSE(called);
}

// An output that is a symbolic link is written through it (AtomicFile.h): the link stays a link,
// the file it names gets the content and keeps its own mode, a dangling link's file is created
// with the umask's mode, and the temporary is made beside the file, not beside the link.
TEST(AtomicFile, WritesThroughSymbolicLinks)
{
  TemporaryDirectory dir;
  ASSERT_EQ(::mkdir(dir.File("real").c_str(), 0755), 0);
  const std::string real = dir.Write("real/f.vti", "previous");
  ::chmod(real.c_str(), 0640);
  ASSERT_EQ(::symlink("real/f.vti", dir.File("link.vti").c_str()), 0);
  ASSERT_EQ(::symlink("link.vti", dir.File("link2.vti").c_str()), 0); // a chain of two
  cloudvis::WriteStreamAtomically(
    dir.File("link2.vti"), "the test file", [](std::ostream& out) { out << "new"; });
  struct stat info;
  ASSERT_EQ(::lstat(dir.File("link.vti").c_str(), &info), 0);
  EXPECT_TRUE(S_ISLNK(info.st_mode)) << "the link was replaced by a file";
  ASSERT_EQ(::lstat(dir.File("link2.vti").c_str(), &info), 0);
  EXPECT_TRUE(S_ISLNK(info.st_mode)) << "the link was replaced by a file";
  EXPECT_EQ(ReadText(real), "new");
  ASSERT_EQ(::stat(real.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0640u) << "the file behind the link keeps its mode";
  EXPECT_EQ(dir.Files("/real"), std::vector<std::string>{ "f.vti" });

  ASSERT_EQ(::symlink("real/new.vdb", dir.File("dangling.vdb").c_str()), 0);
  cloudvis::WriteStreamAtomically(
    dir.File("dangling.vdb"), "the test file", [](std::ostream& out) { out << "x"; });
  EXPECT_EQ(ReadText(dir.File("real/new.vdb")), "x");
  ASSERT_EQ(::lstat(dir.File("dangling.vdb").c_str(), &info), 0);
  EXPECT_TRUE(S_ISLNK(info.st_mode));
  ASSERT_EQ(::stat(dir.File("real/new.vdb").c_str(), &info), 0);
  const mode_t mask = ::umask(0);
  ::umask(mask);
  EXPECT_EQ(info.st_mode & 0777, 0666u & ~mask) << "a new file gets the umask's permissions";

  ASSERT_EQ(::symlink("loop.vti", dir.File("loop.vti").c_str()), 0);
  EXPECT_NE(cloudvis::test::ErrorOf([&]
              { cloudvis::WriteStreamAtomically(dir.File("loop.vti"), "x", [](std::ostream&) {}); })
              .find("loop.vti: cannot write: too many levels of symbolic links"),
    std::string::npos);
}

// Through cloudvis itself: a .vdb and a .pvti behind links. The pieces of a .pvti go beside the
// file the link names, where its relative Source attributes find them.
TEST(AtomicFile, GenerateWritesThroughLinks)
{
  TemporaryDirectory dir;
  ASSERT_EQ(::mkdir(dir.File("sub").c_str(), 0755), 0);
  ASSERT_EQ(::symlink("sub/real.vdb", dir.File("f.vdb").c_str()), 0);
  ASSERT_EQ(::symlink("sub/real.pvti", dir.File("p.pvti").c_str()), 0);
  RunCloudvis({ "generate", "--set", "field.dimensions=8", "-o", dir.File("f.vdb") });
  RunCloudvis({ "generate", "--set", "field.dimensions=8", "-o", dir.File("p.pvti") });
  struct stat info;
  ASSERT_EQ(::lstat(dir.File("f.vdb").c_str(), &info), 0);
  EXPECT_TRUE(S_ISLNK(info.st_mode));
  ASSERT_EQ(::lstat(dir.File("p.pvti").c_str(), &info), 0);
  EXPECT_TRUE(S_ISLNK(info.st_mode));
  EXPECT_EQ(dir.Files("/sub"), (std::vector<std::string>{ "real.pvti", "real.vdb", "real_0.vti" }));
  EXPECT_NE(RunCloudvis({ "info", dir.File("f.vdb") }).find("OpenVDB"), std::string::npos);
  EXPECT_NE(RunCloudvis({ "info", dir.File("sub/real.pvti") }).find("parallel image data"),
    std::string::npos);
}

// The checked stream is seekable as OpenVDB, VTK and OpenEXR need (tellp without a flush, seekp
// back to fill in an offset), and the file holds exactly what was written.
TEST(AtomicFile, StreamSeeksBackAndChecksTheSize)
{
  TemporaryDirectory dir;
  const std::string target = dir.File("f.bin");
  cloudvis::WriteStreamAtomically(target,
    "the test file",
    [](std::ostream& out)
    {
      out << "0000";
      EXPECT_EQ(out.tellp(), std::streampos(4));
      out << std::string(3u << 20, 'x'); // more than the buffer holds
      const std::streampos end = out.tellp();
      EXPECT_EQ(end, std::streampos(4 + (3 << 20)));
      out.seekp(0);
      out << "head";
      out.seekp(end);
      out << "tail";
    });
  const std::string text = ReadText(target);
  ASSERT_EQ(text.size(), 4u + (3u << 20) + 4u);
  EXPECT_EQ(text.substr(0, 4), "head");
  EXPECT_EQ(text.substr(text.size() - 4), "tail");
  EXPECT_EQ(dir.Files(), std::vector<std::string>{ "f.bin" });
}

// Every InputError and UsageError is one printable line (Errors.h): control characters in what
// it quotes are escaped as \xNN, a NUL included (which would otherwise end the message), C1
// controls too; valid UTF-8 passes; escaping twice changes nothing.
TEST(Messages, ControlCharactersAreEscaped)
{
  EXPECT_EQ(
    std::string(cloudvis::InputError(std::string("a\0b\nc\td\x1b[31m\x7f", 13) + ".vti").what()),
    "a\\x00b\\x0ac\\x09d\\x1b[31m\\x7f.vti");
  EXPECT_EQ(std::string(cloudvis::UsageError("x\ry").what()), "x\\x0dy");
  EXPECT_EQ(cloudvis::PrintableText("\xc2\x9b\xc3\xa9\xff"),
    "\\xc2\\x9b\xc3\xa9\\xff"); // CSI, é, a stray byte
  const std::string once = cloudvis::PrintableText("a\nb\xfe");
  EXPECT_EQ(cloudvis::PrintableText(once), once);
  EXPECT_EQ(cloudvis::EscapeInvalidUtf8("a\nb"), "a\nb") << "JSON text keeps its newlines";

  // End to end: the error about a missing file whose name holds a newline and an ESC is one line,
  // and so is the "wrote" line of an output with a tab and a newline in its name.
  TemporaryDirectory dir;
  const cloudvis::support::CommandResult missing =
    cloudvis::support::RunCloudvis({ "info", dir.File("new\nline\x1b[2J.vti") });
  EXPECT_EQ(missing.Status, 1);
  EXPECT_EQ(missing.Err,
    "cloudvis: error: " + dir.File("new\\x0aline\\x1b[2J.vti") +
      ": cannot read field: No such file or directory\n");
  const std::string out =
    RunCloudvis({ "generate", "--set", "field.dimensions=8", "-o", dir.File("a\tb\nc.vti") });
  EXPECT_EQ(out, "wrote " + dir.File("a\\x09b\\x0ac.vti") + " (8 x 8 x 8 voxels)\n");
}

// ---- help documents every option of every command -------------------------------------------

TEST(Help, EveryOptionOfEveryCommand)
{
  for (const cloudvis::CommandSpec& command : cloudvis::Commands())
  {
    const std::string help = RunCloudvis({ command.Name, "--help" });
    for (const cloudvis::OptionSpec& option : command.Options)
    {
      EXPECT_NE(help.find("--" + option.Long), std::string::npos) << command.Name << " --" << option.Long;
      EXPECT_NE(help.find(option.Help.substr(0, 20)), std::string::npos) << option.Help;
    }
    EXPECT_NE(RunCloudvis({ "--help" }).find(command.Name), std::string::npos);
  }
}

// ---- scene sections of the renderer ---------------------------------------------------------

TEST(Scene, RenderSectionsReachTheScene)
{
  const cloudvis::Scene scene = cloudvis::LoadScene("",
    { "transfer_function.opacity=[[0,0],[0.2,0.1],[1,0.5]]", "transfer_function.color=[[0,1,0,0.5]]",
      "transfer_function.unit_distance=0.5", "camera.position=1,2,3", "camera.focal_point=0,1,0",
      "camera.view_up=1,0,0", "camera.view_angle=45", "background=0,0.5,1", "render.step=0.02",
      "render.jitter=false", "render.resolution_scale=0.5", "render.accumulate=3",
      "render.skip_empty_space=false", "render.size=100,50" },
    { { "render.lighting", "none", "--lighting" }, { "render.size", json({ 120, 60 }), "--size" } });
  using P2 = std::array<double, 2>;
  EXPECT_EQ(scene.TransferFunction.Opacity, (std::vector<P2>{ { 0, 0 }, { 0.2, 0.1 }, { 1, 0.5 } }));
  EXPECT_EQ(scene.TransferFunction.Color, (std::vector<std::array<double, 4>>{ { 0, 1, 0, 0.5 } }));
  EXPECT_EQ(scene.TransferFunction.UnitDistance, 0.5);
  EXPECT_EQ(scene.Camera.Position, (std::array<double, 3>{ 1, 2, 3 }));
  EXPECT_EQ(scene.Camera.FocalPoint, (std::array<double, 3>{ 0, 1, 0 }));
  EXPECT_EQ(scene.Camera.ViewUp, (std::array<double, 3>{ 1, 0, 0 }));
  EXPECT_EQ(scene.Camera.ViewAngle, 45.0);
  EXPECT_EQ(scene.Background, (std::array<double, 3>{ 0, 0.5, 1 }));
  EXPECT_EQ(scene.Render.Lighting.Model, cloudvis::LightingModel::None);
  EXPECT_EQ(scene.Render.Step, 0.02);
  EXPECT_FALSE(scene.Render.Jitter);
  EXPECT_EQ(scene.Render.ResolutionScale, 0.5);
  EXPECT_EQ(scene.Render.Accumulate, 3);
  EXPECT_FALSE(scene.Render.SkipEmptySpace);
  EXPECT_EQ(scene.Render.Size, (std::array<int, 2>{ 120, 60 })) << "an option overrides --set";
}

// The view section (what `cloudvis view` restores) reaches the scene and is written back as it
// was read, so that a scene the viewer saves opens as it was left; a scene without one has none.
TEST(Scene, ViewSectionReachesTheSceneAndRoundTrips)
{
  const cloudvis::Scene scene = cloudvis::LoadScene("",
    { R"(view={"layout": "four", "slices": [true, false, true], "slice_position": [0.5, 0, -1],
      "oblique": {"visible": true, "origin": [0.1, 0.2, 0.3], "normal": [0, 0, 2]},
      "window_level": [0.4, 0.3], "slice_colors": "viridis", "legends": false})" },
    {});
  ASSERT_TRUE(scene.View.has_value());
  const cloudvis::ViewSpec& view = *scene.View;
  EXPECT_EQ(view.Layout, cloudvis::ViewLayout::Four);
  EXPECT_EQ(view.Slices, (std::array<bool, 3>{ true, false, true }));
  EXPECT_EQ(view.SlicePosition, (std::array<double, 3>{ 0.5, 0, -1 }));
  EXPECT_TRUE(view.Oblique.Visible);
  EXPECT_EQ(view.Oblique.Origin, (std::array<double, 3>{ 0.1, 0.2, 0.3 }));
  EXPECT_EQ(view.Oblique.Normal, (std::array<double, 3>{ 0, 0, 2 }));
  EXPECT_EQ(view.WindowLevel, (std::array<double, 2>{ 0.4, 0.3 }));
  EXPECT_EQ(cloudvis::SliceColormapNames()[size_t(view.SliceColors)], "viridis");
  EXPECT_FALSE(view.Legends);
  const json written = cloudvis::SceneToJson(scene, cloudvis::ResolvedCamera{});
  EXPECT_EQ(written["view"], scene.Document["view"]);
  EXPECT_FALSE(cloudvis::LoadScene("", {}).View.has_value());
  EXPECT_FALSE(cloudvis::SceneToJson(cloudvis::LoadScene("", {}), cloudvis::ResolvedCamera{})
                 .contains("view"));
}

TEST(Scene, ShippedDefaultSceneFileMatchesTheBuiltInDefaults)
{
  // fbm-sphere.json writes the default scene out in full (all but the computed camera).
  const cloudvis::Scene file = cloudvis::LoadScene(CLOUDVIS_SCENES "/fbm-sphere.json", {});
  const cloudvis::Scene builtIn = cloudvis::DefaultScene();
  EXPECT_EQ(file.TransferFunction.Opacity, builtIn.TransferFunction.Opacity);
  EXPECT_EQ(file.TransferFunction.Color, builtIn.TransferFunction.Color);
  EXPECT_EQ(file.TransferFunction.UnitDistance, builtIn.TransferFunction.UnitDistance);
  EXPECT_EQ(file.Background, builtIn.Background);
  EXPECT_EQ(file.Render.Size, builtIn.Render.Size);
  EXPECT_EQ(file.Render.Accumulate, builtIn.Render.Accumulate);
  EXPECT_FALSE(builtIn.Camera.Position.has_value());
  EXPECT_FALSE(builtIn.Camera.FocalPoint.has_value());
}

TEST(Camera, DefaultsLookAlongMinusZAtTheCentreAndFitTheBounds)
{
  vtkNew<vtkRenderer> renderer;
  const double bounds[6] = { 0, 2, -1, 1, 4, 6 };
  cloudvis::ApplyCamera(cloudvis::CameraSpec{}, bounds, renderer, "s");
  vtkCamera* camera = renderer->GetActiveCamera();
  const double* f = camera->GetFocalPoint();
  const double* p = camera->GetPosition();
  EXPECT_NEAR(f[0], 1.0, 1e-12);
  EXPECT_NEAR(f[1], 0.0, 1e-12);
  EXPECT_NEAR(f[2], 5.0, 1e-12);
  EXPECT_NEAR(p[0], 1.0, 1e-12);
  EXPECT_NEAR(p[1], 0.0, 1e-12);
  // The bounding sphere (radius sqrt(3)) fits the 30-degree view.
  EXPECT_GE((p[2] - 5.0) * std::sin(15.0 * M_PI / 180.0), std::sqrt(3.0) - 1e-9);
  EXPECT_EQ(camera->GetViewAngle(), 30.0);
  EXPECT_NEAR(camera->GetViewUp()[1], 1.0, 1e-12);

  cloudvis::CameraSpec given;
  given.Position = { { 5, 0, 5 } };
  given.ViewAngle = 50;
  cloudvis::ApplyCamera(given, bounds, renderer, "s");
  EXPECT_NEAR(camera->GetPosition()[0], 5.0, 1e-12);
  EXPECT_NEAR(camera->GetFocalPoint()[0], 1.0, 1e-12) << "the focal point stays the centre";
  EXPECT_EQ(camera->GetViewAngle(), 50.0);
  cloudvis::CameraSpec wide;
  wide.ViewAngle = 90;
  cloudvis::ApplyCamera(wide, bounds, renderer, "s");
  EXPECT_NEAR((camera->GetPosition()[2] - 5.0) * std::sin(M_PI / 4.0), std::sqrt(3.0), 0.1)
    << "a wider view comes closer, still fitting the bounding sphere";

  cloudvis::CameraSpec parallel;
  parallel.ViewUp = { { 0, 0, 1 } };
  EXPECT_THROW(cloudvis::ApplyCamera(parallel, bounds, renderer, "s"), cloudvis::InputError);
}

// ---- render: pixels (needs an X display; `make test` runs under Xvfb) -----------------------

// Within one 8-bit step of a color given in [0, 1].
bool IsColor(const cloudvis::support::Image& image, int x, int y, const std::array<double, 3>& rgb)
{
  for (int c = 0; c < 3; ++c)
  {
    if (std::abs(image.Level(x, y, c) - 255.0 * rgb[c]) > 1.0)
    {
      return false;
    }
  }
  return true;
}

TEST(Render, WritesAPngOfTheRequestedSizeWithTheCloudOverTheBackground)
{
  TemporaryDirectory dir;
  const std::string out = RunCloudvis({ "render", CLOUDVIS_SCENES "/fbm-sphere.json", "--size",
    "64x48", "--set", "render.accumulate=2", "--set", "field.dimensions=48", "-o", dir.File("r.png") });
  EXPECT_NE(out.find("wrote " + dir.File("r.png") + " (64 x 48 pixels, 2 frames averaged)"),
    std::string::npos) << out;
  EXPECT_EQ(dir.Files(), std::vector<std::string>{ "r.png" });
  const cloudvis::support::Image png = cloudvis::support::ReadPng(dir.File("r.png"));
  ASSERT_EQ(png.Width, 64);
  ASSERT_EQ(png.Height, 48);
  ASSERT_EQ(png.Components, 3) << "an RGB PNG";
  const std::array<double, 3> background = cloudvis::DefaultScene().Background;
  for (const auto& corner : { std::make_pair(0, 0), std::make_pair(63, 0), std::make_pair(0, 47),
         std::make_pair(63, 47) })
  {
    EXPECT_TRUE(IsColor(png, corner.first, corner.second, background))
      << "corner " << corner.first << "," << corner.second;
  }
  EXPECT_FALSE(IsColor(png, 32, 24, background));
  // The cloud is white-ish: brighter than the background in every channel.
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_GT(int(png.Level(32, 24, c)), int(255.0 * background[c]) + 40) << "channel " << c;
  }
}

TEST(Render, BackgroundKeyReachesTheWindow)
{
  TemporaryDirectory dir;
  RunCloudvis({ "render", CLOUDVIS_SCENES "/sphere.json", "--size", "32x16", "--set",
    "background=1,0,0", "--set", "render.accumulate=1", "--set", "field.dimensions=16", "-o",
    dir.File("r.png") });
  const cloudvis::support::Image png = cloudvis::support::ReadPng(dir.File("r.png"));
  ASSERT_EQ(png.Width, 32);
  ASSERT_EQ(png.Height, 16);
  EXPECT_TRUE(IsColor(png, 0, 0, { { 1, 0, 0 } }));
}

cloudvis::Scene SmallScene()
{
  cloudvis::Scene scene = cloudvis::LoadScene("", { "field.dimensions=16" });
  scene.Render.Size = { { 32, 24 } };
  return scene;
}

TEST(Render, AccumulatesTheRequestedFramesAndTimesEachBenchmarkFrame)
{
  cloudvis::Scene scene = SmallScene();
  scene.Render.Accumulate = 3;
  const vtkSmartPointer<vtkImageData> field = cloudvis::ProduceField(scene);
  const cloudvis::OffscreenRenderResult result = cloudvis::RenderOffscreen(scene, field, "f", 2);
  EXPECT_EQ(result.AccumulatedFrames, 3);
  ASSERT_EQ(result.FrameMilliseconds.size(), 2u);
  for (double ms : result.FrameMilliseconds)
  {
    EXPECT_GT(ms, 0.0);
  }
  EXPECT_EQ(result.Image.Width, 32);
  EXPECT_EQ(result.Image.RGB.size(), 32u * 24u * 3u);

  scene.Render.Jitter = false; // every frame would be the same: one is rendered
  EXPECT_EQ(cloudvis::RenderOffscreen(scene, field, "f").AccumulatedFrames, 1);
}

TEST(Render, MapperErrorBecomesTheInputError)
{
  vtkNew<vtkImageData> field;
  field->SetDimensions(4, 4, 4);
  field->AllocateScalars(VTK_FLOAT, 3);
  std::fill_n(static_cast<float*>(field->GetScalarPointer()), 4 * 4 * 4 * 3, 0.0f);
  try
  {
    cloudvis::RenderOffscreen(SmallScene(), field, "vectors.vti");
    FAIL() << "a 3-component field rendered";
  }
  catch (const cloudvis::InputError& e)
  {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("vectors.vti: the scalar array", 0), 0u) << message;
    EXPECT_NE(message.find("has 3 components; a density has exactly 1"), std::string::npos) << message;
  }
}

TEST(Render, WithoutDisplayFailsWithTheXvfbHintAndWritesNothing)
{
  TemporaryDirectory dir;
  const cloudvis::support::CommandResult run = cloudvis::support::RunCloudvis(
    { "render", CLOUDVIS_SCENES "/sphere.json", "-o", dir.File("r.png") }, { "-DISPLAY" });
  EXPECT_EQ(run.Status, 1);
  EXPECT_NE(run.Err.find("cloudvis needs an X display"), std::string::npos) << run.Err;
  EXPECT_NE(run.Err.find("xvfb-run -a cloudvis render"), std::string::npos) << run.Err;
  EXPECT_TRUE(dir.Files().empty());
}

} // namespace

TEST(Render, ANonFiniteImageIsAnErrorNamingTheLikelyCauseBeforeAnyFileIsWritten)
{
  // The check every writing path makes on the float image (render, compare, animate, the
  // viewer's screenshot, --cpu-reference): the renderers' own validation should leave nothing
  // for it to find, so it is tested on an image made bad on purpose.
  std::vector<float> rgba(4 * 6, 0.25f);
  EXPECT_NO_THROW(cloudvis::CheckFiniteImage(rgba.data(), 6, "cloud.vti"));
  rgba[5] = std::nanf("");
  rgba[10] = INFINITY;
  try
  {
    cloudvis::CheckFiniteImage(rgba.data(), 6, "cloud.vti");
    FAIL() << "a NaN pixel was accepted";
  }
  catch (const cloudvis::InputError& e)
  {
    const std::string message = e.what();
    EXPECT_NE(message.find("cloud.vti: the rendered image has 2 values that are NaN or infinite, "
                           "so nothing was written"),
      std::string::npos)
      << message;
    EXPECT_NE(message.find("likely causes"), std::string::npos);
  }
}

// ---- inputs and outputs: right or refused (docs/reliability.md) -----------------------------

namespace
{

using cloudvis::test::ExpectSameField;

// Class "valid files refused": what VTK writes, cloudvis reads, value for value.
TEST(FieldFormats, BigEndianFilesWrittenByVtkReadAsWritten)
{
  TemporaryDirectory dir;
  const vtkSmartPointer<vtkImageData> reference = cloudvis::test::ReferenceField();
  for (const cloudvis::test::BigEndianVariant& variant : cloudvis::test::BigEndianVariants())
  {
    SCOPED_TRACE(variant.Name);
    const std::string path = cloudvis::test::WriteBigEndian(dir.Path, variant);
    ASSERT_NE(ReadText(path).find("byte_order=\"BigEndian\""), std::string::npos);
    ExpectSameField(reference, cloudvis::ReadField(path));
  }
}

TEST(FieldFormats, ParallelFilesWrittenByVtkAssembleIntoTheWholeField)
{
  TemporaryDirectory dir;
  const vtkSmartPointer<vtkImageData> reference = cloudvis::test::ReferenceField();
  struct Layout
  {
    int Pieces;
    bool Subdirectory, BigEndian;
  };
  for (const Layout& layout : { Layout{ 1, false, false },
         Layout{ 3, false, false },
         Layout{ 4, true, true },
         Layout{ 7, true, false } })
  {
    const std::string name = "p" + std::to_string(layout.Pieces) + ".pvti";
    SCOPED_TRACE(name);
    const std::string path = cloudvis::test::WriteParallel(
      dir.Path, name, layout.Pieces, layout.Subdirectory, layout.BigEndian);
    // The writer really split the field: one <Piece> element per piece.
    const std::string text = ReadText(path);
    int pieces = 0;
    for (auto at = text.find("<Piece "); at != std::string::npos; at = text.find("<Piece ", at + 1))
    {
      ++pieces;
    }
    EXPECT_EQ(pieces, layout.Pieces);
    ExpectSameField(reference, cloudvis::ReadField(path));
  }
}

TEST(FieldFormats, ExtensionsMatchWithoutRegardToCase)
{
  for (const char* path : { "f.vti", "dir/F.VTI", "f.Vti", "f.pvti", "F.PVTI", "dir.d/f.pVtI" })
  {
    EXPECT_TRUE(cloudvis::IsFieldFile(path)) << path;
  }
  for (const char* path : { "f.json", "f.vtk", "vti", ".vti", "f.vti.bak", "f.vti/scene", "f" })
  {
    EXPECT_FALSE(cloudvis::IsFieldFile(path)) << path;
  }
  const cloudvis::FieldFormat* parallel = cloudvis::FindFieldFormat("A.PVTI");
  ASSERT_NE(parallel, nullptr);
  EXPECT_EQ(parallel->Name, "VTK XML parallel image data");
  EXPECT_EQ(cloudvis::LowerCaseExtension("dir/Image.EXR"), ".exr");
  EXPECT_EQ(cloudvis::FieldFileExtensions(),
    ".vti, .pvti, .vdb, .nc, .nc4, .cdf, .nrrd, .nhdr, .mha, .mhd, .raw");
}

// Class "JSON files above the size limit": the limit is the largest size read, inclusive.
TEST(InputFiles, SizeLimitIsInclusive)
{
  TemporaryDirectory dir;
  const std::string path = dir.File("f.json");
  WriteText(path, std::string(100, ' '));
  const cloudvis::RegularInputFile file(path, "test file");
  EXPECT_EQ(file.ReadAll(100).size(), 100u);
  try
  {
    file.ReadAll(99);
    FAIL() << "a file one byte above the limit was read";
  }
  catch (const cloudvis::InputError& e)
  {
    EXPECT_STREQ(e.what(),
      (path +
        ": cannot read test file: it is 0 MiB (100 bytes), above the "
        "limit of 0 MiB (99 bytes) for a test file")
        .c_str());
  }
  EXPECT_EQ(file.ReadAt(98, 10), "  ");
}

// Class "paths that are not UTF-8": the escape must accept exactly what nlohmann::json's dump()
// accepts, or a path it passes still throws (type_error 316) in a JSON document.
TEST(Utf8, EscapesExactlyTheBytesJsonRefuses)
{
  EXPECT_EQ(cloudvis::EscapeInvalidUtf8("bad\xff\xfe.vti"), "bad\\xff\\xfe.vti");
  EXPECT_EQ(cloudvis::EscapeInvalidUtf8("\xc0\xaf"), "\\xc0\\xaf");          // overlong '/'
  EXPECT_EQ(cloudvis::EscapeInvalidUtf8("\xed\xa0\x80"), "\\xed\\xa0\\x80"); // a surrogate
  EXPECT_EQ(cloudvis::EscapeInvalidUtf8("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80"); // > U+10FFFF
  EXPECT_EQ(cloudvis::EscapeInvalidUtf8("\xe2\x82"), "\\xe2\\x82");                   // cut short
  EXPECT_EQ(cloudvis::EscapeInvalidUtf8("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8c\xa7"),
    "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8c\xa7"); // é, €, a cloud: unchanged
  // Random byte strings rich in lead and continuation bytes, against nlohmann::json itself.
  std::mt19937 random(10);
  std::uniform_int_distribution<int> length(0, 8), kind(0, 2), ascii(0x20, 0x7e),
    continuation(0x80, 0xbf), lead(0xc0, 0xff);
  int valid = 0;
  for (int n = 0; n < 20000; ++n)
  {
    std::string text;
    for (int i = length(random); i > 0; --i)
    {
      const int k = kind(random);
      text += char(k == 0 ? ascii(random) : k == 1 ? continuation(random) : lead(random));
    }
    bool jsonAccepts = true;
    try
    {
      (void)json(text).dump();
    }
    catch (const json::type_error&)
    {
      jsonAccepts = false;
    }
    ASSERT_EQ(cloudvis::IsValidUtf8(text), jsonAccepts) << json(cloudvis::EscapeInvalidUtf8(text));
    valid += jsonAccepts ? 1 : 0;
    const std::string escaped = cloudvis::EscapeInvalidUtf8(text);
    ASSERT_NO_THROW((void)json(escaped).dump());
    if (jsonAccepts)
    {
      ASSERT_EQ(escaped, text);
    }
  }
  EXPECT_GT(valid, 2000) << "too few valid strings to test the multi-byte forms";
}

// The temporaries of a .pvti's pieces, written by several processes into one group directory: a
// signal ending any one of them removes every member, the others' too, and the directory, since
// mpirun may SIGKILL the others before their own handler runs. Here a child writes the even
// members and this process the odd ones; SIGTERM to the child leaves nothing.
TEST(AtomicFile, ASignalToOneProcessRemovesTheWholeGroupWhoeverWroteItsMembers)
{
  TemporaryDirectory dir;
  const std::string target = dir.File("g.pvti");
  const std::string tag = "0123456789abcdef0123456789abcdef";
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0)
  {
    cloudvis::TemporaryGroup group(target, tag, true, "g_", ".vti", 20, "g.pvti");
    for (int i = 0; i < 20; i += 2)
    {
      WriteText(group.Member("g_" + std::to_string(i) + ".vti"), "piece");
    }
    WriteText(group.Member("g.pvti"), "parallel file");
    (void)!::write(ready[1], "x", 1);
    for (;;)
    {
      ::pause();
    }
  }
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1);
  {
    cloudvis::TemporaryGroup group(target, tag, false, "g_", ".vti", 20, "g.pvti");
    for (int i = 1; i < 20; i += 2)
    {
      WriteText(group.Member("g_" + std::to_string(i) + ".vti"), "piece");
    }
    EXPECT_EQ(dir.Files().size(), 1u) << "the group's directory, beside the target";
    ASSERT_EQ(::kill(child, SIGTERM), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
    EXPECT_EQ(dir.Files(), std::vector<std::string>{}) << "members or the directory left";
  }
  ::close(ready[0]);
  ::close(ready[1]);
}

// Class "temporary names beyond the file-name limit": the temporary of any legal name fits.
TEST(AtomicFile, TemporaryNamesStayWithinTheFileNameLimit)
{
  TemporaryDirectory dir;
  const long limit = ::pathconf(dir.Path.c_str(), _PC_NAME_MAX);
  ASSERT_EQ(limit, 255) << "the test's names assume the usual limit";
  std::string twoByteCharacters;
  for (int i = 0; i < 125; ++i)
  {
    twoByteCharacters += "\xc3\xa9"; // é
  }
  const std::string names[] = {
    std::string(251, 'a') + ".vti", // 255 bytes
    twoByteCharacters + ".vti",     // 254 bytes: cut between characters
    "a." + std::string(253, 'x'),   // an extension too long to keep
    "short.png",
  };
  for (const std::string& name : names)
  {
    SCOPED_TRACE(name.size());
    std::string temporary;
    cloudvis::WriteStreamAtomically(dir.File(name),
      "the test's text",
      [&](std::ostream& out)
      {
        out << "x";
        temporary = TemporaryIn(dir);
      });
    const std::string temporaryName = cloudvis::FileNameOf(temporary);
    EXPECT_LE(temporaryName.size(), 255u);
    EXPECT_EQ(cloudvis::DirectoryOf(temporary), dir.Path) << "not beside the target";
    EXPECT_EQ(temporaryName.rfind("." + name.substr(0, 4), 0), 0u) << temporaryName;
    EXPECT_TRUE(cloudvis::IsValidUtf8(temporaryName)) << "a character cut in two";
    if (cloudvis::LowerCaseExtension(name).size() < 20)
    {
      EXPECT_EQ(cloudvis::LowerCaseExtension(temporaryName), cloudvis::LowerCaseExtension(name));
    }
    EXPECT_EQ(ReadText(dir.File(name)), "x");
  }
}

} // namespace
