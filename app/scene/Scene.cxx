// Scene parsing is table-driven at every level: top-level sections, the keys of "field", the
// keys of a shape object, and the names of enumerations are each one table, and one set of typed
// readers (number, integer, vector, name) checks every value, so each check is written once and
// every message has the same shape: "<source>: <dotted key>: <problem>".
#include "Scene.h"

#include "Errors.h"
#include "FieldIO.h"
#include "InputFiles.h"
#include "Presets.h"
#include "SceneField.h"
#include "Utf8.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>

namespace cloudvis
{
namespace
{
using json = nlohmann::json;

// Where the document came from, for messages and relative paths.
struct Context
{
  std::string Source;
  std::string BaseDirectory;
  // Dotted keys set on the command line, each with the option that set it; the last one to
  // set a key is the one whose value is checked.
  std::vector<std::pair<std::string, std::string>> OverriddenKeys;

  [[noreturn]] void Fail(const std::string& key, const std::string& problem) const
  {
    std::string note;
    for (const auto& overridden : this->OverriddenKeys)
    {
      const std::string& k = overridden.first;
      if (key == k || key.rfind(k + ".", 0) == 0 || key.rfind(k + "[", 0) == 0)
      {
        note = " (set with " + overridden.second + ")";
      }
    }
    throw InputError(this->Source + ": " + key + ": " + problem + note);
  }
};

std::string Join(const std::vector<std::string>& names)
{
  std::string joined;
  for (const std::string& name : names)
  {
    joined += (joined.empty() ? "" : ", ") + name;
  }
  return joined;
}

std::string Describe(const json& value)
{
  // A string from --set may hold any bytes, and dump() throws on invalid UTF-8.
  const std::string text = WithValidUtf8(value).dump();
  return std::string(value.type_name()) + " " + (text.size() > 40 ? text.substr(0, 37) + "..." : text);
}

std::string FormatNumber(double value)
{
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

// An allowed interval of a number, and its description for messages and docs.
struct Range
{
  double Min = -std::numeric_limits<double>::max();
  double Max = std::numeric_limits<double>::max();
  bool MinOpen = false; // true: Min itself is excluded
  bool MaxOpen = false; // true: Max itself is excluded

  bool Contains(double v) const
  {
    return (this->MinOpen ? v > this->Min : v >= this->Min) &&
      (this->MaxOpen ? v < this->Max : v <= this->Max);
  }
  std::string Text() const
  {
    const bool bounded = this->Max < std::numeric_limits<double>::max();
    const bool floored = this->Min > -std::numeric_limits<double>::max();
    if (floored && bounded)
    {
      return std::string(this->MinOpen ? "(" : "[") + FormatNumber(this->Min) + ", " +
        FormatNumber(this->Max) + (this->MaxOpen ? ")" : "]");
    }
    if (floored)
    {
      return std::string(this->MinOpen ? "> " : ">= ") + FormatNumber(this->Min);
    }
    return "any finite number";
  }
};
const Range AnyNumber{};
const Range NonNegative{ 0.0 };
const Range Positive{ 0.0, std::numeric_limits<double>::max(), true };
const Range UnitInterval{ 0.0, 1.0 };

double ReadNumber(const Context& c, const json& v, const std::string& key, const Range& range)
{
  if (!v.is_number())
  {
    c.Fail(key, "expected a number, got " + Describe(v));
  }
  const double value = v.get<double>();
  if (!std::isfinite(value))
  {
    c.Fail(key, "expected a finite number, got " + FormatNumber(value));
  }
  if (!range.Contains(value))
  {
    c.Fail(key, "value " + FormatNumber(value) + " is out of range: allowed " + range.Text());
  }
  return value;
}

// Integers may be written as 6 or 6.0, never 6.5.
long long ReadInteger(
  const Context& c, const json& v, const std::string& key, long long min, long long max)
{
  const std::string allowed = "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  if (!v.is_number())
  {
    c.Fail(key, "expected " + allowed + ", got " + Describe(v));
  }
  if (v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(max))
  {
    c.Fail(key, "value " + v.dump() + " is out of range: allowed " + allowed);
  }
  const double asDouble = v.get<double>();
  if (v.is_number_float() && (!std::isfinite(asDouble) || asDouble != std::floor(asDouble)))
  {
    c.Fail(key, "expected " + allowed + ", got " + v.dump());
  }
  if (asDouble < double(min) || asDouble > double(max))
  {
    c.Fail(key, "value " + v.dump() + " is out of range: allowed " + allowed);
  }
  return v.is_number_float() ? static_cast<long long>(asDouble) : v.get<long long>();
}

template <size_t N>
std::array<double, N> ReadNumbers(
  const Context& c, const json& v, const std::string& key, const Range& range)
{
  if (!v.is_array() || v.size() != N)
  {
    c.Fail(key, "expected an array of " + std::to_string(N) + " numbers, got " + Describe(v));
  }
  std::array<double, N> values;
  for (size_t i = 0; i < N; ++i)
  {
    values[i] = ReadNumber(c, v[i], key + "[" + std::to_string(i) + "]", range);
  }
  return values;
}

bool ReadBool(const Context& c, const json& v, const std::string& key)
{
  if (!v.is_boolean())
  {
    c.Fail(key, "expected true or false, got " + Describe(v));
  }
  return v.get<bool>();
}

glm::vec3 ReadVec3(const Context& c, const json& v, const std::string& key, const Range& range)
{
  const std::array<double, 3> a = ReadNumbers<3>(c, v, key, range);
  return glm::vec3(float(a[0]), float(a[1]), float(a[2]));
}

// The names scene files use for enumerations.
template <typename E>
struct Named
{
  const char* Name;
  E Value;
};
const Named<DensityModel> DensityModels[] = {
  { "sdf_plus_fbm", DensityModel::SdfPlusFbm },
  { "fbm_falloff", DensityModel::FbmFalloff },
  { "constant", DensityModel::Constant },
};
const Named<noise::NoiseType> NoiseTypes[] = {
  { "none", noise::NoiseType::None },
  { "white", noise::NoiseType::White },
  { "value", noise::NoiseType::Value },
  { "perlin", noise::NoiseType::Perlin },
};
const Named<ShapeBlend> Blends[] = {
  { "union", ShapeBlend::Union },
  { "smooth_union", ShapeBlend::SmoothUnion },
};
const Named<ShapeType> ShapeTypes[] = {
  { "sphere", ShapeType::Sphere },
  { "box", ShapeType::Box },
  { "torus", ShapeType::Torus },
  { "cross", ShapeType::Cross },
  { "capsule", ShapeType::Capsule },
};
const char* const MorphName = "morph";
// One line per lighting model; the renderer maps each onto the mapper.
const Named<LightingModel> LightingModels[] = {
  { "none", LightingModel::None },
  { "derivative", LightingModel::Derivative },
  { "march", LightingModel::March },
};

template <typename E, size_t N>
std::vector<std::string> NamesOf(const Named<E> (&table)[N])
{
  std::vector<std::string> names;
  for (const Named<E>& entry : table)
  {
    names.emplace_back(entry.Name);
  }
  return names;
}

template <typename E, size_t N>
E ReadName(const Context& c, const json& v, const std::string& key, const Named<E> (&table)[N])
{
  if (!v.is_string())
  {
    c.Fail(key, "expected a string (one of " + Join(NamesOf(table)) + "), got " + Describe(v));
  }
  for (const Named<E>& entry : table)
  {
    if (v.get<std::string>() == entry.Name)
    {
      return entry.Value;
    }
  }
  c.Fail(key, "unknown name \"" + v.get<std::string>() + "\"; allowed: " + Join(NamesOf(table)));
}

// Keys of an object section, each with the function that reads its value into T.
template <typename T>
struct Key
{
  const char* Name;
  void (*Read)(const Context&, const json&, const std::string& key, T&);
};

template <typename T, size_t N>
std::vector<std::string> KeyNames(const Key<T> (&table)[N])
{
  std::vector<std::string> names;
  for (const Key<T>& entry : table)
  {
    names.emplace_back(entry.Name);
  }
  return names;
}

template <typename T, size_t N>
const Key<T>* FindKey(const Key<T> (&table)[N], const std::string& name)
{
  for (const Key<T>& entry : table)
  {
    if (name == entry.Name)
    {
      return &entry;
    }
  }
  return nullptr;
}

// Reads every member of an object through a key table, refusing keys the table lacks.
template <typename T, size_t N>
void ReadObject(const Context& c, const json& object, const std::string& key,
  const Key<T> (&table)[N], T& target)
{
  if (!object.is_object())
  {
    c.Fail(key, "expected an object, got " + Describe(object));
  }
  for (const auto& member : object.items())
  {
    const std::string memberKey = key.empty() ? member.key() : key + "." + member.key();
    const Key<T>* entry = FindKey(table, member.key());
    if (!entry)
    {
      c.Fail(memberKey, "unknown key; allowed keys: " + Join(KeyNames(table)));
    }
    entry->Read(c, member.value(), memberKey, target);
  }
}

// ---- shapes -------------------------------------------------------------------------------

// Which shape types use a key, as a bit mask over ShapeType.
constexpr unsigned Bit(ShapeType t)
{
  return 1u << static_cast<unsigned>(t);
}
constexpr unsigned AllShapes = Bit(ShapeType::Sphere) | Bit(ShapeType::Box) |
  Bit(ShapeType::Torus) | Bit(ShapeType::Cross) | Bit(ShapeType::Capsule);

struct ShapeKey
{
  const char* Name;
  unsigned UsedBy;
  void (*Read)(const Context&, const json&, const std::string& key, Shape&);
};
const ShapeKey ShapeKeys[] = {
  { "type", AllShapes, [](const Context&, const json&, const std::string&, Shape&) {} },
  { "center", AllShapes,
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.Center = ReadVec3(c, v, k, AnyNumber); } },
  { "rotation", AllShapes,
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.RotationDegrees = ReadVec3(c, v, k, AnyNumber); } },
  { "scale", AllShapes,
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.Scale = float(ReadNumber(c, v, k, Positive)); } },
  { "radius", Bit(ShapeType::Sphere) | Bit(ShapeType::Capsule),
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.Radius = float(ReadNumber(c, v, k, NonNegative)); } },
  { "half_size", Bit(ShapeType::Box),
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.HalfSize = ReadVec3(c, v, k, NonNegative); } },
  { "major_radius", Bit(ShapeType::Torus),
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.MajorRadius = float(ReadNumber(c, v, k, NonNegative)); } },
  { "minor_radius", Bit(ShapeType::Torus),
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.MinorRadius = float(ReadNumber(c, v, k, NonNegative)); } },
  { "arm_width", Bit(ShapeType::Cross),
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.ArmWidth = float(ReadNumber(c, v, k, NonNegative)); } },
  { "arm_length", Bit(ShapeType::Cross),
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.ArmLength = float(ReadNumber(c, v, k, NonNegative)); } },
  { "end_a", Bit(ShapeType::Capsule),
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.EndA = ReadVec3(c, v, k, AnyNumber); } },
  { "end_b", Bit(ShapeType::Capsule),
    [](const Context& c, const json& v, const std::string& k, Shape& s)
    { s.EndB = ReadVec3(c, v, k, AnyNumber); } },
};

