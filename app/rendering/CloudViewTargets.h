// What vtkCloudVolumeMapper keeps for one renderer: the opaque scene's depth (full viewport), the
// march's float targets (at the march's resolution) and their framebuffer, the state of the
// progressive accumulation, and the temporal reprojection's history (CloudTemporalHistory.h). The
// targets hold the SUM of the accumulated frames (additive blending, no blend constant to keep
// outside vtkOpenGLState); readers divide by the frame count. Private to the module.
#ifndef CloudViewTargets_h
#define CloudViewTargets_h

#include "CloudTemporalHistory.h"

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

class ViewTargets
{
public:
  enum Target
  {
    Color = 0,  // premultiplied radiance and opacity, RGBA32F
    Counts = 1, // samples taken, useful samples, depth of the cloud, opacity-weighted depth sum
                // (the path tracer: 1 where the frame's paths ran whole, CountCutPathTracePixels)
    Moments = 2 // the path tracer's mean square of its samples, RGBA32F (only when allocated)
  };

  // (Re)allocates what the viewport and the march size need; a change restarts accumulation.
  bool Resize(vtkOpenGLRenderWindow* window,
    int viewportWidth,
    int viewportHeight,
    int marchWidth,
    int marchHeight,
    GpuMemoryBudget& budget,
    std::string& problem);
  // Copies the opaque scene's depth from the current framebuffer (the rays end there).
  void CopyDepth(const int viewport[4]);
  // Accumulation goes on while `signature` (what the image depends on) holds; else restarts.
  void Continue(const std::vector<double>& signature);

  // Allocates the moment target at the march size (the path tracer's second moments), or keeps
  // it; Resize releases it when the march size changes.
  bool AllocateMoments(vtkOpenGLRenderWindow* window,
    GpuMemoryBudget& budget,
    std::string& problem);
  // Frees the moment target (a model other than the path tracer needs none).
  void ReleaseMoments(vtkWindow* window);

  // Draws into both march targets, and the moment target as a third with `moments`; false
  // (bindings restored) when the framebuffer is incomplete.
  bool BindTargets(vtkOpenGLRenderWindow* window, bool moments = false);
  void UnbindTargets(vtkOpenGLRenderWindow* window);

  // The mean over the accumulated frames of one target, rows bottom to top. False when nothing
  // has been drawn.
  bool Read(vtkOpenGLRenderWindow* window,
    Target target,
    std::vector<float>& values,
    int& width,
    int& height);

  vtkTextureObject* GetDepth() { return this->Depth; }
  vtkTextureObject* GetTarget(Target target)
  {
    return target == Color ? this->ColorTexture
                           : (target == Counts ? this->CountTexture : this->MomentTexture);
  }
  const int* GetMarchSize() const { return this->MarchSize; }
  long long GetBytes() const
  {
    return this->DepthBytes + this->TargetBytes + this->MomentBytes + this->History.GetBytes();
  }
  void Release(vtkWindow* window);

  int AccumulatedFrames = 0;
  double SecondsPerPixel = 0.0;   // measured march cost, for the interactive scale
  double MostSamplesPerRay = 1.0; // a ray across the whole volume: full scale of the count view
  double LocalUnit = 1.0;         // world units per local unit of the march's frame, for depths
  bool PathTraced = false;        // the accumulated frames are the path tracer's
  int SamplesPerFrame = 1;        // samples per pixel in each accumulated frame (path tracer)
  bool Marched = false;           // this frame added a march frame (else the targets held)
  TemporalHistory History;        // allocated only while temporal reprojection is on

private:
  vtkNew<vtkTextureObject> Depth;
  vtkNew<vtkTextureObject> ColorTexture;
  vtkNew<vtkTextureObject> CountTexture;
  vtkNew<vtkTextureObject> MomentTexture;
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  int ViewportSize[2] = { 0, 0 };
  int MarchSize[2] = { 0, 0 };
  std::vector<double> Signature;
  long long DepthBytes = 0;
  long long TargetBytes = 0;
  long long MomentBytes = 0;
  int AttachedTargets = 2;
};

} // namespace cloudvis

#endif
