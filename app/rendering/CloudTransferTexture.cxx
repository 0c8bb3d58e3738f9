#include "CloudTransferTexture.h"

#include "CloudGpuMemory.h"

#include <vtkOpenGLRenderWindow.h>
#include <vtkTimeStamp.h>
#include <vtkVolumeProperty.h>

namespace cloudvis
{

bool TransferTexture::Update(vtkOpenGLRenderWindow* window,
  vtkVolumeProperty* property,
  double extinctionScale,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  if (this->BuiltFrom == property && this->PropertyTime >= property->GetMTime() &&
    this->ExtinctionScale == extinctionScale && this->Texture->GetHandle())
  {
    return true;
  }
  const auto fail = [&](const std::string& message)
  {
    this->Release(window);
    problem = message;
    return false;
  };
  std::string tableProblem;
  TransferTable table = TransferTableOf(property, extinctionScale, tableProblem);
  if (!tableProblem.empty())
  {
    return fail(tableProblem);
  }
  const long long bytes = (long long)table.Size * 4 * sizeof(float);
  this->Texture->SetContext(window);
  const std::string allocationProblem = budget.Allocate("the transfer-function texture",
    bytes,
    this->Bytes,
    [&]() { return this->Texture->Create1DFromRaw(table.Size, 4, VTK_FLOAT, table.RGBA.data()); });
  if (!allocationProblem.empty())
  {
    return fail(allocationProblem);
  }
  SetSampling(this->Texture, vtkTextureObject::Linear, vtkTextureObject::ClampToEdge);
  this->Table = std::move(table);
  this->Bytes = TextureBytes(this->Texture);
  this->BuiltFrom = property;
  this->PropertyTime = property->GetMTime();
  this->ExtinctionScale = extinctionScale;
  vtkTimeStamp built;
  built.Modified();
  this->TableTime = built.GetMTime();
  return true;
}

void TransferTexture::Release(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->BuiltFrom = nullptr;
  this->PropertyTime = this->TableTime = 0;
  this->ExtinctionScale = -1.0;
  this->Bytes = 0;
}

} // namespace cloudvis
