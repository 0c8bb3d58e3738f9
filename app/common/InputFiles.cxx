#include "InputFiles.h"

#include "Errors.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace cloudvis
{
namespace
{

// What a file of this mode is, for a message; empty for a regular file.
std::string NotRegularReason(mode_t mode)
{
  if (S_ISREG(mode))
  {
    return "";
  }
  const char* kind = S_ISDIR(mode) ? "a directory"
    : S_ISFIFO(mode)               ? "a FIFO (named pipe)"
    : S_ISCHR(mode)                ? "a character device"
    : S_ISBLK(mode)                ? "a block device"
    : S_ISSOCK(mode)               ? "a socket"
                                   : "not a file";
  return std::string("it is ") + kind + ", not a regular file";
}

[[noreturn]] void Refuse(const std::string& path,
  const std::string& what,
  const std::string& reason)
{
  throw InputError(path + ": cannot read " + what + ": " + reason);
}

std::string SizeInWords(std::uint64_t bytes)
{
  return std::to_string(bytes >> 20) + " MiB (" + std::to_string(bytes) + " bytes)";
}

} // namespace

std::uint64_t CheckRegularInputFile(const std::string& path, const std::string& what)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    Refuse(path, what, std::strerror(errno));
  }
  const std::string reason = NotRegularReason(info.st_mode);
  if (!reason.empty())
  {
    Refuse(path, what, reason);
  }
  return std::uint64_t(info.st_size);
}

RegularInputFile::RegularInputFile(const std::string& path, const std::string& what)
  : Path(path)
  , What(what)
{
  CheckRegularInputFile(path, what);
  // O_NONBLOCK: should the path have become a FIFO since the check, the open returns at once
  // (and the fstat below refuses it) instead of waiting for a writer. It changes nothing for a
  // regular file.
  this->Descriptor = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (this->Descriptor < 0)
  {
    Refuse(path, what, std::strerror(errno));
  }
  struct stat info;
  std::string reason =
    ::fstat(this->Descriptor, &info) != 0 ? std::strerror(errno) : NotRegularReason(info.st_mode);
  if (!reason.empty())
  {
    ::close(this->Descriptor);
    Refuse(path, what, reason);
  }
  this->Bytes = std::uint64_t(info.st_size);
}

RegularInputFile::~RegularInputFile()
{
  ::close(this->Descriptor);
}

std::string RegularInputFile::ReadAt(std::uint64_t offset, std::size_t count) const
{
  std::string bytes(count, '\0');
  std::size_t done = 0;
  while (done < count)
  {
    const ssize_t got = ::pread(this->Descriptor, &bytes[done], count - done, off_t(offset + done));
    if (got < 0 && errno == EINTR)
    {
      continue;
    }
    if (got < 0)
    {
      Refuse(this->Path, this->What, std::strerror(errno));
    }
    if (got == 0)
    {
      break;
    }
    done += std::size_t(got);
  }
  bytes.resize(done);
  return bytes;
}

std::string RegularInputFile::ReadAll(std::uint64_t maximumBytes) const
{
  const std::string limit =
    ", above the limit of " + SizeInWords(maximumBytes) + " for a " + this->What;
  if (this->Bytes > maximumBytes)
  {
    Refuse(this->Path, this->What, "it is " + SizeInWords(this->Bytes) + limit);
  }
  // Read to the end rather than Size() bytes: a file that grew since it was opened is refused
  // once it passes the limit.
  std::string text;
  constexpr std::size_t chunk = std::size_t(1) << 16;
  for (std::string part = this->ReadAt(0, chunk); !part.empty();
       part = this->ReadAt(text.size(), chunk))
  {
    text += part;
    if (text.size() > maximumBytes)
    {
      Refuse(this->Path, this->What, "it grew while being read" + limit);
    }
  }
  return text;
}

} // namespace cloudvis
