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

#include "cloudvisFiltersModule.h"

#include <vtkImageAlgorithm.h>

class vtkImageData;

// VTK's wrappers do not see the C++ field description (its glm types are neither wrappable nor
// quick for their parser): wrapped languages use the Set/Get methods that expose its values.
#ifndef __VTK_WRAP__
#include "CloudDensityEvaluator.h"
#endif

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

#ifndef __VTK_WRAP__
  ///@{
  /**
   * Everything that defines the cloud: density model and scale, shapes and how they combine,
   * the morph, the fBm noise and the wind. Default: the article's cloud, a unit sphere plus
   * 6 octaves of value noise. The Set/Get methods below expose the same values one by one (for
   * Python and other wrapped languages); the equations are in CloudDensityEvaluator.h.
   */
  void SetField(const cloudvis::FieldDescription& field);
  const cloudvis::FieldDescription& GetField() const
  {
    return this->Field;
  }
  ///@}
#endif

  enum DensityModels
  {
    SdfPlusFbmModel = 0, // scale * max(0, -sdf + fbm): the article's cloud
    FbmFalloffModel = 1, // scale * max(0, fbm) * smooth falloff inside the shapes
    ConstantModel = 2,   // scale inside the shapes, 0 outside (analytic tests)
    CloudModel = 3,      // a cloud layer: coverage, cloud type, eroded noise (CloudLayer.h)
  };

  ///@{
  /**
   * The density model: SdfPlusFbmModel, FbmFalloffModel, ConstantModel or CloudModel. Default
   * SdfPlusFbmModel.
   */
  void SetDensityModel(int model);
  int GetDensityModel() const;
  void SetDensityModelToSdfPlusFbm()
  {
    this->SetDensityModel(SdfPlusFbmModel);
  }
  void SetDensityModelToFbmFalloff()
  {
    this->SetDensityModel(FbmFalloffModel);
  }
  void SetDensityModelToConstant()
  {
    this->SetDensityModel(ConstantModel);
  }
  void SetDensityModelToCloud()
  {
    this->SetDensityModel(CloudModel);
  }
  ///@}

  ///@{
  /**
   * Density multiplier (> 0) and the width of the FbmFalloff model's falloff inside the shapes
   * (world units, > 0). Defaults 1 and 0.25.
   */
  void SetDensityScale(double scale);
  double GetDensityScale() const
  {
    return this->Field.DensityScale;
  }
  void SetFalloffWidth(double width);
  double GetFalloffWidth() const
  {
    return this->Field.FalloffWidth;
  }
  ///@}

  ///@{
  /**
   * The shapes whose signed distance functions bound the cloud. Each Add method appends one
   * (centre and sizes in world units) and returns its index; SetShapeRotation (degrees about x,
   * then y, then z) and SetShapeScale (> 0) place shape i. Default: one unit sphere at the origin.
   * A field needs at least one shape unless Morph is on.
   */
  void RemoveAllShapes();
  int GetNumberOfShapes() const
  {
    return static_cast<int>(this->Field.Shapes.size());
  }
  int AddSphere(double cx, double cy, double cz, double radius);
  int AddBox(double cx, double cy, double cz, double halfX, double halfY, double halfZ);
  int AddTorus(double cx, double cy, double cz, double majorRadius, double minorRadius);
  int AddCross(double cx, double cy, double cz, double armWidth, double armLength);
  int AddCapsule(double ax, double ay, double az, double bx, double by, double bz, double radius);
  void SetShapeRotation(int shape, double rx, double ry, double rz);
  void SetShapeScale(int shape, double scale);
  ///@}

  enum ShapeBlends
  {
    UnionBlend = 0,       // the minimum of the distances
    SmoothUnionBlend = 1, // a smooth minimum over BlendRadius
  };

  ///@{
  /**
   * How the shapes combine: UnionBlend or SmoothUnionBlend, with the smooth union's radius
   * (world units, >= 0). Defaults UnionBlend and 0.25.
   */
  void SetShapeBlend(int blend);
  int GetShapeBlend() const;
  void SetBlendRadius(double radius);
  double GetBlendRadius() const
  {
    return this->Field.BlendRadius;
  }
  ///@}

  ///@{
  /**
   * Use the built-in morph timeline (sphere, box, torus, cross, capsule, one every few seconds)
   * instead of the shapes. Default off.
   */
  void SetMorph(bool morph);
  bool GetMorph() const
  {
    return this->Field.Morph;
  }
  vtkBooleanMacro(Morph, bool);
  ///@}

  enum NoiseTypes
  {
    NoNoise = 0,             // fBm is 0
    WhiteNoise = 1,          // an independent random value per lattice cell
    ValueNoise = 2,          // random lattice values, cubic interpolation
    PerlinNoise = 3,         // random lattice gradients, quintic interpolation
    WorleyNoise = 4,         // F1 cellular noise, 2 F1 - 1
    InvertedWorleyNoise = 5, // 1 - 2 F1: puffs around the feature points
    PerlinWorleyNoise = 6,   // Perlin remapped by an inverted Worley fBm
  };

  ///@{
  /**
   * The fBm noise: its type (one of NoiseTypes), number of octaves (1 to 12), base frequency
   * (cycles per world unit, > 0), lacunarity (the frequency factor between octaves) and its growth
   * per octave, gain (the amplitude factor between octaves), first amplitude and seed. Octave o
   * samples frequency f_o, f_0 = frequency, f_{o+1} = f_o * (lacunarity + o * increment), with
   * amplitude amplitude * gain^o. Defaults: ValueNoise, 6 octaves, 1, 2.02, 0.21, 0.5, 0.5 and seed
   * 0.
   */
  void SetNoiseType(int type);
  int GetNoiseType() const;
  void SetNoiseOctaves(int octaves);
  int GetNoiseOctaves() const
  {
    return this->Field.Noise.Octaves;
  }
  void SetNoiseFrequency(double frequency);
  double GetNoiseFrequency() const
  {
    return this->Field.Noise.Frequency;
  }
  void SetNoiseLacunarity(double lacunarity);
  double GetNoiseLacunarity() const
  {
    return this->Field.Noise.Lacunarity;
  }
  void SetNoiseLacunarityIncrement(double increment);
  double GetNoiseLacunarityIncrement() const
  {
    return this->Field.Noise.LacunarityIncrement;
  }
  void SetNoiseGain(double gain);
  double GetNoiseGain() const
  {
    return this->Field.Noise.Gain;
  }
  void SetNoiseAmplitude(double amplitude);
  double GetNoiseAmplitude() const
  {
    return this->Field.Noise.Amplitude;
  }
  void SetNoiseSeed(unsigned int seed);
  unsigned int GetNoiseSeed() const
  {
    return this->Field.Noise.Seed;
  }
  ///@}

  ///@{
  /**
   * The noise's period in lattice cells of the first octave (0: it never repeats). With a period
   * P > 0 the fBm repeats every P / frequency world units along each axis; it then needs a
   * whole-number lacunarity and no lacunarity increment. Default 0.
   */
  void SetNoisePeriod(int period);
  int GetNoisePeriod() const
  {
    return this->Field.Noise.Period;
  }
  ///@}

  enum CloudTypes
  {
    Stratus = 0,
    Stratocumulus = 1,
    Cumulus = 2,
    Cumulonimbus = 3,
    Altocumulus = 4,
    Congestus = 5,
  };
  enum CoverageSources
  {
    ShapesCoverage = 0, // the shapes, softened over FalloffWidth: one cloud
    NoiseCoverage = 1,  // a procedural weather map: many clouds
    MapCoverage = 2,    // a 2-D map given with SetCoverageMap
  };

  ///@{
  /**
   * The CloudModel's layer (CloudLayer.h has its equations): the cloud type (one of CloudTypes,
   * default Cumulus), the base and top altitudes along y (world units, default -1 and 1), the
   * coverage in [0, 1] (default 0.6) and where it comes from (one of CoverageSources, default
   * ShapesCoverage).
   */
  void SetCloudType(int type);
  int GetCloudType() const;
  void SetCloudAltitudes(double base, double top);
  double GetCloudBase() const
  {
    return this->Field.Layer.Base;
  }
  double GetCloudTop() const
  {
    return this->Field.Layer.Top;
  }
  void SetCloudCoverage(double coverage);
  double GetCloudCoverage() const
  {
    return this->Field.Layer.Coverage;
  }
  void SetCoverageSource(int source);
  int GetCoverageSource() const;
  ///@}

  /**
   * The weather map of MapCoverage: a 2-D image (one axis of its dimensions 1) whose first
   * point-data component holds values in [0, 1]; its first index axis runs along x over the
   * field's x bounds, its second along z over the z bounds. The values are copied. Setting a map
   * also selects MapCoverage; null clears it.
   */
  void SetCoverageMap(vtkImageData* map);

  ///@{
  /**
   * The procedural weather map (NoiseCoverage): the world size of its largest features (default
   * 4), its octaves (default 6) and the gain between them (default 0.6; the rougher the cloud
   * edges seen from above, the higher).
   */
  void SetWeatherMap(double scale, int octaves, double gain);
  ///@}

  ///@{
  /**
   * The CloudModel's noises: the world lengths over which the shape and the detail noise repeat
   * (defaults 2 and 0.5), the erosion of the edges by the detail, in [0, 1] (default 0.4), the
   * curl-noise turbulence under the cloud, in [0, 1] (default 0), the break-up of a weather
   * map's columns above the base, in [0, 1] (default 0), the cumulonimbus anvil's
   * strength, in [0, 1] (default 0), the direction [x, z] of the upper wind it streams along
   * (default [1, 0]), how far it reaches downwind in world units (default 0), the height of the
   * overshooting dome above the top in world units (default 0), the rain shaft's density under
   * the base as a fraction of the density scale, in [0, 1] (default 0; the last three need
   * CoverageSource ShapesCoverage), and the shear: x and z displacement per unit of height
   * (default 0).
   */
  void SetCloudNoiseScales(double shape, double detail);
  void SetCloudErosion(double erosion);
  void SetCloudCurl(double curl);
  void SetCloudBreakup(double breakup);
  void SetCloudAnvil(double anvil);
  void SetCloudAnvilDirection(double x, double z);
  void SetCloudAnvilReach(double reach);
  void SetCloudOvershoot(double overshoot);
  void SetCloudRain(double rain);
  void SetCloudShear(double x, double z);
  ///@}

  ///@{
  /**
   * The drift of the noise with time: the noise is sampled at p + Wind * t (world units per
   * second). Default (0.5, -0.1, -0.5).
   */
  void SetWind(double x, double y, double z);
  void GetWind(double wind[3]) const;
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
#ifndef __VTK_WRAP__
  cloudvis::FieldDescription Field;
#endif
  double Time = 0.0;
  double TimeRange[2] = { 0.0, 12.0 };
  int NumberOfTimeSteps = 49;

private:
#ifndef __VTK_WRAP__
  // Assigns one value of Field, Modified() only when it changes.
  template<typename T>
  void SetFieldValue(T& member, const T& value);
  // Field as it is generated: the coverage map placed over Bounds.
  cloudvis::FieldDescription FieldToGenerate() const;
  // Appends a shape to Field and returns its index.
  int AddShape(const cloudvis::Shape& shape);
  // Shape i of Field, or null (after an error naming the index) when there is none.
  cloudvis::Shape* ShapeAt(int shape);
#endif
  vtkCloudDensitySource(const vtkCloudDensitySource&) = delete;
  void operator=(const vtkCloudDensitySource&) = delete;
};

#endif
