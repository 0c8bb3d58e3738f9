// vtkCloudOccupancyFilter: which bricks are occupied (apron included, transfer function
// respected), the exact Chebyshev distances, the output geometry, input types, pipeline
// manners (re-execution only on change) and determinism across SMP backends.
#include "CloudReferenceMarch.h"
#include "CloudTransferTable.h"
#include "vtkCloudOccupancyFilter.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedShortArray.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <random>
#include <vector>

using namespace cloudvis;

namespace
{
using Index = std::array<int, 3>;

// A one-component image of type ArrayT filled with `value`.
template <typename ArrayT>
vtkSmartPointer<vtkImageData> MakeField(const Index& dims, double value = 0.0)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims[0], dims[1], dims[2]);
  vtkNew<ArrayT> scalars;
  scalars->SetName("density");
  scalars->SetNumberOfTuples(vtkIdType(dims[0]) * dims[1] * dims[2]);
  scalars->Fill(value);
  image->GetPointData()->SetScalars(scalars);
  return image;
}

// A float field of `dims` whose voxel v holds value(v, u), u drawn uniformly from [0, 1) in
// voxel order by `rng`.
vtkSmartPointer<vtkImageData> RandomField(const Index& dims,
  std::mt19937& rng,
  const std::function<float(vtkIdType, float)>& value)
{
  auto field = MakeField<vtkFloatArray>(dims);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  auto* scalars = vtkFloatArray::SafeDownCast(field->GetPointData()->GetScalars());
  for (vtkIdType v = 0; v < scalars->GetNumberOfValues(); ++v)
  {
    scalars->SetValue(v, value(v, unit(rng)));
  }
  return field;
}

void SetVoxel(vtkImageData* image, const Index& v, double value)
{
  const int* dims = image->GetDimensions();
  image->GetPointData()->GetScalars()->SetComponent(
    (vtkIdType(v[2]) * dims[1] + v[1]) * dims[0] + v[0], 0, value);
}

// Opacity 0 at density 0 rising linearly to 1 at `top`: any non-zero density is visible.
TransferTable RampTable(double top = 1.0)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(top, 1.0);
  const double range[2] = { 0.0, top };
  return BuildTransferTable(nullptr, opacity, 1.0, range);
}

struct Bricks
{
  Index Dims;
  std::vector<float> MaxExtinction;
  std::vector<int> Distance;
  double Fraction;

  int At(const Index& b) const { return (b[2] * this->Dims[1] + b[1]) * this->Dims[0] + b[0]; }
  bool Occupied(const Index& b) const { return this->MaxExtinction[this->At(b)] > 0.0f; }
};

Bricks Read(vtkImageData* output)
{
  Bricks bricks;
  const int* dims = output->GetDimensions();
  bricks.Dims = { dims[0], dims[1], dims[2] };
  auto* sigma_t = vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray("max_extinction"));
  auto* distance =
    vtkUnsignedCharArray::SafeDownCast(output->GetPointData()->GetArray("empty_distance"));
  auto* fraction =
    vtkDoubleArray::SafeDownCast(output->GetFieldData()->GetArray("occupied_fraction"));
  EXPECT_NE(sigma_t, nullptr);
  EXPECT_NE(distance, nullptr);
  EXPECT_NE(fraction, nullptr);
  EXPECT_EQ(output->GetPointData()->GetScalars(), sigma_t);
  if (!sigma_t || !distance || !fraction)
  {
    return bricks;
  }
  for (vtkIdType i = 0; i < sigma_t->GetNumberOfValues(); ++i)
  {
    bricks.MaxExtinction.push_back(sigma_t->GetValue(i));
    bricks.Distance.push_back(distance->GetValue(i));
  }
  bricks.Fraction = fraction->GetValue(0);
  return bricks;
}

// Most tests use a one-voxel apron; ApronZeroIsTheTrilinearFootprint checks the default.
Bricks Occupancy(vtkImageData* field, const TransferTable& table, int brickSize, int apron = 1)
{
  vtkNew<vtkCloudOccupancyFilter> filter;
  filter->SetInputData(field);
  filter->SetTransferTable(table);
  filter->SetBrickSize(brickSize);
  filter->SetApron(apron);
  filter->Update();
  EXPECT_EQ(filter->GetOccupiedFraction(),
    Read(filter->GetOutput()).Fraction); // getter and field data agree
  return Read(filter->GetOutput());
}

