// The viewer's state and helpers, shared by the files that implement Viewer: Viewer.cxx (the
// window, its layout and rendering, files), ViewerKeys.cxx (what the keys do) and
// ViewerState.cxx (the state tests and tools read).
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
#include "ViewerHistory.h"
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
  TransferFunctionSpec SceneTransferFunction; // what R goes back to
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
  std::unique_ptr<StatusOverlay> Status;
  std::unique_ptr<TransferFunctionEditor> Editing;
  std::unique_ptr<SliceColors> Colors;
  std::unique_ptr<SlicePlanes> Slices;
  std::unique_ptr<SliceViews> Views2D;
  std::unique_ptr<LiveLoop> Loop;

  bool FourViews = false;
  bool Typing = false; // the keys type a point's values
  std::string Typed;
  int PresetIndex = -1;
  bool PreviewNext = false;         // the next frame answers a key that changed the cloud
  bool LastFrameWasPreview = false; // the image is not at full resolution yet
  // Where refinement stood when it last asked for a frame: the frames rendered then and the
  // frames the mapper had accumulated.
  std::pair<long, int> RefinementCheck{ std::numeric_limits<long>::max(), 0 };
  std::string Preset;
  std::vector<std::string> MessageLog;
  std::vector<std::string> SavedFiles;
  std::vector<HandledKey> Keys;
  long FramesRendered = 0;
  double LastFrameAt = -1.0;
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

  // The scene's lights and lighting model on the 3D view and the mapper, as `render` sets them.
  void ApplyLighting();

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
  // A slice is shown somewhere, so the color bar explains its colors.
  bool ColorBarWanted() const;
  // Places the renderers for the layout: the 3D view alone above the editor, or the four views
  // as 3D Slicer's "four-up" places them (axial top left, 3D top right, sagittal bottom left,
  // coronal bottom right).
  void ApplyLayout();
  // The probe readout line from the last probe.
  void UpdateReadout();
  // The slices moved, probed or changed their colors (from a plane, a slice view or a key).
  void SlicesChanged();
  // The 3D view alone, converged (render.accumulate frames), without the viewer's own
  // decorations (texts, outline, orientation marker), so that `render` draws the same picture.
  RenderedImage Capture(bool floatImage);
  // The first directional light, or -1.
  int FirstDirectionalLight() const;
  // Turns the first directional light about its focal point (elevation within +-89 degrees).
  void MoveLight(double azimuthDegrees, double elevationDegrees);
  // render.step, or the field's smallest spacing when it is 0 (automatic).
  double EffectiveStep() const;
  // p and Shift+p: the next preset of PresetDirectory(), the function saved as a preset.
  void LoadNextPreset();
  void SavePreset();
  // A key while typing a point's values: characters of numbers, BackSpace, Enter, Esc.
  void TypeKey(const std::string& keySym, char keyCode);
  // Enter: typing the selected point's values starts (a message when none is selected).
  void StartTyping();
  void ToggleSlice(int axis);
  // The edits a user would lose by quitting, as text to compare: the scene `w` saves (its size
  // aside: resizing the window is no edit) and the slices.
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
};

} // namespace cloudvis

#endif
