// The table of field formats, the conversion every reader's image goes through, and the .vti
// writer. The readers themselves live with their formats (VtkXmlImageFiles.cxx for .vti and
// .pvti).
#include "FieldIO.h"

#include "AtomicFile.h"
#include "Errors.h"
#include "FileNames.h"
#include "VtkMessageCapture.h"
#include "VtkXmlImageFiles.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{
namespace
{

[[noreturn]] void Fail(const std::string& path, const std::string& problem)
{
  throw InputError(path + ": " + problem);
}

// The array a density is taken from: "density" by name, else whatever the file marks as scalars.
vtkDataArray* DensityArray(vtkImageData* image)
{
  vtkPointData* points = image->GetPointData();
  if (vtkDataArray* named = points->GetArray("density"))
  {
    return named;
  }
  return points->GetScalars();
}

// The density field of an image a reader returned: its geometry and one float array "density",
// after checking the array is one the renderer can use.
vtkSmartPointer<vtkImageData> DensityFieldOf(const std::string& path, vtkImageData* image)
{
  if (image->GetNumberOfPoints() == 0)
  {
    Fail(path, "the image has no voxels");
  }
  vtkDataArray* array = DensityArray(image);
  if (!array)
  {
    Fail(path, "no point array named \"density\" and no active point scalars");
  }
  const std::string name = array->GetName() ? array->GetName() : "(unnamed)";
  if (array->GetNumberOfComponents() != 1)
  {
    Fail(path,
      "point array \"" + name + "\" has " + std::to_string(array->GetNumberOfComponents()) +
        " components; a density field needs 1");
  }
  const int type = array->GetDataType();
  if (type != VTK_FLOAT && type != VTK_UNSIGNED_CHAR && type != VTK_UNSIGNED_SHORT)
  {
    Fail(path,
      "point array \"" + name + "\" is of type " + array->GetDataTypeAsString() +
        "; supported: float, unsigned char, unsigned short");
  }
  if (array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    Fail(path,
      "point array \"" + name + "\" has " + std::to_string(array->GetNumberOfTuples()) +
        " values for " + std::to_string(image->GetNumberOfPoints()) + " voxels");
  }

  vtkNew<vtkFloatArray> density;
  density->SetName("density");
  density->SetNumberOfTuples(array->GetNumberOfTuples());
  vtkIdType nonFinite = 0;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    const double value = array->GetComponent(i, 0);
    nonFinite += std::isfinite(value) ? 0 : 1;
    density->SetValue(i, static_cast<float>(value));
  }
  if (nonFinite > 0)
  {
    Fail(path,
      "point array \"" + name + "\" holds " + std::to_string(nonFinite) +
        " values that are NaN or infinite");
  }

  // A new image with just the geometry and the density, so arrays of other meanings in the file
  // do not travel on as if they were ours.
  vtkSmartPointer<vtkImageData> field = vtkSmartPointer<vtkImageData>::New();
  field->SetExtent(image->GetExtent());
  field->SetOrigin(image->GetOrigin());
  field->SetSpacing(image->GetSpacing());
  field->GetPointData()->SetScalars(density);
  return field;
}

} // namespace

const std::vector<FieldFormat>& FieldFormats()
{
  static const std::vector<FieldFormat> formats = {
    { "VTK XML image data", { ".vti" }, ReadVtkXmlImageFile },
    { "VTK XML parallel image data", { ".pvti" }, ReadVtkXmlParallelImageFile },
  };
  return formats;
}

const FieldFormat* FindFieldFormat(const std::string& path)
{
  const std::string extension = LowerCaseExtension(path);
  for (const FieldFormat& format : FieldFormats())
  {
    if (std::find(format.Extensions.begin(), format.Extensions.end(), extension) !=
      format.Extensions.end())
    {
      return &format;
    }
  }
  return nullptr;
}

bool IsFieldFile(const std::string& path)
{
  return FindFieldFormat(path) != nullptr;
}

std::string FieldFileExtensions()
{
  std::string list;
  for (const FieldFormat& format : FieldFormats())
  {
    for (const std::string& extension : format.Extensions)
    {
      list += (list.empty() ? "" : ", ") + extension;
    }
  }
  return list;
}

vtkSmartPointer<vtkImageData> ReadField(const std::string& path)
{
  const FieldFormat* format = FindFieldFormat(path);
  if (!format)
  {
    const std::string extension = LowerCaseExtension(path);
    Fail(path,
      (extension.empty() ? std::string("the file name has no field extension")
                         : "unsupported field format \"" + extension + "\"") +
        "; supported: " + FieldFileExtensions());
  }
  const vtkSmartPointer<vtkImageData> image = format->Read(path);
  return DensityFieldOf(path, image);
}

void CheckFieldOutput(const std::string& path)
{
  CheckOutputTarget(path); // first: "it is a directory" says more than a missing extension
  if (LowerCaseExtension(path) != ".vti")
  {
    Fail(path, "fields are written as VTK XML image data: give the output a .vti name");
  }
}

void WriteField(vtkImageData* field, const std::string& path)
{
  CheckFieldOutput(path);
  WriteFileAtomically(path,
    [field, &path](const std::string& temporary)
    {
      VtkMessageCapture messages;
      vtkNew<vtkXMLImageDataWriter> writer;
      writer->SetInputData(field);
      writer->SetFileName(temporary.c_str());
      // Raw appended binary (no base64) compressed with zlib: the smallest file VTK and
      // ParaView read back exactly.
      writer->SetDataModeToAppended();
      writer->EncodeAppendedDataOff();
      writer->SetCompressorTypeToZLib();
      if (writer->Write() != 1 || writer->GetErrorCode() != 0)
      {
        const std::string summary = messages.Summary();
        Fail(path, "cannot write the field" + (summary.empty() ? "" : " (VTK: " + summary + ")"));
      }
    });
}

} // namespace cloudvis
