// The readers of the field formats VTK's XML image readers handle: .vti (vtkXMLImageDataReader)
// and .pvti (vtkXMLPImageDataReader: a small XML file listing pieces, each a .vti, assembled into
// one image). VTK's XML readers trust the file: crafted headers make them crash, loop or allocate
// gigabytes (docs/reliability.md lists what the fuzzer found). Three layers stand between a file
// and the cloudvis process:
//   1. text checks of the markup and of the binary headers of raw appended data (CheckVtiText),
//      closing the classes the fuzzer found one by one, with messages that say what is wrong;
//   2. the read itself in a forked child under an address-space and a time limit
//      (ReadInIsolation, IsolatedRead.h), which sends the image back: a crash, a hang or a
//      runaway allocation in VTK ends the child, not cloudvis;
//   3. in that read, the header's extent checked against the memory available and
//      field.max_voxels before VTK allocates the arrays it claims, and the image's Origin,
//      Spacing and Direction attributes checked (VTK silently replaces one it cannot parse by
//      its default); the Direction is set on the image where VTK 9.1 drops it (.pvti).
// A .pvti names its pieces; each piece goes through layer 1 as a .vti would, the child reads the
// whole assembly, and the memory check counts a piece's arrays on top of the output's. (Pieces
// that leave part of the whole extent uncovered are refused by VTK itself: "No available piece
// provides data for the following extents".) Pieces that overlap must agree where they do
// (CheckOverlapsAgree). Messages number pieces from 0, as their file names <stem>_<p>.vti do.
#include "FieldFormatReaders.h"

#include "Errors.h"
#include "FieldPieces.h" // PieceRunAttribute
#include "FieldUnits.h"
#include "FileNames.h"
#include "InputFiles.h"
#include "IsolatedRead.h"
#include "VtkMessageCapture.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPImageDataReader.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

