#include "vtkCloudReferenceRenderer.h"

#include "CloudFieldGeometry.h"
#include "CloudLightVolumes.h"
#include "CloudOpticalDepthGrid.h"
#include "CloudReferenceMarch.h"
#include "CloudScatteringVolume.h"
#include "CloudTransferTable.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkMath.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCloudReferenceRenderer);

namespace
{
bool Finite3(const double v[3])
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// A row-major 4x4 (m[row][col], as vtkMatrix4x4 and VTK's transforms write them) as GLM.
glm::dmat4 FromRows(const double m[4][4])
{
  glm::dmat4 g(0.0);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      g[c][r] = m[r][c];
  return g;
}

// Where normalized device coordinates (ndc, ndcDepth) lie in the local frame: the GLSL's
// LocalPoint with DCLocalMatrix, in double.
glm::dvec3 LocalPoint(const glm::dmat4& deviceToLocal, glm::dvec2 ndc, double ndcDepth)
{
  const glm::dvec4 p = deviceToLocal * glm::dvec4(ndc, ndcDepth, 1.0);
  return glm::dvec3(p) / p.w;
}

// vtkSMPTools::For wants a functor object.
struct RowFunctor
{
  const std::function<void(vtkIdType, vtkIdType)>* Rows;
  void operator()(vtkIdType begin, vtkIdType end) const { (*this->Rows)(begin, end); }
};
}

vtkCloudReferenceRenderer::vtkCloudReferenceRenderer()
  : LightingProperty(vtkSmartPointer<vtkCloudLightingProperty>::New())
  , Lights(vtkSmartPointer<vtkLightCollection>::New())
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

vtkCloudReferenceRenderer::~vtkCloudReferenceRenderer()
{
  this->SetVolumeProperty(nullptr);
}

vtkCxxSetObjectMacro(vtkCloudReferenceRenderer, VolumeProperty, vtkVolumeProperty);

void vtkCloudReferenceRenderer::SetLightingProperty(vtkCloudLightingProperty* property)
{
  if (!property || property != this->LightingProperty)
  {
    this->LightingProperty = property ? vtkSmartPointer<vtkCloudLightingProperty>(property)
                                      : vtkSmartPointer<vtkCloudLightingProperty>::New();
    this->Modified();
  }
}

void vtkCloudReferenceRenderer::SetLights(vtkLightCollection* lights)
{
  if (!lights || lights != this->Lights || this->CloudLights)
  {
    this->Lights = lights ? vtkSmartPointer<vtkLightCollection>(lights)
                          : vtkSmartPointer<vtkLightCollection>::New();
    this->CloudLights.reset();
    this->Modified();
  }
}

void vtkCloudReferenceRenderer::SetLights(const std::vector<cloudvis::Light>& lights)
{
  if (!this->CloudLights || *this->CloudLights != lights)
  {
    this->CloudLights = lights;
    this->Modified();
  }
}

void vtkCloudReferenceRenderer::SetExternalOpticalDepths(const cloudvis::OpticalDepthGrid& grid)
{
  this->ExternalDepths =
    grid.Empty() ? nullptr : std::make_shared<const cloudvis::OpticalDepthGrid>(grid);
  this->Modified();
}

void vtkCloudReferenceRenderer::SetExternalScatteringVolume(
  const cloudvis::WholeFieldScattering& volume)
{
  this->ExternalScattering =
    volume.Empty() ? nullptr : std::make_shared<const cloudvis::WholeFieldScattering>(volume);
  this->Modified();
}

const std::vector<cloudvis::Light>* vtkCloudReferenceRenderer::GetCloudLights() const
{
  return this->CloudLights ? &*this->CloudLights : nullptr;
}

std::vector<cloudvis::Light> vtkCloudReferenceRenderer::GetLightList() const
{
  return this->CloudLights ? *this->CloudLights : cloudvis::LightsOf(this->Lights);
}

vtkMTimeType vtkCloudReferenceRenderer::GetMTime()
{
  vtkMTimeType latest = this->Superclass::GetMTime();
  if (this->VolumeProperty)
  {
    latest = std::max(latest, this->VolumeProperty->GetMTime());
  }
  latest = std::max(latest, this->LightingProperty->GetMTime());
  if (this->CloudLights)
  {
    return latest; // the vtkLights light nothing
  }
  latest = std::max(latest, this->Lights->GetMTime());
  vtkCollectionSimpleIterator it;
  this->Lights->InitTraversal(it);
  while (vtkLight* light = this->Lights->GetNextLight(it))
  {
    latest = std::max(latest, light->GetMTime());
  }
  return latest;
}

