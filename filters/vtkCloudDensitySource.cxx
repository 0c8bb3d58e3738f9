#include "vtkCloudDensitySource.h"

#include "CloudFieldGeometry.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkCloudDensitySource);

vtkCloudDensitySource::vtkCloudDensitySource()
{
  this->SetNumberOfInputPorts(0);
}

void vtkCloudDensitySource::SetField(const cloudvis::FieldDescription& field)
{
  this->Field = field;
  this->Modified();
}

// The wrapped enums name the C++ ones by value.
static_assert(
  static_cast<int>(cloudvis::DensityModel::Constant) == vtkCloudDensitySource::ConstantModel,
  "vtkCloudDensitySource::DensityModels follows cloudvis::DensityModel");
static_assert(
  static_cast<int>(cloudvis::ShapeBlend::SmoothUnion) == vtkCloudDensitySource::SmoothUnionBlend,
  "vtkCloudDensitySource::ShapeBlends follows cloudvis::ShapeBlend");
static_assert(static_cast<int>(cloudvis::noise::NoiseType::PerlinWorley) ==
    vtkCloudDensitySource::PerlinWorleyNoise,
  "vtkCloudDensitySource::NoiseTypes follows cloudvis::noise::NoiseType");
static_assert(static_cast<int>(cloudvis::DensityModel::Cloud) == vtkCloudDensitySource::CloudModel,
  "vtkCloudDensitySource::DensityModels follows cloudvis::DensityModel");
static_assert(static_cast<int>(cloudvis::CloudType::Congestus) == vtkCloudDensitySource::Congestus,
  "vtkCloudDensitySource::CloudTypes follows cloudvis::CloudType");
static_assert(static_cast<int>(cloudvis::CoverageSource::Map) == vtkCloudDensitySource::MapCoverage,
  "vtkCloudDensitySource::CoverageSources follows cloudvis::CoverageSource");

template<typename T>
void vtkCloudDensitySource::SetFieldValue(T& member, const T& value)
{
  if (!(member == value))
  {
    member = value;
    this->Modified();
  }
}

void vtkCloudDensitySource::SetDensityModel(int model)
{
  if (model < SdfPlusFbmModel || model > CloudModel)
  {
    vtkErrorMacro(<< "density model " << model << " is not one of 0 (sdf+fbm), 1 (fbm falloff), "
                  << "2 (constant), 3 (cloud); it stays " << this->GetDensityModel());
    return;
  }
  this->SetFieldValue(this->Field.Model, static_cast<cloudvis::DensityModel>(model));
}

int vtkCloudDensitySource::GetDensityModel() const
{
  return static_cast<int>(this->Field.Model);
}

void vtkCloudDensitySource::SetDensityScale(double scale)
{
  this->SetFieldValue(this->Field.DensityScale, scale);
}

void vtkCloudDensitySource::SetFalloffWidth(double width)
{
  this->SetFieldValue(this->Field.FalloffWidth, width);
}

void vtkCloudDensitySource::RemoveAllShapes()
{
  if (!this->Field.Shapes.empty())
  {
    this->Field.Shapes.clear();
    this->Modified();
  }
}

int vtkCloudDensitySource::AddShape(const cloudvis::Shape& shape)
{
  this->Field.Shapes.push_back(shape);
  this->Modified();
  return static_cast<int>(this->Field.Shapes.size()) - 1;
}

int vtkCloudDensitySource::AddSphere(double cx, double cy, double cz, double radius)
{
  cloudvis::Shape shape;
  shape.Type = cloudvis::ShapeType::Sphere;
  shape.Center = glm::vec3(glm::dvec3(cx, cy, cz));
  shape.Radius = static_cast<float>(radius);
  return this->AddShape(shape);
}

int vtkCloudDensitySource::AddBox(double cx,
  double cy,
  double cz,
  double halfX,
  double halfY,
  double halfZ)
{
  cloudvis::Shape shape;
  shape.Type = cloudvis::ShapeType::Box;
  shape.Center = glm::vec3(glm::dvec3(cx, cy, cz));
  shape.HalfSize = glm::vec3(glm::dvec3(halfX, halfY, halfZ));
  return this->AddShape(shape);
}

int vtkCloudDensitySource::AddTorus(double cx,
  double cy,
  double cz,
  double majorRadius,
  double minorRadius)
{
  cloudvis::Shape shape;
  shape.Type = cloudvis::ShapeType::Torus;
  shape.Center = glm::vec3(glm::dvec3(cx, cy, cz));
  shape.MajorRadius = static_cast<float>(majorRadius);
  shape.MinorRadius = static_cast<float>(minorRadius);
  return this->AddShape(shape);
}

