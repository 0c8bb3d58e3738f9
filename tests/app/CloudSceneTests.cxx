// The cloud model in scene files (issue 22): every field.cloud key and the new noise keys reach
// the field description and come back from the resolved scene unchanged, and a coverage map
// given as an image file (a PNG written here by VTK's own writer) is read and stretched over the
// field as vtkCloudDensitySource::SetCoverageMap does. The refusals (bad values naming their
// dotted key, a missing or 3-D map file) are command-line cases in CMakeLists.txt. Maps read
// safely (issue 36): damaged, huge and impossible image headers are refused without a crash (the
// PNGs are made here by hand, with zlib), a map is read once and only by the cloud model, and
// integer maps mean the same in every container. Detail matched to the camera (issue 35):
// field.dimensions "auto" gives voxels no wider than a pixel on the nearest cloud in view, within
// field.max_voxels, and a resolved scene generates the same lattice again.
#include "CameraDetail.h"
#include "Errors.h"
#include "ExportRender.h"
#include "Scene.h"
#include "SceneField.h"
#include "SceneJson.h"
#include "SupportRun.h"
#include "vtkCloudDensitySource.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataWriter.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <zlib.h>

namespace
{
using json = nlohmann::json;
using cloudvis::support::TemporaryDirectory;
using cloudvis::support::WriteText;

// A cloud layer with every key away from its default.
json EveryCloudKey()
{
  return { { "type", "cumulonimbus" },
    { "base", 0.5 },
    { "top", 3.0 },
    { "coverage", 0.45 },
    { "coverage_map", "noise" },
    { "map_scale", 3.0 },
    { "map_octaves", 5 },
    { "map_gain", 0.55 },
    { "shape_scale", 1.75 },
    { "detail_scale", 0.25 },
    { "erosion", 0.3 },
    { "curl", 0.6 },
    { "breakup", 0.35 },
    { "anvil", 0.7 },
    { "anvil_direction", { -0.5, 2.0 } },
    { "shear", { 0.125, -0.25 } } };
}

// The keys of a cumulonimbus on the shapes (the tower's plan) away from their defaults.
json TowerKeys()
{
  return { { "type", "cumulonimbus" },
    { "base", -1.5 },
    { "top", 1.0 },
    { "anvil", 0.5 },
    { "anvil_reach", 1.5 },
    { "overshoot", 0.25 },
    { "rain", 0.01 } };
}

const float* DensityOf(vtkImageData* image)
{
  auto* array = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("density"));
  return array ? array->GetPointer(0) : nullptr;
}

