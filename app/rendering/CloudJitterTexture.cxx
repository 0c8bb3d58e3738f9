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
  std::vector<float> mask = BlueNoiseMask(Size);
  this->Texture->SetContext(window);
  problem = budget.Allocate("the jitter texture",
    (long long)Size * Size * sizeof(float),
    0,
    [&]() { return this->Texture->Create2DFromRaw(Size, Size, 1, VTK_FLOAT, mask.data()); });
  if (!problem.empty())
  {
    this->Release(window);
    return false;
  }
  SetSampling(this->Texture, vtkTextureObject::Nearest, vtkTextureObject::Repeat);
  this->Bytes = TextureBytes(this->Texture);
  return true;
}

void JitterTexture::Release(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->Bytes = 0;
}

} // namespace cloudvis
