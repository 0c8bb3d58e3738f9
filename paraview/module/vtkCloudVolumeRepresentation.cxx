#include "vtkCloudVolumeRepresentation.h"

#include "CloudLightingParameters.h"
#include "CloudOpticalDepthGrid.h"
#include "CloudTransferTable.h"
#include "vtkCloudPieceExchange.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkAlgorithm.h>
#include <vtkCommunicator.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiProcessController.h>
#include <vtkObjectFactory.h>
#include <vtkPVLODVolume.h>
#include <vtkPVRenderView.h>
#include <vtkRenderer.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkCloudVolumeRepresentation);

namespace
{
// The exchange's grid is this many times coarser than the finest piece's voxels.
constexpr double ExchangeGridDivisor = 4.0;
}

vtkCloudVolumeRepresentation::vtkCloudVolumeRepresentation()
{
  vtkCloudVolumeMapper* mapper = vtkCloudVolumeMapper::New();
  this->VolumeMapper.TakeReference(mapper);
  this->CloudMapper = mapper;
  mapper->SetLightingProperty(this->Lighting);
  // ParaView, not the mapper, decides what an interactive render is (its LOD settings): the
  // mapper's own lowering of the resolution, keyed to the window's desired update rate, would
  // blur ParaView's still renders, whose update rate ParaView does not keep below 1.
  mapper->SetInteractiveFrameRate(0.0);
  // Across ranks IceT composites the ranks' 8-bit images without saturating: each must hold
  // valid premultiplied colours, and one rank draws the same for the pictures to agree.
  mapper->SetColorWithinAlpha(true);
  this->Exchange->SetMapper(mapper);
  this->Exchange->SetVolume(this->Actor);
  this->UpdateSun();
}

vtkCloudVolumeRepresentation::~vtkCloudVolumeRepresentation() = default;

// ---- Lighting ----

void vtkCloudVolumeRepresentation::SetLightingModel(int model)
{
  this->Lighting->SetModel(model);
}

void vtkCloudVolumeRepresentation::SetAmbientColor(double r, double g, double b)
{
  this->Lighting->SetAmbientColor(float(r), float(g), float(b));
}

void vtkCloudVolumeRepresentation::SetAmbientStrength(double strength)
{
  this->Lighting->SetAmbientStrength(float(strength));
}

void vtkCloudVolumeRepresentation::SetDerivativeDistance(double distance)
{
  this->Lighting->SetDerivativeDistance(float(distance));
}

void vtkCloudVolumeRepresentation::SetLightSteps(int steps)
{
  this->Lighting->SetLightSteps(steps);
}

void vtkCloudVolumeRepresentation::SetPhaseG1(double g)
{
  this->Lighting->SetPhaseG1(float(g));
}

void vtkCloudVolumeRepresentation::SetPhaseG2(double g)
{
  this->Lighting->SetPhaseG2(float(g));
}

void vtkCloudVolumeRepresentation::SetPhaseLobeWeight(double weight)
{
  this->Lighting->SetPhaseLobeWeight(float(weight));
}

void vtkCloudVolumeRepresentation::SetPhase(int phase)
{
  this->Lighting->SetPhase(phase);
}

void vtkCloudVolumeRepresentation::SetDropletEffectiveRadius(double radius)
{
  this->Lighting->SetDropletEffectiveRadius(float(radius));
}

void vtkCloudVolumeRepresentation::SetDropletEffectiveVariance(double variance)
{
  this->Lighting->SetDropletEffectiveVariance(float(variance));
}

void vtkCloudVolumeRepresentation::SetMultipleScattering(int scattering)
{
  this->Lighting->SetMultipleScattering(scattering);
}

void vtkCloudVolumeRepresentation::SetMultipleScatteringOctaves(int octaves)
{
  this->Lighting->SetMultipleScatteringOctaves(octaves);
}

void vtkCloudVolumeRepresentation::SetTransmittance(int transmittance)
{
  this->Lighting->SetTransmittance(transmittance);
}

// ---- The sun ----

