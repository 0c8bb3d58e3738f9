#include "CloudDensityTexels.h"

#include <vtkDataArray.h>
#include <vtkType.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace cloudvis
{

int BytesPerTexel(TexelFormat format)
{
  switch (format)
  {
    case TexelFormat::UNorm8:
      return 1;
    case TexelFormat::UNorm16:
    case TexelFormat::Float16:
      return 2;
    case TexelFormat::Float32:
    default:
      return 4;
  }
}

const char* TexelFormatName(TexelFormat format)
{
  switch (format)
  {
    case TexelFormat::UNorm8:
      return "R8";
    case TexelFormat::UNorm16:
      return "R16";
    case TexelFormat::Float16:
      return "R16F";
    case TexelFormat::Float32:
    default:
      return "R32F";
  }
}

DensityTexels DensityTexelsOf(vtkDataArray* scalars, bool halfFloat)
{
  DensityTexels texels;
  texels.Values = scalars->GetVoidPointer(0);
  switch (scalars->GetDataType())
  {
    case VTK_UNSIGNED_CHAR:
      texels.Format = TexelFormat::UNorm8;
      texels.Scale = 255.0f;
      break;
    case VTK_UNSIGNED_SHORT:
      texels.Format = TexelFormat::UNorm16;
      texels.Scale = 65535.0f;
      break;
    default:
      if (halfFloat)
      {
        // The power of two at or above the largest magnitude: every value / Scale lies in
        // [-1, 1], and dividing by a power of two rounds nothing.
        const auto* values = static_cast<const float*>(scalars->GetVoidPointer(0));
        const vtkIdType n = scalars->GetNumberOfTuples();
        float largest = 0.0f;
        for (vtkIdType i = 0; i < n; ++i)
        {
          largest = std::max(largest, std::abs(values[i]));
        }
        texels.Format = TexelFormat::Float16;
        texels.Scale = largest > 0.0f ? std::ldexp(1.0f, std::ilogb(largest)) : 1.0f;
        if (texels.Scale < largest)
        {
          texels.Scale *= 2.0f;
        }
        texels.Values = nullptr;
      }
      break;
  }
  return texels;
}

std::uint16_t HalfFromFloat(float value)
{
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  const std::uint16_t sign = std::uint16_t((bits >> 16) & 0x8000u);
  const std::uint32_t magnitude = bits & 0x7fffffffu;
  if (magnitude >= 0x7f800000u) // infinity or NaN (a quiet NaN keeps a payload bit)
  {
    return std::uint16_t(sign | 0x7c00u | (magnitude > 0x7f800000u ? 0x200u : 0u));
  }
  if (magnitude >= 0x477ff000u) // rounds to beyond 65504
  {
    return std::uint16_t(sign | 0x7c00u);
  }
  if (magnitude < 0x38800000u) // below 2^-14: a subnormal half (or zero)
  {
    if (magnitude < 0x33000000u) // below half of the smallest subnormal, 2^-25: zero
    {
      return sign;
    }
    // value = significand * 2^(exponent - 150), so in units of the smallest subnormal, 2^-24, it
    // is significand / 2^(126 - exponent): shift right by 14 to 24 bits, rounding to even.
    const int exponent = int(magnitude >> 23);
    const std::uint32_t significand = (magnitude & 0x7fffffu) | 0x800000u;
    const int shift = 126 - exponent;
    const std::uint32_t truncated = significand >> shift;
    const std::uint32_t remainder = significand & ((1u << shift) - 1u);
    const std::uint32_t halfway = 1u << (shift - 1);
    const std::uint32_t rounded =
      truncated + (remainder > halfway || (remainder == halfway && (truncated & 1u)) ? 1u : 0u);
    return std::uint16_t(sign | rounded);
  }
  // A normal half: rebias the exponent, round the significand from 23 to 10 bits to even; a carry
  // into the exponent is the correct result.
  const std::uint32_t rebiased = magnitude - 0x38000000u; // exponent - 127 + 15
  const std::uint32_t truncated = rebiased >> 13;
  const std::uint32_t remainder = rebiased & 0x1fffu;
  const std::uint32_t rounded =
    truncated + (remainder > 0x1000u || (remainder == 0x1000u && (truncated & 1u)) ? 1u : 0u);
  return std::uint16_t(sign | rounded);
}

float FloatFromHalf(std::uint16_t half)
{
  const float sign = (half & 0x8000u) ? -1.0f : 1.0f;
  const int exponent = (half >> 10) & 0x1f;
  const int significand = half & 0x3ff;
  if (exponent == 0x1f)
  {
    return significand ? std::nanf("") : sign * INFINITY;
  }
  if (exponent == 0)
  {
    return sign * std::ldexp(float(significand), -24);
  }
  return sign * std::ldexp(float(significand | 0x400), exponent - 25);
}

} // namespace cloudvis
