// Images as the tests and benchmarks see them: PNG and EXR files read back with independent
// readers (vtkPNGReader, OpenEXR's Imf::InputFile), a render window's pixels, and the metrics
// that compare two images. Every test program and bench/ uses these; none carries its own reader
// or difference function.
//
// An Image holds `Components` values per pixel, rows bottom to top (VTK's order, the mapper's),
// scaled to [0, 1] for 8- and 16-bit files, so that a difference of 1/255 is one 8-bit level
// whatever the file's depth; float images (EXR, the mapper's float target) hold linear values as
// they are.
#ifndef cloudvis_SupportImages_h
#define cloudvis_SupportImages_h

#include <ImfPixelType.h>

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
  std::map<std::string, std::string> Text; // a PNG's text chunks (key -> value)

  double At(int x, int y, int c) const
  {
    return this->Values[(size_t(y) * size_t(this->Width) + size_t(x)) * size_t(this->Components) +
      size_t(c)];
  }
  // The value in 8-bit levels (0 .. 255).
  double Level(int x, int y, int c) const { return 255.0 * this->At(x, y, c); }
};

// A PNG file, 8 or 16 bits per channel, with its text chunks. An unreadable file gives an empty
// image (Width 0).
Image ReadPng(const std::string& path);

// Writes the first three (or four) channels as an 8-bit PNG, each value clamped to [0, 1].
// Returns false when the file could not be written.
bool WritePng(const Image& image, const std::string& path);

// A render window's back buffer, 8-bit RGB (or RGBA), as the window shows it after Render().
Image GrabWindow(vtkRenderWindow* window, bool alpha = false);

// An OpenEXR file: every channel as floats, its pixel type, and the string attributes.
struct Exr
{
  int Width = 0, Height = 0;
  std::map<std::string, Imf::PixelType> Types;
  std::map<std::string, std::vector<float>> Channels; // rows top to bottom, as stored
  std::map<std::string, std::string> Strings;
  // Channel value at (x, y) with y counted from the bottom, like VTK and the mapper.
  float At(const std::string& name, int x, int y) const
  {
    return this->Channels.at(name)[size_t(this->Height - 1 - y) * size_t(this->Width) + size_t(x)];
  }
};
// Throws (OpenEXR's exceptions) when the file cannot be read.
Exr ReadExr(const std::string& path);

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
// Levels() turns [0, 1] values into 8-bit levels. Images of different sizes differ infinitely.
struct Difference
{
  size_t Count = 0;
  double Rms = 0.0, Max = 0.0, Mean = 0.0;
  double RmsLevels() const { return 255.0 * this->Rms; }
  double MaxLevels() const { return 255.0 * this->Max; }
  double MeanLevels() const { return 255.0 * this->Mean; }
};
Difference Compare(const Image& a, const Image& b, int channels = 0, const Mask& mask = {});

// |a - b| per value, scaled by `gain` and clamped to [0, 1], as an RGB image: where two
// pictures differ, for looking (gain 10: a 25-level difference is white).
Image DifferenceImage(const Image& a, const Image& b, double gain = 10.0);

} // namespace support
} // namespace cloudvis

#endif