void vtkCloudReferenceRenderer::SetVolumeMatrix(vtkMatrix4x4* matrix)
{
  vtkNew<vtkMatrix4x4> copy;
  if (matrix)
  {
    copy->DeepCopy(matrix);
  }
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      if (copy->GetElement(r, c) != this->VolumeMatrix->GetElement(r, c))
      {
        this->VolumeMatrix->DeepCopy(copy);
        this->Modified();
        return;
      }
}

bool vtkCloudReferenceRenderer::GetCamera(glm::dmat4& viewToDevice,
  glm::dmat3& worldToView,
  glm::dvec3& eye) const
{
  const double* position = this->CameraPosition;
  const double* focal = this->CameraFocalPoint;
  const double* up = this->CameraViewUp;
  const double* range = this->ClippingRange;
  if (!Finite3(position) || !Finite3(focal) || !Finite3(up) ||
    !(range[0] > 0.0 && range[1] > range[0] && std::isfinite(range[1])) || this->ImageSize[0] < 1 ||
    this->ImageSize[1] < 1)
  {
    return false;
  }
  if (this->ParallelProjection ? !(this->ParallelScale > 0.0 && std::isfinite(this->ParallelScale))
                               : !(this->ViewAngle > 0.0 && this->ViewAngle < 180.0))
  {
    return false;
  }
  // vtkPerspectiveTransform::SetupCamera: the rows of the rotation are the sideways, the
  // orthogonalised up and the view plane normal (from the focal point toward the camera).
  eye = glm::dvec3(position[0], position[1], position[2]);
  const glm::dvec3 toCamera = eye - glm::dvec3(focal[0], focal[1], focal[2]);
  const glm::dvec3 sidewaysRaw = glm::cross(glm::dvec3(up[0], up[1], up[2]), toCamera);
  if (!(glm::length(toCamera) > 0.0) || !(glm::length(sidewaysRaw) > 0.0))
  {
    return false; // the camera sits on its focal point, or looks along its view up
  }
  const glm::dvec3 viewPlaneNormal = glm::normalize(toCamera);
  const glm::dvec3 sideways = glm::normalize(sidewaysRaw);
  const glm::dvec3 orthoViewUp = glm::cross(viewPlaneNormal, sideways);
  worldToView = glm::transpose(glm::dmat3(sideways, orthoViewUp, viewPlaneNormal));

  // vtkCamera::ComputeProjectionTransform with the window centred and no shear: Ortho or
  // Frustum, as glOrtho and glFrustum define them.
  const double aspect = double(this->ImageSize[0]) / double(this->ImageSize[1]);
  const double zNear = range[0], zFar = range[1];
  double projection[4][4] = {};
  if (this->ParallelProjection)
  {
    const double height = this->ParallelScale;
    const double width = height * aspect;
    projection[0][0] = 2.0 / (2.0 * width);
    projection[1][1] = 2.0 / (2.0 * height);
    projection[2][2] = -2.0 / (zFar - zNear);
    projection[2][3] = -(zNear + zFar) / (zFar - zNear);
    projection[3][3] = 1.0;
  }
  else
  {
    const double tangent = std::tan(vtkMath::RadiansFromDegrees(this->ViewAngle) / 2.0);
    const double height = zNear * tangent;
    const double width = height * aspect;
    projection[0][0] = 2.0 * zNear / (2.0 * width);
    projection[1][1] = 2.0 * zNear / (2.0 * height);
    projection[2][2] = -(zNear + zFar) / (zFar - zNear);
    projection[2][3] = -2.0 * zNear * zFar / (zFar - zNear);
    projection[3][2] = -1.0;
  }
  viewToDevice = FromRows(projection);
  return true;
}

bool vtkCloudReferenceRenderer::GetDeviceToWorldMatrix(vtkMatrix4x4* deviceToWorld) const
{
  glm::dmat4 viewToDevice;
  glm::dmat3 worldToView;
  glm::dvec3 eye;
  if (!deviceToWorld || !this->GetCamera(viewToDevice, worldToView, eye))
  {
    return false;
  }
  glm::dmat4 worldToViewMatrix(worldToView);
  worldToViewMatrix[3] = glm::dvec4(-(worldToView * eye), 1.0);
  const glm::dmat4 inverse = glm::inverse(viewToDevice * worldToViewMatrix);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      deviceToWorld->SetElement(r, c, inverse[c][r]);
  return true;
}

int vtkCloudReferenceRenderer::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, std::max(this->ImageSize[0], 1) - 1, 0,
    std::max(this->ImageSize[1], 1) - 1, 0, 0 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  const double spacing[3] = { 1.0, 1.0, 1.0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 4);
  return 1;
}

int vtkCloudReferenceRenderer::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Any pixel's ray may cross any voxel: always ask for the whole field.
  const std::string problem = cloudvis::RequestWholeExtent(inputVector[0]->GetInformationObject(0));
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  return 1;
}

