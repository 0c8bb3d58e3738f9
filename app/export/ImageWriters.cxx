// PNG through vtkPNGWriter (8- or 16-bit samples from unsigned char or unsigned short scalars,
// tEXt chunks from AddText), EXR through OpenEXR's scan-line Imf::OutputFile. Both write onto
// the checked stream of the atomic write (AtomicFile.h), not to a file of their own: PNG from
// memory (WriteToMemory), EXR through an Imf::OStream over the stream. Rows: VTK and the
// mapper keep them bottom to top, which is what vtkPNGWriter expects; EXR stores the top row
// first, so the EXR writer hands OpenEXR one line at a time, from the last in memory.
#include "ImageWriters.h"

#include "AtomicFile.h"
#include "Errors.h"
#include "FileNames.h"
#include "VtkMessageCapture.h"
#include "Words.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <ImfFloatAttribute.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <vector>

#ifndef CLOUDVIS_VERSION
#error "CLOUDVIS_VERSION must be defined (app/CMakeLists.txt passes the project version)"
#endif

namespace cloudvis
{

std::string ShowExposure(double ev)
{
  char text[32];
  std::snprintf(text, sizeof text, "%+.2f EV", ev);
  return text;
}

namespace
{

// A display value in [0, 1] as an n-bit sample.
template <typename T>
T Quantize(double value, double maximum)
{
  return T(std::lround(std::min(std::max(value, 0.0), 1.0) * maximum));
}

// The float image as display values, per pixel: opaque, the "over" of the cloud on the
// background the window drew (the computation the GPU's blend does for the 8-bit window, here
// without its rounding); transparent, the straight color (premultiplied color / alpha) and the
// alpha. The mapper's radiance goes through the display transform the window applied (the
// image's exposure and curve, the shared source of CloudDisplayTransform.h), so every PNG of a
// scene shows the same picture (docs/export.md).
template <typename T>
void FillDisplayPixels(const RenderedImage& image, bool transparent, T* out)
{
  const double maximum = double(std::numeric_limits<T>::max());
  const size_t pixels = size_t(image.Width) * size_t(image.Height);
  const int components = transparent ? 4 : 3;
  for (size_t p = 0; p < pixels; ++p)
  {
    const float* premultiplied = image.Radiance.data() + 4 * p;
    const glm::vec3 c = DisplayValueOf(
      glm::vec3(premultiplied[0], premultiplied[1], premultiplied[2]), premultiplied[3],
      image.ExposureEV, image.Display);
    const double alpha = std::min(std::max(double(premultiplied[3]), 0.0), 1.0);
    T* o = out + components * p;
    for (int k = 0; k < 3; ++k)
    {
      double value;
      if (transparent)
      {
        value = alpha > 0.0 ? double(c[k]) / alpha : 0.0;
      }
      else
      {
        value = double(c[k]) + (1.0 - alpha) * image.BackgroundRGB[3 * p + k] / 255.0;
      }
      o[k] = Quantize<T>(value, maximum);
    }
    if (transparent)
    {
      o[3] = Quantize<T>(alpha, maximum);
    }
  }
}

// OpenEXR's output onto a std::ostream: it seeks back to fill in the line offsets. A failed
// stream throws, which OpenEXR passes on; the atomic write then names the OS reason.
class ExrStream : public Imf::OStream
{
public:
  explicit ExrStream(std::ostream& out)
    : Imf::OStream("the EXR image")
    , Out(out)
  {
  }
  void write(const char c[], int n) override
  {
    if (!this->Out.write(c, n))
    {
      throw std::runtime_error("the write failed");
    }
  }
  uint64_t tellp() override
  {
    const std::streamoff at = this->Out.tellp();
    if (at < 0)
    {
      throw std::runtime_error("the stream has no position");
    }
    return uint64_t(at);
  }
  void seekp(uint64_t position) override
  {
    if (!this->Out.seekp(std::streamoff(position)))
    {
      throw std::runtime_error("the seek failed");
    }
  }

private:
  std::ostream& Out;
};

// One scan line at a time through a row buffer per channel (y stride 0: every line of the
// frame buffer is the same memory), filled from the bottom-up buffers in EXR's top-down order.
// OpenEXR writes a channel from a slice of its own pixel type only, hence T = float or half.
template <typename T>
void WriteExrScanLines(const RenderedImage& image, const ImageExportOptions& options,
  std::ostream& out, Imf::PixelType type)
{
  // A path-traced image adds the variance of each RGBA mean, as the layer "variance".
  const bool variance = !image.Variance.empty();
  std::vector<const char*> names = { "R", "G", "B", "A", "Z", "transmittance", "samples" };
  if (variance)
  {
    names.insert(names.end(), { "variance.R", "variance.G", "variance.B", "variance.A" });
  }
  const size_t channels = names.size();
  const size_t width = size_t(image.Width);
  std::vector<T> row(channels * width);
  Imf::Header header(image.Width, image.Height);
  Imf::FrameBuffer frame;
  for (size_t c = 0; c < channels; ++c)
  {
    header.channels().insert(names[c], Imf::Channel(type));
    frame.insert(
      names[c], Imf::Slice(type, reinterpret_cast<char*>(row.data() + c * width), sizeof(T), 0));
  }
  header.insert("cloudvis.version", Imf::StringAttribute(CloudvisVersion()));
  // The channels stay linear radiance; what the PNG of the same render shows is recorded.
  header.insert("cloudvis.radiance",
    Imf::StringAttribute("linear, premultiplied by alpha, in the lights' radiance units (a light "
                         "of intensity 1 facing a white albedo-1 surface gives about 1); not "
                         "exposed"));
  header.insert("cloudvis.exposure_ev", Imf::FloatAttribute(float(image.ExposureEV)));
  header.insert("cloudvis.display", Imf::StringAttribute(DisplayCurveName(image.Display)));
  header.insert("cloudvis.scene", Imf::StringAttribute(options.SceneJson));
  header.insert("cloudvis.command", Imf::StringAttribute(options.CommandLine));
  if (!image.Coarsened.empty())
  {
    header.insert("cloudvis.coarsened", Imf::StringAttribute(image.Coarsened));
  }
  ExrStream stream(out);
  Imf::OutputFile file(stream, header);
  file.setFrameBuffer(frame);
  for (int y = image.Height - 1; y >= 0; --y)
  {
    const float* radiance = image.Radiance.data() + 4 * width * size_t(y);
    const float* auxiliary = image.Auxiliary.data() + 4 * width * size_t(y);
    for (size_t x = 0; x < width; ++x)
    {
      for (size_t k = 0; k < 4; ++k)
      {
        row[k * width + x] = T(radiance[4 * x + k]);
      }
      row[4 * width + x] = T(auxiliary[4 * x + 2]);         // Z
      row[5 * width + x] = T(1.0f - radiance[4 * x + 3]); // transmittance
      row[6 * width + x] = T(auxiliary[4 * x + 0]);         // samples
      for (size_t k = 0; variance && k < 4; ++k)
      {
        row[(7 + k) * width + x] = T(image.Variance[4 * (width * size_t(y) + x) + k]);
      }
    }
    file.writePixels(1);
  }
}

// The writers of the format table. They write onto `out` (the checked stream of the atomic
// write, AtomicFile.h); `target` names the output in errors (InputError).
void WritePngImage(const RenderedImage& image, const ImageExportOptions& options,
  std::ostream& out, const std::string& target)
{
  vtkNew<vtkImageData> pixels;
  pixels->SetDimensions(image.Width, image.Height, 1);
  const bool fromFloat = NeedsFloatImage(target, options);
  if (fromFloat && (image.Radiance.size() != 4 * size_t(image.Width) * size_t(image.Height) ||
                     (!options.Transparent && image.BackgroundRGB.size() != image.RGB.size())))
  {
    throw InputError(target + ": cannot write the PNG image: the float render was not kept");
  }
  const int components = options.Transparent ? 4 : 3;
  if (options.PngBits == 16)
  {
    pixels->AllocateScalars(VTK_UNSIGNED_SHORT, components);
    FillDisplayPixels(
      image, options.Transparent, static_cast<std::uint16_t*>(pixels->GetScalarPointer()));
  }
  else if (options.Transparent)
  {
    pixels->AllocateScalars(VTK_UNSIGNED_CHAR, components);
    FillDisplayPixels(image, true, static_cast<unsigned char*>(pixels->GetScalarPointer()));
  }
  else
  {
    pixels->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    std::copy(image.RGB.begin(), image.RGB.end(),
      static_cast<unsigned char*>(pixels->GetScalarPointer()));
  }
  VtkMessageCapture messages;
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(pixels);
  writer->WriteToMemoryOn();
  writer->AddText("Software", ("cloudvis " + CloudvisVersion()).c_str());
  if (!options.SceneJson.empty())
  {
    writer->AddText("cloudvis.scene", options.SceneJson.c_str());
  }
  if (!options.CommandLine.empty())
  {
    writer->AddText("cloudvis.command", options.CommandLine.c_str());
  }
  if (!image.Coarsened.empty())
  {
    writer->AddText("cloudvis.coarsened", image.Coarsened.c_str());
  }
  writer->AddText("cloudvis.display",
    (DisplayCurveName(image.Display) + ", exposure " + ShowExposure(image.ExposureEV)).c_str());
  writer->Write();
  vtkUnsignedCharArray* encoded = writer->GetResult();
  if (writer->GetErrorCode() != 0 || !messages.Messages().empty() || !encoded)
  {
    throw InputError(messages.WithVtkReason(target + ": cannot write the PNG image"));
  }
  out.write(reinterpret_cast<const char*>(encoded->GetPointer(0)),
    std::streamsize(encoded->GetNumberOfValues()));
}

void WriteExrImage(const RenderedImage& image, const ImageExportOptions& options,
  std::ostream& out, const std::string& target)
{
  const size_t pixels = size_t(image.Width) * size_t(image.Height);
  if (image.Radiance.size() != 4 * pixels || image.Auxiliary.size() != 4 * pixels ||
    (!image.Variance.empty() && image.Variance.size() != 4 * pixels))
  {
    throw InputError(target + ": cannot write the EXR image: the float render was not kept");
  }
  try
  {
    if (options.ExrHalf)
    {
      WriteExrScanLines<half>(image, options, out, Imf::HALF);
    }
    else
    {
      WriteExrScanLines<float>(image, options, out, Imf::FLOAT);
    }
  }
  catch (const std::exception& e)
  {
    throw InputError(target + ": cannot write the EXR image (OpenEXR: " + e.what() + ")");
  }
}

// Output formats: one entry per extension, with its writer (above).
struct ImageFormat
{
  const char* Extension;
  const char* What; // in "cannot write WHAT: REASON"
  // Writes onto `out` (the temporary's checked stream); `target` names the file in errors.
  void (*Write)(const RenderedImage& image,
    const ImageExportOptions& options,
    std::ostream& out,
    const std::string& target);
};

const ImageFormat ImageFormats[] = {
  { ".png", "the PNG image", WritePngImage },
  { ".exr", "the EXR image", WriteExrImage },
};

// The image formats cloudvis writes, as lower-case extensions with the dot (".png").
std::vector<std::string> SupportedImageExtensions()
{
  std::vector<std::string> extensions;
  for (const ImageFormat& format : ImageFormats)
  {
    extensions.emplace_back(format.Extension);
  }
  return extensions;
}

const ImageFormat& FormatOf(const std::string& path)
{
  const std::string extension = LowerCaseExtension(path);
  for (const ImageFormat& format : ImageFormats)
  {
    if (extension == format.Extension)
    {
      return format;
    }
  }
  throw InputError(path + ": " +
    (extension.empty() ? std::string("the file name has no image extension")
                       : "unsupported image format \"" + extension + "\"") +
    "; supported: " + Join(SupportedImageExtensions()));
}

} // namespace

std::string CloudvisVersion()
{
  return CLOUDVIS_VERSION;
}

bool NeedsFloatImage(const std::string& path, const ImageExportOptions& options)
{
  return LowerCaseExtension(path) == ".exr" || options.PngBits == 16 || options.Transparent;
}

void CheckImageOutput(const std::string& path)
{
  FormatOf(path);
  CheckOutputTarget(path);
}

void WriteImage(const RenderedImage& image, const std::string& path)
{
  WriteImage(image, path, ImageExportOptions{});
}

void WriteImage(
  const RenderedImage& image, const std::string& path, const ImageExportOptions& options)
{
  const ImageFormat& format = FormatOf(path);
  WriteStreamAtomically(
    path, format.What, [&](std::ostream& out) { format.Write(image, options, out, path); });
}

} // namespace cloudvis
