#include "CloudTemporalHistory.h"

#include "CloudGpuMemory.h"

#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtk_glew.h>

namespace cloudvis
{

bool TemporalHistory::Resize(vtkOpenGLRenderWindow* window,
  int width,
  int height,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  if (this->Size[0] == width && this->Size[1] == height && this->Color[0]->GetHandle())
  {
    return true;
  }
  // Half floats hold the displayed radiance (at most a few units) to 11 significant bits, far
  // below what an 8-bit screen shows; the depth (and the age beside it) keep a float's precision.
  problem = budget.Allocate("the temporal history targets",
    2LL * width * height * (4 * 2 + 2 * sizeof(float)),
    this->Bytes,
    [&]()
    {
      bool allocated = true;
      for (int i = 0; i < 2; ++i)
      {
        this->Color[i]->SetContext(window);
        this->Color[i]->SetInternalFormat(GL_RGBA16F);
        this->Color[i]->SetFormat(GL_RGBA);
        allocated = this->Color[i]->Allocate2D(width, height, 4, VTK_FLOAT) && allocated;
        SetSampling(this->Color[i], vtkTextureObject::Nearest, vtkTextureObject::ClampToEdge);
        this->Depth[i]->SetContext(window);
        this->Depth[i]->SetInternalFormat(GL_RG32F);
        this->Depth[i]->SetFormat(GL_RG);
        allocated = this->Depth[i]->Allocate2D(width, height, 2, VTK_FLOAT) && allocated;
        SetSampling(this->Depth[i], vtkTextureObject::Nearest, vtkTextureObject::ClampToEdge);
      }
      return allocated;
    });
  if (!problem.empty())
  {
    this->Release(window);
    return false;
  }
  this->Bytes = 0;
  for (int i = 0; i < 2; ++i)
  {
    this->Bytes += TextureBytes(this->Color[i]) + TextureBytes(this->Depth[i]);
  }
  this->Framebuffer->SetContext(window);
  this->Size[0] = width;
  this->Size[1] = height;
  this->HasImage = false;
  return true;
}

void TemporalHistory::BeginFrame(const std::vector<double>& content,
  bool reproject,
  const glm::dmat4& deviceToLocal)
{
  this->Reproject = reproject && this->HasImage && content == this->Content;
  if (!this->Reproject)
  {
    this->Sequence = 0;
  }
  this->Content = content;
  this->DeviceToLocal = deviceToLocal;
}

bool TemporalHistory::BindNext(vtkOpenGLRenderWindow* window)
{
  const int next = 1 - this->Last;
  window->GetState()->PushFramebufferBindings();
  this->Framebuffer->Bind();
  this->Framebuffer->AddColorAttachment(0, this->Color[next]);
  this->Framebuffer->AddColorAttachment(1, this->Depth[next]);
  this->Framebuffer->ActivateDrawBuffers(2);
  if (!this->Framebuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER))
  {
    this->Framebuffer->RemoveColorAttachments(2);
    window->GetState()->PopFramebufferBindings();
    return false;
  }
  return true;
}

void TemporalHistory::FinishNext(vtkOpenGLRenderWindow* window)
{
  this->Framebuffer->RemoveColorAttachments(2);
  window->GetState()->PopFramebufferBindings();
  this->Last = 1 - this->Last;
  this->HasImage = true;
  this->Sequence += this->Reproject ? 1 : 0;
  this->LastDeviceToLocal = this->DeviceToLocal;
}

void TemporalHistory::Release(vtkWindow* window)
{
  for (int i = 0; i < 2; ++i)
  {
    this->Color[i]->ReleaseGraphicsResources(window);
    this->Depth[i]->ReleaseGraphicsResources(window);
  }
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->Size[0] = this->Size[1] = 0;
  this->Bytes = 0;
  this->HasImage = false;
  this->Reproject = false;
  this->Content.clear();
}

} // namespace cloudvis
