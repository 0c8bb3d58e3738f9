// `cloudvis animate`: a numbered sequence of stills of one scene, each made by RenderOffscreen and
// written by WriteImage like `render` makes one, so every frame is exactly the still of the scene
// it records in its metadata. Two motions:
//   turntable  the camera orbits the focal point about the scene's view-up, 360 degrees over the
//              N frames (frame i at 360 i / N degrees, so frame N would be frame 0 again: the
//              sequence loops);
//   time       the field is generated again for each frame at t_i = T0 + i (T1 - T0) / (N - 1)
//              (wind and morph move; the camera stays).
// Frames are written one by one, each atomically, into a directory created when the first frame
// is written: a failure part-way leaves the frames before it complete and no partial frame.
#ifndef cloudvis_Animate_h
#define cloudvis_Animate_h

#include "ImageWriters.h"
#include "Scene.h"

#include <functional>
#include <string>
#include <vector>

namespace cloudvis
{

struct AnimationRequest
{
  int Frames = 1;
  bool Turntable = false; // else the time steps, else the time range below
  // The field file's time steps, one per frame (field.time_step of each frame's scene).
  std::vector<int> TimeSteps;
  double TimeBegin = 0.0;
  double TimeEnd = 0.0;
  // The input is a field file given alone, without a scene: its transfer function is the
  // default fitted to the first frame's field (FitTransferFunctionNote).
  bool FieldFileAlone = false;
  std::string Directory;         // without a trailing slash
  std::string Extension = ".png"; // ".png" or ".exr"
  ImageExportOptions Export;     // format options and the command line; the scene is per frame
};

// "DIR/frame_0007.png": the index zero-padded to at least 4 digits, more when N - 1 needs them.
std::string FrameFileName(const AnimationRequest& request, int index);

// The time of frame `index` (the time mode): T0 + i (T1 - T0) / (N - 1), T0 for one frame, T1
// exactly for the last.
double FrameTime(const AnimationRequest& request, int index);

// Throws InputError unless the frames can be written to `directory`: an existing writable
// directory, or a missing one whose parent is a writable directory. Creates nothing.
void CheckAnimationDirectory(const std::string& directory);

// Renders and writes the frames of `scene` (a procedural field is generated for each time; a
// field.file is read once for the turntable, and at each frame's step for request.TimeSteps,
// whose last step is checked against the file's before frame 0 is written: CheckTimeSteps).
// `input` names the scene in errors. `progress` is told
// the label and overall fraction as the work advances. The transfer function is fitted to the
// first frame's field (FitTransferFunctionNote, said in `transferFunctionNote`) and kept for
// every frame. Returns the number of frames written. On failure throws the InputError of the
// failing step; after frame 0 it adds " (frame i; frames 0 .. i-1 were written)".
int RenderAnimation(const Scene& scene, const std::string& input, const AnimationRequest& request,
  const std::function<void(const std::string& label, double fraction)>& progress = {},
  std::string* transferFunctionNote = nullptr);

} // namespace cloudvis

#endif
