// `cloudvis-bench-rendering matrix` (issue 12): every combination of fields, sizes, image sizes,
// lighting models and light counts, cloudvis against VTK's mapper in one run, one markdown table
// row per combination, then the targets met or not.
#include "CloudFieldGeometry.h"
#include "RenderingBench.h"
#include "Scene.h"
#include "vtkCloudLightingProperty.h"

#include <vtkAbstractArray.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace cloudvis
{
namespace bench
{

// ---------------------------------------------------------------------------------------------
// The matrix (issue 12): fields x sizes x image sizes x lighting models x light counts, cloudvis
// against VTK's mapper (unlit for `none`, shaded with the same lights for the lit models) in one
// run; frame times to the GPU's completion, the resolution the mapper settles at while
// interacting, and the GPU memory of both. The path-traced model is measured by
// cloudvis-bench-gpu-pathtrace, not here.
namespace
{

struct ImageSize
{
  int Width, Height;
};

struct Settings
{
  std::vector<std::string> Fields = { "sparse", "dense" };
  std::vector<int> Sizes = { 256, 512, 1024 };
  std::vector<ImageSize> Images = { { 800, 600 }, { 1920, 1080 }, { 3840, 2160 } };
  // MeasuredLighting's names, measured in this order after `none` (the lit rows' "x none").
  std::vector<std::string> Models = { "none", "derivative", "march", "nested" };
  std::vector<int> Lights = { 1, 2 };
  // Samples per reading of the occupancy map: 0 lets the mapper choose by the field's occupancy.
  std::vector<int> MapReads = { 0 };
  int Frames = 10;
  int InteractiveFrames = 10;
  int ScalarType = VTK_UNSIGNED_CHAR;
  bool Vtk = true;
};

// One measured row of the table.
struct Row
{
  std::string Field;
  int Size = 0;
  ImageSize Image{};
  std::string Model;
  int Lights = 0;   // 0: the model uses none
  int MapReads = 0; // samples per map read forced on the mapper; 0: its own choice
  double CloudMs = -1.0;
  double VtkMs = -1.0;
  double NoneMs = -1.0; // cloudvis unlit on the same field and image
  double InteractiveScale = -1.0;
  double InteractiveMs = -1.0;
  long long CloudBytes = -1;
  long long CloudDriverBytes = -1; // the driver's free-memory delta over the first render
  long long VtkBytes = -1;
  bool VtkBytesMeasured = false;
  std::string Refused;
};

std::vector<std::string> SplitList(const std::string& text)
{
  std::vector<std::string> items;
  std::size_t begin = 0;
  while (begin <= text.size())
  {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    if (end > begin)
    {
      items.push_back(text.substr(begin, end - begin));
    }
    begin = end + 1;
  }
  return items;
}

// A positive integer, or -1.
int PositiveInteger(const std::string& text)
{
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  return end && *end == '\0' && value > 0 && value < (1L << 30) ? int(value) : -1;
}

// The driver's free video memory before and after `render`, when it reports it (-1 otherwise).
long long DriverBytesUsedBy(vtkRenderWindow* window, const std::function<void()>& render)
{
  const long long before = vtkCloudVolumeMapper::GetFreeGPUMemoryBytes(window);
  render();
  window->WaitForCompletion();
  const long long after = vtkCloudVolumeMapper::GetFreeGPUMemoryBytes(window);
  return before >= 0 && after >= 0 ? before - after : -1;
}

std::string Ms(double ms)
{
  char text[32];
  std::snprintf(text, sizeof text, ms < 0.0 ? "-" : "%.1f", ms);
  return ms < 0.0 ? "-" : text;
}

std::string Bytes(long long bytes)
{
  return bytes < 0 ? "-" : FormatBytes(double(bytes));
}

void PrintHeader()
{
  std::printf("| field | voxels | image | model | lights | cloudvis ms | VTK ms | VTK / cloudvis "
              "| x none | interactive: scale, ms | cloudvis GPU memory (driver delta) | VTK GPU "
              "memory |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
}

void PrintRow(const Row& row)
{
  const std::string image = row.Image.Width > 0
    ? std::to_string(row.Image.Width) + "x" + std::to_string(row.Image.Height)
    : "-";
  const std::string model = row.MapReads > 0
    ? row.Model + " (" + std::to_string(row.MapReads) + " per map read)"
    : row.Model;
  std::printf("| %s | %d^3 | %s | %s | %s |",
    row.Field.c_str(),
    row.Size,
    image.c_str(),
    model.c_str(),
    row.Lights ? std::to_string(row.Lights).c_str() : "-");
  if (!row.Refused.empty())
  {
    std::printf(" %s |||||||\n", row.Refused.c_str());
    std::fflush(stdout);
    return;
  }
  char ratioText[32] = "-";
  if (row.CloudMs > 0.0 && row.VtkMs > 0.0)
  {
    std::snprintf(ratioText, sizeof ratioText, "**%.2f**", row.VtkMs / row.CloudMs);
  }
  char noneText[32] = "-";
  if (row.NoneMs > 0.0)
  {
    std::snprintf(noneText, sizeof noneText, "%.2f", row.CloudMs / row.NoneMs);
  }
  char interactive[64] = "-";
  if (row.InteractiveScale > 0.0)
  {
    std::snprintf(interactive,
      sizeof interactive,
      "%.2f (%dx%d), %.1f",
      row.InteractiveScale,
      int(std::lround(row.InteractiveScale * row.Image.Width)),
      int(std::lround(row.InteractiveScale * row.Image.Height)),
      row.InteractiveMs);
  }
  std::printf(" %s | %s | %s | %s | %s | %s (%s) | %s%s |\n",
    Ms(row.CloudMs).c_str(),
    Ms(row.VtkMs).c_str(),
    ratioText,
    noneText,
    interactive,
    Bytes(row.CloudBytes).c_str(),
    Bytes(row.CloudDriverBytes).c_str(),
    Bytes(row.VtkBytes).c_str(),
    row.VtkBytes < 0 ? "" : (row.VtkBytesMeasured ? " (driver delta)" : " (estimate)"));
  std::fflush(stdout);
}

// VTK's mapper on one field and image: unlit, then shaded with each light count. Its memory is
// the driver's free-memory delta over its first render where the driver reports free memory,
// else an estimate: the field's 3-D texture in its native texels (VTK 9.1 uploads unsigned char
// as R8, unsigned short as R16, float as R32F), the largest part by far.
struct VtkResults
{
  double UnlitMs = -1.0;
  std::map<int, double> ShadedMs; // per light count
  long long Bytes = -1;
  bool Measured = false;
  std::string Refused;
};

VtkResults MeasureVtk(vtkImageData* field,
  const Options& options,
  const Settings& settings,
  double densityMax)
{
  VtkResults results;
  const int size = field->GetDimensions()[0];
  auto mapper = VtkMapper(4.0 / (size - 1));
  View view(mapper, field, options, densityMax);
  view.Volume->VisibilityOff(); // the context and the window's buffers first
  view.Window->Render();
  GLint largest = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &largest);
  const long long textureBytes =
    (long long)size * size * size * vtkAbstractArray::GetDataTypeSize(field->GetScalarType());
  const long long free = vtkCloudVolumeMapper::GetFreeGPUMemoryBytes(view.Window);
  if (size > largest || (free >= 0 && textureBytes > free))
  {
    results.Refused = "refused: VTK's mapper needs a 3-D texture of " + std::to_string(size) +
      "^3 texels, " + FormatBytes(double(textureBytes)) + " (the GPU allows " +
      std::to_string(largest) + " per axis" +
      (free >= 0 ? ", reports " + FormatBytes(double(free)) + " free" : "") + ")";
    return results;
  }
  view.Volume->VisibilityOn();
  const long long delta = DriverBytesUsedBy(view.Window, [&] { view.Window->Render(); });
  results.Measured = delta >= 0;
  results.Bytes = results.Measured ? delta : textureBytes;
  const bool anyUnlit =
    std::find(settings.Models.begin(), settings.Models.end(), "none") != settings.Models.end();
  if (anyUnlit)
  {
    results.UnlitMs = view.MillisecondsPerFrame(settings.Frames, [] {});
  }
  if (settings.Models.size() > (anyUnlit ? 1u : 0u))
  {
    view.Property->ShadeOn();
    for (int lights : settings.Lights)
    {
      SetLights(view.Renderer, lights);
      results.ShadedMs[lights] = view.MillisecondsPerFrame(settings.Frames, [] {});
    }
  }
  return results;
}

// cloudvis on one field and image, for every model and light count asked for.
void MeasureCloud(const std::string& fieldName,
  vtkImageData* field,
  const Options& options,
  const Settings& settings,
  double densityMax,
  const VtkResults& vtk,
  std::vector<Row>& rows)
{
  const int size = field->GetDimensions()[0];
  auto mapper = CloudMapper(4.0 / (size - 1));
  View view(mapper, field, options, densityMax);
  vtkCamera* camera = view.Renderer->GetActiveCamera();
  std::map<int, double> noneMs; // per samples-per-map-read setting
  bool first = true;
  for (const std::string& model : settings.Models)
  {
    const LightingParameters lighting = *MeasuredLighting(model);
    const bool lit = lighting.Model != LightingModel::None;
    for (int lights : lit ? settings.Lights : std::vector<int>{ 0 })
      for (int mapReads : settings.MapReads)
      {
        mapper->SetSamplesPerMapRead(mapReads);
        Row row;
        row.MapReads = mapReads;
        row.Field = fieldName;
        row.Size = size;
        row.Image = { options.Width, options.Height };
        row.Model = model;
        row.Lights = lights;
        mapper->GetLightingProperty()->SetParameters(lighting);
        SetLights(view.Renderer, lights);
        if (first)
        {
          view.Volume->VisibilityOff();
          view.Window->Render();
          view.Volume->VisibilityOn();
          row.CloudDriverBytes = DriverBytesUsedBy(view.Window, [&] { view.Window->Render(); });
          first = false;
          mapper->CollectStatisticsOn();
          view.Window->Render();
          mapper->CollectStatisticsOff();
          std::fprintf(stderr,
            "(%s %d^3: %.1f%% of the occupancy bricks occupied)\n",
            fieldName.c_str(),
            size,
            100.0 * mapper->GetLastFrameStatistics().OccupiedBrickFraction);
        }
        else
        {
          view.Window->Render();
        }
        if (!mapper->GetLastError().empty())
        {
          row.Refused = "refused by cloudvis: " + mapper->GetLastError();
          PrintRow(row);
          rows.push_back(row);
          if (mapper->GetGPUMemoryBytes() == 0 || mapper->GetDensityTextureBytes() == 0)
          {
            return; // the field itself does not fit: no other model will
          }
          continue;
        }
        row.CloudMs = view.MillisecondsPerFrame(settings.Frames, [&] { mapper->Modified(); });
        row.CloudBytes = mapper->GetGPUMemoryBytes();
        row.VtkMs =
          lit ? (vtk.ShadedMs.count(lights) ? vtk.ShadedMs.at(lights) : -1.0) : vtk.UnlitMs;
        row.VtkBytes = vtk.Bytes;
        row.VtkBytesMeasured = vtk.Measured;
        if (!lit)
        {
          noneMs[mapReads] = row.CloudMs;
        }
        row.NoneMs = noneMs.count(mapReads) ? noneMs[mapReads] : -1.0;

        // Interacting: the window's desired update rate above 1, the camera turning each frame; the
        // mapper lowers its resolution scale to keep InteractiveFrameRate. A few frames to settle,
        // then the measured ones, then one more that reads back the march's size.
        double position[3];
        camera->GetPosition(position);
        view.Window->SetDesiredUpdateRate(20.0);
        const auto turn = [&] { camera->Azimuth(1.0); };
        view.MillisecondsPerFrame(5, turn);
        row.InteractiveMs = view.MillisecondsPerFrame(settings.InteractiveFrames, turn);
        mapper->CollectStatisticsOn();
        turn();
        view.Window->Render();
        mapper->CollectStatisticsOff();
        row.InteractiveScale = double(mapper->GetLastFrameStatistics().Width) / options.Width;
        view.Window->SetDesiredUpdateRate(0.0001); // vtkRenderWindow's still rate
        camera->SetPosition(position);
        camera->SetViewUp(0.0, 1.0, 0.0);
        PrintRow(row);
        rows.push_back(row);
    }
  }
}

// Each of the targets, met or not for the rows that measure it.
void PrintTargets(const std::vector<Row>& rows)
{
  std::printf("\nTargets (issue 12; they are GPU targets: on a software renderer the verdicts are "
              "indicative only):\n");
  const auto verdict = [](bool met) { return met ? "met" : "NOT met"; };
  bool any = false;
  for (const Row& row : rows)
  {
    const bool hd = row.Image.Width == 1920 && row.Image.Height == 1080;
    if (row.Refused.empty() && row.Model == "none" && hd && (row.Size == 256 || row.Size == 512) &&
      row.VtkMs > 0.0)
    {
      const double wanted = row.Field == "sparse" ? 5.0 : 1.3;
      const double ratio = row.VtkMs / row.CloudMs;
      std::printf("- unlit %s %d^3 at 1920x1080: %.2fx VTK (target at least %.1fx): %s\n",
        row.Field.c_str(),
        row.Size,
        ratio,
        wanted,
        verdict(ratio >= wanted));
      any = true;
    }
  }
  if (!any)
  {
    std::printf("- unlit against VTK at 1920x1080, 256^3 and 512^3: not measured in this run\n");
  }
  any = false;
  for (const Row& row : rows)
  {
    if (row.Refused.empty() && row.Model == "march" && row.Lights == 2 && row.NoneMs > 0.0)
    {
      const double cost = row.CloudMs / row.NoneMs;
      std::printf("- march (light volumes), two lights, %s %d^3 at %dx%d: %.2fx none (target at "
                  "most 1.5x): %s\n",
        row.Field.c_str(),
        row.Size,
        row.Image.Width,
        row.Image.Height,
        cost,
        verdict(cost <= 1.5));
      any = true;
    }
  }
  if (!any)
  {
    std::printf("- march with two lights against none: not measured in this run\n");
  }
  any = false;
  for (const Row& row : rows)
  {
    if (row.Refused.empty() && row.Model == "march" && row.Lights == 2 && row.Size == 512 &&
      row.Field == "sparse" && row.Image.Width == 1920 && row.Image.Height == 1080)
    {
      const double fps = 1000.0 / row.CloudMs;
      std::printf("- two lights, march, sparse 512^3 at 1920x1080: %.1f frames/s (target at "
                  "least 60): %s\n",
        fps,
        verdict(fps >= 60.0));
      any = true;
    }
  }
  if (!any)
  {
    std::printf("- two lights at 512^3, 1920x1080, 60 frames/s: not measured in this run\n");
  }
}

} // namespace

int Matrix(int argc, char* argv[])
{
  Settings settings;
  bool chosen = false; // any of the subset options given
  const char* usage =
    "usage: cloudvis-bench-rendering matrix [--fields sparse,dense] [--sizes "
    "256,512,1024] [--images 800x600,1920x1080,3840x2160] [--models "
    "none,derivative,march,nested] [--lights 1,2] [--map-reads auto,1,2,4] [--frames F] "
    "[--interactive-frames F] [--type uchar|ushort|float] [--no-vtk]\n";
  for (int i = 2; i < argc; ++i)
  {
    const std::string option = argv[i];
    if (option == "--help" || option == "-h")
    {
      std::printf("%s", usage);
      return 0;
    }
    if (option == "--no-vtk")
    {
      settings.Vtk = false;
      continue;
    }
    if (i + 1 >= argc)
    {
      std::fprintf(stderr, "%s: %s needs a value\n%s", argv[0], option.c_str(), usage);
      return 2;
    }
    const std::string value = argv[++i];
    const std::vector<std::string> items = SplitList(value);
    bool valid = !items.empty();
    if (option == "--fields")
    {
      settings.Fields = items;
      for (const std::string& item : items)
        valid = valid && (item == "sparse" || item == "dense");
      chosen = true;
    }
    else if (option == "--sizes" || option == "--lights")
    {
      std::vector<int>& list = option == "--sizes" ? settings.Sizes : settings.Lights;
      list.clear();
      for (const std::string& item : items)
      {
        const int n = PositiveInteger(item);
        valid = valid && n > 0 && (option == "--sizes" ? n >= 8 : n <= 2);
        list.push_back(n);
      }
      chosen = true;
    }
    else if (option == "--map-reads")
    {
      settings.MapReads.clear();
      for (const std::string& item : items)
      {
        const int n = item == "auto" ? 0 : PositiveInteger(item);
        valid = valid && n >= 0 && n <= 4;
        settings.MapReads.push_back(n);
      }
    }
    else if (option == "--images")
    {
      settings.Images.clear();
      for (const std::string& item : items)
      {
        ImageSize image{ 0, 0 };
        char end = 0;
        valid = valid &&
          std::sscanf(item.c_str(), "%dx%d%c", &image.Width, &image.Height, &end) == 2 &&
          image.Width >= 16 && image.Height >= 16 && image.Width <= 16384 && image.Height <= 16384;
        settings.Images.push_back(image);
      }
      chosen = true;
    }
    else if (option == "--models")
    {
      settings.Models = items;
      for (const std::string& item : items)
      {
        valid = valid && MeasuredLighting(item).has_value();
      }
      // `none` first: the lit rows are measured against it.
      std::stable_partition(settings.Models.begin(),
        settings.Models.end(),
        [](const std::string& model) { return model == "none"; });
      chosen = true;
    }
    else if (option == "--frames" || option == "--interactive-frames")
    {
      (option == "--frames" ? settings.Frames : settings.InteractiveFrames) =
        PositiveInteger(value);
      valid = PositiveInteger(value) > 0;
    }
    else if (option == "--type")
    {
      settings.ScalarType = value == "uchar" ? VTK_UNSIGNED_CHAR
        : value == "ushort"                  ? VTK_UNSIGNED_SHORT
        : value == "float"                   ? VTK_FLOAT
                                             : -1;
      valid = settings.ScalarType >= 0;
    }
    else
    {
      std::fprintf(stderr, "%s: unknown option %s\n%s", argv[0], option.c_str(), usage);
      return 2;
    }
    if (!valid)
    {
      std::fprintf(stderr,
        "%s: invalid value \"%s\" for %s\n%s",
        argv[0],
        value.c_str(),
        option.c_str(),
        usage);
      return 2;
    }
  }

  // What renders: a software renderer gets a small default matrix (the full one takes hours).
  std::string renderer, version;
  {
    vtkNew<vtkRenderWindow> probe;
    probe->SetOffScreenRendering(1);
    probe->SetSize(16, 16);
    probe->Render();
    renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  }
  const bool software = renderer.find("llvmpipe") != std::string::npos ||
    renderer.find("softpipe") != std::string::npos;
  std::printf("renderer: %s, OpenGL %s\n", renderer.c_str(), version.c_str());
  if (software && !chosen)
  {
    settings.Sizes = { 128, 256 };
    settings.Images = { { 800, 600 } };
    settings.Frames = std::min(settings.Frames, 3);
    std::printf("a software renderer and no --sizes/--images/--fields/--models/--lights given: "
                "the llvmpipe subset (128^3 and 256^3, 800x600, 3 frames); the full matrix is "
                "the default on a GPU\n");
  }
  std::printf("fields stored as %s; %d frames per measure (after one warm-up), %d interactive; "
              "ms/frame to the GPU's completion (glFinish); the path-traced model is measured "
              "by cloudvis-bench-gpu-pathtrace\n\n",
    vtkImageScalarTypeNameMacro(settings.ScalarType),
    settings.Frames,
    settings.InteractiveFrames);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  PrintHeader();

  std::vector<Row> rows;
  const double densityMax = FullScale(settings.ScalarType);
  for (int size : settings.Sizes)
  {
    for (const std::string& fieldName : settings.Fields)
    {
      // The field once in host memory, and a copy in the driver's (llvmpipe's textures are host
      // memory too; a GPU driver may stage it).
      const long long fieldBytes =
        (long long)size * size * size * vtkAbstractArray::GetDataTypeSize(settings.ScalarType);
      const long long needed = 2 * fieldBytes + 32LL * size * size * 4;
      const long long available = static_cast<long long>(AvailableMemoryBytes());
      if (available > 0 && needed > available)
      {
        Row row;
        row.Field = fieldName;
        row.Size = size;
        row.Model = "all";
        row.Refused = "skipped: the " +
          std::string(vtkImageScalarTypeNameMacro(settings.ScalarType)) + " field needs about " +
          FormatBytes(double(needed)) + " of host memory, " + FormatBytes(double(available)) +
          " available";
        PrintRow(row);
        rows.push_back(row);
        continue;
      }
      const auto field = Field(size, fieldName == "dense", settings.ScalarType);
      for (const ImageSize& image : settings.Images)
      {
        Options options;
        options.Size = size;
        options.Width = image.Width;
        options.Height = image.Height;
        VtkResults vtk;
        if (settings.Vtk)
        {
          vtk = MeasureVtk(field, options, settings, densityMax);
          if (!vtk.Refused.empty())
          {
            Row row;
            row.Field = fieldName;
            row.Size = size;
            row.Image = image;
            row.Model = "VTK";
            row.Refused = vtk.Refused;
            PrintRow(row);
            rows.push_back(row);
          }
        }
        MeasureCloud(fieldName, field, options, settings, densityMax, vtk, rows);
      }
    }
  }
  PrintTargets(rows);
  return 0;
}

} // namespace bench
} // namespace cloudvis
