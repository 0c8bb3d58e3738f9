// The GPU scene of the renderer tests (SupportScene.h).
#include "SupportScene.h"

#include "vtkCloudVolumeMapper.h"

#include <vtkCamera.h>

#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace cloudvis
{
namespace support
{

GpuScene::GpuScene(vtkVolumeMapper* mapper, int width, int height)
  : Mapper(mapper)
{
  this->Window->SetOffScreenRendering(1);
  this->Window->SetMultiSamples(0);
  this->Window->SetSize(width, height);
  this->Window->AddRenderer(this->Renderer);
  this->Renderer->SetBackground(0.0, 0.0, 0.0);
  this->Volume->SetMapper(mapper);
  this->Volume->SetProperty(this->Property);
  this->Renderer->AddVolume(this->Volume);
  this->LookAlongMinusZ();
}

void GpuScene::SetInput(vtkImageData* field)
{
  this->Mapper->SetInputDataObject(field);
}

void GpuScene::ShowSparseCloud(int size)
{
  this->SetInput(SparseCloud(size));
  SetRampMedium(this->Property, 1.0, 0.6);
}

void GpuScene::LookAlongMinusZ(double distance, bool parallel, double parallelScale)
{
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  camera->SetPosition(0.0, 0.0, distance);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetParallelProjection(parallel);
  camera->SetParallelScale(parallelScale);
  camera->SetViewAngle(30.0);
  camera->SetClippingRange(0.1, 2.0 * distance + 10.0);
}

Image GpuScene::Render()
{
  this->Window->Render();
  return GrabWindow(this->Window, true);
}

Image GpuScene::RenderOnce()
{
  this->Window->Render();
  return GrabWindow(this->Window, true, false);
}

Image GpuScene::RenderFloat()
{
  this->Window->Render();
  auto* cloud = vtkCloudVolumeMapper::SafeDownCast(this->Mapper);
  std::vector<float> rgba;
  int width = 0, height = 0;
  if (!cloud || !cloud->ReadImage(this->Renderer, rgba, width, height))
  {
    throw std::runtime_error("no float image to read");
  }
  return FromRgba(rgba, width, height);
}

Image GpuScene::RenderPathTraced(int frames)
{
  for (int f = 0; f < frames; ++f)
  {
    this->Window->Render();
  }
  auto* cloud = vtkCloudVolumeMapper::SafeDownCast(this->Mapper);
  std::vector<float> rgba, variance;
  int width = 0, height = 0, varianceWidth = 0, varianceHeight = 0;
  if (!cloud || !cloud->ReadImage(this->Renderer, rgba, width, height) ||
    !cloud->ReadVariance(this->Renderer, variance, varianceWidth, varianceHeight))
  {
    return Image{};
  }
  return FromRgba(rgba, width, height, variance);
}

void Dump(const Image& image, const std::string& name)
{
  const char* directory = std::getenv("CLOUDVIS_RENDER_DUMP");
  if (!directory || image.Components < 3)
  {
    return;
  }
  Image color = image;
  color.Components = 3;
  color.Values.clear();
  for (size_t p = 0; p < image.Pixels(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      color.Values.push_back(image.At(p, c));
    }
  }
  WritePng(color, std::string(directory) + "/" + name + ".png");
}

} // namespace support
} // namespace cloudvis
