// The command table and the commands. Each command is a short function over the library:
// LoadScene -> ProduceField -> WriteField, ComputeFieldStatistics or RenderOffscreen + WriteImage;
// options shared between commands (--set, --help) are defined once and listed by each command
// that takes them. Options that stand for a scene key (--lighting, --size) become SceneOverrides,
// so the scene's validation checks them like any other value.
#include "CommandLine.h"

#include "AtomicFile.h"
#include "CloudStatistics.h"
#include "CommandSupport.h"
#include "Compare.h"
#include "CpuReference.h"
#include "Display.h"
#include "Errors.h"
#include "ExportCommands.h"
#include "ExportRender.h" // FitTransferFunctionNote
#include "FieldIO.h"
#include "FieldPieces.h"
#include "FieldSeries.h"
#include "FieldStatistics.h"
#include "FileNames.h"
#include "ImageWriters.h"
#include "OffscreenRender.h"
#include "OutOfMemory.h"
#include "ProcessGroup.h"
#include "Progress.h"
#include "Scene.h"
#include "SceneField.h"
#include "Utf8.h"
#include "VtkMessageCapture.h"
#include "Words.h"
#include "vtkCloudDensitySource.h"

#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <limits>
#include <numeric>
#include <optional>
#include <regex>
#include <sstream>
#include <sys/stat.h>

namespace cloudvis
{

const OptionSpec SetOption{ "set", 0, "KEY=VALUE",
  "override a scene value before validation, e.g. --set field.octaves=4 or "
  "--set field.dimensions=64,64,64 (every key: cloudvis schema, or docs/scene-format.md)",
  true };
const OptionSpec HelpOption{ "help", 'h', "", "show this help and exit" };

OptionSpec LightingOption()
{
  return { "lighting",
    0,
    "MODEL",
    "lighting model, one of: " + Join(LightingModelNames()) + "; overrides render.lighting" };
}

nlohmann::json ParseSizeOption(const std::string& command, const std::string& text)
{
  static const std::regex form("([0-9]{1,9})[xX]([0-9]{1,9})");
  std::smatch match;
  if (!std::regex_match(text, match, form))
  {
    throw UsageError(command + ": --size expects WIDTHxHEIGHT in pixels (for example 800x600), "
                               "got \"" + text + "\"");
  }
  return nlohmann::json::array({ std::stoi(match[1]), std::stoi(match[2]) });
}

const std::vector<OptionSpec> FieldFileOptions = {
  { "field-format",
    0,
    "NAME",
    "read the field file operand as this format, whatever its extension: one of " +
      FieldFormatIds() + "; overrides field.format" },
  { "array",
    0,
    "NAME",
    "the grid (OpenVDB), variable (NetCDF) or point array (.vti, .pvti) to read from the field "
    "file; overrides field.array" },
  { "time-step",
    0,
    "N",
    "the time step to read from a NetCDF field file, from 0; overrides field.time_step" },
};

bool ParseNumber(const std::string& text, double& value)
{
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])))
  {
    return false;
  }
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return *end == '\0' && std::isfinite(value);
}

int ParseCount(const std::string& command,
  const std::string& option,
  const std::string& text,
  const std::string& unit)
{
  static const std::regex form("[0-9]{1,6}");
  if (!std::regex_match(text, form) || std::stoi(text) < 1)
  {
    throw UsageError(command + ": --" + option + " expects a number of " + unit +
      " in [1, 999999], got \"" + text + "\"");
  }
  return std::stoi(text);
}

std::vector<int> ParseTimeSteps(const std::string& command, const std::string& text)
{
  static const std::regex form("([0-9]{1,9}):([0-9]{1,9})(:([0-9]{1,9}))?");
  std::smatch parts;
  const bool matched = std::regex_match(text, parts, form);
  const int first = matched ? std::stoi(parts[1]) : 0, last = matched ? std::stoi(parts[2]) : 0;
  const int stride = matched && parts[4].matched ? std::stoi(parts[4]) : 1;
  if (!matched || first > last || stride < 1 || (last - first) / stride >= 999999)
  {
    throw UsageError(command +
      ": --time-steps expects A:B or A:B:STRIDE, time steps from 0 with A <= B and STRIDE >= 1, "
      "at most 999999 of them (for example 0:19 or 0:99:10), got \"" +
      text + "\"");
  }
  std::vector<int> steps;
  for (long long step = first; step <= last; step += stride)
  {
    steps.push_back(int(step));
  }
  return steps;
}

