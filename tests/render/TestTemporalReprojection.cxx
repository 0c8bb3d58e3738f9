// Temporal reprojection of interactive frames (vtkCloudVolumeMapper::TemporalReprojection): after
// a still frame, an interactive frame after a small camera move must be closer to the still
// render of the new view than the low-resolution frame alone; a large move must leave no ghost
// where the cloud was; a change other than the camera (here the transfer function) must drop the
// history. The interactive frames march at the lowest scale, 0.25: each scene first renders one
// interactive frame at an unreachable frame rate, so the mapper's measured cost asks for it.
#include "SupportScene.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <iostream>

using namespace cloudvis::support;

namespace
{
constexpr int Size = 128;
constexpr double Step = 0.02;

// A perspective view of the article's cloud through a fresh mapper.
struct CloudScene
{
  explicit CloudScene(bool reprojection)
    : Mapper(CloudMapper(Step))
    , View(Mapper, Size, Size)
  {
    this->Mapper->SetTemporalReprojection(reprojection);
    // The article's cloud with detail finer than the quarter-resolution march shows.
    static const vtkSmartPointer<vtkImageData> field = SparseCloud(128);
    this->View.SetInput(field);
    SetRampMedium(this->View.Property, 0.5, 0.9);
    this->View.LookAlongMinusZ(6.0, false);
    this->Mapper->SetInteractiveFrameRate(1000.0);
    this->Interactive();
  }
  Image Still()
  {
    this->View.Window->SetDesiredUpdateRate(0.0001);
    return this->View.RenderOnce();
  }
  Image Interactive()
  {
    this->View.Window->SetDesiredUpdateRate(1000.0);
    return this->View.RenderOnce();
  }
  vtkCamera* Camera() { return this->View.Renderer->GetActiveCamera(); }

  vtkSmartPointer<vtkCloudVolumeMapper> Mapper;
  GpuScene View;
};

// The still render of the view `steps` times `move` lead to, and the last of the interactive
// frames after a still frame and each move, with and without reprojection.
struct Frames
{
  Image Truth, Before, Reprojected, LowResolution;
};
Frames RenderMove(const std::function<void(vtkCamera*)>& move, int steps = 1)
{
  Frames frames;
  CloudScene truth(false);
  for (int step = 0; step < steps; ++step)
  {
    move(truth.Camera());
  }
  frames.Truth = truth.Still();
  for (bool reprojection : { true, false })
  {
    CloudScene scene(reprojection);
    frames.Before = scene.Still();
    for (int step = 0; step < steps; ++step)
    {
      move(scene.Camera());
      (reprojection ? frames.Reprojected : frames.LowResolution) = scene.Interactive();
    }
    std::vector<float> rgba;
    int width = 0, height = 0;
    scene.Mapper->ReadImage(scene.View.Renderer, rgba, width, height);
    EXPECT_EQ(width, Size / 4) << "the interactive frame marches at scale 0.25";
  }
  return frames;
}
}

TEST(TemporalReprojection, SharpensAnInteractiveFrameAfterASmallRotation)
{
  // 2 degrees: a frame of a drag at 40 degrees a second and 20 frames a second.
  const Frames frames = RenderMove([](vtkCamera* camera) { camera->Azimuth(2.0); });
  Dump(frames.Truth, "reprojection-rotate-truth");
  Dump(frames.Reprojected, "reprojection-rotate-reprojected");
  Dump(frames.LowResolution, "reprojection-rotate-low-resolution");
  const double reprojected = RmsDifference(frames.Reprojected, frames.Truth);
  const double lowResolution = RmsDifference(frames.LowResolution, frames.Truth);
  std::cout << "RMS error against the still render: reprojected " << reprojected
            << " levels, low resolution " << lowResolution << " levels\n";
  EXPECT_GT(lowResolution, 2.0) << "the quarter resolution must lose detail";
  EXPECT_LT(reprojected, 0.6 * lowResolution);
}

TEST(TemporalReprojection, AnOrbitDoesNotLagBehindTheCamera)
{
  // Eight frames of 1 degree: the history ages as its views turn away from the camera, so the
  // blend does not trail the orbit. (Without sub-pixel jitter of the march the current frames
  // bring no detail finer than their own, so by then the gain of the first frames has faded to
  // the low-resolution frame's error: measured 0.98 of it, 0.67 after three frames.)
  const Frames frames = RenderMove([](vtkCamera* camera) { camera->Azimuth(1.0); }, 8);
  Dump(frames.Reprojected, "reprojection-orbit-reprojected");
  const double reprojected = RmsDifference(frames.Reprojected, frames.Truth);
  const double lowResolution = RmsDifference(frames.LowResolution, frames.Truth);
  std::cout << "after 8 frames: reprojected " << reprojected << " levels, low resolution "
            << lowResolution << " levels\n";
  // Measured 0.976 of it; with the age ignored, 1.022.
  EXPECT_LT(reprojected, lowResolution);
}

