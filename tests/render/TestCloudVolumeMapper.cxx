// vtkCloudVolumeMapper against known answers and against VTK's vtkGPUVolumeRayCastMapper.
#include "SupportScene.h"

#include <vtkCamera.h>
#include <vtkFloatArray.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkTransform.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>

using namespace cloudvis;
using namespace cloudvis::support;

TEST(CloudVolumeMapper, HomogeneousSphereTransmitsBeerLambert)
{
  // Constant density 1 in a sphere of radius 1; opacity 0.5 per unit length 0.5, so
  // sigma_t = ln 2 / 0.5. Through the centre the path is 2: alpha = 1 - exp(-sigma_t * 2).
  auto mapper = CloudMapper(0.01);
  GpuScene scene(mapper);
  scene.SetInput(ConstantSphere(1.0));
  SetUniformMedium(scene.Property, 0.5, 0.5);
  const Image image = scene.RenderFloat();
  Dump(image, "homogeneous-sphere");
  ASSERT_EQ(mapper->GetLastError(), "");
  const double sigma = std::log(2.0) / 0.5;
  const double expected = 1.0 - std::exp(-sigma * 2.0);
  const float alpha = image.At(image.Width / 2, image.Height / 2, 3);
  EXPECT_NEAR(alpha, expected, 0.01 * expected);
  // Outside the sphere nothing is drawn.
  EXPECT_EQ(image.At(2, 2, 3), 0.0f);
}

namespace
{
// Renders `field` with cloudvis's mapper and with VTK's, both volumes placed by `place` (the
// camera looks at the volume's centre), and compares the 8-bit images over the pixels where
// either shows cloud (the background is black).
void ExpectMatchesVtk(
  vtkImageData* field,
  const char* name,
  double rmsLevels,
  const std::function<void(vtkVolume*)>& place = [](vtkVolume*) {})
{
  const double step = 0.02;
  auto ours = CloudMapper(step);
  GpuScene cloud(ours);
  cloud.SetInput(field);
  SetRampMedium(cloud.Property, 1.0, 0.6);
  auto theirs = VtkMapper(step);
  GpuScene vtk(theirs);
  vtk.SetInput(field);
  SetRampMedium(vtk.Property, 1.0, 0.6);
  for (GpuScene* scene : { &cloud, &vtk })
  {
    place(scene->Volume);
    double bounds[6];
    scene->Volume->GetBounds(bounds);
    vtkCamera* camera = scene->Renderer->GetActiveCamera();
    camera->SetFocalPoint(
      0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5]));
    camera->SetPosition(0.5 * (bounds[0] + bounds[1]),
      0.5 * (bounds[2] + bounds[3]),
      0.5 * (bounds[4] + bounds[5]) + 6.0);
  }
  const Image a = cloud.Render(), b = vtk.Render();
  Dump(a, std::string(name) + "-cloudvis");
  Dump(b, std::string(name) + "-vtk");
  ASSERT_EQ(ours->GetLastError(), "");
  const Difference d = Compare(a, b, 3, ShowsCloud(a, b));
  const size_t cloudPixels = d.Count / 3;
  std::cout << name << ": " << cloudPixels << " cloud pixels, RMS " << d.RmsLevels()
            << " levels, max " << d.MaxLevels() << "\n";
  ASSERT_GT(cloudPixels, size_t(a.Width * a.Height / 10)) << "an empty window proves nothing";
  // Both integrate the same emission-absorption sum; they differ where the two place the first
  // sample inside a voxel at the volume's edge and in 8-bit rounding.
  EXPECT_LT(d.RmsLevels(), rmsLevels) << name;
}
}

TEST(CloudVolumeMapper, MatchesVtkGpuRayCastOnASparseCloud)
{
  ExpectMatchesVtk(SparseCloud(64), "sparse", 1.0);
}

TEST(CloudVolumeMapper, MatchesVtkGpuRayCastOnADenseField)
{
  ExpectMatchesVtk(DenseCloud(64), "dense", 1.0);
}

TEST(CloudVolumeMapper, MatchesVtkGpuRayCastOnARotatedVolume)
{
  // The image's direction matrix and the vtkVolume's orientation, which VTK's mapper honours.
  auto field = SparseCloud(64);
  field->SetDirectionMatrix(0.8, -0.6, 0.0, 0.6, 0.8, 0.0, 0.0, 0.0, 1.0);
  ExpectMatchesVtk(field,
    "rotated",
    1.0,
    [](vtkVolume* volume)
    {
      volume->RotateX(30.0);
      volume->RotateY(-20.0);
    });
}

