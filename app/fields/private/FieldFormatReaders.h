// The readers of the table in FieldIO.cxx, one per format, each in the file of its format, and
// what they share (FieldFormatReaders.cxx): the size check every reader makes before it allocates,
// the scalar types of raw files, the refusal of values beyond float's range and the lines of
// the report that every format fills the same way.
#ifndef cloudvis_FieldFormatReaders_h
#define cloudvis_FieldFormatReaders_h

#include "FieldIO.h"

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

class vtkFloatArray;
class vtkImageData;
class vtkMatrix3x3;

namespace cloudvis
{
class RegularInputFile;

// VtkXmlImageFiles.cxx
FieldFileContents ReadVtkXmlImageFile(const std::string& path, const FieldReadOptions& options);
FieldFileContents ReadVtkXmlParallelImageFile(const std::string& path,
  const FieldReadOptions& options);
// NrrdMetaImageRawFiles.cxx
FieldFileContents ReadNrrdFile(const std::string& path, const FieldReadOptions& options);
FieldFileContents ReadMetaImageFile(const std::string& path, const FieldReadOptions& options);
FieldFileContents ReadRawFile(const std::string& path, const FieldReadOptions& options);
// NetCdfFiles.cxx
FieldFileContents ReadNetCdfFile(const std::string& path, const FieldReadOptions& options);
// OpenVdbFiles.cxx (the one translation unit that includes OpenVDB's headers)
FieldFileContents ReadOpenVdbFile(const std::string& path, const FieldReadOptions& options);
void WriteOpenVdbFile(vtkImageData* field, const std::string& path, const FieldMetadata& metadata);

// ---- shared by the readers (FieldFormatReaders.cxx) ---------------------------------------

// Throws InputError "PATH: PROBLEM": every reader's one way to refuse a file.
[[noreturn]] void Fail(const std::string& path, const std::string& problem);

// A number in six significant digits, as reports and messages print them.
std::string Number(double value);

// A type's name after its indefinite article, for "got an int32", "a uint64", "a float".
std::string WithArticle(const std::string& name);

// The scalar types of raw files (field.raw.type), as VTK types.
struct RawType
{
  const char* Name; // "uint16"
  int VtkType;      // VTK_UNSIGNED_SHORT
  int Bytes;
};
const std::vector<RawType>& RawTypes();

// How the values after a header are stored.
enum class ValueEncoding
{
  Raw,  // the bytes of the values, one after the other
  Zlib, // one zlib or gzip stream of those bytes
  Text  // numbers written as text, separated by white space or commas
};

// Where and how a file stores the values its header declares (StoredValues.cxx).
struct StoredValues
{
  const RawType* Type = nullptr;
  bool BigEndian = false;
  ValueEncoding Encoding = ValueEncoding::Raw;
  std::uint64_t Offset = 0;            // the first byte of the data in the file
  std::optional<std::uint64_t> Length; // bytes of (compressed) data, when the header says
  bool AtEnd = false;                  // raw: the values end the file, bytes before them skipped
  std::uint64_t SkipDecoded = 0;       // compressed: decompressed bytes to skip before the values
};

// The `count` values `file` stores as `stored` says, as floats named "density". The data region
// (from the offset to the end of the file) must hold exactly those values: a region too short or
// too long, a compressed stream that cannot expand to the declared size, ends early, is corrupt
// or yields more, text too short for the numbers or with fewer or more of them, and values beyond
// float's range are refused (whatever the region's size rules out, before anything of the
// declared size is allocated) (InputError naming `path`; `what`, such as
// "an image of 60 float values", says what was expected). The caller checks `count` with
// CheckFieldSize first.
vtkSmartPointer<vtkFloatArray> ReadStoredValues(const std::string& path,
  const RegularInputFile& file,
  const StoredValues& stored,
  std::uint64_t count,
  const std::string& what);

// "a field of 2048 x 2048 x 1024 voxels (4.29e+09 voxels, 16 GiB as float) is more than
// field.max_voxels allows (1073741824): ..." for messages.
std::string TooManyVoxels(const int dimensions[3], std::uint64_t maximumVoxels);

// Throws InputError naming `path` unless a field of `dimensions` voxels (each at least 1) fits:
// at most `maximumVoxels`, and `bytesPerVoxel` (what the reader holds per voxel while reading;
// twice in the isolated child, whose parent receives a copy) plus the 4-byte float copy
// ReadField makes, plus `extraBytes`, within the memory available. Called before anything of
// that size is allocated.
void CheckFieldSize(const std::string& path,
  const std::array<double, 3>& dimensions,
  double bytesPerVoxel,
  std::uint64_t maximumVoxels,
  double extraBytes = 0.0);

// Throws InputError naming `path` unless the file holds at least `needed` bytes of voxel data
// after `offset`: a truncated file is refused before its claimed size is allocated.
void CheckFileHoldsData(const std::string& path,
  std::uint64_t fileBytes,
  std::uint64_t offset,
  double needed,
  const std::string& what);

// Whether `value` is finite but beyond float's range: converted, it would become infinite. (NaN
// and infinity are kept, for ReadField to count and refuse.)
bool BeyondFloat(double value);

// Throws InputError "PATH: HOLDER holds N values beyond the range of float (about 3.4e38)" when
// `beyond` (values for which BeyondFloat held) is not 0: every reader's one refusal of them.
void RefuseBeyondFloat(const std::string& path, const std::string& holder, std::uint64_t beyond);

// The report line "array": the point array used and the others the image holds.
void ReportPointArrays(FieldReport& report, vtkImageData* image, const std::string& chosen);

// ---- units a file declares (docs/data.md, "Physical units") ----------------------------------

// A droplets' effective radius (micrometres, in [0.001, 1000000]) or number concentration (per
// cm^3, in [DropletNumberMin, DropletNumberMax]) a file declares, into report.Units with a report
// line saying `source` ("the variable's effective_radius", "grid metadata"); refused, naming
// `path` and `declaration` ("variable \"ql\": attribute effective_radius"), when out of range.
// NetCDF attributes, OpenVDB grid metadata and VTK XML field data share these checks.
void DeclareEffectiveRadius(const std::string& path,
  const std::string& declaration,
  const std::string& source,
  double radius,
  FieldReport& report);
void DeclareDropletNumber(const std::string& path,
  const std::string& declaration,
  const std::string& source,
  double number,
  FieldReport& report);

// The quantity a `units` text declares (QuantityFromUnits): a liquid water content into
// report.Units, with the factor to g/m^3 in report.LwcScale (applied by ResolveFieldValues once
// the scene's field.quantity is known) and a report line naming `whose` ("the variable's");
// nothing for any other units.
void DeclareQuantityOfUnits(const std::string& units,
  const std::string& whose,
  FieldReport& report);

// A named declaration of a unit in a file's metadata, as NamedUnits reads it: a string, a number
// or another type (named for messages: "a float", "an int32").
struct MetadataEntry
{
  std::optional<std::string> Text;
  std::optional<double> Number;
  std::string TypeName;
};

// The units a file declares by name in its metadata (OpenVDB grid metadata, VTK XML field data):
// the strings "quantity" ("density" or "lwc"), "length_unit" ("none", "m", "km"), "up" ("x",
// "y", "z"), and the numbers "effective_radius" (micrometres) and "droplet_number" (per cm^3).
// `lookup` finds an entry by name (nothing when absent); `owner` names the metadata in messages
// (`grid "ql": metadata`, `field data`) and `source` in the report ("grid metadata"). An entry of
// another type, or a value not among those allowed, is refused naming the file, the owner and the
// name: a declaration is read as declared or not at all.
void DeclareNamedUnits(const std::string& path,
  const std::string& owner,
  const std::string& source,
  const std::function<std::optional<MetadataEntry>(const std::string& name)>& lookup,
  FieldReport& report);

// Sets the image's spacing and direction from three axis vectors (world length and direction of
// one step along i, j, k), as NRRD's space directions and MetaImage's TransformMatrix with
// ElementSpacing and OpenVDB's affine maps state them. Throws InputError naming `path` when an
// axis has no length. Axes that are not perpendicular (a sheared lattice) are kept as stated and
// refused by ReadField with every format's, whose direction must be a rotation.
void SetAxes(const std::string& path,
  vtkImageData* image,
  const std::array<std::array<double, 3>, 3>& axes);

} // namespace cloudvis

#endif
