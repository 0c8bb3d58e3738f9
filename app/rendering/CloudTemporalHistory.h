// What vtkCloudVolumeMapper keeps of the cloud it last showed in one renderer, for temporal
// reprojection (vtkCloudVolumeMapper::TemporalReprojection): the image at the viewport's full
// resolution (premultiplied RGBA16F, before it is blended over the scene), per pixel the cloud's
// opacity-weighted mean depth (local units from the near plane along the pixel's ray, from the
// march's count target) and the age of the history there (the angle its views lie from the last
// one, RG32F), and the device-to-local matrix it was seen with.
// Two such pairs of targets alternate: the composite pass reads the last one while it writes the
// next. The matrix is in the march's local frame (filters/CloudMarchUniforms.h), which only the
// volume's placement changes, and a change of that invalidates the history anyway, so
// reprojection keeps the march's precision wherever the volume sits. Private to the module.
#ifndef CloudTemporalHistory_h
#define CloudTemporalHistory_h

#include <glm/glm.hpp>
#include <vtkNew.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkTextureObject.h>

#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkWindow;

namespace cloudvis
{
class GpuMemoryBudget;

class TemporalHistory
{
public:
  // (Re)allocates both pairs of targets at the viewport's size; a new size forgets the image.
  bool Resize(vtkOpenGLRenderWindow* window,
    int width,
    int height,
    GpuMemoryBudget& budget,
    std::string& problem);

  // Starts a frame: the last image may be reprojected into it when `reproject` (the caller's
  // judgement that the frame is interactive) and nothing but the camera (and the march's
  // resolution) changed since it was drawn: `content` is everything else the image depends on.
  void BeginFrame(const std::vector<double>& content,
    bool reproject,
    const glm::dmat4& deviceToLocal);

  // Draws into the targets that do not hold the last image (color as output 0, depth as output
  // 1); false (bindings restored) when the framebuffer is incomplete.
  bool BindNext(vtkOpenGLRenderWindow* window);
  // Restores the bindings and makes what was drawn the last image.
  void FinishNext(vtkOpenGLRenderWindow* window);

  // The last image and its depth.
  vtkTextureObject* GetColor() { return this->Color[this->Last]; }
  vtkTextureObject* GetDepth() { return this->Depth[this->Last]; }
  const int* GetSize() const { return this->Size; }
  bool IsAllocated() const { return this->Size[0] > 0; }
  long long GetBytes() const { return this->Bytes; }
  void Release(vtkWindow* window);

  bool HasImage = false;        // the last image was drawn (since the size last changed)
  bool Reproject = false;       // this frame blends the last image, reprojected
  int Sequence = 0;             // images blended since the history last started afresh
  double DepthTolerance = 1.0;  // local units a reprojected depth may differ by
  glm::dmat4 LastDeviceToLocal; // the camera the last image was seen with
  glm::dmat4 DeviceToLocal;     // this frame's

private:
  vtkNew<vtkTextureObject> Color[2];
  vtkNew<vtkTextureObject> Depth[2];
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  int Last = 0;
  int Size[2] = { 0, 0 };
  long long Bytes = 0;
  std::vector<double> Content;
};

} // namespace cloudvis

#endif
