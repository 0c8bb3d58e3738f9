// The matched pair of volume mappers (SupportMappers.h).
#include "SupportMappers.h"

namespace cloudvis
{
namespace support
{

vtkSmartPointer<vtkCloudVolumeMapper> MatchedCloudMapper(double step)
{
  auto mapper = vtkSmartPointer<vtkCloudVolumeMapper>::New();
  mapper->SetSampleDistance(step);
  mapper->JitterOff();
  return mapper;
}

vtkSmartPointer<vtkGPUVolumeRayCastMapper> MatchedVtkMapper(double step)
{
  auto mapper = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
  mapper->SetSampleDistance(step);
  mapper->AutoAdjustSampleDistancesOff();
  mapper->LockSampleDistanceToInputSpacingOff();
  mapper->SetUseJittering(0);
  mapper->SetBlendModeToComposite();
  return mapper;
}

} // namespace support
} // namespace cloudvis
