// Kept apart from Scene.cxx so that parsing stays free of pipeline objects and this file is the
// single place that maps scene values onto vtkCloudDensitySource.
#include "SceneField.h"

#include "Errors.h"
#include "FieldIO.h"
#include "InputFiles.h"
#include "VtkMessageCapture.h"
#include "vtkCloudDensitySource.h"

#include <vtkCallbackCommand.h>
#include <vtkImageData.h>
#include <vtkImageReader2.h>
#include <vtkImageReader2Factory.h>
#include <vtkNew.h>

namespace cloudvis
{

namespace
{
// field.cloud.coverage_map's file: a field file of any format cloudvis reads (by its extension,
// as field.file is read), else an image VTK's image readers know (PNG, JPEG, TIFF, BMP, PNM).
// The field readers go first because VTK's image factory picks a reader by probing contents, and
// its HDR reader claims some .vti files (XML with a comment), then fails with "Read error". The
// file is checked first, so a missing file, a directory or a FIFO is reported as such, not as
// an unsupported format.
vtkSmartPointer<vtkImageData> ReadCoverageMap(const std::string& path)
{
  CheckRegularInputFile(path, "coverage map");
  if (IsFieldFile(path))
  {
    return ReadField(path, FieldReadOptions{});
  }
  VtkMessageCapture messages;
  vtkSmartPointer<vtkImageReader2> reader;
  reader.TakeReference(vtkImageReader2Factory::CreateImageReader2(path.c_str()));
  if (!reader)
  {
    throw InputError(path +
      ": coverage map: not an image VTK can read (PNG, JPEG, TIFF, BMP, "
      "PNM) nor a field file (" +
      FieldFileExtensions() + ")");
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (!messages.Messages().empty() || !image || image->GetNumberOfPoints() == 0)
  {
    throw InputError(path + ": coverage map: the image cannot be read" +
      (messages.Summary().empty() ? "" : " (VTK: " + messages.Summary() + ")"));
  }
  vtkSmartPointer<vtkImageData> copy = vtkSmartPointer<vtkImageData>::New();
  copy->ShallowCopy(image);
  return copy;
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
  source->SetField(field.Description);
  source->SetTime(field.Time);
  if (!field.CoverageMapFile.empty())
  {
    std::string problem;
    std::shared_ptr<const CoverageMap> map =
      CoverageMapOfImage(ReadCoverageMap(field.CoverageMapFile), problem);
    if (!map)
    {
      throw InputError(field.CoverageMapFile + ": coverage map: " + problem);
    }
    FieldDescription description = field.Description;
    description.Layer.Map = map;
    source->SetField(description);
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
    throw InputError(scene.Source + ": field: generation failed" +
      (messages.Summary().empty() ? "" : " (VTK: " + messages.Summary() + ")"));
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
    field = GenerateField(scene, progress);
    ResolveFieldValues(scene.Source, field, scene.Field.Units, read);
  }
  ResolveFieldOptics(scene, read.Resolved, scene.Field.FromFile() ? scene.Field.File : "");
  if (report)
  {
    *report = read;
  }
  return field;
}

} // namespace cloudvis
