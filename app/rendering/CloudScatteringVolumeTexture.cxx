#include "CloudScatteringVolumeTexture.h"

#include "CloudGpuMemory.h"
#include "CloudMarchShader.h"
#include "CloudMarchUniforms.h"
#include "CloudScatteringVolume.h"

#include "CloudScatteringVolumeFS.h"
#include "CloudScatteringVolumeGS.h"
#include "CloudScatteringVolumeVS.h"

#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkOpenGLVertexArrayObject.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtkTimerLog.h>
#include <vtk_glew.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <utility>

namespace cloudvis
{

namespace
{
// A progressive computation's most cells per step: about 4 ms of the relaxation's on llvmpipe
// (a frame runs as many steps as its time allows).
constexpr int CellsPerStep = 1 << 12;

// The passes of CloudScatteringVolumeFS.glsl, as its ScatteringPass numbers them.
enum PassNumber
{
  MediumPass = 0,
  SourcePass = 1,
  StartPass = 2,
  ProlongPass = 3,
  RelaxPass = 4,
  FluxPass = 5
};

// What the volume depends on, as numbers: when one changes it is computed again. The light
// volumes count by their computations (the source reads them).
std::vector<double> SignatureOf(const MarchUniforms& u, const ScatteringVolumeTexture::Inputs& in)
{
  const LightingParameters& p = u.Lighting;
  std::vector<double> s = { in.DensityTime,
    in.TableTime,
    double(in.BrickSize),
    double(in.SkipEmptySpace),
    double(u.ExtinctionUnit),
    double(u.Dimensions.x),
    double(u.Dimensions.y),
    double(u.Dimensions.z),
    double(p.PhaseG1),
    double(p.PhaseG2),
    double(p.PhaseLobeWeight),
    double(p.LightSteps),
    double(p.LightStep),
    double(p.LightStepGrowth),
    in.LightVolumes ? double(in.LightVolumes->GetComputeCount()) : -1.0 };
  s.insert(s.end(), glm::value_ptr(u.IndexToLocal), glm::value_ptr(u.IndexToLocal) + 16);
  s.insert(s.end(), glm::value_ptr(u.LocalToIndex), glm::value_ptr(u.LocalToIndex) + 9);
  for (const LocalLight& light : u.Lights)
  {
    s.push_back(light.Positional ? 1.0 : 0.0);
    for (const glm::vec3& v :
      { light.Position, light.Direction, light.Radiance, light.Attenuation, light.IndexDirection })
    {
      s.insert(s.end(), glm::value_ptr(v), glm::value_ptr(v) + 3);
    }
  }
  return s;
}

vtkSmartPointer<vtkTextureObject> NewGridTexture(vtkOpenGLRenderWindow* window, glm::ivec3 size)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  if (!texture->Allocate3D(size.x, size.y, size.z, 4, VTK_FLOAT))
  {
    return nullptr;
  }
  SetSampling(texture, vtkTextureObject::Linear, vtkTextureObject::ClampToEdge);
  return texture;
}
}

// One grid's textures: the medium, the source and its direction, two fluences (a half-sweep
// reads one and writes the other) and, on the finest grid, the flux.
struct ScatteringVolumeTexture::Grid
{
  glm::ivec3 Size{ 0 };
  glm::vec3 CellSize{ 0.0f }; // a cell's local length per axis (ScatteringCellSize)
  vtkSmartPointer<vtkTextureObject> Medium, Source, Direction, Flux;
  std::array<vtkSmartPointer<vtkTextureObject>, 2> Fluence;
  int Current = 0; // the fluence holding the latest values

  // Every texture it holds (the coarser grids have no flux: null).
  std::array<vtkTextureObject*, 6> Textures() const
  {
    return {
      this->Medium, this->Source, this->Direction, this->Fluence[0], this->Fluence[1], this->Flux
    };
  }
};

ScatteringVolumeTexture::ScatteringVolumeTexture() = default;
ScatteringVolumeTexture::~ScatteringVolumeTexture() = default;

