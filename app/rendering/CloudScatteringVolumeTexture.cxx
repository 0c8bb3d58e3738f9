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
#include <cmath>
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
  FinishPass = 5 // the finest grid's fluence and flux, into the 3-D textures the march reads
};

// What the volume depends on, as numbers: when one changes it is computed again. The light
// volumes count by their computations (the source reads them), the external depths by their
// uploads (the source adds them).
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
    double(p.Phase),
    double(p.PhaseG1),
    double(p.PhaseG2),
    double(p.PhaseLobeWeight),
    double(p.DropletEffectiveRadius),
    double(p.DropletEffectiveVariance),
    double(p.LightSteps),
    double(p.LightStep),
    double(p.LightStepGrowth),
    in.LightVolumes ? double(in.LightVolumes->GetComputeCount()) : -1.0,
    in.ExternalDepthsTime };
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

// An RGBA32F texture of `size` texels (z 0: a 2-D one), linearly interpolated, clamped to its
// edges; null when the GL refuses it.
vtkSmartPointer<vtkTextureObject> NewTexture(vtkOpenGLRenderWindow* window, glm::ivec3 size)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  if (size.z > 0 ? !texture->Allocate3D(size.x, size.y, size.z, 4, VTK_FLOAT)
                 : !texture->Allocate2D(size.x, size.y, 4, VTK_FLOAT))
  {
    return nullptr;
  }
  SetSampling(texture, vtkTextureObject::Linear, vtkTextureObject::ClampToEdge);
  return texture;
}

// The tiles of a grid's atlas (Accessors.glsl): its layers in rows of about their square root.
glm::ivec2 AtlasTiles(glm::ivec3 size)
{
  const int columns = int(std::ceil(std::sqrt(double(size.z))));
  return { columns, (size.z + columns - 1) / columns };
}
}

// One grid's textures, atlases of its layers: the medium, the source and its direction, and two
// fluences (a half-sweep reads one and writes the other).
struct ScatteringVolumeTexture::Grid
{
  glm::ivec3 Size{ 0 };
  glm::ivec2 Tiles{ 0 };      // columns and rows of layers in its atlases
  glm::vec3 CellSize{ 0.0f }; // a cell's local length per axis (ScatteringCellSize)
  vtkSmartPointer<vtkTextureObject> Medium, Source, Direction;
  std::array<vtkSmartPointer<vtkTextureObject>, 2> Fluence;
  int Current = 0; // the fluence holding the latest values

