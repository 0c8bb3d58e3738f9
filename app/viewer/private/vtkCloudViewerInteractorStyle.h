/**
 * @class   vtkCloudViewerInteractorStyle
 * @brief   trackball camera in the 3D view, chart events in the transfer-function editor
 *
 * The viewer's window holds two interactive viewports: the 3D view and the editor's charts
 * (a vtkContextScene drawn by a vtkContextActor). One interactor style serves both: each mouse
 * event goes to the chart scene when it happens over the editor's renderer, else to the
 * trackball camera of vtkInteractorStyleTrackballCamera. A drag belongs to the viewport where its
 * button went down until the button comes up, so a camera drag that wanders over the editor keeps
 * turning the camera and a point drag that leaves the editor keeps moving the point.
 *
 * Keys never reach VTK's default bindings (w, s, p, f, r, 3, ... would change the cloud's
 * representation or camera behind the viewer's back): every key press goes to the chart first
 * when the pointer is over the editor (Delete removes the current control point there), then to
 * KeyHandler. The 3D widgets (slice planes) observe the interactor themselves, ahead of the
 * style, and take the events that hit them.
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
   * Called for every key press with the key's symbol ("m", "P", "Left", "plus") and its
   * character (0 for keys without one). Default none.
   */
  std::function<void(const std::string& keySym, char keyCode)> KeyHandler;

  /**
   * Called when a chart drag starts (true) and ends (false), so the window can render at
   * interactive speed meanwhile. Default none.
   */
  std::function<void(bool dragging)> ChartDragHandler;

  /**
   * Whether the last event position lies over the editor's viewport.
   */
  bool IsOverEditor() const;

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
  void OnKeyPress() override;
  void OnChar() override;

protected:
  vtkCloudViewerInteractorStyle();
  ~vtkCloudViewerInteractorStyle() override;

private:
  enum class Grab
  {
    None,
    Chart,
    Camera
  };
  // Which viewport owns the drag in progress.
  Grab Owner = Grab::None;
  vtkRenderer* EditorRenderer = nullptr;
  // Handles the chart events; it is handed the interactor without observing it itself.
  vtkSmartPointer<vtkContextInteractorStyle> Chart;

  // A button went down: does the editor take it?
  bool PressGoesToChart();
  // A button came up: returns whether the chart owned the drag.
  bool ReleaseGoesToChart();
};

#endif
