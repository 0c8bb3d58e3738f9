/**
 * @class   vtkCloudViewerInteractorStyle
 * @brief   routes the viewer window's mouse and keys: trackball camera, 2D slice views, editor
 *
 * The viewer's window holds several interactive viewports: the 3D view, in the four-view layout
 * three 2D slice views, and the transfer-function editor's charts (a vtkContextScene drawn by a
 * vtkContextActor). One interactor style serves them all: a button press goes to the chart scene
 * when it happens over the editor's renderer, to SliceViewMouse when that handler takes it (the
 * pointer is over a slice view), else to the trackball camera of
 * vtkInteractorStyleTrackballCamera. A drag belongs to the viewport where its button went down
 * until the button comes up, so a camera drag that wanders over the editor keeps turning the
 * camera and a point drag that leaves the editor keeps moving the point.
 *
 * The camera moves only with mouse motion: OnTimer does nothing, because
 * vtkInteractorStyle::OnTimer repeats the last motion (Rotate() with the last event positions)
 * on every interactor timer while a button is held, which turned a held drag on and on.
 *
 * Keys never reach VTK's default bindings (w, s, p, f, r, 3, ... would change the cloud's
 * representation or camera behind the viewer's back), nor the charts' own (which act on key
 * release, and move points with the arrow keys): every key press goes to KeyHandler alone, which
 * the viewer drives from its key table. The 3D widgets (slice planes) observe the interactor
 * themselves, ahead of the style, and take the events that hit them, but for a plain left
 * drag, which always turns the camera (Ctrl+left probes a slice).
 *
 * Nothing here renders: the style and the charts ask for a frame through the interactor's
 * Render(), which the viewer's live loop turns into a request (LiveLoop.h).
 */
#ifndef vtkCloudViewerInteractorStyle_h
#define vtkCloudViewerInteractorStyle_h

#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkSmartPointer.h>

#include <functional>
#include <string>

class vtkContextInteractorStyle;
class vtkContextScene;
class vtkRenderer;

class vtkCloudViewerInteractorStyle : public vtkInteractorStyleTrackballCamera
{
public:
  static vtkCloudViewerInteractorStyle* New();
  vtkTypeMacro(vtkCloudViewerInteractorStyle, vtkInteractorStyleTrackballCamera);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  vtkCloudViewerInteractorStyle(const vtkCloudViewerInteractorStyle&) = delete;
  void operator=(const vtkCloudViewerInteractorStyle&) = delete;

  /**
   * The editor: its renderer (whose viewport receives chart events) and its scene.
   * Default none: every event goes to the trackball.
   */
  void SetEditor(vtkRenderer* renderer, vtkContextScene* scene);

  /**
   * Called for every key press with the key's symbol ("m", "P", "Left", "plus"), its character
   * (0 for keys without one) and whether Control was held. Default none.
   */
  std::function<void(const std::string& keySym, char keyCode, bool control)> KeyHandler;

  enum class MouseAction
  {
    Press,
    Move,
    Release,
    WheelForward,
    WheelBackward
  };
  /**
   * The 2D slice views' mouse handler: called for presses and wheel turns not over the editor
   * (it returns whether it takes them: the pointer is over a slice view), and for the moves and
   * the release of a drag it took. `button` is 1 left, 2 middle, 3 right, 0 for moves and
   * wheels; x, y are the event position in window pixels. Default none.
   */
  std::function<bool(MouseAction action, int button, int x, int y)> SliceViewMouse;

  /**
   * Called for every mouse move while no button is held (x, y in window pixels), and with
   * -1, -1 when the pointer leaves the window: the readout of the voxel under the pointer
   * follows it. Default none.
   */
  std::function<void(int x, int y)> HoverHandler;

  /**
   * Called when a drag in the editor or a slice view starts (true) and ends (false), so that
   * the window renders at interactive speed meanwhile. Default none.
   */
  std::function<void(bool dragging)> DragHandler;

  /**
   * Called when the pointer, no button held, leaves the editor's viewport (or the window from
   * over the editor), so that the editor hides its hover tooltip. Default none.
   */
  std::function<void()> EditorLeft;

  /**
   * Whether the last event position lies over the editor's viewport.
   */
  bool IsOverEditor() const;

  /**
   * Whether a mouse button is held in some viewport (camera, editor or slice view).
   */
  bool IsDragging() const;

  void SetInteractor(vtkRenderWindowInteractor* interactor) override;
  void OnMouseMove() override;
  void OnLeftButtonDown() override;
  void OnLeftButtonUp() override;
  void OnMiddleButtonDown() override;
  void OnMiddleButtonUp() override;
  void OnRightButtonDown() override;
  void OnRightButtonUp() override;
  void OnMouseWheelForward() override;
  void OnMouseWheelBackward() override;
  void OnLeave() override;
  void OnKeyPress() override;
  void OnChar() override;
  void OnTimer() override;

protected:
  vtkCloudViewerInteractorStyle();
  ~vtkCloudViewerInteractorStyle() override;

private:
  enum class Grab
  {
    None,
    Chart,
    SliceView,
    Camera
  };
  // Which viewport owns the drag in progress.
  Grab Owner = Grab::None;
  // The last move without a drag was over the editor.
  bool WasOverEditor = false;
  vtkRenderer* EditorRenderer = nullptr;
  // Handles the chart events; it is handed the interactor without observing it itself.
  vtkSmartPointer<vtkContextInteractorStyle> Chart;

  // A button went down: who takes it?
  Grab Press(int button);
  // A button came up: returns who owned the drag, and ends it.
  Grab Release(int button);
  // The press and release of button 1 (left), 2 (middle) or 3 (right), routed.
  void ChartButton(int button, bool down);
  void CameraButton(int button, bool down);
  void ButtonDown(int button);
  // A wheel turn that the editor (nothing) or a slice view takes from the camera.
  bool WheelTakenElsewhere(MouseAction action);
  void ButtonUp(int button);
};

#endif
