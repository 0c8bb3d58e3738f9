/**
 * @class   vtkCloudDensitySource
 * @brief   procedural cloud density on a regular lattice
 *
 * vtkCloudDensitySource samples a procedural cloud (shapes given by signed distance functions,
 * white / value / Perlin noise summed in fBm octaves, a wind and a morph over time) on the
 * lattice spanned by Bounds and Dimensions, like vtkSampleFunction. The output is vtkImageData
 * with one float point-data array named "density", >= 0 everywhere and exactly 0 where there is
 * no cloud. The density models and their equations are documented in CloudDensityEvaluator.h
 * and docs/scene-format.md.
 *
 * Pipeline manners: the source produces any requested sub-extent (a field assembled from
 * pieces is bit-identical to the whole; only the requested extent must fit in memory), publishes
 * TIME_STEPS and TIME_RANGE and answers UPDATE_TIME_STEP, reports progress and honours
 * AbortExecute. The voxel loop runs under vtkSMPTools; a voxel's value depends only on its index
 * and the parameters, never on the number of threads or the SMP backend.
 */
#ifndef vtkCloudDensitySource_h
#define vtkCloudDensitySource_h

#include "CloudDensityEvaluator.h"
#include "cloudvisFiltersModule.h"

#include <vtkImageAlgorithm.h>

class CLOUDVISFILTERS_EXPORT vtkCloudDensitySource : public vtkImageAlgorithm
{
public:
  static vtkCloudDensitySource* New();
  vtkTypeMacro(vtkCloudDensitySource, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of voxels along x, y and z. Default 128 x 128 x 128.
   */
  vtkSetVector3Macro(Dimensions, int);
  vtkGetVector3Macro(Dimensions, int);
  ///@}

  ///@{
  /**
   * World box sampled: xmin, xmax, ymin, ymax, zmin, zmax. The first and last voxels lie on
   * the bounds; origin and spacing follow from them. Default [-2, 2] on each axis.
   */
  vtkSetVector6Macro(Bounds, double);
  vtkGetVector6Macro(Bounds, double);
  ///@}

  ///@{
  /**
   * Everything that defines the cloud: density model and scale, shapes and how they combine,
   * the morph, the fBm noise and the wind. Default: the article's cloud, a unit sphere plus
   * 6 octaves of value noise.
   */
  void SetField(const cloudvis::FieldDescription& field);
  const cloudvis::FieldDescription& GetField() const { return this->Field; }
  ///@}

  ///@{
  /**
   * Time at which the field is sampled when the pipeline does not request one (seconds).
   * Default 0.
   */
  vtkSetMacro(Time, double);
  vtkGetMacro(Time, double);
  ///@}

  ///@{
  /**
   * Time steps the source publishes as TIME_STEPS, evenly spaced over TimeRange, both ends
   * included. Any time inside or outside the range can still be requested. Defaults: range
   * [0, 12] (one cycle of the morph) in 49 steps (every 0.25 s).
   */
  vtkSetVector2Macro(TimeRange, double);
  vtkGetVector2Macro(TimeRange, double);
  vtkSetMacro(NumberOfTimeSteps, int);
  vtkGetMacro(NumberOfTimeSteps, int);
  ///@}

  /**
   * Empty when the current parameters describe a field that can be generated (its geometry,
   * shapes, noise range and time steps), else the problem, in words. The memory the field needs
   * is not checked here: it depends on the extent requested (ValidateExtent).
   */
  std::string Validate() const;

  /**
   * Empty when the voxels of `extent` (a sub-extent of the whole, as UPDATE_EXTENT requests it)
   * fit in the memory available, else the problem, stating how much they need. RequestData checks
   * the update extent with it before allocating, so a process that generates one piece of a
   * field larger than its memory (cloudvis generate under mpirun) needs only the piece's memory.
   */
  std::string ValidateExtent(const int extent[6]) const;

protected:
  vtkCloudDensitySource();
  ~vtkCloudDensitySource() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Dimensions[3] = { 128, 128, 128 };
  double Bounds[6] = { -2.0, 2.0, -2.0, 2.0, -2.0, 2.0 };
  cloudvis::FieldDescription Field;
  double Time = 0.0;
  double TimeRange[2] = { 0.0, 12.0 };
  int NumberOfTimeSteps = 49;

private:
  vtkCloudDensitySource(const vtkCloudDensitySource&) = delete;
  void operator=(const vtkCloudDensitySource&) = delete;
};

#endif
