// vtkCloudVolumeMapper: its settings, the textures it keeps up to date, the march's uniforms (the
// same MarchUniforms the CPU reference computes with, from the mapper's LightingParameters and
// lights) and the march pass. The composite pass and the read-backs are
// vtkCloudVolumeMapperComposite.cxx's and vtkCloudVolumeMapperReadBack.cxx's; what the three
// share is CloudVolumeMapperInternals.h.
#include "vtkCloudVolumeMapper.h"

#include "CloudFieldGeometry.h"
#include "CloudGpuMemory.h"
#include "CloudMarchUniforms.h"
#include "CloudOpticalDepthGrid.h"
#include "CloudScatteringVolume.h"
#include "CloudVolumeMapperInternals.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkMath.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOpenGLCamera.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkPointData.h>
#include <vtkPropCollection.h>
#include <vtkTextureObject.h>
#include <vtkTimerLog.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>
#include <limits>

using cloudvis::mapper::HistoryDepthSteps;
using cloudvis::mapper::SetMatrix;
using cloudvis::mapper::WindowOf;

vtkStandardNewMacro(vtkCloudVolumeMapper);

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

vtkCloudVolumeMapper::vtkCloudVolumeMapper()
  : LightingProperty(vtkSmartPointer<vtkCloudLightingProperty>::New())
  , Internal(new Internals)
{
}

vtkCloudVolumeMapper::~vtkCloudVolumeMapper() = default;

void vtkCloudVolumeMapper::SetLightingProperty(vtkCloudLightingProperty* property)
{
  if (!property || property != this->LightingProperty)
  {
    this->LightingProperty = property ? vtkSmartPointer<vtkCloudLightingProperty>(property)
                                      : vtkSmartPointer<vtkCloudLightingProperty>::New();
    this->Modified();
  }
}

void vtkCloudVolumeMapper::SetLights(const std::vector<cloudvis::Light>& lights)
{
  if (!this->CloudLights || *this->CloudLights != lights)
  {
    this->CloudLights = lights;
    this->Modified();
  }
}

void vtkCloudVolumeMapper::UseRendererLights()
{
  if (this->CloudLights)
  {
    this->CloudLights.reset();
    this->Modified();
  }
}

const std::vector<cloudvis::Light>* vtkCloudVolumeMapper::GetCloudLights() const
{
  return this->CloudLights ? &*this->CloudLights : nullptr;
}

bool vtkCloudVolumeMapper::ComputeOnPiece(vtkRenderer* renderer,
  vtkVolume* volume,
  const char* what,
  const std::function<cloudvis::MarchProblem(const cloudvis::MarchSetup&)>& compute)
{
  // What ComputeUniforms gives the march, from the objects rather than the textures (which need
  // a context and may not be made yet): the same texels, table and lights.
  this->LastError.clear();
  if (!volume)
  {
    return this->Fail(std::string(what) + " needs the volume the mapper draws");
  }
  vtkImageData* input = this->ValidInput(volume);
  if (!input)
  {
    return false;
  }
  int cellFlag = 0;
  vtkDataArray* scalars = this->InputScalars(input, cellFlag);
  const std::string valueProblem = cloudvis::ValidateDensityValues(scalars);
  if (!valueProblem.empty())
  {
    return this->Fail(valueProblem);
  }
  std::string tableProblem;
  const cloudvis::TransferTable table =
    cloudvis::TransferTableOf(volume->GetProperty(), this->ExtinctionScale, tableProblem);
  if (!tableProblem.empty())
  {
    return this->Fail(tableProblem);
  }
  const cloudvis::MarchSetup setup = cloudvis::MakeMarchSetup(input,
    volume->GetMatrix(),
    cloudvis::DensityTexelsOf(scalars, this->HalfFloatDensity),
    &table,
    this->SampleDistance,
    this->TerminationTransmittance,
    this->LightingProperty->GetParameters(),
    this->CloudLights ? *this->CloudLights
                      : cloudvis::LightsOf(renderer ? renderer->GetLights() : nullptr));
  const cloudvis::MarchProblem problem = compute(setup);
  return !problem || this->Fail(problem.Message);
}

