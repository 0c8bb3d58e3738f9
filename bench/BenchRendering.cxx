// Rendering speed: vtkCloudVolumeMapper against VTK's vtkGPUVolumeRayCastMapper in one run,
// on the same fields, transfer functions, camera and sample distance, 800x600, no shading,
// no jitter:
//   sparse  the article's cloud (unit sphere + 6 octaves of fBm) on 256^3 voxels over [-2, 2]^3
//   dense   6 octaves of fBm filling the whole 256^3 box
// Prints ms/frame of both, the ratio, the RMS difference of the two images (8-bit levels),
// cloudvis's useful-sample fraction (samples where the transfer function gives extinction /
// samples taken), its frame rate while interacting (automatic reduced resolution) and the GPU
// memory it takes; then the lighting models on the sparse field against VTK's shaded mapper; then
// the sparse field stored as float, unsigned short, unsigned char and half floats: the GPU memory
// of each, its frame time and its image against the float field's.
//
// The commands (Usage below; `--help` prints it) run that default run or a part of it alone, for
// narrower measurements (RenderingCompare.cxx), temporal reprojection (RenderingReprojection.cxx),
// and the matrix of issue 12 (RenderingMatrix.cxx): every combination of fields, sizes, images,
// models and light counts in one run, both mappers on the same field (unsigned char by default,
// so that 1024^3 takes 1 GiB), one markdown table row per combination, then the targets
// met or not. Its default is the full matrix; on a software renderer (llvmpipe) without subset
// options, 128^3 and 256^3 at 800x600. What the GPU or the host cannot hold is reported as
// refused with the size needed. Lighting models are named as in scenes (render.lighting), plus
// `nested` for the march with the nested light march and `octaves` for the march with the
// multiple-scattering octaves instead of the volume.
#include "RenderingBench.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace cloudvis::bench;

namespace
{
const char* const UsageText =
  "usage: %s [COMMAND] [--size N] [--frames F] [--width W] [--height H]\n"
  "  --size N        the fields' voxels along each axis (default 256, at least 8)\n"
  "  --frames F      frames timed per measure, after one warm-up frame (default 10)\n"
  "  --width W, --height H   the window (default 800 x 600, each at least 16)\n"
  "commands (none: both fields against VTK's mapper, then the lighting models, then the texel "
  "formats):\n"
  "  lighting        only the lighting models on the sparse field against VTK's shaded mapper\n"
  "  storage         only the sparse field in each texel format\n"
  "  occupancy       only the occupancy recomputation time per brick size\n"
  "  one --model M [--dense] [--brick N]\n"
  "                  one mapper alone, timed, e.g. under valgrind --tool=callgrind with\n"
  "                  LP_NUM_THREADS=0 and VTK_SMP_BACKEND_IN_USE=Sequential for instruction\n"
  "                  counts: cloudvis with the lighting model M (none, derivative, march,\n"
  "                  nested, octaves) and one sun, or VTK's mapper unlit (M = vtk); --dense:\n"
  "                  the dense field instead of the sparse one; --brick: cloudvis's brick size\n"
  "  reprojection [--dump DIR]\n"
  "                  only temporal reprojection: an orbit of interactive frames with and\n"
  "                  without it, timed and compared with still renders; --dump writes each\n"
  "                  frame's images to DIR\n"
  "  matrix [--help | OPTIONS]   issue 12's matrix (its own options: matrix --help)\n";

int Usage(const char* program, std::FILE* out = stderr)
{
  std::fprintf(out, UsageText, program);
  return out == stderr ? 2 : 0;
}

// A positive integer, or -1.
int Positive(const char* text)
{
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  return end != text && *end == '\0' && value > 0 && value < (1L << 30) ? int(value) : -1;
}
}

int main(int argc, char* argv[])
{
  int first = 1;
  std::string command;
  if (argc > 1 && argv[1][0] != '-')
  {
    command = argv[1];
    first = 2;
  }
  if (command == "matrix")
  {
    return Matrix(argc, argv);
  }
  Options options;
  std::string model, dump;
  bool dense = false;
  int brick = 0;
  for (int i = first; i < argc; ++i)
  {
    const std::string option = argv[i];
    if (option == "--help" || option == "-h")
      return Usage(argv[0], stdout);
    if (option == "--dense" && command == "one")
    {
      dense = true;
      continue;
    }
    if (i + 1 >= argc)
      return Usage(argv[0]);
    const char* value = argv[++i];
    if (option == "--size")
      options.Size = Positive(value);
    else if (option == "--frames")
      options.Frames = Positive(value);
    else if (option == "--width")
      options.Width = Positive(value);
    else if (option == "--height")
      options.Height = Positive(value);
    else if (option == "--model" && command == "one")
      model = value;
    else if (option == "--brick" && command == "one")
      brick = Positive(value);
    else if (option == "--dump" && command == "reprojection")
      dump = value;
    else
      return Usage(argv[0]);
  }
  if (options.Size < 8 || options.Frames < 1 || options.Width < 16 || options.Height < 16 ||
    brick < 0)
    return Usage(argv[0]);
  if (command.empty())
    return Default(options, false);
  if (command == "lighting")
    return Default(options, true);
  if (command == "storage")
    return Storage(options);
  if (command == "occupancy")
    return Occupancy(options);
  if (command == "reprojection")
    return Reprojection(options, dump);
  if (command == "one" && (model == "vtk" || MeasuredLighting(model)))
    return OneModel(options, model, dense, brick);
  return Usage(argv[0]);
}
