// The code of the scene schema: reading and writing what is more than a list of keys (a field
// from a file or not, a shape list, a transfer-function preset, the camera, the typed objects
// whose "type" decides which keys they take: shapes, lights, backgrounds), and what is resolved
// once the whole scene is read (the sky's sun, the droplets' extinction). The tables that name
// these functions are SceneSchema.cxx's.
//
// Every message has the shape "<source>: <dotted key>: <problem>" (Context::Fail); the wording
// of a value's problem is Schema.cxx's, once per kind of value.
#include "SceneSchemaReaders.h"

#include "Errors.h"
#include "FieldIO.h"
#include "Presets.h"
#include "SceneField.h"

#include "CloudTransferTable.h" // MaxTransferDensity

#include <glm/glm.hpp>

#include <cmath>
#include <limits>

namespace cloudvis
{
namespace schema
{

namespace
{
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

} // namespace

// ---- field -----------------------------------------------------------------------------------

namespace
{
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

} // namespace

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

namespace
{
// A field is read from a file or generated, never both: a section takes keys of one kind (and
// the units, and max_voxels, which caps a generated field's "auto" dimensions).
void CheckFieldKind(const Context& c, const json& v, const std::string& key)
{
  if (!v.is_object())
  {
    return; // ReadObject says what is wrong
  }
  const bool fromFile = v.contains("file");
  for (const auto& member : v.items())
  {
    const bool fileKey =
      FindKey(FieldFileKeys(), member.key()) != nullptr && member.key() != "max_voxels";
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

} // namespace

void ReadField(const Context& c, const json& v, const std::string& key, Scene& scene)
{
  CheckFieldKind(c, v, key);
  ReadObject(c, v, key, FieldKeys(), scene.Field);
  if (v.is_object() && v.contains("cloud") && scene.Field.Description.Model != DensityModel::Cloud)
  {
    c.Fail(key + ".cloud",
      "applies to the density model \"cloud\" only, and this field's " + key +
        ".density_model is another: set it to \"cloud\", or leave " + key + ".cloud out");
  }
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
  // The coverage map's file, read once here when the cloud model will use it; then the source's
  // own checks, for what only a combination of keys can get wrong (a lacunarity that turns
  // negative after some octaves, noise coordinates beyond the lattice's range).
  LoadCoverageMap(scene.Field);
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

std::vector<Name> FieldFormatNames()
{
  std::vector<Name> names;
  for (const FieldFormat& format : FieldFormats())
  {
    names.push_back({ format.Id, int(names.size()), format.Name });
  }
  return names;
}

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

ValueType Dimensions()
{
  return IntegerOrIntegersIn(3, 1, std::numeric_limits<int>::max(), "[nx, ny, nz]");
}

// ---- transfer_function -----------------------------------------------------------------------

namespace
{
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

} // namespace

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

std::string OctaveCountMoved(const json& value)
{
  if (!value.is_number())
  {
    return "";
  }
  std::string names;
  for (const MultipleScatteringModelEntry& entry : MultipleScatteringModelTable())
  {
    names += std::string(names.empty() ? "" : " or ") + "\"" + entry.Name + "\"";
  }
  return "the number " + value.dump() + ": this key is now " + names +
    "; the number of octaves is render.march.octaves (what " + value.dump() + " meant: \"" +
    MultipleScatteringModelName(MultipleScatteringModel::Octaves) +
    "\" here and render.march.octaves " + value.dump() + ")";
}

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

namespace
{
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

} // namespace

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

// ---- resolved once the whole scene is read ---------------------------------------------------

namespace
{
// " (neither the scene nor rico.nc declares it)", " (rico.nc declares \"density\")": where a
// refused unit of a field file's came from; empty for a generated field, whose scene says all.
std::string UnitOrigin(const std::string& file, const std::string& from, const std::string& value)
{
  if (file.empty() || from == "scene")
  {
    return "";
  }
  return from == "file" ? " (" + file + " declares " + value + ")"
                        : " (neither the scene nor " + file + " declares it)";
}
}

void ResolveFieldOptics(const Context& c,
  Scene& s,
  const ResolvedFieldUnits& u,
  const std::string& file)
{
  s.Field.Resolved = u;
  TransferFunctionSpec& t = s.TransferFunction;
  if (t.Extinction == TransferFunctionSpec::ExtinctionRule::Droplets)
  {
    if (u.Quantity != FieldQuantity::Lwc)
    {
      c.Fail("transfer_function.extinction",
        "\"droplets\" derives the extinction from liquid water content: it needs field.quantity "
        "\"lwc\"" +
          UnitOrigin(file, u.QuantityFrom, "\"" + QuantityName(u.Quantity) + "\""));
    }
    if (u.Length == LengthUnit::None)
    {
      c.Fail("transfer_function.extinction",
        "\"droplets\" gives an extinction per metre: it needs field.length_unit \"m\" or "
        "\"km\" to convert it to world units" +
          UnitOrigin(file, u.LengthFrom, "\"" + LengthUnitName(u.Length) + "\""));
    }
    // With a droplet number, r_e at 1 g/m^3, and sigma grows as LWC^(2/3) from there.
    const double radius =
      u.DropletNumber > 0.0 ? EffectiveRadiusOfDroplets(1.0, u.DropletNumber) : u.EffectiveRadius;
    t.DropletExtinctionPerLwc = DropletExtinctionPerMetre(1.0, radius) * MetresPerUnit(u.Length);
    t.DropletLwcPower = u.DropletNumber > 0.0 ? 2.0 / 3.0 : 1.0;
  }
  LightingParameters& lighting = s.Render.Lighting;
  if (lighting.Phase == PhaseModel::Droplets && !s.Render.DropletRadiusGiven)
  {
    if (!(u.EffectiveRadius >= DropletEffectiveRadiusMinUm &&
          u.EffectiveRadius <= DropletEffectiveRadiusMaxUm))
    {
      c.Fail("render.march.effective_radius",
        "the droplets' phase takes the field's effective radius, " +
          FormatNumber(u.EffectiveRadius) + " um (" +
          (u.EffectiveRadiusFrom == "file"                ? file
              : u.EffectiveRadiusFrom == "droplet number" ? "field.droplet_number's at the "
                                                            "cloud's mean liquid water"
                                                          : "field.effective_radius") +
          "), outside the [" + FormatNumber(DropletEffectiveRadiusMinUm) + ", " +
          FormatNumber(DropletEffectiveRadiusMaxUm) +
          "] micrometres its table covers: give render.march.effective_radius");
    }
    lighting.DropletEffectiveRadius = float(u.EffectiveRadius);
  }
}

void ResolveDroplets(const Context& c, const json& document, Scene& s)
{
  if (s.Field.Units.DropletNumber && s.Field.Units.EffectiveRadius)
  {
    c.Fail("field.droplet_number",
      "gives the droplets' effective radius from their liquid water, and field.effective_radius "
      "gives one radius for all: give one of them");
  }
  const json* render = document.contains("render") ? &document["render"] : nullptr;
  s.Render.DropletRadiusGiven = render && render->is_object() && render->contains("march") &&
    (*render)["march"].is_object() && (*render)["march"].contains("effective_radius");
  if (!s.Field.FromFile())
  {
    ResolveFieldOptics(c, s, ResolveFieldUnits(s.Field.Units, {}), "");
    return;
  }
  // A field file may declare what the scene does not: what the scene's own keys contradict is
  // refused now, before the file is read (as if the file declared an lwc field in metres), the
  // rest once it is read (ProduceField).
  s.Field.Resolved.reset();
  FieldUnits hoped;
  hoped.Quantity = FieldQuantity::Lwc;
  hoped.Length = LengthUnit::Metre;
  Scene probe = s;
  ResolveFieldOptics(c, probe, ResolveFieldUnits(s.Field.Units, hoped), "");
}

void ResolveAutoDimensions(const Context& c, Scene& s)
{
  FieldSpec& f = s.Field;
  if (!f.AutoDimensions)
  {
    return;
  }
  const CameraSpec& camera = s.Camera;
  if (!camera.Position && !(camera.Orbit && camera.Orbit->Distance))
  {
    c.Fail("field.dimensions",
      "\"auto\" chooses the voxels from where the camera is, and this scene places it to fit "
      "the field: give camera.position, or camera.orbit with a distance");
  }
  if (f.Read.MaximumVoxels < 8)
  {
    c.Fail("field.max_voxels",
      "dimensions \"auto\" need at least 8 voxels (2 along each axis), got " +
        std::to_string(f.Read.MaximumVoxels));
  }
  const std::array<double, 6>& b = f.Bounds;
  CameraView view;
  view.FocalPoint = camera.FocalPoint.value_or(
    std::array<double, 3>{ { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) } });
  view.Position =
    camera.Position ? *camera.Position : OrbitPosition(*camera.Orbit, view.FocalPoint, 0.0);
  view.ViewUp = camera.ViewUp;
  view.ViewAngle = camera.ViewAngle;
  view.Width = s.Render.Size[0];
  view.Height = s.Render.Size[1];
  const glm::dvec3 direction(view.FocalPoint[0] - view.Position[0],
    view.FocalPoint[1] - view.Position[1],
    view.FocalPoint[2] - view.Position[2]);
  const glm::dvec3 up(view.ViewUp[0], view.ViewUp[1], view.ViewUp[2]);
  if (!(glm::length(glm::cross(direction, up)) > 1e-9 * glm::length(direction) * glm::length(up)))
  {
    c.Fail(glm::length(direction) > 0.0 ? "camera.view_up" : "camera.position",
      glm::length(direction) > 0.0
        ? "parallel to the view direction (from the position to the focal point); choose a "
          "view-up across it"
        : "the camera position equals the focal point; the view has no direction");
  }
  // What can hold cloud: the field; the cloud model's layer, from its base to its top and the
  // cumulonimbus's overshooting dome, and down to the field's floor where it rains.
  std::array<double, 6> region = b;
  if (f.Description.Model == DensityModel::Cloud)
  {
    const CloudLayer& layer = f.Description.Layer;
    region[2] = layer.Rain > 0.0 ? b[2] : std::max(b[2], layer.Base);
    region[3] = std::min(b[3], layer.Top + layer.Overshoot);
    if (!(region[2] < region[3]))
    {
      region = b;
    }
  }
  const std::optional<CameraDetail> detail =
    ChooseCameraDetail(view, region, b, f.Read.MaximumVoxels);
  if (!detail)
  {
    c.Fail("field.dimensions",
      "\"auto\" matches the voxels to the nearest cloud the camera sees, and this camera sees "
      "none of the field's bounds" +
        std::string(
          f.Description.Model == DensityModel::Cloud ? " between the layer's base and top" : "") +
        ": point it at the field, or give the dimensions");
  }
  f.AutoDimensions = detail;
  f.Dimensions = detail->Dimensions;
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
