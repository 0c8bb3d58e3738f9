// The cloud model (CloudLayer.h) and the evaluator's fast row path for the new noises: the
// layer's altitude limits and density ceiling, the height profiles, a cumulus's flat base,
// coverage from nothing, from a procedural map and from an image, what an invalid layer is told,
// and that rows and pieces give the bits that point evaluation and the whole field give.
#include "CloudDensityEvaluator.h"
#include "CloudLayer.h"
#include "SourcePieces.h"
#include "vtkCloudDensitySource.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <string>
#include <tuple>
#include <vector>

using namespace cloudvis;

namespace
{
std::vector<float> Densities(vtkCloudDensitySource* source)
{
  source->Modified();
  source->Update();
  auto* array =
    vtkFloatArray::SafeDownCast(source->GetOutput()->GetPointData()->GetArray("density"));
  EXPECT_NE(array, nullptr);
  if (!array)
  {
    return {};
  }
  return std::vector<float>(
    array->GetPointer(0), array->GetPointer(0) + array->GetNumberOfValues());
}

using test::SameBits;

size_t CloudyVoxels(const std::vector<float>& density)
{
  return static_cast<size_t>(
    std::count_if(density.begin(), density.end(), [](float v) { return v > 0.0f; }));
}

// A cloud layer between `base` and `top`, with its coverage and the scales of its two noises.
CloudLayer Layer(double base, double top, double coverage, double shapeScale, double detailScale)
{
  CloudLayer layer;
  std::tie(layer.Base, layer.Top, layer.Coverage) = std::make_tuple(base, top, coverage);
  std::tie(layer.ShapeScale, layer.DetailScale) = std::make_tuple(shapeScale, detailScale);
  return layer;
}

// cumulus.json's cloud: four smoothly united spheres give the coverage of one cumulus.
FieldDescription Cumulus()
{
  FieldDescription field;
  field.Model = DensityModel::Cloud;
  const auto sphere = [](float x, float y, float z, float r)
  {
    Shape s;
    s.Center = glm::vec3(x, y, z);
    s.Radius = r;
    return s;
  };
  field.Shapes = { sphere(0.0f, -0.2f, 0.0f, 1.1f),
    sphere(0.75f, -0.35f, 0.3f, 0.75f),
    sphere(-0.8f, -0.4f, -0.2f, 0.7f),
    sphere(0.15f, 0.75f, 0.1f, 0.65f) };
  field.Blend = ShapeBlend::SmoothUnion;
  field.BlendRadius = 0.4;
  field.FalloffWidth = 0.5;
  field.Noise.Seed = 3;
  field.Layer = Layer(-0.8, 1.6, 1.0, 1.5, 1.0);
  field.Layer.Type = CloudType::Cumulus;
  field.Layer.Erosion = 0.7;
  return field;
}

// cumulus.json's spheres as a cumulonimbus's tower: an anvil streaming along +z from the
// footprint, an overshooting dome above the top, and a rain shaft below the base.
FieldDescription Tower()
{
  FieldDescription field = Cumulus();
  field.Layer.Type = CloudType::Cumulonimbus;
  field.Layer.Anvil = 1.0;
  field.Layer.AnvilDirection = { { 0.3, 1.0 } };
  field.Layer.AnvilReach = 1.5;
  field.Layer.Overshoot = 0.3;
  field.Layer.Rain = 0.05;
  field.Layer.Shear = { { 0.1, 0.0 } };
  return field;
}

// A cloudscape: a procedural weather map of many clouds, with curl, shear and wind at work.
FieldDescription Cloudscape()
{
  FieldDescription field;
  field.Model = DensityModel::Cloud;
  field.Noise.Seed = 7;
  field.Layer = Layer(-0.5, 1.0, 0.5, 1.5, 0.6);
  field.Layer.Source = CoverageSource::Noise;
  field.Layer.MapScale = 2.0;
  field.Layer.Curl = 0.5;
  field.Layer.Shear = { { 0.3, -0.2 } };
  return field;
}

// A 2-D map over x (first axis) and z (second): 0 where i < 8 of 16, else `full`.
vtkSmartPointer<vtkImageData> HalfMap(float full)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(16, 1, 16);
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfTuples(16 * 16);
  for (int k = 0; k < 16; ++k)
    for (int i = 0; i < 16; ++i)
      values->SetValue(k * 16 + i, i < 8 ? 0.0f : full);
  image->GetPointData()->SetScalars(values);
  return image;
}

