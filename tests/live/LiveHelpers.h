// Small helpers the live-test files share (LiveTests.cxx, LiveKeysTests.cxx): the viewer's
// arguments for a small, quickly converging cloud in a 480 x 400 window, a pause, and a point of
// the state as window pixels.
#ifndef cloudvis_LiveHelpers_h
#define cloudvis_LiveHelpers_h

#include <nlohmann/json.hpp>

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

} // namespace live
} // namespace cloudvis

#endif
