// The export side of the command line: the options that choose an image's format details
// (--png-bits, --exr-half, --transparent, --quiet), shared by `render` and `animate`, and the
// `animate` command itself. Commands.cxx lists the options in `render` and the command in its
// table; everything else about export lives here.
#ifndef cloudvis_ExportCommands_h
#define cloudvis_ExportCommands_h

#include "CommandLine.h"
#include "ExportRender.h" // ResolvedSceneJson, for the commands
#include "ImageWriters.h"
#include "Progress.h"
#include "Scene.h"

#include <functional>
#include <vector>

class vtkImageData;

namespace cloudvis
{

extern const OptionSpec PngBitsOption;
extern const OptionSpec ExposureOption;
extern const OptionSpec ExrHalfOption;
extern const OptionSpec TransparentOption;
extern const OptionSpec QuietOption;

// The override of a numeric scene key by an option's text: an integer or a number as such,
// anything else as text, for the scene to refuse by key (naming the option).
SceneOverride NumericOverride(const std::string& key,
  const std::string& text,
  const std::string& option);

// Adds the scene overrides the export options stand for (--png-bits N is render.png_bits,
// --exr-half is render.exr_type = "half").
void AddExportOverrides(const Arguments& arguments, std::vector<SceneOverride>& overrides);

// The export options of a validated scene: format details from the scene and the flags, the
// command line as metadata (the caller adds the resolved scene, SceneToJson, once the field is
// known). Throws InputError when `output` needs the float image (EXR, 16-bit or transparent
// PNG) and render.resolution_scale is below 1.
ImageExportOptions MakeExportOptions(
  const Arguments& arguments, const Scene& scene, const std::string& output);

// The progress bar of a command: on stderr when it is a terminal and --quiet is absent.
bool ShowProgress(const Arguments& arguments);

// The command line quoted for a POSIX shell where needed, as stored in "cloudvis.command" (by
// render, animate and the viewer), with bytes that are not UTF-8 escaped as \xNN.
std::string QuoteCommandLine(const std::vector<std::string>& arguments);

} // namespace cloudvis

#endif
