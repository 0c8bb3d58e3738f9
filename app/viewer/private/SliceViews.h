// The three 2D slice views of the four-view layout, as ParaView and 3D Slicer show them: axial
// (the slice across z, x to the right and y up), coronal (across y; x right, z up) and sagittal
// (across x; y right, z up). Each is a renderer with a parallel camera fitted to its slice, the
// slice itself (vtkImageSlice, colored by the shared SliceColors table), crosshair lines where
// the other two slices cut it (in their plane colors: x red, y green, z blue) and a caption with
// the slice's index and position.
//
// The slices shown are SlicePlanes' (the 3D planes' indices): moving a plane in 3D moves the
// view's slice and the crosshairs, and the views move the planes. Mouse, in a view: the wheel
// steps its slice by one voxel, a middle drag moves it (one voxel per 4 pixels), a left click or
// drag probes the voxel under the pointer and moves the other two slices through it (the
// crosshairs follow), a right drag sets the window/level of every slice; as in 3D Slicer,
// Control + wheel zooms about the pointer and Shift + left drag pans. Each view keeps its zoom
// and pan (ResetZoom fits the slices again).
#ifndef cloudvis_SliceViews_h
#define cloudvis_SliceViews_h

#include "SlicePlanes.h"
#include "vtkCloudViewerInteractorStyle.h"

#include <vtkNew.h>

#include <array>
#include <functional>
#include <memory>
#include <string>

class vtkActor;
class vtkImageData;
class vtkImageSlice;
class vtkImageSliceMapper;
class vtkPoints;
class vtkPolyData;
class vtkRenderer;
class vtkTextActor;

namespace cloudvis
{

class SliceColors;

class SliceViews
{
public:
  SliceViews(vtkImageData* field, SlicePlanes& planes, SliceColors& colors);
  ~SliceViews();
  SliceViews(const SliceViews&) = delete;
  SliceViews& operator=(const SliceViews&) = delete;

  static constexpr int Count = 3;
  // View 0 axial, 1 coronal, 2 sagittal; the axis each slices across (2, 1, 0) and its name.
  static int Axis(int view);
  static const char* Name(int view);

  // The view's renderer; the viewer adds it to the window in the four-view layout.
  vtkRenderer* GetRenderer(int view) const;

  // Follows the slice indices, the probe and the viewports (cameras, crosshairs, captions).
  void Update();

  // Called after the mouse moved a slice, probed or changed the window/level.
  std::function<void()> Changed;

  // The mouse in window pixels (vtkCloudViewerInteractorStyle::SliceViewMouse), with the
  // modifiers held: returns whether a view shown in the window takes the event.
  bool Mouse(vtkCloudViewerInteractorStyle::MouseAction action,
    int button,
    int x,
    int y,
    bool control,
    bool shift);

  // The axis of the slice shown in the view at window pixel x, y; -1 when none is there.
  int AxisAt(int x, int y);

  // A view's magnification over the fitted slice (1: the slice fits the view) and its pan, in
  // world units along the view's right and up axes.
  double GetZoom(int view) const;
  std::array<double, 2> GetPan(int view) const;
  // Every view fits its slice again.
  void ResetZoom();

  // The voxel under window pixel x, y in a view shown (Valid false elsewhere), not probed.
  SliceProbe VoxelUnder(int x, int y);

private:
  struct View;
  View* ViewAt(int x, int y);
  std::array<double, 3> WorldPoint(const View& view, int x, int y) const;
  // Zooms the view by `factor` keeping the point under x, y where it is.
  void Zoom(View& view, double factor, int x, int y);
  void Probe(const View& view, int x, int y);

  vtkImageData* Field;
  SlicePlanes& Planes;
  SliceColors& Colors;
  std::array<std::unique_ptr<View>, Count> Views;
  View* Dragged = nullptr;
  int DragButton = 0;
  int DragStartY = 0;
  bool Panning = false; // the drag (Shift + left) pans the view
  std::array<int, 2> DragLast{ { 0, 0 } };
  int DragStartIndex = 0;
};

} // namespace cloudvis

#endif
