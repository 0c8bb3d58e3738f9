// Routing by viewport. The chart half is VTK's own vtkContextInteractorStyle, which turns the
// interactor's events into vtkContextMouseEvents for the scene; a subclass takes the interactor
// without adding observers to it, so it only ever sees the events this style forwards. The
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
  // The chart style renders through the interactor when its scene changes.
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

bool vtkCloudViewerInteractorStyle::PressGoesToChart()
{
  if (this->Owner == Grab::None)
  {
    this->Owner = this->IsOverEditor() ? Grab::Chart : Grab::Camera;
    if (this->Owner == Grab::Chart && this->ChartDragHandler)
    {
      this->ChartDragHandler(true);
    }
  }
  return this->Owner == Grab::Chart;
}

bool vtkCloudViewerInteractorStyle::ReleaseGoesToChart()
{
  const bool chart = this->Owner == Grab::Chart;
  this->Owner = Grab::None;
  return chart;
}

void vtkCloudViewerInteractorStyle::OnMouseMove()
{
  const bool chart = this->Owner == Grab::Chart || (this->Owner == Grab::None && this->IsOverEditor());
  if (chart)
  {
    this->Chart->OnMouseMove();
  }
  else
  {
    this->Superclass::OnMouseMove();
  }
}

void vtkCloudViewerInteractorStyle::OnLeftButtonDown()
{
  if (this->PressGoesToChart())
  {
    this->Chart->OnLeftButtonDown();
  }
  else
  {
    this->Superclass::OnLeftButtonDown();
  }
}

void vtkCloudViewerInteractorStyle::OnLeftButtonUp()
{
  if (this->ReleaseGoesToChart())
  {
    this->Chart->OnLeftButtonUp();
    if (this->ChartDragHandler)
    {
      this->ChartDragHandler(false);
    }
  }
  else
  {
    this->Superclass::OnLeftButtonUp();
  }
}

void vtkCloudViewerInteractorStyle::OnMiddleButtonDown()
{
  if (this->PressGoesToChart())
  {
    this->Chart->OnMiddleButtonDown();
  }
  else
  {
    this->Superclass::OnMiddleButtonDown();
  }
}

void vtkCloudViewerInteractorStyle::OnMiddleButtonUp()
{
  if (this->ReleaseGoesToChart())
  {
    this->Chart->OnMiddleButtonUp();
    if (this->ChartDragHandler)
    {
      this->ChartDragHandler(false);
    }
  }
  else
  {
    this->Superclass::OnMiddleButtonUp();
  }
}

void vtkCloudViewerInteractorStyle::OnRightButtonDown()
{
  if (this->PressGoesToChart())
  {
    this->Chart->OnRightButtonDown();
  }
  else
  {
    this->Superclass::OnRightButtonDown();
  }
}

void vtkCloudViewerInteractorStyle::OnRightButtonUp()
{
  if (this->ReleaseGoesToChart())
  {
    this->Chart->OnRightButtonUp();
    if (this->ChartDragHandler)
    {
      this->ChartDragHandler(false);
    }
  }
  else
  {
    this->Superclass::OnRightButtonUp();
  }
}

// The wheel dollies the camera in the 3D view; over the editor it does nothing (the charts'
// zoom is off: their axes always show the transfer function's range).
void vtkCloudViewerInteractorStyle::OnMouseWheelForward()
{
  if (!this->IsOverEditor())
  {
    this->Superclass::OnMouseWheelForward();
  }
}

void vtkCloudViewerInteractorStyle::OnMouseWheelBackward()
{
  if (!this->IsOverEditor())
  {
    this->Superclass::OnMouseWheelBackward();
  }
}

void vtkCloudViewerInteractorStyle::OnKeyPress()
{
  if (!this->Interactor)
  {
    return;
  }
  if (this->IsOverEditor())
  {
      this->Chart->OnKeyPress();
  }
  const char* keySym = this->Interactor->GetKeySym();
  if (this->KeyHandler)
  {
    this->KeyHandler(keySym ? keySym : "", this->Interactor->GetKeyCode());
  }
}

void vtkCloudViewerInteractorStyle::OnChar()
{
  // Every key is handled on its key press (OnKeyPress); VTK's default bindings stay off.
}
