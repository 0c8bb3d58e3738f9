#include "CloudMarchUniforms.h"

#include "CloudLighting.h" // PeakRadiancePerLightRadiance

#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <sstream>
#include <utility>

namespace cloudvis
{
namespace
{
bool FitsFloat(double v)
{
  return std::isfinite(v) && std::abs(v) <= FLT_MAX;
}

std::string Number(double v)
{
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

std::string Triple(const double v[3])
{
  return "(" + Number(v[0]) + ", " + Number(v[1]) + ", " + Number(v[2]) + ")";
}

std::string Triple(const glm::dvec3& v)
{
  const double a[3] = { v.x, v.y, v.z };
  return Triple(a);
}

// |det A| against the product of its column lengths (Hadamard's bound): 1 for orthogonal
// columns, 0 for dependent ones, whatever the scale.
double Conditioning(const glm::dmat3& a)
{
  const double lengths = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
  return lengths > 0.0 ? std::abs(glm::determinant(a)) / lengths : 0.0;
}
constexpr double SingularConditioning = 1e-9;

bool Finite(const glm::dvec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool Finite(const glm::dmat4& m)
{
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r]))
        return false;
  return true;
}

bool FitsFloat(const glm::dmat4& m)
{
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!FitsFloat(m[c][r]))
        return false;
  return true;
}

// vtkMatrix4x4 (row-major elements) as GLM (column-major).
glm::dmat4 ToGlm(vtkMatrix4x4* m)
{
  glm::dmat4 g(1.0);
  if (m)
  {
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        g[c][r] = m->GetElement(r, c);
  }
  return g;
}

MarchProblem Problem(MarchInput input, const std::string& message, int light = -1)
{
  MarchProblem problem;
  problem.Input = input;
  problem.Light = light;
  problem.Message = message;
  return problem;
}
}

VolumeGeometry GeometryOf(vtkImageData* image, vtkMatrix4x4* volumeMatrix)
{
  VolumeGeometry geometry;
  int extent[6];
  image->GetExtent(extent);
  const double* origin = image->GetOrigin();
  const double* spacing = image->GetSpacing();
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  glm::dmat4 indexToPhysical(1.0);
  glm::dvec3 translation(origin[0], origin[1], origin[2]);
  for (int a = 0; a < 3; ++a)
  {
    geometry.Dimensions[a] = extent[2 * a + 1] - extent[2 * a] + 1;
    for (int r = 0; r < 3; ++r)
    {
      indexToPhysical[a][r] = direction->GetElement(r, a) * spacing[a];
      // The extent's first voxel, not index 0 of the lattice, is the march's p = 0.
      translation[r] += direction->GetElement(r, a) * spacing[a] * extent[2 * a];
    }
  }
  indexToPhysical[3] = glm::dvec4(translation, 1.0);
  geometry.IndexToWorld = ToGlm(volumeMatrix) * indexToPhysical;
  return geometry;
}

std::string ValidateVolumeGeometry(vtkImageData* image, vtkMatrix4x4* volumeMatrix)
{
  const double* spacing = image->GetSpacing();
  const double* origin = image->GetOrigin();
  for (int a = 0; a < 3; ++a)
  {
    if (!(spacing[a] > 0.0 && std::isfinite(spacing[a])))
    {
      return "the image's spacing " + Triple(spacing) + " must be three positive finite numbers";
    }
    if (!std::isfinite(origin[a]))
    {
      return "the image's origin " + Triple(origin) + " must be three finite numbers";
    }
  }
  glm::dmat3 direction;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      direction[c][r] = image->GetDirectionMatrix()->GetElement(r, c);
  if (!Finite(glm::dmat4(direction)))
  {
    return "the image's direction matrix holds a value that is not a finite number";
  }
  if (Conditioning(direction) < SingularConditioning)
  {
    return "the image's direction matrix is singular (determinant " +
      Number(glm::determinant(direction)) + "): its axes must be independent";
  }
  if (volumeMatrix)
  {
    const glm::dmat4 m = ToGlm(volumeMatrix);
    if (!Finite(m))
    {
      return "the volume's matrix (position, orientation, scale, user matrix) holds a value "
             "that is not a finite number";
    }
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
    {
      return "the volume's matrix is projective (its last row is not 0 0 0 1); a volume can be "
             "moved, rotated and scaled, not projected";
    }
    if (Conditioning(glm::dmat3(m)) < SingularConditioning)
    {
      return "the volume's matrix is singular (determinant " +
        Number(glm::determinant(glm::dmat3(m))) + "): a scale of 0 flattens the volume";
    }
  }
  return {};
}