bool ScatteringVolumeTexture::Update(vtkOpenGLRenderWindow* window,
  const MarchUniforms& u,
  const Inputs& inputs,
  GpuMemoryBudget& budget,
  std::string& problem,
  double seconds)
{
  std::vector<double> signature = SignatureOf(u, inputs);
  if (signature != this->Signature || this->Grids.empty())
  {
    if (!this->Allocate(window, u, budget, problem))
    {
      return false;
    }
    this->Signature = std::move(signature);
    // Without a finished volume to show meanwhile, the march waits for this one.
    this->Progressive = this->Finished && seconds > 0.0;
    this->Plan(u, this->Progressive);
  }
  if (!this->IsConverging())
  {
    return true;
  }
  if (!this->Run(window, u, inputs, this->Progressive ? seconds : 0.0, problem))
  {
    this->Signature.clear();
    this->Steps.clear();
    this->Next = 0;
    return false;
  }
  return true;
}

bool ScatteringVolumeTexture::Allocate(vtkOpenGLRenderWindow* window,
  const MarchUniforms& u,
  GpuMemoryBudget& budget,
  std::string& problem)
{
  const std::vector<glm::ivec3> sizes = ScatteringGrids(u.Dimensions);
  bool same = sizes.size() == this->Grids.size() && this->Fluence;
  for (std::size_t level = 0; same && level < sizes.size(); ++level)
  {
    same = sizes[level] == this->Grids[level].Size;
  }
  if (same)
  {
    return true;
  }
  const long long held = this->Bytes;
  this->Release(window);
  GLint largest = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &largest);
  const glm::ivec3 finest = sizes.back();
  if (finest.x > largest || finest.y > largest || finest.z > largest)
  {
    problem = "the multiple-scattering volume needs a 3-D texture of " + std::to_string(finest.x) +
      " x " + std::to_string(finest.y) + " x " + std::to_string(finest.z) +
      " texels, more than this GPU's " + std::to_string(largest) + " per axis";
    budget.Release(held);
    return false;
  }
  // RGBA32F: five textures per grid, the flux on the finest, and the finished fluence and flux.
  long long texels = 0;
  for (const glm::ivec3& size : sizes)
  {
    texels += 5LL * size.x * size.y * size.z;
  }
  texels += 3LL * finest.x * finest.y * finest.z;
  std::vector<Grid> grids(sizes.size());
  problem = budget.Allocate("the multiple-scattering volume",
    16 * texels,
    held,
    [&]()
    {
      for (std::size_t level = 0; level < sizes.size(); ++level)
      {
        Grid& grid = grids[level];
        grid.Size = sizes[level];
        grid.Medium = NewGridTexture(window, grid.Size);
        grid.Source = NewGridTexture(window, grid.Size);
        grid.Direction = NewGridTexture(window, grid.Size);
        grid.Fluence = { NewGridTexture(window, grid.Size), NewGridTexture(window, grid.Size) };
        if (!grid.Medium || !grid.Source || !grid.Direction || !grid.Fluence[0] || !grid.Fluence[1])
        {
          return false;
        }
      }
      grids.back().Flux = NewGridTexture(window, finest);
      this->Fluence = NewGridTexture(window, finest);
      this->Flux = NewGridTexture(window, finest);
      return grids.back().Flux && this->Fluence && this->Flux;
    });
  this->Grids = std::move(grids);
  if (!problem.empty())
  {
    this->Release(window);
    budget.Release(held);
    return false;
  }
  this->Bytes = 0;
  for (const Grid& grid : this->Grids)
  {
    for (vtkTextureObject* texture : grid.Textures())
    {
      this->Bytes += texture ? TextureBytes(texture) : 0;
    }
  }
  this->Bytes += TextureBytes(this->Fluence) + TextureBytes(this->Flux);
  return true;
}

// The passes of ComputeScatteringVolume, in its order: per grid from the coarsest, the medium,
// the source, the first guess (the start on the coarsest, the coarser grid's fluence on the
// others), the sweeps' half-sweeps of parity 0 then 1, and on the finest grid the flux.
// A progressive computation splits each pass into layers of at most about CellsPerStep cells, so
// that a frame's share of the work is bounded whatever the field's size (a pass over a 256^3
// field's 65^3 finest grid takes about 0.3 s on llvmpipe); a whole one draws each pass at once.
void ScatteringVolumeTexture::Plan(const MarchUniforms& u, bool progressive)
{
  const ScatteringSolve solve;
  this->Steps.clear();
  for (Grid& grid : this->Grids)
  {
    grid.CellSize = ScatteringCellSize(u, grid.Size);
  }
  const auto add = [&](int level, int pass, int parity)
  {
    const glm::ivec3 size = this->Grids[std::size_t(level)].Size;
    const int layers = progressive ? std::max(1, CellsPerStep / (size.x * size.y)) : size.z;
    for (int first = 0; first < size.z; first += layers)
    {
      this->Steps.push_back({ level, pass, parity, first, std::min(layers, size.z - first) });
    }
  };
  for (int level = 0; level < int(this->Grids.size()); ++level)
  {
    add(level, MediumPass, 0);
    add(level, SourcePass, 0);
    add(level, level == 0 ? StartPass : ProlongPass, 0);
    const int sweeps = level == 0 ? solve.CoarsestSweeps : solve.SweepsPerGrid;
    for (int sweep = 0; sweep < sweeps; ++sweep)
    {
      add(level, RelaxPass, 0);
      add(level, RelaxPass, 1);
    }
  }
  add(int(this->Grids.size()) - 1, FluxPass, 0);
  this->Next = 0;
  this->Seconds = 0.0;
}