// The error messages an object reports (vtkErrorMacro) while `action` runs.
template<typename Action>
std::string ErrorsOf(vtkObject* object, Action action)
{
  std::string errors;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* message)
    { *static_cast<std::string*>(client) += static_cast<const char*>(message); });
  const unsigned long tag = object->AddObserver(vtkCommand::ErrorEvent, onError);
  action();
  object->RemoveObserver(tag);
  return errors;
}
}

// ---- rows equal points -------------------------------------------------------------------

// The row path (which vtkCloudDensitySource runs) gives, bit for bit, Density() at each voxel,
// for each cellular noise, for tiled lattice noises and for the cloud model.
TEST(CloudRows, RowsOfTheNewNoisesAreBitIdenticalToPointEvaluation)
{
  std::vector<FieldDescription> fields;
  for (noise::NoiseType type : { noise::NoiseType::Worley,
         noise::NoiseType::InvertedWorley,
         noise::NoiseType::PerlinWorley,
         noise::NoiseType::Value,
         noise::NoiseType::Perlin })
  {
    for (DensityModel model : { DensityModel::SdfPlusFbm, DensityModel::FbmFalloff })
    {
      FieldDescription field;
      field.Model = model;
      field.Noise.Type = type;
      field.Noise.Octaves = 4;
      field.Shapes[0].Radius = 1.5f;
      const bool tiled = type == noise::NoiseType::Value || type == noise::NoiseType::Perlin;
      if (tiled)
      {
        field.Noise.Lacunarity = 3.0;
        field.Noise.LacunarityIncrement = 0.0;
        field.Noise.Period = 5;
      }
      fields.push_back(field);
    }
  }
  fields.push_back(Cumulus());
  fields.push_back(Cloudscape());
  fields.push_back(Tower());
  FieldDescription broken = Cloudscape();
  broken.Layer.Breakup = 0.3;
  fields.push_back(broken);
  FieldDescription anvil = Cloudscape();
  anvil.Layer.Type = CloudType::Cumulonimbus;
  anvil.Layer.Anvil = 0.8;
  fields.push_back(anvil);
  FieldDescription mapped = Cloudscape();
  std::string problem;
  auto map = std::make_shared<CoverageMap>(*CoverageMapOfImage(HalfMap(0.9f), problem));
  map->XMin = -2.0;
  map->XMax = 2.0;
  map->ZMin = -2.0;
  map->ZMax = 2.0;
  mapped.Layer.Source = CoverageSource::Map;
  mapped.Layer.Map = map;
  fields.push_back(mapped);

  for (size_t f = 0; f < fields.size(); ++f)
  {
    ASSERT_EQ(ValidateFieldDescription(fields[f]), "") << "field " << f;
    const DensityEvaluator evaluator(fields[f], 1.3);
    RowScratch scratch;
    std::vector<float> row(70);
    const double originX = -2.0, dx = 4.0 / 79.0;
    int cloudy = 0;
    for (double y : { -0.9, -0.45, 0.1, 0.35, 0.9, 1.5, 1.7 })
    {
      for (double z : { -0.7, 0.05, 0.6 })
      {
        evaluator.EvaluateRow(5, 70, originX, dx, y, z, row.data(), scratch);
        for (int i = 0; i < 70; ++i)
        {
          const float point = evaluator.Density(glm::dvec3(originX + (5 + i) * dx, y, z));
          ASSERT_EQ(std::memcmp(&row[i], &point, sizeof(float)), 0)
            << "field " << f << ", voxel " << i << " of the row at y " << y << ", z " << z
            << ": row " << row[i] << ", point " << point;
          cloudy += row[i] > 0.0f;
        }
      }
    }
    EXPECT_GT(cloudy, 20) << "field " << f << ": rows must cross cloud to compare anything";
  }
}

// ---- the layer -----------------------------------------------------------------------------

