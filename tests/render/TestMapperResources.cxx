// What vtkCloudVolumeMapper takes from the GPU and leaves behind: each field uploaded in its
// native texels (1, 2 or 4 bytes a voxel, half floats 2) with the memory reported as the driver
// allocated it; a field beyond the mapper's memory limit refused with the size it needs and
// nothing drawn; the light volumes computed only when their inputs change and counted; and the GL
// state left as vtkOpenGLState believes it is, since every change goes through it.
#include "RenderFixture.h"

#include <vtkCamera.h>
#include <vtkLight.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtk_glew.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

using namespace cloudvis;
using namespace cloudvis::test;

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
void SetField(Scene& scene, vtkCloudVolumeMapper* mapper, const Storage& storage)
{
  mapper->SetHalfFloatDensity(storage.HalfFloat);
  scene.SetInput(support::QuantizedField(SparseCloud(FieldSize), storage.ScalarType));
  SetRampMedium(scene.Property, support::FullScale(storage.ScalarType), 0.6);
}

double LargestAlpha(const Image& image)
{
  double largest = 0.0;
  for (size_t i = 3; i < image.RGBA.size(); i += 4)
  {
    largest = std::max(largest, double(image.RGBA[i]));
  }
  return largest;
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
  // the viewport's 32-bit depth and its two RGBA32F march targets.
  const long long others = 1024 * 16 + 21 * 21 * 21 + 64 * 64 * 4 +
    static_cast<long long>(ImageSize) * ImageSize * (4 + 2 * 16);
  for (const Storage& storage : Storages)
  {
    auto mapper = CloudMapper(0.05);
    Scene scene(mapper, ImageSize, ImageSize);
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
  Scene scene(mapper, ImageSize, ImageSize);
  SetField(scene, mapper, Storages[0]);
  const Image refused = scene.Render();
  const std::string error = mapper->GetLastError();
  EXPECT_NE(error.find("64 x 64 x 64 voxels of R32F"), std::string::npos) << error;
  EXPECT_NE(error.find("needs 1 MiB"), std::string::npos) << error;
  EXPECT_NE(error.find("MaximumGPUMemory"), std::string::npos) << error;
  for (size_t i = 0; i < refused.RGBA.size(); i += 4)
  {
    ASSERT_EQ(refused.RGBA[i] + refused.RGBA[i + 1] + refused.RGBA[i + 2], 0.0f)
      << "nothing drawn: the background everywhere";
  }
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
  Scene scene(mapper, ImageSize, ImageSize);
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
  Scene scene(mapper, ImageSize, ImageSize);
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
  Scene scene(mapper, ImageSize, ImageSize);
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
