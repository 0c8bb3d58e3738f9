// The image formats cloudvis exports (docs/export.md), each a function from a RenderedImage to
// one file, called by WriteImage below on the checked stream that WriteStreamAtomically hands it:
//   PNG, 8-bit RGB (default): the window's pixels as they were shown;
//   PNG, 16-bit and/or transparent: the mapper's float image composited by the same "over" the
//     window applies (cloud + (1 - alpha) * background, in the window's display values), or with
//     --transparent not composited at all: straight (un-premultiplied) color and alpha;
//   OpenEXR: the float image itself, linear and premultiplied, with depth, transmittance and
//     sample-count channels, and the exposure and display curve PNG would apply in its header.
// PNG's display values are the cloud's radiance through the render's display transform
// (RenderedImage::ExposureEV and Display) over the background.
// Every file carries the cloudvis version, the resolved scene and the command line as metadata.
#ifndef cloudvis_ImageWriters_h
#define cloudvis_ImageWriters_h

#include "RenderedImage.h"

#include <iosfwd>
#include <string>

namespace cloudvis
{

struct ImageExportOptions
{
  int PngBits = 8;          // 8 or 16 (render.png_bits, --png-bits)
  bool Transparent = false; // PNG: RGBA, alpha = the cloud's opacity, no background (--transparent)
  bool ExrHalf = false;     // EXR: HALF channels instead of FLOAT (render.exr_type, --exr-half)
  std::string SceneJson;    // the resolved scene (SceneToJson), embedded as "cloudvis.scene"
  std::string CommandLine;  // embedded as "cloudvis.command"
};

// An exposure as cloudvis prints and records it: "+1.25 EV".
std::string ShowExposure(double ev);

// "0.1.0": the CMake project version cloudvis was built as.
std::string CloudvisVersion();

// Whether writing `path` with `options` needs the float image of RenderedImage (Radiance,
// Auxiliary, BackgroundRGB): EXR, 16-bit PNG and transparent PNG do.
bool NeedsFloatImage(const std::string& path, const ImageExportOptions& options);

// Throws InputError unless `path` ends in a supported extension (the message lists them) and can
// be written (CheckOutputTarget). Called before any rendering.
void CheckImageOutput(const std::string& path);

// Writes the image in the format its extension names, atomically (WriteStreamAtomically), with
// default or given export options and metadata.
void WriteImage(const RenderedImage& image, const std::string& path);
void WriteImage(
  const RenderedImage& image, const std::string& path, const ImageExportOptions& options);

} // namespace cloudvis

#endif
