// The code of the scene schema (SceneSchemaReaders.cxx) that its tables (SceneSchema.cxx) name:
// the readers and writers of the keys that are more than a member of a struct (a field from a
// file or not, a shape list, a transfer-function preset, the camera, the typed objects whose
// "type" decides their keys: backgrounds and lights), and the templates that make a table's
// entries. A Read* function reads a key's value into the scene and fails through the Context
// ("<source>: <dotted key>: <problem>"); a Write* function writes what it read. Private to the
// scene layer.
#ifndef cloudvis_SceneSchemaReaders_h
#define cloudvis_SceneSchemaReaders_h

#include "SceneSchema.h"

#include <functional>
#include <string>
#include <vector>

namespace cloudvis
{
namespace schema
{

// A bit per value of an enumeration, for the UsedBy masks of typed objects.
template<typename E>
constexpr unsigned Bit(E value)
{
  return 1u << static_cast<unsigned>(value);
}
constexpr unsigned Directional = Bit(0), Point = Bit(1); // the values of LightTypes()

// ---- field -----------------------------------------------------------------------------------

void ReadShapes(const Context& c, const json& v, const std::string& key, FieldSpec& f);

json WriteShapes(const FieldSpec& f);

void ReadField(const Context& c, const json& v, const std::string& key, Scene& scene);

json WriteField(const Scene& scene);

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
std::vector<Name> FieldFormatNames();

// "VTK XML image data `.vti`, ..., NetCDF (CF conventions) `.nc`/`.nc4`/`.cdf`, ...".
std::string FieldFormatsInWords();

// Voxels along x, y and z, of a generated field and of a raw file.
ValueType Dimensions();

// ---- transfer_function -----------------------------------------------------------------------

// transfer_function.preset fills the section first (from the defaults: what a preset leaves out
// keeps its default), then the section's explicit keys override it.
void ReadTransferFunction(const Context& c, const json& v, const std::string& key, Scene& scene);

// A transfer function's points as the renderers can tabulate them: the densities' span must be
// a width float arithmetic holds (the renderers check the opacity and color points together).
std::string DensitiesWithinFloat(const json& points);

// preset and preset_name are read by ReadTransferFunction, before the other keys.
Key<TransferFunctionSpec> PresetReference(const std::string& name,
  ValueType type,
  std::string help);

// ---- camera ----------------------------------------------------------------------------------

void ReadCamera(const Context& c, const json& v, const std::string& key, Scene& scene);

// ---- background ------------------------------------------------------------------------------

// [r, g, b] (a solid color, as before types existed) or {"type": ..., keys of that type}.
void ReadBackground(const Context& c, const json& v, const std::string& key, Scene& s);

json WriteBackground(const Scene& s);

std::string NormalizeSun(Scene& s);

// ---- render ----------------------------------------------------------------------------------

// The names of one of CloudLightingParameters.h's tables (LightingModelTable,
// MultipleScatteringModelTable), with their descriptions, in the table's order.
template<typename Table>
std::vector<Name> NamesOfTable(const Table& table)
{
  std::vector<Name> names;
  for (const auto& entry : table)
  {
    names.push_back({ entry.Name, int(entry.Model), entry.Description });
  }
  return names;
}

// render.march.multiple_scattering held the number of octaves before it chose between the
// volume and the octaves: a number there is refused with where the count went.
std::string OctaveCountMoved(const json& value);

// render.derivative or render.march: the keys, then the lighting's own check (a value a float
// cannot hold, say 0.99999999 for g, passes the double range but not it).
Key<RenderSpec> LightingObject(const std::string& name,
  const Keys<LightingParameters>& (*keys)(),
  std::string help);

// ---- lights ----------------------------------------------------------------------------------

void ReadLights(const Context& c, const json& v, const std::string& key, Scene& s);

json WriteLights(const Scene& s);

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

} // namespace schema
} // namespace cloudvis

#endif
