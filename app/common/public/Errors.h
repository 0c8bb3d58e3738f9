// The two kinds of failure the application reports, kept apart because they end the program
// with different exit statuses: a UsageError (2) means the command line itself is wrong, an
// InputError (1) means a scene, field or output path is. Both carry the complete message the
// user sees after "cloudvis: error: ", so the code that detects a problem is the code that
// names the file, key and value involved.
#ifndef cloudvis_Errors_h
#define cloudvis_Errors_h

#include <stdexcept>
#include <string>

namespace cloudvis
{

class InputError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

class UsageError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

} // namespace cloudvis

#endif
