#include "CloudMarchShader.h"

#include "CloudMarchUniforms.h"
#include "CloudPathTraceInputs.h"
#include "CloudTransport.h"
#include "CloudTransportUniforms.h"

#include "CloudMarchFS.h"
#include "CloudTransportAccessors.h"
#include "CloudTransportDropletPhase.h"
#include "CloudTransportLightMarch.h"
#include "CloudTransportLightingModels.h"
#include "CloudTransportMedium.h"
#include "CloudTransportPathTrace.h"
#include "CloudTransportPhase.h"
#include "CloudTransportPrelude.h"
#include "CloudTransportScattering.h"

#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkShaderProgram.h>

#include <glm/gtc/type_ptr.hpp>

#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace cloudvis
{
namespace
{

// A float as a GLSL literal that reads back as the same float.
std::string GlslFloat(float value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(value));
  std::string literal = text;
  if (literal.find_first_of(".e") == std::string::npos)
  {
    literal += ".0";
  }
  return literal;
}
constexpr int MaxLights = LightingLimits::MaxLights;

// A glsl::Transport member as the uniform of its name, by its type (the GLSL's: the same
// declaration). vtkShaderProgram takes the matrices by non-const pointer, hence the copies.
void UploadUniform(vtkShaderProgram* program, const char* name, int value)
{
  program->SetUniformi(name, value);
}
void UploadUniform(vtkShaderProgram* program, const char* name, float value)
{
  program->SetUniformf(name, value);
}
void UploadUniform(vtkShaderProgram* program, const char* name, const glm::vec3& value)
{
  program->SetUniform3f(name, glm::value_ptr(value));
}
void UploadUniform(vtkShaderProgram* program, const char* name, glm::mat3 value)
{
  program->SetUniformMatrix3x3(name, glm::value_ptr(value));
}
void UploadUniform(vtkShaderProgram* program, const char* name, glm::mat4 value)
{
  program->SetUniformMatrix4x4(name, glm::value_ptr(value));
}
void UploadUniform(vtkShaderProgram* program, const char* name, const int (&values)[MaxLights])
{
  program->SetUniform1iv(name, MaxLights, values);
}
void UploadUniform(vtkShaderProgram* program,
  const char* name,
  const glm::vec3 (&values)[MaxLights])
{
  program->SetUniform3fv(name, MaxLights, glm::value_ptr(values[0]));
}

// The constants the GLSL shares with the C++, from their one definition, the program's variant of
// the march loop, its phase, and its switches when they are constants of the program (null: they
// stay uniforms, as the volume passes have them; SetMarchUniforms sets them for those).
std::string Constants(int samplesPerMapRead, PhaseModel phase, const MarchSwitches* switches)
{
  std::ostringstream glsl;
  if (switches)
  {
    glsl << "#define LightTransmittanceVolumes " << int(switches->LightVolumes) << "\n"
         << "#define ScatteringVolumeOn " << int(switches->ScatteringVolume) << "\n"
         << "#define ExternalOpticalDepths " << int(switches->ExternalDepths) << "\n"
         << "#define ExternalScatteringVolume " << int(switches->ExternalScattering) << "\n";
  }
  glsl << "#define MAX_LIGHTS " << MaxLights << "\n"
       << "#define PhaseType " << int(phase) << "\n"
       << "#define SAMPLES_PER_MAP_READ " << samplesPerMapRead << "\n"
       << "const float Pi = " << GlslFloat(Pi) << ";\n"
       << "const float PhaseToRadiance = " << GlslFloat(PhaseToRadiance) << ";\n"
       << "const float DirectionalLightDistance = " << GlslFloat(DirectionalLightDistance) << ";\n"
       << "const float LightBoxMargin = " << GlslFloat(LightBoxMargin) << ";\n"
       << "const float DiffuseEscapeSpeed = " << GlslFloat(DiffuseEscapeSpeed) << ";\n"
       << "const float RatioTrackingRouletteThreshold = "
       << GlslFloat(RatioTrackingRouletteThreshold) << ";\n"
       << "const float NoCrossing = " << GlslFloat(NoCrossing) << ";\n"
       << "const int MaxTentativeCollisions = " << MaxTentativeCollisions << ";\n"
       << "const float GaveUp = " << GlslFloat(GaveUp) << ";\n"
       << "const int MaxWalkSteps = " << MaxWalkSteps << ";\n"
       << "const float NoDepth = " << GlslFloat(NoDepth) << ";\n"
       << "const float DepthTransmittance = " << GlslFloat(DepthTransmittance) << ";\n"
       << "const int PhaseTwoLobe = " << PhaseTwoLobe << ";\n"
       << "const int PhaseDroplets = " << PhaseDroplets << ";\n"
       << "const int DropletPhaseNodeCount = " << DropletPhaseNodeCount << ";\n";
  return glsl.str();
}

// The shared light transport: the GLSL prelude, the source the CPU compiles too (in the order
// GLSL needs: a function before its callers), and the GPU's accessors (docs/transport.md).
std::string TransportSource()
{
  std::string source = CloudTransportPrelude;
  for (const char* file : { CloudTransportDropletPhase,
         CloudTransportMedium,
         CloudTransportPhase,
         CloudTransportLightMarch,
         CloudTransportLightingModels,
         CloudTransportPathTrace,
         CloudTransportScattering,
         CloudTransportAccessors })
  {
    source += std::string("\n") + file;
  }
  return source;
}

// The lighting model's SourceTerm, which calls the model's term of each light (the shared
// source's <Model>PointTerm or <Model>DirectionalTerm) with a constant index, so no light loop
// runs per sample; the path tracer's main() instead.
std::string LightingSource(LightingModel model, const std::vector<LocalLight>& lights)
{
  if (model == LightingModel::PathTrace)
  {
    return PathTraceLightingSource(); // with a main() of its own
  }
  std::ostringstream source;
  source << "vec3 SourceTerm(vec3 p, float density, vec3 albedo, vec3 d)\n{\n";
  if (model == LightingModel::None)
  {
    source << "  return SourceTermNone(p, density, albedo, d);\n}\n";
    return source.str();
  }
  const char* prefix = model == LightingModel::Derivative ? "Derivative" : "March";
  source << "  vec3 light = Ambient;\n";
  for (size_t i = 0; i < lights.size(); ++i)
  {
    source << "  light += " << prefix << (lights[i].Positional ? "PointTerm" : "DirectionalTerm")
           << "(" << i << ", p, density, albedo, d);\n";
  }
  if (model == LightingModel::March) // orders two and up, as the CPU's SourceTerm adds them
  {
    source << "  if (ScatteringVolumeOn != 0) light += MultipleScatteringTerm(p, d);\n";
  }
  source << "  return albedo * light;\n}\n";
  return source.str();
}

std::string ShaderSource(LightingModel model,
  const std::vector<LocalLight>& lights,
  int samplesPerMapRead,
  PhaseModel phase,
  const MarchSwitches* switches)
{
  std::string source = CloudMarchFS;
  vtkShaderProgram::Substitute(
    source, "//CLOUD::Constants::Dec", Constants(samplesPerMapRead, phase, switches));
  vtkShaderProgram::Substitute(source, "//CLOUD::Transport::Dec", TransportSource());
  vtkShaderProgram::Substitute(source, "//CLOUD::Lighting::Dec", LightingSource(model, lights));
  return source;
}
}

