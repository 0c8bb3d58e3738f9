#include "vtkCloudVolumeRepresentation.h"

#include "CloudLightingParameters.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkAlgorithm.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiProcessController.h>
#include <vtkObjectFactory.h>
#include <vtkPVLODVolume.h>
#include <vtkPVRenderView.h>
#include <vtkRenderer.h>
#include <vtkVolumeProperty.h>

#include <algorithm>

vtkStandardNewMacro(vtkCloudVolumeRepresentation);

vtkCloudVolumeRepresentation::vtkCloudVolumeRepresentation()
{
  vtkCloudVolumeMapper* mapper = vtkCloudVolumeMapper::New();
  this->VolumeMapper.TakeReference(mapper);
  this->CloudMapper = mapper;
  mapper->SetLightingProperty(this->Lighting);
  this->UpdateSun();
}

vtkCloudVolumeRepresentation::~vtkCloudVolumeRepresentation() = default;

// ---- Lighting ----

void vtkCloudVolumeRepresentation::SetLightingModel(int model)
{
  this->Lighting->SetModel(model);
}

void vtkCloudVolumeRepresentation::SetAmbientColor(double r, double g, double b)
{
  this->Lighting->SetAmbientColor(float(r), float(g), float(b));
}

void vtkCloudVolumeRepresentation::SetAmbientStrength(double strength)
{
  this->Lighting->SetAmbientStrength(float(strength));
}

void vtkCloudVolumeRepresentation::SetDerivativeDistance(double distance)
{
  this->Lighting->SetDerivativeDistance(float(distance));
}

void vtkCloudVolumeRepresentation::SetLightSteps(int steps)
{
  this->Lighting->SetLightSteps(steps);
}

void vtkCloudVolumeRepresentation::SetPhaseG1(double g)
{
  this->Lighting->SetPhaseG1(float(g));
}

void vtkCloudVolumeRepresentation::SetPhaseG2(double g)
{
  this->Lighting->SetPhaseG2(float(g));
}

void vtkCloudVolumeRepresentation::SetPhaseLobeWeight(double weight)
{
  this->Lighting->SetPhaseLobeWeight(float(weight));
}

void vtkCloudVolumeRepresentation::SetMultipleScattering(int scattering)
{
  this->Lighting->SetMultipleScattering(scattering);
}

void vtkCloudVolumeRepresentation::SetMultipleScatteringOctaves(int octaves)
{
  this->Lighting->SetMultipleScatteringOctaves(octaves);
}

void vtkCloudVolumeRepresentation::SetTransmittance(int transmittance)
{
  this->Lighting->SetTransmittance(transmittance);
}

// ---- The sun ----

void vtkCloudVolumeRepresentation::SetSunDirection(double x, double y, double z)
{
  this->SunDirection[0] = x;
  this->SunDirection[1] = y;
  this->SunDirection[2] = z;
  this->UpdateSun();
}

void vtkCloudVolumeRepresentation::SetSunColor(double r, double g, double b)
{
  this->SunColor[0] = r;
  this->SunColor[1] = g;
  this->SunColor[2] = b;
  this->UpdateSun();
}

void vtkCloudVolumeRepresentation::SetSunIntensity(double intensity)
{
  this->SunIntensity = intensity;
  this->UpdateSun();
}

void vtkCloudVolumeRepresentation::UpdateSun()
{
  // A scene's directional light: from its position toward its focal point, the origin. The
  // mapper refuses a zero direction with a message naming it.
  cloudvis::Light sun;
  sun.Positional = false;
  sun.Position = glm::dvec3(this->SunDirection[0], this->SunDirection[1], this->SunDirection[2]);
  sun.FocalPoint = glm::dvec3(0.0);
  sun.Color = glm::vec3(float(this->SunColor[0]), float(this->SunColor[1]), float(this->SunColor[2]));
  sun.Intensity = float(this->SunIntensity);
  this->CloudMapper->SetLights({ sun });
}

// ---- The mapper ----

void vtkCloudVolumeRepresentation::SetSampleDistance(double distance)
{
  this->CloudMapper->SetSampleDistance(distance);
}

void vtkCloudVolumeRepresentation::SetExtinctionScale(double scale)
{
  this->CloudMapper->SetExtinctionScale(scale);
}

void vtkCloudVolumeRepresentation::SetJitter(bool jitter)
{
  this->CloudMapper->SetJitter(jitter);
}

void vtkCloudVolumeRepresentation::SetMaximumAccumulatedFrames(int frames)
{
  this->CloudMapper->SetMaximumAccumulatedFrames(frames);
}

void vtkCloudVolumeRepresentation::SetPathTraceSamplesPerFrame(int samples)
{
  this->CloudMapper->SetPathTraceSamplesPerFrame(samples);
}

void vtkCloudVolumeRepresentation::SetMaximumGPUMemory(double mebibytes)
{
  this->CloudMapper->SetMaximumGPUMemory(vtkTypeInt64(std::max(0.0, mebibytes) * 1048576.0));
}

void vtkCloudVolumeRepresentation::SetShadowExchange(bool exchange)
{
  if (this->ShadowExchange != exchange)
  {
    this->ShadowExchange = exchange;
    this->ExchangedTime = 0;
    this->Modified();
  }
}

void vtkCloudVolumeRepresentation::UpdateMapperParameters()
{
  this->Superclass::UpdateMapperParameters();
  // cloudvis's mapper reads the active scalars; ParaView's choice of the array to color by
  // becomes them (the superclass has set it on the mapper as VTK's mappers take it).
  this->Actor->SetMapper(this->CloudMapper);
}

int vtkCloudVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* requestType, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(requestType, inInfo, outInfo))
  {
    return 0;
  }
  if (requestType == vtkPVView::REQUEST_RENDER())
  {
    auto* view = vtkPVRenderView::SafeDownCast(inInfo->Get(vtkPVView::VIEW()));
    this->ExchangeOpticalDepth(view ? view->GetRenderer() : nullptr);
  }
  return 1;
}

void vtkCloudVolumeRepresentation::ExchangeOpticalDepth(vtkRenderer*)
{
  // Filled in with the mapper's piece optical depth (issue 25).
}

void vtkCloudVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lighting: " << this->Lighting->GetModelAsString() << "\n";
  os << indent << "SunDirection: " << this->SunDirection[0] << ", " << this->SunDirection[1]
     << ", " << this->SunDirection[2] << "\n";
  os << indent << "SunIntensity: " << this->SunIntensity << "\n";
  os << indent << "ShadowExchange: " << this->ShadowExchange << "\n";
  os << indent << "ExchangeCount: " << this->ExchangeCount << "\n";
}
