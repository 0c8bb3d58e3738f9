// vtkCloudVolumeMapper's composite pass: the march's float target, at ResolutionScale of the
// viewport, upsampled (Catmull-Rom) and blended over the scene, with the temporal history of a
// still's accumulation or of the interactive frames' reprojection (shaders/CloudCompositeFS.glsl).
#include "CloudVolumeMapperInternals.h"

#include "CloudCompositeFS.h"
#include "CloudDisplayTransformSource.h"

#include <vtkMath.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>
#include <string>

using cloudvis::mapper::HistoryFadeDegrees;
using cloudvis::mapper::HistoryWeight;
using cloudvis::mapper::SetMatrix;
using cloudvis::mapper::WindowOf;

namespace
{
// The composite shader with the shared display transform spliced in.
std::string CompositeSource()
{
  std::string source = CloudCompositeFS;
  const std::string marker = "//CLOUDVIS::DisplayTransform";
  source.replace(source.find(marker), marker.size(), CloudDisplayTransformSource);
  return source;
}
} // namespace

bool vtkCloudVolumeMapper::CompositePass(vtkRenderer* renderer)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = WindowOf(renderer);
  vtkOpenGLState* state = window->GetState();
  cloudvis::ViewTargets& view = in.ViewOf(renderer);
  if (!in.Composite)
  {
    in.Composite = std::make_unique<vtkOpenGLQuadHelper>(
      window, nullptr, CompositeSource().c_str(), "");
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(in.Composite->Program);
  }
  vtkShaderProgram* program = in.Composite->Program;
  if (!program || !program->GetCompiled())
  {
    return this->Fail("the composite shader failed to compile or link (the driver's log is in "
                      "VTK's error output)");
  }

  int viewport[4];
  renderer->GetTiledSizeAndOrigin(&viewport[2], &viewport[3], &viewport[0], &viewport[1]);
  vtkOpenGLState::ScopedglViewport savedViewport(state);
  vtkOpenGLState::ScopedglEnableDisable savedBlend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable savedDepthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate savedBlendFunction(state);
  vtkOpenGLState::ScopedglDepthMask savedDepthMask(state);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);

  vtkTextureObject* color = view.GetTarget(cloudvis::ViewTargets::Color);
  vtkTextureObject* counts = view.GetTarget(cloudvis::ViewTargets::Counts);
  cloudvis::TemporalHistory& history = view.History;
  color->Activate();
  counts->Activate();
  program->SetUniformi("CountTexture", counts->GetTextureUnit());
  program->SetUniformi("ShowSampleCount", this->DisplayMode == SampleCount ? 1 : 0);
  program->SetUniformf("SampleCountScale", float(1.0 / view.MostSamplesPerRay));
  program->SetUniformf("ExposureScale", float(std::exp2(this->ExposureEV)));
  program->SetUniformi("DisplayCurve", this->DisplayCurve);
  program->SetUniformi("ColorWithinAlpha", this->ColorWithinAlpha ? 1 : 0);
  // The samplers the pass does not read must still name units of their type.
  program->SetUniformi("HistoryColorTexture", color->GetTextureUnit());
  program->SetUniformi("HistoryDepthTexture", counts->GetTextureUnit());
  // Draws `image` (its texels times `weight`) over the viewport, or into the history with
  // `resolve`.
  const auto draw = [&](vtkTextureObject* image, const int* size, float weight, bool resolve)
  {
    program->SetUniformi("MarchTexture", image->GetTextureUnit());
    const float imageSize[2] = { float(size[0]), float(size[1]) };
    program->SetUniform2f("MarchSize", imageSize);
    program->SetUniformi("Upsample", size[0] != viewport[2] || size[1] != viewport[3] ? 1 : 0);
    program->SetUniformf("FrameWeight", weight);
    program->SetUniformi("ResolveHistory", resolve ? 1 : 0);
    in.Composite->Render();
  };
  const float frameWeight = 1.0f / float(std::max(1, view.AccumulatedFrames));

  if (history.IsAllocated() && (view.Marched || !history.HasImage))
  {
    // A new frame: resolved at full resolution into the history, blended with the last image
    // reprojected on an interactive frame.
    vtkTextureObject* lastColor = history.GetColor();
    vtkTextureObject* lastDepth = history.GetDepth();
    if (history.Reproject)
    {
      lastColor->Activate();
      lastDepth->Activate();
      program->SetUniformi("HistoryColorTexture", lastColor->GetTextureUnit());
      program->SetUniformi("HistoryDepthTexture", lastDepth->GetTextureUnit());
      const float historySize[2] = { float(history.GetSize()[0]), float(history.GetSize()[1]) };
      program->SetUniform2f("HistorySize", historySize);
      SetMatrix(program, "DCLocalMatrix", history.DeviceToLocal);
      SetMatrix(program, "LastDCLocalMatrix", history.LastDeviceToLocal);
      SetMatrix(program, "LastLocalDCMatrix", glm::inverse(history.LastDeviceToLocal));
      program->SetUniformf("HistoryWeight", HistoryWeight);
      program->SetUniformf("DepthTolerance", float(history.DepthTolerance));
      program->SetUniformf("FadeAngle", float(HistoryFadeDegrees * vtkMath::Pi() / 180.0));
    }
    program->SetUniformi("Reproject", history.Reproject ? 1 : 0);
    if (!history.BindNext(window))
    {
      color->Deactivate();
      counts->Deactivate();
      return this->Fail("the temporal history framebuffer is incomplete on this GPU");
    }
    state->vtkglViewport(0, 0, viewport[2], viewport[3]);
    state->vtkglDisable(GL_BLEND);
    draw(color, view.GetMarchSize(), frameWeight, true);
    history.FinishNext(window);
    if (history.Reproject)
    {
      lastColor->Deactivate();
      lastDepth->Deactivate();
    }
  }

  state->vtkglViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  state->vtkglEnable(GL_BLEND);
  // Premultiplied "over": the cloud in front of what the renderer has drawn.
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  if (history.IsAllocated())
  {
    vtkTextureObject* shown = history.GetColor();
    shown->Activate();
    draw(shown, history.GetSize(), 1.0f, false);
    shown->Deactivate();
  }
  else
  {
    draw(color, view.GetMarchSize(), frameWeight, false);
  }
  color->Deactivate();
  counts->Deactivate();
  return true;
}