std::string KeysUsedBy(ShapeType type)
{
  std::vector<std::string> names;
  for (const ShapeKey& entry : ShapeKeys)
  {
    if (entry.UsedBy & Bit(type))
    {
      names.emplace_back(entry.Name);
    }
  }
  return Join(names);
}

std::vector<std::string> AllShapeNames()
{
  std::vector<std::string> names = NamesOf(ShapeTypes);
  names.emplace_back(MorphName);
  return names;
}

// One entry of "shape": a name (that shape with its default parameters) or an object.
// Returns false for "morph", which is not a Shape but a switch of the whole field.
bool ReadShape(const Context& c, const json& v, const std::string& key, Shape& shape)
{
  if (v.is_string())
  {
    if (v.get<std::string>() == MorphName)
    {
      return false;
    }
    for (const Named<ShapeType>& entry : ShapeTypes)
    {
      if (v.get<std::string>() == entry.Name)
      {
        shape.Type = entry.Value;
        return true;
      }
    }
    c.Fail(key, "unknown shape \"" + v.get<std::string>() + "\"; allowed: " + Join(AllShapeNames()));
  }
  if (!v.is_object())
  {
    c.Fail(key, "expected a shape name (one of " + Join(AllShapeNames()) +
        "), a shape object or a list of them, got " + Describe(v));
  }
  if (!v.contains("type"))
  {
    c.Fail(key + ".type", "missing; a shape object needs a type (one of " +
        Join(NamesOf(ShapeTypes)) + ")");
  }
  if (v["type"] == MorphName)
  {
    c.Fail(key + ".type", "\"morph\" is not a shape type; write \"shape\": \"morph\" instead");
  }
  shape.Type = ReadName(c, v["type"], key + ".type", ShapeTypes);
  const std::string typeName = v["type"].get<std::string>();
  for (const auto& member : v.items())
  {
    const std::string memberKey = key + "." + member.key();
    const ShapeKey* found = nullptr;
    for (const ShapeKey& entry : ShapeKeys)
    {
      found = member.key() == entry.Name ? &entry : found;
    }
    if (!found)
    {
      c.Fail(memberKey, "unknown key; allowed keys for a " + typeName + ": " + KeysUsedBy(shape.Type));
    }
    if (!(found->UsedBy & Bit(shape.Type)))
    {
      c.Fail(memberKey, "not a parameter of a " + typeName + "; allowed keys for a " + typeName +
          ": " + KeysUsedBy(shape.Type));
    }
    found->Read(c, member.value(), memberKey, shape);
  }
  return true;
}

