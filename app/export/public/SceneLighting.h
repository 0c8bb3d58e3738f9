// The scene's lights section and lighting model onto VTK: vtkLights in the renderer (which the
// mapper reads, as VTK mappers do) and the LightingParameters of the mapper. Every path that draws
// a Scene calls ConfigureLighting (render, compare, the viewer), so they light it alike; the CPU
// reference takes the same cloudvis::Light values straight from the Scene.
#ifndef cloudvis_SceneLighting_h
#define cloudvis_SceneLighting_h

#include "Scene.h"

#include <vtkSmartPointer.h>

class vtkCloudVolumeMapper;
class vtkLight;
class vtkRenderer;

namespace cloudvis
{

// A scene light as a vtkLight: a scene light (fixed in world coordinates), positional for point
// lights (cone angle 180: no spot), with the light's position, focal point, color as the diffuse
// color, intensity and attenuation values.
vtkSmartPointer<vtkLight> MakeLight(const Light& light);

// Replaces the renderer's lights with the scene's and turns off VTK's automatic headlight, which
// a renderer without lights would otherwise create (so "lights": [] means no lights), then gives
// the mapper LightingOf(scene).
void ConfigureLighting(const Scene& scene, vtkRenderer* renderer, vtkCloudVolumeMapper* mapper);

} // namespace cloudvis

#endif