namespace cloudvis
{
namespace
{

using Extent = std::array<int, 6>;

std::string Shorten(const std::string& text, std::size_t length)
{
  return text.size() > length ? text.substr(0, length - 3) + "..." : text;
}

// The value of attribute `name` in a start tag ("<Piece Extent="0 3 0 7 0 5" ...>"), with the
// XML entities VTK's writers produce decoded; nothing when the tag has no such attribute.
std::optional<std::string> Attribute(const std::string& tag, const std::string& name)
{
  const std::string pattern = name + "=\"";
  for (auto at = tag.find(pattern); at != std::string::npos; at = tag.find(pattern, at + 1))
  {
    if (at == 0 || !std::isspace(static_cast<unsigned char>(tag[at - 1])))
    {
      continue; // the end of a longer name: WholeExtent when looking for Extent
    }
    const auto begin = at + pattern.size();
    const auto end = tag.find('"', begin);
    if (end == std::string::npos)
    {
      return std::nullopt;
    }
    std::string value = tag.substr(begin, end - begin);
    static const std::pair<const char*, char> entities[] = {
      { "&quot;", '"' }, { "&apos;", '\'' }, { "&lt;", '<' }, { "&gt;", '>' }, { "&amp;", '&' }
    };
    for (const auto& entity : entities)
    {
      for (auto e = value.find(entity.first); e != std::string::npos;
           e = value.find(entity.first, e + 1))
      {
        value.replace(e, std::strlen(entity.first), 1, entity.second);
      }
    }
    return value;
  }
  return std::nullopt;
}

// Six integers (an Extent or WholeExtent attribute), or nothing when the text is not that.
std::optional<Extent> ParseExtent(const std::string& text)
{
  Extent extent{};
  const char* at = text.c_str();
  for (int& value : extent)
  {
    char* end = nullptr;
    errno = 0;
    const long parsed = std::strtol(at, &end, 10);
    if (end == at || errno != 0 || parsed < std::numeric_limits<int>::min() ||
      parsed > std::numeric_limits<int>::max())
    {
      return std::nullopt;
    }
    value = int(parsed);
    at = end;
  }
  return extent;
}

// The start tag beginning at `at` ("<Piece ...>"), without the brackets' contents past it.
std::string StartTag(const std::string& xml, std::size_t at)
{
  const auto end = xml.find('>', at);
  return xml.substr(at, end == std::string::npos ? std::string::npos : end - at);
}

// VTK loops for minutes over a NumberOfComponents it misreads (found by the fuzzer:
// "1888888888888cii"). An array's component count must be a plain integer from 1 to 1024.
void CheckComponentCount(const std::string& path, const std::string& tag)
{
  const std::optional<std::string> value = Attribute(tag, "NumberOfComponents");
  if (!value)
  {
    return; // VTK's default: 1
  }
  const bool digits = !value->empty() && value->size() <= 4 &&
    value->find_first_not_of("0123456789") == std::string::npos;
  if (!digits || std::stoi(*value) < 1 || std::stoi(*value) > 1024)
  {
    Fail(path,
      "an array's NumberOfComponents is not an integer from 1 to 1024 (\"" + Shorten(*value, 20) +
        "\")");
  }
}

// VTK 9.1 dereferences a null array when an element of FieldData, PointData or CellData is not an
// array of a type it knows (found by the fuzzer: a FieldData array without type=, and an element
// of another name, crash vtkXMLReader::ReadXMLInformation). So every start tag in those sections,
// other than the InformationKey/Value entries VTK nests in arrays, must be a DataArray (or Array,
// for non-numeric arrays) of a known type: VTK reads any element there as an array, and another
// name with a known type (a PointData nested in PointData, found by the fuzzer) made it allocate
// 17 GB.
void CheckArrayElements(const std::string& path, const std::string& xml, std::size_t markupEnd)
{
  static const char* const types[] = { "Int8",
    "UInt8",
    "Int16",
    "UInt16",
    "Int32",
    "UInt32",
    "Int64",
    "UInt64",
    "Float32",
    "Float64",
    "String",
    "Bit",
    "IdType",
    "Char" };
  const auto hasKnownType = [](const std::string& tag)
  {
    const std::optional<std::string> type = Attribute(tag, "type");
    return type &&
      std::any_of(
        std::begin(types), std::end(types), [&type](const char* known) { return *type == known; });
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
        if (xml.find('>', at) == std::string::npos)
        {
          break; // VTK's parser reports an unterminated tag itself
        }
        const std::string tag = StartTag(xml, at);
        if (tag[1] == '/' || tag[1] == '!' || tag[1] == '?' ||
          tag.rfind("<InformationKey", 0) == 0 || tag.rfind("<Value", 0) == 0)
        {
          continue;
        }
        const auto named = [&tag](const char* name)
        {
          const std::string prefix = std::string("<") + name;
          return tag.rfind(prefix, 0) == 0 && tag.size() > prefix.size() &&
            std::isspace(static_cast<unsigned char>(tag[prefix.size()]));
        };
        if ((named("DataArray") || named("Array")) && hasKnownType(tag))
        {
          CheckComponentCount(path, tag);
          continue;
        }
        Fail(path,
          std::string("an element of ") + section + " is not a DataArray of a known type (" +
            Shorten(tag, 60) + ">)");
      }
    }
  }
}

