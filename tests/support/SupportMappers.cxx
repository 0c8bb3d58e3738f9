// The matched pair of volume mappers (SupportMappers.h).
#include "SupportMappers.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>

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

double FullScale(int scalarType)
{
  switch (scalarType)
  {
    case VTK_UNSIGNED_CHAR:
      return 255.0;
    case VTK_UNSIGNED_SHORT:
      return 65535.0;
    default:
      return 1.0;
  }
}

vtkSmartPointer<vtkImageData> QuantizedField(vtkImageData* field, int scalarType)
{
  auto quantized = vtkSmartPointer<vtkImageData>::New();
  quantized->CopyStructure(field);
  vtkDataArray* values = field->GetPointData()->GetScalars();
  vtkSmartPointer<vtkDataArray> converted =
    vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(scalarType));
  converted->SetName(values->GetName());
  converted->SetNumberOfTuples(values->GetNumberOfTuples());
  const double scale = FullScale(scalarType);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    const double v = values->GetComponent(i, 0);
    converted->SetComponent(
      i, 0, scalarType == VTK_FLOAT ? v : std::round(std::min(1.0, std::max(0.0, v)) * scale));
  }
  quantized->GetPointData()->SetScalars(converted);
  return quantized;
}

} // namespace support
} // namespace cloudvis