bool IsFieldOperand(const std::string& input, const Arguments& arguments)
{
  return IsFieldFile(input) || arguments.Has("field-format");
}

namespace
{

// Adds the scene overrides the field file options stand for.
void AddFieldFileOverrides(const Arguments& arguments, std::vector<SceneOverride>& overrides)
{
  const std::pair<const char*, const char*> options[] = { { "field-format", "field.format" },
    { "array", "field.array" },
    { "time-step", "field.time_step" } };
  for (const auto& option : options)
  {
    if (arguments.Has(option.first))
    {
      overrides.push_back({ option.second,
        ParseOverrideValue(option.second, arguments.Value(option.first)),
        std::string("--") + option.first });
    }
  }
}
} // namespace

Scene LoadOperandScene(const std::string& command,
  const std::string& input,
  const Arguments& arguments,
  std::vector<SceneOverride> overrides,
  bool fieldKeysOnly)
{
  AddFieldFileOverrides(arguments, overrides);
  const std::vector<std::string> assignments = arguments.Values("set");
  if (!IsFieldOperand(input, arguments))
  {
    return LoadScene(input, assignments, overrides);
  }
  // A field file has no procedural parameters; with `fieldKeysOnly` (info) nothing but how it
  // is read applies.
  const std::vector<std::string>& fileKeys = FieldFileKeyNames();
  for (const std::string& assignment : assignments)
  {
    const std::string key = assignment.substr(0, assignment.find('='));
    const bool fieldKey = key == "field" || key.rfind("field.", 0) == 0;
    const std::string member =
      fieldKey && key.size() > 6 ? key.substr(6, key.find('.', 6) - 6) : "";
    const bool fileKey =
      std::find(fileKeys.begin(), fileKeys.end(), member) != fileKeys.end() && member != "file";
    if (fieldKey ? !fileKey : fieldKeysOnly)
    {
      std::string allowed;
      for (const std::string& name : fileKeys)
      {
        allowed += name == "file" ? "" : (allowed.empty() ? "field." : ", field.") + name;
      }
      throw UsageError(command + ": --set " + key + " does not apply to the field file " + input +
        "; for a field file it takes only " + allowed +
        (fieldKeysOnly ? "" : " and the keys of the other sections"));
    }
  }
  return LoadFieldFileScene(input, assignments, overrides);
}

const OptionSpec ImageOutputOption{ "output",
  'o',
  "IMAGE.png",
  "write the rendered image to this file: .png (8-bit RGB unless --png-bits 16 or "
  "--transparent) or .exr (float channels, docs/export.md); required",
  false,
  true };

SceneInput LoadSceneInput(const std::string& command,
  const Arguments& arguments,
  const std::vector<SceneOverride>& options,
  const std::string& output,
  bool needsDisplay,
  const std::function<void(double)>& generationProgress,
  const std::function<void(const Scene&)>& checkScene)
{
  const std::string& input = arguments.Operands[0];
  CheckImageOutput(output);
  SceneInput loaded{ LoadOperandScene(command, input, arguments, options), nullptr, "" };
  if (checkScene)
  {
    checkScene(loaded.Loaded);
  }
  if (needsDisplay)
  {
    RequireDisplay("cloudvis " + command + " ...");
  }
  loaded.Field = ProduceField(loaded.Loaded, generationProgress);
  loaded.Note =
    FitTransferFunctionNote(loaded.Loaded, loaded.Field, IsFieldOperand(input, arguments));
  return loaded;
}

