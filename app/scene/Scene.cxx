// The scene language's entry points: reading a scene file, applying --set and option overrides
// to its JSON document, and validating the document into a Scene. What a scene may contain (every
// key, its type, range, default and help) is the schema of SceneSchema.cxx; this file only walks
// it, so a value from a file and a value from the command line are checked by the same entry and
// reported in the same shape, "<source>: <dotted key>: <problem>".
#include "Scene.h"

#include "Errors.h"
#include "InputFiles.h"
#include "SceneSchema.h"
#include "Utf8.h"

#include "CloudTransferTable.h" // TransferTableSize

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>

namespace cloudvis
{
namespace
{
using json = nlohmann::json;

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

// One object or array the parser is inside: the keys an object has had so far, and its last.
struct OpenJsonValue
{
  bool Array = false;
  std::set<std::string> Keys;
  std::string LastKey;
};

// The key path of `key` inside the open values ("field.cloud.type", "lights[].type").
std::string JsonKeyPath(const std::vector<OpenJsonValue>& open, const std::string& key)
{
  std::string path;
  for (size_t i = 0; i + 1 < open.size(); ++i)
  {
    path += open[i].Array ? "[]" : (path.empty() ? "" : ".") + open[i].LastKey;
  }
  return path + (path.empty() ? "" : ".") + key;
}

// json::parse, refusing deeper nesting and a key given twice in one object (JSON parsers keep
// one of the two silently: a second "field" section replaced the first) with an InputError
// prefixed by `where`.
json ParseJsonText(const std::string& text, const std::string& where)
{
  std::vector<OpenJsonValue> open;
  return json::parse(text,
    [&where, &open](int depth, json::parse_event_t event, json& parsed)
    {
      if (depth > MaxJsonDepth)
      {
        throw InputError(where + ": JSON nested deeper than " + std::to_string(MaxJsonDepth) +
          " levels");
      }
      switch (event)
      {
        case json::parse_event_t::object_start:
        case json::parse_event_t::array_start:
          open.push_back(OpenJsonValue{ event == json::parse_event_t::array_start, {}, {} });
          break;
        case json::parse_event_t::object_end:
        case json::parse_event_t::array_end:
          open.pop_back();
          break;
        case json::parse_event_t::key:
        {
          const std::string key = parsed.get<std::string>();
          if (!open.back().Keys.insert(key).second)
          {
            throw InputError(where + ": " + JsonKeyPath(open, key) +
              ": the key is given twice in one object; JSON keeps only one of them, so give it "
              "once");
          }
          open.back().LastKey = key;
          break;
        }
        case json::parse_event_t::value:
          break;
      }
      return true;
    });
}

} // namespace

std::vector<Light> DefaultLights()
{
  Light sun;
  sun.Positional = false;
  sun.Position = glm::dvec3(6.0, 8.0, 4.0);
  sun.FocalPoint = glm::dvec3(0.0);
  sun.Color = glm::vec3(1.0f);
  // An intensity means the same light in every model (docs/lighting.md, Lights).
  sun.Intensity = 1.0f;
  sun.Attenuation = glm::vec3(0.0f, 0.0f, 1.0f);
  return { sun };
}

Scene DefaultScene()
{
  return Scene{};
}

namespace
{

// Reads a scene file into a JSON document. Throws InputError for an unreadable file (with the
// OS reason) or malformed JSON (with line and column).
nlohmann::json ReadSceneDocument(const std::string& path)
{
  return ReadJsonFile(path, "scene file");
}
} // namespace

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
  // A key whose value is free text (description, field.file, transfer_function.preset) takes
  // text that is not JSON as written: description=inf is the string "inf", not a refused number.
  const schema::ValueType* type = schema::FindType(schema::SceneSections(), key);
  if (text.empty() || (type && type->Type == schema::ValueType::Text))
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

namespace
{

// Sets a dotted key of a document to a value, creating missing objects on the way. `option`
// names where the value came from in errors ("--set"). Throws InputError when a part of the
// key names a value that is not an object.
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
} // namespace

void ApplyOverride(nlohmann::json& document, const std::string& assignment)
{
  const auto equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0)
  {
    throw UsageError(
      "--set expects KEY=VALUE (for example field.octaves=4), got \"" + assignment + "\"");
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

Scene SceneFromDocument(const nlohmann::json& document, const std::string& source,
  const std::string& baseDirectory, const std::vector<std::string>& overriddenKeys,
  const std::vector<SceneOverride>& optionKeys)
{
  schema::Context context{ source, baseDirectory, {} };
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
    throw InputError(source + ": a scene must be a JSON object, got " + schema::Describe(document));
  }
  Scene scene;
  scene.Source = source;
  schema::ReadObject(context, document, "", schema::SceneSections(), scene);
  schema::ResolveSkySun(document, scene);
  schema::ResolveDroplets(context, document, scene);
  schema::ResolveAutoDimensions(context, scene);
  scene.Document = document;
  return scene;
}

const std::vector<std::string>& FieldFileKeyNames()
{
  static const std::vector<std::string> names = []
  {
    std::vector<std::string> all = schema::KeyNames(schema::FieldFileKeys());
    for (const std::string& name : schema::KeyNames(schema::FieldUnitKeys()))
    {
      all.push_back(name);
    }
    return all;
  }();
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

void ResolveFieldOptics(Scene& scene, const ResolvedFieldUnits& units, const std::string& file)
{
  const schema::Context context{ scene.Source, "", {} };
  schema::ResolveFieldOptics(context, scene, units, file);
}

std::array<double, 3> OrbitPosition(const OrbitSpec& orbit,
  const std::array<double, 3>& focal,
  double distance)
{
  constexpr double degree = 3.14159265358979323846 / 180.0;
  const double azimuth = orbit.Azimuth * degree;
  const double elevation = orbit.Elevation * degree;
  const double radius = orbit.Distance.value_or(distance);
  return { { focal[0] + radius * std::cos(elevation) * std::sin(azimuth),
    focal[1] + radius * std::sin(elevation),
    focal[2] + radius * std::cos(elevation) * std::cos(azimuth) } };
}

TransferFunctionSpec TabulatedTransferFunction(const TransferFunctionSpec& transferFunction)
{
  TransferFunctionSpec t = transferFunction;
  if (t.Extinction != TransferFunctionSpec::ExtinctionRule::Droplets)
  {
    return t;
  }
  if (!(t.DropletExtinctionPerLwc > 0.0))
  {
    // A scene over a field file resolves its droplets once the file is read (ProduceField): a
    // caller that tabulates before that would render the default effective radius.
    throw std::logic_error("transfer_function.extinction \"droplets\": the extinction is not "
                           "resolved yet: the scene's field has not been produced (ProduceField)");
  }
  // The table spans the opacity points and the color points together (TransferFunctionRange):
  // the opacity points span [0, LwcMax] widened to the color's span, so that the table's
  // densities are exactly the points'.
  double lo = 0.0, hi = t.LwcMax;
  if (!t.Color.empty())
  {
    lo = std::min(lo, t.Color.front()[0]);
    hi = std::max(hi, t.Color.back()[0]);
  }
  const auto extinction = [&t](double lwc)
  { return t.DropletExtinctionPerLwc * std::pow(std::max(lwc, 0.0), t.DropletLwcPower); };
  const double sigmaMax = extinction(hi);
  // Opacity 1 - 1/e at the densest entry: far from the clamp at 1 - 1e-4, and every opacity
  // keeps double's relative precision through -log1p(-a) / u.
  t.UnitDistance = sigmaMax > 0.0 ? 1.0 / sigmaMax : 1.0;
  t.Opacity.clear();
  const int entries = TransferTableSize;
  for (int i = 0; i < entries; ++i)
  {
    const double density = lo + (hi - lo) * (double(i) / (entries - 1));
    const double sigma = extinction(density);
    t.Opacity.push_back({ { density, -std::expm1(-sigma * t.UnitDistance) } });
  }
  return t;
}

double OpacityRisesAbove(const TransferFunctionSpec& spec)
{
  double rises = spec.Opacity.front()[0];
  for (const auto& point : spec.Opacity)
  {
    if (point[1] > 0.0)
    {
      return rises;
    }
    rises = point[0];
  }
  return rises;
}

bool HidesEveryValue(const TransferFunctionSpec& spec)
{
  return spec.Extinction == TransferFunctionSpec::ExtinctionRule::Opacity &&
    std::all_of(spec.Opacity.begin(),
      spec.Opacity.end(),
      [](const std::array<double, 2>& point) { return point[1] == 0.0; });
}

std::array<double, 2> TransferFunctionSpan(const TransferFunctionSpec& spec)
{
  return { { std::min(spec.Opacity.front()[0], spec.Color.front()[0]),
    std::max(spec.Opacity.back()[0], spec.Color.back()[0]) } };
}

TransferFunctionSpec StretchTransferFunction(const TransferFunctionSpec& spec,
  const std::array<double, 2>& target)
{
  TransferFunctionSpec stretched = spec;
  const auto [lo, hi] = TransferFunctionSpan(spec);
  if (!(hi > lo) || !(target[1] > target[0]))
  {
    return stretched;
  }
  const auto map = [&](double x)
  { return target[0] + (x - lo) / (hi - lo) * (target[1] - target[0]); };
  for (auto& p : stretched.Opacity)
  {
    p[0] = map(p[0]);
  }
  for (auto& p : stretched.Color)
  {
    p[0] = map(p[0]);
  }
  return stretched;
}

namespace
{
double Diagonal(const double b[6])
{
  return std::hypot(b[1] - b[0], b[3] - b[2], b[5] - b[4]);
}
} // namespace

TransferFunctionFit FitTransferFunctionToField(Scene& scene,
  const std::array<double, 2>& range,
  bool fieldFileAlone,
  const double bounds[6])
{
  TransferFunctionSpec& function = scene.TransferFunction;
  if (function.Extinction == TransferFunctionSpec::ExtinctionRule::Droplets ||
    !(range[1] > range[0]))
  {
    return TransferFunctionFit::Kept;
  }
  const std::array<double, 2> span = TransferFunctionSpan(function);
  const double slack = 1e-6 * std::max(span[1] - span[0], range[1] - range[0]);
  const bool covered = range[0] >= span[0] - slack && range[1] <= span[1] + slack;
  if (scene.Document.contains("transfer_function"))
  {
    return covered ? TransferFunctionFit::Kept : TransferFunctionFit::ValuesBeyondItsPoints;
  }
  const bool fit = fieldFileAlone || range[1] <= OpacityRisesAbove(function);
  if (!fit && covered)
  {
    return TransferFunctionFit::Kept;
  }
  function = StretchTransferFunction(function,
    fit ? range
        : std::array<double, 2>{ { std::min(span[0], range[0]), std::max(span[1], range[1]) } });
  const double diagonal = Diagonal(bounds), defaultDiagonal = Diagonal(FieldSpec{}.Bounds.data());
  if (diagonal > 0.0 && std::isfinite(diagonal))
  {
    function.UnitDistance *= diagonal / defaultDiagonal;
  }
  return fit ? TransferFunctionFit::FittedToValues : TransferFunctionFit::GrownToValues;
}

void TurnDefaultViewToUp(Scene& scene, int up)
{
  if (up != 0 && up != 2)
  {
    return;
  }
  // The rotation that takes y to the up axis: z up turns (x, y, z) into (x, -z, y); x up turns it
  // into (y, -x, z).
  const auto turn = [up](const glm::dvec3& v)
  { return up == 2 ? glm::dvec3(v.x, -v.z, v.y) : glm::dvec3(v.y, -v.x, v.z); };
  const auto turnArray = [&](std::array<double, 3>& a)
  {
    const glm::dvec3 t = turn(glm::dvec3(a[0], a[1], a[2]));
    a = { { t.x, t.y, t.z } };
  };
  const json& camera = scene.Document.contains("camera") ? scene.Document["camera"] : json();
  if (!camera.contains("position") && !camera.contains("orbit") && !camera.contains("view_up"))
  {
    turnArray(scene.Camera.ViewUp);
    turnArray(scene.Camera.DefaultDirection);
  }
  if (!scene.Document.contains("lights"))
  {
    for (Light& light : scene.Lights)
    {
      light.Position = turn(light.Position);
      light.FocalPoint = turn(light.FocalPoint);
    }
  }
}

} // namespace cloudvis
