// Images read as field files are (ImageFiles.h says why): the header checked here, the decoding
// isolated. The header parsers read only what they check: PNG's signature and IHDR chunk (its
// CRC, and a width and height from 1 to 2^31 - 1, as the PNG specification allows), a PNM
// header's magic number, width, height and maximum value, and a BMP's width and height.
#include "ImageFiles.h"

#include "Errors.h"
#include "FieldIO.h" // FieldFileExtensions
#include "InputFiles.h"
#include "IsolatedRead.h"
#include "VtkMessageCapture.h"

#include "CloudFieldGeometry.h" // AvailableMemoryBytes, FormatBytes

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkImageReader2.h>
#include <vtkImageReader2Factory.h>
#include <vtkInformation.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <zlib.h>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fcntl.h>
#include <limits>
#include <sstream>
#include <unistd.h>

namespace cloudvis
{
namespace
{

constexpr double LargestDimension = double(std::numeric_limits<std::int32_t>::max());

// "900 M": a count of pixels in three significant digits.
std::string Count(double count)
{
  const char* suffixes[] = { "", " K", " M", " G", " T", " P" };
  int s = 0;
  while (count >= 1000.0 && s < 5)
  {
    count /= 1000.0;
    ++s;
  }
  std::ostringstream text;
  text.precision(3);
  text << count << suffixes[s];
  return text.str();
}

std::string Dimensions(const std::array<double, 3>& d)
{
  std::ostringstream text;
  text.precision(12);
  text << d[0] << " x " << d[1];
  if (d[2] != 1.0)
  {
    text << " x " << d[2];
  }
  return text.str();
}

// A header's text for a message: at most 24 characters, bytes outside printable ASCII as \xNN.
std::string Shown(const std::string& token)
{
  std::string shown;
  for (std::size_t i = 0; i < token.size() && i < 24; ++i)
  {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f)
    {
      shown += char(c);
    }
    else
    {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
      shown += escaped;
    }
  }
  return token.size() > 24 ? shown + "..." : shown;
}

void CheckSize(const std::string& path,
  const std::string& what,
  const std::array<double, 3>& d,
  double bytesPerPixel,
  std::uint64_t maximumPixels,
  const std::string& limit)
{
  const std::string prefix = path + ": " + what + ": ";
  const double pixels = d[0] * d[1] * d[2];
  if (pixels > double(maximumPixels))
  {
    throw InputError(
      prefix + Dimensions(d) + " pixels (" + Count(pixels) + ") is more than " + limit);
  }
  const double needed = pixels * bytesPerPixel;
  const std::uint64_t available = AvailableMemoryBytes();
  if (available > 0 && needed > double(available))
  {
    throw InputError(prefix + Dimensions(d) + " pixels (" + Count(pixels) + ") need " +
      FormatBytes(needed) + " to read, but only " + FormatBytes(double(available)) +
      " of memory is available");
  }
}

std::uint32_t BigEndian32(const std::string& bytes, std::size_t at)
{
  return std::uint32_t(static_cast<unsigned char>(bytes[at])) << 24 |
    std::uint32_t(static_cast<unsigned char>(bytes[at + 1])) << 16 |
    std::uint32_t(static_cast<unsigned char>(bytes[at + 2])) << 8 |
    std::uint32_t(static_cast<unsigned char>(bytes[at + 3]));
}

// The image formats VTK's factory takes, by their first bytes: the name of the reader for
// messages, and whether its header is checked here.
enum class Kind
{
  Png,
  Pnm,
  Bmp,
  Other
};

struct Sniffed
{
  Kind Format = Kind::Other;
  std::string Parser = "VTK's image reader";
};

Sniffed Sniff(const std::string& head)
{
  const auto starts = [&head](const std::string& magic)
  { return head.compare(0, magic.size(), magic) == 0; };
  if (starts(std::string("\x89PNG\r\n\x1a\n", 8)))
  {
    return { Kind::Png, "VTK's PNG reader" };
  }
  if (head.size() >= 2 && head[0] == 'P' && head[1] >= '1' && head[1] <= '6')
  {
    return { Kind::Pnm, "VTK's PNM reader" };
  }
  if (starts("\xFF\xD8\xFF"))
  {
    return { Kind::Other, "VTK's JPEG reader" };
  }
  if (starts(std::string("II*\0", 4)) || starts(std::string("MM\0*", 4)))
  {
    return { Kind::Other, "VTK's TIFF reader" };
  }
  if (starts("BM"))
  {
    return { Kind::Bmp, "VTK's BMP reader" };
  }
  return {};
}

// PNG: the signature, then the IHDR chunk (length 13, type, width, height, 5 bytes, CRC).
std::array<double, 3> PngSize(const std::string& path,
  const std::string& what,
  const std::string& head)
{
  const std::string prefix = path + ": " + what + ": ";
  if (head.size() < 33)
  {
    throw InputError(prefix + "the file ends inside its PNG header (" +
      std::to_string(head.size()) + " bytes; the signature and IHDR chunk take 33)");
  }
  if (BigEndian32(head, 8) != 13 || head.compare(12, 4, "IHDR") != 0)
  {
    throw InputError(prefix + "the PNG header is damaged: its first chunk is not a 13-byte IHDR");
  }
  const std::uint32_t crc =
    std::uint32_t(::crc32(0L, reinterpret_cast<const Bytef*>(head.data() + 12), 17));
  if (crc != BigEndian32(head, 29))
  {
    throw InputError(prefix + "the PNG header is damaged: the IHDR chunk's CRC does not match");
  }
  const std::uint32_t width = BigEndian32(head, 16), height = BigEndian32(head, 20);
  if (width < 1 || height < 1 || width > LargestDimension || height > LargestDimension)
  {
    throw InputError(prefix + "the PNG header gives a size of " + std::to_string(width) + " x " +
      std::to_string(height) + " pixels; each must be from 1 to 2147483647");
  }
  return { { double(width), double(height), 1.0 } };
}

// The next token of a PNM header from `at`: white space and comments (# to the end of the line)
// skipped first.
std::string PnmToken(const std::string& head, std::size_t& at)
{
  while (at < head.size())
  {
    if (head[at] == '#')
    {
      while (at < head.size() && head[at] != '\n' && head[at] != '\r')
      {
        ++at;
      }
    }
    else if (std::isspace(static_cast<unsigned char>(head[at])))
    {
      ++at;
    }
    else
    {
      break;
    }
  }
  const std::size_t start = at;
  while (at < head.size() && head[at] != '#' && !std::isspace(static_cast<unsigned char>(head[at])))
  {
    ++at;
  }
  return head.substr(start, at - start);
}

// A whole number from `lowest` to `highest` written in decimal digits, or -1.
double PnmNumber(const std::string& token, double lowest, double highest)
{
  if (token.empty() || token.size() > 12)
  {
    return -1.0;
  }
  double value = 0.0;
  for (char c : token)
  {
    if (c < '0' || c > '9')
    {
      return -1.0;
    }
    value = value * 10.0 + (c - '0');
  }
  return value >= lowest && value <= highest ? value : -1.0;
}

// PNM: "P1" to "P6", width, height and (but for the bitmaps P1 and P4) the maximum value.
std::array<double, 3> PnmSize(const std::string& path,
  const std::string& what,
  const std::string& head)
{
  const char magic = head[1];
  const std::string kind = std::string(magic == '1' || magic == '4' ? "PBM"
                               : magic == '2' || magic == '5'       ? "PGM"
                                                                    : "PPM") +
    " header (P" + magic + ")";
  const std::string prefix = path + ": " + what + ": the " + kind;
  std::size_t at = 2;
  const std::string width = PnmToken(head, at), height = PnmToken(head, at);
  if (height.empty())
  {
    throw InputError(prefix + " ends before its width and height");
  }
  const double w = PnmNumber(width, 1.0, LargestDimension),
               h = PnmNumber(height, 1.0, LargestDimension);
  if (w < 0.0 || h < 0.0)
  {
    throw InputError(prefix + " gives a size of " + Shown(width) + " x " + Shown(height) +
      " pixels; each must be a whole number from 1 to 2147483647");
  }
  if (magic != '1' && magic != '4')
  {
    const std::string maximum = PnmToken(head, at);
    if (PnmNumber(maximum, 1.0, 65535.0) < 0.0)
    {
      throw InputError(prefix +
        (maximum.empty() ? std::string(" ends before its maximum value")
                         : " gives a maximum value of " + Shown(maximum) +
              "; it must be a whole number from 1 to 65535"));
    }
  }
  return { { w, h, 1.0 } };
}

// BMP: the file header (14 bytes), then the size of the info header and the width and height:
// 16-bit unsigned in an OS/2 header of 12 bytes, else 32-bit signed, a negative height meaning
// rows stored top down (VTK's reader takes the width's sign off too).
std::array<double, 3> BmpSize(const std::string& path,
  const std::string& what,
  const std::string& head)
{
  const std::string prefix = path + ": " + what + ": ";
  if (head.size() < 26)
  {
    throw InputError(
      prefix + "the file ends inside its BMP header (" + std::to_string(head.size()) + " bytes)");
  }
  const auto little = [&head](std::size_t at, int bytes)
  {
    std::uint32_t value = 0;
    for (int i = bytes - 1; i >= 0; --i)
    {
      value = value << 8 | static_cast<unsigned char>(head[at + i]);
    }
    return value;
  };
  const bool os2 = little(14, 4) == 12;
  const double width = os2 ? double(little(18, 2)) : double(std::int32_t(little(18, 4)));
  const double height = os2 ? double(little(20, 2)) : double(std::int32_t(little(22, 4)));
  if (width < 1.0 || height == 0.0)
  {
    std::ostringstream text;
    text << prefix << "the BMP header gives a size of " << width << " x " << height
         << " pixels; the width must be from 1 to 2147483647, the height not 0 (negative: rows "
            "stored top down)";
    throw InputError(text.str());
  }
  return { { width, std::fabs(height), 1.0 } };
}

} // namespace

