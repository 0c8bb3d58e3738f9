// The blue-noise mask (CloudBlueNoise.h) that jitters the first sample of each of
// vtkCloudVolumeMapper's rays, as a tiled R32F texture. Private to the module.
#ifndef CloudJitterTexture_h
#define CloudJitterTexture_h

#include <vtkNew.h>
#include <vtkTextureObject.h>

#include <string>

class vtkOpenGLRenderWindow;
class vtkWindow;

namespace cloudvis
{
class GpuMemoryBudget;

class JitterTexture
{
public:
  // Edge length of the mask, in pixels.
  static constexpr int Size = 64;

  // Creates the texture once per context.
  bool Update(vtkOpenGLRenderWindow* window, GpuMemoryBudget& budget, std::string& problem);
  vtkTextureObject* GetTexture() { return this->Texture; }
  long long GetBytes() const { return this->Bytes; }
  void Release(vtkWindow* window);

private:
  vtkNew<vtkTextureObject> Texture;
  long long Bytes = 0;
};

} // namespace cloudvis

#endif