int vtkCloudDensitySource::AddCross(double cx,
  double cy,
  double cz,
  double armWidth,
  double armLength)
{
  cloudvis::Shape shape;
  shape.Type = cloudvis::ShapeType::Cross;
  shape.Center = glm::vec3(glm::dvec3(cx, cy, cz));
  shape.ArmWidth = static_cast<float>(armWidth);
  shape.ArmLength = static_cast<float>(armLength);
  return this->AddShape(shape);
}

int vtkCloudDensitySource::AddCapsule(double ax,
  double ay,
  double az,
  double bx,
  double by,
  double bz,
  double radius)
{
  cloudvis::Shape shape;
  shape.Type = cloudvis::ShapeType::Capsule;
  shape.EndA = glm::vec3(glm::dvec3(ax, ay, az));
  shape.EndB = glm::vec3(glm::dvec3(bx, by, bz));
  shape.Radius = static_cast<float>(radius);
  return this->AddShape(shape);
}

cloudvis::Shape* vtkCloudDensitySource::ShapeAt(int shape)
{
  if (shape < 0 || shape >= this->GetNumberOfShapes())
  {
    vtkErrorMacro(<< "shape " << shape << " does not exist: there are " << this->GetNumberOfShapes()
                  << " shapes");
    return nullptr;
  }
  return &this->Field.Shapes[static_cast<std::size_t>(shape)];
}

void vtkCloudDensitySource::SetShapeRotation(int shape, double rx, double ry, double rz)
{
  if (cloudvis::Shape* placed = this->ShapeAt(shape))
  {
    this->SetFieldValue(placed->RotationDegrees, glm::vec3(glm::dvec3(rx, ry, rz)));
  }
}

void vtkCloudDensitySource::SetShapeScale(int shape, double scale)
{
  if (cloudvis::Shape* placed = this->ShapeAt(shape))
  {
    this->SetFieldValue(placed->Scale, static_cast<float>(scale));
  }
}

void vtkCloudDensitySource::SetShapeBlend(int blend)
{
  if (blend != UnionBlend && blend != SmoothUnionBlend)
  {
    vtkErrorMacro(<< "shape blend " << blend << " is not one of 0 (union), 1 (smooth union); it "
                  << "stays " << this->GetShapeBlend());
    return;
  }
  this->SetFieldValue(this->Field.Blend, static_cast<cloudvis::ShapeBlend>(blend));
}

int vtkCloudDensitySource::GetShapeBlend() const
{
  return static_cast<int>(this->Field.Blend);
}

void vtkCloudDensitySource::SetBlendRadius(double radius)
{
  this->SetFieldValue(this->Field.BlendRadius, radius);
}

void vtkCloudDensitySource::SetMorph(bool morph)
{
  this->SetFieldValue(this->Field.Morph, morph);
}

void vtkCloudDensitySource::SetNoiseType(int type)
{
  if (type < NoNoise || type > PerlinWorleyNoise)
  {
    vtkErrorMacro(<< "noise type " << type << " is not one of 0 (none), 1 (white), 2 (value), "
                  << "3 (perlin), 4 (worley), 5 (inverted worley), 6 (perlin-worley); it stays "
                  << this->GetNoiseType());
    return;
  }
  this->SetFieldValue(this->Field.Noise.Type, static_cast<cloudvis::noise::NoiseType>(type));
}

int vtkCloudDensitySource::GetNoiseType() const
{
  return static_cast<int>(this->Field.Noise.Type);
}

void vtkCloudDensitySource::SetNoiseOctaves(int octaves)
{
  this->SetFieldValue(this->Field.Noise.Octaves, octaves);
}

void vtkCloudDensitySource::SetNoiseFrequency(double frequency)
{
  this->SetFieldValue(this->Field.Noise.Frequency, frequency);
}

void vtkCloudDensitySource::SetNoiseLacunarity(double lacunarity)
{
  this->SetFieldValue(this->Field.Noise.Lacunarity, lacunarity);
}

void vtkCloudDensitySource::SetNoiseLacunarityIncrement(double increment)
{
  this->SetFieldValue(this->Field.Noise.LacunarityIncrement, increment);
}

void vtkCloudDensitySource::SetNoiseGain(double gain)
{
  this->SetFieldValue(this->Field.Noise.Gain, gain);
}

