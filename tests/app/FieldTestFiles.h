// What the tests of the field formats share (FieldFormatTests.cxx, OpenVdbTests.cxx) beyond
// tests/support (temporary folders, whole files): a field's values, a field compared with the one
// read back, a read's report and its failure message, the formats' own tools, and the cloud's
// pixels in a render.
#ifndef cloudvis_FieldTestFiles_h
#define cloudvis_FieldTestFiles_h

#include "Errors.h"
#include "FieldIO.h"
#include "SupportImages.h"
#include "SupportRun.h"

#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

namespace cloudvis
{
namespace test
{

// The density at point (i, j, k) of the field's extent.
inline double Density(vtkImageData* field, int i, int j, int k)
{
  int ijk[3] = { i, j, k };
  return field->GetPointData()->GetScalars()->GetComponent(field->ComputePointId(ijk), 0);
}

// `actual` is `expected` read back: the same extent, origin, spacing, direction and values (the
// density ReadField makes against the expected scalars), exactly.
inline void ExpectSameField(vtkImageData* expected, vtkImageData* actual)
{
  ASSERT_NE(actual, nullptr);
  int e[6], a[6];
  expected->GetExtent(e);
  actual->GetExtent(a);
  EXPECT_EQ(std::vector<int>(e, e + 6), std::vector<int>(a, a + 6));
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_EQ(actual->GetOrigin()[i], expected->GetOrigin()[i]) << "origin " << i;
    EXPECT_EQ(actual->GetSpacing()[i], expected->GetSpacing()[i]) << "spacing " << i;
  }
  for (int i = 0; i < 9; ++i)
  {
    EXPECT_EQ(
      actual->GetDirectionMatrix()->GetData()[i], expected->GetDirectionMatrix()->GetData()[i])
      << "direction " << i;
  }
  vtkDataArray* x = expected->GetPointData()->GetScalars();
  vtkDataArray* y = actual->GetPointData()->GetArray("density");
  ASSERT_NE(y, nullptr);
  ASSERT_EQ(x->GetNumberOfTuples(), y->GetNumberOfTuples());
  vtkIdType different = 0;
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
  {
    different += x->GetComponent(i, 0) == y->GetComponent(i, 0) ? 0 : 1;
  }
  EXPECT_EQ(different, 0) << "voxels whose value differs";
}

// The message of the InputError `read` throws, or "" (and a test failure) when it throws none.
inline std::string ErrorOf(const std::function<void()>& read)
{
  try
  {
    read();
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

// The text of a report's detail `label` (the first with that label), or "".
inline std::string Detail(const FieldReport& report, const std::string& label)
{
  for (const auto& detail : report.Details)
  {
    if (detail.first == label)
    {
      return detail.second;
    }
  }
  return "";
}

// Runs a shell command (a format's own tool); the test fails when it does not succeed.
inline void RunTool(const std::string& command)
{
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

// Writes `cdl` as the NetCDF file `name` in `dir` with ncgen, of ncgen's kind `kind` (1 classic,
// 2 64-bit offset, 3 netCDF-4, 4 netCDF-4 classic model, 5 CDF-5); returns its path.
inline std::string Ncgen(const support::TemporaryDirectory& dir,
  const std::string& name,
  const std::string& cdl,
  int kind = 1)
{
  support::WriteText(dir.File(name + ".cdl"), cdl);
  RunTool("ncgen -k " + std::to_string(kind) + " -o '" + dir.File(name) + "' '" +
    dir.File(name + ".cdl") + "'");
  return dir.File(name);
}

// Pixels of `image` more than 8 levels from its corner (the background), and those at 255.
struct CloudPixels
{
  size_t Cloud = 0, Clipped = 0;
};
inline CloudPixels CountCloud(const support::Image& image)
{
  CloudPixels count;
  for (int y = 0; y < image.Height; ++y)
  {
    for (int x = 0; x < image.Width; ++x)
    {
      double difference = 0.0;
      bool white = false;
      for (int c = 0; c < 3; ++c)
      {
        difference = std::max(difference, std::abs(image.Level(x, y, c) - image.Level(0, 0, c)));
        white = white || image.Level(x, y, c) >= 254.5;
      }
      count.Cloud += difference > 8.0 ? 1 : 0;
      count.Clipped += white ? 1 : 0;
    }
  }
  return count;
}

} // namespace test
} // namespace cloudvis

#endif
