#include "CloudExternalScatteringTexture.h"

#include "CloudGpuMemory.h"

#include <vtkOpenGLRenderWindow.h>
#include <vtkShaderProgram.h>

namespace cloudvis
{

void ExternalScatteringTexture::Set(const WholeFieldScattering& volume)
{
  this->Volume = volume.Empty() ? WholeFieldScattering() : volume;
  this->Changed.Modified();
}

bool ExternalScatteringTexture::Update(vtkOpenGLRenderWindow* window,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  const VolumeSources::Numbers now = { double(this->Changed.GetMTime()) };
  if (this->Sources.Current(now, this->Fluence))
  {
    return true;
  }
  const ScatteringGrid& grid = this->Volume.Volume;
  const std::size_t texels = std::size_t(grid.Size.x) * grid.Size.y * grid.Size.z;
  if (grid.Fluence.size() != texels || grid.Flux.size() != texels)
  {
    problem = "the multiple-scattering volume of the whole field holds " +
      std::to_string(grid.Fluence.size()) + " fluence and " + std::to_string(grid.Flux.size()) +
      " flux texels, not its size's " + std::to_string(texels);
    this->Release(window);
    return false;
  }
  const long long held = this->Bytes;
  problem = budget.AllocateVolume("the multiple-scattering volume of the whole field",
    grid.Size,
    2 * 16LL * grid.Size.x * grid.Size.y * grid.Size.z,
    held,
    [&]()
    {
      bool made = true;
      for (auto texture : { std::make_pair(this->Fluence.Get(), &grid.Fluence),
             std::make_pair(this->Flux.Get(), &grid.Flux) })
      {
        texture.first->SetContext(window);
        made = made &&
          texture.first->Create3DFromRaw(grid.Size.x,
            grid.Size.y,
            grid.Size.z,
            4,
            VTK_FLOAT,
            const_cast<float*>(&texture.second->front().x));
      }
      return made;
    });
  if (!problem.empty())
  {
    this->Release(window);
    return false;
  }
  this->Bytes = FinishVolumeTexture(this->Fluence) + FinishVolumeTexture(this->Flux);
  this->Sources.Take(now);
  this->Uploaded.Modified();
  return true;
}

void ExternalScatteringTexture::Activate(vtkShaderProgram* march)
{
  this->Fluence->Activate();
  this->Flux->Activate();
  march->SetUniformi("ScatteringVolumeTexture", this->Fluence->GetTextureUnit());
  march->SetUniformi("ScatteringFluxTexture", this->Flux->GetTextureUnit());
}

void ExternalScatteringTexture::Deactivate()
{
  this->Fluence->Deactivate();
  this->Flux->Deactivate();
}

void ExternalScatteringTexture::Release(vtkWindow* window)
{
  this->Fluence->ReleaseGraphicsResources(window);
  this->Flux->ReleaseGraphicsResources(window);
  this->Sources.Forget();
  this->Bytes = 0;
}

} // namespace cloudvis
