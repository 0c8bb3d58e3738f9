#include "CloudVolumePass.h"

#include "CloudExternalDepthTexture.h"
#include "CloudMarchShader.h"
#include "CloudMarchUniforms.h"

#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

namespace cloudvis
{

// The GL state the pass changes, restored when it ends, and the inputs it bound.
struct VolumePass::SavedState
{
  vtkOpenGLState* State;
  vtkOpenGLState::ScopedglViewport Viewport;
  vtkOpenGLState::ScopedglEnableDisable Blend;
  vtkOpenGLState::ScopedglEnableDisable DepthTest;
  vtkOpenGLState::ScopedglEnableDisable Scissor;
  VolumePassInputs Inputs;

  SavedState(vtkOpenGLState* state, const VolumePassInputs& inputs)
    : State(state)
    , Viewport(state)
    , Blend(state, GL_BLEND)
    , DepthTest(state, GL_DEPTH_TEST)
    , Scissor(state, GL_SCISSOR_TEST)
    , Inputs(inputs)
  {
  }
};

VolumePass::VolumePass() = default;
VolumePass::~VolumePass() = default;

vtkShaderProgram* VolumePass::Begin(vtkOpenGLRenderWindow* window,
  const MarchUniforms& u,
  const VolumePassInputs& inputs,
  const VolumePassShaders& shaders,
  const std::string& what,
  std::string& problem)
{
  std::string key = std::to_string(int(u.Lighting.Phase)) + ":";
  for (const LocalLight& light : u.Lights)
  {
    key += light.Positional ? 'P' : 'D';
  }
  if (!this->Pass || key != this->Key)
  {
    this->Pass = std::make_unique<vtkOpenGLQuadHelper>(window,
      shaders.Vertex,
      PassShaderSource(u.Lights, u.Lighting.Phase, shaders.FragmentMain).c_str(),
      shaders.Geometry ? shaders.Geometry : "");
    this->Key = key;
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(this->Pass->Program);
  }
  vtkShaderProgram* program = this->Pass->Program;
  if (!program || !program->GetCompiled())
  {
    problem = "the " + what +
      " shader failed to compile or link (the driver's log is in VTK's error output)";
    return nullptr;
  }

  vtkOpenGLState* state = window->GetState();
  this->Saved = std::make_unique<SavedState>(state, inputs);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);

  for (vtkTextureObject* texture :
    { inputs.Density, inputs.Transfer, inputs.Occupancy, inputs.DropletPhase })
  {
    texture->Activate();
  }
  SetMarchUniforms(program, u);
  program->SetUniformi("DensityTexture", inputs.Density->GetTextureUnit());
  program->SetUniformi("TransferTexture", inputs.Transfer->GetTextureUnit());
  program->SetUniformi("EmptyDistanceTexture", inputs.Occupancy->GetTextureUnit());
  program->SetUniformi("DropletPhaseTexture", inputs.DropletPhase->GetTextureUnit());
  const float brickCount[3] = {
    float(inputs.BrickCount[0]), float(inputs.BrickCount[1]), float(inputs.BrickCount[2])
  };
  program->SetUniform3f("BrickCount", brickCount);
  program->SetUniformf("BrickSize", float(inputs.BrickSize));
  program->SetUniformi("SkipEmptySpace", inputs.SkipEmptySpace ? 1 : 0);
  if (inputs.ExternalDepths)
  {
    inputs.ExternalDepths->Activate();
  }
  BindExternalDepths(program, inputs.ExternalDepths, inputs.Density->GetTextureUnit());

  state->PushFramebufferBindings();
  if (!this->Framebuffer)
  {
    glGenFramebuffers(1, &this->Framebuffer);
  }
  state->vtkglBindFramebuffer(GL_FRAMEBUFFER, this->Framebuffer);
  return program;
}

void VolumePass::End()
{
  glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, 0, 0);
  glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, 0, 0);
  this->Saved->State->PopFramebufferBindings();
  const VolumePassInputs& inputs = this->Saved->Inputs;
  for (vtkTextureObject* texture :
    { inputs.Density, inputs.Transfer, inputs.Occupancy, inputs.DropletPhase })
  {
    texture->Deactivate();
  }
  if (inputs.ExternalDepths)
  {
    inputs.ExternalDepths->Deactivate();
  }
  this->Saved.reset();
}

void VolumePass::Release()
{
  this->Pass.reset();
  this->Key.clear();
  if (this->Framebuffer)
  {
    glDeleteFramebuffers(1, &this->Framebuffer);
    this->Framebuffer = 0;
  }
}

} // namespace cloudvis
