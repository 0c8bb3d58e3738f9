// Export options and `cloudvis animate`. Everything is validated before the first field is
// generated and before the output directory is created, so a bad command leaves nothing behind.
#include "ExportCommands.h"

#include "Animate.h"
#include "CommandSupport.h"
#include "Display.h"
#include "Errors.h"
#include "ExportRender.h"
#include "FieldIO.h"
#include "OffscreenRender.h"
#include "Utf8.h"

#include <vtkImageData.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <regex>

namespace cloudvis
{

const OptionSpec PngBitsOption{ "png-bits", 0, "8|16",
  "bits per PNG channel; 16 composites the float render itself instead of reading the window "
  "(docs/export.md); overrides render.png_bits" };
const OptionSpec ExrHalfOption{ "exr-half", 0, "",
  "write EXR channels as 16-bit half floats instead of 32-bit floats; overrides render.exr_type" };
const OptionSpec TransparentOption{ "transparent", 0, "",
  "PNG with an alpha channel: straight color and alpha = the cloud's opacity, no background" };
const OptionSpec ExposureOption{ "exposure", 0, "EV|auto",
  "exposure of PNG and the viewer in EV (the radiance times 2^EV before render.display's curve), "
  "or auto: from the cloud's luminance (docs/export.md); overrides render.exposure" };
const OptionSpec QuietOption{ "quiet", 'q', "",
  "no progress bar (it is shown only when stderr is a terminal)" };

namespace
{

const OptionSpec DirectoryOption{ "output", 'o', "DIR/",
  "write the frames into this directory as frame_0000.png, frame_0001.png, ... (created if "
  "missing); required",
  false, true };
const OptionSpec FramesOption{ "frames", 0, "N",
  "number of frames, in [1, 999999]; required, except with --time-steps (one frame per step)" };
const OptionSpec TurntableOption{ "turntable", 0, "",
  "orbit the camera 360 degrees about the focal point, around the view-up, over the frames" };
const OptionSpec TimeOption{ "time", 0, "T0:T1",
  "generate the field again for each frame i at time T0 + i (T1 - T0) / (N - 1) (seconds: "
  "wind and morph)" };
const OptionSpec TimeStepsOption{ "time-steps", 0, "A:B[:STRIDE]",
  "one frame for each time step A, A + STRIDE, ... B of the field file (its field.time_step, "
  "from 0)" };
const OptionSpec FormatOption{ "format", 0, "png|exr", "frame format (default png)" };
const OptionSpec AnimateSizeOption{ "size", 0, "WxH",
  "frame size in pixels, e.g. 800x600; overrides render.size" };

void ParseTimeRange(const std::string& text, AnimationRequest& request)
{
  const auto colon = text.find(':');
  if (colon == std::string::npos || !ParseNumber(text.substr(0, colon), request.TimeBegin) ||
    !ParseNumber(text.substr(colon + 1), request.TimeEnd))
  {
    throw UsageError("animate: --time expects T0:T1, two numbers of seconds (for example 0:12), "
                     "got \"" + text + "\"");
  }
}

int Animate(const Arguments& arguments, std::ostream& out)
{
  if (!arguments.Has("output"))
  {
    throw UsageError("animate: missing the output directory: -o DIR/");
  }
  const int motions = int(arguments.Has("turntable")) + int(arguments.Has("time")) +
    int(arguments.Has("time-steps"));
  if (motions != 1)
  {
    throw UsageError("animate: give exactly one motion: --turntable, --time T0:T1 or "
                     "--time-steps A:B[:STRIDE]");
  }
  AnimationRequest request;
  if (arguments.Has("time-steps"))
  {
    if (arguments.Has("frames"))
    {
      throw UsageError("animate: --time-steps makes one frame per step: --frames is not given "
                       "with it");
    }
    request.TimeSteps = ParseTimeSteps("animate", arguments.Value("time-steps"));
    request.Frames = int(request.TimeSteps.size());
  }
  else if (!arguments.Has("frames"))
  {
    throw UsageError("animate: missing the number of frames: --frames N");
  }
  else
  {
    request.Frames = ParseCount("animate", "frames", arguments.Value("frames"), "frames");
  }
  request.Turntable = arguments.Has("turntable");
  if (arguments.Has("time"))
  {
    ParseTimeRange(arguments.Value("time"), request);
  }
  const std::string format = arguments.Has("format") ? arguments.Value("format") : "png";
  if (format != "png" && format != "exr")
  {
    throw UsageError("animate: --format expects png or exr, got \"" + format + "\"");
  }
  request.Extension = "." + format;
  const std::string& input = arguments.Operands[0];
  std::string directory = arguments.Value("output");
  while (directory.size() > 1 && directory.back() == '/')
  {
    directory.pop_back();
  }
  request.Directory = directory;
  request.FieldFileAlone = IsFieldOperand(input, arguments);

  std::vector<SceneOverride> overrides;
  if (arguments.Has("lighting"))
  {
    overrides.push_back({ "render.lighting", arguments.Value("lighting"), "--lighting" });
  }
  if (arguments.Has("size"))
  {
    overrides.push_back(
      { "render.size", ParseSizeOption("animate", arguments.Value("size")), "--size" });
  }
  AddExportOverrides(arguments, overrides);
  CheckAnimationDirectory(request.Directory);
  const Scene scene = LoadOperandScene("animate", input, arguments, overrides);
  if (arguments.Has("time") && scene.Field.FromFile())
  {
    throw InputError(scene.Source + ": field.file: --time generates the field again at each " +
      "time; a field file's own time steps are --time-steps A:B[:STRIDE]");
  }
  if (!request.TimeSteps.empty() && !scene.Field.FromFile())
  {
    throw InputError(scene.Source + ": --time-steps steps through a field file's time axis; " +
      "this scene's field is generated (--time T0:T1 animates it)");
  }
  request.Export = MakeExportOptions(arguments, scene, FrameFileName(request, 0));
  RequireDisplay("cloudvis animate ...");

  Progress progress(std::cerr, ShowProgress(arguments));
  std::string note;
  const int written = RenderAnimation(
    scene,
    input,
    request,
    [&](const std::string& label, double fraction) { progress.Update(label, fraction); },
    &note);
  progress.Finish();
  out << note << "wrote " << written << " frame" << (written == 1 ? "" : "s") << " to "
      << PrintableText(request.Directory) << "/ ("
      << FrameFileName(request, 0).substr(request.Directory.size() + 1) << " .. "
      << FrameFileName(request, written - 1).substr(request.Directory.size() + 1) << ", "
      << scene.Render.Size[0] << " x " << scene.Render.Size[1] << " pixels)\n";
  return ExitSuccess;
}

} // namespace

SceneOverride NumericOverride(const std::string& key,
  const std::string& text,
  const std::string& option)
{
  double number = 0.0;
  // A number goes in as a number, anything else as text, for the scene to refuse by key.
  return { key,
    ParseNumber(text, number)
      ? nlohmann::json(number == std::floor(number) && std::abs(number) < 2147483648.0
            ? nlohmann::json(int(number))
            : nlohmann::json(number))
      : nlohmann::json(text),
    option };
}

void AddExportOverrides(const Arguments& arguments, std::vector<SceneOverride>& overrides)
{
  if (arguments.Has("png-bits"))
  {
    overrides.push_back(
      NumericOverride("render.png_bits", arguments.Value("png-bits"), "--png-bits"));
  }
  if (arguments.Has("exr-half"))
  {
    overrides.push_back({ "render.exr_type", "half", "--exr-half" });
  }
  if (arguments.Has("exposure"))
  {
    overrides.push_back(
      NumericOverride("render.exposure", arguments.Value("exposure"), "--exposure"));
  }
}

ImageExportOptions MakeExportOptions(
  const Arguments& arguments, const Scene& scene, const std::string& output)
{
  ImageExportOptions options;
  options.PngBits = scene.Render.PngBits;
  options.ExrHalf = scene.Render.ExrHalf;
  options.Transparent = arguments.Has("transparent");
  options.CommandLine = QuoteCommandLine(arguments.CommandLine);
  if (NeedsFloatImage(output, options) && scene.Render.ResolutionScale != 1.0)
  {
    throw InputError(scene.Source + ": render.resolution_scale: EXR, 16-bit and transparent " +
      "PNG exports are made from the float render at full size; set it to 1");
  }
  return options;
}

bool ShowProgress(const Arguments& arguments)
{
  return !arguments.Has("quiet") && Progress::StderrIsTerminal();
}

std::string QuoteCommandLine(const std::vector<std::string>& arguments)
{
  static const std::regex plain("[A-Za-z0-9_@%+=:,./-]+");
  std::string line;
  for (size_t i = 0; i < arguments.size(); ++i)
  {
    // The program as a user types it, not the path it was started from.
    std::string argument = arguments[i];
    if (i == 0)
    {
      argument = argument.substr(argument.find_last_of('/') + 1);
    }
    if (!std::regex_match(argument, plain))
    {
      std::string quoted = "'";
      for (char c : argument)
      {
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
      }
      argument = quoted + "'";
    }
    line += (line.empty() ? "" : " ") + argument;
  }
  return EscapeInvalidUtf8(line); // metadata is text: arguments may hold any bytes
}

CommandSpec AnimateCommand()
{
  return { "animate", "SCENE|FIELD", 1, 1,
    "render a numbered sequence of frames: a turntable, the field over time, or a field file's "
    "time steps",
    "Each frame is the still `cloudvis render` makes of the scene with that frame's camera or\n"
    "time (render.size pixels, render.accumulate frames averaged), written atomically as\n"
    "DIR/frame_0000.png, frame_0001.png, ... (more digits when N needs them) and carrying its own\n"
    "scene as metadata. --turntable orbits the camera about the focal point around the view-up,\n"
    "frame i at 360 i / N degrees (the sequence loops). --time T0:T1 generates the field at\n"
    "t_i = T0 + i (T1 - T0) / (N - 1) for each frame. --time-steps A:B[:STRIDE] reads a field\n"
    "file's (or a scene's field.file's) time steps A, A + STRIDE, ... B, one per frame: the\n"
    "transfer function and an automatic exposure are those of the first frame, kept for all,\n"
    "and a step beyond the file is refused before a frame is written. DIR is created when the\n"
    "first frame is written; a failure part-way keeps the frames written before it. Needs an X\n"
    "display (xvfb-run -a cloudvis animate ...).",
    { DirectoryOption, FramesOption, TurntableOption, TimeOption, TimeStepsOption,
      AnimateSizeOption, FormatOption, FieldFileOptions[0], FieldFileOptions[1],
      LightingOption(), PngBitsOption, ExrHalfOption, TransparentOption, ExposureOption, QuietOption, SetOption,
      HelpOption },
    Animate };
}

} // namespace cloudvis