void vtkCloudVolumeRepresentation::SetSunDirection(double x, double y, double z)
{
  this->SunDirection[0] = x;
  this->SunDirection[1] = y;
  this->SunDirection[2] = z;
  this->UpdateSun();
}

void vtkCloudVolumeRepresentation::SetSunColor(double r, double g, double b)
{
  this->SunColor[0] = r;
  this->SunColor[1] = g;
  this->SunColor[2] = b;
  this->UpdateSun();
}

void vtkCloudVolumeRepresentation::SetSunIntensity(double intensity)
{
  this->SunIntensity = intensity;
  this->UpdateSun();
}

void vtkCloudVolumeRepresentation::UpdateSun()
{
  // A scene's directional light: from its position toward its focal point, the origin. The
  // mapper refuses a zero direction with a message naming it.
  cloudvis::Light sun;
  sun.Positional = false;
  sun.Position = glm::dvec3(this->SunDirection[0], this->SunDirection[1], this->SunDirection[2]);
  sun.FocalPoint = glm::dvec3(0.0);
  sun.Color =
    glm::vec3(float(this->SunColor[0]), float(this->SunColor[1]), float(this->SunColor[2]));
  sun.Intensity = float(this->SunIntensity);
  this->CloudMapper->SetLights({ sun });
  this->ExchangeInputsTime.Modified();
}

// ---- The mapper ----

void vtkCloudVolumeRepresentation::SetSampleDistance(double distance)
{
  this->CloudMapper->SetSampleDistance(distance);
}

void vtkCloudVolumeRepresentation::SetExtinctionScale(double scale)
{
  this->CloudMapper->SetExtinctionScale(scale);
  this->ExchangeInputsTime.Modified();
}

void vtkCloudVolumeRepresentation::SetJitter(bool jitter)
{
  this->CloudMapper->SetJitter(jitter);
}

void vtkCloudVolumeRepresentation::SetMaximumAccumulatedFrames(int frames)
{
  this->CloudMapper->SetMaximumAccumulatedFrames(frames);
}

void vtkCloudVolumeRepresentation::SetPathTraceSamplesPerFrame(int samples)
{
  this->CloudMapper->SetPathTraceSamplesPerFrame(samples);
}

void vtkCloudVolumeRepresentation::SetMaximumGPUMemory(double mebibytes)
{
  this->CloudMapper->SetMaximumGPUMemory(vtkTypeInt64(std::max(0.0, mebibytes) * 1048576.0));
}

void vtkCloudVolumeRepresentation::SetShadowExchange(bool exchange)
{
  if (this->ShadowExchange != exchange)
  {
    this->ShadowExchange = exchange;
    this->ExchangedTime = 0;
    this->Modified();
  }
}

int vtkCloudVolumeRepresentation::ProcessViewRequest(vtkInformationRequestKey* requestType,
  vtkInformation* inInfo,
  vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(requestType, inInfo, outInfo))
  {
    return 0;
  }
  if (requestType == vtkPVView::REQUEST_RENDER())
  {
    vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
    const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
    if (ranks > 1 && this->Lighting->GetModel() == vtkCloudLightingProperty::PathTraceLighting)
    {
      // A path wanders through the whole field, which no rank holds: refused, not drawn wrong.
      vtkErrorMacro(<< "the pathtrace lighting model traces paths through the whole field, which "
                    << "none of the " << ranks << " ranks holds: render it on one rank, or "
                    << "choose the march model");
      this->Actor->SetVisibility(false);
      return 1;
    }
    auto* view = vtkPVRenderView::SafeDownCast(inInfo->Get(vtkPVView::VIEW()));
    this->ExchangeOpticalDepth(view ? view->GetRenderer() : nullptr);
  }
  return 1;
}

