#include "Words.h"

namespace cloudvis
{

std::string Join(const std::vector<std::string>& names, const std::string& separator)
{
  std::string joined;
  for (const std::string& name : names)
  {
    joined += (joined.empty() ? "" : separator) + name;
  }
  return joined;
}

} // namespace cloudvis
