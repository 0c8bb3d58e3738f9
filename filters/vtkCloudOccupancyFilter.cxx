#include "vtkCloudOccupancyFilter.h"

#include "CloudFieldGeometry.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkCloudOccupancyFilter);

namespace
{
constexpr int MaxDistance = 255;

// Bricks along an axis of n voxels: enough to cover its n - 1 cells, and one for a flat axis.
int BrickCount(int n, int brickSize)
{
  const std::int64_t cells = std::max(n - 1, 0);
  return static_cast<int>(std::max<std::int64_t>(1, (cells + brickSize - 1) / brickSize));
}

// Voxels whose density a trilinear sample inside brick b can see, plus the apron.
void BrickVoxels(int b, int brickSize, int apron, int n, int& first, int& last)
{
  const std::int64_t lo = std::int64_t(b) * brickSize - apron;
  const std::int64_t hi = std::int64_t(b + 1) * brickSize + apron;
  first = static_cast<int>(std::max<std::int64_t>(lo, 0));
  last = static_cast<int>(std::min<std::int64_t>(hi, n - 1));
}

// Per brick, the density range of its apron-extended voxels and the extinction range the table
// gives it. One work item is a row of bricks along x, so the voxel rows it reads are contiguous.
template <typename T>
struct BrickExtinction
{
  const T* Density;
  int N[3];
  int Bricks[3];
  int BrickSize;
  int Apron;
  const cloudvis::TransferTable* Table;
  float* MaxExtinction;
  float* MinExtinction;

  void operator()(vtkIdType begin, vtkIdType end) const
  {
    const int nb = this->Bricks[0];
    std::vector<double> lo(nb), hi(nb);
    std::vector<int> firstX(nb), lastX(nb);
    for (int bx = 0; bx < nb; ++bx)
    {
      BrickVoxels(bx, this->BrickSize, this->Apron, this->N[0], firstX[bx], lastX[bx]);
    }
    for (vtkIdType row = begin; row < end; ++row)
    {
      const int by = static_cast<int>(row % this->Bricks[1]);
      const int bz = static_cast<int>(row / this->Bricks[1]);
      int j0, j1, k0, k1;
      BrickVoxels(by, this->BrickSize, this->Apron, this->N[1], j0, j1);
      BrickVoxels(bz, this->BrickSize, this->Apron, this->N[2], k0, k1);
      std::fill(lo.begin(), lo.end(), std::numeric_limits<double>::infinity());
      std::fill(hi.begin(), hi.end(), -std::numeric_limits<double>::infinity());
      for (int k = k0; k <= k1; ++k)
      {
        for (int j = j0; j <= j1; ++j)
        {
          const T* voxels = this->Density + (vtkIdType(k) * this->N[1] + j) * this->N[0];
          for (int bx = 0; bx < nb; ++bx)
          {
            // T, not double, in the inner loop lets the compiler vectorise the min / max.
            T vmin = voxels[firstX[bx]], vmax = vmin;
            for (int i = firstX[bx] + 1; i <= lastX[bx]; ++i)
            {
              vmin = std::min(vmin, voxels[i]);
              vmax = std::max(vmax, voxels[i]);
            }
            lo[bx] = std::min(lo[bx], double(vmin));
            hi[bx] = std::max(hi[bx], double(vmax));
          }
        }
      }
      float* outMax = this->MaxExtinction + row * nb;
      float* outMin = this->MinExtinction + row * nb;
      for (int bx = 0; bx < nb; ++bx)
      {
        outMax[bx] = this->Table->MaxExtinction(lo[bx], hi[bx]);
        outMin[bx] = this->Table->MinExtinction(lo[bx], hi[bx]);
      }
    }
  }
};

// One 1-D pass of the separable Chebyshev distance transform over lines of `count` values
// `stride` apart: g(y) = min over q of max(|y - q|, f(q)). Along the first axis f is 0 at
// occupied bricks and MaxDistance elsewhere, which gives the 1-D distance; the next two passes
// turn it into the exact 3-D Chebyshev distance (the L-infinity counterpart of the min-plus
// passes of the Euclidean and city-block transforms). A candidate q at |y - q| = s cannot beat a
// current best <= s, so the search stops there: cost O(count * distance), distance <= 255.
// Capping f at MaxDistance before the pass equals capping g after it.
struct ChebyshevPass
{
  unsigned char* Distance;
  int N[3];
  int Axis;

