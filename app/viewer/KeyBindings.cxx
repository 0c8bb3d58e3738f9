// The key and mouse tables and what is made from them: key lookup, the help overlay's pages, the
// docs' tables.
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
    { ',', "comma" },
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
    { { "4" }, {}, false, A::ToggleLayout, View, "four views / 3D view alone" },
    { { "v" }, {}, false, A::ToggleVolume, View, "show / hide the cloud", true },
    { { "b" }, {}, false, A::ToggleLegends, View, "show / hide the legends" },
    { { "r" }, {}, false, A::ResetCamera, View, "reset camera and slice zoom", true },
    { { "z" }, {}, true, A::Undo, View, "undo the last change", true },
    { { "y" }, { "Z" }, true, A::Redo, View, "redo", true },
    { { "h" }, {}, false, A::Help, View, "help: keys, mouse, off" },
    { { "Escape" }, {}, false, A::Close, View, "close help, cancel typing" },
    { { "q" }, {}, false, A::Quit, View, "quit (asks if unsaved)" },
    { { "x", "y", "z" }, {}, false, A::ToggleSlice, Slices, "slice across x, y, z (3D)", true },
    { { "o" }, {}, false, A::ToggleOblique, Slices, "oblique slice in 3D", true },
    { { "c" }, {}, false, A::CycleSliceColors, Slices, "next slice colormap", true },
    { { "Prior", "Next" }, {}, false, A::StepSlice, Slices, "step the pointer's slice", true },
    { { "comma", "period" }, {}, false, A::StepTime, View, "previous / next time step", true },
    { { "a" }, {}, false, A::AutoWindowLevel, Slices, "auto window/level", true },
    { { "A" }, {}, false, A::ResetWindowLevel, Slices, "reset window/level", true },
    { { "L" }, {}, false, A::TypeWindowLevel, Slices, "type the window and level" },
    { { "m" }, {}, false, A::CycleLighting, Rendering, "next lighting model", true },
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
    // The exposure is the composite pass's alone: the converged still is shown again, not marched.
    { { "e", "E" }, {}, false, A::StepExposure, Rendering, "exposure - / + 1/2 EV" },
    { { "e" }, {}, true, A::AutoExposure, Rendering, "automatic exposure" },
    { { "p" }, {}, false, A::NextPreset, Function, "next preset", true },
    { { "P" }, {}, false, A::SavePreset, Function, "save as a preset file" },
    { { "l" }, {}, false, A::HistogramScale, Function, "histogram: log / linear" },
    { { "f" }, {}, false, A::FitTransferFunction, Function, "fit the points to the data", true },
    { { "R" }, {}, false, A::ResetTransferFunction, Function, "back to the opened function", true },

    { { "Delete" },
      { "BackSpace" },
      false,
      A::DeletePoint,
      Function,
      "remove the selected point",
      true },
    { { "Return" }, { "KP_Enter" }, false, A::TypePointValues, Function, "type its values" },
    { { "s" }, {}, false, A::Screenshot, Files, "screenshot (PNG, EXR)" },
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

