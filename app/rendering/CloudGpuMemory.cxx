#include "CloudGpuMemory.h"

#include "CloudFieldGeometry.h"

#include <vtkOpenGLRenderWindow.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>

namespace cloudvis
{
namespace
{
// Reads and clears GL's error flags (a bounded number: a lost context may keep reporting).
GLenum TakeError()
{
  GLenum first = GL_NO_ERROR;
  for (int i = 0; i < 16; ++i)
  {
    const GLenum error = glGetError();
    if (error == GL_NO_ERROR)
    {
      break;
    }
    first = first == GL_NO_ERROR ? error : first;
  }
  return first;
}
}

long long FreeGpuMemory(vtkOpenGLRenderWindow* window)
{
  window->MakeCurrent();
  GLint kib[4] = { -1, -1, -1, -1 };
  if (GLEW_NVX_gpu_memory_info)
  {
    glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, kib);
  }
  else if (GLEW_ATI_meminfo)
  {
    glGetIntegerv(GL_TEXTURE_FREE_MEMORY_ATI, kib); // total free in the pool, largest block, ...
  }
  return kib[0] >= 0 ? 1024LL * kib[0] : -1;
}

GpuMemoryBudget::GpuMemoryBudget(vtkOpenGLRenderWindow* window, long long limit, long long held)
  : Window(window)
  , Limit(limit)
  , Held(held)
{
}

std::string GpuMemoryBudget::Allocate(const std::string& what,
  long long bytes,
  long long released,
  const std::function<bool()>& create)
{
  const long long others = this->Held - released; // what the mapper keeps besides
  if (this->Limit > 0 && others + bytes > this->Limit)
  {
    this->OutOfMemory = true;
    return what + " needs " + FormatBytes(double(bytes)) +
      (others > 0 ? "; with the " + FormatBytes(double(others)) + " the mapper holds, that is"
                  : ",") +
      " more than its GPU memory limit of " + FormatBytes(double(this->Limit)) +
      " (MaximumGPUMemory)";
  }
  const long long free = FreeGpuMemory(this->Window);
  if (free >= 0 && bytes - released > free)
  {
    this->OutOfMemory = true;
    return what + " needs " + FormatBytes(double(bytes)) + " of GPU memory; the GPU reports " +
      FormatBytes(double(free)) + " free";
  }
  TakeError(); // earlier errors are not this allocation's
  const bool created = create();
  const GLenum error = TakeError();
  if (error == GL_OUT_OF_MEMORY)
  {
    this->OutOfMemory = true;
    return "the GPU could not allocate " + FormatBytes(double(bytes)) + " for " + what +
      " (GL_OUT_OF_MEMORY)";
  }
  if (error != GL_NO_ERROR || !created)
  {
    return "the GPU refused " + what + " (" + FormatBytes(double(bytes)) + ", GL error " +
      std::to_string(error) + ")";
  }
  this->Held += bytes - released;
  return {};
}

std::string GpuMemoryBudget::AllocateVolume(const std::string& what,
  const glm::ivec3& texels,
  long long bytes,
  long long released,
  const std::function<bool()>& create,
  const std::string& advice)
{
  const int largest = vtkTextureObject::GetMaximumTextureSize3D(this->Window);
  if (texels.x > largest || texels.y > largest || texels.z > largest)
  {
    return what + " needs a 3-D texture of " + std::to_string(texels.x) + " x " +
      std::to_string(texels.y) + " x " + std::to_string(texels.z) +
      " texels; this GPU's 3-D textures hold at most " + std::to_string(largest) + " per axis" +
      advice;
  }
  return this->Allocate(what, bytes, released, create);
}

long long FinishVolumeTexture(vtkTextureObject* texture)
{
  SetSampling(texture, vtkTextureObject::Linear, vtkTextureObject::ClampToEdge);
  return TextureBytes(texture);
}

long long TextureBytes(vtkTextureObject* texture)
{
  if (!texture->GetHandle())
  {
    return 0;
  }
  const GLenum target = texture->GetTarget();
  GLint bits = 0;
  texture->Activate();
  for (GLenum component : { GL_TEXTURE_RED_SIZE,
         GL_TEXTURE_GREEN_SIZE,
         GL_TEXTURE_BLUE_SIZE,
         GL_TEXTURE_ALPHA_SIZE,
         GL_TEXTURE_DEPTH_SIZE,
         GL_TEXTURE_STENCIL_SIZE })
  {
    GLint size = 0;
    glGetTexLevelParameteriv(target, 0, component, &size);
    bits += size;
  }
  texture->Deactivate();
  const long long texels = (long long)texture->GetWidth() * std::max(1u, texture->GetHeight()) *
    std::max(1u, texture->GetDepth());
  return texels * ((bits + 7) / 8);
}

void SetSampling(vtkTextureObject* texture, int filter, int wrap)
{
  texture->SetMinificationFilter(filter);
  texture->SetMagnificationFilter(filter);
  texture->SetWrapS(wrap);
  texture->SetWrapT(wrap);
  texture->SetWrapR(wrap);
}

} // namespace cloudvis