void CheckImageSize(const std::string& path,
  const std::string& what,
  double width,
  double height,
  double bytesPerPixel,
  std::uint64_t maximumPixels,
  const std::string& limit)
{
  CheckSize(path, what, { { width, height, 1.0 } }, bytesPerPixel, maximumPixels, limit);
}

vtkSmartPointer<vtkImageData> ReadImageFile(const std::string& path,
  const std::string& what,
  std::uint64_t maximumPixels,
  const std::string& limit,
  double bytesPerPixelAfter)
{
  const RegularInputFile file(path, what);
  // Headers are short: PNG's IHDR ends at byte 33; a PNM header's comments may run longer.
  const std::string head = file.ReadAt(0, 4096);
  const Sniffed sniffed = Sniff(head);
  if (sniffed.Format == Kind::Png)
  {
    const std::array<double, 3> d = PngSize(path, what, head);
    CheckSize(path, what, d, 0.0, maximumPixels, limit);
  }
  else if (sniffed.Format == Kind::Pnm)
  {
    const std::array<double, 3> d = PnmSize(path, what, head);
    CheckSize(path, what, d, 0.0, maximumPixels, limit);
  }
  else if (sniffed.Format == Kind::Bmp)
  {
    const std::array<double, 3> d = BmpSize(path, what, head);
    CheckSize(path, what, d, 0.0, maximumPixels, limit);
  }
  const auto read = [&]() -> FieldFileContents
  {
    // libpng and libjpeg print their own complaints to stderr; the child's outcome says it in
    // one line. Sanitized builds too: the child runs VTK's decoders alone, whose crash on a
    // damaged image is the outcome reported, and a sanitizer's report of it would break the
    // one-line error.
    if (InIsolatedRead())
    {
      const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
      if (null >= 0)
      {
        ::dup2(null, STDERR_FILENO);
        ::close(null);
      }
    }
    VtkMessageCapture messages;
    vtkSmartPointer<vtkImageReader2> reader;
    reader.TakeReference(vtkImageReader2Factory::CreateImageReader2(path.c_str()));
    if (!reader)
    {
      throw InputError(path + ": " + what +
        ": not an image VTK can read (PNG, JPEG, TIFF, BMP, PNM) nor a field file (" +
        FieldFileExtensions() + ")");
    }
    const auto refuse = [&]() {
      throw InputError(messages.WithVtkReason(path + ": " + what + ": the image cannot be read"));
    };
    reader->SetFileName(path.c_str());
    reader->UpdateInformation();
    int extent[6] = { 0, -1, 0, -1, 0, -1 };
    vtkInformation* information = reader->GetOutputInformation(0);
    if (!messages.Messages().empty() || !information ||
      !information->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    {
      refuse();
    }
    information->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
    const std::array<double, 3> d{ { double(extent[1]) - extent[0] + 1.0,
      double(extent[3]) - extent[2] + 1.0,
      double(extent[5]) - extent[4] + 1.0 } };
    if (!(d[0] >= 1.0 && d[1] >= 1.0 && d[2] >= 1.0))
    {
      const char* name = reader->GetDescriptiveName();
      throw InputError(path + ": " + what + ": the " + (name ? name : "image") +
        " header gives an empty image (" + Dimensions(d) + " pixels)");
    }
    // Held per pixel: the decoded image here and its copy in the parent, then the caller's own.
    const double decoded = double(reader->GetNumberOfScalarComponents()) *
      double(vtkDataArray::GetDataTypeSize(reader->GetDataScalarType()));
    CheckSize(path,
      what,
      d,
      decoded * (InIsolatedRead() ? 2.0 : 1.0) + bytesPerPixelAfter,
      maximumPixels,
      limit);
    reader->Update();
    vtkImageData* image = reader->GetOutput();
    if (!messages.Messages().empty() || !image || image->GetNumberOfPoints() == 0)
    {
      refuse();
    }
    auto copy = vtkSmartPointer<vtkImageData>::New();
    copy->ShallowCopy(image);
    return FieldFileContents{ copy, "", {} };
  };
  return ReadInIsolation(path + ": " + what, file.Size(), sniffed.Parser, read).Image;
}

} // namespace cloudvis