// Whether brick b (brick size B) sees voxel v along one axis: v within b*B - 1 .. (b+1)*B + 1.
bool SeesVoxel(int b, int brickSize, int v)
{
  return b * brickSize - 1 <= v && v <= (b + 1) * brickSize + 1; // with the one-voxel apron
}

// The definition, by brute force: Chebyshev distance to the nearest occupied brick, capped.
int BruteForceDistance(const Bricks& bricks, const Index& p)
{
  int best = 255;
  for (int z = 0; z < bricks.Dims[2]; ++z)
    for (int y = 0; y < bricks.Dims[1]; ++y)
      for (int x = 0; x < bricks.Dims[0]; ++x)
        if (bricks.Occupied({ x, y, z }))
          best = std::min(best,
            std::max({ std::abs(x - p[0]), std::abs(y - p[1]), std::abs(z - p[2]) }));
  return best;
}

void ExpectExactDistances(const Bricks& bricks)
{
  for (int z = 0; z < bricks.Dims[2]; ++z)
    for (int y = 0; y < bricks.Dims[1]; ++y)
      for (int x = 0; x < bricks.Dims[0]; ++x)
        ASSERT_EQ(bricks.Distance[bricks.At({ x, y, z })], BruteForceDistance(bricks, { x, y, z }))
          << "brick " << x << ", " << y << ", " << z;
}
}

TEST(OccupancyFilter, OneVoxelOccupiesExactlyTheBricksWhoseApronHoldsIt)
{
  const Index dims = { 33, 29, 20 };
  const Index voxel = { 16, 12, 7 };
  auto field = MakeField<vtkFloatArray>(dims);
  SetVoxel(field, voxel, 1.0);
  const Bricks bricks = Occupancy(field, RampTable(), 8);
  ASSERT_EQ(bricks.Dims, (Index{ 4, 4, 3 }));

  int occupied = 0;
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
      {
        const bool expected =
          SeesVoxel(x, 8, voxel[0]) && SeesVoxel(y, 8, voxel[1]) && SeesVoxel(z, 8, voxel[2]);
        EXPECT_EQ(bricks.Occupied({ x, y, z }), expected) << x << ", " << y << ", " << z;
        occupied += expected;
      }
  // x = 16 sits on the boundary of bricks 1 and 2, y = 12 inside brick 1, z = 7 in brick 0's
  // cells but within brick 1's apron.
  EXPECT_EQ(occupied, 2 * 1 * 2);
  EXPECT_DOUBLE_EQ(bricks.Fraction, 4.0 / 48.0);
  EXPECT_NEAR(bricks.MaxExtinction[bricks.At({ 1, 1, 0 })], -std::log(1e-4), 1e-3);

  // Distances grow by one per brick away from the occupied block (x 1..2, y 1, z 0..1).
  EXPECT_EQ(bricks.Distance[bricks.At({ 1, 1, 0 })], 0);
  EXPECT_EQ(bricks.Distance[bricks.At({ 0, 1, 0 })], 1);
  EXPECT_EQ(bricks.Distance[bricks.At({ 3, 3, 2 })], 2);
  EXPECT_EQ(bricks.Distance[bricks.At({ 0, 3, 2 })], 2);
  ExpectExactDistances(bricks);
}

