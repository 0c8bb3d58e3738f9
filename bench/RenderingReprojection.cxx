// `cloudvis-bench-rendering reprojection`: temporal reprojection while interacting (issue 12),
// timed and compared with still renders of the same views.
#include "ImageWriters.h"
#include "RenderingBench.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkPiecewiseFunction.h>
#include <vtkTimerLog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace cloudvis
{
namespace bench
{

// Issue 12's interaction item: the sparse cloud after a still frame, orbiting 1 degree per
// interactive frame (desired update rate 20, so the mapper lowers its scale to keep 20 frames per
// second), with and without TemporalReprojection. Each interactive frame is compared with the
// still render of its view by a second mapper (jitter on, 16 frames accumulated: converged);
// prints ms/frame, the march's scale and the RMS error (8-bit levels) of both, and their ratios.
// The transfer function is the render tests' contrasted one (opacity 0.9 per 0.1 at density 0.5,
// orange to blue), whose detail the reduced resolution loses; the default one is nearly uniform
// white, which any resolution shows alike.
int Reprojection(const Options& options, const std::string& dumpDirectory)
{
  const auto field = Field(options.Size, false);
  const auto contrast = [](vtkVolumeProperty* property)
  {
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(0.5, 0.9);
    vtkNew<vtkColorTransferFunction> color;
    color->AddRGBPoint(0.0, 0.9, 0.5, 0.2);
    color->AddRGBPoint(0.5, 0.3, 0.6, 1.0);
    property->SetScalarOpacity(opacity);
    property->SetColor(color);
  };
  const double step = 4.0 / (options.Size - 1);
  const int orbit = std::max(options.Frames, 2);
  std::printf("temporal reprojection on the sparse field (%d^3, %dx%d, step %.4f, %d interactive "
              "frames orbiting 1 degree each):\n",
    options.Size,
    options.Width,
    options.Height,
    step,
    orbit);
  const auto converged = [&](int frame)
  {
    auto mapper = CloudMapper(step);
    mapper->JitterOn();
    mapper->SetMaximumAccumulatedFrames(16);
    View still(mapper, field, options);
    contrast(still.Property);
    still.Renderer->GetActiveCamera()->Azimuth(double(frame));
    for (int f = 0; f < 16; ++f)
    {
      still.Window->Render();
    }
    return still.Pixels();
  };
  std::vector<RenderedImage> truth;
  for (int frame = 1; frame <= orbit; ++frame)
  {
    truth.push_back(converged(frame));
  }
  double results[2][2] = {}; // [reprojection][ms, error]
  for (const bool reprojection : { false, true })
  {
    auto mapper = CloudMapper(step);
    mapper->JitterOn();
    mapper->SetMaximumAccumulatedFrames(16);
    mapper->SetTemporalReprojection(reprojection);
    View cloud(mapper, field, options);
    contrast(cloud.Property);
    for (int f = 0; f < 16; ++f)
    {
      cloud.Window->Render(); // the converged still frame the interaction starts from
    }
    cloud.Window->SetDesiredUpdateRate(20.0);
    double seconds = 0.0, squaredError = 0.0;
    int scaledWidth = 0;
    for (int frame = 1; frame <= orbit; ++frame)
    {
      cloud.Renderer->GetActiveCamera()->Azimuth(1.0);
      const double start = vtkTimerLog::GetUniversalTime();
      cloud.Window->Render();
      cloud.Window->WaitForCompletion();
      seconds += vtkTimerLog::GetUniversalTime() - start;
      const RenderedImage shown = cloud.Pixels();
      const double rms = RmsLevels(shown, truth[frame - 1]);
      if (!dumpDirectory.empty())
      {
        const std::string name = dumpDirectory + "/frame" + std::to_string(frame);
        WriteImage(shown, name + (reprojection ? "-reprojected.png" : "-low.png"));
        WriteImage(truth[frame - 1], name + "-truth.png");
      }
      squaredError += rms * rms;
      if (frame == 1 || frame == orbit)
      {
        std::printf("  %s, interactive frame %d: RMS error %.2f levels\n",
          reprojection ? "with reprojection" : "without reprojection",
          frame,
          rms);
      }
      std::vector<float> rgba;
      int height = 0;
      mapper->ReadImage(cloud.Renderer, rgba, scaledWidth, height);
    }
    const double ms = 1000.0 * seconds / orbit;
    const double error = std::sqrt(squaredError / orbit);
    results[reprojection][0] = ms;
    results[reprojection][1] = error;
    std::printf("  %-22s %8.1f ms/frame  march %4d px wide  RMS error vs converged %.2f levels\n",
      reprojection ? "with reprojection" : "without reprojection",
      ms,
      scaledWidth,
      error);
  }
  std::printf(
    "  reprojection frame-time ratio (with / without): %.2f\n", results[1][0] / results[0][0]);
  std::printf("  reprojection error ratio (with / without): %.2f\n", results[1][1] / results[0][1]);
  return 0;
}

} // namespace bench
} // namespace cloudvis
