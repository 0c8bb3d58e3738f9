// The per-light optical-depth volumes of vtkCloudVolumeMapper (issue 12,
// filters/CloudLightVolumes.h states the grid): one 3-D float texture holding every light's block,
// computed on the GPU by a pass over its slices (shaders/CloudLightVolumeFS.glsl, rendered into one
// layer of the texture at a time) when anything it depends on changed, and read by the march once
// per sample per light. Its memory goes through the mapper's GpuMemoryBudget. Private to the
// module.
#ifndef CloudLightVolumeTexture_h
#define CloudLightVolumeTexture_h

#include "CloudVolumePass.h"
#include "CloudVolumeSources.h"

#include <vtkNew.h>
#include <vtkTextureObject.h>

#include <memory>
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkWindow;

namespace cloudvis
{
class GpuMemoryBudget;
struct MarchUniforms;

class LightVolumeTexture
{
public:
  LightVolumeTexture();
  ~LightVolumeTexture();

  // What the pass reads besides the uniforms: the march's textures and empty-space settings.
  using Inputs = VolumePassInputs;

  // Recomputes the volumes for u's lights when the field, the table, the extinction, the step,
  // the geometry or the lights changed since the last time: false with `problem` when the
  // texture cannot be allocated or the pass cannot run.
  bool Update(vtkOpenGLRenderWindow* window,
    const MarchUniforms& u,
    const Inputs& inputs,
    GpuMemoryBudget& budget,
    std::string& problem);

  // True when the volumes hold what u and inputs ask for except the lights, which moved (or came
  // or went) since they were computed: Update would recompute them for the lights alone. While
  // the view is interacting the mapper then marches toward the lights instead (a light that
  // follows the camera would otherwise recompute them every frame).
  bool OnlyLightsChanged(const MarchUniforms& u, const Inputs& inputs) const;

  // Binds the texture and sets the march's uniforms that read it (LightVolumeTexture,
  // LightVolumeSize, LightVolumeCount); Deactivate after the draw.
  void Activate(vtkShaderProgram* march);
  void Deactivate();

  vtkTextureObject* GetTexture() { return this->Texture; }
  long long GetBytes() const { return this->Bytes; }
  // How many times the volumes were computed (the tests check they are not recomputed per frame).
  int GetComputeCount() const { return this->ComputeCount; }
  void Release(vtkWindow* window);

private:
  bool Compute(vtkOpenGLRenderWindow* window,
    const MarchUniforms& u,
    const Inputs& inputs,
    std::string& problem);

  vtkNew<vtkTextureObject> Texture;
  VolumePass Pass;
  VolumeSources InputSources; // what the volumes were computed for, lights apart
  VolumeSources LightSources;
  int Size[3] = { 0, 0, 0 }; // one light's block
  int Lights = 0;
  long long Bytes = 0;
  int ComputeCount = 0;
};

} // namespace cloudvis

#endif
