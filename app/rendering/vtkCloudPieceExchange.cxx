// vtkCloudPieceExchange: the mapper's side of the exchange between the pieces of a distributed
// field. The transport it runs is filters/'s (CloudOpticalDepthGrid.h, CloudScatteringVolume.h);
// the mapper's MarchSetup of its piece (ComputeOnPiece) and the textures it reads the results
// through (CloudExternalDepthTexture.h, CloudExternalScatteringTexture.h) are the mapper's.
#include "vtkCloudPieceExchange.h"

#include "CloudFieldGeometry.h"
#include "CloudOpticalDepthGrid.h"
#include "CloudScatteringVolume.h"
#include "CloudVolumeMapperInternals.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkImageData.h>
#include <vtkObjectFactory.h>
#include <vtkVolume.h>

#include <glm/glm.hpp>

vtkStandardNewMacro(vtkCloudPieceExchange);

namespace
{
// The points per axis of an extent; 0 on an axis where it is empty.
glm::ivec3 ExtentDimensions(const int extent[6])
{
  return glm::max(glm::ivec3(extent[1] - extent[0] + 1,
                    extent[3] - extent[2] + 1,
                    extent[5] - extent[4] + 1),
    glm::ivec3(0));
}
} // namespace

vtkCloudPieceExchange::vtkCloudPieceExchange() = default;
vtkCloudPieceExchange::~vtkCloudPieceExchange() = default;

void vtkCloudPieceExchange::SetMapper(vtkCloudVolumeMapper* mapper)
{
  if (mapper != this->Mapper)
  {
    this->Mapper = mapper;
    this->Modified();
  }
}

vtkCloudVolumeMapper* vtkCloudPieceExchange::GetMapper() const
{
  return this->Mapper;
}

void vtkCloudPieceExchange::SetVolume(vtkVolume* volume)
{
  if (volume != this->Volume)
  {
    this->Volume = volume;
    this->Modified();
  }
}

vtkVolume* vtkCloudPieceExchange::GetVolume() const
{
  return this->Volume;
}

std::string vtkCloudPieceExchange::GetLastError() const
{
  return this->Mapper ? this->Mapper->GetLastError() : this->NoMapperError;
}

bool vtkCloudPieceExchange::Ready(const char* what)
{
  this->NoMapperError.clear();
  if (!this->Mapper)
  {
    this->NoMapperError = std::string(what) + " needs the mapper whose piece it exchanges";
    vtkErrorMacro(<< this->NoMapperError);
    return false;
  }
  return true;
}

bool vtkCloudPieceExchange::ComputePieceOpticalDepths(vtkRenderer* renderer,
  cloudvis::OpticalDepthGrid& grid)
{
  grid.Lights = 0;
  grid.Depths.clear();
  return this->Ready("ComputePieceOpticalDepths") &&
    this->Mapper->ComputeOnPiece(renderer,
      this->Volume,
      "ComputePieceOpticalDepths",
      [&grid](const cloudvis::MarchSetup& setup)
      { return cloudvis::ComputePieceOpticalDepths(setup, grid); });
}

void vtkCloudPieceExchange::SetExternalOpticalDepths(const cloudvis::OpticalDepthGrid& grid)
{
  if (this->Ready("SetExternalOpticalDepths"))
  {
    this->Mapper->Internal->External.Set(grid);
    this->Mapper->Modified();
  }
}

const cloudvis::OpticalDepthGrid& vtkCloudPieceExchange::GetExternalOpticalDepths() const
{
  static const cloudvis::OpticalDepthGrid none;
  return this->Mapper ? this->Mapper->Internal->External.GetGrid() : none;
}

std::size_t vtkCloudPieceExchange::GetScatteringInputCount(const int wholeExtent[6])
{
  const glm::ivec3 dimensions = ExtentDimensions(wholeExtent);
  return glm::any(glm::lessThan(dimensions, glm::ivec3(1)))
    ? 0
    : cloudvis::ScatteringInputValues(dimensions);
}

