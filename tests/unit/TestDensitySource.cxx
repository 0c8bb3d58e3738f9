// vtkCloudDensitySource and the density evaluator behind it: the density rules, pipeline
// manners (pieces, time, progress, abort) and determinism across SMP backends.
#include "CloudDensityEvaluator.h"
#include "SourcePieces.h"
#include "vtkCloudDensitySource.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

using namespace cloudvis;

namespace
{
std::vector<float> Densities(vtkImageData* image)
{
  auto* array = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("density"));
  EXPECT_NE(array, nullptr);
  if (!array)
  {
    return {};
  }
  return std::vector<float>(array->GetPointer(0), array->GetPointer(0) + array->GetNumberOfValues());
}

vtkSmartPointer<vtkImageData> Generate(vtkCloudDensitySource* source)
{
  source->Update();
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->DeepCopy(source->GetOutput());
  return copy;
}

using test::SameBits;

FieldDescription PerlinCloud()
{
  FieldDescription field;
  field.Noise.Type = noise::NoiseType::Perlin;
  field.Noise.Octaves = 4;
  Shape torus;
  torus.Type = ShapeType::Torus;
  torus.MajorRadius = 1.0f;
  torus.MinorRadius = 0.4f;
  torus.RotationDegrees = glm::vec3(30.0f, 0.0f, 10.0f);
  Shape box;
  box.Type = ShapeType::Box;
  box.HalfSize = glm::vec3(0.5f);
  box.Center = glm::vec3(0.8f, 0.0f, 0.0f);
  field.Shapes = { torus, box };
  field.Blend = ShapeBlend::SmoothUnion;
  return field;
}
}

TEST(DensityEvaluator, RowsAreBitIdenticalToPointEvaluation)
{
  for (noise::NoiseType type :
    { noise::NoiseType::White, noise::NoiseType::Value, noise::NoiseType::Perlin })
  {
    for (DensityModel model : { DensityModel::SdfPlusFbm, DensityModel::FbmFalloff })
    {
      FieldDescription field = PerlinCloud();
      field.Noise.Type = type;
      field.Model = model;
      const DensityEvaluator evaluator(field, 1.7);
      RowScratch scratch;
      std::vector<float> row(64);
      const double originX = -2.0, dx = 4.0 / 63.0, y = 0.3, z = -0.2;
      evaluator.EvaluateRow(0, 64, originX, dx, y, z, row.data(), scratch);
      for (int i = 0; i < 64; ++i)
      {
        ASSERT_EQ(row[i], evaluator.Density(glm::dvec3(originX + i * dx, y, z)))
          << "voxel " << i << ", noise " << int(type) << ", model " << int(model);
      }
    }
  }
}

TEST(DensityEvaluator, DensityIsNonNegativeAndExactlyZeroOutsideTheBound)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(48, 48, 48);
  source->SetField(PerlinCloud());
  auto image = Generate(source);
  const DensityEvaluator evaluator(source->GetField(), 0.0);
  const std::vector<float> density = Densities(image);
  int inside = 0;
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    ASSERT_GE(density[id], 0.0f);
    if (evaluator.SignedDistance(glm::vec3(p[0], p[1], p[2])) >= evaluator.DensityBound())
    {
      ASSERT_EQ(density[id], 0.0f) << "voxel " << id << " is outside the bound";
    }
    inside += density[id] > 0.0f;
  }
  EXPECT_GT(inside, 1000); // and the cloud is not empty
}

TEST(DensityEvaluator, ConstantModelIsTheShapeExactly)
{
  FieldDescription field;
  field.Model = DensityModel::Constant;
  field.DensityScale = 3.0;
  const DensityEvaluator evaluator(field, 0.0);
  EXPECT_EQ(evaluator.Density(glm::dvec3(0.0, 0.0, 0.5)), 3.0f);
  EXPECT_EQ(evaluator.Density(glm::dvec3(0.0, 0.0, 1.01)), 0.0f);
}

TEST(DensityEvaluator, ValidationNamesTheProblem)
{
  FieldDescription field;
  field.Noise.Octaves = 13;
  EXPECT_NE(ValidateFieldDescription(field).find("octaves"), std::string::npos);
  field.Noise.Octaves = 6;
  field.Shapes[0].Radius = std::nanf("");
  EXPECT_NE(ValidateFieldDescription(field).find("shape 0"), std::string::npos);
}