void ReadShapes(const Context& c, const json& v, const std::string& key, FieldSpec& f)
{
  const bool list = v.is_array();
  if (list && v.empty())
  {
    c.Fail(key, "the list of shapes is empty; give at least one shape");
  }
  const json items = list ? v : json::array({ v });
  f.Description.Shapes.clear();
  f.Description.Morph = false;
  for (size_t i = 0; i < items.size(); ++i)
  {
    const std::string itemKey = list ? key + "[" + std::to_string(i) + "]" : key;
    Shape shape;
    if (!ReadShape(c, items[i], itemKey, shape))
    {
      if (items.size() > 1)
      {
        c.Fail(itemKey, "\"morph\" cannot be combined with other shapes");
      }
      f.Description.Morph = true;
      f.Description.Shapes = { Shape{} };
      return;
    }
    f.Description.Shapes.push_back(shape);
  }
}

// ---- the field section -------------------------------------------------------------------

// Voxels along x, y and z: one integer for a cube, or three.
std::array<int, 3> ReadDimensions(const Context& c, const json& v, const std::string& key)
{
  const long long maxInt = std::numeric_limits<int>::max();
  std::array<int, 3> dimensions{};
  if (v.is_number())
  {
    dimensions.fill(int(ReadInteger(c, v, key, 1, maxInt)));
    return dimensions;
  }
  if (!v.is_array() || v.size() != 3)
  {
    c.Fail(key, "expected an integer or an array of 3 integers, got " + Describe(v));
  }
  for (int a = 0; a < 3; ++a)
  {
    dimensions[a] = int(ReadInteger(c, v[a], key + "[" + std::to_string(a) + "]", 1, maxInt));
  }
  return dimensions;
}

// field.raw: the layout of a raw volume.
const Key<RawLayout> RawKeys[] = {
  { "dimensions",
    [](const Context& c, const json& v, const std::string& k, RawLayout& r)
    { r.Dimensions = ReadDimensions(c, v, k); } },
  { "type",
    [](const Context& c, const json& v, const std::string& k, RawLayout& r)
    {
      const std::vector<std::string> names = RawTypeNames();
      if (!v.is_string() ||
        std::find(names.begin(), names.end(), v.get<std::string>()) == names.end())
      {
        c.Fail(k, "expected one of " + Join(names) + ", got " + Describe(v));
      }
      r.Type = v.get<std::string>();
    } },
  { "byte_order",
    [](const Context& c, const json& v, const std::string& k, RawLayout& r)
    {
      if (!v.is_string() || (v.get<std::string>() != "little" && v.get<std::string>() != "big"))
      {
        c.Fail(k, "expected \"little\" or \"big\", got " + Describe(v));
      }
      r.BigEndian = v.get<std::string>() == "big";
    } },
  { "spacing",
    [](const Context& c, const json& v, const std::string& k, RawLayout& r)
    { r.Spacing = ReadNumbers<3>(c, v, k, Positive); } },
  { "origin",
    [](const Context& c, const json& v, const std::string& k, RawLayout& r)
    { r.Origin = ReadNumbers<3>(c, v, k, AnyNumber); } },
  { "header_bytes",
    [](const Context& c, const json& v, const std::string& k, RawLayout& r)
    { r.HeaderBytes = std::uint64_t(ReadInteger(c, v, k, 0, 1LL << 62)); } },
};

// The keys that say how a field file is read; the first is the file itself.
const Key<FieldSpec> FieldFileKeys[] = {
  { "file",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    {
      if (!v.is_string() || v.get<std::string>().empty())
      {
        c.Fail(k,
          "expected the path of a field file (" + FieldFileExtensions() +
            ", a non-empty string), got " + Describe(v));
      }
      // Whether the extension names a format is checked with field.format, in ReadField.
      const std::string path = v.get<std::string>();
      f.File = path[0] == '/' || c.BaseDirectory.empty() ? path : c.BaseDirectory + "/" + path;
    } },
  { "format",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    {
      if (!v.is_string() || !FindFieldFormatById(v.get<std::string>()))
      {
        c.Fail(k,
          (v.is_string() ? "unknown format \"" + v.get<std::string>() + "\""
                         : "expected a format name, got " + Describe(v)) +
            "; allowed: " + FieldFormatIds());
      }
      f.Read.Format = v.get<std::string>();
    } },
  { "array",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    {
      if (!v.is_string() || v.get<std::string>().empty())
      {
        c.Fail(k,
          "expected the name of a grid, variable or point array (a non-empty string), got " +
            Describe(v));
      }
      f.Read.Array = v.get<std::string>();
    } },
  { "time_step",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Read.TimeStep = int(ReadInteger(c, v, k, 0, std::numeric_limits<int>::max())); } },
  { "max_voxels",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Read.MaximumVoxels = std::uint64_t(ReadInteger(c, v, k, 1, 1LL << 62)); } },
  { "raw",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { ReadObject(c, v, k, RawKeys, f.Read.Raw); } },
};

const Key<FieldSpec> FieldKeys[] = {
  FieldFileKeys[0],
  FieldFileKeys[1],
  FieldFileKeys[2],
  FieldFileKeys[3],
  FieldFileKeys[4],
  FieldFileKeys[5],
  { "dimensions",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Dimensions = ReadDimensions(c, v, k); } },
  { "bounds",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    {
      f.Bounds = ReadNumbers<6>(c, v, k, AnyNumber);
      for (int a = 0; a < 3; ++a)
      {
        if (!(f.Bounds[2 * a] < f.Bounds[2 * a + 1]))
        {
          c.Fail(k, std::string("bounds along ") + "xyz"[a] + " must increase (min < max), got [" +
              FormatNumber(f.Bounds[2 * a]) + ", " + FormatNumber(f.Bounds[2 * a + 1]) + "]");
        }
      }
    } },
  { "density_model",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.Model = ReadName(c, v, k, DensityModels); } },
  { "density_scale",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.DensityScale = ReadNumber(c, v, k, NonNegative); } },
  { "falloff_width",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.FalloffWidth = ReadNumber(c, v, k, Positive); } },
  { "shape", ReadShapes },
  { "blend",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.Blend = ReadName(c, v, k, Blends); } },
  { "blend_radius",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.BlendRadius = ReadNumber(c, v, k, NonNegative); } },
  { "noise",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.Noise.Type = ReadName(c, v, k, NoiseTypes); } },
  { "octaves",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.Noise.Octaves = int(ReadInteger(c, v, k, 1, 12)); } },
  { "frequency",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f) {
      f.Description.Noise.Frequency = ReadNumber(c, v, k, Range{ 0.0, 1e6, true });
    } },
  { "lacunarity",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.Noise.Lacunarity = ReadNumber(c, v, k, Positive); } },
  { "lacunarity_increment",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.Noise.LacunarityIncrement = ReadNumber(c, v, k, AnyNumber); } },
  { "gain",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.Noise.Gain = ReadNumber(c, v, k, NonNegative); } },
  { "amplitude",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.Noise.Amplitude = ReadNumber(c, v, k, NonNegative); } },
  { "seed",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Description.Noise.Seed = std::uint32_t(ReadInteger(c, v, k, 0, 4294967295LL)); } },
  { "wind",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    {
      const std::array<double, 3> w = ReadNumbers<3>(c, v, k, AnyNumber);
      f.Description.Wind = glm::dvec3(w[0], w[1], w[2]);
    } },
  { "time",
    [](const Context& c, const json& v, const std::string& k, FieldSpec& f)
    { f.Time = ReadNumber(c, v, k, AnyNumber); } },
};

