#include "vtkCloudLightingProperty.h"

#include <vtkObjectFactory.h>

#include <algorithm>

vtkStandardNewMacro(vtkCloudLightingProperty);

namespace
{
using P = cloudvis::LightingParameters;
}

template<typename T>
void vtkCloudLightingProperty::Assign(T P::*member, T value)
{
  if (!(this->Parameters.*member == value))
  {
    this->Parameters.*member = value;
    this->Modified();
  }
}

void vtkCloudLightingProperty::SetParameters(const cloudvis::LightingParameters& parameters)
{
  if (this->Parameters != parameters)
  {
    this->Parameters = parameters;
    this->Modified();
  }
}

void vtkCloudLightingProperty::DeepCopy(vtkCloudLightingProperty* other)
{
  if (other)
  {
    this->SetParameters(other->GetParameters());
  }
}

// The VTK-facing accessors of the members that are plain numbers, each Set and Get a view of one
// member of Parameters.
#define CLOUDVIS_LIGHTING_ACCESSORS(type, name)                                                    \
  void vtkCloudLightingProperty::Set##name(type value)                                             \
  {                                                                                                \
    this->Assign(&P::name, value);                                                                 \
  }                                                                                                \
  type vtkCloudLightingProperty::Get##name()                                                       \
  {                                                                                                \
    return this->Parameters.name;                                                                  \
  }
CLOUDVIS_LIGHTING_ACCESSORS(float, AmbientStrength)
CLOUDVIS_LIGHTING_ACCESSORS(float, DerivativeDistance)
CLOUDVIS_LIGHTING_ACCESSORS(int, LightSteps)
CLOUDVIS_LIGHTING_ACCESSORS(float, LightStep)
CLOUDVIS_LIGHTING_ACCESSORS(float, LightStepGrowth)
CLOUDVIS_LIGHTING_ACCESSORS(float, PhaseG1)
CLOUDVIS_LIGHTING_ACCESSORS(float, PhaseG2)
CLOUDVIS_LIGHTING_ACCESSORS(float, PhaseLobeWeight)
CLOUDVIS_LIGHTING_ACCESSORS(float, DropletEffectiveRadius)
CLOUDVIS_LIGHTING_ACCESSORS(float, DropletEffectiveVariance)
CLOUDVIS_LIGHTING_ACCESSORS(int, MultipleScatteringOctaves)
CLOUDVIS_LIGHTING_ACCESSORS(float, ScatteringFalloff)
CLOUDVIS_LIGHTING_ACCESSORS(float, ExtinctionFalloff)
CLOUDVIS_LIGHTING_ACCESSORS(float, EccentricityFalloff)
CLOUDVIS_LIGHTING_ACCESSORS(float, PowderStrength)
#undef CLOUDVIS_LIGHTING_ACCESSORS

// The enumerations are clamped into their range, as vtkSetClampMacro would.
void vtkCloudLightingProperty::SetModel(int model)
{
  this->Assign(
    &P::Model, cloudvis::LightingModel(std::clamp(model, int(NoLighting), int(PathTraceLighting))));
}

int vtkCloudLightingProperty::GetModel()
{
  return int(this->Parameters.Model);
}

void vtkCloudLightingProperty::SetTransmittance(int transmittance)
{
  this->Assign(&P::Transmittance,
    cloudvis::LightTransmittance(std::clamp(transmittance, int(LightVolumes), int(NestedMarch))));
}

int vtkCloudLightingProperty::GetTransmittance()
{
  return int(this->Parameters.Transmittance);
}

void vtkCloudLightingProperty::SetPhase(int phase)
{
  this->Assign(
    &P::Phase, cloudvis::PhaseModel(std::clamp(phase, int(TwoLobePhase), int(DropletPhase))));
}

int vtkCloudLightingProperty::GetPhase()
{
  return int(this->Parameters.Phase);
}

void vtkCloudLightingProperty::SetMultipleScattering(int scattering)
{
  this->Assign(&P::MultipleScattering,
    cloudvis::MultipleScatteringModel(
      std::clamp(scattering, int(ScatteringVolume), int(ScatteringOctaves))));
}

int vtkCloudLightingProperty::GetMultipleScattering()
{
  return int(this->Parameters.MultipleScattering);
}

const char* vtkCloudLightingProperty::GetMultipleScatteringAsString() const
{
  return cloudvis::MultipleScatteringModelName(this->Parameters.MultipleScattering);
}

void vtkCloudLightingProperty::SetAmbientColor(float r, float g, float b)
{
  this->Assign(&P::AmbientColor, glm::vec3(r, g, b));
}

void vtkCloudLightingProperty::SetAmbientColor(const float color[3])
{
  this->SetAmbientColor(color[0], color[1], color[2]);
}

float* vtkCloudLightingProperty::GetAmbientColor()
{
  return &this->Parameters.AmbientColor[0];
}

void vtkCloudLightingProperty::GetAmbientColor(float& r, float& g, float& b)
{
  r = this->Parameters.AmbientColor.r;
  g = this->Parameters.AmbientColor.g;
  b = this->Parameters.AmbientColor.b;
}

void vtkCloudLightingProperty::GetAmbientColor(float color[3])
{
  this->GetAmbientColor(color[0], color[1], color[2]);
}

const char* vtkCloudLightingProperty::GetModelAsString() const
{
  return cloudvis::LightingModelName(this->Parameters.Model);
}

void vtkCloudLightingProperty::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const P& p = this->Parameters;
  os << indent << "Model: " << this->GetModelAsString() << "\n";
  os << indent << "AmbientColor: (" << p.AmbientColor.r << ", " << p.AmbientColor.g << ", "
     << p.AmbientColor.b << ")\n";
  os << indent << "AmbientStrength: " << p.AmbientStrength << "\n";
  os << indent << "DerivativeDistance: " << p.DerivativeDistance << "\n";
  os << indent << "LightSteps: " << p.LightSteps << "\n";
  os << indent << "LightStep: " << p.LightStep << "\n";
  os << indent << "LightStepGrowth: " << p.LightStepGrowth << "\n";
  os << indent << "PhaseG1: " << p.PhaseG1 << "\n";
  os << indent << "PhaseG2: " << p.PhaseG2 << "\n";
  os << indent << "PhaseLobeWeight: " << p.PhaseLobeWeight << "\n";
  os << indent << "Phase: " << (p.Phase == cloudvis::PhaseModel::Droplets ? "droplets" : "two lobes")
     << "\n";
  os << indent << "DropletEffectiveRadius: " << p.DropletEffectiveRadius << "\n";
  os << indent << "DropletEffectiveVariance: " << p.DropletEffectiveVariance << "\n";
  os << indent << "MultipleScattering: " << this->GetMultipleScatteringAsString() << "\n";
  os << indent << "MultipleScatteringOctaves: " << p.MultipleScatteringOctaves << "\n";
  os << indent << "ScatteringFalloff: " << p.ScatteringFalloff << "\n";
  os << indent << "ExtinctionFalloff: " << p.ExtinctionFalloff << "\n";
  os << indent << "EccentricityFalloff: " << p.EccentricityFalloff << "\n";
  os << indent << "PowderStrength: " << p.PowderStrength << "\n";
  os << indent << "Transmittance: "
     << (p.Transmittance == cloudvis::LightTransmittance::Nested ? "nested march" : "light volumes")
     << "\n";
}
