// The scene schema: each key of a scene file is one entry below, with its name, its type and
// range (the filters' own limits where a filter checks the parameter), the member it fills and
// its help text; its default is that member's value in a default-constructed Scene. A new key is
// a new entry. The functions after the tables read and write what is more than a list of keys:
// a field from a file or not, a shape list, a transfer-function preset, the typed objects
// (shapes, lights, backgrounds) whose "type" decides which keys they take.
//
// Every message has the shape "<source>: <dotted key>: <problem>" (Context::Fail); the wording
// of a value's problem is Schema.cxx's, once per kind of value.
#include "SceneSchema.h"

#include "Errors.h"
#include "FieldIO.h"
#include "Presets.h"
#include "SceneField.h"

#include "CloudMarchUniforms.h" // FloatLimit
#include "CloudTransferTable.h" // MaxTransferDensity, MinUnitDistance

#include <cmath>
#include <limits>

namespace cloudvis
{
namespace schema
{
namespace
{

// A bit per value of an enumeration, for the UsedBy masks of typed objects.
template<typename E>
constexpr unsigned Bit(E value)
{
  return 1u << static_cast<unsigned>(value);
}
constexpr unsigned Directional = Bit(0), Point = Bit(1); // the values of LightTypes()

std::string IndexKey(const std::string& key, size_t i)
{
  return key + "[" + std::to_string(i) + "]";
}

// A key checked but stored nowhere: a preset file's labels.
template<typename S>
Key<S> Label(const std::string& name)
{
  const ValueType type = Text();
  return Key<S>(
    name,
    type,
    [type](const Context& c, const json& v, const std::string& k, S&) { Check(c, type, v, k); },
    nullptr,
    "");
}

// Reads a typed object's members (a shape, a light): the "type" first, which decides the keys
// the object takes, then every member. `noun` follows the type's name in messages ("a point
// light"). Returns the type's value.
template<typename S>
int ReadTypedMembers(const Context& c,
  const json& v,
  const std::string& key,
  const Keys<S>& keys,
  const std::string& noun,
  S& target)
{
  const Key<S>& typeKey = *FindKey(keys, "type");
  typeKey.Read(c, v["type"], key + ".type", target);
  const int type = int(Check(c, typeKey.Type, v["type"], key + ".type"));
  const std::string a = "a " + v["type"].get<std::string>() + noun;
  const std::string allowed = "allowed keys for " + a + ": " + Join(KeyNames(keys, 1u << type));
  for (const auto& member : v.items())
  {
    const std::string memberKey = key + "." + member.key();
    const Key<S>* entry = FindKey(keys, member.key());
    if (!entry)
    {
      c.Fail(memberKey, "unknown key; " + allowed);
    }
    if (!(entry->UsedBy & (1u << type)))
    {
      c.Fail(memberKey, "not a parameter of " + a + "; " + allowed);
    }
    entry->Read(c, member.value(), memberKey, target);
  }
  return type;
}

// ---- field -----------------------------------------------------------------------------------

const char* const MorphName = "morph";

std::vector<std::string> AllShapeNames()
{
  std::vector<std::string> names = TextsOf(ShapeTypes());
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
    for (const Name& name : ShapeTypes())
    {
      if (v.get<std::string>() == name.Text)
      {
        shape.Type = static_cast<ShapeType>(name.Value);
        return true;
      }
    }
    c.Fail(
      key, "unknown shape \"" + v.get<std::string>() + "\"; allowed: " + Join(AllShapeNames()));
  }
  if (!v.is_object())
  {
    c.Fail(key,
      "expected a shape name (one of " + Join(AllShapeNames()) +
        "), a shape object or a list of them, got " + Describe(v));
  }
  if (!v.contains("type"))
  {
    c.Fail(key + ".type",
      "missing; a shape object needs a type (one of " + Join(TextsOf(ShapeTypes())) + ")");
  }
  if (v["type"] == MorphName)
  {
    c.Fail(key + ".type", "\"morph\" is not a shape type; write \"shape\": \"morph\" instead");
  }
  ReadTypedMembers(c, v, key, ShapeKeys(), "", shape);
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
    const std::string itemKey = list ? IndexKey(key, i) : key;
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

json WriteShapes(const FieldSpec& f)
{
  if (f.Description.Morph)
  {
    return MorphName;
  }
  json shapes = json::array();
  for (const Shape& shape : f.Description.Shapes)
  {
    shapes.push_back(WriteObject(ShapeKeys(), shape, Bit(shape.Type)));
  }
  return shapes;
}

// A field is read from a file or generated, never both: a section takes keys of one kind.
void CheckFieldKind(const Context& c, const json& v, const std::string& key)
{
  if (!v.is_object())
  {
    return; // ReadObject says what is wrong
  }
  const bool fromFile = v.contains("file");
  for (const auto& member : v.items())
  {
    const bool fileKey = FindKey(FieldFileKeys(), member.key()) != nullptr;
    if (fromFile && !fileKey && FindKey(GeneratedFieldKeys(), member.key()))
    {
      c.Fail(key + ".file",
        "cannot be combined with " + key + "." + member.key() +
          ": a field loaded from a file has no procedural parameters");
    }
    if (!fromFile && fileKey)
    {
      c.Fail(key + "." + member.key(),
        "says how a field file is read; give " + key +
          ".file too (or leave it out for a procedural field)");
    }
  }
}

void ReadField(const Context& c, const json& v, const std::string& key, Scene& scene)
{
  CheckFieldKind(c, v, key);
  ReadObject(c, v, key, FieldKeys(), scene.Field);
  if (scene.Field.FromFile())
  {
    // What the file's format decides, once every key is read (format may follow file): an
    // extension no format has, options the format does not take, a raw file without its layout.
    if (const auto problem = CheckFieldReadOptions(scene.Field.File, scene.Field.Read))
    {
      c.Fail(key + "." + problem->Key, problem->Problem);
    }
    return;
  }
  // The source's own checks, for what only a combination of keys can get wrong (a lacunarity
  // that turns negative after some octaves, noise coordinates beyond the lattice's range).
  const std::string problem = ValidateProceduralField(scene.Field);
  if (!problem.empty())
  {
    c.Fail(key, problem);
  }
}

json WriteField(const Scene& scene)
{
  const json units = WriteObject(FieldUnitKeys(), scene.Field);
  if (!scene.Field.FromFile())
  {
    json field = WriteObject(GeneratedFieldKeys(), scene.Field);
    field.update(units);
    return field;
  }
  // What reading the file again needs: the file, and the read options that differ from their
  // defaults.
  json field = WriteObject(FieldFileKeys(), scene.Field);
  const json defaults = WriteObject(FieldFileKeys(), FieldSpec{});
  for (const auto& option : defaults.items())
  {
    if (field.value(option.key(), json()) == option.value())
    {
      field.erase(option.key());
    }
  }
  field.update(units);
  return field;
}

// A choice whose member holds the chosen name itself (a format's Id, a raw type's name), empty
// when the key was not given.
template<typename S, typename Member>
Key<S> NameKey(const std::string& name, const ValueType& type, Member member, std::string help)
{
  return Key<S>(
    name,
    type,
    [member, type](const Context& c, const json& v, const std::string& k, S& s)
    { std::invoke(member, s) = NameOf(type.Names, Check(c, type, v, k).get<int>()); },
    [member](const S& s)
    {
      const std::string& text = std::invoke(member, const_cast<S&>(s));
      return text.empty() ? json() : json(text);
    },
    std::move(help));
}

// The formats of FieldFormats(), by their Ids, for field.format.
std::vector<Name> FieldFormatNames()
{
  std::vector<Name> names;
  for (const FieldFormat& format : FieldFormats())
  {
    names.push_back({ format.Id, int(names.size()), format.Name });
  }
  return names;
}

// "VTK XML image data `.vti`, ..., NetCDF (CF conventions) `.nc`/`.nc4`/`.cdf`, ...".
std::string FieldFormatsInWords()
{
  std::vector<std::string> formats;
  for (const FieldFormat& format : FieldFormats())
  {
    std::vector<std::string> extensions;
    for (const std::string& extension : format.Extensions)
    {
      extensions.push_back("`" + extension + "`");
    }
    formats.push_back(format.Name + " " + Join(extensions, "/"));
  }
  return Join(formats);
}

// Voxels along x, y and z, of a generated field and of a raw file.
ValueType Dimensions()
{
  return IntegerOrIntegersIn(3, 1, std::numeric_limits<int>::max(), "[nx, ny, nz]");
}

// ---- transfer_function -----------------------------------------------------------------------

// A preset file in cloudvis's format: the transfer function's own keys plus two labels.
const Keys<TransferFunctionSpec>& PresetKeys()
{
  static const Keys<TransferFunctionSpec> keys = {
    Label<TransferFunctionSpec>("name"),
    Label<TransferFunctionSpec>("description"),
    *FindKey(TransferFunctionKeys(), "opacity"),
    *FindKey(TransferFunctionKeys(), "color"),
    *FindKey(TransferFunctionKeys(), "unit_distance"),
  };
  return keys;
}

// transfer_function.preset fills the section first (from the defaults: what a preset leaves out
// keeps its default), then the section's explicit keys override it.
void ReadTransferFunction(const Context& c, const json& v, const std::string& key, Scene& scene)
{
  const Keys<TransferFunctionSpec>& keys = TransferFunctionKeys();
  if (v.is_object() && v.contains("preset"))
  {
    const std::string presetKey = key + ".preset";
    const std::string reference = Check(c, FindKey(keys, "preset")->Type, v["preset"], presetKey);
    std::string paraViewName;
    if (v.contains("preset_name"))
    {
      paraViewName =
        Check(c, FindKey(keys, "preset_name")->Type, v["preset_name"], key + ".preset_name");
    }
    std::string problem;
    try
    {
      const PresetDocument preset = ReadPreset(reference, c.BaseDirectory, paraViewName);
      const Context presetContext{ preset.Path, "", {} };
      TransferFunctionSpec fromPreset;
      ReadObject(presetContext, preset.Document, "", PresetKeys(), fromPreset);
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
  ReadObject(c, v, key, keys, scene.TransferFunction);
}

// A transfer function's points as the renderers can tabulate them: the densities' span must be
// a width float arithmetic holds (the renderers check the opacity and color points together).
std::string DensitiesWithinFloat(const json& points)
{
  const double first = points.front()[0].get<double>(), last = points.back()[0].get<double>();
  if (std::abs(first) <= MaxTransferDensity && std::abs(last) <= MaxTransferDensity &&
    last - first <= MaxTransferDensity)
  {
    return "";
  }
  return "its points span densities [" + FormatNumber(first) + ", " + FormatNumber(last) +
    "], beyond what float arithmetic holds (" + FormatNumber(MaxTransferDensity) + ")";
}

// preset and preset_name are read by ReadTransferFunction, before the other keys.
Key<TransferFunctionSpec> PresetReference(const std::string& name, ValueType type, std::string help)
{
  return Key<TransferFunctionSpec>(
    name,
    std::move(type),
    [](const Context&, const json&, const std::string&, TransferFunctionSpec&) {},
    nullptr,
    std::move(help));
}

// ---- camera ----------------------------------------------------------------------------------

void ReadCamera(const Context& c, const json& v, const std::string& key, Scene& scene)
{
  ReadObject(c, v, key, CameraKeys(), scene.Camera);
  // What can be checked before the field is known; the renderer checks the view direction
  // against view_up once the defaults are filled in.
  const CameraSpec& camera = scene.Camera;
  if (camera.Position && camera.Orbit)
  {
    c.Fail(key + ".orbit",
      "cannot be combined with " + key + ".position: give either the position " +
        "or the orbit around the focal point");
  }
  if (camera.Position && camera.FocalPoint && *camera.Position == *camera.FocalPoint)
  {
    c.Fail(
      key + ".position", "the camera position equals the focal point; the view has no direction");
  }
}

// ---- background ------------------------------------------------------------------------------

// [r, g, b] (a solid color, as before types existed) or {"type": ..., keys of that type}.
void ReadBackground(const Context& c, const json& v, const std::string& key, Scene& s)
{
  const Keys<Scene>& keys = BackgroundKeys();
  s.BackgroundStyle = BackgroundSpec{};
  if (v.is_array())
  {
    FindKey(keys, "color")->Read(c, v, key, s);
    return;
  }
  const std::string types = Join(TextsOf(BackgroundTypes()));
  if (!v.is_object())
  {
    c.Fail(key,
      "expected [r, g, b] or an object with a \"type\" (one of " + types + "), got " + Describe(v));
  }
  if (!v.contains("type"))
  {
    c.Fail(key + ".type", "missing; one of " + types);
  }
  const Key<Scene>& typeKey = *FindKey(keys, "type");
  const unsigned type = 1u << Check(c, typeKey.Type, v["type"], key + ".type").get<int>();
  const std::string a = "a " + v["type"].get<std::string>() + " background";
  const std::vector<std::string> allowed = KeyNames(keys, type);
  for (const auto& member : v.items())
  {
    const Key<Scene>* entry = FindKey(keys, member.key());
    if (!entry || !(entry->UsedBy & type))
    {
      c.Fail(key + "." + member.key(), "not a key of " + a + "; allowed keys: " + Join(allowed));
    }
    entry->Read(c, member.value(), key + "." + member.key(), s);
  }
  for (const Key<Scene>& entry : keys)
  {
    if ((entry.UsedBy & type) && entry.Type.Required && !v.contains(entry.Name))
    {
      c.Fail(key + "." + entry.Name,
        "missing; " + a + " needs " +
          Join(std::vector<std::string>(allowed.begin() + 1, allowed.end())));
    }
  }
}

json WriteBackground(const Scene& s)
{
  if (s.BackgroundStyle.Type == BackgroundType::Solid)
  {
    return ToJson(s.Background);
  }
  return WriteObject(BackgroundKeys(), s, Bit(s.BackgroundStyle.Type));
}

std::string NormalizeSun(Scene& s)
{
  std::array<double, 3>& sun = *s.BackgroundStyle.Sun;
  const double length = std::sqrt(sun[0] * sun[0] + sun[1] * sun[1] + sun[2] * sun[2]);
  if (!(length > 0.0) || !std::isfinite(length))
  {
    return "the direction toward the sun must not be zero";
  }
  for (double& x : sun)
  {
    x /= length;
  }
  return "";
}

// ---- render ----------------------------------------------------------------------------------

// render.derivative or render.march: the keys, then the lighting's own check (a value a float
// cannot hold, say 0.99999999 for g, passes the double range but not it).
Key<RenderSpec> LightingObject(const std::string& name,
  const Keys<LightingParameters>& (*keys)(),
  std::string help)
{
  return Key<RenderSpec>(
    name,
    CustomValue("object").DefaultIs("below"),
    [keys](const Context& c, const json& v, const std::string& k, RenderSpec& r)
    {
      ReadObject(c, v, k, keys(), r.Lighting);
      const std::string problem = ValidateLightingParameters(r.Lighting);
      if (!problem.empty())
      {
        c.Fail(k, problem);
      }
    },
    [keys](const RenderSpec& r) { return WriteObject(keys(), r.Lighting); },
    std::move(help),
    Inside(keys));
}

// ---- lights ----------------------------------------------------------------------------------

Light ReadLight(const Context& c, const json& v, const std::string& key)
{
  const std::string types = Join(TextsOf(LightTypes()));
  if (!v.is_object())
  {
    c.Fail(key, "expected a light object with a type (one of " + types + "), got " + Describe(v));
  }
  for (const Key<Light>& entry : LightKeys())
  {
    if (entry.Type.Required && !v.contains(entry.Name))
    {
      c.Fail(key + "." + entry.Name,
        "missing; a light needs a type (one of " + types + ") and a position");
    }
  }
  Light light;
  ReadTypedMembers(c, v, key, LightKeys(), " light", light);
  if (!light.Positional && light.Position == light.FocalPoint)
  {
    c.Fail(key + ".position",
      "a directional light's position equals its focal point; the " +
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
  if (v.size() > size_t(LightingLimits::MaxLights))
  {
    c.Fail(key,
      "at most " + std::to_string(LightingLimits::MaxLights) +
        " lights (the renderer's limit), got " + std::to_string(v.size()));
  }
  s.Lights.clear();
  for (size_t i = 0; i < v.size(); ++i)
  {
    s.Lights.push_back(ReadLight(c, v[i], IndexKey(key, i)));
  }
}

json WriteLights(const Scene& s)
{
  json lights = json::array();
  for (const Light& light : s.Lights)
  {
    lights.push_back(WriteObject(LightKeys(), light, light.Positional ? Point : Directional));
  }
  return lights;
}

// A section that is an object of keys and nothing more. `member` is a member of Scene or a
// function that returns a reference to one (Nested: the ambient section is the lighting's).
template<typename T, typename Member>
Key<Scene> Section(const std::string& name,
  Member member,
  const Keys<T>& (*keys)(),
  std::string help)
{
  return Key<Scene>(
    name,
    CustomValue("object").DefaultIs("below"),
    [member, keys](const Context& c, const json& v, const std::string& k, Scene& s)
    { ReadObject(c, v, k, keys(), std::invoke(member, s)); },
    [member, keys](const Scene& s)
    { return WriteObject(keys(), std::invoke(member, const_cast<Scene&>(s))); },
    std::move(help),
    Inside(keys));
}

} // namespace

// ==== the schema ==============================================================================

const std::vector<Name>& ShapeTypes()
{
  static const std::vector<Name> names = NamesOf<ShapeType>({ { "sphere", ShapeType::Sphere },
    { "box", ShapeType::Box },
    { "torus", ShapeType::Torus },
    { "cross", ShapeType::Cross },
    { "capsule", ShapeType::Capsule } });
  return names;
}

const std::vector<Name>& BackgroundTypes()
{
  static const std::vector<Name> names = {
    { "solid", int(BackgroundType::Solid), "one color" },
    { "gradient",
      int(BackgroundType::Gradient),
      "a vertical gradient, `bottom` at the bottom edge, `top` at the top (VTK's gradient "
      "background)" },
    { "sky", int(BackgroundType::Sky), "the article's sky, below" },
  };
  return names;
}

// As the flag vtkLight and cloudvis::Light call Positional.
const std::vector<Name>& LightTypes()
{
  static const std::vector<Name> names = {
    { "directional",
      0,
      "parallel light from `position` toward `focal_point`, the same everywhere" },
    { "point", 1, "light from `position` in all directions" },
  };
  return names;
}

// The lighting models by the one table of their names (CloudLightingParameters.h).
const std::vector<Name>& LightingModels()
{
  static const std::vector<Name> names = []
  {
    std::vector<Name> all;
    for (const LightingModelEntry& entry : LightingModelTable())
    {
      all.push_back({ entry.Name, int(entry.Model), entry.Description });
    }
    return all;
  }();
  return names;
}

const Keys<FieldSpec>& FieldKeys()
{
  static const Keys<FieldSpec> keys = []
  {
    Keys<FieldSpec> all = FieldFileKeys();
    all.insert(all.end(), GeneratedFieldKeys().begin(), GeneratedFieldKeys().end());
    all.insert(all.end(), FieldUnitKeys().begin(), FieldUnitKeys().end());
    return all;
  }();
  return keys;
}

// Keys of both kinds of field: what its values and world units mean (FieldUnits.h). Each is
// optional: absent, the file's declaration applies, else the default.
const Keys<FieldSpec>& FieldUnitKeys()
{
  using F = FieldSpec;
  using U = FieldUnits;
  static const Keys<F> keys = {
    { "quantity",
      ChoiceOf({ { "density",
                   int(FieldQuantity::Density),
                   "dimensionless; the transfer function says what it looks like" },
                 { "lwc", int(FieldQuantity::Lwc), "liquid water content in g/m^3" } })
        .DefaultIs("the file's, else `density`"),
      Nested(&F::Units, &U::Quantity),
      "what the values are: `info` reports the statistics in its units, and "
      "`transfer_function.extinction` `\"droplets\"` derives the extinction from it" },
    { "length_unit",
      ChoiceOf({ { "none", int(LengthUnit::None), "world units only" },
                 { "m", int(LengthUnit::Metre), "metres" },
                 { "km", int(LengthUnit::Kilometre), "kilometres" } })
        .DefaultIs("the file's, else `none`"),
      Nested(&F::Units, &U::Length),
      "how long one world unit (of `bounds`, a file's spacing and origin) is" },
    { "up",
      ChoiceOf({ { "x", 0, "" }, { "y", 1, "" }, { "z", 2, "" } })
        .DefaultIs("the file's, else `y`"),
      Nested(&F::Units, &U::Up),
      "the vertical axis of the lattice, for `info`'s cloud fraction per height, base, top and "
      "liquid water path; cloudvis's generated fields and cameras have y up" },
    { "effective_radius",
      NumberIn(Range{ 1e-3, 1e6 }).In("micrometres").DefaultIs("the file's, else `10`"),
      Nested(&F::Units, &U::EffectiveRadius),
      "the droplets' effective radius r_e of an lwc field: extinction = 3 lwc / (2 rho_w r_e)" },
  };
  return keys;
}

const Keys<FieldSpec>& FieldFileKeys()
{
  using F = FieldSpec;
  using R = FieldReadOptions;
  static const Keys<F> keys = {
    { "file",
      Path("the path of a field file (" + FieldFileExtensions() + ", a non-empty string)")
        .DefaultIs("none"),
      &F::File,
      "path of a field file: " + FieldFormatsInWords() +
        " ([data.md](data.md)); the extension in any case (`.VTI`), or any name with `format`; a "
        "relative path is relative to the folder of the scene file (to the current directory for "
        "the default scene)" },
    NameKey<F>("format",
      ChoiceOf(FieldFormatNames()).DefaultIs("by the extension"),
      Nested(&F::Read, &R::Format),
      "the file's format, whatever its extension"),
    { "array",
      NonEmptyText("the name of a grid, variable or point array (a non-empty string)")
        .DefaultIs("the format's default"),
      Nested(&F::Read, &R::Array),
      "the OpenVDB grid, NetCDF variable or `.vti`/`.pvti` point array to read; refused for a "
      "format that holds one array" },
    { "time_step",
      IntegerIn(0, std::numeric_limits<int>::max()).DefaultIs("`0`, the first"),
      Nested(&F::Read, &R::TimeStep),
      "the time step of a NetCDF file, from 0; refused for a format that holds one time step" },
    { "missing",
      ChoiceOf(
        { { "refuse",
            int(MissingValueRule::Refuse),
            "a file with missing values is refused, with their count and marking" },
          { "empty", int(MissingValueRule::Empty), "missing values are read as density 0" } })
        .DefaultIs("`refuse`"),
      Nested(&F::Read, &R::Missing),
      "what the values a NetCDF file marks as missing (`_FillValue`, `missing_value`, "
      "`valid_min`, `valid_max`, `valid_range`) become: cloudvis does not guess what a missing "
      "density is, so the file is refused unless this says to read them as empty space; `info` "
      "then reports their count. NetCDF only: refused for a format that marks no values as "
      "missing" },
    { "max_voxels",
      IntegerIn(1, 1LL << 62),
      Nested(&F::Read, &R::MaximumVoxels),
      "the most voxels the field may have once read (1024^3, a 4 GiB float field, by default); "
      "a file that needs more is refused, with its size, before anything is allocated" },
    { "raw",
      CustomValue("object").DefaultIs("none"),
      [](const Context& c, const json& v, const std::string& k, F& f)
      { ReadObject(c, v, k, RawKeys(), f.Read.Raw); },
      [](const F& f)
      { return f.Read.Raw.Dimensions[0] > 0 ? WriteObject(RawKeys(), f.Read.Raw) : json(); },
      "a raw file's layout ([below](#loading-a-field)); required for a raw file, refused for any "
      "other format",
      Inside(RawKeys) },
  };
  return keys;
}

const Keys<RawLayout>& RawKeys()
{
  using R = RawLayout;
  const auto types = []
  {
    std::vector<Name> names;
    for (const std::string& type : RawTypeNames())
    {
      names.push_back({ type, int(names.size()), "" });
    }
    return ChoiceOf(names);
  };
  const auto byteOrder = []
  {
    ValueType t = ChoiceOf({ { "little", 0, "" }, { "big", 1, "" } });
    t.StrictNames = true;
    return t;
  };
  static const Keys<R> keys = {
    { "dimensions",
      Dimensions().Mandatory(),
      &R::Dimensions,
      "voxels along x, y and z (one integer for a cube)" },
    NameKey<R>("type", types(), &R::Type, "the type of every voxel"),
    { "byte_order", byteOrder(), &R::BigEndian, "of every voxel of more than one byte" },
    { "spacing", NumbersIn(3, Positive).In("world units"), &R::Spacing, "" },
    { "origin",
      NumbersIn(3, AnyNumber).In("world units"),
      &R::Origin,
      "the position of the first voxel" },
    { "header_bytes",
      IntegerIn(0, 1LL << 62),
      &R::HeaderBytes,
      "bytes before the first voxel, skipped" },
  };
  return keys;
}

const Keys<FieldSpec>& GeneratedFieldKeys()
{
  using F = FieldSpec;
  using D = FieldDescription;
  using N = noise::FbmParameters;
  static const Keys<F> keys = {
    { "dimensions",
      Dimensions(),
      &F::Dimensions,
      "the field (4 bytes per voxel) must fit in the memory available when it is generated "
      "whole; generated in pieces (`generate -o FIELD.pvti`), each piece must" },
    { "bounds",
      NumbersIn(6, AnyNumber, "[xmin, xmax, ymin, ymax, zmin, zmax]"),
      &F::Bounds,
      "min < max on each axis",
      ~0u,
      [](F& f) -> std::string
      {
        for (int a = 0; a < 3; ++a)
        {
          if (!(f.Bounds[2 * a] < f.Bounds[2 * a + 1]))
          {
            return std::string("bounds along ") + "xyz"[a] + " must increase (min < max), got [" +
              FormatNumber(f.Bounds[2 * a]) + ", " + FormatNumber(f.Bounds[2 * a + 1]) + "]";
          }
        }
        return "";
      } },
    { "density_model",
      ChoiceOf(NamesOf<DensityModel>({ { "sdf_plus_fbm", DensityModel::SdfPlusFbm },
        { "fbm_falloff", DensityModel::FbmFalloff },
        { "constant", DensityModel::Constant },
        { "cloud", DensityModel::Cloud } })),
      Nested(&F::Description, &D::Model),
      "see [Density models](#density-models)" },
    { "density_scale",
      NumberIn(NonNegative),
      Nested(&F::Description, &D::DensityScale),
      "multiplies the density" },
    { "falloff_width",
      NumberIn(Positive),
      Nested(&F::Description, &D::FalloffWidth),
      "used by `fbm_falloff`" },
    { "shape",
      CustomValue("string, object, or array of strings/objects")
        .DefaultIs("`\"sphere\"` (radius 1)"),
      ReadShapes,
      WriteShapes,
      "see [Shapes](#shapes)" },
    { "blend",
      ChoiceOf(NamesOf<ShapeBlend>(
        { { "union", ShapeBlend::Union }, { "smooth_union", ShapeBlend::SmoothUnion } })),
      Nested(&F::Description, &D::Blend),
      "how a list of shapes is combined" },
    { "blend_radius",
      NumberIn(NonNegative),
      Nested(&F::Description, &D::BlendRadius),
      "used by `smooth_union`" },
    { "noise",
      ChoiceOf(NamesOf<noise::NoiseType>({ { "none", noise::NoiseType::None },
        { "white", noise::NoiseType::White },
        { "value", noise::NoiseType::Value },
        { "perlin", noise::NoiseType::Perlin },
        { "worley", noise::NoiseType::Worley },
        { "inverted_worley", noise::NoiseType::InvertedWorley },
        { "perlin_worley", noise::NoiseType::PerlinWorley } })),
      Nested(&F::Description, &D::Noise, &N::Type),
      "see [Noise and fBm](#noise-and-fbm)" },
    { "octaves",
      IntegerIn(1, noise::MaxOctaves),
      Nested(&F::Description, &D::Noise, &N::Octaves),
      "" },
    { "frequency",
      NumberIn(Range{ 0.0, noise::MaxFrequency, true }),
      Nested(&F::Description, &D::Noise, &N::Frequency),
      "" },
    { "lacunarity",
      NumberIn(Positive),
      Nested(&F::Description, &D::Noise, &N::Lacunarity),
      "with `lacunarity_increment`, every octave's factor must stay > 0" },
    { "lacunarity_increment",
      NumberIn(AnyNumber),
      Nested(&F::Description, &D::Noise, &N::LacunarityIncrement),
      "" },
    { "gain", NumberIn(NonNegative), Nested(&F::Description, &D::Noise, &N::Gain), "" },
    { "amplitude", NumberIn(NonNegative), Nested(&F::Description, &D::Noise, &N::Amplitude), "" },
    { "seed",
      IntegerIn(0, std::numeric_limits<std::uint32_t>::max()),
      Nested(&F::Description, &D::Noise, &N::Seed),
      "" },
    { "noise_period",
      IntegerIn(0, noise::MaxPeriod),
      Nested(&F::Description, &D::Noise, &N::Period),
      "lattice cells of the first octave after which the noise repeats (0: never); needs a "
      "whole-number `lacunarity` and `lacunarity_increment` 0; see [Noise and "
      "fBm](#noise-and-fbm)" },
    { "wind",
      NumbersIn(3, AnyNumber),
      Nested(&F::Description, &D::Wind),
      "world units per second" },
    { "cloud",
      CustomValue("object").DefaultIs("the defaults of [field.cloud](#fieldcloud)"),
      [](const Context& c, const json& v, const std::string& k, F& f)
      { ReadObject(c, v, k, CloudKeys(), f); },
      [](const F& f)
      { return f.Description.Model == DensityModel::Cloud ? WriteObject(CloudKeys(), f) : json(); },
      "the layer, cloud type, coverage and noises of the `cloud` density model; see "
      "[Cloud layers](#cloud-layers)",
      Inside(CloudKeys) },
    { "time", NumberIn(AnyNumber), &F::Time, "seconds" },
  };
  return keys;
}

const Keys<FieldSpec>& CloudKeys()
{
  using F = FieldSpec;
  using D = FieldDescription;
  using L = CloudLayer;
  static const Keys<F> keys = {
    { "type",
      ChoiceOf({ { "stratus", int(CloudType::Stratus), "a thin flat sheet" },
        { "stratocumulus", int(CloudType::Stratocumulus), "a deck of rolls and lumps" },
        { "cumulus", int(CloudType::Cumulus), "a flat base under a rounded, billowing top" },
        { "cumulonimbus", int(CloudType::Cumulonimbus), "a tower to the top, with `anvil`" } }),
      Nested(&F::Description, &D::Layer, &L::Type),
      "the height profile" },
    { "base",
      NumberIn(AnyNumber).In("world units"),
      Nested(&F::Description, &D::Layer, &L::Base),
      "the altitude (y) of the cloud base; below `top`" },
    { "top",
      NumberIn(AnyNumber).In("world units"),
      Nested(&F::Description, &D::Layer, &L::Top),
      "the altitude (y) of the cloud tops" },
    { "coverage",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::Coverage),
      "how much of the sky the weather map fills (a threshold on it), or the shapes' strength" },
    { "coverage_map",
      CustomValue("`\"shapes\"`, `\"noise\"` or the path of a 2-D image or field file")
        .DefaultIs("`\"shapes\"`"),
      [](const Context& c, const json& v, const std::string& k, F& f)
      {
        if (!v.is_string() || v.get<std::string>().empty())
        {
          c.Fail(k, "expected \"shapes\", \"noise\" or a file path, got " + Describe(v));
        }
        const std::string text = v.get<std::string>();
        f.CoverageMapFile.clear();
        if (text == "shapes" || text == "noise")
        {
          f.Description.Layer.Source =
            text == "shapes" ? CoverageSource::Shapes : CoverageSource::Noise;
          return;
        }
        f.Description.Layer.Source = CoverageSource::Map;
        f.CoverageMapFile =
          text[0] != '/' && !c.BaseDirectory.empty() ? c.BaseDirectory + "/" + text : text;
      },
      [](const F& f) -> json
      {
        switch (f.Description.Layer.Source)
        {
          case CoverageSource::Shapes:
            return "shapes";
          case CoverageSource::Noise:
            return "noise";
          case CoverageSource::Map:
            break;
        }
        return f.CoverageMapFile;
      },
      "`shapes`: the field's shapes, softened over `falloff_width`, are one cloud; `noise`: a "
      "procedural weather map of many clouds (`map_scale`, `map_octaves`, `map_gain`); a path "
      "(relative to the scene file's folder): a 2-D image (PNG, its first channel) or a 2-D "
      "field file stretched over the field's x and z bounds, 8-bit 255 or float 1 meaning full "
      "coverage" },
    { "map_scale",
      NumberIn(Positive).In("world units"),
      Nested(&F::Description, &D::Layer, &L::MapScale),
      "the size of the weather map's largest features" },
    { "map_octaves",
      IntegerIn(1, noise::MaxOctaves),
      Nested(&F::Description, &D::Layer, &L::MapOctaves),
      "" },
    { "map_gain",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::MapGain),
      "amplitude factor between the map's octaves: higher, rougher cloud edges seen from above "
      "(the area-perimeter dimension of the map's clouds: about 1.27 at 0.6, 1.34 at 0.7, 1.41 at "
      "0.8)" },
    { "shape_scale",
      NumberIn(Positive).In("world units"),
      Nested(&F::Description, &D::Layer, &L::ShapeScale),
      "the length over which the shape noise (the cloud's masses) repeats" },
    { "detail_scale",
      NumberIn(Positive).In("world units"),
      Nested(&F::Description, &D::Layer, &L::DetailScale),
      "the length over which the detail noise (the billows) repeats" },
    { "erosion",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::Erosion),
      "how deep the detail noise eats into the edges" },
    { "curl",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::Curl),
      "curl-noise turbulence of the detail, strongest at the base" },
    { "anvil",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::Anvil),
      "how far a cumulonimbus spreads at its top" },
    { "shear",
      NumbersIn(2, AnyNumber, "[x, z]"),
      Nested(&F::Description, &D::Layer, &L::Shear),
      "horizontal displacement per unit of height above the base: the cloud leans" },
  };
  return keys;
}

const Keys<Shape>& ShapeKeys()
{
  static const Keys<Shape> keys = {
    { "type", ChoiceOf(ShapeTypes()).Mandatory(), &Shape::Type, "" },
    { "center", NumbersIn(3, AnyNumber), &Shape::Center, "" },
    { "rotation",
      NumbersIn(3, AnyNumber).In("degrees"),
      &Shape::RotationDegrees,
      "applied about x, then y, then z" },
    { "scale", NumberIn(Positive), &Shape::Scale, "" },
    { "radius",
      NumberIn(NonNegative),
      &Shape::Radius,
      "",
      Bit(ShapeType::Sphere) | Bit(ShapeType::Capsule) },
    { "half_size", NumbersIn(3, NonNegative), &Shape::HalfSize, "", Bit(ShapeType::Box) },
    { "major_radius",
      NumberIn(NonNegative),
      &Shape::MajorRadius,
      "centre of the tube to the axis (the torus lies around y)",
      Bit(ShapeType::Torus) },
    { "minor_radius",
      NumberIn(NonNegative),
      &Shape::MinorRadius,
      "radius of the tube",
      Bit(ShapeType::Torus) },
    { "arm_width",
      NumberIn(NonNegative),
      &Shape::ArmWidth,
      "half-width of the three bars",
      Bit(ShapeType::Cross) },
    { "arm_length",
      NumberIn(NonNegative),
      &Shape::ArmLength,
      "half-length of the three bars",
      Bit(ShapeType::Cross) },
    { "end_a",
      NumbersIn(3, AnyNumber),
      &Shape::EndA,
      "different from `end_b`",
      Bit(ShapeType::Capsule) },
    { "end_b", NumbersIn(3, AnyNumber), &Shape::EndB, "", Bit(ShapeType::Capsule) },
  };
  return keys;
}

const Keys<TransferFunctionSpec>& TransferFunctionKeys()
{
  using T = TransferFunctionSpec;
  const std::string densities = "densities within +-" + FormatNumber(MaxTransferDensity) +
    " (float's range), spanning at most that";
  static const Keys<T> keys = {
    { "opacity",
      PointsIn(2, UnitInterval, "[density, opacity]").CheckedBy(DensitiesWithinFloat),
      &T::Opacity,
      densities },
    { "color",
      PointsIn(4, UnitInterval, "[density, r, g, b]").CheckedBy(DensitiesWithinFloat),
      &T::Color,
      densities },
    { "unit_distance",
      NumberIn(Range{ MinUnitDistance() }).In("world units"),
      &T::UnitDistance,
      "the distance over which `opacity` applies; the bound keeps the extinction of opacity 1, "
      "-ln(1e-4) / `unit_distance`, within float range" },
    { "extinction",
      ChoiceOf(
        { { "opacity", int(T::ExtinctionRule::Opacity), "from `opacity` per `unit_distance`" },
          { "droplets",
            int(T::ExtinctionRule::Droplets),
            "the extinction of cloud droplets, 3 lwc / (2 rho_w r_e) per metre (rho_w = 10^6 "
            "g/m^3, r_e = `field.effective_radius`), converted to world units; needs "
            "`field.quantity` `\"lwc\"` and `field.length_unit` `\"m\"` or `\"km\"`; "
            "`opacity` and `unit_distance` are then unused" } }),
      &T::Extinction,
      "where the extinction comes from; `color` gives the albedo either way" },
    { "lwc_max",
      NumberIn(Positive).In("g/m^3"),
      &T::LwcMax,
      "with `extinction` `\"droplets\"`: the largest liquid water content the table resolves; "
      "denser voxels get its extinction" },
    PresetReference("preset",
      NonEmptyText("a preset name or the path of a .json file").DefaultIs("none"),
      "a shipped preset's name, or the path of a preset file (relative to the scene file's "
      "folder); [below](#transfer-function-presets)"),
    PresetReference("preset_name",
      NonEmptyText("the Name of a preset in the ParaView file")
        .DefaultIs("the file's first preset"),
      "with a ParaView file holding several presets: the `Name` of the one to use; an error with "
      "anything else"),
  };
  return keys;
}

const Keys<CameraSpec>& CameraKeys()
{
  using C = CameraSpec;
  static const Keys<C> keys = {
    { "position",
      NumbersIn(3, AnyNumber).DefaultIs("`focal_point + (0, 0, d)`: looking along -z"),
      &C::Position,
      "not equal to `focal_point`" },
    { "focal_point",
      NumbersIn(3, AnyNumber).DefaultIs("the centre of the field's bounds"),
      &C::FocalPoint,
      "" },
    { "view_up",
      NumbersIn(3, AnyNumber),
      &C::ViewUp,
      "not zero, not parallel to the view direction",
      ~0u,
      [](C& camera) -> std::string
      {
        const std::array<double, 3>& u = camera.ViewUp;
        return u[0] * u[0] + u[1] * u[1] + u[2] * u[2] == 0.0
          ? "the view-up vector must not be zero"
          : "";
      } },
    { "view_angle",
      NumberIn(Range{ 0.0, 180.0, true, true }).In("degrees"),
      &C::ViewAngle,
      "the vertical angle of view" },
    { "orbit",
      CustomValue("object `{\"azimuth\", \"elevation\", \"distance\"}`").DefaultIs("none"),
      [](const Context& c, const json& v, const std::string& k, C& camera)
      {
        OrbitSpec orbit;
        ReadObject(c, v, k, OrbitKeys(), orbit);
        camera.Orbit = orbit;
      },
      [](const C& camera)
      { return camera.Orbit ? WriteObject(OrbitKeys(), *camera.Orbit) : json(); },
      "places the camera on a sphere around `focal_point`; cannot be combined with `position`",
      Inside(OrbitKeys) },
  };
  return keys;
}

const Keys<OrbitSpec>& OrbitKeys()
{
  using O = OrbitSpec;
  static const Keys<O> keys = {
    { "azimuth",
      NumberIn(AnyNumber).In("degrees"),
      &O::Azimuth,
      "about the y axis, from +z toward +x" },
    { "elevation", NumberIn(Range{ -90.0, 90.0, true, true }).In("degrees"), &O::Elevation, "" },
    { "distance",
      NumberIn(Positive).In("world units").DefaultIs("`d` above: the field fits the view"),
      &O::Distance,
      "" },
  };
  return keys;
}

const Keys<Scene>& BackgroundKeys()
{
  const auto solid = Bit(BackgroundType::Solid), gradient = Bit(BackgroundType::Gradient),
             sky = Bit(BackgroundType::Sky);
  static const Keys<Scene> keys = {
    { "type",
      ChoiceOf(BackgroundTypes()).Mandatory(),
      Nested(&Scene::BackgroundStyle, &BackgroundSpec::Type),
      "" },
    { "color", NumbersIn(3, UnitInterval).Mandatory(), &Scene::Background, "", solid },
    { "top",
      NumbersIn(3, UnitInterval).Mandatory(),
      Nested(&Scene::BackgroundStyle, &BackgroundSpec::Top),
      "",
      gradient },
    { "bottom", NumbersIn(3, UnitInterval).Mandatory(), &Scene::Background, "", gradient },
    { "sun",
      NumbersIn(3, AnyNumber),
      Nested(&Scene::BackgroundStyle, &BackgroundSpec::Sun),
      "a direction toward the sun, any length but not zero",
      sky,
      NormalizeSun },
  };
  return keys;
}

const Keys<RenderSpec>& RenderKeys()
{
  using R = RenderSpec;
  static const Keys<R> keys = {
    { "lighting",
      ChoiceOf(LightingModels()),
      Nested(&R::Lighting, &LightingParameters::Model),
      "see [lighting.md](lighting.md). `--lighting` overrides it." },
    { "step",
      NumberIn(NonNegative).In("world units"),
      &R::Step,
      "between samples along a ray; `0` means automatic: one voxel (the smallest spacing of the "
      "field). A ray takes at most " +
        std::to_string(MaxSamplesPerRay) +
        " samples: a step needing more along the field's longest diagonal is refused once the "
        "field is known, with the smallest step it allows" },
    { "jitter",
      Boolean(),
      &R::Jitter,
      "offset each ray's start by blue noise, turning banding into fine noise that accumulation "
      "averages away" },
    { "resolution_scale",
      NumberIn(Range{ 0.25, 1.0 }),
      &R::ResolutionScale,
      "the march runs at this fraction of the image's width and height and is upsampled "
      "(Catmull-Rom)" },
    { "accumulate",
      IntegerIn(1, 65536),
      &R::Accumulate,
      "frames averaged into a still (with `jitter: false` one frame is rendered: every frame "
      "would be the same)" },
    { "spp",
      IntegerIn(2, 1 << 24),
      &R::SamplesPerPixel,
      "`pathtrace`: paths averaged per pixel of a still (its noise falls as 1 / sqrt(spp)); "
      "`--spp` overrides it" },
    { "skip_empty_space",
      Boolean(),
      &R::SkipEmptySpace,
      "leap over empty bricks; changes the speed, never the image" },
    { "size",
      IntegersIn(2, 16, 16384, "[width, height]").In("pixels"),
      &R::Size,
      "`--size WxH` overrides it" },
    { "png_bits",
      IntegerOneOf({ 8, 16 }),
      &R::PngBits,
      "bits per PNG channel ([export.md](export.md)); `--png-bits` overrides it" },
    { "exr_type",
      []
      {
        ValueType t = ChoiceOf({ { "half", 1, "" }, { "float", 0, "" } });
        t.StrictNames = true;
        return t;
      }(),
      &R::ExrHalf,
      "pixel type of every EXR channel; `--exr-half` sets `\"half\"`" },
    { "reprojection",
      Boolean(),
      &R::Reprojection,
      "`cloudvis view`: while the camera moves, blend the last image, reprojected to the new "
      "view, into each reduced-resolution frame where it still holds ([viewer.md](viewer.md)); "
      "stills and exports are unchanged" },
    LightingObject("derivative",
      DerivativeKeys,
      "the derivative model's parameters ([below](#renderderivative-and-rendermarch))"),
    LightingObject("march",
      MarchKeys,
      "the light march's parameters ([below](#renderderivative-and-rendermarch))"),
  };
  return keys;
}

// The ranges are the filters' (LightingLimits, ValidateLightingParameters in CloudLighting.h),
// which also checks the whole after these keys.
const Keys<LightingParameters>& DerivativeKeys()
{
  using P = LightingParameters;
  static const Keys<P> keys = {
    { "distance",
      NumberIn(NonNegative).In("world units"),
      &P::DerivativeDistance,
      "the finite-difference distance `h` toward each light; `0` means automatic: 4 voxels (the "
      "smallest spacing)" },
  };
  return keys;
}

const Keys<LightingParameters>& MarchKeys()
{
  using P = LightingParameters;
  using L = LightingLimits;
  const Range g{ -1.0, 1.0, true, true };
  static const Keys<P> keys = {
    { "light_steps",
      IntegerIn(L::MinLightSteps, L::MaxLightSteps),
      &P::LightSteps,
      "segments of the march toward each light, spanning the way to the volume's exit (or a point "
      "light)" },
    { "light_step",
      NumberIn(NonNegative).In("world units"),
      &P::LightStep,
      "shortest first segment (a short way takes fewer segments); `0` means automatic: 2 voxels" },
    { "light_step_growth",
      NumberIn(Range{ L::MinLightStepGrowth, L::MaxLightStepGrowth }),
      &P::LightStepGrowth,
      "each segment is this much longer than the one before (1: uniform)" },
    { "transmittance",
      ChoiceOf(NamesOf<LightTransmittance>(
        { { "volumes", LightTransmittance::Volumes }, { "nested", LightTransmittance::Nested } })),
      &P::Transmittance,
      "where the optical depth toward each light comes from: `\"volumes\"`, per-light volumes at "
      "half the field's resolution computed when the field, transfer function or lights change "
      "(fast), or `\"nested\"`, the march above at every sample (the quality setting); see "
      "[lighting.md](lighting.md#light-volumes)" },
    { "g1",
      NumberIn(g),
      &P::PhaseG1,
      "Henyey-Greenstein eccentricity of the forward lobe (> 0 scatters forward)" },
    { "g2", NumberIn(g), &P::PhaseG2, "eccentricity of the second (backward) lobe" },
    { "lobe_weight",
      NumberIn(UnitInterval),
      &P::PhaseLobeWeight,
      "weight of the first lobe (1: one lobe)" },
    { "multiple_scattering",
      IntegerIn(0, L::MaxMultipleScatteringOctaves),
      &P::MultipleScatteringOctaves,
      "octaves of approximate multiple scattering added to single scattering (0: none)" },
    { "scattering_falloff",
      NumberIn(UnitInterval),
      &P::ScatteringFalloff,
      "`a`: each octave scatters `a` times less" },
    { "extinction_falloff",
      NumberIn(UnitInterval),
      &P::ExtinctionFalloff,
      "`b`: each octave sees `b` times less extinction toward the light" },
    { "eccentricity_falloff",
      NumberIn(UnitInterval),
      &P::EccentricityFalloff,
      "`c`: each octave's phase is `c` times less eccentric" },
    { "powder",
      NumberIn(UnitInterval),
      &P::PowderStrength,
      "the \"powder\" darkening of thin, lit regions. **Not physical**: it removes light single "
      "scattering says is there; an artistic, labelled choice" },
  };
  return keys;
}

const Keys<Light>& LightKeys()
{
  static const Keys<Light> keys = {
    { "type", ChoiceOf(LightTypes()).Mandatory(), &Light::Positional, "" },
    { "position",
      NumbersIn(3, AnyNumber).Mandatory(),
      &Light::Position,
      "for a directional light, not equal to `focal_point`" },
    { "focal_point",
      NumbersIn(3, AnyNumber),
      &Light::FocalPoint,
      "directional lights only (on a point light it is an error)",
      Directional },
    { "color", NumbersIn(3, UnitInterval), &Light::Color, "" },
    { "intensity",
      NumberIn(Range{ 0.0, FloatLimit, false, true }),
      &Light::Intensity,
      "multiplies `color`; the renderers also refuse a light bright enough to overflow float "
      "arithmetic in the light it scatters (with `render.march`'s phase function)" },
    { "attenuation",
      NumbersIn(3, NonNegative, "[a0, a1, a2]"),
      &Light::Attenuation,
      "point lights only; not all 0; the light falls off as `1 / (a0 + a1 r + a2 r^2)` at "
      "distance `r` (the default is the inverse square)",
      Point,
      [](Light& l) -> std::string
      {
        return l.Attenuation == glm::vec3(0.0f)
          ? "the attenuation [a0, a1, a2] must not be all zero (the falloff is 1 / (a0 + a1 r + "
            "a2 r^2))"
          : "";
      } },
  };
  return keys;
}

const Keys<LightingParameters>& AmbientKeys()
{
  using P = LightingParameters;
  static const Keys<P> keys = {
    { "color", NumbersIn(3, UnitInterval), &P::AmbientColor, "" },
    { "strength", NumberIn(NonNegative), &P::AmbientStrength, "multiplies `color`" },
  };
  return keys;
}

const Keys<Scene>& SceneSections()
{
  static const Keys<Scene> keys = {
    { "description",
      Text().DefaultIs("none"),
      &Scene::Description,
      "free text, shown nowhere yet; say what the scene is for" },
    { "field",
      CustomValue("object").DefaultIs("the default scene's field"),
      ReadField,
      WriteField,
      "the density field ([below](#the-field-section))",
      Inside(FieldKeys) },
    { "transfer_function",
      CustomValue("object").DefaultIs("below"),
      ReadTransferFunction,
      [](const Scene& s) { return WriteObject(TransferFunctionKeys(), s.TransferFunction); },
      "what density looks like: opacity and color ([below](#the-transfer_function-section))",
      Inside(TransferFunctionKeys) },
    { "camera",
      CustomValue("object").DefaultIs("framing the field"),
      ReadCamera,
      [](const Scene& s) { return WriteObject(CameraKeys(), s.Camera); },
      "where the view is from ([below](#the-camera-section))",
      Inside(CameraKeys) },
    { "background",
      CustomValue("`[r, g, b]` (each in [0, 1]) or an object with a `type`"),
      ReadBackground,
      WriteBackground,
      "what is behind the cloud: a color, a gradient or the article's sky "
      "([below](#the-background-section))",
      Inside(BackgroundKeys) },
    Section(
      "render", &Scene::Render, RenderKeys, "how the image is made ([below](#the-render-section))"),
    { "lights",
      CustomValue("list of objects").DefaultIs("one white sun"),
      ReadLights,
      WriteLights,
      "the light sources of the `derivative` and `march` models "
      "([below](#the-lights-section))" },
    Section("ambient",
      Nested(&Scene::Render, &RenderSpec::Lighting),
      AmbientKeys,
      "isotropic, unshadowed light those models add ([below](#the-ambient-section))"),
    ViewSection(),
  };
  return keys;
}

void ResolveDroplets(const Context& c, Scene& s)
{
  TransferFunctionSpec& t = s.TransferFunction;
  if (t.Extinction != TransferFunctionSpec::ExtinctionRule::Droplets)
  {
    return;
  }
  const FieldUnits& units = s.Field.Units;
  if (units.Quantity != FieldQuantity::Lwc)
  {
    c.Fail("transfer_function.extinction",
      "\"droplets\" derives the extinction from liquid water content: it needs field.quantity "
      "\"lwc\"");
  }
  if (!units.Length || *units.Length == LengthUnit::None)
  {
    c.Fail("transfer_function.extinction",
      "\"droplets\" gives an extinction per metre: it needs field.length_unit \"m\" or "
      "\"km\" to convert it to world units");
  }
  t.DropletExtinctionPerLwc =
    DropletExtinctionPerMetre(1.0, units.EffectiveRadius.value_or(DefaultEffectiveRadius)) *
    MetresPerUnit(*units.Length);
}

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
        const glm::dvec3 toward = DirectionTowardLight(light);
        background.Sun = std::array<double, 3>{ { toward.x, toward.y, toward.z } };
        return;
      }
    }
  }
  const std::array<double, 3>& d = BackgroundSpec::DefaultSun;
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  background.Sun = std::array<double, 3>{ { d[0] / length, d[1] / length, d[2] / length } };
}

} // namespace schema
} // namespace cloudvis