TEST(OccupancyFilter, ExtinctionBoundsHoldForEveryTrilinearSampleInTheBrick)
{
  // A random field and table: at random points of each brick, the extinction of the trilinear
  // sample (the renderers' DensityAt) lies between the brick's min_extinction and
  // max_extinction, the path tracer's minorant and majorant.
  const Index dims = { 19, 14, 11 };
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  auto field = RandomField(dims, rng, [&](vtkIdType v, float u) { // empty at low x
    return v % dims[0] < 3 ? 0.0f : 0.1f + 0.9f * u;
  });
  TransferTable table = RampTable();
  for (int e = 0; e < table.Size; ++e)
    table.RGBA[4 * e + 3] *= 0.5f + unit(rng); // not monotonic
  vtkNew<vtkCloudOccupancyFilter> filter;
  filter->SetInputData(field);
  filter->SetTransferTable(table);
  filter->SetBrickSize(4);
  filter->Update();
  vtkImageData* output = filter->GetOutput();
  auto* maxima = vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray("max_extinction"));
  auto* minima = vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray("min_extinction"));
  ASSERT_NE(minima, nullptr);
  ASSERT_EQ(minima->GetNumberOfValues(), maxima->GetNumberOfValues());
  MarchUniforms u;
  u.Density.Values =
    vtkFloatArray::SafeDownCast(field->GetPointData()->GetScalars())->GetPointer(0);
  u.Dimensions = glm::ivec3(dims[0], dims[1], dims[2]);
  u.Table = &table;
  const int* bricks = output->GetDimensions();
  int positive = 0;
  for (int bz = 0; bz < bricks[2]; ++bz)
    for (int by = 0; by < bricks[1]; ++by)
      for (int bx = 0; bx < bricks[0]; ++bx)
      {
        const vtkIdType b = (vtkIdType(bz) * bricks[1] + by) * bricks[0] + bx;
        positive += minima->GetValue(b) > 0.0f;
        ASSERT_LE(minima->GetValue(b), maxima->GetValue(b));
        for (int k = 0; k < 200; ++k)
        {
          // Within the brick's cells and the volume: [4 b, 4 b + 4] clamped to [0, n - 1].
          glm::vec3 p;
          for (int a = 0; a < 3; ++a)
          {
            const float lo = 4.0f * glm::ivec3(bx, by, bz)[a];
            const float hi = std::min(lo + 4.0f, float(dims[a] - 1));
            p[a] = lo + unit(rng) * (hi - lo);
          }
          const float sigma_t = ExtinctionAt(u, p);
          ASSERT_GE(sigma_t, minima->GetValue(b)) << "brick " << bx << ", " << by << ", " << bz;
          ASSERT_LE(sigma_t, maxima->GetValue(b)) << "brick " << bx << ", " << by << ", " << bz;
        }
      }
  EXPECT_GT(positive, 10); // the bricks away from the empty side
}

TEST(OccupancyFilter, ApronZeroIsTheTrilinearFootprint)
{
  // Voxel 8 along x is shared by bricks 0 and 1 (both interpolate with it); voxel 9 belongs to
  // brick 1 alone.
  for (int v : { 8, 9 })
  {
    auto field = MakeField<vtkFloatArray>({ 33, 2, 2 });
    SetVoxel(field, { v, 0, 0 }, 1.0);
    const Bricks bricks = Occupancy(field, RampTable(), 8, 0);
    ASSERT_EQ(bricks.Dims, (Index{ 4, 1, 1 }));
    EXPECT_EQ(bricks.Occupied({ 0, 0, 0 }), v == 8) << v;
    EXPECT_TRUE(bricks.Occupied({ 1, 0, 0 })) << v;
    EXPECT_FALSE(bricks.Occupied({ 2, 0, 0 })) << v;
  }
}

TEST(OccupancyFilter, DistancesAreExactForScatteredVoxels)
{
  const Index dims = { 41, 30, 23 };
  auto field = MakeField<vtkFloatArray>(dims);
  std::mt19937 rng(3);
  for (int n = 0; n < 5; ++n)
  {
    SetVoxel(field, { int(rng() % 41), int(rng() % 30), int(rng() % 23) }, 0.5);
  }
  const Bricks bricks = Occupancy(field, RampTable(), 2);
  ASSERT_EQ(bricks.Dims, (Index{ 20, 15, 11 }));
  ExpectExactDistances(bricks);
}

TEST(OccupancyFilter, DistancesGrowOneBrickAtATimeAndStopAt255)
{
  auto field = MakeField<vtkFloatArray>({ 300, 2, 2 });
  SetVoxel(field, { 0, 0, 0 }, 1.0);
  const Bricks bricks = Occupancy(field, RampTable(), 1);
  ASSERT_EQ(bricks.Dims, (Index{ 299, 1, 1 }));
  // Bricks 0 and 1 see voxel 0 (brick 1's apron starts at voxel 0).
  for (int x = 0; x < 299; ++x)
  {
    EXPECT_EQ(bricks.Distance[x], std::min(std::max(x - 1, 0), 255)) << x;
  }
}

