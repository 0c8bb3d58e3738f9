// The two kinds of failure the application reports, kept apart because they end the program
// with different exit statuses: a UsageError (2) means the command line itself is wrong, an
// InputError (1) means a scene, field or output path is. Both carry the complete message the
// user sees after "cloudvis: error: ", so the code that detects a problem is the code that
// names the file, key and value involved. The message is stored as PrintableText (Utf8.h): a
// path or value quoted in it that holds a newline, a tab, an ESC or a NUL is shown escaped
// (\x0a, \x09, \x1b, \x00), so every refusal stays one line and none is cut short, whoever
// built it.
#ifndef cloudvis_Errors_h
#define cloudvis_Errors_h

#include "Utf8.h"

#include <stdexcept>
#include <string>

namespace cloudvis
{

class InputError : public std::runtime_error
{
public:
  explicit InputError(const std::string& message)
    : std::runtime_error(PrintableText(message))
  {
  }
};

class UsageError : public std::runtime_error
{
public:
  explicit UsageError(const std::string& message)
    : std::runtime_error(PrintableText(message))
  {
  }
};

} // namespace cloudvis

#endif
