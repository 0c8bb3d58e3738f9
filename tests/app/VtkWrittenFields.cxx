#include "VtkWrittenFields.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRTAnalyticSource.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPImageDataWriter.h>

#include <stdexcept>

namespace cloudvis
{
namespace test
{
namespace
{

vtkSmartPointer<vtkRTAnalyticSource> Source()
{
  auto source = vtkSmartPointer<vtkRTAnalyticSource>::New();
  source->SetWholeExtent(0, 9, 0, 7, 0, 5);
  return source;
}

void Check(int written, const std::string& path)
{
  if (written != 1)
  {
    throw std::runtime_error("VTK could not write " + path);
  }
}

} // namespace

vtkSmartPointer<vtkImageData> ReferenceField()
{
  vtkSmartPointer<vtkRTAnalyticSource> source = Source();
  source->Update();
  return source->GetOutput();
}

const std::vector<BigEndianVariant>& BigEndianVariants()
{
  static const std::vector<BigEndianVariant> variants = {
    { "big-endian-zlib.vti", true, true, vtkXMLWriterBase::ZLIB, false },
    { "big-endian-zlib-uint64.vti", true, true, vtkXMLWriterBase::ZLIB, true },
    { "big-endian-lz4.vti", true, true, vtkXMLWriterBase::LZ4, false },
    { "big-endian-uncompressed.vti", true, true, vtkXMLWriterBase::NONE, false },
    { "big-endian-base64-zlib.vti", true, false, vtkXMLWriterBase::ZLIB, false },
    { "big-endian-inline.vti", false, false, vtkXMLWriterBase::ZLIB, false },
  };
  return variants;
}

std::string WriteBigEndian(const std::string& directory, const BigEndianVariant& variant)
{
  const std::string path = directory + "/" + variant.Name;
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputConnection(Source()->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->SetByteOrderToBigEndian();
  if (variant.Appended)
  {
    writer->SetDataModeToAppended();
  }
  else
  {
    writer->SetDataModeToBinary();
  }
  writer->SetEncodeAppendedData(!variant.Raw);
  writer->SetCompressorType(variant.Compressor);
  if (variant.Header64)
  {
    writer->SetHeaderTypeToUInt64();
  }
  Check(writer->Write(), path);
  return path;
}

std::string WriteParallel(const std::string& directory,
  const std::string& name,
  int pieces,
  bool subdirectory,
  bool bigEndian)
{
  const std::string path = directory + "/" + name;
  vtkNew<vtkXMLPImageDataWriter> writer;
  writer->SetInputConnection(Source()->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->SetNumberOfPieces(pieces);
  writer->SetStartPiece(0);
  writer->SetEndPiece(pieces - 1);
  writer->SetUseSubdirectory(subdirectory);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  if (bigEndian)
  {
    writer->SetByteOrderToBigEndian();
  }
  Check(writer->Write(), path);
  return path;
}

} // namespace test
} // namespace cloudvis
