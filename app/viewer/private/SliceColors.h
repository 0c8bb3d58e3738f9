// How every slice shows density: one vtkLookupTable shared by the 3D slice planes, the oblique
// cut and the 2D slice views. Its colors come from a named colormap spread over the window/level
// (density level - window/2 to level + window/2; beyond it colors clamp), set by a right-button
// drag on any slice or the window/level keys; or from the transfer function's own colors (the
// albedo the cloud is drawn with) over the function's own range, so that a density has the same
// color on a slice as in the editor's color strip whatever the window (a window would clamp the
// densities below it to the color of its low end: with the cloud-dusk preset, empty space showed
// salmon instead of the strip's purple). A vtkScalarBarActor (GetColorBar) shows the table with
// its densities.
#ifndef cloudvis_SliceColors_h
#define cloudvis_SliceColors_h

#include <vtkNew.h>

#include <array>
#include <string>
#include <vector>

class vtkColorTransferFunction;
class vtkLookupTable;
class vtkScalarBarActor;

namespace cloudvis
{

class SliceColors
{
public:
  // `range`: the field's density range, the initial window. `transferColors`: the volume's
  // color function, for the "transfer function" colors (the caller calls Update() after it
  // changed).
  SliceColors(const std::array<double, 2>& range, vtkColorTransferFunction* transferColors);
  ~SliceColors();
  SliceColors(const SliceColors&) = delete;
  SliceColors& operator=(const SliceColors&) = delete;

  vtkLookupTable* GetTable() const;
  vtkScalarBarActor* GetColorBar() const;

  // The names the colors cycle through: "blue-yellow" (the default), "gray", "viridis",
  // "transfer function" (SliceColormapNames(), the names of the scene's view.slice_colors).
  static const std::vector<std::string>& ColormapNames();
  void NextColormap();
  const std::string& GetColormap() const;
  // By index of ColormapNames() (a saved scene's view.slice_colors).
  void SetColormap(size_t index);
  size_t GetColormapIndex() const { return this->Colormap; }

  // Window > 0 (clamped to a thousandth of the field's range at least).
  void SetWindowLevel(double window, double level);
  std::array<double, 2> GetWindowLevel() const { return { { this->Window, this->Level } }; }
  // Back to the window the slices opened with: the field's range.
  void ResetWindowLevel();
  // The colors follow the window/level (a named colormap, not the transfer function's colors).
  bool IsWindowed() const;

  // Window/level by dragging, as in ParaView and Slicer: from the window/level at Begin, moving
  // right widens the window and moving up raises the level, a full viewport width or height
  // changing them by the field's range. x, y in pixels.
  void BeginWindowLevelDrag(int x, int y);
  void DragWindowLevel(int x, int y, int viewportWidth, int viewportHeight);

  // Rebuilds the table (after the transfer function changed, in "transfer function" colors).
  void Update();

private:
  vtkColorTransferFunction* TransferColors;
  std::array<double, 2> Range;
  double Window;
  double Level;
  size_t Colormap = 0;
  std::array<int, 2> DragStart{ { 0, 0 } };
  std::array<double, 2> DragStartWindowLevel{ { 0.0, 0.0 } };
  vtkNew<vtkLookupTable> Table;
  vtkNew<vtkScalarBarActor> ColorBar;
};

// The look every color bar of the viewer shares (the slices' and the cloud's legend): three
// labels, a narrow bar, light 12-pixel text, the title clear of the top label.
void StyleColorBar(vtkScalarBarActor* bar, const std::string& title);
// The bar's texts at `scale` times their size (a screenshot larger than the window).
void SetColorBarFontScale(vtkScalarBarActor* bar, double scale);

} // namespace cloudvis

#endif
