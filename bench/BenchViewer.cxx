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
// The view arguments default to the default scene at its default window size (800 x 800) lit by
// the derivative model (--set render.lighting=derivative), so that turning the light changes the
// picture.
#include "LiveSession.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
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
  std::string before;
  std::vector<std::string> arguments;
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument == "--before" && i + 1 < argc)
    {
      before = argv[++i];
    }
    else
    {
      arguments.push_back(argument);
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
