// `cloudvis view`: the interactive viewer. One vtkRenderWindow (no Qt) holds, in its upper three
// quarters, either the 3D view of the cloud alone or four views (the 3D view and the axial,
// coronal and sagittal slices, SliceViews.h); the transfer-function editor
// (TransferFunctionEditor.h) in the bottom quarter; and a text overlay (StatusOverlay.h). The 3D
// view is drawn exactly as `render` draws it (the configuration functions of
// export/OffscreenRender.h, SceneLighting.h and Background.h), with the slice widgets of
// SlicePlanes.h, an outline of the field and an orientation marker. Keys (KeyBindings.h; docs/
// viewer.md lists them) change the layout, slices, lighting, step, resolution and transfer
// function, step through the field's time steps (ViewerTimeSteps.h) and save screenshots, scenes
// and presets (ViewerFiles.h). The event loop (LiveLoop.h) renders only when something changed or
// the image is still refining. Sessions can be recorded and replayed with
// vtkInteractorEventRecorder.
//
// Everything the user can change is kept in the Scene the viewer was opened with, so the scene
// it saves (SceneToJson) re-renders with `cloudvis render` to the image the window showed.
#ifndef cloudvis_Viewer_h
#define cloudvis_Viewer_h

#include "FieldIO.h"
#include "Scene.h"

#include <vtkSmartPointer.h>

#include <array>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

class vtkImageData;
class vtkTextProperty;

namespace cloudvis
{

struct ViewerOptions
{
  std::array<int, 2> WindowSize{ { 800, 800 } }; // pixels; the 3D view is the top 75%
  std::string OutputDirectory = ".";             // where s, w and shift-p write
  std::string RecordFile;  // --record: the session's events, as VTK writes them
  std::string StateFile;   // --state-file: ViewerStateJson written after every frame or input
  // s saves the views at this size in pixels (--screenshot-size); 0 x 0: as the window shows
  // them (the window's width, the height above the editor).
  std::array<int, 2> ScreenshotSize{ { 0, 0 } };
  // --save-scene-on-exit: the scene is written when the viewer ends, so quitting loses nothing
  // and q quits without asking.
  bool SceneSavedOnExit = false;
  std::string CommandLine; // embedded in screenshots' metadata
  std::ostream* Messages = nullptr; // messages besides the window (stderr by default)
  // The field was opened as a file (`cloudvis view FIELD.vti`), not through a scene: its transfer
  // function is fitted to its values on opening, as ParaView does (docs/viewer.md).
  bool FieldFile = false;
  // What the field's values and lengths mean, for the readouts and the legends' titles
  // (FieldUnits.h).
  ResolvedFieldUnits Units;
  // The field's time steps (a NetCDF file's time axis, a numbered file series): reads step N as
  // `render --time-step N` reads it, filling `report`; throws InputError. Empty for a field
  // without them (a generated one). `Opened` is what the read of the field shown first said: its
  // step, time and the number of steps.
  std::function<vtkSmartPointer<vtkImageData>(int step, FieldReport& report)> ReadTimeStep;
  FieldReport Opened;
};

// A key press the viewer handled, with when (MonotonicSeconds: CLOCK_MONOTONIC) it was handled
// and when the first frame rendered after it was complete (negative until then).
struct HandledKey
{
  std::string KeySym;
  double HandledAt = 0.0;
  double ShownAt = -1.0;
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
  std::string HelpPage; // the help page shown: "keys", "mouse-3d", "mouse-2d", or empty
  std::vector<std::array<int, 4>> HelpBoxes; // its columns, window pixels x0, y0, x1, y1
  int HelpFontSize = 0;
  bool UnsavedChanges = false; // edits since the window opened or the last w (docs/viewer.md)
  bool LogHistogram = true;
  std::array<double, 2> EditorRange{ { 0.0, 1.0 } };
  std::array<double, 3> FirstLightPosition{ { 0.0, 0.0, 0.0 } };
  std::string Preset;                // the preset last loaded, empty for none
  std::vector<std::string> Messages; // every message shown, in order
  std::vector<std::string> SavedFiles;
  int AccumulatedFrames = 0;
  std::array<int, 2> ViewSize{ { 0, 0 } }; // the 3D view's pixels
  // The display transform the 3D view applies: the EV (the metered one while AutoExposure),
  // render.display's curve ("linear", "filmic"), how many stills the automatic exposure has
  // metered, and how many frames the last one had accumulated.
  double ExposureEV = 0.0;
  bool AutoExposure = false;
  std::string Display;
  long ExposureMeterings = 0;
  int MeteredFrames = 0;

