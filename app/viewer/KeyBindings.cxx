// The key table and the three things made from it: lookup, help overlay, docs table.
#include "KeyBindings.h"

#include "Viewer.h"

#include <algorithm>
#include <map>
#include <sstream>

namespace cloudvis
{
namespace
{
const char* const View = "view";
const char* const Slices = "slices";
const char* const Rendering = "rendering";
const char* const Function = "transfer function";
const char* const Files = "files";

// The groups in the order they are listed; the help overlay puts the first two in its left column.
const std::vector<const char*>& Groups()
{
  static const std::vector<const char*> groups = { View, Slices, Rendering, Function, Files };
  return groups;
}

// X key symbols of the characters that are not their own name.
const std::map<char, std::string>& CharacterNames()
{
  static const std::map<char, std::string> names = { { '+', "plus" },
    { '-', "minus" },
    { '=', "equal" },
    { '[', "bracketleft" },
    { ']', "bracketright" },
    { ' ', "space" },
    { '.', "period" },
    { '\r', "Return" },
    { 27, "Escape" },
    { 127, "Delete" },
    { 8, "BackSpace" } };
  return names;
}
} // namespace

const std::vector<KeyBinding>& KeyBindings()
{
  using A = ViewerAction;
  static const std::vector<KeyBinding> table = {
    { { "4" },
      false,
      A::ToggleLayout,
      View,
      "four views (3D, axial, coronal, sagittal) / the 3D view alone" },
    { { "v" }, false, A::ToggleVolume, View, "show / hide the cloud (the slices stay)" },
    { { "r" }, false, A::ResetCamera, View, "reset the camera to the scene's" },
    { { "h" }, false, A::Help, View, "show / hide this help" },
    { { "q", "Escape" }, false, A::Quit, View, "quit" },
    { { "x", "y", "z" },
      false,
      A::ToggleSlice,
      Slices,
      "show / hide the slice across x, y, z in the 3D view" },
    { { "o" }, false, A::ToggleOblique, Slices, "show / hide the oblique slice" },
    { { "c" },
      false,
      A::CycleSliceColors,
      Slices,
      "slice colors: blue-yellow, gray, viridis, the transfer function's colors" },
    { { "m" }, false, A::CycleLighting, Rendering, "lighting model: none, derivative, march" },
    { { "Left", "Right" },
      false,
      A::MoveLightAzimuth,
      Rendering,
      "turn the first directional light 10 degrees in azimuth" },
    { { "Up", "Down" },
      false,
      A::MoveLightElevation,
      Rendering,
      "raise / lower the first directional light 10 degrees (within +-89)" },
    { { "plus", "equal", "KP_Add" },
      false,
      A::StepLarger,
      Rendering,
      "step size times 1.25 (render.step)" },
    { { "minus", "KP_Subtract" }, false, A::StepSmaller, Rendering, "step size times 0.8" },
    { { "bracketleft" },
      false,
      A::ResolutionDown,
      Rendering,
      "resolution scale -0.125 (render.resolution_scale, down to 0.25)" },
    { { "bracketright" }, false, A::ResolutionUp, Rendering, "resolution scale +0.125 (up to 1)" },
    { { "p" },
      false,
      A::NextPreset,
      Function,
      "next preset of the preset directory (data/presets or $CLOUDVIS_PRESET_DIR)" },
    { { "P" },
      false,
      A::SavePreset,
      Function,
      "save the transfer function as cloudvis-preset-NNN.json" },
    { { "l" }, false, A::HistogramScale, Function, "histogram: log / linear" },
    { { "f" },
      false,
      A::FitTransferFunction,
      Function,
      "fit: stretch the points over the field's value range" },
    { { "R" },
      false,
      A::ResetTransferFunction,
      Function,
      "reset the transfer function to the scene's" },
    { { "z" }, true, A::Undo, Function, "undo the last transfer-function edit" },
    { { "y", "Z" }, true, A::Redo, Function, "redo it" },
    { { "Delete", "BackSpace" },
      false,
      A::DeletePoint,
      Function,
      "remove the selected point (not an end point)" },
    { { "Return", "KP_Enter" },
      false,
      A::TypePointValues,
      Function,
      "type the selected point's values (Enter applies, Esc cancels)" },
    { { "s" }, false, A::Screenshot, Files, "screenshot: cloudvis-screenshot-NNN.png and .exr" },
    { { "w" }, false, A::SaveScene, Files, "save the scene as cloudvis-view-NNN.json" },
  };
  return table;
}

std::string KeySymOfCharacter(char character)
{
  if (character == 0)
  {
    return "";
  }
  const auto found = CharacterNames().find(character);
  return found != CharacterNames().end() ? found->second : std::string(1, character);
}

KeyMatch FindKeyBinding(const std::string& keySym, char keyCode, bool control)
{
  const std::string sym = keySym.empty() ? KeySymOfCharacter(keyCode) : keySym;
  for (const KeyBinding& binding : KeyBindings())
  {
    if (binding.Control != control)
    {
      continue;
    }
    const auto found = std::find(binding.Keys.begin(), binding.Keys.end(), sym);
    if (found != binding.Keys.end())
    {
      return { &binding, int(found - binding.Keys.begin()) };
    }
  }
  return {};
}

std::string KeyLabel(const std::string& keySym, bool control)
{
  static const std::map<std::string, std::string> labels = { { "Escape", "Esc" },
    { "KP_Add", "keypad +" },
    { "KP_Subtract", "keypad -" },
    { "KP_Enter", "keypad Enter" },
    { "Return", "Enter" } };
  std::string label = keySym;
  const auto found = labels.find(keySym);
  if (found != labels.end())
  {
    label = found->second;
  }
  else
  {
    for (const auto& [character, name] : CharacterNames())
    {
      if (name == keySym && character >= ' ' && character < 127)
      {
        label = std::string(1, character);
      }
    }
  }
  if (keySym.size() == 1 && keySym[0] >= 'A' && keySym[0] <= 'Z')
  {
    label = "Shift+" + std::string(1, char(keySym[0] - 'A' + 'a'));
  }
  return control ? "Ctrl+" + label : label;
}

namespace
{
std::string KeysLabel(const KeyBinding& binding, const char* separator)
{
  std::string text;
  for (const std::string& key : binding.Keys)
  {
    text += (text.empty() ? "" : separator) + KeyLabel(key, binding.Control);
  }
  return text;
}
} // namespace

std::array<std::string, 2> KeyHelpColumns()
{
  std::array<std::ostringstream, 2> columns;
  const auto& groups = Groups();
  for (size_t g = 0; g < groups.size(); ++g)
  {
    std::ostringstream& out = columns[g < 2 ? 0 : 1];
    out << (out.tellp() > 0 ? "\n" : "") << groups[g] << ":\n";
    for (const KeyBinding& binding : KeyBindings())
    {
      if (binding.Group == groups[g])
      {
        std::string keys = KeysLabel(binding, " ");
        keys.resize(std::max<size_t>(keys.size(), 14), ' ');
        out << "  " << keys << " " << binding.Description << "\n";
      }
    }
  }
  columns[0] << "\nmouse: see docs/viewer.md; q or Esc quits";
  return { { columns[0].str(), columns[1].str() } };
}

std::string ViewerKeysMarkdown()
{
  std::ostringstream out;
  out << "| key | group | effect |\n|---|---|---|\n";
  for (const char* group : Groups())
  {
    for (const KeyBinding& binding : KeyBindings())
    {
      if (binding.Group == group)
      {
        std::string keys;
        for (const std::string& key : binding.Keys)
        {
          keys += (keys.empty() ? "" : ", ") + ("`" + KeyLabel(key, binding.Control) + "`");
        }
        std::string description = binding.Description;
        // A '|' would end the table cell.
        for (size_t at = description.find('|'); at != std::string::npos;
             at = description.find('|', at + 2))
        {
          description.replace(at, 1, "\\|");
        }
        out << "| " << keys << " | " << group << " | " << description << " |\n";
      }
    }
  }
  return out.str();
}

} // namespace cloudvis
