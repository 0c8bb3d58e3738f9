// The noise target's options and messages, shared by render and compare (CommandSupport.h): the
// two commands name their options differently (--spp and --spp-time, --reference and
// --reference-time), so every message is built from NoiseTargetOptions rather than written twice.
// A target not reached is an InputError (status 1), as a scene the GPU cannot draw is: the
// command line was well formed, the run could not deliver what it asked for.
#include "CommandSupport.h"

#include "Errors.h"

#include <cstdio>

namespace cloudvis
{
namespace
{

std::string Format(const char* format, double value)
{
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string Seconds(double seconds)
{
  return Format("%.1f s", seconds);
}

// Why the accumulation stopped short of the target.
std::string Shortfall(const NoiseTargetOptions& names, const NoiseReport& report)
{
  const std::string limit = "the --" + names.TimeOption + " limit of " +
    Format("%g", report.Target.TimeLimit) + " s";
  switch (report.Stop)
  {
    case NoiseStop::TimeLimit:
      return "stopped at " + limit;
    case NoiseStop::Projection:
      return "stopped early: the time it needs is more than " +
        Format("%g", NoiseProjectionMargin) + " times " + limit;
    case NoiseStop::FrameLimit:
      return "stopped at the most the path tracer accumulates, " +
        std::to_string(MaximumNoiseTargetFrames * NoiseTargetSamplesPerFrame) +
        " paths per pixel";
    case NoiseStop::Reached:
      break;
  }
  return "";
}

} // namespace

const OptionSpec AcceptNoiseOption{ "accept-noise",
  0,
  "",
  "with a noise target (P%): when the time limit ends the accumulation first, write the image "
  "with the noise it reached (said in what is printed) instead of failing with status 1" };

OptionSpec NoiseTimeOption(const NoiseTargetOptions& names)
{
  return { names.TimeOption,
    0,
    "SECONDS",
    "with a noise target (" + names.Example + "): give up after this long (default " +
      Format("%g", DefaultNoiseTimeLimit) +
      " s); a target not reached by then fails with status 1, naming the noise reached, unless "
      "--accept-noise" };
}

std::optional<double> ParseNoisePercent(const NoiseTargetOptions& names, const std::string& value)
{
  if (value.empty() || value.back() != '%')
  {
    return std::nullopt;
  }
  double percent = 0.0;
  if (!ParseNumber(value.substr(0, value.size() - 1), percent) || !(percent > 0.0) ||
    percent > 100.0)
  {
    throw UsageError(names.Command + ": --" + names.TargetOption +
      ": a noise target is a percentage above 0 and at most 100 (the relative standard error " +
      "over the cloud, e.g. " + names.Example + "), got \"" + value + "\"");
  }
  return percent / 100.0;
}

std::optional<NoiseTarget> ReadNoiseTarget(const NoiseTargetOptions& names,
  const Arguments& arguments,
  std::optional<double> relativeStandardError,
  const std::string& given)
{
  if (!relativeStandardError)
  {
    for (const std::string& option : { names.TimeOption, AcceptNoiseOption.Long })
    {
      if (arguments.Has(option))
      {
        throw UsageError(names.Command + ": --" + option + " applies to a noise target (" +
          names.Example + ")" +
          (given.empty() ? "; none was given" : ", not to --" + names.TargetOption + " " + given));
      }
    }
    return std::nullopt;
  }
  NoiseTarget target;
  target.RelativeStandardError = *relativeStandardError;
  target.AcceptNoise = arguments.Has(AcceptNoiseOption.Long);
  if (arguments.Has(names.TimeOption))
  {
    const std::string text = arguments.Value(names.TimeOption);
    if (!ParseNumber(text, target.TimeLimit) || !(target.TimeLimit > 0.0))
    {
      throw UsageError(names.Command + ": --" + names.TimeOption +
        " expects a number of seconds above 0, got \"" + text + "\"");
    }
  }
  return target;
}

std::string DescribeNoiseReport(const NoiseTargetOptions& names, const NoiseReport& report)
{
  std::string text = std::to_string(report.Samples) + " paths per pixel, relative standard " +
    "error " + Format("%.4f", report.Noise.RelativeStandardError) + " (target " +
    Format("%g", report.Target.RelativeStandardError) + "), " + Seconds(report.Seconds);
  if (!report.Reached())
  {
    text += "; target not reached, " + Shortfall(names, report);
  }
  return text;
}

void CheckNoiseReport(
  const NoiseTargetOptions& names, const std::string& given, const NoiseReport& report)
{
  if (report.Reached() || report.Target.AcceptNoise)
  {
    return;
  }
  throw InputError(names.Command + ": --" + names.TargetOption + " " + given +
    ": noise target not reached (" + Shortfall(names, report) + "): relative standard error " +
    Format("%.4f", report.Noise.RelativeStandardError) + " after " +
    std::to_string(report.Samples) + " paths per pixel in " + Seconds(report.Seconds) +
    "; the target needs about " + std::to_string(report.ProjectedSamples) +
    " paths per pixel, about " + Seconds(report.ProjectedSeconds) +
    " at this rate; allow more time with --" + names.TimeOption +
    ", loosen the target or shrink --size, or keep this image with --" + AcceptNoiseOption.Long);
}

} // namespace cloudvis