TEST(OccupancyFilter, NoOccupiedBrickMeansEverythingIsFarAndTheFractionIsZero)
{
  const Bricks bricks = Occupancy(MakeField<vtkFloatArray>({ 20, 20, 20 }), RampTable(), 4);
  EXPECT_EQ(bricks.Fraction, 0.0);
  for (int d : bricks.Distance)
  {
    EXPECT_EQ(d, 255);
  }
}

TEST(OccupancyFilter, DensitiesTheTransferFunctionHidesAreEmpty)
{
  // 0.3 everywhere (visible to a ramp, but not to this function), 0.8 from x = 24 on.
  const Index dims = { 40, 40, 40 };
  auto field = MakeField<vtkFloatArray>(dims, 0.3);
  for (int z = 0; z < 40; ++z)
    for (int y = 0; y < 40; ++y)
      for (int x = 24; x < 40; ++x)
        SetVoxel(field, { x, y, z }, 0.8);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(0.5, 0.0);
  opacity->AddPoint(0.55, 0.7);
  opacity->AddPoint(1.0, 0.7);
  const double range[2] = { 0.0, 1.0 };
  const Bricks bricks = Occupancy(field, BuildTransferTable(nullptr, opacity, 1.0, range), 8);
  ASSERT_EQ(bricks.Dims, (Index{ 5, 5, 5 }));
  for (int z = 0; z < 5; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 5; ++x)
      {
        // Brick 2 covers voxels 16..24 and sees 15..25, which reaches the 0.8 slab.
        EXPECT_EQ(bricks.Occupied({ x, y, z }), x >= 2);
        EXPECT_EQ(bricks.Distance[bricks.At({ x, y, z })], std::max(2 - x, 0));
      }
  EXPECT_DOUBLE_EQ(bricks.Fraction, 0.6);

  // The same field under a ramp from 0: every brick is visible.
  const Bricks ramp = Occupancy(field, RampTable(), 8);
  EXPECT_DOUBLE_EQ(ramp.Fraction, 1.0);
}

TEST(OccupancyFilter, OutputGeometryCoversTheCellsWithOnePointPerBrick)
{
  struct Case
  {
    int N;
    int Bricks;
  };
  for (const Case& c : { Case{ 64, 8 }, Case{ 65, 8 }, Case{ 66, 9 }, Case{ 1, 1 }, Case{ 2, 1 },
         Case{ 9, 1 }, Case{ 10, 2 } })
  {
    auto field = MakeField<vtkFloatArray>({ c.N, 65, 1 });
    field->SetOrigin(1.0, -2.0, 3.0);
    field->SetSpacing(0.5, 0.25, 2.0);
    vtkNew<vtkCloudOccupancyFilter> filter;
    filter->SetInputData(field);
    filter->SetTransferTable(RampTable());
    filter->Update();
    vtkImageData* output = filter->GetOutput();
    const int* dims = output->GetDimensions();
    EXPECT_EQ(dims[0], c.Bricks) << "n = " << c.N;
    EXPECT_EQ(dims[1], 8);
    EXPECT_EQ(dims[2], 1);
    const double* spacing = output->GetSpacing();
    EXPECT_DOUBLE_EQ(spacing[0], 4.0);
    EXPECT_DOUBLE_EQ(spacing[1], 2.0);
    EXPECT_DOUBLE_EQ(spacing[2], 16.0);
    const double* origin = output->GetOrigin();
    EXPECT_DOUBLE_EQ(origin[0], 1.0);
    EXPECT_DOUBLE_EQ(origin[1], -2.0);
    EXPECT_DOUBLE_EQ(origin[2], 3.0);
    // The pipeline's information agrees with the data (downstream allocates from it).
    int whole[6];
    filter->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    EXPECT_EQ(whole[1], c.Bricks - 1);
  }
}