TEST(CloudVolumeMapper, MatchesVtkGpuRayCastOnAMovedScaledVolume)
{
  // Position, origin, a non-uniform scale and a user transform; and an extent that starts at -5.
  auto field = SparseCloud(64);
  int e[6];
  field->GetExtent(e);
  field->SetExtent(e[0] - 5, e[1] - 5, e[2] - 5, e[3] - 5, e[4] - 5, e[5] - 5);
  ExpectMatchesVtk(field,
    "moved",
    1.0,
    [](vtkVolume* volume)
    {
      volume->SetPosition(2.0, -1.0, 0.5);
      volume->SetOrigin(0.3, 0.0, 0.0);
      volume->SetScale(1.2, 0.8, 1.0);
      vtkNew<vtkTransform> user;
      user->RotateZ(25.0);
      volume->SetUserTransform(user);
    });
}

namespace
{
// The scene's float image without and with empty-space skipping, with each of the march loop's
// variants (1 to 4 samples per reading of the occupancy map), and the samples each took.
struct SkippingRenders
{
  Image Full;
  double AllSamples = 0.0; // without skipping
  // With skipping, per samples per map read; [0] unused.
  Image Skipped[5];
  vtkCloudVolumeMapper::FrameStatistics Skipping[5];
};
SkippingRenders RenderWithAndWithoutSkipping(vtkCloudVolumeMapper* mapper,
  GpuScene& scene,
  const std::string& dumpName)
{
  SkippingRenders r;
  mapper->CollectStatisticsOn();
  mapper->EmptySpaceSkippingOff();
  r.Full = scene.RenderFloat();
  r.AllSamples = mapper->GetLastFrameStatistics().SamplesTaken;
  mapper->EmptySpaceSkippingOn();
  for (int perRead = 1; perRead <= 4; ++perRead)
  {
    mapper->SetSamplesPerMapRead(perRead);
    r.Skipped[perRead] = scene.RenderFloat();
    r.Skipping[perRead] = mapper->GetLastFrameStatistics();
  }
  mapper->SetSamplesPerMapRead(0);
  Dump(r.Skipped[1], dumpName);
  return r;
}
}

TEST(CloudVolumeMapper, EmptySpaceSkippingChangesTheSampleCountNotTheImage)
{
  // Skipping lands on the same lattice of samples and only leaps over samples whose extinction
  // is exactly 0, so the float image must be bit for bit the same, under every lighting model
  // (the light march skips too) and wherever the volume is, with either loop variant (a second
  // sample before the map is read again adds nothing where its brick is empty).
  for (LightingModel model :
    { LightingModel::None, LightingModel::Derivative, LightingModel::March })
  {
    auto mapper = CloudMapper(0.02);
    LightingParameters lighting;
    lighting.Model = model;
    mapper->GetLightingProperty()->SetParameters(lighting);
    GpuScene scene(mapper, 96, 96);
    auto field = SparseCloud(96);
    field->SetDirectionMatrix(0.8, -0.6, 0.0, 0.6, 0.8, 0.0, 0.0, 0.0, 1.0);
    scene.SetInput(field);
    scene.Volume->RotateX(20.0);
    SetRampMedium(scene.Property, 1.0, 0.6);
    AddLight(scene.Renderer, DirectionalLight(glm::dvec3(6.0, 8.0, 4.0)));
    AddLight(scene.Renderer, PointLight(glm::dvec3(-2.0, 0.5, 1.5), 4.0));
    const SkippingRenders r = RenderWithAndWithoutSkipping(mapper, scene, "skipping");
    ASSERT_GT(MeanOver(r.Full, 3, Columns(0, 96)), 0.05) << "an empty window proves nothing";
    for (int perRead = 1; perRead <= 4; ++perRead)
    {
      EXPECT_EQ(MaxDifference(r.Full, r.Skipped[perRead]), 0.0)
        << "model " << int(model) << ", " << perRead << " samples per map read";
      EXPECT_EQ(r.Skipping[perRead].SamplesPerMapRead, perRead);
      EXPECT_LT(r.Skipping[perRead].SamplesTaken, 0.8 * r.AllSamples);
      EXPECT_GT(r.Skipping[perRead].UsefulSamples, 0.0);
    }
  }
}

