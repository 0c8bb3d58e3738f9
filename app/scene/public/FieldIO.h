// Reading and writing density fields. Every field format cloudvis reads is one entry of the table
// FieldFormats(): its name for messages, its file extensions (matched without regard to case),
// and its reader, which returns the image as the format holds it. ReadField picks the entry by
// extension and hands the rest of cloudvis one form only: a float point array named "density",
// set as the active scalars. A new format (OpenVDB, NetCDF, raw, NRRD, MetaImage) is a new entry;
// the command line's choice between a scene and a field file, the scene's field.file, the help
// texts and the error messages all follow the table. Every problem becomes one InputError naming
// the file and what is wrong with it. Fields are written as .vti only.
#ifndef cloudvis_FieldIO_h
#define cloudvis_FieldIO_h

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkImageData;

namespace cloudvis
{

struct FieldFormat
{
  std::string Name;                    // for messages and help: "VTK XML image data"
  std::vector<std::string> Extensions; // lower case, with the dot: ".vti"
  // Reads `path` into image data whose point data holds the density (an array named "density",
  // else the active scalars), with the format's own protections against hostile input. Throws
  // InputError naming the file.
  vtkSmartPointer<vtkImageData> (*Read)(const std::string& path);
};

// The field formats cloudvis reads, in the order help texts list them.
const std::vector<FieldFormat>& FieldFormats();

// The format whose extension `path` ends in (any case), or nullptr.
const FieldFormat* FindFieldFormat(const std::string& path);

// Whether `path` names a field file (its extension is one of FieldFormats()) rather than a scene.
bool IsFieldFile(const std::string& path);

// The extensions of FieldFormats() for messages: ".vti, .pvti".
std::string FieldFileExtensions();

// Loads a density field in any format of FieldFormats(). The point array used is the one named
// "density", else the active scalars; it must have one component of type float, unsigned char
// or unsigned short and only finite values. Throws InputError otherwise, and for an extension no
// format has.
vtkSmartPointer<vtkImageData> ReadField(const std::string& path);

// Throws InputError unless `path` can take a field: its directory writable (CheckOutputTarget),
// and its extension .vti (any case).
void CheckFieldOutput(const std::string& path);

// Writes a field as binary VTK XML image data, zlib-compressed, atomically (see AtomicFile.h).
// Throws InputError when the target cannot be written.
void WriteField(vtkImageData* field, const std::string& path);

} // namespace cloudvis

#endif
