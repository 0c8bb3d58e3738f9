// vtkCloudVolumeMapper and its VTK peer, vtkGPUVolumeRayCastMapper, set up to march the same
// way: the same sample distance, no jitter, no automatic change of the step, composite
// blending. Given the same input, volume property and camera, their emission-absorption images
// differ only by the integration details both document, so the render tests compare them and
// bench/ times them against each other.
#ifndef cloudvis_SupportMappers_h
#define cloudvis_SupportMappers_h

#include "vtkCloudVolumeMapper.h"

#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkSmartPointer.h>

namespace cloudvis
{
namespace support
{

// cloudvis's mapper marching every `step` world units, without jitter.
vtkSmartPointer<vtkCloudVolumeMapper> MatchedCloudMapper(double step);

// VTK's GPU ray caster marching like MatchedCloudMapper(step).
vtkSmartPointer<vtkGPUVolumeRayCastMapper> MatchedVtkMapper(double step);

} // namespace support
} // namespace cloudvis

#endif
