// The field as vtkCloudVolumeMapper's 3-D density texture, in its native type
// (CloudDensityTexels.h): R8 for unsigned char, R16 for unsigned short, R32F for float, or R16F
// for float when half floats are asked for, read by the shader as texel * Scale + Bias. Uploaded
// again only when the data, or the choice of half floats, change. Private to the module.
#ifndef CloudDensityTexture_h
#define CloudDensityTexture_h

#include "CloudDensityTexels.h"
#include "CloudVolumeSources.h"

#include <vtkNew.h>
#include <vtkTextureObject.h>
#include <vtkType.h>

#include <string>

class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkWindow;

namespace cloudvis
{
class GpuMemoryBudget;

class DensityTexture
{
public:
  // Brings the texture up to date with `scalars`, the point scalars of `input` (one component of
  // a type DensityTexelsOf takes, one value per voxel): refuses values that are not finite, a
  // field beyond the GPU's 3-D texture size, or one the budget cannot hold; uploads with linear
  // filtering and clamping to the edge. On a problem, sets it and releases the texture (nothing
  // is drawn from a stale or half-made one).
  bool Update(vtkOpenGLRenderWindow* window,
    vtkImageData* input,
    vtkDataArray* scalars,
    bool halfFloat,
    GpuMemoryBudget& budget,
    std::string& problem);

  vtkTextureObject* GetTexture() { return this->Texture; }
  // The texels' format, Scale and Bias (Values is null: the data are on the GPU).
  const DensityTexels& GetTexels() const { return this->Texels; }
  // Changes whenever another field (or the same field in another format) is uploaded.
  vtkMTimeType GetUploadTime() const { return this->UploadTime; }
  long long GetBytes() const { return this->Bytes; }
  void Release(vtkWindow* window);

private:
  vtkNew<vtkTextureObject> Texture;
  DensityTexels Texels;
  VolumeSources Sources; // the input, its MTime and its scalars', and the half-float switch
  vtkMTimeType UploadTime = 0;
  long long Bytes = 0;
};

} // namespace cloudvis

#endif
