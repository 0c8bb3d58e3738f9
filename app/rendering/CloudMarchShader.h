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

// A float as a GLSL literal that reads back as the same float.
std::string GlslFloat(float value);

// The fragment shader's source for a lighting model and the kinds of the lights (positional or
// directional, in order).
std::string MarchShaderSource(LightingModel model, const std::vector<LocalLight>& lights);

// Uploads every uniform SetUpMarch computed: the geometry, the density texels' scale and bias,
// the table's range, the step, the lighting parameters and the lights (arrays of
// LightingLimits::MaxLights, unused entries zero).
void SetMarchUniforms(vtkShaderProgram* program, const MarchUniforms& uniforms);

// One compiled march program per lighting model and kind of lights ("2:DP": march with a
// directional and a point light), built on first use.
class MarchPrograms
{
public:
  MarchPrograms();
  ~MarchPrograms();
  // The program made current, or null when it fails to compile or link.
  vtkShaderProgram* Ready(vtkOpenGLRenderWindow* window,
    LightingModel model,
    const std::vector<LocalLight>& lights);
  // The quad the last Ready() made current draws with.
  void Render();
  void Release();

private:
  std::map<std::string, std::unique_ptr<vtkOpenGLQuadHelper>> Programs;
  vtkOpenGLQuadHelper* Current = nullptr;
};

} // namespace cloudvis

#endif
