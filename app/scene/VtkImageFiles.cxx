// The readers of single-array volume formats: NRRD (vtkNrrdReader), MetaImage (vtkMetaImageReader)
// and raw volumes (read here: the file states nothing, field.raw says everything).
//
// For NRRD and MetaImage cloudvis reads the text header itself before VTK does, for two reasons.
// First, protection: the header states the dimensions, the value type, the encoding and where the
// voxel bytes are (in the file, or in a separate data file), so the field's size is checked
// against field.max_voxels and the memory available, and an uncompressed file against its own
// size, before VTK allocates what the header claims; a separate data file must be a regular file
// too. VTK's parsing then runs first in the isolated child (IsolatedRead.h). Second, geometry:
// VTK 9.1's readers keep only the length of each axis (NRRD's "space directions", MetaImage's
// TransformMatrix and the sign of its ElementSpacing are dropped), and vtkNrrdReader takes a
// first axis of 9 voxels or fewer for vector components. The header's own geometry (origin,
// spacing, direction) is therefore set on the image here, and VTK is used to decode the values
// (types, byte order, gzip/zlib), whose count must match the header's.
#include "FieldFormatReaders.h"

#include "Errors.h"
#include "FileNames.h"
#include "InputFiles.h"
#include "IsolatedRead.h"
#include "VtkMessageCapture.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMetaImageReader.h>
#include <vtkNew.h>
#include <vtkNrrdReader.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>