bool IsFieldFileKey(const std::string& name)
{
  return FindKey(FieldFileKeys, name) != nullptr;
}

void ReadField(const Context& c, const json& v, const std::string& key, Scene& scene)
{
  if (v.is_object())
  {
    for (const auto& member : v.items())
    {
      const bool fileKey = IsFieldFileKey(member.key());
      if (v.contains("file") && !fileKey && FindKey(FieldKeys, member.key()))
      {
        c.Fail(key + ".file", "cannot be combined with " + key + "." + member.key() +
            ": a field loaded from a file has no procedural parameters");
      }
      if (!v.contains("file") && fileKey)
      {
        c.Fail(key + "." + member.key(),
          "says how a field file is read; give " + key +
            ".file too (or leave it out for a procedural field)");
      }
    }
  }
  ReadObject(c, v, key, FieldKeys, scene.Field);
  if (scene.Field.FromFile())
  {
    if (const auto problem = CheckFieldReadOptions(scene.Field.File, scene.Field.Read))
    {
      c.Fail(key + "." + problem->Key, problem->Problem);
    }
    return;
  }
  // The source's own checks, for what only a combination of keys can get wrong (a field too
  // large for memory, a lacunarity that turns negative after some octaves, noise coordinates
  // beyond the lattice's range).
  const std::string problem = ValidateProceduralField(scene.Field);
  if (!problem.empty())
  {
    c.Fail(key, problem);
  }
}

// ---- the transfer_function section --------------------------------------------------------

// A list of control points [density, v1, .. v(N-1)]: at least one, values in `range`, densities
// strictly increasing (a transfer function is a function of density).
template <size_t N>
std::vector<std::array<double, N>> ReadControlPoints(
  const Context& c, const json& v, const std::string& key, const Range& range, const char* form)
{
  if (!v.is_array())
  {
    c.Fail(key, std::string("expected a list of ") + form + " points, got " + Describe(v));
  }
  if (v.empty())
  {
    c.Fail(key, std::string("the list is empty; give at least one ") + form + " point");
  }
  std::vector<std::array<double, N>> points;
  for (size_t i = 0; i < v.size(); ++i)
  {
    const std::string pointKey = key + "[" + std::to_string(i) + "]";
    if (!v[i].is_array() || v[i].size() != N)
    {
      c.Fail(pointKey, std::string("expected a point ") + form + ", got " + Describe(v[i]));
    }
    std::array<double, N> point;
    point[0] = ReadNumber(c, v[i][0], pointKey + "[0]", AnyNumber);
    for (size_t j = 1; j < N; ++j)
    {
      point[j] = ReadNumber(c, v[i][j], pointKey + "[" + std::to_string(j) + "]", range);
    }
    if (!points.empty() && !(point[0] > points.back()[0]))
    {
      c.Fail(pointKey + "[0]", "densities must increase strictly from point to point: " +
          FormatNumber(point[0]) + " follows " + FormatNumber(points.back()[0]));
    }
    points.push_back(point);
  }
  return points;
}

const Key<TransferFunctionSpec> TransferFunctionKeys[] = {
  { "opacity",
    [](const Context& c, const json& v, const std::string& k, TransferFunctionSpec& t)
    { t.Opacity = ReadControlPoints<2>(c, v, k, UnitInterval, "[density, opacity]"); } },
  { "color",
    [](const Context& c, const json& v, const std::string& k, TransferFunctionSpec& t)
    { t.Color = ReadControlPoints<4>(c, v, k, UnitInterval, "[density, r, g, b]"); } },
  { "unit_distance",
    [](const Context& c, const json& v, const std::string& k, TransferFunctionSpec& t)
    { t.UnitDistance = ReadNumber(c, v, k, Positive); } },
  // Read first, by ReadTransferFunction, so that the keys above override the preset's.
  { "preset", [](const Context&, const json&, const std::string&, TransferFunctionSpec&) {} },
  { "preset_name", [](const Context&, const json&, const std::string&, TransferFunctionSpec&) {} },
};

// A preset file in cloudvis's format: the transfer function's own keys plus two labels.
void ReadPresetLabel(const Context& c, const json& v, const std::string& k, TransferFunctionSpec&)
{
  if (!v.is_string())
  {
    c.Fail(k, "expected a string, got " + Describe(v));
  }
}
void ReadPresetPoints(const Context& c, const json& v, const std::string& k, TransferFunctionSpec& t)
{
  FindKey(TransferFunctionKeys, k)->Read(c, v, k, t);
}
const Key<TransferFunctionSpec> PresetKeys[] = {
  { "name", ReadPresetLabel },
  { "description", ReadPresetLabel },
  { "opacity", ReadPresetPoints },
  { "color", ReadPresetPoints },
  { "unit_distance", ReadPresetPoints },
};

// transfer_function.preset fills the section first (from the defaults: what a preset leaves out
// keeps its default), then the section's explicit keys override it.
void ReadTransferFunction(const Context& c, const json& v, const std::string& key, Scene& scene)
{
  if (v.is_object() && v.contains("preset"))
  {
    const std::string presetKey = key + ".preset";
    const json& reference = v["preset"];
    if (!reference.is_string() || reference.get<std::string>().empty())
    {
      c.Fail(presetKey, "expected a preset name or the path of a .json file, got " + Describe(reference));
    }
    std::string paraViewName;
    if (v.contains("preset_name"))
    {
      const json& name = v["preset_name"];
      if (!name.is_string() || name.get<std::string>().empty())
      {
        c.Fail(key + ".preset_name", "expected the Name of a preset in the ParaView file, got " +
            Describe(name));
      }
      paraViewName = name.get<std::string>();
    }
    std::string problem;
    try
    {
      const PresetDocument preset = ReadPreset(reference.get<std::string>(), c.BaseDirectory, paraViewName);
      const Context presetContext{ preset.Path, "", {} };
      TransferFunctionSpec fromPreset;
      ReadObject(presetContext, preset.Document, "", PresetKeys, fromPreset);
      scene.TransferFunction = fromPreset;
    }
    catch (const InputError& e)
    {
      problem = e.what();
    }
    if (!problem.empty())
    {
      c.Fail(presetKey, problem);
    }
  }
  else if (v.is_object() && v.contains("preset_name"))
  {
    c.Fail(key + ".preset_name", "applies only with " + key + ".preset (a ParaView preset file)");
  }
  ReadObject(c, v, key, TransferFunctionKeys, scene.TransferFunction);
}

