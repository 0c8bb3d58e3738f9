// The known field the format tests write in every format (FieldFormatTests.cxx,
// FieldDataTests.cxx): 5 x 4 x 3 voxels holding Known(i, j, k), as raw floats for teem's `unu` to
// wrap, and as an image for VTK's writers.
#ifndef cloudvis_KnownFieldFiles_h
#define cloudvis_KnownFieldFiles_h

#include "FieldPieces.h"
#include "FieldTestFiles.h"
#include "SupportRun.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMetaImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <string>

namespace cloudvis
{
namespace test
{

// The value every test file holds at voxel (i, j, k), unless a test says otherwise.
inline double Known(int i, int j, int k)
{
  return i + 10.0 * j + 100.0 * k;
}

inline void Truncate(const std::string& path, std::size_t bytes)
{
  support::WriteText(path, support::ReadText(path).substr(0, bytes));
}

// Every voxel of `field` (extent from 0) holds Known(i, j, k) + offset; with `flippedRows`, the
// rows come in the opposite order (j counted from the top), as VTK's raw writer stores them.
inline void ExpectKnownValues(vtkImageData* field, double offset = 0.0, bool flippedRows = false)
{
  int d[3];
  field->GetDimensions(d);
  int wrong = 0;
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
      {
        const int row = flippedRows ? d[1] - 1 - j : j;
        wrong += Density(field, i, j, k) == Known(i, row, k) + offset ? 0 : 1;
      }
  EXPECT_EQ(wrong, 0) << "voxels whose value is not the one the file holds";
}

// 5 x 4 x 3 floats Known(i, j, k) in a raw little-endian file, for unu to wrap.
inline std::string WriteKnownRaw(const support::TemporaryDirectory& dir,
  const std::string& name = "known.raw")
{
  std::string bytes;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 5; ++i)
      {
        const float value = float(Known(i, j, k));
        bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
      }
  support::WriteText(dir.File(name), bytes);
  return dir.File(name);
}

inline std::string Unu(const std::string& raw,
  const std::string& output,
  const std::string& options)
{
  return "teem-unu make -i '" + raw + "' -t float -s 5 4 3 -en little " + options + " -o '" +
    output + "' 2>/dev/null";
}

inline vtkSmartPointer<vtkImageData> KnownImage(int type)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(5, 4, 3);
  image->SetSpacing(0.5, 1.0, 2.0);
  image->SetOrigin(1.0, 2.0, 3.0);
  image->AllocateScalars(type, 1);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 5; ++i)
      {
        int ijk[3] = { i, j, k };
        image->GetPointData()->GetScalars()->SetComponent(
          image->ComputePointId(ijk), 0, Known(i, j, k));
      }
  return image;
}

inline std::string WriteMetaImage(const std::string& path, int type, bool compressed)
{
  vtkNew<vtkMetaImageWriter> writer;
  writer->SetInputData(KnownImage(type));
  writer->SetFileName(path.c_str());
  writer->SetCompression(compressed);
  writer->Write();
  return path;
}

// A field with a rotated lattice, values Known(i, j, k) over an extent that does not start at 0.
inline vtkSmartPointer<vtkImageData> RotatedField()
{
  auto field = vtkSmartPointer<vtkImageData>::New();
  field->SetExtent(2, 12, -3, 5, 1, 7);
  field->SetOrigin(0.5, -1.0, 2.0);
  field->SetSpacing(0.25, 0.5, 1.0);
  field->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1);
  vtkNew<vtkFloatArray> density;
  density->SetName("density");
  density->SetNumberOfTuples(field->GetNumberOfPoints());
  for (int k = 1; k <= 7; ++k)
    for (int j = -3; j <= 5; ++j)
      for (int i = 2; i <= 12; ++i)
      {
        int ijk[3] = { i, j, k };
        density->SetValue(field->ComputePointId(ijk), float(Known(i, j + 3, k)));
      }
  field->GetPointData()->SetScalars(density);
  return field;
}

// The run a .pvti or piece records (CloudvisRun="..."), empty when none.
inline std::string RecordedRun(const std::string& path)
{
  const std::string text = support::ReadText(path).substr(0, 4096);
  const auto at = text.find(std::string(" ") + cloudvis::PieceRunAttribute + "=\"");
  if (at == std::string::npos)
  {
    return "";
  }
  const auto begin = text.find('"', at) + 1;
  return text.substr(begin, text.find('"', begin) - begin);
}

} // namespace test
} // namespace cloudvis

#endif
