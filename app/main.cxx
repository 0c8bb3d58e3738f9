// The cloudvis executable: everything lives in the cloudvisApp library (app/cli/CommandLine.h)
// so tests can drive the same code in-process.
#include "cli/CommandLine.h"

#include <iostream>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  return cloudvis::RunCommandLine(std::vector<std::string>(argv, argv + argc), std::cout, std::cerr);
}