bool ScatteringVolumeTexture::Run(vtkOpenGLRenderWindow* window,
  const MarchUniforms& u,
  const Inputs& inputs,
  double seconds,
  std::string& problem)
{
  // The march's textures and uniforms for the texel functions (the source's march toward the
  // lights or its light volumes).
  vtkShaderProgram* program = this->Pass.Begin(window,
    u,
    inputs,
    { CloudScatteringVolumeFS, CloudScatteringVolumeVS, CloudScatteringVolumeGS },
    "multiple-scattering",
    problem);
  if (!program)
  {
    return false;
  }
  program->SetUniformi("LightTransmittanceVolumes", inputs.LightVolumes ? 1 : 0);
  if (inputs.LightVolumes)
  {
    inputs.LightVolumes->Activate(program);
  }
  else // never read, but a sampler must name a unit of its own type
  {
    program->SetUniformi("LightVolumeTexture", inputs.Density->GetTextureUnit());
  }

  const double start = vtkTimerLog::GetUniversalTime();
  bool complete = true;
  while (complete && this->IsConverging())
  {
    complete = this->RunStep(window, this->Steps[this->Next], inputs.Density->GetTextureUnit());
    ++this->Next;
    if (seconds > 0.0 && this->IsConverging())
    {
      window->WaitForCompletion(); // the passes' time, not what the driver has queued
      if (vtkTimerLog::GetUniversalTime() - start >= seconds)
      {
        break;
      }
    }
  }
  window->WaitForCompletion();
  this->Seconds += vtkTimerLog::GetUniversalTime() - start;
  if (inputs.LightVolumes)
  {
    inputs.LightVolumes->Deactivate();
  }
  this->Pass.End();
  if (!complete)
  {
    problem =
      "the multiple-scattering volume cannot be rendered into on this GPU (incomplete framebuffer)";
    return false;
  }
  if (!this->IsConverging())
  {
    this->Finish();
  }
  return true;
}

