// The viewer's live loop, measured as a person meets it: `cloudvis view` on its own Xvfb server
// with real X input (tests/live/LiveSession.h), for one or two cloudvis binaries in one run (the
// build and, with --before, an older one to compare with). For each it prints
//   - idle CPU: the viewer's user + system time over 10 s once the picture has stopped changing,
//     as a percentage of one core;
//   - key latency: from sending a key (Right / Left, which turn the light) to the first change of
//     the 3D view's pixels, the median and the worst of 8 presses, each from a still picture;
//   - a burst: five Right presses sent at once, the time until the viewer has handled the fifth
//     (its fifth "light 0: ..." message on stderr) and, where the binary writes --state-file,
//     until the frame that shows it is complete.
// Nothing here reads the viewer's internals: pixels come from the window, messages from its
// stderr, so a binary from before --state-file can be measured the same way.
//
//   cloudvis-bench-viewer [--before OLD_CLOUDVIS] [VIEW ARGUMENTS...]
//
// With --time-steps FIELD.nc it measures stepping through a field's time steps instead
// (docs/performance.md, "Stepping through time"): `cloudvis view FIELD.nc` is sent `.` once per
// step, each from a still picture after a pause (a person looks at a step before the next), and
// prints the time from the key to the first change of the 3D view's pixels and to the first
// complete frame after it (the state file's shown_at), median and worst. Its peer, in the same
// run, is ParaView: pvbatch (bench/paraview/time_steps.py) opens the file with its own NetCDF
// reader, draws it as a volume, and times GoToNext() and a render per step; the ratio of the
// medians is printed. Run it under Xvfb for pvbatch (xvfb-run -a -s "-screen 0 1280x1024x24").
//
//   cloudvis-bench-viewer --time-steps FIELD.nc [--steps N] [--pause SECONDS] [VIEW ARGUMENTS...]
//
// The view arguments default to the default scene at its default window size (800 x 800) lit by
// the derivative model (--set render.lighting=derivative), so that turning the light changes the
// picture.
#include "LiveSession.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

namespace
{
using cloudvis::live::LiveSession;
using cloudvis::live::Now;

void Pause(double seconds)
{
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

// A 64 x 64 block at the 3D view's center (the window's upper three quarters).
std::array<int, 4> Probe(const LiveSession& session)
{
  const auto size = session.WindowSize();
  const int cx = size[0] / 2, cy = size[1] / 4 + size[1] * 3 / 8;
  return { { cx - 32, cy - 32, cx + 32, cy + 32 } };
}

// Waits until the probed pixels have not changed for `still` seconds (at most `limit`).
void WaitUntilStill(LiveSession& session, double still, double limit = 180.0)
{
  const double end = Now() + limit;
  auto last = session.Pixels(Probe(session));
  double since = Now();
  while (Now() < end && Now() - since < still)
  {
    Pause(0.05);
    const auto now = session.Pixels(Probe(session));
    if (now.Values != last.Values)
    {
      last = now;
      since = Now();
    }
  }
}

int CountLines(const std::string& text, const std::string& needle)
{
  int count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
  {
    ++count;
  }
  return count;
}

struct Figures
{
  double IdleCpuPercent = 0.0;
  double MedianLatency = 0.0;
  double WorstLatency = 0.0;
  double BurstHandled = 0.0;
  double BurstShown = -1.0;
};

Figures Measure(const std::string& cloudvis,
  const std::vector<std::string>& arguments,
  bool stateFile)
{
  Figures figures;
  LiveSession session(cloudvis, arguments, stateFile);
  const double started = Now();
  while (!session.WindowId() && Now() - started < 120.0)
  {
    Pause(0.1);
  }
  Pause(1.0);
  WaitUntilStill(session, 3.0);

  const double cpu = session.CpuSeconds();
  Pause(10.0);
  figures.IdleCpuPercent = (session.CpuSeconds() - cpu) / 10.0 * 100.0;

  std::vector<double> latencies;
  for (int i = 0; i < 8; ++i)
  {
    const auto before = session.Pixels(Probe(session));
    const double sent = Now();
    session.Key(i % 2 == 0 ? "Right" : "Left");
    while (session.Pixels(Probe(session)).Values == before.Values && Now() - sent < 30.0)
    {
      Pause(0.002);
    }
    latencies.push_back(Now() - sent);
    WaitUntilStill(session, 1.5);
  }
  std::sort(latencies.begin(), latencies.end());
  figures.MedianLatency = 0.5 * (latencies[3] + latencies[4]);
  figures.WorstLatency = latencies.back();

  const int messages = CountLines(session.Stderr(), "light 0:");
  const double sent = Now();
  session.Keys({ "Right", "Right", "Right", "Right", "Right" });
  while (CountLines(session.Stderr(), "light 0:") < messages + 5 && Now() - sent < 60.0)
  {
    Pause(0.002);
  }
  figures.BurstHandled = Now() - sent;
  if (stateFile)
  {
    // The fifth key handled after `sent`, and a frame after it.
    const auto burst = [sent](const nlohmann::json& s)
    {
      int count = 0;
      for (const nlohmann::json& key : s["keys"])
      {
        count += key["handled_at"].get<double>() >= sent ? 1 : 0;
      }
      return count == 5 && !s["keys"].back()["shown_at"].is_null();
    };
    const nlohmann::json state = session.WaitFor(burst, "the burst's last frame", 60.0);
    figures.BurstShown = state["keys"].back()["shown_at"].get<double>() - sent;
  }
  return figures;
}

// The median and the largest of `values` (sorted here).
std::pair<double, double> MedianAndWorst(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return { n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]), values.back() };
}

