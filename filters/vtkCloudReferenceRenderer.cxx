#include "vtkCloudReferenceRenderer.h"

#include "CloudReferenceMarch.h"

#include "CloudFieldGeometry.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMath.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCloudReferenceRenderer);

namespace
{
constexpr std::size_t MaxLights = cloudvis::LightingLimits::MaxLights;

bool Finite3(const double v[3])
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}
bool Finite3(glm::vec3 v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
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

// Where normalized device coordinates (ndc, ndcDepth) lie in the world: the GLSL's WorldPoint
// with DCWCMatrix.
glm::dvec3 WorldPoint(const glm::dmat4& deviceToWorld, glm::dvec2 ndc, double ndcDepth)
{
  const glm::dvec4 p = deviceToWorld * glm::dvec4(ndc, ndcDepth, 1.0);
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
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

void vtkCloudReferenceRenderer::SetTransferTable(const cloudvis::TransferTable& table)
{
  if (table != this->TransferTable)
  {
    this->TransferTable = table;
    this->Modified();
  }
}

void vtkCloudReferenceRenderer::SetLighting(const cloudvis::LightingParameters& lighting)
{
  this->Lighting = lighting;
  this->Modified();
}

void vtkCloudReferenceRenderer::SetLights(const std::vector<cloudvis::Light>& lights)
{
  this->Lights = lights;
  this->Modified();
}

bool vtkCloudReferenceRenderer::GetDeviceToWorldMatrix(vtkMatrix4x4* deviceToWorld) const
{
  const double* position = this->CameraPosition;
  const double* focal = this->CameraFocalPoint;
  const double* up = this->CameraViewUp;
  const double* range = this->ClippingRange;
  if (!deviceToWorld || !Finite3(position) || !Finite3(focal) || !Finite3(up) ||
    !(range[0] > 0.0 && range[1] > range[0] && std::isfinite(range[1])) ||
    this->ImageSize[0] < 1 || this->ImageSize[1] < 1)
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
  const glm::dvec3 eye(position[0], position[1], position[2]);
  const glm::dvec3 toCamera = eye - glm::dvec3(focal[0], focal[1], focal[2]);
  const glm::dvec3 sidewaysRaw = glm::cross(glm::dvec3(up[0], up[1], up[2]), toCamera);
  if (!(glm::length(toCamera) > 0.0) || !(glm::length(sidewaysRaw) > 0.0))
  {
    return false; // the camera sits on its focal point, or looks along its view up
  }
  const glm::dvec3 viewPlaneNormal = glm::normalize(toCamera);
  const glm::dvec3 sideways = glm::normalize(sidewaysRaw);
  const glm::dvec3 orthoViewUp = glm::cross(viewPlaneNormal, sideways);
  const double view[4][4] = {
    { sideways.x, sideways.y, sideways.z, -glm::dot(sideways, eye) },
    { orthoViewUp.x, orthoViewUp.y, orthoViewUp.z, -glm::dot(orthoViewUp, eye) },
    { viewPlaneNormal.x, viewPlaneNormal.y, viewPlaneNormal.z, -glm::dot(viewPlaneNormal, eye) },
    { 0.0, 0.0, 0.0, 1.0 },
  };

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
  const glm::dmat4 inverse = glm::inverse(FromRows(projection) * FromRows(view));
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
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  int wholeExtent[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), wholeExtent, 6);
  return 1;
}

int vtkCloudReferenceRenderer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);

  // The parameters.
  const cloudvis::TransferTable& table = this->TransferTable;
  if (table.Size < 1 || table.RGBA.size() < std::size_t(table.Size) * 4)
  {
    vtkErrorMacro(<< "no transfer table: call SetTransferTable before updating");
    return 0;
  }
  const int width = this->ImageSize[0], height = this->ImageSize[1];
  if (width < 1 || height < 1)
  {
    vtkErrorMacro(<< "the image size must be at least 1 x 1, not " << width << " x " << height);
    return 0;
  }
  if (!(this->SampleDistance >= 0.0 && std::isfinite(this->SampleDistance)))
  {
    vtkErrorMacro(<< "the sample distance must be >= 0 (0: the smallest voxel spacing)");
    return 0;
  }
  if (!(this->TerminationTransmittance >= 0.0 && this->TerminationTransmittance <= 1.0))
  {
    vtkErrorMacro(<< "the termination transmittance must be in [0, 1]");
    return 0;
  }
  const std::string lightingProblem = cloudvis::ValidateLightingParameters(this->Lighting);
  if (!lightingProblem.empty())
  {
    vtkErrorMacro(<< "lighting: " << lightingProblem);
    return 0;
  }
  if (this->Lights.size() > MaxLights)
  {
    vtkErrorMacro(<< this->Lights.size() << " lights; the renderers take at most " << MaxLights);
    return 0;
  }
  for (const cloudvis::Light& light : this->Lights)
  {
    if (!Finite3(light.Position) || !Finite3(light.FocalPoint) || !Finite3(light.Color) ||
      !Finite3(light.Attenuation) || !std::isfinite(light.Intensity) ||
      (!light.Positional && light.Position == light.FocalPoint))
    {
      vtkErrorMacro(<< "a light has a non-finite value, or is directional with its position "
                       "on its focal point");
      return 0;
    }
  }
  vtkNew<vtkMatrix4x4> deviceToWorldMatrix;
  if (!this->GetDeviceToWorldMatrix(deviceToWorldMatrix))
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
  const int type = scalars->GetDataType();
  int extent[6];
  input->GetExtent(extent);
  const int n[3] = { extent[1] - extent[0] + 1, extent[3] - extent[2] + 1,
    extent[5] - extent[4] + 1 };
  if (n[0] < 2 || n[1] < 2 || n[2] < 2)
  {
    vtkErrorMacro(<< "the input needs at least 2 voxels along each axis");
    return 0;
  }
  if (scalars->GetNumberOfTuples() != vtkIdType(n[0]) * n[1] * n[2])
  {
    vtkErrorMacro(<< "the input scalars do not match the input extent");
    return 0;
  }
  const double* origin = input->GetOrigin();
  const double* spacing = input->GetSpacing();
  if (!(spacing[0] > 0.0 && spacing[1] > 0.0 && spacing[2] > 0.0) || !Finite3(spacing) ||
    !Finite3(origin))
  {
    vtkErrorMacro(<< "the input needs a finite origin and a positive spacing");
    return 0;
  }
  if (!input->GetDirectionMatrix()->IsIdentity())
  {
    vtkErrorMacro(<< "the input has a rotated direction matrix; only the identity is supported");
    return 0;
  }

  // The density as the GPU's float texture holds it.
  std::vector<float> converted;
  const float* density = nullptr;
  if (type == VTK_FLOAT)
  {
    density = static_cast<const float*>(scalars->GetVoidPointer(0));
  }
  else
  {
    converted.resize(std::size_t(scalars->GetNumberOfTuples()));
    for (vtkIdType v = 0; v < scalars->GetNumberOfTuples(); ++v)
    {
      converted[std::size_t(v)] = static_cast<float>(scalars->GetComponent(v, 0));
    }
    density = converted.data();
  }

  // The uniforms the mapper would set.
  const double smallestSpacing = std::min({ spacing[0], spacing[1], spacing[2] });
  const double step = this->SampleDistance > 0.0 ? this->SampleDistance : smallestSpacing;
  double diagonal = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    diagonal += (n[a] - 1) * spacing[a] * (n[a] - 1) * spacing[a];
  }
  diagonal = std::sqrt(diagonal);
  cloudvis::MarchUniforms uniforms;
  uniforms.Density = density;
  uniforms.Dimensions = glm::ivec3(n[0], n[1], n[2]);
  uniforms.IndexOrigin = glm::vec3(glm::dvec3(origin[0] + extent[0] * spacing[0],
    origin[1] + extent[2] * spacing[1], origin[2] + extent[4] * spacing[2]));
  uniforms.Spacing = glm::vec3(glm::dvec3(spacing[0], spacing[1], spacing[2]));
  uniforms.Table = &table;
  uniforms.StepWorld = static_cast<float>(step);
  uniforms.TerminationTransmittance = static_cast<float>(this->TerminationTransmittance);
  uniforms.MaximumIterations =
    static_cast<int>(std::min(std::ceil(diagonal / step) + 16.0, double(INT_MAX)));
  uniforms.Lighting = cloudvis::ResolveLighting(this->Lighting, smallestSpacing);
  uniforms.Lights = this->Lights;
  uniforms.Ambient = this->Lighting.AmbientColor * this->Lighting.AmbientStrength;
  if (!(uniforms.StepWorld > 0.0f))
  {
    vtkErrorMacro(<< "the sample distance is too small for float");
    return 0;
  }

  // The image.
  int outExtent[6] = { 0, width - 1, 0, height - 1, 0, 0 };
  output->SetExtent(outExtent);
  output->SetOrigin(0.0, 0.0, 0.0);
  output->SetSpacing(1.0, 1.0, 1.0);
  glm::dmat4 deviceToWorld;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      deviceToWorld[c][r] = deviceToWorldMatrix->GetElement(r, c);
  return this->RenderImage(uniforms, deviceToWorld, input, output) ? 1 : 0;
}

