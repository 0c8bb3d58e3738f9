#include "CloudBlueNoise.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <random>
#include <utility>

namespace cloudvis
{

namespace
{
// Width of the Gaussian energy filter, in pixels: Ulichney's 1.5 keeps the clusters and voids
// the method finds on the scale of a few pixels, which is what pushes the spectrum's energy
// to high frequencies.
constexpr double Sigma = 1.5;
// Fraction of pixels set in the initial binary pattern.
constexpr double InitialFraction = 0.1;
// Energies are fixed point (kernel values times 2^32) so that adding and later subtracting a
// splat restores the energy exactly, and ties break the same way on every compiler.
constexpr double FixedPointScale = 4294967296.0;

// The state of Ulichney's method: a binary pattern and, per pixel, the sum of the Gaussian
// kernel centred on every set pixel (toroidal distances). Set pixels with the highest energy
// are the tightest clusters; unset pixels with the lowest energy are the largest voids.
class VoidAndCluster
{
public:
  explicit VoidAndCluster(int size)
    : Size(size)
    , Kernel(std::size_t(size) * size)
    , Energy(std::size_t(size) * size, 0)
    , Ones(std::size_t(size) * size, 0)
  {
    for (int dy = 0; dy < size; ++dy)
    {
      for (int dx = 0; dx < size; ++dx)
      {
        const double x = std::min(dx, size - dx), y = std::min(dy, size - dy);
        this->Kernel[std::size_t(dy) * size + dx] =
          std::llround(std::exp(-(x * x + y * y) / (2.0 * Sigma * Sigma)) * FixedPointScale);
      }
    }
  }

  void Set(int pixel, bool one)
  {
    this->Ones[pixel] = one;
    const std::int64_t sign = one ? 1 : -1;
    const int px = pixel % this->Size, py = pixel / this->Size;
    for (int dy = 0; dy < this->Size; ++dy)
    {
      const int y = (py + dy) % this->Size;
      const std::int64_t* kernel = &this->Kernel[std::size_t(dy) * this->Size];
      std::int64_t* energy = &this->Energy[std::size_t(y) * this->Size];
      // The row wraps once: kernel[0 .. Size - px) lands on [px, Size), the rest on [0, px).
      const int split = this->Size - px;
      for (int dx = 0; dx < split; ++dx)
      {
        energy[px + dx] += sign * kernel[dx];
      }
      for (int dx = split; dx < this->Size; ++dx)
      {
        energy[dx - split] += sign * kernel[dx];
      }
    }
  }

  bool IsSet(int pixel) const { return this->Ones[pixel] != 0; }

  // Ties go to the lowest index, so the result depends only on the energies. Callers always
  // have a candidate (a set pixel, resp. an unset one); the max(, 0) only tells the compiler.
  int TightestCluster() const
  {
    int best = -1;
    for (int p = 0; p < int(this->Energy.size()); ++p)
    {
      if (this->Ones[p] && (best < 0 || this->Energy[p] > this->Energy[best]))
      {
        best = p;
      }
    }
    return std::max(best, 0);
  }

  int LargestVoid() const
  {
    int best = -1;
    for (int p = 0; p < int(this->Energy.size()); ++p)
    {
      if (!this->Ones[p] && (best < 0 || this->Energy[p] < this->Energy[best]))
      {
        best = p;
      }
    }
    return std::max(best, 0);
  }

private:
  int Size;
  std::vector<std::int64_t> Kernel; // toroidal Gaussian centred on pixel 0
  std::vector<std::int64_t> Energy;
  std::vector<unsigned char> Ones;
};

std::vector<float> GenerateBlueNoiseMask(int size, std::uint32_t seed)
{
  const int n = size * size;
  VoidAndCluster pattern(size);

  // Initial binary pattern: distinct random pixels. The raw mt19937 output (specified by the
  // standard) is mapped with a multiply-shift, unlike std::uniform_int_distribution whose
  // algorithm differs between standard libraries.
  std::mt19937 rng(seed);
  const int ones = std::max(1, static_cast<int>(std::lround(n * InitialFraction)));
  for (int placed = 0; placed < ones;)
  {
    const int pixel = static_cast<int>((std::uint64_t(rng()) * std::uint64_t(n)) >> 32);
    if (!pattern.IsSet(pixel))
    {
      pattern.Set(pixel, true);
      ++placed;
    }
  }

  // Relax into the prototype pattern: move the tightest cluster into the largest void until the
  // pixel removed is the void found. The cap only guards against a cycle; Ulichney's
  // experience (and ours) is that it settles within a few hundred moves.
  for (int move = 0; move < 16 * n; ++move)
  {
    const int cluster = pattern.TightestCluster();
    pattern.Set(cluster, false);
    const int voidPixel = pattern.LargestVoid();
    pattern.Set(voidPixel, true);
    if (voidPixel == cluster)
    {
      break;
    }
  }

  std::vector<int> rank(n, -1);
  // Phase 1: remove the prototype's ones, tightest cluster first, ranks ones - 1 down to 0.
  VoidAndCluster phase1 = pattern;
  for (int r = ones - 1; r >= 0; --r)
  {
    const int cluster = phase1.TightestCluster();
    phase1.Set(cluster, false);
    rank[cluster] = r;
  }
  // Phases 2 and 3: fill the largest void, ranks ones .. n - 1. Ulichney's phase 3 (past half
  // full) looks for the tightest cluster of zeros using the zeros' energy; that energy is the
  // kernel sum minus the ones' energy at every pixel, so its tightest cluster is exactly the
  // ones' largest void and one loop serves both phases.
  for (int r = ones; r < n; ++r)
  {
    const int voidPixel = pattern.LargestVoid();
    pattern.Set(voidPixel, true);
    rank[voidPixel] = r;
  }

  std::vector<float> mask(n);
  for (int p = 0; p < n; ++p)
  {
    mask[p] = static_cast<float>((rank[p] + 0.5) / n);
  }
  return mask;
}
}

std::vector<float> BlueNoiseMask(int size, std::uint32_t seed)
{
  if (size < 1)
  {
    return {};
  }
  static std::mutex mutex;
  static std::map<std::pair<int, std::uint32_t>, std::vector<float>> cache;
  // Held while generating: two threads asking for the same mask wait for one generation.
  std::lock_guard<std::mutex> lock(mutex);
  auto& mask = cache[{ size, seed }];
  if (mask.empty())
  {
    mask = GenerateBlueNoiseMask(size, seed);
  }
  return mask;
}

} // namespace cloudvis
