/**
 * @class   vtkCloudOccupancyFilter
 * @brief   brick occupancy and empty-space distances for skipping transparent space
 *
 * vtkCloudOccupancyFilter cuts a density volume into bricks of BrickSize^3 cells and says, per
 * brick, how much a ray marcher may skip. The output is vtkImageData with one point per brick
 * (dimensions ceil((n - 1) / BrickSize) per axis, at least 1; spacing BrickSize times the input
 * spacing; origin at the input's first voxel), so brick b along an axis covers the cells
 * between voxels b * BrickSize and (b + 1) * BrickSize. Point arrays:
 *
 * - "max_extinction" (float, the active scalars): the largest sigma_t the transfer table can
 *   return for any density a trilinear sample inside the brick can see. The density range is
 *   taken over voxels b * BrickSize - Apron .. (b + 1) * BrickSize + Apron (clamped to the
 *   data). With Apron 0 that is exactly the trilinear footprint of the brick's cells; GPU
 *   rounding of a sample position can at most give a neighbouring voxel a weight below the
 *   filter's 1/256 precision. A brick is occupied when this is > 0.
 * - "min_extinction" (float): the smallest sigma_t the table can return for any density of the
 *   same voxels, so no trilinear sample inside the brick has less (the path tracer's control
 *   extinction for residual ratio tracking).
 * - "empty_distance" (unsigned char): Chebyshev distance in bricks to the nearest occupied
 *   brick (0 occupied, 1 empty but touching an occupied brick, ...), capped at 255. A marcher
 *   at an empty brick with distance k may advance to the boundary of the (2k - 1)^3 block of
 *   bricks centred on it without missing anything.
 *
 * The field data holds "occupied_fraction" (one double), also available through
 * GetOccupiedFraction after an update. The transfer table is the one the renderer uses
 * (cloudvis::TransferTable), so skipping is exact with respect to what will be drawn.
 *
 * The input is the active point scalars of a vtkImageData, one component of float, unsigned
 * char or unsigned short. The whole input is read whatever extent is requested downstream. The
 * work runs under vtkSMPTools; every brick's values depend only on the data and the table,
 * never on the number of threads.
 */
#ifndef vtkCloudOccupancyFilter_h
#define vtkCloudOccupancyFilter_h

#include "CloudTransferTable.h"
#include "cloudvisFiltersModule.h"

#include <vtkImageAlgorithm.h>

class CLOUDVISFILTERS_EXPORT vtkCloudOccupancyFilter : public vtkImageAlgorithm
{
public:
  static vtkCloudOccupancyFilter* New();
  vtkTypeMacro(vtkCloudOccupancyFilter, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The transfer table that decides which densities are transparent; its Range is in the
   * units of the input scalars (0..255 for unsigned char data stored as such). Setting an
   * equal table does not modify the filter, so the pipeline does not re-execute. Default: an
   * empty table, which the filter refuses with an error: set it before updating.
   */
  void SetTransferTable(const cloudvis::TransferTable& table);
  const cloudvis::TransferTable& GetTransferTable() const { return this->TransferTable; }
  ///@}

  ///@{
  /**
   * Cells per brick edge, at least 1. Default 8.
   */
  vtkSetClampMacro(BrickSize, int, 1, VTK_INT_MAX);
  vtkGetMacro(BrickSize, int);
  ///@}

  ///@{
  /**
   * Extra voxels around each brick's trilinear footprint whose density also counts. A wider
   * apron marks more bricks occupied (safer, slower). Default 0.
   */
  vtkSetClampMacro(Apron, int, 0, 8);
  vtkGetMacro(Apron, int);
  ///@}

  /**
   * Fraction of bricks that are occupied (max_extinction > 0) in the last output, in [0, 1];
   * 0 before the first update.
   */
  vtkGetMacro(OccupiedFraction, double);

protected:
  vtkCloudOccupancyFilter() = default;
  ~vtkCloudOccupancyFilter() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  cloudvis::TransferTable TransferTable;
  int BrickSize = 8;
  int Apron = 0;
  double OccupiedFraction = 0.0;

private:
  vtkCloudOccupancyFilter(const vtkCloudOccupancyFilter&) = delete;
  void operator=(const vtkCloudOccupancyFilter&) = delete;
};

#endif
