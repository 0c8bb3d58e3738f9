// vtkCloudVolumeMapper's march pass, phase by phase. A MarchFrame holds what one frame decides
// (the march's resolution and uniforms, the camera's matrices, which lighting inputs the march
// reads) and MarchPass runs its phases in order: the targets sized, the uniforms computed, the
// lighting inputs brought up to date, the accumulation continued or restarted, then one frame
// marched. Each phase returns false on a problem, recorded by the mapper's Fail.
#include "vtkCloudVolumeMapper.h"

#include "CloudGpuMemory.h"
#include "CloudMarchUniforms.h"
#include "CloudOpticalDepthGrid.h"
#include "CloudScatteringVolume.h"
#include "CloudVolumeMapperInternals.h"

#include <vtkCollection.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkOpenGLCamera.h>
#include <vtkOpenGLState.h>
#include <vtkPropCollection.h>
#include <vtkTextureObject.h>
#include <vtkTimerLog.h>
#include <vtkVolume.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>
#include <vector>

using cloudvis::mapper::HistoryDepthSteps;
using cloudvis::mapper::SetMatrix;
using cloudvis::mapper::WindowOf;

namespace
{
constexpr double GoldenRatioFraction = 0.61803398874989484;

// The matrix a vtkMatrix4x4 holds, as GLM (column-major) sees it.
glm::dmat4 ToGlm(const vtkMatrix4x4* m)
{
  glm::dmat4 g;
  for (int row = 0; row < 4; ++row)
  {
    for (int column = 0; column < 4; ++column)
    {
      g[column][row] = m->GetElement(row, column);
    }
  }
  return g;
}

// The latest change of the renderer's lights; without `cameraLights`, of its scene lights only:
// the renderer moves headlights and camera lights with the camera, so a camera move changes them.
// 0 when the mapper has lights of its own (its MTime tells their changes).
vtkMTimeType LatestChangeOfLights(vtkRenderer* renderer,
  const std::optional<std::vector<cloudvis::Light>>& ownLights,
  bool cameraLights = true)
{
  if (ownLights)
  {
    return 0;
  }
  vtkMTimeType latest = renderer->GetLights()->GetMTime();
  vtkCollectionSimpleIterator it;
  renderer->GetLights()->InitTraversal(it);
  while (vtkLight* light = renderer->GetLights()->GetNextLight(it))
  {
    if (cameraLights || light->LightTypeIsSceneLight())
    {
      latest = std::max(latest, light->GetMTime());
    }
  }
  return latest;
}

// The latest change to anything else the renderer draws: opaque geometry that moves changes
// where rays end, so the accumulated cloud must start again.
vtkMTimeType LatestChangeOfOtherProps(vtkRenderer* renderer, vtkVolume* volume)
{
  vtkMTimeType latest = 0;
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (prop != volume && prop->GetVisibility())
    {
      latest = std::max(latest, prop->GetRedrawMTime());
    }
  }
  return latest;
}
}

// One frame of the march pass (MarchPass runs its phases in their order of declaration).
class vtkCloudVolumeMapper::MarchFrame
{
public:
  MarchFrame(vtkCloudVolumeMapper& mapper,
    vtkRenderer* renderer,
    vtkVolume* volume,
    vtkImageData* input);

  // The view's targets at the viewport's size and the march's resolution, and the opaque
  // scene's depth copied into them: it ends the rays.
  bool SizeTargets();
  // The uniforms SetUpMarch computes from the mapper's objects (what the CPU reference computes
  // from the same objects, with its refusals) and the camera's matrices.
  bool ComputeUniforms();
  // What the march reads besides the field: the droplets' phase table, the optical depths from
  // outside the field, the light volumes and the multiple-scattering volume.
  bool UpdateLightingInputs();
  // Progressive accumulation continued while everything the image depends on holds, and the
  // temporal history readied. Converged() then says whether another frame adds anything.
  bool ContinueAccumulation();
  bool Converged() const
  {
    return this->View.AccumulatedFrames >= this->Mapper.MaximumAccumulatedFrames;
  }
  // One more frame marched into the targets, added to those accumulated.
  bool March();

private:
  bool IsInteracting() const;
  double ChooseResolutionScale() const;
  bool UpdateExternalDepths();
  bool UpdateLightVolumes(const cloudvis::LightVolumeTexture::Inputs& lightInputs);
  bool UpdateScatteringVolume(const cloudvis::LightVolumeTexture::Inputs& lightInputs);
  cloudvis::LightVolumeTexture::Inputs LightInputs();
  vtkShaderProgram* ReadyProgram();
  bool ReadyPathTraceInputs();
  std::vector<vtkTextureObject*> ActivateTextures(vtkShaderProgram* program);
  void SetFieldUniforms(vtkShaderProgram* program);
  void BindLightingInputs(vtkShaderProgram* program);
  void DeactivateTextures(const std::vector<vtkTextureObject*>& textures);
  void Record(double start);
  // Records Problem as the mapper's error (an allocation the budget refused, when it did).
  bool Fail() { return this->Mapper.Fail(this->Problem, this->Budget.Refused()); }

