// `cloudvis view`: the command-line side of the interactive viewer (viewer/Viewer.h): its
// options, the scene or field it opens, and what happens when the window closes.
#include "CommandSupport.h"

#include "AtomicFile.h"
#include "Display.h"
#include "Errors.h"
#include "ExportCommands.h"
#include "FieldIO.h"
#include "ImageWriters.h"
#include "InputFiles.h"
#include "SceneField.h"
#include "Utf8.h"
#include "Viewer.h"

#include <vtkImageData.h>

#include <array>
#include <regex>
#include <string>
#include <unistd.h>
#include <vector>

namespace cloudvis
{
namespace
{

// --size and --screenshot-size: WIDTHxHEIGHT.
std::array<int, 2> ParseWindowSize(const std::string& text, const std::string& option)
{
  static const std::regex form("([0-9]{1,5})[xX]([0-9]{1,5})");
  std::smatch match;
  if (!std::regex_match(text, match, form) || std::stoi(match[1]) < 64 ||
    std::stoi(match[2]) < 64 || std::stoi(match[1]) > 16384 || std::stoi(match[2]) > 16384)
  {
    throw UsageError("view: --" + option +
      " expects WIDTHxHEIGHT in pixels, each in [64, 16384] (for example 800x800), got \"" + text +
      "\"");
  }
  return { { std::stoi(match[1]), std::stoi(match[2]) } };
}

std::string Absolute(const std::string& path)
{
  if (!path.empty() && path[0] == '/')
  {
    return path;
  }
  char buffer[4096];
  return ::getcwd(buffer, sizeof(buffer)) ? std::string(buffer) + "/" + path : path;
}

int View(const Arguments& arguments, std::ostream& out)
{
  if (arguments.Has("keys"))
  {
    out << ViewerKeysMarkdown();
    return ExitSuccess;
  }
  if (arguments.Has("mouse"))
  {
    out << ViewerMouseMarkdown();
    return ExitSuccess;
  }
  const std::string input = arguments.Operands.empty() ? "" : arguments.Operands[0];
  const bool fieldFile = !input.empty() && IsFieldOperand(input, arguments);
  ViewerOptions options;
  const std::string saveOnExit = arguments.Value("save-scene-on-exit");
  options.SceneSavedOnExit = !saveOnExit.empty();
  const std::string windowImage = arguments.Value("window-image");
  const std::string play = arguments.Value("play");
  options.RecordFile = arguments.Value("record");
  options.OutputDirectory = arguments.Has("output-dir") ? arguments.Value("output-dir") : ".";
  options.StateFile = arguments.Value("state-file");
  // --layout stands for view.layout: it overrides a saved scene's layout.
  std::vector<SceneOverride> overrides;
  if (arguments.Has("layout"))
  {
    const std::string layout = arguments.Value("layout");
    if (layout != "3d" && layout != "four")
    {
      throw UsageError("view: --layout expects 3d or four, got \"" + layout + "\"");
    }
    overrides.push_back({ "view.layout", layout, "--layout" });
  }
  if (arguments.Has("exposure"))
  {
    overrides.push_back(
      NumericOverride("render.exposure", arguments.Value("exposure"), "--exposure"));
  }
  for (const std::string& target : { saveOnExit, options.RecordFile, options.StateFile })
  {
    if (!target.empty())
    {
      CheckOutputTarget(target);
    }
  }
  if (!windowImage.empty())
  {
    if (play.empty())
    {
      throw UsageError("view: --window-image saves the window when playback ends: it needs --play");
    }
    CheckImageOutput(windowImage);
  }
  if (!play.empty())
  {
    // Before the window opens; Viewer::PlayFile reads it through the same check.
    CheckRegularInputFile(play, "recording");
  }
  if (arguments.Has("screenshot-size"))
  {
    options.ScreenshotSize = ParseWindowSize(arguments.Value("screenshot-size"), "screenshot-size");
  }
  options.CommandLine = QuoteCommandLine(arguments.CommandLine);

  Scene scene = LoadOperandScene("view", input, arguments, overrides);
  if (arguments.Has("size"))
  {
    options.WindowSize = ParseWindowSize(arguments.Value("size"), "size");
  }
  else
  {
    // The 3D view at render.size: the window is a third taller for the editor.
    options.WindowSize = { { scene.Render.Size[0], scene.Render.Size[1] * 4 / 3 } };
  }
  RequireDisplay("cloudvis view ...");
  if (fieldFile)
  {
    // Absolute, so that a saved scene finds the field wherever the scene is kept.
    scene.Field.File = Absolute(input);
  }
  // Each time step is read as the scene opened was: from the scene as loaded, before ProduceField
  // finished it with the first step's units.
  const Scene opened = scene;
  FieldReport report;
  const vtkSmartPointer<vtkImageData> field = ProduceField(scene, {}, &report);
  options.FieldFile = fieldFile;
  options.Units = report.Resolved;
  if (scene.Field.FromFile())
  {
    options.Opened = report;
    options.ReadTimeStep = [opened](int step, FieldReport& read)
    {
      Scene at = opened;
      at.Field.Read.TimeStep = step;
      return ProduceField(at, {}, &read);
    };
  }
  Viewer viewer(scene, field, options);
  if (!play.empty())
  {
    viewer.PlayFile(play);
  }
  else
  {
    viewer.Start();
  }
  if (!windowImage.empty())
  {
    viewer.SaveWindowImage(windowImage);
    out << "wrote " << PrintableText(windowImage) << "\n";
  }
  if (!saveOnExit.empty())
  {
    viewer.SaveScene(saveOnExit);
    out << "wrote " << PrintableText(saveOnExit) << "\n";
  }
  return ExitSuccess;
}

} // namespace

CommandSpec ViewCommand()
{
  return { "view",
    "[SCENE|FIELD.vti]",
    0,
    1,
    "open the interactive viewer: the cloud, slices and a transfer-function editor",
    "One window: the cloud drawn as `render` draws it (top three quarters; trackball camera,\n"
    "orthogonal and oblique slices; key 4 switches to four views: 3D, axial, coronal and\n"
    "sagittal slices) and the transfer-function editor over the density histogram (bottom\n"
    "quarter). Press h in the window for the keys and the mouse; --keys and --mouse print\n"
    "them and docs/viewer.md lists them. s saves a screenshot of the views with their color\n"
    "legends (cloudvis-screenshot-NNN.png, and .exr of the 3D view), w the scene as\n"
    "cloudvis-view-NNN.json, which `cloudvis render` turns into the same image. Without\n"
    "SCENE the default scene is shown. --record writes the session's events, --play replays\n"
    "such a file and exits at its end. Needs an X display (xvfb-run -a cloudvis view ...).",
    { { "size",
        0,
        "WxH",
        "window size in pixels (default: render.size widened by a third in height for the "
        "editor, so the 3D view is render.size)" },
      { "record", 0, "FILE.log", "record the session's events to FILE.log" },
      { "play", 0, "FILE.log", "replay a recorded session, then exit" },
      { "window-image",
        0,
        "FILE.png",
        "with --play: save the whole window (views, editor, texts) when playback ends" },
      { "save-scene-on-exit",
        0,
        "FILE.json",
        "write the scene as the window shows it when the window closes or playback ends" },
      { "output-dir",
        0,
        "DIR",
        "where screenshots, saved scenes and presets go (default: the current directory)" },
      { "layout",
        0,
        "3d|four",
        "start with the 3D view alone (default) or the four views; overrides a scene's "
        "view.layout" },
      { "screenshot-size",
        0,
        "WxH",
        "the size of the screenshots s saves (default: the views as the window shows them)" },
      { "state-file",
        0,
        "FILE.json",
        "write the viewer's state as JSON after every frame and every input (for tests and "
        "tools; docs/viewer.md)" },
      ExposureOption,
      { "keys", 0, "", "print the key bindings (a Markdown table) and exit" },
      { "mouse", 0, "", "print the mouse bindings (a Markdown table) and exit" },
      SetOption,
      FieldFileOptions[0],
      FieldFileOptions[1],
      FieldFileOptions[2],
      HelpOption },
    View };
}

} // namespace cloudvis
