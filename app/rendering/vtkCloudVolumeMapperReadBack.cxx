// vtkCloudVolumeMapper's read-backs: the last frame's float image, its path-traced variance, its
// auxiliary channels (samples, depth) and the statistics of its samples, read from the view's
// float targets (CloudViewTargets.h) for exports and tests.
#include "CloudVolumeMapperInternals.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <algorithm>
#include <limits>
#include <vector>

using cloudvis::mapper::WindowOf;

void vtkCloudVolumeMapper::ReadStatistics(vtkRenderer* renderer)
{
  cloudvis::ViewTargets& view = this->Internal->ViewOf(renderer);
  std::vector<float> counts;
  FrameStatistics statistics;
  if (view.Read(WindowOf(renderer),
        cloudvis::ViewTargets::Counts,
        counts,
        statistics.Width,
        statistics.Height))
  {
    for (size_t i = 0; i < counts.size(); i += 4)
    {
      statistics.SamplesTaken += counts[i];
      statistics.UsefulSamples += counts[i + 1];
    }
  }
  statistics.OccupiedBrickFraction = this->Internal->Occupancy.GetOccupiedFraction();
  statistics.SamplesPerMapRead = this->Internal->March.GetSamplesPerMapRead();
  if (this->Internal->Scattering.GetBytes() > 0)
  {
    statistics.ScatteringVolumeMilliseconds =
      1000.0 * this->Internal->Scattering.GetLastComputeSeconds();
  }
  this->LastStatistics = statistics;
}

bool vtkCloudVolumeMapper::ReadImage(vtkRenderer* renderer,
  std::vector<float>& rgba,
  int& width,
  int& height)
{
  auto found = this->Internal->Views.find(renderer);
  return found != this->Internal->Views.end() &&
    found->second->Read(WindowOf(renderer), cloudvis::ViewTargets::Color, rgba, width, height);
}

bool vtkCloudVolumeMapper::ReadVariance(vtkRenderer* renderer,
  std::vector<float>& variance,
  int& width,
  int& height)
{
  auto found = this->Internal->Views.find(renderer);
  if (found == this->Internal->Views.end() || !found->second->PathTraced)
  {
    return false;
  }
  cloudvis::ViewTargets& view = *found->second;
  const double samples = double(view.AccumulatedFrames) * view.SamplesPerFrame;
  std::vector<float> mean;
  if (samples < 2.0 ||
    !view.Read(WindowOf(renderer), cloudvis::ViewTargets::Color, mean, width, height) ||
    !view.Read(WindowOf(renderer), cloudvis::ViewTargets::Moments, variance, width, height))
  {
    return false;
  }
  // The sample variance from the first two moments, over the samples: the variance of the mean.
  for (size_t i = 0; i < variance.size(); ++i)
  {
    const double m = mean[i];
    const double sampleVariance =
      std::max(0.0, double(variance[i]) - m * m) * samples / (samples - 1.0);
    variance[i] = float(sampleVariance / samples);
  }
  return true;
}

vtkIdType vtkCloudVolumeMapper::CountCutPathTracePixels(vtkRenderer* renderer)
{
  auto found = this->Internal->Views.find(renderer);
  if (found == this->Internal->Views.end() || found->second->AccumulatedFrames < 1)
  {
    return -1;
  }
  cloudvis::ViewTargets& view = *found->second;
  std::vector<float> counts;
  int width = 0, height = 0;
  if (!view.PathTraced) // only the path tracer's fragments say whether their loops ran whole
  {
    return 0;
  }
  if (!view.Read(WindowOf(renderer), cloudvis::ViewTargets::Counts, counts, width, height))
  {
    return -1;
  }
  // The fourth channel is 1 for a frame whose loops ran to their ends, 0 for one cut; Read gives
  // its mean over the frames, below 1 by at least 1 / frames where one was cut.
  const float wholeFrames = 1.0f - 0.5f / float(view.AccumulatedFrames);
  vtkIdType cut = 0;
  for (size_t i = 3; i < counts.size(); i += 4)
  {
    cut += counts[i] < wholeFrames;
  }
  return cut;
}

bool vtkCloudVolumeMapper::ReadAuxiliary(vtkRenderer* renderer,
  std::vector<float>& channels,
  int& width,
  int& height)
{
  auto found = this->Internal->Views.find(renderer);
  if (found == this->Internal->Views.end() ||
    !found->second->Read(
      WindowOf(renderer), cloudvis::ViewTargets::Counts, channels, width, height))
  {
    return false;
  }
  // The march writes local distances, and NoDepth where the cloud never passes 2%: a mean over
  // frames that holds it in any one of them is still above NoDepth / 65536 (65536 being the most
  // frames accumulated), so half of that tells them apart from any real distance. The fourth
  // channel (the opacity-weighted depths temporal reprojection reads) is not part of this.
  const double unit = found->second->LocalUnit;
  const float noDepthInSomeFrame = cloudvis::NoDepth / (2.0f * 65536.0f);
  for (size_t i = 2; i < channels.size(); i += 4)
  {
    channels[i] = channels[i] >= noDepthInSomeFrame ? std::numeric_limits<float>::infinity()
                                                    : float(double(channels[i]) * unit);
    channels[i + 1] = 1.0f;
  }
  return true;
}

namespace
{
// One of the mapper's read-backs into std::vector (ReadImage, ReadAuxiliary).
using ReadBack = bool (vtkCloudVolumeMapper::*)(vtkRenderer*, std::vector<float>&, int&, int&);

// Runs a read-back and puts its width x height x 4 floats into image as its one 4-component
// point array `name`; leaves the image alone when the read-back fails.
bool ReadIntoImage(vtkCloudVolumeMapper* mapper,
  ReadBack read,
  vtkRenderer* renderer,
  const char* name,
  vtkImageData* image)
{
  std::vector<float> values;
  int width = 0;
  int height = 0;
  if (!image || !(mapper->*read)(renderer, values, width, height))
  {
    return false;
  }
  vtkNew<vtkFloatArray> pixels;
  pixels->SetName(name);
  pixels->SetNumberOfComponents(4);
  pixels->SetNumberOfTuples(vtkIdType(width) * height);
  std::copy(values.begin(), values.end(), pixels->GetPointer(0));
  image->Initialize();
  image->SetDimensions(width, height, 1);
  image->GetPointData()->SetScalars(pixels);
  return true;
}
}

bool vtkCloudVolumeMapper::ReadImage(vtkRenderer* renderer, vtkImageData* image)
{
  return ReadIntoImage(this, &vtkCloudVolumeMapper::ReadImage, renderer, "rgba", image);
}

bool vtkCloudVolumeMapper::ReadAuxiliary(vtkRenderer* renderer, vtkImageData* image)
{
  return ReadIntoImage(this, &vtkCloudVolumeMapper::ReadAuxiliary, renderer, "auxiliary", image);
}
