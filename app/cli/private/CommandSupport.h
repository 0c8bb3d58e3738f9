// What the command files (Commands.cxx, CompareCommand.cxx, ExportCommands.cxx, ViewCommand.cxx)
// share: the options several commands take, the parsing of option values that stand for scene keys,
// the handling of an operand that is a field file rather than a scene, and the commands defined
// outside Commands.cxx, which the command table lists.
#ifndef cloudvis_CommandSupport_h
#define cloudvis_CommandSupport_h

#include "CommandLine.h"
#include "NoiseTarget.h"
#include "Scene.h"

#include <nlohmann/json.hpp>
#include <vtkSmartPointer.h>

#include <functional>
#include <optional>
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

// --time-steps A:B[:STRIDE]: the time steps A, A + STRIDE, ... up to B, counted from 0 (A <= B,
// STRIDE >= 1, 1 when not given; at most 999999 steps, as many as --frames allows). Throws
// UsageError naming `command` otherwise.
std::vector<int> ParseTimeSteps(const std::string& command, const std::string& text);

// The options that say how a field file operand is read: --field-format, --array, --time-step
// (field.format, field.array, field.time_step). Every command that takes a field file lists them.
extern const std::vector<OptionSpec> FieldFileOptions;

// Whether the operand `input` is a field file rather than a scene: its extension is a field
// format's (FieldIO.h), or --field-format names its format.
bool IsFieldOperand(const std::string& input, const Arguments& arguments);

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
// keys set for a field file, a bad -o, scene values, `checkScene` on the scene, the display when
// `needsDisplay`): none of them should cost a field's generation.
// The transfer function is fitted to the field's values as the viewer fits it
// (FitTransferFunctionToField); Note says what was done ("" when nothing), for the command's
// output.
struct SceneInput
{
  Scene Loaded;
  vtkSmartPointer<vtkImageData> Field;
  std::string Note;
};
SceneInput LoadSceneInput(const std::string& command,
  const Arguments& arguments,
  const std::vector<SceneOverride>& options,
  const std::string& output,
  bool needsDisplay,
  const std::function<void(double)>& generationProgress = {},
  const std::function<void(const Scene&)>& checkScene = {});

// The noise target of the GPU path tracer on the command line (NoiseTargetOptions.cxx): render's
// --spp P%, --spp-time, --accept-noise and compare's --reference pathtrace:P%, --reference-time,
// --accept-noise, parsed, checked and reported by one set of functions over the option names.
struct NoiseTargetOptions
{
  std::string Command;      // "render"
  std::string TargetOption; // "spp": the option whose value may be a percentage
  std::string TimeOption;   // "spp-time"
  std::string Example;      // "--spp 2%", in messages
};
extern const OptionSpec AcceptNoiseOption; // --accept-noise
// --TIME-OPTION SECONDS, the time limit of the noise target.
OptionSpec NoiseTimeOption(const NoiseTargetOptions& names);

// A value ending in '%' as a noise target: P% for a finite P in (0, 100] is the relative standard
// error P / 100; nullopt for a value without the '%' (a count of paths). Throws UsageError
// "COMMAND: --TARGET-OPTION: ..." naming the value for any other P.
std::optional<double> ParseNoisePercent(const NoiseTargetOptions& names, const std::string& value);

// The noise target of `relativeStandardError` (ParseNoisePercent's) with the time option (default
// DefaultNoiseTimeLimit) and --accept-noise; without one (nullopt), refuses those two options as
// meaningless with `given`, the value of the target option (empty: the option is absent).
// Throws UsageError.
std::optional<NoiseTarget> ReadNoiseTarget(const NoiseTargetOptions& names,
  const Arguments& arguments,
  std::optional<double> relativeStandardError,
  const std::string& given);

// "1536 paths per pixel, relative standard error 0.0198 (target 0.02), 41.2 s", and where the
// target was not reached (accepted), "; target not reached: <why>".
std::string DescribeNoiseReport(const NoiseTargetOptions& names, const NoiseReport& report);

// Throws InputError (exit status 1) when the target was not reached and not accepted: what noise
// was reached in how many paths and seconds, why it stopped, what the target needs at this rate,
// and the options that change the outcome. `given` is the target as typed (e.g. "2%").
void CheckNoiseReport(
  const NoiseTargetOptions& names, const std::string& given, const NoiseReport& report);

// The commands defined in their own files.
CommandSpec CompareCommand(); // CompareCommand.cxx
CommandSpec AnimateCommand(); // ExportCommands.cxx
CommandSpec ViewCommand();    // ViewCommand.cxx

} // namespace cloudvis

#endif