namespace cloudvis
{
namespace
{

// The most a header may hold: VTK's NRRD reader reads 4 MiB at most, MetaImage headers are a few
// hundred bytes.
constexpr std::size_t MaximumHeaderBytes = std::size_t(4) << 20;

// What cloudvis takes from a header itself.
struct ImageHeader
{
  std::array<double, 3> Dimensions{ { 1.0, 1.0, 1.0 } }; // voxels along x, y, z
  double Components = 1.0;                               // values per voxel
  int ValueBytes = 0;                                    // 0: a type VTK will name itself
  std::string TypeName;                                  // as the header writes it
  bool Compressed = false;
  std::string DataFile;         // where the values are: the file itself or a separate one
  std::uint64_t DataOffset = 0; // where they start in it (uncompressed data)
  bool DataAtEnd = false;       // MetaImage HeaderSize = -1: the values end the data file
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

// A data file named by a header, relative to the header's folder unless absolute (as VTK and
// the formats' specifications resolve it).
std::string Beside(const std::string& header, const std::string& name)
{
  const std::string path = !name.empty() && name[0] == '/' ? name
    : header.find('/') == std::string::npos                ? name
                                                           : DirectoryOf(header) + "/" + name;
  return std::filesystem::path(path).lexically_normal().string(); // "dir/./data.raw": dir/data.raw
}

// The bytes per value of the type `name` in a table of a header format's type names; 0 for a
// name the table lacks (VTK's reader then names the problem).
template<std::size_t N>
int BytesOfType(const std::pair<const char*, int> (&types)[N], const std::string& name)
{
  for (const auto& known : types)
  {
    if (name == known.first)
    {
      return known.second;
    }
  }
  return 0;
}

// ---- NRRD ---------------------------------------------------------------------------------

int NrrdValueBytes(const std::string& type)
{
  static const std::pair<const char*, int> types[] = { { "signed char", 1 },
    { "int8", 1 },
    { "int8_t", 1 },
    { "uchar", 1 },
    { "unsigned char", 1 },
    { "uint8", 1 },
    { "uint8_t", 1 },
    { "short", 2 },
    { "short int", 2 },
    { "signed short", 2 },
    { "signed short int", 2 },
    { "int16", 2 },
    { "int16_t", 2 },
    { "ushort", 2 },
    { "unsigned short", 2 },
    { "unsigned short int", 2 },
    { "uint16", 2 },
    { "uint16_t", 2 },
    { "int", 4 },
    { "signed int", 4 },
    { "int32", 4 },
    { "int32_t", 4 },
    { "uint", 4 },
    { "unsigned int", 4 },
    { "uint32", 4 },
    { "uint32_t", 4 },
    { "float", 4 },
    { "double", 8 } };
  return BytesOfType(types, type);
}

ImageHeader ParseNrrdHeader(const std::string& path, const std::string& text)
{
  if (text.compare(0, 4, "NRRD") != 0)
  {
    Fail(path, "not a NRRD file (it does not start with \"NRRD\")");
  }
  ImageHeader header;
  header.DataFile = path;
  // VTK's reader reads the header as a C string (up to the first NUL byte) and then line by line
  // until an empty line; a last line without its line break makes it loop forever (found by the
  // fuzzer: a NUL byte in a comment). It must therefore end with a line break.
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
  header.DataOffset = end;
  std::istringstream lines(text.substr(0, end));
  std::string line;
  std::getline(lines, line); // the magic
  std::vector<double> sizes;
  std::vector<std::string> directions;
  std::vector<double> spacings;
  std::string encoding = "raw";
  int dimension = 0;
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
      dimension = std::atoi(value.c_str());
    }
    else if (field == "sizes")
    {
      // VTK's reader sizes its list by the dimension read so far (found by the fuzzer: sizes
      // before the dimension made it read a 1-voxel image and crash).
      if (dimension == 0)
      {
        Fail(path, "the NRRD header gives its sizes before its dimension");
      }
      sizes = Numbers(value);
    }
    else if (field == "spacings")
    {
      std::istringstream in(value);
      for (std::string token; in >> token;)
      {
        spacings.push_back(token == "nan" || token == "NaN" ? 0.0 : std::atof(token.c_str()));
      }
    }
    else if (field == "space directions")
    {
      std::istringstream in(value);
      for (std::string token; in >> token;)
      {
        directions.push_back(token);
      }
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
    else if (field == "space")
    {
      // VTK flips the rows of these spaces as it reads them, which the geometry set here would
      // then contradict.
      if (value == "left-anterior-superior" || value == "LAS" || value == "3D-left-handed")
      {
        Fail(
          path, "the NRRD space \"" + value + "\" is not supported (VTK's reader flips its rows)");
      }
    }
    else if (field == "type")
    {
      header.TypeName = value;
      header.ValueBytes = NrrdValueBytes(value);
    }
    else if (field == "encoding")
    {
      encoding = value;
    }
    else if (field == "data file" || field == "datafile")
    {
      if (value.rfind("LIST", 0) == 0 || value.find(' ') != std::string::npos)
      {
        Fail(
          path, "NRRD data split over several files is not supported (data file: " + value + ")");
      }
      header.DataFile = Beside(path, value);
      header.DataOffset = 0;
    }
  }
  if (dimension < 1 || dimension > 4 || int(sizes.size()) != dimension)
  {
    Fail(path,
      "the NRRD header states " + std::to_string(dimension) + " dimensions and " +
        std::to_string(sizes.size()) + " sizes; a field needs 2 or 3 spatial dimensions");
  }
  for (double size : sizes)
  {
    if (!(size >= 1.0) || size != std::floor(size))
    {
      Fail(path, "the NRRD sizes are not positive integers");
    }
  }
  // A leading non-spatial axis ("none" in space directions, or a fourth axis) holds the values
  // of one voxel.
  std::size_t first = 0;
  if (dimension == 4 || (!directions.empty() && directions[0] == "none"))
  {
    header.Components = sizes[0];
    first = 1;
  }
  const std::size_t spatial = sizes.size() - first;
  if (spatial < 2 || spatial > 3)
  {
    Fail(path,
      "the NRRD header has " + std::to_string(spatial) + " spatial axes; a field needs 2 or 3");
  }
  for (std::size_t a = 0; a < spatial; ++a)
  {
    header.Dimensions[a] = sizes[first + a];
    if (directions.size() == sizes.size())
    {
      const std::vector<double> axis = Numbers(directions[first + a]);
      if (axis.size() != 3)
      {
        Fail(path,
          "the NRRD \"space directions\" of axis " + std::to_string(a) +
            " is not a vector of three numbers (\"" + directions[first + a] + "\")");
      }
      std::copy(axis.begin(), axis.end(), header.Axes[a].begin());
    }
    else if (spacings.size() == sizes.size() && spacings[first + a] != 0.0)
    {
      header.Axes[a] = { { 0.0, 0.0, 0.0 } };
      header.Axes[a][a] = spacings[first + a];
    }
  }
  header.Compressed = encoding != "raw";
  return header;
}

// ---- MetaImage ----------------------------------------------------------------------------

int MetaValueBytes(const std::string& type)
{
  static const std::pair<const char*, int> types[] = { { "MET_CHAR", 1 },
    { "MET_UCHAR", 1 },
    { "MET_SHORT", 2 },
    { "MET_USHORT", 2 },
    { "MET_INT", 4 },
    { "MET_UINT", 4 },
    { "MET_FLOAT", 4 },
    { "MET_DOUBLE", 8 } };
  return BytesOfType(types, type);
}

ImageHeader ParseMetaImageHeader(const std::string& path, const std::string& text)
{
  ImageHeader header;
  std::vector<double> sizes, spacing, matrix;
  int dimensions = 0;
  bool dataFileSeen = false;
  long long headerSize = 0;
  std::size_t at = 0;
  while (at < text.size() && !dataFileSeen)
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
      dimensions = std::atoi(value.c_str());
    }
    else if (key == "DimSize")
    {
      sizes = Numbers(value);
    }
    else if (key == "ElementSpacing")
    {
      spacing = Numbers(value);
    }
    else if (key == "Offset" || key == "Position" || key == "Origin")
    {
      const std::vector<double> origin = Numbers(value);
      std::copy_n(origin.begin(), std::min<std::size_t>(3, origin.size()), header.Origin.begin());
    }
    else if (key == "TransformMatrix" || key == "Rotation" || key == "Orientation")
    {
      matrix = Numbers(value);
    }
    else if (key == "ElementType")
    {
      header.TypeName = value;
      header.ValueBytes = MetaValueBytes(value);
    }
    else if (key == "ElementNumberOfChannels")
    {
      header.Components = std::atof(value.c_str());
    }
    else if (key == "CompressedData")
    {
      header.Compressed = value == "True" || value == "true";
    }
    else if (key == "HeaderSize")
    {
      headerSize = std::atoll(value.c_str());
    }
    else if (key == "ElementDataFile")
    {
      // The last key of a header: the values follow it (LOCAL) or lie in the named file.
      dataFileSeen = true;
      if (value == "LOCAL" || value == "Local" || value == "local")
      {
        header.DataFile = path;
        header.DataOffset = at > text.size() ? text.size() : at;
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
        header.DataOffset = headerSize > 0 ? std::uint64_t(headerSize) : 0;
        header.DataAtEnd = headerSize == -1;
      }
    }
  }
  if (!dataFileSeen)
  {
    Fail(path,
      "not a MetaImage file (no ElementDataFile in its first " + std::to_string(text.size()) +
        " bytes)");
  }
  if (dimensions < 2 || dimensions > 3 || int(sizes.size()) != dimensions)
  {
    Fail(path,
      "the MetaImage header states NDims = " + std::to_string(dimensions) + " and " +
        std::to_string(sizes.size()) + " sizes (DimSize); a field needs 2 or 3 dimensions");
  }
  if (!spacing.empty() && int(spacing.size()) != dimensions)
  {
    Fail(path, "the MetaImage ElementSpacing does not give one number per dimension");
  }
  if (!matrix.empty() && int(matrix.size()) != dimensions * dimensions)
  {
    Fail(path, "the MetaImage TransformMatrix does not hold NDims x NDims numbers");
  }
  for (int a = 0; a < dimensions; ++a)
  {
    if (!(sizes[a] >= 1.0) || sizes[a] != std::floor(sizes[a]))
    {
      Fail(path, "the MetaImage DimSize is not a list of positive integers");
    }
    header.Dimensions[a] = sizes[a];
    // TransformMatrix lists the direction of each axis in turn (ITK writes
    // matrix[i * n + j] = direction of axis i, component j); a negative spacing points the axis
    // the other way.
    const double step = spacing.empty() ? 1.0 : spacing[a];
    header.Axes[a] = { { 0.0, 0.0, 0.0 } };
    for (int j = 0; j < dimensions; ++j)
    {
      header.Axes[a][j] =
        step * (matrix.empty() ? (a == j ? 1.0 : 0.0) : matrix[a * dimensions + j]);
    }
  }
  return header;
}

