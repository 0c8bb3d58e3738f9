// The charts are laid out by hand (AutoSize off) from the renderer's size at the start of every
// render, because one scene holds two charts: the opacity chart above, the color strip below.
// Both charts show the same density range with fixed axes, and every chart action (pan, zoom,
// select) is switched off, so a mouse button in the editor only ever reaches the control points.
#include "TransferFunctionEditor.h"

#include "CloudTransferTable.h"

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
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPen.h>
#include <vtkPiecewiseControlPointsItem.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPiecewiseFunctionItem.h>
#include <vtkPlotBar.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkVector.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{
namespace
{
constexpr int HistogramBins = 64;

void DisableChartActions(vtkChartXY* chart)
{
  for (int action : { vtkChart::PAN, vtkChart::ZOOM, vtkChart::ZOOM_AXIS, vtkChart::SELECT,
         vtkChart::SELECT_POLYGON, vtkChart::CLICK_AND_DRAG })
  {
    chart->SetActionToButton(action, vtkContextMouseEvent::NO_BUTTON);
  }
  chart->SetZoomWithMouseWheel(false);
  chart->SetAutoSize(false);
  chart->SetShowLegend(false);
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

TransferFunctionEditor::TransferFunctionEditor(
  vtkVolumeProperty* property, vtkImageData* field, vtkRenderer* renderer)
  : Property(property)
  , Renderer(renderer)
{
  vtkDataArray* scalars = field->GetPointData()->GetScalars();
  if (scalars && scalars->GetNumberOfTuples() > 0)
  {
    scalars->GetRange(this->DataRange.data(), 0);
    this->Counts.assign(HistogramBins, 0.0);
    const double width = this->DataRange[1] - this->DataRange[0];
    for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
    {
      const double v = scalars->GetComponent(i, 0);
      const int bin = width > 0.0 ? int((v - this->DataRange[0]) / width * HistogramBins) : 0;
      this->Counts[size_t(std::min(std::max(bin, 0), HistogramBins - 1))] += 1.0;
    }
  }

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
  this->OpacityChart->AddPlot(this->HistogramBars);

  this->OpacityCurve->SetPiecewiseFunction(property->GetScalarOpacity());
  this->OpacityCurve->SetSelectable(false);
  this->OpacityChart->AddPlot(this->OpacityCurve);
  this->OpacityPoints->SetPiecewiseFunction(property->GetScalarOpacity());
  this->OpacityPoints->SetEndPointsRemovable(false);
  this->OpacityPoints->SetShowLabels(true);
  this->OpacityPoints->SetLabelFormat("%.3g: %.3g");
  this->OpacityChart->AddPlot(this->OpacityPoints);

  this->ColorBar->SetColorTransferFunction(property->GetRGBTransferFunction());
  this->ColorBar->SetSelectable(false);
  this->ColorChart->AddPlot(this->ColorBar);
  this->ColorPoints->SetColorTransferFunction(property->GetRGBTransferFunction());
  this->ColorPoints->SetEndPointsRemovable(false);
  this->ColorChart->AddPlot(this->ColorPoints);

  for (vtkChartXY* chart : { this->OpacityChart.Get(), this->ColorChart.Get() })
  {
    DisableChartActions(chart);
    chart->GetAxis(vtkAxis::LEFT)->SetBehavior(vtkAxis::FIXED);
    chart->GetAxis(vtkAxis::LEFT)->SetRange(0.0, 1.0);
    chart->GetAxis(vtkAxis::BOTTOM)->SetBehavior(vtkAxis::FIXED);
    for (int side : { vtkAxis::LEFT, vtkAxis::BOTTOM })
    {
      chart->GetAxis(side)->GetLabelProperties()->SetFontSize(10);
      chart->GetAxis(side)->GetTitleProperties()->SetFontSize(10);
    }
    this->Scene->AddItem(chart);
  }
  this->OpacityChart->GetAxis(vtkAxis::LEFT)->SetTitle("opacity");
  this->OpacityChart->GetAxis(vtkAxis::BOTTOM)->SetTitle("");
  this->ColorChart->GetAxis(vtkAxis::LEFT)->SetTitle("color");
  this->ColorChart->GetAxis(vtkAxis::LEFT)->SetLabelsVisible(false);
  this->ColorChart->GetAxis(vtkAxis::LEFT)->SetTicksVisible(false);
  this->ColorChart->GetAxis(vtkAxis::LEFT)->SetGridVisible(false);
  this->ColorChart->GetAxis(vtkAxis::BOTTOM)->SetTitle("density");
  this->UpdateRange();

  this->Actor->SetScene(this->Scene);
  this->Scene->SetRenderer(renderer);
  renderer->AddViewProp(this->Actor);
  vtkNew<vtkCallbackCommand> layout;
  layout->SetClientData(this);
  layout->SetCallback([](vtkObject*, unsigned long, void* self, void*)
    { static_cast<TransferFunctionEditor*>(self)->LayOut(); });
  this->LayoutObserver = renderer->AddObserver(vtkCommand::StartEvent, layout);
}

TransferFunctionEditor::~TransferFunctionEditor()
{
  this->Renderer->RemoveObserver(this->LayoutObserver);
  this->Renderer->RemoveViewProp(this->Actor);
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

void TransferFunctionEditor::FillHistogram()
{
  const double largest =
    this->Counts.empty() ? 0.0 : *std::max_element(this->Counts.begin(), this->Counts.end());
  const double width = (this->DataRange[1] - this->DataRange[0]) / HistogramBins;
  this->Histogram->SetNumberOfRows(vtkIdType(this->Counts.size()));
  for (size_t i = 0; i < this->Counts.size(); ++i)
  {
    const double c = this->Counts[i];
    const double height = largest <= 0.0 ? 0.0
      : this->LogHistogram ? std::log10(1.0 + c) / std::log10(1.0 + largest)
                           : c / largest;
    this->Histogram->SetValue(vtkIdType(i), 0, this->DataRange[0] + (double(i) + 0.5) * width);
    this->Histogram->SetValue(vtkIdType(i), 1, height);
  }
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
  for (vtkChartXY* chart : { this->OpacityChart.Get(), this->ColorChart.Get() })
  {
    chart->GetAxis(vtkAxis::BOTTOM)->SetRange(lo, hi);
  }
  const double bounds[4] = { lo, hi, 0.0, 1.0 };
  this->OpacityPoints->SetValidBounds(bounds[0], bounds[1], bounds[2], bounds[3]);
  this->ColorPoints->SetValidBounds(bounds[0], bounds[1], bounds[2], bounds[3]);
  this->OpacityPoints->ResetBounds();
  this->ColorPoints->ResetBounds();
  this->Scene->SetDirty(true);
}

void TransferFunctionEditor::FitToData()
{
  TransferFunctionSpec spec = TransferFunctionOf(this->Property);
  double lo = spec.Opacity.front()[0], hi = spec.Opacity.back()[0];
  lo = std::min(lo, spec.Color.front()[0]);
  hi = std::max(hi, spec.Color.back()[0]);
  const double target[2] = { this->DataRange[0], this->DataRange[1] };
  if (hi > lo && target[1] > target[0])
  {
    const auto map = [&](double x) { return target[0] + (x - lo) / (hi - lo) * (target[1] - target[0]); };
    for (auto& p : spec.Opacity)
    {
      p[0] = map(p[0]);
    }
    for (auto& p : spec.Color)
    {
      p[0] = map(p[0]);
    }
    SetTransferFunction(this->Property, spec);
  }
  this->UpdateRange();
}

void TransferFunctionEditor::LayOut()
{
  int size[2];
  this->Renderer->GetTiledSize(&size[0], &size[1]);
  const float w = float(size[0]), h = float(size[1]);
  // The color strip takes a quarter of the height (at least 24 pixels) under the opacity chart;
  // both leave the same margins so their density axes line up.
  const float strip = std::max(24.0f, 0.28f * h);
  this->ColorChart->SetSize(vtkRectf(0.0f, 0.0f, w, strip));
  this->OpacityChart->SetSize(vtkRectf(0.0f, strip - 8.0f, w, h - strip + 8.0f));
}

} // namespace cloudvis
