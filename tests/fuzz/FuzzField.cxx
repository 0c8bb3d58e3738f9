// Fuzz target: field files through the scene's field section and ProduceField: every reader of
// FieldIO.h's table (.vti, .pvti, OpenVDB, NetCDF, NRRD, MetaImage, raw) with cloudvis' checks
// around the libraries (headers, sizes against memory, the file and field.max_voxels, array
// name, type, component count, finiteness, the isolated first read).
// An input is one of:
//   - the bytes of one .vti;
//   - a .pvti and its pieces: the parts of the input between lines "#piece" are written as
//     input.pvti, piece-1.vti, piece-2.vti, ..., so the fuzzer mutates the parallel file and its
//     pieces together (seeds name their pieces that way);
//   - a first line "#field {...}" holding the scene's field section as JSON, whose "file" (a
//     plain name such as "input.nc") names the file the rest of the input is written to: its
//     extension (or "format") chooses the reader, and "array", "time_step", "missing",
//     "max_voxels" and "raw" are fuzzed with it. (A .pvti named so is split at "#piece" lines too.)
// Contract: a field is returned or an InputError names the problem; VTK's own messages must not
// escape to the terminal, and nothing may crash, leak or allocate without bound.
#include "FuzzInput.h"

#include "Errors.h"
#include "FieldIO.h"
#include "FileNames.h"
#include "Scene.h"
#include "SceneField.h"

#include <vtkImageData.h>

#include <cstring>
#include <vector>

namespace
{

// The separator between the parts of a parallel input, and the marker of a field section line.
const char PieceSeparator[] = "\n#piece\n";
const char FieldSectionMarker[] = "#field ";

// Writes the input's files (`name` the file the field is read from) and returns its path.
std::string WriteFieldFiles(const std::uint8_t* data, std::size_t size, const std::string& name)
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
  const bool parallel = cloudvis::LowerCaseExtension(name) == ".pvti" || parts.size() > 1;
  if (!parallel)
  {
    return cloudvis::fuzz::WriteInputFile(name, data, size);
  }
  for (std::size_t p = 1; p < parts.size(); ++p)
  {
    cloudvis::fuzz::WriteInputFile("piece-" + std::to_string(p) + ".vti",
      data + parts[p].first,
      parts[p].second - parts[p].first);
    piecesWritten = int(p);
  }
  return cloudvis::fuzz::WriteInputFile(
    cloudvis::LowerCaseExtension(name) == ".pvti" ? name : "input.pvti", data, parts[0].second);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  // The field section: given by the first line, or {"file": "input.vti"}.
  nlohmann::json field = { { "file", "input.vti" } };
  const std::size_t marker = std::strlen(FieldSectionMarker);
  if (size >= marker && std::memcmp(data, FieldSectionMarker, marker) == 0)
  {
    const auto* newline = static_cast<const std::uint8_t*>(std::memchr(data, '\n', size));
    const std::size_t lineEnd = newline ? std::size_t(newline - data) : size;
    field = nlohmann::json::parse(data + marker, data + lineEnd, nullptr, false);
    // Only a file of this process's input directory is of interest: a procedural field, or a
    // path elsewhere, is not what this target fuzzes.
    if (!field.is_object() || !field.contains("file") || !field["file"].is_string() ||
      field["file"].get<std::string>().empty() ||
      field["file"].get<std::string>().find('/') != std::string::npos ||
      field["file"].get<std::string>()[0] == '.')
    {
      return 0;
    }
    const std::size_t skip = newline ? lineEnd + 1 : size;
    data += skip;
    size -= skip;
  }
  const std::string path = WriteFieldFiles(data, size, field["file"].get<std::string>());
  field["file"] = cloudvis::FileNameOf(path); // input.pvti when the input was split into pieces
  try
  {
    const cloudvis::Scene scene = cloudvis::SceneFromDocument(
      { { "field", field } }, "fuzz input", cloudvis::DirectoryOf(path));
    vtkSmartPointer<vtkImageData> image = cloudvis::ProduceField(scene);
    if (!image || image->GetNumberOfPoints() <= 0)
    {
      __builtin_trap(); // ProduceField promises a non-empty field or an exception
    }
  }
  catch (const cloudvis::InputError&)
  {
  }
  return 0;
}
