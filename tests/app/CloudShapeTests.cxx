// The shapes of the shipped cloud types, measured on the fields `cloudvis generate` writes from
// the shipped scenes, as a meteorologist would judge them (docs/user-guide.md, "Cloud types"). A
// voxel is cloudy above 1% of the field's maximum; up is y, the scenes' vertical.
//
// - A cumulonimbus's anvil streams downwind: on the projected mask of the top fifth of the cloud,
//   the reach from the tower's axis (the centroid of the cloudy level at a quarter of the height)
//   in its longest direction is at least 3x the reach in the opposite direction.
// - Its tower holds its width: sqrt(cloudy area) at 3/8 and 5/8 of the height is at least 85% of
//   that at 1/8 (no waist).
// - A cumulus cloudscape's clouds have flat bases: for at least 90% of its clouds (the projected
//   mask's 4-connected parts of at least 10 columns), the lowest tenth of the cloud's columns
//   start within one voxel of the lowest cloudy level.
// - And its clouds are not the weather map drawn straight up: the correlation between the cloud
//   masks one voxel above the base and 500 m above it is below 0.8.
// - Nor are their sides fluted (the map's fine octaves drawn straight up, which reads as vertical
//   ridges from the ground): the fine detail of the mask (less its 9 x 9 voxel box mean) at a
//   quarter of the layer's cloudy depth correlates with that 200 m above it at most 0.2 (0.11;
//   0.29 when the map's octaves are all 2-D; 200 m across, -0.03).
// - A cumulonimbus rains from its base, in streaks: below the base (the field's voxels above a
//   tenth of the rain's own peak) at least 95% of the rain's columns lie under the projected
//   mask of the cloud's lowest eighth (1.0), the rain covers at least 10% of those columns
//   (0.15), at least 40% of its columns reach the floor (0.58), and its mask under the base
//   correlates with that 300 m further down more than with that 300 m across, by 0.2 or more
//   (0.83 against 0.55: streaks that fall; isotropic blobs measure 0.69 against 0.60, and a
//   shaft without streaks 0.95 against 0.82).
// - An altocumulus is a thin sheet of cloudlets: at most 500 m deep, and its projected mask at
//   least 100 clouds of 10 columns or more whose median size sqrt(area) is of the lattice's
//   300 m (between 100 and 500 m), where a weather map alone makes a few large clouds.
// - A congestus is a tower: at least 1.5 times as tall as it is wide at a quarter of its height,
//   and narrowing into turrets (at 7/8 of its height at most 70% of that width).
#include "SupportRun.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace
{
using cloudvis::support::RunCloudvis;
using cloudvis::support::TemporaryDirectory;

// A generated field's cloud mask, [x + nx * (y + ny * z)].
struct CloudMask
{
  int Nx = 0, Ny = 0, Nz = 0;
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  std::vector<std::uint8_t> Cloudy;
  std::vector<float> Density;   // the field itself, same order
  int Lowest = 0, Highest = -1; // the levels (y indices) holding cloud

  bool At(int i, int j, int k) const
  {
    return this->Cloudy[(static_cast<size_t>(k) * this->Ny + j) * this->Nx + i] != 0;
  }
  // The level at a fraction of the cloud's height.
  int Level(double fraction) const
  {
    return static_cast<int>(std::lround(this->Lowest + fraction * (this->Highest - this->Lowest)));
  }
};

// Generates a shipped scene's field with the cloudvis binary and reads its mask back.
CloudMask GenerateMask(const std::string& scene)
{
  const TemporaryDirectory folder;
  const std::string file = folder.File("field.vti");
  const auto run =
    RunCloudvis({ "generate", std::string(CLOUDVIS_SCENES) + "/" + scene, "-o", file });
  EXPECT_EQ(run.Status, 0) << run.Err;
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  auto* density = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("density"));
  CloudMask mask;
  if (!density)
  {
    ADD_FAILURE() << scene << ": no density array";
    return mask;
  }
  int dims[3];
  image->GetDimensions(dims);
  mask.Nx = dims[0];
  mask.Ny = dims[1];
  mask.Nz = dims[2];
  image->GetSpacing(mask.Spacing);
  const float* v = density->GetPointer(0);
  const vtkIdType n = density->GetNumberOfValues();
  const float threshold = 0.01f * *std::max_element(v, v + n);
  mask.Cloudy.resize(static_cast<size_t>(n));
  mask.Density.assign(v, v + n);
  mask.Lowest = mask.Ny;
  for (vtkIdType i = 0; i < n; ++i)
  {
    mask.Cloudy[static_cast<size_t>(i)] = v[i] > threshold;
    if (v[i] > threshold)
    {
      const int level = static_cast<int>((i / mask.Nx) % mask.Ny);
      mask.Lowest = std::min(mask.Lowest, level);
      mask.Highest = std::max(mask.Highest, level);
    }
  }
  EXPECT_LT(mask.Lowest, mask.Highest) << scene << ": no cloud over two levels or more";
  return mask;
}

