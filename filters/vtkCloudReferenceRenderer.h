/**
 * @class   vtkCloudReferenceRenderer
 * @brief   CPU reference render of a density field with the GPU mapper's equations
 *
 * vtkCloudReferenceRenderer renders a cloud density field on the CPU, one ray per pixel, with
 * the equations of docs/lighting.md and the order of operations of the GPU march
 * (shaders/CloudMarchFS.glsl and the lighting models; the per-ray code is in
 * CloudReferenceMarch.h). It is slow and exact: the oracle the GPU images are tested against.
 * No jitter, no empty-space skipping (which does not change the sum), no opaque geometry.
 *
 * Input: vtkImageData whose active point scalars have one component of float, unsigned char or
 * unsigned short, finite values and at least 2 voxels per axis. Its whole geometry counts, as
 * VTK's volume mappers read it: extent (which need not start at 0), origin, spacing and
 * direction matrix, placed in the world by VolumeMatrix (a vtkVolume's matrix). The density is
 * sampled as the GPU mapper's native-type texture holds it (CloudDensityTexels.h: the normalized
 * texels interpolated, then scaled to the scalar units the transfer function is in). The march
 * computes in the local frame of CloudMarchUniforms.h, like the GPU, and SetUpMarch refuses, with
 * the GPU's words, what float arithmetic cannot render faithfully.
 *
 * Every parameter is a VTK property (wrappable): the transfer function as a vtkVolumeProperty,
 * the lighting as a vtkCloudLightingProperty, the lights as vtkLights, the camera and the volume
 * matrix as numbers and a vtkMatrix4x4. From C++ the lights may also be cloudvis::Lights, as a
 * scene holds them (cloudvis gives a scene's lights so, never as vtkLights).
 *
 * Output: vtkImageData of ImageSize[0] x ImageSize[1] x 1 points (origin 0, spacing 1) with a
 * float, 4-component point array "rgba" (the active scalars): premultiplied radiance in r, g, b
 * and opacity 1 - T in a. Row 0 is the bottom of the image, as in OpenGL.
 *
 * The camera follows vtkCamera's conventions exactly, so giving the same numbers to a vtkCamera
 * and rendering into a viewport of ImageSize pixels shows the same view: pixel (i, j) has
 * normalized device coordinates ((i + 0.5) / W * 2 - 1, (j + 0.5) / H * 2 - 1) and its ray runs
 * from the near plane to the far plane through them; t is distance from the near plane in the
 * march's local units.
 *
 * Rows are rendered under vtkSMPTools; each pixel depends only on the input and the
 * parameters, never on the threads.
 *
 * vtkCloudPathTracer is the same renderer with a Monte Carlo path tracer in place of the march
 * (RenderImage): the same input checks, camera, table, lighting and lights.
 */
#ifndef vtkCloudReferenceRenderer_h
#define vtkCloudReferenceRenderer_h

#include "cloudvisFiltersModule.h"
#include "vtkCloudLightingProperty.h"

#include <vtkImageAlgorithm.h>
#include <vtkLightCollection.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#ifndef __VTK_WRAP__
#include <glm/glm.hpp>
#endif

class vtkVolumeProperty;
namespace cloudvis
{
struct MarchUniforms;
struct OpticalDepthGrid;
struct WholeFieldScattering;
}