// VTK's reader sizes buffers from the binary headers of raw appended arrays (a byte count, or a
// block count followed by that many block sizes) before it reads them, so a corrupt count makes
// it allocate gigabytes while reading the header (found by the fuzzer). Each header must at least
// fit in the file. The header words are in the file's byte order (byte_order="BigEndian" from a
// big-endian machine or a writer asked for it: both ParaView and VTK read those).
void CheckAppendedHeaders(const std::string& path,
  const RegularInputFile& file,
  const std::string& xml,
  std::size_t header,
  std::size_t appended)
{
  const auto appendedEnd = appended == std::string::npos ? appended : xml.find('>', appended);
  if (header == std::string::npos || appendedEnd == std::string::npos ||
    Attribute(StartTag(xml, appended), "encoding").value_or("") != "raw")
  {
    return; // base64 and inline data are left to VTK (and the isolated read)
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
  const std::string fileTag = StartTag(xml, header);
  const std::uint64_t word = Attribute(fileTag, "header_type").value_or("") == "UInt64" ? 8 : 4;
  const bool bigEndian = Attribute(fileTag, "byte_order").value_or("") == "BigEndian";
  const bool compressed = Attribute(fileTag, "compressor").has_value();
  const std::uint64_t start = underscore + 1;
  const std::uint64_t available = file.Size() > start ? file.Size() - start : 0;
  // Every offset="N" before the appended data is the position of an array's header.
  for (auto at = xml.find("offset=\"", header); at != std::string::npos && at < appended;
       at = xml.find("offset=\"", at + 1))
  {
    const std::uint64_t offset = std::strtoull(xml.c_str() + at + 8, nullptr, 10);
    const std::uint64_t words = compressed ? 3 : 1;
    if (offset > available || (available - offset) / word < words)
    {
      Fail(path,
        "the appended data ends before the header of the array at offset " +
          std::to_string(offset));
    }
    if (compressed)
    {
      const std::string bytes = file.ReadAt(start + offset, std::size_t(word));
      std::uint64_t blocks = 0;
      for (std::size_t i = 0; i < bytes.size(); ++i)
      {
        const std::uint64_t byte = static_cast<unsigned char>(bytes[i]);
        blocks |= byte << (8 * (bigEndian ? bytes.size() - 1 - i : i));
      }
      if (bytes.size() != word || blocks > (available - offset) / word - 3)
      {
        Fail(path,
          "the header of the array at offset " + std::to_string(offset) + " claims " +
            std::to_string(blocks) + " compressed blocks, more than the file holds");
      }
    }
  }
}

// Layer 1 for one .vti file (a field, or a piece of a .pvti). Returns the markup read.
std::string CheckVtiText(const std::string& path, const RegularInputFile& file)
{
  // The XML part: up to the '_' that starts the raw appended bytes (1 MiB is far more than the
  // markup of any image file needs).
  const std::string xml =
    file.ReadAt(0, std::size_t(std::min<std::uint64_t>(file.Size(), 1 << 20)));
  const auto header = xml.find("<VTKFile");
  const auto appended = xml.find("<AppendedData");
  CheckArrayElements(path, xml, appended == std::string::npos ? xml.size() : appended);
  CheckAppendedHeaders(path, file, xml, header, appended);
  return xml;
}

double VoxelCount(const Extent& e)
{
  double voxels = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    voxels *= std::max(0.0, double(e[2 * a + 1]) - double(e[2 * a]) + 1.0);
  }
  return voxels;
}

// Layer 3: refuses a header whose whole extent is empty, larger than `maximumVoxels`, or whose
// point arrays (counted as 4 bytes per voxel each, plus the float copy ReadField makes, plus the
// reader's own `extraBytes`) would not fit in the memory available.
void CheckExtentFitsInMemory(const std::string& path,
  vtkXMLReader* reader,
  std::uint64_t maximumVoxels,
  double extraBytes)
{
  vtkInformation* information = reader->GetOutputInformation(0);
  if (!information || !information->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    Fail(path, "the image data header states no extent");
  }
  Extent extent{};
  information->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent.data());
  std::array<double, 3> dimensions{};
  for (int a = 0; a < 3; ++a)
  {
    // In double: a corrupt extent such as "-2147483648 2147483647" overflows int.
    dimensions[a] = double(extent[2 * a + 1]) - double(extent[2 * a]) + 1.0;
    if (dimensions[a] < 1.0)
    {
      Fail(path,
        "the image has no voxels (whole extent " + std::to_string(extent[2 * a]) + " to " +
          std::to_string(extent[2 * a + 1]) + " along axis " + std::to_string(a) + ")");
    }
  }
  const int arrays = std::max(1, reader->GetNumberOfPointArrays());
  CheckFieldSize(path, dimensions, 4.0 * arrays, maximumVoxels, extraBytes);
}