  vtkCloudVolumeMapper& Mapper;
  Internals& In;
  vtkRenderer* Renderer;
  vtkVolume* Volume;
  vtkImageData* Input;
  vtkOpenGLRenderWindow* Window;
  cloudvis::ViewTargets& View;
  cloudvis::GpuMemoryBudget Budget;
  std::string Problem;

  // SizeTargets: the viewport (x, y, width, height) and the march's scale and size.
  int Viewport[4] = { 0, 0, 0, 0 };
  double Scale = 1.0;
  int MarchWidth = 1;
  int MarchHeight = 1;
  bool Interacting = false;
  // ComputeUniforms.
  cloudvis::MarchUniforms Uniforms;
  cloudvis::LocalFrame Local;
  glm::dmat4 DeviceToLocal{ 1.0 };
  glm::dmat4 WorldToDevice{ 1.0 };
  glm::dmat4 ModelToWorld{ 1.0 };
  int Iterations = 0;
  bool MarchModel = false;
  bool PathTrace = false;
  // UpdateLightingInputs: which inputs the march reads.
  bool ExternalDepths = false;
  bool LightVolumes = false;
  bool ExternalScattering = false;
  bool ScatteringVolume = false;
};

vtkCloudVolumeMapper::MarchFrame::MarchFrame(vtkCloudVolumeMapper& mapper,
  vtkRenderer* renderer,
  vtkVolume* volume,
  vtkImageData* input)
  : Mapper(mapper)
  , In(*mapper.Internal)
  , Renderer(renderer)
  , Volume(volume)
  , Input(input)
  , Window(WindowOf(renderer))
  , View(mapper.Internal->ViewOf(renderer))
  , Budget(WindowOf(renderer), mapper.MaximumGPUMemory, mapper.Internal->Bytes())
{
}

bool vtkCloudVolumeMapper::MarchPass(vtkRenderer* renderer, vtkVolume* volume, vtkImageData* input)
{
  MarchFrame frame(*this, renderer, volume, input);
  if (!frame.SizeTargets() || !frame.ComputeUniforms() || !frame.UpdateLightingInputs() ||
    !frame.ContinueAccumulation())
  {
    return false;
  }
  // Converged: the composite pass shows the accumulated image again.
  return frame.Converged() || frame.March();
}

bool vtkCloudVolumeMapper::MarchFrame::IsInteracting() const
{
  return this->Mapper.InteractiveFrameRate > 0.0 &&
    this->Renderer->GetRenderWindow()->GetDesiredUpdateRate() > 1.0;
}

double vtkCloudVolumeMapper::MarchFrame::ChooseResolutionScale() const
{
  if (!this->Interacting)
  {
    return this->Mapper.ResolutionScale;
  }
  if (this->View.SecondsPerPixel <= 0.0)
  {
    return std::min(0.5, this->Mapper.ResolutionScale);
  }
  // The march gets half of the frame period: the composite pass, the depth copy and the rest
  // of the renderer's frame take the other half.
  const double budget = 0.5 / this->Mapper.InteractiveFrameRate;
  const double pixels = double(this->Viewport[2]) * this->Viewport[3];
  const double scale = std::sqrt(budget / (this->View.SecondsPerPixel * pixels));
  return std::max(0.25, std::min(this->Mapper.ResolutionScale, scale));
}

