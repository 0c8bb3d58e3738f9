// How a density field is stored as texels, for the GPU mapper's 3-D texture and for the CPU
// reference that samples the same texels. A field keeps its native type on the GPU: unsigned
// char as 8-bit normalized texels (R8), unsigned short as 16-bit normalized texels (R16), float
// as 32-bit floats (R32F), and optionally float as 16-bit half floats (R16F). The shader's
// GL_LINEAR fetch returns the texels' normalized values (c / 255, c / 65535, or the float)
// interpolated; `filtered * Scale + Bias` gives the density in the data's own units, which is
// what the transfer table's Range is in. Interpolation commutes with that affine map, so the
// density a renderer sees is the trilinear interpolation of the data, with only the texels'
// rounding in between. 1, 2 and 4 bytes per voxel: a byte field takes 4x less GPU memory than
// as float, a short field 2x less, and half floats 2x less than float.
//
// Half floats hold 11 significant bits: a value is stored with a relative error of at most
// 2^-11 (about 4.9e-4) when its magnitude is at least 2^-14 of Scale, and with an absolute error
// of at most 2^-25 Scale below that. Scale is the power of two at or above the field's largest
// magnitude, so no value overflows.
#ifndef CloudDensityTexels_h
#define CloudDensityTexels_h

#include "cloudvisFiltersModule.h"

#include <cstddef>
#include <cstdint>
#include <string>

class vtkDataArray;

namespace cloudvis
{

enum class TexelFormat
{
  Float32, // R32F: the float values
  UNorm8,  // R8: unsigned char c, read as c / 255
  UNorm16, // R16: unsigned short c, read as c / 65535
  Float16, // R16F: float values / Scale as half floats
};

// Bytes a texel of the format takes.
CLOUDVISFILTERS_EXPORT int BytesPerTexel(TexelFormat format);
// "R8", "R16", "R32F", "R16F": the GL internal format's name, for messages and reports.
CLOUDVISFILTERS_EXPORT const char* TexelFormatName(TexelFormat format);

struct DensityTexels
{
  TexelFormat Format = TexelFormat::Float32;
  float Scale = 1.0f; // density = filtered texel value * Scale + Bias
  float Bias = 0.0f;
  // The texels in Format (Float16 excepted: the CPU reference reads the field's own floats), x
  // fastest, for the CPU reference; the GPU mapper uploads a texture instead.
  const void* Values = nullptr;
};

// The texels of `scalars` (one component of float, unsigned char or unsigned short, finite, as
// ValidateDensityScalars and ValidateDensityValues accept them): their native format, with
// halfFloat choosing Float16 for a float field (other types keep theirs). Values point at the
// array's data except for Float16.
CLOUDVISFILTERS_EXPORT DensityTexels DensityTexelsOf(vtkDataArray* scalars, bool halfFloat = false);

// The normalized value of texel `index` (not Float16), as a GL_LINEAR fetch reads it before
// filtering: the float, or c / (2^bits - 1).
inline float NormalizedTexel(const DensityTexels& texels, std::size_t index)
{
  switch (texels.Format)
  {
    case TexelFormat::UNorm8:
      return float(static_cast<const std::uint8_t*>(texels.Values)[index]) / 255.0f;
    case TexelFormat::UNorm16:
      return float(static_cast<const std::uint16_t*>(texels.Values)[index]) / 65535.0f;
    case TexelFormat::Float32:
    case TexelFormat::Float16:
    default:
      return static_cast<const float*>(texels.Values)[index];
  }
}

// IEEE 754 binary16 conversions: round to nearest, ties to even; beyond the largest half
// (65504) a value becomes infinity, NaN stays NaN.
CLOUDVISFILTERS_EXPORT std::uint16_t HalfFromFloat(float value);
CLOUDVISFILTERS_EXPORT float FloatFromHalf(std::uint16_t half);

} // namespace cloudvis

#endif