// ---- both: the checks, then VTK's reader -------------------------------------------------

template<typename Reader>
FieldFileContents ReadHeaderedImage(const std::string& path,
  const FieldReadOptions& options,
  const std::string& formatName,
  ImageHeader (*parse)(const std::string&, const std::string&))
{
  std::uint64_t fileBytes = 0;
  ImageHeader header;
  {
    const RegularInputFile file(path, "field");
    fileBytes = file.Size();
    header = parse(
      path, file.ReadAt(0, std::size_t(std::min<std::uint64_t>(fileBytes, MaximumHeaderBytes))));
  }
  const std::uint64_t dataBytes =
    header.DataFile == path ? fileBytes : CheckRegularInputFile(header.DataFile, "field data file");
  if (header.Components != 1.0)
  {
    std::ostringstream text;
    text << "the " << formatName << " image has " << header.Components
         << " values per voxel; a density field needs 1";
    Fail(path, text.str());
  }
  const double voxels = header.Dimensions[0] * header.Dimensions[1] * header.Dimensions[2];
  // VTK's array of the file's type, then the float copy made here.
  CheckFieldSize(
    path, header.Dimensions, std::max(header.ValueBytes, 1) + 4.0, options.MaximumVoxels);
  if (!header.Compressed && header.ValueBytes > 0)
  {
    const double needed = voxels * header.ValueBytes;
    const std::uint64_t offset = header.DataAtEnd
      ? (dataBytes > needed ? dataBytes - std::uint64_t(needed) : 0)
      : header.DataOffset;
    CheckFileHoldsData(
      header.DataFile == path ? path : path + " (data file " + header.DataFile + ")",
      dataBytes,
      offset,
      needed,
      "an image of " + std::to_string(std::uint64_t(voxels)) + " " + header.TypeName + " values");
  }

  const auto read = [&]()
  {
    VtkMessageCapture messages;
    vtkNew<Reader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkImageData* image = reader->GetOutput();
    vtkDataArray* values = image ? image->GetPointData()->GetScalars() : nullptr;
    if (reader->GetErrorCode() != 0 || !messages.Messages().empty() || !values)
    {
      const std::string summary = messages.Summary();
      Fail(path, "cannot read " + formatName + (summary.empty() ? "" : " (VTK: " + summary + ")"));
    }
    if (double(values->GetNumberOfValues()) != voxels)
    {
      std::ostringstream text;
      text << "VTK's reader read " << values->GetNumberOfValues() << " values, the header states "
           << voxels;
      Fail(path, text.str());
    }
    auto field = vtkSmartPointer<vtkImageData>::New();
    field->SetExtent(0,
      int(header.Dimensions[0]) - 1,
      0,
      int(header.Dimensions[1]) - 1,
      0,
      int(header.Dimensions[2]) - 1);
    field->SetOrigin(header.Origin.data());
    SetAxes(path, field, header.Axes);
    field->GetPointData()->SetScalars(ToFloat(path, values, "density"));
    FieldFileContents contents{ field, "", {} };
    contents.Report.Add("values",
      (header.TypeName.empty() ? TypeInWords(values->GetDataType()) : header.TypeName) +
        (values->GetDataType() == VTK_FLOAT ? "" : ", converted to float") +
        (header.Compressed ? " (compressed)" : ""));
    if (header.DataFile != path)
    {
      contents.Report.Add("data file", header.DataFile);
    }
    return contents;
  };
  return ReadInIsolation(path, dataBytes, "VTK's " + formatName + " reader", read);
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

// Value `i` of a block of raw bytes, as a double.
template<typename T>
double RawValue(const unsigned char* bytes, bool swap)
{
  unsigned char copy[sizeof(T)];
  for (std::size_t b = 0; b < sizeof(T); ++b)
  {
    copy[b] = bytes[swap ? sizeof(T) - 1 - b : b];
  }
  T value;
  std::memcpy(&value, copy, sizeof(T));
  return double(value);
}

double (*RawDecoder(int vtkType))(const unsigned char*, bool)
{
  switch (vtkType)
  {
    case VTK_UNSIGNED_CHAR:
      return RawValue<std::uint8_t>;
    case VTK_SIGNED_CHAR:
      return RawValue<std::int8_t>;
    case VTK_UNSIGNED_SHORT:
      return RawValue<std::uint16_t>;
    case VTK_SHORT:
      return RawValue<std::int16_t>;
    case VTK_UNSIGNED_INT:
      return RawValue<std::uint32_t>;
    case VTK_INT:
      return RawValue<std::int32_t>;
    case VTK_DOUBLE:
      return RawValue<double>;
    default:
      return RawValue<float>;
  }
}

} // namespace

