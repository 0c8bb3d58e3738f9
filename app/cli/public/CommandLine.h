// The command line of cloudvis: a table of commands, each with its options, operands, help text
// and the function that runs it. Parsing, dispatch, help and the mapping of failures onto exit
// statuses are written once, over that table; adding a command (render, compare, ...) is adding
// an entry. main() only forwards to RunCommandLine.
#ifndef cloudvis_CommandLine_h
#define cloudvis_CommandLine_h

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace cloudvis
{

// Exit statuses: documented in docs/command-line.md.
enum ExitStatus
{
  ExitSuccess = 0,
  ExitFailure = 1, // bad input or failed output
  ExitUsage = 2,   // unknown command or option, missing argument
};

struct OptionSpec
{
  std::string Long;  // "output" for --output
  char Short = 0;    // 'o' for -o, 0 for none
  std::string Value; // name of the value in help ("FILE"); empty for a flag
  std::string Help;
  bool Repeatable = false;
  bool Required = false; // shown without brackets in the usage line; the command checks it
};

// The result of parsing one command's arguments.
struct Arguments
{
  std::vector<std::string> Operands;
  std::map<std::string, std::vector<std::string>> Options; // long name -> values ("" for flags)
  std::vector<std::string> CommandLine; // the whole command line, as main() got it (metadata)

  bool Has(const std::string& option) const { return this->Options.count(option) > 0; }
  std::string Value(const std::string& option) const;              // last value, or ""
  std::vector<std::string> Values(const std::string& option) const; // all values, in order
};

struct CommandSpec
{
  std::string Name;
  std::string Operands; // e.g. "[SCENE]", for the usage line
  size_t MinOperands = 0;
  size_t MaxOperands = 0;
  std::string Summary;     // one line, for the command list
  std::string Description; // paragraphs for COMMAND --help
  std::vector<OptionSpec> Options;
  int (*Run)(const Arguments& arguments, std::ostream& out) = nullptr;
};

// The commands, in the order help lists them.
const std::vector<CommandSpec>& Commands();

// What `cloudvis` with no arguments does: generate the default scene into out/default.vti, render
// it to out/default.png and print its statistics. Needs an X display.
int RunDefault(std::ostream& out);

// The whole program: arguments as main() gets them (arguments[0] is the program name). Prints
// results on `out`, errors on `err` as "cloudvis: error: ...", returns the exit status. Bytes
// that are not UTF-8 (in paths, --set values) are printed escaped as \xNN on both (Utf8.h).
int RunCommandLine(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err);

} // namespace cloudvis

#endif
