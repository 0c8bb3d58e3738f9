#include "vtkCloudLightingProperty.h"

#include <vtkObjectFactory.h>

vtkStandardNewMacro(vtkCloudLightingProperty);

static_assert(int(cloudvis::LightingModel::None) == vtkCloudLightingProperty::NoLighting &&
    int(cloudvis::LightingModel::Derivative) == vtkCloudLightingProperty::DerivativeLighting &&
    int(cloudvis::LightingModel::March) == vtkCloudLightingProperty::MarchLighting &&
    int(cloudvis::LightingModel::PathTrace) == vtkCloudLightingProperty::PathTraceLighting,
  "the property's models are cloudvis::LightingModel's");

namespace
{
// member = value, noting whether that changed it.
template<typename T, typename V>
void Assign(T& member, V value, bool& changed)
{
  if (member != static_cast<T>(value))
  {
    member = static_cast<T>(value);
    changed = true;
  }
}
}

vtkCloudLightingProperty::vtkCloudLightingProperty()
{
  this->AssignParameters(cloudvis::LightingParameters());
}

// Every member from `p`: the one list of the members, for the constructor, SetParameters and
// DeepCopy alike. True when one changed.
bool vtkCloudLightingProperty::AssignParameters(const cloudvis::LightingParameters& p)
{
  bool changed = false;
  Assign(this->Model, int(p.Model), changed);
  for (int c = 0; c < 3; ++c)
  {
    Assign(this->AmbientColor[c], p.AmbientColor[c], changed);
  }
  Assign(this->AmbientStrength, p.AmbientStrength, changed);
  Assign(this->DerivativeDistance, p.DerivativeDistance, changed);
  Assign(this->LightSteps, p.LightSteps, changed);
  Assign(this->LightStep, p.LightStep, changed);
  Assign(this->LightStepGrowth, p.LightStepGrowth, changed);
  Assign(this->PhaseG1, p.PhaseG1, changed);
  Assign(this->PhaseG2, p.PhaseG2, changed);
  Assign(this->PhaseLobeWeight, p.PhaseLobeWeight, changed);
  Assign(this->MultipleScatteringOctaves, p.MultipleScatteringOctaves, changed);
  Assign(this->ScatteringFalloff, p.ScatteringFalloff, changed);
  Assign(this->ExtinctionFalloff, p.ExtinctionFalloff, changed);
  Assign(this->EccentricityFalloff, p.EccentricityFalloff, changed);
  Assign(this->PowderStrength, p.PowderStrength, changed);
  Assign(this->Transmittance, int(p.Transmittance), changed);
  return changed;
}

void vtkCloudLightingProperty::SetParameters(const cloudvis::LightingParameters& parameters)
{
  if (this->AssignParameters(parameters))
  {
    this->Modified();
  }
}

cloudvis::LightingParameters vtkCloudLightingProperty::GetParameters() const
{
  cloudvis::LightingParameters p;
  p.Model = static_cast<cloudvis::LightingModel>(this->Model);
  p.AmbientColor = glm::vec3(this->AmbientColor[0], this->AmbientColor[1], this->AmbientColor[2]);
  p.AmbientStrength = this->AmbientStrength;
  p.DerivativeDistance = this->DerivativeDistance;
  p.LightSteps = this->LightSteps;
  p.LightStep = this->LightStep;
  p.LightStepGrowth = this->LightStepGrowth;
  p.PhaseG1 = this->PhaseG1;
  p.PhaseG2 = this->PhaseG2;
  p.PhaseLobeWeight = this->PhaseLobeWeight;
  p.MultipleScatteringOctaves = this->MultipleScatteringOctaves;
  p.ScatteringFalloff = this->ScatteringFalloff;
  p.ExtinctionFalloff = this->ExtinctionFalloff;
  p.EccentricityFalloff = this->EccentricityFalloff;
  p.PowderStrength = this->PowderStrength;
  p.Transmittance = static_cast<cloudvis::LightTransmittance>(this->Transmittance);
  return p;
}

void vtkCloudLightingProperty::DeepCopy(vtkCloudLightingProperty* other)
{
  if (other)
  {
    this->SetParameters(other->GetParameters());
  }
}

const char* vtkCloudLightingProperty::GetModelAsString() const
{
  switch (this->Model)
  {
    case DerivativeLighting:
      return "derivative";
    case MarchLighting:
      return "march";
    case PathTraceLighting:
      return "pathtrace";
    case NoLighting:
    default:
      return "none";
  }
}

void vtkCloudLightingProperty::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Model: " << this->GetModelAsString() << "\n";
  os << indent << "AmbientColor: (" << this->AmbientColor[0] << ", " << this->AmbientColor[1]
     << ", " << this->AmbientColor[2] << ")\n";
  os << indent << "AmbientStrength: " << this->AmbientStrength << "\n";
  os << indent << "DerivativeDistance: " << this->DerivativeDistance << "\n";
  os << indent << "LightSteps: " << this->LightSteps << "\n";
  os << indent << "LightStep: " << this->LightStep << "\n";
  os << indent << "LightStepGrowth: " << this->LightStepGrowth << "\n";
  os << indent << "PhaseG1: " << this->PhaseG1 << "\n";
  os << indent << "PhaseG2: " << this->PhaseG2 << "\n";
  os << indent << "PhaseLobeWeight: " << this->PhaseLobeWeight << "\n";
  os << indent << "MultipleScatteringOctaves: " << this->MultipleScatteringOctaves << "\n";
  os << indent << "ScatteringFalloff: " << this->ScatteringFalloff << "\n";
  os << indent << "ExtinctionFalloff: " << this->ExtinctionFalloff << "\n";
  os << indent << "EccentricityFalloff: " << this->EccentricityFalloff << "\n";
  os << indent << "PowderStrength: " << this->PowderStrength << "\n";
  os << indent
     << "Transmittance: " << (this->Transmittance == NestedMarch ? "nested march" : "light volumes")
     << "\n";
}
