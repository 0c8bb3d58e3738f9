// The slice widgets are placed in the 3D renderer explicitly (SetCurrentRenderer): left to
// themselves they would attach to whichever renderer is under the pointer when enabled, which
// may be the editor's. Their key activation is off: the viewer's keys toggle them.
#include "SlicePlanes.h"

#include "CloudTransferTable.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCutter.h>
#include <vtkImageData.h>
#include <vtkImagePlaneWidget.h>
#include <vtkImplicitPlaneRepresentation.h>
#include <vtkImplicitPlaneWidget2.h>
#include <vtkLookupTable.h>
#include <vtkPlane.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include <cmath>
#include <limits>

namespace cloudvis
{

SlicePlanes::SlicePlanes(
  vtkImageData* field, vtkRenderer* renderer, vtkRenderWindowInteractor* interactor)
  : Renderer(renderer)
{
  double range[2];
  field->GetScalarRange(range);
  WidenEmptyRange(range);
  // Dark blue through teal to pale yellow: empty space dark, dense cloud bright.
  this->Colors->SetTableRange(range);
  this->Colors->SetHueRange(0.66, 0.14);
  this->Colors->SetSaturationRange(0.85, 0.45);
  this->Colors->SetValueRange(0.25, 1.0);
  this->Colors->Build();

  int dimensions[3];
  field->GetDimensions(dimensions);
  for (int axis = 0; axis < 3; ++axis)
  {
    auto slice = vtkSmartPointer<vtkImagePlaneWidget>::New();
    slice->SetInteractor(interactor);
    slice->SetCurrentRenderer(renderer);
    slice->KeyPressActivationOff();
    slice->SetPicker(nullptr); // its own vtkCellPicker, restricted to its plane
    slice->SetInputData(field);
    slice->SetPlaneOrientation(axis);
    slice->SetSliceIndex(dimensions[axis] / 2);
    slice->UserControlledLookupTableOn();
    slice->SetLookupTable(this->Colors);
    slice->DisplayTextOn();
    slice->TextureInterpolateOn();
    slice->SetResliceInterpolateToLinear();
    const double outline[3][3] = { { 1.0, 0.35, 0.35 }, { 0.35, 1.0, 0.35 }, { 0.4, 0.55, 1.0 } };
    slice->GetPlaneProperty()->SetColor(outline[axis][0], outline[axis][1], outline[axis][2]);
    this->Slices[size_t(axis)] = slice;
  }

  // Oblique: a plane through the centre, tilted off every axis.
  double bounds[6], center[3];
  field->GetBounds(bounds);
  field->GetCenter(center);
  this->ObliqueRepresentation->SetPlaceFactor(1.0);
  this->ObliqueRepresentation->PlaceWidget(bounds);
  this->ObliqueRepresentation->SetOrigin(center);
  this->ObliqueRepresentation->SetNormal(1.0, 1.0, 2.0);
  this->ObliqueRepresentation->DrawPlaneOff();
  this->ObliqueRepresentation->OutlineTranslationOff();
  this->ObliqueRepresentation->ScaleEnabledOff();
  this->ObliqueRepresentation->ConstrainToWidgetBoundsOn();
  this->ObliqueWidget->SetInteractor(interactor);
  this->ObliqueWidget->SetCurrentRenderer(renderer);
  this->ObliqueWidget->KeyPressActivationOff();
  this->ObliqueWidget->SetRepresentation(this->ObliqueRepresentation);
  vtkNew<vtkCallbackCommand> follow;
  follow->SetClientData(this);
  follow->SetCallback([](vtkObject*, unsigned long, void* self, void*)
    { static_cast<SlicePlanes*>(self)->UpdateObliqueCut(); });
  this->ObliqueWidget->AddObserver(vtkCommand::InteractionEvent, follow);

  this->ObliqueCutter->SetInputData(field);
  this->ObliqueCutter->SetCutFunction(this->ObliquePlane);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(this->ObliqueCutter->GetOutputPort());
  mapper->SetLookupTable(this->Colors);
  mapper->UseLookupTableScalarRangeOn();
  mapper->ScalarVisibilityOn();
  this->ObliqueActor->SetMapper(mapper);
  this->ObliqueActor->GetProperty()->LightingOff(); // the density's color, as the slices show it
  this->ObliqueActor->VisibilityOff();
  this->ObliqueActor->PickableOff(); // the orthogonal slices are picked through it
  renderer->AddActor(this->ObliqueActor);
  this->UpdateObliqueCut();
}

SlicePlanes::~SlicePlanes()
{
  for (auto& slice : this->Slices)
  {
    slice->Off();
    slice->SetInteractor(nullptr);
  }
  this->ObliqueWidget->Off();
  this->ObliqueWidget->SetInteractor(nullptr);
  this->Renderer->RemoveActor(this->ObliqueActor);
}

void SlicePlanes::SetSliceVisible(int axis, bool visible)
{
  this->Slices[size_t(axis)]->SetEnabled(visible ? 1 : 0);
}

bool SlicePlanes::GetSliceVisible(int axis) const
{
  return this->Slices[size_t(axis)]->GetEnabled() != 0;
}

double SlicePlanes::GetSlicePosition(int axis) const
{
  return this->Slices[size_t(axis)]->GetSlicePosition();
}

double SlicePlanes::GetProbedValue(int axis) const
{
  const double value = this->Slices[size_t(axis)]->GetCurrentImageValue();
  // VTK_DOUBLE_MAX until the cursor has been over the slice.
  return value >= 1e299 ? std::numeric_limits<double>::quiet_NaN() : value;
}

void SlicePlanes::SetObliqueVisible(bool visible)
{
  this->ObliqueVisible = visible;
  this->ObliqueWidget->SetEnabled(visible ? 1 : 0);
  this->ObliqueActor->SetVisibility(visible);
  this->UpdateObliqueCut();
}

std::array<double, 3> SlicePlanes::GetObliqueOrigin() const
{
  std::array<double, 3> origin;
  this->ObliqueRepresentation->GetOrigin(origin.data());
  return origin;
}

std::array<double, 3> SlicePlanes::GetObliqueNormal() const
{
  std::array<double, 3> normal;
  this->ObliqueRepresentation->GetNormal(normal.data());
  return normal;
}

long SlicePlanes::GetObliqueCutPoints() const
{
  this->ObliqueCutter->Update();
  return long(this->ObliqueCutter->GetOutput()->GetNumberOfPoints());
}

void SlicePlanes::UpdateObliqueCut()
{
  this->ObliqueRepresentation->GetPlane(this->ObliquePlane);
  this->ObliqueCutter->Modified();
}

} // namespace cloudvis