bool vtkCloudVolumeMapper::MarchFrame::SizeTargets()
{
  int* v = this->Viewport;
  this->Renderer->GetTiledSizeAndOrigin(&v[2], &v[3], &v[0], &v[1]);
  this->Interacting = this->IsInteracting();
  this->Scale = this->ChooseResolutionScale();
  this->MarchWidth = std::max(1, int(std::lround(v[2] * this->Scale)));
  this->MarchHeight = std::max(1, int(std::lround(v[3] * this->Scale)));
  if (!this->View.Resize(
        this->Window, v[2], v[3], this->MarchWidth, this->MarchHeight, this->Budget, this->Problem))
  {
    return this->Fail();
  }
  this->View.CopyDepth(v);
  return true;
}

bool vtkCloudVolumeMapper::MarchFrame::ComputeUniforms()
{
  vtkCloudVolumeMapper& m = this->Mapper;
  const cloudvis::MarchSetup setup = cloudvis::MakeMarchSetup(this->Input,
    this->Volume->GetMatrix(),
    this->In.Density.GetTexels(),
    &this->In.Transfer.GetTable(),
    m.SampleDistance,
    m.TerminationTransmittance,
    m.LightingProperty->GetParameters(),
    m.CloudLights ? *m.CloudLights : cloudvis::LightsOf(this->Renderer->GetLights()));
  const cloudvis::MarchProblem problem = cloudvis::SetUpMarch(setup, this->Uniforms, &this->Local);
  if (problem)
  {
    return m.Fail(problem.Message);
  }
  this->MarchModel = this->Uniforms.Lighting.Model == cloudvis::LightingModel::March;
  this->PathTrace = this->Uniforms.Lighting.Model == cloudvis::LightingModel::PathTrace;

  // Normalized device coordinates to the local frame, built camera-relative (DeviceToLocal) so
  // that no world coordinate enters it: the view's rotation and translation, the eye recovered
  // from them (the camera's position, or where its model transform puts it), the projection.
  auto* camera = static_cast<vtkOpenGLCamera*>(this->Renderer->GetActiveCamera());
  vtkMatrix4x4 *wcvc, *vcdc, *wcdc;
  vtkMatrix3x3* normals;
  camera->GetKeyMatrices(this->Renderer, wcvc, normals, vcdc, wcdc);
  const glm::dmat4 worldToView = glm::transpose(ToGlm(wcvc)); // key matrices are transposed
  const glm::dmat3 rotation(worldToView);
  const glm::dvec3 eye = -glm::inverse(rotation) * glm::dvec3(worldToView[3]);
  this->DeviceToLocal =
    cloudvis::DeviceToLocal(this->Local, glm::transpose(ToGlm(vcdc)), rotation, eye);
  this->WorldToDevice = glm::transpose(ToGlm(wcdc));
  this->ModelToWorld = ToGlm(this->Volume->GetMatrix());

  this->View.MostSamplesPerRay = std::max(1.0, double(this->Uniforms.LongestRaySamples));
  // One iteration per sample, and at most about three leaps per brick crossed.
  const int* bricks = this->In.Occupancy.GetBrickCount();
  this->Iterations = this->Uniforms.MaximumSamples + 3 * (bricks[0] + bricks[1] + bricks[2]);
  return true;
}

bool vtkCloudVolumeMapper::MarchFrame::UpdateLightingInputs()
{
  // Every program that holds the transport reads the droplets' table (or its placeholder).
  if (!this->In.DropletPhase.Update(
        this->Window, this->Uniforms.Lighting, this->Budget, this->Problem) ||
    !this->UpdateExternalDepths())
  {
    return this->Fail();
  }
  const cloudvis::LightVolumeTexture::Inputs lightInputs = this->LightInputs();
  return this->UpdateLightVolumes(lightInputs) && this->UpdateScatteringVolume(lightInputs);
}

