// main() for the fuzz targets in an ordinary build: feeds each file named on the command line
// (or every file of a named directory) to LLVMFuzzerTestOneInput, the same entry function the
// libFuzzer binaries run. ctest runs it on the seed corpus and on tests/fuzz/regressions/, so
// every crash a fuzzer once found stays fixed in the normal and the sanitized builds.
#include "FuzzInput.h"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

namespace
{

std::vector<std::filesystem::path> InputsOf(const std::filesystem::path& argument)
{
  std::vector<std::filesystem::path> inputs;
  if (std::filesystem::is_directory(argument))
  {
    for (const auto& entry : std::filesystem::directory_iterator(argument))
    {
      if (entry.is_regular_file() && entry.path().filename().string()[0] != '.')
      {
        inputs.push_back(entry.path());
      }
    }
    std::sort(inputs.begin(), inputs.end());
  }
  else
  {
    inputs.push_back(argument);
  }
  return inputs;
}

} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: " << argv[0] << " FILE|DIRECTORY...\n";
    return 2;
  }
  int count = 0;
  for (int a = 1; a < argc; ++a)
  {
    for (const std::filesystem::path& input : InputsOf(argv[a]))
    {
      std::ifstream in(input, std::ios::binary);
      if (!in)
      {
        std::cerr << input.string() << ": cannot read\n";
        return 1;
      }
      const std::vector<char> bytes{ std::istreambuf_iterator<char>(in),
        std::istreambuf_iterator<char>() };
      try
      {
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      }
      catch (const std::exception& e)
      {
        std::cerr << input.string() << ": unexpected exception: " << e.what() << "\n";
        return 1;
      }
      ++count;
    }
  }
  if (count == 0)
  {
    std::cerr << "no inputs found\n";
    return 1;
  }
  std::cout << count << " inputs replayed without a failure\n";
  return 0;
}
