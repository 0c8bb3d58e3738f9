// The .pvti writer (FieldPieces.h says what it promises). The .pvti is written here as text, not
// by vtkXMLPImageDataWriter: that writer names the files it writes after its own file name, so it
// cannot write through the temporary files of AtomicFile.h, and VTK 9.1's does not record the
// direction. The pieces are written by vtkXMLImageDataWriter (WriteVtkXmlImageFile).
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

#include <cstdio>
#include <fstream>
#include <sstream>
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

void WritePvti(const FieldLattice& lattice, const std::string& path, int pieces)
{
  std::ostringstream xml;
  const std::uint16_t one = 1;
  const bool littleEndian = *reinterpret_cast<const unsigned char*>(&one) == 1;
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PImageData\" version=\"1.0\" byte_order=\""
      << (littleEndian ? "LittleEndian" : "BigEndian") << "\" header_type=\"UInt64\">\n"
      << "  <PImageData WholeExtent=\"" << Joined(lattice.WholeExtent)
      << "\" GhostLevel=\"0\" Origin=\"" << Joined(lattice.Origin) << "\" Spacing=\""
      << Joined(lattice.Spacing) << "\" Direction=\"" << Joined(lattice.Direction) << "\">\n"
      << "    <PPointData Scalars=\"density\">\n"
      << "      <PDataArray type=\"Float32\" Name=\"density\"/>\n"
      << "    </PPointData>\n";
  for (int p = 0; p < pieces; ++p)
  {
    xml << "    <Piece Extent=\"" << Joined(PieceExtent(lattice.WholeExtent, p, pieces))
        << "\" Source=\"" << EscapedAttribute(PieceSource(path, p)) << "\"/>\n";
  }
  xml << "  </PImageData>\n</VTKFile>\n";
  const std::string text = xml.str();
  WriteFileAtomically(path,
    [&](const std::string& temporary)
    {
      std::ofstream out(temporary, std::ios::binary);
      out << text;
      out.close();
      if (!out)
      {
        Fail(path, "cannot write the parallel image data file");
      }
    });
}

// Whether any process reported a failure (`failed` on this one); with no controller, this one's.
bool AnyFailed(vtkMultiProcessController* controller, bool failed)
{
  if (!controller || controller->GetNumberOfProcesses() < 2)
  {
    return failed;
  }
  const int mine = failed ? 1 : 0;
  int all = 0;
  controller->AllReduce(&mine, &all, 1, vtkCommunicator::SUM_OP);
  return all > 0;
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

void WriteFieldPieces(const FieldLattice& lattice,
  const std::string& path,
  int pieces,
  const PieceProducer& produce,
  vtkMultiProcessController* controller)
{
  const int processes = controller ? controller->GetNumberOfProcesses() : 1;
  const int rank = controller ? controller->GetLocalProcessId() : 0;
  std::string problem;
  std::vector<std::string> written; // this process's pieces, removed again if any process fails
  try
  {
    if (pieces < 1)
    {
      Fail(path, "the number of pieces must be at least 1");
    }
    for (int p = 0; p < pieces; ++p)
    {
      PieceExtent(lattice.WholeExtent, p, pieces); // every piece non-empty, before any work
    }
    for (int p = rank; p < pieces; p += processes)
    {
      const std::string piecePath = PieceFileName(path, p);
      const vtkSmartPointer<vtkImageData> piece =
        produce(PieceExtent(lattice.WholeExtent, p, pieces));
      WriteFileAtomically(piecePath,
        [&](const std::string& temporary) { WriteVtkXmlImageFile(piece, temporary, piecePath); });
      written.push_back(piecePath);
    }
  }
  catch (const std::exception& e)
  {
    problem = e.what();
  }
  const auto removeWritten = [&written]
  {
    for (const std::string& piecePath : written)
    {
      std::remove(piecePath.c_str());
    }
  };
  if (AnyFailed(controller, !problem.empty()))
  {
    removeWritten();
    throw InputError(problem.empty()
        ? path + ": another process could not write its pieces (its message says why); the " +
          "parallel image data file was not written"
        : problem);
  }
  if (rank == 0)
  {
    try
    {
      WritePvti(lattice, path, pieces);
    }
    catch (const std::exception& e)
    {
      problem = e.what();
    }
  }
  if (AnyFailed(controller, !problem.empty()))
  {
    removeWritten();
    throw InputError(problem.empty() ? path + ": process 0 could not write the file" : problem);
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
