// Writing a field as VTK XML parallel image data: a .pvti that lists N pieces, each a .vti holding
// one block of the whole extent, split as VTK's vtkExtentTranslator splits it (adjacent blocks
// share their boundary plane of points, as VTK's own parallel writer makes them). The pieces are
// named as VTK's parallel writer names them, <stem>_<p>.vti beside the .pvti, so ParaView, VTK and
// cloudvis read them back.
//
// A piece is made by a function of its extent, so a procedural field is generated piece by piece
// (one piece in memory at a time) and, under MPI, each process makes and writes only its own
// pieces: process r of R takes the pieces p with p % R == r.
//
// The output is replaced as one: every process writes its pieces, and process 0 the .pvti, into
// one directory of temporaries named after the run (TemporaryGroup, AtomicFile.h), which the
// signal handler of any process removes whole; the processes agree that all were written
// (RunAgreed); only then each renames its pieces into place, they agree again, and process 0
// removes the pieces of an older output that the new one no longer names and renames the .pvti
// last. Interruptions are held (InterruptionHold) only while a process renames its own files,
// never across a vote, so a process waiting for a peer still ends on a signal. A failure anywhere
// before the renames, or a signal (Ctrl-C, mpirun's SIGTERM) before them, leaves the previous
// output untouched and no temporary. The .pvti and every piece record the run that wrote them
// (PieceRunAttribute, a random 128-bit id), which the reader checks: what renames cannot make
// atomic (a signal between the pieces' renames and the .pvti's, a process killed by SIGKILL or a
// crash during the renames) may leave new pieces beside the old .pvti, which is refused when
// read, never read as a field mixed from two runs.
#ifndef cloudvis_FieldPieces_h
#define cloudvis_FieldPieces_h

#include <vtkSmartPointer.h>

#include <array>
#include <functional>
#include <string>

class vtkImageData;
class vtkMultiProcessController;

namespace cloudvis
{

using Extent = std::array<int, 6>;

// The whole lattice of a field written in pieces.
struct FieldLattice
{
  Extent WholeExtent{};
  std::array<double, 3> Origin{};
  std::array<double, 3> Spacing{ { 1.0, 1.0, 1.0 } };
  std::array<double, 9> Direction{ { 1, 0, 0, 0, 1, 0, 0, 0, 1 } }; // row-major
};

// The lattice of a field in memory.
FieldLattice LatticeOf(vtkImageData* field);

// The extent of piece `piece` (0 .. pieces - 1) of `whole`, as vtkExtentTranslator's block mode
// splits it. Throws InputError when the extent has fewer points than pieces along every axis
// (some piece would be empty).
Extent PieceExtent(const Extent& whole, int piece, int pieces);

// The file of piece `piece` of the .pvti `path`: "dir/stem_3.vti" for "dir/stem.pvti", and the
// name the .pvti records for it ("stem_3.vti", relative to the .pvti's folder).
std::string PieceFileName(const std::string& path, int piece);
std::string PieceSource(const std::string& path, int piece);

// Makes one piece: the field over exactly `extent`, with the lattice's origin, spacing and
// direction and a float array "density".
using PieceProducer = std::function<vtkSmartPointer<vtkImageData>(const Extent& extent)>;

// The attribute, on the PImageData element of a .pvti and the ImageData element of each of its
// pieces, that records the generation run (32 hexadecimal digits). VTK's readers ignore it.
constexpr const char* PieceRunAttribute = "CloudvisRun";

// Runs `step` here and agrees with the other processes of `controller` on the outcome: a
// collective call, which every process makes at the same point whatever its own work did, so no
// process ever waits for one that has given up. When `step` throws on any process (anything, not
// only a std::exception: "an unknown error" then), every process throws: a failing one its own
// exception, the others an InputError (a UsageError when that was
// the failure) "process R of N failed: MESSAGE" with the message of the lowest-ranked failing
// process R. With no controller or one process, `step` simply runs.
void RunAgreed(vtkMultiProcessController* controller, const std::function<void()>& step);

// Writes `path` (a .pvti) and its `pieces` pieces, each made by `produce`, as one replacement
// (see above). `controller` (may be null: one process) says which pieces this process writes.
// Throws on every process when any piece or the .pvti could not be made or written (RunAgreed);
// the failing process's message names the file and the problem.
// For the interruption tests (tests/faults/InterruptPieces.sh): when the environment variable
// CLOUDVIS_TEST_PAUSE_AFTER_PIECE holds a number of seconds, each process writes
// "cloudvis: paused after piece P" to stderr and sleeps that long after each piece it wrote, so
// that a signal can be sent while the pieces wait as temporaries.
void WriteFieldPieces(const FieldLattice& lattice,
  const std::string& path,
  int pieces,
  const PieceProducer& produce,
  vtkMultiProcessController* controller = nullptr);

// The points of `field` within `extent` (inside the field's extent), as a field of their own.
vtkSmartPointer<vtkImageData> ExtractPiece(vtkImageData* field, const Extent& extent);

// The same for a field in memory (each process holds all of it and writes its own pieces).
void WriteFieldPieces(vtkImageData* field,
  const std::string& path,
  int pieces,
  vtkMultiProcessController* controller = nullptr);

} // namespace cloudvis

#endif
