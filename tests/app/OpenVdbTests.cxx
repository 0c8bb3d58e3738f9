// OpenVDB files made here with OpenVDB's own C++ API, read by cloudvis (ReadField), and the .vdb
// files cloudvis writes, read back with OpenVDB's API: values voxel for voxel, the transform as
// the field's geometry (rotated and scaled lattices included, frustums and shears refused), the
// default grid, the size cap, non-finite values and truncated files. The test that includes
// OpenVDB's headers, as OpenVdbFiles.cxx is the one file of the application that does.
#include "FieldTestFiles.h"

#include "SceneField.h"
#include "SupportRun.h"

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{

using cloudvis::FieldReadOptions;
using cloudvis::FieldReport;
using namespace cloudvis::support;
using namespace cloudvis::test;

// The value of active voxel (i, j, k) in the test grids.
float Known(int i, int j, int k)
{
  return float(1 + i + 10 * j + 100 * k);
}

// A fog volume: voxels of the box [min, max] active with Known(), except (min + 1) left inactive,
// so the dense copy must give it the background.
openvdb::FloatGrid::Ptr KnownGrid(const std::string& name,
  const openvdb::Coord& min,
  const openvdb::Coord& max,
  float background = 0.0f)
{
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(background);
  grid->setName(name);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  auto accessor = grid->getAccessor();
  for (int k = min.z(); k <= max.z(); ++k)
    for (int j = min.y(); j <= max.y(); ++j)
      for (int i = min.x(); i <= max.x(); ++i)
      {
        if (openvdb::Coord(i, j, k) != min.offsetBy(1))
        {
          accessor.setValue(openvdb::Coord(i, j, k), Known(i, j, k));
        }
      }
  return grid;
}

// How far apart (largest coordinate difference) the field's point (i, j, k) and the grid's voxel
// (i, j, k) are in world space.
double PositionError(vtkImageData* field, const openvdb::GridBase& grid, int i, int j, int k)
{
  double world[3];
  field->TransformIndexToPhysicalPoint(i, j, k, world);
  const openvdb::Vec3d vdb = grid.indexToWorld(openvdb::Coord(i, j, k));
  return std::max({ std::fabs(world[0] - vdb.x()),
    std::fabs(world[1] - vdb.y()),
    std::fabs(world[2] - vdb.z()) });
}

void Write(const std::string& path, const openvdb::GridPtrVec& grids)
{
  openvdb::io::File file(path);
  file.write(grids);
  file.close();
}

class OpenVdb : public ::testing::Test
{
protected:
  static void SetUpTestSuite() { openvdb::initialize(); }
  TemporaryDirectory Directory;
};

TEST_F(OpenVdb, ReadsAFloatGridVoxelForVoxelOverItsActiveBox)
{
  const openvdb::Coord min(-2, 3, 5), max(6, 7, 8);
  openvdb::FloatGrid::Ptr grid = KnownGrid("density", min, max, 0.25f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
  grid->transform().postTranslate(openvdb::Vec3d(1.0, 2.0, 3.0));
  const std::string path = Directory.File("known.vdb");
  Write(path, { grid });

  FieldReport report;
  const auto field = cloudvis::ReadField(path, {}, &report);
  int extent[6];
  field->GetExtent(extent);
  EXPECT_EQ(std::vector<int>(extent, extent + 6), (std::vector<int>{ -2, 6, 3, 7, 5, 8 }));
  int wrong = 0;
  for (int k = min.z(); k <= max.z(); ++k)
    for (int j = min.y(); j <= max.y(); ++j)
      for (int i = min.x(); i <= max.x(); ++i)
      {
        const float expected = openvdb::Coord(i, j, k) == min.offsetBy(1) ? 0.25f : Known(i, j, k);
        wrong += Density(field, i, j, k) == expected ? 0 : 1;
        // The image point and the VDB voxel are at the same world position.
        wrong += PositionError(field, *grid, i, j, k) < 1e-12 ? 0 : 1;
      }
  EXPECT_EQ(wrong, 0) << "voxels whose value or position differ from the grid's";
  EXPECT_EQ(report.Format, "OpenVDB");
  EXPECT_EQ(Detail(report, "grid")
              .find("\"density\" (float, fog volume, " + std::to_string(grid->activeVoxelCount()) +
                " active voxels, background 0.25)"),
    0u);
  EXPECT_EQ(Detail(report, "transform"), "UniformScaleTranslateMap, voxel size 0.5 x 0.5 x 0.5");
}

TEST_F(OpenVdb, TheDefaultGridIsDensityElseTheFirstFloatGrid)
{
  const openvdb::Coord min(0, 0, 0), max(3, 2, 1);
  openvdb::FloatGrid::Ptr temperature = KnownGrid("temperature", min, max);
  openvdb::FloatGrid::Ptr density = KnownGrid("density", min, max);
  density->tree().setValue(openvdb::Coord(0, 0, 0), 42.0f);
  openvdb::Vec3SGrid::Ptr velocity = openvdb::Vec3SGrid::create();
  velocity->setName("vel");
  velocity->tree().setValue(openvdb::Coord(0, 0, 0), openvdb::Vec3s(1, 0, 0));
  const std::string both = Directory.File("both.vdb");
  Write(both, { velocity, temperature, density });
  FieldReport report;
  EXPECT_EQ(Density(cloudvis::ReadField(both, {}, &report), 0, 0, 0), 42.0);
  EXPECT_NE(Detail(report, "grid")
              .find("other grids (field.array): \"vel\" (vec3s), "
                    "\"temperature\" (float)"),
    std::string::npos);
  FieldReadOptions named;
  named.Array = "temperature";
  EXPECT_EQ(Density(cloudvis::ReadField(both, named), 0, 0, 0), Known(0, 0, 0));
  named.Array = "vel";
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(both, named); })
              .find("grid \"vel\" holds vec3s values; a density field is a float grid"),
    std::string::npos);
  named.Array = "smoke";
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(both, named); })
              .find("no grid named \"smoke\" (field.array); the file's grids: \"vel\" (vec3s), "
                    "\"temperature\" (float), \"density\" (float)"),
    std::string::npos);
  const std::string noDensity = Directory.File("temperature.vdb");
  Write(noDensity, { velocity, temperature });
  EXPECT_EQ(Density(cloudvis::ReadField(noDensity), 0, 0, 0), Known(0, 0, 0));
  const std::string vectorsOnly = Directory.File("vectors.vdb");
  Write(vectorsOnly, { velocity });
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(vectorsOnly); })
              .find("no float grid to read as a density; the file's grids: \"vel\" (vec3s)"),
    std::string::npos);
}

