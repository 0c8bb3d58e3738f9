// Transfer-function presets: finding a preset file and reading it into cloudvis's own form, so
// the scene validates a preset's points with the very readers that check transfer_function keys
// (Scene.cxx). Two formats are read:
//
// - cloudvis's own: an object {"name", "description", "opacity": [[d, a], ...],
//   "color": [[d, r, g, b], ...], "unit_distance"}; the shipped presets in data/presets/ are in
//   it. It is returned as written and checked by the scene (unknown keys included).
// - ParaView's JSON colormap presets: a list of objects with "Name", "ColorSpace",
//   "RGBPoints": [x, r, g, b, ...] and optionally "Points": [x, opacity, midpoint, sharpness, ...]
//   for opacity. RGBPoints become color points and Points opacity points, x taken as density as
//   written (ParaView would rescale a preset to the data range; cloudvis does not). Midpoint and
//   sharpness are ignored (the transfer functions are piecewise linear), so is ColorSpace (colors
//   are interpolated in RGB). Checked here, so messages name ParaView's keys.
//
// The scene key is transfer_function.preset; docs/scene-format.md documents both formats.
#ifndef cloudvis_Presets_h
#define cloudvis_Presets_h

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace cloudvis
{

// Where named presets are looked up: $CLOUDVIS_PRESET_DIR when set and not empty, else the
// data/presets folder of the source tree cloudvis was built from.
std::string PresetDirectory();

// The names of the presets in PresetDirectory() (file names without ".json"), sorted.
std::vector<std::string> ShippedPresetNames();

struct PresetDocument
{
  std::string Path;   // the file read, as opened
  bool ParaView = false;
  std::string Name;   // a ParaView file: the Name of the preset taken; else the "name" key, if any
  // cloudvis's form: the file itself for cloudvis's format (unchecked beyond being an object); for
  // ParaView, {"name", "color", "opacity"?} built from the chosen preset (checked).
  nlohmann::json Document;
};

// Locates and reads a preset. `reference` is a name (letters, digits, '-' and '_': the file
// PresetDirectory()/NAME.json) or a path, relative to `baseDirectory` unless absolute (empty:
// the current directory). `paraViewName` picks a preset from a ParaView file holding several
// (empty: the first); it is an error for a file in cloudvis's format. Throws InputError whose
// message is the problem alone (the caller adds the scene and key), naming the file: an
// unknown name (listing the shipped ones), an unreadable file, malformed JSON (file, line and
// column), a ParaView file without usable points, x values that do not increase, values out of
// [0, 1].
PresetDocument ReadPreset(
  const std::string& reference, const std::string& baseDirectory, const std::string& paraViewName);

} // namespace cloudvis

#endif