// VTK's readers turn an Origin, Spacing or Direction attribute they cannot parse ("nan", "inf",
// too few numbers) into its default (origin 0, spacing 1, identity) without a word: the text of
// the image element (ImageData for a .vti or a piece, PImageData for a .pvti) is checked here, as
// VTK's own XML parser read it. Returns the Direction attribute's nine numbers (row by row, as VTK
// writes them) when there is one, for ReadChecked to set where VTK drops it.
std::optional<std::array<double, 9>> CheckGeometryAttributes(const std::string& path,
  vtkXMLReader* reader)
{
  vtkXMLDataParser* parser = reader->GetXMLParser();
  vtkXMLDataElement* root = parser ? parser->GetRootElement() : nullptr;
  vtkXMLDataElement* image = nullptr;
  for (const char* element : { "ImageData", "PImageData" })
  {
    image = image ? image : (root ? root->FindNestedElementWithName(element) : nullptr);
  }
  std::optional<std::array<double, 9>> direction;
  if (!image)
  {
    return direction;
  }
  for (const auto& [name, count] :
    { std::pair<const char*, std::size_t>{ "Origin", 3 }, { "Spacing", 3 }, { "Direction", 9 } })
  {
    const char* text = image->GetAttribute(name);
    if (!text)
    {
      continue;
    }
    const std::string attribute =
      std::string("the image's ") + name + " attribute \"" + Shorten(text, 80) + "\"";
    std::istringstream in{ std::string(text) };
    std::vector<double> values;
    std::string token;
    while (in >> token)
    {
      char* end = nullptr;
      values.push_back(std::strtod(token.c_str(), &end));
      if (*end != '\0' || !std::isfinite(values.back()))
      {
        Fail(path, attribute + " holds \"" + Shorten(token, 40) + "\", not a finite number");
      }
    }
    if (values.size() != count)
    {
      Fail(path,
        attribute + " holds " + std::to_string(values.size()) + " numbers, not " +
          std::to_string(count));
    }
    if (count == 9)
    {
      direction.emplace();
      std::copy(values.begin(), values.end(), direction->begin());
    }
  }
  return direction;
}

// The Direction of a .pvti: vtkXMLPImageDataReader (VTK 9.1) reads the PImageData's Origin and
// Spacing but drops its Direction, and VTK 9.1's parallel writer leaves the Direction out of the
// .pvti altogether, writing it only in each piece. So the direction is the .pvti's when it states
// one (cloudvis and newer VTK write it there), else its first piece's (checked the same way).
std::optional<std::array<double, 9>> ParallelImageDirection(vtkXMLReader* reader,
  const std::string& path,
  const std::string& firstPiece)
{
  if (std::optional<std::array<double, 9>> direction = CheckGeometryAttributes(path, reader))
  {
    return direction;
  }
  vtkNew<vtkXMLImageDataReader> piece;
  piece->SetFileName(firstPiece.c_str());
  piece->UpdateInformation();
  return CheckGeometryAttributes(firstPiece, piece);
}

