// Images as the tests see them: PNG and EXR files read back with independent readers
// (vtkPNGReader, OpenEXR's Imf::InputFile), a render window's pixels, the renderers' float
// images (the mapper's float target, the CPU reference's and the path tracer's outputs, with
// their per-pixel variances), and the one set of metrics that compares them: differences (RMS,
// largest, mean, over a mask such as the cloud's pixels), means over a region, and the
// statistics of a Monte Carlo image. Every test program uses these; none carries its own image
// type, reader or difference function.
//
// An Image holds `Components` values per pixel, rows bottom to top (VTK's order, the mapper's),
// scaled to [0, 1] for 8- and 16-bit files, so that a difference of 1/255 is one 8-bit level
// whatever the file's depth; float images (EXR, the mapper's float target, the CPU renderers)
// hold linear values as they are: premultiplied RGBA, 4 components.
#ifndef cloudvis_SupportImages_h
#define cloudvis_SupportImages_h

#include <ImfPixelType.h>

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

class vtkRenderWindow;

namespace cloudvis
{
namespace support
{

struct Image
{
  int Width = 0, Height = 0, Components = 0;
  int Bits = 0;                            // per value: 8 or 16 for a PNG, 32 for floats
  std::vector<double> Values;              // Width * Height * Components
  // For a path-traced image: the variance of each value's mean, laid out as Values; else empty.
  std::vector<double> Variance;
  std::map<std::string, std::string> Text; // a PNG's text chunks (key -> value)