namespace
{
// The exchange's grid: the whole field's box (the union of the ranks' pieces) at a quarter of
// the finest spacing any piece has, as the multiple-scattering volume's grid (at least 2 points
// per axis). The same on every rank, which all call this together.
cloudvis::OpticalDepthGrid WholeFieldGrid(vtkMultiProcessController* controller,
  vtkImageData* piece)
{
  double lower[3], upper[3], spacing[3];
  for (int a = 0; a < 3; ++a)
  {
    lower[a] = std::numeric_limits<double>::max();
    upper[a] = -std::numeric_limits<double>::max();
    spacing[a] = std::numeric_limits<double>::max();
  }
  if (piece && piece->GetNumberOfPoints() > 0)
  {
    double bounds[6];
    piece->GetBounds(bounds);
    for (int a = 0; a < 3; ++a)
    {
      lower[a] = bounds[2 * a];
      upper[a] = bounds[2 * a + 1];
      spacing[a] = std::abs(piece->GetSpacing()[a]);
    }
  }
  double globalLower[3], globalUpper[3], globalSpacing[3];
  controller->AllReduce(lower, globalLower, 3, vtkCommunicator::MIN_OP);
  controller->AllReduce(upper, globalUpper, 3, vtkCommunicator::MAX_OP);
  controller->AllReduce(spacing, globalSpacing, 3, vtkCommunicator::MIN_OP);

  cloudvis::OpticalDepthGrid grid;
  for (int a = 0; a < 3; ++a)
  {
    const double extent = globalUpper[a] - globalLower[a];
    const int cells = extent > 0.0 && globalSpacing[a] > 0.0
      ? int(std::ceil(extent / (ExchangeGridDivisor * globalSpacing[a]) - 1e-9))
      : 1;
    grid.Size[a] = std::max(cells, 1) + 1;
    grid.Origin[a] = globalLower[a];
    grid.Spacing[a] = extent > 0.0 ? extent / (grid.Size[a] - 1) : 1.0;
  }
  return grid;
}
}

void vtkCloudVolumeRepresentation::ExchangeOpticalDepth(vtkRenderer* renderer)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!controller || controller->GetNumberOfProcesses() < 2)
  {
    return;
  }
  // Every rank holds the same properties, so every rank takes the same branch, and either all
  // of them reduce below or none does.
  auto* piece = vtkImageData::SafeDownCast(this->Cache);
  const bool wanted =
    this->ShadowExchange && this->Lighting->GetModel() == vtkCloudLightingProperty::MarchLighting;
  if (!wanted)
  {
    if (!this->Exchange->GetExternalOpticalDepths().Empty())
    {
      this->Exchange->SetExternalOpticalDepths(cloudvis::OpticalDepthGrid());
    }
    this->ExchangeScatteringVolume(controller, renderer, piece, false);
    this->ExchangedTime = 0;
    return;
  }
  // Recomputed when any rank's piece, transfer function, lighting, sun or extinction changed
  // since the last exchange.
  // The transfer function by what the march reads of it (its table), not by the volume
  // property's MTime: ParaView touches the property after the first render without changing it,
  // and an exchange with the multiple-scattering volume costs seconds on a large field.
  std::string tableProblem;
  const cloudvis::TransferTable table = cloudvis::TransferTableOf(
    this->Property, this->CloudMapper->GetExtinctionScale(), tableProblem);
  std::vector<double> tableSignature = { table.Range[0], table.Range[1] };
  tableSignature.insert(tableSignature.end(), table.RGBA.begin(), table.RGBA.end());
  if (tableSignature != this->ExchangedTable)
  {
    this->ExchangedTable = std::move(tableSignature);
    this->ExchangedTableTime.Modified();
  }
  const vtkMTimeType inputs = std::max({ piece ? piece->GetMTime() : vtkMTimeType(0),
    this->ExchangedTableTime.GetMTime(),
    this->Lighting->GetMTime(),
    this->ExchangeInputsTime.GetMTime() });
  int stale = inputs > this->ExchangedTime ? 1 : 0, anyStale = 0;
  controller->AllReduce(&stale, &anyStale, 1, vtkCommunicator::MAX_OP);
  if (!anyStale)
  {
    return;
  }

  cloudvis::OpticalDepthGrid own = WholeFieldGrid(controller, piece);
  const std::size_t values = own.PointCount(); // per light: the representation has one sun
  own.Lights = 1;
  own.Depths.assign(values, 0.0f);
  int failed = 0;
  if (piece && piece->GetNumberOfPoints() > 0)
  {
    cloudvis::OpticalDepthGrid computed = own;
    if (this->Exchange->ComputePieceOpticalDepths(renderer, computed) &&
      computed.Lights == 1 && computed.Depths.size() == values)
    {
      own = computed;
    }
    else
    {
      failed = 1;
    }
  }
  // A rank that cannot compute its share (its mapper says why) makes every rank light its piece
  // without the others', rather than with a wrong sum.
  int anyFailed = 0;
  controller->AllReduce(&failed, &anyFailed, 1, vtkCommunicator::MAX_OP);
  cloudvis::OpticalDepthGrid total = own;
  if (!anyFailed)
  {
    controller->AllReduce(
      own.Depths.data(), total.Depths.data(), vtkIdType(values), vtkCommunicator::SUM_OP);
  }
  this->Exchange->SetExternalOpticalDepths(
    anyFailed ? cloudvis::OpticalDepthGrid() : cloudvis::DepthsFromOutside(total, own));
  this->ExchangeScatteringVolume(controller,
    renderer,
    piece,
    !anyFailed && cloudvis::UsesScatteringVolume(this->Lighting->GetParameters()));
  this->ExchangedTime = inputs;
}

