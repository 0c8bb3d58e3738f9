#include "CloudDensityTexture.h"

#include "CloudFieldGeometry.h"
#include "CloudGpuMemory.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkTimeStamp.h>
#include <vtk_glew.h>

#include <vector>

namespace cloudvis
{

bool DensityTexture::Update(vtkOpenGLRenderWindow* window,
  vtkImageData* input,
  vtkDataArray* scalars,
  bool halfFloat,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  const VolumeSources::Numbers now = {
    IdentityOf(input), double(input->GetMTime()), double(scalars->GetMTime()), double(halfFloat)
  };
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
  const std::string valueProblem = ValidateDensityValues(scalars);
  if (!valueProblem.empty())
  {
    return fail(valueProblem);
  }
  int dimensions[3];
  input->GetDimensions(dimensions);
  const DensityTexels texels = DensityTexelsOf(scalars, halfFloat);
  const long long voxels = (long long)dimensions[0] * dimensions[1] * dimensions[2];
  const std::string what = "the density texture (" + std::to_string(dimensions[0]) + " x " +
    std::to_string(dimensions[1]) + " x " + std::to_string(dimensions[2]) + " voxels of " +
    TexelFormatName(texels.Format) + ")";
  const long long bytes = voxels * BytesPerTexel(texels.Format);
  this->Texture->SetContext(window);
  this->Texture->ResetFormatAndType();
  const std::string allocationProblem = budget.AllocateVolume(what,
    glm::ivec3(dimensions[0], dimensions[1], dimensions[2]),
    bytes,
    this->Bytes,
    [&]()
    {
      if (texels.Format != TexelFormat::Float16)
      {
        // The array's own type: its default internal formats are R8, R16 and R32F.
        return this->Texture->Create3DFromRaw(dimensions[0],
          dimensions[1],
          dimensions[2],
          1,
          scalars->GetDataType(),
          scalars->GetVoidPointer(0));
      }
      const auto* values = static_cast<const float*>(scalars->GetVoidPointer(0));
      std::vector<std::uint16_t> halves(static_cast<std::size_t>(voxels));
      for (std::size_t i = 0; i < halves.size(); ++i)
      {
        halves[i] = HalfFromFloat(values[i] / texels.Scale);
      }
      this->Texture->SetInternalFormat(GL_R16F);
      this->Texture->SetFormat(GL_RED);
      this->Texture->SetDataType(GL_HALF_FLOAT);
      return this->Texture->Create3DFromRaw(
        dimensions[0], dimensions[1], dimensions[2], 1, VTK_FLOAT, halves.data());
    });
  if (!allocationProblem.empty())
  {
    return fail(allocationProblem);
  }
  this->Texels = texels;
  this->Texels.Values = nullptr;
  this->Bytes = FinishVolumeTexture(this->Texture);
  this->Sources.Take(now);
  vtkTimeStamp uploaded;
  uploaded.Modified();
  this->UploadTime = uploaded.GetMTime();
  return true;
}

void DensityTexture::Release(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->Sources.Forget();
  this->UploadTime = 0;
  this->Bytes = 0;
}

} // namespace cloudvis