int SamplesPerMapRead(double occupiedBrickFraction)
{
  return occupiedBrickFraction >= DenseOccupiedBrickFraction ? DenseSamplesPerMapRead : 1;
}

MarchSwitches MarchSwitchesOf(const MarchUniforms& uniforms, bool lightVolumes)
{
  const glsl::Transport t = TransportOf(uniforms);
  MarchSwitches switches;
  switches.Phase = uniforms.Lighting.Phase;
  switches.LightVolumes = lightVolumes;
  switches.ScatteringVolume = t.ScatteringVolumeOn != 0;
  switches.ExternalDepths = t.ExternalOpticalDepths != 0;
  switches.ExternalScattering = t.ExternalScatteringVolume != 0;
  return switches;
}

namespace
{

// The fragment shader's source for a lighting model, the kinds of the lights (positional or
// directional, in order), the samples the march takes per reading of the occupancy map and the
// switches (the phase function's among them: the two lobes' programs hold none of the droplets'
// table code).
std::string MarchShaderSource(LightingModel model,
  const std::vector<LocalLight>& lights,
  int samplesPerMapRead,
  const MarchSwitches& switches)
{
  return ShaderSource(model, lights, samplesPerMapRead, switches.Phase, &switches);
}
} // namespace

std::string PassShaderSource(
  const std::vector<LocalLight>& lights, PhaseModel phase, const std::string& passMain)
{
  std::string source = ShaderSource(LightingModel::March, lights, 1, phase, nullptr);
  const std::string marchMain = "#ifndef CLOUD_OWN_MAIN";
  const std::size_t at = source.rfind(marchMain);
  if (at == std::string::npos)
  {
    throw std::logic_error("the march shader has no \"" + marchMain + "\" around its main()");
  }
  return source.insert(at, "#define CLOUD_OWN_MAIN\n") + passMain;
}

