// cloudvis::SetUpMarch, where the GPU mapper and the CPU reference get their uniforms: the local
// frame (centred on the volume, a power-of-two unit, exact under power-of-two scaling), the
// geometry it reads (extent start, direction, volume matrix) and every refusal, with the words
// both renderers use.
#include "CloudMarchUniforms.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

using namespace cloudvis;

namespace
{
// sigma_t rising from 0 at density 0 to `sigma_t` at density 1.
TransferTable LinearTable(float sigma_t)
{
  TransferTable table;
  table.Size = 2;
  table.RGBA = { 1.0f, 1.0f, 1.0f, 0.0f, 1.0f, 1.0f, 1.0f, sigma_t };
  return table;
}

// n^3 voxels of edge `spacing` from `origin`.
MarchSetup Cube(int n, double spacing, double origin = 0.0)
{
  MarchSetup setup;
  setup.Geometry.Dimensions = glm::ivec3(n);
  setup.Geometry.IndexToWorld = glm::dmat4(glm::dmat3(spacing));
  setup.Geometry.IndexToWorld[3] = glm::dvec4(glm::dvec3(origin), 1.0);
  return setup;
}

MarchProblem Problem(MarchSetup setup, const TransferTable& table = LinearTable(1.0f))
{
  setup.Table = &table;
  MarchUniforms u;
  return SetUpMarch(setup, u);
}

bool Mentions(const MarchProblem& p, const std::string& words)
{
  return p.Message.find(words) != std::string::npos;
}
}

TEST(MarchUniforms, TheLocalFrameIsCentredOnTheVolumeInUnitsOfAPowerOfTwo)
{
  const TransferTable table = LinearTable(1.0f);
  MarchSetup setup = Cube(11, 0.3, 1e10);
  setup.Table = &table;
  MarchUniforms u;
  LocalFrame frame;
  ASSERT_FALSE(SetUpMarch(setup, u, &frame));
  EXPECT_EQ(frame.Unit, 0.25);
  EXPECT_EQ(frame.Anchor, glm::dvec3(1e10 + 1.5));
  EXPECT_EQ(glm::vec3(u.IndexToLocal * glm::vec4(5.0f, 5.0f, 5.0f, 1.0f)), glm::vec3(0.0f))
    << "the centre voxel is at local 0, however far the volume is";
  EXPECT_NEAR(frame.LongestChord, std::sqrt(3.0) * 3.0 / 0.25, 1e-9);
  EXPECT_FLOAT_EQ(u.ExtinctionUnit, 0.25f);
  EXPECT_EQ(u.MaximumSamples, int(std::ceil(std::sqrt(3.0) * 10.0)) + 16);
}

TEST(MarchUniforms, APowerOfTwoScaleGivesTheSameUniforms)
{
  const TransferTable table = LinearTable(1.0f);
  MarchSetup small = Cube(9, 0.1, -0.4), large = Cube(9, 0.1 * 1024.0, -0.4 * 1024.0);
  small.Table = large.Table = &table;
  small.SampleDistance = 0.03;
  large.SampleDistance = 0.03 * 1024.0;
  small.Lights.emplace_back();
  small.Lights.back().Positional = true;
  small.Lights.back().Position = glm::dvec3(0.5, 1.0, 2.0);
  large.Lights = small.Lights;
  large.Lights.back().Position *= 1024.0;
  large.Lights.back().Attenuation.z /= 1024.0f * 1024.0f;
  MarchUniforms a, b;
  ASSERT_FALSE(SetUpMarch(small, a));
  ASSERT_FALSE(SetUpMarch(large, b));
  EXPECT_EQ(a.IndexToLocal, b.IndexToLocal);
  EXPECT_EQ(a.LocalToIndex, b.LocalToIndex);
  EXPECT_EQ(a.Step, b.Step);
  EXPECT_EQ(a.Lights[0].Position, b.Lights[0].Position);
  EXPECT_EQ(a.Lights[0].Attenuation, b.Lights[0].Attenuation);
  EXPECT_EQ(a.ExtinctionUnit * 1024.0f, b.ExtinctionUnit);
}

