// What vtkCloudVolumeMapper takes from the GPU and leaves behind: each field uploaded in its
// native texels (1, 2 or 4 bytes a voxel, half floats 2) with the memory reported as the driver
// allocated it; a field beyond the mapper's memory limit refused with the size it needs and
// nothing drawn; the light volumes computed only when their inputs change and counted; and the GL
// state left as vtkOpenGLState believes it is, since every change goes through it.
#include "SupportScene.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkPointData.h>
#include <vtk_glew.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace cloudvis;
using namespace cloudvis::support;

namespace
{
constexpr int FieldSize = 64;
constexpr int ImageSize = 64;

struct Storage
{
  const char* Name;
  int ScalarType;
  bool HalfFloat;
  long long BytesPerVoxel;
};

// The sparse cloud stored as `storage` says, with the ramp medium over its units.
void SetField(GpuScene& scene, vtkCloudVolumeMapper* mapper, const Storage& storage)
{
  mapper->SetHalfFloatDensity(storage.HalfFloat);
  scene.SetInput(support::QuantizedField(SparseCloud(FieldSize), storage.ScalarType));
  SetRampMedium(scene.Property, support::FullScale(storage.ScalarType), 0.6);
}

double LargestAlpha(const Image& image)
{
  return Largest(image, 1, {}, 3);
}

const Storage Storages[] = { { "float", VTK_FLOAT, false, 4 },
  { "unsigned short", VTK_UNSIGNED_SHORT, false, 2 },
  { "unsigned char", VTK_UNSIGNED_CHAR, false, 1 },
  { "half float", VTK_FLOAT, true, 2 } };
}

TEST(MapperResources, EachFieldIsUploadedInItsNativeTexelsAndItsMemoryReported)
{
  const long long voxels = static_cast<long long>(FieldSize) * FieldSize * FieldSize;
  // Everything else the mapper holds, whatever the field's type: the transfer table (1024 RGBA32F
  // texels), the occupancy map (one R8 texel per brick of 3: 21^3), the 64 x 64 R32F jitter mask,
  // the droplets' phase table's placeholder (1 x 2 RGB32F texels: the phase is the two lobes),
  // the viewport's 32-bit depth and its two RGBA32F march targets.
  const long long others = 1024 * 16 + 21 * 21 * 21 + 64 * 64 * 4 + 2 * 12 +
    static_cast<long long>(ImageSize) * ImageSize * (4 + 2 * 16);
  for (const Storage& storage : Storages)
  {
    auto mapper = CloudMapper(0.05);
    GpuScene scene(mapper, ImageSize, ImageSize);
    SetField(scene, mapper, storage);
    const Image image = scene.RenderFloat();
    ASSERT_EQ(mapper->GetLastError(), "") << storage.Name;
    EXPECT_GT(LargestAlpha(image), 0.3) << storage.Name << ": the cloud is drawn";
    EXPECT_EQ(mapper->GetDensityTextureBytes(), voxels * storage.BytesPerVoxel) << storage.Name;
    EXPECT_EQ(mapper->GetGPUMemoryBytes(), voxels * storage.BytesPerVoxel + others) << storage.Name;
    mapper->ReleaseGraphicsResources(scene.Window);
    EXPECT_EQ(mapper->GetGPUMemoryBytes(), 0) << storage.Name;
  }
}

