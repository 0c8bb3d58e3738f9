/**
 * @class   vtkCloudPathTracer
 * @brief   Monte Carlo path-traced ground truth of a cloud density field, on the CPU
 *
 * vtkCloudPathTracer renders the medium the lighting models approximate, with every order of
 * scattering and no approximation beyond Monte Carlo noise: sigma_t and albedo from the transfer
 * table, the two-lobe Henyey-Greenstein phase of the lighting parameters (PhaseG1, PhaseG2,
 * PhaseLobeWeight), the lights, and the ambient as a uniform environment of radiance
 * AmbientColor x AmbientStrength around the volume. Delta tracking with a majorant per occupancy
 * brick, next-event estimation to every light with ratio-tracked transmittance, Russian roulette
 * and a bounce cap; the equations and the estimators are in docs/lighting.md ("The path
 * tracer"), the per-path code in CloudPathTrace.h.
 *
 * It is a vtkCloudReferenceRenderer: the same input with its whole geometry (extent, origin,
 * spacing, direction matrix, VolumeMatrix), camera, image size, transfer table, lighting
 * parameters and lights, checked the same way (cloudvis::SetUpMarch), and the same local frame
 * around the volume for its arithmetic. It ignores what only the march uses (Lighting.Model, the
 * light-march, octave, powder and derivative parameters, SampleDistance,
 * TerminationTransmittance), though SetUpMarch still refuses them where the march would. With
 * MaxBounces 1 and no ambient it computes what the march computes with MultipleScatteringOctaves 0
 * and enough uniform light steps.
 *
 * Output: the "rgba" point array (the active scalars) holds each pixel's mean over
 * SamplesPerPixel paths through the pixel centre: premultiplied radiance in r, g, b (the
 * background, ambient or not, is composited behind by the caller, as for the other renderers) and
 * the opacity 1 - T in a. "rgba_variance" (float, 4 components) holds the estimated variance of
 * each of those means (the sample variance over the pixel's paths divided by their number), so
 * its square root is the pixel's standard error.
 *
 * Deterministic: a path's random numbers are a hash of (pixel, sample, dimension, Seed), so the
 * image depends only on the parameters, never on the threads or the vtkSMPTools backend.
 */
#ifndef vtkCloudPathTracer_h
#define vtkCloudPathTracer_h

// CloudPathTrace.h (glm and the per-path code) is not included here: VTK's Python wrapper parses
// everything a wrapped header includes, and that header alone cost it minutes of CPU.
#include "vtkCloudReferenceRenderer.h"

class CLOUDVISFILTERS_EXPORT vtkCloudPathTracer : public vtkCloudReferenceRenderer
{
public:
  static vtkCloudPathTracer* New();
  vtkTypeMacro(vtkCloudPathTracer, vtkCloudReferenceRenderer);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Paths per pixel, at least 2 (the variance needs two). Default 64.
   */
  vtkSetMacro(SamplesPerPixel, int);
  vtkGetMacro(SamplesPerPixel, int);
  ///@}

  ///@{
  /**
   * The seed of the random numbers: another seed gives an independent image. Default 0.
   */
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

  ///@{
  /**
   * The most scattering events a path may have, at least 1; 1 is single scattering. The
   * default, 1024, loses less light than the noise can show in the shipped scenes
   * (docs/lighting.md).
   */
  vtkSetMacro(MaxBounces, int);
  vtkGetMacro(MaxBounces, int);
  ///@}

  ///@{
  /**
   * Cells per edge of the majorant bricks (vtkCloudOccupancyFilter's BrickSize), at least 1.
   * Smaller bricks give tighter majorants (fewer rejected tentative collisions) and more bricks
   * to cross; the image does not depend on it beyond the noise. Default 8 (the fastest on the
   * shipped scenes, docs/performance.md).
   */
  vtkSetMacro(BrickSize, int);
  vtkGetMacro(BrickSize, int);
  ///@}

  ///@{
  /**
   * The estimator of each scattering event's next event: Plain (next-event estimation along
   * the walk alone), LightGuided (also along a direction drawn toward the lights, weighed by
   * multiple importance sampling), or ByPhase (the default: light-guided for the droplets'
   * phase, plain for the two lobes). The image does not depend on it beyond the noise
   * (docs/lighting.md, "The estimators").
   */
  enum NextEventEstimators
  {
    ByPhase = 0,
    Plain = 1,
    LightGuided = 2,
  };
  vtkSetClampMacro(NextEventEstimator, int, ByPhase, LightGuided);
  vtkGetMacro(NextEventEstimator, int);
  ///@}

protected:
  vtkCloudPathTracer() = default;
  ~vtkCloudPathTracer() override = default;

#ifndef __VTK_WRAP__
  bool RenderImage(const cloudvis::MarchUniforms& uniforms,
    const glm::dmat4& deviceToLocal,
    vtkImageData* input,
    vtkImageData* output) override;
#endif

  int SamplesPerPixel = 64;
  unsigned int Seed = 0;
  int MaxBounces = 65536; // cloudvis::PathTraceBounceCap (the .cxx asserts that they agree)
  int BrickSize = 8; // cloudvis::PathTraceBrickSize (the .cxx asserts that they agree)
  int NextEventEstimator = ByPhase;

private:
  vtkCloudPathTracer(const vtkCloudPathTracer&) = delete;
  void operator=(const vtkCloudPathTracer&) = delete;
};

#endif