TEST(CloudScene, EveryCloudKeyReachesTheLayerAndRoundTrips)
{
  const json document = { { "field",
    { { "density_model", "cloud" },
      { "noise", "perlin_worley" },
      { "noise_period", 4 },
      { "lacunarity", 2 },
      { "lacunarity_increment", 0 },
      { "cloud", EveryCloudKey() } } } };
  const cloudvis::Scene scene = cloudvis::SceneFromDocument(document, "d", "");
  const cloudvis::FieldDescription& f = scene.Field.Description;
  const cloudvis::CloudLayer& l = f.Layer;
  EXPECT_EQ(f.Model, cloudvis::DensityModel::Cloud);
  EXPECT_EQ(f.Noise.Type, cloudvis::noise::NoiseType::PerlinWorley);
  EXPECT_EQ(f.Noise.Period, 4);
  EXPECT_EQ(l.Type, cloudvis::CloudType::Cumulonimbus);
  EXPECT_EQ(l.Source, cloudvis::CoverageSource::Noise);
  // Each number as EveryCloudKey gives it.
  const json keys = EveryCloudKey();
  const std::pair<const char*, double> numbers[] = { { "base", l.Base },
    { "top", l.Top },
    { "coverage", l.Coverage },
    { "map_scale", l.MapScale },
    { "map_octaves", l.MapOctaves },
    { "map_gain", l.MapGain },
    { "shape_scale", l.ShapeScale },
    { "detail_scale", l.DetailScale },
    { "erosion", l.Erosion },
    { "curl", l.Curl },
    { "breakup", l.Breakup },
    { "anvil", l.Anvil } };
  for (const auto& [key, value] : numbers)
  {
    EXPECT_EQ(value, keys[key].get<double>()) << key;
  }
  EXPECT_EQ(l.Shear[0], keys["shear"][0].get<double>());
  EXPECT_EQ(l.Shear[1], keys["shear"][1].get<double>());
  EXPECT_EQ(l.AnvilDirection[0], keys["anvil_direction"][0].get<double>());
  EXPECT_EQ(l.AnvilDirection[1], keys["anvil_direction"][1].get<double>());

  // The resolved scene writes the same keys back, and reads back to the same scene.
  const double bounds[6] = { -2, 2, -2, 2, -2, 2 };
  const json written = cloudvis::SceneToJson(scene, cloudvis::ResolveCamera(scene, bounds));
  // Every key, the tower's three at their defaults (they need the shapes' coverage; see
  // TowerKeysReachTheLayerAndRoundTrip).
  json expected = EveryCloudKey();
  expected["anvil_reach"] = 0.0;
  expected["overshoot"] = 0.0;
  expected["rain"] = 0.0;
  EXPECT_EQ(written["field"]["cloud"], expected) << written["field"].dump();
  EXPECT_EQ(written["field"]["noise"], "perlin_worley");
  EXPECT_EQ(written["field"]["noise_period"], 4);
  const cloudvis::Scene again = cloudvis::SceneFromDocument(written, "d", "");
  EXPECT_EQ(cloudvis::SceneToJson(again, cloudvis::ResolveCamera(again, bounds)), written);
}

// The anvil's reach, the overshooting dome and the rain shaft need the shapes' tower; they read
// and write back like the other keys.
TEST(CloudScene, TowerKeysReachTheLayerAndRoundTrip)
{
  const json document = { { "field", { { "density_model", "cloud" }, { "cloud", TowerKeys() } } } };
  const cloudvis::Scene scene = cloudvis::SceneFromDocument(document, "d", "");
  const cloudvis::CloudLayer& l = scene.Field.Description.Layer;
  EXPECT_EQ(l.AnvilReach, 1.5);
  EXPECT_EQ(l.Overshoot, 0.25);
  EXPECT_EQ(l.Rain, 0.01);
  const double bounds[6] = { -2, 2, -2, 2, -2, 2 };
  const json written = cloudvis::SceneToJson(scene, cloudvis::ResolveCamera(scene, bounds));
  for (const char* key : { "anvil_reach", "overshoot", "rain" })
  {
    EXPECT_EQ(written["field"]["cloud"][key], TowerKeys()[key]) << written["field"].dump();
  }
}

TEST(CloudScene, EveryNameReadsBackToItsValue)
{
  const cloudvis::ResolvedCamera camera;
  for (const char* noise : { "worley", "inverted_worley", "perlin_worley" })
  {
    const json document = { { "field", { { "noise", noise } } } };
    EXPECT_EQ(cloudvis::SceneToJson(
                cloudvis::SceneFromDocument(document, "d", ""), camera)["field"]["noise"],
      noise);
  }
  for (const char* type : { "stratus", "stratocumulus", "cumulus", "cumulonimbus" })
  {
    for (const char* map : { "shapes", "noise" })
    {
      const json document = { { "field",
        { { "density_model", "cloud" },
          { "cloud", { { "type", type }, { "coverage_map", map } } } } } };
      const json written =
        cloudvis::SceneToJson(cloudvis::SceneFromDocument(document, "d", ""), camera)["field"];
      EXPECT_EQ(written["cloud"]["type"], type);
      EXPECT_EQ(written["cloud"]["coverage_map"], map);
    }
  }
}