namespace
{
// Dots of 2^3 voxels of density 1, 6 voxels apart on each axis, over [-2, 2]^3 (zero elsewhere).
// With the default bricks of 3 voxels, every other brick along each axis sees only zeros, and the
// voxel just past its far face (on either side) is a dot's: a ray through the field meets empty
// and occupied bricks in turn, and density starts right where a leap out of an empty brick lands.
vtkSmartPointer<vtkImageData> DotsBetweenEmptyBricks(int size)
{
  auto field = vtkSmartPointer<vtkImageData>::New();
  field->SetDimensions(size, size, size);
  const double spacing = 4.0 / (size - 1);
  field->SetSpacing(spacing, spacing, spacing);
  field->SetOrigin(-2.0, -2.0, -2.0);
  vtkNew<vtkFloatArray> density;
  density->SetName("density");
  density->SetNumberOfTuples(vtkIdType(size) * size * size);
  const auto inDot = [](int i) { return i % 6 == 1 || i % 6 == 2; };
  vtkIdType n = 0;
  for (int z = 0; z < size; ++z)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        density->SetValue(n++, inDot(x) && inDot(y) && inDot(z) ? 1.0f : 0.0f);
  field->GetPointData()->SetScalars(density);
  return field;
}
}

TEST(CloudVolumeMapper, EmptySpaceSkippingMissesNothingWhereEmptyAndOccupiedBricksAlternate)
{
  // Every leap must land on the first lattice sample past the empty bricks it leaves, whichever
  // face it leaves them by (the march computes only the far face's distance on each axis), and
  // the march must read the occupancy again wherever a ray may have entered another brick: a
  // leap one sample too far, or a sample skipped without its brick being read, drops density
  // that the unskipped march keeps.
  auto mapper = CloudMapper(0.03);
  GpuScene scene(mapper, 96, 96);
  scene.SetInput(DotsBetweenEmptyBricks(48));
  scene.Volume->RotateX(23.0);
  scene.Volume->RotateY(-37.0);
  SetRampMedium(scene.Property, 1.0, 0.6);
  const SkippingRenders r = RenderWithAndWithoutSkipping(mapper, scene, "skipping-dots");
  ASSERT_EQ(mapper->GetLastError(), "");
  std::cout << "mean opacity " << MeanOver(r.Full, 3, Columns(0, 96)) << ", samples "
            << r.AllSamples << " unskipped, " << r.Skipping[1].SamplesTaken << " skipped\n";
  ASSERT_GT(MeanOver(r.Full, 3, Columns(0, 96)), 0.1) << "an empty window proves nothing";
  ASSERT_LT(MeanOver(r.Full, 3, Columns(0, 96)), 0.9) << "an opaque window hides what is missed";
  for (int perRead = 1; perRead <= 4; ++perRead)
  {
    EXPECT_EQ(MaxDifference(r.Full, r.Skipped[perRead]), 0.0) << perRead << " per map read";
    EXPECT_LT(r.Skipping[perRead].SamplesTaken, 0.9 * r.AllSamples)
      << "the march must leap, " << perRead << " per map read";
  }
}

TEST(CloudVolumeMapper, DenseFieldsTakeFourSamplesPerMapReadSparseOnesOne)
{
  // The loop's variant follows the field's occupied-brick fraction (SamplesPerMapRead 0, the
  // default): the sparse cloud leaps often and reads the map before every sample, the dense field
  // rarely leaps and reads it every fourth sample.
  for (bool dense : { false, true })
  {
    auto mapper = CloudMapper(0.03);
    mapper->CollectStatisticsOn();
    GpuScene scene(mapper, 64, 64);
    scene.SetInput(dense ? DenseCloud(48) : SparseCloud(48));
    SetRampMedium(scene.Property, 1.0, 0.6);
    scene.RenderFloat();
    const auto& statistics = mapper->GetLastFrameStatistics();
    ASSERT_EQ(mapper->GetLastError(), "");
    EXPECT_EQ(statistics.SamplesPerMapRead, dense ? 4 : 1)
      << (dense ? "dense" : "sparse") << ", occupied " << statistics.OccupiedBrickFraction;
  }
}

TEST(CloudVolumeMapper, HalvingTheStepBarelyChangesTheImage)
{
  auto mapper = CloudMapper(0.02);
  GpuScene scene(mapper);
  scene.ShowSparseCloud(64);
  const Image coarse = scene.RenderFloat();
  mapper->SetSampleDistance(0.01);
  const Image fine = scene.RenderFloat();
  // Extinction is per unit length and in-scattering is integrated per step, so only the
  // quadrature error of the density along the ray remains: well under 1 8-bit level RMS.
  EXPECT_LT(RmsDifference(coarse, fine), 1.0);
}