int vtkCloudReferenceRenderer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);

  // The parameters.
  std::string tableProblem;
  const cloudvis::TransferTable table =
    cloudvis::TransferTableOf(this->VolumeProperty, this->ExtinctionScale, tableProblem);
  if (!tableProblem.empty())
  {
    vtkErrorMacro(<< tableProblem << (this->VolumeProperty ? "" : ": call SetVolumeProperty"));
    return 0;
  }
  const int width = this->ImageSize[0], height = this->ImageSize[1];
  if (width < 1 || height < 1)
  {
    vtkErrorMacro(<< "the image size must be at least 1 x 1, not " << width << " x " << height);
    return 0;
  }
  glm::dmat4 viewToDevice;
  glm::dmat3 worldToView;
  glm::dvec3 eye;
  if (!this->GetCamera(viewToDevice, worldToView, eye))
  {
    vtkErrorMacro(<< "unusable camera: it needs a position away from the focal point, a view up "
                     "not along the view direction, 0 < near < far, a view angle in (0, 180) "
                     "and a parallel scale > 0");
    return 0;
  }

  // The input.
  vtkDataArray* scalars = input ? input->GetPointData()->GetScalars() : nullptr;
  const std::string scalarProblem = cloudvis::ValidateDensityScalars(scalars);
  if (!scalarProblem.empty())
  {
    vtkErrorMacro(<< scalarProblem);
    return 0;
  }
  const std::string valueProblem = cloudvis::ValidateDensityValues(scalars);
  if (!valueProblem.empty())
  {
    vtkErrorMacro(<< valueProblem);
    return 0;
  }
  int extent[6];
  input->GetExtent(extent);
  const vtkIdType voxels = vtkIdType(extent[1] - extent[0] + 1) * (extent[3] - extent[2] + 1) *
    (extent[5] - extent[4] + 1);
  if (scalars->GetNumberOfTuples() != voxels)
  {
    vtkErrorMacro(<< "the input scalars do not match the input extent");
    return 0;
  }
  const std::string geometryProblem = cloudvis::ValidateVolumeGeometry(input, this->VolumeMatrix);
  if (!geometryProblem.empty())
  {
    vtkErrorMacro(<< geometryProblem);
    return 0;
  }

  // The uniforms the mapper would set, and its refusals; the density as the GPU's texture holds
  // it, in the input's native type.
  const cloudvis::MarchSetup setup = cloudvis::MakeMarchSetup(input,
    this->VolumeMatrix,
    cloudvis::DensityTexelsOf(scalars),
    &table,
    this->SampleDistance,
    this->TerminationTransmittance,
    this->LightingProperty->GetParameters(),
    this->GetLightList());
  cloudvis::MarchUniforms uniforms;
  cloudvis::LocalFrame frame;
  const cloudvis::MarchProblem problem = cloudvis::SetUpMarch(setup, uniforms, &frame);
  if (problem)
  {
    vtkErrorMacro(<< problem.Message);
    return 0;
  }

  // Depths from outside the field, added to the march's own toward each light.
  if (this->ExternalDepths)
  {
    const std::string gridProblem =
      cloudvis::ValidateOpticalDepthGrid(*this->ExternalDepths, int(uniforms.Lights.size()));
    if (!gridProblem.empty())
    {
      vtkErrorMacro(<< gridProblem);
      return 0;
    }
    cloudvis::SetExternalOpticalDepths(uniforms, frame, this->ExternalDepths.get());
  }

  // The march with light volumes reads them: computed once per image, as the GPU computes them
  // when its inputs change.
  cloudvis::LightVolumes lightVolumes;
  if (uniforms.Lighting.Model == cloudvis::LightingModel::March &&
    uniforms.Lighting.Transmittance == cloudvis::LightTransmittance::Volumes)
  {
    cloudvis::ComputeLightVolumes(uniforms, lightVolumes);
    uniforms.LightDepths = &lightVolumes;
  }
  // And the multiple-scattering volume, after them (its source reads them), unless one solved
  // over the whole field is given.
  cloudvis::ScatteringGrid scattering;
  if (this->ExternalScattering)
  {
    cloudvis::SetExternalScatteringVolume(uniforms, frame, this->ExternalScattering.get());
  }
  else if (cloudvis::UsesScatteringVolume(uniforms.Lighting))
  {
    cloudvis::ComputeScatteringVolume(uniforms, scattering);
    uniforms.MultipleScattering = &scattering;
  }

  // The image.
  int outExtent[6] = { 0, width - 1, 0, height - 1, 0, 0 };
  output->SetExtent(outExtent);
  output->SetOrigin(0.0, 0.0, 0.0);
  output->SetSpacing(1.0, 1.0, 1.0);
  const glm::dmat4 deviceToLocal = cloudvis::DeviceToLocal(frame, viewToDevice, worldToView, eye);
  return this->RenderImage(uniforms, deviceToLocal, input, output) ? 1 : 0;
}

