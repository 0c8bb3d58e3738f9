// The charts are laid out by hand from the renderer's size at the start of every render, because
// one scene holds two charts: the opacity chart above, the color strip below. Both charts show
// the same density range with fixed axes, and every chart action (pan, zoom, select) is switched
// off, so a mouse button in the editor only ever reaches the control points. Keys never reach
// the charts (the viewer's key table calls DeleteSelectedPoint and the typed-value entry).
#include "TransferFunctionEditor.h"

#include "CloudTransferTable.h"
#include "ColorPalette.h"
#include "Viewer.h"

#include <vtkAxis.h>
#include <vtkBrush.h>
#include <vtkCallbackCommand.h>
#include <vtkChartXY.h>
#include <vtkColorTransferControlPointsItem.h>
#include <vtkColorTransferFunction.h>
#include <vtkColorTransferFunctionItem.h>
#include <vtkContextActor.h>
#include <vtkContextMouseEvent.h>
#include <vtkContextScene.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkObjectFactory.h>
#include <vtkPen.h>
#include <vtkPiecewiseControlPointsItem.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPiecewiseFunctionItem.h>
#include <vtkPlotBar.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTooltipItem.h>
#include <vtkVector.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace cloudvis
{
namespace
{
constexpr int HistogramBins = 64;
// How far the axes reach beyond the range, as a fraction of it, so that points on its edges lie
// strictly inside the chart (vtkChartXY::Hit) and can be grabbed.
constexpr double AxisPadding = 0.03;
constexpr double OpacityAxisLow = -0.05;
constexpr double OpacityAxisHigh = 1.05;
// The editor's layout in pixels.
constexpr double LeftMargin = 44.0;
constexpr double RightMargin = 14.0;
constexpr double MinimumStrip = 14.0;
constexpr double MaximumStrip = 30.0;
// The tooltips' one format, "density D: VALUE": the dragged point's label (the control points'
// label format, printf with the point's density and opacity) and the histogram bar under the
// pointer (the chart's hover tooltip, made from the bar's bin).
const char* const OpacityTooltipFormat = "density %.3g: opacity %.3g";
const char* const ColorTooltipFormat = "density %.3g";
const char* const BarTooltipFormat = "density %.3g: %.0f voxels";

// Opacity points whose end points move in both directions. VTK's items move an end point along
// one axis only (x when EndPointsXMovable, the default, else y), so the opacity at the ends of
// the range could not be dragged up or down.
class vtkCloudOpacityPointsItem : public vtkPiecewiseControlPointsItem
{
public:
  static vtkCloudOpacityPointsItem* New();
  vtkTypeMacro(vtkCloudOpacityPointsItem, vtkPiecewiseControlPointsItem);

  bool MouseMoveEvent(const vtkContextMouseEvent& mouse) override
  {
    const vtkIdType current = this->GetCurrentPoint();
    const bool endPoint = current == 0 || current == this->GetNumberOfPoints() - 1;
    if (mouse.GetButton() != vtkContextMouseEvent::LEFT_BUTTON || current < 0 || !endPoint ||
      this->GetStrokeMode())
    {
      return this->Superclass::MouseMoveEvent(mouse);
    }
    // By the motion, not to the pointer: a vertical drag keeps the density exactly where it was.
    vtkVector2f now, last;
    this->TransformScreenToData(mouse.GetPos(), now);
    this->TransformScreenToData(mouse.GetLastPos(), last);
    double point[4];
    this->GetControlPoint(current, point);
    this->StartInteractionIfNotStarted();
    // Within the valid bounds and the neighbours.
    this->SetCurrentPointPos(
      vtkVector2f(float(point[0] + (now[0] - last[0])), float(point[1] + (now[1] - last[1]))));
    this->Interaction();
    return true;
  }

protected:
  vtkCloudOpacityPointsItem() = default;
  ~vtkCloudOpacityPointsItem() override = default;
};
vtkStandardNewMacro(vtkCloudOpacityPointsItem);

void DisableChartActions(vtkChartXY* chart)
{
  for (int action : { vtkChart::PAN,
         vtkChart::ZOOM,
         vtkChart::ZOOM_AXIS,
         vtkChart::SELECT,
         vtkChart::SELECT_POLYGON,
         vtkChart::CLICK_AND_DRAG })
  {
    chart->SetActionToButton(action, vtkContextMouseEvent::NO_BUTTON);
  }
  chart->SetZoomWithMouseWheel(false);
  chart->SetAutoSize(false);
  chart->SetShowLegend(false);
  // The axes on the rectangle SetSize gives (labels and titles outside it): both charts' axes
  // then start and end at the same x.
  chart->SetLayoutStrategy(vtkChart::AXES_TO_RECT);
}

} // namespace

std::vector<double> ParseTypedNumbers(const std::string& text)
{
  std::string spaced = text;
  std::replace(spaced.begin(), spaced.end(), ',', ' ');
  std::istringstream in(spaced);
  std::vector<double> numbers;
  std::string word;
  while (in >> word)
  {
    size_t used = 0;
    double value = 0.0;
    try
    {
      value = std::stod(word, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (used != word.size() || !std::isfinite(value))
    {
      return {};
    }
    numbers.push_back(value);
  }
  return numbers;
}

namespace
{
std::string Format(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", value);
  return text;
}
} // namespace

TransferFunctionSpec TransferFunctionOf(vtkVolumeProperty* property)
{
  TransferFunctionSpec spec;
  spec.Opacity.clear();
  spec.Color.clear();
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity();
  for (int i = 0; i < opacity->GetSize(); ++i)
  {
    double node[4];
    opacity->GetNodeValue(i, node);
    spec.Opacity.push_back({ { node[0], node[1] } });
  }
  vtkColorTransferFunction* color = property->GetRGBTransferFunction();
  for (int i = 0; i < color->GetSize(); ++i)
  {
    double node[6];
    color->GetNodeValue(i, node);
    spec.Color.push_back({ { node[0], node[1], node[2], node[3] } });
  }
  spec.UnitDistance = property->GetScalarOpacityUnitDistance();
  return spec;
}

void SetTransferFunction(vtkVolumeProperty* property, const TransferFunctionSpec& spec)
{
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity();
  opacity->RemoveAllPoints();
  for (const auto& point : spec.Opacity)
  {
    opacity->AddPoint(point[0], point[1]);
  }
  vtkColorTransferFunction* color = property->GetRGBTransferFunction();
  color->RemoveAllPoints();
  for (const auto& point : spec.Color)
  {
    color->AddRGBPoint(point[0], point[1], point[2], point[3]);
  }
  property->SetScalarOpacityUnitDistance(spec.UnitDistance);
}

bool SameTransferFunction(const TransferFunctionSpec& a, const TransferFunctionSpec& b)
{
  return a.Opacity == b.Opacity && a.Color == b.Color && a.UnitDistance == b.UnitDistance;
}

TransferFunctionEditor::TransferFunctionEditor(vtkVolumeProperty* property,
  vtkImageData* field,
  vtkRenderer* renderer)
  : Property(property)
  , Renderer(renderer)
  , OpacityPoints(vtkSmartPointer<vtkCloudOpacityPointsItem>::New())
{
  this->CountHistogram(field);

  // Histogram behind the opacity curve: bars at the bin centres, one bin wide.
  vtkNew<vtkFloatArray> density;
  density->SetName("density");
  vtkNew<vtkFloatArray> count;
  count->SetName("count");
  this->Histogram->AddColumn(density);
  this->Histogram->AddColumn(count);
  this->FillHistogram();
  this->HistogramBars->SetInputData(this->Histogram, 0, 1);
  this->HistogramBars->SetColor(0.72, 0.74, 0.80);
  this->HistogramBars->GetPen()->SetLineType(vtkPen::NO_PEN);
  this->HistogramBars->SetSelectable(false);
  this->HistogramBars->SetTooltipLabelFormat("%i"); // FillHistogram's labels
  this->OpacityChart->AddPlot(this->HistogramBars);

  this->OpacityCurve->SetPiecewiseFunction(property->GetScalarOpacity());
  this->OpacityCurve->SetSelectable(false);
  this->OpacityChart->AddPlot(this->OpacityCurve);
  this->OpacityPoints->SetPiecewiseFunction(property->GetScalarOpacity());
  this->OpacityPoints->SetEndPointsRemovable(false);
  this->OpacityPoints->SetShowLabels(false); // only while a drag lasts
  this->OpacityPoints->SetLabelFormat(OpacityTooltipFormat);
  this->OpacityChart->AddPlot(this->OpacityPoints);

  this->ColorBar->SetColorTransferFunction(property->GetRGBTransferFunction());
  this->ColorBar->SetSelectable(false);
  this->ColorChart->AddPlot(this->ColorBar);
  this->ColorPoints->SetColorTransferFunction(property->GetRGBTransferFunction());
  this->ColorPoints->SetEndPointsRemovable(false);
  this->ColorPoints->SetShowLabels(false);
  this->ColorPoints->SetLabelFormat(ColorTooltipFormat);
  // Each color point drawn in its own color, not VTK's default gray.
  this->ColorPoints->SetColorFill(true);
  this->ColorChart->AddPlot(this->ColorPoints);

  for (vtkChartXY* chart : { this->OpacityChart.Get(), this->ColorChart.Get() })
  {
    DisableChartActions(chart);
    chart->GetAxis(vtkAxis::LEFT)->SetBehavior(vtkAxis::FIXED);
    chart->GetAxis(vtkAxis::BOTTOM)->SetBehavior(vtkAxis::FIXED);
    for (int side : { vtkAxis::LEFT, vtkAxis::BOTTOM })
    {
      chart->GetAxis(side)->GetLabelProperties()->SetFontSize(10);
      chart->GetAxis(side)->GetTitleProperties()->SetFontSize(10);
    }
    this->Scene->AddItem(chart);
  }
  // After the charts: drawn over them, and offered the clicks on it first.
  this->Palette->SetVisible(false);
  this->Palette->Picked = [this](const std::array<double, 3>& rgb)
  { this->SetSelectedPointColor(rgb); };
  this->Scene->AddItem(this->Palette);
  vtkAxis* opacityAxis = this->OpacityChart->GetAxis(vtkAxis::LEFT);
  opacityAxis->SetRange(OpacityAxisLow, OpacityAxisHigh);
  vtkNew<vtkDoubleArray> ticks;
  for (double tick : { 0.0, 0.5, 1.0 })
  {
    ticks->InsertNextValue(tick);
  }
  opacityAxis->SetCustomTickPositions(ticks);
  opacityAxis->SetTitle("opacity");
  // The density labels are under the color strip, which shares the opacity chart's x axis.
  this->OpacityChart->GetAxis(vtkAxis::BOTTOM)->SetTitle("");
  this->OpacityChart->GetAxis(vtkAxis::BOTTOM)->SetLabelsVisible(false);
  vtkAxis* colorAxis = this->ColorChart->GetAxis(vtkAxis::LEFT);
  colorAxis->SetRange(0.0, 1.0);
  colorAxis->SetTitle("");
  colorAxis->SetLabelsVisible(false);
  colorAxis->SetTicksVisible(false);
  colorAxis->SetGridVisible(false);
  this->ColorChart->GetAxis(vtkAxis::BOTTOM)->SetTitle("density");
  this->UpdateRange();

  // Which point is selected: the last one made current in either chart.
  vtkNew<vtkCallbackCommand> selected;
  selected->SetClientData(this);
  selected->SetCallback(
    [](vtkObject* caller, unsigned long, void* self, void*)
    {
      auto* editor = static_cast<TransferFunctionEditor*>(self);
      auto* item = static_cast<vtkControlPointsItem*>(caller);
      const bool opacity = item == editor->OpacityPoints.Get();
      if (item->GetCurrentPoint() >= 0)
      {
        editor->Selected = opacity ? Function::Opacity : Function::Color;
        vtkControlPointsItem* other = opacity
          ? static_cast<vtkControlPointsItem*>(editor->ColorPoints.Get())
          : static_cast<vtkControlPointsItem*>(editor->OpacityPoints.Get());
        other->SetCurrentPoint(-1);
      }
      else if (editor->Selected == (opacity ? Function::Opacity : Function::Color))
      {
        editor->Selected = Function::None;
      }
      editor->UpdateInfo();
    });
  this->OpacityPoints->AddObserver(vtkControlPointsItem::CurrentPointChangedEvent, selected);
  this->ColorPoints->AddObserver(vtkControlPointsItem::CurrentPointChangedEvent, selected);
  // Values typed or dragged show in the info line.
  vtkNew<vtkCallbackCommand> changed;
  changed->SetClientData(this);
  changed->SetCallback([](vtkObject*, unsigned long, void* self, void*)
    { static_cast<TransferFunctionEditor*>(self)->UpdateInfo(); });
  property->GetScalarOpacity()->AddObserver(vtkCommand::ModifiedEvent, changed);
  property->GetRGBTransferFunction()->AddObserver(vtkCommand::ModifiedEvent, changed);

  vtkTextProperty* info = this->Info->GetTextProperty();
  UseViewerFont(info);
  info->SetFontSize(11);
  info->SetColor(0.1, 0.1, 0.15);
  info->SetBackgroundColor(1.0, 1.0, 1.0);
  info->SetBackgroundOpacity(0.8);
  info->SetVerticalJustificationToTop();
  this->Info->VisibilityOff();

  this->Actor->SetScene(this->Scene);
  this->Scene->SetRenderer(renderer);
  renderer->AddViewProp(this->Actor);
  renderer->AddActor2D(this->Info); // after the charts, so drawn over them
  vtkNew<vtkCallbackCommand> layout;
  layout->SetClientData(this);
  layout->SetCallback([](vtkObject*, unsigned long, void* self, void*)
    { static_cast<TransferFunctionEditor*>(self)->LayOut(); });
  this->LayoutObserver = renderer->AddObserver(vtkCommand::StartEvent, layout);
}

TransferFunctionEditor::~TransferFunctionEditor()
{
  this->OpacityPoints->RemoveAllObservers();
  this->ColorPoints->RemoveAllObservers();
  this->Renderer->RemoveObserver(this->LayoutObserver);
  this->Renderer->RemoveViewProp(this->Actor);
  this->Renderer->RemoveActor2D(this->Info);
}

vtkContextScene* TransferFunctionEditor::GetScene() const
{
  return this->Scene;
}

void TransferFunctionEditor::SetLogHistogram(bool logScale)
{
  this->LogHistogram = logScale;
  this->FillHistogram();
}

void TransferFunctionEditor::CountHistogram(vtkImageData* field)
{
  vtkDataArray* scalars = field->GetPointData()->GetScalars();
  this->Counts.clear();
  if (!scalars || scalars->GetNumberOfTuples() == 0)
  {
    return;
  }
  scalars->GetRange(this->DataRange.data(), 0);
  this->Counts.assign(HistogramBins, 0.0);
  const double lo = this->DataRange[0], width = this->DataRange[1] - this->DataRange[0];
  const auto count = [&](double v)
  {
    const int bin = width > 0.0 ? int((v - lo) / width * HistogramBins) : 0;
    this->Counts[size_t(std::min(std::max(bin, 0), HistogramBins - 1))] += 1.0;
  };
  const vtkIdType n = scalars->GetNumberOfTuples();
  if (vtkFloatArray* values = vtkFloatArray::FastDownCast(scalars))
  {
    // The density as cloudvis reads every field; a 256^3 step is counted in tens of ms.
    const float* v = values->GetPointer(0);
    for (vtkIdType i = 0; i < n; ++i)
    {
      count(double(v[i * values->GetNumberOfComponents()]));
    }
    return;
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    count(scalars->GetComponent(i, 0));
  }
}

void TransferFunctionEditor::SetField(vtkImageData* field)
{
  this->CountHistogram(field);
  this->FillHistogram();
  this->UpdateRange();
}

void TransferFunctionEditor::FillHistogram()
{
  const double largest =
    this->Counts.empty() ? 0.0 : *std::max_element(this->Counts.begin(), this->Counts.end());
  const double width = (this->DataRange[1] - this->DataRange[0]) / HistogramBins;
  this->Histogram->SetNumberOfRows(vtkIdType(this->Counts.size()));
  vtkNew<vtkStringArray> labels;
  for (size_t i = 0; i < this->Counts.size(); ++i)
  {
    const double c = this->Counts[i];
    const double height = largest <= 0.0 ? 0.0
      : this->LogHistogram               ? std::log10(1.0 + c) / std::log10(1.0 + largest)
                                         : c / largest;
    const double center = this->DataRange[0] + (double(i) + 0.5) * width;
    this->Histogram->SetValue(vtkIdType(i), 0, center);
    this->Histogram->SetValue(vtkIdType(i), 1, height);
    char label[96];
    std::snprintf(label, sizeof(label), BarTooltipFormat, center, c);
    labels->InsertNextValue(label);
  }
  this->HistogramBars->SetIndexedLabels(labels);
  this->Histogram->Modified();
  this->HistogramBars->SetWidth(float(width > 0.0 ? width : 1.0));
  this->Scene->SetDirty(true);
}

void TransferFunctionEditor::UpdateRange()
{
  double lo = this->DataRange[0], hi = this->DataRange[1];
  const TransferFunctionSpec spec = TransferFunctionOf(this->Property);
  for (const auto& p : spec.Opacity)
  {
    lo = std::min(lo, p[0]);
    hi = std::max(hi, p[0]);
  }
  for (const auto& p : spec.Color)
  {
    lo = std::min(lo, p[0]);
    hi = std::max(hi, p[0]);
  }
  double range[2] = { lo, hi };
  WidenEmptyRange(range);
  lo = range[0];
  hi = range[1];
  this->Range = { { lo, hi } };
  const double pad = AxisPadding * (hi - lo);
  this->AxisRange = { { lo - pad, hi + pad } };
  for (vtkChartXY* chart : { this->OpacityChart.Get(), this->ColorChart.Get() })
  {
    chart->GetAxis(vtkAxis::BOTTOM)->SetRange(this->AxisRange[0], this->AxisRange[1]);
  }
  // Points stay within the range, opacity within [0, 1].
  this->OpacityPoints->SetValidBounds(lo, hi, 0.0, 1.0);
  this->ColorPoints->SetValidBounds(lo, hi, 0.0, 1.0);
  this->OpacityPoints->ResetBounds();
  this->ColorPoints->ResetBounds();
  this->Scene->SetDirty(true);
}

void TransferFunctionEditor::Restore(const TransferFunctionSpec& spec)
{
  this->OpacityPoints->SetCurrentPoint(-1);
  this->ColorPoints->SetCurrentPoint(-1);
  SetTransferFunction(this->Property, spec);
  this->UpdateRange();
}

void TransferFunctionEditor::Apply(const TransferFunctionSpec& spec)
{
  this->Restore(spec);
}

void TransferFunctionEditor::FitToData()
{
  this->Apply(StretchTransferFunction(TransferFunctionOf(this->Property), this->DataRange));
}

void TransferFunctionEditor::BeginDrag()
{
  this->Dragging = true;
  this->OpacityPoints->SetShowLabels(true);
  this->ColorPoints->SetShowLabels(true);
}

void TransferFunctionEditor::EndDrag()
{
  if (!this->Dragging)
  {
    return;
  }
  this->Dragging = false;
  // The value tooltip goes with the drag; the info line keeps the selected point's values.
  this->OpacityPoints->SetShowLabels(false);
  this->ColorPoints->SetShowLabels(false);
  this->Scene->SetDirty(true);
  this->UpdateInfo();
}

void TransferFunctionEditor::PointerLeft()
{
  for (vtkChartXY* chart : { this->OpacityChart.Get(), this->ColorChart.Get() })
  {
    if (chart->GetTooltip() && chart->GetTooltip()->GetVisible())
    {
      chart->GetTooltip()->SetVisible(false);
      this->Scene->SetDirty(true);
    }
  }
}

std::string TransferFunctionEditor::GetHoverTooltip() const
{
  for (vtkChartXY* chart : { this->OpacityChart.Get(), this->ColorChart.Get() })
  {
    if (chart->GetTooltip() && chart->GetTooltip()->GetVisible())
    {
      return chart->GetTooltip()->GetText();
    }
  }
  return "";
}

std::string TransferFunctionEditor::GetDragTooltip() const
{
  vtkControlPointsItem* item = this->SelectedItem();
  if (!this->Dragging || !item || !item->GetShowLabels() || item->GetCurrentPoint() < 0)
  {
    return "";
  }
  // As the item writes its label (vtkControlPointsItem::GetControlPointLabel, protected): its
  // format with the point's values.
  double point[4];
  item->GetControlPoint(item->GetCurrentPoint(), point);
  char label[96];
  std::snprintf(label, sizeof(label), item->GetLabelFormat(), point[0], point[1]);
  return label;
}

bool TransferFunctionEditor::GetTooltipsVisible() const
{
  return this->OpacityPoints->GetShowLabels() || this->ColorPoints->GetShowLabels();
}

vtkControlPointsItem* TransferFunctionEditor::SelectedItem() const
{
  switch (this->Selected)
  {
    case Function::Opacity:
      return this->OpacityPoints;
    case Function::Color:
      return this->ColorPoints;
    default:
      return nullptr;
  }
}

TransferFunctionEditor::Function TransferFunctionEditor::GetSelectedFunction() const
{
  return this->Selected;
}

int TransferFunctionEditor::GetSelectedPoint() const
{
  vtkControlPointsItem* item = this->SelectedItem();
  return item ? int(item->GetCurrentPoint()) : -1;
}

const char* TransferFunctionEditor::FunctionName(Function function)
{
  switch (function)
  {
    case Function::Opacity:
      return "opacity";
    case Function::Color:
      return "color";
    default:
      return "";
  }
}

std::string TransferFunctionEditor::DeleteSelectedPoint()
{
  vtkControlPointsItem* item = this->SelectedItem();
  const int point = this->GetSelectedPoint();
  if (!item || point < 0)
  {
    return "no point is selected: click one in the editor first";
  }
  if (point == 0 || point == item->GetNumberOfPoints() - 1)
  {
    return "the end points of a function cannot be removed (move them instead)";
  }
  item->RemovePoint(vtkIdType(point));
  item->SetCurrentPoint(-1);
  return "";
}

std::string TransferFunctionEditor::GetSelectedPointValues() const
{
  const int point = this->GetSelectedPoint();
  if (point < 0)
  {
    return "";
  }
  std::string text;
  if (this->Selected == Function::Opacity)
  {
    double node[4];
    this->Property->GetScalarOpacity()->GetNodeValue(point, node);
    text = Format(node[0]) + " " + Format(node[1]);
  }
  else
  {
    double node[6];
    this->Property->GetRGBTransferFunction()->GetNodeValue(point, node);
    text = Format(node[0]) + " " + Format(node[1]) + " " + Format(node[2]) + " " + Format(node[3]);
  }
  return text;
}

std::string TransferFunctionEditor::SetSelectedPointValues(const std::string& text)
{
  if (this->GetSelectedPoint() < 0)
  {
    return "no point is selected";
  }
  const bool opacity = this->Selected == Function::Opacity;
  const std::vector<double> numbers = ParseTypedNumbers(text);
  const size_t wanted = opacity ? 2 : 4;
  if (numbers.size() != wanted)
  {
    return std::string("type ") +
      (opacity ? "density and opacity" : "density, red, green and blue") + " (" +
      std::to_string(wanted) + " numbers), not \"" + text + "\"";
  }
  return this->SetSelectedPointNumbers(numbers);
}

std::string TransferFunctionEditor::SetSelectedPointColor(const std::array<double, 3>& rgb)
{
  const int point = this->GetSelectedPoint();
  if (this->Selected != Function::Color || point < 0)
  {
    return "no color point is selected";
  }
  double node[6];
  this->Property->GetRGBTransferFunction()->GetNodeValue(point, node);
  return this->SetSelectedPointNumbers({ node[0], rgb[0], rgb[1], rgb[2] });
}

std::string TransferFunctionEditor::SetSelectedPointNumbers(const std::vector<double>& numbers)
{
  vtkControlPointsItem* item = this->SelectedItem();
  const int point = this->GetSelectedPoint();
  const bool opacity = this->Selected == Function::Opacity;
  // The density stays between the neighbouring points and within the range shown.
  double low = this->Range[0], high = this->Range[1];
  const int count = int(item->GetNumberOfPoints());
  double neighbour[4];
  if (point > 0)
  {
    item->GetControlPoint(point - 1, neighbour);
    low = neighbour[0];
  }
  if (point < count - 1)
  {
    item->GetControlPoint(point + 1, neighbour);
    high = neighbour[0];
  }
  const bool inner = point > 0 && point < count - 1;
  if (numbers[0] < low || numbers[0] > high || (inner && (numbers[0] == low || numbers[0] == high)))
  {
    return "the density must lie between " + Format(low) + " and " + Format(high) +
      " (the neighbouring points or the range shown)";
  }
  for (size_t i = 1; i < numbers.size(); ++i)
  {
    if (numbers[i] < 0.0 || numbers[i] > 1.0)
    {
      return std::string(opacity ? "opacity" : "colors") + " must lie in [0, 1], not " +
        Format(numbers[i]);
    }
  }
  if (opacity)
  {
    double node[4];
    this->Property->GetScalarOpacity()->GetNodeValue(point, node);
    node[0] = numbers[0];
    node[1] = numbers[1];
    this->Property->GetScalarOpacity()->SetNodeValue(point, node);
  }
  else
  {
    double node[6];
    this->Property->GetRGBTransferFunction()->GetNodeValue(point, node);
    for (size_t i = 0; i < 4; ++i)
    {
      node[i] = numbers[i];
    }
    this->Property->GetRGBTransferFunction()->SetNodeValue(point, node);
  }
  this->Scene->SetDirty(true);
  return "";
}

void TransferFunctionEditor::SetEntry(const std::string& entry)
{
  this->Entry = entry;
  this->UpdateInfo();
}

std::string TransferFunctionEditor::GetInfoText() const
{
  const char* text = this->Info->GetInput();
  return this->Info->GetVisibility() && text ? text : "";
}

void TransferFunctionEditor::UpdateInfo()
{
  std::string text;
  const int point = this->GetSelectedPoint();
  if (!this->Entry.empty())
  {
    text = this->Entry;
  }
  else if (point >= 0)
  {
    const bool opacity = this->Selected == Function::Opacity;
    text = std::string(opacity ? "opacity" : "color") + " point " + std::to_string(point) + ": " +
      (opacity ? "density, opacity " : "density, r g b ") + this->GetSelectedPointValues() +
      "   Enter: type values, Delete: remove" + (opacity ? "" : ", or click a swatch");
  }
  this->Info->SetInput(text.c_str());
  this->Info->SetVisibility(!text.empty());
  this->Palette->SetVisible(this->Selected == Function::Color && point >= 0);
  this->Scene->SetDirty(true);
}

void TransferFunctionEditor::LayOut()
{
  int size[2];
  this->Renderer->GetTiledSize(&size[0], &size[1]);
  const double w = size[0], h = size[1];
  // Tight editors drop the axis titles first.
  const bool titles = h >= 110.0;
  const double bottom = titles ? 30.0 : 16.0;
  const double top = 6.0;
  const double gap = 6.0;
  const double strip = std::clamp(0.16 * h, MinimumStrip, MaximumStrip);
  const double x0 = LeftMargin, width = std::max(10.0, w - LeftMargin - RightMargin);
  this->ColorRect = { { x0, bottom, width, strip } };
  const double opacityBottom = bottom + strip + gap;
  this->OpacityRect = { { x0, opacityBottom, width, std::max(8.0, h - opacityBottom - top) } };
  this->ColorChart->SetSize(vtkRectf(float(this->ColorRect[0]),
    float(this->ColorRect[1]),
    float(this->ColorRect[2]),
    float(this->ColorRect[3])));
  this->OpacityChart->SetSize(vtkRectf(float(this->OpacityRect[0]),
    float(this->OpacityRect[1]),
    float(this->OpacityRect[2]),
    float(this->OpacityRect[3])));
  this->ColorChart->GetAxis(vtkAxis::BOTTOM)->SetTitle(titles ? "density" : "");
  this->OpacityChart->GetAxis(vtkAxis::LEFT)->SetTitle(titles ? "opacity" : "");
  // Top left, where the opacity curve of a cloud is low and rarely has points.
  this->Info->SetPosition(LeftMargin + 4.0, h - top - 2.0);
  // Under the info line, at the left of the opacity chart too: the right end holds the opacity
  // curve's dense, opaque end, whose points must stay in sight and in reach.
  const double paletteTop = h - top - 16.0;
  this->Palette->SetCorner(
    x0 + 4.0, std::max(this->OpacityRect[1], paletteTop - vtkCloudColorPalette::Size()[1]));
}

std::vector<std::array<double, 2>> TransferFunctionEditor::GetPointPixels(Function function) const
{
  const_cast<TransferFunctionEditor*>(this)->LayOut();
  std::vector<std::array<double, 2>> pixels;
  const bool opacity = function == Function::Opacity;
  vtkControlPointsItem* item = opacity
    ? static_cast<vtkControlPointsItem*>(this->OpacityPoints.Get())
    : static_cast<vtkControlPointsItem*>(this->ColorPoints.Get());
  const std::array<double, 4>& rect = opacity ? this->OpacityRect : this->ColorRect;
  const double yLow = opacity ? OpacityAxisLow : 0.0, yHigh = opacity ? OpacityAxisHigh : 1.0;
  for (vtkIdType i = 0; i < item->GetNumberOfPoints(); ++i)
  {
    double point[4];
    item->GetControlPoint(i, point);
    pixels.push_back({ { rect[0] +
        (point[0] - this->AxisRange[0]) / (this->AxisRange[1] - this->AxisRange[0]) * rect[2],
      rect[1] + (point[1] - yLow) / (yHigh - yLow) * rect[3] } });
  }
  return pixels;
}

std::array<double, 4> TransferFunctionEditor::GetPalettePixels() const
{
  const_cast<TransferFunctionEditor*>(this)->LayOut();
  return this->Palette->GetRect();
}

bool TransferFunctionEditor::GetPaletteVisible() const
{
  return this->Palette->GetVisible();
}

std::array<double, 4> TransferFunctionEditor::GetColorStripPixels() const
{
  const_cast<TransferFunctionEditor*>(this)->LayOut();
  const auto& r = this->ColorRect;
  return { { r[0], r[1], r[0] + r[2], r[1] + r[3] } };
}

} // namespace cloudvis
