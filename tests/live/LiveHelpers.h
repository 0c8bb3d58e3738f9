// Small helpers every live-test file shares: the viewer's arguments for a small, quickly
// converging cloud in a 480 x 400 window, a pause, a point of the state as window pixels, the
// messages the viewer showed, and colors of the window's pixels.
#ifndef cloudvis_LiveHelpers_h
#define cloudvis_LiveHelpers_h

#include "LiveSession.h"
#include "SupportImages.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

namespace cloudvis
{
namespace live
{

// The default cloud on 48^3 voxels, converging in 4 frames.
inline std::vector<std::string> Arguments(const std::vector<std::string>& extra = {})
{
  std::vector<std::string> arguments = {
    "--set", "field.dimensions=48", "--set", "render.accumulate=4", "--size", "480x400"
  };
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

inline void Pause(double seconds)
{
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

// A point of the state ([x, y] in window pixels) rounded to a pixel.
inline std::array<int, 2> Pixel(const nlohmann::json& point)
{
  return { { int(std::lround(point[0].get<double>())), int(std::lround(point[1].get<double>())) } };
}

// Clicks the opacity point before the last (an inner one) in the editor and waits until it is
// selected; returns its index. `start`: a state of the window as it opened.
inline size_t SelectInnerOpacityPoint(LiveSession& session, const nlohmann::json& start)
{
  const size_t inner = start["transfer_function"]["opacity"].size() - 2;
  const auto point = Pixel(start["editor"]["opacity_point_pixels"][inner]);
  session.Move(point[0], point[1]);
  session.Press(1);
  session.Release(1);
  session.WaitFor([&](const nlohmann::json& s) { return s["editor"]["selected_point"] == int(inner); },
    "the point to be selected");
  return inner;
}

// The last message shown holds `text` (the "messages" log: the message line wraps its text).
inline bool Said(const nlohmann::json& state, const std::string& text)
{
  return !state["messages"].empty() &&
    state["messages"].back().get<std::string>().find(text) != std::string::npos;
}

// Any message shown so far holds `text`.
inline bool Logged(const nlohmann::json& state, const std::string& text)
{
  for (const nlohmann::json& message : state["messages"])
  {
    if (message.get<std::string>().find(text) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

// The largest difference of two colors' channels, in 8-bit levels.
inline double ColorDistance(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::max({ std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2]) });
}

// The mean color, in 8-bit levels, of the (2 half + 1)^2 pixels of `image` around (x, y).
inline std::array<double, 3> MeanColorAround(const support::Image& image, int x, int y, int half)
{
  std::array<double, 3> mean{ { 0.0, 0.0, 0.0 } };
  const double count = double((2 * half + 1) * (2 * half + 1));
  for (int j = y - half; j <= y + half; ++j)
  {
    for (int i = x - half; i <= x + half; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        mean[size_t(c)] += image.Level(i, j, c) / count;
      }
    }
  }
  return mean;
}

} // namespace live
} // namespace cloudvis

#endif
