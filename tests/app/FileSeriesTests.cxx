// Numbered file series (issue 34, part 3): field.file "les_*.nc" opens les_0001.nc, les_0002.nc,
// ... as one field with a time step per file, ordered by number, as a user's shell and ParaView
// list them. `info --time-series` and `animate --time-steps` step through it as through a file's
// own time axis; a gap, a file whose grid differs, a file of several steps and a half-written last
// file are refused naming the file (a gap is skipped when field.series_gaps says so). The files
// are DALES-like dumps of one step each, made by ncgen. Part of cloudvis-field-format-tests.
#include "FieldTestFiles.h"

#include "SupportImages.h"
#include "SupportRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>

namespace
{

using namespace cloudvis::support;
using namespace cloudvis::test;
using json = nlohmann::json;

// One step of a growing cloud as `name`: 12 x 12 columns of `dx` m, 8 levels of 25 m, a ball of
// liquid water up to 1 g/kg of radius `radius` m at time `time` s (`steps` records of it).
std::string CloudStep(const TemporaryDirectory& dir,
  const std::string& name,
  double time,
  double radius,
  double dx = 50.0,
  int steps = 1)
{
  const int nx = 12, nz = 8;
  std::ostringstream cdl, ql, xs, zs, ts;
  for (int t = 0; t < steps; ++t)
  {
    ts << (t ? ", " : "") << time + t;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < nx; ++j)
        for (int i = 0; i < nx; ++i)
        {
          const double d = std::hypot(
            dx * (i + 0.5) - 6.0 * dx, dx * (j + 0.5) - 6.0 * dx, 25.0 * (k + 0.5) - 100.0);
          ql << (t + k + j + i ? ", " : "") << std::max(0.0, 1e-3 * (1.0 - d / radius));
        }
  }
  for (int k = 0; k < nz; ++k)
  {
    zs << (k ? ", " : "") << 25.0 * (k + 0.5);
  }
  for (int i = 0; i < nx; ++i)
  {
    xs << (i ? ", " : "") << dx * (i + 0.5);
  }
  cdl << "netcdf step {\ndimensions: time = UNLIMITED ; zt = " << nz << " ; yt = " << nx
      << " ; xt = " << nx << " ;\nvariables:\n  double time(time) ; time:units = \"s\" ;\n"
      << "  float zt(zt) ; zt:units = \"m\" ;\n  float yt(yt) ; yt:units = \"m\" ;\n"
      << "  float xt(xt) ; xt:units = \"m\" ;\n  float ql(time, zt, yt, xt) ; ql:units = "
         "\"kg/kg\" ;\ndata:\n  time = "
      << ts.str() << " ;\n  zt = " << zs.str() << " ;\n  yt = " << xs.str()
      << " ;\n  xt = " << xs.str() << " ;\n  ql = " << ql.str() << " ;\n}\n";
  const std::string path = Ncgen(dir, name, cdl.str());
  std::filesystem::remove(path + ".cdl");
  return path;
}

// les_0001.nc .. les_000N.nc at 60, 120, ... s, the cloud growing by 60 m a step.
std::string Series(const TemporaryDirectory& dir, int files)
{
  for (int n = 1; n <= files; ++n)
  {
    CloudStep(dir, "les_000" + std::to_string(n) + ".nc", 60.0 * n, 100.0 + 60.0 * (n - 1));
  }
  return dir.File("les_*.nc");
}

json InfoJson(const std::vector<std::string>& arguments)
{
  std::vector<std::string> command = { "info" };
  command.insert(command.end(), arguments.begin(), arguments.end());
  command.push_back("--json");
  const auto run = RunCloudvis(command);
  EXPECT_EQ(run.Status, 0) << run.Err;
  return run.Status == 0 ? json::parse(run.Out) : json();
}

