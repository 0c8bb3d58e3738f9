#include "CloudDensityEvaluator.h"

#include "CloudTowerPlan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace cloudvis
{

namespace
{
bool Finite(glm::vec3 v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
}

std::string ValidateFieldDescription(const FieldDescription& f)
{
  std::ostringstream error;
  const auto finite = [](double v) { return std::isfinite(v); };
  const noise::FbmParameters& n = f.Noise;
  if (n.Octaves < 1 || n.Octaves > noise::MaxOctaves)
  {
    error << "octaves must be between 1 and " << noise::MaxOctaves << ", got " << n.Octaves;
  }
  else if (!finite(n.Frequency) || n.Frequency <= 0.0 || n.Frequency > noise::MaxFrequency)
  {
    error << "frequency must be a positive number up to " << noise::MaxFrequency << ", got "
          << n.Frequency;
  }
  else if (!finite(n.Lacunarity) || !finite(n.LacunarityIncrement) ||
    n.Lacunarity + (n.Octaves - 1) * n.LacunarityIncrement <= 0.0)
  {
    error << "lacunarity must stay positive over all octaves";
  }
  else if (!finite(n.Gain) || !finite(n.Amplitude))
  {
    error << "gain and amplitude must be finite numbers";
  }
  else if (!finite(f.DensityScale) || f.DensityScale < 0.0)
  {
    error << "density scale must be a finite number >= 0, got " << f.DensityScale;
  }
  else if (!finite(f.FalloffWidth) || f.FalloffWidth <= 0.0)
  {
    error << "falloff width must be a positive number, got " << f.FalloffWidth;
  }
  else if (!finite(f.BlendRadius) || f.BlendRadius < 0.0)
  {
    error << "blend radius must be a finite number >= 0, got " << f.BlendRadius;
  }
  else if (!finite(f.Wind.x) || !finite(f.Wind.y) || !finite(f.Wind.z))
  {
    error << "wind must be finite";
  }
  else if (!f.Morph && f.Shapes.empty())
  {
    error << "at least one shape is needed";
  }
  else if (n.Period < 0 || n.Period > noise::MaxPeriod)
  {
    error << "the noise period must be between 0 and " << noise::MaxPeriod << " lattice cells, got "
          << n.Period;
  }
  else if (n.Period > 0 &&
    (n.Lacunarity != std::round(n.Lacunarity) || n.LacunarityIncrement != 0.0 ||
      n.Period * std::pow(n.Lacunarity, n.Octaves - 1) > double(noise::MaxPeriod)))
  {
    error << "a noise that repeats (period " << n.Period << ") needs a whole-number lacunarity and "
          << "a lacunarity increment of 0, so that every octave repeats too, and its last octave's "
          << "period within " << noise::MaxPeriod << " cells";
  }
  else if (f.Model == DensityModel::Cloud)
  {
    error << ValidateCloudLayer(f.Layer);
  }
  if (!error.str().empty())
  {
    return error.str();
  }
  for (size_t i = 0; i < f.Shapes.size() && !f.Morph; ++i)
  {
    const Shape& s = f.Shapes[i];
    const bool ok = std::isfinite(s.Scale) && s.Scale > 0.0f &&
      Finite((s.Center)) && Finite((s.RotationDegrees)) &&
      std::isfinite(s.Radius) && s.Radius >= 0.0f && Finite((s.HalfSize)) &&
      glm::all(glm::greaterThanEqual(s.HalfSize, glm::vec3(0.0f))) &&
      std::isfinite(s.MajorRadius) && std::isfinite(s.MinorRadius) && s.MinorRadius >= 0.0f &&
      std::isfinite(s.ArmWidth) && s.ArmWidth >= 0.0f && std::isfinite(s.ArmLength) &&
      s.ArmLength >= 0.0f && Finite((s.EndA)) && Finite((s.EndB));
    if (!ok)
    {
      error << "shape " << i
            << " has a parameter that is not finite, a negative size, or a scale <= 0";
      return error.str();
    }
    if (s.Type == ShapeType::Capsule && s.EndA == s.EndB)
    {
      error << "shape " << i << " is a capsule whose two ends are the same point";
      return error.str();
    }
  }
  return {};
}

std::string ValidateNoiseRange(const FieldDescription& field, const double bounds[6], double time)
{
  // The cloud model samples the layer's own noises (CloudLayer.h), never the fBm.
  const bool cloud = field.Model == DensityModel::Cloud;
  const std::vector<noise::Octave> octaves =
    cloud ? std::vector<noise::Octave>() : noise::OctaveSchedule(field.Noise);
  if (!cloud && octaves.empty())
  {
    return {};
  }
  const glm::dvec3 offset = field.Wind * time;
  double farthest = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    farthest = std::max(farthest, std::abs(bounds[2 * a] + offset[a]));
    farthest = std::max(farthest, std::abs(bounds[2 * a + 1] + offset[a]));
  }
  double highest = 0.0;
  for (const noise::Octave& o : octaves)
  {
    highest = std::max(highest, o.Frequency);
  }
  if (cloud)
  {
    // Shear moves what lies above the base sideways, by up to |shear| x the layer's depth.
    const CloudLayer& l = field.Layer;
    farthest += std::max(std::abs(l.Shear[0]), std::abs(l.Shear[1])) *
      (std::abs(l.Top - l.Base) + l.Overshoot);
    highest = CloudLatticeDensity(l);
  }
  const double limit = 1073741824.0; // 2^30
  if (!(highest * farthest < limit))
  {
    std::ostringstream error;
    if (cloud)
    {
      error << "the cloud layer's finest noise lattice (" << highest
            << " cells per world unit, from its shape, detail and weather map scales)";
    }
    else
    {
      error << "the noise's highest octave frequency (" << highest << ")";
    }
    error << " times the farthest noise coordinate (" << farthest << ", bounds plus wind x time"
          << (cloud ? " and shear" : "") << ") must stay below 2^30";
    return error.str();
  }
  return {};
}

std::string ValidateCloudBounds(const FieldDescription& field, const double bounds[6])
{
  const CloudLayer& l = field.Layer;
  if (field.Model != DensityModel::Cloud || !(l.Overshoot > 0.0) ||
    l.Top + l.Overshoot <= bounds[3])
  {
    return {};
  }
  std::ostringstream error;
  error << "cloud overshoot " << l.Overshoot << " puts the dome's top at " << l.Top + l.Overshoot
        << ", above the field's top " << bounds[3]
        << " (field.bounds): lower it or raise the bounds";
  return error.str();
}

namespace
{
// How deep below its surface a point inside the shape can lie: its largest inscribed radius,
// bounded by its smallest half-size (the signed distance's magnitude inside), in world units.
double InnerDepth(const Shape& s)
{
  double depth = 0.0;
  switch (s.Type)
  {
    case ShapeType::Sphere:
    case ShapeType::Capsule:
      depth = s.Radius;
      break;
    case ShapeType::Box:
      depth = std::min({ s.HalfSize.x, s.HalfSize.y, s.HalfSize.z });
      break;
    case ShapeType::Torus:
      depth = s.MinorRadius;
      break;
    case ShapeType::Cross:
      depth = std::min(s.ArmWidth, s.ArmLength);
      break;
  }
  return depth * double(s.Scale);
}
}

std::string ValidateDensityRange(const FieldDescription& field, const double bounds[6])
{
  std::ostringstream error;
  error.precision(6);
  const double largestFloat = double(std::numeric_limits<float>::max());
  const std::vector<Shape> shapes = field.Morph ? MorphTimeline::Shapes() : field.Shapes;
  const bool smooth = field.Blend == ShapeBlend::SmoothUnion && shapes.size() > 1 && !field.Morph;
  if (field.Model == DensityModel::SdfPlusFbm && smooth)
  {
    double diagonal = 0.0;
    for (int a = 0; a < 3; ++a)
    {
      diagonal += (bounds[2 * a + 1] - bounds[2 * a]) * (bounds[2 * a + 1] - bounds[2 * a]);
    }
    diagonal = std::sqrt(diagonal);
    if (field.BlendRadius > diagonal)
    {
      error << "blend_radius " << field.BlendRadius << " is wider than the whole field (its "
            << "bounds' diagonal is " << diagonal << "): the smooth union would merge every "
            << "shape into one block filling the field; use a radius of at most " << diagonal;
      return error.str();
    }
  }
  // What the model multiplies by density_scale, at most.
  double reach = 1.0;
  std::string what = "the model's largest value, 1";
  const double fbm = noise::FbmBound(field.Noise);
  std::ostringstream fbmWords;
  fbmWords.precision(6);
  fbmWords << "the noise's largest value (amplitude " << field.Noise.Amplitude << " x the gain "
           << field.Noise.Gain << " over " << field.Noise.Octaves << " octaves: " << fbm << ")";
  if (field.Model == DensityModel::FbmFalloff)
  {
    reach = fbm;
    what = fbmWords.str();
  }
  else if (field.Model == DensityModel::SdfPlusFbm)
  {
    double depth = 0.0;
    for (const Shape& s : shapes)
    {
      depth = std::max(depth, InnerDepth(s));
    }
    // A smooth union lowers the distance by up to a quarter of the radius at each of its joins.
    const double blend = smooth ? 0.25 * field.BlendRadius * double(shapes.size() - 1) : 0.0;
    reach = depth + blend + fbm;
    std::ostringstream words;
    words.precision(6);
    words << "the deepest point inside a shape (" << depth << ")";
    if (blend > 0.0)
    {
      words << " plus the smooth union's blend_radius share (" << blend << ")";
    }
    words << " plus " << fbmWords.str();
    what = words.str();
  }
  if (!(reach * field.DensityScale <= largestFloat))
  {
    error << "the density can reach density_scale " << field.DensityScale << " x " << what
          << " = " << reach * field.DensityScale << ", beyond the largest float ("
          << largestFloat << "): lower density_scale";
    if (field.Model != DensityModel::Constant && field.Model != DensityModel::Cloud)
    {
      error << ", amplitude or gain";
    }
    return error.str();
  }
  return {};
}

DensityEvaluator::DensityEvaluator(const FieldDescription& field, double time)
  : Field(field)
  , NoiseOffset(field.Wind * time)
  , Octaves(noise::OctaveSchedule(field.Noise))
{
  const std::vector<Shape> shapes = field.Morph ? MorphTimeline::Shapes() : field.Shapes;
  for (const Shape& s : shapes)
  {
    this->Shapes.emplace_back(s);
  }
  if (field.Morph)
  {
    this->MorphPhase = MorphTimeline::At(time);
  }
  if (field.Model == DensityModel::Cloud)
  {
    this->CloudNoise = BakeCloudNoise(field.Noise.Seed);
    const CloudLayer& l = field.Layer;
    if (l.Type == CloudType::Cumulonimbus && l.Source == CoverageSource::Shapes &&
      !this->Shapes.empty())
    {
      glm::dvec3 low(std::numeric_limits<double>::max()), high(-low);
      for (const Shape& s : shapes)
      {
        glm::dvec3 a, b;
        ShapeBounds(s, a, b);
        low = glm::min(low, a);
        high = glm::max(high, b);
      }
      this->TowerPlan = std::make_shared<const CloudTowerPlan>(
        [this](glm::vec3 p) { return this->SignedDistance(p); }, low, high, l);
    }
  }
  switch (field.Model)
  {
    case DensityModel::SdfPlusFbm:
      this->Bound = noise::FbmBound(field.Noise);
      break;
    case DensityModel::FbmFalloff:
    case DensityModel::Constant:
      this->Bound = 0.0;
      break;
    case DensityModel::Cloud:
      // A weather map's clouds lie anywhere in the layer whatever the shapes, and an anvil
      // spreads beyond them: no signed distance bounds the cloud.
      this->Bound = std::numeric_limits<double>::infinity();
      break;
  }
}

float DensityEvaluator::SignedDistance(glm::vec3 p) const
{
  if (this->Field.Morph)
  {
    const float from = this->Shapes[this->MorphPhase.From].SignedDistance(p);
    const float to = this->Shapes[this->MorphPhase.To].SignedDistance(p);
    return from + (to - from) * this->MorphPhase.Blend;
  }
  float d = this->Shapes.front().SignedDistance(p);
  const float radius = static_cast<float>(this->Field.BlendRadius);
  for (size_t i = 1; i < this->Shapes.size(); ++i)
  {
    const float di = this->Shapes[i].SignedDistance(p);
    d = this->Field.Blend == ShapeBlend::SmoothUnion ? sdf::SmoothMin(d, di, radius)
                                                     : std::min(d, di);
  }
  return d;
}

float DensityEvaluator::Fbm(glm::dvec3 p) const
{
  const glm::dvec3 q = p + this->NoiseOffset;
  float sum = 0.0f;
  for (const noise::Octave& o : this->Octaves)
  {
    sum += o.Amplitude *
      noise::Evaluate(this->Field.Noise.Type,
        q.x * o.Frequency,
        q.y * o.Frequency,
        q.z * o.Frequency,
        o.Seed,
        o.Period);
  }
  return sum;
}

bool DensityEvaluator::NeedsNoise(float signedDistance) const
{
  switch (this->Field.Model)
  {
    case DensityModel::SdfPlusFbm:
      // -sdf + fbm <= -sdf + bound <= 0: the density is 0 whatever the noise.
      return signedDistance < this->Bound && !this->Octaves.empty();
    case DensityModel::FbmFalloff:
      return signedDistance < 0.0f && !this->Octaves.empty();
    case DensityModel::Constant:
    case DensityModel::Cloud:
      break;
  }
  return false;
}

float DensityEvaluator::Combine(float signedDistance, float fbm) const
{
  const float scale = static_cast<float>(this->Field.DensityScale);
  switch (this->Field.Model)
  {
    case DensityModel::SdfPlusFbm:
      return scale * std::max(0.0f, -signedDistance + fbm);
    case DensityModel::FbmFalloff:
    {
      const float width = static_cast<float>(this->Field.FalloffWidth);
      const float t = glm::clamp(-signedDistance / width, 0.0f, 1.0f);
      return scale * std::max(0.0f, fbm) * (t * t * (3.0f - 2.0f * t));
    }
    case DensityModel::Constant:
      return signedDistance <= 0.0f ? scale : 0.0f;
    case DensityModel::Cloud:
      break;
  }
  return 0.0f;
}

namespace
{
using noise::Saturate;
// A cumulonimbus's anvil is this fraction of the layer's depth thick at the tower, its underside
// rises by the second fraction over the third out from the tower, and its overshooting dome is
// this fraction of the tower's radius wide.
constexpr float AnvilThickness = 0.3f;
constexpr float AnvilFlareRise = 0.08f;
constexpr float AnvilFlareLength = 0.25f;
constexpr double DomeWidth = 0.8;
constexpr float TowerInset = 0.5f;
// The break-up of a weather map's columns reaches its full strength this far up the layer, and
// its noise is the shape noise at this fraction of its scale.
constexpr float BreakupHeight = 0.2f;
constexpr double BreakupScale = 0.25;
// The rain shaft falls from the tower's footprint set in by this fraction of its radius, and its
// streaks are this many times longer up and down than across.
constexpr double RainInset = 0.3;
constexpr double RainStretch = 3.0;
// Altocumulus cloudlets per shape_scale.
constexpr double AltocumulusCells = 4.0;
}

float DensityEvaluator::CloudCoverage(glm::dvec3 leaned, float h) const
{
  const CloudLayer& l = this->Field.Layer;
  if (this->TowerPlan)
  {
    // A cumulonimbus on the shapes: the tower's footprint at every height, and the anvil, a
    // layer under the top that thins downwind, from AnvilThickness of the depth at the tower to
    // half that at its far end, its underside flaring up by AnvilFlareRise of the depth over the
    // first AnvilFlareLength out from the tower.
    const float width = static_cast<float>(this->Field.FalloffWidth);
    const CloudTowerPlan& plan = *this->TowerPlan;
    // The tower's sides bulge in and out with height: its footprint moves by up to 1.25 falloff
    // widths, by the shape noise at twice its scale.
    const glm::dvec3 q = (leaned + this->NoiseOffset) / (2.0 * l.ShapeScale);
    const float bulge = 1.25f * width * (2.0f * this->CloudNoise->Shape.Sample(q) - 1.0f);
    // The shapes' own masses bulge out of a footprint set in by TowerInset falloff widths.
    const float footprint = plan.TowerDistance(leaned.x, leaned.z);
    const float tower =
      std::min(footprint + TowerInset * width, this->SignedDistance(glm::vec3(leaned)));
    float c = Saturate(-(tower - bulge) / width);
    if (l.Anvil > 0.0)
    {
      const float along = plan.AnvilFraction(leaned.x, leaned.z);
      const float outward = footprint / (AnvilFlareLength * static_cast<float>(l.Top - l.Base));
      const float bottom = 1.0f - AnvilThickness * (1.0f - 0.5f * along) +
        AnvilFlareRise * glm::smoothstep(0.0f, 1.0f, outward);
      // (Its far end fades out rather than breaking into flecks.)
      c = std::max(c,
        Saturate(-plan.AnvilDistance(leaned.x, leaned.z) / width) *
          glm::smoothstep(bottom, bottom + 0.1f, h) * (1.0f - glm::smoothstep(0.9f, 1.0f, along)));
    }
    return static_cast<float>(l.Coverage) * c;
  }
  // Elsewhere (a weather map's cumulonimbus, or no plan) the anvil spreads the cloud sideways from
  // 60% of the layer up.
  const float anvil = l.Type == CloudType::Cumulonimbus
    ? static_cast<float>(l.Anvil) * glm::smoothstep(0.6f, 0.95f, h)
    : 0.0f;
  if (l.Source == CoverageSource::Shapes)
  {
    // Shapes spread by moving their surface out, by up to a third of the layer's depth.
    const float spread = anvil * static_cast<float>(l.Top - l.Base) / 3.0f;
    const float width = static_cast<float>(this->Field.FalloffWidth);
    const float d = this->SignedDistance(glm::vec3(leaned)) - spread;
    return static_cast<float>(l.Coverage) * Saturate(-d / width);
  }
  if (l.Coverage <= 0.0)
  {
    return 0.0f; // (the threshold below would divide 0 by 0 where the map is 1)
  }
  // The weather map drifts with the wind, like the noises.
  const glm::dvec3 q = leaned + this->NoiseOffset;
  // (A procedural map's fine octaves turn with height, below the base's value: WeatherNoise.)
  const float map = l.Source == CoverageSource::Noise
    ? WeatherNoise(l, this->Field.Noise.Seed, q.x, q.z, h * (l.Top - l.Base))
    : l.Map->Sample(q.x, q.z);
  // Break-up: above the base a 3-D noise moves the map's value, by more the higher up (up to
  // `breakup` from BreakupHeight of the layer on), so that the clouds' sides are not the map's
  // outlines drawn straight up; at the base the map holds, and the bases stay flat.
  float lifted = map;
  if (l.Breakup > 0.0)
  {
    const glm::dvec3 u = q / (BreakupScale * l.ShapeScale) + glm::dvec3(0.37, 0.11, 0.73);
    const float lift = this->CloudNoise->Shape.Sample(u);
    lifted -= static_cast<float>(l.Breakup) * Saturate(h / BreakupHeight) * lift;
  }
  const float coverage =
    Saturate(noise::Remap(lifted, 1.0f - static_cast<float>(l.Coverage), 1.0f, 0.0f, 1.0f));
  // A map spreads by lifting every coverage towards 1 (a power below 1).
  return anvil > 0.0f && coverage > 0.0f ? std::pow(coverage, 1.0f - 0.8f * anvil) : coverage;
}

float DensityEvaluator::DomeCoverage(glm::dvec3 leaned) const
{
  // The overshooting dome: an ellipsoid centred on the tower's axis at the top (its lower half
  // lies in the tower), its half-width DomeWidth of the tower's radius and its half-height the
  // overshoot, softened over the falloff width like the shapes.
  const CloudLayer& l = this->Field.Layer;
  const glm::dvec2 axis = this->TowerPlan->Axis();
  const double across = DomeWidth * this->TowerPlan->Radius();
  const glm::dvec3 u(
    (leaned.x - axis.x) / across, (leaned.y - l.Top) / l.Overshoot, (leaned.z - axis.y) / across);
  const double distance = (glm::length(u) - 1.0) * std::min(across, l.Overshoot);
  return static_cast<float>(l.Coverage) *
    Saturate(static_cast<float>(-distance / this->Field.FalloffWidth));
}

bool DensityEvaluator::InDomeLevels(double y) const
{
  const CloudLayer& l = this->Field.Layer;
  return this->TowerPlan && l.Overshoot > 0.0 && y > l.Top - l.Overshoot && y < l.Top + l.Overshoot;
}

bool DensityEvaluator::Rains() const
{
  return this->TowerPlan && this->Field.Layer.Rain > 0.0;
}

float DensityEvaluator::RainDensity(glm::dvec3 p) const
{
  // The shaft falls straight down (the shear leans the cloud above its base, not the rain) from
  // the tower's footprint set in by RainInset of its radius, its edge frayed over a falloff width
  // by the shape noise. Inside it the rain falls in streaks: the detail noise stretched
  // RainStretch times up and down (and shrunk as much across), of which the highest part rains.
  const CloudLayer& l = this->Field.Layer;
  const CloudNoiseVolumes& volumes = *this->CloudNoise;
  const glm::dvec3 n = p + this->NoiseOffset;
  const float width = static_cast<float>(this->Field.FalloffWidth);
  const float inset = this->TowerPlan->TowerDistance(p.x, p.z) +
    static_cast<float>(RainInset * this->TowerPlan->Radius());
  if (inset - 0.5f * width >= 0.0f)
  {
    return 0.0f; // beyond the fray's reach (the shape noise lies in [0, 1])
  }
  const float fray = 0.5f * width * (2.0f * volumes.Shape.Sample(n / l.ShapeScale) - 1.0f);
  const float edge = inset + fray;
  const float curtain = Saturate(-edge / width);
  if (curtain <= 0.0f)
  {
    return 0.0f;
  }
  const glm::dvec3 streak =
    n * glm::dvec3(RainStretch, 1.0 / RainStretch, RainStretch) / l.DetailScale;
  const float streaks =
    Saturate(noise::Remap(volumes.Detail.Sample(streak), 0.35f, 0.75f, 0.0f, 1.0f));
  return static_cast<float>(this->Field.DensityScale * l.Rain) * curtain * streaks;
}

bool DensityEvaluator::CloudLevelMayHoldCloud(double y) const
{
  // As CloudDensity decides it.
  const CloudLayer& l = this->Field.Layer;
  return HeightProfile(l.Type, static_cast<float>((y - l.Base) / (l.Top - l.Base))) > 0.0f ||
    this->InDomeLevels(y) || (y < l.Base && this->Rains());
}

float DensityEvaluator::CloudDensity(glm::dvec3 p) const
{
  const CloudLayer& l = this->Field.Layer;
  const double height = p.y - l.Base;
  if (height < 0.0 && this->Rains())
  {
    return this->RainDensity(p);
  }
  const float h = static_cast<float>(height / (l.Top - l.Base));
  const float profile = HeightProfile(l.Type, h);
  const bool dome = this->InDomeLevels(p.y);
  if (profile <= 0.0f && !dome)
  {
    return 0.0f;
  }
  // Shear leans the cloud: what is at height `height` above the base comes from straight below.
  const glm::dvec3 leaned = p - glm::dvec3(l.Shear[0] * height, 0.0, l.Shear[1] * height);
  float coverage = profile > 0.0f ? this->CloudCoverage(leaned, h) : 0.0f;
  if (l.Type == CloudType::Altocumulus && coverage > 0.0f)
  {
    // Altocumulus: cloudlets on a cellular lattice of AltocumulusCells per shape tile, dense at
    // their feature points and clear along the cells' borders (Worley's F1, read on a slice
    // that turns slowly with height).
    const glm::dvec3 c =
      (leaned + this->NoiseOffset) * (AltocumulusCells / l.ShapeScale) * glm::dvec3(1.0, 0.5, 1.0);
    const float f1 = noise::WorleyF1(c.x, c.y, c.z, this->Field.Noise.Seed + 0x2545F491u);
    coverage *= Saturate(noise::Remap(f1, 0.75f, 0.3f, 0.0f, 1.0f));
  }
  const float domeCoverage = dome ? this->DomeCoverage(leaned) : 0.0f;
  if (coverage <= 0.0f && domeCoverage <= 0.0f)
  {
    return 0.0f;
  }
  const glm::dvec3 q = leaned + this->NoiseOffset;
  const CloudNoiseVolumes& volumes = *this->CloudNoise;
  const float shape = volumes.Shape.Sample(q / l.ShapeScale);
  float base = coverage > 0.0f
    ? Saturate(noise::Remap(shape * profile, 1.0f - coverage, 1.0f, 0.0f, 1.0f)) * coverage
    : 0.0f;
  if (domeCoverage > 0.0f)
  {
    // The dome has the tower's full profile.
    base = std::max(
      base, Saturate(noise::Remap(shape, 1.0f - domeCoverage, 1.0f, 0.0f, 1.0f)) * domeCoverage);
  }
  if (base <= 0.0f)
  {
    return 0.0f;
  }
  glm::dvec3 u = q / l.DetailScale;
  if (l.Curl > 0.0)
  {
    // Turbulence under the cloud, fading with height: the detail is read at displaced points.
    const glm::dvec3 curl(
      volumes.Curl[0].Sample(u), volumes.Curl[1].Sample(u), volumes.Curl[2].Sample(u));
    u += curl * (0.25 * l.Curl * std::max(1.0 - double(h), 0.0));
  }
  const float detail = volumes.Detail.Sample(u);
  const float modifier = detail + (1.0f - 2.0f * detail) * Saturate(10.0f * h);
  const float eroded =
    Saturate(noise::Remap(base, static_cast<float>(l.Erosion) * modifier, 1.0f, 0.0f, 1.0f));
  return static_cast<float>(this->Field.DensityScale) * eroded;
}

float DensityEvaluator::Density(glm::dvec3 p) const
{
  if (this->Field.Model == DensityModel::Cloud)
  {
    return this->CloudDensity(p);
  }
  const float d = this->SignedDistance(glm::vec3(p));
  return this->Combine(d, this->NeedsNoise(d) ? this->Fbm(p) : 0.0f);
}

void DensityEvaluator::EvaluateRow(int firstIndex, int count, double originX, double spacingX,
  double y, double z, float* out, RowScratch& scratch) const
{
  if (this->Field.Model == DensityModel::Cloud)
  {
    // A row has one height: outside the cloud type's profile (and the dome) it is empty.
    const bool inLayer = this->CloudLevelMayHoldCloud(y);
    for (int j = 0; j < count; ++j)
    {
      const double x = originX + static_cast<double>(firstIndex + j) * spacingX;
      out[j] = inLayer ? this->CloudDensity(glm::dvec3(x, y, z)) : 0.0f;
    }
    return;
  }
  scratch.SignedDistance.resize(count);
  int firstNoisy = count, lastNoisy = -1;
  for (int j = 0; j < count; ++j)
  {
    const double x = originX + static_cast<double>(firstIndex + j) * spacingX;
    const float d = this->SignedDistance(glm::vec3(glm::dvec3(x, y, z)));
    scratch.SignedDistance[j] = d;
    if (this->NeedsNoise(d))
    {
      firstNoisy = std::min(firstNoisy, j);
      lastNoisy = j;
    }
  }

  scratch.Noise.assign(count, 0.0f);
  if (lastNoisy >= firstNoisy)
  {
    const int noisyCount = lastNoisy - firstNoisy + 1;
    // x of each voxel in noise space (with the wind), computed as Fbm() does for a point.
    scratch.NoiseX.resize(noisyCount);
    for (int j = 0; j < noisyCount; ++j)
    {
      const double x = originX + static_cast<double>(firstIndex + firstNoisy + j) * spacingX;
      scratch.NoiseX[j] = x + this->NoiseOffset.x;
    }
    for (const noise::Octave& octave : this->Octaves)
    {
      this->AccumulateOctaveAlongRow(octave, noisyCount, scratch.NoiseX.data(), y, z,
        scratch.Noise.data() + firstNoisy, scratch);
    }
  }

  for (int j = 0; j < count; ++j)
  {
    const float d = scratch.SignedDistance[j];
    out[j] = this->Combine(d, this->NeedsNoise(d) ? scratch.Noise[j] : 0.0f);
  }
}

namespace
{
// The lattice cell (relative to baseCell) and fraction of every voxel of a row at frequency f,
// in a loop of its own so that the compiler can vectorise it.
void SplitRow(const double* noiseX, double f, int count, std::int32_t baseCell, RowScratch& scratch)
{
  scratch.Cell.resize(count);
  scratch.Fraction.resize(count);
  std::int32_t* cell = scratch.Cell.data();
  float* fraction = scratch.Fraction.data();
  for (int j = 0; j < count; ++j)
  {
    const noise::LatticeCoordinate lx = noise::Split(noiseX[j] * f);
    cell[j] = lx.Cell - baseCell;
    fraction[j] = lx.Fraction;
  }
}
}

void DensityEvaluator::AccumulateOctaveAlongRow(const noise::Octave& octave, int count,
  const double* noiseX, double y, double z, float* sum, RowScratch& scratch) const
{
  using namespace noise;
  const double f = octave.Frequency;
  const double noiseY = (y + this->NoiseOffset.y) * f, noiseZ = (z + this->NoiseOffset.z) * f;
  const NoiseType type = this->Field.Noise.Type;

  if (IsCellular(type) || octave.Period > 0)
  {
    // No shared row work for these: each voxel is a point evaluation, as in Fbm().
    for (int j = 0; j < count; ++j)
    {
      sum[j] += octave.Amplitude *
        Evaluate(type, noiseX[j] * f, noiseY, noiseZ, octave.Seed, octave.Period);
    }
    return;
  }
  if (type == NoiseType::White)
  {
    const std::uint32_t yz = HashYZ(Split(noiseY).Cell, Split(noiseZ).Cell, octave.Seed);
    for (int j = 0; j < count; ++j)
    {
      sum[j] += octave.Amplitude * HashToSigned(HashX(yz, Split(noiseX[j] * f).Cell));
    }
    return;
  }

  // The lattice columns the row crosses: x is monotonic along the row, so they are the cells
  // from the first voxel's to the last voxel's, plus one for the upper corner.
  const std::int32_t firstCell = Split(noiseX[0] * f).Cell;
  const std::int32_t lastCell = Split(noiseX[count - 1] * f).Cell;
  const std::int32_t baseCell = std::min(firstCell, lastCell);
  const int columns = static_cast<int>(std::max(firstCell, lastCell) - baseCell) + 2;
  scratch.ColumnA.resize(columns);
  scratch.ColumnB.resize(columns);
  float* a = scratch.ColumnA.data();
  float* b = scratch.ColumnB.data();

  if (type == NoiseType::Value)
  {
    const RowCorners r = CornersOfRow(noiseY, noiseZ, octave.Seed, FadeCubic);
    for (int c = 0; c < columns; ++c)
    {
      a[c] = ValueColumn(baseCell + c, r);
    }
    SplitRow(noiseX, f, count, baseCell, scratch);
    const std::int32_t* cell = scratch.Cell.data();
    const float* fx = scratch.Fraction.data();
    for (int j = 0; j < count; ++j)
    {
      const int c = cell[j];
      sum[j] += octave.Amplitude * ValueAlongX(a[c], a[c + 1], fx[j]);
    }
  }
  else if (type == NoiseType::Perlin)
  {
    const RowCorners r = CornersOfRow(noiseY, noiseZ, octave.Seed, FadeQuintic);
    for (int c = 0; c < columns; ++c)
    {
      const PerlinColumnTerms t = PerlinColumn(baseCell + c, r);
      a[c] = t.Offset;
      b[c] = t.Slope;
    }
    SplitRow(noiseX, f, count, baseCell, scratch);
    const std::int32_t* cell = scratch.Cell.data();
    const float* fx = scratch.Fraction.data();
    for (int j = 0; j < count; ++j)
    {
      const int c = cell[j];
      sum[j] += octave.Amplitude * PerlinAlongX({ a[c], b[c] }, { a[c + 1], b[c + 1] }, fx[j]);
    }
  }
}

} // namespace cloudvis