// One pass over every layer of a grid: its inputs bound, its output (two for the source).
bool ScatteringVolumeTexture::RunStep(vtkOpenGLRenderWindow* window,
  const Step& step,
  int unreadUnit)
{
  vtkOpenGLState* state = window->GetState();
  vtkShaderProgram* program = this->Pass.Quad().Program;
  Grid& grid = this->Grids[std::size_t(step.Level)];
  const Grid* coarse = step.Level > 0 ? &this->Grids[std::size_t(step.Level) - 1] : nullptr;

  // What the pass reads (the others' samplers name the density's unit: they are never read) and
  // writes.
  std::vector<std::pair<const char*, vtkTextureObject*>> reads;
  vtkTextureObject* outputs[2] = { nullptr, nullptr };
  switch (step.Pass)
  {
    case MediumPass:
      outputs[0] = grid.Medium;
      break;
    case SourcePass:
      reads = { { "ScatteringMediumTexture", grid.Medium } };
      outputs[0] = grid.Source;
      outputs[1] = grid.Direction;
      break;
    case StartPass:
      reads = { { "ScatteringMediumTexture", grid.Medium } };
      outputs[0] = grid.Fluence[0];
      grid.Current = 0;
      break;
    case ProlongPass:
      reads = { { "CoarseFluenceTexture", coarse->Fluence[std::size_t(coarse->Current)] } };
      outputs[0] = grid.Fluence[0];
      grid.Current = 0;
      break;
    default: // a half-sweep from the latest fluence into the other, or the flux from the latest
      reads = { { "ScatteringMediumTexture", grid.Medium },
        { "ScatteringSourceTexture", grid.Source },
        { "ScatteringDirectionTexture", grid.Direction },
        { "ScatteringFluenceTexture", grid.Fluence[std::size_t(grid.Current)] } };
      if (step.Pass == RelaxPass)
      {
        outputs[0] = grid.Fluence[std::size_t(1 - grid.Current)];
      }
      else
      {
        outputs[0] = grid.Flux;
      }
      break;
  }
  for (const char* sampler : { "ScatteringMediumTexture",
         "ScatteringSourceTexture",
         "ScatteringDirectionTexture",
         "ScatteringFluenceTexture",
         "CoarseFluenceTexture",
         "ScatteringVolumeTexture",
         "ScatteringFluxTexture" })
  {
    program->SetUniformi(sampler, unreadUnit);
  }
  for (auto& read : reads)
  {
    read.second->Activate();
    program->SetUniformi(read.first, read.second->GetTextureUnit());
  }

  const float size[3] = { float(grid.Size.x), float(grid.Size.y), float(grid.Size.z) };
  const float coarseSize[3] = { coarse ? float(coarse->Size.x) : 0.0f,
    coarse ? float(coarse->Size.y) : 0.0f,
    coarse ? float(coarse->Size.z) : 0.0f };
  program->SetUniform3f("ScatteringVolumeSize", size);
  program->SetUniform3f("ScatteringCoarseSize", coarseSize);
  program->SetUniform3f("ScatteringCellSize", glm::value_ptr(grid.CellSize));
  program->SetUniformi("ScatteringPass", step.Pass);
  program->SetUniformi("ScatteringParity", step.Parity);
  state->vtkglViewport(0, 0, grid.Size.x, grid.Size.y);
  unsigned int buffers[2] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1 };
  state->vtkglDrawBuffers(outputs[1] ? 2 : 1, buffers);
  // Every layer of the output(s) attached at once (layered): the quad is drawn once per layer,
  // as instances, which the geometry shader sends to their layers.
  for (int i = 0; i < 2; ++i)
  {
    glFramebufferTexture(GL_FRAMEBUFFER,
      GL_COLOR_ATTACHMENT0 + unsigned(i),
      outputs[i] ? outputs[i]->GetHandle() : 0,
      0);
  }
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  if (complete)
  {
    program->SetUniformi("ScatteringFirstLayer", step.FirstLayer);
    this->Pass.Quad().VAO->Bind();
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, step.Layers);
    this->Pass.Quad().VAO->Release();
  }
  // The half-sweep's output holds the latest fluence once all its layers are written.
  if (step.Pass == RelaxPass && step.FirstLayer + step.Layers == grid.Size.z)
  {
    grid.Current = 1 - grid.Current;
  }
  for (auto& read : reads)
  {
    read.second->Deactivate();
  }
  return complete;
}

// The finest grid's fluence and flux become the volume the march reads; the textures they
// replace take their place for the next computation.
void ScatteringVolumeTexture::Finish()
{
  Grid& finest = this->Grids.back();
  std::swap(finest.Fluence[std::size_t(finest.Current)], this->Fluence);
  std::swap(finest.Flux, this->Flux);
  this->Finished = true;
  ++this->ComputeCount;
  this->LastComputeSeconds = this->Seconds;
}

void ScatteringVolumeTexture::Activate(vtkShaderProgram* march)
{
  this->Fluence->Activate();
  this->Flux->Activate();
  march->SetUniformi("ScatteringVolumeTexture", this->Fluence->GetTextureUnit());
  march->SetUniformi("ScatteringFluxTexture", this->Flux->GetTextureUnit());
}

void ScatteringVolumeTexture::Deactivate()
{
  this->Fluence->Deactivate();
  this->Flux->Deactivate();
}

void ScatteringVolumeTexture::Release(vtkWindow* window)
{
  for (Grid& grid : this->Grids)
  {
    for (vtkTextureObject* texture : grid.Textures())
    {
      if (texture)
      {
        texture->ReleaseGraphicsResources(window);
      }
    }
  }
  this->Grids.clear();
  for (vtkTextureObject* texture : { this->Fluence.Get(), this->Flux.Get() })
  {
    if (texture)
    {
      texture->ReleaseGraphicsResources(window);
    }
  }
  this->Fluence = nullptr;
  this->Flux = nullptr;
  this->Finished = false;
  this->Progressive = false;
  this->Pass.Release();
  this->Signature.clear();
  this->Steps.clear();
  this->Next = 0;
  this->Bytes = 0;
}

} // namespace cloudvis
