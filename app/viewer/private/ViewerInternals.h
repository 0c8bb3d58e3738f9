// The viewer's state and helpers, shared by the files that implement Viewer: Viewer.cxx (the
// window, its layout and rendering), ViewerSaving.cxx (what s and w save), ViewerKeys.cxx (what
// the keys do), ViewerHistory.cxx (undo) and ViewerState.cxx (the state tests and tools read).
#ifndef cloudvis_ViewerInternals_h
#define cloudvis_ViewerInternals_h

#include "Display.h"
#include "KeyBindings.h"
#include "LiveLoop.h"
#include "RenderedImage.h"
#include "SliceColors.h"
#include "SlicePlanes.h"
#include "SliceViews.h"
#include "StatusOverlay.h"
#include "TransferFunctionEditor.h"
#include "Viewer.h"
#include "ViewerFiles.h"
#include "ViewerHistory.h"
#include "ViewerTimeSteps.h"
#include "vtkCloudViewerInteractorStyle.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkActor.h>
#include <vtkAxesActor.h>
#include <vtkImageData.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkNew.h>
#include <vtkOrientationMarkerWidget.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace cloudvis
{

struct Viewer::Internals
{
  Scene Current; // lighting, lights, step and resolution as they are now; see CurrentScene()
  // What Shift+r goes back to: the scene's function as the window opened with it (fitted to the
  // field's values where FitTransferFunctionOnOpening did).
  TransferFunctionSpec SceneTransferFunction;
  vtkSmartPointer<vtkImageData> Field;
  ViewerOptions Options;
  std::ostream* Messages = &std::cerr;

  // Declared first: the display must outlive the window.
  std::unique_ptr<DisplayConnection> Display;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> View;
  vtkNew<vtkRenderer> Editor;
  vtkNew<vtkRenderer> Overlay;
  vtkNew<vtkRenderWindowInteractor> Interactor;
  vtkNew<vtkCloudViewerInteractorStyle> Style;
  vtkNew<vtkCloudVolumeMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkSmartPointer<vtkVolumeProperty> Property;
  vtkNew<vtkActor> Outline;
  vtkNew<vtkAxesActor> Axes;
  vtkNew<vtkOrientationMarkerWidget> Orientation;
  vtkNew<vtkInteractorEventRecorder> Recorder;
  // The cloud's color legend: the transfer function's colors over density, at the 3D view's right
  // edge (the slices' color bar is SliceColors').
  vtkNew<vtkScalarBarActor> Legend;
  std::unique_ptr<StatusOverlay> Status;
  std::unique_ptr<TransferFunctionEditor> Editing;
  std::unique_ptr<SliceColors> Colors;
  std::unique_ptr<SlicePlanes> Slices;
  std::unique_ptr<SliceViews> Views2D;
  std::unique_ptr<LiveLoop> Loop;
  std::unique_ptr<ViewerTimeSteps> Time;
  // The 3D view draws the field averaged over this many voxels along each axis, to fit the GPU's
  // memory (FieldCoarsening.h), and what was said of it; 1 and "": as it is.
  int Coarsening = 1;
  std::string Coarsened;
  // The top right corner: the time step shown, and that the 3D view is coarsened.
  std::string CornerText() const;

  bool FourViews = false;
  bool LegendsVisible = true; // b: the color legends (the cloud's, and the slices' when shown)
  // A screenshot is being rendered: the views fill the window (ApplyLayout), which has the
  // screenshot's size off screen (CaptureLayout).
  bool Exporting = false;
  // The 3D view in the overlay's normalized viewport coordinates, where the legends go.
  std::array<double, 4> LegendArea{ { 0.0, 0.0, 1.0, 1.0 } };
  bool Typing = false;            // the keys type values (Typed)...
  bool TypingWindowLevel = false; // ... of the slices' window and level, else of a point
  std::string Typed;
  int PresetIndex = -1;
  bool PreviewNext = false;         // the next frame answers a key that changed the cloud
  bool LastFrameWasPreview = false; // the image is not at full resolution yet
  // Where refinement stood when it last asked for a frame: the frames rendered then and the
  // frames the mapper had accumulated.
  std::pair<long, int> RefinementCheck{ std::numeric_limits<long>::max(), 0 };
  // The automatic exposure (render.exposure "auto"): metered once per still, when it has
  // converged (StillComplete), on the mapper's float image; ExposureMetered says the still shown
  // has been, and is cleared by every frame that is not a converged still. AnnounceExposure: Ctrl+e
  // came before the still converged, and the metering says its EV when it comes.
  bool ExposureMetered = false;
  bool AnnounceExposure = false;
  // A path-traced still is checked once for walks the GPU cut short (CheckPathsWhole); cleared
  // with ExposureMetered.
  bool PathsChecked = false;
  long ExposureMeterings = 0;
  int MeteredFrames = 0; // the frames the still last metered had accumulated
  // Frames whose render marched the cloud: its accumulation grew or started over (a frame that
  // only composited the converged still again, under a new exposure say, counts none; a restart
  // from one accumulated frame to one, with render.accumulate 1, goes unseen).
  long MarchedFrames = 0;
  std::string Preset;
  std::vector<std::string> MessageLog;
  std::vector<std::string> SavedFiles;
  std::vector<HandledKey> Keys;
  long FramesRendered = 0;
  double LastFrameAt = -1.0;
  SliceProbe Hovered; // the voxel under the pointer on a slice; Valid false when none
  // What quitting would lose is compared with this: the edits (EditsOf) when the window opened
  // or the scene was last saved with w.
  std::string SavedEdits;
  // Undo (ViewerHistory.h): the state when the gesture in progress began, whether one is in
  // progress, whether it is a wheel's, and the mouse buttons held.
  UndoHistory History;
  UndoableState GestureStart;
  bool InGesture = false;
  bool WheelGesture = false;
  int ButtonsDown = 0;
  // When q (or closing the window) last asked before quitting with unsaved changes; a second
  // one within QuitConfirmSeconds quits.
  double QuitAskedAt = -1e300;

  // The viewer's construction, in its order. The window and its views: the cloud (its mapper,
  // volume and outline, the transfer function fitted where ParaView would), the editor's and the
  // overlay's renderers, the status and the time steps.
  void OpenViews(vtkImageData* field);
  // The interactor and the live loop, and the observers of its input: render requests, resizes,
  // the window manager's close, handled events and undo's gestures.
  void ObserveInput(Viewer& owner);
  // The interactor style, the transfer function editor and the keys, and the function's changes.
  void ConnectEditor(Viewer& owner, vtkImageData* field);
  // The slices, their colors and views, and both legends (after the interactor is initialized).
  void AddSlicesAndLegends(vtkImageData* field);

  // The scene's lights and lighting model on the 3D view and the mapper, as `render` sets them.
  void ApplyLighting();
  // Before the window opens: fits Current's transfer function to the field's value range where
  // ParaView would (Viewer.cxx says when). Returns the message that says so, or "".
  std::string FitTransferFunctionOnOpening(const std::array<double, 2>& range,
    const double bounds[6]);

  // Renders the window. A preview (asked for by a key that changes the cloud, in the live loop)
  // renders at the interactor's DesiredUpdateRate, so the mapper marches at a resolution that
  // keeps up with it, and leaves the full-resolution image to the refinement that follows.
  void RenderFrame();
  // Asks the live loop for a frame; the refinement after it starts over.
  void Request();
  // The frames the mapper averages for a still image (render.accumulate, 1 without jitter).
  int FramesToConverge() const;
  // The 3D view shows its final image (or no cloud to refine).
  bool Converged() const;
  // The 3D view shows a cloud's converged still at full resolution, and nothing is being dragged:
  // the picture the automatic exposure meters.
  bool StillComplete() const;
  // Meters the automatic exposure on the mapper's float image of the 3D view (ResolveExposureEV,
  // as `render` does after its still converges) and sets it on the mapper; the caller composites
  // again. Returns whether the EV changed. A float image that cannot be read, or holds NaN or
  // infinity, is shown as an error and the exposure kept.
  bool MeterExposure();
  // A path-traced still whose walks the GPU cut short (vtkCloudVolumeMapper::
  // CountCutPathTracePixels, which `render` refuses) is said as an error in the message line: it
  // stays on screen, but not as the truth.
  void CheckPathsWhole();
  // The scene's exposure on the mapper: render.exposure's EV, or with "auto" a metering of the
  // next converged still (now, when the one shown is). Returns whether it metered now.
  bool ApplyExposure();
  // e and E: the exposure EV steps (from the metered one when it was automatic, which they end);
  // Ctrl+e: automatic again.
  void StepExposure(double stops);
  void UseAutoExposure();
  // "exposure +0.50 EV", "exposure -1.37 EV (auto)": the exposure the mapper applies.
  std::string ExposureText() const;
  // Another frame would improve the image: it has not converged, nothing is being dragged, and
  // the last refinement frame did accumulate (a guard: something that restarted the accumulation
  // on every frame would otherwise keep the loop rendering forever).
  bool RefinementPending();
  // A message on screen (fading), in the log and on stderr.
  void Show(const std::string& text, bool error);
  // A renderer's viewport in window pixels: x0, y0, x1, y1 from the bottom left.
  std::array<int, 4> PixelViewport(vtkRenderer* renderer) const;
  // The 3D view's size in pixels.
  std::array<int, 2> ViewSize() const;
  // A slice is shown somewhere (and legends are on), so the color bar explains its colors.
  bool ColorBarWanted() const;
  // The legends are on and the cloud is shown.
  bool LegendWanted() const;
  // Places the renderers for the layout: the 3D view alone above the editor, or the four views
  // as 3D Slicer's "four-up" places them (axial top left, 3D top right, sagittal bottom left,
  // coronal bottom right). While Exporting the views fill the window and the editor is not
  // drawn.
  void ApplyLayout();
  // The legends at the 3D view's right edge, each shown when wanted.
  void PlaceLegends();
  // The scene's "view" section as the window shows it now (layout, slices, window/level, slice
  // colors, legends), and the reverse: the window set as a saved scene's view section says.
  ViewSpec CurrentView() const;
  void ApplyView(const ViewSpec& view);
  // An orthogonal slice is shown: in the 3D view, or the slice views.
  bool SlicesShown() const;
  // A voxel as the readout writes it, in the field's units (Options.Units): "probe (0.1, 0.2,
  // 0.3) km  voxel [1, 2, 3]  lwc 0.42 g/m^3".
  std::string VoxelText(const char* label, const SliceProbe& voxel) const;
  // The readout: the voxel under the pointer, over the last probe; nothing (and the probe
  // dropped) while no slice is shown.
  void UpdateReadout();
  // The pointer moved to window pixel x, y with no button held (-1, -1: it left the window).
  void Hover(int x, int y);
  // The slices moved, probed or changed their colors (from a plane, a slice view or a key).
  void SlicesChanged();
  // The screenshot's size: ViewerOptions::ScreenshotSize, or the views as the window shows them.
  std::array<int, 2> ScreenshotSize() const;
  // What s saves, rendered at `size` off screen (the window on screen keeps its size and
  // picture): the layout's views as the window shows them, converged, with the color legends,
  // without the editor and the viewer's texts (message, hint, help, readout); and with
  // `floatImage` the 3D view's float image (the cloud as `render` exports it).
  ScreenshotImages CaptureLayout(const std::array<int, 2>& size, bool floatImage);
  // The first directional light, or -1.
  int FirstDirectionalLight() const;
  // Turns the first directional light about its focal point (elevation within +-89 degrees).
  void MoveLight(double azimuthDegrees, double elevationDegrees);
  // render.step, or when it is 0 (automatic) the one voxel the mapper marches with
  // (EffectiveSampleDistance: the voxel edge after the volume's placement).
  double EffectiveStep() const;
  // p and Shift+p: the next preset of PresetDirectory(), the function saved as a preset.
  void LoadNextPreset();
  void SavePreset();
  // A key while typing a point's values: characters of numbers, BackSpace, Enter, Esc.
  void TypeKey(const std::string& keySym, char keyCode);
  // Enter: typing the selected point's values starts (a message when none is selected).
  void StartTyping();
  // Shift+l: typing the window and level starts; Enter sets them from Typed (returns what is
  // wrong with it, or ""), in the same entry line.
  void StartTypingWindowLevel();
  std::string SetTypedWindowLevel();
  // a: the window/level from the values of the slices shown.
  void AutoWindowLevel();
  // "WHAT: window W, level L (densities A to B)", for messages.
  std::string WindowLevelText(const std::string& what) const;
  void ToggleSlice(int axis);
  // PageUp / PageDown: the slice under the pointer (a slice view, or a slice in the 3D view),
  // else the last one shown, one voxel up (+1) or down (-1).
  void StepSlice(int step);
  // , and .: the field's previous (-1) or next (+1) time step, its values in place of the shown
  // step's (the grid, camera, slices and transfer function stay), and the one after it asked to
  // be read ahead (ViewerTimeSteps::ReadAheadLater). A step that cannot be read is an error
  // message, and the step shown stays.
  void StepTime(int direction);
  int ActiveAxis = 2; // the slice across z until another is shown
  // The edits a user would lose by quitting, as text to compare: the scene `w` saves, its view
  // section included (its size aside: resizing the window is no edit).
  std::string EditsOf(const Viewer& viewer) const;
  // There are edits since the window opened or the last w, and quitting would lose them (no
  // --save-scene-on-exit).
  bool UnsavedChanges(const Viewer& viewer) const;
  // What undo can take back, as it is now, and putting a state back (only what differs).
  UndoableState Undoable() const;
  void RestoreUndoable(const UndoableState& state);
  // A gesture begins (a button pressed, a wheel notch): the state before it is kept; a gesture
  // that ended (no button held, or a wheel notch handled) becomes an undo step if it changed
  // something. SettleGesture is called once input has been handled (the loop, playback, the
  // next gesture, a key).
  void BeginGesture(bool wheel);
  void SettleGesture();
  // Ctrl+z, Ctrl+y.
  void UndoStep(bool redo);
  // q or the window manager's close: quits, or with unsaved changes asks for a second q first.
  void Quit(const Viewer& viewer, bool fromWindowManager);
  // What a key of the table does; `variant` is the index of the key pressed in its row.
  void Act(ViewerAction action, int variant, Viewer& viewer);
  // Act's families of actions, each true when it knows the action (and has done it): the slices,
  // their colors and the time steps; the layout, what is shown, the camera and the help; the
  // lighting, the march and the exposure; the transfer function, its presets and undo; the files
  // the viewer writes, and quitting.
  bool ActOnSlices(ViewerAction action, int variant);
  bool ActOnView(ViewerAction action);
  bool ActOnRendering(ViewerAction action, int variant);
  bool ActOnTransferFunction(ViewerAction action);
  bool ActOnSession(ViewerAction action, Viewer& viewer);
};

} // namespace cloudvis

#endif
