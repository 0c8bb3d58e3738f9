/**
 * @class   vtkCloudVolumeRepresentation
 * @brief   ParaView's "Cloud Volume" representation: image data drawn by vtkCloudVolumeMapper
 *
 * The representation is ParaView's own image volume representation (data delivery, the outline
 * where a rank has no data, ordered compositing of the ranks' pieces in visibility order) with
 * its volume mapper replaced by cloudvis's, and the mapper's lighting models and their parameters
 * as properties (docs/paraview.md). The volume property ParaView's transfer-function editor edits
 * (color map and scalar opacity, ScalarOpacityUnitDistance) is the mapper's transfer function,
 * read as cloudvis reads a scene's: opacity per unit distance gives the extinction, the color the
 * albedo (docs/lighting.md).
 *
 * The lights are one sun (a direction toward it, a color and an intensity) and the ambient light,
 * as a scene's; ParaView's light kit does not light the cloud.
 *
 * Under MPI each rank marches its own piece. So that light crosses pieces (a cloud on one rank
 * shadows a cloud on another), each rank computes the optical depth its piece adds toward the sun
 * over a coarse grid of the whole field, an MPI_Allreduce sums them, and each rank's march adds
 * what the other ranks' pieces hold (ShadowExchange, on by default; docs/paraview.md states the
 * grid and what it costs). With the multiple-scattering volume (the march's default), the ranks
 * then sum the inputs of the whole field's volume, each for the cells its piece owns, and every
 * rank solves the same whole-field volume, which its march reads (docs/paraview.md). The path
 * tracer needs the whole field on one rank and is refused on more.
 */
#ifndef vtkCloudVolumeRepresentation_h
#define vtkCloudVolumeRepresentation_h

#include "cloudvisParaViewModule.h"
#include "vtkCloudLightingProperty.h" // for the lighting property
#include "vtkCloudPieceExchange.h"    // for the exchange between ranks
#include "vtkImageVolumeRepresentation.h"
#include "vtkNew.h"       // for the lighting property
#include "vtkTimeStamp.h" // for the exchange's inputs

#include <vector> // for the exchange's inputs

class vtkCloudVolumeMapper;
class vtkImageData;
class vtkMultiProcessController;
class vtkRenderer;

class CLOUDVISPARAVIEW_EXPORT vtkCloudVolumeRepresentation : public vtkImageVolumeRepresentation
{
public:
  static vtkCloudVolumeRepresentation* New();
  vtkTypeMacro(vtkCloudVolumeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* requestType,
    vtkInformation* inInfo,
    vtkInformation* outInfo) override;

  ///@{
  /**
   * The lighting model: 0 none, 1 derivative, 2 march, 3 pathtrace (vtkCloudLightingProperty's
   * LightingModels), and the parameters of vtkCloudLightingProperty of the same names.
   */
  void SetLightingModel(int model);
  void SetAmbientColor(double r, double g, double b);
  void SetAmbientStrength(double strength);
  void SetDerivativeDistance(double distance);
  void SetLightSteps(int steps);
  void SetPhaseG1(double g);
  void SetPhaseG2(double g);
  void SetPhaseLobeWeight(double weight);
  void SetPhase(int phase);
  void SetDropletEffectiveRadius(double radius);
  void SetDropletEffectiveVariance(double variance);
  void SetMultipleScattering(int scattering);
  void SetMultipleScatteringOctaves(int octaves);
  void SetTransmittance(int transmittance);
  ///@}

  ///@{
  /**
   * The sun: the direction toward it (any length but not zero), its color and its intensity.
   * Defaults (6, 8, 4), white, 1: a scene's default sun.
   */
  void SetSunDirection(double x, double y, double z);
  void SetSunColor(double r, double g, double b);
  void SetSunIntensity(double intensity);
  ///@}

  ///@{
  /**
   * The mapper's settings of the same names (vtkCloudVolumeMapper); MaximumGPUMemory in MiB per
   * rank (0: no limit of cloudvis's own).
   */
  void SetSampleDistance(double distance);
  void SetExtinctionScale(double scale);
  void SetJitter(bool jitter);
  void SetMaximumAccumulatedFrames(int frames);
  void SetPathTraceSamplesPerFrame(int samples);
  void SetMaximumGPUMemory(double mebibytes);
  ///@}

  ///@{
  /**
   * Exchange optical depth between ranks so that light crosses pieces, and with the
   * multiple-scattering volume its inputs, so that diffuse light crosses them too. Default on.
   * Off, each rank lights its piece as if it were the whole field (what ParaView's own volume
   * mappers do).
   */
  void SetShadowExchange(bool exchange);
  vtkGetMacro(ShadowExchange, bool);
  ///@}

protected:
  vtkCloudVolumeRepresentation();
  ~vtkCloudVolumeRepresentation() override;

private:
  vtkCloudVolumeRepresentation(const vtkCloudVolumeRepresentation&) = delete;
  void operator=(const vtkCloudVolumeRepresentation&) = delete;

  void UpdateSun();
  // Collective over the ranks of the global controller: every rank calls it in each render.
  void ExchangeOpticalDepth(vtkRenderer* renderer);
  // Collective, after the optical depths are exchanged: the multiple-scattering volume over the
  // whole field when `wanted`, else none (each rank's mapper solves its own piece's).
  void ExchangeScatteringVolume(vtkMultiProcessController* controller,
    vtkRenderer* renderer,
    vtkImageData* piece,
    bool wanted);

  vtkCloudVolumeMapper* CloudMapper = nullptr; // this->VolumeMapper, as the cloud mapper it is
  vtkNew<vtkCloudPieceExchange> Exchange;       // CloudMapper's side of the exchange
  vtkNew<vtkCloudLightingProperty> Lighting;
  double SunDirection[3] = { 6.0, 8.0, 4.0 };
  double SunColor[3] = { 1.0, 1.0, 1.0 };
  double SunIntensity = 1.0;
  bool ShadowExchange = true;
  // What the last exchange was computed for: the latest modification time of its inputs (the
  // piece, the transfer table, the lighting, and ExchangeInputsTime: the sun, the extinction
  // scale).
  vtkTimeStamp ExchangeInputsTime;
  vtkMTimeType ExchangedTime = 0;
  // The transfer table the last exchange read (its range and entries), and when it last changed.
  std::vector<double> ExchangedTable;
  vtkTimeStamp ExchangedTableTime;
};

#endif
