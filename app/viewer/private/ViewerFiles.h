// The files the viewer reads and writes, apart from its window: the naming they share
// (DIR/PREFIX-NNN.EXT, the first NNN free), the window's pixels as an image, screenshots (PNG and
// EXR through the export writers), transfer-function presets (written in cloudvis's preset format,
// read through the scene's own reader so a preset is checked exactly as transfer_function.preset)
// and text files such as saved scenes. Every write is atomic and checked (WriteStreamAtomically).
#ifndef cloudvis_ViewerFiles_h
#define cloudvis_ViewerFiles_h

#include "RenderedImage.h"
#include "Scene.h"

#include <functional>
#include <string>
#include <vector>

class vtkRenderWindow;

namespace cloudvis
{

// DIR/PREFIXNNN with the first NNN (001, 002, ...) for which no file with any of `extensions`
// exists yet. Throws InputError when all are taken.
std::string NextFreeBase(const std::string& directory,
  const std::string& prefix,
  const std::vector<std::string>& extensions);

// The window's back buffer as 8-bit RGB, whole or the part `viewport` covers (normalized
// viewport coordinates, as vtkRenderer::GetViewport gives them). Throws InputError when the
// pixels cannot be read back.
RenderedImage GrabWindow(vtkRenderWindow* window, const double* viewport = nullptr);

// Writes `text` to `path` atomically; `what` names the content in errors ("the scene").
void WriteTextFile(const std::string& path, const std::string& text, const std::string& what);

// A screenshot: the PNG's 8-bit picture (the layout's views) and the EXR's float image (the 3D
// view's cloud; empty without one).
struct ScreenshotImages
{
  RenderedImage Layout;
  RenderedImage Cloud;
};

// Writes DIR/cloudvis-screenshot-NNN.png of the images' Layout and, with `floatImage`, .exr of
// their Cloud (`capture` is called once the targets are known to be writable; its Cloud must hold
// the float image when `floatImage`), with the scene and command line as metadata. Returns the
// files written.
std::vector<std::string> WriteScreenshot(const std::string& directory,
  bool floatImage,
  const std::function<ScreenshotImages()>& capture,
  const std::string& sceneJson,
  const std::string& commandLine);

// The transfer function as DIR/cloudvis-preset-NNN.json in cloudvis's preset format (named
// after its file). Returns the path.
std::string WritePreset(const TransferFunctionSpec& spec, const std::string& directory);

// The transfer function of the named preset of PresetDirectory(). Throws InputError naming the
// preset and the problem.
TransferFunctionSpec ReadNamedPreset(const std::string& name);

} // namespace cloudvis

#endif