void vtkCloudDensitySource::SetNoiseAmplitude(double amplitude)
{
  this->SetFieldValue(this->Field.Noise.Amplitude, amplitude);
}

void vtkCloudDensitySource::SetNoiseSeed(unsigned int seed)
{
  this->SetFieldValue(this->Field.Noise.Seed, static_cast<std::uint32_t>(seed));
}

void vtkCloudDensitySource::SetNoisePeriod(int period)
{
  this->SetFieldValue(this->Field.Noise.Period, static_cast<std::int32_t>(period));
}

void vtkCloudDensitySource::SetCloudType(int type)
{
  if (type < Stratus || type > Cumulonimbus)
  {
    vtkErrorMacro(<< "cloud type " << type << " is not one of 0 (stratus), 1 (stratocumulus), "
                  << "2 (cumulus), 3 (cumulonimbus); it stays " << this->GetCloudType());
    return;
  }
  this->SetFieldValue(this->Field.Layer.Type, static_cast<cloudvis::CloudType>(type));
}

int vtkCloudDensitySource::GetCloudType() const
{
  return static_cast<int>(this->Field.Layer.Type);
}

void vtkCloudDensitySource::SetCloudAltitudes(double base, double top)
{
  this->SetFieldValue(this->Field.Layer.Base, base);
  this->SetFieldValue(this->Field.Layer.Top, top);
}

void vtkCloudDensitySource::SetCloudCoverage(double coverage)
{
  this->SetFieldValue(this->Field.Layer.Coverage, coverage);
}

void vtkCloudDensitySource::SetCoverageSource(int source)
{
  if (source < ShapesCoverage || source > MapCoverage)
  {
    vtkErrorMacro(<< "coverage source " << source << " is not one of 0 (shapes), 1 (noise), "
                  << "2 (map); it stays " << this->GetCoverageSource());
    return;
  }
  this->SetFieldValue(this->Field.Layer.Source, static_cast<cloudvis::CoverageSource>(source));
}

int vtkCloudDensitySource::GetCoverageSource() const
{
  return static_cast<int>(this->Field.Layer.Source);
}

void vtkCloudDensitySource::SetCoverageMap(vtkImageData* image)
{
  if (!image)
  {
    this->Field.Layer.Map.reset();
    this->Modified();
    return;
  }
  std::string problem;
  auto map = cloudvis::CoverageMapOfImage(image, problem);
  if (!map)
  {
    vtkErrorMacro(<< "coverage map: " << problem);
    return;
  }
  this->Field.Layer.Map = std::move(map);
  this->Field.Layer.Source = cloudvis::CoverageSource::Map;
  this->Modified();
}

void vtkCloudDensitySource::SetWeatherMap(double scale, int octaves, double gain)
{
  this->SetFieldValue(this->Field.Layer.MapScale, scale);
  this->SetFieldValue(this->Field.Layer.MapOctaves, octaves);
  this->SetFieldValue(this->Field.Layer.MapGain, gain);
}

void vtkCloudDensitySource::SetCloudNoiseScales(double shape, double detail)
{
  this->SetFieldValue(this->Field.Layer.ShapeScale, shape);
  this->SetFieldValue(this->Field.Layer.DetailScale, detail);
}

void vtkCloudDensitySource::SetCloudErosion(double erosion)
{
  this->SetFieldValue(this->Field.Layer.Erosion, erosion);
}

void vtkCloudDensitySource::SetCloudCurl(double curl)
{
  this->SetFieldValue(this->Field.Layer.Curl, curl);
}

void vtkCloudDensitySource::SetCloudBreakup(double breakup)
{
  this->SetFieldValue(this->Field.Layer.Breakup, breakup);
}

void vtkCloudDensitySource::SetCloudAnvil(double anvil)
{
  this->SetFieldValue(this->Field.Layer.Anvil, anvil);
}

void vtkCloudDensitySource::SetCloudAnvilDirection(double x, double z)
{
  this->SetFieldValue(this->Field.Layer.AnvilDirection, std::array<double, 2>{ { x, z } });
}

void vtkCloudDensitySource::SetCloudAnvilReach(double reach)
{
  this->SetFieldValue(this->Field.Layer.AnvilReach, reach);
}

void vtkCloudDensitySource::SetCloudOvershoot(double overshoot)
{
  this->SetFieldValue(this->Field.Layer.Overshoot, overshoot);
}

void vtkCloudDensitySource::SetCloudRain(double rain)
{
  this->SetFieldValue(this->Field.Layer.Rain, rain);
}

