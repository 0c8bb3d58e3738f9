/**
 * @class   vtkCloudVolumeMapper
 * @brief   GPU ray marcher for cloud density fields with empty-space skipping
 *
 * vtkCloudVolumeMapper renders vtkImageData with one scalar component (float, unsigned char or
 * unsigned short) like any VTK volume mapper: vtkVolume + vtkVolumeProperty + vtkRenderer. It
 * honours the image's whole geometry (extent, which need not start at 0, origin, spacing and
 * direction matrix) and the vtkVolume's matrix (position, orientation, scale, origin, user
 * matrix). The march computes in a local frame around the volume (CloudMarchUniforms.h), so
 * its precision does not depend on where the volume sits in the world or how large it is.
 * Each pixel's ray is clipped to the volume box and to the opaque geometry already in the depth
 * buffer, then samples the density at fixed steps t0 + k * dt. A brick occupancy structure
 * (vtkCloudOccupancyFilter) lets rays leap over bricks where the transfer function gives no
 * extinction; the leap lands on the same lattice of samples, so skipping never changes the
 * image, only the number of samples taken.
 *
 * The transfer functions of the vtkVolumeProperty are read as physical quantities: the scalar
 * opacity a is opacity per ScalarOpacityUnitDistance u, giving the extinction
 * sigma_t = -ln(1 - a) / u, and the color is the albedo. Per step a sample absorbs
 * 1 - exp(-sigma_t dt) of the light behind it, so the image does not depend on the step. The
 * functions are tabulated over their own points (not the data's range), and densities outside
 * them take the end values, as in VTK.
 *
 * Lighting (docs/lighting.md): the model and its parameters are a vtkCloudLightingProperty (none
 * = emission-absorption, derivative = the directional derivative toward each light, or march = a
 * nested march toward each light with Beer-Lambert transmittance, a two-lobe Henyey-Greenstein
 * phase and approximate multiple scattering), which the CPU renderers (vtkCloudReferenceRenderer,
 * vtkCloudPathTracer) take too. The lights are the renderer's switched-on vtkLights, or from C++
 * a list of cloudvis::Lights given to the mapper (SetLights: a scene's lights, which cloudvis
 * gives so, never as vtkLights): at most cloudvis::LightingLimits::MaxLights, 8 (more are
 * refused, not dropped), directional or positional, with their color, intensity and
 * attenuation.
 *
 * The field is uploaded in its native type (unsigned char as R8, unsigned short as R16, float as
 * R32F, or as R16F half floats with HalfFloatDensity), which the shader reads back in the data's
 * units through a scale and bias (CloudDensityTexels.h): 1, 2 or 4 bytes per voxel.
 * GetGPUMemoryBytes reports what the textures and targets take. A field the GPU cannot hold
 * (beyond what the driver reports free, beyond MaximumGPUMemory, or refused by the driver when
 * allocated) is refused with the size it needs.
 *
 * The march renders into a float target at ResolutionScale times the viewport, which a
 * composite pass upsamples (Catmull-Rom) and blends over the scene. While nothing changes,
 * successive frames with different blue-noise jitter are averaged (progressive accumulation).
 * While the user interacts (the render window's desired update rate is above 1), the scale is
 * lowered automatically to keep InteractiveFrameRate.
 *
 * The pathtrace lighting model runs vtkCloudPathTracer's path tracer on the GPU (the same code:
 * shaders/transport/PathTrace.glsl, docs/transport.md): each frame traces PathTraceSamplesPerFrame
 * paths through every pixel centre (no jitter, the CPU's random numbers for pixel, sample and
 * PathTraceSeed) and adds them to the accumulation, up to MaximumAccumulatedFrames frames; a second
 * float target accumulates the squares, so ReadVariance gives each pixel's standard error. Opaque
 * geometry ends the view ray; paths that scatter ignore it.
 *
 * Light crosses the pieces of a distributed field (a ParaView representation under MPI, each
 * rank's mapper drawing its piece) through a vtkCloudPieceExchange: the optical depths and the
 * multiple-scattering volume the other pieces add.
 *
 * The work is split as VTK's own volume mapper splits it, into helpers private to the module
 * (app/rendering/Cloud*.h): the density, transfer, occupancy and jitter textures, the per-view
 * targets, the march shader and its uniforms, and the GPU memory checks; Render() runs one
 * method per pass. Every GL state change goes through vtkOpenGLState.
 *
 * Errors (no usable scalars, NaN or infinite densities, an unusable geometry, a field beyond the
 * GPU's 3-D texture limit or its memory, an invalid transfer function, a step that needs more
 * than cloudvis::MaxSamplesPerRay samples per ray, more than 8 lights, lights or extinctions
 * beyond float range: everything cloudvis::SetUpMarch refuses, in the CPU reference's words; a
 * multisampled render window, whose depth the march cannot copy: call SetMultiSamples(0); a
 * shader or framebuffer failure) are reported with vtkErrorMacro and kept in GetLastError(); the
 * volume is then not drawn.
 */
