#include "SceneLighting.h"

#include "vtkCloudVolumeMapper.h"

#include <vtkLight.h>
#include <vtkRenderer.h>

namespace cloudvis
{

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

void ConfigureLighting(const Scene& scene, vtkRenderer* renderer, vtkCloudVolumeMapper* mapper)
{
  renderer->AutomaticLightCreationOff();
  renderer->RemoveAllLights();
  for (const Light& light : scene.Lights)
  {
    renderer->AddLight(MakeLight(light));
  }
  mapper->SetLighting(LightingOf(scene));
}

} // namespace cloudvis
