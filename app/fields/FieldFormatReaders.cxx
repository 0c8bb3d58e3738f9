// What the field readers share: every size check, the float conversion and the report lines are
// written here once, so every format refuses the same problems with the same words.
#include "FieldFormatReaders.h"

#include "Errors.h"
#include "IsolatedRead.h"

#include "CloudFieldGeometry.h" // AvailableMemoryBytes, FormatBytes

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

namespace cloudvis
{
namespace
{

std::string Dimensions(const std::array<double, 3>& d)
{
  std::ostringstream text;
  text.precision(12);
  text << d[0] << " x " << d[1] << " x " << d[2];
  return text.str();
}

// FormatBytes, with sizes below 1 KiB as whole numbers (FormatBytes prints 500 as "5e+02").
std::string Bytes(double bytes)
{
  return bytes < 1024.0 ? std::to_string(std::uint64_t(bytes)) + " bytes" : FormatBytes(bytes);
}

} // namespace

void Fail(const std::string& path, const std::string& problem)
{
  throw InputError(path + ": " + problem);
}

std::string Number(double value)
{
  std::ostringstream text;
  text.precision(6);
  text << value;
  return text.str();
}

std::string WithArticle(const std::string& name)
{
  // By sound: "an int32", "an array", but "a uint8", "a ubyte", "a ushort" (you-).
  const char first = char(std::tolower(static_cast<unsigned char>(name.empty() ? 'x' : name[0])));
  const bool you = name.rfind("ui", 0) == 0 || name.rfind("ub", 0) == 0 || name.rfind("us", 0) == 0;
  const bool vowel = std::string("aeio").find(first) != std::string::npos || (first == 'u' && !you);
  return (vowel ? "an " : "a ") + name;
}

const std::vector<RawType>& RawTypes()
{
  static const std::vector<RawType> types = {
    { "uint8", VTK_UNSIGNED_CHAR, 1 },
    { "int8", VTK_SIGNED_CHAR, 1 },
    { "uint16", VTK_UNSIGNED_SHORT, 2 },
    { "int16", VTK_SHORT, 2 },
    { "uint32", VTK_UNSIGNED_INT, 4 },
    { "int32", VTK_INT, 4 },
    { "uint64", VTK_TYPE_UINT64, 8 },
    { "int64", VTK_TYPE_INT64, 8 },
    { "float32", VTK_FLOAT, 4 },
    { "float64", VTK_DOUBLE, 8 },
  };
  return types;
}

std::string TooManyVoxels(const int dimensions[3], std::uint64_t maximumVoxels)
{
  const std::array<double, 3> d{
    { double(dimensions[0]), double(dimensions[1]), double(dimensions[2]) }
  };
  std::ostringstream text;
  text << "a field of " << Dimensions(d) << " voxels (" << d[0] * d[1] * d[2] << " voxels, "
       << Bytes(d[0] * d[1] * d[2] * 4.0) << " as float) is more than field.max_voxels allows ("
       << maximumVoxels << "); raise field.max_voxels if the memory and the GPU can hold it";
  return text.str();
}

void CheckFieldSize(const std::string& path,
  const std::array<double, 3>& dimensions,
  double bytesPerVoxel,
  std::uint64_t maximumVoxels,
  double extraBytes)
{
  for (int a = 0; a < 3; ++a)
  {
    if (!(dimensions[a] >= 1.0))
    {
      Fail(path,
        "the field has no voxels (" + Dimensions(dimensions) + ", " + "xyz"[a] + " is empty)");
    }
  }
  const double voxels = dimensions[0] * dimensions[1] * dimensions[2];
  for (int a = 0; a < 3; ++a)
  {
    if (dimensions[a] > double(std::numeric_limits<int>::max()))
    {
      Fail(path,
        "the field's extent along " + std::string(1, "xyz"[a]) + " is too large (" +
          Dimensions(dimensions) + " voxels)");
    }
  }
  if (voxels > double(maximumVoxels))
  {
    const int d[3] = { int(dimensions[0]), int(dimensions[1]), int(dimensions[2]) };
    Fail(path, TooManyVoxels(d, maximumVoxels));
  }
  // In the isolated child (IsolatedRead.h) the parent's copy of what it sends back is alive at
  // the same time.
  const double copies = InIsolatedRead() ? 2.0 : 1.0;
  const double needed = voxels * (copies * bytesPerVoxel + 4.0) + extraBytes;
  NoteReadNeeds("a field of " + Dimensions(dimensions) + " voxels", needed);
  const std::uint64_t available = AvailableMemoryBytes();
  if (available > 0 && needed > double(available))
  {
    Fail(path,
      "a field of " + Dimensions(dimensions) + " voxels needs at least " + Bytes(needed) +
        " to read but only " + FormatBytes(double(available)) + " of memory is available");
  }
}

void CheckFileHoldsData(const std::string& path,
  std::uint64_t fileBytes,
  std::uint64_t offset,
  double needed,
  const std::string& what)
{
  const double held = fileBytes > offset ? double(fileBytes - offset) : 0.0;
  if (held < needed)
  {
    std::ostringstream text;
    text.precision(15);
    text << what << " needs " << needed << " bytes of data";
    if (offset > 0)
    {
      text << " after " << offset << " bytes of header";
    }
    text << " but the file holds " << held << ": it is truncated or its header is wrong";
    Fail(path, text.str());
  }
}

bool BeyondFloat(double value)
{
  return std::isfinite(value) && std::fabs(value) > double(std::numeric_limits<float>::max());
}

void RefuseBeyondFloat(const std::string& path, const std::string& holder, std::uint64_t beyond)
{
  if (beyond > 0)
  {
    Fail(path,
      holder + " holds " + std::to_string(beyond) +
        " values beyond the range of float (about 3.4e38)");
  }
}

namespace
{

// "float", "unsigned short", ...: a VTK type in words.
std::string TypeInWords(int vtkType)
{
  switch (vtkType)
  {
    case VTK_FLOAT:
      return "float";
    case VTK_DOUBLE:
      return "double";
    case VTK_UNSIGNED_CHAR:
      return "unsigned char";
    case VTK_SIGNED_CHAR:
    case VTK_CHAR:
      return "signed char";
    case VTK_UNSIGNED_SHORT:
      return "unsigned short";
    case VTK_SHORT:
      return "short";
    case VTK_UNSIGNED_INT:
      return "unsigned int";
    case VTK_INT:
      return "int";
    default:
      return vtkImageScalarTypeNameMacro(vtkType);
  }
}
} // namespace

void ReportPointArrays(FieldReport& report, vtkImageData* image, const std::string& chosen)
{
  vtkPointData* points = image->GetPointData();
  vtkDataArray* used = chosen.empty()
    ? (points->GetArray("density") ? points->GetArray("density") : points->GetScalars())
    : points->GetArray(chosen.c_str());
  if (!used)
  {
    return; // ReadField refuses the file and says why
  }
  std::string others;
  for (int i = 0; i < points->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* array = points->GetArray(i);
    if (array && array != used)
    {
      others += std::string(others.empty() ? "" : ", ") +
        (array->GetName() ? array->GetName() : "(unnamed)");
    }
  }
  report.Add("array",
    std::string("\"") + (used->GetName() ? used->GetName() : "(unnamed)") + "\" (" +
      TypeInWords(used->GetDataType()) + ")" +
      (others.empty() ? "" : "; other point arrays (field.array): " + others));
}

namespace
{
std::string EffectiveRadiusRange()
{
  return "a number of micrometres in [0.001, 1000000]";
}

std::string DropletNumberRange()
{
  return "a number of droplets per cm^3 in [" + Number(DropletNumberMin) + ", " +
    Number(DropletNumberMax) + "]";
}
} // namespace

void DeclareEffectiveRadius(const std::string& path,
  const std::string& declaration,
  const std::string& source,
  double radius,
  FieldReport& report)
{
  if (!(radius >= 1e-3 && radius <= 1e6))
  {
    Fail(path, declaration + " must be " + EffectiveRadiusRange() + ", got " + Number(radius));
  }
  report.Units.EffectiveRadius = radius;
  report.Add("effective radius", Number(radius) + " um (" + source + ")");
}

void DeclareDropletNumber(const std::string& path,
  const std::string& declaration,
  const std::string& source,
  double number,
  FieldReport& report)
{
  if (!(number >= DropletNumberMin && number <= DropletNumberMax))
  {
    Fail(path, declaration + " must be " + DropletNumberRange() + ", got " + Number(number));
  }
  report.Units.DropletNumber = number;
  report.Add("droplet number", Number(number) + " per cm^3 (" + source + ")");
}

void DeclareQuantityOfUnits(const std::string& units, const std::string& whose, FieldReport& report)
{
  if (const auto declared = QuantityFromUnits(units))
  {
    report.Units.Quantity = declared->Quantity;
    if (declared->Scale != 1.0)
    {
      report.LwcScale = declared->Scale;
      report.LwcScaleFrom = units;
    }
    report.Add("quantity", "lwc (liquid water content, by " + whose + " units)");
  }
}

void DeclareNamedUnits(const std::string& path,
  const std::string& owner,
  const std::string& source,
  const std::function<std::optional<MetadataEntry>(const std::string& name)>& lookup,
  FieldReport& report)
{
  // The index of the entry's value among `allowed`; -1 when there is no such entry.
  const auto text = [&](const std::string& name, const std::vector<std::string>& allowed)
  {
    const std::optional<MetadataEntry> entry = lookup(name);
    if (!entry)
    {
      return -1;
    }
    const auto found =
      entry->Text ? std::find(allowed.begin(), allowed.end(), *entry->Text) : allowed.end();
    if (found == allowed.end())
    {
      std::string names;
      for (const std::string& a : allowed)
      {
        names += (names.empty() ? "\"" : ", \"") + a + "\"";
      }
      Fail(path,
        owner + " \"" + name + "\" must be one of the strings " + names + ", got " +
          (entry->Text ? "\"" + *entry->Text + "\"" : WithArticle(entry->TypeName)));
    }
    report.Add(name, *entry->Text + " (" + source + ")");
    return int(found - allowed.begin());
  };
  if (const int q = text("quantity", { "density", "lwc" }); q >= 0)
  {
    report.Units.Quantity = FieldQuantity(q);
  }
  if (const int l = text("length_unit", { "none", "m", "km" }); l >= 0)
  {
    report.Units.Length = LengthUnit(l);
  }
  if (const int u = text("up", { "x", "y", "z" }); u >= 0)
  {
    report.Units.Up = u;
  }
  const auto number = [&](const std::string& name, const std::string& range, auto declare)
  {
    if (const std::optional<MetadataEntry> entry = lookup(name))
    {
      const std::string declaration = owner + " \"" + name + "\"";
      if (!entry->Number)
      {
        Fail(path, declaration + " must be " + range + ", got " + WithArticle(entry->TypeName));
      }
      declare(path, declaration, source, *entry->Number, report);
    }
  };
  number("effective_radius", EffectiveRadiusRange(), DeclareEffectiveRadius);
  number("droplet_number", DropletNumberRange(), DeclareDropletNumber);
}

void SetAxes(const std::string& path,
  vtkImageData* image,
  const std::array<std::array<double, 3>, 3>& axes)
{
  double spacing[3];
  vtkNew<vtkMatrix3x3> direction;
  for (int i = 0; i < 3; ++i)
  {
    const std::array<double, 3>& a = axes[i];
    spacing[i] = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(spacing[i] > 0.0) || !std::isfinite(spacing[i]))
    {
      Fail(path, "the step along axis " + std::to_string(i) + " has no length (or is not finite)");
    }
    for (int row = 0; row < 3; ++row)
    {
      direction->SetElement(row, i, a[row] / spacing[i]);
    }
  }
  image->SetSpacing(spacing);
  image->SetDirectionMatrix(direction);
}

} // namespace cloudvis
