/**
 * @class   vtkCloudLightingProperty
 * @brief   the lighting model of a cloud and its parameters, shared by every cloudvis renderer
 *
 * vtkCloudLightingProperty is to cloudvis's renderers what vtkVolumeProperty is to VTK's volume
 * mappers: a vtkObject holding how a cloud is lit. vtkCloudVolumeMapper (GPU),
 * vtkCloudReferenceRenderer (its CPU twin) and vtkCloudPathTracer each hold one, and one property
 * may be shared by several renderers so that they light the cloud alike. The lights themselves
 * are vtkLights: the renderer's for the GPU mapper, the CPU renderers' own light collection.
 *
 * The equations are in docs/lighting.md. Lengths are world units. Values are checked when a
 * renderer uses them (cloudvis::ValidateLightingParameters): a value outside the range stated
 * below is refused with an error naming it, not clamped. The property holds one
 * cloudvis::LightingParameters (CloudLightingParameters.h), the value a scene gives the renderers
 * and the renderers compute with: its defaults are the ones stated below, and in C++
 * GetParameters and SetParameters read and set it whole.
 */
#ifndef vtkCloudLightingProperty_h
#define vtkCloudLightingProperty_h

#include "cloudvisFiltersModule.h"

#include <vtkObject.h>

#ifndef __VTK_WRAP__
#include "CloudLightingParameters.h"
#endif

