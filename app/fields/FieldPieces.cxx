// The .pvti writer (FieldPieces.h says what it promises). The .pvti is written here as text, not
// by vtkXMLPImageDataWriter: that writer names the files it writes after its own file name, so it
// cannot write through the temporary files of AtomicFile.h, and VTK 9.1's does not record the
// direction. The pieces are written by vtkXMLImageDataWriter (WriteVtkXmlImageFile), each
// recording the run.
#include "FieldPieces.h"

#include "AtomicFile.h"
#include "Errors.h"
#include "FieldIO.h"
#include "FileNames.h"

#include <vtkCommunicator.h>
#include <vtkExtentTranslator.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <dirent.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

namespace cloudvis
{
namespace
{

[[noreturn]] void Fail(const std::string& path, const std::string& problem)
{
  throw InputError(path + ": " + problem);
}

std::string Stem(const std::string& path)
{
  const std::string name = FileNameOf(path);
  const auto dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

// An XML attribute value: the five characters XML reserves, escaped.
std::string EscapedAttribute(const std::string& text)
{
  std::string escaped;
  for (char c : text)
  {
    switch (c)
    {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&apos;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

template<typename Values>
std::string Joined(const Values& values)
{
  std::ostringstream text;
  text.precision(17); // doubles written back exactly
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    text << (i ? " " : "") << values[i];
  }
  return text.str();
}

// The text of the .pvti of run `run`.
std::string PvtiText(const FieldLattice& lattice,
  const std::string& path,
  int pieces,
  const std::string& run)
{
  std::ostringstream xml;
  const std::uint16_t one = 1;
  const bool littleEndian = *reinterpret_cast<const unsigned char*>(&one) == 1;
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PImageData\" version=\"1.0\" byte_order=\""
      << (littleEndian ? "LittleEndian" : "BigEndian") << "\" header_type=\"UInt64\">\n"
      << "  <PImageData WholeExtent=\"" << Joined(lattice.WholeExtent)
      << "\" GhostLevel=\"0\" Origin=\"" << Joined(lattice.Origin) << "\" Spacing=\""
      << Joined(lattice.Spacing) << "\" Direction=\"" << Joined(lattice.Direction) << "\" "
      << PieceRunAttribute << "=\"" << run << "\">\n"
      << "    <PPointData Scalars=\"density\">\n"
      << "      <PDataArray type=\"Float32\" Name=\"density\"/>\n"
      << "    </PPointData>\n";
  for (int p = 0; p < pieces; ++p)
  {
    xml << "    <Piece Extent=\"" << Joined(PieceExtent(lattice.WholeExtent, p, pieces))
        << "\" Source=\"" << EscapedAttribute(PieceSource(path, p)) << "\"/>\n";
  }
  xml << "  </PImageData>\n</VTKFile>\n";
  return xml.str();
}

void WriteText(const std::string& text, const std::string& file, const std::string& target)
{
  WriteNewFileChecked(file,
    target,
    "the parallel image data file",
    [&](std::ostream& out) { out.write(text.data(), std::streamsize(text.size())); });
}

// The first `bytes` of a file (less when it is shorter), empty when it cannot be read.
std::string Head(const std::string& path, std::size_t bytes)
{
  std::ifstream in(path, std::ios::binary);
  std::string text(bytes, '\0');
  in.read(&text[0], std::streamsize(bytes));
  text.resize(std::size_t(in.gcount()));
  return text;
}

// A new run id: 128 random bits from the system's entropy source, as 32 hexadecimal digits.
std::string NewRunId()
{
  std::random_device entropy;
  char id[33] = {};
  for (int word = 0; word < 4; ++word)
  {
    std::snprintf(id + 8 * word, 9, "%08x", unsigned(entropy()));
  }
  return id;
}

// Process 0's `run`, on every process.
std::string SharedRunId(vtkMultiProcessController* controller, std::string run)
{
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    run.resize(32);
    controller->Broadcast(&run[0], 32, 0);
  }
  return run;
}

// Removes the files <stem>_<N>.vti beside `path` with N >= `pieces`: pieces of an older output
// that the new one does not name, when the .pvti being replaced names them or they record a run
// (cloudvis wrote them as pieces). Left in place they would look like valid pieces. Other files
// are not touched.
void RemovePiecesBeyond(const std::string& path, int pieces)
{
  const std::string previous = Head(path, std::size_t(16) << 20);
  const std::string directory = DirectoryOf(path);
  DIR* listing = ::opendir(directory.c_str());
  if (!listing)
  {
    Fail(directory, std::string("cannot list the directory (") + std::strerror(errno) + ")");
  }
  std::vector<std::string> stale;
  const std::string prefix = Stem(path) + "_";
  while (const dirent* entry = ::readdir(listing))
  {
    const std::string name = entry->d_name;
    if (name.size() <= prefix.size() + 4 || name.compare(0, prefix.size(), prefix) != 0)
    {
      continue;
    }
    const std::string number = name.substr(prefix.size(), name.size() - prefix.size() - 4);
    if (number.empty() || number.size() > 9 ||
      number.find_first_not_of("0123456789") != std::string::npos)
    {
      continue;
    }
    const int index = std::atoi(number.c_str());
    if (index < pieces || PieceSource(path, index) != name)
    {
      continue;
    }
    const std::string file = path.find('/') == std::string::npos ? name : directory + "/" + name;
    const bool named =
      previous.find("Source=\"" + EscapedAttribute(name) + "\"") != std::string::npos;
    const bool cloudvisPiece =
      Head(file, 4096).find(std::string(" ") + PieceRunAttribute + "=\"") != std::string::npos;
    if (named || cloudvisPiece)
    {
      stale.push_back(file);
    }
  }
  ::closedir(listing);
  for (const std::string& file : stale)
  {
    if (::unlink(file.c_str()) != 0 && errno != ENOENT)
    {
      Fail(file,
        std::string("cannot remove this piece of the previous output (") + std::strerror(errno) +
          ")");
    }
  }
}

// After a failure once renames have begun: the previous output is no longer whole, so none is
// left, rather than a .pvti naming pieces of two runs. Each process removes its pieces, process
// 0 the pieces beyond the new count and the .pvti.
void RemoveOutput(const std::string& path, int pieces, int rank, int processes)
{
  for (int p = rank; p < pieces; p += processes)
  {
    std::remove(PieceFileName(path, p).c_str());
  }
  if (rank == 0)
  {
    try
    {
      RemovePiecesBeyond(path, pieces);
    }
    catch (const InputError&)
    {
      // The failure being reported says enough; without the .pvti these name nothing.
    }
    std::remove(path.c_str());
  }
}

// CLOUDVIS_TEST_PAUSE_AFTER_PIECE (FieldPieces.h): seconds to pause after each piece, 0: none.
double TestPauseAfterPiece()
{
  const char* value = std::getenv("CLOUDVIS_TEST_PAUSE_AFTER_PIECE");
  return value ? std::max(0.0, std::atof(value)) : 0.0;
}

} // namespace

FieldLattice LatticeOf(vtkImageData* field)
{
  FieldLattice lattice;
  field->GetExtent(lattice.WholeExtent.data());
  field->GetOrigin(lattice.Origin.data());
  field->GetSpacing(lattice.Spacing.data());
  for (int i = 0; i < 9; ++i)
  {
    lattice.Direction[std::size_t(i)] = field->GetDirectionMatrix()->GetData()[i];
  }
  return lattice;
}

Extent PieceExtent(const Extent& whole, int piece, int pieces)
{
  vtkNew<vtkExtentTranslator> translator;
  Extent wholeCopy = whole;
  Extent extent{};
  if (!translator->PieceToExtentThreadSafe(
        piece, pieces, 0, wholeCopy.data(), extent.data(), vtkExtentTranslator::BLOCK_MODE, 0))
  {
    throw InputError("a field of extent " + Joined(whole) + " cannot be split into " +
      std::to_string(pieces) + " pieces: piece " + std::to_string(piece) + " would be empty");
  }
  return extent;
}

std::string PieceSource(const std::string& path, int piece)
{
  return Stem(path) + "_" + std::to_string(piece) + ".vti";
}

std::string PieceFileName(const std::string& path, int piece)
{
  return path.find('/') == std::string::npos ? PieceSource(path, piece)
                                             : DirectoryOf(path) + "/" + PieceSource(path, piece);
}

void RunAgreed(vtkMultiProcessController* controller, const std::function<void()>& step)
{
  const int processes = controller ? controller->GetNumberOfProcesses() : 1;
  if (processes < 2)
  {
    step();
    return;
  }
  const int rank = controller->GetLocalProcessId();
  enum Outcome : int
  {
    Succeeded,
    InputFailure,
    UsageFailure
  };
  int outcome = Succeeded;
  std::string message;
  std::exception_ptr failure;
  try
  {
    step();
  }
  catch (const UsageError& e)
  {
    outcome = UsageFailure;
    message = e.what();
    failure = std::current_exception();
  }
  catch (const std::bad_alloc&)
  {
    outcome = InputFailure;
    message = "out of memory";
    failure = std::current_exception();
  }
  catch (const std::exception& e)
  {
    outcome = InputFailure;
    message = e.what();
    failure = std::current_exception();
  }
  catch (...)
  {
    // Whatever was thrown (a library's own type, an int), this process still votes: letting it
    // pass the vote would leave every other process waiting for it for ever.
    outcome = InputFailure;
    message = "an unknown error";
    failure = std::current_exception();
  }
  // The lowest-ranked failing process (`processes` when none failed), then its outcome and
  // message, sent by it: every process takes part in both, so none waits for another in vain.
  const int mine = outcome == Succeeded ? processes : rank;
  int first = processes;
  controller->AllReduce(&mine, &first, 1, vtkCommunicator::MIN_OP);
  if (first == processes)
  {
    return;
  }
  int header[2] = { outcome, int(std::min<std::size_t>(message.size(), 1 << 20)) };
  controller->Broadcast(header, 2, first);
  std::vector<char> text(static_cast<std::size_t>(header[1]));
  if (rank == first)
  {
    std::copy(message.begin(), message.begin() + header[1], text.begin());
  }
  if (!text.empty())
  {
    controller->Broadcast(text.data(), vtkIdType(text.size()), first);
  }
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  const std::string agreed = "process " + std::to_string(first) + " of " +
    std::to_string(processes) + " failed: " + std::string(text.begin(), text.end());
  if (header[0] == UsageFailure)
  {
    throw UsageError(agreed);
  }
  throw InputError(agreed);
}

void WriteFieldPieces(const FieldLattice& lattice,
  const std::string& requested,
  int pieces,
  const PieceProducer& produce,
  vtkMultiProcessController* controller)
{
  // A .pvti that is a symbolic link is written through it (AtomicFile.h), pieces included: they
  // go beside the file the link names, where that file's relative Source attributes find them.
  // Every process sees the same links, so all reach the same answer.
  const std::string path = OutputFileBehindLinks(requested);
  const int processes = controller ? controller->GetNumberOfProcesses() : 1;
  const int rank = controller ? controller->GetLocalProcessId() : 0;
  // From the start, so that a signal on any process, whenever it comes, goes through the handler
  // that removes the run's temporaries (AtomicFile.h), not the default action.
  InstallInterruptCleanup();
  // The temporaries of the whole run: one directory, named after the run, holding the pieces
  // under their own names and the .pvti (AtomicFile.h). Process 0 draws the run id; every process
  // learns it before the directory exists, and registers the group (process 0 creating the
  // directory) as soon as it knows it, with no collective call in between: from the directory's
  // creation on, a signal to any process removes it.
  std::string run;
  std::optional<TemporaryGroup> temporaries;
  RunAgreed(controller,
    [&]
    {
      if (pieces < 1)
      {
        Fail(path, "the number of pieces must be at least 1");
      }
      for (int p = 0; p < pieces; ++p)
      {
        PieceExtent(lattice.WholeExtent, p, pieces); // every piece non-empty, before any work
      }
      CheckOutputTarget(path);
      for (int p = rank; p < pieces; p += processes)
      {
        CheckOutputTarget(PieceFileName(path, p));
      }
      if (rank == 0)
      {
        run = NewRunId();
      }
    });
  run = SharedRunId(controller, run);
  RunAgreed(controller,
    [&] {
      temporaries.emplace(path, run, rank == 0, Stem(path) + "_", ".vti", pieces, FileNameOf(path));
    });

  // 1. This process's pieces, and the .pvti on process 0, into the run's directory. A signal
  // now ends the process at once and removes the directory with everything in it, whichever
  // process wrote it (AtomicFile.h); under mpirun the others end too: mpirun passes its own
  // SIGINT or SIGTERM on to every process as SIGTERM, and kills the job when one process dies.
  const double pause = TestPauseAfterPiece();
  RunAgreed(controller,
    [&]
    {
      for (int p = rank; p < pieces; p += processes)
      {
        const Extent extent = PieceExtent(lattice.WholeExtent, p, pieces);
        try
        {
          WriteVtkXmlImageFile(produce(extent),
            temporaries->Member(PieceSource(path, p)),
            PieceFileName(path, p),
            run);
        }
        catch (const std::bad_alloc&)
        {
          Fail(PieceFileName(path, p),
            "out of memory while making this piece (" + std::to_string(extent[1] - extent[0] + 1) +
              " x " + std::to_string(extent[3] - extent[2] + 1) + " x " +
              std::to_string(extent[5] - extent[4] + 1) + " voxels)");
        }
        if (pause > 0.0)
        {
          std::fprintf(stderr, "cloudvis: paused after piece %d\n", p);
          std::fflush(stderr);
          std::this_thread::sleep_for(std::chrono::duration<double>(pause));
        }
      }
      if (rank == 0)
      {
        WriteText(
          PvtiText(lattice, path, pieces, run), temporaries->Member(FileNameOf(path)), path);
      }
    });

  // 2. All written everywhere: put the new output in place, pieces first, the .pvti last. Each
  // process holds signals only while it renames its own files, so that none cuts those renames
  // in two (one arriving meanwhile ends the process once they are done); the votes between them
  // are made with signals acted on, so a process waiting for a peer that died or stalls still
  // ends on SIGINT or SIGTERM. A signal between the two steps leaves the new pieces beside the
  // old .pvti, which the reader refuses by their run (FieldPieces.h). A failure leaves no
  // output rather than a mixed one.
  try
  {
    RunAgreed(controller,
      [&]
      {
        const InterruptionHold hold;
        for (int p = rank; p < pieces; p += processes)
        {
          temporaries->Commit(PieceSource(path, p), PieceFileName(path, p));
        }
      });
    RunAgreed(controller,
      [&]
      {
        if (rank == 0)
        {
          const InterruptionHold hold;
          RemovePiecesBeyond(path, pieces);
          temporaries->Commit(FileNameOf(path), path);
        }
      });
  }
  catch (...)
  {
    RemoveOutput(path, pieces, rank, processes);
    throw;
  }
}

vtkSmartPointer<vtkImageData> ExtractPiece(vtkImageData* field, const Extent& extent)
{
  auto piece = vtkSmartPointer<vtkImageData>::New();
  piece->SetExtent(const_cast<int*>(extent.data()));
  piece->SetOrigin(field->GetOrigin());
  piece->SetSpacing(field->GetSpacing());
  piece->SetDirectionMatrix(field->GetDirectionMatrix());
  vtkDataArray* whole = field->GetPointData()->GetScalars();
  vtkSmartPointer<vtkDataArray> values;
  values.TakeReference(whole->NewInstance());
  values->SetName(whole->GetName() ? whole->GetName() : "density");
  values->SetNumberOfComponents(1);
  values->SetNumberOfTuples(piece->GetNumberOfPoints());
  vtkIdType at = 0;
  for (int k = extent[4]; k <= extent[5]; ++k)
  {
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      for (int i = extent[0]; i <= extent[1]; ++i)
      {
        int ijk[3] = { i, j, k };
        values->SetTuple(at++, field->ComputePointId(ijk), whole);
      }
    }
  }
  piece->GetPointData()->SetScalars(values);
  return piece;
}

void WriteFieldPieces(vtkImageData* field,
  const std::string& path,
  int pieces,
  vtkMultiProcessController* controller)
{
  WriteFieldPieces(
    LatticeOf(field),
    path,
    pieces,
    [field](const Extent& extent) { return ExtractPiece(field, extent); },
    controller);
}

} // namespace cloudvis