// ---- the camera section -------------------------------------------------------------------

const Key<OrbitSpec> OrbitKeys[] = {
  { "azimuth",
    [](const Context& c, const json& v, const std::string& k, OrbitSpec& o)
    { o.Azimuth = ReadNumber(c, v, k, AnyNumber); } },
  { "elevation",
    [](const Context& c, const json& v, const std::string& k, OrbitSpec& o)
    { o.Elevation = ReadNumber(c, v, k, Range{ -90.0, 90.0, true, true }); } },
  { "distance",
    [](const Context& c, const json& v, const std::string& k, OrbitSpec& o)
    { o.Distance = ReadNumber(c, v, k, Positive); } },
};

const Key<CameraSpec> CameraKeys[] = {
  { "position",
    [](const Context& c, const json& v, const std::string& k, CameraSpec& camera)
    { camera.Position = ReadNumbers<3>(c, v, k, AnyNumber); } },
  { "focal_point",
    [](const Context& c, const json& v, const std::string& k, CameraSpec& camera)
    { camera.FocalPoint = ReadNumbers<3>(c, v, k, AnyNumber); } },
  { "view_up",
    [](const Context& c, const json& v, const std::string& k, CameraSpec& camera)
    {
      camera.ViewUp = ReadNumbers<3>(c, v, k, AnyNumber);
      const std::array<double, 3>& u = camera.ViewUp;
      if (u[0] * u[0] + u[1] * u[1] + u[2] * u[2] == 0.0)
      {
        c.Fail(k, "the view-up vector must not be zero");
      }
    } },
  { "view_angle",
    [](const Context& c, const json& v, const std::string& k, CameraSpec& camera)
    { camera.ViewAngle = ReadNumber(c, v, k, Range{ 0.0, 180.0, true, true }); } },
  { "orbit",
    [](const Context& c, const json& v, const std::string& k, CameraSpec& camera)
    {
      OrbitSpec orbit;
      ReadObject(c, v, k, OrbitKeys, orbit);
      camera.Orbit = orbit;
    } },
};

void ReadCamera(const Context& c, const json& v, const std::string& key, Scene& scene)
{
  ReadObject(c, v, key, CameraKeys, scene.Camera);
  // What can be checked before the field is known; the renderer checks the view direction
  // against view_up once the defaults are filled in.
  const CameraSpec& camera = scene.Camera;
  if (camera.Position && camera.Orbit)
  {
    c.Fail(key + ".orbit", "cannot be combined with " + key + ".position: give either the position " +
        "or the orbit around the focal point");
  }
  if (camera.Position && camera.FocalPoint && *camera.Position == *camera.FocalPoint)
  {
    c.Fail(key + ".position", "the camera position equals the focal point; the view has no direction");
  }
}

// ---- the background section ---------------------------------------------------------------

const Named<BackgroundType> BackgroundTypes[] = {
  { "solid", BackgroundType::Solid },
  { "gradient", BackgroundType::Gradient },
  { "sky", BackgroundType::Sky },
};

// The keys of a background object besides "type", each with the type that uses it.
struct BackgroundKey
{
  const char* Name;
  BackgroundType Type;
  bool Required;
  void (*Read)(const Context&, const json&, const std::string& key, Scene&);
};
void ReadBackgroundColor(const Context& c, const json& v, const std::string& k, Scene& s)
{
  s.Background = ReadNumbers<3>(c, v, k, UnitInterval);
}
const BackgroundKey BackgroundKeys[] = {
  { "color", BackgroundType::Solid, true, ReadBackgroundColor },
  { "top", BackgroundType::Gradient, true,
    [](const Context& c, const json& v, const std::string& k, Scene& s)
    { s.BackgroundStyle.Top = ReadNumbers<3>(c, v, k, UnitInterval); } },
  { "bottom", BackgroundType::Gradient, true, ReadBackgroundColor },
  { "sun", BackgroundType::Sky, false,
    [](const Context& c, const json& v, const std::string& k, Scene& s)
    {
      std::array<double, 3> sun = ReadNumbers<3>(c, v, k, AnyNumber);
      const double length = std::sqrt(sun[0] * sun[0] + sun[1] * sun[1] + sun[2] * sun[2]);
      if (!(length > 0.0) || !std::isfinite(length))
      {
        c.Fail(k, "the direction toward the sun must not be zero");
      }
      for (double& x : sun)
      {
        x /= length;
      }
      s.BackgroundStyle.Sun = sun;
    } },
};

// [r, g, b] (a solid color, as before types existed) or {"type": ..., keys of that type}.
void ReadBackground(const Context& c, const json& v, const std::string& key, Scene& s)
{
  s.BackgroundStyle = BackgroundSpec{};
  if (v.is_array())
  {
    ReadBackgroundColor(c, v, key, s);
    return;
  }
  if (!v.is_object())
  {
    c.Fail(key, "expected [r, g, b] or an object with a \"type\" (one of " +
        Join(NamesOf(BackgroundTypes)) + "), got " + Describe(v));
  }
  if (!v.contains("type"))
  {
    c.Fail(key + ".type", "missing; one of " + Join(NamesOf(BackgroundTypes)));
  }
  const BackgroundType type = ReadName(c, v["type"], key + ".type", BackgroundTypes);
  const std::string typeName = v["type"].get<std::string>();
  std::vector<std::string> allowed{ "type" };
  for (const BackgroundKey& entry : BackgroundKeys)
  {
    if (entry.Type == type)
    {
      allowed.emplace_back(entry.Name);
    }
  }
  for (const auto& member : v.items())
  {
    if (member.key() == "type")
    {
      continue;
    }
    const BackgroundKey* found = nullptr;
    for (const BackgroundKey& entry : BackgroundKeys)
    {
      if (member.key() == entry.Name && entry.Type == type)
      {
        found = &entry;
      }
    }
    if (!found)
    {
      c.Fail(key + "." + member.key(), "not a key of a " + typeName + " background; allowed keys: " +
          Join(allowed));
    }
    found->Read(c, member.value(), key + "." + member.key(), s);
  }
  for (const BackgroundKey& entry : BackgroundKeys)
  {
    if (entry.Type == type && entry.Required && !v.contains(entry.Name))
    {
      c.Fail(key + "." + entry.Name, "missing; a " + typeName + " background needs " +
          Join(std::vector<std::string>(allowed.begin() + 1, allowed.end())));
    }
  }
  s.BackgroundStyle.Type = type;
}