struct StepFigures
{
  std::vector<double> Changed; // key to the first change of the 3D view's pixels, seconds
  std::vector<double> Shown;   // key to the first complete frame after it
};

StepFigures MeasureTimeSteps(const std::string& cloudvis,
  const std::vector<std::string>& arguments,
  int steps,
  double pause)
{
  StepFigures figures;
  LiveSession session(cloudvis, arguments, true);
  session.WaitFor([](const nlohmann::json& s) { return s.value("time_steps", 1) > 1; },
    "a field with time steps",
    180.0);
  WaitUntilStill(session, 3.0);
  for (int step = 1; step <= steps; ++step)
  {
    Pause(pause);
    const auto before = session.Pixels(Probe(session));
    const double sent = Now();
    session.Key("period");
    while (session.Pixels(Probe(session)).Values == before.Values && Now() - sent < 60.0)
    {
      Pause(0.002);
    }
    figures.Changed.push_back(Now() - sent);
    const nlohmann::json state = session.WaitFor(
      [&](const nlohmann::json& s)
      {
        return s.value("time_step", 0) == step && !s["keys"].empty() &&
          s["keys"].back()["handled_at"].get<double>() >= sent &&
          !s["keys"].back()["shown_at"].is_null();
      },
      "time step " + std::to_string(step) + " on screen",
      60.0);
    figures.Shown.push_back(state["keys"].back()["shown_at"].get<double>() - sent);
    std::printf("  step %2d: pixels changed after %4.0f ms, frame complete after %4.0f ms\n",
      step,
      1000.0 * figures.Changed.back(),
      1000.0 * figures.Shown.back());
    std::fflush(stdout);
    WaitUntilStill(session, 1.0);
  }
  return figures;
}

