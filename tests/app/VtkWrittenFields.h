// Fields written by VTK's own writers, the way VTK scripts and ParaView write them, for the tests
// of the formats cloudvis reads (class "valid files refused", docs/reliability.md): big-endian
// .vti in each encoding, and .pvti with its pieces beside it or in a subdirectory (ParaView's
// layout). The field is vtkRTAnalyticSource's float "RTData" on a 10 x 8 x 6 extent: a source
// that produces any sub-extent, so the parallel writer really splits it into pieces.
#ifndef cloudvis_VtkWrittenFields_h
#define cloudvis_VtkWrittenFields_h

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkImageData;

namespace cloudvis
{
namespace test
{

// The whole field the files below hold, as the source produces it in memory.
vtkSmartPointer<vtkImageData> ReferenceField();

// One .vti written by vtkXMLImageDataWriter in big-endian byte order.
struct BigEndianVariant
{
  std::string Name; // file name, also the test's label: "big-endian-zlib.vti"
  bool Appended;    // appended data (ParaView's default) or inline
  bool Raw;         // raw appended bytes (EncodeAppendedDataOff) or base64
  int Compressor;   // vtkXMLWriterBase::NONE, ZLIB, LZ4
  bool Header64;    // header_type UInt64 rather than UInt32
};
const std::vector<BigEndianVariant>& BigEndianVariants();

// Writes `variant` into `directory`; returns the file's path.
std::string WriteBigEndian(const std::string& directory, const BigEndianVariant& variant);

// Writes `name` (a .pvti) into `directory` with vtkXMLPImageDataWriter: `pieces` pieces, raw
// appended zlib data in `bigEndian` byte order or not, the pieces in a subdirectory named after
// the file (ParaView's layout) when `subdirectory`. Returns the .pvti's path.
std::string WriteParallel(const std::string& directory,
  const std::string& name,
  int pieces,
  bool subdirectory,
  bool bigEndian);

} // namespace test
} // namespace cloudvis

#endif
