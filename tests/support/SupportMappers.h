// vtkCloudVolumeMapper and its VTK peer, vtkGPUVolumeRayCastMapper, set up to march the same
// way: the same sample distance, no jitter, no automatic change of the step, composite
// blending. Given the same input, volume property and camera, their emission-absorption images
// differ only by the integration details both document, so the render tests compare them and
// bench/ times them against each other. Also a float field in the other scalar types the mapper
// uploads natively (unsigned char, unsigned short), for tests and benchmarks of those textures.
#ifndef cloudvis_SupportMappers_h
#define cloudvis_SupportMappers_h

#include "vtkCloudVolumeMapper.h"

#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkSmartPointer.h>

namespace cloudvis
{
namespace support
{

// cloudvis's mapper marching every `step` world units, without jitter.
vtkSmartPointer<vtkCloudVolumeMapper> MatchedCloudMapper(double step);

// VTK's GPU ray caster marching like MatchedCloudMapper(step).
vtkSmartPointer<vtkGPUVolumeRayCastMapper> MatchedVtkMapper(double step);

// The largest value of a scalar type, which a density of 1 becomes in QuantizedField: 255 for
// VTK_UNSIGNED_CHAR, 65535 for VTK_UNSIGNED_SHORT, 1 for VTK_FLOAT.
double FullScale(int scalarType);

// A float field's densities in `scalarType`: round(clamp(v, 0, 1) * FullScale), with the same
// geometry (extent, origin, spacing, direction). VTK_FLOAT gives a copy of the field.
vtkSmartPointer<vtkImageData> QuantizedField(vtkImageData* field, int scalarType);

} // namespace support
} // namespace cloudvis

#endif
