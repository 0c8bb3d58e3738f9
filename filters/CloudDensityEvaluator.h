// The density of a procedural cloud at a point in space and time, and the same for a whole row
// of voxels at once.
//
// Four density models (see docs/scene-format.md):
//   SdfPlusFbm  rho = scale * max(0, -sdf(p) + fbm(p + wind * t))          (the article's cloud)
//   FbmFalloff  rho = scale * max(0, fbm(p + wind * t)) * falloff(sdf(p))   (the three.js demo)
//   Constant    rho = scale inside the shape, 0 outside                     (analytic tests)
//   Cloud       a cloud layer: coverage, height profile, shape noise eroded by detail noise
//               (CloudLayer.h, where its equations are)
// where falloff(d) = smoothstep(0, -FalloffWidth, d). Density is exactly 0 outside the bound:
// for SdfPlusFbm where sdf >= the fBm bound, for FbmFalloff and Constant where sdf >= 0; the
// Cloud model is bounded by its layer, not by the shapes.
//
// EvaluateRow is the fast path used by vtkCloudDensitySource: it computes the shape once per
// voxel, skips noise where the density must be 0, and per octave shares the lattice work of a
// row (the hashing and y/z interpolation of each lattice column) between all its voxels. Its
// result is bit-identical to Density() at the same points.
#ifndef CloudDensityEvaluator_h
#define CloudDensityEvaluator_h

#include "CloudLayer.h"
#include "CloudNoise.h"
#include "CloudShapes.h"
#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace cloudvis
{

class CloudTowerPlan;

enum class DensityModel
{
  SdfPlusFbm,
  FbmFalloff,
  Constant,
  Cloud,
};

// Everything that defines a procedural field, apart from where it is sampled.
struct FieldDescription
{
  DensityModel Model = DensityModel::SdfPlusFbm;
  double DensityScale = 1.0;
  double FalloffWidth = 0.25;
  std::vector<Shape> Shapes = std::vector<Shape>(1); // one default shape: the unit sphere
  ShapeBlend Blend = ShapeBlend::Union;
  double BlendRadius = 0.25;
  bool Morph = false; // when true, Shapes is ignored and the morph timeline is used
  noise::FbmParameters Noise;
  glm::dvec3 Wind{ 0.5, -0.1, -0.5 }; // the article's drift, 0.5 * (1, -0.2, -1), per second
  CloudLayer Layer; // the Cloud model's layer; its noises take their seed from Noise.Seed
};

// Returns an empty string when the description can be evaluated, else what is wrong with it.
CLOUDVISFILTERS_EXPORT std::string ValidateFieldDescription(const FieldDescription& field);

// Empty when the noise lattice coordinates of every point of the bounds at this time fit the
// evaluator's 32-bit lattice cells, else the problem: frequency x distance must stay below 2^30.
// The frequencies are the fBm's octaves, or for the Cloud model its layer's noises
// (CloudLatticeDensity), which do not use the fBm.
CLOUDVISFILTERS_EXPORT std::string ValidateNoiseRange(
  const FieldDescription& field, const double bounds[6], double time);

// Empty when every density the description can give over the bounds is a finite float, else
// the problem, naming the keys: the largest density is density_scale times what the model's
// shapes and noise can reach (the deepest point inside a shape, what smooth unions add, the
// fBm's bound: the sum of its octaves' amplitudes), computed in double. Also refuses a smooth
// union's blend_radius wider than the bounds' diagonal, which merges every shape into one block
// filling the field (and, far beyond, loses the distances to float rounding).
CLOUDVISFILTERS_EXPORT std::string ValidateDensityRange(
  const FieldDescription& field, const double bounds[6]);

// Empty when the cloud model's layer fits the bounds, else the problem: a cumulonimbus's
// overshooting dome (top + overshoot) must not rise above the field's top (its y bound).
CLOUDVISFILTERS_EXPORT std::string ValidateCloudBounds(const FieldDescription& field,
  const double bounds[6]);

// Scratch memory of one thread for EvaluateRow; reused from row to row.
struct RowScratch
{
  std::vector<float> SignedDistance;
  std::vector<double> NoiseX;
  std::vector<float> Noise;
  std::vector<float> ColumnA;
  std::vector<float> ColumnB;
  std::vector<std::int32_t> Cell;
  std::vector<float> Fraction;
};

class CLOUDVISFILTERS_EXPORT DensityEvaluator
{
public:
  DensityEvaluator(const FieldDescription& field, double time);

  float SignedDistance(glm::vec3 p) const;
  float Fbm(glm::dvec3 p) const;
  float Density(glm::dvec3 p) const;

  // Densities of voxels i = firstIndex .. firstIndex + count - 1 at x = originX + i * spacingX
  // and the given y and z, written to out[0 .. count - 1].
  void EvaluateRow(int firstIndex, int count, double originX, double spacingX, double y, double z,
    float* out, RowScratch& scratch) const;

  // Signed distances beyond which the density is exactly 0 (infinity for the Cloud model, which
  // the shapes do not bound).
  double DensityBound() const { return this->Bound; }

private:
  float Combine(float signedDistance, float fbm) const;
  float CloudDensity(glm::dvec3 p) const;
  float CloudCoverage(glm::dvec3 leaned, float h) const;
  float DomeCoverage(glm::dvec3 leaned) const;
  bool InDomeLevels(double y) const; // within a cumulonimbus's overshooting dome's heights
  bool Rains() const;                // a cumulonimbus on the shapes with a rain shaft
  float RainDensity(glm::dvec3 p) const; // the rain shaft's, below the base
  bool CloudLevelMayHoldCloud(double y) const;
  bool NeedsNoise(float signedDistance) const;
  void AccumulateOctaveAlongRow(const noise::Octave& octave, int count, const double* noiseX,
    double y, double z, float* sum, RowScratch& scratch) const;

  FieldDescription Field;
  glm::dvec3 NoiseOffset; // wind * time
  std::vector<PlacedShape> Shapes;
  MorphTimeline::Phase MorphPhase{ 0, 1, 0.0f };
  std::vector<noise::Octave> Octaves;
  double Bound = 0.0;
  std::shared_ptr<const CloudNoiseVolumes> CloudNoise; // the Cloud model's baked noises
  // A cumulonimbus on the shapes: its tower's footprint and its anvil (CloudTowerPlan.h).
  std::shared_ptr<const CloudTowerPlan> TowerPlan;
};

} // namespace cloudvis

#endif