bool vtkCloudReferenceRenderer::RenderImage(const cloudvis::MarchUniforms& uniforms,
  const glm::dmat4& deviceToWorld, vtkImageData*, vtkImageData* output)
{
  const int width = this->ImageSize[0], height = this->ImageSize[1];
  vtkNew<vtkFloatArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(vtkIdType(width) * height);
  rgba->Fill(0.0);
  output->GetPointData()->SetScalars(rgba);
  float* pixels = rgba->GetPointer(0);
  this->RenderRowBlocks(height, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType j = begin; j < end; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        glm::dvec3 nearWorld, farWorld;
        PixelRay(deviceToWorld, i, int(j), width, height, nearWorld, farWorld);
        const glm::vec4 color = cloudvis::MarchRay(uniforms, nearWorld, farWorld);
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

void vtkCloudReferenceRenderer::PixelRay(const glm::dmat4& deviceToWorld, int i, int j, int width,
  int height, glm::dvec3& nearWorld, glm::dvec3& farWorld)
{
  const glm::dvec2 ndc((i + 0.5) / width * 2.0 - 1.0, (double(j) + 0.5) / height * 2.0 - 1.0);
  nearWorld = WorldPoint(deviceToWorld, ndc, -1.0);
  farWorld = WorldPoint(deviceToWorld, ndc, 1.0);
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
  const char* models[] = { "None", "Derivative", "March" };
  const cloudvis::LightingParameters& l = this->Lighting;
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
  os << indent << "TransferTable: " << this->TransferTable.Size << " entries over ["
     << this->TransferTable.Range[0] << ", " << this->TransferTable.Range[1] << "]\n";
  os << indent << "Lighting: " << models[static_cast<int>(l.Model)] << ", ambient "
     << l.AmbientStrength << " x (" << l.AmbientColor.x << ", " << l.AmbientColor.y << ", "
     << l.AmbientColor.z << "), derivative distance " << l.DerivativeDistance << ", "
     << l.LightSteps << " light steps from " << l.LightStep << " growing " << l.LightStepGrowth
     << ", phase g " << l.PhaseG1 << " / " << l.PhaseG2 << " weight " << l.PhaseLobeWeight << ", "
     << l.MultipleScatteringOctaves << " octaves (" << l.ScatteringFalloff << ", "
     << l.ExtinctionFalloff << ", " << l.EccentricityFalloff << "), powder " << l.PowderStrength
     << "\n";
  os << indent << "Lights: " << this->Lights.size() << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "TerminationTransmittance: " << this->TerminationTransmittance << "\n";
}
