// Well-formedness follows the Unicode Standard's table of well-formed byte sequences (Table
// 3-7): the second byte's range depends on the first byte, which is what excludes overlong
// forms, surrogates and code points above U+10FFFF.
#include "Utf8.h"

#include <cstddef>

namespace cloudvis
{
namespace
{

// The length of the well-formed sequence starting at text[i], or 0 when the byte there does not
// start one.
std::size_t SequenceLength(const std::string& text, std::size_t i)
{
  const auto byte = [&text](std::size_t at) { return static_cast<unsigned char>(text[at]); };
  const unsigned char lead = byte(i);
  if (lead < 0x80)
  {
    return 1;
  }
  std::size_t length = 0;
  unsigned char secondLow = 0x80, secondHigh = 0xBF;
  if (lead >= 0xC2 && lead <= 0xDF)
  {
    length = 2;
  }
  else if (lead >= 0xE0 && lead <= 0xEF)
  {
    length = 3;
    secondLow = lead == 0xE0 ? 0xA0 : 0x80;  // no overlong forms
    secondHigh = lead == 0xED ? 0x9F : 0xBF; // no surrogates
  }
  else if (lead >= 0xF0 && lead <= 0xF4)
  {
    length = 4;
    secondLow = lead == 0xF0 ? 0x90 : 0x80;  // no overlong forms
    secondHigh = lead == 0xF4 ? 0x8F : 0xBF; // nothing above U+10FFFF
  }
  else
  {
    return 0; // a continuation byte, C0, C1 or F5..FF
  }
  if (i + length > text.size() || byte(i + 1) < secondLow || byte(i + 1) > secondHigh)
  {
    return 0;
  }
  for (std::size_t k = 2; k < length; ++k)
  {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF)
    {
      return 0;
    }
  }
  return length;
}

} // namespace

bool IsValidUtf8(const std::string& text)
{
  for (std::size_t i = 0; i < text.size();)
  {
    const std::size_t length = SequenceLength(text, i);
    if (length == 0)
    {
      return false;
    }
    i += length;
  }
  return true;
}

namespace
{

// `text` with each byte outside a well-formed sequence, and with `controls` each control
// character (C0, DEL, and C1 as U+0080..U+009F), written as \xNN (one escape per byte).
std::string Escaped(const std::string& text, bool controls)
{
  static const char digits[] = "0123456789abcdef";
  std::string escaped;
  escaped.reserve(text.size() + 16);
  for (std::size_t i = 0; i < text.size();)
  {
    const std::size_t length = SequenceLength(text, i);
    const auto lead = static_cast<unsigned char>(text[i]);
    const bool control = controls &&
      ((length == 1 && (lead < 0x20 || lead == 0x7F)) ||
        (length == 2 && lead == 0xC2 && static_cast<unsigned char>(text[i + 1]) < 0xA0));
    if (length > 0 && !control)
    {
      escaped.append(text, i, length);
      i += length;
      continue;
    }
    for (const std::size_t end = i + (length > 0 ? length : 1); i < end; ++i)
    {
      const auto byte = static_cast<unsigned char>(text[i]);
      escaped += "\\x";
      escaped += digits[byte >> 4];
      escaped += digits[byte & 15];
    }
  }
  return escaped;
}

} // namespace

std::string EscapeInvalidUtf8(const std::string& text)
{
  return IsValidUtf8(text) ? text : Escaped(text, false);
}

std::string PrintableText(const std::string& text)
{
  return Escaped(text, true);
}

} // namespace cloudvis