  glm::ivec2 AtlasSize() const { return this->Tiles * glm::ivec2(this->Size); }
  std::array<vtkTextureObject*, 5> Textures() const
  {
    return { this->Medium, this->Source, this->Direction, this->Fluence[0], this->Fluence[1] };
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
  VolumeSources::Numbers signature = SignatureOf(u, inputs);
  if (!this->Sources.Current(signature, this->Fluence) || this->Grids.empty())
  {
    if (!this->Allocate(window, u, budget, problem))
    {
      return false;
    }
    this->Sources.Take(std::move(signature));
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
    this->Sources.Forget();
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
  const glm::ivec3 finest = sizes.back();
  // RGBA32F: five atlases per grid, and the finished fluence and flux the march reads with the
  // two the next computation writes.
  long long texels = 0;
  for (const glm::ivec3& size : sizes)
  {
    const glm::ivec2 atlas = AtlasTiles(size) * glm::ivec2(size);
    texels += 5LL * atlas.x * atlas.y;
  }
  texels += 4LL * finest.x * finest.y * finest.z + 1; // and a texel for the unread samplers
  std::vector<Grid> grids(sizes.size());
  problem = budget.AllocateVolume("the multiple-scattering volume",
    finest,
    16 * texels,
    held,
    [&]()
    {
      for (std::size_t level = 0; level < sizes.size(); ++level)
      {
        Grid& grid = grids[level];
        grid.Size = sizes[level];
        grid.Tiles = AtlasTiles(grid.Size);
        const glm::ivec3 atlas(grid.AtlasSize(), 0);
        grid.Medium = NewTexture(window, atlas);
        grid.Source = NewTexture(window, atlas);
        grid.Direction = NewTexture(window, atlas);
        grid.Fluence = { NewTexture(window, atlas), NewTexture(window, atlas) };
        if (!grid.Medium || !grid.Source || !grid.Direction || !grid.Fluence[0] || !grid.Fluence[1])
        {
          return false;
        }
      }
      for (auto& texture : { &this->Fluence, &this->Flux, &this->NextFluence, &this->NextFlux })
      {
        *texture = NewTexture(window, finest);
      }
      this->Unread = NewTexture(window, glm::ivec3(1, 1, 0));
      return this->Fluence && this->Flux && this->NextFluence && this->NextFlux && this->Unread;
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
  for (vtkTextureObject* texture :
    { this->Fluence, this->Flux, this->NextFluence, this->NextFlux, this->Unread })
  {
    this->Bytes += TextureBytes(texture);
  }
  return true;
}

// The passes of ComputeScatteringVolume, in its order: per grid from the coarsest, the medium,
// the source, the first guess (the start on the coarsest, the coarser grid's fluence on the
// others), the sweeps' half-sweeps of parity 0 then 1, and on the finest grid the flux.
// A progressive computation splits each pass into steps of at most about CellsPerStep cells (rows
// of an atlas' tiles, or layers of the finished volume), so that a frame's share of the work is
// bounded whatever the field's size (a pass over a 256^3 field's 65^3 finest grid takes about
// 0.3 s on llvmpipe); a whole one draws each pass at once.
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
    const Grid& grid = this->Grids[std::size_t(level)];
    // The units a step covers: rows of tiles, or for the finished volume layers.
    const int units = pass == FinishPass ? grid.Size.z : grid.Tiles.y;
    const int cells = grid.Size.x * grid.Size.y * (pass == FinishPass ? 1 : grid.Tiles.x);
    const int perStep = progressive ? std::max(1, CellsPerStep / cells) : units;
    for (int first = 0; first < units; first += perStep)
    {
      this->Steps.push_back({ level, pass, parity, first, std::min(perStep, units - first) });
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
  add(int(this->Grids.size()) - 1, FinishPass, 0);
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

// One step of a pass: its inputs bound, its outputs (two for the source and the finished volume)
// attached, the step's rows of atlas tiles drawn (or the finished volume's layers).
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
    default: // a half-sweep from the latest fluence into the other, or the finished volume
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
        outputs[0] = this->NextFluence;
        outputs[1] = this->NextFlux;
      }
      break;
  }
  // The samplers the pass does not read name a unit of their own type: the 1 x 1 texture's (2-D)
  // or `unreadUnit` (3-D).
  this->Unread->Activate();
  for (const char* sampler : { "ScatteringMediumTexture",
         "ScatteringSourceTexture",
         "ScatteringDirectionTexture",
         "ScatteringFluenceTexture",
         "CoarseFluenceTexture" })
  {
    program->SetUniformi(sampler, this->Unread->GetTextureUnit());
  }
  for (const char* sampler : { "ScatteringVolumeTexture", "ScatteringFluxTexture" })
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
  program->SetUniformf("ScatteringAtlasColumns", float(grid.Tiles.x));
  program->SetUniformf("CoarseAtlasColumns", coarse ? float(coarse->Tiles.x) : 1.0f);
  // An atlas pass draws the quad over its rows of tiles; the finished volume's, once per layer
  // (instances the geometry shader sends to their layers of the outputs, attached layered).
  const bool finish = step.Pass == FinishPass;
  if (finish)
  {
    state->vtkglViewport(0, 0, grid.Size.x, grid.Size.y);
  }
  else
  {
    const glm::ivec2 atlas = grid.AtlasSize();
    state->vtkglViewport(0, step.First * grid.Size.y, atlas.x, step.Count * grid.Size.y);
  }
  unsigned int buffers[2] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1 };
  state->vtkglDrawBuffers(outputs[1] ? 2 : 1, buffers);
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
    program->SetUniformi("ScatteringFirstLayer", finish ? step.First : 0);
    this->Pass.Quad().VAO->Bind();
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, finish ? step.Count : 1);
    this->Pass.Quad().VAO->Release();
  }
  this->Unread->Deactivate();
  // The half-sweep's output holds the latest fluence once all its rows are written.
  if (step.Pass == RelaxPass && step.First + step.Count == grid.Tiles.y)
  {
    grid.Current = 1 - grid.Current;
  }
  for (auto& read : reads)
  {
    read.second->Deactivate();
  }
  return complete;
}

// The finished volume's fluence and flux become the ones the march reads; the textures they
// replace take their place for the next computation.
void ScatteringVolumeTexture::Finish()
{
  std::swap(this->NextFluence, this->Fluence);
  std::swap(this->NextFlux, this->Flux);
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
  for (auto* texture :
    { &this->Fluence, &this->Flux, &this->NextFluence, &this->NextFlux, &this->Unread })
  {
    if (*texture)
    {
      (*texture)->ReleaseGraphicsResources(window);
    }
    *texture = nullptr;
  }
  this->Finished = false;
  this->Progressive = false;
  this->Pass.Release();
  this->Sources.Forget();
  this->Steps.clear();
  this->Next = 0;
  this->Bytes = 0;
}

} // namespace cloudvis