TEST(MapperResources, AFieldBeyondTheMemoryLimitIsRefusedWithItsSizeAndNotDrawn)
{
  // 64^3 floats need 1 MiB; as half floats or bytes the same cloud fits the limit.
  constexpr long long Limit = 800000;
  auto mapper = CloudMapper(0.05);
  mapper->SetMaximumGPUMemory(Limit);
  GpuScene scene(mapper, ImageSize, ImageSize);
  SetField(scene, mapper, Storages[0]);
  const Image refused = scene.Render();
  const std::string error = mapper->GetLastError();
  EXPECT_NE(error.find("64 x 64 x 64 voxels of R32F"), std::string::npos) << error;
  EXPECT_NE(error.find("needs 1 MiB"), std::string::npos) << error;
  EXPECT_NE(error.find("MaximumGPUMemory"), std::string::npos) << error;
  ASSERT_EQ(Largest(refused, 3), 0.0) << "nothing drawn: the background everywhere";
  EXPECT_LE(mapper->GetGPUMemoryBytes(), Limit);

  for (const Storage& storage : { Storages[3], Storages[2] })
  {
    SetField(scene, mapper, storage);
    const Image image = scene.RenderFloat();
    EXPECT_EQ(mapper->GetLastError(), "") << storage.Name;
    EXPECT_GT(LargestAlpha(image), 0.3) << storage.Name;
    EXPECT_LE(mapper->GetGPUMemoryBytes(), Limit) << storage.Name;
  }
  mapper->SetMaximumGPUMemory(0); // no limit: the float field is drawn again
  SetField(scene, mapper, Storages[0]);
  EXPECT_GT(LargestAlpha(scene.RenderFloat()), 0.3);
  EXPECT_EQ(mapper->GetLastError(), "");
}

TEST(MapperResources, LightVolumesAreComputedWhenTheirInputsChangeAndCountInTheBudget)
{
  // The march with light volumes (the default) computes them once for a scene, not per frame,
  // again when a light moves or the transfer function changes; they take one R32F texel per
  // texel of half the field's resolution per light (33^3 for 64^3 voxels), in GetGPUMemoryBytes.
  auto mapper = CloudMapper(0.05);
  mapper->GetLightingProperty()->SetModelToMarch();
  GpuScene scene(mapper, ImageSize, ImageSize);
  SetField(scene, mapper, Storages[0]);
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(1.0, 0.5, 0.3);
  sun->SetFocalPoint(0.0, 0.0, 0.0);
  scene.Renderer->AddLight(sun);
  const Image first = scene.RenderFloat();
  ASSERT_EQ(mapper->GetLastError(), "");
  EXPECT_GT(LargestAlpha(first), 0.3);
  EXPECT_EQ(mapper->GetLightVolumeComputeCount(), 1);
  EXPECT_EQ(mapper->GetLightVolumeBytes(), 33LL * 33 * 33 * 4);
  scene.Renderer->GetActiveCamera()->Azimuth(20.0); // a new view: the same volumes
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetLightVolumeComputeCount(), 1);
  sun->SetPosition(-1.0, 0.5, 0.3); // the light moves
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetLightVolumeComputeCount(), 2);
  SetRampMedium(scene.Property, 1.0, 0.3); // another transfer function
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetLightVolumeComputeCount(), 3);
  vtkNew<vtkLight> second; // a second light: a block more
  second->SetLightTypeToSceneLight();
  second->SetPositional(true);
  second->SetPosition(0.0, -3.0, 1.0);
  scene.Renderer->AddLight(second);
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetLightVolumeComputeCount(), 4);
  EXPECT_EQ(mapper->GetLightVolumeBytes(), 2 * 33LL * 33 * 33 * 4);
  // The nested march needs none: they are not held for nothing.
  mapper->GetLightingProperty()->SetTransmittanceToNestedMarch();
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetLightVolumeBytes(), 0);
  // Released with the rest.
  mapper->GetLightingProperty()->SetTransmittanceToLightVolumes();
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetLightVolumeComputeCount(), 5);
  mapper->ReleaseGraphicsResources(scene.Window);
  EXPECT_EQ(mapper->GetLightVolumeBytes(), 0);
}

