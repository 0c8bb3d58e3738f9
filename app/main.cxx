// The cloudvis executable: everything lives in the layers of app/ (the command line is
// app/cli/public/CommandLine.h)
// so tests can drive the same code in-process.
#include "CommandLine.h"

#include <iostream>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  return cloudvis::RunCommandLine(std::vector<std::string>(argv, argv + argc), std::cout, std::cerr);
}
