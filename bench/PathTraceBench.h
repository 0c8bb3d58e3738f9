// What the commands of cloudvis-bench-pathtrace share (BenchPathTrace.cxx lists them): the
// options, the shipped scenes read by the scene library exactly as `cloudvis render` reads them
// (LoadScene, ProduceField), and the CPU renderers set up from a scene as `cloudvis render
// --cpu-reference` sets them up (SetUpReference): the march's reference and the path tracer. A
// command changes a scene only through its keys (--set assignments, or the Scene's members for
// the lights and the albedo it varies), so every case it measures is a scene the app can render.
#ifndef cloudvis_PathTraceBench_h
#define cloudvis_PathTraceBench_h

#include "CloudLightingParameters.h"
#include "Scene.h"

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkCloudPathTracer;
class vtkCloudReferenceRenderer;
class vtkImageData;

namespace cloudvis
{
namespace bench
{

struct Options
{
  std::string PngDirectory; // --png: where to write the images, for a look
  int Width = 200, Height = 150;
  int Samples = 16;
  int Bounces = PathTraceBounceCap;
  int BrickSize = 8;
  unsigned Seed = 0;
  int FitDimensions = 64;  // fit: the fields' voxels along each axis (0: the scenes' own)
  int FitMaxOctaves = 6;   // fit: octave counts 1..this are fitted
  int FitEvaluations = 60; // fit: the most objective evaluations per octave count
  std::string FitSplit = "stratified"; // fit: which fields are held out
  std::string FitCases = "standard";   // fit: the case set, "standard" or "real" (issue 38)
  std::string ReferenceCache; // --reference-cache: keep the references here, read them again
  std::string MultipleScattering = "octaves"; // fit: "volume" measures the volume, fits nothing
  std::vector<std::string> Scenes;
};

// A scene file read by LoadScene with `assignments` (--set's key=value), named for the tables.
struct BenchScene
{
  std::string Name; // the file's name, unless the command names the variant
  Scene Spec;
};
BenchScene ReadBenchScene(const std::string& path,
  const std::vector<std::string>& assignments = {});

// The scene lit by `lights` alone, with every transfer-function color replaced by the gray
// `albedo` when that is >= 0.
Scene Relit(const Scene& scene, const std::vector<Light>& lights, float albedo = -1.0f);

// One directional white light of intensity 1 from 10 units along `towardLight`.
Light LightToward(glm::vec3 towardLight);

// The scene's field (ProduceField).
vtkSmartPointer<vtkImageData> FieldOf(const Scene& scene);

// The march's reference (vtkCloudReferenceRenderer) of the scene's field through its camera at the
// benchmark's size, with the scene's transfer function and lights and this lighting.
vtkSmartPointer<vtkCloudReferenceRenderer> NewMarch(const Scene& scene,
  vtkImageData* field,
  const LightingParameters& lighting,
  const Options& options);

// The same as a path tracer with the scene's lighting (its phase and ambient), the benchmark's
// paths per pixel, brick size and seed, and this bounce cap.
vtkSmartPointer<vtkCloudPathTracer> NewTracer(const Scene& scene,
  vtkImageData* field,
  int maxBounces,
  const Options& options);

// An image of a renderer: premultiplied RGBA floats and, from the path tracer, the variance of
// each value's mean.
struct Rendered
{
  std::vector<float> RGBA;
  std::vector<float> Variance; // path tracer only
  double Seconds = 0.0;
};
Rendered Run(vtkCloudReferenceRenderer* renderer);

// The mean of r, g, b over the footprint of an image (MeasureImageNoise).
double MeanRadiance(const Rendered& image);

// An image composited over black, clamped to [0, 1], as an 8-bit PNG DIRECTORY/NAME.png (to look
// at; nothing when `directory` is empty).
void WritePng(const std::string& directory,
  const std::string& name,
  const std::vector<float>& rgba,
  int width,
  int height);

// The fields of the `errors`, `bounces` and `defects` tables: the fbm-sphere scene's, and a dense
// one (a sphere of radius 1.8 filling the same box, the same noise, extinction up to 3.2 per unit
// length), both without ambient light.
std::vector<BenchScene> ErrorFields();

[[noreturn]] void Fail(const std::string& message);

// The commands.
int Speed(const Options& options);
int Estimators(const Options& options);
int Errors(const Options& options);
int Bounces(const Options& options);
int Defects(const Options& options);
int Fit(const Options& options);

} // namespace bench
} // namespace cloudvis

#endif