// The 4-connected parts of a projected nx x nz mask: a label per column (0: clear), and the count.
int LabelClouds(const std::vector<std::uint8_t>& projected, int nx, int nz, std::vector<int>& label)
{
  label.assign(projected.size(), 0);
  int clouds = 0;
  std::vector<int> stack;
  for (int start = 0; start < nx * nz; ++start)
  {
    if (!projected[start] || label[start])
    {
      continue;
    }
    label[start] = ++clouds;
    stack.assign(1, start);
    while (!stack.empty())
    {
      const int c = stack.back();
      stack.pop_back();
      const int i = c % nx, k = c / nx;
      const int next[4][2] = { { i - 1, k }, { i + 1, k }, { i, k - 1 }, { i, k + 1 } };
      for (const auto& n : next)
      {
        const int at = n[1] * nx + n[0];
        if (n[0] >= 0 && n[0] < nx && n[1] >= 0 && n[1] < nz && projected[at] && !label[at])
        {
          label[at] = clouds;
          stack.push_back(at);
        }
      }
    }
  }
  return clouds;
}

// The Pearson correlation of two series of values (masks, or their detail).
double Correlation(const std::vector<double>& a, const std::vector<double>& b)
{
  const double n = static_cast<double>(a.size());
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    sa += a[i];
    sb += b[i];
    saa += a[i] * a[i];
    sbb += b[i] * b[i];
    sab += a[i] * b[i];
  }
  const double cov = sab / n - sa / n * sb / n;
  return cov / std::sqrt((saa / n - sa * sa / n / n) * (sbb / n - sb * sb / n / n));
}

// sqrt(cloudy area) of a level, in world units.
double LevelWidth(const CloudMask& m, int level)
{
  size_t area = 0;
  for (int k = 0; k < m.Nz; ++k)
    for (int i = 0; i < m.Nx; ++i)
      area += m.At(i, level, k);
  return std::sqrt(static_cast<double>(area) * m.Spacing[0] * m.Spacing[2]);
}

// The fine detail of a level's mask: the mask less its mean over the 9 x 9 columns around each
// (clamped at the field's sides), [x + nx * z].
std::vector<double> LevelDetail(const CloudMask& m, int level)
{
  // A summed-area table of the level, (nx + 1) x (nz + 1).
  const int w = m.Nx + 1;
  std::vector<double> sum(static_cast<size_t>(w) * (m.Nz + 1), 0.0);
  for (int k = 0; k < m.Nz; ++k)
    for (int i = 0; i < m.Nx; ++i)
      sum[(k + 1) * w + i + 1] =
        m.At(i, level, k) + sum[k * w + i + 1] + sum[(k + 1) * w + i] - sum[k * w + i];
  std::vector<double> detail(static_cast<size_t>(m.Nx) * m.Nz);
  const int r = 4;
  for (int k = 0; k < m.Nz; ++k)
    for (int i = 0; i < m.Nx; ++i)
    {
      const int i0 = std::max(i - r, 0), i1 = std::min(i + r + 1, m.Nx);
      const int k0 = std::max(k - r, 0), k1 = std::min(k + r + 1, m.Nz);
      const double box = sum[k1 * w + i1] - sum[k0 * w + i1] - sum[k1 * w + i0] + sum[k0 * w + i0];
      detail[static_cast<size_t>(k) * m.Nx + i] = m.At(i, level, k) - box / ((i1 - i0) * (k1 - k0));
    }
  return detail;
}