bool vtkCloudReferenceRenderer::RenderImage(const cloudvis::MarchUniforms& uniforms,
  const glm::dmat4& deviceToLocal,
  vtkImageData*,
  vtkImageData* output)
{
  if (uniforms.Lighting.Model == cloudvis::LightingModel::PathTrace)
  {
    // The march has no path-trace source term; the path tracer is a renderer of its own.
    vtkErrorMacro(<< "the pathtrace lighting model is rendered by vtkCloudPathTracer, not by "
                     "vtkCloudReferenceRenderer's march");
    return false;
  }
  const int width = this->ImageSize[0], height = this->ImageSize[1];
  vtkNew<vtkFloatArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(vtkIdType(width) * height);
  rgba->Fill(0.0);
  output->GetPointData()->SetScalars(rgba);
  float* pixels = rgba->GetPointer(0);
  this->RenderRowBlocks(height,
    [&](vtkIdType begin, vtkIdType end)
    {
      cloudvis::glsl::Transport transport = cloudvis::TransportOf(uniforms); // this thread's
      for (vtkIdType j = begin; j < end; ++j)
      {
        for (int i = 0; i < width; ++i)
        {
          glm::dvec3 nearPoint, farPoint;
          PixelRay(deviceToLocal, i, int(j), width, height, nearPoint, farPoint);
          const glm::vec4 color =
            cloudvis::MarchRay(transport, glm::vec3(nearPoint), glm::vec3(farPoint));
          float* out = pixels + (std::size_t(j) * width + i) * 4;
          out[0] = color.r;
          out[1] = color.g;
          out[2] = color.b;
          out[3] = color.a;
        }
      }
    });
  return true;
}

void vtkCloudReferenceRenderer::PixelRay(const glm::dmat4& deviceToLocal,
  int i,
  int j,
  int width,
  int height,
  glm::dvec3& nearPoint,
  glm::dvec3& farPoint)
{
  const glm::dvec2 ndc((i + 0.5) / width * 2.0 - 1.0, (double(j) + 0.5) / height * 2.0 - 1.0);
  nearPoint = LocalPoint(deviceToLocal, ndc, -1.0);
  farPoint = LocalPoint(deviceToLocal, ndc, 1.0);
}

void vtkCloudReferenceRenderer::RenderRowBlocks(
  int height, const std::function<void(vtkIdType, vtkIdType)>& renderRows)
{
  // Blocks of rows, so progress and abort are handled on this thread between them.
  const RowFunctor functor{ &renderRows };
  const int blocks = std::min(height, 16);
  this->UpdateProgress(0.0);
  for (int b = 0; b < blocks && !this->GetAbortExecute(); ++b)
  {
    const vtkIdType firstRow = vtkIdType(b) * height / blocks;
    const vtkIdType endRow = vtkIdType(b + 1) * height / blocks;
    vtkSMPTools::For(firstRow, endRow, functor);
    this->UpdateProgress(double(b + 1) / blocks);
  }
}

void vtkCloudReferenceRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ImageSize: " << this->ImageSize[0] << " x " << this->ImageSize[1] << "\n";
  os << indent << "CameraPosition: " << this->CameraPosition[0] << ", " << this->CameraPosition[1]
     << ", " << this->CameraPosition[2] << "\n";
  os << indent << "CameraFocalPoint: " << this->CameraFocalPoint[0] << ", "
     << this->CameraFocalPoint[1] << ", " << this->CameraFocalPoint[2] << "\n";
  os << indent << "CameraViewUp: " << this->CameraViewUp[0] << ", " << this->CameraViewUp[1]
     << ", " << this->CameraViewUp[2] << "\n";
  os << indent << "ViewAngle: " << this->ViewAngle << "\n";
  os << indent << "ParallelProjection: " << (this->ParallelProjection ? "On" : "Off") << "\n";
  os << indent << "ParallelScale: " << this->ParallelScale << "\n";
  os << indent << "ClippingRange: " << this->ClippingRange[0] << ", " << this->ClippingRange[1]
     << "\n";
  os << indent << "VolumeProperty: " << this->VolumeProperty << "\n";
  os << indent << "ExtinctionScale: " << this->ExtinctionScale << "\n";
  os << indent << "LightingProperty:\n";
  this->LightingProperty->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Lights: " << this->Lights->GetNumberOfItems() << "\n";
  os << indent << "VolumeMatrix:\n";
  this->VolumeMatrix->PrintSelf(os, indent.GetNextIndent());
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "TerminationTransmittance: " << this->TerminationTransmittance << "\n";
}
