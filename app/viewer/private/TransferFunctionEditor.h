// The viewer's transfer-function editor: two VTK charts in one vtkContextScene, drawn by a
// vtkContextActor in the bottom viewport of the viewer's window (no vtkContextView, no Qt).
// The upper chart edits opacity per unit distance over density (vtkPiecewiseControlPointsItem:
// click to add a point, drag to move, Delete to remove) over the field's histogram (a vtkPlotBar,
// log scale by default because cloud fields are mostly empty); the lower strip edits the color
// (vtkColorTransferControlPointsItem over vtkColorTransferFunctionItem). The functions edited
// are the very vtkPiecewiseFunction and vtkColorTransferFunction of the volume's property, so
// the 3D view follows every change; the viewer observes their ModifiedEvent to re-render.
#ifndef cloudvis_TransferFunctionEditor_h
#define cloudvis_TransferFunctionEditor_h

#include "Scene.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <array>
#include <vector>

class vtkChartXY;
class vtkColorTransferControlPointsItem;
class vtkColorTransferFunction;
class vtkColorTransferFunctionItem;
class vtkContextActor;
class vtkContextScene;
class vtkImageData;
class vtkPiecewiseControlPointsItem;
class vtkPiecewiseFunction;
class vtkPiecewiseFunctionItem;
class vtkPlotBar;
class vtkRenderer;
class vtkTable;
class vtkVolumeProperty;

namespace cloudvis
{

// The points of a property's functions as a scene's transfer_function section (unit distance
// included), and back.
TransferFunctionSpec TransferFunctionOf(vtkVolumeProperty* property);
void SetTransferFunction(vtkVolumeProperty* property, const TransferFunctionSpec& spec);

class TransferFunctionEditor
{
public:
  // Edits `property`'s functions; the histogram is of `field`'s scalars. The charts are drawn in
  // `renderer`, whose viewport the caller places.
  TransferFunctionEditor(vtkVolumeProperty* property, vtkImageData* field, vtkRenderer* renderer);
  ~TransferFunctionEditor();
  TransferFunctionEditor(const TransferFunctionEditor&) = delete;
  TransferFunctionEditor& operator=(const TransferFunctionEditor&) = delete;

  vtkContextScene* GetScene() const;

  // Histogram heights as log10(1 + count) (true, the default) or counts, both scaled to [0, 1].
  void SetLogHistogram(bool logScale);
  bool GetLogHistogram() const { return this->LogHistogram; }

  // Stretches the functions' points so that they span the field's value range (the first point
  // at its minimum, the last at its maximum) and shows that range.
  void FitToData();

  // Call after the functions were replaced wholesale (a preset): the axes follow their points.
  void UpdateRange();

  // The density range the charts show.
  std::array<double, 2> GetRange() const { return this->Range; }

private:
  void FillHistogram();
  void LayOut();

  vtkVolumeProperty* Property;
  vtkRenderer* Renderer;
  std::array<double, 2> DataRange{ { 0.0, 1.0 } };
  std::array<double, 2> Range{ { 0.0, 1.0 } };
  std::vector<double> Counts; // histogram bins over DataRange
  bool LogHistogram = true;

  vtkNew<vtkContextScene> Scene;
  vtkNew<vtkContextActor> Actor;
  vtkNew<vtkChartXY> OpacityChart;
  vtkNew<vtkChartXY> ColorChart;
  vtkNew<vtkTable> Histogram;
  vtkNew<vtkPlotBar> HistogramBars;
  vtkNew<vtkPiecewiseFunctionItem> OpacityCurve;
  vtkNew<vtkPiecewiseControlPointsItem> OpacityPoints;
  vtkNew<vtkColorTransferFunctionItem> ColorBar;
  vtkNew<vtkColorTransferControlPointsItem> ColorPoints;
  unsigned long LayoutObserver = 0;
};

} // namespace cloudvis

#endif