namespace
{

// How help and docs write a key ("plus" -> "+", "Escape" -> "Esc", Control -> "Ctrl+").
std::string KeyLabel(const std::string& keySym, bool control)
{
  static const std::map<std::string, std::string> labels = { { "Escape", "Esc" },
    { "KP_Add", "keypad +" },
    { "KP_Subtract", "keypad -" },
    { "KP_Enter", "keypad Enter" },
    { "Prior", "PageUp" },
    { "Next", "PageDown" },
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

// Every mouse binding, grouped by where, in the order help and docs list them.
const std::vector<MouseBinding>& MouseBindings()
{
  // clang-format off: one row per binding.
  // where, action, effect (help and docs), more (docs only)
  static const std::vector<MouseBinding> table = {
    { "3D view",
      "left drag",
      "rotate",
      "trackball camera; the camera turns only while the mouse moves, also when the drag starts "
      "on a slice" },
    { "3D view", "middle drag, Shift+left drag", "pan", "" },
    { "3D view", "right drag, wheel", "zoom", "" },
    { "3D view", "Ctrl+left drag, away from the slices", "spin about the view direction", "" },
    { "a slice in 3D", "pointer over it", "readout of the voxel under the pointer", "" },
    { "a slice in 3D",
      "Ctrl+left click or drag",
      "probe, move the crosshair",
      "the other two slices move through the voxel; the readout stays after release" },
    { "a slice in 3D",
      "middle drag",
      "move the slice along its normal",
      "voxel by voxel; a slice facing the camera moves up (toward you) and down with the mouse" },
    { "a slice in 3D",
      "right drag",
      "window/level of every slice",
      "right: wider window, up: higher level" },
    { "oblique slice", "drag arrow / plane / origin", "tilt / push / move it", "" },
    { "slice view", "pointer over it", "readout of the voxel under the pointer", "" },
    { "slice view", "wheel", "step the slice one voxel", "" },
    { "slice view", "Ctrl+wheel", "zoom about the pointer", "r fits the slices again" },
    { "slice view", "Shift+left drag", "pan", "the slice follows the pointer" },
    { "slice view",
      "left click or drag",
      "probe, move the crosshair",
      "the other two slices move through the voxel" },
    { "slice view", "middle drag", "move the slice", "one voxel per 4 pixels" },
    { "slice view", "right drag", "window/level of every slice", "" },
    { "editor", "click a point", "select it", "its values show at the top left of the editor" },
    { "editor", "click empty opacity chart", "add a point (selected)", "" },
    { "editor",
      "drag an opacity point",
      "move it",
      "the end points move up and down (and inward), inner points anywhere between their "
      "neighbours" },
    { "editor", "drag a color point", "move it along density", "the end points inward too" },
    { "editor",
      "click a palette swatch",
      "color the selected color point",
      "the palette shows while a color point is selected" },
    { "editor", "wheel", "nothing", "the charts always show the transfer function's range" },
  };
  // clang-format on
  return table;
}
// The help's label of a binding's keys: the keypad's twins of other keys are left to the docs, so
// that the help fits a small window in a readable font.
std::string KeysLabel(const KeyBinding& binding, const char* separator)
{
  std::string text;
  for (const std::string& key : binding.Keys)
  {
    const std::string label = KeyLabel(key, binding.Control);
    if (label.rfind("keypad ", 0) != 0 || binding.Keys.size() == 1)
    {
      text += (text.empty() ? "" : separator) + label;
    }
  }
  return text;
}

// A help row: its group, what to press, what it does.
struct HelpRow
{
  std::string Group, Input, Effect;
};

// A column of the help: `groups` in order, each a heading and its rows, the inputs padded to the
// group's widest (the help is drawn in a fixed-width font).
std::string HelpColumn(const std::vector<std::string>& groups, const std::vector<HelpRow>& rows)
{
  std::ostringstream out;
  for (const std::string& group : groups)
  {
    size_t width = 0;
    for (const HelpRow& row : rows)
    {
      if (row.Group == group)
      {
        width = std::max(width, row.Input.size());
      }
    }
    out << (group == groups.front() ? "" : "\n") << group << ":\n";
    for (const HelpRow& row : rows)
    {
      if (row.Group == group)
      {
        std::string input = row.Input;
        input.resize(width, ' ');
        out << "  " << input << "  " << row.Effect << "\n";
      }
    }
  }
  return out.str();
}
} // namespace

std::vector<HelpPage> HelpPages()
{
  std::vector<HelpRow> keys;
  for (const KeyBinding& binding : KeyBindings())
  {
    keys.push_back({ binding.Group, KeysLabel(binding, " "), binding.Description });
  }
  std::vector<HelpRow> mouse;
  std::vector<std::string> places;
  for (const MouseBinding& binding : MouseBindings())
  {
    mouse.push_back({ binding.Where, binding.Action, binding.Effect });
    if (std::find(places.begin(), places.end(), binding.Where) == places.end())
    {
      places.push_back(binding.Where);
    }
  }
  // The keys in two columns, their first two groups on the left; the mouse in one column, whose
  // rows are too wide for two, on two pages: the 3D view's places, then the slice views' and the
  // editor's (one page would not fit a small window in a readable font).
  const auto& groups = Groups();
  const std::vector<std::string> left(groups.begin(), groups.begin() + 2),
    right(groups.begin() + 2, groups.end());
  const auto firstOf2D = std::find(places.begin(), places.end(), std::string("slice view"));
  const std::vector<std::string> mouse3D(places.begin(), firstOf2D),
    mouse2D(firstOf2D, places.end());
  return { { "keys",
             { { "KEYS   (h: the mouse, Esc: close)\n\n" + HelpColumn(left, keys),
               HelpColumn(right, keys) } } },
    { "mouse-3d",
      { { "MOUSE IN 3D   (h: the slice views and the editor, Esc: close)\n\n" +
            HelpColumn(mouse3D, mouse),
        "" } } },
    { "mouse-2d",
      { { "MOUSE IN THE SLICE VIEWS AND THE EDITOR   (h or Esc: close)\n\n" +
            HelpColumn(mouse2D, mouse),
        "" } } } };
}

namespace
{
// A '|' would end a Markdown table cell.
std::string TableCell(std::string text)
{
  for (size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2))
  {
    text.replace(at, 1, "\\|");
  }
  return text;
}
} // namespace

std::string ViewerMouseMarkdown()
{
  std::ostringstream out;
  out << "| where | action | effect |\n|---|---|---|\n";
  for (const MouseBinding& binding : MouseBindings())
  {
    const std::string more = *binding.More ? std::string(": ") + binding.More : "";
    out << "| " << TableCell(binding.Where) << " | " << TableCell(binding.Action) << " | "
        << TableCell(binding.Effect + more) << " |\n";
  }
  return out.str();
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
        out << "| " << keys << " | " << group << " | " << TableCell(binding.Description) << " |\n";
      }
    }
  }
  return out.str();
}

} // namespace cloudvis