FieldFileContents ReadNrrdFile(const std::string& path, const FieldReadOptions& options)
{
  return ReadHeaderedImage<vtkNrrdReader>(path, options, "NRRD", ParseNrrdHeader);
}

FieldFileContents ReadMetaImageFile(const std::string& path, const FieldReadOptions& options)
{
  return ReadHeaderedImage<vtkMetaImageReader>(path, options, "MetaImage", ParseMetaImageHeader);
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
  auto density = vtkSmartPointer<vtkFloatArray>::New();
  density->SetName("density");
  density->SetNumberOfTuples(vtkIdType(voxels));
  const bool littleEndianHost = []
  {
    const std::uint16_t one = 1;
    unsigned char first = 0;
    std::memcpy(&first, &one, 1);
    return first == 1;
  }();
  const bool reverse = type.Bytes > 1 && layout.BigEndian == littleEndianHost;
  const auto decode = RawDecoder(type.VtkType);
  // In blocks, so the bytes are never held whole next to the floats.
  constexpr std::uint64_t blockValues = std::uint64_t(1) << 22;
  float* out = density->GetPointer(0);
  std::uint64_t beyond = 0;
  constexpr double largest = std::numeric_limits<float>::max();
  for (std::uint64_t first = 0; first < voxels; first += blockValues)
  {
    const std::uint64_t count = std::min(blockValues, voxels - first);
    const std::string bytes =
      file.ReadAt(layout.HeaderBytes + first * type.Bytes, std::size_t(count * type.Bytes));
    if (bytes.size() != count * type.Bytes)
    {
      Fail(path, "the file became shorter while it was read");
    }
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    for (std::uint64_t i = 0; i < count; ++i)
    {
      const double value = decode(data + i * type.Bytes, reverse);
      beyond += std::isfinite(value) && std::fabs(value) > largest ? 1 : 0;
      out[first + i] = float(value);
    }
  }
  if (beyond > 0)
  {
    Fail(path,
      "the raw volume holds " + std::to_string(beyond) +
        " values beyond the range of float (about 3.4e38)");
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetExtent(
    0, layout.Dimensions[0] - 1, 0, layout.Dimensions[1] - 1, 0, layout.Dimensions[2] - 1);
  image->SetSpacing(layout.Spacing.data());
  image->SetOrigin(layout.Origin.data());
  image->GetPointData()->SetScalars(density);
  FieldFileContents contents{ image, "", {} };
  contents.Report.Add("layout",
    described +
      (layout.HeaderBytes ? " after " + std::to_string(layout.HeaderBytes) + " header bytes" : "") +
      " (field.raw)" + (type.VtkType == VTK_FLOAT ? "" : ", converted to float"));
  return contents;
}

} // namespace cloudvis