TEST(MapperResources, ThePathTracersTexturesAreReleasedWhenAnotherModelRenders)
{
  // The path tracer adds a moment target and a texture of extinction bounds per brick; back on
  // another model the mapper holds what that model holds, and no more.
  auto mapper = CloudMapper(0.05);
  GpuScene scene(mapper, ImageSize, ImageSize);
  SetField(scene, mapper, Storages[0]);
  scene.RenderFloat();
  ASSERT_EQ(mapper->GetLastError(), "");
  const vtkTypeInt64 unlit = mapper->GetGPUMemoryBytes();
  mapper->GetLightingProperty()->SetModelToPathTrace();
  scene.RenderFloat();
  ASSERT_EQ(mapper->GetLastError(), "");
  EXPECT_GE(mapper->GetGPUMemoryBytes(), unlit + vtkTypeInt64(ImageSize) * ImageSize * 16);
  mapper->GetLightingProperty()->SetModelToNone();
  scene.RenderFloat();
  ASSERT_EQ(mapper->GetLastError(), "");
  EXPECT_EQ(mapper->GetGPUMemoryBytes(), unlit);
}

TEST(MapperResources, GlStateIsLeftAsVtkOpenGLStateHasIt)
{
  auto mapper = CloudMapper(0.05);
  mapper->CollectStatisticsOn(); // a read-back after each frame
  mapper->SetMaximumAccumulatedFrames(4);
  mapper->JitterOn();
  GpuScene scene(mapper, ImageSize, ImageSize);
  SetField(scene, mapper, Storages[0]);
  scene.RenderFloat();
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(scene.Window);
  window->MakeCurrent();
  vtkOpenGLState* state = window->GetState();
  // A blend constant someone else set: the mapper has no business changing it.
  glBlendColor(0.25f, 0.5f, 0.75f, 1.0f);
  for (int frame = 1; frame < 3; ++frame) // accumulating frames blend into the targets
  {
    scene.RenderFloat();
  }
  ASSERT_EQ(mapper->GetLastError(), "");
  ASSERT_EQ(mapper->GetNumberOfAccumulatedFrames(scene.Renderer), 3);
  window->MakeCurrent();
  GLfloat blendColor[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  glGetFloatv(GL_BLEND_COLOR, blendColor);
  EXPECT_EQ(blendColor[0], 0.25f);
  EXPECT_EQ(blendColor[3], 1.0f);

  // A change made behind vtkOpenGLState's back leaves its cache stale, and a later request for
  // the value it believes is set never reaches the GL.
  state->vtkglPixelStorei(GL_PACK_ALIGNMENT, 4);
  std::vector<float> rgba;
  int width = 0, height = 0;
  ASSERT_TRUE(mapper->ReadImage(scene.Renderer, rgba, width, height)); // reads with alignment 1
  state->vtkglPixelStorei(GL_PACK_ALIGNMENT, 4);
  GLint alignment = 0;
  glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
  EXPECT_EQ(alignment, 4);

  int blend[4];
  state->GetBlendFuncState(blend);
  GLint actual[4];
  glGetIntegerv(GL_BLEND_SRC_RGB, &actual[0]);
  glGetIntegerv(GL_BLEND_DST_RGB, &actual[1]);
  glGetIntegerv(GL_BLEND_SRC_ALPHA, &actual[2]);
  glGetIntegerv(GL_BLEND_DST_ALPHA, &actual[3]);
  for (int i = 0; i < 4; ++i)
  {
    EXPECT_EQ(blend[i], actual[i]);
  }
  for (GLenum capability : { GL_BLEND, GL_DEPTH_TEST, GL_SCISSOR_TEST })
  {
    EXPECT_EQ(state->GetEnumState(capability), glIsEnabled(capability) == GL_TRUE);
  }
}

TEST(MapperResources, AHeadlightWhileInteractingMarchesTowardItInsteadOfRecomputingTheVolumes)
{
  // A light that follows the camera (VTK's headlight) changes with every frame of an
  // interaction: the light volumes are not recomputed for each (that would cost more than the
  // nested march); those frames are the nested march's, to the bit, and the still render after
  // the interaction computes the volumes once. A second mapper with the nested march, looking
  // from the same camera, is the image each interactive frame must be (the nested march is
  // compared with the CPU reference in TestGpuMatchesCpuReference).
  struct HeadlitScene
  {
    vtkSmartPointer<vtkCloudVolumeMapper> Mapper = CloudMapper(0.05);
    GpuScene View{ Mapper, ImageSize, ImageSize };
    explicit HeadlitScene(LightTransmittance transmittance)
    {
      this->Mapper->GetLightingProperty()->SetModelToMarch();
      LightingParameters lighting = this->Mapper->GetLightingProperty()->GetParameters();
      lighting.Transmittance = transmittance;
      this->Mapper->GetLightingProperty()->SetParameters(lighting);
      // While interacting the scale stays at ResolutionScale (a frame rate any frame meets), so
      // that both mappers march the same pixels.
      this->Mapper->SetResolutionScale(0.5);
      this->Mapper->SetInteractiveFrameRate(0.01);
      SetField(this->View, this->Mapper, Storages[0]);
      vtkNew<vtkLight> headlight;
      headlight->SetLightTypeToHeadlight();
      this->View.Renderer->AddLight(headlight);
    }
  };
  HeadlitScene volumes(LightTransmittance::Volumes);
  HeadlitScene nested(LightTransmittance::Nested);
  const auto turn = [](HeadlitScene& scene)
  { scene.View.Renderer->GetActiveCamera()->Azimuth(15.0); };

  const Image still = volumes.View.RenderFloat();
  ASSERT_EQ(volumes.Mapper->GetLastError(), "");
  EXPECT_GT(LargestAlpha(still), 0.3);
  EXPECT_EQ(volumes.Mapper->GetLightVolumeComputeCount(), 1);

  volumes.View.Window->SetDesiredUpdateRate(20.0); // what an interactor sets while dragging
  nested.View.Window->SetDesiredUpdateRate(20.0);
  for (int frame = 0; frame < 4; ++frame)
  {
    turn(volumes);
    turn(nested);
    const Image interactive = volumes.View.RenderFloat();
    const Image reference = nested.View.RenderFloat();
    ASSERT_EQ(volumes.Mapper->GetLastError(), "");
    EXPECT_EQ(volumes.Mapper->GetLightVolumeComputeCount(), 1) << "frame " << frame;
    EXPECT_LE(MaxDifference(interactive, reference), 1e-6) << "frame " << frame;
    EXPECT_GT(volumes.Mapper->GetLightVolumeBytes(), 0) << "kept for the still render";
  }

  // The interaction ends: the still frame recomputes the volumes for the light where it is now,
  // and reads them (no longer the nested march's image; the two differ by the grid's error).
  volumes.View.Window->SetDesiredUpdateRate(0.0001);
  nested.View.Window->SetDesiredUpdateRate(0.0001);
  const Image after = volumes.View.RenderFloat();
  const Image nestedAfter = nested.View.RenderFloat();
  EXPECT_EQ(volumes.Mapper->GetLightVolumeComputeCount(), 2);
  EXPECT_GT(MaxDifference(after, nestedAfter), 1e-4);
  // A light that moves while the camera holds still (not interacting) recomputes them at once.
  volumes.View.Renderer->RemoveAllLights();
  AddLight(volumes.View.Renderer, DirectionalLight(glm::dvec3(1.0, 0.5, 0.3)));
  volumes.View.RenderFloat();
  EXPECT_EQ(volumes.Mapper->GetLightVolumeComputeCount(), 3);
}

TEST(MapperResources, AResizeNearTheMemoryLimitCountsThePathTracersOldMomentTargetOnce)
{
  // The path tracer holds a moment target of the march's size. A resize replaces it: what the
  // budget checks is what the mapper holds after, not that plus the target it freed.
  constexpr int Larger = ImageSize + 16;
  const auto pathTraced = [](long long limit)
  {
    auto mapper = CloudMapper(0.05);
    mapper->GetLightingProperty()->SetModelToPathTrace();
    mapper->SetMaximumGPUMemory(limit);
    return mapper;
  };
  // What the path tracer holds at the larger size, from a mapper that renders only that.
  long long needed = 0;
  {
    auto mapper = pathTraced(0);
    GpuScene scene(mapper, Larger, Larger);
    SetField(scene, mapper, Storages[0]);
    scene.RenderFloat();
    ASSERT_EQ(mapper->GetLastError(), "");
    needed = mapper->GetGPUMemoryBytes();
  }
  auto mapper = pathTraced(needed);
  GpuScene scene(mapper, ImageSize, ImageSize);
  SetField(scene, mapper, Storages[0]);
  scene.RenderFloat();
  ASSERT_EQ(mapper->GetLastError(), "");
  scene.Window->SetSize(Larger, Larger);
  const Image resized = scene.RenderFloat();
  EXPECT_EQ(mapper->GetLastError(), "") << "fits the limit exactly";
  EXPECT_EQ(resized.Width, Larger);
  EXPECT_GT(LargestAlpha(resized), 0.1);
  EXPECT_EQ(mapper->GetGPUMemoryBytes(), needed);
  // One byte less is refused: the limit above was tight.
  mapper->SetMaximumGPUMemory(needed - 1);
  scene.Window->SetSize(ImageSize, ImageSize);
  scene.RenderFloat();
  scene.Window->SetSize(Larger, Larger);
  scene.Render();
  EXPECT_NE(mapper->GetLastError().find("MaximumGPUMemory"), std::string::npos)
    << mapper->GetLastError();
}

TEST(MapperResources, LightVolumesBeyondTheLargest3DTextureAreRefusedNamingTheNestedMarch)
{
  // The light volumes stack one block per light along z in one 3-D texture: a field deep in z
  // with two lights needs more layers than GL_MAX_3D_TEXTURE_SIZE (2048 on llvmpipe) although it
  // is small (4 x 4 x that many voxels). It is refused in words, nothing drawn; the nested march,
  // or one light, renders it.
  auto mapper = CloudMapper(0.05);
  mapper->GetLightingProperty()->SetModelToMarch();
  GpuScene scene(mapper, ImageSize, ImageSize);
  scene.Volume->VisibilityOff(); // a context, to ask its limit
  scene.Render();
  scene.Volume->VisibilityOn();
  scene.Renderer->RemoveAllLights(); // the headlight VTK made for a renderer without lights
  GLint largest = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &largest);
  ASSERT_GE(largest, 256);
  const int depth = largest; // one light's block: depth / 2 + 1 layers; two: more than largest
  vtkNew<vtkImageData> field;
  field->SetDimensions(4, 4, depth);
  field->SetOrigin(-1.5, -1.5, -2.0);
  field->SetSpacing(1.0, 1.0, 4.0 / (depth - 1));
  field->AllocateScalars(VTK_FLOAT, 1);
  field->GetPointData()->GetScalars()->SetName("density");
  field->GetPointData()->GetScalars()->Fill(1.0);
  scene.SetInput(field);
  SetUniformMedium(scene.Property, 0.5, 1.0);
  AddLight(scene.Renderer, DirectionalLight(glm::dvec3(1.0, 0.5, 0.3)));
  AddLight(scene.Renderer, PointLight(glm::dvec3(0.0, 3.0, 1.0)));

  const Image refused = scene.Render();
  const std::string error = mapper->GetLastError();
  EXPECT_NE(error.find("the light-volume texture (2 lights) needs a 3-D texture of 3 x 3 x " +
              std::to_string(2 * (depth / 2 + 1)) + " texels"),
    std::string::npos)
    << error;
  EXPECT_NE(error.find("render.march.transmittance \"nested\""), std::string::npos) << error;
  ASSERT_EQ(Largest(refused, 3), 0.0) << "nothing drawn: the background everywhere";

  mapper->GetLightingProperty()->SetTransmittanceToNestedMarch();
  EXPECT_GT(LargestAlpha(scene.RenderFloat()), 0.3);
  EXPECT_EQ(mapper->GetLastError(), "");
  mapper->GetLightingProperty()->SetTransmittanceToLightVolumes();
  scene.Renderer->RemoveAllLights();
  AddLight(scene.Renderer, DirectionalLight(glm::dvec3(1.0, 0.5, 0.3)));
  EXPECT_GT(LargestAlpha(scene.RenderFloat()), 0.3);
  EXPECT_EQ(mapper->GetLastError(), "");
}

