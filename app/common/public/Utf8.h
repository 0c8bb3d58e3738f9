// Text that reaches a user or a JSON document must be valid UTF-8: nlohmann::json refuses to
// dump a string that is not (type_error 316), and a terminal shows stray bytes as noise. Paths
// are byte strings on POSIX, and --set values are whatever the shell passed, so any of them may
// hold bytes that are not UTF-8. EscapeInvalidUtf8 is the one place such text is made safe:
// every byte that is not part of a well-formed UTF-8 sequence is written as the four characters
// \xNN (two lower-case hex digits); valid text, including every multi-byte character, passes
// unchanged. Error messages, standard output, `info --json`, export metadata and saved scenes all
// go through it (docs/reliability.md).
#ifndef cloudvis_Utf8_h
#define cloudvis_Utf8_h

#include <string>

namespace cloudvis
{

// True when `text` is well-formed UTF-8 as Unicode defines it (no overlong forms, no surrogates,
// nothing above U+10FFFF): exactly what nlohmann::json accepts.
bool IsValidUtf8(const std::string& text);

// `text` with each byte outside a well-formed UTF-8 sequence replaced by "\xNN".
std::string EscapeInvalidUtf8(const std::string& text);

// EscapeInvalidUtf8, and also every control character written as its bytes in \xNN: NUL, tab,
// newline, ESC and the rest of C0, DEL, and C1 (U+0080..U+009F, "\xc2\x9b" for the
// one-character CSI). For text that must stay on one line and never drive a terminal: every
// InputError and UsageError message is made of it (Errors.h), so a path holding a newline does
// not split a one-line error, and one holding a NUL does not cut it short. Idempotent: the
// backslash itself is not escaped.
std::string PrintableText(const std::string& text);

} // namespace cloudvis

#endif
