// The readers of single-array volume formats whose headers cloudvis parses itself: NRRD,
// MetaImage and raw volumes (the file states nothing, field.raw says everything).
//
// cloudvis reads the header and decodes the values itself (StoredValues.cxx), with no library in
// between. The header states the dimensions, the value type, the byte order, the encoding (raw,
// zlib or gzip, text) and where the values are (in the file, or in a separate data file, after
// skipped bytes or lines); the field's size is checked against field.max_voxels and the memory
// available before anything of that size is allocated, and the data are then counted as they are
// decoded: exactly the declared values, or the file is refused. VTK's readers were used to decode
// before; they checked none of this (a .zraw cut in half read as garbage with exit 0), misread or
// crashed on types they do not know (MetaImage's MET_LONG is 4 bytes, VTK read it as 8;
// MET_LONG_LONG corrupted the heap), printed to the terminal, and dropped the geometry
// (vtkNrrdReader keeps only the lengths of "space directions" and takes a first axis of 9 voxels or
// fewer for vector components; vtkMetaImageReader drops TransformMatrix and the sign of
// ElementSpacing). The header's own geometry (origin, spacing, direction) is set on the image.
#include "FieldFormatReaders.h"

#include "FileNames.h"
#include "InputFiles.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <sstream>

namespace cloudvis
{
namespace
{

// The most a header may hold: NRRD headers (VTK reads 4 MiB at most) and MetaImage headers are a
// few hundred bytes.
constexpr std::size_t MaximumHeaderBytes = std::size_t(4) << 20;

// What cloudvis takes from a header.
struct ImageHeader
{
  std::array<double, 3> Dimensions{ { 1.0, 1.0, 1.0 } }; // voxels along x, y, z
  double Components = 1.0;                               // values per voxel
  std::string TypeName;                                  // as the header writes it
  std::string DataFile;       // where the values are: the file itself or a separate one
  StoredValues Stored;        // how they are stored there (Offset: from the start of DataFile)
  std::uint64_t LineSkip = 0; // NRRD: lines of the data file skipped after the offset
  std::uint64_t ByteSkip = 0; // NRRD, raw encoding: bytes skipped after those lines
  std::array<double, 3> Origin{ { 0.0, 0.0, 0.0 } };
  std::array<std::array<double, 3>, 3> Axes{
    { { { 1.0, 0.0, 0.0 } }, { { 0.0, 1.0, 0.0 } }, { { 0.0, 0.0, 1.0 } } }
  };
};

std::string Trim(const std::string& text)
{
  const auto begin = text.find_first_not_of(" \t\r");
  const auto end = text.find_last_not_of(" \t\r");
  return begin == std::string::npos ? "" : text.substr(begin, end - begin + 1);
}

// Numbers separated by spaces, commas or parentheses ("(1,0,0)", "64 64 32").
std::vector<double> Numbers(const std::string& text)
{
  std::string spaced = text;
  std::replace_if(
    spaced.begin(), spaced.end(), [](char c) { return c == ',' || c == '(' || c == ')'; }, ' ');
  std::istringstream in(spaced);
  std::vector<double> values;
  for (std::string token; in >> token;)
  {
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (*end != '\0' || !std::isfinite(value))
    {
      return {}; // not a list of finite numbers: the caller says which field
    }
    values.push_back(value);
  }
  return values;
}

// The entries of NRRD's "space directions": "(x,y,z)" vectors, in which teem allows spaces after
// the commas, and "none" for an axis that is not spatial. A parenthesis left open is refused.
std::vector<std::string> DirectionVectors(const std::string& path, const std::string& text)
{
  std::vector<std::string> entries;
  std::size_t at = 0;
  while ((at = text.find_first_not_of(" \t", at)) != std::string::npos)
  {
    std::size_t end = 0; // one past the entry
    if (text[at] == '(')
    {
      end = text.find(')', at);
      if (end == std::string::npos)
      {
        Fail(path,
          "the NRRD \"space directions\" opens a vector it does not close (\"" + text + "\")");
      }
      ++end;
    }
    else
    {
      end = std::min(text.find_first_of(" \t(", at), text.size());
    }
    entries.push_back(text.substr(at, end - at));
    at = end;
  }
  return entries;
}

// A data file named by a header, relative to the header's folder unless absolute (as VTK and
// the formats' specifications resolve it).
std::string Beside(const std::string& header, const std::string& name)
{
  const std::string path = !name.empty() && name[0] == '/' ? name
    : header.find('/') == std::string::npos                ? name
                                                           : DirectoryOf(header) + "/" + name;
  return std::filesystem::path(path).lexically_normal().string(); // "dir/./data.raw": dir/data.raw
}

// The value type of a header's type name in a table of (format's name, RawTypes() name); nullptr
// for a name the table lacks.
template<std::size_t N>
const RawType* TypeNamed(const std::pair<const char*, const char*> (&types)[N],
  const std::string& name)
{
  for (const auto& known : types)
  {
    if (name == known.first)
    {
      for (const RawType& type : RawTypes())
      {
        if (std::strcmp(type.Name, known.second) == 0)
        {
          return &type;
        }
      }
    }
  }
  return nullptr;
}

// A whole number of at least `minimum` written in a header field, or a refusal naming it.
long long HeaderInteger(const std::string& path,
  const std::string& field,
  const std::string& value,
  long long minimum)
{
  char* end = nullptr;
  errno = 0;
  const long long number = std::strtoll(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || errno != 0 || number < minimum)
  {
    Fail(path,
      "the header's " + field + " is not a whole number of at least " + std::to_string(minimum) +
        " (\"" + value.substr(0, 40) + "\")");
  }
  return number;
}

// ---- NRRD ---------------------------------------------------------------------------------

const RawType* NrrdType(const std::string& type)
{
  static const std::pair<const char*, const char*> types[] = { { "signed char", "int8" },
    { "int8", "int8" },
    { "int8_t", "int8" },
    { "uchar", "uint8" },
    { "unsigned char", "uint8" },
    { "uint8", "uint8" },
    { "uint8_t", "uint8" },
    { "short", "int16" },
    { "short int", "int16" },
    { "signed short", "int16" },
    { "signed short int", "int16" },
    { "int16", "int16" },
    { "int16_t", "int16" },
    { "ushort", "uint16" },
    { "unsigned short", "uint16" },
    { "unsigned short int", "uint16" },
    { "uint16", "uint16" },
    { "uint16_t", "uint16" },
    { "int", "int32" },
    { "signed int", "int32" },
    { "int32", "int32" },
    { "int32_t", "int32" },
    { "uint", "uint32" },
    { "unsigned int", "uint32" },
    { "uint32", "uint32" },
    { "uint32_t", "uint32" },
    { "longlong", "int64" },
    { "long long", "int64" },
    { "long long int", "int64" },
    { "signed long long", "int64" },
    { "signed long long int", "int64" },
    { "int64", "int64" },
    { "int64_t", "int64" },
    { "ulonglong", "uint64" },
    { "unsigned long long", "uint64" },
    { "unsigned long long int", "uint64" },
    { "uint64", "uint64" },
    { "uint64_t", "uint64" },
    { "float", "float32" },
    { "double", "float64" } };
  return TypeNamed(types, type);
}

// Where a NRRD header's lines end: after its first empty line, or (a detached header) at the
// end of the file. Refuses text that is not a whole header.
std::size_t NrrdHeaderEnd(const std::string& path, const std::string& text)
{
  if (text.compare(0, 4, "NRRD") != 0)
  {
    Fail(path, "not a NRRD file (it does not start with \"NRRD\")");
  }
  // A NRRD header is text that ends with an empty line (or, detached, with the file): a NUL byte
  // before that line, or a last line without its line break, means the file is not a whole
  // header (a binary file, or one cut short), so it is refused rather than read up to the NUL.
  const std::string visible = text.substr(0, std::min(text.find('\0'), MaximumHeaderBytes - 1));
  if (visible.find("\n\n") == std::string::npos && visible.find("\n\r\n") == std::string::npos &&
    (visible.empty() || visible.back() != '\n'))
  {
    Fail(path,
      text.find('\0') != std::string::npos
        ? "a NUL byte in the NRRD header, before the empty line that ends it"
        : "the NRRD header's last line has no line break");
  }
  // The header ends at the first empty line (VTK's rule too); a detached header (.nhdr) may be
  // the whole file.
  std::size_t end = text.size();
  for (const char* blank : { "\n\n", "\n\r\n" })
  {
    const auto at = text.find(blank);
    if (at != std::string::npos && at + std::strlen(blank) < end)
    {
      end = at + std::strlen(blank);
    }
  }
  return end;
}

// The fields of a NRRD header that its encoding and axes are made of, as written.
struct NrrdFields
{
  int Dimension = 0;
  std::vector<double> Sizes;
  std::vector<std::string> Directions;
  std::vector<double> Spacings;
  std::string Encoding = "raw";
  std::string Endian;
  long long ByteSkip = 0;
};

// Reads the header's fields: into `header` those it takes as they are (origin, type, line skip,
// data file), into the result those the encoding and the axes are made of.
NrrdFields ReadNrrdFields(const std::string& path, std::istringstream& lines, ImageHeader& header)
{
  NrrdFields fields;
  std::string line;
  while (std::getline(lines, line) && !Trim(line).empty())
  {
    const auto colon = line.find(": ");
    if (line[0] == '#' || colon == std::string::npos)
    {
      continue; // a comment or a key:=value pair
    }
    const std::string field = line.substr(0, colon);
    const std::string value = Trim(line.substr(colon + 2));
    if (field == "dimension")
    {
      fields.Dimension = std::atoi(value.c_str());
    }
    else if (field == "sizes")
    {
      // NRRD's format requires the dimension first: the number of sizes is checked against it.
      if (fields.Dimension == 0)
      {
        Fail(path, "the NRRD header gives its sizes before its dimension");
      }
      fields.Sizes = Numbers(value);
    }
    else if (field == "spacings")
    {
      std::istringstream in(value);
      for (std::string token; in >> token;)
      {
        fields.Spacings.push_back(
          token == "nan" || token == "NaN" ? 0.0 : std::atof(token.c_str()));
      }
    }
    else if (field == "space directions")
    {
      fields.Directions = DirectionVectors(path, value);
    }
    else if (field == "space origin")
    {
      const std::vector<double> origin = Numbers(value);
      if (origin.size() != 3)
      {
        Fail(path, "the NRRD \"space origin\" is not three numbers (\"" + value + "\")");
      }
      std::copy(origin.begin(), origin.end(), header.Origin.begin());
    }
    else if (field == "type")
    {
      header.TypeName = value;
      header.Stored.Type = NrrdType(value);
      if (!header.Stored.Type)
      {
        Fail(path,
          "the NRRD type \"" + value +
            "\" is not a numeric type cloudvis reads (it reads 8, 16, 32 and 64-bit integers, "
            "signed or not, float and double)");
      }
    }
    else if (field == "encoding")
    {
      fields.Encoding = value;
      std::transform(fields.Encoding.begin(),
        fields.Encoding.end(),
        fields.Encoding.begin(),
        [](unsigned char c) { return char(std::tolower(c)); });
    }
    else if (field == "endian")
    {
      fields.Endian = value;
    }
    else if (field == "byte skip" || field == "byteskip")
    {
      fields.ByteSkip = HeaderInteger(path, "NRRD \"byte skip\"", value, -1);
    }
    else if (field == "line skip" || field == "lineskip")
    {
      header.LineSkip = std::uint64_t(HeaderInteger(path, "NRRD \"line skip\"", value, 0));
    }
    else if (field == "data file" || field == "datafile")
    {
      if (value.rfind("LIST", 0) == 0 || value.find(' ') != std::string::npos)
      {
        Fail(
          path, "NRRD data split over several files is not supported (data file: " + value + ")");
      }
      header.DataFile = Beside(path, value);
      header.Stored.Offset = 0;
    }
  }
  return fields;
}

// The header's value encoding: its type, encoding, byte order and skipped bytes.
void SetNrrdEncoding(const std::string& path, const NrrdFields& fields, ImageHeader& header)
{
  if (!header.Stored.Type)
  {
    Fail(path, "the NRRD header states no type");
  }
  if (fields.Encoding == "raw")
  {
    header.Stored.Encoding = ValueEncoding::Raw;
  }
  else if (fields.Encoding == "gzip" || fields.Encoding == "gz")
  {
    header.Stored.Encoding = ValueEncoding::Zlib;
  }
  else if (fields.Encoding == "ascii" || fields.Encoding == "text" || fields.Encoding == "txt")
  {
    header.Stored.Encoding = ValueEncoding::Text;
  }
  else
  {
    Fail(path,
      "the NRRD encoding \"" + fields.Encoding +
        "\" is not supported (cloudvis reads raw, gzip and ascii; convert with "
        "`unu save -e gzip`)");
  }
  if (header.Stored.Type->Bytes > 1 && header.Stored.Encoding != ValueEncoding::Text &&
    fields.Endian != "little" && fields.Endian != "big")
  {
    Fail(path,
      "the NRRD header's endian is \"" + fields.Endian + "\"; values of " +
        std::to_string(header.Stored.Type->Bytes) + " bytes need \"little\" or \"big\"");
  }
  header.Stored.BigEndian = fields.Endian == "big";
  // NRRD's byte skip: bytes of the file before the values (-1: the values end the file) for raw
  // data, bytes of the decompressed stream for gzip.
  if (fields.ByteSkip != 0 && header.Stored.Encoding == ValueEncoding::Text)
  {
    Fail(path, "a NRRD \"byte skip\" with ascii encoding is not supported");
  }
  if (fields.ByteSkip == -1 && header.Stored.Encoding != ValueEncoding::Raw)
  {
    Fail(path, "the NRRD \"byte skip: -1\" (the values end the file) needs raw encoding");
  }
  header.Stored.AtEnd = fields.ByteSkip == -1;
  if (fields.ByteSkip > 0)
  {
    (header.Stored.Encoding == ValueEncoding::Raw ? header.ByteSkip : header.Stored.SkipDecoded) =
      std::uint64_t(fields.ByteSkip);
  }
}

// The header's axes: the voxels along each spatial one and its vector (from the space directions
// or the spacings), and the components of a leading non-spatial axis.
void SetNrrdAxes(const std::string& path, const NrrdFields& fields, ImageHeader& header)
{
  if (fields.Dimension < 1 || fields.Dimension > 4 || int(fields.Sizes.size()) != fields.Dimension)
  {
    Fail(path,
      "the NRRD header states " + std::to_string(fields.Dimension) + " dimensions and " +
        std::to_string(fields.Sizes.size()) + " sizes; a field needs 2 or 3 spatial dimensions");
  }
  for (double size : fields.Sizes)
  {
    if (!(size >= 1.0) || size != std::floor(size))
    {
      Fail(path, "the NRRD sizes are not positive integers");
    }
  }
  // A leading non-spatial axis ("none" in space directions, or a fourth axis) holds the values
  // of one voxel.
  std::size_t first = 0;
  if (fields.Dimension == 4 || (!fields.Directions.empty() && fields.Directions[0] == "none"))
  {
    header.Components = fields.Sizes[0];
    first = 1;
  }
  if (!fields.Directions.empty() && fields.Directions.size() != fields.Sizes.size())
  {
    Fail(path,
      "the NRRD \"space directions\" gives " + std::to_string(fields.Directions.size()) +
        " vectors (or \"none\") for " + std::to_string(fields.Sizes.size()) + " axes");
  }
  const std::size_t spatial = fields.Sizes.size() - first;
  if (spatial < 2 || spatial > 3)
  {
    Fail(path,
      "the NRRD header has " + std::to_string(spatial) + " spatial axes; a field needs 2 or 3");
  }
  for (std::size_t a = 0; a < spatial; ++a)
  {
    header.Dimensions[a] = fields.Sizes[first + a];
    if (!fields.Directions.empty())
    {
      const std::vector<double> axis = Numbers(fields.Directions[first + a]);
      if (axis.size() != 3)
      {
        Fail(path,
          "the NRRD \"space directions\" of axis " + std::to_string(a) +
            " is not a vector of three numbers (\"" + fields.Directions[first + a] + "\")");
      }
      std::copy(axis.begin(), axis.end(), header.Axes[a].begin());
    }
    else if (fields.Spacings.size() == fields.Sizes.size() && fields.Spacings[first + a] != 0.0)
    {
      header.Axes[a] = { { 0.0, 0.0, 0.0 } };
      header.Axes[a][a] = fields.Spacings[first + a];
    }
  }
}

ImageHeader ParseNrrdHeader(const std::string& path, const std::string& text)
{
  ImageHeader header;
  header.DataFile = path;
  header.Stored.Offset = NrrdHeaderEnd(path, text);
  std::istringstream lines(text.substr(0, header.Stored.Offset));
  std::string magic;
  std::getline(lines, magic);
  const NrrdFields fields = ReadNrrdFields(path, lines, header);
  SetNrrdEncoding(path, fields, header);
  SetNrrdAxes(path, fields, header);
  return header;
}

// ---- MetaImage ----------------------------------------------------------------------------

// MetaIO's sizes: MET_LONG and MET_ULONG are 4 bytes (ITK writes a 64-bit long as MET_LONG_LONG).
const RawType* MetaImageType(const std::string& type)
{
  static const std::pair<const char*, const char*> types[] = { { "MET_CHAR", "int8" },
    { "MET_UCHAR", "uint8" },
    { "MET_SHORT", "int16" },
    { "MET_USHORT", "uint16" },
    { "MET_INT", "int32" },
    { "MET_UINT", "uint32" },
    { "MET_LONG", "int32" },
    { "MET_ULONG", "uint32" },
    { "MET_LONG_LONG", "int64" },
    { "MET_ULONG_LONG", "uint64" },
    { "MET_FLOAT", "float32" },
    { "MET_DOUBLE", "float64" } };
  return TypeNamed(types, type);
}

// The fields of a MetaImage header that its encoding and axes are made of, as written.
struct MetaImageFields
{
  int Dimensions = 0;
  std::vector<double> Sizes, Spacing, Matrix;
  bool DataFileSeen = false;
  long long HeaderSize = 0;
  bool Compressed = false;
  bool Binary = true;
  std::optional<std::uint64_t> CompressedBytes;
};

// Reads the header's fields up to ElementDataFile, its last: into `header` those it takes as
// they are (origin, type, byte order, components, data file), into the result the others.
MetaImageFields ReadMetaImageFields(const std::string& path,
  const std::string& text,
  ImageHeader& header)
{
  MetaImageFields fields;
  std::size_t at = 0;
  while (at < text.size() && !fields.DataFileSeen)
  {
    auto end = text.find('\n', at);
    end = end == std::string::npos ? text.size() : end;
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    const auto equals = line.find('=');
    if (equals == std::string::npos)
    {
      continue;
    }
    const std::string key = Trim(line.substr(0, equals));
    const std::string value = Trim(line.substr(equals + 1));
    if (key == "NDims")
    {
      fields.Dimensions = std::atoi(value.c_str());
    }
    else if (key == "DimSize")
    {
      fields.Sizes = Numbers(value);
    }
    else if (key == "ElementSpacing")
    {
      fields.Spacing = Numbers(value);
    }
    else if (key == "Offset" || key == "Position" || key == "Origin")
    {
      const std::vector<double> origin = Numbers(value);
      std::copy_n(origin.begin(), std::min<std::size_t>(3, origin.size()), header.Origin.begin());
    }
    else if (key == "TransformMatrix" || key == "Rotation" || key == "Orientation")
    {
      fields.Matrix = Numbers(value);
    }
    else if (key == "ElementType")
    {
      header.TypeName = value;
      header.Stored.Type = MetaImageType(value);
      if (!header.Stored.Type)
      {
        Fail(path,
          "the MetaImage ElementType " + value +
            (value.size() > 6 && value.compare(value.size() - 6, 6, "_ARRAY") == 0
                ? " holds vectors; a density field needs one value per voxel"
                : " is not a numeric type cloudvis reads (it reads MET_CHAR, MET_UCHAR, "
                  "MET_SHORT, MET_USHORT, MET_INT, MET_UINT, MET_LONG, MET_ULONG, "
                  "MET_LONG_LONG, MET_ULONG_LONG, MET_FLOAT and MET_DOUBLE)"));
      }
    }
    else if (key == "BinaryData")
    {
      fields.Binary = value == "True" || value == "true";
    }
    else if (key == "BinaryDataByteOrderMSB" || key == "ElementByteOrderMSB")
    {
      header.Stored.BigEndian = value == "True" || value == "true";
    }
    else if (key == "CompressedDataSize")
    {
      fields.CompressedBytes = std::uint64_t(HeaderInteger(path, "CompressedDataSize", value, 1));
    }
    else if (key == "ElementNumberOfChannels")
    {
      header.Components = std::atof(value.c_str());
    }
    else if (key == "CompressedData")
    {
      fields.Compressed = value == "True" || value == "true";
    }
    else if (key == "HeaderSize")
    {
      fields.HeaderSize = HeaderInteger(path, "HeaderSize", value, -1);
    }
    else if (key == "ElementDataFile")
    {
      // The last key of a header: the values follow it (LOCAL) or lie in the named file.
      fields.DataFileSeen = true;
      if (value == "LOCAL" || value == "Local" || value == "local")
      {
        header.DataFile = path;
        header.Stored.Offset = at > text.size() ? text.size() : at;
      }
      else if (value.rfind("LIST", 0) == 0 || value.find('%') != std::string::npos)
      {
        Fail(path,
          "MetaImage data split over several files is not supported (ElementDataFile = " + value +
            ")");
      }
      else
      {
        header.DataFile = Beside(path, value);
        header.Stored.Offset = fields.HeaderSize > 0 ? std::uint64_t(fields.HeaderSize) : 0;
        header.Stored.AtEnd = fields.HeaderSize == -1;
      }
    }
  }
  return fields;
}

// The header's value encoding: binary, text or compressed, and where the values end.
void SetMetaImageEncoding(const std::string& path,
  const std::string& text,
  const MetaImageFields& fields,
  ImageHeader& header)
{
  if (!fields.DataFileSeen)
  {
    Fail(path,
      "not a MetaImage file (no ElementDataFile in its first " + std::to_string(text.size()) +
        " bytes)");
  }
  if (!header.Stored.Type)
  {
    Fail(path, "the MetaImage header states no ElementType");
  }
  header.Stored.Encoding = fields.Compressed ? ValueEncoding::Zlib
    : fields.Binary                          ? ValueEncoding::Raw
                                             : ValueEncoding::Text;
  if (fields.Compressed)
  {
    if (header.Stored.AtEnd)
    {
      Fail(path, "HeaderSize = -1 (the values end the file) applies to uncompressed data only");
    }
    header.Stored.Length = fields.CompressedBytes;
  }
  else if (!fields.Binary && header.Stored.AtEnd)
  {
    Fail(path, "HeaderSize = -1 (the values end the file) applies to binary data only");
  }
}

// The header's axes: the voxels along each and its vector, from the spacing and the matrix.
void SetMetaImageAxes(const std::string& path, const MetaImageFields& fields, ImageHeader& header)
{
  if (fields.Dimensions < 2 || fields.Dimensions > 3 ||
    int(fields.Sizes.size()) != fields.Dimensions)
  {
    Fail(path,
      "the MetaImage header states NDims = " + std::to_string(fields.Dimensions) + " and " +
        std::to_string(fields.Sizes.size()) + " sizes (DimSize); a field needs 2 or 3 dimensions");
  }
  if (!fields.Spacing.empty() && int(fields.Spacing.size()) != fields.Dimensions)
  {
    Fail(path, "the MetaImage ElementSpacing does not give one number per dimension");
  }
  if (!fields.Matrix.empty() && int(fields.Matrix.size()) != fields.Dimensions * fields.Dimensions)
  {
    Fail(path, "the MetaImage TransformMatrix does not hold NDims x NDims numbers");
  }
  for (int a = 0; a < fields.Dimensions; ++a)
  {
    if (!(fields.Sizes[a] >= 1.0) || fields.Sizes[a] != std::floor(fields.Sizes[a]))
    {
      Fail(path, "the MetaImage DimSize is not a list of positive integers");
    }
    header.Dimensions[a] = fields.Sizes[a];
    // TransformMatrix lists the direction of each axis in turn (ITK writes
    // matrix[i * n + j] = direction of axis i, component j); a negative spacing points the axis
    // the other way.
    const double step = fields.Spacing.empty() ? 1.0 : fields.Spacing[a];
    header.Axes[a] = { { 0.0, 0.0, 0.0 } };
    for (int j = 0; j < fields.Dimensions; ++j)
    {
      header.Axes[a][j] = step *
        (fields.Matrix.empty() ? (a == j ? 1.0 : 0.0) : fields.Matrix[a * fields.Dimensions + j]);
    }
  }
}

ImageHeader ParseMetaImageHeader(const std::string& path, const std::string& text)
{
  ImageHeader header;
  const MetaImageFields fields = ReadMetaImageFields(path, text, header);
  SetMetaImageEncoding(path, text, fields, header);
  SetMetaImageAxes(path, fields, header);
  return header;
}

// ---- both: the header's checks, then the values ---------------------------------------------

// The offset of the line after `lines` line breaks from `offset` on (NRRD's line skip).
std::uint64_t SkipLines(const std::string& path,
  const RegularInputFile& file,
  std::uint64_t offset,
  std::uint64_t lines)
{
  constexpr std::size_t block = std::size_t(1) << 16;
  while (lines > 0)
  {
    const std::string text = file.ReadAt(offset, block);
    if (text.empty())
    {
      Fail(path, "the file ends before the lines its header's \"line skip\" skips");
    }
    for (std::size_t i = 0; i < text.size() && lines > 0; ++i)
    {
      lines -= text[i] == '\n' ? 1 : 0;
      offset += 1;
    }
  }
  return offset;
}

FieldFileContents ReadHeaderedImage(const std::string& path,
  const FieldReadOptions& options,
  const std::string& formatName,
  ImageHeader (*parse)(const std::string&, const std::string&))
{
  const RegularInputFile file(path, "field");
  ImageHeader header = parse(
    path, file.ReadAt(0, std::size_t(std::min<std::uint64_t>(file.Size(), MaximumHeaderBytes))));
  if (header.Components != 1.0)
  {
    std::ostringstream text;
    text << "the " << formatName << " image has " << header.Components
         << " values per voxel; a density field needs 1";
    Fail(path, text.str());
  }
  // Only the float array of the field is allocated.
  CheckFieldSize(path, header.Dimensions, 0.0, options.MaximumVoxels);
  const bool detached = header.DataFile != path;
  std::unique_ptr<RegularInputFile> dataFile;
  if (detached)
  {
    dataFile = std::make_unique<RegularInputFile>(header.DataFile, "field data file");
  }
  const RegularInputFile& data = detached ? *dataFile : file;
  const std::string named = detached ? path + " (data file " + header.DataFile + ")" : path;
  StoredValues stored = header.Stored;
  stored.Offset = SkipLines(named, data, stored.Offset, header.LineSkip) + header.ByteSkip;
  const std::uint64_t voxels =
    std::uint64_t(header.Dimensions[0] * header.Dimensions[1] * header.Dimensions[2]);
  auto field = vtkSmartPointer<vtkImageData>::New();
  field->SetExtent(0,
    int(header.Dimensions[0]) - 1,
    0,
    int(header.Dimensions[1]) - 1,
    0,
    int(header.Dimensions[2]) - 1);
  field->SetOrigin(header.Origin.data());
  SetAxes(path, field, header.Axes);
  field->GetPointData()->SetScalars(ReadStoredValues(named,
    data,
    stored,
    voxels,
    "an image of " + std::to_string(voxels) + " " + header.TypeName + " values"));
  FieldFileContents contents{ field, "", {} };
  contents.Report.StoredType = stored.Type->VtkType;
  contents.Report.Add("values",
    header.TypeName + (stored.Type->VtkType == VTK_FLOAT ? "" : ", converted to float") +
      (stored.Encoding == ValueEncoding::Zlib      ? " (compressed)"
          : stored.Encoding == ValueEncoding::Text ? " (text)"
                                                   : ""));
  if (detached)
  {
    contents.Report.Add("data file", header.DataFile);
  }
  return contents;
}

// ---- raw ----------------------------------------------------------------------------------

const RawType& RawTypeNamed(const std::string& path, const std::string& name)
{
  for (const RawType& type : RawTypes())
  {
    if (name == type.Name)
    {
      return type;
    }
  }
  Fail(path, "unknown raw type \"" + name + "\" (field.raw.type)");
}

} // namespace

FieldFileContents ReadNrrdFile(const std::string& path, const FieldReadOptions& options)
{
  return ReadHeaderedImage(path, options, "NRRD", ParseNrrdHeader);
}

FieldFileContents ReadMetaImageFile(const std::string& path, const FieldReadOptions& options)
{
  return ReadHeaderedImage(path, options, "MetaImage", ParseMetaImageHeader);
}

FieldFileContents ReadRawFile(const std::string& path, const FieldReadOptions& options)
{
  const RawLayout& layout = options.Raw;
  const RawType& type = RawTypeNamed(path, layout.Type);
  const RegularInputFile file(path, "field");
  const std::array<double, 3> dimensions{
    { double(layout.Dimensions[0]), double(layout.Dimensions[1]), double(layout.Dimensions[2]) }
  };
  CheckFieldSize(path, dimensions, 0.0, options.MaximumVoxels);
  const std::uint64_t voxels = std::uint64_t(layout.Dimensions[0]) *
    std::uint64_t(layout.Dimensions[1]) * std::uint64_t(layout.Dimensions[2]);
  const std::uint64_t expected = layout.HeaderBytes + voxels * std::uint64_t(type.Bytes);
  const std::string described = std::to_string(layout.Dimensions[0]) + " x " +
    std::to_string(layout.Dimensions[1]) + " x " + std::to_string(layout.Dimensions[2]) + " " +
    type.Name + (type.Bytes > 1 ? (layout.BigEndian ? " big-endian" : " little-endian") : "") +
    " values";
  // The file states nothing, so its size is the only check that the layout is the file's.
  if (file.Size() != expected)
  {
    Fail(path,
      "a raw volume of " + described +
        (layout.HeaderBytes ? " after " + std::to_string(layout.HeaderBytes) + " header bytes"
                            : "") +
        " is " + std::to_string(expected) + " bytes, but the file holds " +
        std::to_string(file.Size()) + ": check field.raw.dimensions, type and header_bytes");
  }
  StoredValues stored;
  stored.Type = &type;
  stored.BigEndian = layout.BigEndian;
  stored.Offset = layout.HeaderBytes;
  const vtkSmartPointer<vtkFloatArray> density =
    ReadStoredValues(path, file, stored, voxels, "a raw volume of " + described);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetExtent(
    0, layout.Dimensions[0] - 1, 0, layout.Dimensions[1] - 1, 0, layout.Dimensions[2] - 1);
  image->SetSpacing(layout.Spacing.data());
  image->SetOrigin(layout.Origin.data());
  image->GetPointData()->SetScalars(density);
  FieldFileContents contents{ image, "", {} };
  contents.Report.StoredType = type.VtkType;
  contents.Report.Add("layout",
    described +
      (layout.HeaderBytes ? " after " + std::to_string(layout.HeaderBytes) + " header bytes" : "") +
      " (field.raw)" + (type.VtkType == VTK_FLOAT ? "" : ", converted to float"));
  return contents;
}

} // namespace cloudvis
