#include "FileNames.h"

namespace cloudvis
{

std::string DirectoryOf(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos)
  {
    return ".";
  }
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string FileNameOf(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string LowerCaseExtension(const std::string& path)
{
  const std::string name = FileNameOf(path);
  const auto dot = name.find_last_of('.');
  if (dot == std::string::npos || dot == 0)
  {
    return "";
  }
  std::string extension = name.substr(dot);
  for (char& c : extension)
  {
    if (c >= 'A' && c <= 'Z')
    {
      c = char(c - 'A' + 'a');
    }
  }
  return extension;
}

} // namespace cloudvis