// A PNG coverage map, named relative to the scene file, half 0 and half 255: the scene's field
// is, bit for bit, the source's with the same image given to SetCoverageMap, and its 0 half is
// empty.
TEST(CloudScene, ACoverageMapPngIsReadAsTheSourceReadsTheImage)
{
  TemporaryDirectory dir;
  vtkNew<vtkImageData> image;
  image->SetDimensions(16, 16, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* pixels = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int row = 0; row < 16; ++row)
    for (int column = 0; column < 16; ++column)
      pixels[row * 16 + column] = column < 8 ? 0 : 255;
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(dir.File("map.png").c_str());
  writer->Write();

  const json scene = { { "field",
    { { "dimensions", { 61, 21, 30 } },
      { "bounds", { -2, 2, -1, 1.5, -2, 2 } },
      { "density_model", "cloud" },
      { "wind", { 0, 0, 0 } },
      { "seed", 5 },
      { "cloud",
        { { "base", -0.5 },
          { "top", 1.0 },
          { "coverage", 1.0 },
          { "coverage_map", "map.png" },
          { "shape_scale", 1.5 },
          { "detail_scale", 0.6 } } } } } };
  WriteText(dir.File("scene.json"), scene.dump());
  const cloudvis::Scene loaded = cloudvis::LoadScene(dir.File("scene.json"), {});
  EXPECT_EQ(loaded.Field.CoverageMapFile, dir.File("map.png"));
  // The map was read once, with the scene: generating needs the file no more.
  ASSERT_EQ(std::remove(dir.File("map.png").c_str()), 0);
  vtkSmartPointer<vtkImageData> field = cloudvis::ProduceField(loaded);

  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(61, 21, 30);
  source->SetBounds(-2, 2, -1, 1.5, -2, 2);
  source->SetField(loaded.Field.Description);
  source->SetCoverageMap(image);
  source->Update();
  const vtkIdType n = source->GetOutput()->GetNumberOfPoints();
  ASSERT_EQ(field->GetNumberOfPoints(), n);
  const float* read = DensityOf(field);
  const float* expected = DensityOf(source->GetOutput());
  ASSERT_NE(read, nullptr);
  EXPECT_EQ(std::memcmp(read, expected, sizeof(float) * n), 0);

  // Voxel i lies at x = -2 + i / 15; the map's last 0 (column 7) at x = -2 + 7 / 15 * 4.
  size_t emptyHalf = 0, fullHalf = 0;
  for (vtkIdType id = 0; id < n; ++id)
  {
    (id % 61 <= 28 ? emptyHalf : fullHalf) += read[id] > 0.0f;
  }
  EXPECT_EQ(emptyHalf, 0u);
  EXPECT_GT(fullHalf, 500u);
}

// ---- coverage maps read safely (issue 36) -------------------------------------------------

std::string Bytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void WriteBytes(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary) << bytes;
}

void PutBigEndian32(std::string& bytes, std::size_t at, std::uint32_t value)
{
  for (int i = 0; i < 4; ++i)
  {
    bytes[at + i] = char((value >> (24 - 8 * i)) & 0xff);
  }
}

// A PNG chunk: length, type, data, CRC.
std::string PngChunk(const std::string& type, const std::string& data)
{
  std::string chunk(4, '\0');
  PutBigEndian32(chunk, 0, std::uint32_t(data.size()));
  chunk += type + data + std::string(4, '\0');
  const std::string covered = type + data;
  PutBigEndian32(chunk,
    chunk.size() - 4,
    std::uint32_t(
      ::crc32(0L, reinterpret_cast<const Bytef*>(covered.data()), uInt(covered.size()))));
  return chunk;
}

// A 16 x 16 8-bit map written by VTK's PNG writer: 0 in its left half, 255 in its right.
std::string HalfMapPng(const TemporaryDirectory& dir)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(16, 16, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* pixels = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int i = 0; i < 256; ++i)
  {
    pixels[i] = i % 16 < 8 ? 0 : 255;
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(dir.File("written.png").c_str());
  writer->Write();
  return Bytes(dir.File("written.png"));
}

