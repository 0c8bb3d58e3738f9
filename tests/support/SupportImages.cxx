// Reading, grabbing and comparing images for the tests (SupportImages.h).
#include "SupportImages.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfFloatAttribute.h>
#include <ImfStringAttribute.h>

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cloudvis
{
namespace support
{
namespace
{
// The values of an 8- or 16-bit vtkImageData, scaled to [0, 1].
Image FromVtk(vtkImageData* pixels)
{
  Image image;
  vtkDataArray* scalars = pixels ? pixels->GetPointData()->GetScalars() : nullptr;
  if (!scalars)
  {
    return image;
  }
  int dimensions[3];
  pixels->GetDimensions(dimensions);
  image.Width = dimensions[0];
  image.Height = dimensions[1];
  image.Components = scalars->GetNumberOfComponents();
  image.Bits = pixels->GetScalarType() == VTK_UNSIGNED_SHORT ? 16 : 8;
  const double maximum = image.Bits == 16 ? 65535.0 : 255.0;
  image.Values.resize(size_t(scalars->GetNumberOfValues()));
  for (vtkIdType i = 0; i < scalars->GetNumberOfValues(); ++i)
  {
    image.Values[size_t(i)] = scalars->GetVariantValue(i).ToDouble() / maximum;
  }
  return image;
}
}

Image FromRgba(const std::vector<float>& rgba,
  int width,
  int height,
  const std::vector<float>& variance)
{
  Image image;
  image.Width = width;
  image.Height = height;
  image.Components = 4;
  image.Bits = 32;
  image.Values.assign(rgba.begin(), rgba.end());
  image.Variance.assign(variance.begin(), variance.end());
  return image;
}

Image ReadPng(const std::string& path)
{
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    return Image{};
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  Image image = FromVtk(reader->GetOutput());
  for (size_t i = 0; i < reader->GetNumberOfTextChunks(); ++i)
  {
    image.Text[reader->GetTextKey(int(i))] = reader->GetTextValue(int(i));
  }
  return image;
}

bool WritePng(const Image& image, const std::string& path)
{
  const int components = std::min(image.Components, 4);
  if (image.Width < 1 || image.Height < 1 || components < 1)
  {
    return false;
  }
  vtkNew<vtkImageData> pixels;
  pixels->SetDimensions(image.Width, image.Height, 1);
  pixels->AllocateScalars(VTK_UNSIGNED_CHAR, components);
  auto* data = static_cast<unsigned char*>(pixels->GetScalarPointer());
  for (int y = 0; y < image.Height; ++y)
  {
    for (int x = 0; x < image.Width; ++x)
    {
      for (int c = 0; c < components; ++c)
      {
        const double v = std::min(1.0, std::max(0.0, image.At(x, y, c)));
        *data++ = static_cast<unsigned char>(std::lround(255.0 * v));
      }
    }
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(pixels);
  writer->SetFileName(path.c_str());
  writer->Write();
  return writer->GetErrorCode() == 0;
}

Image GrabWindow(vtkRenderWindow* window, bool alpha, bool rerender)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetShouldRerender(rerender);
  if (alpha)
  {
    grab->SetInputBufferTypeToRGBA();
  }
  grab->ReadFrontBufferOff();
  grab->Update();
  return FromVtk(grab->GetOutput());
}

Exr ReadExr(const std::string& path)
{
  Imf::InputFile file(path.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  Exr exr;
  exr.Width = window.max.x - window.min.x + 1;
  exr.Height = window.max.y - window.min.y + 1;
  Imf::FrameBuffer frame;
  for (auto c = file.header().channels().begin(); c != file.header().channels().end(); ++c)
  {
    exr.Types[c.name()] = c.channel().type;
    std::vector<float>& data = exr.Channels[c.name()];
    data.resize(size_t(exr.Width) * size_t(exr.Height));
    frame.insert(c.name(),
      Imf::Slice(Imf::FLOAT,
        reinterpret_cast<char*>(data.data()),
        sizeof(float),
        sizeof(float) * size_t(exr.Width)));
  }
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  for (auto a = file.header().begin(); a != file.header().end(); ++a)
  {
    if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&a.attribute()))
    {
      exr.Strings[a.name()] = text->value();
    }
    else if (const auto* number = dynamic_cast<const Imf::FloatAttribute*>(&a.attribute()))
    {
      exr.Floats[a.name()] = number->value();
    }
  }
  return exr;
}

double AutoExposureOf(const Exr& exr, size_t& cloudPixels)
{
  std::vector<double> luminance;
  for (const double minimumAlpha : { 0.5, 1.0 / 255.0 })
  {
    for (int y = 0; y < exr.Height; ++y)
    {
      for (int x = 0; x < exr.Width; ++x)
      {
        const double a = exr.At("A", x, y);
        if (a >= minimumAlpha)
        {
          luminance.push_back(
            (0.2126 * exr.At("R", x, y) + 0.7152 * exr.At("G", x, y) + 0.0722 * exr.At("B", x, y)) /
            a);
        }
      }
    }
    if (!luminance.empty())
    {
      break;
    }
  }
  cloudPixels = luminance.size();
  if (luminance.empty())
  {
    return 0.0;
  }
  std::sort(luminance.begin(), luminance.end());
  const double p99 = luminance[size_t(std::floor(0.99 * double(luminance.size() - 1) + 0.5))];
  return p99 > 0.0 ? std::log2(1.2 / p99) : 0.0;
}

Image OverBackground(const Image& premultiplied, double r, double g, double b)
{
  Image image = premultiplied;
  image.Bits = 8;
  image.Variance.clear();
  const double background[3] = { r, g, b };
  for (size_t p = 0; p < image.Pixels(); ++p)
  {
    const double alpha = premultiplied.At(p, 3);
    for (int c = 0; c < 3; ++c)
    {
      const double v = premultiplied.At(p, c) + (1.0 - alpha) * background[c];
      image.Values[4 * p + size_t(c)] = std::round(255.0 * std::min(1.0, std::max(0.0, v))) / 255.0;
    }
    image.Values[4 * p + 3] = 1.0;
  }
  return image;
}

Image Crop(const Image& image, const Region& region)
{
  Image crop;
  crop.Components = image.Components;
  crop.Bits = image.Bits;
  crop.Width = region.Width > 0 ? region.Width : image.Width - region.X;
  crop.Height = region.Height > 0 ? region.Height : image.Height - region.Y;
  for (int y = region.Y; y < region.Y + crop.Height; ++y)
  {
    for (int x = region.X; x < region.X + crop.Width; ++x)
    {
      for (int c = 0; c < image.Components; ++c)
      {
        crop.Values.push_back(image.At(x, y, c));
      }
    }
  }
  return crop;
}

Difference Compare(const Image& a, const Image& b, int channels, const Mask& mask, int first)
{
  Difference difference;
  if (a.Width != b.Width || a.Height != b.Height || a.Components != b.Components ||
    a.Values.empty())
  {
    difference.Rms = difference.Max = difference.Mean = std::numeric_limits<double>::infinity();
    return difference;
  }
  const int end = channels > 0 ? std::min(first + channels, a.Components) : a.Components;
  double sum = 0.0, squares = 0.0;
  for (int y = 0; y < a.Height; ++y)
  {
    for (int x = 0; x < a.Width; ++x)
    {
      if (mask && !mask(x, y))
      {
        continue;
      }
      for (int c = first; c < end; ++c)
      {
        const double d = std::fabs(a.At(x, y, c) - b.At(x, y, c));
        sum += d;
        squares += d * d;
        // std::max would drop a NaN; a NaN value is no match for anything.
        difference.Max =
          std::isnan(d) || std::isnan(difference.Max) ? std::nan("") : std::max(difference.Max, d);
        ++difference.Count;
      }
    }
  }
  if (difference.Count > 0)
  {
    difference.Mean = sum / double(difference.Count);
    difference.Rms = std::sqrt(squares / double(difference.Count));
  }
  return difference;
}

double Largest(const Image& image, int channels, const Mask& mask, int first)
{
  const int end = channels > 0 ? std::min(first + channels, image.Components) : image.Components;
  double largest = 0.0;
  for (int y = 0; y < image.Height; ++y)
  {
    for (int x = 0; x < image.Width; ++x)
    {
      for (int c = first; c < end && (!mask || mask(x, y)); ++c)
      {
        largest = std::max(largest, image.At(x, y, c));
      }
    }
  }
  return largest;
}

Mask ShowsCloud(const Image& a, const Image& b)
{
  return [&a, &b](int x, int y)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (a.At(x, y, c) > 0.0 || b.At(x, y, c) > 0.0)
      {
        return true;
      }
    }
    return false;
  };
}

