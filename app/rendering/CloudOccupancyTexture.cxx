#include "CloudOccupancyTexture.h"

#include "CloudGpuMemory.h"
#include "CloudTransferTable.h"

#include <vtkDataArray.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

namespace cloudvis
{

bool OccupancyTexture::Update(vtkOpenGLRenderWindow* window,
  vtkImageData* input,
  vtkDataArray* scalars,
  vtkMTimeType densityTime,
  const TransferTable& table,
  vtkMTimeType tableTime,
  int brickSize,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  if (this->DensityTime != densityTime)
  {
    this->FilterInput->Initialize();
    this->FilterInput->SetDimensions(input->GetDimensions());
    this->FilterInput->SetOrigin(input->GetOrigin());
    this->FilterInput->SetSpacing(input->GetSpacing());
    this->FilterInput->GetPointData()->SetScalars(scalars);
    this->Filter->SetInputData(this->FilterInput);
    this->DensityTime = densityTime;
  }
  if (this->TableTime != tableTime)
  {
    this->Filter->SetTransferTable(table);
    this->TableTime = tableTime;
  }
  // The filter re-executes only when its input, table or brick size changed.
  this->Filter->SetBrickSize(brickSize);
  this->Filter->Update();
  vtkImageData* occupancy = this->Filter->GetOutput();
  const VolumeSources::Numbers now = { double(occupancy->GetMTime()) };
  if (this->Sources.Current(now, this->Texture))
  {
    return true;
  }
  const auto fail = [&](const std::string& message)
  {
    this->Release(window);
    problem = message;
    return false;
  };
  auto* distance =
    vtkUnsignedCharArray::SafeDownCast(occupancy->GetPointData()->GetArray("empty_distance"));
  if (!distance)
  {
    return fail("the occupancy filter produced no empty_distance array");
  }
  int bricks[3];
  occupancy->GetDimensions(bricks);
  const long long bytes = (long long)bricks[0] * bricks[1] * bricks[2];
  this->Texture->SetContext(window);
  const std::string allocationProblem = budget.AllocateVolume("the occupancy texture",
    glm::ivec3(bricks[0], bricks[1], bricks[2]),
    bytes,
    this->Bytes,
    [&]()
    {
      return this->Texture->Create3DFromRaw(
        bricks[0], bricks[1], bricks[2], 1, VTK_UNSIGNED_CHAR, distance->GetPointer(0));
    });
  if (!allocationProblem.empty())
  {
    return fail(allocationProblem);
  }
  SetSampling(this->Texture, vtkTextureObject::Nearest, vtkTextureObject::ClampToEdge);
  std::copy(bricks, bricks + 3, this->BrickCount);
  const vtkIdType count = distance->GetNumberOfValues();
  vtkIdType occupied = 0;
  for (vtkIdType b = 0; b < count; ++b)
  {
    occupied += distance->GetValue(b) == 0;
  }
  this->OccupiedFraction = count ? double(occupied) / double(count) : 0.0;
  this->Bytes = TextureBytes(this->Texture);
  this->Sources.Take(now);
  return true;
}

void OccupancyTexture::Release(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->Sources.Forget();
  this->Bytes = 0;
}

} // namespace cloudvis
