// A noise target for the GPU path tracer: instead of a fixed number of paths per pixel, frames are
// accumulated until the image's relative standard error over the cloud (MeasureImageNoise, the
// figure `compare --reference` prints) is at most the target, or a time limit is spent. `render
// --spp P%` and `compare --reference pathtrace:P%` use it (docs/lighting.md, "A noise target").
// Reading the variance back stalls the GPU and copies two float images, so the noise is read only
// at the frame counts NextNoiseCheck chooses: where the 1 / sqrt(paths) law puts the target, at
// most double the frames of the last reading. That is doubling far from the target and the law's
// count near it: log2(paths / 64) + 1 or 2 readings and a few percent more paths than needed,
// where a fixed schedule reads back every few frames and plain doubling traces up to twice the
// paths needed; the cap keeps one early reading that is too high from overshooting by any factor.
#ifndef cloudvis_NoiseTarget_h
#define cloudvis_NoiseTarget_h

#include "CloudImageComparison.h"

#include <functional>
#include <string>

class vtkCloudVolumeMapper;
class vtkRenderWindow;
class vtkRenderer;

namespace cloudvis
{

// Paths per pixel each frame traces under a noise target: the most PathTraceFramesOf gives a
// fixed count, so that a frame costs what it costs there.
constexpr int NoiseTargetSamplesPerFrame = 8;
// Frames before the noise is first read (64 paths): with fewer, a pixel's sample variance has
// seldom met the rare bright paths (the sun through a thin edge) and reads low.
constexpr int FirstNoiseCheckFrames = 8;
// The mapper's most accumulated frames (vtkCloudVolumeMapper::SetMaximumAccumulatedFrames).
constexpr int MaximumNoiseTargetFrames = 65536;
// The time limit when none is given, in seconds (docs/lighting.md says why ten minutes).
constexpr double DefaultNoiseTimeLimit = 600.0;
// Without AcceptNoise, the accumulation stops at a reading whose projection of the time the
// target needs is beyond this many times the limit: the answer would be the same refusal, later.
constexpr double NoiseProjectionMargin = 2.0;

struct NoiseTarget
{
  double RelativeStandardError = 0.02; // the target, in (0, 1]
  double TimeLimit = DefaultNoiseTimeLimit; // seconds of accumulation, > 0
  // Whether a target not reached is still an image (the command writes it): then the
  // accumulation runs to the time limit rather than stopping at a hopeless projection.
  bool AcceptNoise = false;
};

enum class NoiseStop
{
  Reached,    // the noise is at or below the target
  TimeLimit,  // the time limit was spent first
  Projection, // the projected time was beyond NoiseProjectionMargin times the limit
  FrameLimit, // MaximumNoiseTargetFrames were accumulated first
};

struct NoiseReport
{
  NoiseTarget Target;
  NoiseStop Stop = NoiseStop::Reached;
  ImageNoise Noise;   // of the image as accumulated when it stopped
  int Frames = 0;     // accumulated
  int Samples = 0;    // paths per pixel in them
  double Seconds = 0.0; // wall clock of the accumulation, the readings included
  // Where the target is not reached: the paths per pixel the 1 / sqrt(paths) law says it needs,
  // and the time they would take at the rate of the frames after the first (which compiles the
  // shaders and uploads the field).
  long long ProjectedSamples = 0;
  double ProjectedSeconds = 0.0;
  bool Reached() const { return this->Stop == NoiseStop::Reached; }
};

// The frame count at which to read the noise next, after a reading of `noise` at `frames`
// frames, for `target` (noise and target as relative standard errors): the frames the
// 1 / sqrt(paths) law needs for the target, 5% more so that one more reading usually ends it,
// at least one frame more and at most double, and at most MaximumNoiseTargetFrames.
int NextNoiseCheck(int frames, double noise, double target);

// Sets the mapper up for a noise target: NoiseTargetSamplesPerFrame paths a frame and frames
// up to MaximumNoiseTargetFrames. Call it after ConfigureMapper (which sets render.spp's).
void ConfigureNoiseTarget(vtkCloudVolumeMapper* mapper);

// Accumulates the path-traced image of `mapper` in `renderer` (configured by
// ConfigureNoiseTarget, with nothing accumulated yet) until `target` is met or given up: each
// frame is `renderFrame()` (which renders `window` once and checks the mapper), after which
// `onFrame(frame, frames)` is told the frames done and the frames the latest projection needs.
// The noise is read at FirstNoiseCheckFrames, then at NextNoiseCheck's counts, and once more when
// the time or frame limit ends it. On return the mapper's frame limit is the frames accumulated,
// so later renders composite this very image (the one measured) again. Throws InputError naming
// `input` when the images cannot be read back.
NoiseReport AccumulateToNoiseTarget(const NoiseTarget& target,
  vtkRenderWindow* window,
  vtkCloudVolumeMapper* mapper,
  vtkRenderer* renderer,
  const std::function<void()>& renderFrame,
  const std::string& input,
  const std::function<void(int frame, int frames)>& onFrame = {});

} // namespace cloudvis

#endif
