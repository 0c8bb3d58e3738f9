// The slice widgets are placed in the 3D renderer explicitly (SetCurrentRenderer): left to
// themselves they would attach to whichever renderer is under the pointer when enabled, which
// may be the editor's. Their key activation is off: the viewer's keys toggle them.
//
// Three behaviours of vtkImagePlaneWidget are replaced:
// - its left button probes wherever it hits the plane, which took the left drag from the camera
//   whenever it started on a slice (a slice facing the camera covers most of the view); here it
//   probes only with Control held, and a plain left drag turns the camera;
// - its middle-button push moves the plane by the mouse motion projected on the plane's normal,
//   which is nothing when the plane faces the camera; here the motion is measured along the
//   normal's image on screen, or vertically when that image is too short to follow;
// - its window/level with a shared (user controlled) lookup table only reports the new values;
//   here the drag sets them on SliceColors, so every slice changes.
#include "SlicePlanes.h"

#include "Scene.h" // ObliqueSpec
#include "SliceColors.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellPicker.h>
#include <vtkCutter.h>
#include <vtkImageData.h>
#include <vtkImagePlaneWidget.h>
#include <vtkImplicitPlaneRepresentation.h>
#include <vtkImplicitPlaneWidget2.h>
#include <vtkLookupTable.h>
#include <vtkObjectFactory.h>
#include <vtkPlane.h>
#include <vtkPlaneSource.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cloudvis
{
namespace
{
// An orthogonal slice plane whose middle-button drag works from every view direction and moves
// the plane from voxel layer to voxel layer.
class vtkCloudSlicePlaneWidget : public vtkImagePlaneWidget
{
public:
  static vtkCloudSlicePlaneWidget* New();
  vtkTypeMacro(vtkCloudSlicePlaneWidget, vtkImagePlaneWidget);

  // The textured plane the slice is drawn on, for picking.
  vtkActor* GetTexturePlane() const { return this->TexturePlaneActor; }

protected:
  vtkCloudSlicePlaneWidget() = default;
  ~vtkCloudSlicePlaneWidget() override = default;

  void OnLeftButtonDown() override
  {
    if (this->Interactor->GetControlKey())
    {
      this->Superclass::OnLeftButtonDown();
    }
  }

  void OnMiddleButtonDown() override
  {
    this->Superclass::OnMiddleButtonDown();
    this->PushStart = this->GetSlicePosition();
    this->Pushed = 0.0;
  }

  void OnMouseMove() override
  {
    if (this->State != vtkImagePlaneWidget::Pushing || !this->CurrentRenderer)
    {
      this->Superclass::OnMouseMove();
      return;
    }
    vtkRenderer* renderer = this->CurrentRenderer;
    const int* now = this->Interactor->GetEventPosition();
    const int* last = this->Interactor->GetLastEventPosition();
    const double move[2] = { double(now[0] - last[0]), double(now[1] - last[1]) };
    double center[3], normal[3];
    this->PlaneSource->GetCenter(center);
    this->PlaneSource->GetNormal(normal);
    // The normal's image on screen (pixels per world unit) and the world size of a pixel there.
    double a[3], b[3], up[4];
    ComputeWorldToDisplay(renderer, center[0], center[1], center[2], a);
    ComputeWorldToDisplay(
      renderer, center[0] + normal[0], center[1] + normal[1], center[2] + normal[2], b);
    ComputeDisplayToWorld(renderer, a[0], a[1] + 1.0, a[2], up);
    const double unitsPerPixel = std::sqrt(vtkMath::Distance2BetweenPoints(center, up));
    const double n[2] = { b[0] - a[0], b[1] - a[1] };
    const double n2 = n[0] * n[0] + n[1] * n[1];
    double distance = 0.0;
    // Followable when the normal is more than about 17 degrees off the view direction.
    if (std::sqrt(n2) * unitsPerPixel > 0.3)
    {
      distance = (move[0] * n[0] + move[1] * n[1]) / n2;
    }
    else
    {
      // Facing the camera: moving the mouse up brings the slice toward the viewer.
      double eye[3];
      renderer->GetActiveCamera()->GetPosition(eye);
      const double toward = (eye[0] - center[0]) * normal[0] + (eye[1] - center[1]) * normal[1] +
        (eye[2] - center[2]) * normal[2];
      distance = move[1] * unitsPerPixel * (toward >= 0.0 ? 1.0 : -1.0);
    }
    this->Pushed += distance;
    // Snap to the nearest voxel layer.
    double origin[3], spacing[3];
    this->ImageData->GetOrigin(origin);
    this->ImageData->GetSpacing(spacing);
    const int axis = this->PlaneOrientation;
    const int index =
      int(std::lround((this->PushStart + this->Pushed - origin[axis]) / spacing[axis]));
    int extent[6];
    this->ImageData->GetExtent(extent);
    this->SetSliceIndex(std::clamp(index, extent[2 * axis], extent[2 * axis + 1]));
    this->EventCallbackCommand->SetAbortFlag(1);
    this->InvokeEvent(vtkCommand::InteractionEvent, nullptr);
    this->Interactor->Render();
  }

private:
  double PushStart = 0.0;
  double Pushed = 0.0;
};
vtkStandardNewMacro(vtkCloudSlicePlaneWidget);

struct PlaneObserver
{
  SlicePlanes* Owner;
  int Axis;
};
} // namespace

SlicePlanes::SlicePlanes(vtkImageData* field,
  vtkRenderer* renderer,
  vtkRenderWindowInteractor* interactor,
  SliceColors& colors)
  : Field(field)
  , Renderer(renderer)
  , Interactor(interactor)
  , Colors(colors)
{
  int dimensions[3];
  field->GetDimensions(dimensions);
  for (int axis = 0; axis < 3; ++axis)
  {
    auto slice = vtkSmartPointer<vtkCloudSlicePlaneWidget>::New();
    slice->SetInteractor(interactor);
    slice->SetCurrentRenderer(renderer);
    slice->KeyPressActivationOff();
    slice->SetPicker(nullptr); // its own vtkCellPicker, restricted to its plane
    slice->SetInputData(field);
    slice->SetPlaneOrientation(axis);
    slice->SetSliceIndex(dimensions[axis] / 2);
    slice->UserControlledLookupTableOn();
    slice->SetLookupTable(colors.GetTable());
    slice->DisplayTextOff();    // the viewer's readout shows the probe, and keeps it
    slice->SetMarginSizeX(0.0); // no margins: the middle button always pushes, never tilts
    slice->SetMarginSizeY(0.0);
    slice->TextureInterpolateOn();
    slice->SetResliceInterpolateToLinear();
    const double outline[3][3] = { { 1.0, 0.35, 0.35 }, { 0.35, 1.0, 0.35 }, { 0.4, 0.55, 1.0 } };
    slice->GetPlaneProperty()->SetColor(outline[axis][0], outline[axis][1], outline[axis][2]);
    vtkNew<vtkCallbackCommand> observer;
    observer->SetClientData(new PlaneObserver{ this, axis });
    observer->SetClientDataDeleteCallback(
      [](void* data) { delete static_cast<PlaneObserver*>(data); });
    observer->SetCallback(
      [](vtkObject*, unsigned long event, void* data, void*)
      {
        auto* self = static_cast<PlaneObserver*>(data);
        self->Owner->OnPlaneEvent(self->Axis, event);
      });
    for (unsigned long event : { vtkCommand::StartInteractionEvent,
           vtkCommand::InteractionEvent,
           vtkCommand::StartWindowLevelEvent,
           vtkCommand::WindowLevelEvent })
    {
      slice->AddObserver(event, observer);
    }
    this->Slices[size_t(axis)] = slice;
  }

  this->HoverPicker->PickFromListOn();
  this->HoverPicker->SetTolerance(0.0);

  // Oblique: a plane through the centre, tilted off every axis.
  double bounds[6], center[3];
  field->GetBounds(bounds);
  field->GetCenter(center);
  this->ObliqueRepresentation->SetPlaceFactor(1.0);
  this->ObliqueRepresentation->PlaceWidget(bounds);
  this->ObliqueRepresentation->SetOrigin(center);
  this->ObliqueRepresentation->SetNormal(ObliqueSpec{}.Normal.data());
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
  mapper->SetLookupTable(colors.GetTable());
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
    slice->RemoveAllObservers();
    slice->SetInteractor(nullptr);
  }
  this->ObliqueWidget->Off();
  this->ObliqueWidget->SetInteractor(nullptr);
  this->Renderer->RemoveActor(this->ObliqueActor);
}

