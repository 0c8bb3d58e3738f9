// The per-process input file of FuzzInput.h.
#include "FuzzInput.h"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <unistd.h>

namespace cloudvis
{
namespace fuzz
{
namespace
{

std::map<std::string, std::string>& Paths()
{
  static std::map<std::string, std::string> paths;
  return paths;
}

void RemoveInputFiles()
{
  for (const auto& entry : Paths())
  {
    std::remove(entry.second.c_str());
  }
}

} // namespace

const std::string& WriteInputFile(const char* extension, const std::uint8_t* data, std::size_t size)
{
  std::string& path = Paths()[extension];
  if (path.empty())
  {
    const char* tmp = std::getenv("TMPDIR");
    path = std::string(tmp && *tmp ? tmp : "/tmp") + "/cloudvis-fuzz-" +
      std::to_string(::getpid()) + "-input" + extension;
    static const bool registered = std::atexit(RemoveInputFiles) == 0;
    (void)registered;
  }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file || (size > 0 && std::fwrite(data, 1, size, file) != size) || std::fclose(file) != 0)
  {
    std::perror(path.c_str());
    std::abort();
  }
  return path;
}

} // namespace fuzz
} // namespace cloudvis