  void operator()(vtkIdType begin, vtkIdType end) const
  {
    const int a1 = (this->Axis + 1) % 3, a2 = (this->Axis + 2) % 3;
    const vtkIdType strides[3] = { 1, this->N[0], vtkIdType(this->N[0]) * this->N[1] };
    const vtkIdType stride = strides[this->Axis];
    const int count = this->N[this->Axis];
    std::vector<int> f(count);
    for (vtkIdType line = begin; line < end; ++line)
    {
      const int u = static_cast<int>(line % this->N[a1]);
      const int v = static_cast<int>(line / this->N[a1]);
      unsigned char* first = this->Distance + u * strides[a1] + v * strides[a2];
      for (int y = 0; y < count; ++y)
      {
        f[y] = first[y * stride];
      }
      for (int y = 0; y < count; ++y)
      {
        int best = f[y];
        for (int s = 1; s < best && (y - s >= 0 || y + s < count); ++s)
        {
          if (y - s >= 0)
          {
            best = std::min(best, std::max(s, f[y - s]));
          }
          if (y + s < count)
          {
            best = std::min(best, std::max(s, f[y + s]));
          }
        }
        first[y * stride] = static_cast<unsigned char>(best);
      }
    }
  }
};
}

void vtkCloudOccupancyFilter::SetTransferTable(const cloudvis::TransferTable& table)
{
  if (table != this->TransferTable)
  {
    this->TransferTable = table;
    this->Modified();
  }
}

bool vtkCloudOccupancyFilter::SetTransferFunction(vtkVolumeProperty* property,
  double extinctionScale)
{
  std::string problem;
  const cloudvis::TransferTable table =
    cloudvis::TransferTableOf(property, extinctionScale, problem);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return false;
  }
  this->SetTransferTable(table);
  return true;
}

int vtkCloudOccupancyFilter::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int inExtent[6];
  const std::string extentError =
    cloudvis::PipelineExtent(inInfo, vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), inExtent);
  if (!extentError.empty())
  {
    vtkErrorMacro(<< extentError);
    return 0;
  }
  double origin[3] = { 0.0, 0.0, 0.0 }, spacing[3] = { 1.0, 1.0, 1.0 };
  if (inInfo->Has(vtkDataObject::ORIGIN()))
  {
    inInfo->Get(vtkDataObject::ORIGIN(), origin);
  }
  if (inInfo->Has(vtkDataObject::SPACING()))
  {
    inInfo->Get(vtkDataObject::SPACING(), spacing);
  }
  double direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  if (inInfo->Has(vtkDataObject::DIRECTION()))
  {
    inInfo->Get(vtkDataObject::DIRECTION(), direction);
  }

  int outExtent[6];
  double outOrigin[3], outSpacing[3];
  for (int a = 0; a < 3; ++a)
  {
    const int n = inExtent[2 * a + 1] - inExtent[2 * a] + 1;
    if (n < 1)
    {
      vtkErrorMacro(<< "the input has no voxels along axis " << a);
      return 0;
    }
    outExtent[2 * a] = 0;
    outExtent[2 * a + 1] = BrickCount(n, this->BrickSize) - 1;
    outSpacing[a] = spacing[a] * this->BrickSize;
  }
  // Brick 0 starts at the first voxel of the whole extent, wherever that extent begins.
  for (int a = 0; a < 3; ++a)
  {
    outOrigin[a] = origin[a];
    for (int b = 0; b < 3; ++b)
    {
      outOrigin[a] += direction[3 * a + b] * inExtent[2 * b] * spacing[b];
    }
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), outExtent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), outOrigin, 3);
  outInfo->Set(vtkDataObject::SPACING(), outSpacing, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), direction, 9);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

int vtkCloudOccupancyFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Every brick's range depends on voxels beyond any sub-extent's bricks (the apron), and the
  // distances on all bricks: always ask for the whole input.
  const std::string problem = cloudvis::RequestWholeExtent(inputVector[0]->GetInformationObject(0));
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  return 1;
}

int vtkCloudOccupancyFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  this->OccupiedFraction = 0.0;
  if (this->TransferTable.Size < 1 ||
    this->TransferTable.RGBA.size() < std::size_t(this->TransferTable.Size) * 4)
  {
    vtkErrorMacro(
      << "no transfer table: call SetTransferTable (SetTransferFunction) before updating");
    return 0;
  }
  vtkDataArray* scalars = input ? input->GetPointData()->GetScalars() : nullptr;
  const std::string scalarProblem = cloudvis::ValidateDensityScalars(scalars);
  if (!scalarProblem.empty())
  {
    vtkErrorMacro(<< scalarProblem);
    return 0;
  }
  const int type = scalars->GetDataType();

  int inExtent[6];
  input->GetExtent(inExtent);
  int n[3], bricks[3], outExtent[6];
  for (int a = 0; a < 3; ++a)
  {
    n[a] = inExtent[2 * a + 1] - inExtent[2 * a] + 1;
    bricks[a] = BrickCount(n[a], this->BrickSize);
    outExtent[2 * a] = 0;
    outExtent[2 * a + 1] = bricks[a] - 1;
  }
  if (scalars->GetNumberOfTuples() != vtkIdType(n[0]) * n[1] * n[2])
  {
    vtkErrorMacro(<< "the input scalars do not match the input extent");
    return 0;
  }
  output->SetExtent(outExtent);
  output->SetOrigin(outInfo->Get(vtkDataObject::ORIGIN()));
  output->SetSpacing(outInfo->Get(vtkDataObject::SPACING()));
  output->SetDirectionMatrix(input->GetDirectionMatrix());
  const vtkIdType brickCount = vtkIdType(bricks[0]) * bricks[1] * bricks[2];

  vtkNew<vtkFloatArray> maxExtinction;
  maxExtinction->SetName("max_extinction");
  maxExtinction->SetNumberOfTuples(brickCount);
  vtkNew<vtkFloatArray> minExtinction;
  minExtinction->SetName("min_extinction");
  minExtinction->SetNumberOfTuples(brickCount);
  vtkNew<vtkUnsignedCharArray> emptyDistance;
  emptyDistance->SetName("empty_distance");
  emptyDistance->SetNumberOfTuples(brickCount);
  output->GetPointData()->SetScalars(maxExtinction);
  output->GetPointData()->AddArray(minExtinction);
  output->GetPointData()->AddArray(emptyDistance);

  this->UpdateProgress(0.0);
  const vtkIdType brickRows = vtkIdType(bricks[1]) * bricks[2];
  auto fill = [&](auto* density) {
    using T = std::remove_const_t<std::remove_pointer_t<decltype(density)>>;
    BrickExtinction<T> work{ density, { n[0], n[1], n[2] }, { bricks[0], bricks[1], bricks[2] },
      this->BrickSize, this->Apron, &this->TransferTable, maxExtinction->GetPointer(0),
      minExtinction->GetPointer(0) };
    vtkSMPTools::For(0, brickRows, work);
  };
  switch (type)
  {
    case VTK_FLOAT:
      fill(static_cast<const float*>(scalars->GetVoidPointer(0)));
      break;
    case VTK_UNSIGNED_CHAR:
      fill(static_cast<const unsigned char*>(scalars->GetVoidPointer(0)));
      break;
    default:
      fill(static_cast<const unsigned short*>(scalars->GetVoidPointer(0)));
      break;
  }
  const float* sigma_t = maxExtinction->GetPointer(0);
  unsigned char* distance = emptyDistance->GetPointer(0);
  if (this->GetAbortExecute())
  {
    // Distance 0 everywhere skips nothing: an aborted output can only cost speed, never
    // correctness, should someone render with it.
    std::fill(distance, distance + brickCount, 0);
    return 1;
  }
  this->UpdateProgress(0.8);

  vtkIdType occupied = 0;
  for (vtkIdType b = 0; b < brickCount; ++b)
  {
    const bool isOccupied = sigma_t[b] > 0.0f;
    occupied += isOccupied;
    distance[b] = isOccupied ? 0 : MaxDistance;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    ChebyshevPass pass{ distance, { bricks[0], bricks[1], bricks[2] }, axis };
    vtkSMPTools::For(0, brickCount / bricks[axis], pass);
  }
  this->OccupiedFraction = double(occupied) / double(brickCount);

  vtkNew<vtkDoubleArray> fraction;
  fraction->SetName("occupied_fraction");
  fraction->SetNumberOfTuples(1);
  fraction->SetValue(0, this->OccupiedFraction);
  output->GetFieldData()->AddArray(fraction);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCloudOccupancyFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TransferTable: " << this->TransferTable.Size << " entries over ["
     << this->TransferTable.Range[0] << ", " << this->TransferTable.Range[1] << "]\n";
  os << indent << "BrickSize: " << this->BrickSize << "\n";
  os << indent << "Apron: " << this->Apron << "\n";
  os << indent << "OccupiedFraction: " << this->OccupiedFraction << "\n";
}
