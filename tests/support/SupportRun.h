// Running the real cloudvis binary from a test, and the folders tests write into.
//
// RunCloudvis starts the executable this build made (CLOUDVIS_BINARY), as a user would: main(),
// the object factories it registers, its exit status and both output streams are what is tested,
// and a crash is a failed status in the test rather than the end of the test program.
#ifndef cloudvis_SupportRun_h
#define cloudvis_SupportRun_h

#include <string>
#include <vector>

namespace cloudvis
{
namespace support
{

struct CommandResult
{
  int Status = -1; // the exit status; 128 + N when killed by signal N
  std::string Out; // stdout
  std::string Err; // stderr
};

// The path of the cloudvis executable this build made, for programs that start it themselves
// (the live tests run it in the background on their own X server).
std::string CloudvisBinary();

// Runs `cloudvis arguments...` and waits for it. `environment` changes the child's environment
// only: "NAME=VALUE" sets a variable, "-NAME" removes it.
CommandResult RunCloudvis(const std::vector<std::string>& arguments,
  const std::vector<std::string>& environment = {});

// `a` followed by `b`: a command's arguments and a shared tail of options.
std::vector<std::string> With(std::vector<std::string> a, const std::vector<std::string>& b);

// A fresh folder under /tmp, removed with everything in it when the object goes.
class TemporaryDirectory
{
public:
  explicit TemporaryDirectory(const std::string& prefix = "cloudvis-test");
  ~TemporaryDirectory();
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  // The path of `name` inside the folder.
  std::string File(const std::string& name) const { return this->Path + "/" + name; }
  // The names in the folder (or in its subfolder `sub`, "/frames"), sorted.
  std::vector<std::string> Files(const std::string& sub = "") const;
  // Writes `content` to File(name) and returns that path.
  std::string Write(const std::string& name, const std::string& content) const;

  std::string Path;
};

// The whole of a text file ("" when it cannot be read), and a text file written whole.
std::string ReadText(const std::string& path);
void WriteText(const std::string& path, const std::string& text);

} // namespace support
} // namespace cloudvis

#endif