double SmallestVoxelEdge(const VolumeGeometry& geometry)
{
  const glm::dmat3 m(geometry.IndexToWorld); // world displacement per index step, by column
  return std::min({ glm::length(m[0]), glm::length(m[1]), glm::length(m[2]) });
}

double EffectiveSampleDistance(const VolumeGeometry& geometry, double sampleDistance)
{
  return sampleDistance > 0.0 ? sampleDistance : SmallestVoxelEdge(geometry);
}

LocalFrame MakeLocalFrame(const VolumeGeometry& geometry)
{
  LocalFrame frame;
  const glm::dmat3 m(geometry.IndexToWorld); // world displacement per index step, by column
  const glm::dvec3 last = glm::dvec3(geometry.Dimensions) - 1.0;
  const glm::dvec3 centre = 0.5 * last;
  frame.Anchor = glm::dvec3(geometry.IndexToWorld * glm::dvec4(centre, 1.0));
  frame.SmallestVoxelEdge = SmallestVoxelEdge(geometry);
  frame.Unit = std::ldexp(1.0, int(std::lround(std::log2(frame.SmallestVoxelEdge))));
  // (world(p) - Anchor) / Unit = m (p - centre) / Unit: no large coordinates cancel.
  const glm::dmat3 toLocal = m / frame.Unit;
  frame.IndexToLocal = glm::dmat4(toLocal);
  frame.IndexToLocal[3] = glm::dvec4(-(toLocal * centre), 1.0);
  frame.LocalToIndex = glm::dmat4(glm::inverse(toLocal));
  frame.LocalToIndex[3] = glm::dvec4(centre, 1.0);
  // The longest segment inside a parallelepiped is one of its four diagonals.
  for (const glm::dvec3 sign :
    { glm::dvec3(1, 1, 1), glm::dvec3(-1, 1, 1), glm::dvec3(1, -1, 1), glm::dvec3(1, 1, -1) })
  {
    frame.LongestChord = std::max(frame.LongestChord, glm::length(toLocal * (sign * last)));
  }
  return frame;
}

glm::dmat4 DeviceToLocal(const LocalFrame& frame,
  const glm::dmat4& viewToDevice,
  const glm::dmat3& worldToView,
  const glm::dvec3& eye)
{
  // view = R (world - eye) = R (Unit x + (Anchor - eye)) for a local point x.
  glm::dmat4 localToView(worldToView * frame.Unit);
  localToView[3] = glm::dvec4(worldToView * (frame.Anchor - eye), 1.0);
  return glm::inverse(viewToDevice * localToView);
}