Mask OpacityAbove(const Image& a, const Image& b, double opacity)
{
  return [&a, &b, opacity](int x, int y)
  { return a.At(x, y, 3) > opacity || b.At(x, y, 3) > opacity; };
}

size_t CountPixels(const Image& image, const Mask& mask)
{
  size_t count = 0;
  for (int y = 0; y < image.Height; ++y)
  {
    for (int x = 0; x < image.Width; ++x)
    {
      count += mask(x, y) ? 1 : 0;
    }
  }
  return count;
}

double RmsDifference(const Image& a, const Image& b)
{
  return Compare(a, b, 3).RmsLevels();
}

double MaxDifference(const Image& a, const Image& b)
{
  return Compare(a, b).Max;
}

double MeanOver(const Image& image, int channel, const Region& region)
{
  const int width = region.Width > 0 ? region.Width : image.Width - region.X;
  const int height = region.Height > 0 ? region.Height : image.Height - region.Y;
  double sum = 0.0;
  for (int y = region.Y; y < region.Y + height; ++y)
  {
    for (int x = region.X; x < region.X + width; ++x)
    {
      sum += image.At(x, y, channel);
    }
  }
  return sum / (double(width) * double(height));
}

double MeanRadiance(const Image& image, const Region& region)
{
  return MeanOver(image, 0, region) + MeanOver(image, 1, region) + MeanOver(image, 2, region);
}

