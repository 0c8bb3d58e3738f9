// Implementation of ViewerFiles.h.
#include "ViewerFiles.h"

#include "AtomicFile.h"
#include "Errors.h"
#include "FileNames.h"
#include "ImageWriters.h"
#include "Scene.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sys/stat.h>

namespace cloudvis
{
namespace
{
bool Exists(const std::string& path)
{
  struct stat info;
  return ::stat(path.c_str(), &info) == 0;
}

std::string JoinPath(const std::string& directory, const std::string& name)
{
  if (directory.empty() || directory == ".")
  {
    return name;
  }
  return directory + (directory.back() == '/' ? "" : "/") + name;
}

std::string FileStem(const std::string& path)
{
  const std::string name = FileNameOf(path);
  return name.substr(0, name.find_last_of('.'));
}
} // namespace

std::string NextFreeBase(const std::string& directory,
  const std::string& prefix,
  const std::vector<std::string>& extensions)
{
  for (int n = 1; n < 100000; ++n)
  {
    char number[16];
    std::snprintf(number, sizeof(number), "%03d", n);
    const std::string base = JoinPath(directory, prefix + number);
    if (std::none_of(extensions.begin(),
          extensions.end(),
          [&](const std::string& e) { return Exists(base + e); }))
    {
      return base;
    }
  }
  throw InputError(JoinPath(directory, prefix) + "NNN: every number is taken");
}

RenderedImage GrabWindow(vtkRenderWindow* window, const double* viewport)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  if (viewport)
  {
    grab->SetViewport(const_cast<double*>(viewport));
  }
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff(); // the frame the caller rendered is in the back buffer
  grab->Update();
  vtkImageData* pixels = grab->GetOutput();
  auto* data = vtkUnsignedCharArray::SafeDownCast(pixels->GetPointData()->GetScalars());
  int dimensions[3];
  pixels->GetDimensions(dimensions);
  if (!data || data->GetNumberOfComponents() != 3 || dimensions[0] <= 0 || dimensions[1] <= 0)
  {
    throw InputError("could not read the image back from the window");
  }
  RenderedImage image;
  image.Width = dimensions[0];
  image.Height = dimensions[1];
  image.RGB.assign(data->GetPointer(0), data->GetPointer(0) + data->GetNumberOfValues());
  return image;
}

void WriteTextFile(const std::string& path, const std::string& text, const std::string& what)
{
  WriteStreamAtomically(
    path, what, [&](std::ostream& out) { out.write(text.data(), std::streamsize(text.size())); });
}

std::vector<std::string> WriteScreenshot(const std::string& directory,
  bool floatImage,
  const std::function<ScreenshotImages()>& capture,
  const std::string& sceneJson,
  const std::string& commandLine)
{
  const std::string base = NextFreeBase(directory, "cloudvis-screenshot-", { ".png", ".exr" });
  std::vector<std::string> paths = { base + ".png" };
  if (floatImage)
  {
    paths.push_back(base + ".exr");
  }
  for (const std::string& path : paths)
  {
    CheckImageOutput(path); // before the capture, which takes time
  }
  const ScreenshotImages images = capture();
  ImageExportOptions options;
  options.SceneJson = sceneJson;
  options.CommandLine = commandLine;
  WriteImage(images.Layout, paths[0], options);
  if (floatImage)
  {
    WriteImage(images.Cloud, paths[1], options);
  }
  return paths;
}

std::string WritePreset(const TransferFunctionSpec& spec, const std::string& directory)
{
  const std::string path = NextFreeBase(directory, "cloudvis-preset-", { ".json" }) + ".json";
  CheckOutputTarget(path);
  const nlohmann::json preset = { { "name", FileStem(path) },
    { "description", "saved by cloudvis view" },
    { "opacity", spec.Opacity },
    { "color", spec.Color },
    { "unit_distance", spec.UnitDistance } };
  WriteTextFile(path, preset.dump(2) + "\n", "the preset");
  return path;
}

TransferFunctionSpec ReadNamedPreset(const std::string& name)
{
  const nlohmann::json document = { { "transfer_function", { { "preset", name } } } };
  return SceneFromDocument(document, "preset " + name, "").TransferFunction;
}

} // namespace cloudvis
