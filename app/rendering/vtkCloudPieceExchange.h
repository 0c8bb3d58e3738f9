/**
 * @class   vtkCloudPieceExchange
 * @brief   light across the pieces of a distributed field: what one rank's mapper gives and takes
 *
 * Under MPI (a ParaView representation across ranks), each rank's vtkCloudVolumeMapper draws its
 * piece of one image. For light to cross the pieces' faces, the ranks exchange two things
 * (docs/transport.md, "Across the pieces of a distributed field"):
 *
 * - Optical depths. On a grid all ranks share (the whole field's box), each rank computes the
 *   optical depth its piece adds toward each light (ComputePieceOpticalDepths); the sum over the
 *   ranks less the rank's own is what the other pieces add (cloudvis::DepthsFromOutside), which
 *   its mapper adds wherever it uses an optical depth toward a light (SetExternalOpticalDepths).
 * - The multiple-scattering volume. Its diffusion must be solved over the whole field, or light
 *   would not diffuse across the faces. Each rank computes the inputs of the whole field's grids
 *   for the cells its piece owns, zero elsewhere, as one array of floats
 *   (ComputePieceScatteringInputs); every rank solves the sum over the ranks
 *   (SolveScatteringVolume: the same floats give the same volume on every rank), which its mapper
 *   then reads in place of a volume of its own piece.
 *
 * The exchange computes on the CPU and never communicates: the caller sums the arrays over the
 * ranks (vtkMultiProcessController::AllReduce, MPI_Allreduce) and hands the sums back, so it
 * needs neither OpenGL nor MPI. What it takes and gives are public types: the mapper and its
 * volume, cloudvis::OpticalDepthGrid (CloudOpticalDepthGrid.h), VTK extents and arrays of floats.
 * Failures return false with the mapper's GetLastError().
 */
#ifndef vtkCloudPieceExchange_h
#define vtkCloudPieceExchange_h

#include "cloudvisRenderingModule.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <cstddef>
#include <string>
#include <vector>

class vtkCloudVolumeMapper;
class vtkRenderer;
class vtkVolume;

namespace cloudvis
{
struct OpticalDepthGrid;
}

class CLOUDVISRENDERING_EXPORT vtkCloudPieceExchange : public vtkObject
{
public:
  static vtkCloudPieceExchange* New();
  vtkTypeMacro(vtkCloudPieceExchange, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The mapper whose piece is exchanged, and the volume that draws it (its property and matrix
   * are what the march uses). Both are needed before anything below.
   */
  void SetMapper(vtkCloudVolumeMapper* mapper);
  vtkCloudVolumeMapper* GetMapper() const;
  void SetVolume(vtkVolume* volume);
  vtkVolume* GetVolume() const;
  ///@}

  /**
   * Why the last computation failed: the mapper's GetLastError(), or the exchange's own words
   * when it has no mapper.
   */
  std::string GetLastError() const;

#ifndef __VTK_WRAP__
  ///@{
  /**
   * ComputePieceOpticalDepths fills `grid`'s Depths and Lights for its Origin, Spacing and Size:
   * at each grid point, per light (the mapper's lights, in order: SetLights, else `renderer`'s
   * switched-on lights), the optical depth the mapper's input adds along the ray toward the
   * light, counting only the part inside the input's box, with the march's extinction (the
   * volume's property, ExtinctionScale, HalfFloatDensity's texels). With vtkSMPTools.
   *
   * SetExternalOpticalDepths gives the mapper the depths that come from outside its input: the
   * march adds them wherever it uses an optical depth toward a light (the single-scattering beam
   * with the light volumes or the nested march, and the multiple-scattering volume's source), for
   * the march lighting model. The grid is copied (an empty one clears them) and must hold the
   * lights the mapper lights with, else the render fails in words. Setting it restarts the
   * progressive accumulation and recomputes the multiple-scattering volume, not the light
   * volumes (which hold the field's own depths). Its texture is part of the mapper's
   * GetGPUMemoryBytes. Default none.
   */
  bool ComputePieceOpticalDepths(vtkRenderer* renderer, cloudvis::OpticalDepthGrid& grid);
  void SetExternalOpticalDepths(const cloudvis::OpticalDepthGrid& grid);
  const cloudvis::OpticalDepthGrid& GetExternalOpticalDepths() const;
  ///@}

  ///@{
  /**
   * The whole field is the image whose extent is `wholeExtent` (the union of the pieces'
   * extents: the pieces of one image share its origin, spacing and direction, and the volume's
   * matrix places them all).
   *
   * GetScatteringInputCount is the length of the arrays below for a whole field of that extent
   * (0 when the extent is empty).
   *
   * ComputePieceScatteringInputs fills `inputs` (resized to that length) with the inputs of the
   * whole field's grids for the cells the mapper's input owns, zero elsewhere, lit as the march
   * lights (the volume's property, the mapper's lights or `renderer`'s, and the external optical
   * depths): a cell is the piece's when its centre lies within the piece's points, each cell on a
   * face pieces share counted once. False when the input, the volume or the geometry cannot be
   * used (the input's points are not a sub-grid of the whole field's).
   *
   * SolveScatteringVolume solves the inputs summed over every rank's piece and gives the mapper
   * the volume: while it is set and the march's multiple scattering comes from the volume, the
   * march reads it through the map from its input's voxels to the whole field's, instead of
   * computing a volume of its input. Setting it restarts the progressive accumulation; its
   * textures are part of the mapper's GetGPUMemoryBytes. False, with the volume cleared, when
   * `summedInputs` has another length than GetScatteringInputCount or the mapper has no input to
   * place the whole field by. ClearScatteringVolume lets the mapper compute its own again;
   * HasScatteringVolume says whether it reads one solved over the whole field.
   */
  static std::size_t GetScatteringInputCount(const int wholeExtent[6]);
  bool ComputePieceScatteringInputs(vtkRenderer* renderer,
    const int wholeExtent[6],
    std::vector<float>& inputs);
  bool SolveScatteringVolume(const std::vector<float>& summedInputs, const int wholeExtent[6]);
  void ClearScatteringVolume();
  bool HasScatteringVolume() const;
  ///@}
#endif

protected:
  vtkCloudPieceExchange();
  ~vtkCloudPieceExchange() override;

private:
  vtkCloudPieceExchange(const vtkCloudPieceExchange&) = delete;
  void operator=(const vtkCloudPieceExchange&) = delete;

  // Whether the mapper and the volume are set; else records why in NoMapperError.
  bool Ready(const char* what);

  vtkSmartPointer<vtkCloudVolumeMapper> Mapper;
  vtkSmartPointer<vtkVolume> Volume;
  std::string NoMapperError;
};

#endif
