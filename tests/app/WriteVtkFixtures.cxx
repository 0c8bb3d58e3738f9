// cloudvis-write-vtk-fixtures DIR: writes the fields of VtkWrittenFields.h into DIR for the
// command-line tests (the ctest fixture "vtk_written" in CMakeLists.txt): every big-endian
// variant, parallel.pvti (3 pieces beside it), paraview/parallel.pvti (4 big-endian pieces in
// the subdirectory paraview/parallel/, as ParaView lays them out), and the same data under names
// whose extensions are not lower case (FIELD.VTI, Parallel.Pvti).
#include "VtkWrittenFields.h"

#include <exception>
#include <iostream>
#include <sys/stat.h>

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::cerr << "usage: " << argv[0] << " DIRECTORY\n";
    return 2;
  }
  const std::string directory = argv[1];
  try
  {
    using namespace cloudvis::test;
    ::mkdir(directory.c_str(), 0777);
    ::mkdir((directory + "/paraview").c_str(), 0777);
    for (const BigEndianVariant& variant : BigEndianVariants())
    {
      WriteBigEndian(directory, variant);
    }
    WriteParallel(directory, "parallel.pvti", 3, false, false);
    WriteParallel(directory + "/paraview", "parallel.pvti", 4, true, true);
    BigEndianVariant upper = BigEndianVariants().front();
    upper.Name = "FIELD.VTI";
    WriteBigEndian(directory, upper);
    WriteParallel(directory, "Parallel.Pvti", 2, false, false);
  }
  catch (const std::exception& e)
  {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