// The projected mask (along y) of a field's cloud.
std::vector<std::uint8_t> Projected(const CloudMask& m)
{
  std::vector<std::uint8_t> projected(static_cast<size_t>(m.Nx) * m.Nz, 0);
  for (int k = 0; k < m.Nz; ++k)
    for (int j = 0; j < m.Ny; ++j)
      for (int i = 0; i < m.Nx; ++i)
        projected[static_cast<size_t>(k) * m.Nx + i] |= m.At(i, j, k) ? 1 : 0;
  return projected;
}
}

TEST(CloudShapes, CumulonimbusAnvilStreamsDownwindAboveATowerWithoutAWaist)
{
  const CloudMask m = GenerateMask("cumulonimbus.json");
  ASSERT_LT(m.Lowest, m.Highest);
  const double height = m.Highest - m.Lowest;
  const double w1 = LevelWidth(m, m.Level(1.0 / 8.0)), w3 = LevelWidth(m, m.Level(3.0 / 8.0)),
               w5 = LevelWidth(m, m.Level(5.0 / 8.0));
  std::printf(
    "tower width at 3/8 and 5/8 of the height: %.3f and %.3f of that at 1/8\n", w3 / w1, w5 / w1);
  EXPECT_GE(w3 / w1, 0.85);
  EXPECT_GE(w5 / w1, 0.85);

  // The axis: the centroid of the level at a quarter of the height.
  double cx = 0, cz = 0, count = 0;
  for (int k = 0; k < m.Nz; ++k)
    for (int i = 0; i < m.Nx; ++i)
      if (m.At(i, m.Level(0.25), k))
      {
        cx += i;
        cz += k;
        count += 1;
      }
  ASSERT_GT(count, 0);
  cx /= count;
  cz /= count;
  // The top fifth, projected: the farthest reach from the axis per direction.
  std::vector<std::pair<double, double>> top;
  const int from = static_cast<int>(std::lround(m.Highest - 0.2 * height));
  for (int k = 0; k < m.Nz; ++k)
    for (int i = 0; i < m.Nx; ++i)
      for (int j = from; j <= m.Highest; ++j)
        if (m.At(i, j, k))
        {
          top.emplace_back((i - cx) * m.Spacing[0], (k - cz) * m.Spacing[2]);
          break;
        }
  ASSERT_FALSE(top.empty());
  const auto reach = [&](double angle)
  {
    double farthest = 0.0;
    for (const auto& p : top)
      farthest = std::max(farthest, p.first * std::cos(angle) + p.second * std::sin(angle));
    return farthest;
  };
  double longest = 0.0, direction = 0.0;
  for (int degree = 0; degree < 360; ++degree)
  {
    const double angle = degree * 3.14159265358979323846 / 180.0;
    const double r = reach(angle);
    if (r > longest)
    {
      longest = r;
      direction = angle;
    }
  }
  const double opposite = reach(direction + 3.14159265358979323846);
  std::printf(
    "anvil reach %.0f downwind, %.0f upwind: %.2fx\n", longest, opposite, longest / opposite);
  EXPECT_GE(longest / opposite, 3.0);
}