TEST(OccupancyFilter, BrickZeroStartsAtTheFirstVoxelOfAnExtentThatDoesNotStartAtZero)
{
  auto field = MakeField<vtkFloatArray>({ 64, 9, 1 });
  field->SetExtent(4, 67, -2, 6, 0, 0);
  field->SetSpacing(0.5, 1.0, 1.0);
  SetVoxel(field, { 0, 0, 0 }, 1.0); // voxel (4, -2, 0)
  vtkNew<vtkCloudOccupancyFilter> filter;
  filter->SetInputData(field);
  filter->SetTransferTable(RampTable());
  filter->Update();
  vtkImageData* output = filter->GetOutput();
  EXPECT_DOUBLE_EQ(output->GetOrigin()[0], 2.0);
  EXPECT_DOUBLE_EQ(output->GetOrigin()[1], -2.0);
  EXPECT_EQ(output->GetExtent()[0], 0);
  EXPECT_EQ(output->GetDimensions()[0], 8);
  const Bricks bricks = Read(output);
  EXPECT_TRUE(bricks.Occupied({ 0, 0, 0 }));
  EXPECT_FALSE(bricks.Occupied({ 1, 0, 0 }));
}

TEST(OccupancyFilter, ReExecutesOnlyWhenTheInputOrTheParametersChange)
{
  auto field = MakeField<vtkFloatArray>({ 17, 17, 17 });
  SetVoxel(field, { 3, 3, 3 }, 1.0);
  vtkNew<vtkCloudOccupancyFilter> filter;
  filter->SetInputData(field);
  filter->SetTransferTable(RampTable());
  int executions = 0;
  vtkNew<vtkCallbackCommand> onStart;
  onStart->SetClientData(&executions);
  onStart->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void*) { ++*static_cast<int*>(clientData); });
  filter->AddObserver(vtkCommand::StartEvent, onStart);

  filter->Update();
  EXPECT_EQ(executions, 1);
  filter->Update();
  EXPECT_EQ(executions, 1);
  filter->SetTransferTable(RampTable()); // an equal table
  filter->SetBrickSize(8);               // the current value
  filter->Update();
  EXPECT_EQ(executions, 1);

  filter->SetTransferTable(RampTable(2.0));
  filter->Update();
  EXPECT_EQ(executions, 2);
  filter->SetBrickSize(4);
  filter->Update();
  EXPECT_EQ(executions, 3);
  EXPECT_EQ(filter->GetOutput()->GetDimensions()[0], 4);
  field->Modified();
  filter->Update();
  EXPECT_EQ(executions, 4);
}

TEST(OccupancyFilter, IntegerInputsGiveTheSameBricksAsFloat)
{
  const Index dims = { 33, 29, 20 };
  const Index voxel = { 16, 12, 7 };
  auto asFloat = MakeField<vtkFloatArray>(dims);
  SetVoxel(asFloat, voxel, 200.0 / 255.0);
  auto asByte = MakeField<vtkUnsignedCharArray>(dims);
  SetVoxel(asByte, voxel, 200.0);
  auto asShort = MakeField<vtkUnsignedShortArray>(dims);
  SetVoxel(asShort, voxel, 200.0 * 257.0);

  const Bricks reference = Occupancy(asFloat, RampTable(1.0), 8);
  const Bricks bytes = Occupancy(asByte, RampTable(255.0), 8);
  const Bricks shorts = Occupancy(asShort, RampTable(65535.0), 8);
  EXPECT_DOUBLE_EQ(reference.Fraction, 4.0 / 48.0);
  for (const Bricks* other : { &bytes, &shorts })
  {
    ASSERT_EQ(other->Dims, reference.Dims);
    EXPECT_EQ(other->Distance, reference.Distance);
    for (std::size_t b = 0; b < reference.MaxExtinction.size(); ++b)
    {
      EXPECT_EQ(other->MaxExtinction[b] > 0.0f, reference.MaxExtinction[b] > 0.0f) << b;
    }
  }
}

