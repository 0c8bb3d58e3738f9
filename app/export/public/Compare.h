// `cloudvis compare`: the lighting models side by side on one field. One window holds one
// viewport per model, render.size each, left to right in the order given, plus an optional
// difference panel; every viewport shares one vtkCamera (the one ApplyCamera sets up) and the
// mappers start from the same jitter frame, so the panels differ only by their lighting. A panel
// is a model, and for the march also how it adds multiple scattering (ComparedLighting), so the
// volume and the octaves can stand side by side. Each panel has its own vtkVolume and
// vtkCloudVolumeMapper (ConfigureMapper, ConfigureLighting with the panel's lighting) and a label
// with the panel's name and its measured frame time.
#ifndef cloudvis_Compare_h
#define cloudvis_Compare_h

#include "CloudImageComparison.h"
#include "NoiseTarget.h"
#include "OffscreenRender.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cloudvis
{

// One panel's lighting: a model and, for the march, how it adds multiple scattering (none given:
// the scene's render.march.multiple_scattering).
struct ComparedLighting
{
  LightingModel Model = LightingModel::None;
  std::optional<MultipleScatteringModel> MultipleScattering;
};
bool operator==(const ComparedLighting& a, const ComparedLighting& b);

// The lighting a panel renders with: the scene's, with the panel's model and, where the panel
// gives one, its multiple scattering.
LightingParameters PanelLighting(const LightingParameters& scene, const ComparedLighting& panel);

// A panel's name on its label and in what compare prints: the model's name, and for the march
// "march:NAME" with the multiple scattering it renders with (the scene's where the panel gives
// none), so that a picture says which it shows.
std::string PanelName(const LightingParameters& scene, const ComparedLighting& panel);

struct ComparisonResult
{
  RenderedImage Image;
  std::vector<std::string> Names;   // per panel, in the order given (then the reference): PanelName
  std::vector<double> Milliseconds; // per model, in the order given: mean full-window frame time
  int AccumulatedFrames = 0;        // frames averaged into each panel
  double MaxDifference = 0.0;       // with a difference panel: max over pixels of |A - B|
  // With a reference: each model's error against it (in the order given), and its own noise.
  std::vector<ImageError> Errors;
  ImageNoise ReferenceNoise;
  int ReferenceSamples = 0; // paths per pixel in the reference panel
  std::optional<NoiseReport> ReferenceTarget; // with a noise target: how the reference met it
};

// The reference panel's paths: SamplesPerPixel, or with Target as many as reach that noise.
struct ReferencePaths
{
  int SamplesPerPixel = 256;
  std::optional<NoiseTarget> Target;
};

// The widest window compare opens, in pixels (render.size's own limit per axis).
constexpr int MaximumComparisonWidth = 16384;

// Renders `field` once per model into one off-screen window of (models + 1 if `difference`) x
// render.size[0] by render.size[1] pixels and captures it. Per model, first `timingFrames`
// frames are marched in full with the other panels' volumes hidden and timed up to the GPU's
// completion (after one untimed frame of all panels that compiles the shaders and uploads the
// textures); the mean labels the panel. Then all panels render render.accumulate jittered frames
// together (one without jitter), like `render`.
//
// `difference` (indices into `models`) adds a last panel: the per-pixel max over r, g, b of
// |A - B| between the two models' accumulated float radiances (vtkCloudVolumeMapper::ReadImage),
// scaled so the largest difference is the top of a black-purple-orange-yellow ramp, labelled
// "|A - B|" with that largest difference. The scene's render.lighting is not used; its
// render.march.multiple_scattering is, by a march panel that gives none.
//
// `reference` adds a ground-truth panel after the models' (before the difference): the GPU path
// tracer with that many paths per pixel, or accumulated to its noise target alongside the models'
// frames and on alone after them (AccumulateToNoiseTarget; ReferenceTarget says how it went; the
// models' errors are measured against the image it reached either way), a difference index of
// models.size() being that panel. It is labelled with its noise (MeasureImageNoise); each model's
// panel is labelled with its error against it (CompareWithReference: relative RMSE, bias as the
// ratio of means, max error relative to the reference's peak), which Errors and ReferenceNoise
// return.
// Throws InputError naming `input` for a window wider than MaximumComparisonWidth, a mapper
// error, or nothing drawn.
ComparisonResult RenderComparison(const Scene& scene,
  vtkImageData* field,
  const std::string& input,
  const std::vector<ComparedLighting>& models,
  const std::optional<std::pair<size_t, size_t>>& difference,
  int timingFrames = 3,
  const std::optional<ReferencePaths>& reference = std::nullopt);

} // namespace cloudvis

#endif