// A rotated, anisotropically scaled lattice: the affine map becomes origin, spacing and direction,
// and every voxel keeps its world position.
TEST_F(OpenVdb, ARotatedAffineTransformBecomesTheFieldsDirection)
{
  openvdb::FloatGrid::Ptr grid =
    KnownGrid("density", openvdb::Coord(0, 0, 0), openvdb::Coord(4, 3, 2));
  openvdb::math::Mat4d matrix = openvdb::math::Mat4d::identity();
  matrix.preScale(openvdb::Vec3d(0.5, 1.0, 2.0));
  matrix.postRotate(openvdb::math::Z_AXIS, M_PI / 6.0);
  matrix.postTranslate(openvdb::Vec3d(-1.0, 4.0, 0.5));
  grid->setTransform(openvdb::math::Transform::createLinearTransform(matrix));
  const std::string path = Directory.File("rotated.vdb");
  Write(path, { grid });
  const auto field = cloudvis::ReadField(path);
  EXPECT_NEAR(field->GetSpacing()[0], 0.5, 1e-12);
  EXPECT_NEAR(field->GetSpacing()[1], 1.0, 1e-12);
  EXPECT_NEAR(field->GetSpacing()[2], 2.0, 1e-12);
  EXPECT_NEAR(field->GetDirectionMatrix()->GetElement(0, 0), std::cos(M_PI / 6.0), 1e-12);
  EXPECT_NEAR(field->GetDirectionMatrix()->GetElement(1, 0), std::sin(M_PI / 6.0), 1e-12);
  double largest = 0.0;
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j <= 3; ++j)
      for (int i = 0; i <= 4; ++i)
      {
        largest = std::max(largest, PositionError(field, *grid, i, j, k));
      }
  EXPECT_LT(largest, 1e-12);
}

