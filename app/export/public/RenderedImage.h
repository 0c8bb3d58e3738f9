// What a render produces, as every exporter and test sees it: the window's 8-bit pixels and,
// for exports that need them, the mapper's float image, auxiliary channels and the background.
#ifndef cloudvis_RenderedImage_h
#define cloudvis_RenderedImage_h

#include "CloudDisplayTransform.h" // DisplayCurve

#include <cstddef>
#include <string>
#include <vector>

namespace cloudvis
{

// 8-bit RGB pixels as the window showed them, rows from bottom to top (VTK's order).
struct RenderedImage
{
  int Width = 0;
  int Height = 0;
  std::vector<unsigned char> RGB; // Width * Height * 3
  // The display transform RGB's cloud went through (render.exposure, resolved when "auto", and
  // render.display): the writers that make display values from Radiance apply the same, and EXR
  // records it.
  double ExposureEV = 0.0;
  DisplayCurve Display = DisplayCurve::Linear;
  // The field was drawn coarser than it is to fit the GPU's memory (FieldCoarsening.h): what was
  // done, which the writers record as "cloudvis.coarsened"; empty when it was drawn as it is.
  std::string Coarsened;

  // Kept only when RenderOptions::FloatImage asks for them (exports: ImageWriters.h), same size
  // and row order: the mapper's premultiplied linear RGBA (alpha = 1 - transmittance); per pixel
  // samples taken, useful samples, the cloud's distance from the camera and 1 (ExportRender.h);
  // and the window's pixels without the cloud.
  std::vector<float> Radiance;
  std::vector<float> Auxiliary;
  std::vector<unsigned char> BackgroundRGB;
  // A path-traced render's estimated variance of each Radiance channel's per-pixel mean (its
  // square root is the standard error), same size and order; empty for the other models.
  std::vector<float> Variance;

  const unsigned char* Pixel(int x, int y) const
  {
    return this->RGB.data() + 3 * (size_t(y) * size_t(this->Width) + size_t(x));
  }
};

} // namespace cloudvis

#endif
