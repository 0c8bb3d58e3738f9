#include "SceneLighting.h"

#include "CloudMarchUniforms.h"
#include "OffscreenRender.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudReferenceRenderer.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkRenderer.h>
#include <vtkVolumeProperty.h>

namespace cloudvis
{

RendererSettings RendererSettingsOf(const Scene& scene)
{
  RendererSettings settings;
  settings.TransferFunction = MakeVolumeProperty(scene.TransferFunction);
  settings.Lighting = vtkSmartPointer<vtkCloudLightingProperty>::New();
  settings.Lighting->SetParameters(LightingOf(scene));
  settings.Lights = MakeLights(scene.Lights);
  settings.SampleDistance = scene.Render.Step;
  return settings;
}

void ConfigureLighting(const Scene& scene, vtkRenderer* renderer, vtkCloudVolumeMapper* mapper)
{
  const RendererSettings settings = RendererSettingsOf(scene);
  renderer->AutomaticLightCreationOff();
  renderer->RemoveAllLights();
  vtkCollectionSimpleIterator it;
  settings.Lights->InitTraversal(it);
  while (vtkLight* light = settings.Lights->GetNextLight(it))
  {
    renderer->AddLight(light);
  }
  mapper->SetLightingProperty(settings.Lighting);
  mapper->SetSampleDistance(settings.SampleDistance);
}

void ConfigureReference(const Scene& scene, vtkCloudReferenceRenderer* reference)
{
  const RendererSettings settings = RendererSettingsOf(scene);
  reference->SetVolumeProperty(settings.TransferFunction);
  reference->SetLightingProperty(settings.Lighting);
  reference->SetLights(settings.Lights);
  reference->SetSampleDistance(settings.SampleDistance);
}

} // namespace cloudvis
