// Images cloudvis reads (a coverage map given as PNG, JPEG, TIFF, BMP or PNM), read as field
// files are (IsolatedRead.h): the decoders (VTK's image readers over libpng, libjpeg, libtiff and
// VTK's own BMP and PNM code) trust the file, and a damaged PNG crashes libpng's caller in VTK,
// so they run in the forked child under its memory and time limits, never in the cloudvis
// process. Before anything is decoded the image's size is checked against a limit and the memory
// available: for PNG, PNM and BMP from the header, parsed here (PNG's IHDR with its CRC; a PNM
// or BMP header whose size is not positive, which VTK's readers read "-5" as 5, is refused), for
// JPEG and TIFF from what VTK's reader makes of the header, in the child.
#ifndef cloudvis_ImageFiles_h
#define cloudvis_ImageFiles_h

#include <vtkSmartPointer.h>

#include <cstdint>
#include <string>

class vtkImageData;

namespace cloudvis
{

// Throws InputError "PATH: WHAT: W x H pixels (900 M) is more than LIMIT" unless an image of
// `width` x `height` pixels is at most `maximumPixels` (`limit` says what that limit is, in
// words, for the message), and "... need 8.4 GiB to read, but only ... is available" unless
// `bytesPerPixel` (what is held per pixel while it is read) fits in the memory available. Width
// and height are at least 1.
void CheckImageSize(const std::string& path,
  const std::string& what,
  double width,
  double height,
  double bytesPerPixel,
  std::uint64_t maximumPixels,
  const std::string& limit);

// The image in `path`, a regular file (checked first), decoded by the VTK image reader that
// claims it, in the isolated child, with the size checks above first (the memory counted: the
// decoded image twice, in the child and in the copy sent back, and `bytesPerPixelAfter`, what
// the caller makes of each pixel). Throws InputError naming `path` and `what` ("coverage map")
// for a file no image reader takes, a header that is damaged or states an impossible size, an
// image beyond the limits, and a decoder that fails, crashes, runs out of memory or time.
vtkSmartPointer<vtkImageData> ReadImageFile(const std::string& path,
  const std::string& what,
  std::uint64_t maximumPixels,
  const std::string& limit,
  double bytesPerPixelAfter);

} // namespace cloudvis

#endif