namespace
{

const OptionSpec OutputOption{ "output",
  'o',
  "FIELD.vti",
  "write the field to this file: .vti (VTK XML image data, zlib-compressed), .pvti (pieces, "
  "see --pieces) or .vdb (an OpenVDB float grid \"density\"); required",
  false,
  true };
const OptionSpec PiecesOption{ "pieces",
  0,
  "N",
  "with a .pvti output: write the field as N pieces FIELD_0.vti .. FIELD_<N-1>.vti beside it "
  "(default: 1, or the number of MPI processes under mpirun); a procedural field is generated "
  "one piece at a time" };
const OptionSpec JsonOption{ "json", 0, "", "print the statistics as one JSON object" };
const OptionSpec SizeOption{ "size", 0, "WxH",
  "image size in pixels, e.g. 800x600 (each in [16, 16384]); overrides render.size" };
const OptionSpec SamplesPerPixelOption{ "spp",
  0,
  "N|P%",
  "paths per pixel of a pathtrace still, at least 2; overrides render.spp. P% (e.g. 2%) is a "
  "noise target instead: paths are traced until the image's relative standard error over the "
  "cloud is at most P% (see --spp-time, docs/lighting.md)" };
const NoiseTargetOptions SamplesNoiseNames{ "render", "spp", "spp-time", "--spp 2%" };
const OptionSpec BenchmarkOption{ "benchmark", 0, "N",
  "after the image is made, march N more frames in full and print the mean time per frame as "
  "'<milliseconds> ms/frame'" };
const OptionSpec CpuReferenceOption{ "cpu-reference",
  0,
  "",
  "render with the CPU reference renderer (vtkCloudReferenceRenderer) instead of the GPU: the "
  "same camera, transfer function, lights and step, one exact ray per pixel, no jitter; slow, "
  "needs no display" };

std::string DescribeDimensions(vtkImageData* field)
{
  int d[3];
  field->GetDimensions(d);
  return std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]);
}

// A procedural field, made one piece (extent) at a time by the scene's source.
PieceProducer ProceduralPieces(const Scene& scene, FieldLattice& lattice)
{
  vtkSmartPointer<vtkCloudDensitySource> source = MakeDensitySource(scene.Field);
  const std::string problem = source->Validate();
  if (!problem.empty())
  {
    throw InputError(scene.Source + ": field: " + problem);
  }
  source->UpdateInformation();
  vtkInformation* information = source->GetOutputInformation(0);
  information->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), lattice.WholeExtent.data());
  information->Get(vtkDataObject::ORIGIN(), lattice.Origin.data());
  information->Get(vtkDataObject::SPACING(), lattice.Spacing.data());
  const std::string name = scene.Source;
  return [source, name](const Extent& extent)
  {
    VtkMessageCapture messages;
    source->UpdateExtent(extent.data());
    vtkImageData* output = source->GetOutput();
    if (!messages.Messages().empty() || !output || output->GetNumberOfPoints() == 0)
    {
      throw InputError(messages.WithVtkReason(name + ": field: generation failed"));
    }
    auto piece = vtkSmartPointer<vtkImageData>::New();
    piece->ShallowCopy(output);
    return piece;
  };
}

int Generate(const Arguments& arguments, std::ostream& out)
{
  if (!arguments.Has("output"))
  {
    throw UsageError("generate: missing the output file: -o FIELD.vti");
  }
  const std::string output = arguments.Value("output");
  const bool parallelFile = LowerCaseExtension(output) == ".pvti";
  if (arguments.Has("pieces") && !parallelFile)
  {
    throw UsageError("generate: --pieces applies to a .pvti output only, not to " + output);
  }
  const int requestedPieces = arguments.Has("pieces")
    ? ParseCount("generate", "pieces", arguments.Value("pieces"), "pieces")
    : 0;
  // MPI, when mpirun started this process: every rank runs this command with the same arguments.
  const ProcessGroup processes;
  if (processes.Size() > 1 && !parallelFile)
  {
    throw UsageError("generate: under mpirun the output is written in pieces: give it a .pvti "
                     "name (got " +
      output + ")");
  }
  const std::string input = arguments.Operands.empty() ? "" : arguments.Operands[0];
  if (!parallelFile)
  {
    // Before the work: a bad -o should not cost a field's generation time.
    CheckFieldOutput(output);
    const Scene scene = LoadOperandScene("generate", input, arguments, {});
    const vtkSmartPointer<vtkImageData> field = ProduceField(scene);
    WriteField(field, output, { ResolvedSceneJson(scene, field) });
    out << "wrote " << PrintableText(output) << " (" << DescribeDimensions(field) << " voxels)\n";
    return ExitSuccess;
  }
  const int pieces = requestedPieces > 0 ? requestedPieces : processes.Size();
  // Under MPI each step is agreed between the processes (RunAgreed): a scene or field file one
  // process cannot read, or memory one node lacks, ends every process with its message instead
  // of leaving the others waiting for it.
  FieldLattice lattice;
  PieceProducer produce;
  RunAgreed(processes.Controller(),
    [&]
    {
      CheckFieldOutput(output);
      const Scene scene = LoadOperandScene("generate", input, arguments, {});
      if (scene.Field.FromFile())
      {
        // A field file is read whole by every process, which writes its own pieces of it.
        const vtkSmartPointer<vtkImageData> field = ProduceField(scene);
        lattice = LatticeOf(field);
        produce = [field](const Extent& extent) { return ExtractPiece(field, extent); };
      }
      else
      {
        // A procedural field is generated piece by piece, each process its own pieces.
        produce = ProceduralPieces(scene, lattice);
      }
    });
  WriteFieldPieces(lattice, output, pieces, produce, processes.Controller());
  if (processes.Rank() == 0)
  {
    const Extent& e = lattice.WholeExtent;
    out << "wrote " << PrintableText(output) << " (" << e[1] - e[0] + 1 << " x " << e[3] - e[2] + 1
        << " x " << e[5] - e[4] + 1 << " voxels in " << pieces << " piece"
        << (pieces == 1 ? "" : "s") << ", " << PrintableText(PieceSource(output, 0)) << " .. "
        << PrintableText(PieceSource(output, pieces - 1));
    if (processes.Size() > 1)
    {
      out << ", written by " << processes.Size() << " MPI processes";
    }
    out << ")\n";
  }
  return ExitSuccess;
}