namespace
{
// The sections of SetUpMarch, in its order; each fills its part of `u` or returns the problem.

// The geometry and its local frame, and the density texels' scale.
MarchProblem SetUpGeometry(const MarchSetup& setup, MarchUniforms& u, LocalFrame& frame)
{
  const VolumeGeometry& geometry = setup.Geometry;
  if (glm::any(glm::lessThan(geometry.Dimensions, glm::ivec3(2))))
  {
    return Problem(MarchInput::Geometry, "the volume needs at least 2 voxels along each axis");
  }
  if (!Finite(geometry.IndexToWorld) ||
    Conditioning(glm::dmat3(geometry.IndexToWorld)) < SingularConditioning)
  {
    return Problem(MarchInput::Geometry,
      "the volume's placement (origin, spacing, direction and volume matrix together) is not "
      "finite or flattens the volume");
  }
  frame = MakeLocalFrame(geometry);
  if (!std::isfinite(frame.Unit) || !(frame.Unit > 0.0) || !FitsFloat(frame.IndexToLocal) ||
    !FitsFloat(frame.LocalToIndex) || !(frame.LongestChord < FloatLimit))
  {
    const glm::dmat3 m(geometry.IndexToWorld);
    return Problem(MarchInput::Geometry,
      "the volume's voxel edges, " +
        Triple(glm::dvec3(glm::length(m[0]), glm::length(m[1]), glm::length(m[2]))) +
        " world units, differ too much for float arithmetic");
  }
  u.Dimensions = geometry.Dimensions;
  u.Density = setup.Density;
  if (!(u.Density.Scale > 0.0f) || !FitsFloat(u.Density.Scale) || !FitsFloat(u.Density.Bias))
  {
    return Problem(MarchInput::Geometry,
      "the density texels' scale " + Number(u.Density.Scale) + " and bias " +
        Number(u.Density.Bias) + " must be finite, the scale > 0");
  }
  u.IndexToLocal = glm::mat4(frame.IndexToLocal);
  u.LocalToIndex = glm::mat3(glm::dmat3(frame.LocalToIndex));
  u.ExtinctionUnit = float(frame.Unit);
  if (!(u.ExtinctionUnit > 0.0f) || !std::isfinite(u.ExtinctionUnit))
  {
    return Problem(MarchInput::Geometry,
      "the volume's voxels, " + Number(frame.SmallestVoxelEdge) +
        " world units, are beyond what float arithmetic holds");
  }
  return {};
}

// The transfer table, and the width of its density range (the derivative's density unit).
MarchProblem SetUpTransferTable(const MarchSetup& setup,
  const LocalFrame& frame,
  MarchUniforms& u,
  double& densityUnit)
{
  const TransferTable* table = setup.Table;
  if (!table || table->Size < 1 || table->RGBA.size() < std::size_t(table->Size) * 4)
  {
    return Problem(MarchInput::TransferFunction, "no transfer table");
  }
  densityUnit = table->Range[1] - table->Range[0];
  if (!(densityUnit > 0.0))
  {
    // The GPU's lookup divides by the width (TransferFunctionRange never gives 0).
    return Problem(MarchInput::TransferFunction,
      "the transfer table spans no densities (from " + Number(table->Range[0]) + " to " +
        Number(table->Range[1]) + ")");
  }
  if (!(std::abs(table->Range[0]) <= MaxTransferDensity &&
        std::abs(table->Range[1]) <= MaxTransferDensity && densityUnit <= MaxTransferDensity))
  {
    return Problem(MarchInput::TransferFunction,
      "the transfer function spans densities [" + Number(table->Range[0]) + ", " +
        Number(table->Range[1]) + "], beyond what float arithmetic holds");
  }
  u.Table = table;
  double sigmaMax = 0.0; // per world unit
  for (int i = 0; i < table->Size; ++i)
  {
    const float* entry = &table->RGBA[std::size_t(i) * 4];
    if (!std::isfinite(entry[0]) || !std::isfinite(entry[1]) || !std::isfinite(entry[2]) ||
      !std::isfinite(entry[3]))
    {
      return Problem(MarchInput::TransferFunction,
        "the transfer function's extinction, -ln(1 - opacity) / unit distance, exceeds float "
        "range (3.4e38 per world unit): raise the unit distance");
    }
    sigmaMax = std::max(sigmaMax, double(entry[3]));
  }
  if (!(sigmaMax * frame.Unit * 4.0 * frame.LongestChord < FloatLimit))
  {
    return Problem(MarchInput::TransferFunction,
      "the transfer function's extinction reaches " + Number(sigmaMax) +
        " per world unit: the optical depth across the volume (" +
        Number(frame.LongestChord * frame.Unit) +
        " world units long) is beyond float range: raise the unit distance");
  }
  return {};
}

// The step, the samples a ray may take and the termination transmittance.
MarchProblem SetUpStep(const MarchSetup& setup, const LocalFrame& frame, MarchUniforms& u)
{
  const VolumeGeometry& geometry = setup.Geometry;
  if (!(setup.SampleDistance >= 0.0 && std::isfinite(setup.SampleDistance)))
  {
    return Problem(MarchInput::Step,
      "the step (sample distance) " + Number(setup.SampleDistance) +
        " must be a finite number >= 0 (0: one voxel)");
  }
  const double step = EffectiveSampleDistance(geometry, setup.SampleDistance);
  const double samples = frame.LongestChord * frame.Unit / step;
  if (!(samples <= MaxSamplesPerRay))
  {
    return Problem(MarchInput::Step,
      "the step " + Number(step) + " would take " + Number(std::ceil(samples)) +
        " samples along the volume's longest ray (" + Number(frame.LongestChord * frame.Unit) +
        " world units); the most is " + std::to_string(MaxSamplesPerRay) +
        ": use a step of at least " +
        // rounded up in its 6 printed digits, so that the step given is accepted
        Number(frame.LongestChord * frame.Unit / MaxSamplesPerRay * (1.0 + 1e-5)));
  }
  u.Step = float(step / frame.Unit);
  u.LongestRaySamples = int(std::ceil(samples));
  u.MaximumSamples = u.LongestRaySamples + 16;
  if (!(setup.TerminationTransmittance >= 0.0 && setup.TerminationTransmittance <= 1.0))
  {
    return Problem(MarchInput::Step, "the termination transmittance must be in [0, 1]");
  }
  u.TerminationTransmittance = float(setup.TerminationTransmittance);
  return {};
}

// The lighting parameters, with the automatic distances (docs/lighting.md).
MarchProblem SetUpLightingParameters(const MarchSetup& setup,
  const LocalFrame& frame,
  double densityUnit,
  MarchUniforms& u)
{
  const LightingParameters& p = setup.Lighting;
  const std::string lightingProblem = ValidateLightingParameters(p);
  if (!lightingProblem.empty())
  {
    return Problem(MarchInput::Lighting, lightingProblem);
  }
  const double h =
    p.DerivativeDistance > 0.0f ? p.DerivativeDistance : 4.0 * frame.SmallestVoxelEdge;
  const double lightStep = p.LightStep > 0.0f ? p.LightStep : 2.0 * frame.SmallestVoxelEdge;
  u.Lighting = p;
  u.Lighting.DerivativeDistance = float(h / frame.Unit);
  u.Lighting.LightStep = float(lightStep / frame.Unit);
  if (!(u.Lighting.DerivativeDistance > 0.0f) || !FitsFloat(u.Lighting.DerivativeDistance) ||
    !(u.Lighting.LightStep > 0.0f) || !FitsFloat(u.Lighting.LightStep))
  {
    return Problem(MarchInput::Lighting,
      "the derivative distance " + Number(h) + " and the light-march step " + Number(lightStep) +
        " must be within float range of the voxel size " + Number(frame.SmallestVoxelEdge));
  }
  const double slopeScale = 1.0 / (h * densityUnit);
  if (!FitsFloat(slopeScale))
  {
    return Problem(MarchInput::Lighting,
      "the derivative distance " + Number(h) + " times the transfer function's density span " +
        Number(densityUnit) + " is too small for float arithmetic");
  }
  u.DerivativeSlopeScale = float(slopeScale);
  const glm::dvec3 ambient = glm::dvec3(p.AmbientColor) * double(p.AmbientStrength);
  if (!(std::max({ ambient.x, ambient.y, ambient.z }) < FloatLimit))
  {
    return Problem(MarchInput::Lighting,
      "the ambient color x strength " + Triple(ambient) + " is beyond float range");
  }
  u.Ambient = glm::vec3(ambient);
  return {};
}

// One light (its index `index`) in the local frame, and the largest falloff a sample inside the
// volume can see of it (1 for directional lights). Needs u.LocalToIndex and u.Lighting.
MarchProblem SetUpLight(const Light& light,
  int index,
  const LocalFrame& frame,
  const MarchUniforms& u,
  LocalLight& local,
  double& falloff)
{
  const std::string name = "light " + std::to_string(index) + " (" +
    (light.Positional ? "a point light at " : "a directional light from ") +
    Triple(light.Position) + ")";
  const glm::dvec3 radiance = glm::dvec3(light.Color) * double(light.Intensity);
  const glm::dvec3 attenuation(light.Attenuation.x,
    light.Attenuation.y * frame.Unit,
    light.Attenuation.z * frame.Unit * frame.Unit);
  if (!Finite(light.Position) || !Finite(light.FocalPoint) || !Finite(radiance) ||
    !FitsFloat(radiance.x) || !FitsFloat(radiance.y) || !FitsFloat(radiance.z) ||
    (light.Positional &&
      !(FitsFloat(attenuation.x) && FitsFloat(attenuation.y) && FitsFloat(attenuation.z))))
  {
    return Problem(MarchInput::Light,
      name +
        ": its color, intensity, position, focal point and attenuation must be finite, "
        "and color x intensity and the attenuation within float range",
      index);
  }
  local.Positional = light.Positional;
  local.Radiance = glm::vec3(radiance);
  local.Attenuation = glm::vec3(attenuation);
  falloff = 1.0;
  if (light.Positional)
  {
    const glm::dvec3 position = frame.ToLocal(light.Position);
    const double distance = glm::length(position);
    if (!(distance <= MaxPointLightDistance))
    {
      return Problem(MarchInput::Light,
        name + " is " + Number(distance * frame.Unit) +
          " world units from the volume's centre, too far for float arithmetic (at most " +
          Number(MaxPointLightDistance * frame.Unit) +
          " for this volume): use a directional light for a light this far",
        index);
    }
    local.Position = glm::vec3(position);
    // The nearest a sample can be: inside the sphere around the volume, possibly 0.
    const double r = std::max(0.0, distance - 0.5 * frame.LongestChord);
    falloff = 1.0 /
      std::max(double(local.Attenuation.x) + double(local.Attenuation.y) * r +
          double(local.Attenuation.z) * r * r,
        1e-20);
  }
  else
  {
    const glm::dvec3 direction = DirectionTowardLight(light);
    if (direction == glm::dvec3(0.0))
    {
      return Problem(MarchInput::Light,
        name + " is directional with its position on its focal point: it has no direction",
        index);
    }
    local.Direction = glm::vec3(direction);
    local.IndexDirection = u.LocalToIndex * local.Direction;
    local.IndexOffset = u.LocalToIndex * (u.Lighting.DerivativeDistance * local.Direction);
  }
  return {};
}

// The lights, and the bound on the radiance they can make a sample send toward the eye.
MarchProblem SetUpLights(const MarchSetup& setup, const LocalFrame& frame, MarchUniforms& u)
{
  const LightingParameters& p = setup.Lighting;
  const glm::dvec3 ambient = glm::dvec3(p.AmbientColor) * double(p.AmbientStrength);
  if (setup.Lights.size() > std::size_t(LightingLimits::MaxLights))
  {
    return Problem(MarchInput::Light,
      std::to_string(setup.Lights.size()) + " lights; the renderers take at most " +
        std::to_string(LightingLimits::MaxLights),
      LightingLimits::MaxLights);
  }
  // Each light's radiance can reach E * falloff * PeakRadiancePerLightRadiance at a sample; the
  // sum over lights, plus the ambient term, bounds what a ray gathers (sum T (1 - T_step) <= 1).
  const bool lit = p.Model != LightingModel::None;
  const double perLight = PeakRadiancePerLightRadiance(p);
  double peakTotal = std::max({ ambient.x, ambient.y, ambient.z });
  double brightest = -1.0;
  int brightestLight = -1;
  u.Lights.clear();
  for (std::size_t i = 0; i < setup.Lights.size(); ++i)
  {
    const Light& light = setup.Lights[i];
    const int index = int(i);
    LocalLight local;
    double falloff = 1.0;
    if (MarchProblem problem = SetUpLight(light, index, frame, u, local, falloff))
    {
      return problem;
    }
    const glm::dvec3 radiance = glm::dvec3(light.Color) * double(light.Intensity);
    const double peak =
      std::max({ std::abs(radiance.x), std::abs(radiance.y), std::abs(radiance.z) }) * falloff *
      perLight;
    peakTotal += peak;
    if (peak > brightest)
    {
      brightest = peak;
      brightestLight = index;
    }
    u.Lights.push_back(local);
  }
  if (lit && !(peakTotal < FloatLimit))
  {
    const Light& light = setup.Lights[std::size_t(std::max(brightestLight, 0))];
    return Problem(MarchInput::Light,
      "light " + std::to_string(brightestLight) + " (color x intensity " +
        Number(
          double(light.Intensity) * std::max({ light.Color.x, light.Color.y, light.Color.z })) +
        ") can make a sample send a radiance of " + Number(peakTotal) +
        " toward the eye, beyond float range (" + Number(FloatLimit) + "): lower its intensity",
      brightestLight);
  }
  return {};
}
}

