#include "RenderFixture.h"

#include "vtkCloudDensitySource.h"

#include <vtkCamera.h>
#include <vtkFloatArray.h>
#include <vtkLight.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <stdexcept>

namespace cloudvis
{
namespace test
{
namespace
{
vtkSmartPointer<vtkImageData> Generate(const FieldDescription& field, int size, double extent)
{
  vtkNew<vtkCloudDensitySource> source;
  source->SetDimensions(size, size, size);
  source->SetBounds(-extent, extent, -extent, extent, -extent, extent);
  source->SetField(field);
  source->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(source->GetOutput());
  return image;
}
}

vtkSmartPointer<vtkImageData> ConstantSphere(double radius, int size)
{
  FieldDescription field;
  field.Model = DensityModel::Constant;
  field.Shapes[0].Radius = float(radius);
  return Generate(field, size, 2.0);
}

vtkSmartPointer<vtkImageData> ConstantBox(double halfSize, int size, double extent)
{
  FieldDescription field;
  field.Model = DensityModel::Constant;
  field.Shapes[0].Type = ShapeType::Box;
  field.Shapes[0].HalfSize = glm::vec3(float(halfSize));
  return Generate(field, size, extent);
}

vtkSmartPointer<vtkImageData> SparseCloud(int size)
{
  FieldDescription field; // the article's cloud: unit sphere + 6 octaves
  return Generate(field, size, 2.0);
}

vtkSmartPointer<vtkImageData> DenseCloud(int size)
{
  FieldDescription field;
  field.Shapes[0].Type = ShapeType::Box;
  field.Shapes[0].HalfSize = glm::vec3(2.5f);
  field.DensityScale = 0.5;
  return Generate(field, size, 2.0);
}

void SetUniformMedium(
  vtkVolumeProperty* property, double opacity, double unitDistance, double r, double g, double b)
{
  vtkNew<vtkPiecewiseFunction> o;
  o->AddPoint(0.0, 0.0);
  o->AddPoint(0.49, 0.0);
  o->AddPoint(0.51, opacity);
  o->AddPoint(1.0, opacity);
  vtkNew<vtkColorTransferFunction> c;
  c->AddRGBPoint(0.0, r, g, b);
  c->AddRGBPoint(1.0, r, g, b);
  property->SetScalarOpacity(o);
  property->SetColor(c);
  property->SetScalarOpacityUnitDistance(unitDistance);
  property->SetInterpolationTypeToLinear();
  property->ShadeOff();
}

void SetRampMedium(vtkVolumeProperty* property, double max, double opacity)
{
  vtkNew<vtkPiecewiseFunction> o;
  o->AddPoint(0.0, 0.0);
  o->AddPoint(max, opacity);
  vtkNew<vtkColorTransferFunction> c;
  c->AddRGBPoint(0.0, 0.9, 0.5, 0.2);
  c->AddRGBPoint(max, 0.3, 0.6, 1.0);
  property->SetScalarOpacity(o);
  property->SetColor(c);
  property->SetScalarOpacityUnitDistance(0.1);
  property->SetInterpolationTypeToLinear();
  property->ShadeOff();
}

Scene::Scene(vtkVolumeMapper* mapper, int width, int height)
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

void Scene::SetInput(vtkImageData* field)
{
  this->Mapper->SetInputDataObject(field);
}

void Scene::LookAlongMinusZ(double distance, bool parallel, double parallelScale)
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

namespace
{
Image Grab(vtkRenderWindow* window, bool render)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGBA();
  grab->ReadFrontBufferOff();
  grab->SetShouldRerender(render);
  grab->Update();
  vtkImageData* pixels = grab->GetOutput();
  int dims[3];
  pixels->GetDimensions(dims);
  Image image;
  image.Width = dims[0];
  image.Height = dims[1];
  auto* data = vtkUnsignedCharArray::SafeDownCast(pixels->GetPointData()->GetScalars());
  image.RGBA.resize(size_t(image.Width) * image.Height * 4);
  for (size_t i = 0; i < image.RGBA.size(); ++i)
  {
    image.RGBA[i] = data->GetValue(vtkIdType(i)) / 255.0f;
  }
  return image;
}
}

Image Scene::Render()
{
  this->Window->Render();
  return Grab(this->Window, true);
}

Image Scene::RenderOnce()
{
  this->Window->Render();
  return Grab(this->Window, false);
}

Image Scene::RenderFloat()
{
  this->Window->Render();
  auto* cloud = vtkCloudVolumeMapper::SafeDownCast(this->Mapper);
  Image image;
  if (!cloud || !cloud->ReadImage(this->Renderer, image.RGBA, image.Width, image.Height))
  {
    throw std::runtime_error("no float image to read");
  }
  return image;
}

void Dump(const Image& image, const std::string& name)
{
  const char* directory = std::getenv("CLOUDVIS_RENDER_DUMP");
  if (!directory)
  {
    return;
  }
  vtkNew<vtkImageData> pixels;
  pixels->SetDimensions(image.Width, image.Height, 1);
  pixels->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
  auto* data = static_cast<unsigned char*>(pixels->GetScalarPointer());
  for (size_t i = 0; i < image.RGBA.size(); ++i)
  {
    const float v = i % 4 == 3 ? 1.0f : std::min(1.0f, std::max(0.0f, image.RGBA[i]));
    data[i] = static_cast<unsigned char>(std::lround(v * 255.0f));
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(pixels);
  writer->SetFileName((std::string(directory) + "/" + name + ".png").c_str());
  writer->Write();
}

void AddDirectionalLight(vtkRenderer* renderer, double fromX, double fromY, double fromZ,
  double intensity, double r, double g, double b)
{
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetPosition(fromX, fromY, fromZ);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetDiffuseColor(r, g, b);
  light->SetIntensity(intensity);
  renderer->AddLight(light);
}

void AddPointLight(vtkRenderer* renderer, double x, double y, double z, double intensity,
  double r, double g, double b)
{
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(180.0);
  light->SetPosition(x, y, z);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetDiffuseColor(r, g, b);
  light->SetIntensity(intensity);
  light->SetAttenuationValues(0.0, 0.0, 1.0);
  renderer->AddLight(light);
}

double MeanOver(const Image& image, int channel, int x0, int x1)
{
  double sum = 0.0;
  for (int y = 0; y < image.Height; ++y)
    for (int x = x0; x < x1; ++x)
      sum += image.At(x, y, channel);
  return sum / (double(image.Height) * (x1 - x0));
}

CloudDifference CloudPixelDifference(const Image& a, const Image& b)
{
  CloudDifference d;
  if (a.Width != b.Width || a.Height != b.Height)
  {
    d.RmsLevels = d.MaxLevels = 1e9;
    return d;
  }
  double sum = 0.0;
  for (size_t i = 0; i < a.RGBA.size(); i += 4)
  {
    const float shown = std::max(
      { a.RGBA[i], a.RGBA[i + 1], a.RGBA[i + 2], b.RGBA[i], b.RGBA[i + 1], b.RGBA[i + 2] });
    if (!(shown > 0.0f))
    {
      continue;
    }
    ++d.CloudPixels;
    for (size_t c = 0; c < 3; ++c)
    {
      const double level = 255.0 * std::abs(double(a.RGBA[i + c]) - double(b.RGBA[i + c]));
      sum += level * level;
      d.MaxLevels = std::max(d.MaxLevels, level);
    }
  }
  d.RmsLevels = d.CloudPixels ? std::sqrt(sum / (3.0 * d.CloudPixels)) : 0.0;
  return d;
}

double RmsDifference(const Image& a, const Image& b)
{
  if (a.Width != b.Width || a.Height != b.Height)
  {
    return 1e9;
  }
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < a.RGBA.size(); ++i)
  {
    if (i % 4 != 3)
    {
      const double d = 255.0 * (a.RGBA[i] - b.RGBA[i]);
      sum += d * d;
      ++n;
    }
  }
  return std::sqrt(sum / double(n));
}

double MaxDifference(const Image& a, const Image& b)
{
  if (a.Width != b.Width || a.Height != b.Height)
  {
    return 1e9;
  }
  double largest = 0.0;
  for (size_t i = 0; i < a.RGBA.size(); ++i)
  {
    const double d = std::abs(double(a.RGBA[i]) - double(b.RGBA[i]));
    if (std::isnan(d))
    {
      return d; // a NaN pixel is no match for anything (std::max would drop it)
    }
    largest = std::max(largest, d);
  }
  return largest;
}

} // namespace test
} // namespace cloudvis
