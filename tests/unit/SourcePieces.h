// What the density-source tests share to check that a field generated in pieces is the whole:
// the pieces (eight uneven octants, as MPI ranks and streaming request sub-extents) and a bitwise
// comparison.
#ifndef cloudvis_tests_SourcePieces_h
#define cloudvis_tests_SourcePieces_h

#include "vtkCloudDensitySource.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

namespace cloudvis
{
namespace test
{

inline bool SameBits(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// The lattice the octants cut, and where: uneven, so that no piece boundary falls on a row the
// source might treat specially.
constexpr int PieceTestDimensions[3] = { 40, 33, 27 };

// The source's field (set to PieceTestDimensions) assembled from eight octants, each requested
// through the update extent and computed anew. Fails the test if a piece's extent is not the one
// requested; unfilled voxels stay -1.
inline std::vector<float> FieldFromOctants(vtkCloudDensitySource* source)
{
  const int* d = PieceTestDimensions;
  const int cuts[3][3] = { { 0, 17, d[0] - 1 }, { 0, 20, d[1] - 1 }, { 0, 9, d[2] - 1 } };
  std::vector<float> assembled(static_cast<size_t>(d[0]) * d[1] * d[2], -1.0f);
  for (int octant = 0; octant < 8; ++octant)
  {
    int extent[6];
    for (int a = 0; a < 3; ++a)
    {
      const int half = (octant >> a) & 1;
      extent[2 * a] = half ? cuts[a][1] + 1 : cuts[a][0];
      extent[2 * a + 1] = half ? cuts[a][2] : cuts[a][1];
    }
    source->Modified(); // compute the piece anew rather than cut it from the last output
    source->UpdateExtent(extent);
    vtkImageData* piece = source->GetOutput();
    int produced[6];
    piece->GetExtent(produced);
    EXPECT_TRUE(std::equal(extent, extent + 6, produced))
      << "the source must fill exactly the requested extent";
    const float* values =
      vtkFloatArray::SafeDownCast(piece->GetPointData()->GetArray("density"))->GetPointer(0);
    size_t n = 0;
    for (int k = extent[4]; k <= extent[5]; ++k)
      for (int j = extent[2]; j <= extent[3]; ++j)
        for (int i = extent[0]; i <= extent[1]; ++i)
          assembled[(size_t(k) * d[1] + j) * d[0] + i] = values[n++];
  }
  return assembled;
}

} // namespace test
} // namespace cloudvis

#endif