// ParaView's seconds per step (GoToNext and a render) on `field`, from pvbatch; empty when
// pvbatch is not installed or fails (said on stderr).
std::vector<double> ParaViewTimeSteps(const std::string& field, int steps)
{
  const std::string script = std::string(CLOUDVIS_BENCH_SOURCE_DIR) + "/paraview/time_steps.py";
  const std::string command = "PYTHONPATH='" + std::string(CLOUDVIS_PARAVIEW_PYTHONPATH) +
    "' pvbatch --force-offscreen-rendering '" + script + "' '" + field + "' " +
    std::to_string(steps) + " 2>&1";
  std::vector<double> seconds;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe)
  {
    return seconds;
  }
  char line[512];
  std::string output;
  while (std::fgets(line, sizeof(line), pipe))
  {
    output += line;
    double ms = 0.0;
    if (std::sscanf(line, "step %*d: %lf ms", &ms) == 1)
    {
      seconds.push_back(ms / 1000.0);
    }
  }
  if (::pclose(pipe) != 0 || seconds.empty())
  {
    std::cerr << "cloudvis-bench-viewer: ParaView's time steps not measured:\n" << output;
    seconds.clear();
  }
  return seconds;
}

int BenchTimeSteps(const std::string& field,
  int steps,
  double pause,
  std::vector<std::string> arguments)
{
  arguments.insert(arguments.begin(), field);
  std::printf("cloudvis view %s: %d steps with '.', %.1f s apart\n", field.c_str(), steps, pause);
  const StepFigures cloudvis =
    MeasureTimeSteps(cloudvis::support::CloudvisBinary(), arguments, steps, pause);
  const auto changed = MedianAndWorst(cloudvis.Changed);
  const auto shown = MedianAndWorst(cloudvis.Shown);
  std::printf("cloudvis  next step on screen: median %4.0f ms, worst %4.0f ms (pixels changed); "
              "frame complete: median %4.0f ms, worst %4.0f ms\n",
    1000.0 * changed.first,
    1000.0 * changed.second,
    1000.0 * shown.first,
    1000.0 * shown.second);
  const std::vector<double> paraView = ParaViewTimeSteps(field, steps);
  if (!paraView.empty())
  {
    const auto peer = MedianAndWorst(paraView);
    std::printf("ParaView  GoToNext + render: median %4.0f ms, worst %4.0f ms\n",
      1000.0 * peer.first,
      1000.0 * peer.second);
    std::printf(
      "ratio     ParaView / cloudvis (medians, frame complete): %.2fx\n", peer.first / shown.first);
  }
  return 0;
}

void Print(const std::string& name, const Figures& f)
{
  std::printf("%-8s idle CPU %5.1f %% of a core | key latency median %4.0f ms, worst %4.0f ms | "
              "5 keys at once: handled after %4.0f ms",
    name.c_str(),
    f.IdleCpuPercent,
    1000.0 * f.MedianLatency,
    1000.0 * f.WorstLatency,
    1000.0 * f.BurstHandled);
  if (f.BurstShown >= 0.0)
  {
    std::printf(", shown after %4.0f ms", 1000.0 * f.BurstShown);
  }
  std::printf("\n");
}
} // namespace

int main(int argc, char** argv)
{
  std::string before, timeSteps;
  int steps = 19;
  double pause = 2.0;
  std::vector<std::string> arguments;
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument == "--before" && i + 1 < argc)
    {
      before = argv[++i];
    }
    else if (argument == "--time-steps" && i + 1 < argc)
    {
      timeSteps = argv[++i];
    }
    else if (argument == "--steps" && i + 1 < argc)
    {
      steps = std::max(1, std::atoi(argv[++i]));
    }
    else if (argument == "--pause" && i + 1 < argc)
    {
      pause = std::max(0.0, std::atof(argv[++i]));
    }
    else
    {
      arguments.push_back(argument);
    }
  }
  if (!timeSteps.empty())
  {
    try
    {
      return BenchTimeSteps(timeSteps, steps, pause, arguments);
    }
    catch (const std::exception& e)
    {
      std::cerr << "cloudvis-bench-viewer: " << e.what() << "\n";
      return 1;
    }
  }
  if (arguments.empty())
  {
    arguments = { "--set", "render.lighting=derivative" };
  }
  try
  {
    const Figures now = Measure(cloudvis::support::CloudvisBinary(), arguments, true);
    Print("cloudvis", now);
    if (!before.empty())
    {
      const Figures old = Measure(before, arguments, false);
      Print("before", old);
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "cloudvis-bench-viewer: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