// The read in the isolated child, after layer 1: the header, the memory check, the geometry
// attributes, then the data, with the Direction set on the image (`firstPiece`: a .pvti's, see
// ParallelImageDirection).
template<typename Reader>
vtkSmartPointer<vtkImageData> ReadChecked(const std::string& path,
  const std::string& formatName,
  std::uint64_t maximumVoxels,
  double extraBytes = 0.0,
  const std::string& firstPiece = "")
{
  VtkMessageCapture messages;
  vtkNew<Reader> reader;
  // CanReadFile checks the XML header names VTKFile of the reader's type, before any parsing
  // that would otherwise fill the output window with errors.
  if (!reader->CanReadFile(path.c_str()))
  {
    Fail(path, messages.WithVtkReason("not a " + formatName + " file"));
  }
  reader->SetFileName(path.c_str());
  // The header states the extent; VTK allocates every point array for it before reading a value,
  // so a file of a few bytes can claim petabytes. Check the claim against memory first.
  reader->UpdateInformation();
  if (reader->GetErrorCode() != 0 || !messages.Messages().empty())
  {
    Fail(path, messages.WithVtkReason("cannot read " + formatName));
  }
  CheckExtentFitsInMemory(path, reader, maximumVoxels, extraBytes);
  const std::optional<std::array<double, 9>> direction = firstPiece.empty()
    ? CheckGeometryAttributes(path, reader)
    : ParallelImageDirection(reader, path, firstPiece);
  reader->Update();
  vtkSmartPointer<vtkImageData> image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  if (reader->GetErrorCode() != 0 || !messages.Messages().empty() || !image)
  {
    Fail(path, messages.WithVtkReason("cannot read " + formatName));
  }
  if (direction)
  {
    image->SetDirectionMatrix(direction->data());
  }
  return image;
}

// ---- .pvti --------------------------------------------------------------------------------

struct Piece
{
  std::string Source; // as the .pvti writes it
  std::string Path;   // resolved as VTK resolves it
  Extent Region{};    // the piece's extent, as the .pvti states it
};

// "piece 2 (f_2.vti)": a piece in messages, numbered from 0 as listed, with the Source the .pvti
// gives it.
std::string PieceLabel(std::size_t number, const std::string& source)
{
  return "piece " + std::to_string(number) + " (" + source + ")";
}

// The markup of a .pvti, read whole (it lists pieces; it holds no data).
constexpr std::uint64_t MaximumParallelFileBytes = std::uint64_t(16) << 20;

// The <Piece> elements of a .pvti's <PImageData>, with the paths VTK will open: relative to the
// .pvti's directory unless absolute (vtkXMLPDataObjectReader::CreatePieceFileName).
std::vector<Piece> ListPieces(const std::string& path, const std::string& xml)
{
  std::vector<Piece> pieces;
  const auto image = xml.find("<PImageData");
  if (image == std::string::npos)
  {
    return pieces; // not a .pvti: CanReadFile says so in VTK's words
  }
  const std::string directory = path.find('/') == std::string::npos ? "" : DirectoryOf(path) + "/";
  for (auto at = xml.find("<Piece", image); at != std::string::npos;
       at = xml.find("<Piece", at + 1))
  {
    const std::string tag = StartTag(xml, at);
    if (tag.size() <= 6 || !std::isspace(static_cast<unsigned char>(tag[6])))
    {
      continue; // another element whose name starts with Piece
    }
    const std::string number = "piece " + std::to_string(pieces.size());
    const std::optional<std::string> source = Attribute(tag, "Source");
    if (!source || source->empty())
    {
      Fail(path, number + " names no file (no Source attribute)");
    }
    const std::optional<std::string> region = Attribute(tag, "Extent");
    const std::optional<Extent> extent = region ? ParseExtent(*region) : std::nullopt;
    if (!extent)
    {
      Fail(path, PieceLabel(pieces.size(), *source) + " states no extent of six integers");
    }
    pieces.push_back({ *source, (*source)[0] == '/' ? *source : directory + *source, *extent });
  }
  if (pieces.empty())
  {
    Fail(path, "the parallel image data lists no pieces");
  }
  return pieces;
}

