// The .vti reader and writer, with VTK's messages captured so failures read as one sentence.
#include "FieldIO.h"

#include "AtomicFile.h"
#include "Errors.h"
#include "VtkMessageCapture.h"

#include "CloudFieldGeometry.h" // AvailableMemoryBytes, FormatBytes

#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <limits>
#include <cstring>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>
#include <sys/wait.h>
#include <sys/resource.h>
#include <csignal>

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

// Refuses a header whose whole extent is empty, or whose point arrays (counted as 4 bytes per
// voxel each, plus the float copy ReadField makes) would not fit in the memory available.
void CheckExtentFitsInMemory(const std::string& path, vtkXMLImageDataReader* reader)
{
  vtkInformation* information = reader->GetOutputInformation(0);
  if (!information || !information->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    Fail(path, "the image data header states no extent");
  }
  int extent[6];
  information->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  double voxels = 1.0;
  int dimensions[3];
  for (int a = 0; a < 3; ++a)
  {
    // In double: a corrupt extent such as "-2147483648 2147483647" overflows int.
    const double size = double(extent[2 * a + 1]) - double(extent[2 * a]) + 1.0;
    if (size < 1.0)
    {
      Fail(path, "the image has no voxels (whole extent " + std::to_string(extent[2 * a]) + " to " +
          std::to_string(extent[2 * a + 1]) + " along axis " + std::to_string(a) + ")");
    }
    if (size > double(std::numeric_limits<int>::max()))
    {
      Fail(path, "the image's extent along axis " + std::to_string(a) + " is too large");
    }
    dimensions[a] = int(size);
    voxels *= size;
  }
  const int arrays = std::max(1, reader->GetNumberOfPointArrays());
  const double needed = voxels * 4.0 * (arrays + 1);
  const std::uint64_t available = AvailableMemoryBytes();
  if (voxels >= double(std::numeric_limits<vtkIdType>::max()))
  {
    Fail(path, "the image's extent holds more voxels than can be addressed");
  }
  if (available > 0 && needed > double(available))
  {
    Fail(path, "an image of " + std::to_string(dimensions[0]) + " x " +
        std::to_string(dimensions[1]) + " x " + std::to_string(dimensions[2]) +
        " voxels needs at least " + FormatBytes(needed) + " but only " +
        FormatBytes(double(available)) + " of memory is available");
  }
}

// VTK's reader sizes buffers from the binary headers of appended arrays (a byte count, or a
// block count followed by that many block sizes) before it reads them, so a corrupt count makes
// it allocate gigabytes while reading the header (found by the fuzzer). For raw appended data,
// each header must at least fit in the file; base64 and inline data are left to VTK.
// VTK loops for minutes over a NumberOfComponents it misreads (found by the fuzzer:
// "1888888888888cii"). An array's component count must be a plain integer from 1 to 1024.
void CheckComponentCount(const std::string& path, const std::string& tag)
{
  const std::string attribute = "NumberOfComponents=\"";
  const auto at = tag.find(attribute);
  if (at == std::string::npos)
  {
    return; // VTK's default: 1
  }
  const auto begin = at + attribute.size();
  const auto end = tag.find('"', begin);
  const std::string value = tag.substr(begin, end == std::string::npos ? end : end - begin);
  const bool digits = !value.empty() && value.size() <= 4 &&
    value.find_first_not_of("0123456789") == std::string::npos;
  if (!digits || std::stoi(value) < 1 || std::stoi(value) > 1024)
  {
    Fail(path, "an array's NumberOfComponents is not an integer from 1 to 1024 (\"" +
        (value.size() > 20 ? value.substr(0, 17) + "..." : value) + "\")");
  }
}