TEST(CloudShapes, CumulonimbusRainsInStreaksUnderItsBase)
{
  const CloudMask m = GenerateMask("cumulonimbus.json");
  ASSERT_GT(m.Lowest, 2) << "the cloud's base must stand above the field's floor";
  const auto at = [&m](int i, int j, int k)
  { return m.Density[(static_cast<size_t>(k) * m.Ny + j) * m.Nx + i]; };
  // The rain: what lies under the lowest cloudy level, up to `below`, the highest level of it.
  int below = -1;
  float peak = 0.0f;
  for (int k = 0; k < m.Nz; ++k)
    for (int j = 0; j < m.Lowest; ++j)
      for (int i = 0; i < m.Nx; ++i)
        if (at(i, j, k) > 0.0f)
        {
          peak = std::max(peak, at(i, j, k));
          below = std::max(below, j);
        }
  ASSERT_GT(peak, 0.0f) << "no rain under the base";
  const auto rains = [&](int i, int j, int k) { return at(i, j, k) > 0.1f * peak; };
  // The base: the projected mask of the cloud's lowest eighth.
  const int eighth = m.Level(1.0 / 8.0);
  size_t baseColumns = 0, rainColumns = 0, underBase = 0, toFloor = 0;
  std::vector<std::uint8_t> base(static_cast<size_t>(m.Nx) * m.Nz, 0);
  for (int k = 0; k < m.Nz; ++k)
    for (int i = 0; i < m.Nx; ++i)
    {
      std::uint8_t& b = base[static_cast<size_t>(k) * m.Nx + i];
      for (int j = m.Lowest; j <= eighth && !b; ++j)
        b = m.At(i, j, k) ? 1 : 0;
      baseColumns += b;
      bool rained = false;
      for (int j = 0; j <= below && !rained; ++j)
        rained = rains(i, j, k);
      rainColumns += rained;
      underBase += rained && b;
      toFloor += rained && rains(i, 0, k);
    }
  ASSERT_GT(rainColumns, 0u);
  // Streaks: the rain's mask under the base, just below it against 300 m lower and 300 m across.
  const int down = static_cast<int>(std::lround(300.0 / m.Spacing[1]));
  const int across = static_cast<int>(std::lround(300.0 / m.Spacing[0]));
  ASSERT_GE(below - down, 0);
  std::vector<double> here, lower, beside;
  for (int k = 0; k < m.Nz; ++k)
    for (int i = 0; i + across < m.Nx; ++i)
      if (base[static_cast<size_t>(k) * m.Nx + i] &&
        base[static_cast<size_t>(k) * m.Nx + i + across])
      {
        here.push_back(rains(i, below, k));
        lower.push_back(rains(i, below - down, k));
        beside.push_back(rains(i + across, below, k));
      }
  const double vertical = Correlation(here, lower), horizontal = Correlation(here, beside);
  std::printf("rain: %.3f of its columns under the base, over %.3f of the base's, %.3f reach the "
              "floor; its mask correlates %.3f 300 m down, %.3f 300 m across\n",
    double(underBase) / rainColumns,
    double(rainColumns) / baseColumns,
    double(toFloor) / rainColumns,
    vertical,
    horizontal);
  EXPECT_GE(double(underBase) / rainColumns, 0.95);
  EXPECT_GE(double(rainColumns) / baseColumns, 0.1);
  EXPECT_GE(double(toFloor) / rainColumns, 0.4);
  EXPECT_GE(vertical - horizontal, 0.2);
}