TEST(DensitySource, PublishesGeometryTimeAndSubExtentCapability)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(11, 21, 5);
  source->SetBounds(-1, 1, 0, 4, -2, 2);
  source->UpdateInformation();
  vtkInformation* info = source->GetOutputInformation(0);
  int extent[6];
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  EXPECT_EQ(extent[1], 10);
  EXPECT_EQ(extent[3], 20);
  EXPECT_EQ(extent[5], 4);
  double spacing[3], origin[3];
  info->Get(vtkDataObject::SPACING(), spacing);
  info->Get(vtkDataObject::ORIGIN(), origin);
  EXPECT_DOUBLE_EQ(spacing[0], 0.2);
  EXPECT_DOUBLE_EQ(spacing[1], 0.2);
  EXPECT_DOUBLE_EQ(spacing[2], 1.0);
  EXPECT_DOUBLE_EQ(origin[1], 0.0);
  EXPECT_EQ(info->Get(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT()), 1);
  EXPECT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 49);
  double range[2];
  info->Get(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range);
  EXPECT_EQ(range[1], 12.0);
}

TEST(DensitySource, PiecesEqualTheWhole)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(test::PieceTestDimensions);
  source->SetField(PerlinCloud());
  const std::vector<float> whole = Densities(Generate(source));
  EXPECT_TRUE(SameBits(whole, test::FieldFromOctants(source)));
}

TEST(DensitySource, SequentialStdThreadAndTbbBackendsGiveTheSameBytes)
{
  const std::string original = vtkSMPTools::GetBackend();
  std::vector<std::vector<float>> results;
  for (const char* backend : { "Sequential", "STDThread", "TBB" })
  {
    ASSERT_TRUE(vtkSMPTools::SetBackend(backend)) << backend;
    vtkNew<vtkCloudDensitySource> source;
    source->SetDimensions(64, 48, 40);
    source->SetField(PerlinCloud());
    results.push_back(Densities(Generate(source)));
  }
  vtkSMPTools::SetBackend(original.c_str());
  EXPECT_TRUE(SameBits(results[0], results[1]));
  EXPECT_TRUE(SameBits(results[0], results[2]));
}

TEST(DensitySource, RequestedTimeStepsMoveTheNoise)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(32, 32, 32);
  source->UpdateTimeStep(0.0);
  const std::vector<float> t0 = Densities(source->GetOutput());
  EXPECT_EQ(source->GetOutput()->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), 0.0);
  source->UpdateTimeStep(2.0);
  const std::vector<float> t2 = Densities(source->GetOutput());
  EXPECT_EQ(source->GetOutput()->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), 2.0);
  EXPECT_FALSE(SameBits(t0, t2));

  // Without a requested time the source uses its Time, equal to the same requested time.
  vtkNew<vtkCloudDensitySource> untimed;
  untimed->SetDimensions(32, 32, 32);
  untimed->SetTime(2.0);
  EXPECT_TRUE(SameBits(Densities(Generate(untimed)), t2));
}

TEST(DensitySource, TheSeedChangesTheField)
{
  vtkNew<vtkCloudDensitySource> a, b;
  for (auto* s : { a.Get(), b.Get() })
  {
    s->SetDimensions(24, 24, 24);
  }
  FieldDescription field;
  field.Noise.Seed = 42;
  b->SetField(field);
  EXPECT_FALSE(SameBits(Densities(Generate(a)), Densities(Generate(b))));
}

TEST(DensitySource, MorphEndpointsEqualThePureShapes)
{
  const std::vector<Shape> shapes = MorphTimeline::Shapes();
  for (int k = 0; k < 4; ++k)
  {
    FieldDescription morph;
    morph.Morph = true;
    FieldDescription pure;
    pure.Shapes = { shapes[k] };
    vtkNew<vtkCloudDensitySource> a, b;
    for (auto* s : { a.Get(), b.Get() })
    {
      s->SetDimensions(32, 32, 32);
      s->SetBounds(-3.5, 3.5, -3.5, 3.5, -3.5, 3.5);
      s->SetTime(3.0 * k);
    }
    a->SetField(morph);
    b->SetField(pure);
    EXPECT_TRUE(SameBits(Densities(Generate(a)), Densities(Generate(b)))) << "shape " << k;
  }
}

