// The forked, resource-limited read of a field file (IsolatedRead.h says why). The child writes
// one record to a pipe: either the field (geometry, every numeric point array, the array to use,
// the report) or the message of the InputError it threw. The parent reads the record while the
// child runs (a field is larger than a pipe's buffer), then looks at how the child ended: only a
// child that exited cleanly after a complete record has read the file; a signal, a time-out, an
// allocation beyond the limit or a sanitizer's exit status is reported without the parent ever
// parsing the file.
#include "IsolatedRead.h"

#include "AtomicFile.h"
#include "Errors.h"

#include "CloudFieldGeometry.h" // AvailableMemoryBytes, FormatBytes

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkPointData.h>

#include <oneapi/tbb/global_control.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <new>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace cloudvis
{
namespace
{

// How the child ends; any other exit status, or a signal, is a failure.
constexpr int ChildReadCleanly = 0;
constexpr int ChildRefused = 3; // an InputError, whose message is in the record
constexpr int ChildOutOfMemory = 4;
// The first word of a record.
constexpr std::uint64_t FieldRecord = 0x31444c4549465643;   // "CVFIELD1"
constexpr std::uint64_t RefusalRecord = 0x3146455246565643; // "CVREFUS1"
constexpr std::uint64_t MemoryRecord = 0x3159524d454d5643;  // "CVMEMRY1": what it needed

bool InChild = false;
// NoteReadNeeds: the largest need a reader noted, and what it is.
double NeededBytes = 0.0;
std::string Needed;
// The memory the child may take: its address-space limit less what it mapped at the start
// (0: unknown, no limit).
double ChildMemoryBytes = 0.0;

[[noreturn]] void Fail(const std::string& path, const std::string& problem)
{
  throw InputError(path + ": " + problem);
}

// ---- the child's side: a record written to the pipe -------------------------------------------

class RecordWriter
{
public:
  explicit RecordWriter(int descriptor)
    : Descriptor(descriptor)
  {
  }

  // Whether every byte so far reached the pipe (the parent may have gone).
  bool Good() const { return this->Ok; }

  void Bytes(const void* data, std::size_t count)
  {
    const char* at = static_cast<const char*>(data);
    while (this->Ok && count > 0)
    {
      const ssize_t written = ::write(this->Descriptor, at, count);
      if (written < 0 && errno == EINTR)
      {
        continue;
      }
      this->Ok = written > 0;
      at += written > 0 ? written : 0;
      count -= written > 0 ? std::size_t(written) : 0;
    }
  }
  template<typename T>
  void Value(const T& value)
  {
    this->Bytes(&value, sizeof value);
  }
  void Text(const std::string& text)
  {
    this->Value(std::uint64_t(text.size()));
    this->Bytes(text.data(), text.size());
  }

private:
  int Descriptor;
  bool Ok = true;
};

void WriteFieldRecord(RecordWriter& out, const FieldFileContents& contents)
{
  vtkImageData* image = contents.Image;
  out.Value(FieldRecord);
  int extent[6];
  image->GetExtent(extent);
  out.Bytes(extent, sizeof extent);
  out.Bytes(image->GetOrigin(), 3 * sizeof(double));
  out.Bytes(image->GetSpacing(), 3 * sizeof(double));
  out.Bytes(image->GetDirectionMatrix()->GetData(), 9 * sizeof(double));
  out.Text(contents.Array);
  vtkPointData* points = image->GetPointData();
  vtkDataArray* scalars = points->GetScalars();
  out.Text(scalars && scalars->GetName() ? scalars->GetName() : "");
  std::uint64_t arrays = 0;
  for (int i = 0; i < points->GetNumberOfArrays(); ++i)
  {
    arrays += points->GetArray(i) ? 1 : 0; // numeric arrays only
  }
  out.Value(arrays);
  for (int i = 0; i < points->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* array = points->GetArray(i);
    if (!array)
    {
      continue;
    }
    out.Value(std::uint8_t(array->GetName() ? 1 : 0));
    out.Text(array->GetName() ? array->GetName() : "");
    out.Value(std::int32_t(array->GetDataType()));
    out.Value(std::int32_t(array->GetNumberOfComponents()));
    out.Value(std::int64_t(array->GetNumberOfTuples()));
    const std::uint64_t bytes =
      std::uint64_t(array->GetNumberOfValues()) * std::uint64_t(array->GetDataTypeSize());
    out.Value(bytes);
    out.Bytes(array->GetVoidPointer(0), std::size_t(bytes));
  }
  out.Text(contents.Report.Format);
  out.Value(std::uint64_t(contents.Report.Details.size()));
  for (const auto& detail : contents.Report.Details)
  {
    out.Text(detail.first);
    out.Text(detail.second);
  }
  // The declared units: a presence byte and a value each.
  const FieldUnits& units = contents.Report.Units;
  out.Value(std::uint8_t(units.Quantity.has_value()));
  out.Value(std::int32_t(units.Quantity.value_or(FieldQuantity::Density)));
  out.Value(std::uint8_t(units.Length.has_value()));
  out.Value(std::int32_t(units.Length.value_or(LengthUnit::None)));
  out.Value(std::uint8_t(units.Up.has_value()));
  out.Value(std::int32_t(units.Up.value_or(1)));
  out.Value(std::uint8_t(units.EffectiveRadius.has_value()));
  out.Value(units.EffectiveRadius.value_or(0.0));
  out.Value(std::uint8_t(units.DropletNumber.has_value()));
  out.Value(units.DropletNumber.value_or(0.0));
  out.Value(contents.Report.LwcScale);
  out.Text(contents.Report.LwcScaleFrom);
  out.Value(std::uint64_t(contents.Report.TimeSteps));
  out.Value(contents.Report.Time);
  out.Text(contents.Report.TimeUnits);
  out.Value(std::uint64_t(contents.Report.Times.size()));
  out.Bytes(contents.Report.Times.data(), contents.Report.Times.size() * sizeof(double));
  out.Value(FieldRecord); // complete
}

// In the child: the limits, the read, the record; never returns.
[[noreturn]] void RunChild(const std::string& path,
  const std::string& parser,
  unsigned seconds,
  int descriptor,
  const std::function<FieldFileContents()>& read)
{
  InChild = true;
  // The temporaries of an export in progress are the parent's: a signal ending the child (the
  // alarm below) must not remove them.
  ForgetTemporariesInChild();
  // A parent that stopped reading must not end the child with SIGPIPE before it exits cleanly.
  std::signal(SIGPIPE, SIG_IGN);
#if !defined(__SANITIZE_ADDRESS__)
  // The child may use what the process already maps plus the memory still available, so a
  // header claiming more fails here as an allocation, not in the parent as an OOM kill.
  // (AddressSanitizer reserves terabytes of shadow memory, so its builds skip the limit.)
  std::uint64_t mapped = 0;
  std::ifstream status("/proc/self/status");
  for (std::string key; status >> key;)
  {
    if (key == "VmSize:")
    {
      status >> mapped;
      mapped *= 1024u;
      break;
    }
  }
  const std::uint64_t available = AvailableMemoryBytes();
  if (mapped > 0 && available > 0)
  {
    const rlimit memory{ rlim_t(mapped + available), rlim_t(mapped + available) };
    ::setrlimit(RLIMIT_AS, &memory);
  }
  // What the limit is now: a lower one the process was started under (ulimit -v) stays.
  rlimit limit{};
  if (mapped > 0 && ::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
    limit.rlim_cur > mapped)
  {
    ChildMemoryBytes = double(limit.rlim_cur - mapped);
  }
#endif
  // The time limit must end the child even when cloudvis was started with SIGALRM ignored or
  // blocked (both are inherited through exec and fork).
  std::signal(SIGALRM, SIG_DFL);
  sigset_t alarmOnly;
  sigemptyset(&alarmOnly);
  sigaddset(&alarmOnly, SIGALRM);
  ::pthread_sigmask(SIG_UNBLOCK, &alarmOnly, nullptr);
  ::alarm(seconds);
  int code = ChildReadCleanly;
  RecordWriter out(descriptor);
  try
  {
    WriteFieldRecord(out, read());
  }
  catch (const std::bad_alloc&)
  {
    code = ChildOutOfMemory;
    // The record needs no allocation: the parent reads what the file needs from it.
    out.Value(MemoryRecord);
    out.Value(NeededBytes);
    out.Value(ChildMemoryBytes);
    out.Text(Needed);
  }
  catch (const std::exception& e)
  {
    // InputError, or a library's exception a reader did not translate.
    out.Value(RefusalRecord);
    out.Text(dynamic_cast<const InputError*>(&e)
        ? std::string(e.what())
        : path + ": " + parser + " failed on this file: " + e.what());
    code = ChildRefused;
  }
  catch (...)
  {
    code = ChildRefused;
  }
  ::_exit(code);
}

// ---- the parent's side: the record read back --------------------------------------------------

class RecordReader
{
public:
  explicit RecordReader(int descriptor)
    : Descriptor(descriptor)
  {
  }

  // False once the pipe ended early: the child died while writing.
  bool Bytes(void* data, std::size_t count)
  {
    char* at = static_cast<char*>(data);
    while (count > 0)
    {
      const ssize_t got = ::read(this->Descriptor, at, count);
      if (got < 0 && errno == EINTR)
      {
        continue;
      }
      if (got <= 0)
      {
        return false;
      }
      at += got;
      count -= std::size_t(got);
    }
    return true;
  }
  template<typename T>
  bool Value(T& value)
  {
    return this->Bytes(&value, sizeof value);
  }
  // Texts are names, reports and messages: a length beyond 16 MiB is not the child's.
  bool Text(std::string& text)
  {
    std::uint64_t length = 0;
    if (!this->Value(length) || length > (std::uint64_t(16) << 20))
    {
      return false;
    }
    text.resize(std::size_t(length));
    return this->Bytes(&text[0], text.size());
  }

private:
  int Descriptor;
};

// The field of a record; false when the record is incomplete.
bool ReadFieldRecord(RecordReader& in, FieldFileContents& contents)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  int extent[6];
  double origin[3], spacing[3], direction[9];
  std::string scalars;
  std::uint64_t arrays = 0;
  if (!in.Bytes(extent, sizeof extent) || !in.Bytes(origin, sizeof origin) ||
    !in.Bytes(spacing, sizeof spacing) || !in.Bytes(direction, sizeof direction) ||
    !in.Text(contents.Array) || !in.Text(scalars) || !in.Value(arrays) || arrays > 4096)
  {
    return false;
  }
  image->SetExtent(extent);
  image->SetOrigin(origin);
  image->SetSpacing(spacing);
  image->SetDirectionMatrix(direction);
  for (std::uint64_t a = 0; a < arrays; ++a)
  {
    std::uint8_t named = 0;
    std::string name;
    std::int32_t type = 0, components = 0;
    std::int64_t tuples = 0;
    std::uint64_t bytes = 0;
    if (!in.Value(named) || !in.Text(name) || !in.Value(type) || !in.Value(components) ||
      !in.Value(tuples) || !in.Value(bytes))
    {
      return false;
    }
    vtkSmartPointer<vtkDataArray> array;
    array.TakeReference(vtkDataArray::CreateDataArray(type));
    if (!array || components < 1 || tuples < 0 ||
      bytes !=
        std::uint64_t(tuples) * std::uint64_t(components) * std::uint64_t(array->GetDataTypeSize()))
    {
      return false;
    }
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(tuples);
    if (!in.Bytes(array->GetVoidPointer(0), std::size_t(bytes)))
    {
      return false;
    }
    if (named)
    {
      array->SetName(name.c_str());
    }
    image->GetPointData()->AddArray(array);
    if (named && !scalars.empty() && name == scalars)
    {
      image->GetPointData()->SetActiveScalars(name.c_str());
    }
  }
  std::uint64_t details = 0;
  if (!in.Text(contents.Report.Format) || !in.Value(details) || details > 4096)
  {
    return false;
  }
  for (std::uint64_t d = 0; d < details; ++d)
  {
    std::string label, text;
    if (!in.Text(label) || !in.Text(text))
    {
      return false;
    }
    contents.Report.Add(label, text);
  }
  std::uint8_t has[5] = {};
  std::int32_t quantity = 0, length = 0, up = 0;
  double radius = 0.0, droplets = 0.0;
  if (!in.Value(has[0]) || !in.Value(quantity) || !in.Value(has[1]) || !in.Value(length) ||
    !in.Value(has[2]) || !in.Value(up) || !in.Value(has[3]) || !in.Value(radius) ||
    !in.Value(has[4]) || !in.Value(droplets) || quantity < 0 || quantity > 1 || length < 0 ||
    length > 2 || up < 0 || up > 2)
  {
    return false;
  }
  FieldUnits& units = contents.Report.Units;
  units.Quantity = has[0] ? std::optional<FieldQuantity>(FieldQuantity(quantity)) : std::nullopt;
  units.Length = has[1] ? std::optional<LengthUnit>(LengthUnit(length)) : std::nullopt;
  units.Up = has[2] ? std::optional<int>(up) : std::nullopt;
  units.EffectiveRadius = has[3] ? std::optional<double>(radius) : std::nullopt;
  units.DropletNumber = has[4] ? std::optional<double>(droplets) : std::nullopt;
  std::uint64_t end = 0, steps = 0, times = 0;
  contents.Image = image;
  if (!(in.Value(contents.Report.LwcScale) && std::isfinite(contents.Report.LwcScale) &&
        in.Text(contents.Report.LwcScaleFrom) && in.Value(steps) && steps >= 1 &&
        in.Value(contents.Report.Time) && in.Text(contents.Report.TimeUnits) && in.Value(times) &&
        (times == 0 || times == steps) && times <= (std::uint64_t(1) << 26)))
  {
    return false;
  }
  contents.Report.Times.resize(std::size_t(times));
  if (!(in.Bytes(contents.Report.Times.data(), std::size_t(times) * sizeof(double)) &&
        in.Value(end) && end == FieldRecord))
  {
    return false;
  }
  contents.Report.TimeSteps = std::size_t(steps);
  return true;
}

unsigned TimeLimitSeconds(std::uint64_t fileBytes)
{
  const char* configured = std::getenv("CLOUDVIS_READ_SECONDS");
  const int base = configured && std::atoi(configured) > 0 ? std::atoi(configured) : 60;
  return unsigned(base) + unsigned(fileBytes / (10u << 20)); // + 1 s per 10 MiB
}

} // namespace