#include <vtkActor.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>

namespace
{
void AddOpaqueSphere(GpuScene& scene, double x, double y, double z, double radius)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(x, y, z);
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(1.0, 0.0, 0.0);
  actor->GetProperty()->LightingOff();
  scene.Renderer->AddActor(actor);
}

int PixelOf(const Image& image, double world, double parallelScale, int size)
{
  return int(std::lround((world / parallelScale * 0.5 + 0.5) * size - 0.5));
  (void)image;
}
}

TEST(CloudVolumeMapper, OpaqueGeometryOccludesAndIsOccludedThroughTheDepthBuffer)
{
  // A white slab of constant density over z in [-1, 1]; red spheres of radius 0.3 poking out of
  // its front face, centred inside it, and poking out of its back face. With no light model the
  // green channel is the cloud's opacity in front of whatever the ray hits.
  auto mapper = CloudMapper(0.005);
  GpuScene scene(mapper, 128, 128);
  scene.SetInput(ConstantBox(1.0, 96));
  const double sigma = std::log(2.0) / 0.5;
  SetUniformMedium(scene.Property, 0.5, 0.5);
  AddOpaqueSphere(scene, -0.6, 0.0, 1.0, 0.3);
  AddOpaqueSphere(scene, 0.0, 0.6, 0.0, 0.3);
  AddOpaqueSphere(scene, 0.6, 0.0, -1.0, 0.3);
  const Image image = scene.Render();
  Dump(image, "depth");
  const auto green = [&](double x, double y)
  { return image.At(PixelOf(image, x, 2.2, 128), PixelOf(image, y, 2.2, 128), 1); };
  const auto red = [&](double x, double y)
  { return image.At(PixelOf(image, x, 2.2, 128), PixelOf(image, y, 2.2, 128), 0); };
  EXPECT_NEAR(green(-0.6, 0.0), 0.0, 0.02) << "a sphere in front of the cloud is not covered";
  EXPECT_NEAR(red(-0.6, 0.0), 1.0, 0.02);
  EXPECT_NEAR(green(0.0, 0.6), 1.0 - std::exp(-sigma * 0.7), 0.03) << "0.7 of cloud in front";
  EXPECT_NEAR(green(0.6, 0.0), 1.0 - std::exp(-sigma * 1.7), 0.03) << "1.7 of cloud in front";
  EXPECT_NEAR(green(0.0, -0.6), 1.0 - std::exp(-sigma * 2.0), 0.03) << "the whole slab";
}

TEST(CloudVolumeMapper, CameraInsideTheVolumeSeesTheCloudAroundIt)
{
  auto mapper = CloudMapper(0.005);
  GpuScene scene(mapper, 64, 64);
  scene.SetInput(ConstantBox(1.5, 96));
  SetUniformMedium(scene.Property, 0.5, 0.5);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetParallelProjection(false);
  camera->SetPosition(0.0, 0.0, 0.0);
  camera->SetFocalPoint(0.0, 0.0, -1.0);
  camera->SetClippingRange(0.1, 10.0);
  const Image image = scene.RenderFloat();
  // From the near plane at z = -0.1 to the box face at z = -1.5.
  const double expected = 1.0 - std::exp(-std::log(2.0) / 0.5 * 1.4);
  EXPECT_NEAR(image.At(32, 32, 3), expected, 0.01 * expected);
}

TEST(CloudVolumeMapper, ResizingTheWindowRendersAtTheNewSize)
{
  auto mapper = CloudMapper(0.02);
  GpuScene scene(mapper, 96, 64);
  scene.ShowSparseCloud(64);
  scene.Render();
  scene.Window->SetSize(128, 96);
  const Image resized = scene.Render();
  ASSERT_EQ(resized.Width, 128);
  ASSERT_EQ(resized.Height, 96);

  auto fresh = CloudMapper(0.02);
  GpuScene reference(fresh, 128, 96);
  reference.ShowSparseCloud(64);
  EXPECT_LT(RmsDifference(resized, reference.Render()), 0.5);
}

