// The viewer's transfer-function editor: two VTK charts in one vtkContextScene, drawn by a
// vtkContextActor in the bottom viewport of the viewer's window (no vtkContextView, no Qt).
// The upper chart edits opacity per unit distance over density (vtkPiecewiseControlPointsItem:
// click to add a point, drag to move) over the field's histogram (a vtkPlotBar, log scale by
// default because cloud fields are mostly empty); the lower strip edits the color
// (vtkColorTransferControlPointsItem over vtkColorTransferFunctionItem). The functions edited
// are the very vtkPiecewiseFunction and vtkColorTransferFunction of the volume's property, so
// the 3D view follows every change; the viewer observes their ModifiedEvent to re-render.
//
// Both charts put their axes on rectangles computed from the renderer's size (AXES_TO_RECT), with
// the same left and right edges, so one density sits at the same x on both; the color strip is
// never less than 14 pixels tall, enough to see and grab its points. The axes reach a little
// beyond the function's range on every side, because a chart only takes presses strictly inside
// its axes: a point on the range's edge could not be grabbed otherwise.
//
// Color points are drawn in their own colors; while one is selected a palette of swatches
// (ColorPalette.h) offers colors for it at a click.
//
// Undo is the viewer's (ViewerHistory.h): a drag, an added or removed point, typed values, a
// swatch picked, a preset, a fit or a reset is one step each there, with the camera and lighting
// changes.
#ifndef cloudvis_TransferFunctionEditor_h
#define cloudvis_TransferFunctionEditor_h

#include "Scene.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

class vtkChartXY;
class vtkColorTransferControlPointsItem;
class vtkColorTransferFunction;
class vtkColorTransferFunctionItem;
class vtkContextActor;
class vtkContextScene;
class vtkControlPointsItem;
class vtkImageData;
class vtkPiecewiseControlPointsItem;
class vtkPiecewiseFunction;
class vtkPiecewiseFunctionItem;
class vtkPlotBar;
class vtkRenderer;
class vtkTable;
class vtkTextActor;
class vtkVolumeProperty;

namespace cloudvis
{

class vtkCloudColorPalette;

// The points of a property's functions as a scene's transfer_function section (unit distance
// included), and back.
TransferFunctionSpec TransferFunctionOf(vtkVolumeProperty* property);
void SetTransferFunction(vtkVolumeProperty* property, const TransferFunctionSpec& spec);
bool SameTransferFunction(const TransferFunctionSpec& a, const TransferFunctionSpec& b);

// Numbers typed by the user, separated by spaces or commas; empty when a word is not a finite
// number.
std::vector<double> ParseTypedNumbers(const std::string& text);

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

  // The histogram is of `field`'s scalars now (the viewer's next time step); the functions stay,
  // the charts' range takes in the new values.
  void SetField(vtkImageData* field);

  // Histogram heights as log10(1 + count) (true, the default) or counts, both scaled to [0, 1].
  void SetLogHistogram(bool logScale);
  bool GetLogHistogram() const { return this->LogHistogram; }

  // Stretches the functions' points so that they span the field's value range (the first point
  // at its minimum, the last at its maximum) and shows that range.
  void FitToData();

  // Replaces the functions (a preset, the scene's function, an undone step) and shows their
  // range.
  void Apply(const TransferFunctionSpec& spec);

  // The density range the charts show.
  std::array<double, 2> GetRange() const { return this->Range; }

  // Around a mouse drag in the charts: the value of the point under the pointer is shown only
  // while the drag lasts.
  void BeginDrag();
  void EndDrag();
  bool GetTooltipsVisible() const;
  // The pointer left the editor: the charts' hover tooltip (the histogram bar under the pointer)
  // goes. The charts hide it only on their own leave event, which never came.
  void PointerLeft();
  // The tooltips' texts (empty when not shown), in one format: "density D: VALUE".
  std::string GetHoverTooltip() const;
  std::string GetDragTooltip() const;

  enum class Function
  {
    None,
    Opacity,
    Color
  };
  // The selected point (the last clicked or added): its function and index, or None and -1.
  Function GetSelectedFunction() const;
  int GetSelectedPoint() const;
  static const char* FunctionName(Function function);

  // Removes the selected point. Returns an empty string, or why it could not be removed.
  std::string DeleteSelectedPoint();

  // The selected point's values as typed: "density opacity" or "density red green blue".
  std::string GetSelectedPointValues() const;
  // Sets them from typed text (numbers separated by spaces or commas). Returns an empty string,
  // or what is wrong with the text (nothing changes then).
  std::string SetSelectedPointValues(const std::string& text);
  // Gives the selected color point `rgb` (each in [0, 1]; the color palette's swatch clicked),
  // as typed values would. Returns an empty string, or why not.
  std::string SetSelectedPointColor(const std::array<double, 3>& rgb);

  // The line at the top of the editor: the selected point's values and what keys do with it,
  // or `entry` while values are being typed (empty: not typing).
  void SetEntry(const std::string& entry);
  std::string GetInfoText() const;

  // Where the points are drawn, in window pixels (x, y from the bottom left), for tests and
  // tools driving the editor with a real mouse.
  std::vector<std::array<double, 2>> GetPointPixels(Function function) const;
  // The color strip's rectangle in window pixels: x0, y0, x1, y1.
  std::array<double, 4> GetColorStripPixels() const;
  // The color palette (ColorPalette.h), shown while a color point is selected: its rectangle in
  // window pixels, x0, y0, x1, y1.
  std::array<double, 4> GetPalettePixels() const;
  bool GetPaletteVisible() const;

private:
  void CountHistogram(vtkImageData* field); // Counts and DataRange
  void FillHistogram();
  void LayOut();
  void UpdateRange();
  void UpdateInfo();
  // The selected point's values, checked (density between its neighbours, values in [0, 1]).
  std::string SetSelectedPointNumbers(const std::vector<double>& numbers);
  void Restore(const TransferFunctionSpec& spec);
  vtkControlPointsItem* SelectedItem() const;

  vtkVolumeProperty* Property;
  vtkRenderer* Renderer;
  std::array<double, 2> DataRange{ { 0.0, 1.0 } };
  std::array<double, 2> Range{ { 0.0, 1.0 } };
  std::vector<double> Counts; // histogram bins over DataRange
  bool LogHistogram = true;
  Function Selected = Function::None;
  std::string Entry;
  bool Dragging = false;
  // The charts' axes rectangles (x, y, width, height in the editor's pixels) and the ranges their
  // axes show, padded beyond the function's range.
  std::array<double, 4> OpacityRect{ { 0.0, 0.0, 1.0, 1.0 } };
  std::array<double, 4> ColorRect{ { 0.0, 0.0, 1.0, 1.0 } };
  std::array<double, 2> AxisRange{ { 0.0, 1.0 } };

  vtkNew<vtkContextScene> Scene;
  vtkNew<vtkContextActor> Actor;
  vtkNew<vtkChartXY> OpacityChart;
  vtkNew<vtkChartXY> ColorChart;
  vtkNew<vtkTable> Histogram;
  vtkNew<vtkPlotBar> HistogramBars;
  vtkNew<vtkPiecewiseFunctionItem> OpacityCurve;
  vtkSmartPointer<vtkPiecewiseControlPointsItem> OpacityPoints; // end points move in x and y
  vtkNew<vtkColorTransferFunctionItem> ColorBar;
  vtkNew<vtkColorTransferControlPointsItem> ColorPoints;
  vtkNew<vtkCloudColorPalette> Palette;
  vtkNew<vtkTextActor> Info;
  unsigned long LayoutObserver = 0;
};

} // namespace cloudvis

#endif
