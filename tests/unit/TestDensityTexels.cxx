// How a field is stored as texels (CloudDensityTexels.h), as the GPU mapper uploads it and the
// CPU reference samples it: each scalar type's format, scale and bias, the half-float
// conversion (exact rounding and its documented error bound), and DensityAt reading normalized
// texels back in the data's units.
#include "CloudDensityTexels.h"
#include "CloudReferenceMarch.h"

#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedShortArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace cloudvis;

namespace
{
vtkSmartPointer<vtkFloatArray> Floats(const std::vector<float>& values)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetNumberOfTuples(vtkIdType(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    array->SetValue(vtkIdType(i), values[i]);
  }
  return array;
}
}

TEST(DensityTexels, EachTypeKeepsItsNativeFormatWithAScaleToItsUnits)
{
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetNumberOfTuples(2);
  const DensityTexels b = DensityTexelsOf(bytes);
  EXPECT_EQ(b.Format, TexelFormat::UNorm8);
  EXPECT_EQ(BytesPerTexel(b.Format), 1);
  EXPECT_EQ(b.Scale, 255.0f);
  EXPECT_EQ(b.Bias, 0.0f);
  EXPECT_EQ(b.Values, bytes->GetVoidPointer(0));

  vtkNew<vtkUnsignedShortArray> shorts;
  shorts->SetNumberOfTuples(2);
  const DensityTexels s = DensityTexelsOf(shorts, true); // half floats are for float fields
  EXPECT_EQ(s.Format, TexelFormat::UNorm16);
  EXPECT_EQ(BytesPerTexel(s.Format), 2);
  EXPECT_EQ(s.Scale, 65535.0f);

  const auto floats = Floats({ 0.5f, -3.0f });
  const DensityTexels f = DensityTexelsOf(floats);
  EXPECT_EQ(f.Format, TexelFormat::Float32);
  EXPECT_EQ(BytesPerTexel(f.Format), 4);
  EXPECT_EQ(f.Scale, 1.0f);
  EXPECT_EQ(f.Values, floats->GetVoidPointer(0));
}

TEST(DensityTexels, HalfFloatsAreScaledByThePowerOfTwoAtOrAboveTheLargestMagnitude)
{
  const DensityTexels h = DensityTexelsOf(Floats({ 0.5f, -3.0f, 1.0f }), true);
  EXPECT_EQ(h.Format, TexelFormat::Float16);
  EXPECT_EQ(BytesPerTexel(h.Format), 2);
  EXPECT_EQ(h.Scale, 4.0f);
  EXPECT_EQ(DensityTexelsOf(Floats({ 4.0f }), true).Scale, 4.0f);
  EXPECT_EQ(DensityTexelsOf(Floats({ 0.3f }), true).Scale, 0.5f);
  EXPECT_EQ(DensityTexelsOf(Floats({ 1e6f }), true).Scale, 1048576.0f); // beyond 65504: scaled
  EXPECT_EQ(DensityTexelsOf(Floats({ 0.0f }), true).Scale, 1.0f);
}

TEST(DensityTexels, HalfFromFloatRoundsToNearestEven)
{
  EXPECT_EQ(HalfFromFloat(1.0f), 0x3c00);
  EXPECT_EQ(HalfFromFloat(-2.0f), 0xc000);
  EXPECT_EQ(HalfFromFloat(0.0f), 0x0000);
  EXPECT_EQ(HalfFromFloat(-0.0f), 0x8000);
  EXPECT_EQ(HalfFromFloat(65504.0f), 0x7bff); // the largest half
  EXPECT_EQ(HalfFromFloat(65519.0f), 0x7bff); // below the halfway point
  EXPECT_EQ(HalfFromFloat(65520.0f), 0x7c00); // halfway, to even: infinity
  EXPECT_EQ(HalfFromFloat(INFINITY), 0x7c00);
  EXPECT_TRUE(std::isnan(FloatFromHalf(HalfFromFloat(NAN))));
  EXPECT_EQ(HalfFromFloat(std::ldexp(1.0f, -14)), 0x0400);        // the smallest normal
  EXPECT_EQ(HalfFromFloat(std::ldexp(1.0f, -24)), 0x0001);        // the smallest subnormal
  EXPECT_EQ(HalfFromFloat(std::ldexp(1.0f, -25)), 0x0000);        // halfway to it, to even: zero
  EXPECT_EQ(HalfFromFloat(std::ldexp(3.0f, -25)), 0x0002);        // 1.5 subnormals, to even: 2
  EXPECT_EQ(HalfFromFloat(1.0f + std::ldexp(1.0f, -11)), 0x3c00); // halfway, to even
  EXPECT_EQ(HalfFromFloat(1.0f + std::ldexp(3.0f, -11)), 0x3c02); // halfway, to even
  EXPECT_EQ(HalfFromFloat(1.0f + std::ldexp(1.0f, -10)), 0x3c01);
}

