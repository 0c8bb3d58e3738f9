// The blue-noise dither mask that jitters the start of every ray. Offsetting each pixel's first
// sample by a blue-noise fraction of the step turns the banding of a fixed-step march into
// fine, high-frequency grain that the eye (and temporal accumulation) averages away, where
// white-noise jitter would leave visible low-frequency blotches. The mask is generated at
// start-up with Ulichney's void-and-cluster method instead of being shipped as an image, so it
// has no licence or asset to track and any size can be asked for.
#ifndef CloudBlueNoise_h
#define CloudBlueNoise_h

#include "cloudvisFiltersModule.h"

#include <cstdint>
#include <vector>

namespace cloudvis
{

// size * size values, row-major, a permutation of the ranks (k + 0.5) / size^2 for
// k = 0 .. size^2 - 1: every threshold appears exactly once, so the mask is uniform. The mask
// is tileable (all distances are toroidal) and the same for the same (size, seed) on every
// machine (integer energies, a fixed PRNG). Generation costs O(size^4); 64 x 64 takes a few
// tens of milliseconds. Results are cached per (size, seed) for the life of the process and
// the cache is thread-safe. size < 1 gives an empty vector.
CLOUDVISFILTERS_EXPORT std::vector<float> BlueNoiseMask(int size = 64, std::uint32_t seed = 1);

} // namespace cloudvis

#endif
