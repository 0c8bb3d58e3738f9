// `cloudvis compare`: its options and their parsing, and the command, a short function over
// RenderComparison (app/export Compare.h). A panel is named as in --lighting: a model's name, or
// march:NAME for the march with one of the ways of adding multiple scattering
// (MultipleScatteringModelTable), so that one comparison shows the volume and the octaves side by
// side; everything is checked before the field is produced.
#include "CommandSupport.h"

#include "Compare.h"
#include "Errors.h"
#include "ExportCommands.h"
#include "ImageWriters.h"
#include "Utf8.h"

#include <vtkImageData.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <iomanip>
#include <optional>
#include <sstream>

namespace cloudvis
{
namespace
{

const OptionSpec CompareLightingOption{ "lighting",
  0,
  "M1,M2,...",
  "the lighting models to compare, left to right, each at most once (default "
  "none,derivative,march); march:volume and march:octaves set how the march adds multiple "
  "scattering, plain march takes the scene's render.march.multiple_scattering" };
const OptionSpec DifferenceOption{ "difference",
  0,
  "A,B",
  "add a panel showing |A - B| of two of the compared models, false colored, labelled with the "
  "largest difference" };
const OptionSpec ReferenceOption{ "reference",
  0,
  "pathtrace[:SPP|:P%]",
  "add a ground-truth panel path-traced with SPP paths per pixel (default render.spp, at least "
  "2), or with P% (e.g. pathtrace:2%) until its relative standard error over the cloud is at "
  "most P% (see --reference-time), and measure every model against it: relative RMSE, bias "
  "(ratio of means) and max error relative to the peak, on its panel and printed, with the "
  "reference's own standard error" };
const NoiseTargetOptions ReferenceNoiseNames{ "compare",
  "reference",
  "reference-time",
  "--reference pathtrace:2%" };
const OptionSpec PanelSizeOption{ "size",
  0,
  "WxH",
  "size of each panel in pixels, e.g. 400x300; overrides render.size (the window is the panels "
  "side by side)" };

// The march's panels with a multiple scattering: march:volume, march:octaves.
std::vector<std::string> MarchPanelNames()
{
  std::vector<std::string> names;
  for (const MultipleScatteringModelEntry& entry : MultipleScatteringModelTable())
  {
    names.push_back(std::string(LightingModelName(LightingModel::March)) + ":" + entry.Name);
  }
  return names;
}

// Every name a panel may have, in the tables' order: none, derivative, march, march:volume,
// march:octaves, pathtrace.
std::string AllowedPanelNames()
{
  std::string allowed;
  for (const LightingModelEntry& entry : LightingModelTable())
  {
    allowed += (allowed.empty() ? "" : ", ") + std::string(entry.Name);
    if (entry.Model == LightingModel::March)
    {
      for (const std::string& name : MarchPanelNames())
      {
        allowed += ", " + name;
      }
    }
  }
  return allowed;
}

// The panel a name stands for, or nullopt for a name that is none of AllowedPanelNames().
std::optional<ComparedLighting> FindPanel(const std::string& name)
{
  const auto colon = name.find(':');
  const std::optional<LightingModel> model = FindLightingModel(name.substr(0, colon));
  if (!model)
  {
    return std::nullopt;
  }
  ComparedLighting panel{ *model, std::nullopt };
  if (colon != std::string::npos)
  {
    panel.MultipleScattering = FindMultipleScatteringModel(name.substr(colon + 1));
    if (*model != LightingModel::March || !panel.MultipleScattering)
    {
      return std::nullopt;
    }
  }
  return panel;
}

// --lighting of compare: a comma-separated list of distinct panel names.
std::vector<ComparedLighting> ParseModelList(const std::string& text)
{
  std::vector<ComparedLighting> panels;
  std::string name;
  std::istringstream in(text + ",");
  while (std::getline(in, name, ','))
  {
    const std::optional<ComparedLighting> panel = FindPanel(name);
    const auto colon = name.find(':');
    const std::optional<LightingModel> model = FindLightingModel(name.substr(0, colon));
    if (!panel && model)
    {
      std::string marchNames;
      for (const std::string& march : MarchPanelNames())
      {
        marchNames += (marchNames.empty() ? "" : ", ") + march;
      }
      throw UsageError("compare: --lighting: " +
        (*model == LightingModel::March
            ? "unknown multiple scattering \"" + name.substr(colon + 1) + "\""
            : "\"" + name + "\": only the march takes a multiple scattering") +
        " in \"" + text + "\"; allowed: " + marchNames);
    }
    if (!panel)
    {
      throw UsageError("compare: --lighting: " +
        (name.empty() ? std::string("an empty model name") : "unknown model \"" + name + "\"") +
        " in \"" + text + "\"; allowed: " + AllowedPanelNames());
    }
    if (std::find(panels.begin(), panels.end(), *panel) != panels.end())
    {
      throw UsageError("compare: --lighting: \"" + name + "\" is listed twice");
    }
    panels.push_back(*panel);
  }
  return panels;
}

// --reference pathtrace[:SPP|:P%]: the reference's paths per pixel (SPP, or 0 for the scene's
// render.spp), or its noise target (P%, with --reference-time and --accept-noise).
ReferencePaths ParseReference(const std::string& text, const Arguments& arguments)
{
  const std::string name = LightingModelName(LightingModel::PathTrace);
  const auto colon = text.find(':');
  if (text.substr(0, colon) != name)
  {
    throw UsageError("compare: --reference expects " + name + " or " + name +
      ":SPP (the path tracer with SPP paths per pixel) or " + name +
      ":P% (until a noise of P%), got \"" + text + "\"");
  }
  const std::string count = colon == std::string::npos ? "" : text.substr(colon + 1);
  ReferencePaths reference;
  reference.SamplesPerPixel = 0;
  reference.Target = ReadNoiseTarget(
    ReferenceNoiseNames, arguments, ParseNoisePercent(ReferenceNoiseNames, count), text);
  if (colon == std::string::npos || reference.Target)
  {
    return reference;
  }
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(count.c_str(), &end, 10);
  if (count.empty() || *end != '\0' || errno != 0 || value < 2 || value > (1L << 24) ||
    !std::isdigit(static_cast<unsigned char>(count[0])))
  {
    throw UsageError("compare: --reference: SPP must be an integer from 2 to 16777216 (paths per "
                     "pixel) or a noise target P%, got \"" +
      count + "\"");
  }
  reference.SamplesPerPixel = int(value);
  return reference;
}

// --difference A,B: two of the compared panels, as indices into `panels` (which ends with the
// reference, pathtrace, when there is one), named as in --lighting. With a reference, one name A
// means A,pathtrace.
std::pair<size_t, size_t> ParseDifference(const std::string& text,
  const std::vector<ComparedLighting>& panels,
  bool reference)
{
  auto comma = text.find(',');
  std::string pair = text;
  if (comma == std::string::npos && reference)
  {
    pair = text + "," + LightingModelName(LightingModel::PathTrace);
    comma = text.size();
  }
  const std::string names[2] = { pair.substr(0, comma),
    comma == std::string::npos ? "" : pair.substr(comma + 1) };
  size_t indices[2] = { 0, 0 };
  for (int i = 0; i < 2; ++i)
  {
    const std::optional<ComparedLighting> panel = FindPanel(names[i]);
    const auto found = panel ? std::find(panels.begin(), panels.end(), *panel) : panels.end();
    if (comma == std::string::npos || found == panels.end())
    {
      throw UsageError("compare: --difference expects two of the compared models, A,B (for " +
        std::string("example march,derivative), got \"") + text + "\"");
    }
    indices[i] = size_t(found - panels.begin());
  }
  if (indices[0] == indices[1])
  {
    throw UsageError("compare: --difference needs two different models, got \"" + text + "\"");
  }
  return { indices[0], indices[1] };
}

int Compare(const Arguments& arguments, std::ostream& out)
{
  if (!arguments.Has("output"))
  {
    throw UsageError("compare: missing the output image: -o IMAGE.png");
  }
  const std::string output = arguments.Value("output");
  const std::vector<ComparedLighting> models = ParseModelList(
    arguments.Has("lighting") ? arguments.Value("lighting") : "none,derivative,march");
  std::optional<ReferencePaths> reference;
  if (arguments.Has("reference"))
  {
    reference = ParseReference(arguments.Value("reference"), arguments);
    if (std::any_of(models.begin(),
          models.end(),
          [](const ComparedLighting& m) { return m.Model == LightingModel::PathTrace; }))
    {
      throw UsageError("compare: --lighting lists pathtrace, which --reference already adds as "
                       "the reference panel");
    }
  }
  else
  {
    ReadNoiseTarget(ReferenceNoiseNames, arguments, std::nullopt, "");
  }
  std::vector<ComparedLighting> panels = models;
  if (reference)
  {
    panels.push_back({ LightingModel::PathTrace, std::nullopt });
  }
  std::optional<std::pair<size_t, size_t>> difference;
  if (arguments.Has("difference"))
  {
    difference = ParseDifference(arguments.Value("difference"), panels, bool(reference));
  }
  std::vector<SceneOverride> options;
  if (arguments.Has("size"))
  {
    options.push_back(
      { "render.size", ParseSizeOption("compare", arguments.Value("size")), "--size" });
  }
  if (arguments.Has("exposure"))
  {
    options.push_back(
      NumericOverride("render.exposure", arguments.Value("exposure"), "--exposure"));
  }
  const SceneInput loaded = LoadSceneInput("compare", arguments, options, output, true);
  out << loaded.Note;
  if (reference && !reference->Target && reference->SamplesPerPixel == 0)
  {
    reference->SamplesPerPixel = loaded.Loaded.Render.SamplesPerPixel;
  }
  const ComparisonResult result = RenderComparison(
    loaded.Loaded, loaded.Field, arguments.Operands[0], models, difference, 3, reference);
  if (result.ReferenceTarget)
  {
    const std::string text = arguments.Value("reference");
    CheckNoiseReport(ReferenceNoiseNames, text, *result.ReferenceTarget);
  }
  WriteImage(result.Image, output);
  out << "wrote " << PrintableText(output) << " (" << result.Image.Width << " x "
      << result.Image.Height << " pixels, " << panels.size() + (difference ? 1 : 0) << " panels, "
      << result.AccumulatedFrames << " frame" << (result.AccumulatedFrames == 1 ? "" : "s")
      << " averaged";
  if (loaded.Loaded.Render.AutoExposure || result.Image.ExposureEV != 0.0)
  {
    out << ", one exposure for all: " << ShowExposure(result.Image.ExposureEV)
        << (loaded.Loaded.Render.AutoExposure ? " (auto)" : "");
  }
  out << ")\n";
  if (!result.Image.Coarsened.empty())
  {
    out << result.Image.Coarsened << "\n";
  }
  for (size_t i = 0; i < panels.size(); ++i)
  {
    out << result.Names[i] << ": " << std::fixed << std::setprecision(2) << result.Milliseconds[i]
        << " ms/frame";
    if (reference && i < models.size())
    {
      const ImageError& e = result.Errors[i];
      out << "; against the reference: relative RMSE " << std::setprecision(4) << e.RelativeRMSE
          << ", bias " << e.BiasRatio << " (ratio of means), max error " << e.MaxErrorOverPeak
          << " of the peak";
    }
    else if (result.ReferenceTarget)
    {
      out << "; reference: " << DescribeNoiseReport(ReferenceNoiseNames, *result.ReferenceTarget);
    }
    else if (reference)
    {
      out << "; reference: " << result.ReferenceSamples << " paths per pixel, relative standard "
          << "error " << std::setprecision(4) << result.ReferenceNoise.RelativeStandardError;
    }
    out << "\n";
  }
  if (difference)
  {
    out << "max |" << result.Names[difference->first] << " - " << result.Names[difference->second]
        << "|: " << std::setprecision(6) << result.MaxDifference << "\n";
  }
  return ExitSuccess;
}

} // namespace

CommandSpec CompareCommand()
{
  return { "compare",
    "SCENE|FIELD",
    1,
    1,
    "render lighting models side by side on one field and camera, with their frame times",
    "One off-screen window with one panel per model (--lighting), render.size each, all\n"
    "sharing one camera and jitter sequence; each panel is labelled with its name and its\n"
    "mean frame time, measured with the other panels hidden. A march panel is named with the\n"
    "multiple scattering it renders with: march:volume or march:octaves as listed, plain\n"
    "march the scene's render.march.multiple_scattering. --difference A,B adds a panel\n"
    "of |A - B|. --reference pathtrace[:SPP] adds the path tracer's ground truth and each\n"
    "model's error against it (--difference A then means A,pathtrace); pathtrace:P% traces\n"
    "until the reference's relative standard error is P% (docs/lighting.md), checked every\n"
    "few frames, within --reference-time.\n"
    "The scene's render.lighting is not used; everything else is as in render.\n"
    "Prints each panel's time as '<name>: <milliseconds> ms/frame'. Needs an X display:\n"
    "xvfb-run -a cloudvis compare ...",
    { ImageOutputOption,
      PanelSizeOption,
      CompareLightingOption,
      ReferenceOption,
      NoiseTimeOption(ReferenceNoiseNames),
      AcceptNoiseOption,
      ExposureOption,
      DifferenceOption,
      SetOption,
      FieldFileOptions[0],
      FieldFileOptions[1],
      FieldFileOptions[2],
      HelpOption },
    Compare };
}

} // namespace cloudvis
