#include "CloudPathTraceInputs.h"

#include "CloudGpuMemory.h"
#include "CloudPathTrace.h"

#include "CloudLightingPathTraceFS.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPointData.h>
#include <vtkShaderProgram.h>
#include <vtk_glew.h>

#include <vector>

namespace cloudvis
{
std::string PathTraceLightingSource()
{
  return CloudLightingPathTraceFS;
}

bool ExtinctionBoundsTexture::Update(vtkOpenGLRenderWindow* window,
  vtkImageData* bricks,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  const VolumeSources::Numbers now = { double(bricks->GetMTime()) };
  if (this->Sources.Current(now, this->Texture))
  {
    return true;
  }
  auto* majorant = vtkFloatArray::SafeDownCast(bricks->GetPointData()->GetArray("max_extinction"));
  auto* minorant = vtkFloatArray::SafeDownCast(bricks->GetPointData()->GetArray("min_extinction"));
  int count[3];
  bricks->GetDimensions(count);
  const vtkIdType total = vtkIdType(count[0]) * count[1] * count[2];
  if (!majorant || !minorant || majorant->GetNumberOfTuples() != total ||
    minorant->GetNumberOfTuples() != total)
  {
    this->Release(window);
    problem = "the occupancy filter produced no extinction bounds per brick";
    return false;
  }
  std::vector<float> bounds(std::size_t(total) * 2);
  for (vtkIdType b = 0; b < total; ++b)
  {
    bounds[std::size_t(b) * 2] = minorant->GetValue(b);
    bounds[std::size_t(b) * 2 + 1] = majorant->GetValue(b);
  }
  this->Texture->SetContext(window);
  problem = budget.AllocateVolume("the extinction bounds texture",
    glm::ivec3(count[0], count[1], count[2]),
    (long long)total * 2 * sizeof(float),
    this->Bytes,
    [&]()
    {
      this->Texture->SetInternalFormat(GL_RG32F);
      this->Texture->SetFormat(GL_RG);
      return this->Texture->Create3DFromRaw(
        count[0], count[1], count[2], 2, VTK_FLOAT, bounds.data());
    });
  if (!problem.empty())
  {
    this->Release(window);
    return false;
  }
  SetSampling(this->Texture, vtkTextureObject::Nearest, vtkTextureObject::ClampToEdge);
  this->Bytes = TextureBytes(this->Texture);
  this->Sources.Take(now);
  return true;
}

void ExtinctionBoundsTexture::Release(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->Sources.Forget();
  this->Bytes = 0;
}

void SetPathTraceUniforms(vtkShaderProgram* program, const PathTraceFrame& frame)
{
  program->SetUniformi("MaxBounces", frame.MaxBounces);
  program->SetUniformi("RouletteBounces", PathTraceUniforms{}.RouletteBounces);
  program->SetUniformi("LightGuidedNextEvents", frame.LightGuidedNextEvents);
  program->SetUniformi("PathTraceSeed", frame.Seed);
  program->SetUniformi("SampleBase", frame.SampleBase);
  program->SetUniformi("SamplesPerFrame", frame.SamplesPerFrame);
  program->SetUniformi("MarchWidth", frame.MarchWidth);
}

} // namespace cloudvis
