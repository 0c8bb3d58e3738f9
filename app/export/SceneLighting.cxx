#include "SceneLighting.h"

#include "OffscreenRender.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudReferenceRenderer.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkVolumeProperty.h>

namespace cloudvis
{

RendererSettings RendererSettingsOf(const Scene& scene)
{
  RendererSettings settings;
  settings.TransferFunction = MakeVolumeProperty(scene.TransferFunction);
  settings.Lighting = vtkSmartPointer<vtkCloudLightingProperty>::New();
  settings.Lighting->SetParameters(scene.Render.Lighting);
  settings.Lights = scene.Lights;
  settings.SampleDistance = scene.Render.Step;
  return settings;
}

void ConfigureLighting(const Scene& scene, vtkCloudVolumeMapper* mapper)
{
  const RendererSettings settings = RendererSettingsOf(scene);
  mapper->SetLightingProperty(settings.Lighting);
  mapper->SetLights(settings.Lights);
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
