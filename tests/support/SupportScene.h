// The GPU side of the renderer fixture: a small off-screen scene of one render window (no
// multisampling), one renderer on black, one volume with either cloudvis's mapper or VTK's GPU
// ray caster, a fixed camera, and the read-backs the tests compare: the window's 8-bit pixels,
// the cloudvis mapper's float image, and its path-traced mean with the variance of each pixel.
// Fields, media, lights and the view are SupportFixtures.h's, the same the CPU renderers get.
#ifndef cloudvis_SupportScene_h
#define cloudvis_SupportScene_h

#include "SupportFixtures.h"
#include "SupportImages.h"
#include "SupportMappers.h"

#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkVolume.h>
#include <vtkVolumeMapper.h>
#include <vtkVolumeProperty.h>

#include <string>

namespace cloudvis
{
namespace support
{

// cloudvis's mapper and VTK's GPU ray caster at a fixed step, jitter off, marching the same way
// (SupportMappers.h): every sample where the tests expect it.
inline const auto CloudMapper = MatchedCloudMapper;
inline const auto VtkMapper = MatchedVtkMapper;

class GpuScene
{
public:
  explicit GpuScene(vtkVolumeMapper* mapper, int width = 128, int height = 128);

  void SetInput(vtkImageData* field);
  // The render tests' usual subject: the article's cloud (SparseCloud(size)) under the ramp
  // medium of opacity 0.6 per 0.1 at density 1 (SetRampMedium(Property, 1.0, 0.6)).
  void ShowSparseCloud(int size = 64);
  // Camera on +z looking at the origin; parallel projection when `parallel`.
  void LookAlongMinusZ(double distance = 6.0, bool parallel = true, double parallelScale = 2.2);
  Image Render();      // the window's 8-bit RGBA pixels, as [0, 1] values
  Image RenderOnce();  // the same from exactly one render (Render's read-back renders again)
  Image RenderFloat(); // the cloudvis mapper's float image (mapper must be vtkCloudVolumeMapper)
  // The cloudvis mapper's path-traced mean after `frames` more frames, with the variance of each
  // pixel's mean; an empty image when the mapper kept none.
  Image RenderPathTraced(int frames);

  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;
  vtkVolumeMapper* Mapper;
};

// Writes the image's color as <name>.png into $CLOUDVIS_RENDER_DUMP when that is set: for
// looking.
void Dump(const Image& image, const std::string& name);

} // namespace support
} // namespace cloudvis

#endif