TEST(DensityTexels, EveryHalfConvertsBackToItself)
{
  for (std::uint32_t h = 0; h < 0x10000; ++h)
  {
    const float f = FloatFromHalf(std::uint16_t(h));
    if (std::isnan(f))
    {
      continue;
    }
    ASSERT_EQ(HalfFromFloat(f), h) << std::hex << h;
  }
}

TEST(DensityTexels, HalfFloatErrorIsWithinTheDocumentedBound)
{
  // Relative 2^-11 down to 2^-14 of the scale, absolute 2^-25 of it below.
  std::mt19937 random(7);
  std::uniform_real_distribution<float> exponent(-30.0f, 0.0f);
  double worstRelative = 0.0, worstAbsolute = 0.0;
  for (int i = 0; i < 200000; ++i)
  {
    const float x = std::exp2(exponent(random));
    const double error = std::abs(double(FloatFromHalf(HalfFromFloat(x))) - double(x));
    if (x >= std::ldexp(1.0f, -14))
    {
      worstRelative = std::max(worstRelative, error / x);
    }
    else
    {
      worstAbsolute = std::max(worstAbsolute, error);
    }
  }
  EXPECT_LE(worstRelative, std::ldexp(1.0, -11));
  EXPECT_GT(worstRelative, std::ldexp(1.0, -12)); // the bound is reached, not loose
  EXPECT_LE(worstAbsolute, std::ldexp(1.0, -25));
}

TEST(DensityTexels, DensityAtInterpolatesNormalizedTexelsThenScales)
{
  // Two voxels along x, texels 51 and 204 of 255, scale 2 and bias 1 (as a shader would read
  // them): the density halfway is 2 * (51 + 204) / 2 / 255 + 1.
  const std::vector<std::uint8_t> texels = { 51, 204, 51, 204, 51, 204, 51, 204 };
  MarchUniforms u;
  u.Dimensions = glm::ivec3(2);
  u.Density.Format = TexelFormat::UNorm8;
  u.Density.Scale = 2.0f;
  u.Density.Bias = 1.0f;
  u.Density.Values = texels.data();
  EXPECT_FLOAT_EQ(DensityAt(u, glm::vec3(0.0f)), 2.0f * 51.0f / 255.0f + 1.0f);
  EXPECT_FLOAT_EQ(DensityAt(u, glm::vec3(0.5f, 0.0f, 0.0f)), 2.0f * 127.5f / 255.0f + 1.0f);
  EXPECT_FLOAT_EQ(DensityAt(u, glm::vec3(1.0f, 1.0f, 1.0f)), 2.0f * 204.0f / 255.0f + 1.0f);

  const std::vector<std::uint16_t> shorts = { 0, 65535, 0, 65535, 0, 65535, 0, 65535 };
  u.Density.Format = TexelFormat::UNorm16;
  u.Density.Scale = 65535.0f;
  u.Density.Bias = 0.0f;
  u.Density.Values = shorts.data();
  EXPECT_FLOAT_EQ(DensityAt(u, glm::vec3(0.25f, 0.5f, 0.5f)), 0.25f * 65535.0f);
}