TEST_F(OpenVdb, FrustumAndShearedTransformsAreRefused)
{
  openvdb::FloatGrid::Ptr grid =
    KnownGrid("density", openvdb::Coord(0, 0, 0), openvdb::Coord(4, 3, 2));
  grid->setTransform(openvdb::math::Transform::createFrustumTransform(
    openvdb::BBoxd(openvdb::Vec3d(0, 0, 0), openvdb::Vec3d(10, 10, 10)), 0.5, 2.0, 1.0));
  Write(Directory.File("frustum.vdb"), { grid });
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(Directory.File("frustum.vdb")); })
              .find("the grid's transform is a NonlinearFrustumMap, which is not linear (a "
                    "frustum): image data cannot represent it"),
    std::string::npos);
  openvdb::math::Mat4d shear = openvdb::math::Mat4d::identity();
  shear(1, 0) = 0.5; // index axis j leans along x
  grid->setTransform(openvdb::math::Transform::createLinearTransform(shear));
  Write(Directory.File("shear.vdb"), { grid });
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(Directory.File("shear.vdb")); })
              .find("the image's direction matrix is not a rotation: its axes must be "
                    "perpendicular unit vectors (axes 0 and 1 have a dot product of "),
    std::string::npos);
}

// Two voxels 4096 apart make a box of 4097^3: refused with the size, before the box is
// allocated (68 billion floats would end the test).
TEST_F(OpenVdb, AGridBeyondTheCapIsRefusedWithTheSizeItNeeds)
{
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
  grid->tree().setValue(openvdb::Coord(4096, 4096, 4096), 1.0f);
  Write(Directory.File("wide.vdb"), { grid });
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(Directory.File("wide.vdb")); })
              .find("a field of 4097 x 4097 x 4097 voxels (6.87698e+10 voxels, 256 GiB as float) "
                    "is more than field.max_voxels allows (1073741824)"),
    std::string::npos);
  FieldReadOptions small;
  small.MaximumVoxels = 100;
  Write(Directory.File("box.vdb"),
    { KnownGrid("density", openvdb::Coord(0, 0, 0), openvdb::Coord(4, 4, 4)) });
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(Directory.File("box.vdb"), small); })
              .find("a field of 5 x 5 x 5 voxels (125 voxels, 500 bytes as float) is more than "
                    "field.max_voxels allows (100)"),
    std::string::npos);
}

TEST_F(OpenVdb, NonFiniteValuesAndTruncatedFilesAreRefused)
{
  openvdb::FloatGrid::Ptr grid =
    KnownGrid("density", openvdb::Coord(0, 0, 0), openvdb::Coord(7, 7, 7));
  grid->tree().setValue(openvdb::Coord(1, 2, 3), std::numeric_limits<float>::quiet_NaN());
  grid->tree().setValue(openvdb::Coord(3, 2, 1), std::numeric_limits<float>::infinity());
  const std::string path = Directory.File("nan.vdb");
  Write(path, { grid });
  EXPECT_NE(ErrorOf([&] { cloudvis::ReadField(path); })
              .find("point array \"density\" holds 2 values that are NaN or infinite"),
    std::string::npos);
  // Cut anywhere in the grid's data: refused as truncated, every time (OpenVDB's file reader
  // read on with stale buffers: another outcome at each read, or wrong values).
  const std::string complete = Directory.File("cloud.vdb");
  cloudvis::WriteField(
    cloudvis::ProduceField(cloudvis::LoadScene("", { "field.dimensions=24" })), complete);
  const std::string bytes = ReadText(complete);
  for (const std::size_t keep : { bytes.size() / 4, bytes.size() / 2, bytes.size() - 10 })
  {
    WriteText(Directory.File("cut.vdb"), bytes.substr(0, keep));
    for (int attempt = 0; attempt < 3; ++attempt)
    {
      EXPECT_EQ(ErrorOf([&] { cloudvis::ReadField(Directory.File("cut.vdb")); }),
        Directory.File("cut.vdb") +
          ": cannot read OpenVDB: the file ends before its grids do: it is truncated")
        << "cut to " << keep << " of " << bytes.size() << " bytes";
    }
  }
  WriteText(Directory.File("text.vdb"), "not a grid");
  EXPECT_NE(
    ErrorOf([&] { cloudvis::ReadField(Directory.File("text.vdb")); }).find("not an OpenVDB file"),
    std::string::npos);
}

