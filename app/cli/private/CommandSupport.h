// What the command files (Commands.cxx, ExportCommands.cxx, ViewCommand.cxx) share: the options
// several commands take, the parsing of option values that stand for scene keys, the handling
// of an operand that is a field file rather than a scene, and the commands defined outside
// Commands.cxx, which the command table lists.
#ifndef cloudvis_CommandSupport_h
#define cloudvis_CommandSupport_h

#include "CommandLine.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace cloudvis
{

extern const OptionSpec SetOption;  // --set KEY=VALUE, repeatable
extern const OptionSpec HelpOption; // --help, -h

// --lighting MODEL, listing the model names of the scene language.
OptionSpec LightingOption();

// --size WxH as the JSON value of render.size; the scene checks the range. Throws UsageError
// naming `command` when the text is not of that form.
nlohmann::json ParseSizeOption(const std::string& command, const std::string& text);

// Throws UsageError when one of the --set assignments sets a field key: a field file has no
// procedural parameters, so `command` refuses them.
void RefuseFieldKeys(const std::string& command,
  const std::string& fieldFile,
  const std::vector<std::string>& assignments);

// The commands defined in their own files.
CommandSpec AnimateCommand(); // ExportCommands.cxx
CommandSpec ViewCommand();    // ViewCommand.cxx

} // namespace cloudvis

#endif