bool vtkCloudVolumeMapper::ComputePieceOpticalDepths(vtkRenderer* renderer,
  vtkVolume* volume,
  cloudvis::OpticalDepthGrid& grid)
{
  grid.Lights = 0;
  grid.Depths.clear();
  return this->ComputeOnPiece(renderer,
    volume,
    "ComputePieceOpticalDepths",
    [&grid](const cloudvis::MarchSetup& setup)
    { return cloudvis::ComputePieceOpticalDepths(setup, grid); });
}

bool vtkCloudVolumeMapper::ComputePieceScatteringInputs(vtkRenderer* renderer,
  vtkVolume* volume,
  const cloudvis::VolumeGeometry& whole,
  std::vector<cloudvis::ScatteringGrid>& inputs)
{
  inputs.clear();
  const cloudvis::OpticalDepthGrid& external = this->Internal->External.GetGrid();
  return this->ComputeOnPiece(renderer,
    volume,
    "ComputePieceScatteringInputs",
    [&](const cloudvis::MarchSetup& setup)
    {
      return cloudvis::ComputePieceScatteringInputs(
        setup, external.Empty() ? nullptr : &external, whole, inputs);
    });
}

void vtkCloudVolumeMapper::SetExternalScatteringVolume(const cloudvis::WholeFieldScattering& volume)
{
  this->Internal->ExternalScattering.Set(volume);
  this->Modified();
}

const cloudvis::WholeFieldScattering& vtkCloudVolumeMapper::GetExternalScatteringVolume() const
{
  return this->Internal->ExternalScattering.GetVolume();
}

void vtkCloudVolumeMapper::SetExternalOpticalDepths(const cloudvis::OpticalDepthGrid& grid)
{
  this->Internal->External.Set(grid);
  this->Modified();
}

const cloudvis::OpticalDepthGrid& vtkCloudVolumeMapper::GetExternalOpticalDepths() const
{
  return this->Internal->External.GetGrid();
}

vtkMTimeType vtkCloudVolumeMapper::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->LightingProperty->GetMTime());
}

vtkTypeInt64 vtkCloudVolumeMapper::GetGPUMemoryBytes() const
{
  return this->Internal->Bytes();
}

vtkTypeInt64 vtkCloudVolumeMapper::GetFreeGPUMemoryBytes(vtkRenderWindow* window)
{
  auto* openGL = vtkOpenGLRenderWindow::SafeDownCast(window);
  return openGL ? cloudvis::FreeGpuMemory(openGL) : -1;
}

int vtkCloudVolumeMapper::GetLightVolumeComputeCount() const
{
  return this->Internal->LightVolumes.GetComputeCount();
}

vtkTypeInt64 vtkCloudVolumeMapper::GetLightVolumeBytes() const
{
  return this->Internal->LightVolumes.GetBytes();
}

int vtkCloudVolumeMapper::GetScatteringVolumeComputeCount() const
{
  return this->Internal->Scattering.GetComputeCount();
}

vtkTypeInt64 vtkCloudVolumeMapper::GetScatteringVolumeBytes() const
{
  return this->Internal->Scattering.GetBytes();
}

double vtkCloudVolumeMapper::GetScatteringVolumeSeconds() const
{
  return this->Internal->Scattering.GetLastComputeSeconds();
}

bool vtkCloudVolumeMapper::GetScatteringVolumeConverging() const
{
  return this->Internal->Scattering.IsConverging();
}

int vtkCloudVolumeMapper::GetScatteringVolumeStepsDone() const
{
  const cloudvis::ScatteringVolumeTexture& scattering = this->Internal->Scattering;
  return scattering.IsConverging() ? scattering.GetStepsDone() : 0;
}

int vtkCloudVolumeMapper::GetScatteringVolumeStepCount() const
{
  const cloudvis::ScatteringVolumeTexture& scattering = this->Internal->Scattering;
  return scattering.IsConverging() ? scattering.GetStepCount() : 0;
}

vtkTypeInt64 vtkCloudVolumeMapper::GetDensityTextureBytes() const
{
  return this->Internal->Density.GetBytes();
}

bool vtkCloudVolumeMapper::Fail(const std::string& message, bool outOfGpuMemory)
{
  this->LastError = message;
  this->LastErrorIsGpuMemory = outOfGpuMemory;
  if (message != this->Internal->ReportedError)
  {
    vtkErrorMacro(<< message);
    this->Internal->ReportedError = message;
  }
  return false;
}