  // The live loop.
  long FramesRendered = 0;
  // Of them, those that marched the cloud (its accumulation grew or started over); a frame that
  // composited the converged still again (a message, a new exposure) marched nothing.
  long MarchedFrames = 0;
  double LastFrameAt = -1.0;    // MonotonicSeconds when the last frame was complete
  bool Converged = false;       // the 3D view has all the frames render.accumulate asks for,
                                // and its multiple-scattering volume is up to date
  std::vector<HandledKey> Keys; // the last 64 handled
  // The camera of the 3D view.
  std::array<double, 3> CameraPosition{ { 0.0, 0.0, 0.0 } };
  std::array<double, 3> CameraFocalPoint{ { 0.0, 0.0, 0.0 } };
  std::array<double, 3> CameraViewUp{ { 0.0, 1.0, 0.0 } };
  // Layout and what is shown.
  bool FourViews = false;
  bool VolumeVisible = true;
  bool HintVisible = true;
  bool ColorBarVisible = false;
  bool LegendVisible = false; // the cloud's color legend
  std::string Message;        // the message on screen, as wrapped; empty once faded
  std::string Readout;        // the probe readout line
  std::string Progress;       // the progress line ("multiple scattering: converging (k/n)")
  // The field's time steps: the one shown, how many there are (1 without a time axis), the time
  // line ("time step 3 of 0 .. 19: t = 180 s"; empty without), and the step read ahead, waiting
  // to be shown (-1: none).
  int TimeStep = 0;
  int TimeSteps = 1;
  std::string Time;
  int ReadAhead = -1;
  // The 3D view draws the field coarsened to fit the GPU's memory: what was said (empty: no).
  std::string Coarsened;
  unsigned long WindowId = 0; // the X window
  std::array<int, 2> WindowSize{ { 0, 0 } };
  // Viewports in window pixels x0, y0, x1, y1 from the bottom left: "3d", "editor", and in the
  // four-view layout "axial", "coronal", "sagittal".
  std::vector<std::pair<std::string, std::array<int, 4>>> Viewports;
  // Slices.
  std::array<int, 3> SliceIndex{ { 0, 0, 0 } };
  std::array<double, 2> SliceWindowLevel{ { 1.0, 0.5 } };
  std::string SliceColors;
  bool ProbeValid = false;
  std::array<int, 3> ProbeIndex{ { 0, 0, 0 } };
  double ProbeValue = 0.0;
  // The slice views' zoom (1: fitted) and pan (world units along the view's right and up axes):
  // axial, coronal, sagittal.
  std::array<double, 3> SliceViewZoom{ { 1.0, 1.0, 1.0 } };
  std::array<std::array<double, 2>, 3> SliceViewPan{};
  // The voxel under the pointer on a slice, as the readout shows it.
  bool HoverValid = false;
  std::array<int, 3> HoverIndex{ { 0, 0, 0 } };
  double HoverValue = 0.0;
  // The editor: where its points are drawn (window pixels), the selected point, typed entry,
  // undo history.
  std::vector<std::array<double, 2>> OpacityPointPixels;
  std::vector<std::array<double, 2>> ColorPointPixels;
  std::array<double, 4> ColorStripPixels{ { 0.0, 0.0, 0.0, 0.0 } };
  bool PaletteVisible = false; // the color palette, while a color point is selected
  std::array<double, 4> PalettePixels{ { 0.0, 0.0, 0.0, 0.0 } };
  std::string SelectedFunction; // "opacity", "color" or empty
  int SelectedPoint = -1;
  std::string EditorInfo;      // the editor's info line (selected point, typed entry)
  bool EditorTooltips = false; // the value tooltip by the point under the pointer
  std::string HoverTooltip;    // the chart's tooltip (a histogram bar under the pointer), or empty
  std::string DragTooltip;     // the dragged point's tooltip, or empty
  bool Typing = false;         // typing a point's values
  int UndoDepth = 0;
  int RedoDepth = 0;
};

// The state as JSON (the --state-file format, docs/viewer.md); text that is not UTF-8 (a path
// from --output-dir) is escaped as \xNN.
nlohmann::json ViewerStateJson(const ViewerState& state);

// The key bindings as the Markdown table docs/viewer.md holds (`cloudvis view --keys`).
std::string ViewerKeysMarkdown();
// The mouse bindings, likewise (`cloudvis view --mouse`).
std::string ViewerMouseMarkdown();

// Sets the font of the viewer's texts (messages, readout, editor, slice captions; the help keeps
// Courier, for its columns). VTK's embedded Arial, every vtkTextProperty's default, draws '[' and
// ']' as round brackets (its glyphs have no square corners: "[0, 4.58]" reads as an open
// interval), so the texts use DejaVu Sans (fonts-dejavu-core, cmake/debian-packages.txt) or
// Liberation Sans from the system, and where neither is installed VTK's embedded Courier, whose
// brackets are square. Returns the font file used ("" for Courier).
std::string UseViewerFont(vtkTextProperty* text);

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

  // Runs the event loop (LiveLoop.h) until q or the window is closed (a second time within a few
  // seconds when there are unsaved changes).
  void Start();

  // The key bindings, as the keys do them (also for tests).
  void PressKey(const std::string& keySym, char keyCode, bool control = false);

  ViewerState State() const;

  // The scene as the window shows it: the transfer function, lighting, light, step, resolution
  // scale and camera as they are now, render.size the 3D view's size, and the view section
  // (layout, slices, window/level, slice colors, legends).
  Scene CurrentScene() const;
  nlohmann::json CurrentSceneJson() const;

  // Writes CurrentSceneJson() to `path` atomically. Throws InputError.
  void SaveScene(const std::string& path) const;

  // s: cloudvis-screenshot-NNN.png (the layout's views with their color legends, at
  // ViewerOptions::ScreenshotSize) and .exr (the 3D view's float image); w: cloudvis-view-NNN.json
  // (the first NNN free in the output directory; ViewerFiles.h). Failures become messages; the
  // session goes on.
  void SaveScreenshot();
  void SaveSceneFile();

  // The whole window as it is now (3D view, editor, overlays), as an 8-bit PNG: for tests and
  // for looking at the layout.
  void SaveWindowImage(const std::string& path);

private:
  // Writes ViewerStateJson(State()) to the --state-file, if any.
  void WriteStateFile() const;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

} // namespace cloudvis

#endif