json CloudWithMap(const std::string& map, const char* model = "cloud")
{
  return { { "field",
    { { "dimensions", 8 },
      { "density_model", model },
      { "cloud", { { "coverage", 1.0 }, { "coverage_map", map } } } } } };
}

// The message reading a scene whose coverage map is `name` in `dir` is refused with.
std::string RefusalOf(const TemporaryDirectory& dir, const std::string& name)
{
  try
  {
    cloudvis::SceneFromDocument(CloudWithMap(name), "scene", dir.Path);
  }
  catch (const cloudvis::InputError& error)
  {
    return error.what();
  }
  return "(read)";
}

// A damaged PNG crashed VTK's PNG reader (libpng's error handler returns into it) in the cloudvis
// process: SIGSEGV. It is read in the isolated child now, and a header that is damaged or claims
// a size beyond the map limit is refused before any decoder sees the file.
TEST(CloudScene, DamagedPngMapsAreRefusedWithoutCrashing)
{
  TemporaryDirectory dir;
  const std::string png = HalfMapPng(dir);
  ASSERT_GT(png.size(), 60u);
  ASSERT_EQ(png.compare(12, 4, "IHDR"), 0);
  WriteBytes(dir.File("truncated.png"), png.substr(0, png.size() / 2));
  std::string flipped = png;
  for (std::size_t i = 41; i + 12 < flipped.size(); ++i)
  {
    flipped[i] = char(flipped[i] ^ 0x5a); // the image data and its CRC
  }
  WriteBytes(dir.File("flipped.png"), flipped);
  std::string wide = png;
  PutBigEndian32(wide, 16, 0x7fffffffu);
  WriteBytes(dir.File("wide_bad_crc.png"), wide);
  wide.replace(8, 25, PngChunk("IHDR", wide.substr(16, 13)));
  WriteBytes(dir.File("wide.png"), wide);
  WriteBytes(dir.File("header_only.png"), png.substr(0, 20));

  const std::regex malformed(
    "^.*/(truncated|flipped)\\.png: coverage map: VTK's PNG reader (crashed|failed) on this file "
    "\\([^)]*\\): it is malformed$");
  EXPECT_TRUE(std::regex_match(RefusalOf(dir, "truncated.png"), malformed))
    << RefusalOf(dir, "truncated.png");
  EXPECT_TRUE(std::regex_match(RefusalOf(dir, "flipped.png"), malformed))
    << RefusalOf(dir, "flipped.png");
  EXPECT_EQ(RefusalOf(dir, "wide.png"),
    dir.File("wide.png") +
      ": coverage map: 2147483647 x 16 pixels (34.4 G) is more than a coverage map may have "
      "(16384 x 16384, 268 M)");
  EXPECT_EQ(RefusalOf(dir, "wide_bad_crc.png"),
    dir.File("wide_bad_crc.png") +
      ": coverage map: the PNG header is damaged: the IHDR chunk's CRC does not match");
  EXPECT_EQ(RefusalOf(dir, "header_only.png"),
    dir.File("header_only.png") +
      ": coverage map: the file ends inside its PNG header (20 bytes; the signature and IHDR "
      "chunk take 33)");
  // The undamaged file reads.
  WriteBytes(dir.File("map.png"), png);
  EXPECT_EQ(RefusalOf(dir, "map.png"), "(read)");
}

