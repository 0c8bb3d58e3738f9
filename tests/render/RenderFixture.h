// A small off-screen scene for rendering tests: one render window, one renderer, one volume
// with either cloudvis's mapper or VTK's GPU ray caster, a fixed camera, and read-back helpers.
#ifndef RenderFixture_h
#define RenderFixture_h

#include "CloudLighting.h"
#include "SupportMappers.h"
#include "vtkCloudLightingProperty.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkVolume.h>
#include <vtkVolumeMapper.h>
#include <vtkVolumeProperty.h>

#include <string>
#include <vector>

namespace cloudvis
{
namespace test
{

// A field of constant density 1 inside a sphere (or box) of the given radius (half size),
// 0 outside, on a 64^3 lattice over [-2, 2]^3 unless told otherwise.
vtkSmartPointer<vtkImageData> ConstantSphere(double radius, int size = 64);
vtkSmartPointer<vtkImageData> ConstantBox(double halfSize, int size = 64, double extent = 2.0);
// The article's cloud (unit sphere + fBm) and a dense fBm box.
vtkSmartPointer<vtkImageData> SparseCloud(int size = 64);
vtkSmartPointer<vtkImageData> DenseCloud(int size = 64);

// cloudvis's mapper and VTK's GPU ray caster at a fixed step, jitter off, marching the same
// way (tests/support): every sample where the tests expect it.
inline const auto CloudMapper = support::MatchedCloudMapper;
inline const auto VtkMapper = support::MatchedVtkMapper;

// A property whose opacity per unit length is `opacity` for densities >= 0.5 (0 below), with
// the given unit distance and a uniform color.
void SetUniformMedium(vtkVolumeProperty* property, double opacity, double unitDistance,
  double r = 1, double g = 1, double b = 1);
// Opacity rising linearly with density over [0, max] up to `opacity`, with a color ramp.
void SetRampMedium(vtkVolumeProperty* property, double max, double opacity);

// Scene lights as the lighting docs define them: a directional light arriving from `from`
// toward the origin, and a point light at `at` with inverse-square falloff.
void AddDirectionalLight(vtkRenderer* renderer, double fromX, double fromY, double fromZ,
  double intensity = 1.0, double r = 1, double g = 1, double b = 1);
void AddPointLight(vtkRenderer* renderer, double x, double y, double z, double intensity = 1.0,
  double r = 1, double g = 1, double b = 1);

// Mean of one channel (0..3) over the columns [x0, x1) of an image.
double MeanOver(const struct Image& image, int channel, int x0, int x1);

struct Image
{
  int Width = 0, Height = 0;
  std::vector<float> RGBA; // 0..1, rows bottom to top
  float At(int x, int y, int channel) const { return RGBA[(size_t(y) * Width + x) * 4 + channel]; }
};

class Scene
{
public:
  explicit Scene(vtkVolumeMapper* mapper, int width = 128, int height = 128);

  void SetInput(vtkImageData* field);
  // Camera on +z looking at the origin; parallel projection when `parallel`.
  void LookAlongMinusZ(double distance = 6.0, bool parallel = true, double parallelScale = 2.2);
  Image Render();      // the window's 8-bit pixels as floats
  Image RenderOnce();  // the same from exactly one render (Render's read-back renders again)
  Image RenderFloat(); // the cloudvis mapper's float image (mapper must be vtkCloudVolumeMapper)

  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;
  vtkVolumeMapper* Mapper;
};

// Writes the image as <name>.png into $CLOUDVIS_RENDER_DUMP when that is set: for looking.
void Dump(const Image& image, const std::string& name);

// The difference of two images over the pixels where either shows cloud (a color above 0, the
// fixture's background being black), in 8-bit levels.
struct CloudDifference
{
  int CloudPixels = 0;
  double RmsLevels = 0.0;
  double MaxLevels = 0.0;
};
CloudDifference CloudPixelDifference(const Image& a, const Image& b);

// Root mean square difference over the RGB channels, in 8-bit levels.
double RmsDifference(const Image& a, const Image& b);
// The largest difference of any channel; NaN when either image holds a NaN.
double MaxDifference(const Image& a, const Image& b);

} // namespace test
} // namespace cloudvis

#endif