TEST(OccupancyFilter, RefusesWhatItCannotRead)
{
  int errors = 0;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void*) { ++*static_cast<int*>(clientData); });

  vtkNew<vtkCloudOccupancyFilter> noTable;
  noTable->AddObserver(vtkCommand::ErrorEvent, onError);
  noTable->SetInputData(MakeField<vtkFloatArray>({ 8, 8, 8 }));
  noTable->Update();
  EXPECT_EQ(errors, 1);

  auto vectors = MakeField<vtkFloatArray>({ 8, 8, 8 });
  vtkNew<vtkFloatArray> threeComponents;
  threeComponents->SetNumberOfComponents(3);
  threeComponents->SetNumberOfTuples(512);
  vectors->GetPointData()->SetScalars(threeComponents);
  vtkNew<vtkCloudOccupancyFilter> wrongShape;
  wrongShape->AddObserver(vtkCommand::ErrorEvent, onError);
  wrongShape->SetInputData(vectors);
  wrongShape->SetTransferTable(RampTable());
  wrongShape->Update();
  EXPECT_EQ(errors, 2);
}

TEST(OccupancyFilter, SequentialStdThreadAndTbbBackendsGiveTheSameBricks)
{
  const Index dims = { 70, 50, 45 };
  std::mt19937 rng(8);
  auto field = RandomField(dims, rng, [](vtkIdType, float u) { return u > 0.999f ? u : 0.0f; });
  const std::string original = vtkSMPTools::GetBackend();
  std::vector<Bricks> results;
  for (const char* backend : { "Sequential", "STDThread", "TBB" })
  {
    ASSERT_TRUE(vtkSMPTools::SetBackend(backend)) << backend;
    results.push_back(Occupancy(field, RampTable(), 4));
  }
  vtkSMPTools::SetBackend(original.c_str());
  for (std::size_t r = 1; r < results.size(); ++r)
  {
    EXPECT_EQ(results[r].MaxExtinction, results[0].MaxExtinction);
    EXPECT_EQ(results[r].Distance, results[0].Distance);
  }
}

TEST(OccupancyFilter, Timing256Cubed)
{
  // Not an assertion: prints how long a 256^3 float field takes, for the report and bench/.
  const int n = 256;
  auto field = MakeField<vtkFloatArray>({ n, n, n });
  float* density = vtkFloatArray::SafeDownCast(field->GetPointData()->GetScalars())->GetPointer(0);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
      {
        const double r = std::sqrt(double((x - 128) * (x - 128) + (y - 110) * (y - 110) +
                           (z - 140) * (z - 140))) / 80.0;
        density[(std::size_t(z) * n + y) * n + x] = float(std::max(0.0, 1.0 - r));
      }
  vtkNew<vtkCloudOccupancyFilter> filter;
  filter->SetInputData(field);
  filter->SetTransferTable(RampTable());
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  const double ms =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[ timing   ] vtkCloudOccupancyFilter, 256^3 float, brick 8 ("
            << vtkSMPTools::GetBackend() << ", " << vtkSMPTools::GetEstimatedNumberOfThreads()
            << " threads): " << ms << " ms, occupied fraction " << filter->GetOccupiedFraction()
            << "\n";
  EXPECT_GT(filter->GetOccupiedFraction(), 0.0);
  EXPECT_LT(filter->GetOccupiedFraction(), 1.0);
}

TEST(OccupancyFilter, ValuesBeyondTheTransferFunctionTakeItsEndValues)
{
  // The table spans the function (0 .. 1); the data reach far beyond it. A brick of -3.4e38
  // reads the first entry (transparent), bricks of 1e4 or 3.4e38 the last (opaque): skipping
  // stays exact because the occupancy clamps exactly as the lookups do.
  const Index dims = { 17, 9, 9 };
  auto field = MakeField<vtkFloatArray>(dims, -3.4e38);
  for (int z = 0; z < 9; ++z)
    for (int y = 0; y < 9; ++y)
    {
      SetVoxel(field, { 14, y, z }, 1e4);
      SetVoxel(field, { 16, y, z }, 3.4e38);
    }
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(1.0, 0.5);
  const TransferTable table = TabulateTransferFunction(nullptr, opacity, 1.0);
  const Bricks bricks = Occupancy(field, table, 4, 0);
  ASSERT_EQ(bricks.Dims, (Index{ 4, 2, 2 }));
  for (int x = 0; x < 4; ++x)
  {
    EXPECT_EQ(bricks.Occupied({ x, 0, 0 }), x == 3) << "brick " << x;
  }
  EXPECT_FLOAT_EQ(bricks.MaxExtinction[bricks.At({ 3, 1, 1 })], float(Extinction(0.5, 1.0)));
}
