// What the commands of cloudvis-bench-rendering share (BenchRendering.cxx lists them): the two
// benchmark fields, a window with one volume framing them, the pair of mappers set up to march
// alike (cloudvis's and VTK's vtkGPUVolumeRayCastMapper), the lights of the lit measures, and the
// window's pixels read back as the app reads them (CaptureWindow) with their RMS difference.
#ifndef cloudvis_RenderingBench_h
#define cloudvis_RenderingBench_h

#include "CloudLightingParameters.h"
#include "RenderedImage.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <functional>
#include <optional>
#include <string>

class vtkImageData;

namespace cloudvis
{
namespace bench
{

struct Options
{
  int Size = 256;
  int Frames = 10;
  int Width = 800;
  int Height = 600;
};

// The bench's two fields on size^3 voxels over [-2, 2]^3: the article's sparse cloud, or fBm
// filling the box (`dense`). Integer types hold round(clamp(density, 0, 1) * FullScale).
vtkSmartPointer<vtkImageData> Field(int size, bool dense, int scalarType = VTK_FLOAT);

// The largest value of a scalar type, which a density of 1 becomes in an integer field: 255 for
// VTK_UNSIGNED_CHAR, 65535 for VTK_UNSIGNED_SHORT, 1 for VTK_FLOAT.
double FullScale(int scalarType);

// A float field's densities in `scalarType` (as Field stores them), same geometry.
vtkSmartPointer<vtkImageData> Quantized(vtkImageData* field, int scalarType);

// cloudvis's mapper marching every `step` world units without jitter, and VTK's GPU ray caster
// marching the same way (the same sample distance, no jitter, no automatic change of the step,
// composite blending): on the same input, property and camera their unlit images differ only by
// the integration details both document.
vtkSmartPointer<vtkCloudVolumeMapper> CloudMapper(double step);
vtkSmartPointer<vtkGPUVolumeRayCastMapper> VtkMapper(double step);

// One window, renderer, volume; the camera frames the [-2, 2]^3 box from an oblique view.
struct View
{
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;

  // densityMax: the density the transfer function's last point sits at (1 for the float field;
  // the full scale of an integer type holding it).
  View(vtkVolumeMapper* mapper,
    vtkImageData* field,
    const Options& options,
    double densityMax = 1.0);

  // Mean milliseconds per frame over `frames` renders after one warm-up render.
  double MillisecondsPerFrame(int frames, const std::function<void()>& beforeEachFrame);

  // The window's pixels after the last render (CaptureWindow).
  RenderedImage Pixels();
};

// The RMS difference of two images' values in 8-bit levels (infinite for images of other sizes).
double RmsLevels(const RenderedImage& a, const RenderedImage& b);

// The sun every lit measure uses: a directional scene light of intensity 1 from (6, 8, 4) toward
// the origin; with two lights, also a warm point light below and to the left (as in
// data/scenes/two-lights.json). Replaces the renderer's lights.
void SetLights(vtkRenderer* renderer, int count);

// A lighting model by its scene name (FindLightingModel), or "nested": the march with the nested
// light march at every sample instead of the light volumes. nullopt for any other name and for
// pathtrace (measured by cloudvis-bench-gpu-pathtrace).
std::optional<LightingParameters> MeasuredLighting(const std::string& name);

// The commands.
int Default(const Options& options, bool lightingOnly);
int Storage(const Options& options);
int Occupancy(const Options& options);
int OneModel(const Options& options, const std::string& model, bool dense, int brickSize);
int Reprojection(const Options& options, const std::string& dumpDirectory);
int Matrix(int argc, char* argv[]);

} // namespace bench
} // namespace cloudvis

#endif
