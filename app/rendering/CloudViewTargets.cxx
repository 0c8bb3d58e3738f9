#include "CloudViewTargets.h"

#include "CloudGpuMemory.h"

#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtk_glew.h>

namespace cloudvis
{

bool ViewTargets::Resize(vtkOpenGLRenderWindow* window,
  int viewportWidth,
  int viewportHeight,
  int marchWidth,
  int marchHeight,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  if (this->ViewportSize[0] != viewportWidth || this->ViewportSize[1] != viewportHeight ||
    !this->Depth->GetHandle())
  {
    this->Depth->SetContext(window);
    problem = budget.Allocate("the depth target",
      (long long)viewportWidth * viewportHeight * sizeof(float),
      this->DepthBytes,
      [&]() {
        return this->Depth->AllocateDepth(viewportWidth, viewportHeight, vtkTextureObject::Float32);
      });
    if (!problem.empty())
    {
      this->Release(window);
      return false;
    }
    SetSampling(this->Depth, vtkTextureObject::Nearest, vtkTextureObject::ClampToEdge);
    this->DepthBytes = TextureBytes(this->Depth);
    this->ViewportSize[0] = viewportWidth;
    this->ViewportSize[1] = viewportHeight;
  }
  if (this->MarchSize[0] != marchWidth || this->MarchSize[1] != marchHeight ||
    !this->ColorTexture->GetHandle())
  {
    // The moment target has the march's size too: freed first, and no longer counted, so that
    // the new targets and the moment target at the new size (AllocateMoments) are checked
    // against what the mapper really holds.
    budget.Release(this->MomentBytes);
    this->ReleaseMoments(window);
    problem = budget.Allocate("the march targets",
      2LL * marchWidth * marchHeight * 4 * sizeof(float),
      this->TargetBytes,
      [&]()
      {
        bool allocated = true;
        for (vtkTextureObject* target : { this->ColorTexture.Get(), this->CountTexture.Get() })
        {
          target->SetContext(window);
          target->SetInternalFormat(GL_RGBA32F);
          target->SetFormat(GL_RGBA);
          allocated = target->Allocate2D(marchWidth, marchHeight, 4, VTK_FLOAT) && allocated;
          SetSampling(target, vtkTextureObject::Nearest, vtkTextureObject::ClampToEdge);
        }
        return allocated;
      });
    if (!problem.empty())
    {
      this->Release(window);
      return false;
    }
    this->TargetBytes = TextureBytes(this->ColorTexture) + TextureBytes(this->CountTexture);
    this->Framebuffer->SetContext(window);
    this->MarchSize[0] = marchWidth;
    this->MarchSize[1] = marchHeight;
    this->AccumulatedFrames = 0;
  }
  return true;
}

void ViewTargets::CopyDepth(const int viewport[4])
{
  this->Depth->CopyFromFrameBuffer(viewport[0], viewport[1], 0, 0, viewport[2], viewport[3]);
}

void ViewTargets::Continue(const std::vector<double>& signature)
{
  if (signature != this->Signature)
  {
    this->Signature = signature;
    this->AccumulatedFrames = 0;
  }
}

bool ViewTargets::AllocateMoments(vtkOpenGLRenderWindow* window,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  if (this->MomentTexture->GetHandle())
  {
    return true;
  }
  problem = budget.Allocate("the moment target",
    (long long)this->MarchSize[0] * this->MarchSize[1] * 4 * sizeof(float),
    this->MomentBytes,
    [&]()
    {
      vtkTextureObject* target = this->MomentTexture;
      target->SetContext(window);
      target->SetInternalFormat(GL_RGBA32F);
      target->SetFormat(GL_RGBA);
      const bool allocated =
        target->Allocate2D(this->MarchSize[0], this->MarchSize[1], 4, VTK_FLOAT);
      SetSampling(target, vtkTextureObject::Nearest, vtkTextureObject::ClampToEdge);
      return allocated;
    });
  if (!problem.empty())
  {
    this->MomentTexture->ReleaseGraphicsResources(window);
    this->MomentBytes = 0;
    return false;
  }
  this->MomentBytes = TextureBytes(this->MomentTexture);
  return true;
}

void ViewTargets::ReleaseMoments(vtkWindow* window)
{
  this->MomentTexture->ReleaseGraphicsResources(window);
  this->MomentBytes = 0;
}

bool ViewTargets::BindTargets(vtkOpenGLRenderWindow* window, bool moments)
{
  window->GetState()->PushFramebufferBindings();
  this->Framebuffer->Bind();
  this->Framebuffer->AddColorAttachment(0, this->ColorTexture);
  this->Framebuffer->AddColorAttachment(1, this->CountTexture);
  this->AttachedTargets = 2;
  if (moments)
  {
    this->Framebuffer->AddColorAttachment(2, this->MomentTexture);
    this->AttachedTargets = 3;
  }
  this->Framebuffer->ActivateDrawBuffers(this->AttachedTargets);
  if (!this->Framebuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER))
  {
    this->UnbindTargets(window);
    return false;
  }
  return true;
}

void ViewTargets::UnbindTargets(vtkOpenGLRenderWindow* window)
{
  this->Framebuffer->RemoveColorAttachments(this->AttachedTargets);
  window->GetState()->PopFramebufferBindings();
}

bool ViewTargets::Read(vtkOpenGLRenderWindow* window,
  Target target,
  std::vector<float>& values,
  int& width,
  int& height)
{
  if (!this->ColorTexture->GetHandle() || !this->GetTarget(target)->GetHandle() ||
    this->AccumulatedFrames < 1)
  {
    return false;
  }
  window->MakeCurrent();
  vtkOpenGLState* state = window->GetState();
  width = this->MarchSize[0];
  height = this->MarchSize[1];
  values.resize(size_t(width) * height * 4);
  state->PushFramebufferBindings();
  this->Framebuffer->Bind();
  this->Framebuffer->AddColorAttachment(0, this->GetTarget(target));
  this->Framebuffer->ActivateReadBuffer(0);
  state->vtkglPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, values.data());
  this->Framebuffer->RemoveColorAttachments(1);
  state->PopFramebufferBindings();
  const float weight = 1.0f / float(this->AccumulatedFrames); // the sum to the mean
  for (float& v : values)
  {
    v *= weight;
  }
  return true;
}

void ViewTargets::Release(vtkWindow* window)
{
  this->Depth->ReleaseGraphicsResources(window);
  this->ColorTexture->ReleaseGraphicsResources(window);
  this->CountTexture->ReleaseGraphicsResources(window);
  this->MomentTexture->ReleaseGraphicsResources(window);
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->History.Release(window);
  this->ViewportSize[0] = this->ViewportSize[1] = 0;
  this->MarchSize[0] = this->MarchSize[1] = 0;
  this->AccumulatedFrames = 0;
  this->DepthBytes = this->TargetBytes = this->MomentBytes = 0;
}

} // namespace cloudvis
