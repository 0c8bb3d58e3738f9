// POSIX implementation of the write-then-rename protocol: mkstemps creates a uniquely named
// temporary in the target's directory, rename(2) replaces the target atomically.
#include "AtomicFile.h"

#include "Errors.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace cloudvis
{
namespace
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

std::string SystemReason()
{
  return std::strerror(errno);
}

// Removes the temporary unless it has been renamed: covers exceptions from the writer as well as
// our own failures.
class TemporaryFile
{
public:
  explicit TemporaryFile(std::string path)
    : Path(std::move(path))
  {
  }
  ~TemporaryFile()
  {
    if (!this->Path.empty())
    {
      std::remove(this->Path.c_str());
    }
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  void Release() { this->Path.clear(); }
  const std::string& GetPath() const { return this->Path; }

private:
  std::string Path;
};

// mkstemps creates files readable only by their owner; a finished output should get the
// permissions an ordinary new file would (or keep those of the file it replaces).
mode_t FinalMode(const std::string& target)
{
  struct stat existing;
  if (::stat(target.c_str(), &existing) == 0)
  {
    return existing.st_mode & 07777;
  }
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

} // namespace

void CheckOutputTarget(const std::string& target)
{
  if (target.empty())
  {
    throw InputError("the output path is empty");
  }
  const std::string directory = DirectoryOf(target);
  struct stat info;
  if (::stat(directory.c_str(), &info) != 0)
  {
    throw InputError(target + ": cannot write: directory " + directory + " does not exist (" +
      SystemReason() + ")");
  }
  if (!S_ISDIR(info.st_mode))
  {
    throw InputError(target + ": cannot write: " + directory + " is not a directory");
  }
  if (::access(directory.c_str(), W_OK | X_OK) != 0)
  {
    throw InputError(
      target + ": cannot write: directory " + directory + " is not writable (" + SystemReason() + ")");
  }
  if (::stat(target.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
  {
    throw InputError(target + ": cannot write: it is a directory");
  }
}

void WriteFileAtomically(
  const std::string& target, const std::function<void(const std::string& temporaryPath)>& write)
{
  CheckOutputTarget(target);
  const std::string directory = DirectoryOf(target);
  const auto slash = target.find_last_of('/');
  const std::string name = slash == std::string::npos ? target : target.substr(slash + 1);
  const auto dot = name.find_last_of('.');
  const std::string extension = dot == std::string::npos || dot == 0 ? "" : name.substr(dot);
  // Hidden, and named after the target, so a leftover from a killed process is recognisable.
  std::string pattern = directory + "/." + name + ".tmp-XXXXXX" + extension;
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  const int fd = ::mkstemps(buffer.data(), static_cast<int>(extension.size()));
  if (fd < 0)
  {
    throw InputError(target + ": cannot create a temporary file in " + directory + " (" +
      SystemReason() + ")");
  }
  TemporaryFile temporary(buffer.data());
  const mode_t mode = FinalMode(target);
  const bool modeSet = ::fchmod(fd, mode) == 0;
  ::close(fd);
  if (!modeSet)
  {
    throw InputError(target + ": cannot set permissions of the temporary file " +
      temporary.GetPath() + " (" + SystemReason() + ")");
  }

  write(temporary.GetPath());

  struct stat written;
  if (::stat(temporary.GetPath().c_str(), &written) != 0)
  {
    throw InputError(target + ": the writer left no file behind (" + SystemReason() + ")");
  }
  if (::rename(temporary.GetPath().c_str(), target.c_str()) != 0)
  {
    throw InputError(target + ": cannot replace the target (" + SystemReason() + ")");
  }
  temporary.Release();
}

} // namespace cloudvis
