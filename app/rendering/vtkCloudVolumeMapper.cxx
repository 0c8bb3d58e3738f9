// vtkCloudVolumeMapper: its settings, the textures it keeps up to date and the checks of its
// input. The march pass (its phases, and the uniforms it computes: the same MarchUniforms the
// CPU reference computes with), the composite pass and the read-backs are
// vtkCloudVolumeMapperMarch.cxx's, vtkCloudVolumeMapperComposite.cxx's and
// vtkCloudVolumeMapperReadBack.cxx's; what the four share is CloudVolumeMapperInternals.h.
#include "vtkCloudVolumeMapper.h"

#include "CloudFieldGeometry.h"
#include "CloudGpuMemory.h"
#include "CloudMarchUniforms.h"
#include "CloudOpticalDepthGrid.h"
#include "CloudScatteringVolume.h"
#include "CloudVolumeMapperInternals.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkLightCollection.h>
#include <vtkMath.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkPointData.h>
#include <vtkTextureObject.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>
#include <limits>

using cloudvis::mapper::WindowOf;

static_assert(cloudvis::PathTraceBounceCap == 65536,
  "vtkCloudVolumeMapper.h's default PathTraceMaxBounces");

vtkStandardNewMacro(vtkCloudVolumeMapper);

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
  // What the march pass computes its uniforms from (MarchFrame::ComputeUniforms), from the objects
  // rather than the textures (which need a context and may not be made yet): the same texels, table
  // and lights.
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