// ---- the writer -------------------------------------------------------------------------------

// The file cloudvis writes, read with OpenVDB's own API: a fog volume "density", background 0,
// only the non-zero voxels stored, each equal to the field's value at the same world position.
void ExpectGridHoldsField(const std::string& path, vtkImageData* field)
{
  openvdb::io::File file(path);
  file.open();
  const openvdb::MetaMap::Ptr metadata = file.getMetadata();
  openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  ASSERT_EQ(grids->size(), 1u);
  openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>((*grids)[0]);
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->getName(), "density");
  EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(grid->background(), 0.0f);
  EXPECT_EQ(grid->getCreator().rfind("cloudvis ", 0), 0u);
  EXPECT_EQ(metadata->metaValue<std::string>("creator"), grid->getCreator());
  EXPECT_NE(
    metadata->metaValue<std::string>("cloudvis_scene").find("\"field\""), std::string::npos);

  vtkDataArray* values = field->GetPointData()->GetScalars();
  int extent[6];
  field->GetExtent(extent);
  openvdb::Index64 nonZero = 0;
  int wrong = 0;
  const auto accessor = grid->getConstAccessor();
  for (int k = extent[4]; k <= extent[5]; ++k)
    for (int j = extent[2]; j <= extent[3]; ++j)
      for (int i = extent[0]; i <= extent[1]; ++i)
      {
        int ijk[3] = { i, j, k };
        const float value = float(values->GetComponent(field->ComputePointId(ijk), 0));
        nonZero += value != 0.0f ? 1 : 0;
        wrong += accessor.getValue(openvdb::Coord(i, j, k)) == value ? 0 : 1;
        wrong += accessor.isValueOn(openvdb::Coord(i, j, k)) == (value != 0.0f) ? 0 : 1;
        wrong += PositionError(field, *grid, i, j, k) < 1e-9 ? 0 : 1;
      }
  EXPECT_EQ(wrong, 0) << "voxels whose value, state or position differ";
  EXPECT_EQ(grid->activeVoxelCount(), nonZero) << "only the non-zero voxels are stored";
  EXPECT_LT(nonZero, openvdb::Index64(field->GetNumberOfPoints()))
    << "the test field has empty space";
}

