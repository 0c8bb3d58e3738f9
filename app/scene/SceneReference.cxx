// The reference tables of docs/scene-format.md, generated from the scene schema: a row per key
// with its type, its default (the member of a default-constructed struct, as SceneToJson would
// write it) and what is allowed (the range or names, then the key's help). The docs hold these
// tables between "<!-- schema:NAME -->" markers; app.scene_docs fails when they differ from what
// this prints, and `cmake -P cmake/SceneDocs.cmake` (make docs) writes them in.
#include "Scene.h"

#include "SceneSchema.h"

#include <sstream>

namespace cloudvis
{
namespace
{
using namespace schema;

std::string Code(const std::string& text)
{
  return "`" + text + "`";
}

std::string JoinNonEmpty(const std::vector<std::string>& parts)
{
  std::vector<std::string> kept;
  for (const std::string& part : parts)
  {
    if (!part.empty())
    {
      kept.push_back(part);
    }
  }
  return Join(kept, "; ");
}

template<typename S>
std::string DefaultWords(const Key<S>& key, const S& defaults)
{
  if (!key.Type.DefaultText.empty())
  {
    return key.Type.DefaultText;
  }
  if (key.Type.Required)
  {
    return "required";
  }
  const json value = key.Write ? key.Write(defaults) : json();
  return value.is_null() ? "none" : Code(ShowValue(value));
}

// The names of the types whose bits are in `usedBy` ("all" for every one).
std::string TypesWords(unsigned usedBy, const std::vector<Name>& types)
{
  std::vector<std::string> names;
  for (const Name& type : types)
  {
    if (usedBy & (1u << type.Value))
    {
      names.push_back(type.Text);
    }
  }
  return names.size() == types.size() ? "all" : Join(names);
}

struct Table
{
  std::string Name;
  std::vector<std::string> Header;
  std::vector<std::vector<std::string>> Rows;

  std::string Markdown() const
  {
    std::ostringstream out;
    out << "<!-- schema:" << this->Name << " -->\n";
    const auto row = [&out](const std::vector<std::string>& cells)
    {
      out << "|";
      for (const std::string& cell : cells)
      {
        out << " " << cell << " |";
      }
      out << "\n";
    };
    row(this->Header);
    out << "|";
    for (size_t i = 0; i < this->Header.size(); ++i)
    {
      out << "-----|";
    }
    out << "\n";
    for (const auto& cells : this->Rows)
    {
      row(cells);
    }
    out << "<!-- /schema -->\n";
    return out.str();
  }
};

// key | type | default | allowed: the keys of `keys`, named with `prefix`.
// For a typed object (a shape, a light), `types` are the values of its "type": a column after
// the key says which of them take it.
template<typename S>
Table KeyTable(const std::string& name,
  const Keys<S>& keys,
  const S& defaults,
  const std::string& prefix = "",
  const std::vector<Name>* types = nullptr)
{
  Table table{ name, { "key", "type", "default", "allowed" }, {} };
  if (types)
  {
    table.Header.insert(table.Header.begin() + 1, "types");
  }
  for (const Key<S>& key : keys)
  {
    std::vector<std::string> row{ Code(prefix + key.Name),
      TypeWords(key.Type),
      DefaultWords(key, defaults),
      JoinNonEmpty({ AllowedWords(key.Type), key.Help }) };
    if (types)
    {
      row.insert(row.begin() + 1, TypesWords(key.UsedBy, *types));
    }
    table.Rows.push_back(row);
  }
  return table;
}

std::vector<Table> ReferenceTables()
{
  const Scene scene;
  std::vector<Table> tables;

  Table sections{ "sections", { "key", "type", "default", "meaning" }, {} };
  for (const Key<Scene>& key : SceneSections())
  {
    sections.Rows.push_back(
      { Code(key.Name), TypeWords(key.Type), DefaultWords(key, scene), key.Help });
  }
  tables.push_back(sections);

  Table fieldFile = KeyTable("field.file", FieldFileKeys(), scene.Field);
  fieldFile.Header.back() = "meaning";
  tables.push_back(fieldFile);
  tables.push_back(KeyTable("field.raw", RawKeys(), RawLayout{}));
  tables.push_back(KeyTable("field.cloud", CloudKeys(), scene.Field));
  tables.push_back(KeyTable("field", GeneratedFieldKeys(), scene.Field));
  tables.push_back(KeyTable("field.units", FieldUnitKeys(), scene.Field));

  tables.push_back(KeyTable("field.shape", ShapeKeys(), Shape{}, "", &ShapeTypes()));
  tables.push_back(KeyTable("transfer_function", TransferFunctionKeys(), scene.TransferFunction));
  tables.push_back(KeyTable("camera", CameraKeys(), scene.Camera));
  tables.push_back(KeyTable("camera.orbit", OrbitKeys(), OrbitSpec{}));

  Table backgrounds{ "background", { "type", "keys", "what is drawn" }, {} };
  for (const Name& type : BackgroundTypes())
  {
    std::vector<std::string> keys;
    for (const Key<Scene>& key : BackgroundKeys())
    {
      if (key.Name != "type" && (key.UsedBy & (1u << type.Value)))
      {
        keys.push_back(Code(key.Name) + " (" +
          JoinNonEmpty({ key.Type.Required ? "required" : "optional", key.Help }) + ")");
      }
    }
    backgrounds.Rows.push_back({ Code("\"" + type.Text + "\""), Join(keys), type.Help });
  }
  tables.push_back(backgrounds);

  tables.push_back(KeyTable("render", RenderKeys(), scene.Render));
  Table lighting =
    KeyTable("render.lighting", DerivativeKeys(), scene.Render.Lighting, "derivative.");
  const Table march = KeyTable("render.lighting", MarchKeys(), scene.Render.Lighting, "march.");
  lighting.Rows.insert(lighting.Rows.end(), march.Rows.begin(), march.Rows.end());
  tables.push_back(lighting);

  tables.push_back(KeyTable("lights", LightKeys(), Light{}, "", &LightTypes()));
  tables.push_back(KeyTable("ambient", AmbientKeys(), scene.Render.Lighting));
  tables.push_back(KeyTable("view", ViewKeys(), ViewSpec{}));
  tables.push_back(KeyTable("view.oblique", ObliqueKeys(), ObliqueSpec{}));
  return tables;
}

} // namespace

std::string SceneReferenceMarkdown()
{
  std::string markdown;
  for (const Table& table : ReferenceTables())
  {
    markdown += (markdown.empty() ? "" : "\n") + table.Markdown();
  }
  return markdown;
}

} // namespace cloudvis
