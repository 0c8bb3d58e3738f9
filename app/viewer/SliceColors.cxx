// Implementation of SliceColors.h. The table has 256 entries; a colormap given by a few anchor
// colors is interpolated linearly between them.
#include "SliceColors.h"

#include "CloudTransferTable.h"
#include "Scene.h" // SliceColormapNames

#include <vtkColorTransferFunction.h>
#include <vtkLookupTable.h>
#include <vtkMath.h>
#include <vtkScalarBarActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{
namespace
{
constexpr int TableSize = 256;

using Rgb = std::array<double, 3>;

// Evenly spaced anchors of matplotlib's viridis (perceptually uniform, readable in gray).
const std::vector<Rgb>& ViridisAnchors()
{
  static const std::vector<Rgb> anchors = { { { 0.267, 0.005, 0.329 } },
    { { 0.283, 0.141, 0.458 } },
    { { 0.254, 0.265, 0.530 } },
    { { 0.207, 0.372, 0.553 } },
    { { 0.164, 0.471, 0.558 } },
    { { 0.128, 0.567, 0.551 } },
    { { 0.135, 0.659, 0.518 } },
    { { 0.267, 0.749, 0.441 } },
    { { 0.478, 0.821, 0.318 } },
    { { 0.741, 0.873, 0.150 } },
    { { 0.993, 0.906, 0.144 } } };
  return anchors;
}

Rgb Interpolate(const std::vector<Rgb>& anchors, double t)
{
  const double at = std::clamp(t, 0.0, 1.0) * double(anchors.size() - 1);
  const size_t i = std::min(size_t(at), anchors.size() - 2);
  const double f = at - double(i);
  Rgb color;
  for (size_t c = 0; c < 3; ++c)
  {
    color[c] = anchors[i][c] * (1.0 - f) + anchors[i + 1][c] * f;
  }
  return color;
}
} // namespace

SliceColors::SliceColors(const std::array<double, 2>& range,
  vtkColorTransferFunction* transferColors)
  : TransferColors(transferColors)
  , Range(range)
{
  WidenEmptyRange(this->Range.data());
  this->Window = this->Range[1] - this->Range[0];
  this->Level = 0.5 * (this->Range[0] + this->Range[1]);
  this->Table->SetNumberOfTableValues(TableSize);
  this->Update();

  this->ColorBar->SetLookupTable(this->Table);
  StyleColorBar(this->ColorBar, "slices");
}

SliceColors::~SliceColors() = default;

vtkLookupTable* SliceColors::GetTable() const
{
  return this->Table;
}

vtkScalarBarActor* SliceColors::GetColorBar() const
{
  return this->ColorBar;
}

const std::vector<std::string>& SliceColors::ColormapNames()
{
  return SliceColormapNames();
}

void SliceColors::NextColormap()
{
  this->Colormap = (this->Colormap + 1) % ColormapNames().size();
  this->Update();
}

const std::string& SliceColors::GetColormap() const
{
  return ColormapNames()[this->Colormap];
}

void SliceColors::SetColormap(size_t index)
{
  this->Colormap = std::min(index, ColormapNames().size() - 1);
  this->Update();
}

void SliceColors::SetWindowLevel(double window, double level)
{
  this->Window = std::max(window, 1e-3 * (this->Range[1] - this->Range[0]));
  this->Level = level;
  this->Update();
}

void SliceColors::ResetWindowLevel()
{
  this->SetWindowLevel(this->Range[1] - this->Range[0], 0.5 * (this->Range[0] + this->Range[1]));
}

bool SliceColors::IsWindowed() const
{
  return this->GetColormap() != "transfer function" || !this->TransferColors;
}

void SliceColors::BeginWindowLevelDrag(int x, int y)
{
  this->DragStart = { { x, y } };
  this->DragStartWindowLevel = { { this->Window, this->Level } };
}

void SliceColors::DragWindowLevel(int x, int y, int viewportWidth, int viewportHeight)
{
  const double span = this->Range[1] - this->Range[0];
  const double dx = double(x - this->DragStart[0]) / std::max(1, viewportWidth);
  const double dy = double(y - this->DragStart[1]) / std::max(1, viewportHeight);
  this->SetWindowLevel(
    this->DragStartWindowLevel[0] + dx * span, this->DragStartWindowLevel[1] + dy * span);
}

void SliceColors::Update()
{
  double low = this->Level - 0.5 * this->Window;
  double high = this->Level + 0.5 * this->Window;
  if (!this->IsWindowed())
  {
    // The function's own range: beyond it the function holds its end colors, as the table does.
    double range[2];
    this->TransferColors->GetRange(range);
    WidenEmptyRange(range);
    low = range[0];
    high = range[1];
  }
  this->Table->SetTableRange(low, high);
  const std::string& name = this->GetColormap();
  for (int i = 0; i < TableSize; ++i)
  {
    const double t = double(i) / (TableSize - 1);
    Rgb color{ { t, t, t } };
    if (name == "blue-yellow")
    {
      // Dark blue through teal to pale yellow: empty space dark, dense cloud bright.
      double hsv[3] = { 0.66 + (0.14 - 0.66) * t, 0.85 + (0.45 - 0.85) * t, 0.25 + 0.75 * t };
      vtkMath::HSVToRGB(hsv, color.data());
    }
    else if (name == "viridis")
    {
      color = Interpolate(ViridisAnchors(), t);
    }
    else if (!this->IsWindowed())
    {
      this->TransferColors->GetColor(low + t * (high - low), color.data());
    }
    this->Table->SetTableValue(i, color[0], color[1], color[2], 1.0);
  }
  this->Table->Modified();
}

void StyleColorBar(vtkScalarBarActor* bar, const std::string& title)
{
  bar->SetTitle(title.c_str());
  bar->SetNumberOfLabels(3);
  bar->SetLabelFormat("%.3g");
  bar->SetBarRatio(0.3);
  bar->UnconstrainedFontSizeOn();
  SetColorBarFontScale(bar, 1.0);
  for (vtkTextProperty* text : { bar->GetTitleTextProperty(), bar->GetLabelTextProperty() })
  {
    text->SetColor(0.95, 0.95, 0.95);
    text->ShadowOff();
    text->BoldOff();
    text->ItalicOff();
  }
}

void SetColorBarFontScale(vtkScalarBarActor* bar, double scale)
{
  const int pixels = std::max(1, int(std::lround(12.0 * scale)));
  bar->GetTitleTextProperty()->SetFontSize(pixels);
  bar->GetLabelTextProperty()->SetFontSize(pixels);
  // The title clear of the top label.
  bar->SetVerticalTitleSeparation(std::max(1, int(std::lround(6.0 * scale))));
}

} // namespace cloudvis