void MakeDirectory(const std::string& directory)
{
  if (::mkdir(directory.c_str(), 0777) != 0 && errno != EEXIST)
  {
    throw InputError(directory + ": cannot create the output directory (" + std::strerror(errno) + ")");
  }
}

// ", filmic, exposure +1.25 EV (auto), 0.3% of the cloud clipped": how the picture's display
// values were made, unless it is the plain default (linear, 0 EV).
std::string DescribeDisplay(
  const RenderedImage& image, const RenderSpec& render, double clippedCloudShare)
{
  if (image.Display == DisplayCurve::Linear && image.ExposureEV == 0.0 && !render.AutoExposure)
  {
    return "";
  }
  char clipped[64];
  std::snprintf(clipped, sizeof clipped, ", %.1f%% of the cloud clipped", 100.0 * clippedCloudShare);
  return ", " + DisplayCurveName(image.Display) + ", exposure " + ShowExposure(image.ExposureEV) +
    (render.AutoExposure ? " (auto)" : "") + clipped;
}

// The share of the cloud clipped above which a linear picture gets ClippingNote.
constexpr double ClippingNoteShare = 0.05;

// A line after "wrote ..." when a linear picture clips much of the cloud to white, saying what
// keeps it; empty otherwise.
std::string ClippingNote(const RenderedImage& image, double clippedCloudShare)
{
  if (image.Display != DisplayCurve::Linear || clippedCloudShare < ClippingNoteShare)
  {
    return "";
  }
  char text[256];
  std::snprintf(text, sizeof text,
    "note: %.1f%% of the cloud's pixels are clipped to white; render.display \"filmic\" with "
    "render.exposure \"auto\" (--exposure auto) keeps their shading (docs/export.md)\n",
    100.0 * clippedCloudShare);
  return text;
}