TEST(CloudLayer, HeightProfilesVanishOutsideTheLayerAndPeakAtOne)
{
  for (CloudType type : { CloudType::Stratus,
         CloudType::Stratocumulus,
         CloudType::Cumulus,
         CloudType::Cumulonimbus,
         CloudType::Altocumulus,
         CloudType::Congestus })
  {
    for (float h : { -1.0f, -1e-6f, 0.0f, 1.0f, 1.0f + 1e-6f, 2.0f })
    {
      EXPECT_EQ(HeightProfile(type, h), 0.0f) << "type " << int(type) << ", h " << h;
    }
    float peak = 0.0f;
    for (int i = 1; i < 1000; ++i)
    {
      const float p = HeightProfile(type, i / 1000.0f);
      ASSERT_GE(p, 0.0f);
      ASSERT_LE(p, 1.0f);
      peak = std::max(peak, p);
    }
    EXPECT_EQ(peak, 1.0f) << "type " << int(type);
  }
  // The types differ where they should: a cumulonimbus still holds its width at 0.85 of the
  // layer, where a cumulus has thinned and a stratus is nearly gone.
  EXPECT_EQ(HeightProfile(CloudType::Cumulonimbus, 0.85f), 1.0f);
  EXPECT_LT(HeightProfile(CloudType::Cumulus, 0.85f), 0.3f);
  EXPECT_LT(HeightProfile(CloudType::Stratus, 0.9f), HeightProfile(CloudType::Stratus, 0.3f));
  // A congestus holds its width higher than a cumulus, and an altocumulus's cloudlets are rounded
  // below as well as above.
  EXPECT_EQ(HeightProfile(CloudType::Congestus, 0.65f), 1.0f);
  EXPECT_LT(HeightProfile(CloudType::Cumulus, 0.65f), 0.9f);
  EXPECT_LT(HeightProfile(CloudType::Altocumulus, 0.1f), 0.5f);
}

// Density is exactly 0 below the base and above the top (voxels that lie on them to rounding
// are left out), and never above density_scale, for
// every cloud type at full coverage without erosion.
TEST(CloudLayer, DensityIsZeroOutsideTheLayerAndNeverAboveTheScale)
{
  for (CloudType type : { CloudType::Stratus,
         CloudType::Stratocumulus,
         CloudType::Cumulus,
         CloudType::Cumulonimbus,
         CloudType::Altocumulus,
         CloudType::Congestus })
  {
    FieldDescription field = Cloudscape();
    field.Layer.Type = type;
    field.Layer.Coverage = 1.0;
    field.Layer.Erosion = 0.0; // nothing eaten away: the most cloud the layer can hold
    field.Layer.Anvil = 1.0;
    field.DensityScale = 2.5;
    vtkNew<vtkCloudDensitySource> source;
    source->SetField(field);
    source->SetBounds(-2.0, 2.0, -1.0, 1.5, -2.0, 2.0);
    source->SetDimensions(40, 51, 40); // y spacing 0.05: base and top fall on voxels
    const std::vector<float> density = Densities(source);
    float largest = 0.0f;
    for (int k = 0; k < 40; ++k)
      for (int j = 0; j < 51; ++j)
        for (int i = 0; i < 40; ++i)
        {
          const float d = density[(k * 51 + j) * 40 + i];
          const double y = -1.0 + j * 0.05;
          if (y < field.Layer.Base - 1e-6 || y > field.Layer.Top + 1e-6)
          {
            ASSERT_EQ(d, 0.0f) << "type " << int(type) << ", y " << y;
          }
          ASSERT_GE(d, 0.0f);
          ASSERT_LE(d, 2.5f) << "type " << int(type);
          largest = std::max(largest, d);
        }
    EXPECT_GT(largest, 1.25f) << "type " << int(type) << ": the cloud must reach its scale";
  }
}

// A cumulus has a flat base: under the cloud's footprint at its base (where the shapes give it
// at least half its coverage), the lowest cloudy voxel of every column lies within two voxels of
// the lowest in the whole cloud, which sits on the layer's base. (Outside the footprint the
// rounded sides overhang and start higher, as a cumulus's do.)
TEST(CloudLayer, ACumulusHasAFlatBase)
{
  const FieldDescription field = Cumulus();
  const DensityEvaluator evaluator(field, 0.0);
  vtkNew<vtkCloudDensitySource> source;
  source->SetField(field);
  source->SetBounds(-2.0, 2.0, -1.0, 2.0, -2.0, 2.0);
  const int nx = 64, ny = 73, nz = 64; // y spacing 1/24 world units
  source->SetDimensions(nx, ny, nz);
  const std::vector<float> density = Densities(source);
  std::vector<int> lowest;
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i)
    {
      const glm::vec3 atBase(-2.0 + i * 4.0 / 63.0, field.Layer.Base, -2.0 + k * 4.0 / 63.0);
      if (evaluator.SignedDistance(atBase) > -0.5 * field.FalloffWidth)
      {
        continue;
      }
      int j = 0;
      while (j < ny && density[(size_t(k) * ny + j) * nx + i] == 0.0f)
      {
        ++j;
      }
      lowest.push_back(j);
    }
  ASSERT_GT(lowest.size(), 300u) << "the cumulus's footprint must cover many columns";
  const int base = *std::min_element(lowest.begin(), lowest.end());
  const double baseY = -1.0 + base * (3.0 / 72.0);
  EXPECT_GE(baseY, field.Layer.Base) << "cloud below the layer's base";
  EXPECT_LT(baseY, field.Layer.Base + 3 * 3.0 / 72.0) << "the lowest cloud must sit on the base";
  const size_t flat = static_cast<size_t>(
    std::count_if(lowest.begin(), lowest.end(), [base](int j) { return j <= base + 2; }));
  EXPECT_EQ(flat, lowest.size()) << flat << " of " << lowest.size()
                                 << " columns under the footprint start within two voxels of "
                                    "the lowest cloud";
}