// A level set (signed distances, negative inside) was read as a density and drawn as a solid
// block. It is converted to the fog volume Houdini and Blender make of it: a sphere of radius R
// becomes density 1 inside, 0 outside, and (R - distance) / w between, w the inner half of the
// narrow band (3 voxels here).
TEST_F(OpenVdb, ALevelSetIsConvertedToAFogVolume)
{
  const float radius = 6.0f, voxel = 0.5f, halfWidth = 3.0f;
  const openvdb::Vec3f centre(0.5f, 0.25f, -1.0f);
  openvdb::FloatGrid::Ptr sphere =
    openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(radius, centre, voxel, halfWidth);
  sphere->setName("surface");
  const std::string path = Directory.File("sphere.vdb");
  Write(path, { sphere });

  FieldReport report;
  const auto field = cloudvis::ReadField(path, {}, &report);
  int extent[6];
  field->GetExtent(extent);
  const double ramp = halfWidth * voxel;
  int inside = 0, ramped = 0, wrong = 0, uncovered = 0;
  for (int k = -20; k <= 20; ++k)
    for (int j = -20; j <= 20; ++j)
      for (int i = -20; i <= 20; ++i)
      {
        const openvdb::Vec3d p = sphere->indexToWorld(openvdb::Coord(i, j, k));
        const double distance = (p - openvdb::Vec3d(centre)).length();
        const double expected = std::clamp((radius - distance) / ramp, 0.0, 1.0);
        const bool covered = i >= extent[0] && i <= extent[1] && j >= extent[2] && j <= extent[3] &&
          k >= extent[4] && k <= extent[5];
        if (!covered)
        {
          uncovered += expected > 0.0 ? 1 : 0; // density outside the field's box
          continue;
        }
        wrong += std::fabs(Density(field, i, j, k) - expected) < 1e-5 ? 0 : 1;
        inside += expected == 1.0 ? 1 : 0;
        ramped += expected > 0.0 && expected < 1.0 ? 1 : 0;
      }
  EXPECT_EQ(wrong, 0) << "voxels whose density differs from the converted sphere's";
  EXPECT_EQ(uncovered, 0) << "voxels of the sphere outside the field";
  EXPECT_GT(inside, 1000);
  EXPECT_GT(ramped, 1000);
  EXPECT_EQ(Detail(report, "grid").find("\"surface\" (float, level set, "), 0u);
  EXPECT_EQ(Detail(report, "converted"),
    "level set converted to a fog volume (OpenVDB's sdfToFogVolume): density 0 outside the "
    "surface, rising linearly to 1 over the inner half of the narrow band (at most 1.5 world "
    "units deep, the grid's background; less where the stored interior is thinner), 1 inside");
}

TEST_F(OpenVdb, GeneratedFieldsAreWrittenAsSparseFogVolumes)
{
  const cloudvis::Scene scene = cloudvis::LoadScene("", { "field.dimensions=24,20,16" });
  const auto field = cloudvis::ProduceField(scene);
  const std::string path = Directory.File("cloud.vdb");
  cloudvis::WriteField(field, path, { "{\"field\": {}}" });
  ExpectGridHoldsField(path, field);
  // And cloudvis reads its own file back: the active box, voxel for voxel.
  const auto read = cloudvis::ReadField(path);
  int extent[6];
  read->GetExtent(extent);
  int wrong = 0;
  for (int k = extent[4]; k <= extent[5]; ++k)
    for (int j = extent[2]; j <= extent[3]; ++j)
      for (int i = extent[0]; i <= extent[1]; ++i)
      {
        wrong += Density(read, i, j, k) == Density(field, i, j, k) ? 0 : 1;
      }
  EXPECT_EQ(wrong, 0);
}

TEST_F(OpenVdb, ARotatedFieldKeepsItsGeometryThroughAFile)
{
  vtkNew<vtkImageData> field;
  field->SetExtent(-1, 6, 2, 7, 0, 4);
  field->SetOrigin(3.0, -2.0, 1.0);
  field->SetSpacing(0.5, 0.25, 2.0);
  const double c = std::cos(0.3), s = std::sin(0.3);
  field->SetDirectionMatrix(c, 0, s, 0, 1, 0, -s, 0, c);
  vtkNew<vtkFloatArray> density;
  density->SetNumberOfTuples(field->GetNumberOfPoints());
  for (vtkIdType p = 0; p < field->GetNumberOfPoints(); ++p)
  {
    density->SetValue(p, p % 3 == 0 ? 0.0f : float(p) * 0.125f);
  }
  field->GetPointData()->SetScalars(density);
  const std::string path = Directory.File("rotated-out.vdb");
  cloudvis::WriteField(field, path, { "{\"field\": {}}" });
  ExpectGridHoldsField(path, field);
  const auto read = cloudvis::ReadField(path);
  for (int e = 0; e < 9; ++e)
  {
    EXPECT_NEAR(
      read->GetDirectionMatrix()->GetData()[e], field->GetDirectionMatrix()->GetData()[e], 1e-12);
  }
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(read->GetSpacing()[a], field->GetSpacing()[a], 1e-12);
    EXPECT_NEAR(read->GetOrigin()[a], field->GetOrigin()[a], 1e-12);
  }
}

} // namespace
