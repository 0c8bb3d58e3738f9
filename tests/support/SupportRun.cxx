// The cloudvis runner and temporary folders of the tests (SupportRun.h).
#include "SupportRun.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <fstream>
#include <ftw.h>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace cloudvis
{
namespace support
{
namespace
{
// A temporary file that catches one output stream of the child.
struct Capture
{
  std::string Path;
  int Descriptor = -1;
  Capture()
  {
    char pattern[] = "/tmp/cloudvis-run-XXXXXX";
    this->Descriptor = ::mkstemp(pattern);
    if (this->Descriptor < 0)
    {
      throw std::runtime_error(std::string("mkstemp: ") + std::strerror(errno));
    }
    this->Path = pattern;
  }
  ~Capture()
  {
    ::close(this->Descriptor);
    ::unlink(this->Path.c_str());
  }
  std::string Text() const { return ReadText(this->Path); }
};

std::vector<std::string> ChildEnvironment(const std::vector<std::string>& changes)
{
  std::vector<std::string> variables;
  for (char** v = environ; *v; ++v)
  {
    variables.emplace_back(*v);
  }
  for (const std::string& change : changes)
  {
    const bool remove = !change.empty() && change[0] == '-';
    const std::string name = remove ? change.substr(1) : change.substr(0, change.find('='));
    variables.erase(std::remove_if(variables.begin(),
                      variables.end(),
                      [&name](const std::string& v) { return v.rfind(name + "=", 0) == 0; }),
      variables.end());
    if (!remove)
    {
      variables.push_back(change);
    }
  }
  return variables;
}

std::vector<char*> Pointers(std::vector<std::string>& strings)
{
  std::vector<char*> pointers;
  for (std::string& s : strings)
  {
    pointers.push_back(&s[0]);
  }
  pointers.push_back(nullptr);
  return pointers;
}
}

std::string CloudvisBinary()
{
  return CLOUDVIS_BINARY;
}

CommandResult RunCloudvis(const std::vector<std::string>& arguments,
  const std::vector<std::string>& environment)
{
  // argv[0] is "cloudvis", as when a user runs it from the PATH (exports record the command).
  const std::string binary = CloudvisBinary();
  std::vector<std::string> argv{ "cloudvis" };
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  std::vector<std::string> envp = ChildEnvironment(environment);
  const Capture out, err;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out.Descriptor, 1);
  posix_spawn_file_actions_adddup2(&actions, err.Descriptor, 2);
  pid_t child = 0;
  const int spawned = ::posix_spawn(
    &child, binary.c_str(), &actions, nullptr, Pointers(argv).data(), Pointers(envp).data());
  posix_spawn_file_actions_destroy(&actions);
  CommandResult result;
  if (spawned != 0)
  {
    result.Err = "cannot start " + binary + ": " + std::strerror(spawned);
    return result;
  }
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR)
  {
  }
  result.Status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.Out = out.Text();
  result.Err = err.Text();
  return result;
}

std::vector<std::string> With(std::vector<std::string> a, const std::vector<std::string>& b)
{
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TemporaryDirectory::TemporaryDirectory(const std::string& prefix)
{
  std::string pattern = "/tmp/" + prefix + "-XXXXXX";
  if (!::mkdtemp(&pattern[0]))
  {
    throw std::runtime_error("mkdtemp " + pattern + ": " + std::strerror(errno));
  }
  this->Path = pattern;
}

TemporaryDirectory::~TemporaryDirectory()
{
  // Depth first, without following links.
  ::nftw(
    this->Path.c_str(),
    [](const char* path, const struct stat*, int, struct FTW*) { return ::remove(path); },
    16,
    FTW_DEPTH | FTW_PHYS);
}

std::vector<std::string> TemporaryDirectory::Files(const std::string& sub) const
{
  std::vector<std::string> names;
  if (DIR* dir = ::opendir((this->Path + sub).c_str()))
  {
    while (dirent* entry = ::readdir(dir))
    {
      const std::string name = entry->d_name;
      if (name != "." && name != "..")
      {
        names.push_back(name);
      }
    }
    ::closedir(dir);
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string TemporaryDirectory::Write(const std::string& name, const std::string& content) const
{
  const std::string path = this->File(name);
  WriteText(path, content);
  return path;
}

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream(path, std::ios::binary) << text;
}

std::string ReadText(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

} // namespace support
} // namespace cloudvis