namespace
{
// The sparse cloud lit by the sun, with the march (whose multiple scattering comes from the
// volume).
void SetSunlitMarch(GpuScene& scene, vtkCloudVolumeMapper* mapper, vtkLight* sun)
{
  mapper->GetLightingProperty()->SetModelToMarch();
  SetField(scene, mapper, Storages[0]);
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(1.0, 0.5, 0.3);
  sun->SetFocalPoint(0.0, 0.0, 0.0);
  scene.Renderer->AddLight(sun);
}

// The multiple-scattering grids of the 64^3 field: 5^3, 9^3 and 17^3 texels, five RGBA32F atlases
// each (medium, source, direction, two fluences) of 3 x 2, 3 x 3 and 5 x 4 tiles of their layers,
// four 3-D textures of the finest grid (the finished fluence and flux the march reads, and the
// next), and one texel for the samplers a pass does not read.
constexpr long long ScatteringBytes =
  16LL * (5 * (6 * 25 + 9 * 81 + 20 * 289) + 4 * 17 * 17 * 17 + 1);
}

TEST(MapperResources, TheScatteringVolumeIsComputedWhenItsInputsChangeAndCountsInTheBudget)
{
  auto mapper = CloudMapper(0.05);
  GpuScene scene(mapper, ImageSize, ImageSize);
  vtkNew<vtkLight> sun;
  SetSunlitMarch(scene, mapper, sun);
  const Image first = scene.RenderFloat();
  ASSERT_EQ(mapper->GetLastError(), "");
  EXPECT_GT(LargestAlpha(first), 0.3);
  EXPECT_EQ(mapper->GetScatteringVolumeComputeCount(), 1);
  EXPECT_EQ(mapper->GetScatteringVolumeBytes(), ScatteringBytes);
  EXPECT_GT(mapper->GetScatteringVolumeSeconds(), 0.0);
  scene.Renderer->GetActiveCamera()->Azimuth(20.0); // a new view: the same volume
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetScatteringVolumeComputeCount(), 1);
  sun->SetPosition(-1.0, 0.5, 0.3); // the light moves
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetScatteringVolumeComputeCount(), 2);
  SetRampMedium(scene.Property, 1.0, 0.3); // another transfer function
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetScatteringVolumeComputeCount(), 3);
  LightingParameters lighting = mapper->GetLightingProperty()->GetParameters();
  lighting.PhaseG1 = 0.5f; // another phase
  mapper->GetLightingProperty()->SetParameters(lighting);
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetScatteringVolumeComputeCount(), 4);
  EXPECT_EQ(mapper->GetLastError(), "");
  // Another model needs none: it is not held for nothing.
  mapper->GetLightingProperty()->SetModelToDerivative();
  scene.RenderFloat();
  EXPECT_EQ(mapper->GetScatteringVolumeBytes(), 0);

  // Refused in words when the memory limit leaves no room for it, nothing drawn.
  mapper->GetLightingProperty()->SetModelToMarch();
  scene.RenderFloat();
  const vtkTypeInt64 held = mapper->GetGPUMemoryBytes();
  mapper->ReleaseGraphicsResources(scene.Window);
  mapper->SetMaximumGPUMemory(held - 1);
  const Image refused = scene.Render();
  const std::string error = mapper->GetLastError();
  EXPECT_NE(error.find("the multiple-scattering volume needs"), std::string::npos) << error;
  EXPECT_NE(error.find("MaximumGPUMemory"), std::string::npos) << error;
  EXPECT_EQ(Largest(refused, 3), 0.0) << "nothing drawn: the background everywhere";
  mapper->SetMaximumGPUMemory(held);
  EXPECT_GT(LargestAlpha(scene.RenderFloat()), 0.3);
  EXPECT_EQ(mapper->GetLastError(), "");
}