TEST(TemporalReprojection, StillFramesAreUnchangedAndTheHistoryIsCounted)
{
  CloudScene plain(false);
  CloudScene reprojecting(true);
  const Image a = plain.Still();
  const Image b = reprojecting.Still();
  // The history keeps the image in half floats: at most one 8-bit level of rounding.
  EXPECT_LE(MaxDifference(a, b), 1.0 / 255.0 + 1e-6);
  // Two full-viewport pairs: RGBA16F (8 bytes) and RG32F (8 bytes).
  EXPECT_EQ(reprojecting.Mapper->GetGPUMemoryBytes() - plain.Mapper->GetGPUMemoryBytes(),
    2LL * Size * Size * (8 + 8));
  reprojecting.Mapper->TemporalReprojectionOff();
  reprojecting.Still();
  EXPECT_EQ(reprojecting.Mapper->GetGPUMemoryBytes(), plain.Mapper->GetGPUMemoryBytes())
    << "turned off, the history is released";
}

TEST(TemporalReprojection, LeavesNoGhostWhereTheCloudWas)
{
  // A pan that moves the cloud by about a third of the view: where it was, the new view shows
  // the background, and so must the reprojected frame.
  const Frames frames = RenderMove(
    [](vtkCamera* camera)
    {
      double position[3], focal[3];
      camera->GetPosition(position);
      camera->GetFocalPoint(focal);
      camera->SetPosition(position[0] + 1.2, position[1] + 0.4, position[2]);
      camera->SetFocalPoint(focal[0] + 1.2, focal[1] + 0.4, focal[2]);
    });
  Dump(frames.Before, "reprojection-pan-before");
  Dump(frames.Reprojected, "reprojection-pan-reprojected");
  Dump(frames.LowResolution, "reprojection-pan-low-resolution");
  Dump(frames.Truth, "reprojection-pan-truth");
  int vacated = 0;
  double worstReprojected = 0.0, worstLowResolution = 0.0;
  for (int y = 0; y < Size; ++y)
  {
    for (int x = 0; x < Size; ++x)
    {
      // Cloud before, background (and no cloud within two pixels) after.
      bool clearAfter = true;
      for (int j = std::max(0, y - 2); j <= std::min(Size - 1, y + 2); ++j)
        for (int i = std::max(0, x - 2); i <= std::min(Size - 1, x + 2); ++i)
          clearAfter = clearAfter && frames.Truth.At(i, j, 0) + frames.Truth.At(i, j, 1) == 0.0f;
      if (!clearAfter || frames.Before.At(x, y, 1) < 0.1f)
      {
        continue;
      }
      ++vacated;
      for (int c = 0; c < 3; ++c)
      {
        worstReprojected = std::max(worstReprojected, 255.0 * frames.Reprojected.At(x, y, c));
        worstLowResolution = std::max(worstLowResolution, 255.0 * frames.LowResolution.At(x, y, c));
      }
    }
  }
  std::cout << vacated << " pixels vacated; brightest there: reprojected " << worstReprojected
            << " levels, low resolution " << worstLowResolution << " levels\n";
  ASSERT_GT(vacated, 500);
  EXPECT_LE(worstReprojected, worstLowResolution + 1.0);
  // Nor anywhere worse than the low-resolution frame.
  EXPECT_LE(RmsDifference(frames.Reprojected, frames.Truth),
    1.05 * RmsDifference(frames.LowResolution, frames.Truth));
}

TEST(TemporalReprojection, ATransferFunctionChangeDropsTheHistory)
{
  // The cloud turns from the ramp's colours to blue between the still frame and a slightly
  // rotated interactive one: no trace of the old colours may remain, so the frame is the
  // low-resolution frame of the new state.
  Image frame[2];
  for (bool reprojection : { true, false })
  {
    CloudScene scene(reprojection);
    scene.Still();
    vtkNew<vtkColorTransferFunction> blue;
    blue->AddRGBPoint(0.0, 0.1, 0.2, 1.0);
    blue->AddRGBPoint(1.0, 0.2, 0.4, 1.0);
    scene.View.Property->SetColor(blue);
    scene.Camera()->Azimuth(3.0);
    frame[reprojection ? 0 : 1] = scene.Interactive();
  }
  Dump(frame[0], "reprojection-recolored");
  EXPECT_LE(MaxDifference(frame[0], frame[1]), 1.0 / 255.0 + 1e-6);
}
