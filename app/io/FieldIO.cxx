// The .vti reader and writer, with VTK's messages captured so failures read as one sentence.
#include "FieldIO.h"

#include "AtomicFile.h"
#include "Errors.h"
#include "VtkMessageCapture.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sys/stat.h>

namespace cloudvis
{
namespace
{

[[noreturn]] void Fail(const std::string& path, const std::string& problem)
{
  throw InputError(path + ": " + problem);
}

std::string WithVtkReason(const std::string& problem, const VtkMessageCapture& messages)
{
  const std::string summary = messages.Summary();
  return summary.empty() ? problem : problem + " (VTK: " + summary + ")";
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

} // namespace

vtkSmartPointer<vtkImageData> ReadField(const std::string& path)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    Fail(path, std::string("cannot read field: ") + std::strerror(errno));
  }
  if (S_ISDIR(info.st_mode))
  {
    Fail(path, "cannot read field: it is a directory");
  }
  if (!std::ifstream(path, std::ios::binary))
  {
    Fail(path, std::string("cannot read field: ") + std::strerror(errno));
  }

  VtkMessageCapture messages;
  vtkNew<vtkXMLImageDataReader> reader;
  // CanReadFile checks the XML header names VTKFile of type ImageData, before any parsing that
  // would otherwise fill the output window with errors.
  if (!reader->CanReadFile(path.c_str()))
  {
    Fail(path, WithVtkReason("not a VTK XML image data file (.vti)", messages));
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || !messages.Messages().empty() || !image)
  {
    Fail(path, WithVtkReason("cannot read VTK XML image data", messages));
  }
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
    Fail(path, "point array \"" + name + "\" has " + std::to_string(array->GetNumberOfComponents()) +
        " components; a density field needs 1");
  }
  const int type = array->GetDataType();
  if (type != VTK_FLOAT && type != VTK_UNSIGNED_CHAR && type != VTK_UNSIGNED_SHORT)
  {
    Fail(path, "point array \"" + name + "\" is of type " + array->GetDataTypeAsString() +
        "; supported: float, unsigned char, unsigned short");
  }
  if (array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    Fail(path, "point array \"" + name + "\" has " + std::to_string(array->GetNumberOfTuples()) +
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
    Fail(path, "point array \"" + name + "\" holds " + std::to_string(nonFinite) +
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

void WriteField(vtkImageData* field, const std::string& path)
{
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
        Fail(path, WithVtkReason("cannot write the field", messages));
      }
    });
}

} // namespace cloudvis