MarchProblem SetUpMarch(const MarchSetup& setup, MarchUniforms& u, LocalFrame* frameOut)
{
  LocalFrame frame;
  double densityUnit = 0.0;
  MarchProblem problem = SetUpGeometry(setup, u, frame);
  if (!problem)
  {
    problem = SetUpTransferTable(setup, frame, u, densityUnit);
  }
  if (!problem)
  {
    problem = SetUpStep(setup, frame, u);
  }
  if (!problem)
  {
    problem = SetUpLightingParameters(setup, frame, densityUnit, u);
  }
  if (!problem)
  {
    problem = SetUpLights(setup, frame, u);
  }
  if (!problem && frameOut)
  {
    *frameOut = frame;
  }
  return problem;
}

std::vector<Light> LightsOf(vtkLightCollection* collection)
{
  std::vector<Light> lights;
  if (!collection)
  {
    return lights;
  }
  vtkCollectionSimpleIterator it;
  collection->InitTraversal(it);
  while (vtkLight* light = collection->GetNextLight(it))
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    Light l;
    l.Positional = light->GetPositional() != 0;
    double position[3], focalPoint[3];
    light->GetTransformedPosition(position);
    light->GetTransformedFocalPoint(focalPoint);
    l.Position = glm::dvec3(position[0], position[1], position[2]);
    l.FocalPoint = glm::dvec3(focalPoint[0], focalPoint[1], focalPoint[2]);
    const double* color = light->GetDiffuseColor();
    l.Color = glm::vec3(float(color[0]), float(color[1]), float(color[2]));
    l.Intensity = float(light->GetIntensity());
    const double* attenuation = light->GetAttenuationValues();
    l.Attenuation = glm::vec3(float(attenuation[0]), float(attenuation[1]), float(attenuation[2]));
    lights.push_back(l);
  }
  return lights;
}