// A sky without background.sun takes its sun from the lights section, which may come after the
// background in the document: resolved once the whole scene is read.
void ResolveSkySun(const json& document, Scene& s)
{
  BackgroundSpec& background = s.BackgroundStyle;
  if (background.Type != BackgroundType::Sky || background.Sun)
  {
    return;
  }
  if (document.contains("lights"))
  {
    for (const Light& light : s.Lights)
    {
      if (!light.Positional)
      {
        const glm::vec3 toward = SampleLight(light, glm::vec3(0.0f)).Direction;
        background.Sun = std::array<double, 3>{ { toward.x, toward.y, toward.z } };
        return;
      }
    }
  }
  const std::array<double, 3>& d = BackgroundSpec::DefaultSun;
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  background.Sun = std::array<double, 3>{ { d[0] / length, d[1] / length, d[2] / length } };
}

// ---- the render section -------------------------------------------------------------------

// render.derivative and render.march: one entry per member of LightingParameters they set.
// The ranges are ValidateLightingParameters' (CloudLighting.h), which runs afterwards as well.
using LightingKey = Key<LightingParameters>;
const LightingKey DerivativeKeys[] = {
  { "distance",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.DerivativeDistance = float(ReadNumber(c, v, k, NonNegative)); } },
};
const LightingKey MarchKeys[] = {
  { "light_steps",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.LightSteps = int(ReadInteger(c, v, k, 1, 64)); } },
  { "light_step",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.LightStep = float(ReadNumber(c, v, k, NonNegative)); } },
  { "light_step_growth",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.LightStepGrowth = float(ReadNumber(c, v, k, Range{ 1.0, 4.0 })); } },
  { "g1",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.PhaseG1 = float(ReadNumber(c, v, k, Range{ -1.0, 1.0, true, true })); } },
  { "g2",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.PhaseG2 = float(ReadNumber(c, v, k, Range{ -1.0, 1.0, true, true })); } },
  { "lobe_weight",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.PhaseLobeWeight = float(ReadNumber(c, v, k, UnitInterval)); } },
  { "multiple_scattering",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.MultipleScatteringOctaves = int(ReadInteger(c, v, k, 0, 8)); } },
  { "scattering_falloff",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.ScatteringFalloff = float(ReadNumber(c, v, k, UnitInterval)); } },
  { "extinction_falloff",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.ExtinctionFalloff = float(ReadNumber(c, v, k, UnitInterval)); } },
  { "eccentricity_falloff",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.EccentricityFalloff = float(ReadNumber(c, v, k, UnitInterval)); } },
  { "powder",
    [](const Context& c, const json& v, const std::string& k, LightingParameters& p)
    { p.PowderStrength = float(ReadNumber(c, v, k, UnitInterval)); } },
};

// Reads render.derivative or render.march, then lets the lighting's own check have its say
// (a value a float cannot hold, say 0.99999999 for g, passes the double range but not it).
template <size_t N>
void ReadLightingKeys(const Context& c, const json& v, const std::string& k,
  const LightingKey (&table)[N], RenderSpec& r)
{
  ReadObject(c, v, k, table, r.Parameters);
  const std::string problem = ValidateLightingParameters(r.Parameters);
  if (!problem.empty())
  {
    c.Fail(k, problem);
  }
}

