// A scene file, parsed and validated: what cloudvis should show or export. A scene is a JSON
// object of sections; each section has one entry in the section table of Scene.cxx and one part
// of the Scene struct, so transfer_function, camera, render, lights and background arrive as
// new entries beside "field" without touching the rest. Overrides from the command line
// (--set key=value) are applied to the JSON document before validation, so a value from a file
// and a value from --set are checked by the same code and reported with the same dotted key.
// The schema is documented in docs/scene-format.md.
#ifndef cloudvis_Scene_h
#define cloudvis_Scene_h

#include "CloudDensityEvaluator.h"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace cloudvis
{

// The "field" section: either a .vti to load, or where and how to generate a procedural field.
struct FieldSpec
{
  // Path of a .vti to load instead of generating, already resolved against the scene file's
  // folder; empty for a procedural field (then the members below apply).
  std::string File;
  std::array<int, 3> Dimensions{ { 128, 128, 128 } };
  std::array<double, 6> Bounds{ { -2.0, 2.0, -2.0, 2.0, -2.0, 2.0 } };
  FieldDescription Description;
  double Time = 0.0;

  bool FromFile() const { return !this->File.empty(); }
};

struct Scene
{
  // Where the scene came from, for messages: the scene file's path, or "default scene".
  std::string Source = "default scene";
  std::string Description;
  FieldSpec Field;
};

// The scene used when none is given: the article's cloud (a unit sphere plus 6 octaves of value
// noise on 128^3 voxels over [-2, 2]^3).
Scene DefaultScene();

// Reads a scene file into a JSON document. Throws InputError for an unreadable file (with the
// OS reason) or malformed JSON (with line and column).
nlohmann::json ReadSceneDocument(const std::string& path);

// Applies one "key=value" assignment (the argument of --set) to a document. The key is dotted
// (field.noise); missing intermediate objects are created. Throws UsageError when the
// assignment has no '=' or an empty key part, InputError when a part of the key names a value
// that is not an object, or when the value is NaN or infinite.
void ApplyOverride(nlohmann::json& document, const std::string& assignment);

// The value of an assignment: JSON when it parses as JSON (6, "perlin", [1,2,3], true), else a
// comma-separated list of numbers as an array (128,128,128), else the text as a string (perlin).
// `key` only names the value in errors.
nlohmann::json ParseOverrideValue(const std::string& key, const std::string& text);

// Validates a document and turns it into a Scene. `source` prefixes every message,
// `baseDirectory` resolves relative paths inside the scene (empty: the current directory),
// `overriddenKeys` are the dotted keys set by --set, so messages about them can say so. Throws
// InputError naming the dotted key and the problem.
Scene SceneFromDocument(const nlohmann::json& document, const std::string& source,
  const std::string& baseDirectory, const std::vector<std::string>& overriddenKeys = {});

// All of the above: reads `path` (the default scene when empty), applies the assignments in
// order, validates. This is what every command that takes a scene calls.
Scene LoadScene(const std::string& path, const std::vector<std::string>& assignments);

} // namespace cloudvis

#endif