class CLOUDVISFILTERS_EXPORT vtkCloudReferenceRenderer : public vtkImageAlgorithm
{
public:
  static vtkCloudReferenceRenderer* New();
  vtkTypeMacro(vtkCloudReferenceRenderer, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Also the latest change of the volume property, the lighting property and the lights.
   */
  vtkMTimeType GetMTime() override;

  ///@{
  /**
   * Output image width and height in pixels, each at least 1. Default 128 x 128.
   */
  vtkSetVector2Macro(ImageSize, int);
  vtkGetVector2Macro(ImageSize, int);
  ///@}

  ///@{
  /**
   * The camera, as vtkCamera's Position, FocalPoint and ViewUp (world). The view up is
   * orthogonalised against the direction of projection as vtkCamera does. Defaults (0, 0, 1),
   * (0, 0, 0) and (0, 1, 0), as vtkCamera's.
   */
  vtkSetVector3Macro(CameraPosition, double);
  vtkGetVector3Macro(CameraPosition, double);
  vtkSetVector3Macro(CameraFocalPoint, double);
  vtkGetVector3Macro(CameraFocalPoint, double);
  vtkSetVector3Macro(CameraViewUp, double);
  vtkGetVector3Macro(CameraViewUp, double);
  ///@}

  ///@{
  /**
   * Vertical view angle in degrees for perspective projection (vtkCamera::ViewAngle), in
   * (0, 180). Default 30.
   */
  vtkSetMacro(ViewAngle, double);
  vtkGetMacro(ViewAngle, double);
  ///@}

  ///@{
  /**
   * Parallel (orthographic) instead of perspective projection. Default false.
   */
  vtkSetMacro(ParallelProjection, bool);
  vtkGetMacro(ParallelProjection, bool);
  vtkBooleanMacro(ParallelProjection, bool);
  ///@}

  ///@{
  /**
   * Half the view height in world units for parallel projection (vtkCamera::ParallelScale),
   * > 0; the half width is ParallelScale * W / H. Default 1.
   */
  vtkSetMacro(ParallelScale, double);
  vtkGetMacro(ParallelScale, double);
  ///@}

  ///@{
  /**
   * Distances of the near and far planes from the camera position along the direction of
   * projection (vtkCamera::ClippingRange), 0 < near < far. Default (0.1, 100).
   */
  vtkSetVector2Macro(ClippingRange, double);
  vtkGetVector2Macro(ClippingRange, double);
  ///@}

  ///@{
  /**
   * The transfer function, as a vtkVolumeProperty's first component: its color (the albedo),
   * scalar opacity and scalar opacity unit distance, from which the renderer builds the table the
   * GPU mapper builds (cloudvis::TransferTableOf: cloudvis::TransferTableSize entries over the
   * function's own points, opacity per unit distance turned into extinction). Densities are in
   * the input's scalar units. Default: none, which the filter refuses with an error.
   */
  virtual void SetVolumeProperty(vtkVolumeProperty* property);
  vtkGetObjectMacro(VolumeProperty, vtkVolumeProperty);
  ///@}

  ///@{
  /**
   * Multiplies every extinction of the transfer function, as vtkCloudVolumeMapper's
   * ExtinctionScale does. Default 1.
   */
  vtkSetClampMacro(ExtinctionScale, double, 0.0, 1e6);
  vtkGetMacro(ExtinctionScale, double);
  ///@}

  ///@{
  /**
   * The lighting model and its parameters (vtkCloudLightingProperty states each default; the
   * default model is none). Share one property with a vtkCloudVolumeMapper to light both alike.
   * Setting null restores a default property. Never null.
   */
  virtual void SetLightingProperty(vtkCloudLightingProperty* property);
  vtkGetObjectMacro(LightingProperty, vtkCloudLightingProperty);
  ///@}

  ///@{
  /**
   * The lights, as vtkLights (the mapper reads its renderer's): the switched-on ones light the
   * cloud, at most cloudvis::LightingLimits::MaxLights (8, the GPU's MAX_LIGHTS; more are
   * refused); their contributions add up. Ignored by the none model. Pass a renderer's
   * GetLights() to light both alike. Setting null restores an empty collection. Default: empty.
   */
  virtual void SetLights(vtkLightCollection* lights);
  vtkGetObjectMacro(Lights, vtkLightCollection);
  ///@}

#ifndef __VTK_WRAP__
  ///@{
  /**
   * The lights as cloudvis::Lights, as a scene holds them (C++): they light the cloud in place of
   * the collection above (Modified when they differ from the last ones set), until
   * SetLights(vtkLightCollection*) gives it vtkLights again. GetCloudLights() is null while the
   * vtkLights are used. GetLightList() is what the renderer lights with: these, else
   * cloudvis::LightsOf(GetLights()).
   */
  void SetLights(const std::vector<cloudvis::Light>& lights);
  const std::vector<cloudvis::Light>* GetCloudLights() const;
  std::vector<cloudvis::Light> GetLightList() const;
  ///@}

  /**
   * Optical depths toward the lights from outside the input (CloudOpticalDepthGrid.h: other
   * pieces of a distributed field), which the march adds wherever it uses an optical depth
   * toward a light, as vtkCloudVolumeMapper::SetExternalOpticalDepths; an empty grid clears them.
   * The grid is copied; it must hold the lights the renderer lights with (else RequestData
   * fails in words). Default none. Not for the path tracer (vtkCloudPathTracer ignores them).
   */
  void SetExternalOpticalDepths(const cloudvis::OpticalDepthGrid& grid);

  /**
   * A multiple-scattering volume solved over the whole distributed field the input is a piece of
   * (CloudScatteringVolume.h), read instead of a volume of the input's own, as
   * vtkCloudVolumeMapper::SetExternalScatteringVolume; an empty one clears it. Copied. Default
   * none.
   */
  void SetExternalScatteringVolume(const cloudvis::WholeFieldScattering& volume);
#endif

  ///@{
  /**
   * The volume's model-to-world matrix, as vtkProp3D::GetMatrix() gives it for a vtkVolume (its
   * position, orientation, scale, origin and user matrix): the field is drawn where a vtkVolume
   * with this matrix would draw it. The matrix is copied; null means identity. Default identity.
   */
  void SetVolumeMatrix(vtkMatrix4x4* matrix);
  vtkMatrix4x4* GetVolumeMatrix() { return this->VolumeMatrix; }
  ///@}

  ///@{
  /**
   * World distance between samples along a view ray, >= 0; 0 means the smallest voxel edge in
   * the world (the mapper's default). A step needing more than cloudvis::MaxSamplesPerRay
   * samples along the volume's longest ray is refused. Default 0.
   */
  vtkSetMacro(SampleDistance, double);
  vtkGetMacro(SampleDistance, double);
  ///@}

  ///@{
  /**
   * A ray stops once its transmittance falls below this, in [0, 1]. Default 1/255.
   */
  vtkSetMacro(TerminationTransmittance, double);
  vtkGetMacro(TerminationTransmittance, double);
  ///@}

  /**
   * The normalized-device-to-world matrix of the current camera parameters and ImageSize
   * (aspect W / H): the inverse of vtkCamera::GetCompositeProjectionTransformMatrix(W / H, -1,
   * 1) for a vtkCamera given the same parameters. Rays start at depth -1 and end at depth 1.
   * Returns false (and leaves the matrix alone) when the camera parameters are unusable.
   */
  bool GetDeviceToWorldMatrix(vtkMatrix4x4* deviceToWorld) const;

#ifndef __VTK_WRAP__
  /**
   * The current camera parameters as cloudvis::DeviceToLocal takes them (CloudMarchUniforms.h):
   * the projection (view to normalized device coordinates), the rotation from world to view axes
   * and the eye's world position. DeviceToLocal of these and the input's LocalFrame is the matrix
   * RequestData gives PixelRay. Returns false when the camera parameters are unusable.
   */
  bool GetCamera(glm::dmat4& viewToDevice, glm::dmat3& worldToView, glm::dvec3& eye) const;

  /**
   * The view ray of pixel (i, j) of an image of width x height pixels: its points on the near
   * and far planes in the march's local frame, for the normalized-device-to-local matrix
   * deviceToLocal (cloudvis::DeviceToLocal, CloudMarchUniforms.h: camera-relative, so no world
   * coordinate enters it). The GLSL's LocalPoint with DCLocalMatrix, in double.
   */
  static void PixelRay(const glm::dmat4& deviceToLocal,
    int i,
    int j,
    int width,
    int height,
    glm::dvec3& nearPoint,
    glm::dvec3& farPoint);
#endif

protected:
  vtkCloudReferenceRenderer();
  ~vtkCloudReferenceRenderer() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * Renders the image once RequestData has checked the parameters and the input (SetUpMarch
   * accepted them) and set the output's extent: `uniforms` describe the field, the table, the
   * lighting and the lights in the march's local frame, `deviceToLocal` the camera (PixelRay).
   * This class marches each pixel's ray (cloudvis::MarchRay); vtkCloudPathTracer path-traces
   * it. Returns false (after an error message) when it cannot.
   */
#ifndef __VTK_WRAP__
  virtual bool RenderImage(const cloudvis::MarchUniforms& uniforms,
    const glm::dmat4& deviceToLocal,
    vtkImageData* input,
    vtkImageData* output);
#endif

  /**
   * Calls renderRows(firstRow, endRow) over the image's rows under vtkSMPTools, in blocks of
   * rows so that progress is reported and AbortExecute honoured between blocks.
   */
  void RenderRowBlocks(int height, const std::function<void(vtkIdType, vtkIdType)>& renderRows);

  int ImageSize[2] = { 128, 128 };
  double CameraPosition[3] = { 0.0, 0.0, 1.0 };
  double CameraFocalPoint[3] = { 0.0, 0.0, 0.0 };
  double CameraViewUp[3] = { 0.0, 1.0, 0.0 };
  double ViewAngle = 30.0;
  bool ParallelProjection = false;
  double ParallelScale = 1.0;
  double ClippingRange[2] = { 0.1, 100.0 };
  vtkVolumeProperty* VolumeProperty = nullptr;
  double ExtinctionScale = 1.0;
  vtkSmartPointer<vtkCloudLightingProperty> LightingProperty;
  vtkSmartPointer<vtkLightCollection> Lights;
#ifndef __VTK_WRAP__
  std::optional<std::vector<cloudvis::Light>> CloudLights; // in place of Lights when set
  std::shared_ptr<const cloudvis::OpticalDepthGrid> ExternalDepths; // null: none
  std::shared_ptr<const cloudvis::WholeFieldScattering> ExternalScattering; // null: none
#endif
  vtkNew<vtkMatrix4x4> VolumeMatrix;
  double SampleDistance = 0.0;
  double TerminationTransmittance = 1.0 / 255.0;

private:
  vtkCloudReferenceRenderer(const vtkCloudReferenceRenderer&) = delete;
  void operator=(const vtkCloudReferenceRenderer&) = delete;
};

#endif
