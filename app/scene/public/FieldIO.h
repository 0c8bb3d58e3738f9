// Reading and writing density fields as VTK XML image data (.vti). Reading accepts what other
// tools commonly write (float, unsigned char or unsigned short, one component) and hands the
// rest of cloudvis one form only: a float point array named "density", set as the active
// scalars. Every problem becomes one InputError naming the file and what is wrong with it.
#ifndef cloudvis_FieldIO_h
#define cloudvis_FieldIO_h

#include <vtkSmartPointer.h>

#include <string>

class vtkImageData;

namespace cloudvis
{

// Loads a density field. The point array used is the one named "density", else the active
// scalars; it must have one component of type float, unsigned char or unsigned short and only
// finite values. Throws InputError otherwise.
vtkSmartPointer<vtkImageData> ReadField(const std::string& path);

// Writes a field as binary VTK XML image data, zlib-compressed, atomically (see AtomicFile.h).
// Throws InputError when the target cannot be written.
void WriteField(vtkImageData* field, const std::string& path);

} // namespace cloudvis

#endif
