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
 * below is refused with an error naming it, not clamped. The defaults are those of
 * cloudvis::LightingParameters (CloudLighting.h), the C++ value type the renderers compute with;
 * GetParameters and SetParameters convert between the two in C++.
 */
#ifndef vtkCloudLightingProperty_h
#define vtkCloudLightingProperty_h

#include "cloudvisFiltersModule.h"

#include <vtkObject.h>

#ifndef __VTK_WRAP__
#include "CloudLighting.h"
#endif

class CLOUDVISFILTERS_EXPORT vtkCloudLightingProperty : public vtkObject
{
public:
  static vtkCloudLightingProperty* New();
  vtkTypeMacro(vtkCloudLightingProperty, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Models
  {
    NoLighting = 0,         // emission-absorption: a sample emits its transfer-function color
    DerivativeLighting = 1, // the directional derivative toward each light
    MarchLighting = 2,      // a nested march toward each light, phase, multiple scattering
    PathTraceLighting = 3,  // Monte Carlo path tracing of the same medium: the ground truth
  };

  ///@{
  /**
   * The lighting model: NoLighting, DerivativeLighting, MarchLighting or PathTraceLighting (the
   * GPU mapper's progressive path tracer; the CPU's is vtkCloudPathTracer). Default NoLighting.
   */
  vtkSetClampMacro(Model, int, NoLighting, PathTraceLighting);
  vtkGetMacro(Model, int);
  void SetModelToNone() { this->SetModel(NoLighting); }
  void SetModelToDerivative() { this->SetModel(DerivativeLighting); }
  void SetModelToMarch() { this->SetModel(MarchLighting); }
  void SetModelToPathTrace() { this->SetModel(PathTraceLighting); }
  const char* GetModelAsString() const;
  ///@}

  ///@{
  /**
   * Ambient light reaching every sample of the lit models: color times strength (strength >= 0).
   * Defaults (1, 1, 1) and 0.
   */
  vtkSetVector3Macro(AmbientColor, float);
  vtkGetVector3Macro(AmbientColor, float);
  vtkSetMacro(AmbientStrength, float);
  vtkGetMacro(AmbientStrength, float);
  ///@}

  ///@{
  /**
   * Derivative model: the distance h toward each light of the extra density sample, >= 0; 0
   * means 4 times the smallest voxel edge. Default 0.
   */
  vtkSetMacro(DerivativeDistance, float);
  vtkGetMacro(DerivativeDistance, float);
  ///@}

  ///@{
  /**
   * March model: LightSteps samples toward each light (1 to 64), the first segment LightStep
   * long (>= 0; 0 means 2 times the smallest voxel edge), each next one LightStepGrowth (1 to 4)
   * times longer. Defaults 6, 0 and 1.6.
   */
  vtkSetMacro(LightSteps, int);
  vtkGetMacro(LightSteps, int);
  vtkSetMacro(LightStep, float);
  vtkGetMacro(LightStep, float);
  vtkSetMacro(LightStepGrowth, float);
  vtkGetMacro(LightStepGrowth, float);
  ///@}

  ///@{
  /**
   * March model: the two-lobe Henyey-Greenstein phase w HG(g1) + (1 - w) HG(g2), g1 and g2 in
   * (-1, 1) (positive scatters forward), w in [0, 1] (1: one lobe). Defaults 0.6, -0.3 and 0.8.
   */
  vtkSetMacro(PhaseG1, float);
  vtkGetMacro(PhaseG1, float);
  vtkSetMacro(PhaseG2, float);
  vtkGetMacro(PhaseG2, float);
  vtkSetMacro(PhaseLobeWeight, float);
  vtkGetMacro(PhaseLobeWeight, float);
  ///@}

  ///@{
  /**
   * March model: approximate multiple scattering, octaves n = 1 .. MultipleScatteringOctaves
   * (0 to 8; 0 is single scattering) added to single scattering, octave n scaling scattering by
   * ScatteringFalloff^n, the extinction toward the light by ExtinctionFalloff^n and the phase's
   * eccentricity by EccentricityFalloff^n (each in [0, 1]). Defaults 3, 0.41, 0.26 and 0.46
   * (fitted to the path tracer: docs/lighting.md).
   */
  vtkSetMacro(MultipleScatteringOctaves, int);
  vtkGetMacro(MultipleScatteringOctaves, int);
  vtkSetMacro(ScatteringFalloff, float);
  vtkGetMacro(ScatteringFalloff, float);
  vtkSetMacro(ExtinctionFalloff, float);
  vtkGetMacro(ExtinctionFalloff, float);
  vtkSetMacro(EccentricityFalloff, float);
  vtkGetMacro(EccentricityFalloff, float);
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
    LightVolumes = 0,
    NestedMarch = 1,
  };
  vtkSetClampMacro(Transmittance, int, LightVolumes, NestedMarch);
  vtkGetMacro(Transmittance, int);
  void SetTransmittanceToLightVolumes() { this->SetTransmittance(LightVolumes); }
  void SetTransmittanceToNestedMarch() { this->SetTransmittance(NestedMarch); }
  ///@}

  ///@{
  /**
   * March model: the non-physical "powder" darkening of thin regions (an artistic term), in
   * [0, 1]; 0 disables it. Default 0.
   */
  vtkSetMacro(PowderStrength, float);
  vtkGetMacro(PowderStrength, float);
  ///@}

  /**
   * Copies every value of another property (Modified only when one changes).
   */
  void DeepCopy(vtkCloudLightingProperty* other);

#ifndef __VTK_WRAP__
  ///@{
  /**
   * The values as the C++ struct the renderers compute with, and all of them set from one.
   */
  cloudvis::LightingParameters GetParameters() const;
  void SetParameters(const cloudvis::LightingParameters& parameters);
  ///@}
#endif

protected:
  vtkCloudLightingProperty();
  ~vtkCloudLightingProperty() override = default;

  // Set by the constructor from a default cloudvis::LightingParameters: the defaults are written
  // once, there (zero until then).
  int Model{};
  float AmbientColor[3]{};
  float AmbientStrength{};
  float DerivativeDistance{};
  int LightSteps{};
  float LightStep{};
  float LightStepGrowth{};
  float PhaseG1{};
  float PhaseG2{};
  float PhaseLobeWeight{};
  int MultipleScatteringOctaves{};
  float ScatteringFalloff{};
  float ExtinctionFalloff{};
  float EccentricityFalloff{};
  float PowderStrength{};
  int Transmittance{};

private:
#ifndef __VTK_WRAP__
  bool AssignParameters(const cloudvis::LightingParameters& parameters);
#endif
  vtkCloudLightingProperty(const vtkCloudLightingProperty&) = delete;
  void operator=(const vtkCloudLightingProperty&) = delete;
};

#endif
