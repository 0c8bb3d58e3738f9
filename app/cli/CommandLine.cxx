// Generic parsing, help and dispatch over the command table (the table itself and the commands
// live in Commands.cxx). Options follow GNU conventions: --name VALUE, --name=VALUE, -o VALUE,
// and "--" ends the options.
#include "CommandLine.h"

#include "CloudFieldGeometry.h" // AvailableMemoryBytes, FormatBytes

#include "Errors.h"
#include "FieldIO.h"
#include "FieldSeries.h"
#include "OutOfMemory.h"
#include "ProcessGroup.h"
#include "Utf8.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <new>
#include <sstream>
#include <streambuf>

#include <sys/resource.h>

namespace cloudvis
{

namespace
{
// "out of memory while generating a field of 2048 x 2048 x 512 voxels (big.json), which needs
// about 8 GiB; 20.1 GiB of memory is available, and the address-space limit (ulimit -v) is
// 5.72 GiB": the step that ran out (OutOfMemory.h) and what this process could have had.
std::string OutOfMemoryReport()
{
  std::string text = "out of memory";
  if (const std::optional<FailedMemoryUse> use = TakeFailedMemoryUse())
  {
    text += " while " + use->What +
      (use->Bytes > 0.0 ? ", which needs about " + FormatBytes(use->Bytes) : std::string());
  }
  if (const std::uint64_t available = AvailableMemoryBytes())
  {
    text += "; " + FormatBytes(double(available)) + " of memory is available";
  }
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
  {
    text += ", and the address-space limit (ulimit -v) is " + FormatBytes(double(limit.rlim_cur));
  }
  return text;
}

const OptionSpec* FindOption(const CommandSpec& command, const std::string& argument)
{
  for (const OptionSpec& option : command.Options)
  {
    if (argument == "--" + option.Long || (option.Short && argument == std::string("-") + option.Short))
    {
      return &option;
    }
  }
  return nullptr;
}

std::string OptionTitle(const OptionSpec& option)
{
  std::string title = option.Short ? std::string("-") + option.Short + ", " : "    ";
  title += "--" + option.Long;
  if (!option.Value.empty())
  {
    title += " " + option.Value;
  }
  return title;
}

// Breaks text into lines of at most `width` characters, continuation lines indented.
std::string Wrap(const std::string& text, size_t indent, size_t width)
{
  std::istringstream words(text);
  std::string word, wrapped, line;
  while (words >> word)
  {
    if (!line.empty() && indent + line.size() + 1 + word.size() > width)
    {
      wrapped += line + "\n" + std::string(indent, ' ');
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return wrapped + line;
}

std::string UsageLine(const CommandSpec& command)
{
  std::string usage = "cloudvis " + command.Name;
  if (!command.Operands.empty())
  {
    usage += " " + command.Operands;
  }
  for (const OptionSpec& option : command.Options)
  {
    if (option.Long == "help")
    {
      continue;
    }
    const std::string name =
      option.Short ? std::string("-") + option.Short : "--" + option.Long;
    const std::string text = option.Value.empty() ? name : name + " " + option.Value;
    usage += option.Required ? " " + text : option.Repeatable ? " [" + text + "]..." : " [" + text + "]";
  }
  return usage;
}

const CommandSpec* FindCommand(const std::string& name)
{
  for (const CommandSpec& command : Commands())
  {
    if (command.Name == name)
    {
      return &command;
    }
  }
  return nullptr;
}

std::string CommandNames()
{
  std::string names;
  for (const CommandSpec& command : Commands())
  {
    names += (names.empty() ? "" : ", ") + command.Name;
  }
  return names;
}

} // namespace

std::string Arguments::Value(const std::string& option) const
{
  const auto found = this->Options.find(option);
  return found == this->Options.end() || found->second.empty() ? "" : found->second.back();
}

std::vector<std::string> Arguments::Values(const std::string& option) const
{
  const auto found = this->Options.find(option);
  return found == this->Options.end() ? std::vector<std::string>{} : found->second;
}

namespace
{

// Parses a command's arguments (everything after the command name). --help is handled by the
// caller. Throws UsageError.
Arguments ParseArguments(const CommandSpec& command, const std::vector<std::string>& arguments)
{
  Arguments parsed;
  bool optionsEnded = false;
  for (size_t i = 0; i < arguments.size(); ++i)
  {
    const std::string& argument = arguments[i];
    if (optionsEnded || argument.size() < 2 || argument[0] != '-')
    {
      parsed.Operands.push_back(argument);
      continue;
    }
    if (argument == "--")
    {
      optionsEnded = true;
      continue;
    }
    // --name=value carries its value inline.
    const auto equals = argument.rfind("--", 0) == 0 ? argument.find('=') : std::string::npos;
    const std::string name = argument.substr(0, equals);
    const OptionSpec* option = FindOption(command, name);
    if (!option)
    {
      throw UsageError(command.Name + ": unknown option " + name);
    }
    std::string value;
    if (option->Value.empty())
    {
      if (equals != std::string::npos)
      {
        throw UsageError(command.Name + ": option --" + option->Long + " takes no value");
      }
    }
    else if (equals != std::string::npos)
    {
      value = argument.substr(equals + 1);
    }
    else if (i + 1 < arguments.size())
    {
      value = arguments[++i];
    }
    else
    {
      throw UsageError(command.Name + ": option " + name + " needs a value (" + option->Value + ")");
    }
    if (!option->Repeatable && parsed.Has(option->Long))
    {
      throw UsageError(command.Name + ": option --" + option->Long + " given more than once");
    }
    parsed.Options[option->Long].push_back(value);
  }
  if (parsed.Has("help"))
  {
    return parsed;
  }
  if (parsed.Operands.size() < command.MinOperands)
  {
    throw UsageError(command.Name + ": missing argument " + command.Operands);
  }
  if (parsed.Operands.size() > command.MaxOperands)
  {
    // `cloudvis view les_*.nc` unquoted: the shell handed over the files of a series.
    const std::string series = command.MaxOperands == 1 && IsFieldFile(parsed.Operands[0])
      ? SeriesPatternOf(parsed.Operands[0], parsed.Operands[1])
      : "";
    throw UsageError(command.Name + ": unexpected argument \"" +
      parsed.Operands[command.MaxOperands] + "\"" +
      (series.empty() ? ""
                      : "; to open numbered files as one time series, quote their pattern so "
                        "that the shell leaves it to cloudvis: '" +
            series + "'"));
  }
  return parsed;
}

std::string CommandHelp(const CommandSpec& command)
{
  std::ostringstream help;
  help << "Usage: " << UsageLine(command) << "\n\n" << command.Summary << "\n\n";
  if (!command.Description.empty())
  {
    help << command.Description << "\n\n";
  }
  help << "Options:\n";
  for (const OptionSpec& option : command.Options)
  {
    const std::string title = OptionTitle(option);
    help << "  " << title << std::string(title.size() < 24 ? 24 - title.size() : 1, ' ')
         << Wrap(option.Help + (option.Repeatable ? " (repeatable)" : ""), 26, 92) << "\n";
  }
  return help.str();
}

std::string GeneralHelp()
{
  std::ostringstream help;
  help << "Usage: cloudvis [COMMAND [OPTIONS]...]\n\n"
       << "Generate and inspect procedural cloud density fields.\n\n"
       << "Without a command, cloudvis generates the default scene (a unit sphere plus 6 octaves\n"
       << "of value noise) into out/default.vti, renders it to out/default.png and prints its\n"
       << "statistics. Rendering needs an X display; headless: xvfb-run -a cloudvis ...\n\n"
       << "Commands:\n";
  for (const CommandSpec& command : Commands())
  {
    help << "  " << command.Name << std::string(command.Name.size() < 12 ? 12 - command.Name.size() : 1, ' ')
         << command.Summary << "\n";
  }
  help << "\nUsage of each command:\n";
  for (const CommandSpec& command : Commands())
  {
    help << "  " << UsageLine(command) << "\n";
  }
  help << "\nOptions:\n"
       << "  -h, --help              show this help; 'cloudvis COMMAND --help' describes a command\n"
       << "\nExit status: 0 on success, 1 for bad input or failed output, 2 for usage errors.\n"
       << "Scene files: docs/scene-format.md. Command line: docs/command-line.md.\n";
  return help.str();
}

// What a command prints on standard output, passed on with every byte that is not UTF-8
// escaped (EscapeInvalidUtf8): commands print paths and scene text, which may hold any bytes.
// Complete lines are passed on, so a multi-byte character is never split; a flush passes the
// rest.
class Utf8Output : public std::streambuf
{
public:
  explicit Utf8Output(std::ostream& target)
    : Target(target)
  {
  }
  ~Utf8Output() override { this->sync(); }

protected:
  int_type overflow(int_type c) override
  {
    if (!traits_type::eq_int_type(c, traits_type::eof()))
    {
      const char character = traits_type::to_char_type(c);
      this->xsputn(&character, 1);
    }
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* text, std::streamsize count) override
  {
    this->Pending.append(text, std::size_t(count));
    const auto lineEnd = this->Pending.rfind('\n');
    if (std::memchr(text, '\n', std::size_t(count)) && lineEnd != std::string::npos)
    {
      this->Target << EscapeInvalidUtf8(this->Pending.substr(0, lineEnd + 1));
      this->Pending.erase(0, lineEnd + 1);
    }
    return count;
  }
  int sync() override
  {
    this->Target << EscapeInvalidUtf8(this->Pending);
    this->Pending.clear();
    this->Target.flush();
    return this->Target ? 0 : -1;
  }

private:
  std::ostream& Target;
  std::string Pending;
};

} // namespace

int RunCommandLine(const std::vector<std::string>& arguments,
  std::ostream& rawOut,
  std::ostream& err)
{
  Utf8Output escaping(rawOut);
  std::ostream out(&escaping);
  std::string hint = "run 'cloudvis --help' for usage";
  try
  {
    if (arguments.size() < 2)
    {
      return RunDefault(out);
    }
    const std::string& name = arguments[1];
    if (name == "--help" || name == "-h" || name == "help")
    {
      const CommandSpec* command = arguments.size() > 2 ? FindCommand(arguments[2]) : nullptr;
      out << (command ? CommandHelp(*command) : GeneralHelp());
      return ExitSuccess;
    }
    const CommandSpec* command = FindCommand(name);
    if (!command)
    {
      throw UsageError(name[0] == '-' ? "unknown option " + name
                                      : "unknown command \"" + name + "\"; commands: " + CommandNames());
    }
    hint = "run 'cloudvis " + command->Name + " --help' for usage";
    // Every rank of an MPI job runs the whole command: only generate shares its work out
    // (FieldPieces.h); any other command would write the same files from every rank.
    if (LaunchedProcesses() > 1 && command->Name != "generate")
    {
      throw UsageError(command->Name + ": only generate runs in several MPI processes; this is " +
        "one of " + std::to_string(LaunchedProcesses()) + " started by mpirun: run " +
        command->Name + " without mpirun");
    }
    Arguments parsed =
      ParseArguments(*command, std::vector<std::string>(arguments.begin() + 2, arguments.end()));
    parsed.CommandLine = arguments;
    if (parsed.Has("help"))
    {
      out << CommandHelp(*command);
      return ExitSuccess;
    }
    return command->Run(parsed, out);
  }
  catch (const UsageError& e)
  {
    err << "cloudvis: error: " << EscapeInvalidUtf8(e.what()) << "\n"
        << "cloudvis: " << EscapeInvalidUtf8(hint) << "\n";
    return ExitUsage;
  }
  catch (const InputError& e)
  {
    err << "cloudvis: error: " << EscapeInvalidUtf8(e.what()) << "\n";
    return ExitFailure;
  }
  catch (const std::bad_alloc&)
  {
    err << "cloudvis: error: " << OutOfMemoryReport() << "\n";
    return ExitFailure;
  }
  catch (const std::exception& e)
  {
    err << "cloudvis: error: " << EscapeInvalidUtf8(e.what()) << "\n";
    return ExitFailure;
  }
}

} // namespace cloudvis
