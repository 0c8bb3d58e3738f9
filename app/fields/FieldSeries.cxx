// Numbered file series (FieldSeries.h): listing a pattern's files, their gaps, and reading one
// step through the file's own format.
#include "FieldSeries.h"

#include "Errors.h"
#include "FieldFormatReaders.h" // Fail, Number
#include "FileNames.h"

#include <vtkImageData.h>
#include <vtkMatrix3x3.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <dirent.h>
#include <memory>

namespace cloudvis
{
namespace
{

// The most digits a number in a name may have: a long long holds 18 of them in full.
constexpr std::size_t MaximumDigits = 18;

// How many missing names a refusal lists before "and N more".
constexpr std::size_t ListedGaps = 3;

struct Pattern
{
  std::string Directory; // "" for the current folder, else with its trailing '/'
  std::string Prefix;
  std::string Suffix;
};

Pattern Split(const std::string& pattern)
{
  const std::string name = FileNameOf(pattern);
  const std::string directory = pattern.substr(0, pattern.size() - name.size());
  const std::size_t star = name.find('*');
  if (directory.find('*') != std::string::npos || name.find('*', star + 1) != std::string::npos)
  {
    Fail(pattern,
      "a file series has one * in its file name, where the files' numbers are (run/les_*.nc), "
      "and none in its folder");
  }
  return { directory, name.substr(0, star), name.substr(star + 1) };
}

bool AllDigits(const std::string& text)
{
  return !text.empty() && text.size() <= MaximumDigits &&
    std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The name the progression expects for `number`, written as `like` writes its number (with
// leading zeros to the same width where it has them).
std::string ExpectedName(const Pattern& p, const std::string& like, long long number)
{
  const std::string digits = like.substr(p.Directory.size() + p.Prefix.size(),
    like.size() - p.Directory.size() - p.Prefix.size() - p.Suffix.size());
  std::string text = std::to_string(number);
  if (digits.size() > 1 && digits[0] == '0' && text.size() < digits.size())
  {
    text = std::string(digits.size() - text.size(), '0') + text;
  }
  return p.Prefix + text + p.Suffix;
}

} // namespace

bool IsFileSeriesPattern(const std::string& path)
{
  return FileNameOf(path).find('*') != std::string::npos;
}

std::string SeriesPatternOf(const std::string& first, const std::string& second)
{
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  std::size_t begin = 0;
  while (begin < first.size() && begin < second.size() && first[begin] == second[begin])
  {
    ++begin;
  }
  std::size_t end = 0; // characters shared at the end
  while (end < first.size() - begin && end < second.size() - begin &&
    first[first.size() - 1 - end] == second[second.size() - 1 - end])
  {
    ++end;
  }
  // Widened to the whole run of digits the difference lies in.
  while (begin > 0 && digit(first[begin - 1]))
  {
    --begin;
  }
  while (end > 0 && digit(first[first.size() - end]))
  {
    --end;
  }
  const auto digits = [&](const std::string& name)
  {
    const std::string middle = name.substr(begin, name.size() - begin - end);
    return AllDigits(middle);
  };
  if (first == second || !digits(first) || !digits(second) ||
    first.find('/', begin) != std::string::npos)
  {
    return "";
  }
  return first.substr(0, begin) + "*" + first.substr(first.size() - end);
}

FileSeries FindFileSeries(const std::string& pattern, bool skipGaps)
{
  const Pattern p = Split(pattern);
  const std::string folder = DirectoryOf(pattern);
  std::unique_ptr<DIR, int (*)(DIR*)> listing(::opendir(folder.c_str()), ::closedir);
  if (!listing)
  {
    Fail(pattern, "cannot list the folder " + folder + " of the series: " + std::strerror(errno));
  }
  std::vector<std::pair<long long, std::string>> found;
  while (const dirent* entry = ::readdir(listing.get()))
  {
    const std::string name = entry->d_name;
    if (name.size() <= p.Prefix.size() + p.Suffix.size() ||
      name.compare(0, p.Prefix.size(), p.Prefix) != 0 ||
      name.compare(name.size() - p.Suffix.size(), p.Suffix.size(), p.Suffix) != 0)
    {
      continue;
    }
    const std::string digits =
      name.substr(p.Prefix.size(), name.size() - p.Prefix.size() - p.Suffix.size());
    if (AllDigits(digits))
    {
      found.emplace_back(std::stoll(digits), p.Directory + name);
    }
  }
  if (found.empty())
  {
    Fail(pattern,
      "no file matches: a series is files named " + p.Prefix + "<number>" + p.Suffix + " in " +
        folder);
  }
  std::sort(found.begin(), found.end());
  FileSeries series;
  long long stride = 0;
  for (std::size_t i = 0; i < found.size(); ++i)
  {
    if (i > 0 && found[i].first == found[i - 1].first)
    {
      Fail(pattern,
        FileNameOf(found[i - 1].second) + " and " + FileNameOf(found[i].second) +
          " have the same number: which is the step is unclear; move one away");
    }
    if (i > 0)
    {
      const long long difference = found[i].first - found[i - 1].first;
      stride = stride == 0 ? difference : std::min(stride, difference);
    }
    series.Numbers.push_back(found[i].first);
    series.Files.push_back(found[i].second);
  }
  // The progression is the smallest step between two numbers: 1 for les_0001, les_0002, ...;
  // 3600 for MicroHH's ql.0000000.nc, ql.0003600.nc, ...
  std::size_t gaps = 0;
  for (std::size_t i = 1; i < found.size(); ++i)
  {
    for (long long number = series.Numbers[i - 1] + stride; number < series.Numbers[i];
         number += stride)
    {
      if (++gaps <= ListedGaps)
      {
        series.Missing.push_back(ExpectedName(p, series.Files[i - 1], number));
      }
    }
  }
  if (gaps > 0 && !skipGaps)
  {
    std::string names;
    for (const std::string& name : series.Missing)
    {
      names += (names.empty() ? "" : ", ") + name;
    }
    if (gaps > series.Missing.size())
    {
      names += " and " + std::to_string(gaps - series.Missing.size()) + " more";
    }
    Fail(pattern,
      "the series has " + std::string(gaps == 1 ? "a gap" : "gaps") + ": " + names + " " +
        (gaps == 1 ? "is" : "are") + " missing from the " + std::to_string(found.size()) +
        " files numbered " + std::to_string(series.Numbers.front()) + " to " +
        std::to_string(series.Numbers.back()) + " in steps of " + std::to_string(stride) +
        "; field.series_gaps \"skip\" reads the files there are as consecutive steps");
  }
  if (gaps > series.Missing.size())
  {
    series.Missing.push_back("and " + std::to_string(gaps - series.Missing.size()) + " more");
  }
  return series;
}

vtkSmartPointer<vtkImageData> ReadFileSeriesStep(const std::string& pattern,
  const FieldReadOptions& options,
  FieldReport* report)
{
  const FileSeries series = FindFileSeries(pattern, options.SeriesGaps == SeriesGapRule::Skip);
  const std::size_t steps = series.Files.size();
  const int step = options.TimeStep.value_or(0);
  if (std::size_t(step) >= steps)
  {
    Fail(pattern,
      "field.time_step: " + std::to_string(step) + " is out of range: the series holds " +
        std::to_string(steps) +
        (steps == 1 ? " file (step 0)" : " files (steps 0 .. " + std::to_string(steps - 1) + ")"));
  }
  const std::string& file = series.Files[std::size_t(step)];
  FieldReadOptions one = options;
  one.TimeStep.reset();
  one.SeriesGaps.reset();
  FieldReport read;
  vtkSmartPointer<vtkImageData> field = ReadField(file, one, &read);
  if (read.TimeSteps > 1)
  {
    Fail(file,
      "holds " + std::to_string(read.TimeSteps) + " time steps, and each file of the series " +
        pattern + " must hold one: open the file alone, with field.time_step choosing its step");
  }
  if (report)
  {
    *report = read;
    report->TimeSteps = steps;
    report->StepFile = file;
    std::string text = std::to_string(steps) + (steps == 1 ? " file, " : " files, ") +
      FileNameOf(series.Files.front()) +
      (steps == 1 ? "" : " .. " + FileNameOf(series.Files.back()));
    if (!series.Missing.empty())
    {
      text += "; skipped, missing: ";
      for (std::size_t i = 0; i < series.Missing.size(); ++i)
      {
        text += (i == 0 ? "" : ", ") + series.Missing[i];
      }
    }
    report->Details.erase(std::remove_if(report->Details.begin(),
                            report->Details.end(),
                            [](const auto& line) { return line.first == "time step"; }),
      report->Details.end());
    report->Add("series", text);
    report->Add("time step",
      std::to_string(step) + " of 0 .. " + std::to_string(steps - 1) + ": " + FileNameOf(file) +
        (std::isnan(read.Time)
            ? ""
            : ", t = " + Number(read.Time) + (read.TimeUnits.empty() ? "" : " " + read.TimeUnits)) +
        (options.TimeStep ? "" : " (the first; field.time_step picks another)"));
  }
  return field;
}

std::string TimeStepName(const std::string& file, int step, const FieldReport& read)
{
  return read.StepFile.empty()
    ? file + " (time step " + std::to_string(step) + ")"
    : read.StepFile + " (step " + std::to_string(step) + " of " + file + ")";
}

void CheckSameGrid(const std::string& name, vtkImageData* first, vtkImageData* step)
{
  const auto describe = [](vtkImageData* image)
  {
    const int* d = image->GetDimensions();
    const double* s = image->GetSpacing();
    const double* o = image->GetOrigin();
    return std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]) +
      " points, spacing " + Number(s[0]) + " x " + Number(s[1]) + " x " + Number(s[2]) +
      ", origin (" + Number(o[0]) + ", " + Number(o[1]) + ", " + Number(o[2]) + ")";
  };
  bool same = std::equal(first->GetExtent(), first->GetExtent() + 6, step->GetExtent());
  for (int i = 0; i < 3 && same; ++i)
  {
    // Equal to float precision: the numbers of two files written by one model agree to it.
    const double tolerance = 1e-6 * std::max(1.0, std::fabs(first->GetSpacing()[i]));
    same = std::fabs(first->GetSpacing()[i] - step->GetSpacing()[i]) <= tolerance &&
      std::fabs(first->GetOrigin()[i] - step->GetOrigin()[i]) <=
        1e-6 * std::max(std::fabs(first->GetOrigin()[i]), std::fabs(first->GetSpacing()[i]));
  }
  for (int i = 0; i < 9 && same; ++i)
  {
    same = std::fabs(first->GetDirectionMatrix()->GetData()[i] -
             step->GetDirectionMatrix()->GetData()[i]) <= 1e-6;
  }
  if (!same)
  {
    throw InputError(name + ": its grid (" + describe(step) + ") is not the first step's (" +
      describe(first) + "): every step of a time series needs the same grid");
  }
}

} // namespace cloudvis
