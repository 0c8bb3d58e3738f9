// The droplets' phase table (filters/CloudDropletOptics.h) as vtkCloudVolumeMapper's 2-D RGB32F
// texture of DropletPhaseTable::NodeCount x 2 texels: row 0 the phase per channel, row 1 its
// cumulative distribution, read with texelFetch by the shared transport's accessors
// (shaders/transport/Accessors.glsl). Every program that holds the transport declares its
// sampler, so the texture is always there: the table of the lighting's droplets, or one texel
// row of zeros when the phase is the two lobes. Private to the module.
#ifndef CloudDropletPhaseTexture_h
#define CloudDropletPhaseTexture_h

#include <vtkNew.h>
#include <vtkTextureObject.h>

#include <string>

class vtkOpenGLRenderWindow;
class vtkWindow;

namespace cloudvis
{
class GpuMemoryBudget;
struct DropletPhaseTable;
struct LightingParameters;

class DropletPhaseTexture
{
public:
  // Brings the texture up to date with `lighting`'s phase; on a problem (a texture the GPU cannot
  // allocate) sets it and releases the texture.
  bool Update(vtkOpenGLRenderWindow* window,
    const LightingParameters& lighting,
    GpuMemoryBudget& budget,
    std::string& problem);

  vtkTextureObject* GetTexture() { return this->Texture; }
  long long GetBytes() const { return this->Bytes; }
  void Release(vtkWindow* window);

private:
  vtkNew<vtkTextureObject> Texture;
  const DropletPhaseTable* Uploaded = nullptr; // identity only; null: the two lobes' zeros
  bool HasTexture = false;
  long long Bytes = 0;
};

} // namespace cloudvis

#endif
