// What the command files (Commands.cxx, CompareCommand.cxx, ExportCommands.cxx, ViewCommand.cxx)
// share: the options several commands take, the parsing of option values that stand for scene keys,
// the handling of an operand that is a field file rather than a scene, and the commands defined
// outside Commands.cxx, which the command table lists.
#ifndef cloudvis_CommandSupport_h
#define cloudvis_CommandSupport_h

#include "CommandLine.h"
#include "Scene.h"

#include <nlohmann/json.hpp>
#include <vtkSmartPointer.h>

#include <functional>
#include <string>
#include <vector>

class vtkImageData;

namespace cloudvis
{

extern const OptionSpec SetOption;  // --set KEY=VALUE, repeatable
extern const OptionSpec HelpOption; // --help, -h
extern const OptionSpec ImageOutputOption; // -o IMAGE.png of render and compare

// --lighting MODEL, listing the model names of the scene language.
OptionSpec LightingOption();

// --size WxH as the JSON value of render.size; the scene checks the range. Throws UsageError
// naming `command` when the text is not of that form.
nlohmann::json ParseSizeOption(const std::string& command, const std::string& text);

// A decimal number that is all of `text` (finite), or false.
bool ParseNumber(const std::string& text, double& value);

// The value of a count option (--frames, --benchmark, --pieces): an integer in [1, 999999].
// Throws UsageError "COMMAND: --OPTION expects a number of UNIT in [1, 999999], got ...".
int ParseCount(const std::string& command,
  const std::string& option,
  const std::string& text,
  const std::string& unit);

// The options that say how a field file operand is read: --field-format, --array, --time-step
// (field.format, field.array, field.time_step). Every command that takes a field file lists them.
extern const std::vector<OptionSpec> FieldFileOptions;

// Whether the operand `input` is a field file rather than a scene: its extension is a field
// format's (FieldIO.h), or --field-format names its format.
bool IsFieldOperand(const std::string& input, const Arguments& arguments);

// Adds the scene overrides the field file options stand for.
void AddFieldFileOverrides(const Arguments& arguments, std::vector<SceneOverride>& overrides);

// The scene of the operand `input`, with --set and `overrides` (AddFieldFileOverrides is added
// here): for a field file, LoadFieldFileScene (after refusing --set keys that do not apply to a
// field file: procedural field keys, and with `fieldKeysOnly` every key outside field), else
// LoadScene.
Scene LoadOperandScene(const std::string& command,
  const std::string& input,
  const Arguments& arguments,
  std::vector<SceneOverride> overrides,
  bool fieldKeysOnly = false);

// The operand of render and compare, a scene or a field file, validated with its --set
// assignments and option overrides and turned into its field. The cheap checks come first (field
// keys set for a field file, a bad -o, scene values, the display when `needsDisplay`): none of
// them should cost a field's generation.
struct SceneInput
{
  Scene Loaded;
  vtkSmartPointer<vtkImageData> Field;
};
SceneInput LoadSceneInput(const std::string& command,
  const Arguments& arguments,
  const std::vector<SceneOverride>& options,
  const std::string& output,
  bool needsDisplay,
  const std::function<void(double)>& generationProgress = {});

// The commands defined in their own files.
CommandSpec CompareCommand(); // CompareCommand.cxx
CommandSpec AnimateCommand(); // ExportCommands.cxx
CommandSpec ViewCommand();    // ViewCommand.cxx

} // namespace cloudvis

#endif