TEST(MarchUniforms, GeometryReadsTheExtentStartTheDirectionAndTheVolumeMatrix)
{
  vtkNew<vtkImageData> image;
  image->SetExtent(-10, 10, 0, 4, 3, 5);
  image->SetOrigin(1.0, 2.0, 3.0);
  image->SetSpacing(0.5, 0.25, 2.0);
  image->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1);
  vtkNew<vtkMatrix4x4> volume;
  volume->SetElement(0, 3, 100.0);
  const VolumeGeometry g = GeometryOf(image, volume);
  EXPECT_EQ(g.Dimensions, glm::ivec3(21, 5, 3));
  // p = 0 is index (-10, 0, 3): physical origin + D (-5, 0, 6) = (1, 2 - 5, 3 + 6), then moved.
  const glm::dvec3 first(g.IndexToWorld * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  EXPECT_EQ(first, glm::dvec3(101.0, -3.0, 9.0));
  // One step along i goes 0.5 along +y (the direction's first column).
  EXPECT_EQ(glm::dvec3(g.IndexToWorld[0]), glm::dvec3(0.0, 0.5, 0.0));
  double bounds[6];
  image->GetBounds(bounds); // VTK's own bounds agree (before the volume matrix)
  EXPECT_DOUBLE_EQ(bounds[2], -3.0);
  EXPECT_DOUBLE_EQ(bounds[4], 9.0);
}

// "Step 0 means one voxel": one voxel after the volume's placement, for the march and for the
// viewer's step keys alike (EffectiveSampleDistance). A volume scaled by 0.3 along x, with a
// direction matrix that turns its axes, has voxels 0.15 long where its image's spacing says 0.4:
// the viewer once took the spacing's 0.4 while the march took 0.15.
TEST(MarchUniforms, StepZeroIsOneVoxelAfterTheVolumesScaleAndDirection)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(8, 8, 8);
  image->SetSpacing(0.5, 0.4, 0.6);
  const double quarterTurn[9] = { 0, -1, 0, 1, 0, 0, 0, 0, 1 }; // x and y swapped, turned
  image->SetDirectionMatrix(quarterTurn);
  vtkNew<vtkMatrix4x4> volumeMatrix; // scale 0.3 along world x, which the image's y axis becomes
  volumeMatrix->SetElement(0, 0, 0.3);
  volumeMatrix->SetElement(2, 2, 2.0);
  const VolumeGeometry geometry = GeometryOf(image, volumeMatrix);
  EXPECT_DOUBLE_EQ(SmallestVoxelEdge(geometry), 0.12); // 0.4 * 0.3: the image's y turned to x
  const double* spacing = image->GetSpacing();
  ASSERT_GT(std::min({ spacing[0], spacing[1], spacing[2] }), 3.0 * SmallestVoxelEdge(geometry))
    << "a case where the image's spacing and the placed voxel disagree";

  const TransferTable table = LinearTable(1.0f);
  MarchSetup setup;
  setup.Geometry = geometry;
  setup.Table = &table;
  setup.SampleDistance = 0.0;
  MarchUniforms u;
  LocalFrame frame;
  ASSERT_FALSE(SetUpMarch(setup, u, &frame));
  EXPECT_NEAR(double(u.Step) * frame.Unit, EffectiveSampleDistance(geometry, 0.0), 1e-7)
    << "the march's step 0 is the one the viewer's step keys scale";
  EXPECT_DOUBLE_EQ(EffectiveSampleDistance(geometry, 0.0), 0.12);
  EXPECT_DOUBLE_EQ(EffectiveSampleDistance(geometry, 0.07), 0.07) << "a given step is itself";
}

TEST(MarchUniforms, AStepBeyondTheSampleCapIsRefusedWithTheSmallestAllowed)
{
  MarchSetup setup = Cube(2, 1.0); // a unit cube: its longest ray is sqrt(3)
  setup.SampleDistance = std::sqrt(3.0) / MaxSamplesPerRay * 0.999;
  const MarchProblem p = Problem(setup);
  EXPECT_EQ(p.Input, MarchInput::Step);
  EXPECT_TRUE(Mentions(p, "the most is 65536: use a step of at least 2.64293e-05")) << p.Message;
  setup.SampleDistance = std::sqrt(3.0) / MaxSamplesPerRay * 1.001;
  EXPECT_FALSE(Problem(setup)) << "just above the limit";
  setup.SampleDistance = -1.0;
  EXPECT_EQ(Problem(setup).Input, MarchInput::Step);
}