bool vtkCloudVolumeMapper::MarchFrame::UpdateExternalDepths()
{
  // The march adds the optical depths from outside the field, when given, to its own toward each
  // light (the march model's; the other models have none).
  Internals& in = this->In;
  this->ExternalDepths = this->MarchModel && in.External.HasDepths();
  if (this->ExternalDepths)
  {
    this->Problem =
      cloudvis::ValidateOpticalDepthGrid(in.External.GetGrid(), int(this->Uniforms.Lights.size()));
    if (!this->Problem.empty() || !in.External.Update(this->Window, this->Budget, this->Problem))
    {
      return false;
    }
    cloudvis::SetExternalOpticalDepths(this->Uniforms, this->Local, &in.External.GetGrid());
  }
  else if (in.External.GetBytes() > 0)
  {
    in.External.Release(this->Window);
    in.ExternalScattering.Release(this->Window);
  }
  return true;
}

cloudvis::LightVolumeTexture::Inputs vtkCloudVolumeMapper::MarchFrame::LightInputs()
{
  Internals& in = this->In;
  cloudvis::LightVolumeTexture::Inputs inputs;
  inputs.Density = in.Density.GetTexture();
  inputs.Transfer = in.Transfer.GetTexture();
  inputs.Occupancy = in.Occupancy.GetTexture();
  inputs.DropletPhase = in.DropletPhase.GetTexture();
  inputs.BrickCount = in.Occupancy.GetBrickCount();
  inputs.BrickSize = this->Mapper.BrickSize;
  inputs.SkipEmptySpace = this->Mapper.EmptySpaceSkipping;
  inputs.DensityTime = double(in.Density.GetUploadTime());
  inputs.TableTime = double(in.Transfer.GetTableTime());
  inputs.ExternalDepths = this->ExternalDepths ? in.External.GetTexture() : nullptr;
  inputs.ExternalDepthsTime = this->ExternalDepths ? in.External.GetUploadTime() : -1.0;
  return inputs;
}

bool vtkCloudVolumeMapper::MarchFrame::UpdateLightVolumes(
  const cloudvis::LightVolumeTexture::Inputs& lightInputs)
{
  // The march with light volumes reads the optical depth toward each light from them, computed
  // (in a pass of their own, before the march's program is made current) when what they depend
  // on changed. While the view is interacting, volumes made stale by the lights alone (a light
  // that follows the camera changes with every frame) are not recomputed: that frame marches
  // toward the lights (the nested march) and the still render after the interaction recomputes
  // them once.
  cloudvis::LightVolumeTexture& volumes = this->In.LightVolumes;
  const bool asked = this->MarchModel &&
    this->Uniforms.Lighting.Transmittance == cloudvis::LightTransmittance::Volumes;
  const bool nestedWhileInteracting =
    asked && this->Interacting && volumes.OnlyLightsChanged(this->Uniforms, lightInputs);
  this->LightVolumes = asked && !nestedWhileInteracting;
  if (this->LightVolumes)
  {
    if (!volumes.Update(this->Window, this->Uniforms, lightInputs, this->Budget, this->Problem))
    {
      return this->Fail();
    }
  }
  else if (!nestedWhileInteracting && volumes.GetBytes() > 0)
  {
    volumes.Release(this->Window); // another model or the nested march: not held for nothing
  }
  return true;
}

bool vtkCloudVolumeMapper::MarchFrame::UpdateScatteringVolume(
  const cloudvis::LightVolumeTexture::Inputs& lightInputs)
{
  // The multiple-scattering volume, after the light volumes (its source reads them, or marches
  // toward the lights in the frames that do), progressive when the mapper is asked to spread it
  // over frames. A volume solved over the whole distributed field, when given, is read instead
  // of one of the input's own.
  Internals& in = this->In;
  const bool uses = cloudvis::UsesScatteringVolume(this->Uniforms.Lighting);
  this->ExternalScattering = uses && in.ExternalScattering.HasVolume();
  this->ScatteringVolume = uses && !this->ExternalScattering;
  if (this->ExternalScattering)
  {
    if (!in.ExternalScattering.Update(this->Window, this->Budget, this->Problem))
    {
      return this->Fail();
    }
    cloudvis::SetExternalScatteringVolume(
      this->Uniforms, this->Local, &in.ExternalScattering.GetVolume());
  }
  else if (in.ExternalScattering.GetBytes() > 0)
  {
    in.ExternalScattering.Release(this->Window);
  }
  if (this->ScatteringVolume)
  {
    cloudvis::ScatteringVolumeTexture::Inputs scatteringInputs;
    static_cast<cloudvis::LightVolumeTexture::Inputs&>(scatteringInputs) = lightInputs;
    scatteringInputs.LightVolumes = this->LightVolumes ? &in.LightVolumes : nullptr;
    if (!in.Scattering.Update(this->Window,
          this->Uniforms,
          scatteringInputs,
          this->Budget,
          this->Problem,
          this->Mapper.ScatteringVolumeSecondsPerFrame))
    {
      return this->Fail();
    }
  }
  else if (in.Scattering.GetBytes() > 0)
  {
    in.Scattering.Release(this->Window);
  }
  this->Uniforms.ScatteringVolumeTextures = this->ScatteringVolume;
  return true;
}

