// The transfer-function editor's color picker: a grid of swatches, a row of hues and a row of
// grays from black to white, drawn in the editor's vtkContextScene over the top left of the
// opacity chart (under its info line) while a color point is selected. A click on a swatch gives
// that swatch's color to the selected point (TransferFunctionEditor sets it, one undo step), as
// ParaView's color map editor offers a color chooser besides typed values. The palette takes the
// clicks that land on it, so the opacity chart under it does not add a point there.
#ifndef cloudvis_ColorPalette_h
#define cloudvis_ColorPalette_h

#include <vtkContextItem.h>

#include <array>
#include <functional>

namespace cloudvis
{

class vtkCloudColorPalette : public vtkContextItem
{
public:
  static vtkCloudColorPalette* New();
  vtkTypeMacro(vtkCloudColorPalette, vtkContextItem);

  static constexpr int Columns = 12;
  static constexpr int Rows = 2;
  static constexpr double Swatch = 11.0; // pixels a side, plus a 1-pixel gap
  // The palette's size in pixels, its frame included.
  static std::array<double, 2> Size();
  // Row 0 (the top): hues at full saturation from red round the circle; row 1: grays from black
  // to white.
  static std::array<double, 3> SwatchColor(int row, int column);

  // Where the palette is, in the scene's pixels: x, y of its bottom left corner.
  void SetCorner(double x, double y);
  // x0, y0, x1, y1 in the scene's pixels.
  std::array<double, 4> GetRect() const;

  // Called with the color of the swatch clicked.
  std::function<void(const std::array<double, 3>&)> Picked;

  bool Paint(vtkContext2D* painter) override;
  bool Hit(const vtkContextMouseEvent& mouse) override;
  bool MouseButtonPressEvent(const vtkContextMouseEvent& mouse) override;
  bool MouseButtonReleaseEvent(const vtkContextMouseEvent& mouse) override;

protected:
  vtkCloudColorPalette() = default;
  ~vtkCloudColorPalette() override = default;

private:
  vtkCloudColorPalette(const vtkCloudColorPalette&) = delete;
  void operator=(const vtkCloudColorPalette&) = delete;

  std::array<double, 2> Corner{ { 0.0, 0.0 } };
};

} // namespace cloudvis

#endif
