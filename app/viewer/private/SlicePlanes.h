// The viewer's slices of the density, and the authority on where they are: three orthogonal
// vtkImagePlaneWidgets in the 3D view (Control + left button: probe the voxel under the cursor
// and move the other two slices through it; middle drag: move the slice; right drag:
// window/level of every slice; a plain left drag is the camera's, as in ParaView and Slicer,
// even on a slice facing the camera) and an oblique slice, a
// vtkImplicitPlaneWidget2 whose plane cuts the field (vtkCutter) into an opaque colored polygon.
// All are opaque geometry in the 3D renderer, so the cloud composites with them through the depth
// buffer, and all are colored by the shared SliceColors table. Each starts hidden; the viewer
// toggles them with keys. The orthogonal slices always sit on a voxel layer (a slice index), so
// the 2D slice views (SliceViews.h) show exactly what the planes show; they read and set the
// indices here. The last probe, from a plane or a slice view, stays until the next one (or until
// ClearProbe: the viewer drops it when no slice is shown). VoxelUnder finds the voxel under the
// pointer without probing it, for the readout that follows the mouse.
#ifndef cloudvis_SlicePlanes_h
#define cloudvis_SlicePlanes_h

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <array>
#include <functional>
#include <vector>

class vtkActor;
class vtkCellPicker;
class vtkCutter;
class vtkImageData;
class vtkImagePlaneWidget;
class vtkImplicitPlaneRepresentation;
class vtkImplicitPlaneWidget2;
class vtkPlane;
class vtkRenderWindowInteractor;
class vtkRenderer;

namespace cloudvis
{

class SliceColors;

// A probed voxel.
struct SliceProbe
{
  bool Valid = false;
  std::array<int, 3> Index{ { 0, 0, 0 } };
  std::array<double, 3> Position{ { 0.0, 0.0, 0.0 } }; // world coordinates of the voxel
  double Value = 0.0;
};

class SlicePlanes
{
public:
  SlicePlanes(vtkImageData* field,
    vtkRenderer* renderer,
    vtkRenderWindowInteractor* interactor,
    SliceColors& colors);
  ~SlicePlanes();
  SlicePlanes(const SlicePlanes&) = delete;
  SlicePlanes& operator=(const SlicePlanes&) = delete;

  // Called after a slice moved, the probe changed or the window/level changed through a plane.
  std::function<void()> Changed;

  // Axis 0, 1, 2: the slice across x, y, z.
  void SetSliceVisible(int axis, bool visible);
  bool GetSliceVisible(int axis) const;
  // The voxel layer the slice shows, clamped to the field.
  void SetSliceIndex(int axis, int index);
  int GetSliceIndex(int axis) const;
  // The voxel layer nearest to world coordinate `position` along the axis (a saved scene's).
  void SetSlicePosition(int axis, double position);
  int GetNumberOfSlices(int axis) const;
  // The field's values on the slice across `axis` (its voxel layer), for the automatic window.
  std::vector<double> GetSliceValues(int axis) const;
  // World coordinate of the slice along its axis.
  double GetSlicePosition(int axis) const;
  // The density under the slice's cursor (the last left-button probe on that plane); NaN before.
  double GetProbedValue(int axis) const;

  // The last probe, from a plane or a slice view.
  const SliceProbe& GetProbe() const { return this->Probe; }
  // Probes the voxel nearest to `position` (world coordinates) on the slice across `axis`, and
  // moves the other two slices through it (the crosshairs); returns false outside the field.
  bool ProbeAt(const std::array<double, 3>& position, int axis);
  void ClearProbe() { this->Probe = SliceProbe(); }
  // The voxel nearest to `position`, not probed (Valid false outside the field).
  SliceProbe VoxelAt(const std::array<double, 3>& position) const;
  // The voxel under window pixel x, y on the nearest shown slice of the 3D view (Valid false when
  // no slice is there).
  SliceProbe VoxelUnder(int x, int y);
  // The axis of the nearest shown slice under window pixel x, y of the 3D view; -1 for none
  // (VoxelUnder's pick).
  int AxisUnder(int x, int y);

  void SetObliqueVisible(bool visible);
  bool GetObliqueVisible() const { return this->ObliqueVisible; }
  std::array<double, 3> GetObliqueOrigin() const;
  std::array<double, 3> GetObliqueNormal() const;
  // Places the oblique plane (a saved scene's): an origin and a normal of any nonzero length.
  void SetObliquePlane(const std::array<double, 3>& origin, const std::array<double, 3>& normal);
  // Number of points in the oblique cut (0 when it misses the field).
  long GetObliqueCutPoints() const;

  // Follows the oblique widget's plane (called on its InteractionEvent).
  void UpdateObliqueCut();

private:
  void OnPlaneEvent(int axis, unsigned long event);

  vtkImageData* Field;
  vtkRenderer* Renderer;
  vtkRenderWindowInteractor* Interactor;
  SliceColors& Colors;
  SliceProbe Probe;
  std::array<vtkSmartPointer<vtkImagePlaneWidget>, 3> Slices;
  vtkNew<vtkCellPicker> HoverPicker; // picks the shown slices' planes only
  vtkNew<vtkImplicitPlaneRepresentation> ObliqueRepresentation;
  vtkNew<vtkImplicitPlaneWidget2> ObliqueWidget;
  vtkNew<vtkPlane> ObliquePlane;
  vtkNew<vtkCutter> ObliqueCutter;
  vtkNew<vtkActor> ObliqueActor;
  bool ObliqueVisible = false;
};

} // namespace cloudvis

#endif