void SetMarchUniforms(vtkShaderProgram* program, const MarchUniforms& u)
{
  // Every uniform of the transport, from the member of the CPU's glsl::Transport of the same
  // name (CloudTransportUniforms.h lists them from their declarations): TransportOf is the one
  // mapping from the march's set-up to them. A program without one of them (a switch that is a
  // constant of it, a term it does not call) ignores its upload; the passes and the path tracer
  // set theirs after this.
  const glsl::Transport t = TransportOf(u);
#define CLOUD_UPLOAD_UNIFORM(name) UploadUniform(program, #name, t.name);
  CLOUD_TRANSPORT_UNIFORMS(CLOUD_UPLOAD_UNIFORM)
#undef CLOUD_UPLOAD_UNIFORM

  // The march loop's own (CloudMarchFS.glsl).
  const float tableRange[2] = { float(u.Table->Range[0]), float(u.Table->Range[1]) };
  program->SetUniform2f("TableRange", tableRange);
  program->SetUniformf("TableSize", float(u.Table->Size));
  program->SetUniformf("Step", u.Step);
  program->SetUniformf("TerminationTransmittance", u.TerminationTransmittance);
}

MarchPrograms::MarchPrograms() = default;
MarchPrograms::~MarchPrograms() = default;

vtkShaderProgram* MarchPrograms::Ready(vtkOpenGLRenderWindow* window,
  LightingModel model,
  const std::vector<LocalLight>& lights,
  int samplesPerMapRead,
  const MarchSwitches& switches)
{
  std::string key = std::to_string(int(model)) + ":" + std::to_string(samplesPerMapRead) + ":" +
    std::to_string(int(switches.Phase)) + ":" + std::to_string(int(switches.LightVolumes)) +
    std::to_string(int(switches.ScatteringVolume)) + std::to_string(int(switches.ExternalDepths)) +
    std::to_string(int(switches.ExternalScattering)) + ":";
  if (model != LightingModel::None)
  {
    for (const LocalLight& light : lights)
    {
      key += light.Positional ? 'P' : 'D';
    }
  }
  std::unique_ptr<vtkOpenGLQuadHelper>& quad = this->Programs[key];
  if (!quad)
  {
    quad = std::make_unique<vtkOpenGLQuadHelper>(
      window, nullptr, MarchShaderSource(model, lights, samplesPerMapRead, switches).c_str(), "");
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(quad->Program);
  }
  this->Current = quad.get();
  this->CurrentSamplesPerMapRead = samplesPerMapRead;
  vtkShaderProgram* program = quad->Program;
  return program && program->GetCompiled() ? program : nullptr;
}

void MarchPrograms::Render()
{
  this->Current->Render();
}

void MarchPrograms::Release()
{
  this->Programs.clear();
  this->Current = nullptr;
}

} // namespace cloudvis
