// The one way cloudvis opens a file it reads: scenes, presets, ParaView preset files, field
// files and their pieces, --play recordings. Only a regular file is read. A FIFO would block the
// open (or the read) forever, a device such as /dev/zero or /dev/urandom never ends, and opening
// some devices has side effects, so the path is checked with stat(2) before it is opened and
// refused with a message naming the path and what it is (a directory, a FIFO, a character
// device, ...). The open then uses O_NONBLOCK and checks the descriptor again, so a path replaced
// by a FIFO in between cannot block either. Files read whole into memory (JSON, recordings) are
// refused above a stated size. Readers that hand a path to VTK check it with
// CheckRegularInputFile first; VTK opens it again by name, so a file swapped between the two
// (by another local user with write access to the directory) is the residual risk.
#ifndef cloudvis_InputFiles_h
#define cloudvis_InputFiles_h

#include <cstddef>
#include <cstdint>
#include <string>

namespace cloudvis
{

// The most a JSON input (a scene, a preset, a ParaView preset file) may hold: 16 MiB. ParaView's
// complete list of shipped colour maps, the largest preset file in common use, is under 2 MiB;
// the limit bounds the parsed document to a few hundred MiB of memory.
constexpr std::uint64_t MaximumJsonFileBytes = std::uint64_t(16) << 20;

// The most a --play recording may hold: 16 MiB, hours of recorded mouse motion.
constexpr std::uint64_t MaximumRecordingBytes = std::uint64_t(16) << 20;

// Throws InputError "PATH: cannot read WHAT: REASON" unless `path` names a regular file
// (symbolic links followed), without opening it; returns its size in bytes. REASON is the
// system's ("No such file or directory") or what the path is instead ("it is a FIFO (named
// pipe), not a regular file").
std::uint64_t CheckRegularInputFile(const std::string& path, const std::string& what);

// A regular file, open for reading while the object lives. `what` names the file's role in
// messages ("scene file", "field", "recording").
class RegularInputFile
{
public:
  // Checks and opens `path`; throws InputError as CheckRegularInputFile does.
  RegularInputFile(const std::string& path, const std::string& what);
  ~RegularInputFile();
  RegularInputFile(const RegularInputFile&) = delete;
  RegularInputFile& operator=(const RegularInputFile&) = delete;

  // The size when the file was opened.
  std::uint64_t Size() const { return this->Bytes; }

  // Up to `count` bytes starting at `offset` (fewer at the end of the file). Throws InputError
  // when the system reports a read error.
  std::string ReadAt(std::uint64_t offset, std::size_t count) const;

  // The whole file. Throws InputError naming the size and the limit when it holds more than
  // `maximumBytes` (checked against what is read, too, so a file that grows is also refused).
  std::string ReadAll(std::uint64_t maximumBytes) const;

private:
  std::string Path;
  std::string What;
  int Descriptor = -1;
  std::uint64_t Bytes = 0;
};

} // namespace cloudvis

#endif