void SlicePlanes::OnPlaneEvent(int axis, unsigned long event)
{
  vtkImagePlaneWidget* slice = this->Slices[size_t(axis)];
  const int* position = this->Interactor->GetEventPosition();
  if (event == vtkCommand::StartWindowLevelEvent)
  {
    this->Colors.BeginWindowLevelDrag(position[0], position[1]);
    return;
  }
  if (event == vtkCommand::WindowLevelEvent)
  {
    const int* size = this->Renderer->GetSize();
    this->Colors.DragWindowLevel(position[0], position[1], size[0], size[1]);
  }
  else if (slice->GetCursorDataStatus())
  {
    double xyzv[4], origin[3], spacing[3];
    slice->GetCursorData(xyzv);
    this->Field->GetOrigin(origin);
    this->Field->GetSpacing(spacing);
    std::array<double, 3> cursor;
    for (int c = 0; c < 3; ++c)
    {
      cursor[size_t(c)] = origin[c] + xyzv[c] * spacing[c];
    }
    this->ProbeAt(cursor, axis);
  }
  if (this->Changed)
  {
    this->Changed();
  }
}

void SlicePlanes::SetSliceVisible(int axis, bool visible)
{
  this->Slices[size_t(axis)]->SetEnabled(visible ? 1 : 0);
}