int Render(const Arguments& arguments, std::ostream& out)
{
  if (!arguments.Has("output"))
  {
    throw UsageError("render: missing the output image: -o IMAGE.png");
  }
  const std::string output = arguments.Value("output");
  const std::string& input = arguments.Operands[0];
  const int benchmarkFrames = arguments.Has("benchmark")
    ? ParseCount("render", "benchmark", arguments.Value("benchmark"), "frames")
    : 0;
  std::vector<SceneOverride> options;
  if (arguments.Has("lighting"))
  {
    options.push_back({ "render.lighting", arguments.Value("lighting"), "--lighting" });
  }
  if (arguments.Has("size"))
  {
    options.push_back({ "render.size", ParseSizeOption("render", arguments.Value("size")), "--size" });
  }
  // --spp is a count (render.spp) or a noise target, which no scene key holds: a time limit and
  // a refusal belong to a run, not to a scene the viewer and the CPU reference also read.
  const std::string spp = arguments.Has("spp") ? arguments.Value("spp") : "";
  const std::optional<NoiseTarget> noiseTarget = ReadNoiseTarget(
    SamplesNoiseNames, arguments, ParseNoisePercent(SamplesNoiseNames, spp), spp);
  if (arguments.Has("spp") && !noiseTarget)
  {
    options.push_back(NumericOverride("render.spp", spp, "--spp"));
  }
  AddExportOverrides(arguments, options);
  const bool cpuReference = arguments.Has("cpu-reference");
  if (cpuReference && benchmarkFrames > 0)
  {
    throw UsageError("render: --benchmark times the GPU; it cannot be combined with --cpu-reference");
  }
  if (cpuReference && noiseTarget)
  {
    throw UsageError("render: --spp " + spp + ": a noise target is the GPU path tracer's; " +
      "--cpu-reference traces a fixed count (--spp N)");
  }
  const auto checkLighting = [&](const Scene& scene)
  {
    const LightingModel model = scene.Render.Lighting.Model;
    if (noiseTarget && model != LightingModel::PathTrace)
    {
      throw UsageError("render: --spp " + spp + ": a noise target needs the path tracer, and the " +
        "lighting is " + LightingModelName(model) + ": add --lighting " +
        LightingModelName(LightingModel::PathTrace));
    }
  };
  Progress progress(std::cerr, ShowProgress(arguments));
  const SceneInput loaded = LoadSceneInput("render", arguments, options, output, !cpuReference,
    [&](double fraction) { progress.Update("generating", fraction); }, checkLighting);
  const Scene& scene = loaded.Loaded;
  const vtkSmartPointer<vtkImageData>& field = loaded.Field;
  out << loaded.Note;
  // Format details and metadata (docs/export.md).
  ImageExportOptions exportOptions = MakeExportOptions(arguments, scene, output);
  exportOptions.SceneJson = ResolvedSceneJson(scene, field);
  RenderOptions renderOptions;
  renderOptions.FloatImage = NeedsFloatImage(output, exportOptions);
  renderOptions.OnFrame = [&](int frame, int frames)
  { progress.Update("rendering", double(frame) / double(frames)); };
  renderOptions.TargetNoise = noiseTarget;
  if (cpuReference)
  {
    if (renderOptions.FloatImage)
    {
      throw InputError(output + ": --cpu-reference writes 8-bit PNG images only");
    }
    const RenderedImage image = RenderCpuReference(scene, field, input);
    const double clipped = ClippedCloudShare(image, image.Radiance);
    progress.Finish();
    WriteImage(image, output, exportOptions);
    out << "wrote " << PrintableText(output) << " (" << image.Width << " x " << image.Height
        << " pixels, CPU reference" << DescribeDisplay(image, scene.Render, clipped) << ")\n"
        << ClippingNote(image, clipped);
    return ExitSuccess;
  }
  const OffscreenRenderResult result =
    RenderOffscreen(scene, field, input, benchmarkFrames, renderOptions);
  progress.Finish();
  if (result.Noise)
  {
    CheckNoiseReport(SamplesNoiseNames, spp, *result.Noise);
  }
  WriteImage(result.Image, output, exportOptions);
  out << "wrote " << PrintableText(output) << " (" << result.Image.Width << " x "
      << result.Image.Height << " pixels, ";
  if (scene.Render.Lighting.Model == LightingModel::PathTrace)
  {
    out << result.AccumulatedSamples << " paths per pixel averaged";
  }
  else
  {
    out << result.AccumulatedFrames << " frame" << (result.AccumulatedFrames == 1 ? "" : "s")
        << " averaged";
  }
  out << DescribeDisplay(result.Image, scene.Render, result.ClippedCloudShare) << ")\n";
  if (!result.Image.Coarsened.empty())
  {
    out << result.Image.Coarsened << "\n";
  }
  if (result.Noise)
  {
    out << "noise target: " << DescribeNoiseReport(SamplesNoiseNames, *result.Noise) << "\n";
  }
  out << ClippingNote(result.Image, result.ClippedCloudShare);
  if (benchmarkFrames > 0)
  {
    const double total =
      std::accumulate(result.FrameMilliseconds.begin(), result.FrameMilliseconds.end(), 0.0);
    out << std::fixed << std::setprecision(2) << total / double(benchmarkFrames) << " ms/frame\n";
  }
  return ExitSuccess;
}

// A number for CSV: empty when it is not finite (a step without cloud has no base).
std::string CsvNumber(double value)
{
  if (!std::isfinite(value))
  {
    return "";
  }
  std::ostringstream text;
  text << std::setprecision(9) << value;
  return text.str();
}