TEST(DensitySource, ReportsProgressAndHonoursAbort)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(32, 32, 40);
  struct Observed
  {
    std::vector<double> Progress;
    bool AbortAtThirdEvent = true;
  } observed;
  std::vector<double>& progress = observed.Progress;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&observed);
  onProgress->SetCallback([](vtkObject* caller, unsigned long, void* clientData, void* callData) {
    auto* seen = static_cast<Observed*>(clientData);
    seen->Progress.push_back(*static_cast<double*>(callData));
    if (seen->AbortAtThirdEvent && seen->Progress.size() == 3)
    {
      vtkAlgorithm::SafeDownCast(caller)->SetAbortExecute(1);
    }
  });
  source->AddObserver(vtkCommand::ProgressEvent, onProgress);
  source->Update();
  // 0 at the start, then one event per finished block until the abort stops the loop.
  ASSERT_EQ(progress.size(), 3u);
  EXPECT_EQ(progress.front(), 0.0);
  EXPECT_LT(progress.back(), 1.0);

  progress.clear();
  observed.AbortAtThirdEvent = false;
  source->SetAbortExecute(0);
  source->Modified();
  source->Update();
  EXPECT_EQ(progress.back(), 1.0);
}

TEST(DensitySource, RefusesBadGeometryWithAReason)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(0, 10, 10);
  EXPECT_NE(source->Validate().find("dimensions"), std::string::npos);
  source->SetDimensions(10, 10, 10);
  source->SetBounds(1, -1, -1, 1, -1, 1);
  EXPECT_NE(source->Validate().find("bounds along x"), std::string::npos);
  source->SetBounds(-1, 1, -1, 1, -1, 1);

  // Noise lattice coordinates beyond 32-bit cells are refused, for the source's time and for a
  // time requested through the pipeline.
  source->SetDimensions(8, 8, 8);
  FieldDescription field;
  field.Noise.Frequency = 1e6;
  field.Noise.Octaves = 12;
  source->SetField(field);
  EXPECT_NE(source->Validate().find("2^30"), std::string::npos);
  source->SetField(FieldDescription{});
  EXPECT_EQ(source->Validate(), "");
  EXPECT_NE(ValidateNoiseRange(FieldDescription{}, source->GetBounds(), 1e10).find("2^30"),
    std::string::npos);
}

// Only the extent requested must fit in memory: a process generating one piece of a field larger
// than its memory (cloudvis generate under mpirun) is not refused for the whole field's size.
TEST(DensitySource, OnlyTheRequestedExtentMustFitInMemory)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(100000, 100000, 100000); // 3.55 PiB of float
  EXPECT_EQ(source->Validate(), "");
  const int whole[6] = { 0, 99999, 0, 99999, 0, 99999 };
  EXPECT_NE(source->ValidateExtent(whole).find("a field of 100000 x 100000 x 100000 voxels needs "
                                               "3.55 PiB but only "),
    std::string::npos)
    << source->ValidateExtent(whole);

  std::vector<std::string> errors;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* message)
    { static_cast<std::vector<std::string>*>(client)->push_back(static_cast<char*>(message)); });
  source->AddObserver(vtkCommand::ErrorEvent, onError);

  // A piece near the far corner: generated, the extent filled.
  int piece[6] = { 99990, 99999, 50000, 50007, 99996, 99999 };
  source->UpdateExtent(piece);
  EXPECT_TRUE(errors.empty()) << errors.front();
  int produced[6];
  source->GetOutput()->GetExtent(produced);
  EXPECT_TRUE(std::equal(piece, piece + 6, produced));
  EXPECT_EQ(Densities(source->GetOutput()).size(), 10u * 8u * 4u);

  // The whole field: refused before anything is allocated, with its size.
  source->Modified();
  source->UpdateExtent(whole);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(
    errors[0].find("a field of 100000 x 100000 x 100000 voxels needs 3.55 PiB"), std::string::npos)
    << errors[0];
}