int vtkCloudVolumeMapper::GetNumberOfAccumulatedFrames(vtkRenderer* renderer) const
{
  auto found = this->Internal->Views.find(renderer);
  return found == this->Internal->Views.end() ? 0 : found->second->AccumulatedFrames;
}

int vtkCloudVolumeMapper::GetNumberOfAccumulatedSamples(vtkRenderer* renderer) const
{
  auto found = this->Internal->Views.find(renderer);
  if (found == this->Internal->Views.end())
  {
    return 0;
  }
  const cloudvis::ViewTargets& view = *found->second;
  return view.AccumulatedFrames * (view.PathTraced ? view.SamplesPerFrame : 1);
}

void vtkCloudVolumeMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  this->LastError.clear();
  this->LastErrorIsGpuMemory = false;
  // The march clips its rays at the scene's depth, copied from the framebuffer VTK draws into.
  // GL cannot copy from a multisampled one (vtkRenderWindow's default, 8 samples where the driver
  // has them): the copy would fail and the cloud vanish without a word, so such a window is
  // refused in words instead.
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  if (samples > 1)
  {
    this->Fail("the render window is multisampled (" + std::to_string(samples) +
      " samples): the cloud mapper needs a single-sampled one, call SetMultiSamples(0) on the "
      "vtkRenderWindow before its first render");
    return;
  }
  vtkImageData* input = this->ValidInput(volume);
  if (input && this->UpdateTextures(renderer, volume, input) &&
    this->MarchPass(renderer, volume, input) && this->CompositePass(renderer))
  {
    this->Internal->ReportedError.clear();
  }
}

vtkDataArray* vtkCloudVolumeMapper::InputScalars(vtkImageData* input, int& cellFlag)
{
  return this->GetScalars(
    input, this->ScalarMode, this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
}

vtkImageData* vtkCloudVolumeMapper::ValidInput(vtkVolume* volume)
{
  vtkImageData* input = vtkImageData::SafeDownCast(this->GetInput());
  if (!input)
  {
    this->Fail("the volume mapper has no input image");
    return nullptr;
  }
  int cellFlag = 0;
  vtkDataArray* scalars = this->InputScalars(input, cellFlag);
  const std::string scalarProblem = cloudvis::ValidateDensityScalars(scalars);
  if (!scalarProblem.empty())
  {
    this->Fail(scalarProblem);
    return nullptr;
  }
  if (cellFlag != 0)
  {
    this->Fail("the input's scalars are cell data; the mapper needs point data");
    return nullptr;
  }
  int dimensions[3];
  input->GetDimensions(dimensions);
  if (dimensions[0] < 2 || dimensions[1] < 2 || dimensions[2] < 2)
  {
    this->Fail("the input image needs at least 2 voxels along each axis");
    return nullptr;
  }
  const std::string geometryProblem = cloudvis::ValidateVolumeGeometry(input, volume->GetMatrix());
  if (!geometryProblem.empty())
  {
    this->Fail(geometryProblem);
    return nullptr;
  }
  return input;
}

bool vtkCloudVolumeMapper::UpdateTextures(vtkRenderer* renderer,
  vtkVolume* volume,
  vtkImageData* input)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = WindowOf(renderer);
  int cellFlag = 0;
  vtkDataArray* scalars = this->InputScalars(input, cellFlag);
  cloudvis::GpuMemoryBudget budget(window, this->MaximumGPUMemory, in.Bytes());
  std::string problem;
  const bool ready =
    in.Density.Update(window, input, scalars, this->HalfFloatDensity, budget, problem) &&
    in.Transfer.Update(window, volume->GetProperty(), this->ExtinctionScale, budget, problem) &&
    in.Occupancy.Update(window,
      input,
      scalars,
      in.Density.GetUploadTime(),
      in.Transfer.GetTable(),
      in.Transfer.GetTableTime(),
      this->BrickSize,
      budget,
      problem) &&
    in.Jitter.Update(window, budget, problem);
  return ready || this->Fail(problem, budget.Refused());
}

