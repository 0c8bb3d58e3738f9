#include "CloudDropletPhaseTexture.h"

#include "CloudGpuMemory.h"
#include "CloudLighting.h"

#include <vtkOpenGLRenderWindow.h>

#include <vector>

namespace cloudvis
{

bool DropletPhaseTexture::Update(vtkOpenGLRenderWindow* window,
  const LightingParameters& lighting,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  const DropletPhaseTable* table =
    lighting.Phase == PhaseModel::Droplets ? &DropletPhaseOf(lighting) : nullptr;
  if (this->HasTexture && this->Uploaded == table && this->Texture->GetHandle())
  {
    return true;
  }
  const int width = table ? DropletPhaseTable::NodeCount : 1;
  std::vector<float> texels(size_t(width) * 2 * 3, 0.0f);
  if (table)
  {
    for (int i = 0; i < width; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        texels[3 * size_t(i) + size_t(c)] = table->Phase[size_t(i)][c];
        texels[3 * (size_t(width) + size_t(i)) + size_t(c)] = table->CDF[size_t(i)][c];
      }
    }
  }
  this->Texture->SetContext(window);
  const std::string allocationProblem = budget.Allocate("the droplets' phase texture",
    (long long)texels.size() * (long long)sizeof(float),
    this->Bytes,
    [&]() { return this->Texture->Create2DFromRaw(width, 2, 3, VTK_FLOAT, texels.data()); });
  if (!allocationProblem.empty())
  {
    this->Release(window);
    problem = allocationProblem;
    return false;
  }
  SetSampling(this->Texture, vtkTextureObject::Nearest, vtkTextureObject::ClampToEdge);
  this->Bytes = TextureBytes(this->Texture);
  this->Uploaded = table;
  this->HasTexture = true;
  return true;
}

void DropletPhaseTexture::Release(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->Uploaded = nullptr;
  this->HasTexture = false;
  this->Bytes = 0;
}

} // namespace cloudvis