void CheckAppendedHeaders(const std::string& path, std::ifstream& file, std::uint64_t fileSize)
{
  // The XML part: up to the '_' that starts the raw appended bytes (1 MiB is far more than the
  // markup of any image file needs).
  std::string xml(std::size_t(std::min<std::uint64_t>(fileSize, 1 << 20)), '\0');
  file.read(&xml[0], std::streamsize(xml.size()));
  xml.resize(std::size_t(file.gcount()));
  const auto header = xml.find("<VTKFile");
  const auto appended = xml.find("<AppendedData");
  // VTK 9.1 dereferences a null array when an element of FieldData, PointData or CellData is not
  // an array of a type it knows (found by the fuzzer: a FieldData array without type=, and an
  // element of another name, crash vtkXMLReader::ReadXMLInformation). So every start tag in those
  // sections, other than the InformationKey/Value entries VTK nests in arrays, needs a known type.
  const auto markupEnd = appended == std::string::npos ? xml.size() : appended;
  static const char* const types[] = { "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32",
    "Int64", "UInt64", "Float32", "Float64", "String", "Bit", "IdType", "Char" };
  const auto hasKnownType = [](const std::string& tag)
  {
    for (const char* type : types)
    {
      for (const char* space : { " ", "\n", "\t", "\r" })
      {
        if (tag.find(std::string(space) + "type=\"" + type + "\"") != std::string::npos)
        {
          return true;
        }
      }
    }
    return false;
  };
  for (const char* section : { "FieldData", "PointData", "CellData" })
  {
    const std::string open = std::string("<") + section;
    const std::string close = std::string("</") + section;
    for (auto start = xml.find(open); start < markupEnd; start = xml.find(open, start + 1))
    {
      const auto sectionTagEnd = xml.find('>', start);
      if (sectionTagEnd == std::string::npos || xml[sectionTagEnd - 1] == '/')
      {
        continue; // cut off by the 1 MiB window, or an empty <PointData/>
      }
      const auto end = std::min(xml.find(close, sectionTagEnd), markupEnd);
      for (auto at = xml.find('<', sectionTagEnd); at < end; at = xml.find('<', at + 1))
      {
        const auto tagEnd = xml.find('>', at);
        if (tagEnd == std::string::npos)
        {
          break; // VTK's parser reports an unterminated tag itself
        }
        const std::string tag = xml.substr(at, tagEnd - at);
        if (tag[1] == '/' || tag[1] == '!' || tag[1] == '?' || tag.rfind("<InformationKey", 0) == 0 ||
          tag.rfind("<Value", 0) == 0)
        {
          continue;
        }
        // VTK reads any element here as an array, whatever its name; its writers only ever put
        // DataArray (and Array, for non-numeric arrays) here. Another name with a known type
        // (a PointData nested in PointData, found by the fuzzer) slipped past the header checks
        // below and made VTK allocate 17 GB.
        const auto named = [&tag](const char* name) {
          const std::string prefix = std::string("<") + name;
          return tag.rfind(prefix, 0) == 0 && tag.size() > prefix.size() &&
            std::isspace(static_cast<unsigned char>(tag[prefix.size()]));
        };
        if ((named("DataArray") || named("Array")) && hasKnownType(tag))
        {
          CheckComponentCount(path, tag);
          continue;
        }
        Fail(path, std::string("an element of ") + section +
            " is not a DataArray of a known type (" +
            (tag.size() > 60 ? tag.substr(0, 57) + "..." : tag) + ">)");
      }
    }
  }
  const auto appendedEnd = appended == std::string::npos ? appended : xml.find('>', appended);
  if (header == std::string::npos || appendedEnd == std::string::npos ||
    xml.substr(appended, appendedEnd - appended).find("encoding=\"raw\"") == std::string::npos)
  {
    return;
  }
  const auto underscore = xml.find('_', appendedEnd);
  if (underscore == std::string::npos)
  {
    // Without the marker VTK takes whatever follows for the array headers (found by the fuzzer:
    // a block count read from text made it allocate 7.8 GB).
    Fail(path, "the appended data has no '_' marking where its bytes start");
  }
  // Only white space may come before the '_' that marks the data: VTK does not insist, and then
  // takes stray bytes for a header (found by the fuzzer).
  if (xml.find_first_not_of(" \t\r\n", appendedEnd + 1) != underscore)
  {
    Fail(path, "unexpected bytes between <AppendedData> and the '_' that starts its data");
  }
  const std::string fileTag = xml.substr(header, xml.find('>', header) - header);
  const std::uint64_t word = fileTag.find("header_type=\"UInt64\"") != std::string::npos ? 8 : 4;
  const bool compressed = fileTag.find("compressor=") != std::string::npos;
  const std::uint64_t start = underscore + 1;
  const std::uint64_t available = fileSize > start ? fileSize - start : 0;
  // Every offset="N" before the appended data is the position of an array's header.
  for (auto at = xml.find("offset=\"", header); at != std::string::npos && at < appended;
       at = xml.find("offset=\"", at + 1))
  {
    const std::uint64_t offset = std::strtoull(xml.c_str() + at + 8, nullptr, 10);
    const std::uint64_t words = compressed ? 3 : 1;
    if (offset > available || (available - offset) / word < words)
    {
      Fail(path, "the appended data ends before the header of the array at offset " +
          std::to_string(offset));
    }
    if (compressed)
    {
      std::uint64_t blocks = 0; // little endian, as cloudvis writes and reads
      file.clear();
      file.seekg(std::streamoff(start + offset));
      file.read(reinterpret_cast<char*>(&blocks), std::streamsize(word));
      if (!file || blocks > (available - offset) / word - 3)
      {
        Fail(path, "the header of the array at offset " + std::to_string(offset) + " claims " +
            std::to_string(blocks) + " compressed blocks, more than the file holds");
      }
    }
  }
}

} // namespace

