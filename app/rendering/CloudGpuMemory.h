// GPU memory for vtkCloudVolumeMapper's textures and targets: what the driver reports free, and
// the check every allocation of the mapper goes through, so that a field too large for the GPU
// is refused with the size it needs instead of being drawn from a texture that was never
// allocated. Private to the rendering module.
#ifndef CloudGpuMemory_h
#define CloudGpuMemory_h

#include <glm/vec3.hpp>

#include <functional>
#include <string>

class vtkOpenGLRenderWindow;
class vtkTextureObject;

namespace cloudvis
{

// Bytes of video memory the driver reports free (GL_NVX_gpu_memory_info on NVIDIA,
// GL_ATI_meminfo on AMD), or -1 when it reports nothing (Mesa's drivers, among others).
long long FreeGpuMemory(vtkOpenGLRenderWindow* window);

// One frame's allocations: each is checked against the mapper's limit (0: none) on all it holds,
// and against what the GPU reports free; then GL's error flag tells whether the allocation
// itself failed.
class GpuMemoryBudget
{
public:
  GpuMemoryBudget(vtkOpenGLRenderWindow* window, long long limit, long long held);

  // Allocates `bytes` for `what`, replacing `released` bytes the mapper holds for it: empty when
  // they fit and `create` (which allocates them, true on success) succeeded without a GL error,
  // else why not, with the sizes (GL_OUT_OF_MEMORY: the driver could not allocate them; then
  // `create` has run). The bytes then count as held.
  std::string Allocate(const std::string& what,
    long long bytes,
    long long released,
    const std::function<bool()>& create);

  // Allocates a 3-D texture (or a set of them) as Allocate does, after checking `texels`, its
  // size along x, y and z (a stacked volume's layers along z), against the GPU's largest 3-D
  // texture: a size it cannot hold is refused naming `what`, the size and the limit, followed by
  // `advice` (what the user can change), and `create` does not run. Every 3-D texture of the
  // mapper is made through this.
  std::string AllocateVolume(const std::string& what,
    const glm::ivec3& texels,
    long long bytes,
    long long released,
    const std::function<bool()>& create,
    const std::string& advice = {});

  // Bytes the mapper freed outside Allocate (a target that goes with another's resize): no longer
  // held, so that the allocations after it are not checked against them.
  void Release(long long bytes) { this->Held -= bytes; }

  // An allocation was refused for want of memory (beyond the limit, beyond what the GPU reports
  // free, or GL_OUT_OF_MEMORY), not for another reason.
  bool Refused() const { return this->OutOfMemory; }

private:
  vtkOpenGLRenderWindow* Window;
  long long Limit;
  long long Held;
  bool OutOfMemory = false;
};

// The bytes the GL allocated for level 0 of a texture, from the sizes of its internal format's
// components as the driver reports them (so R8 really is one byte a texel, or the count says
// otherwise). The texture must have its context current.
long long TextureBytes(vtkTextureObject* texture);

// Finishes a volume's texture as the mapper's interpolated volumes are sampled (trilinear, clamped
// to the edge; the bricks' maps are read texel by texel) and returns the bytes it holds
// (TextureBytes).
long long FinishVolumeTexture(vtkTextureObject* texture);

// How a texture is sampled: `filter` for minification and magnification, `wrap` along every
// axis (vtkTextureObject's enums).
void SetSampling(vtkTextureObject* texture, int filter, int wrap);

} // namespace cloudvis

#endif
