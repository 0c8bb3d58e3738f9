// The CPU side of a rendered support::GpuScene: vtkCloudReferenceRenderer (or vtkCloudPathTracer)
// given the very objects the window rendered with, as a user of both would give them: the field,
// the viewport's size, the camera (after the render, which may have moved its clipping range),
// the volume's matrix and property, the renderer's lights, and for cloudvis's mapper its
// lighting property, step and extinction scale. Header only: the camera goes through the
// application's SetReferenceCamera (app/export, cloudvisApp), which the render tests link and
// the support libraries do not.
#ifndef cloudvis_SupportReference_h
#define cloudvis_SupportReference_h

#include "CpuReference.h"
#include "SupportScene.h"
#include "vtkCloudReferenceRenderer.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkImageData.h>

namespace cloudvis
{
namespace support
{

inline void ConfigureReference(vtkCloudReferenceRenderer* reference, GpuScene& scene)
{
  const int* size = scene.Window->GetSize();
  reference->SetInputData(vtkImageData::SafeDownCast(scene.Mapper->GetInput()));
  reference->SetImageSize(size[0], size[1]);
  reference->SetVolumeMatrix(scene.Volume->GetMatrix());
  SetReferenceCamera(reference, scene.Renderer->GetActiveCamera());
  reference->SetVolumeProperty(scene.Volume->GetProperty());
  reference->SetLights(scene.Renderer->GetLights());
  if (auto* cloud = vtkCloudVolumeMapper::SafeDownCast(scene.Mapper))
  {
    reference->SetLightingProperty(cloud->GetLightingProperty());
    reference->SetSampleDistance(cloud->GetSampleDistance());
    reference->SetExtinctionScale(cloud->GetExtinctionScale());
  }
}

} // namespace support
} // namespace cloudvis

#endif
