// The viewer's keys and mouse, written once: each key binding is a row of (keys, action, group,
// description). The same table drives the key handler (FindKeyBinding), the help overlay's first
// page (HelpPages) and the key list of docs/viewer.md (ViewerKeysMarkdown, printed by `cloudvis
// view --keys`; a test fails when the document and the table disagree). A row may hold several
// keys for one action with a variant (x, y, z toggle the slice across their axis): the handler
// receives the index of the key that was pressed. The mouse bindings are a second table, of
// (where, action, effect): the interactor style and the widgets implement them, and the table
// makes the help overlay's mouse page and docs/viewer.md's mouse list (`cloudvis view --mouse`,
// checked by the same test).
#ifndef cloudvis_KeyBindings_h
#define cloudvis_KeyBindings_h

#include <array>
#include <string>
#include <vector>

namespace cloudvis
{

enum class ViewerAction
{
  ToggleSlice, // variant: axis
  ToggleOblique,
  CycleSliceColors,
  StepSlice, // variant 0: up (PageUp), 1: down
  StepTime,  // variant 0: back (,), 1: forward (.)
  AutoWindowLevel,
  ResetWindowLevel,
  TypeWindowLevel,
  ToggleLayout,
  ToggleVolume,
  ToggleLegends,
  CycleLighting,
  MoveLightAzimuth,   // variant 0: left, 1: right
  MoveLightElevation, // variant 0: up, 1: down
  StepLarger,
  StepSmaller,
  ResolutionDown,
  ResolutionUp,
  StepExposure, // variant 0: down (e), 1: up (E)
  AutoExposure,
  NextPreset,
  SavePreset,
  HistogramScale,
  FitTransferFunction,
  ResetTransferFunction,
  Undo,
  Redo,
  DeletePoint,
  TypePointValues,
  Screenshot,
  SaveScene,
  ResetCamera,
  Help,
  Close, // Esc: closes what is open (the help); typing takes its own Esc first
  Quit
};

struct KeyBinding
{
  std::vector<std::string> Keys;    // X key symbols ("x", "plus", "Left", "Delete"), a variant each
  std::vector<std::string> Aliases; // other keys for the first variant (docs list them, help not)
  bool Control;                     // with the Control key held
  ViewerAction Action;
  const char* Group;
  const char* Description;
  // The key changes how the cloud is drawn: the first frame after it renders at interactive
  // resolution, for a quick answer, and the full-resolution image refines from there.
  bool RedrawsCloud = false;
};

// Every binding, in the order help and docs list them.
const std::vector<KeyBinding>& KeyBindings();

struct KeyMatch
{
  const KeyBinding* Binding = nullptr; // none: not a viewer key
  int Variant = 0;                     // index of the key pressed in Binding->Keys
};

// The binding of a key press. `keySym` is the X key symbol; when it is empty (a recording or a
// caller that gave only the character) `keyCode` is looked up instead.
KeyMatch FindKeyBinding(const std::string& keySym, char keyCode, bool control);

// The key symbol X names a character by ('+' -> "plus", 'a' -> "a"); empty for 0.
std::string KeySymOfCharacter(char character);

struct MouseBinding
{
  const char* Where;  // "3D view", "slice view", "editor", ...
  const char* Action; // "left drag", "wheel", ...
  const char* Effect; // short: the help overlay shows it
  const char* More;   // details docs/viewer.md adds after a colon ("" for none)
};

// The help overlay's pages, each two columns of text: "keys" by group, then "mouse-3d" and
// "mouse-2d" by where (the 3D view's places; the slice views' and the editor's).
// Each page's first line names it and says what h and Esc do next.
struct HelpPage
{
  std::string Name;
  std::array<std::string, 2> Columns;
};
std::vector<HelpPage> HelpPages();

} // namespace cloudvis

#endif
