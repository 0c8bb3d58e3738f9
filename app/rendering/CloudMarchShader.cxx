#include "CloudMarchShader.h"

#include "CloudMarchUniforms.h"
#include "CloudPathTracePass.h"

#include "CloudLightingCommon.h"
#include "CloudLightingDerivative.h"
#include "CloudLightingMarch.h"
#include "CloudLightingNone.h"
#include "CloudMarchFS.h"

#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkShaderProgram.h>

#include <glm/gtc/type_ptr.hpp>

#include <cstdio>
#include <sstream>

namespace cloudvis
{
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

namespace
{
constexpr int MaxLights = LightingLimits::MaxLights;

// The constants the GLSL shares with the C++, from their one definition, and the program's
// variant of the march loop.
std::string Constants(int samplesPerMapRead)
{
  std::ostringstream glsl;
  glsl << "#define MAX_LIGHTS " << MaxLights << "\n"
       << "#define SAMPLES_PER_MAP_READ " << samplesPerMapRead << "\n"
       << "const float Pi = " << GlslFloat(Pi) << ";\n"
       << "const float DirectionalLightDistance = " << GlslFloat(DirectionalLightDistance) << ";\n"
       << "const float LightBoxMargin = " << GlslFloat(LightBoxMargin) << ";\n"
       << "const float NoDepth = " << GlslFloat(NoDepth) << ";\n"
       << "const float DepthTransmittance = " << GlslFloat(DepthTransmittance) << ";\n";
  return glsl.str();
}

// The lighting model's GLSL: shared helpers, the model's light terms, and a SourceTerm that
// calls one term per light with a constant index.
std::string LightingSource(LightingModel model, const std::vector<LocalLight>& lights)
{
  if (model == LightingModel::None)
  {
    return std::string(CloudLightingCommon) + "\n" + CloudLightingNone;
  }
  if (model == LightingModel::PathTrace)
  {
    return PathTraceLightingSource(); // with a main() of its own
  }
  std::ostringstream source;
  source << CloudLightingCommon << "\n"
         << (model == LightingModel::Derivative ? CloudLightingDerivative : CloudLightingMarch)
         << "\nvec3 SourceTerm(vec3 p, float density, vec3 albedo, vec3 d)\n{\n"
         << "  vec3 light = Ambient;\n";
  for (size_t i = 0; i < lights.size(); ++i)
  {
    source << "  light += " << (lights[i].Positional ? "PointLightTerm" : "DirectionalLightTerm")
           << "(" << i << ", p, density, albedo, d);\n";
  }
  source << "  return albedo * light;\n}\n";
  return source.str();
}
}

int SamplesPerMapRead(double occupiedBrickFraction)
{
  return occupiedBrickFraction >= DenseOccupiedBrickFraction ? DenseSamplesPerMapRead : 1;
}

std::string MarchShaderSource(LightingModel model,
  const std::vector<LocalLight>& lights,
  int samplesPerMapRead)
{
  std::string source = CloudMarchFS;
  vtkShaderProgram::Substitute(source, "//CLOUD::Constants::Dec", Constants(samplesPerMapRead));
  vtkShaderProgram::Substitute(source, "//CLOUD::Lighting::Dec", LightingSource(model, lights));
  return source;
}

void SetMarchUniforms(vtkShaderProgram* program, const MarchUniforms& u)
{
  const float dims[3] = { float(u.Dimensions.x), float(u.Dimensions.y), float(u.Dimensions.z) };
  program->SetUniform3f("Dimensions", dims);
  program->SetUniformMatrix4x4("IndexToLocal", const_cast<float*>(glm::value_ptr(u.IndexToLocal)));
  program->SetUniformMatrix3x3("LocalToIndex", const_cast<float*>(glm::value_ptr(u.LocalToIndex)));
  program->SetUniformf("DensityScale", u.Density.Scale);
  program->SetUniformf("DensityBias", u.Density.Bias);
  const float tableRange[2] = { float(u.Table->Range[0]), float(u.Table->Range[1]) };
  program->SetUniform2f("TableRange", tableRange);
  program->SetUniformf("TableSize", float(u.Table->Size));
  program->SetUniformf("ExtinctionUnit", u.ExtinctionUnit);
  program->SetUniformf("Step", u.Step);
  program->SetUniformf("TerminationTransmittance", u.TerminationTransmittance);

  // The lights, packed into the GLSL's arrays.
  std::vector<int> positional(MaxLights, 0);
  std::vector<float> position(3 * MaxLights, 0.0f), direction(3 * MaxLights, 0.0f),
    radiance(3 * MaxLights, 0.0f), attenuation(3 * MaxLights, 0.0f),
    indexDirection(3 * MaxLights, 0.0f), indexOffset(3 * MaxLights, 0.0f);
  const auto pack = [](std::vector<float>& array, size_t i, const glm::vec3& v)
  { std::copy(glm::value_ptr(v), glm::value_ptr(v) + 3, array.begin() + 3 * i); };
  for (size_t i = 0; i < u.Lights.size(); ++i)
  {
    const LocalLight& l = u.Lights[i];
    positional[i] = l.Positional ? 1 : 0;
    pack(position, i, l.Position);
    pack(direction, i, l.Direction);
    pack(radiance, i, l.Radiance);
    pack(attenuation, i, l.Attenuation);
    pack(indexDirection, i, l.IndexDirection);
    pack(indexOffset, i, l.IndexOffset);
  }
  program->SetUniform1iv("LightPositional", MaxLights, positional.data());
  program->SetUniform3fv("LightIndexDirection", MaxLights, indexDirection.data());
  program->SetUniform3fv("LightIndexOffset", MaxLights, indexOffset.data());
  program->SetUniform3fv("LightPosition", MaxLights, position.data());
  program->SetUniform3fv("LightDirection", MaxLights, direction.data());
  program->SetUniform3fv("LightRadiance", MaxLights, radiance.data());
  program->SetUniform3fv("LightAttenuation", MaxLights, attenuation.data());
  program->SetUniform3f("Ambient", glm::value_ptr(u.Ambient));

  const LightingParameters& p = u.Lighting;
  program->SetUniformf("DerivativeDistance", p.DerivativeDistance);
  program->SetUniformf("DerivativeSlopeScale", u.DerivativeSlopeScale);
  program->SetUniformi("LightSteps", p.LightSteps);
  program->SetUniformf("LightStep", p.LightStep);
  program->SetUniformf("LightStepGrowth", p.LightStepGrowth);
  program->SetUniformf("PhaseG1", p.PhaseG1);
  program->SetUniformf("PhaseG2", p.PhaseG2);
  program->SetUniformf("PhaseLobeWeight", p.PhaseLobeWeight);
  program->SetUniformi("MultipleScatteringOctaves", p.MultipleScatteringOctaves);
  program->SetUniformf("ScatteringFalloff", p.ScatteringFalloff);
  program->SetUniformf("ExtinctionFalloff", p.ExtinctionFalloff);
  program->SetUniformf("EccentricityFalloff", p.EccentricityFalloff);
  program->SetUniformf("PowderStrength", p.PowderStrength);
}

MarchPrograms::MarchPrograms() = default;
MarchPrograms::~MarchPrograms() = default;

vtkShaderProgram* MarchPrograms::Ready(vtkOpenGLRenderWindow* window,
  LightingModel model,
  const std::vector<LocalLight>& lights,
  int samplesPerMapRead)
{
  std::string key = std::to_string(int(model)) + ":" + std::to_string(samplesPerMapRead) + ":";
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
      window, nullptr, MarchShaderSource(model, lights, samplesPerMapRead).c_str(), "");
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