bool vtkCloudVolumeMapper::IsInteracting(vtkRenderer* renderer) const
{
  return this->InteractiveFrameRate > 0.0 &&
    renderer->GetRenderWindow()->GetDesiredUpdateRate() > 1.0;
}

double vtkCloudVolumeMapper::ChooseResolutionScale(vtkRenderer* renderer)
{
  if (!this->IsInteracting(renderer))
  {
    return this->ResolutionScale;
  }
  const cloudvis::ViewTargets& view = this->Internal->ViewOf(renderer);
  int size[2], origin[2];
  renderer->GetTiledSizeAndOrigin(&size[0], &size[1], &origin[0], &origin[1]);
  if (view.SecondsPerPixel <= 0.0)
  {
    return std::min(0.5, this->ResolutionScale);
  }
  // The march gets half of the frame period: the composite pass, the depth copy and the rest
  // of the renderer's frame take the other half.
  const double budget = 0.5 / this->InteractiveFrameRate;
  const double scale = std::sqrt(budget / (view.SecondsPerPixel * double(size[0]) * size[1]));
  return std::max(0.25, std::min(this->ResolutionScale, scale));
}

bool vtkCloudVolumeMapper::ComputeUniforms(vtkRenderer* renderer,
  vtkVolume* volume,
  vtkImageData* input,
  cloudvis::MarchUniforms& uniforms,
  cloudvis::LocalFrame& frame)
{
  // What the CPU reference would compute from the same objects (MakeMarchSetup), and its
  // refusals.
  Internals& in = *this->Internal;
  const cloudvis::MarchSetup setup = cloudvis::MakeMarchSetup(input,
    volume->GetMatrix(),
    in.Density.GetTexels(),
    &in.Transfer.GetTable(),
    this->SampleDistance,
    this->TerminationTransmittance,
    this->LightingProperty->GetParameters(),
    this->CloudLights ? *this->CloudLights : cloudvis::LightsOf(renderer->GetLights()));
  const cloudvis::MarchProblem problem = cloudvis::SetUpMarch(setup, uniforms, &frame);
  return !problem || this->Fail(problem.Message);
}