// The points of `region` (inside the piece's extent) as the piece's file holds them, in an image
// that may cover more.
vtkSmartPointer<vtkImageData> ReadPieceRegion(const std::string& path,
  const std::string& number,
  const Piece& piece,
  const Extent& region)
{
  VtkMessageCapture messages;
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(piece.Path.c_str());
  reader->UpdateInformation();
  // Whole rows of the piece: a part of a row (a plane x = const, as pieces split along x share)
  // makes VTK decompress a block for every row, 20 times slower at 320^3 in 8 pieces.
  Extent rows = region;
  rows[0] = piece.Region[0];
  rows[1] = piece.Region[1];
  static_cast<vtkAlgorithm*>(reader)->UpdateExtent(rows.data());
  vtkImageData* image = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || !messages.Messages().empty() || !image)
  {
    Fail(
      path, messages.WithVtkReason(number + ": cannot read the part it shares with another piece"));
  }
  return image;
}

// Pieces may share points (VTK's writer and cloudvis's give neighbours a common boundary plane),
// but only with equal values there: VTK's reader takes each point from one of the pieces that
// hold it and never reads the others, so a conflict would be resolved silently by the order of
// the pieces. Each overlap is read from both pieces and compared, array by array (those both
// hold), refused at the first point (x fastest) where they differ.
void CheckOverlapsAgree(const std::string& path, const std::vector<Piece>& pieces)
{
  const auto number = [&pieces](std::size_t p) { return PieceLabel(p, pieces[p].Source); };
  for (std::size_t p = 0; p < pieces.size(); ++p)
  {
    for (std::size_t q = p + 1; q < pieces.size(); ++q)
    {
      Extent overlap{};
      bool empty = false;
      for (int a = 0; a < 3; ++a)
      {
        overlap[2 * a] = std::max(pieces[p].Region[2 * a], pieces[q].Region[2 * a]);
        overlap[2 * a + 1] = std::min(pieces[p].Region[2 * a + 1], pieces[q].Region[2 * a + 1]);
        empty = empty || overlap[2 * a] > overlap[2 * a + 1];
      }
      if (empty)
      {
        continue;
      }
      const auto first = ReadPieceRegion(path, number(p), pieces[p], overlap);
      const auto second = ReadPieceRegion(path, number(q), pieces[q], overlap);
      for (int n = 0; n < first->GetPointData()->GetNumberOfArrays(); ++n)
      {
        vtkDataArray* a = first->GetPointData()->GetArray(n);
        vtkDataArray* b =
          a && a->GetName() ? second->GetPointData()->GetArray(a->GetName()) : nullptr;
        if (!b || a->GetNumberOfComponents() != b->GetNumberOfComponents())
        {
          continue;
        }
        for (int k = overlap[4]; k <= overlap[5]; ++k)
          for (int j = overlap[2]; j <= overlap[3]; ++j)
            for (int i = overlap[0]; i <= overlap[1]; ++i)
            {
              int ijk[3] = { i, j, k };
              const vtkIdType at = first->ComputePointId(ijk), bt = second->ComputePointId(ijk);
              for (int c = 0; c < a->GetNumberOfComponents(); ++c)
              {
                const double x = a->GetComponent(at, c), y = b->GetComponent(bt, c);
                if (x != y && !(std::isnan(x) && std::isnan(y)))
                {
                  std::ostringstream text;
                  text.precision(9);
                  text << number(p) << " and " << number(q) << " overlap and disagree: at point ("
                       << i << ", " << j << ", " << k << ") \"" << a->GetName() << "\" is " << x
                       << " in piece " << p << " and " << y << " in piece " << q
                       << "; pieces may share points only with equal values";
                  Fail(path, text.str());
                }
              }
            }
      }
    }
  }
}

// The generation run that the start tag of `element` records (PieceRunAttribute, FieldPieces.h:
// cloudvis writes it in a .pvti's PImageData and each piece's ImageData), nothing when none.
std::optional<std::string> RecordedRun(const std::string& xml, const std::string& element)
{
  const auto at = xml.find("<" + element);
  return at == std::string::npos ? std::nullopt : Attribute(StartTag(xml, at), PieceRunAttribute);
}