// A map is read only by the model that uses it: under another density model the damaged file is
// never opened, by the scene's reader (LoadCoverageMap) or by the source.
TEST(CloudScene, AMapIsNotReadUnderAnotherDensityModel)
{
  TemporaryDirectory dir;
  WriteBytes(dir.File("truncated.png"), HalfMapPng(dir).substr(0, 40));
  cloudvis::FieldSpec field;
  field.Dimensions = { { 8, 8, 8 } };
  field.Description.Model = cloudvis::DensityModel::Constant;
  field.Description.Layer.Source = cloudvis::CoverageSource::Map;
  field.CoverageMapFile = dir.File("truncated.png");
  EXPECT_NO_THROW(cloudvis::LoadCoverageMap(field));
  EXPECT_EQ(field.Description.Layer.Map, nullptr);
  EXPECT_EQ(cloudvis::ValidateProceduralField(field), "");
  EXPECT_NO_THROW(cloudvis::MakeDensitySource(field));
  // The cloud model reads it, and refuses it.
  field.Description.Model = cloudvis::DensityModel::Cloud;
  EXPECT_THROW(cloudvis::LoadCoverageMap(field), cloudvis::InputError);
}

// A valid 30000 x 30000 PNG (875 KB of zlib, 900 M pixels) was decoded whole, past 1.8 GB, to a
// bare "out of memory"; its header is checked against the map limit before decoding now.
TEST(CloudScene, AHugeValidPngMapIsRefusedFromItsHeader)
{
  TemporaryDirectory dir;
  const std::uint32_t n = 30000;
  std::string header(13, '\0');
  PutBigEndian32(header, 0, n);
  PutBigEndian32(header, 4, n);
  header[8] = 8; // bit depth; colour type 0 (grey), deflate, no filter, no interlace
  z_stream stream{};
  ASSERT_EQ(deflateInit(&stream, 1), Z_OK);
  std::string row(n + 1, '\x80'), data, buffer(1 << 16, '\0');
  row[0] = 0; // filter type None
  for (std::uint32_t y = 0; y <= n; ++y)
  {
    stream.next_in = reinterpret_cast<Bytef*>(&row[0]);
    stream.avail_in = y < n ? uInt(row.size()) : 0;
    do
    {
      stream.next_out = reinterpret_cast<Bytef*>(&buffer[0]);
      stream.avail_out = uInt(buffer.size());
      deflate(&stream, y < n ? Z_NO_FLUSH : Z_FINISH);
      data.append(buffer, 0, buffer.size() - stream.avail_out);
    } while (stream.avail_out == 0);
  }
  deflateEnd(&stream);
  WriteBytes(dir.File("huge.png"),
    std::string("\x89PNG\r\n\x1a\n", 8) + PngChunk("IHDR", header) + PngChunk("IDAT", data) +
      PngChunk("IEND", ""));
  EXPECT_LT(data.size(), 8u << 20);
  EXPECT_EQ(RefusalOf(dir, "huge.png"),
    dir.File("huge.png") +
      ": coverage map: 30000 x 30000 pixels (900 M) is more than a coverage map may have "
      "(16384 x 16384, 268 M)");
}

