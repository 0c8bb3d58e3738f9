// The sky is a texture rather than a shader pass so that it needs nothing from the mapper: VTK
// draws a renderer's background texture when it clears the frame, before any prop, and the
// mapper's composite pass blends the cloud over whatever the frame holds. Computing it on the
// CPU costs a few milliseconds per camera change, and nothing while accumulation runs.
#include "Background.h"

#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkRenderer.h>
#include <vtkTexture.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{
namespace
{

std::array<double, 3> Normalized(const std::array<double, 3>& v)
{
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return { { v[0] / length, v[1] / length, v[2] / length } };
}

// Keeps a renderer's background texture equal to the sky its camera sees. It runs at the start
// of each render, before the frame is cleared (the texture is drawn by the clear).
class SkyUpdater : public vtkCommand
{
public:
  static SkyUpdater* New() { return new SkyUpdater; }

  void Execute(vtkObject* caller, unsigned long, void*) override
  {
    auto* renderer = static_cast<vtkRenderer*>(caller);
    if (!renderer->GetTexturedBackground() || renderer->GetBackgroundTexture() != this->Texture)
    {
      return; // the background was set to something else since
    }
    vtkCamera* camera = renderer->GetActiveCamera();
    const int* size = renderer->GetSize();
    if (camera == this->Camera && camera->GetMTime() == this->CameraTime &&
      size[0] == this->Size[0] && size[1] == this->Size[1])
    {
      return;
    }
    this->Camera = camera;
    this->CameraTime = camera->GetMTime();
    this->Size[0] = size[0];
    this->Size[1] = size[1];
    if (size[0] > 0 && size[1] > 0)
    {
      this->Texture->SetInputData(
        MakeSkyImage(camera, size[0], size[1], SkySunDirection(this->Background)));
    }
  }

  BackgroundSpec Background;
  vtkNew<vtkTexture> Texture;

private:
  vtkCamera* Camera = nullptr;
  vtkMTimeType CameraTime = 0;
  int Size[2] = { 0, 0 };
};

} // namespace

std::array<double, 3> SkyColor(const std::array<double, 3>& ray, const std::array<double, 3>& sun)
{
  static const double Base[3] = { 0.7, 0.7, 0.9 };
  static const double Gradient[3] = { 0.9, 0.75, 0.9 };
  static const double Glow[3] = { 1.0, 0.5, 0.3 };
  const double towardSun = std::max(sun[0] * ray[0] + sun[1] * ray[1] + sun[2] * ray[2], 0.0);
  const double glow = std::pow(towardSun, 10.0);
  std::array<double, 3> color;
  for (int c = 0; c < 3; ++c)
  {
    const double sky = Base[c] - 0.8 * Gradient[c] * ray[1] + 0.5 * Glow[c] * glow;
    color[c] = std::min(std::max(sky, 0.0), 1.0);
  }
  return color;
}

std::array<double, 3> SkySunDirection(const BackgroundSpec& background)
{
  return Normalized(background.Sun.value_or(BackgroundSpec::DefaultSun));
}

vtkSmartPointer<vtkImageData> MakeSkyImage(
  vtkCamera* camera, int width, int height, const std::array<double, 3>& sun)
{
  // Normalized device coordinates to world: the inverse of the camera's view-projection for the
  // viewport's aspect; a pixel's ray joins its points on the near and far planes.
  vtkNew<vtkMatrix4x4> deviceToWorld;
  deviceToWorld->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(double(width) / double(height), -1.0, 1.0));
  deviceToWorld->Invert();
  const auto unproject = [&](double x, double y, double z, double world[3])
  {
    const double device[4] = { x, y, z, 1.0 };
    double w[4];
    deviceToWorld->MultiplyPoint(device, w);
    for (int c = 0; c < 3; ++c)
    {
      world[c] = w[c] / w[3];
    }
  };

  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* pixels = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int j = 0; j < height; ++j)
  {
    const double y = 2.0 * (j + 0.5) / height - 1.0;
    for (int i = 0; i < width; ++i)
    {
      const double x = 2.0 * (i + 0.5) / width - 1.0;
      double nearPoint[3], farPoint[3];
      unproject(x, y, -1.0, nearPoint);
      unproject(x, y, 1.0, farPoint);
      const std::array<double, 3> ray = Normalized({ { farPoint[0] - nearPoint[0],
        farPoint[1] - nearPoint[1], farPoint[2] - nearPoint[2] } });
      const std::array<double, 3> color = SkyColor(ray, sun);
      unsigned char* pixel = pixels + 3 * (size_t(j) * size_t(width) + size_t(i));
      for (int c = 0; c < 3; ++c)
      {
        pixel[c] = static_cast<unsigned char>(std::lround(255.0 * color[c]));
      }
    }
  }
  return image;
}

void ApplyBackground(const Scene& scene, vtkRenderer* renderer)
{
  // A sky applied before stays observing but turns inert once its texture is not the background.
  renderer->GradientBackgroundOff();
  renderer->TexturedBackgroundOff();
  renderer->SetBackgroundTexture(nullptr);
  renderer->SetBackground(scene.Background[0], scene.Background[1], scene.Background[2]);
  switch (scene.BackgroundStyle.Type)
  {
    case BackgroundType::Solid:
      break;
    case BackgroundType::Gradient:
    {
      const std::array<double, 3>& top = scene.BackgroundStyle.Top;
      renderer->SetBackground2(top[0], top[1], top[2]);
      renderer->GradientBackgroundOn();
      break;
    }
    case BackgroundType::Sky:
    {
      vtkNew<SkyUpdater> updater;
      updater->Background = scene.BackgroundStyle;
      updater->Texture->InterpolateOff(); // one texel per pixel
      updater->Texture->SetColorModeToDirectScalars();
      renderer->AddObserver(vtkCommand::StartEvent, updater);
      renderer->SetBackgroundTexture(updater->Texture);
      renderer->TexturedBackgroundOn();
      break;
    }
  }
}

} // namespace cloudvis