bool vtkCloudPieceExchange::ComputePieceScatteringInputs(vtkRenderer* renderer,
  const int wholeExtent[6],
  std::vector<float>& inputs)
{
  inputs.clear();
  if (!this->Ready("ComputePieceScatteringInputs"))
  {
    return false;
  }
  const cloudvis::OpticalDepthGrid& external = this->Mapper->Internal->External.GetGrid();
  // Without a usable piece ComputeOnPiece says why.
  vtkImageData* piece = this->Volume ? this->Mapper->ValidInput(this->Volume) : nullptr;
  const cloudvis::VolumeGeometry whole = piece
    ? cloudvis::WholeFieldGeometry(piece, this->Volume->GetMatrix(), wholeExtent)
    : cloudvis::VolumeGeometry();
  cloudvis::ScatteringInputs grids;
  const bool computed = this->Mapper->ComputeOnPiece(renderer,
    this->Volume,
    "ComputePieceScatteringInputs",
    [&](const cloudvis::MarchSetup& setup)
    {
      return cloudvis::ComputePieceScatteringInputs(
        setup, external.Empty() ? nullptr : &external, whole, grids);
    });
  if (computed)
  {
    inputs = cloudvis::PackScatteringInputs(grids);
  }
  return computed;
}

bool vtkCloudPieceExchange::SolveScatteringVolume(const std::vector<float>& summedInputs,
  const int wholeExtent[6])
{
  if (!this->Ready("SolveScatteringVolume"))
  {
    return false;
  }
  this->ClearScatteringVolume();
  vtkImageData* piece = this->Volume ? this->Mapper->ValidInput(this->Volume) : nullptr;
  if (!piece)
  {
    return this->Mapper->Fail("SolveScatteringVolume needs the volume and the input it draws, "
                              "which place the whole field");
  }
  const cloudvis::VolumeGeometry whole =
    cloudvis::WholeFieldGeometry(piece, this->Volume->GetMatrix(), wholeExtent);
  cloudvis::ScatteringInputs inputs;
  if (!cloudvis::UnpackScatteringInputs(summedInputs, whole, inputs))
  {
    return this->Mapper->Fail("SolveScatteringVolume: the summed inputs hold " +
      std::to_string(summedInputs.size()) + " values where a whole field of " +
      std::to_string(whole.Dimensions.x) + " x " + std::to_string(whole.Dimensions.y) + " x " +
      std::to_string(whole.Dimensions.z) + " points has " +
      std::to_string(GetScatteringInputCount(wholeExtent)));
  }
  // Every rank solves the same sums with the same code: the same volume on every rank.
  this->Mapper->Internal->ExternalScattering.Set(cloudvis::SolveWholeFieldScattering(
    this->Mapper->GetLightingProperty()->GetParameters(), whole, std::move(inputs)));
  this->Mapper->Modified();
  return true;
}

void vtkCloudPieceExchange::ClearScatteringVolume()
{
  if (this->Mapper && this->Mapper->Internal->ExternalScattering.HasVolume())
  {
    this->Mapper->Internal->ExternalScattering.Set(cloudvis::WholeFieldScattering());
    this->Mapper->Modified();
  }
}

bool vtkCloudPieceExchange::HasScatteringVolume() const
{
  return this->Mapper && this->Mapper->Internal->ExternalScattering.HasVolume();
}

void vtkCloudPieceExchange::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mapper: " << this->Mapper.Get() << "\n";
  os << indent << "Volume: " << this->Volume.Get() << "\n";
  os << indent << "ExternalOpticalDepths: " << (this->GetExternalOpticalDepths().Empty() ? "none" : "set")
     << "\n";
  os << indent << "ScatteringVolume: " << (this->HasScatteringVolume() ? "whole field" : "none")
     << "\n";
}
