// Fuzz target: field files through ReadField, cloudvis' checks around VTK's XML readers (header,
// extent and memory, array name, type, component count, finiteness, the isolated first read).
// An input is either the bytes of one .vti, or a .pvti and its pieces: the parts of the input
// between lines "#piece" are written as input.pvti, piece-1.vti, piece-2.vti, ..., so the fuzzer
// mutates the parallel file and its pieces together (seeds name their pieces that way).
// Contract: a field is returned or an InputError names the problem; VTK's own messages must not
// escape to the terminal, and nothing may crash, leak or allocate without bound.
#include "FuzzInput.h"

#include "Errors.h"
#include "FieldIO.h"

#include <vtkImageData.h>

#include <cstring>
#include <vector>

namespace
{

// The separator between the parts of a parallel input.
const char PieceSeparator[] = "\n#piece\n";

// Writes the input's files and returns the path of the one to read.
std::string WriteFieldFiles(const std::uint8_t* data, std::size_t size)
{
  static int piecesWritten = 0; // of the previous input, removed so that none is read stale
  for (; piecesWritten > 0; --piecesWritten)
  {
    cloudvis::fuzz::RemoveInputFile("piece-" + std::to_string(piecesWritten) + ".vti");
  }
  const std::size_t separator = std::strlen(PieceSeparator);
  std::vector<std::pair<std::size_t, std::size_t>> parts; // begin, end
  std::size_t begin = 0;
  for (std::size_t at = 0; at + separator <= size; ++at)
  {
    if (std::memcmp(data + at, PieceSeparator, separator) == 0)
    {
      parts.emplace_back(begin, at);
      begin = at + separator;
      at = begin - 1;
    }
  }
  parts.emplace_back(begin, size);
  if (parts.size() == 1)
  {
    return cloudvis::fuzz::WriteInputFile("input.vti", data, size);
  }
  for (std::size_t p = 1; p < parts.size(); ++p)
  {
    cloudvis::fuzz::WriteInputFile("piece-" + std::to_string(p) + ".vti",
      data + parts[p].first,
      parts[p].second - parts[p].first);
    piecesWritten = int(p);
  }
  return cloudvis::fuzz::WriteInputFile("input.pvti", data, parts[0].second);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string path = WriteFieldFiles(data, size);
  try
  {
    vtkSmartPointer<vtkImageData> field = cloudvis::ReadField(path);
    if (!field || field->GetNumberOfPoints() <= 0)
    {
      __builtin_trap(); // ReadField promises a non-empty field or an exception
    }
  }
  catch (const cloudvis::InputError&)
  {
  }
  return 0;
}
