// What a cloud is lit with, as one value from the scene file to the renderers' uniforms: the
// lighting model and its parameters (LightingParameters, the model inside), the names of the
// models and of the march's ways of adding multiple scattering (one table each), the lights in
// the world (Light) and the limits the renderers put on them.
// A scene holds a LightingParameters and a list of Lights (app/scene Scene.h);
// vtkCloudLightingProperty holds one LightingParameters for VTK and Python; SetUpMarch
// (CloudMarchUniforms.h) turns both into the march's uniforms for the GPU mapper and the CPU
// renderers alike. The functions the models compute with are CloudLighting.h's.
//
// Public: the application's scene layer includes it. It includes glm and the standard library
// only, no transport code.
#ifndef CloudLightingParameters_h
#define CloudLightingParameters_h

#include "CloudDropletOptics.h" // the droplets' ranges

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace cloudvis
{

enum class LightingModel
{
  None,       // emission-absorption: a sample emits its transfer-function color
  Derivative, // directional derivative toward each light, one extra density sample per light
  March,      // nested march toward each light: Beer-Lambert shadowing and a phase function
  PathTrace,  // Monte Carlo volumetric path tracing: every order of scattering (CloudPathTrace.h)
};

// The look-ups of the name tables below (each entry a Name and the Model it stands for): the
// value a name stands for (nullopt for an unknown name), and the name of a value ("unknown" for
// a value outside the enumeration).
template<typename Entry, std::size_t N>
std::optional<decltype(Entry::Model)> FindInTable(const std::array<Entry, N>& table,
  const std::string& name)
{
  for (const Entry& entry : table)
  {
    if (name == entry.Name)
    {
      return entry.Model;
    }
  }
  return std::nullopt;
}
template<typename Entry, std::size_t N>
const char* NameInTable(const std::array<Entry, N>& table, decltype(Entry::Model) value)
{
  for (const Entry& entry : table)
  {
    if (entry.Model == value)
    {
      return entry.Name;
    }
  }
  return "unknown";
}

// The one table of the models' names: render.lighting and --lighting, the viewer's m key,
// `cloudvis compare`'s panels, vtkCloudLightingProperty::GetModelAsString and the reference
// table of docs/scene-format.md all read it. In the enumeration's order.
struct LightingModelEntry
{
  const char* Name;
  LightingModel Model;
  const char* Description; // for the docs and help
};
inline const std::array<LightingModelEntry, 4>& LightingModelTable()
{
  static const std::array<LightingModelEntry, 4> table{ {
    { "none",
      LightingModel::None,
      "emission-absorption: the cloud shows its color, attenuated; no light sources" },
    { "derivative", LightingModel::Derivative, "the directional derivative toward each light" },
    { "march",
      LightingModel::March,
      "a nested march toward each light: shadows, phase function, multiple scattering" },
    { "pathtrace",
      LightingModel::PathTrace,
      "Monte Carlo path tracing of the same medium, every order of scattering, `render.spp` "
      "paths per pixel: the ground truth" },
  } };
  return table;
}

// The names of LightingModelTable, in its order (for help and messages).
inline std::vector<std::string> LightingModelNames()
{
  std::vector<std::string> names;
  for (const LightingModelEntry& entry : LightingModelTable())
  {
    names.emplace_back(entry.Name);
  }
  return names;
}

// The model a name stands for, and the name of a model (FindInTable, NameInTable).
inline std::optional<LightingModel> FindLightingModel(const std::string& name)
{
  return FindInTable(LightingModelTable(), name);
}
inline const char* LightingModelName(LightingModel model)
{
  return NameInTable(LightingModelTable(), model);
}

// How the march adds the light that has scattered more than once (docs/lighting.md, "Phase and
// multiple scattering"): from the precomputed multiple-scattering volume, or from the octaves,
// an approximation that scales single scattering.
enum class MultipleScatteringModel
{
  Volume,  // one fetch per sample of a volume of the light scattered at least twice
  Octaves, // MultipleScatteringOctaves octaves added to single scattering (the earlier model)
};

// The one table of its names: render.march.multiple_scattering, `cloudvis compare`'s
// `march:NAME` panels, vtkCloudLightingProperty::GetMultipleScatteringAsString and the reference
// table of docs/scene-format.md all read it. In the enumeration's order.
struct MultipleScatteringModelEntry
{
  const char* Name;
  MultipleScatteringModel Model;
  const char* Description; // for the docs and help
};
inline const std::array<MultipleScatteringModelEntry, 2>& MultipleScatteringModelTable()
{
  static const std::array<MultipleScatteringModelEntry, 2> table{ {
    { "volume",
      MultipleScatteringModel::Volume,
      "a precomputed volume of the light scattered more than once, recomputed when the field, "
      "transfer function or lights change" },
    { "octaves",
      MultipleScatteringModel::Octaves,
      "`octaves` octaves added to single scattering, each a scaled copy of it" },
  } };
  return table;
}

// The model a name stands for, and the name of a model (FindInTable, NameInTable).
inline std::optional<MultipleScatteringModel> FindMultipleScatteringModel(const std::string& name)
{
  return FindInTable(MultipleScatteringModelTable(), name);
}
inline const char* MultipleScatteringModelName(MultipleScatteringModel model)
{
  return NameInTable(MultipleScatteringModelTable(), model);
}

// A light in the world, as a scene gives it to every renderer (a vtkLight, where VTK lights the
// volume, becomes one through LightsOf, CloudMarchUniforms.h). Positions are double, like VTK's:
// a light beside a volume far from the origin keeps its place, and a directional light may sit
// at any distance along its direction.
struct Light
{
  bool Positional = false; // false: directional, from Position toward FocalPoint
  glm::dvec3 Position{ 0.0, 10.0, 10.0 };
  glm::dvec3 FocalPoint{ 0.0 };
  glm::vec3 Color{ 1.0f };
  float Intensity = 1.0f;
  glm::vec3 Attenuation{ 0.0f, 0.0f, 1.0f }; // positional: 1 / (a0 + a1 r + a2 r^2), world r
};

inline bool operator==(const Light& a, const Light& b)
{
  return a.Positional == b.Positional && a.Position == b.Position && a.FocalPoint == b.FocalPoint &&
    a.Color == b.Color && a.Intensity == b.Intensity && a.Attenuation == b.Attenuation;
}
inline bool operator!=(const Light& a, const Light& b)
{
  return !(a == b);
}

// The unit direction toward a directional light, computed in double (so a sun placed at 1e300
// keeps its direction); the zero vector when its position equals its focal point.
inline glm::dvec3 DirectionTowardLight(const Light& light)
{
  const glm::dvec3 d = light.Position - light.FocalPoint;
  // Scaled first: the squared length of a vector beyond 1e154 overflows even in double.
  const double largest = std::max({ std::abs(d.x), std::abs(d.y), std::abs(d.z) });
  return largest > 0.0 && std::isfinite(largest) ? glm::normalize(d / largest) : glm::dvec3(0.0);
}

// A light as the march computes with it: in the march's local frame (CloudMarchUniforms.h),
// whose lengths are world lengths divided by the frame's unit. The uniforms of the GLSL's lights.
struct LocalLight
{
  bool Positional = false;
  glm::vec3 Position{ 0.0f };    // local coordinates; positional lights
  glm::vec3 Direction{ 0.0f };   // unit, toward the light; directional lights
  glm::vec3 Radiance{ 0.0f };    // color * intensity
  glm::vec3 Attenuation{ 0.0f }; // (a0, a1 unit, a2 unit^2): the falloff of a local distance
  // Directional lights, the same at every sample (SetUpMarch computes them once, in float, for
  // both renderers): Direction in index units per local unit, and the derivative model's offset
  // h Direction in index units.
  glm::vec3 IndexDirection{ 0.0f };
  glm::vec3 IndexOffset{ 0.0f };
};

// The phase function every lighting model that scatters uses (render.march.phase): the
// transport's PhaseTwoLobe and PhaseDroplets (shaders/transport/Phase.glsl).
enum class PhaseModel
{
  TwoLobe = 0,  // two Henyey-Greenstein lobes, PhaseG1, PhaseG2, PhaseLobeWeight
  Droplets = 1, // the Mie phase of water droplets (CloudDropletOptics.h), tabulated per channel
};
constexpr int PhaseTwoLobe = int(PhaseModel::TwoLobe);
constexpr int PhaseDroplets = int(PhaseModel::Droplets);

// The most scattering events a path of the path tracer may have by default (vtkCloudPathTracer's
// MaxBounces, the mapper's PathTraceMaxBounces; a collision beyond ends the path). At albedo 1 a
// path ends only by leaving the cloud, after about (optical depth)^2 events in a thick one, so a
// cap cuts light off: in a white furnace (docs/lighting.md, "The bounce cap") 1024 events lose
// 3% of the light at optical diameter 240 and 5-6% at 1200-4800, more than the 2% noise a
// reference is rendered to; 65536 lose at most 0.6%, for twice the time on those clouds and
// nothing on thin ones (their paths end long before).
constexpr int PathTraceBounceCap = 65536;

// How the march finds the optical depth toward a light at a sample (docs/lighting.md).
enum class LightTransmittance
{
  Volumes, // read from per-light optical-depth volumes computed when the inputs change
  Nested,  // a march toward each light at every sample (the quality setting)
};

struct LightingParameters
{
  LightingModel Model = LightingModel::None;
  glm::vec3 AmbientColor{ 1.0f };
  float AmbientStrength = 0.0f;

  // derivative: the finite-difference distance h toward the light, world units; 0 means 4
  // voxel spacings (the smallest spacing of the field).
  float DerivativeDistance = 0.0f;

  // march: LightSteps segments toward each light spanning the way to the volume's exit (or a
  // point light), each LightStepGrowth times longer than the one before (1: uniform steps), the
  // first at least LightStep long (0 means 2 voxel spacings).
  int LightSteps = 6;
  float LightStep = 0.0f;
  float LightStepGrowth = 1.6f;
  // Where the optical depth comes from: the volumes (fast; their march has uniform steps of the
  // view's step) or the nested march above at every sample.
  LightTransmittance Transmittance = LightTransmittance::Volumes;
  // The phase function. Henyey-Greenstein, two lobes: w * HG(g1) + (1 - w) * HG(g2); w = 1 is
  // one lobe. Droplets: a modified gamma distribution of effective radius r_e (micrometres) and
  // effective variance v_e, at the table's wavelengths (DefaultDropletWavelengthsUm).
  PhaseModel Phase = PhaseModel::TwoLobe;
  float PhaseG1 = 0.6f;
  float PhaseG2 = -0.3f;
  float PhaseLobeWeight = 0.8f;
  float DropletEffectiveRadius = 10.0f;
  float DropletEffectiveVariance = 0.1f;
  // Where the light scattered more than once comes from: the multiple-scattering volume (the
  // default: docs/lighting.md, "The multiple-scattering volume") or the octaves below.
  MultipleScatteringModel MultipleScattering = MultipleScatteringModel::Volume;
  // The octaves' approximate multiple scattering: octaves n = 1..N added to single scattering
  // (n = 0), each scaling scattering by a^n, extinction toward the light by b^n, eccentricity by
  // c^n. The values are fitted to the path tracer (`cloudvis-bench-pathtrace fit`,
  // docs/lighting.md "Fitting the march to the path tracer"); until that fit they were 3 and 0.5,
  // 0.5, 0.5.
  int MultipleScatteringOctaves = 3;
  float ScatteringFalloff = 0.41f;   // a
  float ExtinctionFalloff = 0.26f;   // b
  float EccentricityFalloff = 0.46f; // c
  // Non-physical "powder" darkening of thin regions (an artistic term): 0 disables.
  float PowderStrength = 0.0f;
};

// Every member equal (vtkCloudLightingProperty is Modified only when a value changes).
inline bool operator==(const LightingParameters& a, const LightingParameters& b)
{
  return a.Model == b.Model && a.AmbientColor == b.AmbientColor &&
    a.AmbientStrength == b.AmbientStrength && a.DerivativeDistance == b.DerivativeDistance &&
    a.LightSteps == b.LightSteps && a.LightStep == b.LightStep &&
    a.LightStepGrowth == b.LightStepGrowth && a.Transmittance == b.Transmittance &&
    a.Phase == b.Phase && a.PhaseG1 == b.PhaseG1 && a.PhaseG2 == b.PhaseG2 &&
    a.PhaseLobeWeight == b.PhaseLobeWeight &&
    a.DropletEffectiveRadius == b.DropletEffectiveRadius &&
    a.DropletEffectiveVariance == b.DropletEffectiveVariance &&
    a.MultipleScattering == b.MultipleScattering &&
    a.MultipleScatteringOctaves == b.MultipleScatteringOctaves &&
    a.ScatteringFalloff == b.ScatteringFalloff && a.ExtinctionFalloff == b.ExtinctionFalloff &&
    a.EccentricityFalloff == b.EccentricityFalloff && a.PowderStrength == b.PowderStrength;
}
inline bool operator!=(const LightingParameters& a, const LightingParameters& b)
{
  return !(a == b);
}

// Whether a march with these parameters reads the multiple-scattering volume (the march model,
// with its multiple scattering from the volume rather than the octaves; CloudScatteringVolume.h).
inline bool UsesScatteringVolume(const LightingParameters& p)
{
  return p.Model == LightingModel::March && p.MultipleScattering == MultipleScatteringModel::Volume;
}

// The limits ValidateLightingParameters puts on LightingParameters, and the number of lights
// the renderers take; the scene schema states the same ones from here.
struct LightingLimits
{
  // The GLSL's MAX_LIGHTS (the mapper substitutes it into shaders/transport/Medium.glsl). The
  // GPU mapper and the CPU renderers refuse more (SetUpMarch), and so does a scene's lights
  // section.
  static constexpr int MaxLights = 8;
  static constexpr int MinLightSteps = 1;
  static constexpr int MaxLightSteps = 64;
  static constexpr float MinLightStepGrowth = 1.0f;
  static constexpr float MaxLightStepGrowth = 4.0f;
  static constexpr int MaxMultipleScatteringOctaves = 8;
};

// Empty when the parameters are usable, else the problem, in words.
inline std::string ValidateLightingParameters(const LightingParameters& p)
{
  using L = LightingLimits;
  const auto finite3 = [](glm::vec3 v)
  { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite3(p.AmbientColor) || !std::isfinite(p.AmbientStrength) || p.AmbientStrength < 0.0f)
    return "ambient color and strength must be finite, strength >= 0";
  if (!std::isfinite(p.DerivativeDistance) || p.DerivativeDistance < 0.0f)
    return "the derivative distance must be >= 0 (0: automatic)";
  if (p.LightSteps < L::MinLightSteps || p.LightSteps > L::MaxLightSteps)
    return "light-march steps must be between " + std::to_string(L::MinLightSteps) + " and " +
      std::to_string(L::MaxLightSteps);
  if (!std::isfinite(p.LightStep) || p.LightStep < 0.0f)
    return "the light-march step must be >= 0 (0: automatic)";
  if (!std::isfinite(p.LightStepGrowth) || p.LightStepGrowth < L::MinLightStepGrowth ||
    p.LightStepGrowth > L::MaxLightStepGrowth)
    return "the light-march step growth must be between " +
      std::to_string(int(L::MinLightStepGrowth)) + " and " +
      std::to_string(int(L::MaxLightStepGrowth));
  if (!(std::abs(p.PhaseG1) < 1.0f) || !(std::abs(p.PhaseG2) < 1.0f))
    return "phase eccentricities g must be in (-1, 1)";
  if (!(p.PhaseLobeWeight >= 0.0f && p.PhaseLobeWeight <= 1.0f))
    return "the phase lobe weight must be in [0, 1]";
  if (p.Phase != PhaseModel::TwoLobe && p.Phase != PhaseModel::Droplets)
    return "the phase must be two_lobe or droplets, got the value " + std::to_string(int(p.Phase));
  if (!(p.DropletEffectiveRadius >= DropletEffectiveRadiusMinUm &&
        p.DropletEffectiveRadius <= DropletEffectiveRadiusMaxUm))
    return "the droplets' effective radius must be in [" +
      std::to_string(int(DropletEffectiveRadiusMinUm)) + ", " +
      std::to_string(int(DropletEffectiveRadiusMaxUm)) + "] micrometres, got " +
      std::to_string(p.DropletEffectiveRadius);
  if (!(p.DropletEffectiveVariance >= DropletEffectiveVarianceMin &&
        p.DropletEffectiveVariance <= DropletEffectiveVarianceMax))
    return "the droplets' effective variance must be in [0.01, 0.3], got " +
      std::to_string(p.DropletEffectiveVariance);
  if (std::string(MultipleScatteringModelName(p.MultipleScattering)) == "unknown")
  {
    std::string names;
    for (const MultipleScatteringModelEntry& entry : MultipleScatteringModelTable())
      names += std::string(names.empty() ? "" : " or ") + entry.Name;
    return "the multiple scattering must be " + names + ", got the value " +
      std::to_string(int(p.MultipleScattering));
  }
  if (p.MultipleScatteringOctaves < 0 ||
    p.MultipleScatteringOctaves > L::MaxMultipleScatteringOctaves)
    return "multiple-scattering octaves must be between 0 and " +
      std::to_string(L::MaxMultipleScatteringOctaves);
  for (float f : { p.ScatteringFalloff, p.ExtinctionFalloff, p.EccentricityFalloff })
    if (!(f >= 0.0f && f <= 1.0f))
      return "multiple-scattering falloffs must be in [0, 1]";
  if (!(p.PowderStrength >= 0.0f && p.PowderStrength <= 1.0f))
    return "the powder strength must be in [0, 1]";
  return {};
}

} // namespace cloudvis

#endif