bool SlicePlanes::GetSliceVisible(int axis) const
{
  return this->Slices[size_t(axis)]->GetEnabled() != 0;
}

void SlicePlanes::SetSliceIndex(int axis, int index)
{
  int extent[6];
  this->Field->GetExtent(extent);
  this->Slices[size_t(axis)]->SetSliceIndex(
    std::clamp(index, extent[2 * axis], extent[2 * axis + 1]));
}

void SlicePlanes::SetSlicePosition(int axis, double position)
{
  const double spacing = this->Field->GetSpacing()[axis];
  const double origin = this->Field->GetOrigin()[axis];
  const double index = std::round((position - origin) / spacing);
  // Clamped here already: a position far outside must not overflow the int.
  const double limit = 1e9;
  this->SetSliceIndex(axis, int(std::clamp(index, -limit, limit)));
}

int SlicePlanes::GetSliceIndex(int axis) const
{
  return this->Slices[size_t(axis)]->GetSliceIndex();
}

int SlicePlanes::GetNumberOfSlices(int axis) const
{
  int dimensions[3];
  this->Field->GetDimensions(dimensions);
  return dimensions[axis];
}

std::vector<double> SlicePlanes::GetSliceValues(int axis) const
{
  int extent[6];
  this->Field->GetExtent(extent);
  extent[2 * axis] = extent[2 * axis + 1] = this->GetSliceIndex(axis);
  std::vector<double> values;
  values.reserve(size_t(extent[1] - extent[0] + 1) * size_t(extent[3] - extent[2] + 1) *
    size_t(extent[5] - extent[4] + 1));
  for (int k = extent[4]; k <= extent[5]; ++k)
  {
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      for (int i = extent[0]; i <= extent[1]; ++i)
      {
        values.push_back(this->Field->GetScalarComponentAsDouble(i, j, k, 0));
      }
    }
  }
  return values;
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

SliceProbe SlicePlanes::VoxelAt(const std::array<double, 3>& position) const
{
  double origin[3], spacing[3];
  int extent[6];
  this->Field->GetOrigin(origin);
  this->Field->GetSpacing(spacing);
  this->Field->GetExtent(extent);
  SliceProbe voxel;
  for (int c = 0; c < 3; ++c)
  {
    const int index = int(std::lround((position[size_t(c)] - origin[c]) / spacing[c]));
    if (index < extent[2 * c] || index > extent[2 * c + 1])
    {
      return SliceProbe();
    }
    voxel.Index[size_t(c)] = index;
    voxel.Position[size_t(c)] = origin[c] + index * spacing[c];
  }
  voxel.Value =
    this->Field->GetScalarComponentAsDouble(voxel.Index[0], voxel.Index[1], voxel.Index[2], 0);
  voxel.Valid = true;
  return voxel;
}

bool SlicePlanes::ProbeAt(const std::array<double, 3>& position, int axis)
{
  const SliceProbe voxel = this->VoxelAt(position);
  if (!voxel.Valid)
  {
    return false;
  }
  this->Probe = voxel;
  for (int other = 0; other < 3; ++other)
  {
    if (other != axis)
    {
      this->SetSliceIndex(other, voxel.Index[size_t(other)]);
    }
  }
  return true;
}

int SlicePlanes::AxisUnder(int x, int y)
{
  if (!this->Renderer->IsInViewport(x, y))
  {
    return -1;
  }
  this->HoverPicker->InitializePickList();
  bool shown = false;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (this->GetSliceVisible(axis))
    {
      this->HoverPicker->AddPickList(
        static_cast<vtkCloudSlicePlaneWidget*>(this->Slices[size_t(axis)].Get())
          ->GetTexturePlane());
      shown = true;
    }
  }
  if (!shown || !this->HoverPicker->Pick(double(x), double(y), 0.0, this->Renderer))
  {
    return -1;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    if (this->HoverPicker->GetActor() ==
      static_cast<vtkCloudSlicePlaneWidget*>(this->Slices[size_t(axis)].Get())->GetTexturePlane())
    {
      return axis;
    }
  }
  return -1;
}

SliceProbe SlicePlanes::VoxelUnder(int x, int y)
{
  if (this->AxisUnder(x, y) < 0)
  {
    return SliceProbe();
  }
  std::array<double, 3> position;
  this->HoverPicker->GetPickPosition(position.data());
  return this->VoxelAt(position);
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

void SlicePlanes::SetObliquePlane(const std::array<double, 3>& origin,
  const std::array<double, 3>& normal)
{
  // Scaled to its largest component first: VTK normalises by the squared length, which a normal
  // of 1e200s (legal in a scene) would overflow.
  const double largest =
    std::max({ std::abs(normal[0]), std::abs(normal[1]), std::abs(normal[2]) });
  this->ObliqueRepresentation->SetNormal(
    normal[0] / largest, normal[1] / largest, normal[2] / largest);
  this->ObliqueRepresentation->SetOrigin(origin[0], origin[1], origin[2]);
  this->UpdateObliqueCut();
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