TEST(FileSeries, IsOneFieldWithAStepPerFileInTheOrderOfTheirNumbers)
{
  TemporaryDirectory dir;
  const std::string pattern = Series(dir, 3);
  const json series = InfoJson({ pattern, "--time-series" });
  ASSERT_EQ(series["steps"].size(), 3u) << series.dump();
  EXPECT_EQ(series["time_units"], "s");
  for (int step = 0; step < 3; ++step)
  {
    // Each step is its file, read alone.
    const json alone = InfoJson({ dir.File("les_000" + std::to_string(step + 1) + ".nc") });
    const json& row = series["steps"][std::size_t(step)];
    EXPECT_EQ(row["step"], step);
    EXPECT_EQ(row["time"], 60.0 * (step + 1));
    EXPECT_EQ(row["mean_path"], alone["clouds"]["mean_path"]) << "step " << step;
    EXPECT_EQ(row["cloud_cover"], alone["clouds"]["projected_cloud_fraction"]) << "step " << step;
  }
  EXPECT_LT(series["steps"][0]["cloud_cover"], series["steps"][2]["cloud_cover"]);
  // `info` of one step says which file it is.
  const auto text = RunCloudvis({ "info", pattern, "--time-step", "1" });
  ASSERT_EQ(text.Status, 0) << text.Err;
  EXPECT_NE(text.Out.find("series       3 files, les_0001.nc .. les_0003.nc"), std::string::npos)
    << text.Out;
  EXPECT_NE(text.Out.find("time step    1 of 0 .. 2: les_0002.nc, t = 120 s"), std::string::npos)
    << text.Out;

  // The pattern left unquoted, the shell hands over the files: the usage error says to quote it.
  const auto expanded = RunCloudvis(
    { "info", dir.File("les_0001.nc"), dir.File("les_0002.nc"), dir.File("les_0003.nc") });
  EXPECT_EQ(expanded.Status, 2);
  EXPECT_NE(expanded.Err.find("to open numbered files as one time series, quote their pattern so "
                              "that the shell leaves it to cloudvis: '" +
              pattern + "'"),
    std::string::npos)
    << expanded.Err;

  // Numbers without leading zeros are ordered as numbers, not as text: 9 before 10.
  TemporaryDirectory unpadded;
  CloudStep(unpadded, "run10.nc", 600.0, 200.0);
  CloudStep(unpadded, "run9.nc", 540.0, 100.0);
  const json ordered = InfoJson({ unpadded.File("run*.nc"), "--time-series" });
  ASSERT_EQ(ordered["steps"].size(), 2u);
  EXPECT_EQ(ordered["steps"][0]["time"], 540.0);
  EXPECT_EQ(ordered["steps"][1]["time"], 600.0);
}

TEST(FileSeries, AnimateRendersAFramePerFile)
{
  TemporaryDirectory dir;
  const std::string pattern = Series(dir, 3);
  const auto run = RunCloudvis({ "animate",
    pattern,
    "--time-steps",
    "0:2:2",
    "-o",
    dir.File("frames"),
    "--size",
    "96x72",
    "--set",
    "render.accumulate=1",
    "-q" });
  ASSERT_EQ(run.Status, 0) << run.Err;
  EXPECT_NE(run.Out.find("wrote 2 frames"), std::string::npos) << run.Out;
  const Image first = ReadPng(dir.File("frames/frame_0000.png"));
  const Image last = ReadPng(dir.File("frames/frame_0001.png"));
  const json scene = json::parse(last.Text.at("cloudvis.scene"));
  EXPECT_EQ(scene["field"]["file"], pattern) << "the frame's scene reads the series again";
  EXPECT_EQ(scene["field"]["time_step"], 2);
  EXPECT_GT(CountCloud(first).Cloud, 50u);
  EXPECT_GT(CountCloud(last).Cloud, 2 * CountCloud(first).Cloud) << "the cloud grows";
}

TEST(FileSeries, AGapIsRefusedNamingTheMissingFileUnlessSkipped)
{
  TemporaryDirectory dir;
  const std::string pattern = Series(dir, 4);
  std::filesystem::remove(dir.File("les_0002.nc"));
  const auto refused = RunCloudvis({ "info", pattern });
  EXPECT_EQ(refused.Status, 1);
  EXPECT_EQ(refused.Out, "");
  EXPECT_NE(refused.Err.find(pattern +
              ": the series has a gap: les_0002.nc is missing from the 3 files numbered 1 to 4 "
              "in steps of 1; field.series_gaps \"skip\""),
    std::string::npos)
    << refused.Err;
  const json skipped = InfoJson({ pattern, "--time-series", "--set", "field.series_gaps=skip" });
  ASSERT_EQ(skipped["steps"].size(), 3u);
  EXPECT_EQ(skipped["steps"][1]["time"], 180.0) << "les_0003.nc follows les_0001.nc";
  const auto said = RunCloudvis({ "info", pattern, "--set", "field.series_gaps=skip" });
  EXPECT_NE(said.Out.find("3 files, les_0001.nc .. les_0004.nc; skipped, missing: les_0002.nc"),
    std::string::npos)
    << said.Out;
  // The key is the series': on one file it is refused.
  const auto single =
    RunCloudvis({ "info", dir.File("les_0001.nc"), "--set", "field.series_gaps=skip" });
  EXPECT_EQ(single.Status, 1);
  EXPECT_NE(single.Err.find("field.series_gaps: applies to a file series only"), std::string::npos)
    << single.Err;
}