// A .pvti names its pieces by file name alone, so the pieces of two generate runs (one
// interrupted by SIGKILL between its renames, or two running at once) could be read as one
// field. Every piece must record the run the .pvti records; where the .pvti records none
// (VTK's writer, cloudvis before runs were recorded), the pieces that record one must agree.
void CheckPiecesOfOneRun(const std::string& path,
  const std::optional<std::string>& run,
  const std::vector<Piece>& listed,
  const std::vector<std::optional<std::string>>& runs)
{
  const auto piece = [&listed](std::size_t index)
  { return PieceLabel(index, listed[index].Source); };
  const std::string advice = ": the pieces of two generate runs are mixed (a run killed while "
                             "renaming its pieces, or two runs writing the same .pvti at once); "
                             "generate the field again";
  std::optional<std::size_t> reference; // the first piece recording a run, without one here
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    if (run && runs[i] != run)
    {
      Fail(path,
        piece(i) + (runs[i] ? " was written by run " + Shorten(*runs[i], 40) : " records no run") +
          ", the .pvti by run " + Shorten(*run, 40) + advice);
    }
    if (!run && runs[i])
    {
      if (reference && runs[*reference] != runs[i])
      {
        Fail(path,
          piece(i) + " was written by run " + Shorten(*runs[i], 40) + ", " + piece(*reference) +
            " by run " + Shorten(*runs[*reference], 40) + advice);
      }
      reference = reference ? reference : i;
    }
  }
}

// The units the image's field data declares (docs/data.md, "Physical units"): the names
// DeclareNamedUnits reads, as ParaView's cloudvis reader and cloudvis.field_from_xarray write
// them (a string array of one value, or a numeric array of one value), and "units", the values'
// units as a file states them ("g m-3", "kg/kg"), where "quantity" is not given: a mixing ratio
// becomes a liquid water content with the number "air_density" (kg/m^3). A "droplet_number" of
// 0 declares none, as the ParaView reader's output says so, and a saved copy of it reads back.
void DeclareFieldDataUnits(const std::string& path, vtkImageData* image, FieldReport& report)
{
  vtkFieldData* data = image->GetFieldData();
  const auto lookup = [data](const std::string& name) -> std::optional<MetadataEntry>
  {
    vtkAbstractArray* array = data ? data->GetAbstractArray(name.c_str()) : nullptr;
    if (!array)
    {
      return std::nullopt;
    }
    MetadataEntry entry;
    const vtkIdType values = array->GetNumberOfValues();
    entry.TypeName = std::string(array->GetDataTypeAsString()) + " array of " +
      std::to_string(values) + (values == 1 ? " value" : " values");
    if (values == 1 && vtkStringArray::SafeDownCast(array))
    {
      entry.Text = vtkStringArray::SafeDownCast(array)->GetValue(0);
    }
    else if (values == 1 && vtkDataArray::SafeDownCast(array))
    {
      entry.Number = vtkDataArray::SafeDownCast(array)->GetTuple1(0);
      if (name == "droplet_number" && *entry.Number == 0.0)
      {
        return std::nullopt; // what ParaView's cloudvis reader writes when none is declared
      }
    }
    return entry;
  };
  DeclareNamedUnits(path, "field data", "field data", lookup, report);
  const std::optional<MetadataEntry> units = lookup("units");
  if (units && units->Text && !report.Units.Quantity)
  {
    report.Add("units", *units->Text + " (field data)");
    DeclareQuantityOfUnits(*units->Text, "the field data's", report);
    const std::optional<double> ratio = MixingRatioGramsPerKilogram(*units->Text, "");
    const std::optional<MetadataEntry> air = lookup("air_density");
    if (!report.Units.Quantity && ratio && !air)
    {
      report.Add("quantity",
        "density: a mixing ratio becomes a liquid water content with the air's density (the "
        "field data's \"air_density\", kg/m^3); without it, read as stored");
    }
    else if (!report.Units.Quantity && ratio)
    {
      const double density = air->Number.value_or(std::nan(""));
      if (!(density >= AirDensityMin && density <= AirDensityMax))
      {
        Fail(path,
          "field data \"air_density\" must be a number of kg/m^3 in [" + Number(AirDensityMin) +
            ", " + Number(AirDensityMax) + "], got " +
            (air->Number ? Number(density) : WithArticle(air->TypeName)));
      }
      report.Units.Quantity = FieldQuantity::Lwc;
      report.LwcScale = *ratio * density;
      report.LwcScaleFrom =
        *units->Text + " times the air's density " + Number(density) + " kg/m^3";
      report.Add("quantity",
        "lwc (liquid water content: the mixing ratio times the field data's air_density)");
    }
  }
}

