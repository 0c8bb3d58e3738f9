#include "vtkCloudVolumeMapper.h"

#include "CloudBlueNoise.h"
#include "CloudFieldGeometry.h"
#include "CloudMarchUniforms.h"
#include "CloudTransferTable.h"
#include "vtkCloudOccupancyFilter.h"

#include "CloudCompositeFS.h"
#include "CloudLightingCommon.h"
#include "CloudLightingDerivative.h"
#include "CloudLightingMarch.h"
#include "CloudLightingNone.h"
#include "CloudMarchFS.h"

#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkObjectFactory.h>
#include <vtkOpenGLCamera.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkPropCollection.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtkTimerLog.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtk_glew.h>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkCloudVolumeMapper);

namespace
{
constexpr int TransferTableSize = 1024;
constexpr double GoldenRatioFraction = 0.61803398874989484;
// The GLSL's MAX_LIGHTS, substituted into its source: the limit SetUpMarch enforces.
constexpr int MaxLights = cloudvis::LightingLimits::MaxLights;

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

void SetMatrix(vtkShaderProgram* program, const char* name, const glm::dmat4& m)
{
  glm::mat4 f(m);
  program->SetUniformMatrix4x4(name, glm::value_ptr(f));
}

// Scalars as float, the format of the density texture.
std::vector<float> ToFloat(vtkDataArray* scalars)
{
  std::vector<float> values(static_cast<size_t>(scalars->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
  {
    values[i] = static_cast<float>(scalars->GetComponent(i, 0));
  }
  return values;
}
}

// What the mapper keeps for one renderer: its targets and its accumulation.
struct ViewTargets
{
  vtkNew<vtkTextureObject> Depth;
  vtkNew<vtkTextureObject> Color;  // premultiplied radiance and opacity, RGBA32F
  vtkNew<vtkTextureObject> Counts; // samples taken, useful samples, depth of the cloud
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  int ViewportSize[2] = { 0, 0 };
  int MarchSize[2] = { 0, 0 };
  std::vector<double> Signature; // what the accumulated image depends on
  int AccumulatedFrames = 0;
  double SecondsPerPixel = 0.0; // measured march cost, for the interactive scale
  double MostSamplesPerRay = 1.0; // a ray across the whole volume: full scale of the count view
  double LocalUnit = 1.0;         // world units per local unit of the march's frame, for its depths

  void Release(vtkWindow* window)
  {
    this->Depth->ReleaseGraphicsResources(window);
    this->Color->ReleaseGraphicsResources(window);
    this->Counts->ReleaseGraphicsResources(window);
    this->Framebuffer->ReleaseGraphicsResources(window);
    this->ViewportSize[0] = this->ViewportSize[1] = 0;
    this->MarchSize[0] = this->MarchSize[1] = 0;
    this->AccumulatedFrames = 0;
  }
};

struct vtkCloudVolumeMapper::Internals
{
  vtkNew<vtkTextureObject> Density;
  vtkNew<vtkTextureObject> Transfer;
  vtkNew<vtkTextureObject> EmptyDistance;
  vtkNew<vtkTextureObject> Jitter;
  vtkNew<vtkCloudOccupancyFilter> Occupancy;
  vtkNew<vtkImageData> OccupancyInput; // the mapped scalars as the active scalars
  cloudvis::TransferTable Table;
  vtkMTimeType DensityUploadTime = 0;
  vtkMTimeType TableTime = 0;
  double TableExtinctionScale = -1.0;
  vtkMTimeType EmptyDistanceUploadTime = 0;
  vtkImageData* UploadedInput = nullptr; // identity only, never dereferenced
  int BrickCount[3] = { 0, 0, 0 };
  double OccupiedBrickFraction = 0.0;
  int JitterSize = 0;
  // One march program per lighting model and kind of lights, e.g. "march:DP" for a directional
  // and a point light: the light terms are then calls with constant indices.
  std::map<std::string, std::unique_ptr<vtkOpenGLQuadHelper>> March;
  std::unique_ptr<vtkOpenGLQuadHelper> Composite;
  std::map<vtkRenderer*, std::unique_ptr<ViewTargets>> Views; // keys are identities only
  std::string ReportedError; // reported once, until a render succeeds again

  ViewTargets& ViewOf(vtkRenderer* renderer)
  {
    auto& view = this->Views[renderer];
    if (!view)
    {
      view = std::make_unique<ViewTargets>();
    }
    return *view;
  }
};

vtkCloudVolumeMapper::vtkCloudVolumeMapper()
  : Internal(new Internals)
{
}

vtkCloudVolumeMapper::~vtkCloudVolumeMapper() = default;

bool vtkCloudVolumeMapper::Fail(const std::string& message)
{
  this->LastError = message;
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

vtkImageData* vtkCloudVolumeMapper::ValidInput(vtkVolume* volume)
{
  vtkImageData* input = vtkImageData::SafeDownCast(this->GetInput());
  if (!input)
  {
    this->Fail("the volume mapper has no input image");
    return nullptr;
  }
  int cellFlag = 0;
  vtkDataArray* scalars = this->GetScalars(
    input, this->ScalarMode, this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
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

bool vtkCloudVolumeMapper::UpdateVolumeTextures(
  vtkRenderer* renderer, vtkVolume* volume, vtkImageData* input)
{
  Internals& in = *this->Internal;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  int cellFlag = 0;
  vtkDataArray* scalars = this->GetScalars(
    input, this->ScalarMode, this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  int dimensions[3];
  input->GetDimensions(dimensions);

  // The density, uploaded again only when the data change.
  const vtkMTimeType dataTime = std::max(input->GetMTime(), scalars->GetMTime());
  if (in.UploadedInput != input || in.DensityUploadTime < dataTime || !in.Density->GetHandle())
  {
    const std::string valueProblem = cloudvis::ValidateDensityValues(scalars);
    if (!valueProblem.empty())
    {
      return this->Fail(valueProblem);
    }
    const int limit = vtkTextureObject::GetMaximumTextureSize3D(window);
    if (dimensions[0] > limit || dimensions[1] > limit || dimensions[2] > limit)
    {
      std::ostringstream message;
      message << "the field has " << dimensions[0] << " x " << dimensions[1] << " x "
              << dimensions[2] << " voxels; this GPU's 3-D textures hold at most " << limit
              << " per axis";
      return this->Fail(message.str());
    }
    in.Density->SetContext(window);
    bool uploaded = false;
    if (scalars->GetDataType() == VTK_FLOAT)
    {
      uploaded = in.Density->Create3DFromRaw(dimensions[0], dimensions[1], dimensions[2], 1,
        VTK_FLOAT, scalars->GetVoidPointer(0));
    }
    else
    {
      std::vector<float> values = ToFloat(scalars);
      uploaded = in.Density->Create3DFromRaw(
        dimensions[0], dimensions[1], dimensions[2], 1, VTK_FLOAT, values.data());
    }
    if (!uploaded)
    {
      return this->Fail("the GPU could not allocate the 3-D density texture");
    }
    in.Density->SetWrapS(vtkTextureObject::ClampToEdge);
    in.Density->SetWrapT(vtkTextureObject::ClampToEdge);
    in.Density->SetWrapR(vtkTextureObject::ClampToEdge);
    in.Density->SetMinificationFilter(vtkTextureObject::Linear);
    in.Density->SetMagnificationFilter(vtkTextureObject::Linear);
    in.UploadedInput = input;
    in.DensityUploadTime = dataTime;

    in.OccupancyInput->Initialize();
    in.OccupancyInput->SetDimensions(dimensions);
    in.OccupancyInput->SetOrigin(input->GetOrigin());
    in.OccupancyInput->SetSpacing(input->GetSpacing());
    in.OccupancyInput->GetPointData()->SetScalars(scalars);
    in.Occupancy->SetInputData(in.OccupancyInput);
  }

  // The transfer table, over the transfer function's own densities (not the data's), rebuilt
  // when the property or the mapper change.
  vtkVolumeProperty* property = volume->GetProperty();
  const vtkMTimeType tableTime = property->GetMTime();
  if (in.TableTime < tableTime || in.TableExtinctionScale != this->ExtinctionScale ||
    !in.Transfer->GetHandle())
  {
    const std::string problem = cloudvis::ValidateTransferFunction(
      property->GetScalarOpacity(0), property->GetRGBTransferFunction(0));
    if (!problem.empty())
    {
      return this->Fail("transfer function: " + problem);
    }
    in.Table = cloudvis::TabulateTransferFunction(property->GetRGBTransferFunction(0),
      property->GetScalarOpacity(0),
      property->GetScalarOpacityUnitDistance(0),
      TransferTableSize,
      this->ExtinctionScale);
    if (in.Table.Size < 1)
    {
      return this->Fail("transfer function: the unit distance must be a positive finite number");
    }
    in.Transfer->SetContext(window);
    if (!in.Transfer->Create1DFromRaw(in.Table.Size, 4, VTK_FLOAT, in.Table.RGBA.data()))
    {
      return this->Fail("the GPU could not allocate the transfer-function texture");
    }
    in.Transfer->SetWrapS(vtkTextureObject::ClampToEdge);
    in.Transfer->SetMinificationFilter(vtkTextureObject::Linear);
    in.Transfer->SetMagnificationFilter(vtkTextureObject::Linear);
    in.Occupancy->SetTransferTable(in.Table);
    in.TableTime = tableTime;
    in.TableExtinctionScale = this->ExtinctionScale;
  }

  // The occupancy map; the filter re-executes only when the density or the table changed.
  in.Occupancy->SetBrickSize(this->BrickSize);
  in.Occupancy->Update();
  vtkImageData* occupancy = in.Occupancy->GetOutput();
  if (in.EmptyDistanceUploadTime < occupancy->GetMTime() || !in.EmptyDistance->GetHandle())
  {
    auto* distance = vtkUnsignedCharArray::SafeDownCast(
      occupancy->GetPointData()->GetArray("empty_distance"));
    if (!distance)
    {
      return this->Fail("the occupancy filter produced no empty_distance array");
    }
    occupancy->GetDimensions(in.BrickCount);
    in.EmptyDistance->SetContext(window);
    if (!in.EmptyDistance->Create3DFromRaw(in.BrickCount[0], in.BrickCount[1], in.BrickCount[2],
          1, VTK_UNSIGNED_CHAR, distance->GetPointer(0)))
    {
      return this->Fail("the GPU could not allocate the occupancy texture");
    }
    in.EmptyDistance->SetWrapS(vtkTextureObject::ClampToEdge);
    in.EmptyDistance->SetWrapT(vtkTextureObject::ClampToEdge);
    in.EmptyDistance->SetWrapR(vtkTextureObject::ClampToEdge);
    in.EmptyDistance->SetMinificationFilter(vtkTextureObject::Nearest);
    in.EmptyDistance->SetMagnificationFilter(vtkTextureObject::Nearest);
    const vtkIdType bricks = distance->GetNumberOfValues();
    vtkIdType occupied = 0;
    for (vtkIdType b = 0; b < bricks; ++b)
    {
      occupied += distance->GetValue(b) == 0;
    }
    in.OccupiedBrickFraction = bricks ? double(occupied) / double(bricks) : 0.0;
    in.EmptyDistanceUploadTime = occupancy->GetMTime();
  }

  if (!in.Jitter->GetHandle())
  {
    const std::vector<float> mask = cloudvis::BlueNoiseMask(64);
    in.JitterSize = 64;
    in.Jitter->SetContext(window);
    std::vector<float> copy(mask);
    in.Jitter->Create2DFromRaw(64, 64, 1, VTK_FLOAT, copy.data());
    in.Jitter->SetWrapS(vtkTextureObject::Repeat);
    in.Jitter->SetWrapT(vtkTextureObject::Repeat);
    in.Jitter->SetMinificationFilter(vtkTextureObject::Nearest);
    in.Jitter->SetMagnificationFilter(vtkTextureObject::Nearest);
  }
  return true;
}

double vtkCloudVolumeMapper::ChooseResolutionScale(vtkRenderer* renderer)
{
  const bool interacting =
    this->InteractiveFrameRate > 0.0 && renderer->GetRenderWindow()->GetDesiredUpdateRate() > 1.0;
  if (!interacting)
  {
    return this->ResolutionScale;
  }
  const ViewTargets& view = this->Internal->ViewOf(renderer);
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

void vtkCloudVolumeMapper::SetLighting(const cloudvis::LightingParameters& lighting)
{
  this->Lighting = lighting;
  this->Modified();
}

namespace
{
// The renderer's switched-on lights as the lighting models see them, all of them: SetUpMarch
// refuses more than MaxLights rather than dropping some.
std::vector<cloudvis::Light> LightsOf(vtkRenderer* renderer)
{
  std::vector<cloudvis::Light> lights;
  vtkLightCollection* collection = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  collection->InitTraversal(it);
  while (vtkLight* light = collection->GetNextLight(it))
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    cloudvis::Light l;
    l.Positional = light->GetPositional() != 0;
    l.Position = glm::make_vec3(light->GetTransformedPosition());
    l.FocalPoint = glm::make_vec3(light->GetTransformedFocalPoint());
    l.Color = glm::vec3(glm::make_vec3(light->GetDiffuseColor()));
    l.Intensity = float(light->GetIntensity());
    l.Attenuation = glm::vec3(glm::make_vec3(light->GetAttenuationValues()));
    lights.push_back(l);
  }
  return lights;
}

// The lighting model's GLSL: shared helpers, the model's light terms, and a SourceTerm that
// calls one term per light with a constant index, so no light loop runs per sample.
std::string LightingSource(cloudvis::LightingModel model,
  const std::vector<cloudvis::LocalLight>& lights)
{
  std::string common = CloudLightingCommon;
  vtkShaderProgram::Substitute(
    common, "//CLOUD::MaxLights::Dec", "#define MAX_LIGHTS " + std::to_string(MaxLights));
  if (model == cloudvis::LightingModel::None)
  {
    return common + "\n" + CloudLightingNone;
  }
  std::ostringstream source;
  source << common << "\n"
         << (model == cloudvis::LightingModel::Derivative ? CloudLightingDerivative
                                                          : CloudLightingMarch)
         << "\nvec3 SourceTerm(vec3 p, float density, vec3 albedo, vec3 d)\n{\n"
         << "  vec3 light = Ambient;\n";
  for (size_t i = 0; i < lights.size(); ++i)
  {
    source << "  light += " << (lights[i].Positional ? "PointLightTerm" : "DirectionalLightTerm")
           << "(" << i << ", p, density, d);\n";
  }
  source << "  return albedo * light;\n}\n";
  return source.str();
}

vtkMTimeType LatestChangeOfLights(vtkRenderer* renderer)
{
  vtkMTimeType latest = renderer->GetLights()->GetMTime();
  vtkCollectionSimpleIterator it;
  renderer->GetLights()->InitTraversal(it);
  while (vtkLight* light = renderer->GetLights()->GetNextLight(it))
  {
    latest = std::max(latest, light->GetMTime());
  }
  return latest;
}
}

void vtkCloudVolumeMapper::SetMarchUniforms(vtkShaderProgram* program,
  const cloudvis::MarchUniforms& u)
{
  const float dims[3] = { float(u.Dimensions.x), float(u.Dimensions.y), float(u.Dimensions.z) };
  program->SetUniform3f("Dimensions", dims);
  program->SetUniformMatrix4x4("IndexToLocal", const_cast<float*>(glm::value_ptr(u.IndexToLocal)));
  program->SetUniformMatrix3x3("LocalToIndex", const_cast<float*>(glm::value_ptr(u.LocalToIndex)));
  const float tableRange[2] = { float(u.Table->Range[0]), float(u.Table->Range[1]) };
  program->SetUniform2f("TableRange", tableRange);
  program->SetUniformf("TableSize", float(u.Table->Size));
  program->SetUniformf("ExtinctionUnit", u.ExtinctionUnit);
  program->SetUniformf("Step", u.Step);
  program->SetUniformf("TerminationTransmittance", u.TerminationTransmittance);

  const cloudvis::LightingParameters& p = u.Lighting;
  std::vector<int> positional(MaxLights, 0);
  std::vector<float> position(3 * MaxLights, 0.0f), direction(3 * MaxLights, 0.0f),
    radiance(3 * MaxLights, 0.0f), attenuation(3 * MaxLights, 0.0f),
    indexDirection(3 * MaxLights, 0.0f), indexOffset(3 * MaxLights, 0.0f);
  for (size_t i = 0; i < u.Lights.size(); ++i)
  {
    const cloudvis::LocalLight& l = u.Lights[i];
    positional[i] = l.Positional ? 1 : 0;
    // Per directional light, what the CPU twin computes per sample: l and h l in index units.
    const glm::vec3 stepInIndex = u.LocalToIndex * l.Direction;
    const glm::vec3 offsetInIndex = u.LocalToIndex * (p.DerivativeDistance * l.Direction);
    for (int c = 0; c < 3; ++c)
    {
      position[3 * i + c] = l.Position[c];
      direction[3 * i + c] = l.Direction[c];
      radiance[3 * i + c] = l.Radiance[c];
      attenuation[3 * i + c] = l.Attenuation[c];
      indexDirection[3 * i + c] = l.Positional ? 0.0f : stepInIndex[c];
      indexOffset[3 * i + c] = l.Positional ? 0.0f : offsetInIndex[c];
    }
  }
  program->SetUniform1iv("LightPositional", MaxLights, positional.data());
  program->SetUniform3fv("LightIndexDirection", MaxLights, indexDirection.data());
  program->SetUniform3fv("LightIndexOffset", MaxLights, indexOffset.data());
  program->SetUniform3fv("LightPosition", MaxLights, position.data());
  program->SetUniform3fv("LightDirection", MaxLights, direction.data());
  program->SetUniform3fv("LightRadiance", MaxLights, radiance.data());
  program->SetUniform3fv("LightAttenuation", MaxLights, attenuation.data());
  program->SetUniform3f("Ambient", glm::value_ptr(u.Ambient));
  program->SetUniformf("DerivativeDistance", p.DerivativeDistance);
  program->SetUniformf("DerivativeSlopeScale", u.DerivativeSlopeScale);
  program->SetUniformi("LightSteps", p.LightSteps);
  program->SetUniformf("LightStep", p.LightStep);
  program->SetUniformf("LightStepGrowth", p.LightStepGrowth);
  program->SetUniformf("PhaseG1", p.PhaseG1);
  program->SetUniformf("PhaseG2", p.PhaseG2);
  program->SetUniformf("PhaseLobeWeight", p.PhaseLobeWeight);
  program->SetUniformi("MultipleScatteringOctaves", p.MultipleScatteringOctaves);
  program->SetUniformf("ScatteringFalloff", p.ScatteringFalloff);
  program->SetUniformf("ExtinctionFalloff", p.ExtinctionFalloff);
  program->SetUniformf("EccentricityFalloff", p.EccentricityFalloff);
  program->SetUniformf("PowderStrength", p.PowderStrength);
}

void vtkCloudVolumeMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  this->LastError.clear();
  vtkImageData* input = this->ValidInput(volume);
  if (!input || !this->UpdateVolumeTextures(renderer, volume, input))
  {
    return;
  }
  this->MarchPass(renderer, volume, input);
  if (this->LastError.empty())
  {
    this->CompositePass(renderer);
  }
  if (this->LastError.empty())
  {
    this->Internal->ReportedError.clear();
  }
}

namespace
{
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

void vtkCloudVolumeMapper::MarchPass(vtkRenderer* renderer, vtkVolume* volume, vtkImageData* input)
{
  Internals& in = *this->Internal;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  vtkOpenGLState* state = window->GetState();
  ViewTargets& view = in.ViewOf(renderer);

  int viewport[4];
  renderer->GetTiledSizeAndOrigin(&viewport[2], &viewport[3], &viewport[0], &viewport[1]);
  const double scale = this->ChooseResolutionScale(renderer);
  const int marchWidth = std::max(1, int(std::lround(viewport[2] * scale)));
  const int marchHeight = std::max(1, int(std::lround(viewport[3] * scale)));

  // Targets follow the viewport and the scale.
  if (view.ViewportSize[0] != viewport[2] || view.ViewportSize[1] != viewport[3] ||
    !view.Depth->GetHandle())
  {
    view.Depth->SetContext(window);
    view.Depth->AllocateDepth(viewport[2], viewport[3], vtkTextureObject::Float32);
    view.Depth->SetMinificationFilter(vtkTextureObject::Nearest);
    view.Depth->SetMagnificationFilter(vtkTextureObject::Nearest);
    view.Depth->SetWrapS(vtkTextureObject::ClampToEdge);
    view.Depth->SetWrapT(vtkTextureObject::ClampToEdge);
    view.ViewportSize[0] = viewport[2];
    view.ViewportSize[1] = viewport[3];
  }
  if (view.MarchSize[0] != marchWidth || view.MarchSize[1] != marchHeight ||
    !view.Color->GetHandle())
  {
    for (vtkTextureObject* target : { view.Color.Get(), view.Counts.Get() })
    {
      target->SetContext(window);
      target->SetMinificationFilter(vtkTextureObject::Nearest);
      target->SetMagnificationFilter(vtkTextureObject::Nearest);
      target->SetWrapS(vtkTextureObject::ClampToEdge);
      target->SetWrapT(vtkTextureObject::ClampToEdge);
    }
    view.Color->SetInternalFormat(GL_RGBA32F);
    view.Color->SetFormat(GL_RGBA);
    view.Color->Allocate2D(marchWidth, marchHeight, 4, VTK_FLOAT);
    view.Counts->SetInternalFormat(GL_RGBA32F);
    view.Counts->SetFormat(GL_RGBA);
    view.Counts->Allocate2D(marchWidth, marchHeight, 4, VTK_FLOAT);
    view.Framebuffer->SetContext(window);
    view.MarchSize[0] = marchWidth;
    view.MarchSize[1] = marchHeight;
    view.AccumulatedFrames = 0;
  }
  // The opaque scene's depth, which ends the rays.
  view.Depth->CopyFromFrameBuffer(viewport[0], viewport[1], 0, 0, viewport[2], viewport[3]);

  // The march's uniforms, the same SetUpMarch computes for the CPU reference, and its refusals.
  cloudvis::MarchSetup setup;
  setup.Geometry = cloudvis::GeometryOf(input, volume->GetMatrix());
  setup.Table = &in.Table;
  setup.SampleDistance = this->SampleDistance;
  setup.TerminationTransmittance = this->TerminationTransmittance;
  setup.Lighting = this->Lighting;
  setup.Lights = LightsOf(renderer);
  cloudvis::MarchUniforms uniforms;
  cloudvis::LocalFrame localFrame;
  const cloudvis::MarchProblem problem = cloudvis::SetUpMarch(setup, uniforms, &localFrame);
  if (problem)
  {
    this->Fail(problem.Message);
    return;
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

  view.MostSamplesPerRay = std::max(1.0, double(uniforms.MaximumSamples - 16));
  // One iteration per sample, and at most about three leaps per brick crossed.
  const int iterations =
    uniforms.MaximumSamples + 3 * (in.BrickCount[0] + in.BrickCount[1] + in.BrickCount[2]);

  // Progressive accumulation: continue averaging while everything the image depends on holds.
  std::vector<double> signature(glm::value_ptr(worldToDevice), glm::value_ptr(worldToDevice) + 16);
  signature.insert(signature.end(), glm::value_ptr(modelToWorld), glm::value_ptr(modelToWorld) + 16);
  for (double v : { double(viewport[2]), double(viewport[3]), scale, double(in.DensityUploadTime),
         double(in.TableTime), double(this->GetMTime()), double(volume->GetMTime()),
         double(LatestChangeOfOtherProps(renderer, volume)), double(LatestChangeOfLights(renderer)) })
  {
    signature.push_back(v);
  }
  if (signature != view.Signature)
  {
    view.Signature = signature;
    view.AccumulatedFrames = 0;
  }
  if (view.AccumulatedFrames >= this->MaximumAccumulatedFrames)
  {
    return; // converged: the composite pass shows the accumulated image again
  }

  // The march is one shader; a lighting model only supplies its source term.
  const std::vector<cloudvis::LocalLight>& lights = uniforms.Lights;
  std::string key = std::to_string(int(this->Lighting.Model)) + ":";
  if (this->Lighting.Model != cloudvis::LightingModel::None)
  {
    for (const cloudvis::LocalLight& light : lights)
    {
      key += light.Positional ? 'P' : 'D';
    }
  }
  std::unique_ptr<vtkOpenGLQuadHelper>& march = in.March[key];
  if (!march)
  {
    std::string source = CloudMarchFS;
    vtkShaderProgram::Substitute(source, "//CLOUD::Lighting::Dec", LightingSource(this->Lighting.Model, lights));
    march = std::make_unique<vtkOpenGLQuadHelper>(window, nullptr, source.c_str(), "");
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(march->Program);
  }
  vtkShaderProgram* program = march->Program;
  if (!program || !program->GetCompiled())
  {
    this->Fail("the march shader failed to compile or link (the driver's log is in VTK's error "
               "output)");
    return;
  }

  const bool interacting =
    this->InteractiveFrameRate > 0.0 && window->GetDesiredUpdateRate() > 1.0;
  const double start = vtkTimerLog::GetUniversalTime();
  if (interacting)
  {
    glFinish(); // time the march alone
  }

  state->PushFramebufferBindings();
  view.Framebuffer->Bind();
  view.Framebuffer->AddColorAttachment(0, view.Color);
  view.Framebuffer->AddColorAttachment(1, view.Counts);
  view.Framebuffer->ActivateDrawBuffers(2);
  if (!view.Framebuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER))
  {
    state->PopFramebufferBindings();
    this->Fail("the march framebuffer is incomplete on this GPU");
    return;
  }
  vtkOpenGLState::ScopedglViewport savedViewport(state);
  vtkOpenGLState::ScopedglEnableDisable savedBlend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable savedDepthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable savedScissor(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate savedBlendFunction(state);
  state->vtkglViewport(0, 0, marchWidth, marchHeight);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  // Frame n + 1 of an accumulation weighs 1 / (n + 1): a running mean through the blend unit.
  const int frame = view.AccumulatedFrames;
  if (frame == 0)
  {
    state->vtkglDisable(GL_BLEND);
  }
  else
  {
    state->vtkglEnable(GL_BLEND);
    glBlendColor(0.0f, 0.0f, 0.0f, 1.0f / float(frame + 1));
    state->vtkglBlendFuncSeparate(
      GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA, GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA);
  }

  for (vtkTextureObject* texture : { in.Density.Get(), in.Transfer.Get(), in.EmptyDistance.Get(),
         in.Jitter.Get(), view.Depth.Get() })
  {
    texture->Activate();
  }
  SetMatrix(program, "DCLocalMatrix", deviceToLocal);
  this->SetMarchUniforms(program, uniforms);
  program->SetUniformi("DensityTexture", in.Density->GetTextureUnit());
  program->SetUniformi("TransferTexture", in.Transfer->GetTextureUnit());
  program->SetUniformi("EmptyDistanceTexture", in.EmptyDistance->GetTextureUnit());
  const float bricks[3] = { float(in.BrickCount[0]), float(in.BrickCount[1]),
    float(in.BrickCount[2]) };
  program->SetUniform3f("BrickCount", bricks);
  program->SetUniformf("BrickSize", float(this->BrickSize));
  program->SetUniformi("SkipEmptySpace", this->EmptySpaceSkipping ? 1 : 0);
  program->SetUniformi("DepthTexture", view.Depth->GetTextureUnit());
  program->SetUniformi("JitterTexture", in.Jitter->GetTextureUnit());
  program->SetUniformf("JitterTextureSize", float(in.JitterSize));
  program->SetUniformf("JitterOffset", float(std::fmod(frame * GoldenRatioFraction, 1.0)));
  program->SetUniformi("JitterEnabled", this->Jitter ? 1 : 0);
  program->SetUniformi("MaximumIterations", iterations);
  march->Render();
  for (vtkTextureObject* texture : { in.Density.Get(), in.Transfer.Get(), in.EmptyDistance.Get(),
         in.Jitter.Get(), view.Depth.Get() })
  {
    texture->Deactivate();
  }
  glBlendColor(0.0f, 0.0f, 0.0f, 0.0f);
  view.AccumulatedFrames = frame + 1;
  view.LocalUnit = localFrame.Unit;

  if (this->CollectStatistics)
  {
    this->ReadStatistics(renderer);
  }
  view.Framebuffer->RemoveColorAttachments(2);
  state->PopFramebufferBindings();

  if (interacting)
  {
    glFinish();
    const double perPixel =
      (vtkTimerLog::GetUniversalTime() - start) / (double(marchWidth) * marchHeight);
    view.SecondsPerPixel =
      view.SecondsPerPixel > 0.0 ? 0.5 * (view.SecondsPerPixel + perPixel) : perPixel;
  }
}

void vtkCloudVolumeMapper::ReadStatistics(vtkRenderer* renderer)
{
  ViewTargets& view = this->Internal->ViewOf(renderer);
  const int w = view.MarchSize[0], h = view.MarchSize[1];
  std::vector<float> counts(size_t(w) * h * 4);
  view.Framebuffer->ActivateReadBuffer(1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, counts.data());
  FrameStatistics statistics;
  for (size_t i = 0; i < counts.size(); i += 4)
  {
    statistics.SamplesTaken += counts[i];
    statistics.UsefulSamples += counts[i + 1];
  }
  statistics.Width = w;
  statistics.Height = h;
  statistics.OccupiedBrickFraction = this->Internal->OccupiedBrickFraction;
  this->LastStatistics = statistics;
}

bool vtkCloudVolumeMapper::ReadTarget(
  vtkRenderer* renderer, int target, std::vector<float>& rgba, int& width, int& height)
{
  auto found = this->Internal->Views.find(renderer);
  if (found == this->Internal->Views.end() || !found->second->Color->GetHandle())
  {
    return false;
  }
  ViewTargets& view = *found->second;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  window->MakeCurrent();
  vtkOpenGLState* state = window->GetState();
  width = view.MarchSize[0];
  height = view.MarchSize[1];
  rgba.resize(size_t(width) * height * 4);
  state->PushFramebufferBindings();
  view.Framebuffer->Bind();
  view.Framebuffer->AddColorAttachment(0, target == 0 ? view.Color.Get() : view.Counts.Get());
  view.Framebuffer->ActivateReadBuffer(0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rgba.data());
  view.Framebuffer->RemoveColorAttachments(1);
  state->PopFramebufferBindings();
  return true;
}

bool vtkCloudVolumeMapper::ReadImage(
  vtkRenderer* renderer, std::vector<float>& rgba, int& width, int& height)
{
  return this->ReadTarget(renderer, 0, rgba, width, height);
}

bool vtkCloudVolumeMapper::ReadAuxiliary(
  vtkRenderer* renderer, std::vector<float>& channels, int& width, int& height)
{
  if (!this->ReadTarget(renderer, 1, channels, width, height))
  {
    return false;
  }
  // The march writes local distances, and NoDepth (1e30) where the cloud never passes 2%: an
  // average over frames that holds it in any one of them is still above 1e30 / 65536.
  const double unit = this->Internal->ViewOf(renderer).LocalUnit;
  for (size_t i = 2; i < channels.size(); i += 4)
  {
    channels[i] = channels[i] >= 1e24f ? std::numeric_limits<float>::infinity()
                                       : float(double(channels[i]) * unit);
  }
  return true;
}

void vtkCloudVolumeMapper::CompositePass(vtkRenderer* renderer)
{
  Internals& in = *this->Internal;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  vtkOpenGLState* state = window->GetState();
  ViewTargets& view = in.ViewOf(renderer);
  if (!in.Composite)
  {
    in.Composite = std::make_unique<vtkOpenGLQuadHelper>(window, nullptr, CloudCompositeFS, "");
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(in.Composite->Program);
  }
  vtkShaderProgram* program = in.Composite->Program;
  if (!program || !program->GetCompiled())
  {
    this->Fail("the composite shader failed to compile or link (the driver's log is in VTK's "
               "error output)");
    return;
  }

  int viewport[4];
  renderer->GetTiledSizeAndOrigin(&viewport[2], &viewport[3], &viewport[0], &viewport[1]);
  vtkOpenGLState::ScopedglViewport savedViewport(state);
  vtkOpenGLState::ScopedglEnableDisable savedBlend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable savedDepthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate savedBlendFunction(state);
  vtkOpenGLState::ScopedglDepthMask savedDepthMask(state);
  state->vtkglViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglEnable(GL_BLEND);
  // Premultiplied "over": the cloud in front of what the renderer has drawn.
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);

  view.Color->Activate();
  view.Counts->Activate();
  program->SetUniformi("MarchTexture", view.Color->GetTextureUnit());
  program->SetUniformi("CountTexture", view.Counts->GetTextureUnit());
  const float marchSize[2] = { float(view.MarchSize[0]), float(view.MarchSize[1]) };
  program->SetUniform2f("MarchSize", marchSize);
  program->SetUniformi(
    "Upsample", view.MarchSize[0] != viewport[2] || view.MarchSize[1] != viewport[3] ? 1 : 0);
  program->SetUniformi("ShowSampleCount", this->DisplayMode == SampleCount ? 1 : 0);
  program->SetUniformf("SampleCountScale", float(1.0 / view.MostSamplesPerRay));
  in.Composite->Render();
  view.Color->Deactivate();
  view.Counts->Deactivate();
}

void vtkCloudVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& in = *this->Internal;
  in.Density->ReleaseGraphicsResources(window);
  in.Transfer->ReleaseGraphicsResources(window);
  in.EmptyDistance->ReleaseGraphicsResources(window);
  in.Jitter->ReleaseGraphicsResources(window);
  for (auto& view : in.Views)
  {
    view.second->Release(window);
  }
  in.Views.clear();
  in.March.clear();
  in.Composite.reset();
  in.UploadedInput = nullptr;
  in.DensityUploadTime = in.TableTime = in.EmptyDistanceUploadTime = 0;
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
  os << indent << "MaximumAccumulatedFrames: " << this->MaximumAccumulatedFrames << "\n";
  os << indent << "DisplayMode: " << this->DisplayMode << "\n";
  os << indent << "CollectStatistics: " << this->CollectStatistics << "\n";
}
