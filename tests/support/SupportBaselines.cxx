// Comparison with committed baseline images (SupportBaselines.h).
#include "SupportBaselines.h"

#include <cstdlib>
#include <sstream>
#include <sys/stat.h>

namespace cloudvis
{
namespace support
{
namespace
{
bool Exists(const std::string& path)
{
  struct stat info;
  return ::stat(path.c_str(), &info) == 0;
}

std::string OutputFolder()
{
  const std::string folder = CLOUDVIS_BASELINE_OUTPUT_DIR;
  ::mkdir(folder.c_str(), 0777);
  return folder;
}
}

BaselineCheck CompareWithBaseline(const Image& image,
  const std::string& name,
  const Tolerance& tolerance)
{
  const std::string baselines = CLOUDVIS_BASELINE_DIR;
  BaselineCheck check;
  if (std::getenv("CLOUDVIS_REGENERATE_BASELINES"))
  {
    const std::string path = baselines + "/" + name + ".png";
    check.Passed = WritePng(image, path);
    check.Message = (check.Passed ? "wrote the baseline " : "could not write the baseline ") + path;
    return check;
  }
  std::ostringstream report;
  std::string closest;
  Difference best;
  for (int alternate = 0;; ++alternate)
  {
    const std::string path =
      baselines + "/" + name + (alternate ? "_" + std::to_string(alternate) : "") + ".png";
    if (!Exists(path))
    {
      break;
    }
    const Image baseline = ReadPng(path);
    const Difference difference = Compare(image, baseline, 3);
    report << "\n  " << path << ": " << difference.RmsLevels() << " levels RMS, "
           << difference.MaxLevels() << " at most";
    if (difference.RmsLevels() <= tolerance.RmsLevels &&
      difference.MaxLevels() <= tolerance.MaxLevels)
    {
      check.Passed = true;
      check.Message = name + " matches " + path + report.str();
      return check;
    }
    if (closest.empty() || difference.Rms < best.Rms)
    {
      closest = path;
      best = difference;
    }
  }
  const std::string output = OutputFolder() + "/" + name + ".png";
  WritePng(image, output);
  if (closest.empty())
  {
    check.Message = "no baseline " + baselines + "/" + name + ".png; the image is " + output +
      ": look at it, and if it is right make it the baseline with tests/baselines/regenerate.sh";
    return check;
  }
  const std::string differenceImage = OutputFolder() + "/" + name + "-difference.png";
  WritePng(DifferenceImage(image, ReadPng(closest)), differenceImage);
  std::ostringstream message;
  message << name << " differs from its baseline beyond " << tolerance.RmsLevels
          << " levels RMS and " << tolerance.MaxLevels << " at most:" << report.str()
          << "\n  the image: " << output << "\n  |image - " << closest
          << "| x 10: " << differenceImage;
  check.Message = message.str();
  return check;
}

} // namespace support
} // namespace cloudvis