void vtkCloudDensitySource::SetCloudShear(double x, double z)
{
  this->SetFieldValue(this->Field.Layer.Shear, std::array<double, 2>{ { x, z } });
}

void vtkCloudDensitySource::SetWind(double x, double y, double z)
{
  this->SetFieldValue(this->Field.Wind, glm::dvec3(x, y, z));
}

void vtkCloudDensitySource::GetWind(double wind[3]) const
{
  for (int i = 0; i < 3; ++i)
  {
    wind[i] = this->Field.Wind[i];
  }
}

cloudvis::FieldDescription vtkCloudDensitySource::FieldToGenerate() const
{
  cloudvis::FieldDescription field = this->Field;
  if (field.Layer.Map)
  {
    // The weather map spans the field's x and z bounds, whatever they are when it generates.
    auto map = std::make_shared<cloudvis::CoverageMap>(*field.Layer.Map);
    map->XMin = this->Bounds[0];
    map->XMax = this->Bounds[1];
    map->ZMin = this->Bounds[4];
    map->ZMax = this->Bounds[5];
    field.Layer.Map = std::move(map);
  }
  return field;
}

std::string vtkCloudDensitySource::Validate() const
{
  std::string error = cloudvis::ValidateFieldGeometry(this->Dimensions, this->Bounds);
  if (error.empty())
  {
    error = cloudvis::ValidateFieldDescription(this->Field);
  }
  if (error.empty())
  {
    error = cloudvis::ValidateNoiseRange(this->Field, this->Bounds, this->Time);
  }
  if (error.empty())
  {
    error = cloudvis::ValidateDensityRange(this->Field, this->Bounds);
  }
  if (error.empty())
  {
    error = cloudvis::ValidateCloudBounds(this->Field, this->Bounds);
  }
  if (error.empty() && (this->NumberOfTimeSteps < 0 || !(this->TimeRange[0] <= this->TimeRange[1])))
  {
    error = "time steps need a count >= 0 and an increasing time range";
  }
  return error;
}

std::string vtkCloudDensitySource::ValidateExtent(const int extent[6]) const
{
  return cloudvis::ValidateExtentMemory(extent);
}

int vtkCloudDensitySource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  const std::string error = this->Validate();
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  double origin[3], spacing[3];
  cloudvis::LatticeFromBounds(this->Dimensions, this->Bounds, origin, spacing);
  const int wholeExtent[6] = { 0, this->Dimensions[0] - 1, 0, this->Dimensions[1] - 1, 0,
    this->Dimensions[2] - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);

  std::vector<double> steps(this->NumberOfTimeSteps);
  for (int i = 0; i < this->NumberOfTimeSteps; ++i)
  {
    const double f = this->NumberOfTimeSteps > 1 ? double(i) / (this->NumberOfTimeSteps - 1) : 0.0;
    steps[i] = this->TimeRange[0] + f * (this->TimeRange[1] - this->TimeRange[0]);
  }
  if (steps.empty())
  {
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  }
  else
  {
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), steps.data(),
      static_cast<int>(steps.size()));
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), this->TimeRange, 2);
  return 1;
}

namespace
{
// Fills the rows (y, z) of one block of z slices of the output extent.
class FillRows
{
public:
  const cloudvis::DensityEvaluator& Evaluator;
  const int* Extent;
  const double* Origin;
  const double* Spacing;
  float* Density; // first voxel of the extent
  int FirstSlice;

  void operator()(vtkIdType begin, vtkIdType end) const
  {
    cloudvis::RowScratch scratch;
    const int nx = this->Extent[1] - this->Extent[0] + 1;
    const int ny = this->Extent[3] - this->Extent[2] + 1;
    for (vtkIdType row = begin; row < end; ++row)
    {
      const int j = this->Extent[2] + static_cast<int>(row % ny);
      const int k = this->FirstSlice + static_cast<int>(row / ny);
      const double y = this->Origin[1] + j * this->Spacing[1];
      const double z = this->Origin[2] + k * this->Spacing[2];
      const vtkIdType offset =
        (vtkIdType(k - this->Extent[4]) * ny + (j - this->Extent[2])) * vtkIdType(nx);
      this->Evaluator.EvaluateRow(this->Extent[0], nx, this->Origin[0], this->Spacing[0], y, z,
        this->Density + offset, scratch);
    }
  }
};
}