// A PNM header's size was read with its signs dropped (-5 x -5 as 5 x 5); it must be two
// positive whole numbers now, and the maximum value one from 1 to 65535. A BMP's width alike (its
// height may be negative: rows stored top down).
TEST(CloudScene, PnmAndBmpHeadersMustStateAPositiveSize)
{
  TemporaryDirectory dir;
  const std::string pixels(25, '\x80');
  WriteBytes(dir.File("negative.pgm"), "P5\n-5 -5\n255\n" + pixels);
  WriteBytes(dir.File("zero.pgm"), "P5 # a comment\n0 5\n255\n" + pixels);
  WriteBytes(dir.File("maximum.pgm"), "P5\n5 5\n0\n" + pixels);
  WriteBytes(dir.File("short.ppm"), "P6\n5");
  WriteBytes(dir.File("good.pgm"), "P5\n# a comment\n5 5\n255\n" + pixels);
  EXPECT_EQ(RefusalOf(dir, "negative.pgm"),
    dir.File("negative.pgm") +
      ": coverage map: the PGM header (P5) gives a size of -5 x -5 pixels; each must be a whole "
      "number from 1 to 2147483647");
  EXPECT_EQ(RefusalOf(dir, "zero.pgm"),
    dir.File("zero.pgm") +
      ": coverage map: the PGM header (P5) gives a size of 0 x 5 pixels; each must be a whole "
      "number from 1 to 2147483647");
  EXPECT_EQ(RefusalOf(dir, "maximum.pgm"),
    dir.File("maximum.pgm") +
      ": coverage map: the PGM header (P5) gives a maximum value of 0; it must be a whole number "
      "from 1 to 65535");
  EXPECT_EQ(RefusalOf(dir, "short.ppm"),
    dir.File("short.ppm") + ": coverage map: the PPM header (P6) ends before its width and height");
  // A 24-bit BMP of 4 x 4 white pixels, its width then made -4.
  std::string bmp = std::string("BM") + std::string(12, '\0') + std::string(1, char(40)) +
    std::string(3, '\0') + std::string("\x04\0\0\0\x04\0\0\0\x01\0\x18\0", 12) +
    std::string(24, '\0') + std::string(48, '\xff');
  bmp[10] = 54; // the pixels' offset
  WriteBytes(dir.File("good.bmp"), bmp);
  PutBigEndian32(bmp, 18, 0xfcffffffu); // -4, little-endian
  WriteBytes(dir.File("negative.bmp"), bmp);
  EXPECT_EQ(RefusalOf(dir, "negative.bmp"),
    dir.File("negative.bmp") +
      ": coverage map: the BMP header gives a size of -4 x 4 pixels; the width must be from 1 to "
      "2147483647, the height not 0 (negative: rows stored top down)");
  EXPECT_EQ(RefusalOf(dir, "good.bmp"), "(read)");
  const cloudvis::Scene scene =
    cloudvis::SceneFromDocument(CloudWithMap("good.pgm"), "scene", dir.Path);
  ASSERT_NE(scene.Field.Description.Layer.Map, nullptr);
  EXPECT_EQ(scene.Field.Description.Layer.Map->Width, 5);
  EXPECT_EQ(scene.Field.Description.Layer.Map->Height, 5);
  EXPECT_EQ(scene.Field.Description.Layer.Map->Values[0], float(128.0 / 255.0));
}

// An integer map means n / (its type's maximum) in every container: an 8-bit .vti or NRRD map of
// 1 gave full coverage (ReadField had made it float 1.0) where the same bytes as a PNG gave
// 1/255, and one of 255 was refused as "outside [0, 1]". 16-bit maps alike, over 65535.
TEST(CloudScene, IntegerMapsAreDividedByTheirTypesMaximumInEveryContainer)
{
  TemporaryDirectory dir;
  struct Case
  {
    int Type;
    const char* Nrrd;
    double Maximum;
  };
  for (const Case& c :
    { Case{ VTK_UNSIGNED_CHAR, "uint8", 255.0 }, Case{ VTK_UNSIGNED_SHORT, "uint16", 65535.0 } })
  {
    for (const double value : { 1.0, c.Maximum / 3.0, c.Maximum })
    {
      vtkNew<vtkImageData> image;
      image->SetDimensions(4, 3, 1);
      image->AllocateScalars(c.Type, 1);
      for (vtkIdType i = 0; i < 12; ++i)
      {
        image->GetPointData()->GetScalars()->SetTuple1(i, value);
      }
      const std::string stem = std::string(c.Nrrd) + "_" + std::to_string(int(value));
      vtkNew<vtkPNGWriter> png;
      png->SetInputData(image);
      png->SetFileName(dir.File(stem + ".png").c_str());
      png->Write();
      vtkNew<vtkXMLImageDataWriter> vti;
      vti->SetInputData(image);
      vti->SetFileName(dir.File(stem + ".vti").c_str());
      vti->Write();
      std::string raw;
      for (int i = 0; i < 12; ++i)
      {
        const unsigned v = unsigned(value);
        raw += char(v & 0xff);
        if (c.Type == VTK_UNSIGNED_SHORT)
        {
          raw += char(v >> 8);
        }
      }
      WriteBytes(dir.File(stem + ".nrrd"),
        std::string("NRRD0004\ntype: ") + c.Nrrd +
          "\ndimension: 2\nsizes: 4 3\nendian: little\nencoding: raw\n\n" + raw);
      for (const char* extension : { ".png", ".vti", ".nrrd" })
      {
        const cloudvis::Scene scene =
          cloudvis::SceneFromDocument(CloudWithMap(stem + extension), "scene", dir.Path);
        const auto& map = scene.Field.Description.Layer.Map;
        ASSERT_NE(map, nullptr) << stem << extension;
        ASSERT_EQ(map->Values.size(), 12u) << stem << extension;
        for (float v : map->Values)
        {
          EXPECT_EQ(v, float(std::floor(value) / c.Maximum)) << stem << extension;
        }
      }
    }
  }
}

