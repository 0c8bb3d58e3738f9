// The per-process input directory of FuzzInput.h.
#include "FuzzInput.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>

namespace cloudvis
{
namespace fuzz
{
namespace
{

const std::string& InputDirectory()
{
  static const std::string directory = []
  {
    const char* tmp = std::getenv("TMPDIR");
    const std::string path =
      std::string(tmp && *tmp ? tmp : "/tmp") + "/cloudvis-fuzz-" + std::to_string(::getpid());
    std::filesystem::create_directories(path);
    return path;
  }();
  // Registered once `directory` is complete, so it runs before the string is destroyed.
  static const bool removedAtExit =
    std::atexit([] { std::filesystem::remove_all(InputDirectory()); }) == 0;
  (void)removedAtExit;
  return directory;
}

} // namespace

std::string WriteInputFile(const std::string& name, const std::uint8_t* data, std::size_t size)
{
  const std::string path = InputDirectory() + "/" + name;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file || (size > 0 && std::fwrite(data, 1, size, file) != size) || std::fclose(file) != 0)
  {
    std::perror(path.c_str());
    std::abort();
  }
  return path;
}

void RemoveInputFile(const std::string& name)
{
  std::remove((InputDirectory() + "/" + name).c_str());
}

} // namespace fuzz
} // namespace cloudvis