const Key<RenderSpec> RenderKeys[] = {
  { "lighting",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    { r.Lighting = ReadName(c, v, k, LightingModels); } },
  { "step",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    { r.Step = ReadNumber(c, v, k, NonNegative); } },
  { "jitter",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    { r.Jitter = ReadBool(c, v, k); } },
  { "resolution_scale",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    { r.ResolutionScale = ReadNumber(c, v, k, Range{ 0.25, 1.0 }); } },
  { "accumulate",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    { r.Accumulate = int(ReadInteger(c, v, k, 1, 65536)); } },
  { "skip_empty_space",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    { r.SkipEmptySpace = ReadBool(c, v, k); } },
  { "size",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    {
      if (!v.is_array() || v.size() != 2)
      {
        c.Fail(k, "expected an array of 2 integers [width, height], got " + Describe(v));
      }
      for (size_t a = 0; a < 2; ++a)
      {
        r.Size[a] = int(ReadInteger(c, v[a], k + "[" + std::to_string(a) + "]", 16, 16384));
      }
    } },
  { "png_bits",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    {
      r.PngBits = int(ReadInteger(c, v, k, 8, 16));
      if (r.PngBits != 8 && r.PngBits != 16)
      {
        c.Fail(k, "expected 8 or 16, got " + v.dump());
      }
    } },
  { "exr_type",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    {
      if (!v.is_string() || (v.get<std::string>() != "half" && v.get<std::string>() != "float"))
      {
        c.Fail(k, "expected \"half\" or \"float\", got " + Describe(v));
      }
      r.ExrHalf = v.get<std::string>() == "half";
    } },
  { "derivative",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    { ReadLightingKeys(c, v, k, DerivativeKeys, r); } },
  { "march",
    [](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    { ReadLightingKeys(c, v, k, MarchKeys, r); } },
};

// ---- the lights and ambient sections ------------------------------------------------------

// Light types, as the flag vtkLight and cloudvis::Light call Positional.
const Named<bool> LightTypes[] = {
  { "directional", false },
  { "point", true },
};
constexpr unsigned DirectionalLight = 1u, PointLight = 2u;
struct LightKey
{
  const char* Name;
  unsigned UsedBy;
  void (*Read)(const Context&, const json&, const std::string& key, Light&);
};
const LightKey LightKeys[] = {
  { "type", DirectionalLight | PointLight,
    [](const Context&, const json&, const std::string&, Light&) {} },
  { "position", DirectionalLight | PointLight,
    [](const Context& c, const json& v, const std::string& k, Light& l)
    { l.Position = ReadVec3(c, v, k, AnyNumber); } },
  { "focal_point", DirectionalLight,
    [](const Context& c, const json& v, const std::string& k, Light& l)
    { l.FocalPoint = ReadVec3(c, v, k, AnyNumber); } },
  { "color", DirectionalLight | PointLight,
    [](const Context& c, const json& v, const std::string& k, Light& l)
    { l.Color = ReadVec3(c, v, k, UnitInterval); } },
  { "intensity", DirectionalLight | PointLight,
    [](const Context& c, const json& v, const std::string& k, Light& l)
    { l.Intensity = float(ReadNumber(c, v, k, NonNegative)); } },
  { "attenuation", PointLight,
    [](const Context& c, const json& v, const std::string& k, Light& l)
    {
      l.Attenuation = ReadVec3(c, v, k, NonNegative);
      if (l.Attenuation == glm::vec3(0.0f))
      {
        c.Fail(k, "the attenuation [a0, a1, a2] must not be all zero (the falloff is " +
            std::string("1 / (a0 + a1 r + a2 r^2))"));
      }
    } },
};

std::string LightKeysOf(unsigned type)
{
  std::vector<std::string> names;
  for (const LightKey& entry : LightKeys)
  {
    if (entry.UsedBy & type)
    {
      names.emplace_back(entry.Name);
    }
  }
  return Join(names);
}

Light ReadLight(const Context& c, const json& v, const std::string& key)
{
  if (!v.is_object())
  {
    c.Fail(key, "expected a light object with a type (one of " + Join(NamesOf(LightTypes)) +
        "), got " + Describe(v));
  }
  for (const char* required : { "type", "position" })
  {
    if (!v.contains(required))
    {
      c.Fail(key + "." + required, std::string("missing; a light needs a type (one of ") +
          Join(NamesOf(LightTypes)) + ") and a position");
    }
  }
  Light light;
  light.Attenuation = glm::vec3(0.0f, 0.0f, 1.0f); // inverse square, as the docs promise
  light.Positional = ReadName(c, v["type"], key + ".type", LightTypes);
  const std::string typeName = v["type"].get<std::string>();
  const unsigned type = light.Positional ? PointLight : DirectionalLight;
  for (const auto& member : v.items())
  {
    const std::string memberKey = key + "." + member.key();
    const LightKey* found = nullptr;
    for (const LightKey& entry : LightKeys)
    {
      found = member.key() == entry.Name ? &entry : found;
    }
    if (!found)
    {
      c.Fail(memberKey, "unknown key; allowed keys for a " + typeName + " light: " + LightKeysOf(type));
    }
    if (!(found->UsedBy & type))
    {
      c.Fail(memberKey, "not a parameter of a " + typeName + " light; allowed keys for a " +
          typeName + " light: " + LightKeysOf(type));
    }
    found->Read(c, member.value(), memberKey, light);
  }
  if (!light.Positional && light.Position == light.FocalPoint)
  {
    c.Fail(key + ".position", "a directional light's position equals its focal point; the " +
        std::string("light has no direction"));
  }
  return light;
}

void ReadLights(const Context& c, const json& v, const std::string& key, Scene& s)
{
  if (!v.is_array())
  {
    c.Fail(key, "expected a list of light objects, got " + Describe(v));
  }
  if (v.size() > 8)
  {
    c.Fail(key, "at most 8 lights (the renderer's limit), got " + std::to_string(v.size()));
  }
  s.Lights.clear();
  for (size_t i = 0; i < v.size(); ++i)
  {
    s.Lights.push_back(ReadLight(c, v[i], key + "[" + std::to_string(i) + "]"));
  }
}

const Key<AmbientSpec> AmbientKeys[] = {
  { "color",
    [](const Context& c, const json& v, const std::string& k, AmbientSpec& a)
    { a.Color = ReadVec3(c, v, k, UnitInterval); } },
  { "strength",
    [](const Context& c, const json& v, const std::string& k, AmbientSpec& a)
    { a.Strength = float(ReadNumber(c, v, k, NonNegative)); } },
};

// ---- top level: one entry per section -----------------------------------------------------

const Key<Scene> SceneKeys[] = {
  { "description",
    [](const Context& c, const json& v, const std::string& k, Scene& s)
    {
      if (!v.is_string())
      {
        c.Fail(k, "expected a string, got " + Describe(v));
      }
      s.Description = v.get<std::string>();
    } },
  { "field", ReadField },
  { "transfer_function", ReadTransferFunction },
  { "camera", ReadCamera },
  { "background", ReadBackground },
  { "render",
    [](const Context& c, const json& v, const std::string& k, Scene& s)
    { ReadObject(c, v, k, RenderKeys, s.Render); } },
  { "lights", ReadLights },
  { "ambient",
    [](const Context& c, const json& v, const std::string& k, Scene& s)
    { ReadObject(c, v, k, AmbientKeys, s.Ambient); } },
};

std::string DirectoryOf(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos)
  {
    return "";
  }
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::vector<std::string> SplitKey(const std::string& key)
{
  std::vector<std::string> parts;
  std::istringstream in(key);
  std::string part;
  while (std::getline(in, part, '.'))
  {
    parts.push_back(part);
  }
  return parts;
}

bool IsNumberToken(const std::string& token, double& value)
{
  const char* begin = token.c_str();
  while (*begin == ' ' || *begin == '\t')
  {
    ++begin;
  }
  if (*begin == '\0')
  {
    return false;
  }
  char* end = nullptr;
  errno = 0;
  value = std::strtod(begin, &end);
  while (*end == ' ' || *end == '\t')
  {
    ++end;
  }
  return *end == '\0' && end != begin;
}

// Far deeper than any scene nests. nlohmann's parser is iterative, but dump(), copies and
// comparisons recurse once per level, so a few hundred kilobytes of '[' would overflow the stack
// in the first message that quotes the value.
constexpr int MaxJsonDepth = 64;

// json::parse, refusing deeper nesting with an InputError prefixed by `where`.
json ParseJsonText(const std::string& text, const std::string& where)
{
  return json::parse(text,
    [&where](int depth, json::parse_event_t, json&)
    {
      if (depth > MaxJsonDepth)
      {
        throw InputError(where + ": JSON nested deeper than " + std::to_string(MaxJsonDepth) +
          " levels");
      }
      return true;
    });
}

} // namespace

std::vector<std::string> LightingModelNames()
{
  return NamesOf(LightingModels);
}

std::optional<LightingModel> FindLightingModel(const std::string& name)
{
  for (const Named<LightingModel>& entry : LightingModels)
  {
    if (name == entry.Name)
    {
      return entry.Value;
    }
  }
  return std::nullopt;
}

std::string LightingModelName(LightingModel model)
{
  for (const Named<LightingModel>& entry : LightingModels)
  {
    if (model == entry.Value)
    {
      return entry.Name;
    }
  }
  return "unknown";
}

std::vector<Light> DefaultLights()
{
  Light sun;
  sun.Positional = false;
  sun.Position = glm::vec3(6.0f, 8.0f, 4.0f);
  sun.FocalPoint = glm::vec3(0.0f);
  sun.Color = glm::vec3(1.0f);
  // An intensity means the same light in every model (docs/lighting.md, Lights).
  sun.Intensity = 1.0f;
  sun.Attenuation = glm::vec3(0.0f, 0.0f, 1.0f);
  return { sun };
}

LightingParameters LightingOf(const Scene& scene)
{
  LightingParameters lighting = scene.Render.Parameters;
  lighting.Model = scene.Render.Lighting;
  lighting.AmbientColor = scene.Ambient.Color;
  lighting.AmbientStrength = scene.Ambient.Strength;
  return lighting;
}

Scene DefaultScene()
{
  return Scene{};
}

nlohmann::json ReadSceneDocument(const std::string& path)
{
  return ReadJsonFile(path, "scene file");
}