// info --time-series: the cloud statistics of each time step of a field file, one field in
// memory at a time, as CSV (a header with the units, then a row per step) or JSON.
int InfoTimeSeries(const Arguments& arguments,
  std::ostream& out,
  const Scene& scene,
  double threshold)
{
  if (!scene.Field.FromFile())
  {
    throw InputError(scene.Source +
      ": --time-series reads the time steps of a field file; this scene's field is generated");
  }
  if (arguments.Has("time-step"))
  {
    throw UsageError("info: --time-series reads every time step (--time-steps A:B[:STRIDE] "
                     "chooses them), not one --time-step");
  }
  std::vector<int> steps = arguments.Has("time-steps")
    ? ParseTimeSteps("info", arguments.Value("time-steps"))
    : std::vector<int>{ 0 };
  struct Row
  {
    int Step;
    double Time;
    CloudStatistics Clouds;
  };
  std::vector<Row> rows;
  FieldReport first;
  vtkNew<vtkImageData> grid; // the first step's lattice, which every other step must have
  for (std::size_t i = 0; i < steps.size(); ++i)
  {
    Scene at = scene;
    at.Field.Read.TimeStep = steps[i];
    FieldReport read;
    const vtkSmartPointer<vtkImageData> field = ProduceField(at, {}, &read);
    if (i > 0)
    {
      CheckSameGrid(TimeStepName(scene.Field.File, steps[i], read), grid, field);
    }
    else
    {
      grid->CopyStructure(field);
      first = read;
      if (!arguments.Has("time-steps"))
      {
        for (int step = 1; step < int(read.TimeSteps); ++step)
        {
          steps.push_back(step);
        }
      }
      CheckTimeSteps(scene, steps, read, "--time-steps");
    }
    rows.push_back(
      { steps[i], read.Time, ComputeCloudStatistics(field, read.Resolved, threshold) });
  }
  const ResolvedFieldUnits& units = first.Resolved;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto base = [nan](const CloudStatistics& c) { return c.HasCloud ? c.CloudBase : nan; };
  const auto top = [nan](const CloudStatistics& c) { return c.HasCloud ? c.CloudTop : nan; };
  if (arguments.Has("json"))
  {
    nlohmann::json json = { { "field", scene.Field.File },
      { "units", UnitsToJson(units) },
      { "time_units", first.TimeUnits },
      { "path_unit", PathUnit(units) },
      { "steps", nlohmann::json::array() } };
    const auto number = [](double v)
    { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
    for (const Row& row : rows)
    {
      json["steps"].push_back({ { "step", row.Step },
        { "time", number(row.Time) },
        { "cloud_cover", row.Clouds.ProjectedCloudFraction },
        { "mean_path", row.Clouds.MeanPath },
        { "mean_cloudy_path", row.Clouds.MeanCloudyPath },
        { "cloud_base", number(base(row.Clouds)) },
        { "cloud_top", number(top(row.Clouds)) } });
    }
    out << json.dump(2) << "\n";
    return ExitSuccess;
  }
  const auto unit = [](const std::string& u) { return u.empty() ? "" : " (" + u + ")"; };
  const std::string path = PathUnit(units);
  const std::string length = units.Length == LengthUnit::None ? "" : LengthUnitName(units.Length);
  out << "step,time" << unit(first.TimeUnits) << ",cloud_cover,mean_path" << unit(path)
      << ",mean_cloudy_path" << unit(path) << ",cloud_base" << unit(length) << ",cloud_top"
      << unit(length) << "\n";
  for (const Row& row : rows)
  {
    out << row.Step << "," << CsvNumber(row.Time) << ","
        << CsvNumber(row.Clouds.ProjectedCloudFraction) << "," << CsvNumber(row.Clouds.MeanPath)
        << "," << CsvNumber(row.Clouds.MeanCloudyPath) << "," << CsvNumber(base(row.Clouds)) << ","
        << CsvNumber(top(row.Clouds)) << "\n";
  }
  return ExitSuccess;
}

int Info(const Arguments& arguments, std::ostream& out)
{
  const std::string& input = arguments.Operands[0];
  // Checked before the field is produced, which may take long.
  double threshold = std::numeric_limits<double>::quiet_NaN();
  if (arguments.Has("cloud-threshold") &&
    !ParseNumber(arguments.Value("cloud-threshold"), threshold))
  {
    throw UsageError("info: --cloud-threshold expects a number (the cloud mask is value > it), "
                     "got \"" +
      arguments.Value("cloud-threshold") + "\"");
  }
  if (arguments.Has("time-steps") && !arguments.Has("time-series"))
  {
    throw UsageError("info: --time-steps chooses the steps of --time-series");
  }
  const Scene scene = LoadOperandScene("info", input, arguments, {}, true);
  if (arguments.Has("time-series"))
  {
    return InfoTimeSeries(arguments, out, scene, threshold);
  }
  FieldReport source;
  const vtkSmartPointer<vtkImageData> field = ProduceField(scene, {}, &source);
  const MemoryUse memory(
    "computing the statistics of " + input + " (" + DescribeDimensions(field) + " voxels)",
    4.0 * double(field->GetNumberOfPoints()));
  const FieldStatistics statistics = ComputeFieldStatistics(field);
  const ResolvedFieldUnits& units = source.Resolved;
  const CloudStatistics clouds = ComputeCloudStatistics(field, units, threshold);
  if (arguments.Has("json"))
  {
    nlohmann::json json = FieldStatisticsToJson(statistics, input, &source);
    json["units"] = UnitsToJson(units);
    json["clouds"] = CloudStatisticsToJson(clouds);
    out << json.dump(2) << "\n";
  }
  else
  {
    PrintFieldStatistics(out, statistics, input, &source);
    PrintCloudStatistics(out, clouds);
  }
  return ExitSuccess;
}

} // namespace