int vtkCloudDensitySource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  // The pipeline asks for data even when RequestInformation refused the parameters (a render
  // updates its volume's mapper regardless), and then with an extent nobody set: the parameters
  // are checked again, and the extent must lie in the lattice they make.
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  const int wholeExtent[6] = {
    0, this->Dimensions[0] - 1, 0, this->Dimensions[1] - 1, 0, this->Dimensions[2] - 1
  };
  std::string error = this->Validate();
  if (error.empty())
  {
    error =
      cloudvis::PipelineExtent(outInfo, vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent);
  }
  if (error.empty())
  {
    error = cloudvis::ValidateSubExtent(extent, wholeExtent);
  }
  if (error.empty())
  {
    error = this->ValidateExtent(extent);
  }
  if (!error.empty())
  {
    output->Initialize();
    vtkErrorMacro(<< error);
    return 0;
  }
  double origin[3], spacing[3];
  cloudvis::LatticeFromBounds(this->Dimensions, this->Bounds, origin, spacing);

  double time = this->Time;
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    time = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  }

  const std::string rangeError = cloudvis::ValidateNoiseRange(this->Field, this->Bounds, time);
  if (!rangeError.empty())
  {
    vtkErrorMacro(<< rangeError);
    return 0;
  }

  output->SetExtent(extent);
  output->SetOrigin(origin);
  output->SetSpacing(spacing);
  vtkNew<vtkFloatArray> density;
  density->SetName("density");
  density->SetNumberOfComponents(1);
  density->SetNumberOfTuples(output->GetNumberOfPoints());
  output->GetPointData()->SetScalars(density);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), time);
  if (output->GetNumberOfPoints() == 0)
  {
    return 1;
  }

  const cloudvis::DensityEvaluator evaluator(this->FieldToGenerate(), time);
  const int ny = extent[3] - extent[2] + 1;
  const int nz = extent[5] - extent[4] + 1;
  // Work in blocks of z slices so progress and abort are handled on this thread between blocks.
  const int blocks = std::min(nz, 20);
  this->UpdateProgress(0.0);
  for (int b = 0; b < blocks && !this->GetAbortExecute(); ++b)
  {
    const int firstSlice = extent[4] + b * nz / blocks;
    const int endSlice = extent[4] + (b + 1) * nz / blocks;
    const vtkIdType rows = vtkIdType(endSlice - firstSlice) * ny;
    FillRows fill{ evaluator, extent, origin, spacing, density->GetPointer(0), firstSlice };
    vtkSMPTools::For(0, rows, fill);
    this->UpdateProgress(double(b + 1) / blocks);
  }
  return 1;
}

void vtkCloudDensitySource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Dimensions: " << this->Dimensions[0] << ", " << this->Dimensions[1] << ", "
     << this->Dimensions[2] << "\n";
  os << indent << "Bounds: ";
  for (int i = 0; i < 6; ++i)
  {
    os << this->Bounds[i] << (i < 5 ? ", " : "\n");
  }
  os << indent << "Shapes: " << this->Field.Shapes.size() << (this->Field.Morph ? " (morph)" : "")
     << "\n";
  os << indent << "DensityModel: " << this->GetDensityModel() << "\n";
  os << indent << "DensityScale: " << this->Field.DensityScale << "\n";
  os << indent << "NoiseType: " << this->GetNoiseType() << "\n";
  os << indent << "Octaves: " << this->Field.Noise.Octaves << "\n";
  os << indent << "NoisePeriod: " << this->Field.Noise.Period << "\n";
  const cloudvis::CloudLayer& layer = this->Field.Layer;
  os << indent << "CloudType: " << this->GetCloudType() << "\n";
  os << indent << "CloudAltitudes: " << layer.Base << ", " << layer.Top << "\n";
  os << indent << "CloudCoverage: " << layer.Coverage << " (source " << this->GetCoverageSource()
     << (layer.Map ? ", a map is set" : "") << ")\n";
  os << indent << "WeatherMap: " << layer.MapScale << ", " << layer.MapOctaves << ", "
     << layer.MapGain << "\n";
  os << indent << "CloudNoiseScales: " << layer.ShapeScale << ", " << layer.DetailScale << "\n";
  os << indent << "CloudErosion: " << layer.Erosion << ", Curl: " << layer.Curl
     << ", Anvil: " << layer.Anvil << ", Shear: " << layer.Shear[0] << ", " << layer.Shear[1]
     << "\n";
  os << indent << "Time: " << this->Time << "\n";
  os << indent << "TimeRange: " << this->TimeRange[0] << ", " << this->TimeRange[1] << "\n";
  os << indent << "NumberOfTimeSteps: " << this->NumberOfTimeSteps << "\n";
}