bool vtkCloudVolumeMapper::MarchFrame::ContinueAccumulation()
{
  // Progressive accumulation: continue averaging while everything the image depends on holds.
  // The temporal history survives a change of the camera (with the lights that follow it) and of
  // the march's scale, not of the rest (the content).
  vtkCloudVolumeMapper& m = this->Mapper;
  const glm::dmat4& model = this->ModelToWorld;
  std::vector<double> content(glm::value_ptr(model), glm::value_ptr(model) + 16);
  for (double v : { double(this->Viewport[2]),
         double(this->Viewport[3]),
         double(this->In.Density.GetUploadTime()),
         double(this->In.Transfer.GetTableTime()),
         double(m.GetMTime()),
         double(this->Volume->GetMTime()),
         double(LatestChangeOfOtherProps(this->Renderer, this->Volume)),
         double(LatestChangeOfLights(this->Renderer, m.CloudLights, false)),
         double(this->In.Scattering.GetComputeCount()),
         this->In.ExternalScattering.GetUploadTime() })
  {
    content.push_back(v);
  }
  const glm::dmat4& device = this->WorldToDevice;
  std::vector<double> signature(glm::value_ptr(device), glm::value_ptr(device) + 16);
  signature.insert(signature.end(), content.begin(), content.end());
  signature.push_back(this->Scale);
  signature.push_back(double(LatestChangeOfLights(this->Renderer, m.CloudLights)));
  // Frames marched toward the lights (while interacting) and through the volumes never average
  // together; the history may blend them, as their difference is small against the motion's.
  signature.push_back(double(this->LightVolumes));
  this->View.Continue(signature);

  this->View.Marched = false;
  cloudvis::TemporalHistory& history = this->View.History;
  if (m.TemporalReprojection && m.DisplayMode == Radiance && !this->PathTrace)
  {
    if (!history.Resize(
          this->Window, this->Viewport[2], this->Viewport[3], this->Budget, this->Problem))
    {
      return this->Fail();
    }
    history.BeginFrame(content, this->Interacting, this->DeviceToLocal);
    // The depth where the opacity passes 2% moves by up to a step with the jitter, and the
    // closest depth of a neighbourhood lies a little before a pixel's own.
    history.DepthTolerance = HistoryDepthSteps * this->Uniforms.Step;
  }
  else
  {
    history.Release(this->Window);
  }
  return true;
}

vtkShaderProgram* vtkCloudVolumeMapper::MarchFrame::ReadyProgram()
{
  // The march is one shader; a lighting model only supplies its source term, and the field's
  // occupancy picks the loop's variant.
  int samplesPerMapRead = this->Mapper.SamplesPerMapRead;
  if (!this->Mapper.EmptySpaceSkipping)
  {
    samplesPerMapRead = 1; // no map is read
  }
  else if (samplesPerMapRead == 0)
  {
    samplesPerMapRead = cloudvis::SamplesPerMapRead(this->In.Occupancy.GetOccupiedFraction());
  }
  return this->In.March.Ready(this->Window,
    this->Uniforms.Lighting.Model,
    this->Uniforms.Lights,
    samplesPerMapRead,
    cloudvis::MarchSwitchesOf(this->Uniforms, this->LightVolumes));
}

