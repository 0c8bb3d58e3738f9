// Implementation of SliceViews.h. The crosshair lines sit a hundredth of a voxel in front of the
// slice, toward the camera, so the depth test never hides them in the slice.
#include "SliceViews.h"

#include "SliceColors.h"
#include "SlicePlanes.h"
#include "Viewer.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkImageData.h>
#include <vtkImageProperty.h>
#include <vtkImageSlice.h>
#include <vtkImageSliceMapper.h>
#include <vtkLookupTable.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cloudvis
{
namespace
{
// The 3D planes' outline colors, by axis.
constexpr double AxisColors[3][3] = { { 1.0, 0.35, 0.35 },
  { 0.35, 1.0, 0.35 },
  { 0.45, 0.6, 1.0 } };
const char* const AxisNames[3] = { "x", "y", "z" };
// Per view (axial, coronal, sagittal): the axis sliced, the axes to the right and up, and the
// side the camera looks from along the sliced axis.
constexpr int SlicedAxis[3] = { 2, 1, 0 };
constexpr int RightAxis[3] = { 0, 0, 1 };
constexpr int UpAxis[3] = { 1, 2, 2 };
constexpr double CameraSide[3] = { 1.0, -1.0, 1.0 };
const char* const ViewNames[3] = { "axial", "coronal", "sagittal" };
} // namespace

struct SliceViews::View
{
  int Index = 0;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkImageSliceMapper> Mapper;
  vtkNew<vtkImageSlice> Slice;
  std::array<vtkNew<vtkActor>, 2> Lines; // where the other two slices cut this one
  std::array<vtkNew<vtkPoints>, 2> LinePoints;
  vtkNew<vtkTextActor> Caption;
  double Zoom = 1.0;
  std::array<double, 2> Pan{ { 0.0, 0.0 } }; // world units along RightAxis and UpAxis
};

int SliceViews::Axis(int view)
{
  return SlicedAxis[view];
}

const char* SliceViews::Name(int view)
{
  return ViewNames[view];
}

SliceViews::SliceViews(vtkImageData* field, SlicePlanes& planes, SliceColors& colors)
  : Field(field)
  , Planes(planes)
  , Colors(colors)
{
  for (int v = 0; v < Count; ++v)
  {
    auto view = std::make_unique<View>();
    view->Index = v;
    view->Renderer->SetBackground(0.08, 0.08, 0.1);
    view->Renderer->GetActiveCamera()->ParallelProjectionOn();
    view->Mapper->SetInputData(field);
    view->Mapper->SetOrientation(SlicedAxis[v]);
    view->Mapper->SliceFacesCameraOff();
    view->Mapper->SliceAtFocalPointOff();
    view->Slice->SetMapper(view->Mapper);
    vtkImageProperty* property = view->Slice->GetProperty();
    property->SetLookupTable(colors.GetTable());
    property->UseLookupTableScalarRangeOn();
    property->SetInterpolationTypeToNearest(); // voxels as they are: what the probe reads
    view->Renderer->AddViewProp(view->Slice);

    for (int l = 0; l < 2; ++l)
    {
      const int other = l == 0 ? RightAxis[v] : UpAxis[v]; // the slice across this axis
      view->LinePoints[size_t(l)]->SetNumberOfPoints(2);
      vtkNew<vtkCellArray> cells;
      const vtkIdType line[2] = { 0, 1 };
      cells->InsertNextCell(2, line);
      vtkNew<vtkPolyData> polyData;
      polyData->SetPoints(view->LinePoints[size_t(l)]);
      polyData->SetLines(cells);
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(polyData);
      vtkActor* actor = view->Lines[size_t(l)];
      actor->SetMapper(mapper);
      actor->GetProperty()->SetColor(
        AxisColors[other][0], AxisColors[other][1], AxisColors[other][2]);
      actor->GetProperty()->SetLineWidth(1.5);
      actor->GetProperty()->LightingOff();
      actor->PickableOff();
      view->Renderer->AddActor(actor);
    }

    vtkTextProperty* text = view->Caption->GetTextProperty();
    UseViewerFont(text);
    text->SetFontSize(12);
    text->SetColor(
      AxisColors[SlicedAxis[v]][0], AxisColors[SlicedAxis[v]][1], AxisColors[SlicedAxis[v]][2]);
    text->SetVerticalJustificationToTop();
    view->Caption->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    view->Caption->SetPosition(0.02, 0.97);
    view->Renderer->AddActor2D(view->Caption);
    this->Views[size_t(v)] = std::move(view);
  }
  this->Update();
}

SliceViews::~SliceViews() = default;

vtkRenderer* SliceViews::GetRenderer(int view) const
{
  return this->Views[size_t(view)]->Renderer;
}

void SliceViews::Update()
{
  double bounds[6], spacing[3];
  this->Field->GetBounds(bounds);
  this->Field->GetSpacing(spacing);
  for (auto& view : this->Views)
  {
    const int v = view->Index;
    const int axis = SlicedAxis[v], right = RightAxis[v], up = UpAxis[v];
    const int index = this->Planes.GetSliceIndex(axis);
    view->Mapper->SetSliceNumber(index);
    const double position = this->Planes.GetSlicePosition(axis);
    // In front of the slice, toward the camera.
    const double front = position + CameraSide[v] * 0.01 * spacing[axis];

    for (int l = 0; l < 2; ++l)
    {
      const int across = l == 0 ? right : up; // the line is where the slice across this sits
      const int along = l == 0 ? up : right;
      double a[3], b[3];
      a[axis] = b[axis] = front;
      a[across] = b[across] = this->Planes.GetSlicePosition(across);
      a[along] = bounds[2 * along];
      b[along] = bounds[2 * along + 1];
      view->LinePoints[size_t(l)]->SetPoint(0, a);
      view->LinePoints[size_t(l)]->SetPoint(1, b);
      view->LinePoints[size_t(l)]->Modified();
    }

    char caption[128];
    std::snprintf(caption,
      sizeof(caption),
      "%s  %s = %.3g  (slice %d of %d)",
      ViewNames[v],
      AxisNames[axis],
      position,
      index,
      this->Planes.GetNumberOfSlices(axis) - 1);
    view->Caption->SetInput(caption);

    // A parallel camera that fits the slice in the viewport, whatever its shape.
    vtkCamera* camera = view->Renderer->GetActiveCamera();
    double center[3];
    for (int c = 0; c < 3; ++c)
    {
      center[c] = 0.5 * (bounds[2 * c] + bounds[2 * c + 1]);
    }
    center[axis] = position;
    center[right] += view->Pan[0];
    center[up] += view->Pan[1];
    double eye[3] = { center[0], center[1], center[2] };
    const double depth = bounds[2 * axis + 1] - bounds[2 * axis] + 1.0;
    eye[axis] += CameraSide[v] * depth;
    double viewUp[3] = { 0.0, 0.0, 0.0 };
    viewUp[up] = 1.0;
    camera->SetFocalPoint(center);
    camera->SetPosition(eye);
    camera->SetViewUp(viewUp);
    int size[2] = { 1, 1 };
    if (view->Renderer->GetRenderWindow())
    {
      view->Renderer->GetTiledSize(&size[0], &size[1]);
    }
    const double aspect = double(std::max(1, size[0])) / std::max(1, size[1]);
    const double width = bounds[2 * right + 1] - bounds[2 * right];
    const double height = bounds[2 * up + 1] - bounds[2 * up];
    // A margin for the caption at the top.
    camera->SetParallelScale(0.5 * std::max(height, width / aspect) * 1.15 / view->Zoom);
    camera->SetClippingRange(0.01, 3.0 * depth);
  }
}

SliceViews::View* SliceViews::ViewAt(int x, int y)
{
  for (auto& view : this->Views)
  {
    if (view->Renderer->GetRenderWindow() && view->Renderer->IsInViewport(x, y))
    {
      return view.get();
    }
  }
  return nullptr;
}

std::array<double, 3> SliceViews::WorldPoint(const View& view, int x, int y) const
{
  vtkRenderer* renderer = view.Renderer;
  renderer->SetDisplayPoint(double(x), double(y), 0.5);
  renderer->DisplayToWorld();
  double world[4];
  renderer->GetWorldPoint(world);
  std::array<double, 3> point{ { world[0], world[1], world[2] } };
  if (world[3] != 0.0)
  {
    for (double& c : point)
    {
      c /= world[3];
    }
  }
  const int axis = SlicedAxis[view.Index];
  point[size_t(axis)] = this->Planes.GetSlicePosition(axis);
  return point;
}

void SliceViews::Probe(const View& view, int x, int y)
{
  // Outside the field nothing changes.
  this->Planes.ProbeAt(this->WorldPoint(view, x, y), SlicedAxis[view.Index]);
}

SliceProbe SliceViews::VoxelUnder(int x, int y)
{
  View* view = this->ViewAt(x, y);
  return view ? this->Planes.VoxelAt(this->WorldPoint(*view, x, y)) : SliceProbe();
}

int SliceViews::AxisAt(int x, int y)
{
  const View* view = this->ViewAt(x, y);
  return view ? SlicedAxis[view->Index] : -1;
}

double SliceViews::GetZoom(int view) const
{
  return this->Views[size_t(view)]->Zoom;
}

std::array<double, 2> SliceViews::GetPan(int view) const
{
  return this->Views[size_t(view)]->Pan;
}

void SliceViews::ResetZoom()
{
  for (auto& view : this->Views)
  {
    view->Zoom = 1.0;
    view->Pan = { { 0.0, 0.0 } };
  }
  this->Update();
}

void SliceViews::Zoom(View& view, double factor, int x, int y)
{
  // The point under the pointer stays: the view's centre moves toward it by 1 - 1/factor of the
  // way, in the view's own right and up coordinates. At the zoom's limits nothing moves.
  const double zoom = std::clamp(view.Zoom * factor, 0.25, 64.0);
  factor = zoom / view.Zoom;
  if (factor == 1.0)
  {
    return;
  }
  const std::array<double, 3> before = this->WorldPoint(view, x, y);
  double focal[3];
  view.Renderer->GetActiveCamera()->GetFocalPoint(focal);
  const int right = RightAxis[view.Index], up = UpAxis[view.Index];
  const double keep = 1.0 - 1.0 / factor;
  view.Pan[0] += (before[size_t(right)] - focal[right]) * keep;
  view.Pan[1] += (before[size_t(up)] - focal[up]) * keep;
  view.Zoom = zoom;
}

bool SliceViews::Mouse(vtkCloudViewerInteractorStyle::MouseAction action,
  int button,
  int x,
  int y,
  bool control,
  bool shift)
{
  using Action = vtkCloudViewerInteractorStyle::MouseAction;
  View* view =
    action == Action::Move || action == Action::Release ? this->Dragged : this->ViewAt(x, y);
  if (!view)
  {
    return false;
  }
  const int axis = SlicedAxis[view->Index];
  switch (action)
  {
    case Action::WheelForward:
    case Action::WheelBackward:
      if (control)
      {
        this->Zoom(*view, action == Action::WheelForward ? 1.25 : 1.0 / 1.25, x, y);
        break;
      }
      this->Planes.SetSliceIndex(
        axis, this->Planes.GetSliceIndex(axis) + (action == Action::WheelForward ? 1 : -1));
      break;
    case Action::Press:
      this->Dragged = view;
      this->DragButton = button;
      this->DragStartY = y;
      this->DragLast = { { x, y } };
      this->DragStartIndex = this->Planes.GetSliceIndex(axis);
      this->Panning = button == 1 && shift;
      if (button == 1 && !this->Panning)
      {
        this->Probe(*view, x, y);
      }
      else if (button == 3)
      {
        this->Colors.BeginWindowLevelDrag(x, y);
      }
      break;
    case Action::Move:
      if (this->Panning)
      {
        // The slice follows the pointer: the view's centre moves the other way.
        const std::array<double, 3> now = this->WorldPoint(*view, x, y);
        const std::array<double, 3> last =
          this->WorldPoint(*view, this->DragLast[0], this->DragLast[1]);
        view->Pan[0] -= now[size_t(RightAxis[view->Index])] - last[size_t(RightAxis[view->Index])];
        view->Pan[1] -= now[size_t(UpAxis[view->Index])] - last[size_t(UpAxis[view->Index])];
        this->DragLast = { { x, y } };
      }
      else if (this->DragButton == 1)
      {
        this->Probe(*view, x, y);
      }
      else if (this->DragButton == 2)
      {
        this->Planes.SetSliceIndex(axis, this->DragStartIndex + (y - this->DragStartY) / 4);
      }
      else if (this->DragButton == 3)
      {
        const int* size = view->Renderer->GetSize();
        this->Colors.DragWindowLevel(x, y, size[0], size[1]);
      }
      break;
    case Action::Release:
      this->Dragged = nullptr;
      this->DragButton = 0;
      this->Panning = false;
      break;
  }
  this->Update();
  if (this->Changed)
  {
    this->Changed();
  }
  return true;
}

} // namespace cloudvis
