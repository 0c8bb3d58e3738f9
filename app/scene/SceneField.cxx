// Kept apart from Scene.cxx so that parsing stays free of pipeline objects and this file is the
// single place that maps scene values onto vtkCloudDensitySource.
#include "SceneField.h"

#include "Errors.h"
#include "FieldIO.h"
#include "ImageFiles.h"
#include "InputFiles.h"
#include "OutOfMemory.h"
#include "VtkMessageCapture.h"
#include "vtkCloudDensitySource.h"

#include <vtkCallbackCommand.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <vector>

namespace cloudvis
{

namespace
{
// The stored values of a field file read as a map, in the type the file stores them (ReadField
// made them float), so that CoverageMapOfImage divides integers by their type's maximum as it
// does an image's: an 8-bit .vti or NRRD map of 255 is full coverage, as an 8-bit PNG's is.
vtkSmartPointer<vtkImageData> AsStored(vtkImageData* field, int storedType)
{
  vtkDataArray* values = field->GetPointData()->GetScalars();
  if (storedType == 0 || storedType == VTK_FLOAT || storedType == VTK_DOUBLE || !values)
  {
    return field;
  }
  vtkSmartPointer<vtkDataArray> stored;
  stored.TakeReference(vtkDataArray::CreateDataArray(storedType));
  stored->SetNumberOfTuples(values->GetNumberOfTuples());
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    stored->SetTuple1(i, values->GetTuple1(i)); // integers, exact in float up to 2^24
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->CopyStructure(field);
  image->GetPointData()->SetScalars(stored);
  return image;
}

// field.cloud.coverage_map's file: a field file of any format cloudvis reads (by its extension,
// as field.file is read), else an image VTK's image readers know (PNG, JPEG, TIFF, BMP, PNM),
// read in isolation with its size checked first (ImageFiles.h). The field readers go first
// because VTK's image factory picks a reader by probing contents, and its HDR reader claims some
// .vti files (XML with a comment), then fails with "Read error". The file is checked first, so a
// missing file, a directory or a FIFO is reported as such, not as an unsupported format. Either
// way the map may have at most MaximumCoverageMapPixels points.
std::shared_ptr<const CoverageMap> ReadCoverageMap(const std::string& path)
{
  static const std::string limit = "a coverage map may have (16384 x 16384, 268 M)";
  static_assert(MaximumCoverageMapPixels == 16384u * 16384u, "the limit's words");
  CheckRegularInputFile(path, "coverage map");
  vtkSmartPointer<vtkImageData> image;
  if (IsFieldFile(path))
  {
    // Read as field.file is, within the field files' limits; the map's own limit then applies
    // to what was read.
    FieldReport report;
    const vtkSmartPointer<vtkImageData> field = ReadField(path, FieldReadOptions{}, &report);
    image = AsStored(field, report.StoredType);
    int d[3];
    image->GetDimensions(d);
    std::vector<double> axes;
    for (int a = 0; a < 3; ++a)
    {
      if (d[a] > 1)
      {
        axes.push_back(d[a]);
      }
    }
    if (axes.size() <= 2)
    {
      axes.resize(2, 1.0);
      CheckImageSize(path, "coverage map", axes[0], axes[1], 4.0, MaximumCoverageMapPixels, limit);
    }
  }
  else
  {
    // Each pixel becomes one float of the map.
    image = ReadImageFile(path, "coverage map", MaximumCoverageMapPixels, limit, 4.0);
  }
  std::string problem;
  std::shared_ptr<const CoverageMap> map = CoverageMapOfImage(image, problem);
  if (!map)
  {
    throw InputError(path + ": coverage map: " + problem);
  }
  return map;
}

// Whether the field takes its coverage from the map in CoverageMapFile: only the cloud model
// reads one.
bool UsesCoverageMapFile(const FieldSpec& field)
{
  return field.Description.Model == DensityModel::Cloud &&
    field.Description.Layer.Source == CoverageSource::Map && !field.CoverageMapFile.empty();
}
}

void LoadCoverageMap(FieldSpec& field)
{
  if (UsesCoverageMapFile(field) && !field.Description.Layer.Map)
  {
    field.Description.Layer.Map = ReadCoverageMap(field.CoverageMapFile);
  }
}

vtkSmartPointer<vtkCloudDensitySource> MakeDensitySource(const FieldSpec& field)
{
  if (field.FromFile())
  {
    throw InputError(field.File + ": a field loaded from a file has no procedural source");
  }
  auto source = vtkSmartPointer<vtkCloudDensitySource>::New();
  source->SetDimensions(field.Dimensions.data());
  source->SetBounds(field.Bounds.data());
  source->SetTime(field.Time);
  if (UsesCoverageMapFile(field) && !field.Description.Layer.Map)
  {
    // A FieldSpec not made by the scene's reader (which loads the map once, LoadCoverageMap).
    FieldSpec loaded = field;
    LoadCoverageMap(loaded);
    source->SetField(loaded.Description);
  }
  else
  {
    source->SetField(field.Description);
  }
  return source;
}

std::string ValidateProceduralField(const FieldSpec& field)
{
  return MakeDensitySource(field)->Validate();
}

namespace
{
// The scene's procedural field, generated whole.
vtkSmartPointer<vtkImageData> GenerateField(const Scene& scene,
  const std::function<void(double fraction)>& progress)
{
  vtkSmartPointer<vtkCloudDensitySource> source = MakeDensitySource(scene.Field);
  VtkMessageCapture messages;
  // The scene was validated with the same checks the source applies; what it could not check is
  // the memory of the whole field, which is what is made here (generating pieces of it, as
  // `generate -o f.pvti` does, needs only a piece's memory).
  const std::array<int, 3>& d = scene.Field.Dimensions;
  const int wholeExtent[6] = { 0, d[0] - 1, 0, d[1] - 1, 0, d[2] - 1 };
  std::string problem = source->Validate();
  problem = problem.empty() ? source->ValidateExtent(wholeExtent) : problem;
  if (!problem.empty())
  {
    throw InputError(scene.Source + ": field: " + problem);
  }
  const MemoryUse memory("generating a field of " + std::to_string(d[0]) + " x " +
      std::to_string(d[1]) + " x " + std::to_string(d[2]) + " voxels (" + scene.Source + ")",
    4.0 * double(d[0]) * double(d[1]) * double(d[2]));
  vtkNew<vtkCallbackCommand> onProgress;
  if (progress)
  {
    onProgress->SetClientData(const_cast<std::function<void(double)>*>(&progress));
    onProgress->SetCallback([](vtkObject*, unsigned long, void* client, void* fraction)
      { (*static_cast<std::function<void(double)>*>(client))(*static_cast<double*>(fraction)); });
    source->AddObserver(vtkCommand::ProgressEvent, onProgress);
  }
  source->Update();
  vtkImageData* output = source->GetOutput();
  if (!output || output->GetNumberOfPoints() == 0 || !messages.Messages().empty())
  {
    throw InputError(messages.WithVtkReason(scene.Source + ": field: generation failed"));
  }
  vtkSmartPointer<vtkImageData> field = vtkSmartPointer<vtkImageData>::New();
  field->ShallowCopy(output);
  return field;
}

} // namespace

vtkSmartPointer<vtkImageData> ProduceField(const Scene& scene,
  const std::function<void(double fraction)>& progress,
  FieldReport* report)
{
  Scene finished = scene;
  return ProduceField(finished, progress, report);
}

vtkSmartPointer<vtkImageData> ProduceField(Scene& scene,
  const std::function<void(double fraction)>& progress,
  FieldReport* report)
{
  FieldReport read;
  vtkSmartPointer<vtkImageData> field;
  if (scene.Field.FromFile())
  {
    FieldReadOptions options = scene.Field.Read;
    options.Units = scene.Field.Units;
    field = ReadField(scene.Field.File, options, &read);
  }
  else
  {
    read.Format = "procedural (generated from the scene's field section)";
    if (scene.Field.AutoDimensions)
    {
      const LengthUnit length = ResolveFieldUnits(scene.Field.Units, {}).Length;
      read.Add("dimensions",
        "auto, " +
          DescribeCameraDetail(*scene.Field.AutoDimensions,
            length == LengthUnit::None ? "world units" : LengthUnitName(length),
            scene.Field.Read.MaximumVoxels));
    }
    field = GenerateField(scene, progress);
    ResolveFieldValues(scene.Source, field, scene.Field.Units, read);
  }
  ResolveFieldOptics(scene, read.Resolved, scene.Field.FromFile() ? scene.Field.File : "");
  TurnDefaultViewToUp(scene, read.Resolved.Up);
  if (report)
  {
    *report = read;
  }
  return field;
}

void CheckTimeSteps(const Scene& scene,
  const std::vector<int>& steps,
  const FieldReport& read,
  const std::string& what)
{
  if (!steps.empty() && std::size_t(steps.back()) >= read.TimeSteps)
  {
    throw InputError(scene.Field.File + ": " + what + ": step " + std::to_string(steps.back()) +
      " is out of range: the file holds " + std::to_string(read.TimeSteps) + " time step" +
      (read.TimeSteps == 1 ? "" : "s") + " (0 .. " + std::to_string(read.TimeSteps - 1) + ")");
  }
}

} // namespace cloudvis
