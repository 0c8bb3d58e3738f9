// The transfer table every renderer reads: extinction from opacity per unit length, the CPU
// copy of the GPU's linear lookup, the conservative range maximum that empty-space skipping
// relies on, and the validation messages people see.
#include "CloudTransferTable.h"

#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPiecewiseFunction.h>
#include <vtkScalarsToColors.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace cloudvis;

namespace
{
const double UnitRange[2] = { 0.0, 1.0 };

// A table whose entries are known exactly: entry i is (i, 2i, 3i, 10i) / 10.
TransferTable KnownTable(int size, double lo, double hi)
{
  TransferTable table;
  table.Range[0] = lo;
  table.Range[1] = hi;
  table.Size = size;
  for (int i = 0; i < size; ++i)
  {
    table.RGBA.insert(table.RGBA.end(), { i / 10.0f, 2 * i / 10.0f, 3 * i / 10.0f, float(i) });
  }
  return table;
}

// A color map that returns one fixed color: lets a test hand the validator colors that VTK's
// own maps (which go through 8-bit tables) can never produce.
class FixedColor : public vtkScalarsToColors
{
public:
  static FixedColor* New();
  vtkTypeMacro(FixedColor, vtkScalarsToColors);
  void GetColor(double, double rgb[3]) override
  {
    rgb[0] = this->RGB[0];
    rgb[1] = this->RGB[1];
    rgb[2] = this->RGB[2];
  }
  double RGB[3] = { 0.5, 0.5, 0.5 };
};
vtkStandardNewMacro(FixedColor);

glm::vec4 Entry(const TransferTable& table, int i)
{
  const float* e = &table.RGBA[std::size_t(i) * 4];
  return glm::vec4(e[0], e[1], e[2], e[3]);
}

// What GL_LINEAR with GL_CLAMP_TO_EDGE returns (exact weights) at texture coordinate s.
glm::vec4 GlLinearFetch(const TransferTable& table, double s)
{
  const double x = std::min(std::max(s * table.Size - 0.5, 0.0), double(table.Size - 1));
  const int i0 = std::min(int(std::floor(x)), table.Size - 1);
  const int i1 = std::min(i0 + 1, table.Size - 1);
  const float f = float(x - i0);
  return Entry(table, i0) * (1.0f - f) + Entry(table, i1) * f;
}

void ExpectNear(const glm::vec4& a, const glm::vec4& b, float tolerance = 1e-5f)
{
  for (int c = 0; c < 4; ++c)
  {
    EXPECT_NEAR(a[c], b[c], tolerance) << "component " << c;
  }
}
}

TEST(TransferTable, ExtinctionIsMinusLogOneMinusOpacityPerUnitLength)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.5);
  opacity->AddPoint(1.0, 0.5);
  const TransferTable table = BuildTransferTable(nullptr, opacity, 2.0, UnitRange, 16);
  ASSERT_EQ(table.Size, 16);
  ASSERT_EQ(table.RGBA.size(), 64u);
  for (int i = 0; i < table.Size; ++i)
  {
    EXPECT_NEAR(table.RGBA[4 * i + 3], std::log(2.0) / 2.0, 1e-7);
  }
  // Composited over one unit distance, sigma_t gives back the opacity the user set.
  EXPECT_NEAR(1.0 - std::exp(-table.Lookup(0.3).a * 2.0), 0.5, 1e-6);

  const TransferTable scaled = BuildTransferTable(nullptr, opacity, 2.0, UnitRange, 16, 3.0);
  EXPECT_NEAR(scaled.RGBA[3], 3.0 * std::log(2.0) / 2.0, 1e-6);
}

TEST(TransferTable, FullOpacityGivesAFiniteExtinction)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 1.0);
  const TransferTable table = BuildTransferTable(nullptr, opacity, 0.5, UnitRange, 4);
  ASSERT_EQ(table.Size, 4);
  EXPECT_TRUE(std::isfinite(table.RGBA[3]));
  EXPECT_NEAR(table.RGBA[3], -std::log(1e-4) / 0.5, 1e-3);
}