// ---- detail matched to the camera -----------------------------------------------------------

// The width a pixel at the image's centre spans at `distance`: distance * 2 tan(angle / 2) / H.
double CentralPixelAt(double distance, const cloudvis::CameraView& view)
{
  return distance * 2.0 * std::tan(0.5 * view.ViewAngle * M_PI / 180.0) / view.Height;
}

// A cube's face straight ahead: its nearest point is on the view's axis, and the voxels are the
// fewest no wider than the pixel there (a lattice with one voxel less along an axis would be).
TEST(CameraDetail, AFaceStraightAheadGetsVoxelsOfItsPixel)
{
  cloudvis::CameraView view;
  view.Position = { { 0.0, 0.0, 10.0 } };
  const std::array<double, 6> cube{ { -1, 1, -1, 1, -1, 1 } };
  const auto detail = cloudvis::ChooseCameraDetail(view, cube, cube, std::uint64_t(1) << 40);
  ASSERT_TRUE(detail);
  EXPECT_DOUBLE_EQ(detail->NearestCloud, 9.0);
  const double pixel = CentralPixelAt(9.0, view);
  // Off the axis the face is farther, and a pixel narrower across its ray (cos^2): the corner of
  // the face, 1.5 degrees further out, sees it 1% narrower.
  EXPECT_LE(detail->PixelFootprint, pixel);
  EXPECT_GT(detail->PixelFootprint, 0.98 * pixel);
  EXPECT_FALSE(detail->Capped);
  for (int a = 0; a < 3; ++a)
  {
    const int n = detail->Dimensions[size_t(a)];
    EXPECT_LE(2.0 / (n - 1), detail->PixelFootprint) << a;
    EXPECT_GT(2.0 / (n - 2), detail->PixelFootprint) << a;
  }
  EXPECT_DOUBLE_EQ(detail->Voxel, 2.0 / (detail->Dimensions[0] - 1));
}

// Under a cap the voxels grow together: the largest cubic lattice within it.
TEST(CameraDetail, TheCapGrowsTheVoxels)
{
  cloudvis::CameraView view;
  view.Position = { { 0.0, 0.0, 10.0 } };
  const std::array<double, 6> cube{ { -1, 1, -1, 1, -1, 1 } };
  const auto detail = cloudvis::ChooseCameraDetail(view, cube, cube, 1000);
  ASSERT_TRUE(detail);
  EXPECT_TRUE(detail->Capped);
  EXPECT_EQ(detail->Dimensions, (std::array<int, 3>{ { 10, 10, 10 } }));
  EXPECT_DOUBLE_EQ(detail->Voxel, 2.0 / 9.0);
  // A flat field keeps its shape: 2 voxels where it is thin, the rest shared out.
  const std::array<double, 6> slab{ { 0, 100, 0, 1e-3, 0, 100 } };
  const auto flat = cloudvis::ChooseCameraDetail(view, slab, slab, 200);
  ASSERT_TRUE(flat);
  EXPECT_EQ(flat->Dimensions, (std::array<int, 3>{ { 10, 2, 10 } }));
}

