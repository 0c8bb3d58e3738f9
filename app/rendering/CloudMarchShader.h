// The march pass's GLSL and uniforms for vtkCloudVolumeMapper. The fragment shader is
// shaders/CloudMarchFS.glsl with, spliced in, the constants the C++ defines (substituted, never
// repeated as literals: the light limit, pi, a directional light's distance, the path tracer's
// bounds, the depth channel's markers), the light transport shared with the CPU
// (shaders/transport/, docs/transport.md) and one lighting model's SourceTerm, which calls one
// term per light with a constant index, so no light loop runs per sample. Its uniforms are what
// cloudvis::SetUpMarch computed (the same MarchUniforms the CPU reference marches with), uploaded
// as they are. Private to the module.
#ifndef CloudMarchShader_h
#define CloudMarchShader_h

#include "CloudLighting.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;

namespace cloudvis
{
struct MarchUniforms;

// The depth channel of the count target: where a ray's transmittance first falls below
// DepthTransmittance (its opacity passes 2%); NoDepth where it never does.
constexpr float NoDepth = 1e30f;
constexpr float DepthTransmittance = 0.98f;

// The march reads the occupancy map before every sample where leaps are common, and before every
// fourth sample (DenseSamplesPerMapRead) in fields whose bricks are mostly occupied (at least
// DenseOccupiedBrickFraction), where a leap is rare and the map's read and the masked leap code
// dominate a sample's cost on SIMD rasterizers (docs/performance.md, "The march's loop
// variants"). The image is the same either way: a sample in an empty brick adds nothing.
constexpr double DenseOccupiedBrickFraction = 0.5;
constexpr int DenseSamplesPerMapRead = 4;
// The march loop's variant for a field with this fraction of occupied bricks: 1 or
// DenseSamplesPerMapRead.
int SamplesPerMapRead(double occupiedBrickFraction);

// The transport's switches that are constants of a march program rather than uniforms, as
// PhaseType is: on SIMD rasterizers a branch on a uniform runs both of its arms under masks, so
// the light volumes' read beside the nested march it stands for, the octaves beside the
// multiple-scattering volume's beam and the outside depths' read made the march with one light
// cost 4.4x `none` in instructions instead of 1.7x on llvmpipe (docs/performance.md, "Where the
// march's per-sample cost went"). A program is built for each combination a view uses.
struct MarchSwitches
{
  PhaseModel Phase = PhaseModel::TwoLobe;
  bool LightVolumes = false;       // LightTransmittanceVolumes: the light volumes are read
  bool ScatteringVolume = false;   // ScatteringVolumeOn: orders >= 2 from the volume
  bool ExternalDepths = false;     // ExternalOpticalDepths: depths from outside the field added
  bool ExternalScattering = false; // ExternalScatteringVolume: a whole field's volume is read
};
// The switches of a march with these uniforms (TransportOf's), the light volumes read or not
// (on the GPU they are textures the mapper holds, not MarchUniforms::LightDepths).
MarchSwitches MarchSwitchesOf(const MarchUniforms& uniforms, bool lightVolumes);

// The fragment shader of a pass over a light-transport volume (the light volumes, the
// multiple-scattering volume): the march's, with the march model's lighting for the lights'
// kinds, without its main() (CLOUD_OWN_MAIN, as for the path tracer), then the pass's `passMain`.
std::string PassShaderSource(
  const std::vector<LocalLight>& lights, PhaseModel phase, const std::string& passMain);

// Uploads every uniform SetUpMarch computed: the geometry, the density texels' scale and bias,
// the table's range, the step, the lighting parameters and the lights (arrays of
// LightingLimits::MaxLights, unused entries zero), and whether the march reads the
// multiple-scattering volume (MarchUniforms::ScatteringVolumeTextures) and its size.
void SetMarchUniforms(vtkShaderProgram* program, const MarchUniforms& uniforms);

// One compiled march program per lighting model, samples per map read, switches and kind of
// lights ("2:1:0:1010:DP": march, one sample per read, the two lobes, light volumes and the
// multiple-scattering volume, a directional and a point light), built on first use.
class MarchPrograms
{
public:
  MarchPrograms();
  ~MarchPrograms();
  // The program made current, or null when it fails to compile or link.
  vtkShaderProgram* Ready(vtkOpenGLRenderWindow* window,
    LightingModel model,
    const std::vector<LocalLight>& lights,
    int samplesPerMapRead,
    const MarchSwitches& switches);
  // The quad the last Ready() made current draws with.
  void Render();
  // The samples per map read of the program the last Ready() made current.
  int GetSamplesPerMapRead() const { return this->CurrentSamplesPerMapRead; }
  void Release();

private:
  std::map<std::string, std::unique_ptr<vtkOpenGLQuadHelper>> Programs;
  vtkOpenGLQuadHelper* Current = nullptr;
  int CurrentSamplesPerMapRead = 1;
};

} // namespace cloudvis

#endif