TEST(TransferTable, EntriesSampleColorAndOpacityFromRangeStartToEnd)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(10.0, 0.0);
  opacity->AddPoint(20.0, 0.8);
  vtkNew<vtkLookupTable> color;
  color->SetTableRange(10.0, 20.0);
  color->SetHueRange(0.0, 0.66);
  color->Build();
  const double range[2] = { 10.0, 20.0 };
  const TransferTable table = BuildTransferTable(color, opacity, 1.0, range, 11);
  ASSERT_EQ(table.Size, 11);
  for (int i = 0; i < table.Size; ++i)
  {
    const double density = 10.0 + i;
    double rgb[3];
    color->GetColor(density, rgb);
    const double a = opacity->GetValue(density);
    EXPECT_FLOAT_EQ(table.RGBA[4 * i + 0], float(rgb[0]));
    EXPECT_FLOAT_EQ(table.RGBA[4 * i + 1], float(rgb[1]));
    EXPECT_FLOAT_EQ(table.RGBA[4 * i + 2], float(rgb[2]));
    EXPECT_NEAR(table.RGBA[4 * i + 3], -std::log(1.0 - a), 1e-6);
  }
  EXPECT_EQ(table.RGBA[3], 0.0f);

  // No color means white albedo.
  const TransferTable white = BuildTransferTable(nullptr, opacity, 1.0, range, 11);
  for (int i = 0; i < white.Size; ++i)
  {
    EXPECT_EQ(white.RGBA[4 * i + 0], 1.0f);
    EXPECT_EQ(white.RGBA[4 * i + 1], 1.0f);
    EXPECT_EQ(white.RGBA[4 * i + 2], 1.0f);
  }
}

TEST(TransferTable, RefusesArgumentsItCannotSample)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.5);
  const double reversed[2] = { 1.0, 0.0 };
  EXPECT_EQ(BuildTransferTable(nullptr, opacity, 0.0, UnitRange).Size, 0);
  EXPECT_EQ(BuildTransferTable(nullptr, opacity, -1.0, UnitRange).Size, 0);
  EXPECT_EQ(BuildTransferTable(nullptr, opacity, 1.0, reversed).Size, 0);
  EXPECT_EQ(BuildTransferTable(nullptr, opacity, 1.0, UnitRange, 0).Size, 0);
  EXPECT_EQ(BuildTransferTable(nullptr, opacity, 1.0, UnitRange).Size, 1024);
}

TEST(TransferTable, LookupReadsEntriesAtTheirDensitiesAndInterpolatesBetween)
{
  const TransferTable table = KnownTable(5, 2.0, 6.0); // entries at densities 2, 3, 4, 5, 6
  for (int i = 0; i < 5; ++i)
  {
    ExpectNear(table.Lookup(2.0 + i), Entry(table, i));
  }
  ExpectNear(table.Lookup(3.5), 0.5f * (Entry(table, 1) + Entry(table, 2)));
  ExpectNear(table.Lookup(5.25), 0.75f * Entry(table, 3) + 0.25f * Entry(table, 4));
}

TEST(TransferTable, LookupMatchesTheGpuFetchAtTexelCentres)
{
  const TransferTable table = KnownTable(7, -1.0, 2.5);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 2.5);
  for (int n = 0; n < 1000; ++n)
  {
    const double density = u(rng);
    const double t = (density - table.Range[0]) / (table.Range[1] - table.Range[0]);
    const double s = (t * (table.Size - 1) + 0.5) / table.Size; // the mapper's remap
    ExpectNear(table.Lookup(density), GlLinearFetch(table, s), 1e-4f);
  }
}

TEST(TransferTable, LookupClampsOutsideTheRange)
{
  const TransferTable table = KnownTable(5, 2.0, 6.0);
  ExpectNear(table.Lookup(-100.0), Entry(table, 0));
  ExpectNear(table.Lookup(1.999), Entry(table, 0));
  ExpectNear(table.Lookup(6.001), Entry(table, 4));
  ExpectNear(table.Lookup(1e30), Entry(table, 4));
  ExpectNear(table.Lookup(std::numeric_limits<double>::quiet_NaN()), Entry(table, 0));
  ExpectNear(TransferTable().Lookup(0.5), glm::vec4(0.0f));
}