TEST(MapperResources, AProgressiveRecomputeShowsTheLastVolumeUntilTheNewOneIsTheWholeOne)
{
  // Spread over frames (the viewer's setting), a recompute after the light moves runs a slice of
  // its passes per render (here one step: a pass over some of a grid's cells, the finest grid's
  // in two steps); meanwhile the march reads the last finished volume, and the renders
  // report the progress. The volume it ends with is the one a whole computation makes (the same
  // passes in the same order), so the image is a second mapper's to the bit.
  auto mapper = CloudMapper(0.05);
  mapper->SetScatteringVolumeSecondsPerFrame(1e-9); // one pass per render
  GpuScene scene(mapper, ImageSize, ImageSize);
  vtkNew<vtkLight> sun;
  SetSunlitMarch(scene, mapper, sun);
  auto whole = CloudMapper(0.05);
  GpuScene reference(whole, ImageSize, ImageSize);
  vtkNew<vtkLight> referenceSun;
  SetSunlitMarch(reference, whole, referenceSun);

  scene.RenderFloat(); // the first volume: computed whole, nothing to show meanwhile
  ASSERT_EQ(mapper->GetLastError(), "");
  EXPECT_EQ(mapper->GetScatteringVolumeComputeCount(), 1);
  EXPECT_FALSE(mapper->GetScatteringVolumeConverging());
  EXPECT_LE(MaxDifference(scene.RenderFloat(), reference.RenderFloat()), 0.0);

  sun->SetPosition(-1.0, 0.5, 0.3);
  referenceSun->SetPosition(-1.0, 0.5, 0.3);
  int renders = 0, done = 0, total = 0, lastDone = 0;
  do
  {
    scene.RenderFloat();
    ++renders;
    ASSERT_EQ(mapper->GetLastError(), "");
    if (mapper->GetScatteringVolumeConverging())
    {
      done = mapper->GetScatteringVolumeStepsDone();
      total = mapper->GetScatteringVolumeStepCount();
      EXPECT_GT(done, lastDone) << "render " << renders;
      EXPECT_LT(done, total);
      EXPECT_EQ(mapper->GetScatteringVolumeComputeCount(), 1) << "the last volume is read";
      lastDone = done;
    }
  } while (mapper->GetScatteringVolumeConverging() && renders < 1000);
  EXPECT_FALSE(mapper->GetScatteringVolumeConverging());
  EXPECT_EQ(renders, total) << "one pass per render, " << total << " passes";
  // 5^3: medium, source, start and 128 half-sweeps; 9^3: medium, source, prolongation and 48; 17^3
  // the same 51 passes in two steps each (two rows of its atlas' 5 x 4 tiles), and the finished
  // volume in two (of 14 and 3 layers).
  EXPECT_EQ(total, 131 + 51 + 2 * 51 + 2);
  EXPECT_EQ(mapper->GetScatteringVolumeComputeCount(), 2);
  const Image progressive = scene.RenderFloat();
  const Image computedWhole = reference.RenderFloat();
  EXPECT_EQ(whole->GetScatteringVolumeComputeCount(), 2);
  EXPECT_LE(MaxDifference(progressive, computedWhole), 0.0);
}
