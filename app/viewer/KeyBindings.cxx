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
  // clang-format off: one row per binding reads better than what the formatter makes of it.
  // keys (a variant each), aliases, Control, action, group, description, redraws the cloud
  static const std::vector<KeyBinding> table = {
    { { "4" }, {}, false, A::ToggleLayout, View, "four views / the 3D view alone" },
    { { "v" }, {}, false, A::ToggleVolume, View, "show / hide the cloud", true },
    { { "r" }, {}, false, A::ResetCamera, View, "reset the camera", true },
    { { "h" }, {}, false, A::Help, View, "show / hide this help" },
    { { "Escape" }, {}, false, A::Close, View, "close the help, cancel typing" },
    { { "q" }, {}, false, A::Quit, View, "quit (asks first if unsaved)" },
    { { "x", "y", "z" }, {}, false, A::ToggleSlice, Slices, "slice across x, y, z in 3D", true },
    { { "o" }, {}, false, A::ToggleOblique, Slices, "oblique slice in 3D", true },
    { { "c" }, {}, false, A::CycleSliceColors, Slices, "slice colors: next colormap", true },
    { { "m" }, {}, false, A::CycleLighting, Rendering, "lighting: none, derivative, march", true },
    { { "Left", "Right" },
      {},
      false,
      A::MoveLightAzimuth,
      Rendering,
      "turn the light 10 degrees",
      true },
    { { "Up", "Down" },
      {},
      false,
      A::MoveLightElevation,
      Rendering,
      "raise / lower the light",
      true },
    { { "plus" },
      { "equal", "KP_Add" },
      false,
      A::StepLarger,
      Rendering,
      "step size x 1.25",
      true },
    { { "minus" }, { "KP_Subtract" }, false, A::StepSmaller, Rendering, "step size x 0.8", true },
    { { "bracketleft" },
      {},
      false,
      A::ResolutionDown,
      Rendering,
      "resolution scale - 0.125",
      true },
    { { "bracketright" }, {}, false, A::ResolutionUp, Rendering, "resolution scale + 0.125", true },
    { { "p" }, {}, false, A::NextPreset, Function, "next preset", true },
    { { "P" }, {}, false, A::SavePreset, Function, "save as a preset file" },
    { { "l" }, {}, false, A::HistogramScale, Function, "histogram: log / linear" },
    { { "f" }, {}, false, A::FitTransferFunction, Function, "fit the points to the data", true },
    { { "R" },
      {},
      false,
      A::ResetTransferFunction,
      Function,
      "back to the scene's function",
      true },
    { { "z" }, {}, true, A::Undo, Function, "undo an edit", true },
    { { "y" }, { "Z" }, true, A::Redo, Function, "redo it", true },
    { { "Delete" },
      { "BackSpace" },
      false,
      A::DeletePoint,
      Function,
      "remove the selected point",
      true },
    { { "Return" }, { "KP_Enter" }, false, A::TypePointValues, Function, "type its values" },
    { { "s" }, {}, false, A::Screenshot, Files, "screenshot (PNG and EXR)" },
    { { "w" }, {}, false, A::SaveScene, Files, "save the scene (JSON)" },
  };
  // clang-format on
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
    if (std::find(binding.Aliases.begin(), binding.Aliases.end(), sym) != binding.Aliases.end())
    {
      return { &binding, 0 };
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
  // The first three groups on the left; keys padded to the column's widest.
  const auto& groups = Groups();
  std::array<std::string, 2> columns;
  for (size_t column = 0; column < 2; ++column)
  {
    const size_t first = column == 0 ? 0 : 3, last = column == 0 ? 3 : groups.size();
    size_t width = 0;
    for (const KeyBinding& binding : KeyBindings())
    {
      for (size_t g = first; g < last; ++g)
      {
        width =
          binding.Group == groups[g] ? std::max(width, KeysLabel(binding, " ").size()) : width;
      }
    }
    std::ostringstream out;
    for (size_t g = first; g < last; ++g)
    {
      out << (g == first ? "" : "\n") << groups[g] << ":\n";
      for (const KeyBinding& binding : KeyBindings())
      {
        if (binding.Group == groups[g])
        {
          std::string keys = KeysLabel(binding, " ");
          keys.resize(width, ' ');
          out << "  " << keys << "  " << binding.Description << "\n";
        }
      }
    }
    columns[column] = out.str();
  }
  columns[1] += "\nmouse: docs/viewer.md lists it";
  return columns;
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
        for (const auto* list : { &binding.Keys, &binding.Aliases })
        {
          for (const std::string& key : *list)
          {
            keys += (keys.empty() ? "" : ", ") + ("`" + KeyLabel(key, binding.Control) + "`");
          }
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
