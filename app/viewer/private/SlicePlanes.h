// The viewer's slices of the density: three orthogonal vtkImagePlaneWidgets (textured with one
// shared colormap over the field's range; left button: cursor with position and value, middle
// button: move the slice, right button: window/level) and an oblique slice, a
// vtkImplicitPlaneWidget2 whose plane cuts the field (vtkCutter) into an opaque colored polygon.
// All are opaque geometry in the 3D renderer, so the cloud composites with them through the
// depth buffer. Each starts hidden; the viewer toggles them with keys.
#ifndef cloudvis_SlicePlanes_h
#define cloudvis_SlicePlanes_h

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <array>

class vtkActor;
class vtkCutter;
class vtkImageData;
class vtkImagePlaneWidget;
class vtkImplicitPlaneRepresentation;
class vtkImplicitPlaneWidget2;
class vtkLookupTable;
class vtkPlane;
class vtkRenderWindowInteractor;
class vtkRenderer;

namespace cloudvis
{

class SlicePlanes
{
public:
  SlicePlanes(vtkImageData* field, vtkRenderer* renderer, vtkRenderWindowInteractor* interactor);
  ~SlicePlanes();
  SlicePlanes(const SlicePlanes&) = delete;
  SlicePlanes& operator=(const SlicePlanes&) = delete;

  // Axis 0, 1, 2: the slice across x, y, z.
  void SetSliceVisible(int axis, bool visible);
  bool GetSliceVisible(int axis) const;
  // World coordinate of the slice along its axis.
  double GetSlicePosition(int axis) const;
  // The density under the slice's cursor (the last left-button probe); NaN before any.
  double GetProbedValue(int axis) const;

  void SetObliqueVisible(bool visible);
  bool GetObliqueVisible() const { return this->ObliqueVisible; }
  std::array<double, 3> GetObliqueOrigin() const;
  std::array<double, 3> GetObliqueNormal() const;
  // Number of points in the oblique cut (0 when it misses the field).
  long GetObliqueCutPoints() const;

  // Follows the oblique widget's plane (called on its InteractionEvent).
  void UpdateObliqueCut();

private:
  vtkRenderer* Renderer;
  vtkNew<vtkLookupTable> Colors;
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
