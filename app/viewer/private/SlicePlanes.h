// The viewer's slices of the density, and the authority on where they are: three orthogonal
// vtkImagePlaneWidgets in the 3D view (left button: probe the voxel under the cursor, middle
// drag: move the slice, right drag: window/level of every slice) and an oblique slice, a
// vtkImplicitPlaneWidget2 whose plane cuts the field (vtkCutter) into an opaque colored polygon.
// All are opaque geometry in the 3D renderer, so the cloud composites with them through the depth
// buffer, and all are colored by the shared SliceColors table. Each starts hidden; the viewer
// toggles them with keys. The orthogonal slices always sit on a voxel layer (a slice index), so
// the 2D slice views (SliceViews.h) show exactly what the planes show; they read and set the
// indices here. The last probe, from a plane or a slice view, stays until the next one.
#ifndef cloudvis_SlicePlanes_h
#define cloudvis_SlicePlanes_h

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <array>
#include <functional>

class vtkActor;
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
  // World coordinate of the slice along its axis.
  double GetSlicePosition(int axis) const;
  // The density under the slice's cursor (the last left-button probe on that plane); NaN before.
  double GetProbedValue(int axis) const;

  // The last probe, from a plane or a slice view.
  const SliceProbe& GetProbe() const { return this->Probe; }
  // Probes the voxel nearest to `position` (world coordinates); returns false outside the field.
  bool ProbeAt(const std::array<double, 3>& position);

  void SetObliqueVisible(bool visible);
  bool GetObliqueVisible() const { return this->ObliqueVisible; }
  std::array<double, 3> GetObliqueOrigin() const;
  std::array<double, 3> GetObliqueNormal() const;
  // Places the oblique plane (a saved scene's); the origin is kept within the field's bounds.
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
  vtkNew<vtkImplicitPlaneRepresentation> ObliqueRepresentation;
  vtkNew<vtkImplicitPlaneWidget2> ObliqueWidget;
  vtkNew<vtkPlane> ObliquePlane;
  vtkNew<vtkCutter> ObliqueCutter;
  vtkNew<vtkActor> ObliqueActor;
  bool ObliqueVisible = false;
};

} // namespace cloudvis

#endif
