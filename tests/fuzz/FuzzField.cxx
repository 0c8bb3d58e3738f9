// Fuzz target: a .vti file's bytes through ReadField, cloudvis' checks around VTK's XML reader
// (header, extent and memory, array name, type, component count, finiteness). Contract: a
// field is returned or an InputError names the problem; VTK's own messages must not escape
// to the terminal, and nothing may crash, leak or allocate without bound.
#include "FuzzInput.h"

#include "Errors.h"
#include "FieldIO.h"

#include <vtkImageData.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string& path = cloudvis::fuzz::WriteInputFile(".vti", data, size);
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
