#include "CloudExternalDepthTexture.h"

#include "CloudGpuMemory.h"

#include <vtkOpenGLRenderWindow.h>
#include <vtkShaderProgram.h>
#include <vtk_glew.h>

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
  if (this->Texture->GetHandle() && this->Uploaded.GetMTime() > this->Changed.GetMTime())
  {
    return true;
  }
  const OpticalDepthGrid& grid = this->Grid;
  const int layers = grid.Size[2] * grid.Lights;
  GLint largest = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &largest);
  if (grid.Size[0] > largest || grid.Size[1] > largest || layers > largest)
  {
    problem = "the optical depths from outside the field need a 3-D texture of " +
      std::to_string(grid.Size[0]) + " x " + std::to_string(grid.Size[1]) + " x " +
      std::to_string(layers) + " texels (" + std::to_string(grid.Lights) +
      " lights), more than this GPU's " + std::to_string(largest) + " per axis";
    this->Release(window);
    return false;
  }
  this->Texture->SetContext(window);
  problem = budget.Allocate("the optical depths from outside the field",
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
  SetSampling(this->Texture, vtkTextureObject::Linear, vtkTextureObject::ClampToEdge);
  this->Bytes = TextureBytes(this->Texture);
  this->Uploaded.Modified();
  return true;
}

void ExternalDepthTexture::Release(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->Bytes = 0;
}

void BindExternalDepths(vtkShaderProgram* program, vtkTextureObject* external, int unreadUnit)
{
  program->SetUniformi("ExternalDepthTexture", external ? external->GetTextureUnit() : unreadUnit);
}

} // namespace cloudvis