namespace
{
// 64 entries over [-0.5, 1.5] whose extinction is `extreme` every 9th entry and random in
// [1, 10] (or 0) elsewhere, and 2000 random intervals in [-1, 2]: bound(a, b) is symmetric and
// holds for 41 lookups across [a, b], above (upper) or below. Returns how many bounds are > 0.
int ExpectBoundHolds(bool upper, unsigned seed)
{
  TransferTable table;
  table.Range[0] = -0.5;
  table.Range[1] = 1.5;
  table.Size = 64;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> sigma(1.0f, 10.0f);
  for (int i = 0; i < table.Size; ++i)
  {
    // Isolated spikes in a transparent table (for the upper bound) or holes in an opaque one
    // (for the lower): the cases where missing a bracket entry shows.
    const bool isolated = i % 9 == 0;
    const float s = upper ? (isolated ? sigma(rng) : 0.0f) : (isolated ? 0.0f : sigma(rng));
    table.RGBA.insert(table.RGBA.end(), { 1.0f, 1.0f, 1.0f, s });
  }
  const auto bound = [&](double a, double b) {
    return upper ? table.MaxExtinction(a, b) : table.MinExtinction(a, b);
  };
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  int positive = 0;
  for (int n = 0; n < 2000; ++n)
  {
    const double a = u(rng), b = u(rng);
    const float value = bound(a, b);
    EXPECT_EQ(value, bound(b, a));
    EXPECT_LE(table.MinExtinction(a, b), table.MaxExtinction(a, b));
    positive += value > 0.0f;
    for (int k = 0; k <= 40; ++k)
    {
      const double density = a + (b - a) * k / 40.0;
      const float sigma_t = table.Lookup(density).a;
      if (upper)
        EXPECT_LE(sigma_t, value) << "density " << density << " in [" << a << ", " << b << "]";
      else
        EXPECT_GE(sigma_t, value) << "density " << density << " in [" << a << ", " << b << "]";
    }
  }
  // One density on an entry: both bounds are that entry.
  const double onEntry = table.Range[0] + 5.0 * (table.Range[1] - table.Range[0]) / 63.0;
  EXPECT_EQ(bound(onEntry, onEntry), table.RGBA[5 * 4 + 3]);
  return positive;
}
}

TEST(TransferTable, MaxExtinctionBoundsEveryLookupInTheInterval)
{
  EXPECT_GT(ExpectBoundHolds(true, 11), 100);
}

TEST(TransferTable, MinExtinctionBoundsEveryLookupInTheIntervalFromBelow)
{
  // The path tracer integrates this bound exactly and ratio-tracks the rest, so a bound above
  // one lookup would bias its transmittance. A bound of 0 everywhere would be useless, not
  // wrong: most intervals contain a hole, but not all.
  EXPECT_GT(ExpectBoundHolds(false, 12), 20);
  EXPECT_EQ(TransferTable().MinExtinction(0.0, 1.0), 0.0f);
}

TEST(TransferTable, MaxExtinctionIsZeroWhereTheOpacityIsZeroAroundTheInterval)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(0.5, 0.0);
  opacity->AddPoint(0.6, 1.0);
  opacity->AddPoint(1.0, 1.0);
  const TransferTable table = BuildTransferTable(nullptr, opacity, 1.0, UnitRange);
  EXPECT_EQ(table.MaxExtinction(0.0, 0.49), 0.0f);
  EXPECT_EQ(table.MaxExtinction(0.1, 0.4), 0.0f);
  EXPECT_EQ(table.MaxExtinction(-3.0, 0.2), 0.0f); // below the range reads entry 0
  EXPECT_GT(table.MaxExtinction(0.1, 0.55), 0.0f);
  EXPECT_GT(table.MaxExtinction(0.7, 0.7), 0.0f);
  EXPECT_GT(table.MaxExtinction(2.0, 3.0), 0.0f); // above the range reads the last entry
  EXPECT_EQ(TransferTable().MaxExtinction(0.0, 1.0), 0.0f);
}

TEST(TransferTable, TablesCompareByContent)
{
  const TransferTable a = KnownTable(4, 0.0, 1.0);
  TransferTable b = a;
  EXPECT_TRUE(a == b);
  b.RGBA[5] += 1.0f;
  EXPECT_TRUE(a != b);
  b = a;
  b.Range[1] = 2.0;
  EXPECT_TRUE(a != b);
}

TEST(ValidateTransferFunction, AcceptsAUsualPairAndANullColor)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(1.0, 0.3);
  vtkNew<vtkLookupTable> color;
  color->Build();
  EXPECT_EQ(ValidateTransferFunction(opacity, color), "");
  EXPECT_EQ(ValidateTransferFunction(opacity, nullptr), "");
}

