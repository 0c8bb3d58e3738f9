// A NetCDF file's time axis as a series (issue 34): `info --time-series` prints each step's
// cloud statistics as CSV or JSON, the same numbers `info --time-step N` gives, and `animate
// --time-steps A:B[:STRIDE]` renders a frame per step with the first frame's transfer function
// kept; steps beyond the file are refused before anything is written. The file is a DALES-like
// dump of a cloud growing over three steps, made by ncgen. Part of cloudvis-field-format-tests.
#include "FieldTestFiles.h"

#include "SupportImages.h"
#include "SupportRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

namespace
{

using namespace cloudvis::support;
using namespace cloudvis::test;
using json = nlohmann::json;

// 12 x 12 columns of 50 m, 8 levels of 25 m, three steps 60 s apart: a ball of liquid water up
// to 1 g/kg whose radius grows from 100 to 220 m.
std::string GrowingCloud(const TemporaryDirectory& dir)
{
  const int nx = 12, nz = 8;
  std::ostringstream cdl, ql, xs, zs;
  cdl << "netcdf series {\ndimensions: time = UNLIMITED ; zt = " << nz << " ; yt = " << nx
      << " ; xt = " << nx << " ;\nvariables:\n  double time(time) ; time:units = \"s\" ;\n"
      << "  float zt(zt) ; zt:units = \"m\" ;\n  float yt(yt) ; yt:units = \"m\" ;\n"
      << "  float xt(xt) ; xt:units = \"m\" ;\n  float ql(time, zt, yt, xt) ; ql:units = "
         "\"kg/kg\" ;\ndata:\n  time = 0, 60, 120 ;\n";
  for (int t = 0; t < 3; ++t)
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < nx; ++j)
        for (int i = 0; i < nx; ++i)
        {
          const double r = 100.0 + 60.0 * t;
          const double d = std::hypot(
            50.0 * (i + 0.5) - 300.0, 50.0 * (j + 0.5) - 300.0, 25.0 * (k + 0.5) - 100.0);
          ql << (t + k + j + i ? ", " : "") << std::max(0.0, 1e-3 * (1.0 - d / r));
        }
  for (int k = 0; k < nz; ++k)
  {
    zs << (k ? ", " : "") << 25.0 * (k + 0.5);
  }
  for (int i = 0; i < nx; ++i)
  {
    xs << (i ? ", " : "") << 50.0 * (i + 0.5);
  }
  cdl << "  zt = " << zs.str() << " ;\n  yt = " << xs.str() << " ;\n  xt = " << xs.str()
      << " ;\n  ql = " << ql.str() << " ;\n}\n";
  return Ncgen(dir, "series.nc", cdl.str());
}

std::vector<std::string> Lines(const std::string& text)
{
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
  {
    lines.push_back(line);
  }
  return lines;
}

TEST(TimeSeries, InfoPrintsEachStepsCloudStatistics)
{
  TemporaryDirectory dir;
  const std::string path = GrowingCloud(dir);
  const auto csv = RunCloudvis({ "info", path, "--time-series" });
  ASSERT_EQ(csv.Status, 0) << csv.Err;
  const std::vector<std::string> lines = Lines(csv.Out);
  ASSERT_EQ(lines.size(), 4u) << csv.Out;
  EXPECT_EQ(lines[0],
    "step,time (s),cloud_cover,mean_path (g/m^2),mean_cloudy_path (g/m^2),cloud_base (m),"
    "cloud_top (m)");
  // Each row holds what `info --time-step N --json` says of that step.
  double cover = 0.0;
  for (int step = 0; step < 3; ++step)
  {
    SCOPED_TRACE(step);
    const json one = json::parse(
      RunCloudvis({ "info", path, "--time-step", std::to_string(step), "--json" }).Out)["clouds"];
    std::istringstream row(lines[std::size_t(step) + 1]);
    std::vector<std::string> cells;
    for (std::string cell; std::getline(row, cell, ',');)
    {
      cells.push_back(cell);
    }
    ASSERT_EQ(cells.size(), 7u) << lines[std::size_t(step) + 1];
    EXPECT_EQ(cells[0], std::to_string(step));
    EXPECT_EQ(std::stod(cells[1]), 60.0 * step);
    EXPECT_NEAR(std::stod(cells[2]), one["projected_cloud_fraction"].get<double>(), 1e-8);
    EXPECT_NEAR(std::stod(cells[3]) / one["mean_path"].get<double>(), 1.0, 1e-8);
    EXPECT_NEAR(std::stod(cells[5]), one["cloud_base"].get<double>(), 1e-6);
    EXPECT_GT(std::stod(cells[2]), cover) << "the cloud grows";
    cover = std::stod(cells[2]);
  }
  // A range with a stride, as JSON.
  const auto some =
    RunCloudvis({ "info", path, "--time-series", "--time-steps", "0:2:2", "--json" });
  ASSERT_EQ(some.Status, 0) << some.Err;
  const json series = json::parse(some.Out);
  ASSERT_EQ(series["steps"].size(), 2u);
  EXPECT_EQ(series["steps"][1]["step"], 2);
  EXPECT_EQ(series["steps"][1]["time"], 120.0);
  EXPECT_EQ(series["time_units"], "s");
  EXPECT_EQ(series["path_unit"], "g/m^2");
  EXPECT_EQ(series["units"]["quantity"], "lwc");
}