// The demo's scene is the shipped cumulus (data/scenes/cumulus.json): a cloud that looks like
// one, lit by the light march.
static std::string DemoScenePath()
{
  const char* overridden = std::getenv("CLOUDVIS_SCENE_DIR");
  return std::string(overridden && *overridden ? overridden : CLOUDVIS_SCENE_DIRECTORY) +
    "/cumulus.json";
}

int RunDefault(std::ostream& out)
{
  const std::string directory = "out";
  const std::string output = directory + "/default.vti";
  const std::string image = directory + "/default.png";
  const std::string comparison = directory + "/compare.png";
  // Before anything is written: without a display the demo cannot complete.
  RequireDisplay("cloudvis");
  MakeDirectory(directory);
  CheckOutputTarget(output);
  CheckImageOutput(image);
  CheckImageOutput(comparison);
  const Scene scene = LoadScene(DemoScenePath(), {});
  const vtkSmartPointer<vtkImageData> field = ProduceField(scene);
  WriteField(field, output);
  out << "wrote " << PrintableText(output) << " (" << DescribeDimensions(field) << " voxels)\n";
  const OffscreenRenderResult result = RenderOffscreen(scene, field, scene.Source);
  WriteImage(result.Image, image);
  out << "wrote " << PrintableText(image) << " (" << result.Image.Width << " x "
      << result.Image.Height << " pixels, lighting "
      << LightingModelName(scene.Render.Lighting.Model)
      << DescribeDisplay(result.Image, scene.Render, result.ClippedCloudShare) << ")\n";
  // The three lighting models side by side, each panel half the render's size.
  Scene halfSize = scene;
  halfSize.Render.Size[0] = std::max(16, scene.Render.Size[0] / 2);
  halfSize.Render.Size[1] = std::max(16, scene.Render.Size[1] / 2);
  const ComparisonResult compared = RenderComparison(halfSize,
    field,
    scene.Source,
    { { LightingModel::None, std::nullopt },
      { LightingModel::Derivative, std::nullopt },
      { LightingModel::March, std::nullopt } },
    std::nullopt);
  WriteImage(compared.Image, comparison);
  out << "wrote " << PrintableText(comparison) << " (none, derivative and march side by side)\n\n";
  PrintFieldStatistics(out, ComputeFieldStatistics(field), output);
  return ExitSuccess;
}

int Schema(const Arguments&, std::ostream& out)
{
  out << SceneReferenceMarkdown();
  return ExitSuccess;
}

