// The command table and the commands. Each command is a short function over the library:
// LoadScene -> ProduceField -> WriteField or ComputeFieldStatistics; options shared between
// commands (--set, --help) are defined once and listed by each command that takes them.
#include "CommandLine.h"

#include "../analysis/FieldStatistics.h"
#include "../io/AtomicFile.h"
#include "../io/Errors.h"
#include "../io/FieldIO.h"
#include "../io/Scene.h"
#include "../io/SceneField.h"

#include <vtkImageData.h>

#include <cerrno>
#include <cstring>
#include <sys/stat.h>

namespace cloudvis
{
namespace
{

const OptionSpec SetOption{ "set", 0, "KEY=VALUE",
  "override a scene value before validation, e.g. --set field.octaves=4 or "
  "--set field.dimensions=64,64,64 (see docs/scene-format.md)",
  true };
const OptionSpec HelpOption{ "help", 'h', "", "show this help and exit" };
const OptionSpec OutputOption{ "output", 'o', "FIELD.vti",
  "write the field to this file (VTK XML image data, zlib-compressed); required", false,
  true };
const OptionSpec JsonOption{ "json", 0, "", "print the statistics as one JSON object" };

bool EndsWith(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() &&
    text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string DescribeDimensions(vtkImageData* field)
{
  int d[3];
  field->GetDimensions(d);
  return std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]);
}

int Generate(const Arguments& arguments, std::ostream& out)
{
  if (!arguments.Has("output"))
  {
    throw UsageError("generate: missing the output file: -o FIELD.vti");
  }
  const std::string output = arguments.Value("output");
  // Before the work: a bad -o should not cost a field's generation time.
  CheckOutputTarget(output);
  const std::string scenePath = arguments.Operands.empty() ? "" : arguments.Operands[0];
  const Scene scene = LoadScene(scenePath, arguments.Values("set"));
  const vtkSmartPointer<vtkImageData> field = ProduceField(scene);
  WriteField(field, output);
  out << "wrote " << output << " (" << DescribeDimensions(field) << " voxels)\n";
  return ExitSuccess;
}

int Info(const Arguments& arguments, std::ostream& out)
{
  const std::string& input = arguments.Operands[0];
  vtkSmartPointer<vtkImageData> field;
  if (EndsWith(input, ".vti"))
  {
    if (arguments.Has("set"))
    {
      throw UsageError("info: --set applies to scenes, not to the field file " + input);
    }
    field = ReadField(input);
  }
  else
  {
    field = ProduceField(LoadScene(input, arguments.Values("set")));
  }
  const FieldStatistics statistics = ComputeFieldStatistics(field);
  if (arguments.Has("json"))
  {
    out << FieldStatisticsToJson(statistics, input).dump(2) << "\n";
  }
  else
  {
    PrintFieldStatistics(out, statistics, input);
  }
  return ExitSuccess;
}

} // namespace

int RunDefault(std::ostream& out)
{
  const std::string directory = "out";
  const std::string output = directory + "/default.vti";
  if (::mkdir(directory.c_str(), 0777) != 0 && errno != EEXIST)
  {
    throw InputError(directory + ": cannot create the output directory (" + std::strerror(errno) + ")");
  }
  CheckOutputTarget(output);
  const Scene scene = LoadScene("", {});
  const vtkSmartPointer<vtkImageData> field = ProduceField(scene);
  WriteField(field, output);
  out << "wrote " << output << " (" << DescribeDimensions(field) << " voxels)\n\n";
  PrintFieldStatistics(out, ComputeFieldStatistics(field), output);
  return ExitSuccess;
}

const std::vector<CommandSpec>& Commands()
{
  static const std::vector<CommandSpec> commands = {
    { "generate", "[SCENE]", 0, 1, "generate a scene's density field and write it to a .vti file",
      "SCENE is a scene file (JSON, see docs/scene-format.md); without it the default scene is\n"
      "used (a unit sphere plus 6 octaves of value noise on 128^3 voxels). If the scene's field\n"
      "names a .vti file, that file is loaded, checked and written out as a float \"density\"\n"
      "field. The output is written to a temporary file next to FIELD.vti and renamed over it\n"
      "once complete: on failure FIELD.vti is left as it was.",
      { OutputOption, SetOption, HelpOption }, Generate },
    { "info", "FIELD.vti|SCENE", 1, 1, "print statistics of a .vti field or of a scene's field",
      "An argument ending in .vti is read as a field; anything else is a scene file whose field\n"
      "is generated (or loaded). Prints dimensions, spacing, bounds (origin .. origin +\n"
      "(n-1) spacing), value range, mean, the fraction of non-empty voxels (density > 0) and a\n"
      "16-bin histogram over [min, max]. --set applies to scenes only.",
      { JsonOption, SetOption, HelpOption }, Info },
  };
  return commands;
}

} // namespace cloudvis
