// Scene -> JSON, the inverse of SceneFromDocument for the keys written here. The names of the
// filters' enumerations are listed once more below (Scene.cxx keeps the reading tables private);
// ExportTests checks that every name written here reads back to the same value, so the two
// lists cannot drift apart unnoticed. Lighting model names are found through the reader itself.
#include "SceneJson.h"

#include <utility>

namespace cloudvis
{
namespace
{
using json = nlohmann::json;

template <typename E>
const char* NameOf(E value, const std::pair<E, const char*>* table, size_t count)
{
  for (size_t i = 0; i < count; ++i)
  {
    if (table[i].first == value)
    {
      return table[i].second;
    }
  }
  return "";
}
#define CLOUDVIS_NAME_OF(value, table) NameOf(value, table, sizeof(table) / sizeof(table[0]))

const std::pair<DensityModel, const char*> DensityModelNames[] = {
  { DensityModel::SdfPlusFbm, "sdf_plus_fbm" },
  { DensityModel::FbmFalloff, "fbm_falloff" },
  { DensityModel::Constant, "constant" },
};
const std::pair<noise::NoiseType, const char*> NoiseTypeNames[] = {
  { noise::NoiseType::None, "none" },
  { noise::NoiseType::White, "white" },
  { noise::NoiseType::Value, "value" },
  { noise::NoiseType::Perlin, "perlin" },
};
const std::pair<ShapeBlend, const char*> BlendNames[] = {
  { ShapeBlend::Union, "union" },
  { ShapeBlend::SmoothUnion, "smooth_union" },
};
const std::pair<ShapeType, const char*> ShapeTypeNames[] = {
  { ShapeType::Sphere, "sphere" },
  { ShapeType::Box, "box" },
  { ShapeType::Torus, "torus" },
  { ShapeType::Cross, "cross" },
  { ShapeType::Capsule, "capsule" },
};

// The render.lighting name the reader maps onto `model`.
std::string LightingName(LightingModel model)
{
  for (const std::string& name : LightingModelNames())
  {
    try
    {
      const json probe = { { "render", { { "lighting", name } } } };
      if (SceneFromDocument(probe, "", "").Render.Lighting == model)
      {
        return name;
      }
    }
    catch (const std::exception&)
    {
    }
  }
  return "";
}

json Vec3(const glm::vec3& v)
{
  return json::array({ double(v.x), double(v.y), double(v.z) });
}

json ShapeToJson(const Shape& s)
{
  json shape = { { "type", CLOUDVIS_NAME_OF(s.Type, ShapeTypeNames) }, { "center", Vec3(s.Center) },
    { "rotation", Vec3(s.RotationDegrees) }, { "scale", double(s.Scale) } };
  switch (s.Type)
  {
    case ShapeType::Sphere:
      shape["radius"] = double(s.Radius);
      break;
    case ShapeType::Box:
      shape["half_size"] = Vec3(s.HalfSize);
      break;
    case ShapeType::Torus:
      shape["major_radius"] = double(s.MajorRadius);
      shape["minor_radius"] = double(s.MinorRadius);
      break;
    case ShapeType::Cross:
      shape["arm_width"] = double(s.ArmWidth);
      shape["arm_length"] = double(s.ArmLength);
      break;
    case ShapeType::Capsule:
      shape["radius"] = double(s.Radius);
      shape["end_a"] = Vec3(s.EndA);
      shape["end_b"] = Vec3(s.EndB);
      break;
  }
  return shape;
}

json FieldToJson(const FieldSpec& f)
{
  if (f.FromFile())
  {
    // What a scene reading the file again needs: the read options that differ from the defaults.
    const FieldReadOptions defaults;
    json field = { { "file", f.File } };
    if (!f.Read.Format.empty())
    {
      field["format"] = f.Read.Format;
    }
    if (!f.Read.Array.empty())
    {
      field["array"] = f.Read.Array;
    }
    if (f.Read.TimeStep)
    {
      field["time_step"] = *f.Read.TimeStep;
    }
    if (f.Read.MaximumVoxels != defaults.MaximumVoxels)
    {
      field["max_voxels"] = f.Read.MaximumVoxels;
    }
    if (f.Read.Raw.Dimensions[0] > 0)
    {
      const RawLayout& r = f.Read.Raw;
      field["raw"] = { { "dimensions", r.Dimensions },
        { "type", r.Type },
        { "byte_order", r.BigEndian ? "big" : "little" },
        { "spacing", r.Spacing },
        { "origin", r.Origin },
        { "header_bytes", r.HeaderBytes } };
    }
    return field;
  }
  const FieldDescription& d = f.Description;
  json shapes = json::array();
  for (const Shape& shape : d.Shapes)
  {
    shapes.push_back(ShapeToJson(shape));
  }
  return { { "dimensions", f.Dimensions }, { "bounds", f.Bounds },
    { "density_model", CLOUDVIS_NAME_OF(d.Model, DensityModelNames) },
    { "density_scale", d.DensityScale }, { "falloff_width", d.FalloffWidth },
    { "shape", d.Morph ? json("morph") : shapes },
    { "blend", CLOUDVIS_NAME_OF(d.Blend, BlendNames) }, { "blend_radius", d.BlendRadius },
    { "noise", CLOUDVIS_NAME_OF(d.Noise.Type, NoiseTypeNames) }, { "octaves", d.Noise.Octaves },
    { "frequency", d.Noise.Frequency }, { "lacunarity", d.Noise.Lacunarity },
    { "lacunarity_increment", d.Noise.LacunarityIncrement }, { "gain", d.Noise.Gain },
    { "amplitude", d.Noise.Amplitude }, { "seed", d.Noise.Seed },
    { "wind", json::array({ d.Wind.x, d.Wind.y, d.Wind.z }) }, { "time", f.Time } };
}

// Writes every member of `resolved` over `target`, descending into objects present in both.
void Overlay(json& target, const json& resolved)
{
  if (!target.is_object() || !resolved.is_object())
  {
    target = resolved;
    return;
  }
  for (const auto& member : resolved.items())
  {
    if (member.value().is_object() && target.contains(member.key()))
    {
      Overlay(target[member.key()], member.value());
    }
    else
    {
      target[member.key()] = member.value();
    }
  }
}

} // namespace

nlohmann::json SceneToJson(const Scene& scene, const ResolvedCamera& camera)
{
  json document = scene.Document.is_object() ? scene.Document : json::object();
  // Keys that the values written below replace: a field file and procedural keys exclude each
  // other, the shape list is written whole, a transfer-function preset is spelt out point by
  // point (and may name a file relative to the scene), and the placed camera replaces an orbit.
  if (document.contains("field"))
  {
    document.erase("field");
  }
  if (document.contains("transfer_function") && document["transfer_function"].is_object())
  {
    document["transfer_function"].erase("preset");
    document["transfer_function"].erase("preset_name");
  }
  if (document.contains("camera") && document["camera"].is_object())
  {
    document["camera"].erase("orbit");
  }

  const TransferFunctionSpec& t = scene.TransferFunction;
  const RenderSpec& r = scene.Render;
  json resolved = {
    { "field", FieldToJson(scene.Field) },
    { "transfer_function",
      { { "opacity", t.Opacity }, { "color", t.Color }, { "unit_distance", t.UnitDistance } } },
    { "camera",
      { { "position", camera.Position }, { "focal_point", camera.FocalPoint },
        { "view_up", camera.ViewUp }, { "view_angle", scene.Camera.ViewAngle } } },
    { "render",
      { { "lighting", LightingName(r.Lighting) }, { "step", r.Step }, { "jitter", r.Jitter },
        { "resolution_scale", r.ResolutionScale }, { "accumulate", r.Accumulate },
        { "skip_empty_space", r.SkipEmptySpace }, { "size", r.Size }, { "png_bits", r.PngBits },
        { "exr_type", r.ExrHalf ? "half" : "float" } } },
  };
  // A background object (gradient, sky) is the user's as written; a plain color is resolved.
  if (!document.contains("background") || document["background"].is_array())
  {
    resolved["background"] = scene.Background;
  }
  if (!scene.Description.empty())
  {
    resolved["description"] = scene.Description;
  }
  Overlay(document, resolved);
  // Paths and --set strings may hold bytes that are not UTF-8; escaped, every dump() succeeds.
  return WithValidUtf8(std::move(document));
}

} // namespace cloudvis