bool vtkCloudVolumeMapper::MarchPass(vtkRenderer* renderer, vtkVolume* volume, vtkImageData* input)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = WindowOf(renderer);
  vtkOpenGLState* state = window->GetState();
  cloudvis::ViewTargets& view = in.ViewOf(renderer);

  int viewport[4];
  renderer->GetTiledSizeAndOrigin(&viewport[2], &viewport[3], &viewport[0], &viewport[1]);
  const double scale = this->ChooseResolutionScale(renderer);
  const int marchWidth = std::max(1, int(std::lround(viewport[2] * scale)));
  const int marchHeight = std::max(1, int(std::lround(viewport[3] * scale)));
  cloudvis::GpuMemoryBudget budget(window, this->MaximumGPUMemory, in.Bytes());
  std::string problem;
  if (!view.Resize(window, viewport[2], viewport[3], marchWidth, marchHeight, budget, problem))
  {
    return this->Fail(problem, budget.Refused());
  }
  view.CopyDepth(viewport); // the opaque scene's depth ends the rays

  cloudvis::MarchUniforms uniforms;
  cloudvis::LocalFrame localFrame;
  if (!this->ComputeUniforms(renderer, volume, input, uniforms, localFrame))
  {
    return false;
  }

  // Normalized device coordinates to the local frame, built camera-relative (DeviceToLocal) so
  // that no world coordinate enters it: the view's rotation and translation, the eye recovered
  // from them (the camera's position, or where its model transform puts it), the projection.
  auto* camera = static_cast<vtkOpenGLCamera*>(renderer->GetActiveCamera());
  vtkMatrix4x4 *wcvc, *vcdc, *wcdc;
  vtkMatrix3x3* normals;
  camera->GetKeyMatrices(renderer, wcvc, normals, vcdc, wcdc);
  const glm::dmat4 worldToView = glm::transpose(ToGlm(wcvc)); // key matrices are transposed
  const glm::dmat3 rotation(worldToView);
  const glm::dvec3 eye = -glm::inverse(rotation) * glm::dvec3(worldToView[3]);
  const glm::dmat4 deviceToLocal =
    cloudvis::DeviceToLocal(localFrame, glm::transpose(ToGlm(vcdc)), rotation, eye);
  const glm::dmat4 worldToDevice = glm::transpose(ToGlm(wcdc));
  const glm::dmat4 modelToWorld = ToGlm(volume->GetMatrix());

  // Every program that holds the transport reads the droplets' table (or its placeholder).
  if (!in.DropletPhase.Update(window, uniforms.Lighting, budget, problem))
  {
    return this->Fail(problem, budget.Refused());
  }

  view.MostSamplesPerRay = std::max(1.0, double(uniforms.LongestRaySamples));
  // One iteration per sample, and at most about three leaps per brick crossed.
  const int* bricks = in.Occupancy.GetBrickCount();
  const int iterations = uniforms.MaximumSamples + 3 * (bricks[0] + bricks[1] + bricks[2]);

  // The march adds the optical depths from outside the field, when given, to its own toward each
  // light (the march model's; the other models have none).
  const bool marchModel = uniforms.Lighting.Model == cloudvis::LightingModel::March;
  const bool external = marchModel && in.External.HasDepths();
  if (external)
  {
    problem =
      cloudvis::ValidateOpticalDepthGrid(in.External.GetGrid(), int(uniforms.Lights.size()));
    if (!problem.empty() || !in.External.Update(window, budget, problem))
    {
      return this->Fail(problem, budget.Refused());
    }
    cloudvis::SetExternalOpticalDepths(uniforms, localFrame, &in.External.GetGrid());
  }
  else if (in.External.GetBytes() > 0)
  {
    in.External.Release(window);
    in.ExternalScattering.Release(window);
  }

  // The march with light volumes reads the optical depth toward each light from them, computed
  // (in a pass of their own, before the march's program is made current) when what they depend
  // on changed. While the view is interacting, volumes made stale by the lights alone (a light
  // that follows the camera changes with every frame) are not recomputed: that frame marches
  // toward the lights (the nested march) and the still render after the interaction recomputes
  // them once.
  const bool interacting = this->IsInteracting(renderer);
  cloudvis::LightVolumeTexture::Inputs lightInputs;
  lightInputs.Density = in.Density.GetTexture();
  lightInputs.Transfer = in.Transfer.GetTexture();
  lightInputs.Occupancy = in.Occupancy.GetTexture();
  lightInputs.DropletPhase = in.DropletPhase.GetTexture();
  lightInputs.BrickCount = bricks;
  lightInputs.BrickSize = this->BrickSize;
  lightInputs.SkipEmptySpace = this->EmptySpaceSkipping;
  lightInputs.DensityTime = double(in.Density.GetUploadTime());
  lightInputs.TableTime = double(in.Transfer.GetTableTime());
  lightInputs.ExternalDepths = external ? in.External.GetTexture() : nullptr;
  lightInputs.ExternalDepthsTime = external ? in.External.GetUploadTime() : -1.0;
  const bool volumesAsked =
    marchModel && uniforms.Lighting.Transmittance == cloudvis::LightTransmittance::Volumes;
  const bool nestedWhileInteracting =
    volumesAsked && interacting && in.LightVolumes.OnlyLightsChanged(uniforms, lightInputs);
  const bool lightVolumes = volumesAsked && !nestedWhileInteracting;
  if (lightVolumes)
  {
    if (!in.LightVolumes.Update(window, uniforms, lightInputs, budget, problem))
    {
      return this->Fail(problem, budget.Refused());
    }
  }
  else if (!nestedWhileInteracting && in.LightVolumes.GetBytes() > 0)
  {
    in.LightVolumes.Release(window); // another model or the nested march: not held for nothing
  }
  // The multiple-scattering volume, after the light volumes (its source reads them, or marches
  // toward the lights in the frames that do), progressive when the mapper is asked to spread it
  // over frames.
  // A volume solved over the whole distributed field, when given, is read instead of one of the
  // input's own.
  const bool externalScattering =
    cloudvis::UsesScatteringVolume(uniforms.Lighting) && in.ExternalScattering.HasVolume();
  if (externalScattering)
  {
    if (!in.ExternalScattering.Update(window, budget, problem))
    {
      return this->Fail(problem, budget.Refused());
    }
    cloudvis::SetExternalScatteringVolume(uniforms, localFrame, &in.ExternalScattering.GetVolume());
  }
  else if (in.ExternalScattering.GetBytes() > 0)
  {
    in.ExternalScattering.Release(window);
  }
  const bool scatteringVolume =
    cloudvis::UsesScatteringVolume(uniforms.Lighting) && !externalScattering;
  if (scatteringVolume)
  {
    cloudvis::ScatteringVolumeTexture::Inputs scatteringInputs;
    static_cast<cloudvis::LightVolumeTexture::Inputs&>(scatteringInputs) = lightInputs;
    scatteringInputs.LightVolumes = lightVolumes ? &in.LightVolumes : nullptr;
    if (!in.Scattering.Update(window,
          uniforms,
          scatteringInputs,
          budget,
          problem,
          this->ScatteringVolumeSecondsPerFrame))
    {
      return this->Fail(problem);
    }
  }
  else if (!scatteringVolume && in.Scattering.GetBytes() > 0)
  {
    in.Scattering.Release(window);
  }
  uniforms.ScatteringVolumeTextures = scatteringVolume;

  // Progressive accumulation: continue averaging while everything the image depends on holds.
  // The temporal history survives a change of the camera (with the lights that follow it) and of
  // the march's scale, not of the rest (the content).
  std::vector<double> content(glm::value_ptr(modelToWorld), glm::value_ptr(modelToWorld) + 16);
  for (double v : { double(viewport[2]),
         double(viewport[3]),
         double(in.Density.GetUploadTime()),
         double(in.Transfer.GetTableTime()),
         double(this->GetMTime()),
         double(volume->GetMTime()),
         double(LatestChangeOfOtherProps(renderer, volume)),
         double(LatestChangeOfLights(renderer, this->CloudLights, false)),
         double(in.Scattering.GetComputeCount()),
         in.ExternalScattering.GetUploadTime() })
  {
    content.push_back(v);
  }
  std::vector<double> signature(glm::value_ptr(worldToDevice), glm::value_ptr(worldToDevice) + 16);
  signature.insert(signature.end(), content.begin(), content.end());
  signature.push_back(scale);
  signature.push_back(double(LatestChangeOfLights(renderer, this->CloudLights)));
  // Frames marched toward the lights (while interacting) and through the volumes never average
  // together; the history may blend them, as their difference is small against the motion's.
  signature.push_back(double(lightVolumes));
  view.Continue(signature);

  const bool pathTrace = uniforms.Lighting.Model == cloudvis::LightingModel::PathTrace;
  view.Marched = false;
  if (this->TemporalReprojection && this->DisplayMode == Radiance && !pathTrace)
  {
    if (!view.History.Resize(window, viewport[2], viewport[3], budget, problem))
    {
      return this->Fail(problem);
    }
    view.History.BeginFrame(content, interacting, deviceToLocal);
    // The depth where the opacity passes 2% moves by up to a step with the jitter, and the
    // closest depth of a neighbourhood lies a little before a pixel's own.
    view.History.DepthTolerance = HistoryDepthSteps * uniforms.Step;
  }
  else
  {
    view.History.Release(window);
  }
  if (view.AccumulatedFrames >= this->MaximumAccumulatedFrames)
  {
    return true; // converged: the composite pass shows the accumulated image again
  }

  // The march is one shader; a lighting model only supplies its source term, and the field's
  // occupancy picks the loop's variant.
  int samplesPerMapRead = this->SamplesPerMapRead;
  if (!this->EmptySpaceSkipping)
  {
    samplesPerMapRead = 1; // no map is read
  }
  else if (samplesPerMapRead == 0)
  {
    samplesPerMapRead = cloudvis::SamplesPerMapRead(in.Occupancy.GetOccupiedFraction());
  }
  vtkShaderProgram* program = in.March.Ready(window,
    uniforms.Lighting.Model,
    uniforms.Lights,
    samplesPerMapRead,
    cloudvis::MarchSwitchesOf(uniforms, lightVolumes));
  if (!program)
  {
    return this->Fail("the march shader failed to compile or link (the driver's log is in VTK's "
                      "error output)");
  }

  const double start = vtkTimerLog::GetUniversalTime();
  if (interacting)
  {
    window->WaitForCompletion(); // time the march alone
  }

  if (pathTrace &&
    (!in.ExtinctionBounds.Update(window, in.Occupancy.GetBricks(), budget, problem) ||
      !view.AllocateMoments(window, budget, problem)))
  {
    return this->Fail(problem);
  }
  if (!pathTrace) // the path tracer's textures are not held for nothing, as the light volumes
  {
    in.ExtinctionBounds.Release(window);
    view.ReleaseMoments(window);
  }
  if (!view.BindTargets(window, pathTrace))
  {
    return this->Fail("the march framebuffer is incomplete on this GPU");
  }
  vtkOpenGLState::ScopedglViewport savedViewport(state);
  vtkOpenGLState::ScopedglEnableDisable savedBlend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable savedDepthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable savedScissor(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate savedBlendFunction(state);
  state->vtkglViewport(0, 0, marchWidth, marchHeight);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  // The targets hold the sum of the accumulated frames: the first overwrites, the next add.
  const int frame = view.AccumulatedFrames;
  if (frame == 0)
  {
    state->vtkglDisable(GL_BLEND);
  }
  else
  {
    state->vtkglEnable(GL_BLEND);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  }

  std::vector<vtkTextureObject*> textures = { in.Density.GetTexture(),
    in.Transfer.GetTexture(),
    in.Occupancy.GetTexture(),
    in.Jitter.GetTexture(),
    in.DropletPhase.GetTexture(),
    view.GetDepth() };
  if (pathTrace)
  {
    textures.push_back(in.ExtinctionBounds.GetTexture());
  }
  if (external)
  {
    textures.push_back(in.External.GetTexture());
  }
  for (vtkTextureObject* texture : textures)
  {
    texture->Activate();
  }
  SetMatrix(program, "DCLocalMatrix", deviceToLocal);
  cloudvis::SetMarchUniforms(program, uniforms);
  program->SetUniformi("DensityTexture", in.Density.GetTexture()->GetTextureUnit());
  program->SetUniformi("TransferTexture", in.Transfer.GetTexture()->GetTextureUnit());
  program->SetUniformi("EmptyDistanceTexture", in.Occupancy.GetTexture()->GetTextureUnit());
  program->SetUniformi("DropletPhaseTexture", in.DropletPhase.GetTexture()->GetTextureUnit());
  const float brickCount[3] = { float(bricks[0]), float(bricks[1]), float(bricks[2]) };
  program->SetUniform3f("BrickCount", brickCount);
  program->SetUniformf("BrickSize", float(this->BrickSize));
  program->SetUniformi("SkipEmptySpace", this->EmptySpaceSkipping ? 1 : 0);
  program->SetUniformi("DepthTexture", view.GetDepth()->GetTextureUnit());
  program->SetUniformi("JitterTexture", in.Jitter.GetTexture()->GetTextureUnit());
  program->SetUniformf("JitterTextureSize", float(cloudvis::JitterTexture::Size));
  // Reprojected frames follow the golden-ratio sequence on from the history's, so the images
  // blended into it have different jitter too.
  const int jitterFrame = frame + (view.History.Reproject ? view.History.Sequence : 0);
  program->SetUniformf("JitterOffset", float(std::fmod(jitterFrame * GoldenRatioFraction, 1.0)));
  program->SetUniformi("JitterEnabled", this->Jitter ? 1 : 0);
  program->SetUniformi("MaximumIterations", iterations);
  if (pathTrace)
  {
    // The same paths whatever the frame split: sample k of frame f is f * per frame + k.
    cloudvis::PathTraceFrame pathFrame;
    pathFrame.MaxBounces = this->PathTraceMaxBounces;
    pathFrame.Seed = this->PathTraceSeed;
    pathFrame.SamplesPerFrame = this->PathTraceSamplesPerFrame;
    pathFrame.SampleBase = frame * this->PathTraceSamplesPerFrame;
    pathFrame.MarchWidth = marchWidth;
    program->SetUniformi(
      "ExtinctionBoundsTexture", in.ExtinctionBounds.GetTexture()->GetTextureUnit());
    cloudvis::SetPathTraceUniforms(program, pathFrame);
  }
  if (marchModel || pathTrace) // both programs hold the march's lighting code and its sampler
  {
    if (lightVolumes) // (whether they are read is a constant of the program: MarchSwitches)
    {
      in.LightVolumes.Activate(program);
    }
    else // never read, but a sampler must name a unit of its own type
    {
      program->SetUniformi("LightVolumeTexture", in.Density.GetTexture()->GetTextureUnit());
    }
    cloudvis::BindExternalDepths(program,
      external ? in.External.GetTexture() : nullptr,
      in.Density.GetTexture()->GetTextureUnit());
  }
  if (scatteringVolume)
  {
    in.Scattering.Activate(program);
  }
  else if (externalScattering)
  {
    in.ExternalScattering.Activate(program);
  }
  else if (marchModel) // the octaves: never read, as above
  {
    program->SetUniformi("ScatteringVolumeTexture", in.Density.GetTexture()->GetTextureUnit());
    program->SetUniformi("ScatteringFluxTexture", in.Density.GetTexture()->GetTextureUnit());
  }
  in.March.Render();
  if (lightVolumes)
  {
    in.LightVolumes.Deactivate();
  }
  if (scatteringVolume)
  {
    in.Scattering.Deactivate();
  }
  if (externalScattering)
  {
    in.ExternalScattering.Deactivate();
  }
  for (vtkTextureObject* texture : textures)
  {
    texture->Deactivate();
  }
  view.UnbindTargets(window);
  view.Marched = true;
  view.AccumulatedFrames = frame + 1;
  view.LocalUnit = localFrame.Unit;
  view.PathTraced = pathTrace;
  view.SamplesPerFrame = this->PathTraceSamplesPerFrame;

  if (this->CollectStatistics)
  {
    this->ReadStatistics(renderer);
  }
  if (interacting)
  {
    window->WaitForCompletion();
    const double perPixel =
      (vtkTimerLog::GetUniversalTime() - start) / (double(marchWidth) * marchHeight);
    view.SecondsPerPixel =
      view.SecondsPerPixel > 0.0 ? 0.5 * (view.SecondsPerPixel + perPixel) : perPixel;
  }
  return true;
}

void vtkCloudVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& in = *this->Internal;
  in.Density.Release(window);
  in.Transfer.Release(window);
  in.DropletPhase.Release(window);
  in.Occupancy.Release(window);
  in.Jitter.Release(window);
  in.ExtinctionBounds.Release(window);
  in.LightVolumes.Release(window);
  in.Scattering.Release(window);
  in.External.Release(window);
  for (auto& view : in.Views)
  {
    view.second->Release(window);
  }
  in.Views.clear();
  in.March.Release();
  in.Composite.reset();
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkCloudVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "EmptySpaceSkipping: " << this->EmptySpaceSkipping << "\n";
  os << indent << "BrickSize: " << this->BrickSize << "\n";
  os << indent << "Jitter: " << this->Jitter << "\n";
  os << indent << "TerminationTransmittance: " << this->TerminationTransmittance << "\n";
  os << indent << "ExtinctionScale: " << this->ExtinctionScale << "\n";
  os << indent << "ResolutionScale: " << this->ResolutionScale << "\n";
  os << indent << "InteractiveFrameRate: " << this->InteractiveFrameRate << "\n";
  os << indent << "TemporalReprojection: " << this->TemporalReprojection << "\n";
  os << indent << "MaximumAccumulatedFrames: " << this->MaximumAccumulatedFrames << "\n";
  os << indent << "DisplayMode: " << this->DisplayMode << "\n";
  os << indent << "CollectStatistics: " << this->CollectStatistics << "\n";
  os << indent << "HalfFloatDensity: " << this->HalfFloatDensity << "\n";
  os << indent << "MaximumGPUMemory: " << this->MaximumGPUMemory << "\n";
  os << indent << "PathTraceSamplesPerFrame: " << this->PathTraceSamplesPerFrame << "\n";
  os << indent << "PathTraceSeed: " << this->PathTraceSeed << "\n";
  os << indent << "PathTraceMaxBounces: " << this->PathTraceMaxBounces << "\n";
  os << indent << "ScatteringVolumeSecondsPerFrame: " << this->ScatteringVolumeSecondsPerFrame
     << "\n";
  os << indent << "LightingProperty:\n";
  this->LightingProperty->PrintSelf(os, indent.GetNextIndent());
}
