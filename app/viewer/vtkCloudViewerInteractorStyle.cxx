// Routing by viewport. The chart half is VTK's own vtkContextInteractorStyle, which turns the
// interactor's events into vtkContextMouseEvents for the scene; a subclass takes the interactor
// without adding observers to it, so it only ever sees the events this style forwards, and asks
// for a frame through the interactor when the scene changed instead of through a timer. The
// scene reads event positions in window pixels, which equal its own coordinates because the
// editor's viewport starts at the window's bottom-left corner.
#include "vtkCloudViewerInteractorStyle.h"

#include <vtkContextInteractorStyle.h>
#include <vtkContextScene.h>
#include <vtkObjectFactory.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

namespace
{
class vtkCloudChartEventStyle : public vtkContextInteractorStyle
{
public:
  static vtkCloudChartEventStyle* New();
  vtkTypeMacro(vtkCloudChartEventStyle, vtkContextInteractorStyle);
  // No observers: the viewer's style calls the On* methods itself.
  void SetInteractor(vtkRenderWindowInteractor* interactor) override
  {
    this->Interactor = interactor;
  }
  // VTK's version renders on a 40 ms one-shot timer, which the viewer's loop does not run: ask
  // for a frame once the event is handled instead.
  void OnSceneModified() override
  {
    if (this->Scene && this->Scene->GetDirty() && this->ProcessingEvents == 0 && this->Interactor &&
      this->Interactor->GetInitialized())
    {
      this->Interactor->Render();
    }
  }

protected:
  vtkCloudChartEventStyle() = default;
  ~vtkCloudChartEventStyle() override = default;
};
vtkStandardNewMacro(vtkCloudChartEventStyle);
} // namespace

vtkStandardNewMacro(vtkCloudViewerInteractorStyle);

vtkCloudViewerInteractorStyle::vtkCloudViewerInteractorStyle()
  : Chart(vtkSmartPointer<vtkCloudChartEventStyle>::New())
{
}

vtkCloudViewerInteractorStyle::~vtkCloudViewerInteractorStyle()
{
  this->Chart->SetScene(nullptr);
}

void vtkCloudViewerInteractorStyle::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EditorRenderer: " << this->EditorRenderer << "\n";
  os << indent << "Owner: " << static_cast<int>(this->Owner) << "\n";
}

void vtkCloudViewerInteractorStyle::SetEditor(vtkRenderer* renderer, vtkContextScene* scene)
{
  this->EditorRenderer = renderer;
  this->Chart->SetScene(scene);
}

void vtkCloudViewerInteractorStyle::SetInteractor(vtkRenderWindowInteractor* interactor)
{
  this->Superclass::SetInteractor(interactor);
  this->Chart->SetInteractor(interactor);
}

bool vtkCloudViewerInteractorStyle::IsOverEditor() const
{
  if (!this->EditorRenderer || !this->Interactor)
  {
    return false;
  }
  const int* position = this->Interactor->GetEventPosition();
  return this->EditorRenderer->IsInViewport(position[0], position[1]) != 0;
}

bool vtkCloudViewerInteractorStyle::IsDragging() const
{
  return this->Owner != Grab::None || this->State != VTKIS_NONE;
}

vtkCloudViewerInteractorStyle::Grab vtkCloudViewerInteractorStyle::Press(int button)
{
  if (this->Owner != Grab::None)
  {
    return Grab::None; // a second button during a drag: the drag's owner keeps the events
  }
  const int* position = this->Interactor->GetEventPosition();
  if (this->IsOverEditor())
  {
    this->Owner = Grab::Chart;
  }
  else if (this->SliceViewMouse &&
    this->SliceViewMouse(MouseAction::Press, button, position[0], position[1]))
  {
    this->Owner = Grab::SliceView;
  }
  else
  {
    this->Owner = Grab::Camera;
  }
  if (this->Owner != Grab::Camera && this->DragHandler)
  {
    this->DragHandler(true);
  }
  return this->Owner;
}

vtkCloudViewerInteractorStyle::Grab vtkCloudViewerInteractorStyle::Release(int button)
{
  const Grab owner = this->Owner;
  this->Owner = Grab::None;
  if (owner == Grab::SliceView)
  {
    const int* position = this->Interactor->GetEventPosition();
    this->SliceViewMouse(MouseAction::Release, button, position[0], position[1]);
  }
  if ((owner == Grab::Chart || owner == Grab::SliceView) && this->DragHandler)
  {
    // After the chart has seen the release (the caller forwards it first for the chart).
    this->DragHandler(false);
  }
  return owner;
}

void vtkCloudViewerInteractorStyle::OnMouseMove()
{
  const int* position = this->Interactor->GetEventPosition();
  switch (this->Owner)
  {
    case Grab::Chart:
      this->Chart->OnMouseMove();
      break;
    case Grab::SliceView:
      this->SliceViewMouse(MouseAction::Move, 0, position[0], position[1]);
      break;
    case Grab::Camera:
      this->Superclass::OnMouseMove();
      break;
    case Grab::None:
    {
      const bool over = this->IsOverEditor();
      if (over)
      {
        this->Chart->OnMouseMove(); // hover highlights and tooltip
      }
      else if (this->WasOverEditor && this->EditorLeft)
      {
        this->EditorLeft();
      }
      this->WasOverEditor = over;
      if (this->HoverHandler)
      {
        this->HoverHandler(position[0], position[1]);
      }
      break;
    }
  }
}

