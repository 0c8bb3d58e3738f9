// The scenes the renderer tests are built from, for the CPU renderers and the GPU mapper alike:
// fields (a box field from a density function, soft and constant spheres, boxes, the article's
// sparse cloud and a dense fBm box), transfer functions (the linear medium whose table is exact,
// uniform and ramped media), lights (cloudvis::Lights, and vtkLights added to a renderer), the
// parallel view both renderers are given, and an image from a CPU renderer
// (vtkCloudReferenceRenderer, vtkCloudPathTracer) as a support::Image with its variances. The
// GPU side, an off-screen window around a mapper, is SupportScene.h; the two agree on the view
// and lights because both take them from here.
#ifndef cloudvis_SupportFixtures_h
#define cloudvis_SupportFixtures_h

#include "CloudImageComparison.h"
#include "CloudLighting.h"
#include "CloudTransferTable.h"
#include "SupportImages.h"

#include <vtkImageData.h>
#include <vtkSmartPointer.h>
#include <vtkVolumeProperty.h>

#include <glm/glm.hpp>

#include <functional>

class vtkAlgorithm;
class vtkCamera;
class vtkCloudReferenceRenderer;
class vtkRenderer;

namespace cloudvis
{
namespace support
{

// ---- fields --------------------------------------------------------------------------------

// A float field "density" of dims voxels spanning the world box [lo, hi], density(x, y, z) at
// each voxel.
vtkSmartPointer<vtkImageData> MakeBoxField(glm::ivec3 dims,
  glm::dvec3 lo,
  glm::dvec3 hi,
  const std::function<double(double, double, double)>& density);
// A sphere of radius 0.6 with a soft edge 0.3 wide in [-1, 1]^3: optically thick at its core.
vtkSmartPointer<vtkImageData> SoftSphere(int n = 32);
// A field of constant density 1 inside a sphere (or box) of the given radius (half size),
// 0 outside, on a size^3 lattice over [-extent, extent]^3 (vtkCloudDensitySource).
vtkSmartPointer<vtkImageData> ConstantSphere(double radius, int size = 64);
vtkSmartPointer<vtkImageData> ConstantBox(double halfSize, int size = 64, double extent = 2.0);
// A ball whose density falls linearly from 1 at its centre to 0 at `radius` voxels, centred in
// `side`^3 voxels spanning the unit cube: a field file's stand-in of known shape and size.
vtkSmartPointer<vtkImageData> LinearBall(int side, double radius);
// Writes `image` to `path` as VTK XML image data (.vti), as a model writes a step: to PATH.part,
// renamed into place once complete. Throws std::runtime_error when it cannot.
void WriteImageData(vtkImageData* image, const std::string& path);
// The article's cloud (unit sphere + fBm) and a dense fBm box, over [-2, 2]^3.
vtkSmartPointer<vtkImageData> SparseCloud(int size = 64);
vtkSmartPointer<vtkImageData> DenseCloud(int size = 64);

// ---- transfer functions --------------------------------------------------------------------

// sigma_t rising linearly from 0 at density 0 to sigma_t at density 1 (so a trilinear sample's
// extinction is exactly sigma_t times its density), one albedo.
TransferTable LinearTable(float sigma_t, glm::vec3 albedo = glm::vec3(1.0f));
// The transfer function whose table (TransferTableOf, TransferTableSize entries over
// [0, densityMax]) is LinearTable's: sigma_t * density / densityMax at every entry, one albedo.
// The opacity per unit distance u is 1 - exp(-sigma_t u d / densityMax), given at each entry's
// density, with u = 1 / sigma_t so that it stays below VTK's opacity of 1.
vtkSmartPointer<vtkVolumeProperty> LinearMedium(float sigma_t,
  glm::vec3 albedo = glm::vec3(1.0f),
  double densityMax = 1.0);
// Opacity per unit length `opacity` for densities >= 0.5 (0 below), with the given unit
// distance and a uniform color.
void SetUniformMedium(vtkVolumeProperty* property,
  double opacity,
  double unitDistance,
  double r = 1,
  double g = 1,
  double b = 1);
// Opacity rising linearly with density over [0, max] up to `opacity`, with a color ramp.
void SetRampMedium(vtkVolumeProperty* property, double max, double opacity);

// ---- lights --------------------------------------------------------------------------------

// No light but the ambient, a uniform environment of this radiance.
LightingParameters Ambient(glm::vec3 radiance);
// Lighting parameters of one model, the rest at their defaults.
LightingParameters ModelOnly(LightingModel model);
// Every lighting parameter away from its default (and within its limits): the march model with
// nested transmittance, for checking that each one reaches where it should.
LightingParameters EveryLightingParameterChanged();
// A directional light arriving at the origin from `towardLight` (its position, in double: a sun
// may stand beyond float range), and a point light with inverse-square falloff, as the lighting
// docs define them.
Light DirectionalLight(glm::dvec3 towardLight,
  float intensity = 1.0f,
  glm::vec3 color = glm::vec3(1.0f));
Light PointLight(glm::dvec3 position, float intensity = 1.0f, glm::vec3 color = glm::vec3(1.0f));
// A light added to a renderer's scene lights (MakeLight), for the GPU mapper or a CPU renderer
// given the renderer's lights.
void AddLight(vtkRenderer* renderer, const Light& light);

// ---- the view and the CPU renderers ------------------------------------------------------------

// A parallel view of the region [-scale, scale]^2 around `focal` (world), looking along `view`
// from 5 units away, clipping range [1, 10]: for a vtkCamera (the GPU) or a CPU renderer.
void SetParallelView(vtkCamera* camera, glm::dvec3 focal, glm::dvec3 view, double scale);
void SetParallelView(vtkCloudReferenceRenderer* renderer,
  glm::dvec3 focal,
  glm::dvec3 view,
  double scale);

// The image a CPU renderer (vtkCloudReferenceRenderer or vtkCloudPathTracer) makes now: updated
// after Modified(), its "rgba" and, for the path tracer, "rgba_variance".
Image Render(vtkCloudReferenceRenderer* renderer);
// The same image from an updated renderer's output.
Image ImageOf(vtkImageData* output);

// How far `image` is from a path-traced `reference` with its variances (the figures
// docs/lighting.md tabulates, CloudImageComparison.h).
ImageError CompareWithReference(const Image& image, const Image& reference);

// How many errors an algorithm reports when it updates.
int CountErrors(vtkAlgorithm* algorithm);

} // namespace support
} // namespace cloudvis

#endif
