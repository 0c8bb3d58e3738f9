// The transfer table (albedo and extinction per density, CloudTransferTable.h) as
// vtkCloudVolumeMapper's 1-D RGBA32F texture, rebuilt when the volume property or the extinction
// scale change. The table is the one every cloudvis renderer builds (TransferTableOf); the
// occupancy map is computed from it too. Private to the module.
#ifndef CloudTransferTexture_h
#define CloudTransferTexture_h

#include "CloudTransferTable.h"

#include <vtkNew.h>
#include <vtkTextureObject.h>
#include <vtkType.h>

#include <string>

class vtkOpenGLRenderWindow;
class vtkVolumeProperty;
class vtkWindow;

namespace cloudvis
{
class GpuMemoryBudget;

class TransferTexture
{
public:
  // Brings table and texture up to date; on a problem (an invalid transfer function, a texture
  // the GPU cannot allocate) sets it and releases the texture.
  bool Update(vtkOpenGLRenderWindow* window,
    vtkVolumeProperty* property,
    double extinctionScale,
    GpuMemoryBudget& budget,
    std::string& problem);

  const TransferTable& GetTable() const { return this->Table; }
  vtkTextureObject* GetTexture() { return this->Texture; }
  // Changes whenever the table is rebuilt.
  vtkMTimeType GetTableTime() const { return this->TableTime; }
  long long GetBytes() const { return this->Bytes; }
  void Release(vtkWindow* window);

private:
  vtkNew<vtkTextureObject> Texture;
  TransferTable Table;
  vtkMTimeType PropertyTime = 0;
  vtkVolumeProperty* BuiltFrom = nullptr; // identity only
  double ExtinctionScale = -1.0;
  vtkMTimeType TableTime = 0;
  long long Bytes = 0;
};

} // namespace cloudvis

#endif