// What both readers return: the image, the array field.array names (if any) and the report.
FieldFileContents Contents(const std::string& path,
  const vtkSmartPointer<vtkImageData>& image,
  const FieldReadOptions& options)
{
  FieldFileContents contents{ image, options.Array, {} };
  ReportPointArrays(contents.Report, image, options.Array);
  DeclareFieldDataUnits(path, image, contents.Report);
  return contents;
}

} // namespace

FieldFileContents ReadVtkXmlImageFile(const std::string& path, const FieldReadOptions& options)
{
  std::uint64_t bytes = 0;
  {
    const RegularInputFile file(path, "field");
    bytes = file.Size();
    CheckVtiText(path, file);
  }
  const auto read = [&path, &options]()
  { return ReadChecked<vtkXMLImageDataReader>(path, "VTK XML image data", options.MaximumVoxels); };
  return ReadInIsolation(
    path, bytes, "VTK's reader", [&] { return Contents(path, read(), options); });
}

FieldFileContents ReadVtkXmlParallelImageFile(const std::string& path,
  const FieldReadOptions& options)
{
  std::vector<Piece> listed;
  std::optional<std::string> run;
  {
    const RegularInputFile file(path, "field");
    const std::string xml = file.ReadAll(MaximumParallelFileBytes);
    listed = ListPieces(path, xml);
    run = RecordedRun(xml, "PImageData");
  }
  // Every piece as a .vti: a regular file that passes the text checks. Errors name the .pvti,
  // the piece and what is wrong with it.
  std::uint64_t totalBytes = 0;
  double largestPiece = 0.0;
  std::vector<std::optional<std::string>> runs;
  for (std::size_t number = 0; number < listed.size(); ++number)
  {
    const Piece& piece = listed[number];
    try
    {
      const RegularInputFile file(piece.Path, "field piece");
      totalBytes += file.Size();
      runs.push_back(RecordedRun(CheckVtiText(piece.Path, file), "ImageData"));
      largestPiece = std::max(largestPiece, VoxelCount(piece.Region));
    }
    catch (const InputError& e)
    {
      // The piece's own message begins with its path; the .pvti and the Source name it here.
      std::string problem = e.what();
      if (problem.rfind(piece.Path + ": ", 0) == 0)
      {
        problem.erase(0, piece.Path.size() + 2);
      }
      Fail(path, PieceLabel(number, piece.Source) + ": " + problem);
    }
  }
  CheckPiecesOfOneRun(path, run, listed, runs);
  // Beyond the output: a piece's arrays while it is copied in (one piece at a time; counted as
  // two arrays of 4 bytes per voxel).
  const auto read = [&path, &options, &listed, largestPiece]()
  {
    vtkSmartPointer<vtkImageData> image = ReadChecked<vtkXMLPImageDataReader>(path,
      "VTK XML parallel image data",
      options.MaximumVoxels,
      largestPiece * 8.0,
      listed.front().Path);
    CheckOverlapsAgree(path, listed);
    return image;
  };
  FieldFileContents contents = ReadInIsolation(
    path, totalBytes, "VTK's reader", [&] { return Contents(path, read(), options); });
  contents.Report.Add("pieces", std::to_string(listed.size()));
  return contents;
}

} // namespace cloudvis
