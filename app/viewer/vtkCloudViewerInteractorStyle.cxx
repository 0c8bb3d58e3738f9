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
      if (this->IsOverEditor())
      {
        this->Chart->OnMouseMove(); // hover highlights
      }
      break;
  }
}

void vtkCloudViewerInteractorStyle::OnLeftButtonDown()
{
  switch (this->Press(1))
  {
    case Grab::Chart:
      // The charts route the moves of a double click's second press nowhere, so a point grabbed
      // again within 400 ms of its release would not move: every press is a single one here.
      this->Interactor->SetRepeatCount(0);
      this->Chart->OnLeftButtonDown();
      break;
    case Grab::Camera:
      this->Superclass::OnLeftButtonDown();
      break;
    default:
      break;
  }
}

void vtkCloudViewerInteractorStyle::OnLeftButtonUp()
{
  if (this->Owner == Grab::Chart)
  {
    this->Chart->OnLeftButtonUp();
  }
  if (this->Release(1) == Grab::Camera)
  {
    this->Superclass::OnLeftButtonUp();
  }
}

void vtkCloudViewerInteractorStyle::OnMiddleButtonDown()
{
  switch (this->Press(2))
  {
    case Grab::Chart:
      this->Chart->OnMiddleButtonDown();
      break;
    case Grab::Camera:
      this->Superclass::OnMiddleButtonDown();
      break;
    default:
      break;
  }
}

void vtkCloudViewerInteractorStyle::OnMiddleButtonUp()
{
  if (this->Owner == Grab::Chart)
  {
    this->Chart->OnMiddleButtonUp();
  }
  if (this->Release(2) == Grab::Camera)
  {
    this->Superclass::OnMiddleButtonUp();
  }
}

void vtkCloudViewerInteractorStyle::OnRightButtonDown()
{
  switch (this->Press(3))
  {
    case Grab::Chart:
      this->Chart->OnRightButtonDown();
      break;
    case Grab::Camera:
      this->Superclass::OnRightButtonDown();
      break;
    default:
      break;
  }
}

void vtkCloudViewerInteractorStyle::OnRightButtonUp()
{
  if (this->Owner == Grab::Chart)
  {
    this->Chart->OnRightButtonUp();
  }
  if (this->Release(3) == Grab::Camera)
  {
    this->Superclass::OnRightButtonUp();
  }
}

// The wheel dollies the camera in the 3D view and steps the slice in a slice view; over the
// editor it does nothing (the charts' zoom is off: their axes always show the transfer
// function's range).
void vtkCloudViewerInteractorStyle::OnMouseWheelForward()
{
  const int* position = this->Interactor->GetEventPosition();
  if (this->Owner != Grab::None || this->IsOverEditor() ||
    (this->SliceViewMouse &&
      this->SliceViewMouse(MouseAction::WheelForward, 0, position[0], position[1])))
  {
    return;
  }
  this->Superclass::OnMouseWheelForward();
}

void vtkCloudViewerInteractorStyle::OnMouseWheelBackward()
{
  const int* position = this->Interactor->GetEventPosition();
  if (this->Owner != Grab::None || this->IsOverEditor() ||
    (this->SliceViewMouse &&
      this->SliceViewMouse(MouseAction::WheelBackward, 0, position[0], position[1])))
  {
    return;
  }
  this->Superclass::OnMouseWheelBackward();
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

void vtkCloudViewerInteractorStyle::OnTimer()
{
  // The camera moves with mouse motion only (see the class comment).
}