class CLOUDVISFILTERS_EXPORT vtkCloudLightingProperty : public vtkObject
{
public:
  static vtkCloudLightingProperty* New();
  vtkTypeMacro(vtkCloudLightingProperty, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // cloudvis::LightingModel's values, by VTK's names (the wrapper reads the names only).
  enum Models
  {
    NoLighting = int(cloudvis::LightingModel::None), // a sample emits its transfer-function color
    DerivativeLighting = int(cloudvis::LightingModel::Derivative), // the derivative toward lights
    MarchLighting = int(cloudvis::LightingModel::March),         // a nested march toward each light
    PathTraceLighting = int(cloudvis::LightingModel::PathTrace), // Monte Carlo: the ground truth
  };

  ///@{
  /**
   * The lighting model: NoLighting, DerivativeLighting, MarchLighting or PathTraceLighting (the
   * GPU mapper's progressive path tracer; the CPU's is vtkCloudPathTracer). Default NoLighting.
   */
  virtual void SetModel(int model); // clamped to the range above
  virtual int GetModel();
  void SetModelToNone() { this->SetModel(NoLighting); }
  void SetModelToDerivative() { this->SetModel(DerivativeLighting); }
  void SetModelToMarch() { this->SetModel(MarchLighting); }
  void SetModelToPathTrace() { this->SetModel(PathTraceLighting); }
  const char* GetModelAsString() const; // the name of cloudvis::LightingModelTable
  ///@}

  ///@{
  /**
   * Ambient light reaching every sample of the lit models: color times strength (strength >= 0).
   * Defaults (1, 1, 1) and 0.
   */
  virtual void SetAmbientColor(float r, float g, float b);
  virtual void SetAmbientColor(const float color[3]);
  virtual float* GetAmbientColor() VTK_SIZEHINT(3);
  virtual void GetAmbientColor(float& r, float& g, float& b);
  virtual void GetAmbientColor(float color[3]);
  virtual void SetAmbientStrength(float strength);
  virtual float GetAmbientStrength();
  ///@}

  ///@{
  /**
   * Derivative model: the distance h toward each light of the extra density sample, >= 0; 0
   * means 4 times the smallest voxel edge. Default 0.
   */
  virtual void SetDerivativeDistance(float value);
  virtual float GetDerivativeDistance();
  ///@}

  ///@{
  /**
   * March model: LightSteps samples toward each light (1 to 64), the first segment LightStep
   * long (>= 0; 0 means 2 times the smallest voxel edge), each next one LightStepGrowth (1 to 4)
   * times longer. Defaults 6, 0 and 1.6.
   */
  virtual void SetLightSteps(int value);
  virtual int GetLightSteps();
  virtual void SetLightStep(float value);
  virtual float GetLightStep();
  virtual void SetLightStepGrowth(float value);
  virtual float GetLightStepGrowth();
  ///@}

  ///@{
  /**
   * March model: the two-lobe Henyey-Greenstein phase w HG(g1) + (1 - w) HG(g2), g1 and g2 in
   * (-1, 1) (positive scatters forward), w in [0, 1] (1: one lobe). Defaults 0.6, -0.3 and 0.8.
   */
  virtual void SetPhaseG1(float value);
  virtual float GetPhaseG1();
  virtual void SetPhaseG2(float value);
  virtual float GetPhaseG2();
  virtual void SetPhaseLobeWeight(float value);
  virtual float GetPhaseLobeWeight();
  ///@}

  ///@{
  /**
   * The phase function of the march and the path tracer: TwoLobePhase (the lobes above, the
   * default) or DropletPhase, the Mie phase of liquid water droplets (cloudvis's own Mie code,
   * CloudDropletOptics.h) of effective radius DropletEffectiveRadius micrometres (2 to 30,
   * default 10) and effective variance DropletEffectiveVariance (0.01 to 0.3, default 0.1).
   */
  enum Phases
  {
    TwoLobePhase = int(cloudvis::PhaseModel::TwoLobe),
    DropletPhase = int(cloudvis::PhaseModel::Droplets),
  };
  virtual void SetPhase(int phase); // clamped to the range above
  virtual int GetPhase();
  void SetPhaseToTwoLobe() { this->SetPhase(TwoLobePhase); }
  void SetPhaseToDroplets() { this->SetPhase(DropletPhase); }
  virtual void SetDropletEffectiveRadius(float value);
  virtual float GetDropletEffectiveRadius();
  virtual void SetDropletEffectiveVariance(float value);
  virtual float GetDropletEffectiveVariance();
  ///@}

  ///@{
  /**
   * March model: how the light scattered more than once is added to single scattering.
   * ScatteringVolume: one fetch per sample of a precomputed volume of that light, recomputed when
   * the field, the transfer function or the lights change. ScatteringOctaves: the octaves below.
   * Default ScatteringVolume. docs/lighting.md compares the two with the path tracer.
   */
  enum MultipleScatterings
  {
    ScatteringVolume = int(cloudvis::MultipleScatteringModel::Volume),
    ScatteringOctaves = int(cloudvis::MultipleScatteringModel::Octaves),
  };
  virtual void SetMultipleScattering(int scattering); // clamped to the range above
  virtual int GetMultipleScattering();
  void SetMultipleScatteringToVolume() { this->SetMultipleScattering(ScatteringVolume); }
  void SetMultipleScatteringToOctaves() { this->SetMultipleScattering(ScatteringOctaves); }
  const char* GetMultipleScatteringAsString() const; // cloudvis::MultipleScatteringModelTable's
  ///@}

  ///@{
  /**
   * March model with ScatteringOctaves: approximate multiple scattering, octaves n = 1 ..
   * MultipleScatteringOctaves (0 to 8; 0 is single scattering) added to single scattering,
   * octave n scaling scattering by
   * ScatteringFalloff^n, the extinction toward the light by ExtinctionFalloff^n and the phase's
   * eccentricity by EccentricityFalloff^n (each in [0, 1]). Defaults 3, 0.41, 0.26 and 0.46
   * (fitted to the path tracer: docs/lighting.md).
   */
  virtual void SetMultipleScatteringOctaves(int value);
  virtual int GetMultipleScatteringOctaves();
  virtual void SetScatteringFalloff(float value);
  virtual float GetScatteringFalloff();
  virtual void SetExtinctionFalloff(float value);
  virtual float GetExtinctionFalloff();
  virtual void SetEccentricityFalloff(float value);
  virtual float GetEccentricityFalloff();
  ///@}

  ///@{
  /**
   * March model: where the optical depth toward each light comes from. LightVolumes (the
   * default): per-light volumes at half the field's resolution, computed when the field, the
   * transfer function, the extinction, the step or the lights change, read once per sample per
   * light. NestedMarch (the quality setting): a march of LightSteps segments toward each light at
   * every sample. docs/lighting.md gives the difference between the two.
   */
  enum Transmittances
  {
    LightVolumes = int(cloudvis::LightTransmittance::Volumes),
    NestedMarch = int(cloudvis::LightTransmittance::Nested),
  };
  virtual void SetTransmittance(int transmittance); // clamped to the range above
  virtual int GetTransmittance();
  void SetTransmittanceToLightVolumes() { this->SetTransmittance(LightVolumes); }
  void SetTransmittanceToNestedMarch() { this->SetTransmittance(NestedMarch); }
  ///@}

  ///@{
  /**
   * March model: the non-physical "powder" darkening of thin regions (an artistic term), in
   * [0, 1]; 0 disables it. Default 0.
   */
  virtual void SetPowderStrength(float value);
  virtual float GetPowderStrength();
  ///@}

  /**
   * Copies every value of another property (Modified only when one changes).
   */
  void DeepCopy(vtkCloudLightingProperty* other);

#ifndef __VTK_WRAP__
  ///@{
  /**
   * The values as the C++ value the renderers compute with (the one the property holds), and all
   * of them set from one (Modified only when one changes).
   */
  const cloudvis::LightingParameters& GetParameters() const
  {
    return this->Parameters;
  }
  void SetParameters(const cloudvis::LightingParameters& parameters);
  ///@}
#endif

protected:
  vtkCloudLightingProperty() = default;
  ~vtkCloudLightingProperty() override = default;

#ifndef __VTK_WRAP__
  // Every value the Set/Get methods above reach: one value, the renderers' own, not a member per
  // parameter.
  cloudvis::LightingParameters Parameters;
#endif

private:
#ifndef __VTK_WRAP__
  // Parameters.*member = value, Modified when that changes it.
  template<typename T>
  void Assign(T cloudvis::LightingParameters::*member, T value);
#endif
  vtkCloudLightingProperty(const vtkCloudLightingProperty&) = delete;
  void operator=(const vtkCloudLightingProperty&) = delete;
};

#endif
