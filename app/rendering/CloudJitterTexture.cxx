#include "CloudJitterTexture.h"

#include "CloudBlueNoise.h"
#include "CloudGpuMemory.h"

#include <vtkOpenGLRenderWindow.h>

#include <vector>

namespace cloudvis
{

bool JitterTexture::Update(vtkOpenGLRenderWindow* window,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  if (this->Texture->GetHandle())
  {
    return true;
  }
  const std::string what = "the jitter texture";
  const long long bytes = (long long)Size * Size * sizeof(float);
  problem = budget.Reserve(what, bytes, 0);
  if (!problem.empty())
  {
    return false;
  }
  std::vector<float> mask = BlueNoiseMask(Size);
  this->Texture->SetContext(window);
  const bool created = this->Texture->Create2DFromRaw(Size, Size, 1, VTK_FLOAT, mask.data());
  problem = budget.Allocated(what, bytes, 0);
  if (!created || !problem.empty())
  {
    problem = problem.empty() ? "the GPU could not create " + what : problem;
    this->Release(window);
    return false;
  }
  this->Texture->SetWrapS(vtkTextureObject::Repeat);
  this->Texture->SetWrapT(vtkTextureObject::Repeat);
  this->Texture->SetMinificationFilter(vtkTextureObject::Nearest);
  this->Texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  this->Bytes = TextureBytes(this->Texture);
  return true;
}

void JitterTexture::Release(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->Bytes = 0;
}

} // namespace cloudvis