// Coverage 0 leaves the field empty, whatever the coverage comes from.
TEST(CloudLayer, CoverageZeroGivesAnEmptyField)
{
  for (CoverageSource from : { CoverageSource::Shapes, CoverageSource::Noise, CoverageSource::Map })
  {
    vtkNew<vtkCloudDensitySource> source;
    FieldDescription field = from == CoverageSource::Shapes ? Cumulus() : Cloudscape();
    source->SetField(field);
    if (from == CoverageSource::Map)
    {
      source->SetCoverageMap(HalfMap(1.0f));
    }
    source->SetBounds(-2.0, 2.0, -1.0, 2.0, -2.0, 2.0);
    source->SetDimensions(32, 32, 32);
    ASSERT_GT(CloudyVoxels(Densities(source)), 100u) << "source " << int(from);
    source->SetCloudCoverage(0.0);
    EXPECT_EQ(CloudyVoxels(Densities(source)), 0u) << "source " << int(from);
  }
}

// A map half 0, half 1 (as a float image and as an 8-bit one, 255 meaning 1) leaves the 0 half
// empty and fills the other.
TEST(CloudLayer, ACoverageMapLeavesItsEmptyHalfEmpty)
{
  vtkSmartPointer<vtkImageData> bytes = vtkSmartPointer<vtkImageData>::New();
  bytes->SetDimensions(16, 16, 1);
  vtkNew<vtkUnsignedCharArray> values;
  values->SetNumberOfTuples(256);
  for (int k = 0; k < 16; ++k)
    for (int i = 0; i < 16; ++i)
      values->SetValue(k * 16 + i, i < 8 ? 0 : 255);
  bytes->GetPointData()->SetScalars(values);

  const vtkSmartPointer<vtkImageData> floats = HalfMap(1.0f);
  for (vtkImageData* map : { floats.Get(), bytes.Get() })
  {
    vtkNew<vtkCloudDensitySource> source;
    source->SetField(Cloudscape());
    source->SetCloudShear(0.0, 0.0); // the map's halves stay put at every height
    source->SetCloudCoverage(1.0);
    source->SetCoverageMap(map);
    EXPECT_EQ(source->GetCoverageSource(), vtkCloudDensitySource::MapCoverage);
    source->SetBounds(-2.0, 2.0, -1.0, 1.5, -2.0, 2.0);
    const int nx = 61, ny = 26, nz = 30;
    source->SetDimensions(nx, ny, nz);
    source->SetWind(0.0, 0.0, 0.0);
    const std::vector<float> density = Densities(source);
    // The map's point 7 (the last 0) lies at x = -2 + 7/15 * 4; voxel i at x = -2 + i/15.
    size_t inEmptyHalf = 0, inFullHalf = 0;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
        {
          const bool cloudy = density[(size_t(k) * ny + j) * nx + i] > 0.0f;
          (i <= 28 ? inEmptyHalf : inFullHalf) += cloudy;
        }
    EXPECT_EQ(inEmptyHalf, 0u);
    EXPECT_GT(inFullHalf, 1000u);
  }
}

