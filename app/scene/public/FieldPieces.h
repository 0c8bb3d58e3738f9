// Writing a field as VTK XML parallel image data: a .pvti that lists N pieces, each a .vti holding
// one block of the whole extent, split as VTK's vtkExtentTranslator splits it (adjacent blocks
// share their boundary plane of points, as VTK's own parallel writer makes them). The pieces are
// named as VTK's parallel writer names them, <stem>_<p>.vti beside the .pvti, so ParaView, VTK and
// cloudvis read them back.
//
// A piece is made by a function of its extent, so a procedural field is generated piece by piece
// (one piece in memory at a time) and, under MPI, each process makes and writes only its own
// pieces: process r of R takes the pieces p with p % R == r, and process 0 writes the .pvti once
// every process has written its pieces. Every file is written atomically (AtomicFile.h); the
// .pvti, which is what a reader opens, is replaced last, so it never names a piece that is not
// complete. A failure on any process fails the write on every process (no .pvti is written).
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

// Writes `path` (a .pvti) and its `pieces` pieces, each made by `produce`. `controller` (may be
// null: one process) says which pieces this process writes. Throws InputError on every process
// when any piece or the .pvti could not be made or written; the failing process's message names
// the file and the problem, the others say which process failed.
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