#ifndef vtkCloudVolumeMapper_h
#define vtkCloudVolumeMapper_h

#include "cloudvisRenderingModule.h"
#include "vtkCloudLightingProperty.h"

#include <vtkSmartPointer.h>
#include <vtkVolumeMapper.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkRenderWindow;
namespace cloudvis
{
struct MarchProblem;
struct MarchSetup;
}

class CLOUDVISRENDERING_EXPORT vtkCloudVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkCloudVolumeMapper* New();
  vtkTypeMacro(vtkCloudVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Distance between samples along a ray, in world units. 0 means one sample per voxel: the
   * smallest edge of a voxel in the world. A step that needs more than cloudvis::MaxSamplesPerRay
   * samples along the volume's longest ray is refused. Default 0.
   */
  vtkSetMacro(SampleDistance, double);
  vtkGetMacro(SampleDistance, double);
  ///@}

  ///@{
  /**
   * Leap over bricks of empty space. Turning it off changes the sample count, not the image.
   * Default on.
   */
  vtkSetMacro(EmptySpaceSkipping, bool);
  vtkGetMacro(EmptySpaceSkipping, bool);
  vtkBooleanMacro(EmptySpaceSkipping, bool);
  ///@}

  ///@{
  /**
   * Edge length of the occupancy bricks, in voxels. Smaller bricks fit the cloud more tightly
   * (fewer wasted samples) but cost more to recompute when the density or the transfer function
   * changes; frame time hardly depends on it (docs/performance.md). Default 3.
   */
  vtkSetClampMacro(BrickSize, int, 2, 64);
  vtkGetMacro(BrickSize, int);
  ///@}

  ///@{
  /**
   * Samples the march takes per reading of the occupancy map, 1 to 4, or 0 (the default) to
   * choose by the field's occupied-brick fraction (4 for dense fields, where leaps are rare, 1
   * otherwise; cloudvis::SamplesPerMapRead). The image is the same either way; only the speed
   * differs (docs/performance.md).
   */
  vtkSetClampMacro(SamplesPerMapRead, int, 0, 4);
  vtkGetMacro(SamplesPerMapRead, int);
  ///@}

  ///@{
  /**
   * Offset each ray's first sample by a fraction of a step read from a blue-noise mask, turning
   * banding into fine noise. Default on.
   */
  vtkSetMacro(Jitter, bool);
  vtkGetMacro(Jitter, bool);
  vtkBooleanMacro(Jitter, bool);
  ///@}

  ///@{
  /**
   * A ray stops once the light reaching the eye through it falls below this transmittance.
   * Default 1/255.
   */
  vtkSetClampMacro(TerminationTransmittance, double, 0.0, 1.0);
  vtkGetMacro(TerminationTransmittance, double);
  ///@}

  ///@{
  /**
   * Multiplies every extinction of the transfer function. Default 1.
   */
  vtkSetClampMacro(ExtinctionScale, double, 0.0, 1e6);
  vtkGetMacro(ExtinctionScale, double);
  ///@}

  ///@{
  /**
   * Fraction of the viewport's width and height the march renders at; the composite pass
   * upsamples with a Catmull-Rom filter. Default 1.
   */
  vtkSetClampMacro(ResolutionScale, double, 0.25, 1.0);
  vtkGetMacro(ResolutionScale, double);
  ///@}

  ///@{
  /**
   * While the render window's desired update rate is above 1 (the interactor sets it during
   * interaction), lower the resolution scale, down to 0.25, to render at this many frames per
   * second. 0 disables the adjustment. Default 20.
   */
  vtkSetClampMacro(InteractiveFrameRate, double, 0.0, 1000.0);
  vtkGetMacro(InteractiveFrameRate, double);
  ///@}

  ///@{
  /**
   * Temporal reprojection of interactive frames: keep the image last shown at the viewport's
   * full resolution, with the cloud's depth per pixel and the camera it was seen with, and blend
   * it into each interactive frame (marched at the lowered scale) where it still holds: each
   * pixel's point on the cloud (the closest cloud depth around it in the new frame) is projected
   * into the last camera, and the last image's value there is kept when it was on the screen and
   * its depth agrees, clamped to the colour range of the new frame's neighbourhood, with 90% of
   * the weight, less as the views the history holds turn away from the new one (none at 12
   * degrees). Disocclusions, what was off screen and moved cloud edges show the new frame
   * alone. Anything but the camera and the scale changing (field, transfer function, lights,
   * lighting, volume, other props, viewport size) starts the history afresh. Still frames and
   * their progressive accumulation are unchanged. Costs two full-viewport RGBA16F + RG32F targets
   * (32 bytes a pixel, in GetGPUMemoryBytes). Not for the path tracer or the sample-count view.
   * Default off (the viewer's render.reprojection; docs/viewer.md gives what it gains).
   */
  vtkSetMacro(TemporalReprojection, bool);
  vtkGetMacro(TemporalReprojection, bool);
  vtkBooleanMacro(TemporalReprojection, bool);
  ///@}

  ///@{
  /**
   * Most frames averaged while the view does not change, 1 to 65536. 1 disables accumulation.
   * Default 1. Like the exposure, it does not change what a frame marches, so it does not modify
   * the mapper and a change never restarts the accumulation: a larger limit goes on from the
   * frames already averaged, and a limit at or below them keeps the image as it is (what a noise
   * target does once it is reached: the next renders composite that image again).
   */
  void SetMaximumAccumulatedFrames(int frames)
  {
    this->MaximumAccumulatedFrames = frames < 1 ? 1 : (frames > 65536 ? 65536 : frames);
  }
  vtkGetMacro(MaximumAccumulatedFrames, int);
  ///@}

  /**
   * Frames averaged in the image last drawn in this renderer.
   */
  int GetNumberOfAccumulatedFrames(vtkRenderer* renderer) const;

  /**
   * Samples per pixel averaged in that image: the frames, times PathTraceSamplesPerFrame when it
   * was path traced.
   */
  int GetNumberOfAccumulatedSamples(vtkRenderer* renderer) const;

  ///@{
  /**
   * Path-trace model: paths per pixel each frame adds, 1 to 4096. More per frame means fewer
   * frames (less overhead) but longer ones. Default 1.
   */
  vtkSetClampMacro(PathTraceSamplesPerFrame, int, 1, 4096);
  vtkGetMacro(PathTraceSamplesPerFrame, int);
  ///@}

  ///@{
  /**
   * Path-trace model: the seed of the random numbers (vtkCloudPathTracer's Seed), 0 to 2^31 - 1:
   * another seed gives an independent image. Default 0.
   */
  vtkSetClampMacro(PathTraceSeed, int, 0, VTK_INT_MAX);
  vtkGetMacro(PathTraceSeed, int);
  ///@}

  ///@{
  /**
   * Path-trace model: the most scattering events a path may have (vtkCloudPathTracer's
   * MaxBounces), 1 to 2^24; 1 is single scattering. Default 65536 (cloudvis::PathTraceBounceCap).
   */
  vtkSetClampMacro(PathTraceMaxBounces, int, 1, 1 << 24);
  vtkGetMacro(PathTraceMaxBounces, int);
  ///@}

  ///@{
  /**
   * The lighting model and its parameters (vtkCloudLightingProperty states each default; the
   * default model is none). Share one property with the CPU renderers to light them alike.
   * Setting null restores a default property. Never null.
   */
  virtual void SetLightingProperty(vtkCloudLightingProperty* property);
  vtkGetObjectMacro(LightingProperty, vtkCloudLightingProperty);
  ///@}

#ifndef __VTK_WRAP__
  ///@{
  /**
   * The mapper's own lights, as cloudvis::Lights (a scene's): they light the cloud in place of
   * the renderer's vtkLights (Modified when they differ from the last ones set) until
   * UseRendererLights(). GetCloudLights() is null while the renderer's lights are used (the
   * default).
   */
  void SetLights(const std::vector<cloudvis::Light>& lights);
  void UseRendererLights();
  const std::vector<cloudvis::Light>* GetCloudLights() const;
  ///@}

#endif

  ///@{
  /**
   * Store a float field's density as 16-bit half floats (R16F) instead of 32-bit floats: half
   * the GPU memory, at the cost of precision. A half float holds 11 significant bits, so each
   * voxel's density is rounded to a relative error of at most 2^-11 (4.9e-4) of itself, or for
   * values below 2^-14 of the field's largest magnitude to an absolute error of at most 2^-25 of
   * that magnitude (docs/performance.md gives the image error this makes). Unsigned char and
   * unsigned short fields keep their own R8 and R16 texels. Default off.
   */
  vtkSetMacro(HalfFloatDensity, bool);
  vtkGetMacro(HalfFloatDensity, bool);
  vtkBooleanMacro(HalfFloatDensity, bool);
  ///@}

  ///@{
  /**
   * The most GPU memory, in bytes, the mapper may hold in textures and targets for all its
   * renderers together; a field (or a viewport) that would need more is refused with the size it
   * needs. 0 means no limit of its own (what the GPU reports free still applies). Default 0.
   */
  vtkSetClampMacro(MaximumGPUMemory, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(MaximumGPUMemory, vtkTypeInt64);
  ///@}

  /**
   * Bytes of GPU memory the mapper's textures and targets take now, as the driver allocated them
   * (from the sizes it reports for their formats): the density, transfer, occupancy and jitter
   * textures, the light volumes, the multiple-scattering volume and the optical depths from
   * outside the field, and every renderer's depth
   * and march targets.
   */
  vtkTypeInt64 GetGPUMemoryBytes() const;

  /**
   * Bytes of video memory the driver of `window`'s context reports free (GL_NVX_gpu_memory_info
   * on NVIDIA, GL_ATI_meminfo on AMD), or -1 when it reports nothing (Mesa's drivers, among
   * others). The mapper checks its allocations against it; benchmarks measure other mappers'
   * memory with it.
   */
  static vtkTypeInt64 GetFreeGPUMemoryBytes(vtkRenderWindow* window);

  /**
   * Bytes of GPU memory the density texture alone takes: voxels times 1 (unsigned char), 2
   * (unsigned short, or half floats) or 4 (float).
   */
  vtkTypeInt64 GetDensityTextureBytes() const;

  /**
   * The march with render.march.transmittance "volumes" (the default) reads the optical depth
   * toward each light from per-light volumes (docs/lighting.md) that the mapper computes on the
   * GPU when the field, the transfer function, the extinction scale, the step, the volume's
   * placement or the lights change. While the window is interacting (its desired update rate
   * above 1), volumes made stale by the lights alone (a headlight following the camera) are not
   * recomputed: those frames take the nested march, and the still render after the interaction
   * recomputes the volumes once. How many times it has computed them (a frame that changes none
   * of these does not), and the bytes they take (part of GetGPUMemoryBytes).
   */
  int GetLightVolumeComputeCount() const;
  vtkTypeInt64 GetLightVolumeBytes() const;

  /**
   * The march whose multiple scattering comes from a volume (docs/lighting.md, "The
   * multiple-scattering volume") reads it from a grid the mapper computes on the GPU, after the
   * light volumes, when the field, the transfer function, the extinction scale, the volume's
   * placement, the phase or the lights change (or the light volumes it reads were recomputed).
   * How many times it has finished computing it, the bytes its grids take (part of
   * GetGPUMemoryBytes), and the wall time of its last computation in seconds.
   */
  int GetScatteringVolumeComputeCount() const;
  vtkTypeInt64 GetScatteringVolumeBytes() const;
  double GetScatteringVolumeSeconds() const;

  ///@{
  /**
   * Progressive recompute of the multiple-scattering volume: when it has to be computed again and
   * a finished volume of the same size exists, each render runs its passes for about this many
   * seconds and the march reads the finished volume until the new one is done (the renders in
   * between are not converged: keep rendering while GetScatteringVolumeConverging()). 0 computes
   * it whole in the render that needs it. Default 0.
   */
  vtkSetClampMacro(ScatteringVolumeSecondsPerFrame, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ScatteringVolumeSecondsPerFrame, double);
  ///@}

  /**
   * Whether a progressive recompute of the multiple-scattering volume is under way, and how far:
   * its steps (a pass over some of a grid's cells) run so far and in all (0 and 0 when none is).
   */
  bool GetScatteringVolumeConverging() const;
  int GetScatteringVolumeStepsDone() const;
  int GetScatteringVolumeStepCount() const;

  /**
   * Also the latest change of the lighting property.
   */
  vtkMTimeType GetMTime() override;

  enum DisplayModes
  {
    Radiance = 0,   // the cloud
    SampleCount = 1 // samples taken per pixel, false colored: the cost of each ray
  };
  ///@{
  /**
   * What the composite pass shows. Default Radiance.
   */
  vtkSetClampMacro(DisplayMode, int, Radiance, SampleCount);
  vtkGetMacro(DisplayMode, int);
  ///@}

  ///@{
  /**
   * The display transform the composite pass applies to the cloud's radiance
   * (filters/CloudDisplayTransform.h): the exposure in EV (a factor of 2^EV, default 0) and the
   * curve, cloudvis::DisplayCurve's value (default 0, linear). Neither changes what is marched:
   * they do not modify the mapper, so a converged still is composited again, not re-marched,
   * when the window renders after a change.
   */
  void SetExposureEV(double ev) { this->ExposureEV = ev; }
  double GetExposureEV() const { return this->ExposureEV; }
  void SetDisplayCurve(int curve) { this->DisplayCurve = curve; }
  int GetDisplayCurve() const { return this->DisplayCurve; }
  ///@}

  ///@{
  /**
   * Clamp each channel of the display colour the composite pass writes to its alpha (default
   * off), so the window holds a valid premultiplied colour: the cloud's own colour clipped to
   * white before the "over" blend. For a window whose image a compositor blends again in 8 bits
   * without saturating, as ParaView's IceT blends the ranks' images (a colour above its alpha,
   * radiance above 1 at partial opacity, wrapped around there into a cyan scar: issue 36). Off,
   * as in cloudvis's own windows, the blend adds the background to the clamped radiance itself,
   * as a camera's sensor would.
   */
  void SetColorWithinAlpha(bool within) { this->ColorWithinAlpha = within; }
  bool GetColorWithinAlpha() const { return this->ColorWithinAlpha; }
  ///@}

  ///@{
  /**
   * Read back the per-pixel sample counts after each frame to fill the statistics below. Costs
   * a read-back per frame. Default off.
   */
  vtkSetMacro(CollectStatistics, bool);
  vtkGetMacro(CollectStatistics, bool);
  vtkBooleanMacro(CollectStatistics, bool);
  ///@}

#ifndef __VTK_WRAP__
  struct FrameStatistics
  {
    double SamplesTaken = 0;  // density samples over all pixels
    double UsefulSamples = 0; // of which the transfer function gave a non-zero extinction
    int Width = 0;            // size of the march target
    int Height = 0;
    double OccupiedBrickFraction = 0;
    int SamplesPerMapRead = 1; // the march loop's variant (SetSamplesPerMapRead)
    // The last finished computation of the multiple-scattering volume, in milliseconds (0 when
    // the march reads none).
    double ScatteringVolumeMilliseconds = 0;
  };
  /**
   * Statistics of the last frame (with CollectStatistics on).
   */
  const FrameStatistics& GetLastFrameStatistics() const { return this->LastStatistics; }
#endif

  /**
   * The image the composite pass last showed in this renderer, before upsampling: premultiplied
   * linear RGBA floats (alpha = 1 - transmittance), rows bottom to top, width x height of the
   * march target. Needs the renderer's window to be current. Returns false when the renderer
   * has drawn no cloud yet.
   */
#ifndef __VTK_WRAP__
  bool ReadImage(vtkRenderer* renderer, std::vector<float>& rgba, int& width, int& height);
#endif

  /**
   * Per pixel of the same target, four floats: samples taken, useful samples (non-zero
   * extinction), the cloud's depth (world distance from the near clipping plane along the ray to
   * where its opacity first exceeds 2%; +infinity where it never does in some accumulated frame)
   * and 1. Averaged over the accumulated frames like the image.
   */
#ifndef __VTK_WRAP__
  bool ReadAuxiliary(vtkRenderer* renderer, std::vector<float>& channels, int& width, int& height);
#endif

  ///@{
  /**
   * ReadImage and ReadAuxiliary into a vtkImageData (for Python and other wrapped languages):
   * width x height x 1 points with one 4-component float point array, "rgba" or "auxiliary",
   * laid out as the reference renderer's output (row 0 at the bottom). The image is left alone
   * when the method returns false.
   */
  bool ReadImage(vtkRenderer* renderer, vtkImageData* image);
  bool ReadAuxiliary(vtkRenderer* renderer, vtkImageData* image);
  ///@}

  /**
   * For a path-traced image: per pixel of the same target, the estimated variance of each of
   * the four channels' mean (the sample variance over the accumulated paths divided by their
   * number; its square root is the pixel's standard error), as vtkCloudPathTracer's
   * "rgba_variance". False when the image was not path traced or at least two samples are not
   * accumulated yet.
   */
#ifndef __VTK_WRAP__
  bool ReadVariance(vtkRenderer* renderer, std::vector<float>& variance, int& width, int& height);
#endif

  /**
   * For a path-traced image: how many of its pixels lack light because the GPU ended a frame's
   * paths early (a software rasterizer's loop budget: llvmpipe stops every loop of a fragment
   * after 65535 turns in all, which the deep walks of an optically thick cloud exceed; the shader
   * detects it, shaders/CloudLightingPathTraceFS.glsl). Such an image is too dark and must not be
   * shown as the truth. 0 when the image was not path traced or every path was whole; -1 when
   * the renderer has no image.
   */
  vtkIdType CountCutPathTracePixels(vtkRenderer* renderer);

  /**
   * The last error, or an empty string when the last render succeeded.
   */
  const std::string& GetLastError() const { return this->LastError; }
  /**
   * The last error is an allocation the GPU's memory refused (beyond MaximumGPUMemory, beyond
   * what the driver reports free, or GL_OUT_OF_MEMORY): a coarser field may fit where this one
   * did not (cloudvis's renders then coarsen it, docs/performance.md).
   */
  bool GetLastErrorIsGpuMemory() const
  {
    return this->LastErrorIsGpuMemory;
  }

  void Render(vtkRenderer* renderer, vtkVolume* volume) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkCloudVolumeMapper();
  ~vtkCloudVolumeMapper() override;

  /**
   * The textures the march reads, each brought up to date with its input: the density (native
   * type), the transfer table, the occupancy map and the jitter mask. False on a problem (then
   * reported by Fail).
   */
  bool UpdateTextures(vtkRenderer* renderer, vtkVolume* volume, vtkImageData* input);

  /**
   * The march pass: the view's targets sized to the viewport and the resolution scale, the
   * opaque depth copied, the uniforms SetUpMarch computes, then one more frame marched into the
   * targets (added to those accumulated while the view holds). False on a problem.
   */
  bool MarchPass(vtkRenderer* renderer, vtkVolume* volume, vtkImageData* input);

  /**
   * The composite pass: the accumulated march target upsampled and blended over the viewport.
   */
  bool CompositePass(vtkRenderer* renderer);

  double SampleDistance = 0.0;
  bool EmptySpaceSkipping = true;
  int BrickSize = 3;
  int SamplesPerMapRead = 0;
  bool Jitter = true;
  double TerminationTransmittance = 1.0 / 255.0;
  double ExtinctionScale = 1.0;
  double ResolutionScale = 1.0;
  double InteractiveFrameRate = 20.0;
  bool TemporalReprojection = false;
  int MaximumAccumulatedFrames = 1;
  int DisplayMode = Radiance;
  double ExposureEV = 0.0;
  int DisplayCurve = 0;
  bool ColorWithinAlpha = false;
  bool CollectStatistics = false;
  bool HalfFloatDensity = false;
  vtkTypeInt64 MaximumGPUMemory = 0;
  int PathTraceSamplesPerFrame = 1;
  int PathTraceSeed = 0;
  int PathTraceMaxBounces = 65536; // cloudvis::PathTraceBounceCap (asserted in the .cxx)
  double ScatteringVolumeSecondsPerFrame = 0.0;
  vtkSmartPointer<vtkCloudLightingProperty> LightingProperty;
#ifndef __VTK_WRAP__
  std::optional<std::vector<cloudvis::Light>> CloudLights; // in place of the renderer's when set
#endif

private:
  // The exchange between the pieces of a distributed field sets up the march of this mapper's
  // piece (ComputeOnPiece) and gives it what the other pieces add (Internals' external textures).
  friend class vtkCloudPieceExchange;

  vtkCloudVolumeMapper(const vtkCloudVolumeMapper&) = delete;
  void operator=(const vtkCloudVolumeMapper&) = delete;

  // Records `message` as the last error (outOfGpuMemory: GetLastErrorIsGpuMemory); returns false.
  bool Fail(const std::string& message, bool outOfGpuMemory = false);
#ifndef __VTK_WRAP__
  // Builds the MarchSetup of this mapper's input as `volume` draws it and runs `compute` on it,
  // `what` naming the caller in the refusal of a missing volume.
  bool ComputeOnPiece(vtkRenderer* renderer,
    vtkVolume* volume,
    const char* what,
    const std::function<cloudvis::MarchProblem(const cloudvis::MarchSetup&)>& compute);
#endif
  // The scalars the mapper draws of `input` (its scalar mode and array selection).
  vtkDataArray* InputScalars(vtkImageData* input, int& cellFlag);
  vtkImageData* ValidInput(vtkVolume* volume);
  void ReadStatistics(vtkRenderer* renderer);

  struct Internals;
  class MarchFrame; // one frame of MarchPass, phase by phase (vtkCloudVolumeMapperMarch.cxx)
  std::unique_ptr<Internals> Internal;
  std::string LastError;
  bool LastErrorIsGpuMemory = false;
#ifndef __VTK_WRAP__
  FrameStatistics LastStatistics;
#endif
};

#endif
