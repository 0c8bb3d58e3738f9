// A Scene as cloudvis's renderers take it: one function, RendererSettingsOf, turns the scene's
// transfer function, lighting model and parameters (render and ambient sections), lights and
// step into the VTK objects every renderer is configured with (a vtkVolumeProperty, a
// vtkCloudLightingProperty, vtkLights), and both the GPU mapper (ConfigureLighting, for
// render, compare and the viewer) and the CPU reference (ConfigureReference) are configured from
// what it returns, so a scene cannot reach one renderer differently from the other.
// CheckSceneRenderable (CpuReference.h) checks the same settings.
#ifndef cloudvis_SceneLighting_h
#define cloudvis_SceneLighting_h

#include "Scene.h"

#include <vtkSmartPointer.h>

class vtkCloudLightingProperty;
class vtkCloudReferenceRenderer;
class vtkCloudVolumeMapper;
class vtkLightCollection;
class vtkRenderer;
class vtkVolumeProperty;

namespace cloudvis
{

// What a scene asks of every renderer.
struct RendererSettings
{
  vtkSmartPointer<vtkVolumeProperty> TransferFunction; // MakeVolumeProperty(transfer_function)
  vtkSmartPointer<vtkCloudLightingProperty> Lighting;  // LightingOf(scene)
  vtkSmartPointer<vtkLightCollection> Lights;          // MakeLights(scene lights)
  double SampleDistance = 0.0;                         // render.step (0: one voxel)
};

RendererSettings RendererSettingsOf(const Scene& scene);

// The GPU path: replaces the renderer's lights with the scene's and turns off VTK's automatic
// headlight, which a renderer without lights would otherwise create (so "lights": [] means no
// lights), then gives the mapper the scene's lighting property and step. The volume property is
// the caller's (MakeVolumeProperty, OffscreenRender.h), as the transfer function of
// RendererSettingsOf is.
void ConfigureLighting(const Scene& scene, vtkRenderer* renderer, vtkCloudVolumeMapper* mapper);

// The CPU path: the same settings given to the reference renderer (or the path tracer): its
// transfer function, lighting property, lights and step.
void ConfigureReference(const Scene& scene, vtkCloudReferenceRenderer* reference);

} // namespace cloudvis

#endif
