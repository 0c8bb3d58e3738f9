// The occupancy map of vtkCloudVolumeMapper: vtkCloudOccupancyFilter's empty distances per brick
// (Chebyshev distance in bricks to occupied space) as an R8 3-D texture the march reads to leap
// over empty space, recomputed when the density, the transfer table or the brick size change.
// Private to the module.
#ifndef CloudOccupancyTexture_h
#define CloudOccupancyTexture_h

#include "CloudVolumeSources.h"
#include "vtkCloudOccupancyFilter.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkTextureObject.h>
#include <vtkType.h>

#include <string>

class vtkDataArray;
class vtkOpenGLRenderWindow;
class vtkWindow;

namespace cloudvis
{
class GpuMemoryBudget;
struct TransferTable;

class OccupancyTexture
{
public:
  // Brings the map up to date with `scalars` of `input` (identified by densityTime, the density
  // texture's upload time), `table` (identified by tableTime) and the brick size.
  bool Update(vtkOpenGLRenderWindow* window,
    vtkImageData* input,
    vtkDataArray* scalars,
    vtkMTimeType densityTime,
    const TransferTable& table,
    vtkMTimeType tableTime,
    int brickSize,
    GpuMemoryBudget& budget,
    std::string& problem);

  vtkTextureObject* GetTexture() { return this->Texture; }
  // The occupancy filter's last output: per brick its empty distance and extinction bounds.
  vtkImageData* GetBricks() { return this->Filter->GetOutput(); }
  const int* GetBrickCount() const { return this->BrickCount; }
  double GetOccupiedFraction() const { return this->OccupiedFraction; }
  long long GetBytes() const { return this->Bytes; }
  void Release(vtkWindow* window);

private:
  vtkNew<vtkTextureObject> Texture;
  vtkNew<vtkCloudOccupancyFilter> Filter;
  vtkNew<vtkImageData> FilterInput; // the mapped scalars as the active scalars
  vtkMTimeType DensityTime = 0;
  vtkMTimeType TableTime = 0;
  VolumeSources Sources; // the occupancy filter's output MTime
  int BrickCount[3] = { 0, 0, 0 };
  double OccupiedFraction = 0.0;
  long long Bytes = 0;
};

} // namespace cloudvis

#endif
