#include "vtkCloudPathTracer.h"

#include "CloudPathTrace.h"
#include "CloudReferenceMarch.h"
#include "vtkCloudOccupancyFilter.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <vector>

vtkStandardNewMacro(vtkCloudPathTracer);

// The header states the default brick size as a number, to stay light for the Python wrapper.
static_assert(cloudvis::PathTraceBrickSize == 8, "vtkCloudPathTracer.h's default BrickSize");
static_assert(cloudvis::PathTraceBounceCap == 65536, "vtkCloudPathTracer.h's default MaxBounces");

namespace
{
// The most scattering events MaxBounces may allow: far beyond what any field needs, and small
// enough that the bounce counter cannot overflow.
constexpr int MaxBouncesLimit = 1 << 24;
}

bool vtkCloudPathTracer::RenderImage(const cloudvis::MarchUniforms& uniforms,
  const glm::dmat4& deviceToLocal,
  vtkImageData* input,
  vtkImageData* output)
{
  if (this->SamplesPerPixel < 2)
  {
    vtkErrorMacro(<< "SamplesPerPixel must be at least 2 (the variance needs two), not "
                  << this->SamplesPerPixel);
    return false;
  }
  if (this->MaxBounces < 1 || this->MaxBounces > MaxBouncesLimit)
  {
    vtkErrorMacro(<< "MaxBounces must be between 1 and " << MaxBouncesLimit << ", not "
                  << this->MaxBounces);
    return false;
  }
  if (this->BrickSize < 1)
  {
    vtkErrorMacro(<< "BrickSize must be at least 1, not " << this->BrickSize);
    return false;
  }

  // The majorants, minorants and empty distances of the occupancy filter's bricks, for the same
  // table.
  vtkNew<vtkImageData> field;
  field->ShallowCopy(input);
  vtkNew<vtkCloudOccupancyFilter> occupancy;
  occupancy->SetInputData(field);
  occupancy->SetTransferTable(*uniforms.Table);
  occupancy->SetBrickSize(this->BrickSize);
  occupancy->Update();
  vtkImageData* bricks = occupancy->GetOutput();
  auto* majorant = vtkFloatArray::SafeDownCast(bricks->GetPointData()->GetArray("max_extinction"));
  auto* minorant = vtkFloatArray::SafeDownCast(bricks->GetPointData()->GetArray("min_extinction"));
  auto* emptyDistance =
    vtkUnsignedCharArray::SafeDownCast(bricks->GetPointData()->GetArray("empty_distance"));
  int brickCount[3];
  bricks->GetDimensions(brickCount);
  const vtkIdType brickTotal = vtkIdType(brickCount[0]) * brickCount[1] * brickCount[2];
  if (!majorant || !minorant || !emptyDistance || majorant->GetNumberOfTuples() != brickTotal ||
    minorant->GetNumberOfTuples() != brickTotal || emptyDistance->GetNumberOfTuples() != brickTotal)
  {
    vtkErrorMacro(<< "the occupancy bricks of the input could not be computed");
    return false;
  }
  // The filter's bounds are per world unit, as the table's entries; the march's extinction is
  // per local unit (Optical). ExtinctionUnit is a power of two: the products are exact, so the
  // bounds still bound every sample.
  const std::size_t brickValues = std::size_t(brickTotal);
  std::vector<float> majorantPerLocalUnit(brickValues), minorantPerLocalUnit(brickValues);
  for (vtkIdType b = 0; b < brickTotal; ++b)
  {
    majorantPerLocalUnit[std::size_t(b)] = majorant->GetValue(b) * uniforms.ExtinctionUnit;
    minorantPerLocalUnit[std::size_t(b)] = minorant->GetValue(b) * uniforms.ExtinctionUnit;
  }
  cloudvis::PathTraceUniforms pt;
  pt.BrickMajorant = majorantPerLocalUnit.data();
  pt.BrickMinorant = minorantPerLocalUnit.data();
  pt.BrickEmptyDistance = emptyDistance->GetPointer(0);
  pt.BrickCount = glm::ivec3(brickCount[0], brickCount[1], brickCount[2]);
  pt.BrickSize = float(this->BrickSize);
  pt.MaxBounces = this->MaxBounces;
  pt.LightGuidedNextEvents = this->NextEventEstimator == LightGuided ||
    (this->NextEventEstimator == ByPhase && cloudvis::GuidesNextEventsByDefault(uniforms.Lighting));

  const int width = this->ImageSize[0], height = this->ImageSize[1];
  const vtkIdType pixels = vtkIdType(width) * height;
  vtkNew<vtkFloatArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(pixels);
  rgba->Fill(0.0);
  vtkNew<vtkFloatArray> variance;
  variance->SetName("rgba_variance");
  variance->SetNumberOfComponents(4);
  variance->SetNumberOfTuples(pixels);
  variance->Fill(0.0);
  output->GetPointData()->SetScalars(rgba);
  output->GetPointData()->AddArray(variance);

  float* means = rgba->GetPointer(0);
  float* variances = variance->GetPointer(0);
  const int samples = this->SamplesPerPixel;
  const unsigned int seed = this->Seed;
  this->RenderRowBlocks(height,
    [&](vtkIdType begin, vtkIdType end)
    {
      cloudvis::glsl::Transport transport = cloudvis::TransportOf(uniforms, pt); // this thread's
      for (vtkIdType j = begin; j < end; ++j)
      {
        for (int i = 0; i < width; ++i)
        {
          glm::dvec3 nearPoint, farPoint;
          PixelRay(deviceToLocal, i, int(j), width, height, nearPoint, farPoint);
          const std::uint32_t pixel = std::uint32_t(j * width + i);
          // Welford's running mean and sum of squared deviations, in double.
          glm::dvec4 mean(0.0), squares(0.0);
          for (int s = 0; s < samples; ++s)
          {
            cloudvis::RandomStream rng;
            rng.Pixel = pixel;
            rng.Sample = std::uint32_t(s);
            rng.Seed = seed;
            const glm::dvec4 x(transport.TracePath(glm::vec3(nearPoint), glm::vec3(farPoint), rng));
            const glm::dvec4 delta = x - mean;
            mean += delta / double(s + 1);
            squares += delta * (x - mean);
          }
          const glm::dvec4 varianceOfMean = squares / (double(samples) * (samples - 1));
          for (int c = 0; c < 4; ++c)
          {
            means[(j * width + i) * 4 + c] = float(mean[c]);
            variances[(j * width + i) * 4 + c] = float(varianceOfMean[c]);
          }
        }
      }
    });
  return true;
}

void vtkCloudPathTracer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MaxBounces: " << this->MaxBounces << "\n";
  os << indent << "BrickSize: " << this->BrickSize << "\n";
  os << indent << "NextEventEstimator: " << this->NextEventEstimator << "\n";
}