// A layer overhead, seen looking along the ground: the nearest cloud in view is where the top of
// the view meets the layer's underside, 10 / sin(15 degrees) away, not the point straight above,
// which the camera does not see.
TEST(CameraDetail, ALayerOverheadIsSeenAtTheTopOfTheView)
{
  cloudvis::CameraView view;
  view.Position = { { 0.0, 0.0, 0.0 } };
  view.FocalPoint = { { 0.0, 0.0, 1.0 } };
  const std::array<double, 6> layer{ { -100, 100, 10, 11, -100, 100 } };
  const std::array<double, 6> bounds{ { -100, 100, 0, 11, -100, 100 } };
  const auto detail = cloudvis::ChooseCameraDetail(view, layer, bounds, std::uint64_t(1) << 40);
  ASSERT_TRUE(detail);
  const double nearest = 10.0 / std::sin(15.0 * M_PI / 180.0);
  EXPECT_NEAR(detail->NearestCloud, nearest, 1e-12 * nearest);
  // Looking away from it, the camera sees none of it.
  view.FocalPoint = { { 0.0, -1.0, 1.0 } };
  EXPECT_FALSE(cloudvis::ChooseCameraDetail(view, layer, bounds, 1000));
}

// In a scene: the lattice comes from the camera and render.size, only the cloud model's layer
// counts as cloud, and the resolved scene writes the numbers, which generate the same field.
TEST(CloudScene, AutoDimensionsFollowTheCameraAndWriteBackAsNumbers)
{
  const json document = { { "field",
                            { { "dimensions", "auto" },
                              { "max_voxels", 1 << 30 },
                              { "bounds", { 0, 4, 0, 4, 0, 4 } },
                              { "density_model", "cloud" },
                              { "cloud", { { "base", 2 }, { "top", 3 } } } } },
    { "camera", { { "position", { 2, 0.5, 10 } }, { "focal_point", { 2, 2.5, 2 } } } },
    { "render", { { "size", { 64, 48 } } } } };
  const cloudvis::Scene scene = cloudvis::SceneFromDocument(document, "d", "");
  ASSERT_TRUE(scene.Field.AutoDimensions);
  const cloudvis::CameraDetail& detail = *scene.Field.AutoDimensions;
  EXPECT_EQ(scene.Field.Dimensions, detail.Dimensions);
  EXPECT_FALSE(detail.Capped);
  // The layer's face at z = 4 is 6 away straight ahead; the field's bottom, nearer, holds none.
  EXPECT_GT(detail.NearestCloud, 6.0);
  EXPECT_LT(detail.NearestCloud, 6.5);
  EXPECT_LE(detail.Voxel, detail.PixelFootprint);

  // Twice the pixels, about twice the voxels along each axis.
  json larger = document;
  larger["render"]["size"] = { 128, 96 };
  const cloudvis::Scene finer = cloudvis::SceneFromDocument(larger, "d", "");
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(
      double(finer.Field.Dimensions[size_t(a)] - 1) / (detail.Dimensions[size_t(a)] - 1), 2.0, 0.1)
      << a;
  }

  const double bounds[6] = { 0, 4, 0, 4, 0, 4 };
  const json written = cloudvis::SceneToJson(scene, cloudvis::ResolveCamera(scene, bounds));
  EXPECT_EQ(written["field"]["dimensions"], json(detail.Dimensions));
  const cloudvis::Scene again = cloudvis::SceneFromDocument(written, "d", "");
  EXPECT_FALSE(again.Field.AutoDimensions);
  EXPECT_EQ(again.Field.Dimensions, detail.Dimensions);
  const vtkSmartPointer<vtkImageData> field = cloudvis::ProduceField(scene);
  EXPECT_EQ(std::vector<int>(field->GetDimensions(), field->GetDimensions() + 3),
    std::vector<int>(detail.Dimensions.begin(), detail.Dimensions.end()));
}

} // namespace