TEST(MarchUniforms, LightsAreRefusedBeyondEightAndBeyondFloatRange)
{
  MarchSetup setup = Cube(8, 0.1);
  setup.Lighting.Model = LightingModel::March;
  setup.Lights.resize(9);
  MarchProblem p = Problem(setup);
  EXPECT_EQ(p.Input, MarchInput::Light);
  EXPECT_TRUE(Mentions(p, "9 lights; the renderers take at most 8")) << p.Message;

  setup.Lights.resize(2);
  setup.Lights[1].Intensity = 1e38f;
  p = Problem(setup);
  EXPECT_EQ(p.Light, 1);
  EXPECT_TRUE(Mentions(p, "lower its intensity")) << p.Message;
  setup.Lighting.Model = LightingModel::None; // lights unused
  EXPECT_FALSE(Problem(setup));
  setup.Lighting.Model = LightingModel::Derivative;

  setup.Lights[1] = Light();
  setup.Lights[1].Positional = true;
  setup.Lights[1].Position = glm::dvec3(1e30, 0.0, 0.0);
  p = Problem(setup);
  EXPECT_EQ(p.Light, 1);
  EXPECT_TRUE(Mentions(p, "too far for float arithmetic")) << p.Message;

  // A directional light may be as far as it likes: only its direction counts.
  setup.Lights[1] = Light();
  setup.Lights[1].Position = glm::dvec3(1e300, 2e300, 0.0);
  MarchUniforms u;
  const TransferTable table = LinearTable(1.0f);
  setup.Table = &table;
  ASSERT_FALSE(SetUpMarch(setup, u));
  EXPECT_FLOAT_EQ(u.Lights[1].Direction.y, float(2.0 / std::sqrt(5.0)));

  setup.Lights[1].Position = setup.Lights[1].FocalPoint;
  EXPECT_TRUE(Mentions(Problem(setup), "has no direction"));
  setup.Lights[1].Position = glm::dvec3(std::nan(""), 0.0, 0.0);
  EXPECT_TRUE(Mentions(Problem(setup), "must be finite"));
}

TEST(MarchUniforms, ExtinctionsAndDensitySpansBeyondFloatRangeAreRefused)
{
  const MarchSetup setup = Cube(8, 1.0);
  const MarchProblem infinite = Problem(setup, LinearTable(INFINITY));
  EXPECT_EQ(infinite.Input, MarchInput::TransferFunction);
  EXPECT_TRUE(Mentions(infinite, "raise the unit distance")) << infinite.Message;
  const MarchProblem deep = Problem(setup, LinearTable(1e37f));
  EXPECT_TRUE(Mentions(deep, "optical depth across the volume")) << deep.Message;
  TransferTable wide = LinearTable(1.0f);
  wide.Range[0] = -3e38;
  wide.Range[1] = 3e38;
  EXPECT_TRUE(Mentions(Problem(setup, wide), "beyond what float arithmetic holds"));
}

TEST(MarchUniforms, FlatOrNonFiniteGeometryIsRefused)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 4, 4);
  EXPECT_EQ(ValidateVolumeGeometry(image, nullptr), "");
  image->SetSpacing(1.0, 0.0, 1.0);
  EXPECT_NE(ValidateVolumeGeometry(image, nullptr).find("spacing (1, 0, 1)"), std::string::npos);
  image->SetSpacing(1.0, 1.0, 1.0);
  image->SetOrigin(INFINITY, 0.0, 0.0);
  EXPECT_NE(ValidateVolumeGeometry(image, nullptr).find("origin (inf, 0, 0)"), std::string::npos);
  image->SetOrigin(0.0, 0.0, 0.0);
  image->SetDirectionMatrix(1, 2, 3, 2, 4, 6, 0, 0, 1);
  EXPECT_NE(
    ValidateVolumeGeometry(image, nullptr).find("direction matrix is singular"), std::string::npos);
  image->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
  vtkNew<vtkMatrix4x4> projective;
  projective->SetElement(3, 2, 1.0);
  EXPECT_NE(ValidateVolumeGeometry(image, projective).find("projective"), std::string::npos);

  MarchSetup flat = Cube(8, 1.0);
  flat.Geometry.Dimensions.z = 1;
  EXPECT_EQ(Problem(flat).Input, MarchInput::Geometry);
}
