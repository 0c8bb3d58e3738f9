// The statistics cloud scientists compute on a field, as `cloudvis info` reports them: a cloud
// mask (value > threshold), cloud fraction projected along the vertical axis and per height,
// cloud base and top, the vertical integral of the field (liquid water path for an lwc field),
// and the projected mask's clouds: their size distribution with a power-law fit, and the
// area-perimeter fractal dimension (Lovejoy, Science 216, 1982). Everything is computed on the
// plain float array in the lattice's index axes; `up` is a world axis, and the index axis the
// direction matrix turns onto it (reversed or not) is the vertical, with heights in world units.
// A lattice tilted against up has no vertical columns and gets no statistics, only the Problem.
// The mask analysis (CloudsOfMask, FitAreaPerimeter, FitPowerLaw) takes any 2-D mask so
// that tests can give it shapes with known answers.
#ifndef cloudvis_CloudStatistics_h
#define cloudvis_CloudStatistics_h

#include "FieldUnits.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

class vtkImageData;

namespace cloudvis
{

// ---- the projected mask's clouds --------------------------------------------------------------

// One connected cloud of a 2-D mask (4-connectivity: pixels sharing an edge).
struct Cloud
{
  std::uint64_t Area = 0;      // pixels
  std::uint64_t Perimeter = 0; // pixel edges between the cloud and a clear pixel (holes included)
  bool TouchesEdge = false;    // it reaches the mask's border, so it may continue beyond it
};

// The clouds of a width x height mask (row-major, x fastest). Edges on the mask's border are not
// counted in Perimeter: the cloud may go on beyond it. The border is not periodic.
std::vector<Cloud> CloudsOfMask(const std::vector<std::uint8_t>& mask, int width, int height);

// A power-law or log-log fit and what it was fitted on.
struct PowerLawFit
{
  bool Fitted = false;
  std::string Problem; // why there is no fit, when there is none
  double Value = 0.0;  // the exponent (FitPowerLaw) or the dimension D (FitAreaPerimeter)
  double StandardError = 0.0;
  double RangeMin = 0.0, RangeMax = 0.0; // sizes (areas) the fit covers
  std::uint64_t Count = 0;               // clouds in the fit
  // FitPowerLaw only: the Kolmogorov-Smirnov distance between the fitted law and the sizes it
  // covers, and whether it is below 1.36 / sqrt(Count), the 5% critical value of the KS test (an
  // approximation: the exponent was fitted to the same sizes, so the true test is stricter).
  double Distance = 0.0;
  bool Consistent = false;
};

// Clouds smaller than this (pixels) are left out of both fits: their pixel-edge perimeters and
// their sizes are dominated by the lattice (a 1-pixel cloud has P = 4, A = 1).
constexpr std::uint64_t MinimumFitArea = 10;
// The fewest clouds either fit accepts.
constexpr std::uint64_t MinimumFitClouds = 10;

// The area-perimeter dimension D: least squares of log P = (D / 2) log A + c over the clouds of
// at least MinimumFitArea pixels that do not touch the border (their perimeter is cut). Refused
// with fewer than MinimumFitClouds such clouds or an area range under a factor of 10.
PowerLawFit FitAreaPerimeter(const std::vector<Cloud>& clouds);

// The exponent b of a size density n(s) ~ s^-b (s = sqrt(area)), by maximum likelihood above a
// lower bound s_min chosen as Clauset, Shalizi and Newman (SIAM Review 51, 2009) do: the s_min,
// among the sizes given (ComputeCloudStatistics gives those of the clouds of at least
// MinimumFitArea pixels), whose fitted law is nearest the
// data (Kolmogorov-Smirnov distance), with at least MinimumFitClouds clouds above it. Sizes in
// whatever unit they are given; RangeMin/RangeMax are s_min and the largest size.
PowerLawFit FitPowerLaw(const std::vector<double>& sizes);

// ---- statistics of a 3-D field ----------------------------------------------------------------

struct CloudStatistics
{
  ResolvedFieldUnits Units;
  double Threshold = 0.0; // cloudy: value > Threshold
  // Why there are no statistics (the rest is empty): a lattice tilted against up, or voxels whose
  // heights or areas a double cannot hold.
  std::string Problem;
  int Connectivity = 4;
  // The horizontal lattice: columns along Units.Up.
  std::uint64_t Columns = 0, CloudyColumns = 0;
  double ProjectedCloudFraction = 0.0;
  // Per level along Up, from the lowest: its height (world units) and its fraction of cloudy
  // voxels.
  std::vector<double> LevelHeights;
  std::vector<double> CloudFractionPerLevel;
  bool HasCloud = false;
  double CloudBase = 0.0, CloudTop = 0.0; // world units: the lowest and highest cloudy level
  // The vertical integral of the values, sum of value x spacing along Up, in value x world units;
  // for an lwc field in m or km, the liquid water path in g/m^2. Mean over all columns and over
  // the cloudy ones.
  double MeanPath = 0.0, MeanCloudyPath = 0.0;
  // The projected mask's clouds, their sizes sqrt(area) in world units, and the size histogram
  // over log-spaced bins (four per decade).
  std::uint64_t Clouds = 0, CloudsTouchingEdge = 0;
  double PixelSize = 1.0; // world units per pixel side used for sizes (sqrt of the pixel area)
  std::vector<double> SizeBinEdges;
  std::vector<std::uint64_t> SizeCounts;
  PowerLawFit SizeDistribution;
  PowerLawFit FractalDimension;
};

// The statistics of the active scalars (component 0) of a field. `threshold`: the cloud mask's,
// or NaN for DefaultCloudThreshold(units.Quantity).
CloudStatistics ComputeCloudStatistics(vtkImageData* field,
  const ResolvedFieldUnits& units,
  double threshold);

// The text report (after PrintFieldStatistics) and the JSON object ("units" and "clouds", whose
// keys docs/command-line.md documents).
void PrintCloudStatistics(std::ostream& out, const CloudStatistics& statistics);
nlohmann::json UnitsToJson(const ResolvedFieldUnits& units);
nlohmann::json CloudStatisticsToJson(const CloudStatistics& statistics);
// The unit of the vertical integral (MeanPath): "g/m^2" for an lwc field in m or km, else the
// value's unit times a length ("density x m", "g/m^3 x world units").
std::string PathUnit(const ResolvedFieldUnits& units);

} // namespace cloudvis

#endif
