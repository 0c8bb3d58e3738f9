// Implementation of ColorPalette.h. Swatches are drawn with the context's brush, flat, so the
// pixels of a swatch are its color exactly.
#include "ColorPalette.h"

#include <vtkBrush.h>
#include <vtkContext2D.h>
#include <vtkContextMouseEvent.h>
#include <vtkMath.h>
#include <vtkObjectFactory.h>
#include <vtkPen.h>

#include <cmath>

namespace cloudvis
{
namespace
{
constexpr double Frame = 2.0; // the white margin around the swatches
constexpr double Pitch = vtkCloudColorPalette::Swatch + 1.0;
} // namespace

vtkStandardNewMacro(vtkCloudColorPalette);

std::array<double, 2> vtkCloudColorPalette::Size()
{
  return { { 2.0 * Frame + Columns * Pitch - 1.0, 2.0 * Frame + Rows * Pitch - 1.0 } };
}

std::array<double, 3> vtkCloudColorPalette::SwatchColor(int row, int column)
{
  std::array<double, 3> rgb;
  if (row == 0)
  {
    double hsv[3] = { double(column) / Columns, 1.0, 1.0 };
    vtkMath::HSVToRGB(hsv, rgb.data());
  }
  else
  {
    const double gray = double(column) / (Columns - 1);
    rgb = { { gray, gray, gray } };
  }
  return rgb;
}

void vtkCloudColorPalette::SetCorner(double x, double y)
{
  this->Corner = { { x, y } };
}

std::array<double, 4> vtkCloudColorPalette::GetRect() const
{
  const std::array<double, 2> size = Size();
  return {
    { this->Corner[0], this->Corner[1], this->Corner[0] + size[0], this->Corner[1] + size[1] }
  };
}

bool vtkCloudColorPalette::Paint(vtkContext2D* painter)
{
  const std::array<double, 4> rect = this->GetRect();
  painter->GetPen()->SetColorF(0.45, 0.45, 0.5);
  painter->GetPen()->SetWidth(1.0f);
  painter->GetBrush()->SetColorF(1.0, 1.0, 1.0, 1.0);
  painter->DrawRect(
    float(rect[0]), float(rect[1]), float(rect[2] - rect[0]), float(rect[3] - rect[1]));
  painter->GetPen()->SetLineType(vtkPen::NO_PEN);
  for (int row = 0; row < Rows; ++row)
  {
    for (int column = 0; column < Columns; ++column)
    {
      const std::array<double, 3> c = SwatchColor(row, column);
      painter->GetBrush()->SetColorF(c[0], c[1], c[2], 1.0);
      // Row 0 on top.
      painter->DrawRect(float(rect[0] + Frame + column * Pitch),
        float(rect[3] - Frame - (row + 1) * Pitch + 1.0),
        float(Swatch),
        float(Swatch));
    }
  }
  painter->GetPen()->SetLineType(vtkPen::SOLID_LINE);
  return true;
}

bool vtkCloudColorPalette::Hit(const vtkContextMouseEvent& mouse)
{
  const std::array<double, 4> rect = this->GetRect();
  const vtkVector2f p = mouse.GetPos();
  return this->GetVisible() && p[0] >= rect[0] && p[0] <= rect[2] && p[1] >= rect[1] &&
    p[1] <= rect[3];
}

bool vtkCloudColorPalette::MouseButtonPressEvent(const vtkContextMouseEvent& mouse)
{
  if (mouse.GetButton() != vtkContextMouseEvent::LEFT_BUTTON)
  {
    return true; // on the palette, other buttons do nothing
  }
  const std::array<double, 4> rect = this->GetRect();
  const vtkVector2f p = mouse.GetPos();
  const int column = int(std::floor((p[0] - rect[0] - Frame) / Pitch));
  const int row = int(std::floor((rect[3] - Frame - p[1]) / Pitch));
  // The frame and the gaps between swatches pick nothing.
  const double inX = p[0] - rect[0] - Frame - column * Pitch;
  const double inY = rect[3] - Frame - p[1] - row * Pitch;
  if (column < 0 || column >= Columns || row < 0 || row >= Rows || inX > Swatch || inY > Swatch)
  {
    return true;
  }
  if (this->Picked)
  {
    this->Picked(SwatchColor(row, column));
  }
  return true;
}

bool vtkCloudColorPalette::MouseButtonReleaseEvent(const vtkContextMouseEvent&)
{
  return true;
}

} // namespace cloudvis