vtkSmartPointer<vtkLight> MakeLight(const Light& light)
{
  auto vtk = vtkSmartPointer<vtkLight>::New();
  vtk->SetLightTypeToSceneLight();
  vtk->SetPositional(light.Positional);
  vtk->SetPosition(light.Position.x, light.Position.y, light.Position.z);
  vtk->SetFocalPoint(light.FocalPoint.x, light.FocalPoint.y, light.FocalPoint.z);
  vtk->SetDiffuseColor(light.Color.x, light.Color.y, light.Color.z);
  vtk->SetIntensity(light.Intensity);
  vtk->SetAttenuationValues(light.Attenuation.x, light.Attenuation.y, light.Attenuation.z);
  if (light.Positional)
  {
    vtk->SetConeAngle(180.0); // a point light, not a spot
  }
  return vtk;
}

vtkSmartPointer<vtkLightCollection> MakeLights(const std::vector<Light>& lights)
{
  auto collection = vtkSmartPointer<vtkLightCollection>::New();
  for (const Light& light : lights)
  {
    collection->AddItem(MakeLight(light));
  }
  return collection;
}

MarchSetup MakeMarchSetup(vtkImageData* image,
  vtkMatrix4x4* volumeMatrix,
  const DensityTexels& texels,
  const TransferTable* table,
  double sampleDistance,
  double terminationTransmittance,
  const LightingParameters& lighting,
  std::vector<Light> lights)
{
  MarchSetup setup;
  setup.Geometry = GeometryOf(image, volumeMatrix);
  setup.Density = texels;
  setup.Table = table;
  setup.SampleDistance = sampleDistance;
  setup.TerminationTransmittance = terminationTransmittance;
  setup.Lighting = lighting;
  setup.Lights = std::move(lights);
  return setup;
}

} // namespace cloudvis