TEST(ValidateTransferFunction, NamesTheProblem)
{
  EXPECT_EQ(ValidateTransferFunction(nullptr, nullptr), "no opacity transfer function");

  vtkNew<vtkPiecewiseFunction> empty;
  EXPECT_EQ(ValidateTransferFunction(empty, nullptr), "the opacity transfer function has no points");

  vtkNew<vtkPiecewiseFunction> tooOpaque;
  tooOpaque->AddPoint(0.0, 0.0);
  tooOpaque->AddPoint(0.25, 1.5);
  EXPECT_EQ(ValidateTransferFunction(tooOpaque, nullptr), "opacity 1.5 at density 0.25 is outside [0, 1]");

  vtkNew<vtkPiecewiseFunction> negative;
  negative->AddPoint(0.0, -0.1);
  EXPECT_EQ(ValidateTransferFunction(negative, nullptr), "opacity -0.1 at density 0 is outside [0, 1]");

  vtkNew<vtkPiecewiseFunction> notANumber;
  notANumber->AddPoint(0.0, 0.0);
  notANumber->AddPoint(1.0, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(ValidateTransferFunction(notANumber, nullptr), "opacity point 1 is not a number");

  // (Midpoint and sharpness outside [0, 1] are checked too, but vtkPiecewiseFunction already
  // refuses to store such points, so no test can build one.)

  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(1.0, 0.5);
  vtkNew<FixedColor> nanColor;
  nanColor->RGB[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ValidateTransferFunction(opacity, nanColor),
    "the color at density 0 is (0.5, nan, 0.5): each component must be a number in [0, 1]");
  vtkNew<FixedColor> tooBright;
  tooBright->RGB[2] = 1.25;
  EXPECT_EQ(ValidateTransferFunction(opacity, tooBright),
    "the color at density 0 is (0.5, 0.5, 1.25): each component must be a number in [0, 1]");
}

TEST(ValidateTransferFunction, PointPositionsMustBeNumbersInOrder)
{
  // vtkPiecewiseFunction re-sorts its points whenever one moves, so only a NaN position can
  // leave them out of order: the order check is defensive and the NaN is what gets reported.
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(1.0, 0.5);
  double moved[4] = { 2.0, 0.2, 0.5, 0.0 };
  opacity->SetNodeValue(0, moved);
  EXPECT_EQ(ValidateTransferFunction(opacity, nullptr), "");
  double nan[4] = { std::numeric_limits<double>::quiet_NaN(), 0.2, 0.5, 0.0 };
  opacity->SetNodeValue(0, nan);
  EXPECT_EQ(ValidateTransferFunction(opacity, nullptr), "opacity point 0 is not a number");
}

namespace
{
// TransferFunctionRange of the pair is [lo, hi].
void ExpectRange(vtkPiecewiseFunction* opacity, vtkScalarsToColors* color, double lo, double hi)
{
  double range[2];
  ASSERT_TRUE(TransferFunctionRange(opacity, color, range));
  EXPECT_EQ(range[0], lo);
  EXPECT_EQ(range[1], hi);
}
}

TEST(TransferTable, SpansTheTransferFunctionNotTheData)
{
  // The opacity's points and the color map's range together; the data's extremes play no part.
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.1, 0.0);
  opacity->AddPoint(0.9, 0.6);
  vtkNew<vtkLookupTable> color;
  color->SetTableRange(0.0, 0.5);
  ExpectRange(opacity, color, 0.0, 0.9);
  ExpectRange(opacity, nullptr, 0.1, 0.9);

  // Outside its points a function keeps its end values, as VTK clamps: so does the table.
  const TransferTable table = TabulateTransferFunction(nullptr, opacity, 1.0);
  ASSERT_EQ(table.Size, 1024);
  EXPECT_EQ(table.Lookup(1e4), table.Lookup(0.9));
  EXPECT_EQ(table.Lookup(3.4e38), table.Lookup(0.9));
  EXPECT_EQ(table.Lookup(-3.4e38).a, 0.0f);
  EXPECT_NEAR(table.Lookup(0.5).a, Extinction(0.3, 1.0), 1e-3);
}

TEST(TransferTable, ASinglePointFunctionGivesAConstantTableOfWidthOne)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(2.0, 0.4);
  ExpectRange(opacity, nullptr, 2.0, 3.0);
  const TransferTable table = TabulateTransferFunction(nullptr, opacity, 0.5);
  for (double density : { -1e30, 0.0, 2.0, 2.5, 1e30 })
  {
    EXPECT_FLOAT_EQ(table.Lookup(density).a, float(Extinction(0.4, 0.5))) << density;
  }
  vtkNew<vtkPiecewiseFunction> none;
  double range[2];
  EXPECT_FALSE(TransferFunctionRange(none, nullptr, range));
  EXPECT_EQ(TabulateTransferFunction(nullptr, none, 1.0).Size, 0);
}
