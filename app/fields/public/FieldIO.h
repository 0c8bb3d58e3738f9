// Reading and writing density fields. Every field format cloudvis reads is one entry of the table
// FieldFormats(): its name for field.format and --format, its name for messages, its file
// extensions (matched without regard to case), the read options it takes and its reader, which
// returns the image as the format holds it together with a report of what it read. ReadField
// picks the entry (by field.format, else by extension) and hands the rest of cloudvis one form
// only: a float point array named "density", set as the active scalars, on an image that keeps
// the file's whole geometry (extent, origin, spacing, direction). The command line's choice between
// a scene and a field file, the scene's field.file and field.format, the help texts and the error
// messages all follow the table. Every problem becomes one InputError naming the file and what is
// wrong with it. Fields are written as .vti, as .pvti with pieces (FieldPieces.h) or as OpenVDB.
// docs/data.md describes every format for users.
#ifndef cloudvis_FieldIO_h
#define cloudvis_FieldIO_h

#include "FieldUnits.h"

#include <vtkSmartPointer.h>

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

class vtkImageData;

namespace cloudvis
{

// The most voxels a field file may become unless field.max_voxels says otherwise: 1024^3, a
// 4 GiB float field, about what one GPU of today renders. A reader refuses more before it
// allocates, naming the size the file needs.
constexpr std::uint64_t DefaultMaximumFieldVoxels = std::uint64_t(1) << 30;

// The layout of a raw volume, which the file itself does not state (field.raw.*).
struct RawLayout
{
  std::array<int, 3> Dimensions{ { 0, 0, 0 } }; // voxels along x, y, z; 0: not given
  std::string Type = "float32";                 // one of RawTypeNames()
  bool BigEndian = false;
  std::array<double, 3> Spacing{ { 1.0, 1.0, 1.0 } };
  std::array<double, 3> Origin{ { 0.0, 0.0, 0.0 } };
  std::uint64_t HeaderBytes = 0; // bytes before the first voxel
};

// What the values a file marks as missing (NetCDF's _FillValue, missing_value, valid_min,
// valid_max, valid_range) become: field.missing. cloudvis does not guess what a missing density
// is: by default such a file is refused with the count; "empty" reads them as empty space.
enum class MissingValueRule
{
  Refuse,
  Empty // density 0
};

// What the gaps of a numbered file series (FieldSeries.h) become: field.series_gaps.
enum class SeriesGapRule
{
  Refuse, // a missing number is refused, naming the file the progression expects
  Skip    // the files there are are read as consecutive steps; the report says what is missing
};

// How a field file is read beyond its path: the scene's field.format, field.array,
// field.time_step, field.missing, field.max_voxels and field.raw (or --format, --array,
// --time-step).
struct FieldReadOptions
{
  std::string Format;          // a FieldFormat's Id; empty: chosen by the extension
  std::string Array;           // grid, variable or point array; empty: the format's default
  std::optional<int> TimeStep; // index from 0; empty: the first (a series' file, FieldSeries.h)
  std::optional<MissingValueRule> Missing; // empty: Refuse
  std::optional<SeriesGapRule> SeriesGaps; // empty: Refuse; only for a series
  std::uint64_t MaximumVoxels = DefaultMaximumFieldVoxels;
  RawLayout Raw;
  // What the scene declares of the field's units (field.quantity, field.length_unit, field.up,
  // field.effective_radius): it wins over what the file declares (ResolveFieldValues).
  FieldUnits Units;
  // field.air_density: where the air's density comes from when a NetCDF file's mixing ratios
  // become a liquid water content (NetCdfAirDensity.h).
  AirDensitySource AirDensity;
};

// What a reader found and did, for `cloudvis info`: the format's name, then labelled lines in
// the order they are printed ("grid", "units", "time step", "resampled", ...).
struct FieldReport
{
  std::string Format;
  std::vector<std::pair<std::string, std::string>> Details;
  // The physical units the file declares (a NetCDF variable's `units`, OpenVDB grid metadata);
  // the scene's field keys win over them (FieldUnits.h).
  FieldUnits Units;
  // The VTK type of the values as the file stores them, before ReadField made them float
  // (VTK_UNSIGNED_CHAR for an 8-bit .vti, NRRD, MetaImage or raw file); 0 where the format's
  // values are physical numbers already (NetCDF's after unpacking, OpenVDB's). A coverage map
  // divides stored integers by their type's maximum, as it does an image's.
  int StoredType = 0;
  // The factor that turns the file's values into g/m^3 when they are read as a liquid water
  // content (1000 for a NetCDF variable in kg m-3), and the units it converts from ("kg m-3");
  // 1 and "" when the values need none. Applied by ResolveFieldValues, not by the reader, so that
  // field.quantity "density" keeps the values as stored.
  double LwcScale = 1.0;
  std::string LwcScaleFrom;
  // The time steps the file holds (1 for a format or a variable without a time axis), and the
  // time of the step read with the units of the file's time coordinate (NaN and "" without one).
  std::size_t TimeSteps = 1;
  double Time = std::numeric_limits<double>::quiet_NaN();
  std::string TimeUnits;
  // The time of every step, in TimeUnits, where the file's time axis has a coordinate (empty
  // otherwise): what ParaView's animation steps through.
  std::vector<double> Times;
  // The file a series' step was read from (FieldSeries.h); empty for a single file.
  std::string StepFile;
  // The units the field has once the scene's declaration and the file's are combined
  // (ResolveFieldValues): what every consumer of the field (the droplets' extinction and phase,
  // info's statistics) takes.
  ResolvedFieldUnits Resolved;

