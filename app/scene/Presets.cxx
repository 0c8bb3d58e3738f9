// Presets are located here and read as JSON; a ParaView preset is also checked and translated
// here, because only this file knows its flat [x, r, g, b, ...] lists and can name their elements
// in messages. cloudvis's own format is checked by the scene's readers (Scene.cxx), which already
// know what a transfer function's points must satisfy.
#include "Presets.h"

#include "Errors.h"
#include "FileNames.h"
#include "Scene.h" // ReadJsonFile
#include "Words.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <dirent.h>
#include <sstream>

#ifndef CLOUDVIS_PRESET_DIRECTORY
#define CLOUDVIS_PRESET_DIRECTORY "data/presets"
#endif

namespace cloudvis
{
namespace
{
using json = nlohmann::json;

std::string FormatNumber(double value)
{
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

bool IsPresetName(const std::string& name)
{
  return !name.empty() &&
    std::all_of(name.begin(), name.end(), [](char ch)
      { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_'; });
}

// One ParaView preset's flat list of `stride`-tuples, [x, v1, ...], as cloudvis points
// [x, v1, ... v(count-1)]: x strictly increasing, the values in [0, 1]. `where` names the list.
json ReadFlatPoints(const std::string& where, const json& flat, size_t stride, size_t count,
  const char* form)
{
  if (!flat.is_array())
  {
    throw InputError(where + ": expected a flat list of numbers " + form);
  }
  if (flat.empty())
  {
    throw InputError(where + ": the list is empty; it has no points");
  }
  if (flat.size() % stride != 0)
  {
    throw InputError(where + ": has " + std::to_string(flat.size()) +
      " numbers, not a multiple of " + std::to_string(stride) + " " + form);
  }
  json points = json::array();
  double previous = 0.0;
  for (size_t i = 0; i < flat.size(); i += stride)
  {
    json point = json::array();
    for (size_t j = 0; j < stride; ++j)
    {
      const std::string element = where + "[" + std::to_string(i + j) + "]";
      if (!flat[i + j].is_number() || !std::isfinite(flat[i + j].get<double>()))
      {
        throw InputError(element + ": expected a number, got " + WithValidUtf8(flat[i + j]).dump());
      }
      const double value = flat[i + j].get<double>();
      if (j == 0 && i > 0 && !(value > previous))
      {
        throw InputError(element + ": x values must increase strictly from point to point: " +
          FormatNumber(value) + " follows " + FormatNumber(previous));
      }
      if (j > 0 && j < count && (value < 0.0 || value > 1.0))
      {
        throw InputError(element + ": value " + FormatNumber(value) +
          " is out of range: allowed [0, 1]");
      }
      if (j == 0)
      {
        previous = value;
      }
      if (j < count)
      {
        point.push_back(value);
      }
    }
    points.push_back(point);
  }
  return points;
}

// A ParaView file: a list of presets (or one preset object); takes the one named, or the first.
PresetDocument ReadParaViewPreset(
  const std::string& path, const json& document, const std::string& wanted)
{
  const json list = document.is_array() ? document : json::array({ document });
  if (list.empty())
  {
    throw InputError(path + ": the ParaView preset list is empty");
  }
  std::vector<std::string> names;
  size_t chosen = list.size();
  for (size_t i = 0; i < list.size(); ++i)
  {
    const json& preset = list[i];
    const std::string name = preset.is_object() && preset.contains("Name") &&
        preset["Name"].is_string() ? preset["Name"].get<std::string>() : "";
    names.push_back(name.empty() ? "(unnamed #" + std::to_string(i) + ")" : "\"" + name + "\"");
    if (chosen == list.size() && (wanted.empty() || name == wanted))
    {
      chosen = i;
    }
  }
  if (chosen == list.size())
  {
    throw InputError(path + ": no ParaView preset named \"" + wanted + "\"; the file has " +
      Join(names));
  }
  const json& preset = list[chosen];
  const std::string where = path + ": [" + std::to_string(chosen) + "]";
  if (!preset.is_object())
  {
    throw InputError(where + ": expected a ParaView preset object, got " + preset.type_name());
  }
  if (!preset.contains("RGBPoints"))
  {
    throw InputError(where + ": no RGBPoints; a ParaView preset needs at least its color points");
  }
  PresetDocument result;
  result.Path = path;
  result.ParaView = true;
  result.Name = preset.contains("Name") && preset["Name"].is_string() ? preset["Name"].get<std::string>() : "";
  result.Document = json::object();
  result.Document["name"] = result.Name;
  result.Document["color"] =
    ReadFlatPoints(where + ".RGBPoints", preset["RGBPoints"], 4, 4, "[x, r, g, b, ...]");
  if (preset.contains("Points"))
  {
    result.Document["opacity"] = ReadFlatPoints(
      where + ".Points", preset["Points"], 4, 2, "[x, opacity, midpoint, sharpness, ...]");
  }
  return result;
}

} // namespace

std::string PresetDirectory()
{
  const char* overridden = std::getenv("CLOUDVIS_PRESET_DIR");
  return overridden && *overridden ? overridden : CLOUDVIS_PRESET_DIRECTORY;
}

std::vector<std::string> ShippedPresetNames()
{
  std::vector<std::string> names;
  if (DIR* dir = ::opendir(PresetDirectory().c_str()))
  {
    while (dirent* entry = ::readdir(dir))
    {
      const std::string file = entry->d_name;
      const std::string suffix = ".json";
      if (file.size() > suffix.size() &&
        file.compare(file.size() - suffix.size(), suffix.size(), suffix) == 0)
      {
        names.push_back(file.substr(0, file.size() - suffix.size()));
      }
    }
    ::closedir(dir);
  }
  std::sort(names.begin(), names.end());
  return names;
}

namespace
{

// True when a transfer_function.preset value is a path (it contains '/' or ends in ".json", in
// any case), false when it is the name of a shipped preset.
bool IsPresetPath(const std::string& reference)
{
  return reference.find('/') != std::string::npos || LowerCaseExtension(reference) == ".json";
}
} // namespace

PresetDocument ReadPreset(
  const std::string& reference, const std::string& baseDirectory, const std::string& paraViewName)
{
  std::string path;
  if (IsPresetPath(reference))
  {
    path = reference[0] == '/' || baseDirectory.empty() ? reference : baseDirectory + "/" + reference;
  }
  else
  {
    const std::vector<std::string> shipped = ShippedPresetNames();
    if (!IsPresetName(reference) ||
      std::find(shipped.begin(), shipped.end(), reference) == shipped.end())
    {
      throw InputError("unknown preset \"" + reference + "\"; shipped presets: " +
        (shipped.empty() ? "none found in " + PresetDirectory() : Join(shipped)) +
        " (or give the path of a .json file)");
    }
    path = PresetDirectory() + "/" + reference + ".json";
  }
  const json document = ReadJsonFile(path, "preset file");
  const bool paraView = document.is_array() || (document.is_object() && document.contains("RGBPoints"));
  if (paraView)
  {
    return ReadParaViewPreset(path, document, paraViewName);
  }
  if (!document.is_object())
  {
    throw InputError(path + ": a preset must be a JSON object (cloudvis's format) or a list of "
                            "ParaView presets, got " + std::string(document.type_name()));
  }
  if (!paraViewName.empty())
  {
    throw InputError(path + ": is a cloudvis preset, not a ParaView file; preset_name only picks "
                            "a preset from a ParaView file");
  }
  if (!document.contains("opacity") && !document.contains("color"))
  {
    throw InputError(path + ": the preset has no points: give \"opacity\", \"color\" or both");
  }
  PresetDocument result;
  result.Path = path;
  result.Name = document.contains("name") && document["name"].is_string() ? document["name"].get<std::string>() : "";
  result.Document = document;
  return result;
}

} // namespace cloudvis
