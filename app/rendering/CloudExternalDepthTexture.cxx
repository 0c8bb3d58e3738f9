#include "CloudExternalDepthTexture.h"

#include "CloudGpuMemory.h"

#include <vtkOpenGLRenderWindow.h>
#include <vtkShaderProgram.h>

namespace cloudvis
{

void ExternalDepthTexture::Set(const OpticalDepthGrid& grid)
{
  this->Grid = grid.Empty() ? OpticalDepthGrid() : grid;
  this->Changed.Modified();
}

bool ExternalDepthTexture::Update(vtkOpenGLRenderWindow* window,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  const VolumeSources::Numbers now = { double(this->Changed.GetMTime()) };
  if (this->Sources.Current(now, this->Texture))
  {
    return true;
  }
  const OpticalDepthGrid& grid = this->Grid;
  const int layers = grid.Size[2] * grid.Lights;
  this->Texture->SetContext(window);
  problem = budget.AllocateVolume("the texture of the optical depths from outside the field (" +
      std::to_string(grid.Lights) + " lights)",
    glm::ivec3(grid.Size[0], grid.Size[1], layers),
    4LL * grid.Size[0] * grid.Size[1] * layers,
    this->Bytes,
    [&]()
    {
      return this->Texture->Create3DFromRaw(
        grid.Size[0], grid.Size[1], layers, 1, VTK_FLOAT, const_cast<float*>(grid.Depths.data()));
    });
  if (!problem.empty())
  {
    this->Release(window);
    return false;
  }
  this->Bytes = FinishVolumeTexture(this->Texture);
  this->Sources.Take(now);
  this->Uploaded.Modified();
  return true;
}

void ExternalDepthTexture::Release(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->Sources.Forget();
  this->Bytes = 0;
}

void BindExternalDepths(vtkShaderProgram* program, vtkTextureObject* external, int unreadUnit)
{
  program->SetUniformi("ExternalDepthTexture", external ? external->GetTextureUnit() : unreadUnit);
}

} // namespace cloudvis