// VTK's XML reader trusts the file: crafted headers make it crash, loop or allocate gigabytes
// (docs/reliability.md lists what the fuzzer found). The text checks above close the classes
// found so far; this closes the family: the file is first read in a forked child under an
// address-space and a time limit, and only a file VTK read there without complaint is read
// here. The cost is reading a field twice.
// How the isolated reader's child ends; any other exit status, or a signal, is a failure.
constexpr int ChildReadCleanly = 0;
constexpr int ChildVtkComplained = 3;
constexpr int ChildOutOfMemory = 4;

void ReadInIsolation(const std::string& path, std::uint64_t fileSize)
{
  const unsigned seconds = 60u + unsigned(fileSize / (10u << 20)); // 60 s + 1 s per 10 MiB
  const pid_t child = ::fork();
  if (child < 0)
  {
    return; // no isolation to be had: read directly, behind the text checks alone
  }
  if (child == 0)
  {
#if !defined(__SANITIZE_ADDRESS__)
    // The child may use what the process already maps plus the memory still available, so a
    // header claiming more fails here as an allocation, not in the parent as an OOM kill.
    // (AddressSanitizer reserves terabytes of shadow memory, so its builds skip the limit.)
    std::uint64_t mapped = 0;
    std::ifstream status("/proc/self/status");
    for (std::string key; status >> key;)
    {
      if (key == "VmSize:")
      {
        status >> mapped;
        mapped *= 1024u;
        break;
      }
    }
    const std::uint64_t available = AvailableMemoryBytes();
    if (mapped > 0 && available > 0)
    {
      const rlimit memory{ rlim_t(mapped + available), rlim_t(mapped + available) };
      ::setrlimit(RLIMIT_AS, &memory);
    }
#endif
    ::alarm(seconds);
    int code = ChildVtkComplained;
    try
    {
      VtkMessageCapture messages;
      vtkNew<vtkXMLImageDataReader> reader;
      if (reader->CanReadFile(path.c_str()))
      {
        reader->SetFileName(path.c_str());
        reader->Update();
        code = reader->GetErrorCode() == 0 && messages.Messages().empty() ? ChildReadCleanly
                                                                          : ChildVtkComplained;
      }
    }
    catch (...)
    {
      code = ChildOutOfMemory; // std::bad_alloc under the limit, most likely
    }
    ::_exit(code);
  }
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR)
  {
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == ChildReadCleanly || code == ChildVtkComplained)
  {
    return; // read it here; VTK's complaints are then reported in its own words
  }
  if (code == ChildOutOfMemory)
  {
    Fail(path, "VTK's reader ran out of memory on this file: it claims more than the " +
        FormatBytes(double(AvailableMemoryBytes())) + " available");
  }
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
  {
    Fail(path, "VTK's reader took longer than " + std::to_string(seconds) +
        " s on this file without finishing: it is malformed");
  }
  if (WIFSIGNALED(status))
  {
    Fail(path, "VTK's reader crashed on this file (" + std::string(strsignal(WTERMSIG(status))) +
        "): it is malformed");
  }
  // Another status: a sanitizer (in sanitized builds) caught VTK doing something fatal.
  Fail(path, "VTK's reader failed on this file (exit status " + std::to_string(code) +
      "): it is malformed");
}

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
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    Fail(path, std::string("cannot read field: ") + std::strerror(errno));
  }
  CheckAppendedHeaders(path, file, std::uint64_t(info.st_size));
  ReadInIsolation(path, std::uint64_t(info.st_size));

  VtkMessageCapture messages;
  vtkNew<vtkXMLImageDataReader> reader;
  // CanReadFile checks the XML header names VTKFile of type ImageData, before any parsing that
  // would otherwise fill the output window with errors.
  if (!reader->CanReadFile(path.c_str()))
  {
    Fail(path, WithVtkReason("not a VTK XML image data file (.vti)", messages));
  }
  reader->SetFileName(path.c_str());
  // The header states the extent; VTK allocates every point array for it before reading a value,
  // so a file of a few bytes can claim petabytes. Check the claim against memory first.
  reader->UpdateInformation();
  if (reader->GetErrorCode() != 0 || !messages.Messages().empty())
  {
    Fail(path, WithVtkReason("cannot read VTK XML image data", messages));
  }
  CheckExtentFitsInMemory(path, reader);
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
