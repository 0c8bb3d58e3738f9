// What the tests of the field formats share (FieldFormatTests.cxx, OpenVdbTests.cxx): a temporary
// directory, reading a field with its report, and checks that a read fails with a message.
#ifndef cloudvis_FieldTestFiles_h
#define cloudvis_FieldTestFiles_h

#include "Errors.h"
#include "FieldIO.h"

#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>

namespace cloudvis
{
namespace test
{

// A directory of its own under /tmp, removed with everything in it.
class TemporaryDirectory
{
public:
  TemporaryDirectory()
  {
    char pattern[] = "/tmp/cloudvis-field-test-XXXXXX";
    this->Path = ::mkdtemp(pattern);
  }
  ~TemporaryDirectory() { std::filesystem::remove_all(this->Path); }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  std::string File(const std::string& name) const { return this->Path + "/" + name; }

  std::string Path;
};

// The density at point (i, j, k) of the field's extent.
inline double Density(vtkImageData* field, int i, int j, int k)
{
  int ijk[3] = { i, j, k };
  return field->GetPointData()->GetScalars()->GetComponent(field->ComputePointId(ijk), 0);
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

} // namespace test
} // namespace cloudvis

#endif
