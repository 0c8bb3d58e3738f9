// The cloud model in scene files (issue 22): every field.cloud key and the new noise keys reach
// the field description and come back from the resolved scene unchanged, and a coverage map
// given as an image file (a PNG written here by VTK's own writer) is read and stretched over the
// field as vtkCloudDensitySource::SetCoverageMap does. The refusals (bad values naming their
// dotted key, a missing or 3-D map file) are command-line cases in CMakeLists.txt.
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

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <utility>

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
    { "anvil", 0.7 },
    { "shear", { 0.125, -0.25 } } };
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
    { "anvil", l.Anvil } };
  for (const auto& [key, value] : numbers)
  {
    EXPECT_EQ(value, keys[key].get<double>()) << key;
  }
  EXPECT_EQ(l.Shear[0], keys["shear"][0].get<double>());
  EXPECT_EQ(l.Shear[1], keys["shear"][1].get<double>());

  // The resolved scene writes the same keys back, and reads back to the same scene.
  const double bounds[6] = { -2, 2, -2, 2, -2, 2 };
  const json written = cloudvis::SceneToJson(scene, cloudvis::ResolveCamera(scene, bounds));
  EXPECT_EQ(written["field"]["cloud"], EveryCloudKey()) << written["field"].dump();
  EXPECT_EQ(written["field"]["noise"], "perlin_worley");
  EXPECT_EQ(written["field"]["noise_period"], 4);
  const cloudvis::Scene again = cloudvis::SceneFromDocument(written, "d", "");
  EXPECT_EQ(cloudvis::SceneToJson(again, cloudvis::ResolveCamera(again, bounds)), written);
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

} // namespace