void vtkCloudVolumeRepresentation::ExchangeScatteringVolume(vtkMultiProcessController* controller,
  vtkRenderer* renderer,
  vtkImageData* piece,
  bool wanted)
{
  // `wanted` is the same on every rank (the same properties, and a failure's flag reduced), so
  // either all of them reduce below or none does.
  if (!wanted)
  {
    this->Exchange->ClearScatteringVolume();
    return;
  }
  // The whole field: the union of the pieces' extents (ParaView's pieces of one image share its
  // origin, spacing and direction, and a plane of points with each neighbour).
  const bool holds = piece && piece->GetNumberOfPoints() > 0;
  int first[3], last[3], wholeFirst[3], wholeLast[3];
  for (int a = 0; a < 3; ++a)
  {
    first[a] = holds ? piece->GetExtent()[2 * a] : std::numeric_limits<int>::max();
    last[a] = holds ? piece->GetExtent()[2 * a + 1] : std::numeric_limits<int>::min();
  }
  controller->AllReduce(first, wholeFirst, 3, vtkCommunicator::MIN_OP);
  controller->AllReduce(last, wholeLast, 3, vtkCommunicator::MAX_OP);
  const int wholeExtent[6] = {
    wholeFirst[0], wholeLast[0], wholeFirst[1], wholeLast[1], wholeFirst[2], wholeLast[2]
  };
  const std::size_t values = vtkCloudPieceExchange::GetScatteringInputCount(wholeExtent);
  if (values == 0)
  {
    return; // no rank holds data (every rank sees the same extents)
  }
  std::vector<float> own(values, 0.0f);
  int failed = 0;
  if (holds)
  {
    std::vector<float> computed;
    if (this->Exchange->ComputePieceScatteringInputs(renderer, wholeExtent, computed) &&
      computed.size() == values)
    {
      own = std::move(computed);
    }
    else
    {
      failed = 1;
    }
  }
  // A rank that cannot compute its cells (its mapper says why) makes every rank solve its own
  // piece's volume, rather than a whole with a hole.
  int anyFailed = 0;
  controller->AllReduce(&failed, &anyFailed, 1, vtkCommunicator::MAX_OP);
  if (anyFailed)
  {
    this->Exchange->ClearScatteringVolume();
    return;
  }
  std::vector<float> total(values);
  controller->AllReduce(own.data(), total.data(), vtkIdType(values), vtkCommunicator::SUM_OP);
  if (holds)
  {
    this->Exchange->SolveScatteringVolume(total, wholeExtent);
  }
}

void vtkCloudVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lighting: " << this->Lighting->GetModelAsString() << "\n";
  os << indent << "SunDirection: " << this->SunDirection[0] << ", " << this->SunDirection[1] << ", "
     << this->SunDirection[2] << "\n";
  os << indent << "SunIntensity: " << this->SunIntensity << "\n";
  os << indent << "ShadowExchange: " << this->ShadowExchange << "\n";
}