TEST(CloudVolumeMapper, OneMapperDrawsTwoViewportsOfAWindow)
{
  auto mapper = CloudMapper(0.02);
  GpuScene scene(mapper, 256, 128);
  scene.ShowSparseCloud(64);
  scene.Renderer->SetViewport(0.0, 0.0, 0.5, 1.0);
  vtkNew<vtkRenderer> right;
  right->SetViewport(0.5, 0.0, 1.0, 1.0);
  right->SetActiveCamera(scene.Renderer->GetActiveCamera());
  right->AddVolume(scene.Volume);
  scene.Window->AddRenderer(right);
  const Image both = scene.Render();
  Dump(both, "viewports");

  auto single = CloudMapper(0.02);
  GpuScene reference(single, 128, 128);
  reference.ShowSparseCloud(64);
  const Image one = reference.Render();
  for (int half = 0; half < 2; ++half)
  {
    const Image part = Crop(both, Region{ half * 128, 0, 128, 128 });
    EXPECT_LT(RmsDifference(part, one), 0.5) << "viewport " << half;
  }
}

TEST(CloudVolumeMapper, AccumulationAveragesJitteredFramesUntilTheViewChanges)
{
  auto reference = CloudMapper(0.002);
  GpuScene fine(reference, 96, 96);
  fine.ShowSparseCloud(64);
  const Image truth = fine.RenderFloat();

  auto mapper = vtkSmartPointer<vtkCloudVolumeMapper>::New();
  mapper->SetSampleDistance(0.05);
  mapper->JitterOn();
  mapper->SetMaximumAccumulatedFrames(16);
  GpuScene scene(mapper, 96, 96);
  scene.ShowSparseCloud(64);
  const Image first = scene.RenderFloat();
  Image accumulated;
  for (int i = 1; i < 16; ++i)
  {
    accumulated = scene.RenderFloat();
  }
  EXPECT_EQ(mapper->GetNumberOfAccumulatedFrames(scene.Renderer), 16);
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetNumberOfAccumulatedFrames(scene.Renderer), 16) << "converged: no more";
  Dump(first, "jitter-1-frame");
  Dump(accumulated, "jitter-16-frames");
  EXPECT_LT(RmsDifference(accumulated, truth), 0.5 * RmsDifference(first, truth));

  scene.Renderer->GetActiveCamera()->Azimuth(5.0);
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetNumberOfAccumulatedFrames(scene.Renderer), 1) << "a camera move restarts";
  scene.RenderFloat();
  ASSERT_EQ(mapper->GetNumberOfAccumulatedFrames(scene.Renderer), 2);
  mapper->GetLightingProperty()->SetAmbientStrength(0.5f);
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetNumberOfAccumulatedFrames(scene.Renderer), 1)
    << "a change of the lighting property restarts";
}

// The frame limit is no part of what a frame marches: a noise target (app/export NoiseTarget.h)
// stops an accumulation by lowering the limit to the frames averaged, and the image must stay the
// one it measured, not restart; a raised limit goes on from there.
TEST(CloudVolumeMapper, ChangingTheFrameLimitKeepsTheAccumulation)
{
  auto mapper = vtkSmartPointer<vtkCloudVolumeMapper>::New();
  mapper->SetSampleDistance(0.05);
  mapper->JitterOn();
  mapper->SetMaximumAccumulatedFrames(16);
  GpuScene scene(mapper, 64, 64);
  scene.ShowSparseCloud(48);
  Image measured;
  for (int i = 0; i < 3; ++i)
  {
    measured = scene.RenderFloat();
  }
  ASSERT_EQ(mapper->GetNumberOfAccumulatedFrames(scene.Renderer), 3);
  mapper->SetMaximumAccumulatedFrames(3);
  const Image kept = scene.RenderFloat();
  EXPECT_EQ(mapper->GetNumberOfAccumulatedFrames(scene.Renderer), 3)
    << "a limit at the frames averaged stops there";
  EXPECT_EQ(RmsDifference(kept, measured), 0.0) << "and keeps their image";
  mapper->SetMaximumAccumulatedFrames(5);
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetNumberOfAccumulatedFrames(scene.Renderer), 4) << "a raised limit goes on";
}

TEST(CloudVolumeMapper, InteractionLowersTheResolutionAndStillnessRestoresIt)
{
  auto mapper = CloudMapper(0.02);
  GpuScene scene(mapper, 200, 160);
  scene.ShowSparseCloud(64);
  scene.Window->SetDesiredUpdateRate(1000.0); // what an interactor asks while dragging
  const Image moving = scene.RenderFloat();
  EXPECT_LT(moving.Width, 200);
  EXPECT_GE(moving.Width, 50);
  scene.Window->SetDesiredUpdateRate(0.0001); // the still rate at the end of interaction
  const Image still = scene.RenderFloat();
  EXPECT_EQ(still.Width, 200);
  EXPECT_EQ(still.Height, 160);
}