const std::vector<CommandSpec>& Commands()
{
  static const std::vector<CommandSpec> commands = {
    { "generate",
      "[SCENE|FIELD]",
      0,
      1,
      "generate a scene's density field and write it to a .vti, .pvti or .vdb file",
      "SCENE is a scene file (JSON, see docs/scene-format.md); without it the default scene is\n"
      "used (a unit sphere plus 6 octaves of value noise on 128^3 voxels). A field file (" +
        FieldFileExtensions() +
        ", or any name with --field-format) is read and written out again, converted: a float\n"
        "\"density\" field (docs/data.md). The output is written to a temporary file next to it\n"
        "and renamed over it once complete: on failure it is left as it was. A .pvti is written\n"
        "as pieces, the .pvti last; under mpirun each process generates and writes its own\n"
        "pieces (mpirun -np 4 cloudvis generate scene.json -o big.pvti).",
      { OutputOption,
        PiecesOption,
        SetOption,
        FieldFileOptions[0],
        FieldFileOptions[1],
        FieldFileOptions[2],
        HelpOption },
      Generate },
    { "info",
      "FIELD|SCENE",
      1,
      1,
      "print what a field file holds, or a scene's field: geometry, statistics, how it was read",
      "An argument ending in a field extension (" + FieldFileExtensions() +
        ", in any case), or any\n"
        "argument with --field-format, is read as a field; anything else is a scene file whose\n"
        "field is generated (or loaded). Prints how the file was read (format, grid or variable,\n"
        "units, time step, resampling), dimensions, spacing, origin, direction, bounds, value\n"
        "range, mean, the fraction of non-empty voxels (density > 0) and a 16-bin histogram over\n"
        "[min, max]; then the field's units (field.quantity, field.length_unit, field.up, from\n"
        "the scene, else the file) and its cloud statistics: the cloud mask (value > threshold),\n"
        "cloud cover projected along up and per level, cloud base and top, the vertical\n"
        "integral (liquid water path for lwc), the projected clouds' size law and\n"
        "area-perimeter fractal dimension (docs/user-guide.md). With a field file, --set takes\n"
        "only the keys that say how it is read (field.format, field.array, field.time_step,\n"
        "field.missing, field.max_voxels, field.raw, field.air_density) and what it holds\n"
        "(field.quantity, field.length_unit, field.up, field.effective_radius,\n"
        "field.droplet_number). --time-series prints the cloud statistics of each time step\n"
        "of a field file instead (docs/data.md).",
      { JsonOption,
        { "cloud-threshold",
          0,
          "V",
          "the cloud mask is value > V (default 0 for density, 0.01 g/m^3 for lwc)" },
        { "time-series",
          0,
          "",
          "a field file's cloud statistics at each time step, one row per step: cloud cover, "
          "mean and cloudy-column path (LWP), base and top; CSV with the units in the header, "
          "or JSON with --json" },
        { "time-steps", 0, "A:B[:STRIDE]", "the steps of --time-series (default: every one)" },
        SetOption,
        FieldFileOptions[0],
        FieldFileOptions[1],
        FieldFileOptions[2],
        HelpOption },
      Info },
    { "render",
      "SCENE|FIELD",
      1,
      1,
      "render a scene or a field file off screen to a PNG image",
      "An argument ending in a field extension (" + FieldFileExtensions() +
        ", in any case), or any\n"
        "argument with --field-format, is a field file (docs/data.md), rendered with the default\n"
        "scene's transfer function, camera, background and render settings (--set may change\n"
        "those, and how the file is read, not procedural field keys); anything else is a scene\n"
        "file. The image is render.size pixels, the average of\n"
        "render.accumulate jittered frames, written as 8-bit RGB through a temporary file renamed\n"
        "over IMAGE.png. Rendering needs an X display: without one, run it under Xvfb,\n"
        "xvfb-run -a cloudvis render ...",
      { ImageOutputOption,
        SizeOption,
        LightingOption(),
        SamplesPerPixelOption,
        NoiseTimeOption(SamplesNoiseNames),
        AcceptNoiseOption,
        BenchmarkOption,
        CpuReferenceOption,
        PngBitsOption,
        ExrHalfOption,
        TransparentOption,
        ExposureOption,
        QuietOption,
        SetOption,
        FieldFileOptions[0],
        FieldFileOptions[1],
        FieldFileOptions[2],
        HelpOption },
      Render },
    CompareCommand(),
    AnimateCommand(),
    ViewCommand(),
    { "schema",
      "",
      0,
      0,
      "print the reference tables of the scene file format (Markdown)",
      "Prints every key a scene file may hold, with its type, default and allowed values, as\n"
      "the Markdown tables of docs/scene-format.md, which are generated from this output (the\n"
      "test app.scene_docs fails when the two differ; `make docs` writes them in).",
      { HelpOption },
      Schema },
  };
  return commands;
}

} // namespace cloudvis