// Each kind of invalid layer is refused, in words that say what is wrong, before any voxel is
// made: base at or above top, values outside [0, 1], a map outside [0, 1], a 3-D map, no map.
TEST(CloudLayer, AnInvalidLayerIsRefusedWithWords)
{
  const auto problemOf = [](void (*change)(CloudLayer&))
  {
    FieldDescription field = Cloudscape();
    change(field.Layer);
    return ValidateFieldDescription(field);
  };
  EXPECT_NE(problemOf([](CloudLayer& l) { l.Top = l.Base; })
              .find("the cloud base (-0.5) must lie below the top (-0.5)"),
    std::string::npos);
  EXPECT_NE(problemOf([](CloudLayer& l) { l.Base = 2.0; }).find("must lie below the top (1)"),
    std::string::npos);
  EXPECT_NE(problemOf([](CloudLayer& l) { l.Coverage = 1.01; })
              .find("cloud coverage must be in [0, 1], got 1.01"),
    std::string::npos);
  EXPECT_NE(problemOf([](CloudLayer& l) { l.Coverage = -0.1; })
              .find("cloud coverage must be in [0, 1], got -0.1"),
    std::string::npos);
  EXPECT_NE(problemOf([](CloudLayer& l) { l.Erosion = 2.0; })
              .find("cloud erosion must be in [0, 1], got 2"),
    std::string::npos);
  EXPECT_NE(problemOf([](CloudLayer& l) { l.Breakup = -0.5; })
              .find("cloud breakup must be in [0, 1], got -0.5"),
    std::string::npos);
  EXPECT_NE(problemOf(
              [](CloudLayer& l) {
                l.AnvilDirection = { { 0.0, 0.0 } };
              })
              .find("cloud anvil direction must not be [0, 0]"),
    std::string::npos);
  EXPECT_NE(problemOf(
              [](CloudLayer& l) {
                l.AnvilDirection = { { NAN, 1.0 } };
              })
              .find("cloud anvil direction x must be a finite number"),
    std::string::npos);
  EXPECT_NE(problemOf([](CloudLayer& l) { l.AnvilReach = INFINITY; })
              .find("cloud anvil reach must be a finite number >= 0, got inf"),
    std::string::npos);
  EXPECT_NE(problemOf([](CloudLayer& l) { l.Overshoot = -1.0; })
              .find("cloud overshoot must be a finite number >= 0, got -1"),
    std::string::npos);
  // A dome and a streaming anvil stand on a tower: not over a weather map.
  EXPECT_NE(problemOf(
              [](CloudLayer& l)
              {
                l.Type = CloudType::Cumulonimbus;
                l.AnvilReach = 1.0;
              })
              .find("cloud anvil reach needs a tower to stand on"),
    std::string::npos);
  EXPECT_NE(
    problemOf([](CloudLayer& l) { l.Rain = 2.0; }).find("cloud rain must be in [0, 1], got 2"),
    std::string::npos);
  EXPECT_NE(problemOf(
              [](CloudLayer& l)
              {
                l.Type = CloudType::Cumulonimbus;
                l.Rain = 0.1;
              })
              .find("cloud rain needs a tower to stand on"),
    std::string::npos);
  EXPECT_NE(problemOf([](CloudLayer& l) { l.Anvil = 1.5; }).find("cloud anvil must be in [0, 1]"),
    std::string::npos);
  EXPECT_NE(problemOf([](CloudLayer& l) { l.DetailScale = 0.0; })
              .find("cloud detail scale must be a positive number, got 0"),
    std::string::npos);
  EXPECT_NE(problemOf([](CloudLayer& l) { l.Source = CoverageSource::Map; })
              .find("the coverage comes from a map, but no map is set"),
    std::string::npos);
  EXPECT_NE(problemOf(
              [](CloudLayer& l)
              {
                auto map = std::make_shared<CoverageMap>();
                map->Width = map->Height = 2;
                map->Values = { 0.0f, 0.5f, 1.5f, 1.0f };
                l.Source = CoverageSource::Map;
                l.Map = map;
              })
              .find("coverage map value 1.5 at point 2 is outside [0, 1]"),
    std::string::npos);

  // Images: a value outside [0, 1] (or NaN) and a 3-D image are refused, naming the problem.
  std::string problem;
  vtkSmartPointer<vtkImageData> over = HalfMap(1.5f);
  EXPECT_EQ(CoverageMapOfImage(over, problem), nullptr);
  EXPECT_NE(problem.find("coverage map value 1.5"), std::string::npos) << problem;
  EXPECT_NE(problem.find("is outside [0, 1]"), std::string::npos) << problem;
  vtkSmartPointer<vtkImageData> nan = HalfMap(std::nanf(""));
  EXPECT_EQ(CoverageMapOfImage(nan, problem), nullptr);
  vtkNew<vtkImageData> cube;
  cube->SetDimensions(4, 4, 4);
  cube->AllocateScalars(VTK_FLOAT, 1);
  EXPECT_EQ(CoverageMapOfImage(cube, problem), nullptr);
  EXPECT_NE(
    problem.find("a coverage map must be a 2-D image, got 4 x 4 x 4 points"), std::string::npos)
    << problem;

  // The source says so and keeps what it had.
  vtkNew<vtkCloudDensitySource> source;
  source->SetField(Cloudscape());
  EXPECT_NE(ErrorsOf(source, [&] { source->SetCoverageMap(cube); })
              .find("coverage map: a coverage map must be a 2-D image"),
    std::string::npos);
  EXPECT_NE(ErrorsOf(source, [&] { source->SetCoverageMap(over); }).find("outside [0, 1]"),
    std::string::npos);
  EXPECT_EQ(source->GetCoverageSource(), vtkCloudDensitySource::NoiseCoverage);
  EXPECT_EQ(source->Validate(), "");

  // A layer refused at generation: an error with the reason, and no voxels.
  source->SetCloudAltitudes(1.0, 0.5);
  EXPECT_NE(source->Validate().find("must lie below the top"), std::string::npos);
  source->SetDimensions(8, 8, 8);
  const std::string errors = ErrorsOf(source, [&] { source->Update(); });
  EXPECT_NE(errors.find("the cloud base (1) must lie below the top (0.5)"), std::string::npos)
    << errors;
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 0);
}

