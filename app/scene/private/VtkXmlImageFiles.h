// The readers of the field formats VTK's XML image readers handle: .vti (vtkXMLImageDataReader)
// and .pvti (vtkXMLPImageDataReader: a small XML file listing pieces, each a .vti, assembled into
// one image). VTK's readers trust the file; these wrap them in cloudvis's protections against
// hostile or corrupt input (text checks of the markup and binary headers, a first read in a
// forked child under memory and time limits, the extent checked against the memory available,
// for .pvti every piece checked the same way and the pieces required to cover the whole extent).
// Each returns the image as VTK read it; FieldIO.cxx turns it into a density field.
#ifndef cloudvis_VtkXmlImageFiles_h
#define cloudvis_VtkXmlImageFiles_h

#include <vtkSmartPointer.h>

#include <string>

class vtkImageData;

namespace cloudvis
{

// Reads a VTK XML image data file (.vti), either byte order, any header type or compressor VTK
// writes. Throws InputError naming the file and the problem.
vtkSmartPointer<vtkImageData> ReadVtkXmlImageFile(const std::string& path);

// Reads a VTK XML parallel image data file (.pvti) and the pieces it names (relative to its own
// directory unless absolute). Throws InputError naming the file (and the piece) and the problem.
vtkSmartPointer<vtkImageData> ReadVtkXmlParallelImageFile(const std::string& path);

} // namespace cloudvis

#endif