nlohmann::json ReadJsonFile(const std::string& path, const std::string& what)
{
  const std::string text = RegularInputFile(path, what).ReadAll(MaximumJsonFileBytes);
  try
  {
    return ParseJsonText(text, path);
  }
  catch (const json::parse_error& e)
  {
    // The byte offset is where the parser stopped; turn it into the line and column an editor
    // shows.
    size_t line = 1, column = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i)
    {
      if (text[i] == '\n')
      {
        ++line;
        column = 1;
      }
      else
      {
        ++column;
      }
    }
    std::string reason = e.what();
    const auto columnAt = reason.find("column ");
    const auto colon = reason.find(": ", columnAt == std::string::npos ? 0 : columnAt);
    if (colon != std::string::npos)
    {
      reason.erase(0, colon + 2);
    }
    throw InputError(path + ":" + std::to_string(line) + ":" + std::to_string(column) +
      ": malformed JSON at line " + std::to_string(line) + ", column " + std::to_string(column) +
      ": " + reason);
  }
  catch (const json::exception& e)
  {
    // Valid syntax, but a value no double holds (1e999): out_of_range, with no position.
    std::string reason = e.what();
    const auto bracket = reason.find("] ");
    throw InputError(path + ": malformed JSON: " +
      (bracket == std::string::npos ? reason : reason.substr(bracket + 2)));
  }
}

nlohmann::json WithValidUtf8(nlohmann::json value)
{
  if (value.is_string())
  {
    return EscapeInvalidUtf8(value.get<std::string>());
  }
  if (value.is_array())
  {
    for (json& element : value)
    {
      element = WithValidUtf8(std::move(element));
    }
  }
  else if (value.is_object())
  {
    json escaped = json::object();
    for (auto& member : value.items())
    {
      escaped[EscapeInvalidUtf8(member.key())] = WithValidUtf8(std::move(member.value()));
    }
    return escaped;
  }
  return value;
}

nlohmann::json ParseOverrideValue(const std::string& key, const std::string& text)
{
  try
  {
    return ParseJsonText(text, key);
  }
  catch (const json::exception&)
  {
    // Not JSON: a number list, a non-finite number, or plain text.
  }
  if (text.empty())
  {
    return text;
  }
  std::vector<std::string> tokens;
  std::string token;
  std::istringstream in(text);
  while (std::getline(in, token, ','))
  {
    tokens.push_back(token);
  }
  if (!text.empty() && text.back() == ',')
  {
    tokens.emplace_back();
  }
  std::vector<double> numbers;
  for (const std::string& t : tokens)
  {
    double value = 0.0;
    if (!IsNumberToken(t, value))
    {
      return text;
    }
    numbers.push_back(value);
  }
  json array = json::array();
  for (double value : numbers)
  {
    if (!std::isfinite(value))
    {
      throw InputError(
        key + ": value \"" + text + "\" is not a finite number (NaN and infinity are not allowed)");
    }
    // Integral tokens stay integers so integer keys accept them.
    if (value == std::floor(value) && std::fabs(value) < 9.0e15)
    {
      array.push_back(static_cast<long long>(value));
    }
    else
    {
      array.push_back(value);
    }
  }
  if (array.size() == 1)
  {
    return array[0];
  }
  return array;
}

void ApplyOverride(nlohmann::json& document, const std::string& assignment)
{
  const auto equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0)
  {
    throw UsageError("--set expects KEY=VALUE (for example field.octaves=4), got \"" + assignment + "\"");
  }
  const std::string key = assignment.substr(0, equals);
  const std::vector<std::string> parts = SplitKey(key);
  for (const std::string& p : parts)
  {
    if (p.empty() || key.back() == '.')
    {
      throw UsageError("--set " + assignment + ": the key \"" + key + "\" has an empty part");
    }
  }
  SetDocumentValue(document, key, ParseOverrideValue(key, assignment.substr(equals + 1)), "--set");
}

void SetDocumentValue(
  nlohmann::json& document, const std::string& key, const nlohmann::json& value, const std::string& option)
{
  const std::vector<std::string> parts = SplitKey(key);
  json* node = &document;
  std::string path;
  for (const std::string& p : parts)
  {
    if (node->is_null())
    {
      *node = json::object(); // an intermediate object that did not exist yet
    }
    if (!node->is_object())
    {
      throw InputError(option + " " + key + ": " + (path.empty() ? "the scene" : path) + " is a " +
        node->type_name() + ", not an object, so it has no key \"" + p + "\"");
    }
    path += (path.empty() ? "" : ".") + p;
    node = &(*node)[p];
  }
  *node = value;
}

Scene SceneFromDocument(const nlohmann::json& document, const std::string& source,
  const std::string& baseDirectory, const std::vector<std::string>& overriddenKeys,
  const std::vector<SceneOverride>& optionKeys)
{
  Context context{ source, baseDirectory, {} };
  for (const std::string& key : overriddenKeys)
  {
    context.OverriddenKeys.emplace_back(key, "--set");
  }
  for (const SceneOverride& option : optionKeys)
  {
    context.OverriddenKeys.emplace_back(option.Key, option.Option);
  }
  if (!document.is_object())
  {
    throw InputError(source + ": a scene must be a JSON object, got " + Describe(document));
  }
  Scene scene;
  scene.Source = source;
  ReadObject(context, document, "", SceneKeys, scene);
  ResolveSkySun(document, scene);
  scene.Document = document;
  return scene;
}

const std::vector<std::string>& FieldFileKeyNames()
{
  static const std::vector<std::string> names = KeyNames(FieldFileKeys);
  return names;
}

namespace
{

// LoadScene and LoadFieldFileScene: the assignments, then the options, applied to `document`.
Scene SceneWithOverrides(json document,
  const std::string& source,
  const std::string& baseDirectory,
  const std::vector<std::string>& assignments,
  const std::vector<SceneOverride>& options)
{
  std::vector<std::string> keys;
  for (const std::string& assignment : assignments)
  {
    ApplyOverride(document, assignment);
    keys.push_back(assignment.substr(0, assignment.find('=')));
  }
  for (const SceneOverride& option : options)
  {
    SetDocumentValue(document, option.Key, option.Value, option.Option);
  }
  return SceneFromDocument(document, source, baseDirectory, keys, options);
}

} // namespace

Scene LoadScene(const std::string& path,
  const std::vector<std::string>& assignments,
  const std::vector<SceneOverride>& options)
{
  return SceneWithOverrides(path.empty() ? json::object() : ReadSceneDocument(path),
    path.empty() ? "default scene" : path,
    path.empty() ? "" : DirectoryOf(path),
    assignments,
    options);
}

Scene LoadFieldFileScene(const std::string& path,
  const std::vector<std::string>& assignments,
  const std::vector<SceneOverride>& options)
{
  // The operand is field.file, set last so --set field.file cannot replace it.
  std::vector<SceneOverride> all = options;
  all.push_back({ "field.file", path, "the field file operand" });
  return SceneWithOverrides(json::object(), path, "", assignments, all);
}

} // namespace cloudvis
