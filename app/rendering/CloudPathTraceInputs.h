// What vtkCloudVolumeMapper's "pathtrace" lighting model needs beyond the march's textures and
// uniforms: the fragment shader's lighting source (shaders/CloudLightingPathTraceFS.glsl, a main()
// of its own that calls the shared source's TracePath, shaders/transport/PathTrace.glsl), the
// per-brick extinction bounds texture (the majorants and minorants of the occupancy filter's
// bricks) and the path-trace uniforms: the GPU's side of vtkCloudPathTracer's set-up. Private
// to the module.
#ifndef CloudPathTraceInputs_h
#define CloudPathTraceInputs_h

#include "CloudLightingParameters.h"
#include "CloudVolumeSources.h"

#include <vtkNew.h>
#include <vtkTextureObject.h>
#include <vtkType.h>

#include <string>

class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkWindow;

namespace cloudvis
{
class GpuMemoryBudget;

// The lighting source of the path-trace model, spliced at CloudMarchFS.glsl's lighting tag.
std::string PathTraceLightingSource();

// The per-brick (minorant, majorant) of sigma_t per world unit, an RG32F 3-D texture read with
// texelFetch, from the occupancy filter's output (its "min_extinction" and "max_extinction"),
// uploaded again when that output changes.
class ExtinctionBoundsTexture
{
public:
  bool Update(vtkOpenGLRenderWindow* window,
    vtkImageData* bricks,
    GpuMemoryBudget& budget,
    std::string& problem);
  vtkTextureObject* GetTexture() { return this->Texture; }
  long long GetBytes() const { return this->Bytes; }
  void Release(vtkWindow* window);

private:
  vtkNew<vtkTextureObject> Texture;
  VolumeSources Sources; // the bricks' MTime
  long long Bytes = 0;
};

// The path-trace uniforms of one frame: samples SampleBase .. SampleBase + SamplesPerFrame - 1
// of every pixel of a march target MarchWidth wide.
struct PathTraceFrame
{
  int MaxBounces = PathTraceBounceCap;
  int Seed = 0;
  int SampleBase = 0;
  int SamplesPerFrame = 1;
  int MarchWidth = 1;
  int LightGuidedNextEvents = 0; // PathTraceUniforms' (filters/CloudTransport.h)
};
void SetPathTraceUniforms(vtkShaderProgram* program, const PathTraceFrame& frame);

} // namespace cloudvis

#endif