TEST(CloudShapes, CumulusCloudscapeHasFlatBasesAndNoExtrudedColumns)
{
  const CloudMask m = GenerateMask("cloudscape-above.json");
  ASSERT_LT(m.Lowest, m.Highest);
  // Each column's first cloudy level, and the projected mask's clouds.
  std::vector<int> first(static_cast<size_t>(m.Nx) * m.Nz, -1);
  std::vector<std::uint8_t> projected(first.size(), 0);
  for (int k = 0; k < m.Nz; ++k)
    for (int i = 0; i < m.Nx; ++i)
      for (int j = 0; j < m.Ny; ++j)
        if (m.At(i, j, k))
        {
          first[static_cast<size_t>(k) * m.Nx + i] = j;
          projected[static_cast<size_t>(k) * m.Nx + i] = 1;
          break;
        }
  std::vector<int> label;
  const int clouds = LabelClouds(projected, m.Nx, m.Nz, label);
  std::vector<std::vector<int>> starts(static_cast<size_t>(clouds) + 1);
  for (size_t c = 0; c < label.size(); ++c)
    if (label[c])
      starts[static_cast<size_t>(label[c])].push_back(first[c]);
  int counted = 0, flat = 0;
  for (auto& s : starts)
  {
    if (s.size() < 10)
    {
      continue;
    }
    ++counted;
    // The lowest tenth of the columns: the 10th percentile of their first levels.
    std::nth_element(s.begin(), s.begin() + s.size() / 10, s.end());
    flat += s[s.size() / 10] <= m.Lowest + 1;
  }
  ASSERT_GE(counted, 20);
  std::printf("%d of %d clouds start within one voxel of the base (%.1f%%)\n",
    flat,
    counted,
    100.0 * flat / counted);
  EXPECT_GE(static_cast<double>(flat) / counted, 0.9);

  const int up = static_cast<int>(std::lround(500.0 / m.Spacing[1]));
  ASSERT_LT(m.Lowest + 1 + up, m.Ny);
  std::vector<double> near, far;
  for (int k = 0; k < m.Nz; ++k)
    for (int i = 0; i < m.Nx; ++i)
    {
      near.push_back(m.At(i, m.Lowest + 1, k));
      far.push_back(m.At(i, m.Lowest + 1 + up, k));
    }
  const double r = Correlation(near, far);
  std::printf("cloud mask correlation between one voxel and 500 m above the base: %.3f\n", r);
  EXPECT_LT(r, 0.8);

  // The sides' fine detail, upwards and across.
  const int level = m.Level(0.25), step = static_cast<int>(std::lround(200.0 / m.Spacing[1]));
  ASSERT_LT(level + step, m.Ny);
  const std::vector<double> detail = LevelDetail(m, level);
  const double vertical = Correlation(detail, LevelDetail(m, level + step));
  const int across = static_cast<int>(std::lround(200.0 / m.Spacing[0]));
  std::vector<double> here, there;
  for (int k = 0; k < m.Nz; ++k)
    for (int i = 0; i + across < m.Nx; ++i)
    {
      here.push_back(detail[static_cast<size_t>(k) * m.Nx + i]);
      there.push_back(detail[static_cast<size_t>(k) * m.Nx + i + across]);
    }
  std::printf("fine detail correlation 200 m up: %.3f, 200 m across: %.3f\n",
    vertical,
    Correlation(here, there));
  EXPECT_LT(vertical, 0.2);
}

TEST(CloudShapes, AltocumulusIsAThinSheetOfCloudlets)
{
  const CloudMask m = GenerateMask("altocumulus.json");
  ASSERT_LT(m.Lowest, m.Highest);
  const double depth = (m.Highest - m.Lowest + 1) * m.Spacing[1];
  std::vector<int> label;
  const int clouds = LabelClouds(Projected(m), m.Nx, m.Nz, label);
  std::vector<size_t> area(static_cast<size_t>(clouds) + 1, 0);
  for (int l : label)
    area[static_cast<size_t>(l)] += l > 0;
  std::vector<double> sizes;
  for (size_t c = 1; c < area.size(); ++c)
    if (area[c] >= 10)
      sizes.push_back(std::sqrt(static_cast<double>(area[c]) * m.Spacing[0] * m.Spacing[2]));
  ASSERT_FALSE(sizes.empty());
  std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
  const double median = sizes[sizes.size() / 2];
  std::printf("altocumulus: %.0f m deep, %zu cloudlets of 10 columns or more, median size %.0f m\n",
    depth,
    sizes.size(),
    median);
  EXPECT_LE(depth, 500.0);
  EXPECT_GE(sizes.size(), 100u);
  EXPECT_GE(median, 100.0);
  EXPECT_LE(median, 500.0);
}

TEST(CloudShapes, CongestusIsATowerThatNarrowsIntoTurrets)
{
  const CloudMask m = GenerateMask("congestus.json");
  ASSERT_LT(m.Lowest, m.Highest);
  const double height = (m.Highest - m.Lowest) * m.Spacing[1];
  const double quarter = LevelWidth(m, m.Level(0.25)), top = LevelWidth(m, m.Level(0.875));
  std::printf(
    "congestus: %.0f m tall, %.0f m wide at 1/4 of its height (%.2fx), %.2f of that at 7/8\n",
    height,
    quarter,
    height / quarter,
    top / quarter);
  EXPECT_GE(height / quarter, 1.5);
  EXPECT_LE(top / quarter, 0.7);
}
