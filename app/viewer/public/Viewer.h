// `cloudvis view`: the interactive viewer. One vtkRenderWindow (no Qt) holds the 3D view of the
// cloud in the upper three quarters, drawn exactly as `render` draws it (the configuration
// functions of export/OffscreenRender.h, SceneLighting.h and Background.h), with the slice
// widgets of SlicePlanes.h; the transfer-function editor (TransferFunctionEditor.h) in the
// bottom quarter; and a text overlay for help and messages over the 3D view. Keys change the
// lighting, step, resolution and presets, save screenshots and scenes (docs/viewer.md lists them);
// sessions can be recorded and replayed with vtkInteractorEventRecorder.
//
// Everything the user can change is kept in the Scene the viewer was opened with, so the scene
// it saves (SceneToJson) re-renders with `cloudvis render` to the image the window showed.
#ifndef cloudvis_Viewer_h
#define cloudvis_Viewer_h

#include "Scene.h"

#include <vtkSmartPointer.h>

#include <array>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

class vtkImageData;

namespace cloudvis
{

struct ViewerOptions
{
  std::array<int, 2> WindowSize{ { 800, 800 } }; // pixels; the 3D view is the top 75%
  std::string OutputDirectory = ".";             // where s, w and shift-p write
  std::string RecordFile;                        // --record: the session's events, as VTK writes them
  std::string CommandLine;                       // embedded in screenshots' metadata
  std::ostream* Messages = nullptr;              // messages besides the window (stderr by default)
};

// What a test or a caller can ask the viewer about its state.
struct ViewerState
{
  LightingModel Lighting = LightingModel::None;
  std::array<bool, 3> SliceVisible{ { false, false, false } };
  std::array<double, 3> SlicePosition{ { 0.0, 0.0, 0.0 } };
  std::array<double, 3> ProbedValue{ { 0.0, 0.0, 0.0 } }; // NaN where not probed
  bool ObliqueVisible = false;
  std::array<double, 3> ObliqueOrigin{ { 0.0, 0.0, 0.0 } };
  std::array<double, 3> ObliqueNormal{ { 0.0, 0.0, 1.0 } };
  long ObliqueCutPoints = 0;
  TransferFunctionSpec TransferFunction;
  double Step = 0.0;
  double ResolutionScale = 1.0;
  bool HelpVisible = false;
  bool LogHistogram = true;
  std::array<double, 2> EditorRange{ { 0.0, 1.0 } };
  std::array<double, 3> FirstLightPosition{ { 0.0, 0.0, 0.0 } };
  std::string Preset;                 // the preset last loaded, empty for none
  std::vector<std::string> Messages;  // every message shown, in order
  std::vector<std::string> SavedFiles;
  int AccumulatedFrames = 0;
  std::array<int, 2> ViewSize{ { 0, 0 } }; // the 3D view's pixels
};

class Viewer
{
public:
  // Opens the window (throws InputError without a display, like render). `field` is the scene's
  // field, already produced.
  Viewer(const Scene& scene, vtkSmartPointer<vtkImageData> field, const ViewerOptions& options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // Replays a recording (vtkInteractorEventRecorder's text format) from a file or a string,
  // synchronously; the window stays open afterwards.
  void PlayFile(const std::string& path);
  void PlayString(const std::string& events);

  // Runs the event loop until the window is closed (or q / Escape).
  void Start();

  // The key bindings, as the keys do them (also for tests).
  void PressKey(const std::string& keySym, char keyCode);

  ViewerState State() const;

  // The scene as the window shows it: the transfer function, lighting, light, step, resolution
  // scale and camera as they are now, render.size the 3D view's size.
  Scene CurrentScene() const;
  nlohmann::json CurrentSceneJson() const;

  // Writes CurrentSceneJson() to `path` atomically. Throws InputError.
  void SaveScene(const std::string& path) const;

  // s: cloudvis-screenshot-NNN.png and .exr; w: cloudvis-view-NNN.json (the first NNN free in
  // the output directory). Failures become messages; the session goes on.
  void SaveScreenshot();
  void SaveSceneFile();

  // The whole window as it is now (3D view, editor, overlays), as an 8-bit PNG: for tests and
  // for looking at the layout.
  void SaveWindowImage(const std::string& path);

private:
  struct Internals;
  std::unique_ptr<Internals> Internal;
};

} // namespace cloudvis

#endif