// The layer's noises are read on 32-bit lattices too (the baked volumes' texels, the weather
// map's octaves): a field whose coordinates, divided by the noise scales, leave them is refused
// rather than generated from overflowed cells (a 10,000 km field with millimetre noise). The fBm
// parameters, which the cloud model does not use, do not refuse a large cloudscape.
TEST(CloudLayer, CoordinatesBeyondTheNoiseLatticesAreRefusedAndOnlyThem)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetField(Cloudscape());
  source->SetDimensions(8, 8, 8);
  source->SetBounds(0.0, 1e7, -1.0, 1.0, 0.0, 1e7);
  source->SetCloudNoiseScales(1e-3, 1e-3);
  EXPECT_NE(source->Validate().find("2^30"), std::string::npos) << source->Validate();
  source->SetCloudNoiseScales(1.5, 1e-3);
  EXPECT_NE(source->Validate().find("2^30"), std::string::npos) << "the detail's lattice";
  source->SetCloudNoiseScales(1e-3, 0.6);
  EXPECT_NE(source->Validate().find("2^30"), std::string::npos) << "the shape's lattice";
  source->SetCloudNoiseScales(1e4, 1e4);
  source->SetWeatherMap(1e-3, 6, 0.6);
  EXPECT_NE(source->Validate().find("2^30"), std::string::npos) << "the weather map's lattice";
  source->SetWeatherMap(1e5, 6, 0.6);
  EXPECT_EQ(source->Validate(), "");

  // A cloudscape 400,000 km wide with kilometre noise fits its lattices; the default fBm (whose
  // highest octave, 83 cycles per unit, would not) plays no part in the cloud model.
  source->SetBounds(0.0, 4e8, -1.0, 1.0, 0.0, 4e8);
  EXPECT_EQ(source->Validate(), "");
  source->SetDensityModelToSdfPlusFbm();
  EXPECT_NE(source->Validate().find("2^30"), std::string::npos);
}

// A cloudscape generated in pieces (sub-extents, as MPI ranks and streaming request them) is the
// whole field, bit for bit: the baked noises and the weather map depend on nothing but the seed.
TEST(CloudLayer, PiecesEqualTheWhole)
{
  FieldDescription broken = Cloudscape();
  broken.Layer.Breakup = 0.15;
  broken.Layer.Coverage = 0.8;
  const FieldDescription fields[] = { Cloudscape(), Cumulus(), Tower(), broken };
  for (size_t from = 0; from < std::size(fields); ++from)
  {
    vtkNew<vtkCloudDensitySource> source;
    const FieldDescription& field = fields[from];
    source->SetField(field);
    source->SetTime(0.7);
    source->SetBounds(-2.0, 2.0, -1.0, 2.0, -2.0, 2.0);
    source->SetDimensions(test::PieceTestDimensions);
    const std::vector<float> whole = Densities(source);
    ASSERT_GT(CloudyVoxels(whole), 1000u) << "field " << from;
    EXPECT_TRUE(SameBits(whole, test::FieldFromOctants(source))) << "field " << from;
  }
}