bool vtkCloudVolumeMapper::MarchFrame::ReadyPathTraceInputs()
{
  Internals& in = this->In;
  if (!this->PathTrace) // the path tracer's textures are not held for nothing
  {
    in.ExtinctionBounds.Release(this->Window);
    this->View.ReleaseMoments(this->Window);
    return true;
  }
  return (in.ExtinctionBounds.Update(
            this->Window, in.Occupancy.GetBricks(), this->Budget, this->Problem) &&
           this->View.AllocateMoments(this->Window, this->Budget, this->Problem)) ||
    this->Fail();
}

bool vtkCloudVolumeMapper::MarchFrame::March()
{
  vtkShaderProgram* program = this->ReadyProgram();
  if (!program)
  {
    return this->Mapper.Fail("the march shader failed to compile or link (the driver's log is in "
                             "VTK's error output)");
  }
  const double start = vtkTimerLog::GetUniversalTime();
  if (this->Interacting)
  {
    this->Window->WaitForCompletion(); // time the march alone
  }
  if (!this->ReadyPathTraceInputs())
  {
    return false;
  }
  if (!this->View.BindTargets(this->Window, this->PathTrace))
  {
    return this->Mapper.Fail("the march framebuffer is incomplete on this GPU");
  }
  vtkOpenGLState* state = this->Window->GetState();
  vtkOpenGLState::ScopedglViewport savedViewport(state);
  vtkOpenGLState::ScopedglEnableDisable savedBlend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable savedDepthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable savedScissor(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate savedBlendFunction(state);
  state->vtkglViewport(0, 0, this->MarchWidth, this->MarchHeight);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  // The targets hold the sum of the accumulated frames: the first overwrites, the next add.
  if (this->View.AccumulatedFrames == 0)
  {
    state->vtkglDisable(GL_BLEND);
  }
  else
  {
    state->vtkglEnable(GL_BLEND);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  }
  const std::vector<vtkTextureObject*> textures = this->ActivateTextures(program);
  this->In.March.Render();
  this->DeactivateTextures(textures);
  this->View.UnbindTargets(this->Window);
  this->Record(start);
  return true;
}

std::vector<vtkTextureObject*> vtkCloudVolumeMapper::MarchFrame::ActivateTextures(
  vtkShaderProgram* program)
{
  Internals& in = this->In;
  std::vector<vtkTextureObject*> textures = { in.Density.GetTexture(),
    in.Transfer.GetTexture(),
    in.Occupancy.GetTexture(),
    in.Jitter.GetTexture(),
    in.DropletPhase.GetTexture(),
    this->View.GetDepth() };
  if (this->PathTrace)
  {
    textures.push_back(in.ExtinctionBounds.GetTexture());
  }
  if (this->ExternalDepths)
  {
    textures.push_back(in.External.GetTexture());
  }
  for (vtkTextureObject* texture : textures)
  {
    texture->Activate();
  }
  this->SetFieldUniforms(program);
  this->BindLightingInputs(program);
  return textures;
}

void vtkCloudVolumeMapper::MarchFrame::SetFieldUniforms(vtkShaderProgram* program)
{
  const vtkCloudVolumeMapper& m = this->Mapper;
  Internals& in = this->In;
  SetMatrix(program, "DCLocalMatrix", this->DeviceToLocal);
  cloudvis::SetMarchUniforms(program, this->Uniforms);
  program->SetUniformi("DensityTexture", in.Density.GetTexture()->GetTextureUnit());
  program->SetUniformi("TransferTexture", in.Transfer.GetTexture()->GetTextureUnit());
  program->SetUniformi("EmptyDistanceTexture", in.Occupancy.GetTexture()->GetTextureUnit());
  program->SetUniformi("DropletPhaseTexture", in.DropletPhase.GetTexture()->GetTextureUnit());
  const int* bricks = in.Occupancy.GetBrickCount();
  const float brickCount[3] = { float(bricks[0]), float(bricks[1]), float(bricks[2]) };
  program->SetUniform3f("BrickCount", brickCount);
  program->SetUniformf("BrickSize", float(m.BrickSize));
  program->SetUniformi("SkipEmptySpace", m.EmptySpaceSkipping ? 1 : 0);
  program->SetUniformi("DepthTexture", this->View.GetDepth()->GetTextureUnit());
  program->SetUniformi("JitterTexture", in.Jitter.GetTexture()->GetTextureUnit());
  program->SetUniformf("JitterTextureSize", float(cloudvis::JitterTexture::Size));
  // Reprojected frames follow the golden-ratio sequence on from the history's, so the images
  // blended into it have different jitter too.
  const int frame = this->View.AccumulatedFrames;
  const cloudvis::TemporalHistory& history = this->View.History;
  const int jitterFrame = frame + (history.Reproject ? history.Sequence : 0);
  program->SetUniformf("JitterOffset", float(std::fmod(jitterFrame * GoldenRatioFraction, 1.0)));
  program->SetUniformi("JitterEnabled", m.Jitter ? 1 : 0);
  program->SetUniformi("MaximumIterations", this->Iterations);
  if (this->PathTrace)
  {
    // The same paths whatever the frame split: sample k of frame f is f * per frame + k.
    cloudvis::PathTraceFrame pathFrame;
    pathFrame.MaxBounces = m.PathTraceMaxBounces;
    pathFrame.Seed = m.PathTraceSeed;
    pathFrame.SamplesPerFrame = m.PathTraceSamplesPerFrame;
    pathFrame.SampleBase = frame * m.PathTraceSamplesPerFrame;
    pathFrame.MarchWidth = this->MarchWidth;
    pathFrame.LightGuidedNextEvents = cloudvis::GuidesNextEventsByDefault(this->Uniforms.Lighting);
    program->SetUniformi(
      "ExtinctionBoundsTexture", in.ExtinctionBounds.GetTexture()->GetTextureUnit());
    cloudvis::SetPathTraceUniforms(program, pathFrame);
  }
}

void vtkCloudVolumeMapper::MarchFrame::BindLightingInputs(vtkShaderProgram* program)
{
  Internals& in = this->In;
  const int placeholder = in.Density.GetTexture()->GetTextureUnit();
  if (this->MarchModel || this->PathTrace) // both hold the march's lighting code and its sampler
  {
    if (this->LightVolumes) // (whether they are read is a constant of the program: MarchSwitches)
    {
      in.LightVolumes.Activate(program);
    }
    else // never read, but a sampler must name a unit of its own type
    {
      program->SetUniformi("LightVolumeTexture", placeholder);
    }
    cloudvis::BindExternalDepths(
      program, this->ExternalDepths ? in.External.GetTexture() : nullptr, placeholder);
  }
  if (this->ScatteringVolume)
  {
    in.Scattering.Activate(program);
  }
  else if (this->ExternalScattering)
  {
    in.ExternalScattering.Activate(program);
  }
  else if (this->MarchModel) // the octaves: never read, as above
  {
    program->SetUniformi("ScatteringVolumeTexture", placeholder);
    program->SetUniformi("ScatteringFluxTexture", placeholder);
  }
}

void vtkCloudVolumeMapper::MarchFrame::DeactivateTextures(
  const std::vector<vtkTextureObject*>& textures)
{
  if (this->LightVolumes)
  {
    this->In.LightVolumes.Deactivate();
  }
  if (this->ScatteringVolume)
  {
    this->In.Scattering.Deactivate();
  }
  if (this->ExternalScattering)
  {
    this->In.ExternalScattering.Deactivate();
  }
  for (vtkTextureObject* texture : textures)
  {
    texture->Deactivate();
  }
}

void vtkCloudVolumeMapper::MarchFrame::Record(double start)
{
  cloudvis::ViewTargets& view = this->View;
  view.Marched = true;
  view.AccumulatedFrames += 1;
  view.LocalUnit = this->Local.Unit;
  view.PathTraced = this->PathTrace;
  view.SamplesPerFrame = this->Mapper.PathTraceSamplesPerFrame;
  if (this->Mapper.CollectStatistics)
  {
    this->Mapper.ReadStatistics(this->Renderer);
  }
  if (this->Interacting)
  {
    this->Window->WaitForCompletion();
    const double perPixel =
      (vtkTimerLog::GetUniversalTime() - start) / (double(this->MarchWidth) * this->MarchHeight);
    view.SecondsPerPixel =
      view.SecondsPerPixel > 0.0 ? 0.5 * (view.SecondsPerPixel + perPixel) : perPixel;
  }
}