  void Add(const std::string& label, const std::string& text)
  {
    this->Details.emplace_back(label, text);
  }
};

// What a reader returns: the image as the format holds it, the point array holding the density
// (empty: "density", else the active scalars) and the report.
struct FieldFileContents
{
  vtkSmartPointer<vtkImageData> Image;
  std::string Array;
  FieldReport Report;
};

// The read options a format takes beyond the path (bits of FieldFormat::Options).
enum FieldReadOption : unsigned
{
  TakesArray = 1u,      // field.array
  TakesTimeStep = 2u,   // field.time_step
  TakesRawLayout = 4u,  // field.raw (and requires its dimensions)
  TakesMissing = 8u,    // field.missing: the format marks missing values
  TakesAirDensity = 16u // field.air_density: the format holds mixing ratios and the air
};

struct FieldFormat
{
  std::string Id;                      // field.format and --format: "vdb"
  std::string Name;                    // for messages and help: "OpenVDB"
  std::vector<std::string> Extensions; // lower case, with the dot: ".vdb"
  unsigned Options = 0;                // FieldReadOption bits
  // Reads `path` with the format's own protections against hostile input (the regular-file
  // check, sizes checked against memory, the file and options.MaximumVoxels before allocation,
  // the library's parsing isolated where it can crash or hang). Throws InputError naming the file.
  FieldFileContents (*Read)(const std::string& path, const FieldReadOptions& options);
};

// The field formats cloudvis reads, in the order help texts list them.
const std::vector<FieldFormat>& FieldFormats();

// The format whose extension `path` ends in (any case), or nullptr.
const FieldFormat* FindFieldFormat(const std::string& path);

// The Ids of FieldFormats() for messages: "vti, pvti, vdb, ...".
std::string FieldFormatIds();

// Whether `path` names a field file (its extension is one of FieldFormats()) rather than a scene.
bool IsFieldFile(const std::string& path);

// The extensions of FieldFormats() for messages: ".vti, .pvti, .vdb, ...".
std::string FieldFileExtensions();

// The names field.raw.type accepts: "uint8", "int8", "uint16", ..., "float64".
std::vector<std::string> RawTypeNames();

// A read option that does not suit the file's format, as the dotted key under "field" that
// names it ("array", "raw.dimensions") and the problem; nullopt when the options suit it.
struct FieldOptionProblem
{
  std::string Key;
  std::string Problem;
};
std::optional<FieldOptionProblem> CheckFieldReadOptions(const std::string& path,
  const FieldReadOptions& options);

// Loads a density field in any format of FieldFormats(), chosen by options.Format or else the
// extension. The density must have one component and only finite values; it becomes a float
// array "density", the active scalars, on an image with the file's extent, origin, spacing and
// direction. Throws InputError otherwise, and for an extension no format has. The field's units
// are then decided and its values made to agree with them (ResolveFieldValues, with
// options.Units as the scene's declaration). `report`, when given, receives what the reader
// found and the resolved units (FieldReport::Resolved).
vtkSmartPointer<vtkImageData> ReadField(const std::string& path,
  const FieldReadOptions& options = {},
  FieldReport* report = nullptr);

// The one place the quantity, length unit, up axis and effective radius of a field are decided
// (FieldUnits.h): the scene's declaration `scene`, else what the file declared (report.Units),
// else the defaults; stored in report.Resolved and returned. The values of `field` (its float
// scalars) are made to agree: a liquid water content the file stores in kg/m^3 is converted to
// g/m^3 (report.LwcScale; a value that overflows float there is refused), and not when the scene
// reads the field as a density; for a liquid water content, negative values down to
// -NegligibleNegativeLwc (the noise of advection schemes in LES output) are read as 0 and said
// so in the report, more negative ones are refused with their count and the most negative; with
// a droplet number, the cloud's mean content and the effective radius there are set
// (ResolvedFieldUnits::CloudMeanLwc).
// `name` (the file, or the scene of a generated field) starts every message. ReadField calls it
// for a file, ProduceField (SceneField.h) for a generated field.
constexpr double NegligibleNegativeLwc = 1e-3; // g/m^3: a tenth of info's cloud threshold
ResolvedFieldUnits ResolveFieldValues(const std::string& name,
  vtkImageData* field,
  const FieldUnits& scene,
  FieldReport& report);

// What is recorded in a field file cloudvis writes, where the format has room for it (.vdb).
struct FieldMetadata
{
  std::string Scene; // the resolved scene as JSON text; empty: none
};

// Throws InputError unless `path` can take a field: its directory writable (CheckOutputTarget),
// and its extension one of FieldOutputExtensions() (any case).
void CheckFieldOutput(const std::string& path);

// Writes a field atomically (see AtomicFile.h): .vti as binary VTK XML image data,
// zlib-compressed; .vdb as an OpenVDB FloatGrid "density" (OpenVdbFiles.h); .pvti as one piece
// (FieldPieces.h writes several). Throws InputError when the target cannot be written.
void WriteField(vtkImageData* field, const std::string& path, const FieldMetadata& metadata = {});

// Writes `field` as VTK XML image data (.vti, as WriteField does) onto a file created (or
// truncated) at exactly `path`, not atomically, every write checked (WriteNewFileChecked,
// AtomicFile.h): the pieces of a .pvti (FieldPieces.h), which their owner renames into place.
// Errors name `target`, the file the user asked for. `run`, when not empty, is recorded as the
// generation run of a piece (PieceRunAttribute, FieldPieces.h).
void WriteVtkXmlImageFile(vtkImageData* field,
  const std::string& path,
  const std::string& target,
  const std::string& run = {});

} // namespace cloudvis

#endif