Estimate MeanOverPixels(const Image& image,
  const PixelFunction& f,
  const PixelFunction& v,
  const PixelSelection& use)
{
  double sum = 0.0, variance = 0.0;
  int n = 0;
  for (size_t p = 0; p < image.Pixels(); ++p)
  {
    if (!use || use(p))
    {
      sum += f(p);
      variance += v(p);
      ++n;
    }
  }
  return { sum / n, std::sqrt(variance) / n };
}

double MeanOf(const Image& image, int channel, const PixelSelection& use)
{
  return MeanOverPixels(
    image, [&](size_t p) { return image.At(p, channel); }, [](size_t) { return 0.0; }, use)
    .Mean;
}

Estimate MeanWithError(const Image& image, int channel, const PixelSelection& use)
{
  return MeanOverPixels(image,
    [&](size_t p) { return image.At(p, channel); },
    [&](size_t p) { return image.VarianceAt(p, channel); },
    use);
}

double LargestBlockZ(const Image& image,
  int blockSize,
  const PixelFunction& difference,
  const PixelFunction& variance,
  const PixelSelection& use,
  int& blocks)
{
  double largest = 0.0;
  blocks = 0;
  for (int bj = 0; bj + blockSize <= image.Height; bj += blockSize)
  {
    for (int bi = 0; bi + blockSize <= image.Width; bi += blockSize)
    {
      double sum = 0.0, v = 0.0;
      int used = 0;
      for (int j = bj; j < bj + blockSize; ++j)
      {
        for (int i = bi; i < bi + blockSize; ++i)
        {
          const size_t p = size_t(j) * size_t(image.Width) + size_t(i);
          if (!use || use(p))
          {
            sum += difference(p);
            v += variance(p);
            ++used;
          }
        }
      }
      if (2 * used >= blockSize * blockSize && v > 0.0)
      {
        largest = std::max(largest, std::abs(sum) / std::sqrt(v));
        ++blocks;
      }
    }
  }
  return largest;
}

Image DifferenceImage(const Image& a, const Image& b, double gain)
{
  Image image;
  if (a.Width != b.Width || a.Height != b.Height || a.Components != b.Components)
  {
    return image;
  }
  image.Width = a.Width;
  image.Height = a.Height;
  image.Components = 3;
  image.Bits = 8;
  for (int y = 0; y < a.Height; ++y)
  {
    for (int x = 0; x < a.Width; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        const int k = std::min(c, a.Components - 1);
        image.Values.push_back(std::min(1.0, gain * std::fabs(a.At(x, y, k) - b.At(x, y, k))));
      }
    }
  }
  return image;
}

} // namespace support
} // namespace cloudvis
