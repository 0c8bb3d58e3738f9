// The multiple-scattering volume of vtkCloudVolumeMapper (issue 21; filters/CloudScatteringVolume.h
// states the grids, the solve and the order of its passes): the textures of every grid, from the
// coarsest to the finest, computed on the GPU by fragment passes (shaders/CloudScatteringVolume
// {VS,GS,FS}.glsl, with the shared source's texel functions, as the CPU's ComputeScatteringVolume
// runs them) when anything it depends on changed, one draw per pass. A grid's textures are 2-D
// atlases of its layers: llvmpipe shares a draw among its threads by 64 x 64 tiles of the target,
// and a grid's layer (33 x 33 texels for a 128^3 field) is one, so a 3-D texture's layers would be
// computed on one thread. The last pass writes the finest grid's fluence and flux into 3-D
// textures, all layers in one instanced draw, for the march to read once per sample with the
// texture unit's interpolation. Its memory goes through the mapper's GpuMemoryBudget.
//
// A recompute may be spread over frames (progressive, for the viewer): each Update then runs the
// passes a time budget allows, and the march meanwhile reads the last finished volume, which a
// finished computation replaces at once (the march never reads a half-solved one, which would be
// too dark until the sweeps had carried the light in). Private to the module.
#ifndef CloudScatteringVolumeTexture_h
#define CloudScatteringVolumeTexture_h

#include "CloudLightVolumeTexture.h"

#include <vtkSmartPointer.h>

#include <memory>
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

namespace cloudvis
{
class GpuMemoryBudget;
struct MarchUniforms;

class ScatteringVolumeTexture
{
public:
  ScatteringVolumeTexture();
  ~ScatteringVolumeTexture();

  // What the passes read besides the uniforms: the light volumes' inputs, and the light volumes
  // themselves when the march reads them (null: the source marches toward each light).
  struct Inputs : LightVolumeTexture::Inputs
  {
    LightVolumeTexture* LightVolumes = nullptr;
  };

  // Brings the volume up to date with u and inputs: the field, the table, the extinction, the
  // geometry, the phase, the albedo (the table's), the lights, the light volumes it read and the
  // optical depths from outside the field. With
  // `seconds` > 0 and a finished volume of the same size to show meanwhile, a recompute runs
  // passes for about that long per call and goes on in the next calls (IsConverging); otherwise
  // it runs to the end. False with `problem` when the textures cannot be allocated or a pass
  // cannot run.
  bool Update(vtkOpenGLRenderWindow* window,
    const MarchUniforms& u,
    const Inputs& inputs,
    GpuMemoryBudget& budget,
    std::string& problem,
    double seconds = 0.0);

  // Whether a recompute is under way (the march reads the last finished volume), and its
  // progress: the steps run and the steps in all (a step: a pass over some of a grid's layers).
  bool IsConverging() const { return this->Next < this->Steps.size(); }
  int GetStepsDone() const { return int(this->Next); }
  int GetStepCount() const { return int(this->Steps.size()); }

  // Binds the finished volume's fluence and flux for the march (ScatteringVolumeTexture,
  // ScatteringFluxTexture); ScatteringVolumeOn and ScatteringVolumeSize come with the march's
  // uniforms (MarchUniforms::ScatteringVolumeTextures). Deactivate after the draw.
  void Activate(vtkShaderProgram* march);
  void Deactivate();

  long long GetBytes() const { return this->Bytes; }
  // How many volumes were finished (the tests check they are not recomputed per frame); each
  // replaces the one the march reads.
  int GetComputeCount() const { return this->ComputeCount; }
  // The wall time of the last finished computation, from its first pass to its last, in seconds
  // (a progressive one: the passes' own time, not the frames between them).
  double GetLastComputeSeconds() const { return this->LastComputeSeconds; }
  void Release(vtkWindow* window);

private:
  struct Grid;
  // One draw: a pass over some of a grid's rows of atlas tiles, or of the finished volume's
  // layers (all of them unless progressive).
  struct Step
  {
    int Level = 0;
    int Pass = 0;
    int Parity = 0;
    int First = 0;
    int Count = 0;
  };

  bool Allocate(vtkOpenGLRenderWindow* window,
    const MarchUniforms& u,
    GpuMemoryBudget& budget,
    std::string& problem);
  void Plan(const MarchUniforms& u, bool progressive);
  bool Run(vtkOpenGLRenderWindow* window,
    const MarchUniforms& u,
    const Inputs& inputs,
    double seconds,
    std::string& problem);
  // One pass; the samplers it does not read name unit `unreadUnit` (a 3-D texture's).
  bool RunStep(vtkOpenGLRenderWindow* window, const Step& step, int unreadUnit);
  void Finish();

  std::vector<Grid> Grids; // coarsest first
  // The finished volume the march reads, 3-D: the finest grid's fluence and flux, and the two the
  // computation under way writes in its last pass, swapped in when it ends.
  vtkSmartPointer<vtkTextureObject> Fluence, Flux, NextFluence, NextFlux;
  vtkSmartPointer<vtkTextureObject> Unread; // 1 x 1, 2-D: what the unread atlas samplers name
  bool Finished = false;
  bool Progressive = false; // the computation under way is spread over frames
  VolumePass Pass;
  VolumeSources Sources;         // what the volume (finished or under way) is computed for
  std::vector<Step> Steps;       // the computation's passes, in order
  std::size_t Next = 0;          // the next of Steps to run
  double Seconds = 0.0;          // spent on the computation under way
  long long Bytes = 0;
  int ComputeCount = 0;
  double LastComputeSeconds = 0.0;
};

} // namespace cloudvis

#endif
