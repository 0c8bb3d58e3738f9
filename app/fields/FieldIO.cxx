// The table of field formats, the checks of read options against a format, the conversion every
// reader's image goes through, and the writers. The readers themselves live with their formats:
// VtkXmlImageFiles.cxx (.vti, .pvti), NrrdMetaImageRawFiles.cxx (raw, NRRD, MetaImage),
// NetCdfFiles.cxx (NetCDF), OpenVdbFiles.cxx (OpenVDB, reader and writer).
#include "FieldIO.h"

#include "AtomicFile.h"
#include "Errors.h"
#include "FieldFormatReaders.h"
#include "FieldPieces.h"
#include "FieldSeries.h"
#include "FileNames.h"
#include "OutOfMemory.h"
#include "Words.h"
#include "VtkMessageCapture.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cloudvis
{
namespace
{

// The array a density is taken from: `name` when the reader named one, else "density" by name,
// else whatever the file marks as scalars.
vtkDataArray* DensityArray(const std::string& path, vtkImageData* image, const std::string& name)
{
  vtkPointData* points = image->GetPointData();
  if (!name.empty())
  {
    vtkDataArray* named = points->GetArray(name.c_str());
    if (!named)
    {
      std::string names;
      for (int i = 0; i < points->GetNumberOfArrays(); ++i)
      {
        const char* arrayName = points->GetArrayName(i);
        names += std::string(names.empty() ? "" : ", ") + (arrayName ? arrayName : "(unnamed)");
      }
      Fail(path,
        "no point array named \"" + name + "\" (field.array); the file's point arrays: " +
          (names.empty() ? std::string("none") : names));
    }
    return named;
  }
  if (vtkDataArray* named = points->GetArray("density"))
  {
    return named;
  }
  return points->GetScalars();
}

// The density field of an image a reader returned: its geometry and one float array "density",
// after checking the array is one the renderer can use.
vtkSmartPointer<vtkImageData> DensityFieldOf(const std::string& path,
  vtkImageData* image,
  const std::string& arrayName,
  std::uint64_t maximumVoxels)
{
  if (image->GetNumberOfPoints() == 0)
  {
    Fail(path, "the image has no voxels");
  }
  // Every reader checks the size before it allocates; this catches a reader that could not.
  if (std::uint64_t(image->GetNumberOfPoints()) > maximumVoxels)
  {
    Fail(path, TooManyVoxels(image->GetDimensions(), maximumVoxels));
  }
  vtkDataArray* array = DensityArray(path, image, arrayName);
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

  // The lattice's axes must be perpendicular unit vectors (a rotation, or a reflection), as VTK's
  // direction cosines are meant to be, though VTK accepts any matrix. Checked here once for every
  // format: a .vti's Direction, NRRD's space directions, MetaImage's TransformMatrix and OpenVDB's
  // affine map alike.
  const double* d = image->GetDirectionMatrix()->GetData();
  for (int a = 0; a < 3; ++a)
  {
    for (int b = 0; b < 3; ++b)
    {
      const double dot = d[a] * d[b] + d[3 + a] * d[3 + b] + d[6 + a] * d[6 + b];
      if (!(std::fabs(dot - (a == b ? 1.0 : 0.0)) <= 1e-6))
      {
        Fail(path,
          "the image's direction matrix is not a rotation: its axes must be perpendicular unit "
          "vectors (axes " +
            std::to_string(a) + " and " + std::to_string(b) + " have a dot product of " +
            std::to_string(dot) + ")");
      }
    }
  }

  // The spacing must be finite and not zero. A negative spacing (a lattice numbered downwards, as
  // a .vti or a NetCDF coordinate may be) is the same geometry as its positive value with that
  // axis of the direction matrix reversed: stored so, every consumer sees positive spacings and
  // finds a reversal in one place, the direction matrix.
  double spacing[3], direction[9];
  image->GetSpacing(spacing);
  std::copy(d, d + 9, direction);
  const double* origin = image->GetOrigin();
  for (int a = 0; a < 3; ++a)
  {
    if (!(std::isfinite(spacing[a]) && spacing[a] != 0.0))
    {
      Fail(path,
        "the image's spacing along axis " + std::to_string(a) + " is " + Number(spacing[a]) +
          ": spacings must be finite and not zero");
    }
    if (!std::isfinite(origin[a]))
    {
      Fail(path, "the image's origin holds " + Number(origin[a]) + ": it must be finite");
    }
    if (spacing[a] < 0.0)
    {
      spacing[a] = -spacing[a];
      for (int r = 0; r < 3; ++r)
      {
        direction[3 * r + a] = -direction[3 * r + a];
      }
    }
  }

  // A new image with just the geometry and the density, so arrays of other meanings in the file
  // do not travel on as if they were ours.
  vtkSmartPointer<vtkImageData> field = vtkSmartPointer<vtkImageData>::New();
  field->SetExtent(image->GetExtent());
  field->SetOrigin(image->GetOrigin());
  field->SetSpacing(spacing);
  field->SetDirectionMatrix(direction);
  field->GetPointData()->SetScalars(density);
  return field;
}

// The format whose Id is `id`, or nullptr.
const FieldFormat* FindFieldFormatById(const std::string& id)
{
  for (const FieldFormat& format : FieldFormats())
  {
    if (format.Id == id)
    {
      return &format;
    }
  }
  return nullptr;
}

const FieldFormat& FormatFor(const std::string& path, const FieldReadOptions& options)
{
  if (!options.Format.empty())
  {
    if (const FieldFormat* format = FindFieldFormatById(options.Format))
    {
      return *format;
    }
    Fail(path,
      "unknown field format \"" + options.Format +
        "\" (field.format); formats: " + FieldFormatIds());
  }
  if (const FieldFormat* format = FindFieldFormat(path))
  {
    return *format;
  }
  const std::string extension = LowerCaseExtension(path);
  Fail(path,
    (extension.empty() ? std::string("the file name has no field extension")
                       : "unsupported field format \"" + extension + "\"") +
      "; supported: " + FieldFileExtensions() + " (or name the format with field.format)");
}

// vtkXMLImageDataWriter that also states, when given one, the generation run a piece of a .pvti
// belongs to: an attribute of its ImageData element (PieceRunAttribute, FieldPieces.h), which
// VTK's and ParaView's readers ignore and cloudvis's .pvti reader compares with the .pvti's.
class vtkCloudRunImageDataWriter : public vtkXMLImageDataWriter
{
public:
  static vtkCloudRunImageDataWriter* New();
  vtkTypeMacro(vtkCloudRunImageDataWriter, vtkXMLImageDataWriter);
  std::string Run;
  // Writes to `out` rather than to a file of the writer's own: vtkXMLWriter's Stream, which
  // it otherwise sets only for itself. No FileName then, so that a failure cannot make VTK
  // delete a file by name.
  void SetOutputStream(ostream* out) { this->Stream = out; }

protected:
  vtkCloudRunImageDataWriter() = default;
  void WritePrimaryElementAttributes(ostream& os, vtkIndent indent) override
  {
    this->Superclass::WritePrimaryElementAttributes(os, indent);
    if (!this->Run.empty())
    {
      this->WriteStringAttribute(PieceRunAttribute, this->Run.c_str());
    }
  }

private:
  vtkCloudRunImageDataWriter(const vtkCloudRunImageDataWriter&) = delete;
  void operator=(const vtkCloudRunImageDataWriter&) = delete;
};
vtkStandardNewMacro(vtkCloudRunImageDataWriter);

// Writes `field` as VTK XML image data (.vti) onto `out` (seekable): the .vti writer calls it on
// the stream of its atomic write (AtomicFile.h), WriteVtkXmlImageFile on a piece's file. Errors
// name `target`, the file the user asked for. `run`, when not empty, is recorded as the
// generation run of a piece (PieceRunAttribute, FieldPieces.h).
void WriteVtkXmlImage(vtkImageData* field,
  std::ostream& out,
  const std::string& target,
  const std::string& run = {})
{
  VtkMessageCapture messages;
  vtkNew<vtkCloudRunImageDataWriter> writer;
  writer->Run = run;
  writer->SetInputData(field);
  writer->SetOutputStream(&out);
  // Raw appended binary (no base64) compressed with zlib: the smallest file VTK and
  // ParaView read back exactly.
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
  {
    Fail(target, messages.WithVtkReason("cannot write the field"));
  }
}

// The writers, by the extension of the output.
struct FieldWriter
{
  std::string Extension;
  void (*Write)(vtkImageData* field, const std::string& path, const FieldMetadata& metadata);
};

const std::vector<FieldWriter>& FieldWriters()
{
  static const std::vector<FieldWriter> writers = {
    { ".vti",
      [](vtkImageData* field, const std::string& path, const FieldMetadata&)
      {
        WriteStreamAtomically(path,
          "the field",
          [field, &path](std::ostream& out) { WriteVtkXmlImage(field, out, path); });
      } },
    { ".pvti",
      [](vtkImageData* field, const std::string& path, const FieldMetadata&)
      { WriteFieldPieces(field, path, 1); } },
    { ".vdb", WriteOpenVdbFile },
  };
  return writers;
}

// The extensions fields are written in: ".vti, .pvti, .vdb".
std::string FieldOutputExtensions()
{
  std::vector<std::string> extensions;
  for (const FieldWriter& writer : FieldWriters())
  {
    extensions.push_back(writer.Extension);
  }
  return Join(extensions);
}

} // namespace

const std::vector<FieldFormat>& FieldFormats()
{
  static const std::vector<FieldFormat> formats = {
    { "vti", "VTK XML image data", { ".vti" }, TakesArray, ReadVtkXmlImageFile },
    { "pvti", "VTK XML parallel image data", { ".pvti" }, TakesArray, ReadVtkXmlParallelImageFile },
    { "vdb", "OpenVDB", { ".vdb" }, TakesArray, ReadOpenVdbFile },
    { "netcdf",
      "NetCDF (CF conventions)",
      { ".nc", ".nc4", ".cdf" },
      TakesArray | TakesTimeStep | TakesMissing | TakesAirDensity,
      ReadNetCdfFile },
    { "nrrd", "NRRD", { ".nrrd", ".nhdr" }, 0, ReadNrrdFile },
    { "metaimage", "MetaImage", { ".mha", ".mhd" }, 0, ReadMetaImageFile },
    { "raw", "raw volume", { ".raw" }, TakesRawLayout, ReadRawFile },
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

std::string FieldFormatIds()
{
  std::vector<std::string> ids;
  for (const FieldFormat& format : FieldFormats())
  {
    ids.push_back(format.Id);
  }
  return Join(ids);
}

bool IsFieldFile(const std::string& path)
{
  return FindFieldFormat(path) != nullptr;
}

std::string FieldFileExtensions()
{
  std::vector<std::string> extensions;
  for (const FieldFormat& format : FieldFormats())
  {
    extensions.insert(extensions.end(), format.Extensions.begin(), format.Extensions.end());
  }
  return Join(extensions);
}

std::vector<std::string> RawTypeNames()
{
  std::vector<std::string> names;
  for (const RawType& type : RawTypes())
  {
    names.emplace_back(type.Name);
  }
  return names;
}

std::optional<FieldOptionProblem> CheckFieldReadOptions(const std::string& path,
  const FieldReadOptions& options)
{
  const FieldFormat* format =
    options.Format.empty() ? FindFieldFormat(path) : FindFieldFormatById(options.Format);
  if (!format)
  {
    return options.Format.empty()
      ? FieldOptionProblem{ "file",
          "\"" + path + "\" is not a field file: supported extensions (in any case) are " +
            FieldFileExtensions() + "; field.format names the format of a file with another name" }
      : FieldOptionProblem{ "format",
          "unknown format \"" + options.Format + "\"; allowed: " + FieldFormatIds() };
  }
  const std::string of = " (" + format->Name + ")";
  if (!options.Array.empty() && !(format->Options & TakesArray))
  {
    return FieldOptionProblem{ "array", "a " + format->Id + " file" + of + " holds one array" };
  }
  const bool series = IsFileSeriesPattern(path);
  if (options.TimeStep && !series && !(format->Options & TakesTimeStep))
  {
    return FieldOptionProblem{ "time_step",
      "a " + format->Id + " file" + of + " holds one time step" };
  }
  if (options.SeriesGaps && !series)
  {
    return FieldOptionProblem{ "series_gaps",
      "applies to a file series only (a field.file with * where the files' numbers are, "
      "run/les_*.nc)" };
  }
  if (options.Missing && !(format->Options & TakesMissing))
  {
    return FieldOptionProblem{ "missing",
      "applies to NetCDF files only; a " + format->Id + " file" + of +
        " marks no values as missing" };
  }
  if (options.AirDensity.From != AirDensitySource::Kind::Auto &&
    !(format->Options & TakesAirDensity))
  {
    return FieldOptionProblem{ "air_density",
      "applies to NetCDF files only, whose mixing ratios it turns into liquid water contents; a " +
        format->Id + " file" + of + " declares no mixing ratio" };
  }
  const bool rawGiven = options.Raw.Dimensions[0] > 0;
  if (format->Options & TakesRawLayout)
  {
    if (!rawGiven)
    {
      return FieldOptionProblem{ "raw.dimensions",
        "missing; a raw file does not state its dimensions: give field.raw.dimensions (and "
        "field.raw.type, byte_order, spacing, origin where they differ from the defaults)" };
    }
  }
  else if (rawGiven)
  {
    return FieldOptionProblem{ "raw",
      "applies to raw files only; a " + format->Id + " file" + of + " states its own layout" };
  }
  return std::nullopt;
}

vtkSmartPointer<vtkImageData> ReadField(const std::string& path,
  const FieldReadOptions& options,
  FieldReport* report)
{
  if (const std::optional<FieldOptionProblem> problem = CheckFieldReadOptions(path, options))
  {
    Fail(path, "field." + problem->Key + ": " + problem->Problem);
  }
  if (IsFileSeriesPattern(path))
  {
    return ReadFileSeriesStep(path, options, report);
  }
  const FieldFormat& format = FormatFor(path, options);
  const MemoryUse memory("reading " + path, 0.0);
  FieldFileContents contents = format.Read(path, options);
  vtkSmartPointer<vtkImageData> field =
    DensityFieldOf(path, contents.Image, contents.Array, options.MaximumVoxels);
  contents.Report.Format = format.Name;
  ResolveFieldValues(path, field, options.Units, contents.Report);
  if (report)
  {
    *report = contents.Report;
    // Readers that hand VTK's arrays on (.vti, .pvti) leave the stored type to the array.
    vtkDataArray* stored =
      report->StoredType == 0 ? DensityArray(path, contents.Image, contents.Array) : nullptr;
    if (stored && stored->GetDataType() != VTK_FLOAT)
    {
      report->StoredType = stored->GetDataType();
    }
  }
  return field;
}

ResolvedFieldUnits ResolveFieldValues(const std::string& name,
  vtkImageData* field,
  const FieldUnits& scene,
  FieldReport& report)
{
  ResolvedFieldUnits units = ResolveFieldUnits(scene, report.Units);
  vtkFloatArray* values = vtkFloatArray::SafeDownCast(field->GetPointData()->GetScalars());
  const bool lwc = units.Quantity == FieldQuantity::Lwc;
  if (values && report.LwcScale != 1.0)
  {
    if (!lwc)
    {
      report.Add("converted",
        "no: the scene's field.quantity \"density\" keeps the values as stored, in " +
          report.LwcScaleFrom);
    }
    else
    {
      // Converted in double and checked: the product of a float the file holds and the scale
      // may be beyond float's range, which is cloudvis's doing, not the file's.
      const double scale = report.LwcScale;
      float* v = values->GetPointer(0);
      vtkIdType overflowing = 0;
      double largest = 0.0;
      for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
      {
        const double converted = double(v[i]) * scale;
        if (!(std::fabs(converted) <= double(std::numeric_limits<float>::max())))
        {
          ++overflowing;
          largest = std::max(largest, std::fabs(double(v[i])));
        }
        v[i] = float(converted);
      }
      if (overflowing > 0)
      {
        Fail(name,
          std::to_string(overflowing) + (overflowing == 1 ? " value" : " values") + " in " +
            report.LwcScaleFrom + " (up to " + Number(largest) + ") are beyond float's range (" +
            Number(double(std::numeric_limits<float>::max())) + ") once converted to g/m^3 (x " +
            Number(scale) +
            "): not a liquid water content; field.quantity \"density\" reads "
            "them as stored");
      }
      values->Modified();
      report.Add(
        "converted", "from " + report.LwcScaleFrom + " to g/m^3 (x " + Number(scale) + ")");
    }
  }
  if (values && lwc)
  {
    // LES output holds tiny negative contents (-1e-12 and the like) from its advection schemes:
    // they are no water, and read as none. A clearly negative content is not a content at all
    // (an unmarked fill value, a wrong variable) and is refused rather than integrated.
    float* v = values->GetPointer(0);
    vtkIdType negligible = 0, negative = 0;
    double lowest = 0.0;
    for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
    {
      if (v[i] < 0.0f)
      {
        lowest = std::min(lowest, double(v[i]));
        if (double(v[i]) >= -NegligibleNegativeLwc)
        {
          ++negligible;
          v[i] = 0.0f;
        }
        else
        {
          ++negative;
        }
      }
    }
    if (negative > 0)
    {
      Fail(name,
        std::to_string(negative) + " liquid water content" + (negative == 1 ? " is" : "s are") +
          " negative beyond -" + Number(NegligibleNegativeLwc) +
          " g/m^3 (the most negative: " + Number(lowest) +
          " g/m^3): a negative content is no water; mark such values missing "
          "(_FillValue) or read the field as a density (field.quantity \"density\")");
    }
    if (negligible > 0)
    {
      values->Modified();
      report.Add("negative",
        std::to_string(negligible) + (negligible == 1 ? " value" : " values") + " down to " +
          Number(lowest) + " g/m^3 read as 0 (at most " + Number(NegligibleNegativeLwc) +
          " g/m^3 below 0: numerical noise, not water)");
    }
  }
  if (values && lwc && units.DropletNumber > 0.0)
  {
    // One r_e for the droplets' phase: that of the cloud's mean content.
    const double threshold = DefaultCloudThreshold(FieldQuantity::Lwc);
    const float* v = values->GetPointer(0);
    double sum = 0.0;
    vtkIdType cloudy = 0;
    for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
    {
      if (double(v[i]) > threshold)
      {
        sum += double(v[i]);
        ++cloudy;
      }
    }
    units.CloudMeanLwc = cloudy > 0 ? sum / double(cloudy) : 0.0;
    if (cloudy > 0)
    {
      units.EffectiveRadius = EffectiveRadiusOfDroplets(units.CloudMeanLwc, units.DropletNumber);
      units.EffectiveRadiusFrom = "droplet number";
    }
  }
  report.Resolved = units;
  return units;
}

void CheckFieldOutput(const std::string& path)
{
  CheckOutputTarget(path); // first: "it is a directory" says more than a missing extension
  const std::string extension = LowerCaseExtension(path);
  const auto& writers = FieldWriters();
  if (std::none_of(writers.begin(),
        writers.end(),
        [&extension](const FieldWriter& writer) { return writer.Extension == extension; }))
  {
    Fail(path,
      "fields are written as VTK XML image data (.vti), parallel image data with pieces (.pvti) "
      "or OpenVDB (.vdb): give the output one of the extensions " +
        FieldOutputExtensions());
  }
}

void WriteField(vtkImageData* field, const std::string& path, const FieldMetadata& metadata)
{
  CheckFieldOutput(path);
  const MemoryUse memory(
    "writing " + path + " (" + std::to_string(field->GetNumberOfPoints()) + " voxels)",
    4.0 * double(field->GetNumberOfPoints()));
  const std::string extension = LowerCaseExtension(path);
  for (const FieldWriter& writer : FieldWriters())
  {
    if (writer.Extension == extension)
    {
      writer.Write(field, path, metadata);
      return;
    }
  }
}

void WriteVtkXmlImageFile(vtkImageData* field,
  const std::string& path,
  const std::string& target,
  const std::string& run)
{
  WriteNewFileChecked(path,
    target,
    "the field",
    [&](std::ostream& out) { WriteVtkXmlImage(field, out, target, run); });
}

} // namespace cloudvis
