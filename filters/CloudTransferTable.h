// The one transfer function every renderer sees. The GPU mapper uploads TransferTable::RGBA as a
// 1-D texture, the occupancy filter asks it which density ranges are transparent, and the CPU
// reference renderer calls Lookup: because all three read the same table, and Lookup reproduces
// the GPU's linearly filtered fetch, a difference between their images is a difference in the
// rendering equations, never in how color and opacity were interpreted. The table stores
// extinction (sigma_t per unit length) rather than VTK's opacity per unit distance, so a
// renderer composites with exp(-sigma_t * step) whatever its step length.
#ifndef CloudTransferTable_h
#define CloudTransferTable_h

#include "cloudvisFiltersModule.h"

#include <glm/vec4.hpp>

#include <string>
#include <vector>

class vtkPiecewiseFunction;
class vtkScalarsToColors;
class vtkVolumeProperty;

namespace cloudvis
{

// The number of entries of the table every renderer builds (the GPU mapper, the CPU reference and
// path tracer, the occupancy map they share): 1024 resolves a transfer function's ramps far
// below what an 8-bit image shows, in 16 KiB of texture.
constexpr int TransferTableSize = 1024;

// The rule for a range of densities with no width (a constant field, or a transfer function whose
// points all lie at one density v): it becomes [v, v + 1], so that lookups, colour maps and axes
// that divide by the width keep working. An increasing range is left alone.
CLOUDVISFILTERS_EXPORT void WidenEmptyRange(double range[2]);

// Color and extinction per density, sampled at Size evenly spaced densities over Range
// (first entry at Range[0], last at Range[1]).
struct CLOUDVISFILTERS_EXPORT TransferTable
{
  double Range[2] = { 0.0, 1.0 };
  int Size = 0;
  // Size * 4 floats: r, g, b (albedo color) and sigma_t (extinction per unit length) in a.
  std::vector<float> RGBA;

  // The GPU's linearly filtered fetch of a Size-texel 1-D texture (texel centres, clamp to
  // edge), reproduced on the CPU: t = (density - Range[0]) / (Range[1] - Range[0]) clamped to
  // [0, 1], x = t * (Size - 1), lerp between entries floor(x) and floor(x) + 1. A degenerate
  // range (Range[1] <= Range[0]) reads entry 0; NaN reads entry 0; an empty table reads 0.
  // The GPU's filter weights have only 8 fractional bits, so it may differ from this exact
  // lerp by up to 1/256 of the step between two neighbouring entries.
  glm::vec4 Lookup(double density) const;

  // The largest sigma_t among the entries that a linear lookup of any density in
  // [densityMin, densityMax] can touch: the bracketing entries floor(x(min)) .. ceil(x(max))
  // and all between, with x as in Lookup. So 0 means every density of the interval is fully
  // transparent. The arguments may come in either order.
  float MaxExtinction(double densityMin, double densityMax) const;
  // The smallest sigma_t among the same entries: no linear lookup of a density in the interval
  // is below it. 0 for an empty table.
  float MinExtinction(double densityMin, double densityMax) const;

  bool operator==(const TransferTable& other) const;
  bool operator!=(const TransferTable& other) const { return !(*this == other); }
};

// The extinction per unit length of an opacity per unitDistance, -ln(1 - a) / unitDistance, times
// extinctionScale, with a clamped to [0, 1 - 1e-4] so that an opacity of 1 still gives a finite
// extinction (about 9.2 / unitDistance). What every table entry holds.
CLOUDVISFILTERS_EXPORT double Extinction(double opacity,
  double unitDistance,
  double extinctionScale = 1.0);

// The largest finite float (FLT_MAX). A table entry's sigma_t is a float, and the GPU looks up
// densities in float: the limits below, and the renderers' (CloudMarchUniforms.h), derive from it.
constexpr double FloatMax = 3.4028234663852886e38;

// The smallest unit distance whose extinctions a float holds whatever the opacity:
// Extinction(1, MinUnitDistance()) is FloatMax (about 2.7e-38). The scene schema refuses smaller
// ones; the renderers also refuse an extinction whose optical depth across the volume overflows.
CLOUDVISFILTERS_EXPORT double MinUnitDistance();

// A transfer function's points must lie within [-MaxTransferDensity, MaxTransferDensity] and span
// at most MaxTransferDensity, so that a table over them has a width float arithmetic holds.
constexpr double MaxTransferDensity = FloatMax;

// The densities the pair defines: from the first to the last point of the opacity function and
// of the color function (its GetRange(), which for a vtkColorTransferFunction spans its points),
// together. A function whose points all lie at one density gives a range of no width, widened by
// WidenEmptyRange so the table has one (it is constant anyway: outside its points a function
// keeps its end values). False when the opacity function is missing or has no points.
CLOUDVISFILTERS_EXPORT bool TransferFunctionRange(vtkPiecewiseFunction* opacity,
  vtkScalarsToColors* color,
  double range[2]);

// The table the renderers use: BuildTransferTable over TransferFunctionRange, so the table
// resolves what the transfer function says wherever the data's values lie (an outlier voxel
// cannot starve it), and a density outside the function's points reads the end entries, as VTK
// clamps. An empty table when the range is unusable (see BuildTransferTable).
CLOUDVISFILTERS_EXPORT TransferTable TabulateTransferFunction(vtkScalarsToColors* color,
  vtkPiecewiseFunction* opacity,
  double unitDistance,
  int size = TransferTableSize,
  double extinctionScale = 1.0);

// Samples color and opacity into a table of `size` entries over `range`. The opacity a(d) is
// VTK's scalar opacity per unitDistance of travel, so sigma_t = -ln(1 - a) / unitDistance, with a
// clamped to [0, 1 - 1e-4] so that an opacity of 1 still gives a finite extinction; sigma_t is
// then multiplied by extinctionScale. The color comes from color->GetColor (a
// vtkColorTransferFunction or any vtkScalarsToColors); a null color means white, a null opacity
// means fully transparent. Returns an empty table (Size 0) when size < 1, unitDistance or
// extinctionScale is not finite and > 0 (resp. >= 0), or the range is not finite and
// non-decreasing: the occupancy filter refuses an empty table, so the mistake shows.
CLOUDVISFILTERS_EXPORT TransferTable BuildTransferTable(vtkScalarsToColors* color,
  vtkPiecewiseFunction* opacity,
  double unitDistance,
  const double range[2],
  int size = TransferTableSize,
  double extinctionScale = 1.0);

// Empty when the pair can drive a renderer, else the problem in words: no opacity function or
// one without points, point positions that are NaN or decrease, opacity values that are NaN or
// outside [0, 1], midpoint / sharpness outside [0, 1], or a color that is NaN or outside [0, 1].
// The color is checked through the vtkScalarsToColors interface, so any color map can be
// given: sampled at 257 densities across its range and at every opacity point. A null color is
// valid (white).
CLOUDVISFILTERS_EXPORT std::string ValidateTransferFunction(
  vtkPiecewiseFunction* opacity, vtkScalarsToColors* color);

// The table of a vtkVolumeProperty's first component, as every renderer builds it: its color and
// scalar opacity checked by ValidateTransferFunction, then TabulateTransferFunction with its
// scalar opacity unit distance, TransferTableSize entries and extinctionScale. On a problem
// (no property, an invalid function, a unit distance that is not a positive finite number)
// returns an empty table and sets `problem`, which starts with "transfer function: ".
CLOUDVISFILTERS_EXPORT TransferTable TransferTableOf(vtkVolumeProperty* property,
  double extinctionScale,
  std::string& problem);

} // namespace cloudvis

#endif