TEST(FileSeries, AFileThatDoesNotFitTheSeriesIsRefusedNamingItAndItsStep)
{
  TemporaryDirectory dir;
  const std::string pattern = Series(dir, 2);
  CloudStep(dir, "les_0003.nc", 180.0, 220.0, 40.0);
  const auto grid = RunCloudvis({ "info", pattern, "--time-series" });
  EXPECT_EQ(grid.Status, 1);
  EXPECT_EQ(grid.Out, "");
  EXPECT_NE(grid.Err.find(dir.File("les_0003.nc") + " (step 2 of " + pattern +
              "): its grid (12 x 12 x 8 points, spacing 40 x 40 x 25"),
    std::string::npos)
    << grid.Err;
  const auto frames = RunCloudvis({ "animate",
    pattern,
    "--time-steps",
    "0:2",
    "-o",
    dir.File("frames"),
    "--size",
    "64x48",
    "-q" });
  EXPECT_EQ(frames.Status, 1);
  EXPECT_NE(frames.Err.find("les_0003.nc (step 2 of"), std::string::npos) << frames.Err;

  CloudStep(dir, "les_0003.nc", 180.0, 220.0, 50.0, 2);
  const auto steps = RunCloudvis({ "info", pattern, "--time-step", "2" });
  EXPECT_EQ(steps.Status, 1);
  EXPECT_NE(steps.Err.find(dir.File("les_0003.nc") +
              ": holds 2 time steps, and each file of the series " + pattern + " must hold one"),
    std::string::npos)
    << steps.Err;

  const auto beyond = RunCloudvis({ "info", pattern, "--time-step", "3" });
  EXPECT_EQ(beyond.Status, 1);
  EXPECT_NE(beyond.Err.find(pattern +
              ": field.time_step: 3 is out of range: the series holds 3 files (steps 0 .. 2)"),
    std::string::npos)
    << beyond.Err;
  const auto none = RunCloudvis({ "info", dir.File("nothing_*.nc") });
  EXPECT_EQ(none.Status, 1);
  EXPECT_NE(
    none.Err.find("no file matches: a series is files named nothing_<number>.nc in " + dir.Path),
    std::string::npos)
    << none.Err;
  const auto twoStars = RunCloudvis({ "info", dir.File("les_*_*.nc") });
  EXPECT_EQ(twoStars.Status, 1);
  EXPECT_NE(twoStars.Err.find("a file series has one * in its file name"), std::string::npos)
    << twoStars.Err;
}

TEST(FileSeries, AHalfWrittenLastFileIsRefusedAndTheStepsBeforeItStillRead)
{
  TemporaryDirectory dir;
  const std::string pattern = Series(dir, 3);
  // A model writing les_0004.nc when it was read: the first half of a whole file.
  const std::string whole = dir.File("les_0003.nc");
  const auto bytes = std::filesystem::file_size(whole);
  std::filesystem::copy_file(whole, dir.File("les_0004.nc"));
  std::filesystem::resize_file(dir.File("les_0004.nc"), bytes / 2);
  const auto last = RunCloudvis({ "info", pattern, "--time-step", "3" });
  EXPECT_EQ(last.Status, 1) << "refused, not a crash";
  EXPECT_EQ(last.Out, "");
  EXPECT_NE(last.Err.find(dir.File("les_0004.nc") + ": "), std::string::npos) << last.Err;
  const json before = InfoJson({ pattern, "--time-series", "--time-steps", "0:2" });
  EXPECT_EQ(before["steps"].size(), 3u);
}

} // namespace
