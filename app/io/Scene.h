// A scene file, parsed and validated: what cloudvis should show or export. A scene is a JSON
// object of sections (field, transfer_function, camera, background, render; lights to come);
// each section has one entry in the section table of Scene.cxx and one part of the Scene struct,
// so a new section is a new entry that does not touch the rest. Overrides from the command line
// (--set key=value, and options such as --lighting that stand for a key) are applied to the JSON
// document before validation, so a value from a file and a value from the command line are
// checked by the same code and reported with the same dotted key.
// The schema is documented in docs/scene-format.md.
#ifndef cloudvis_Scene_h
#define cloudvis_Scene_h

#include "CloudDensityEvaluator.h"
#include "CloudLighting.h" // LightingModel

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
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

// The "transfer_function" section: what density looks like. Opacity is per UnitDistance of
// world units (the mapper turns it into the extinction sigma_t = -ln(1 - a) / u), color is the
// albedo. Points are (density, value...) with strictly increasing densities; between points the
// functions are linear, beyond the ends they hold the end values.
struct TransferFunctionSpec
{
  // Defaults chosen for the default field (densities 0 .. ~0.95, most of the cloud below 0.3):
  // thin wisps stay translucent, the core builds up without saturating, and the grey-to-white
  // color gives depth where there is no lighting.
  std::vector<std::array<double, 2>> Opacity{ { { 0.0, 0.0 } }, { { 0.02, 0.0 } },
    { { 0.5, 0.5 } }, { { 1.0, 0.8 } } };
  std::vector<std::array<double, 4>> Color{ { { 0.0, 0.55, 0.58, 0.65 } },
    { { 0.3, 0.9, 0.9, 0.92 } }, { { 1.0, 1.0, 1.0, 1.0 } } };
  double UnitDistance = 0.1;
};

// The "camera" section. Absent keys are filled when the field is known (see ApplyCamera in
// render/OffscreenRender.h): the focal point is the field's centre, the position looks at it
// along -z from the distance vtkRenderer::ResetCamera picks to fit the field's bounds.
struct CameraSpec
{
  std::optional<std::array<double, 3>> Position;
  std::optional<std::array<double, 3>> FocalPoint;
  std::array<double, 3> ViewUp{ { 0.0, 1.0, 0.0 } };
  double ViewAngle = 30.0; // degrees, vertical
};

// The "render" section: how the mapper marches and how large the image is.
struct RenderSpec
{
  LightingModel Lighting = LightingModel::None; // names: the LightingModels table of Scene.cxx
  double Step = 0.0; // world units; 0: one voxel (the smallest spacing of the field)
  bool Jitter = true;
  double ResolutionScale = 1.0;
  int Accumulate = 16; // frames averaged into a still
  bool SkipEmptySpace = true;
  std::array<int, 2> Size{ { 800, 600 } }; // pixels, width and height
};

struct Scene
{
  // Where the scene came from, for messages: the scene file's path, or "default scene".
  std::string Source = "default scene";
  std::string Description;
  FieldSpec Field;
  TransferFunctionSpec TransferFunction;
  CameraSpec Camera;
  std::array<double, 3> Background{ { 0.1, 0.12, 0.16 } };
  RenderSpec Render;
};

// A scene value given on the command line by an option that stands for a scene key (--lighting M
// is render.lighting = "M"). It is applied to the document like --set, after the --set
// assignments, and validated with the rest; messages about it name the option.
struct SceneOverride
{
  std::string Key; // dotted
  nlohmann::json Value;
  std::string Option; // "--lighting", for messages
};

// The names render.lighting accepts, in the order of the table (for help and messages).
std::vector<std::string> LightingModelNames();

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

// Sets a dotted key of a document to a value, creating missing objects on the way. `option`
// names where the value came from in errors ("--set"). Throws InputError when a part of the
// key names a value that is not an object.
void SetDocumentValue(nlohmann::json& document, const std::string& key, const nlohmann::json& value,
  const std::string& option);

// The value of an assignment: JSON when it parses as JSON (6, "perlin", [1,2,3], true), else a
// comma-separated list of numbers as an array (128,128,128), else the text as a string (perlin).
// `key` only names the value in errors.
nlohmann::json ParseOverrideValue(const std::string& key, const std::string& text);

// Validates a document and turns it into a Scene. `source` prefixes every message,
// `baseDirectory` resolves relative paths inside the scene (empty: the current directory),
// `overriddenKeys` are the dotted keys set by --set, so messages about them can say so;
// `optionKeys` those set by other options (messages name the option). Throws InputError naming
// the dotted key and the problem.
Scene SceneFromDocument(const nlohmann::json& document, const std::string& source,
  const std::string& baseDirectory, const std::vector<std::string>& overriddenKeys = {},
  const std::vector<SceneOverride>& optionKeys = {});

// All of the above: reads `path` (the default scene when empty), applies the assignments in
// order, then the option overrides, validates. This is what every command that takes a scene
// calls.
Scene LoadScene(const std::string& path, const std::vector<std::string>& assignments,
  const std::vector<SceneOverride>& options = {});

} // namespace cloudvis

#endif