void vtkCloudViewerInteractorStyle::ChartButton(int button, bool down)
{
  vtkContextInteractorStyle* chart = this->Chart;
  switch (button)
  {
    case 1:
      down ? chart->OnLeftButtonDown() : chart->OnLeftButtonUp();
      break;
    case 2:
      down ? chart->OnMiddleButtonDown() : chart->OnMiddleButtonUp();
      break;
    default:
      down ? chart->OnRightButtonDown() : chart->OnRightButtonUp();
      break;
  }
}

void vtkCloudViewerInteractorStyle::CameraButton(int button, bool down)
{
  // The trackball's handlers, not this class's overrides.
  switch (button)
  {
    case 1:
      down ? this->Superclass::OnLeftButtonDown() : this->Superclass::OnLeftButtonUp();
      break;
    case 2:
      down ? this->Superclass::OnMiddleButtonDown() : this->Superclass::OnMiddleButtonUp();
      break;
    default:
      down ? this->Superclass::OnRightButtonDown() : this->Superclass::OnRightButtonUp();
      break;
  }
}

void vtkCloudViewerInteractorStyle::ButtonDown(int button)
{
  switch (this->Press(button))
  {
    case Grab::Chart:
      if (button == 1)
      {
        // The charts route the moves of a double click's second press nowhere, so a point
        // grabbed again within 400 ms of its release would not move: every press is a single
        // one here.
        this->Interactor->SetRepeatCount(0);
      }
      this->ChartButton(button, true);
      break;
    case Grab::Camera:
      this->CameraButton(button, true);
      break;
    default:
      break;
  }
}

void vtkCloudViewerInteractorStyle::ButtonUp(int button)
{
  if (this->Owner == Grab::Chart)
  {
    this->ChartButton(button, false);
  }
  if (this->Release(button) == Grab::Camera)
  {
    this->CameraButton(button, false);
  }
}

void vtkCloudViewerInteractorStyle::OnLeftButtonDown()
{
  this->ButtonDown(1);
}

void vtkCloudViewerInteractorStyle::OnLeftButtonUp()
{
  this->ButtonUp(1);
}

void vtkCloudViewerInteractorStyle::OnMiddleButtonDown()
{
  this->ButtonDown(2);
}

void vtkCloudViewerInteractorStyle::OnMiddleButtonUp()
{
  this->ButtonUp(2);
}

void vtkCloudViewerInteractorStyle::OnRightButtonDown()
{
  this->ButtonDown(3);
}

void vtkCloudViewerInteractorStyle::OnRightButtonUp()
{
  this->ButtonUp(3);
}

// The wheel dollies the camera in the 3D view and steps the slice in a slice view; over the
// editor it does nothing (the charts' zoom is off: their axes always show the transfer
// function's range).
bool vtkCloudViewerInteractorStyle::WheelTakenElsewhere(MouseAction action)
{
  const int* position = this->Interactor->GetEventPosition();
  return this->Owner != Grab::None || this->IsOverEditor() ||
    (this->SliceViewMouse && this->SliceViewMouse(action, 0, position[0], position[1]));
}

void vtkCloudViewerInteractorStyle::OnMouseWheelForward()
{
  if (!this->WheelTakenElsewhere(MouseAction::WheelForward))
  {
    this->Superclass::OnMouseWheelForward();
  }
}

void vtkCloudViewerInteractorStyle::OnMouseWheelBackward()
{
  if (!this->WheelTakenElsewhere(MouseAction::WheelBackward))
  {
    this->Superclass::OnMouseWheelBackward();
  }
}

void vtkCloudViewerInteractorStyle::OnKeyPress()
{
  if (!this->Interactor || !this->KeyHandler)
  {
    return;
  }
  const char* keySym = this->Interactor->GetKeySym();
  this->KeyHandler(
    keySym ? keySym : "", this->Interactor->GetKeyCode(), this->Interactor->GetControlKey() != 0);
}

void vtkCloudViewerInteractorStyle::OnChar()
{
  // Every key is handled on its key press (OnKeyPress); VTK's default bindings stay off.
}

void vtkCloudViewerInteractorStyle::OnLeave()
{
  if (this->Owner == Grab::None && this->WasOverEditor && this->EditorLeft)
  {
    this->EditorLeft();
  }
  this->WasOverEditor = false;
  // The pointer left the window: no voxel is under it.
  if (this->HoverHandler)
  {
    this->HoverHandler(-1, -1);
  }
}

void vtkCloudViewerInteractorStyle::OnTimer()
{
  // The camera moves with mouse motion only (see the class comment).
}
