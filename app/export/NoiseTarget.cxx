// The clock runs from the first frame, so the time a user is told includes the first frame's
// shader compilation and upload; the projection leaves that frame out of the rate, or a small
// image would look many times slower than it is and be refused early.
#include "NoiseTarget.h"

#include "Errors.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkRenderWindow.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace cloudvis
{
namespace
{

ImageNoise ReadNoise(vtkRenderWindow* window,
  vtkCloudVolumeMapper* mapper,
  vtkRenderer* renderer,
  const std::string& input)
{
  std::vector<float> rgba, variance;
  int width = 0, height = 0, varianceWidth = 0, varianceHeight = 0;
  window->MakeCurrent();
  if (!mapper->ReadImage(renderer, rgba, width, height) ||
    !mapper->ReadVariance(renderer, variance, varianceWidth, varianceHeight) ||
    varianceWidth != width || varianceHeight != height)
  {
    throw InputError(input + ": could not read the path-traced image back to measure its noise");
  }
  return MeasureImageNoise(rgba.data(), variance.data(), size_t(width) * size_t(height));
}

// (noise / target)^2: how many times the paths so far the target needs.
double PathsFactor(double noise, double target)
{
  return noise > 0.0 ? (noise / target) * (noise / target) : 0.0;
}

} // namespace

int NextNoiseCheck(int frames, double noise, double target)
{
  const double needed = std::ceil(1.05 * double(frames) * PathsFactor(noise, target));
  const double next = std::min(std::max(needed, double(frames) + 1.0), 2.0 * double(frames));
  return int(std::min(next, double(MaximumNoiseTargetFrames)));
}

void ConfigureNoiseTarget(vtkCloudVolumeMapper* mapper)
{
  mapper->SetPathTraceSamplesPerFrame(NoiseTargetSamplesPerFrame);
  mapper->SetMaximumAccumulatedFrames(MaximumNoiseTargetFrames);
}

NoiseReport AccumulateToNoiseTarget(const NoiseTarget& target,
  vtkRenderWindow* window,
  vtkCloudVolumeMapper* mapper,
  vtkRenderer* renderer,
  const std::function<void()>& renderFrame,
  const std::string& input,
  const std::function<void(int frame, int frames)>& onFrame)
{
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point start)
  { return std::chrono::duration<double>(Clock::now() - start).count(); };
  NoiseReport report;
  report.Target = target;
  const Clock::time_point start = Clock::now();
  double firstFrameSeconds = 0.0;
  int nextCheck = FirstNoiseCheckFrames;
  for (int frame = 1;; ++frame)
  {
    renderFrame();
    report.Frames = frame;
    report.Seconds = since(start);
    if (frame == 1)
    {
      firstFrameSeconds = report.Seconds;
    }
    const bool outOfTime = report.Seconds >= target.TimeLimit;
    const bool outOfFrames = frame >= MaximumNoiseTargetFrames;
    if (frame < nextCheck && !outOfTime && !outOfFrames)
    {
      if (onFrame)
      {
        onFrame(frame, nextCheck);
      }
      continue;
    }
    report.Noise = ReadNoise(window, mapper, renderer, input);
    report.Seconds = since(start);
    report.Samples = mapper->GetNumberOfAccumulatedSamples(renderer);
    const double factor = PathsFactor(report.Noise.RelativeStandardError, target.RelativeStandardError);
    report.ProjectedSamples = (long long)std::ceil(double(report.Samples) * factor);
    const double rate = frame > 1 ? (report.Seconds - firstFrameSeconds) / double(frame - 1)
                                  : report.Seconds;
    report.ProjectedSeconds =
      report.Seconds + rate * std::max(0.0, double(frame) * factor - double(frame));
    if (report.Noise.RelativeStandardError <= target.RelativeStandardError)
    {
      report.Stop = NoiseStop::Reached;
    }
    else if (outOfTime)
    {
      report.Stop = NoiseStop::TimeLimit;
    }
    else if (outOfFrames)
    {
      report.Stop = NoiseStop::FrameLimit;
    }
    else if (!target.AcceptNoise &&
      report.ProjectedSeconds > NoiseProjectionMargin * target.TimeLimit)
    {
      report.Stop = NoiseStop::Projection;
    }
    else
    {
      nextCheck = NextNoiseCheck(frame, report.Noise.RelativeStandardError,
        target.RelativeStandardError);
      if (onFrame)
      {
        onFrame(frame, nextCheck);
      }
      continue;
    }
    if (onFrame)
    {
      onFrame(frame, frame);
    }
    break;
  }
  mapper->SetMaximumAccumulatedFrames(report.Frames);
  return report;
}

} // namespace cloudvis