  size_t Pixels() const { return size_t(this->Width) * size_t(this->Height); }
  double At(int x, int y, int c) const
  {
    return this->At(size_t(y) * size_t(this->Width) + size_t(x), c);
  }
  // Pixel p counts rows from the bottom: p = y * Width + x.
  double At(size_t p, int c) const
  {
    return this->Values[p * size_t(this->Components) + size_t(c)];
  }
  double VarianceAt(size_t p, int c) const
  {
    return this->Variance[p * size_t(this->Components) + size_t(c)];
  }
  // The value in 8-bit levels (0 .. 255).
  double Level(int x, int y, int c) const { return 255.0 * this->At(x, y, c); }
  // r + g + b at a pixel.
  double Radiance(int x, int y) const
  {
    return this->At(x, y, 0) + this->At(x, y, 1) + this->At(x, y, 2);
  }
};

// A renderer's float RGBA image (4 values a pixel, rows bottom to top) and, when given, the
// variances of its means: what vtkCloudVolumeMapper::ReadImage and ReadVariance, and the "rgba"
// and "rgba_variance" arrays of the CPU renderers, hold.
Image FromRgba(const std::vector<float>& rgba,
  int width,
  int height,
  const std::vector<float>& variance = {});

// A PNG file, 8 or 16 bits per channel, with its text chunks. An unreadable file gives an empty
// image (Width 0).
Image ReadPng(const std::string& path);

// Writes the first three (or four) channels as an 8-bit PNG, each value clamped to [0, 1].
// Returns false when the file could not be written.
bool WritePng(const Image& image, const std::string& path);

// A render window's back buffer, 8-bit RGB (or RGBA), as the window shows it after Render().
// `rerender` false reads what the last render left without rendering again.
Image GrabWindow(vtkRenderWindow* window, bool alpha = false, bool rerender = true);

// An OpenEXR file: every channel as floats, its pixel type, and the string attributes.
struct Exr
{
  int Width = 0, Height = 0;
  std::map<std::string, Imf::PixelType> Types;
  std::map<std::string, std::vector<float>> Channels; // rows top to bottom, as stored
  std::map<std::string, std::string> Strings;
  std::map<std::string, float> Floats;
  // Channel value at (x, y) with y counted from the bottom, like VTK and the mapper.
  float At(const std::string& name, int x, int y) const
  {
    return this->Channels.at(name)[size_t(this->Height - 1 - y) * size_t(this->Width) + size_t(x)];
  }
};
// Throws (OpenEXR's exceptions) when the file cannot be read.
Exr ReadExr(const std::string& path);

// The EV render.exposure "auto" gives the float image of an EXR, computed here from its channels
// as docs/export.md defines it, apart from the product's code: the 99th percentile of the
// luminance of R G B / A over the pixels at least half opaque (or, with none, at least one 8-bit
// level) put at 1.2. `cloudPixels` receives how many it metered.
double AutoExposureOf(const Exr& exr, size_t& cloudPixels);

// A premultiplied RGBA image composited over an opaque background, c + (1 - a) * background,
// rounded to 8-bit levels as a window shows it (alpha 1).
Image OverBackground(const Image& premultiplied, double r, double g, double b);

// ---- metrics -------------------------------------------------------------------------------

// A rectangle of pixels; a Width or Height of 0 reaches the image's edge.
struct Region
{
  int X = 0, Y = 0, Width = 0, Height = 0;
};
Image Crop(const Image& image, const Region& region);

// Which pixels a comparison looks at: (x, y) -> true to count it. Empty: all.
using Mask = std::function<bool(int x, int y)>;

// |a - b| over the values two images of the same size share: the first `channels` channels of
// each pixel (0: all; 3 leaves alpha out) of the pixels `mask` accepts. In the images' units:
// Levels() turns [0, 1] values into 8-bit levels. Images of different sizes differ infinitely;
// a NaN in either image makes Max (and Rms, Mean) NaN, so that no tolerance accepts it.
struct Difference
{
  size_t Count = 0;
  double Rms = 0.0, Max = 0.0, Mean = 0.0;
  double RmsLevels() const { return 255.0 * this->Rms; }
  double MaxLevels() const { return 255.0 * this->Max; }
  double MeanLevels() const { return 255.0 * this->Mean; }
};
// `first` skips channels: Compare(a, b, 1, mask, 3) compares the opacities alone.
Difference Compare(const Image& a,
  const Image& b,
  int channels = 0,
  const Mask& mask = {},
  int first = 0);
// The largest of `channels` values (0: all) from channel `first` over the pixels `mask` accepts:
// Largest(image, 3) the brightest color, Largest(image, 1, {}, 3) the largest opacity.
double Largest(const Image& image, int channels = 0, const Mask& mask = {}, int first = 0);

// The pixels where either image shows cloud over a black background: a color above 0.
Mask ShowsCloud(const Image& a, const Image& b);
// The pixels where either image's opacity (its fourth value) is above `opacity`.
Mask OpacityAbove(const Image& a, const Image& b, double opacity);

// How many pixels `mask` accepts.
size_t CountPixels(const Image& image, const Mask& mask);

// Shorthands the render tests read best: RMS over r, g, b in 8-bit levels, and the largest
// difference of any value (alpha included) in the images' units.
double RmsDifference(const Image& a, const Image& b);
double MaxDifference(const Image& a, const Image& b);

// The mean of one channel over a region (the whole image by default), and the mean of
// r + g + b.
double MeanOver(const Image& image, int channel, const Region& region = {});
double MeanRadiance(const Image& image, const Region& region = {});
// The columns [x0, x1) of every row.
inline Region Columns(int x0, int x1)
{
  return Region{ x0, 0, x1 - x0, 0 };
}

// ---- Monte Carlo images (the path tracers': values with the variance of each mean) ----------

// A mean and its standard error.
struct Estimate
{
  double Mean = 0.0;
  double StandardError = 0.0;
};
// A function of a pixel index (p = y * Width + x).
using PixelFunction = std::function<double(size_t)>;
using PixelSelection = std::function<bool(size_t)>;

// The mean over the pixels `use` accepts (all when empty) of f(p), each pixel's f having the
// variance v(p), the pixels independent.
Estimate MeanOverPixels(const Image& image,
  const PixelFunction& f,
  const PixelFunction& v,
  const PixelSelection& use = {});

// The mean of one channel over the pixels `use` accepts (all when empty), and the same with its
// standard error from the image's variances.
double MeanOf(const Image& image, int channel, const PixelSelection& use = {});
Estimate MeanWithError(const Image& image, int channel, const PixelSelection& use = {});

// The largest |z| over blocks of blockSize x blockSize pixels (where `use` picks at least half
// of a block's pixels) of the block's summed difference over its standard error; `blocks` is
// how many blocks counted. A block pools thousands of paths, so its mean is close to normal and
// its variance estimate reliable even where single pixels depend on rare events (a path that
// hits a thin edge, or fails to).
double LargestBlockZ(const Image& image,
  int blockSize,
  const PixelFunction& difference,
  const PixelFunction& variance,
  const PixelSelection& use,
  int& blocks);

// |a - b| per value, scaled by `gain` and clamped to [0, 1], as an RGB image: where two
// pictures differ, for looking (gain 10: a 25-level difference is white).
Image DifferenceImage(const Image& a, const Image& b, double gain = 10.0);

} // namespace support
} // namespace cloudvis

#endif