TEST(CloudVolumeMapper, SampleCountViewShowsTheCostOfEachRay)
{
  auto mapper = CloudMapper(0.02);
  GpuScene scene(mapper, 96, 96);
  scene.ShowSparseCloud(64);
  mapper->SetDisplayMode(vtkCloudVolumeMapper::SampleCount);
  const Image counts = scene.Render();
  Dump(counts, "sample-count");
  // Rays through the cloud's middle sample more than rays that miss the bound: the ramp runs
  // from blue (no samples) toward red.
  const auto warmth = [&](int x, int y) { return counts.At(x, y, 0) - counts.At(x, y, 2); };
  EXPECT_EQ(warmth(2, 2), -1.0f);
  EXPECT_GT(warmth(48, 48), warmth(2, 2) + 0.2f);
}

#include <vtkFloatArray.h>
#include <vtkPointData.h>

namespace
{
// Renders a field that the mapper must refuse and returns the error it gives; the window must
// stay the background color.
std::string RefusalOf(vtkImageData* field, double step = 0.02, bool emptyOpacity = false)
{
  auto mapper = CloudMapper(step);
  GpuScene scene(mapper, 32, 32);
  scene.SetInput(field);
  SetRampMedium(scene.Property, 1.0, 0.6);
  if (emptyOpacity)
  {
    vtkNew<vtkPiecewiseFunction> none;
    scene.Property->SetScalarOpacity(none);
  }
  const Image image = scene.Render();
  EXPECT_EQ(Largest(image, 3), 0.0) << "nothing may be drawn from bad input";
  return mapper->GetLastError();
}
}

TEST(CloudVolumeMapper, RefusesBadInputWithAReason)
{
  vtkNew<vtkImageData> noScalars;
  noScalars->SetDimensions(8, 8, 8);
  EXPECT_NE(RefusalOf(noScalars).find("no scalar array"), std::string::npos);

  // AllocateScalars leaves the values as the heap had them: in a fresh process (one test per
  // process under ctest) zeros, but deep in one long process sometimes NaN, which the mapper
  // rightly refuses first. Each field is filled, so the refusal tested is the one named.
  vtkNew<vtkImageData> vectors;
  vectors->SetDimensions(8, 8, 8);
  vectors->AllocateScalars(VTK_FLOAT, 3);
  vectors->GetPointData()->GetScalars()->Fill(0.0);
  EXPECT_NE(RefusalOf(vectors).find("3 components"), std::string::npos);

  vtkNew<vtkImageData> tooLong;
  tooLong->SetDimensions(70000, 2, 2);
  tooLong->AllocateScalars(VTK_FLOAT, 1);
  tooLong->GetPointData()->GetScalars()->Fill(0.0);
  EXPECT_NE(RefusalOf(tooLong).find("(70000 x 2 x 2 voxels of R32F) needs a 3-D texture of 70000 x "
                                    "2 x 2 texels; this GPU's 3-D textures hold at most"),
    std::string::npos);

  auto field = SparseCloud(16);
  EXPECT_NE(RefusalOf(field, -0.5).find("sample distance"), std::string::npos);
  EXPECT_NE(RefusalOf(field, 0.02, true).find("transfer function"), std::string::npos);
}

TEST(CloudVolumeMapper, AuxiliaryChannelsGiveTheCloudsDepthAndSampleCounts)
{
  // A slab from z = 1 down to z = -1, camera at z = 6 with the near plane at 0.1: the cloud's
  // opacity passes 2% just behind its front face, 4.9 from the near plane.
  auto mapper = CloudMapper(0.005);
  GpuScene scene(mapper, 32, 32);
  scene.SetInput(ConstantBox(1.0, 64));
  SetUniformMedium(scene.Property, 0.5, 0.5);
  scene.RenderFloat();
  std::vector<float> channels;
  int w = 0, h = 0;
  ASSERT_TRUE(mapper->ReadAuxiliary(scene.Renderer, channels, w, h));
  const float* centre = &channels[(size_t(16) * w + 16) * 4];
  // useful: 2 units of slab at step 0.005, give or take the faces blurred over a voxel (0.0635)
  EXPECT_NEAR(centre[1], 400.0f, 13.0f);
  EXPECT_GE(centre[0], centre[1]); // taken: also the empty part of the slab's face bricks
  EXPECT_NEAR(centre[2], 4.9f, 0.05f);
  EXPECT_TRUE(std::isinf(channels[2])) << "no cloud in the corner: infinite depth";
}