TEST(TimeSeries, StepsTheFileDoesNotHoldAreRefusedBeforeAnythingIsWritten)
{
  TemporaryDirectory dir;
  const std::string path = GrowingCloud(dir);
  const auto beyond = RunCloudvis({ "info", path, "--time-series", "--time-steps", "1:3" });
  EXPECT_EQ(beyond.Status, 1);
  EXPECT_EQ(beyond.Out, "");
  EXPECT_NE(beyond.Err.find(path +
              ": --time-steps: step 3 is out of range: the file holds 3 "
              "time steps (0 .. 2)"),
    std::string::npos)
    << beyond.Err;
  const auto frames =
    RunCloudvis({ "animate", path, "--time-steps", "0:3", "-o", dir.File("frames"), "-q" });
  EXPECT_EQ(frames.Status, 1);
  EXPECT_NE(frames.Err.find("step 3 is out of range"), std::string::npos) << frames.Err;
  EXPECT_EQ(dir.Files(), (std::vector<std::string>{ "series.nc", "series.nc.cdl" }));
  // Ranges that are no ranges, and options that do not go together.
  for (const char* range : { "2:1", "1", "0:2:0", "-1:2", "a:b", "0:999999999" })
  {
    const auto bad = RunCloudvis({ "info", path, "--time-series", "--time-steps", range });
    EXPECT_EQ(bad.Status, 2) << range;
    EXPECT_NE(bad.Err.find("--time-steps expects A:B or A:B:STRIDE"), std::string::npos) << bad.Err;
  }
  EXPECT_EQ(RunCloudvis({ "info", path, "--time-steps", "0:1" }).Status, 2);
  EXPECT_EQ(RunCloudvis({ "info", path, "--time-series", "--time-step", "1" }).Status, 2);
  EXPECT_EQ(
    RunCloudvis({ "animate", path, "--time-steps", "0:1", "--frames", "2", "-o", dir.File("f") })
      .Status,
    2);
  const std::string scene = dir.Write("generated.json", "{}");
  const auto generated = RunCloudvis({ "info", scene, "--time-series" });
  EXPECT_EQ(generated.Status, 1);
  EXPECT_NE(
    generated.Err.find("--time-series reads the time steps of a field file"), std::string::npos)
    << generated.Err;
  const auto animated =
    RunCloudvis({ "animate", scene, "--time-steps", "0:1", "-o", dir.File("f"), "-q" });
  EXPECT_EQ(animated.Status, 1);
  EXPECT_NE(
    animated.Err.find("--time-steps steps through a field file's time axis"), std::string::npos)
    << animated.Err;
}

TEST(TimeSeries, AnimateRendersAFramePerStepWithTheFirstFramesTransferFunction)
{
  TemporaryDirectory dir;
  const std::string path = GrowingCloud(dir);
  const auto run = RunCloudvis({ "animate",
    path,
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
  EXPECT_NE(
    run.Out.find("transfer function: the default fitted to the field's values"), std::string::npos)
    << run.Out;
  EXPECT_NE(run.Out.find("wrote 2 frames"), std::string::npos) << run.Out;
  const Image first = ReadPng(dir.File("frames/frame_0000.png"));
  const Image last = ReadPng(dir.File("frames/frame_0001.png"));
  const json a = json::parse(first.Text.at("cloudvis.scene"));
  const json b = json::parse(last.Text.at("cloudvis.scene"));
  EXPECT_EQ(a["field"]["time_step"], 0);
  EXPECT_EQ(b["field"]["time_step"], 2);
  EXPECT_EQ(a["transfer_function"], b["transfer_function"])
    << "kept: the sequence must not flicker";
  const CloudPixels small = CountCloud(first), large = CountCloud(last);
  EXPECT_GT(small.Cloud, 50u);
  EXPECT_GT(large.Cloud, 2 * small.Cloud) << "the cloud grows from frame to frame";
}

} // namespace
