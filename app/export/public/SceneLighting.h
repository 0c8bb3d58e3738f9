// A Scene as cloudvis's renderers take it: one function, RendererSettingsOf, gathers what every
// renderer is configured with (the transfer function as a vtkVolumeProperty, the scene's
// LightingParameters in a vtkCloudLightingProperty, the scene's lights as they are, the step),
// and both the GPU mapper (ConfigureLighting, for render, compare and the viewer) and the CPU
// reference (ConfigureReference) are configured from what it returns, so a scene cannot reach
// one renderer differently from the other. The lighting value and the lights are the scene's own
// (CloudLightingParameters.h) from the scene file to the march's uniforms: nothing re-expresses
// them on the way (no vtkLights; the renderer's vtkLights light nothing of the cloud).
// CheckSceneRenderable (CpuReference.h) checks the same settings.
#ifndef cloudvis_SceneLighting_h
#define cloudvis_SceneLighting_h

#include "Scene.h"

#include <vtkSmartPointer.h>

#include <vector>

class vtkCloudLightingProperty;
class vtkCloudReferenceRenderer;
class vtkCloudVolumeMapper;
class vtkVolumeProperty;

namespace cloudvis
{

// What a scene asks of every renderer.
struct RendererSettings
{
  vtkSmartPointer<vtkVolumeProperty> TransferFunction; // MakeVolumeProperty(transfer_function)
  vtkSmartPointer<vtkCloudLightingProperty> Lighting;  // holding scene.Render.Lighting
  std::vector<Light> Lights;                           // scene.Lights
  double SampleDistance = 0.0;                         // render.step (0: one voxel)
};

RendererSettings RendererSettingsOf(const Scene& scene);

// The GPU path: gives the mapper the scene's lighting property, its lights (in place of the
// renderer's vtkLights, so "lights": [] means no lights whatever the renderer holds) and its
// step. The volume property is the caller's (MakeVolumeProperty, OffscreenRender.h), as the
// transfer function of RendererSettingsOf is.
void ConfigureLighting(const Scene& scene, vtkCloudVolumeMapper* mapper);

// The CPU path: the same settings given to the reference renderer (or the path tracer): its
// transfer function, lighting property, lights and step.
void ConfigureReference(const Scene& scene, vtkCloudReferenceRenderer* reference);

} // namespace cloudvis

#endif