bool InIsolatedRead()
{
  return InChild;
}

void NoteReadNeeds(const std::string& what, double bytes)
{
  if (InChild && bytes > NeededBytes)
  {
    NeededBytes = bytes;
    Needed = what;
  }
}

FieldFileContents ReadInIsolation(const std::string& path,
  std::uint64_t fileBytes,
  const std::string& parser,
  const std::function<FieldFileContents()>& read)
{
  const unsigned seconds = TimeLimitSeconds(fileBytes);
  // A child inherits TBB's thread pool without its threads, and the first parallel loop it runs
  // (OpenVDB frees a tree with one) waits for them forever. So the pool's threads are ended
  // first; TBB starts new ones when this process next needs them.
  {
    oneapi::tbb::task_scheduler_handle scheduler{ oneapi::tbb::attach{} };
    // False when another part of the process holds the pool (none of cloudvis does): then the
    // child's time limit is what ends a wait.
    oneapi::tbb::finalize(scheduler, std::nothrow);
  }
  int channel[2];
  if (::pipe2(channel, O_CLOEXEC) != 0)
  {
    return read(); // no isolation to be had: read here, behind the other checks alone
  }
  const pid_t child = ::fork();
  if (child < 0)
  {
    ::close(channel[0]);
    ::close(channel[1]);
    return read();
  }
  if (child == 0)
  {
    ::close(channel[0]);
    RunChild(path, parser, seconds, channel[1], read);
  }
  ::close(channel[1]);
  RecordReader in(channel[0]);
  std::uint64_t kind = 0;
  FieldFileContents contents;
  std::string refusal;
  double neededBytes = 0.0, childBytes = 0.0;
  std::string needed;
  bool complete = false;
  try
  {
    complete = in.Value(kind) &&
      (kind == FieldRecord        ? ReadFieldRecord(in, contents)
          : kind == RefusalRecord ? in.Text(refusal)
                                  : kind == MemoryRecord && in.Value(neededBytes) &&
            in.Value(childBytes) && in.Text(needed));
  }
  catch (const std::bad_alloc&)
  {
    complete = false; // the copy did not fit here: reported after the child has ended
  }
  ::close(channel[0]); // a child still writing gets EPIPE, not a wait
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR)
  {
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == ChildReadCleanly && complete && kind == FieldRecord)
  {
#if defined(CLOUDVIS_FUZZING_BUILD)
    // The child's coverage never reaches libFuzzer's counters: a file the child read (so one
    // known to fit in the limits) is read here again, for the coverage of the readers' code.
    return read();
#else
    return contents;
#endif
  }
  if (code == ChildRefused && complete && kind == RefusalRecord)
  {
    throw InputError(refusal);
  }
  if (code == ChildReadCleanly || code == ChildRefused)
  {
    Fail(path,
      "the field read from this file (" + parser +
        ") does not fit in the memory left to "
        "cloudvis (" +
        FormatBytes(double(AvailableMemoryBytes())) + " available)");
  }
  if (code == ChildOutOfMemory)
  {
    // The memory the read could take: the child's limit where it had one, else what the system
    // has available.
    const std::string available =
      FormatBytes(childBytes > 0.0 ? childBytes : double(AvailableMemoryBytes()));
    if (complete && kind == MemoryRecord && neededBytes > 0.0 && !needed.empty())
    {
      Fail(path,
        parser + " ran out of memory on this file: " + needed + " needs about " +
          FormatBytes(neededBytes) + " to read (by its dimensions)" +
          (childBytes > 0.0 && neededBytes > childBytes
              ? ", more than the " + available + " the read may use (the address-space limit)"
              : "; with the library's own buffers the read took more than the " + available +
                " it may use"));
    }
    Fail(path,
      parser +
        " ran out of memory on this file before its size was known: what its header "
        "claims is more than the " +
        available + " the read may use");
  }
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
  {
    Fail(path,
      parser + " took longer than " + std::to_string(seconds) +
        " s on this file without finishing: it is malformed");
  }
  if (WIFSIGNALED(status))
  {
    Fail(path,
      parser + " crashed on this file (" + std::string(strsignal(WTERMSIG(status))) +
        "): it is malformed");
  }
  // Another status: a sanitizer (in sanitized builds) caught the library doing something fatal.
  Fail(path,
    parser + " failed on this file (exit status " + std::to_string(code) + "): it is malformed");
}

} // namespace cloudvis
