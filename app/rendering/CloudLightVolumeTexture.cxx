#include "CloudLightVolumeTexture.h"

#include "CloudGpuMemory.h"
#include "CloudLightVolumes.h"
#include "CloudMarchShader.h"
#include "CloudMarchUniforms.h"

#include "CloudLightVolumeFS.h"

#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkShaderProgram.h>
#include <vtk_glew.h>

#include <glm/gtc/type_ptr.hpp>

#include <string>

namespace cloudvis
{

namespace
{
// What the volumes depend on, as numbers: when one changes they are computed again. The lights
// apart from the rest (the field, the table, the march and the geometry), since a light that
// follows the camera changes them every frame while the rest holds.
std::vector<double> InputSignatureOf(const MarchUniforms& u,
  const LightVolumeTexture::Inputs& inputs)
{
  std::vector<double> s = { inputs.DensityTime,
    inputs.TableTime,
    double(inputs.BrickSize),
    double(inputs.SkipEmptySpace),
    double(u.ExtinctionUnit),
    double(u.Step),
    double(u.LongestRaySamples),
    double(u.Dimensions.x),
    double(u.Dimensions.y),
    double(u.Dimensions.z) };
  s.insert(s.end(), glm::value_ptr(u.IndexToLocal), glm::value_ptr(u.IndexToLocal) + 16);
  s.insert(s.end(), glm::value_ptr(u.LocalToIndex), glm::value_ptr(u.LocalToIndex) + 9);
  return s;
}

std::vector<double> LightSignatureOf(const MarchUniforms& u)
{
  std::vector<double> s;
  for (const LocalLight& light : u.Lights)
  {
    s.push_back(light.Positional ? 1.0 : 0.0);
    s.insert(s.end(), glm::value_ptr(light.Position), glm::value_ptr(light.Position) + 3);
    s.insert(
      s.end(), glm::value_ptr(light.IndexDirection), glm::value_ptr(light.IndexDirection) + 3);
  }
  return s;
}
}

LightVolumeTexture::LightVolumeTexture() = default;
LightVolumeTexture::~LightVolumeTexture() = default;

bool LightVolumeTexture::Update(vtkOpenGLRenderWindow* window,
  const MarchUniforms& u,
  const Inputs& inputs,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  VolumeSources::Numbers inputNow = InputSignatureOf(u, inputs);
  VolumeSources::Numbers lightsNow = LightSignatureOf(u);
  if (this->InputSources.Current(inputNow, this->Texture) &&
    this->LightSources.Current(lightsNow, this->Texture))
  {
    return true;
  }
  const glm::ivec3 size = LightVolumeSize(u.Dimensions);
  const int lights = int(u.Lights.size());
  const int layers = size.z * std::max(lights, 1);
  if (!this->Texture->GetHandle() || size.x != this->Size[0] || size.y != this->Size[1] ||
    size.z != this->Size[2] || lights != this->Lights)
  {
    this->Texture->SetContext(window);
    problem = budget.AllocateVolume(
      "the light-volume texture (" + std::to_string(lights) + " lights)",
      glm::ivec3(size.x, size.y, layers),
      4LL * size.x * size.y * layers,
      this->Bytes,
      [&]() { return this->Texture->Allocate3D(size.x, size.y, layers, 1, VTK_FLOAT); },
      ": use render.march.transmittance \"nested\" or fewer lights");
    if (!problem.empty())
    {
      this->Release(window);
      return false;
    }
    this->Bytes = FinishVolumeTexture(this->Texture);
    this->Size[0] = size.x;
    this->Size[1] = size.y;
    this->Size[2] = size.z;
    this->Lights = lights;
  }
  if (!this->Compute(window, u, inputs, problem))
  {
    this->InputSources.Forget();
    this->LightSources.Forget();
    return false;
  }
  this->InputSources.Take(std::move(inputNow));
  this->LightSources.Take(std::move(lightsNow));
  ++this->ComputeCount;
  return true;
}

bool LightVolumeTexture::OnlyLightsChanged(const MarchUniforms& u, const Inputs& inputs) const
{
  return this->InputSources.Current(InputSignatureOf(u, inputs), this->Texture) &&
    !this->LightSources.Current(LightSignatureOf(u), this->Texture);
}

bool LightVolumeTexture::Compute(vtkOpenGLRenderWindow* window,
  const MarchUniforms& u,
  const Inputs& inputs,
  std::string& problem)
{
  vtkShaderProgram* program = this->Pass.Begin(window,
    LightVolumeMarch(u),
    inputs,
    { CloudLightVolumeFS, nullptr, nullptr },
    "light-volume",
    problem);
  if (!program)
  {
    return false;
  }
  window->GetState()->vtkglViewport(0, 0, this->Size[0], this->Size[1]);
  const float size[3] = { float(this->Size[0]), float(this->Size[1]), float(this->Size[2]) };
  program->SetUniform3f("LightVolumeSize", size);

  // One layer of the texture at a time is the framebuffer's colour attachment.
  bool complete = true;
  for (int light = 0; light < this->Lights && complete; ++light)
  {
    program->SetUniformi("LightVolumeLight", light);
    for (int k = 0; k < this->Size[2]; ++k)
    {
      glFramebufferTextureLayer(GL_FRAMEBUFFER,
        GL_COLOR_ATTACHMENT0,
        this->Texture->GetHandle(),
        0,
        light * this->Size[2] + k);
      if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      {
        complete = false;
        break;
      }
      program->SetUniformf("LightVolumeSlice", float(k));
      this->Pass.Quad().Render();
    }
  }
  this->Pass.End();
  if (!complete)
  {
    problem = "the light volumes cannot be rendered into on this GPU (incomplete framebuffer)";
  }
  return complete;
}

void LightVolumeTexture::Activate(vtkShaderProgram* march)
{
  this->Texture->Activate();
  march->SetUniformi("LightVolumeTexture", this->Texture->GetTextureUnit());
  const float size[3] = { float(this->Size[0]), float(this->Size[1]), float(this->Size[2]) };
  march->SetUniform3f("LightVolumeSize", size);
  march->SetUniformf("LightVolumeCount", float(std::max(this->Lights, 1)));
}

void LightVolumeTexture::Deactivate()
{
  this->Texture->Deactivate();
}

void LightVolumeTexture::Release(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->Pass.Release();
  this->InputSources.Forget();
  this->LightSources.Forget();
  this->Bytes = 0;
  this->Lights = 0;
}

} // namespace cloudvis
