// `cloudvis-bench-pathtrace fit`: the march's multiple-scattering octaves (N, a, b, c) and the
// derivative model's distance h fitted to the path tracer on a fixed case set with held-out cases
// (docs/lighting.md, "Fitting the march to the path tracer"), with the errors before and after,
// per case and per set, with the light volumes and with the nested light march.
//
// The fit renders each case many times with only the octaves changed, so it prepares each case's
// march once (PreparedMarch: the uniforms and light volumes the reference renderer would compute)
// and marches its pixels with the reference march's entry points, after checking that the image
// is the renderer's own.
#include "CloudImageComparison.h"
#include "CloudLightVolumes.h"
#include "CloudMarchUniforms.h"
#include "CloudReferenceMarch.h"
#include "CloudScatteringVolume.h"
#include "CloudTransferTable.h"
#include "PathTraceBench.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>
#include <vtkTimerLog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cloudvis
{
namespace bench
{

namespace
{

// The fit of the march's multiple-scattering octaves (N, a, b, c) and of the derivative model's
// distance h to the path tracer (docs/lighting.md, "Fitting the march to the path tracer").
//
// The case set is fixed here: seven fields, each lit by one white directional light from four
// directions, with a uniform gray albedo of 1, 0.9 or 0.7 over the field's own transfer-function
// opacity, no ambient. Fields: fbm-sphere, perlin-falloff and sphere (shipped scenes; the last
// optically thin), dense (the `errors` table's), fbm-box (fBm on a box filling most of the
// volume), thick-sphere (sphere.json 8 times denser) and sparse (the fbm noise on a sphere of
// radius 0.5: wisps).
//
// The split (--split): a case is held out when its field is one of the split's held-out fields,
// or when it is lit from above (a direction no training case has) at albedo 0.9 (an albedo no
// training case has). Training cases are lit from the side, behind and in front at albedo 1 and
// 0.7; held-out fields from the side, behind and above at albedo 1 and 0.9.
//   "first": held-out fields perlin-falloff, sphere, sparse. Chosen before any fit; it turned out
//     to hold out every optically thin field, so the training set had none (docs/lighting.md).
//   "stratified" (the default): held-out fields fbm-box, perlin-falloff, sparse; the training
//     set has a field of each kind the held-out set has (thin: sphere; fbm noise: fbm-sphere;
//     dense: dense). Chosen after the "first" split's fit, before its own.
// Each field is a shipped scene with --set assignments, read by the scene library; `dimensions`
// above 0 sets field.dimensions (--voxels).
struct FitField
{
  BenchScene Scene;
  bool HeldOut = false;
};

std::vector<FitField> FitFields(const std::string& split, int dimensions)
{
  const std::string fbm = "data/scenes/fbm-sphere.json", sphere = "data/scenes/sphere.json";
  const struct
  {
    const char* Name;
    std::string Path;
    std::vector<std::string> Assignments;
  } variants[] = {
    { "fbm-sphere", fbm, {} },
    // the `errors` table's dense field: a sphere that touches the box
    { "dense", fbm, { "field.shape.radius=1.8", "transfer_function.unit_distance=0.5" } },
    // fBm on a box filling most of the volume, extinction up to 6.4
    { "fbm-box",
      fbm,
      { R"(field.shape={"type": "box", "half_size": [1.5, 1, 1.5]})",
        "transfer_function.unit_distance=0.25" } },
    // sphere.json 8 times denser: optical radius 4.1 (sphere.json's is 0.51)
    { "thick-sphere",
      sphere,
      { "field.density_scale=8", "transfer_function.opacity=[[0, 0], [8, 0.4]]" } },
    { "perlin-falloff", "data/scenes/perlin-falloff.json", {} },
    { "sphere", sphere, {} },
    // wisps: the fbm noise on a sphere of radius 0.5
    { "sparse", fbm, { "field.shape.radius=0.5" } },
  };
  std::vector<FitField> fields;
  for (const auto& variant : variants)
  {
    std::vector<std::string> assignments = variant.Assignments;
    assignments.push_back("ambient.strength=0");
    if (dimensions > 0)
      assignments.push_back("field.dimensions=" + std::to_string(dimensions));
    fields.push_back({ ReadBenchScene(variant.Path, assignments) });
    fields.back().Scene.Name = variant.Name;
  }
  std::vector<std::string> heldOut;
  if (split == "first")
    heldOut = { "perlin-falloff", "sphere", "sparse" };
  else if (split == "stratified")
    heldOut = { "fbm-box", "perlin-falloff", "sparse" };
  else
    Fail("--split " + split + ": not a split (first, stratified)");
  for (FitField& f : fields)
    f.HeldOut = std::find(heldOut.begin(), heldOut.end(), f.Scene.Name) != heldOut.end();
  return fields;
}

struct FitLight
{
  const char* Name;
  glm::vec3 TowardLight; // the eye looks along -z
};

const FitLight FitLights[] = { { "side", { 1.0f, 0.0f, 0.0f } },
  { "back", glm::normalize(glm::vec3(0.2f, 0.3f, -1.0f)) },
  { "front", glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f)) },
  { "above", { 0.0f, 1.0f, 0.0f } } };
const float FitAlbedos[] = { 1.0f, 0.9f, 0.7f };

// The split, as a rule on (field, light, albedo): every combination is one of training, held
// out, or not used (to bound the running time).
enum class FitRole
{
  Training,
  HeldOut,
  Unused,
};

FitRole RoleOf(const FitField& field, const FitLight& light, float albedo)
{
  const bool above = std::strcmp(light.Name, "above") == 0;
  if (!field.HeldOut)
  {
    if (above)
      return albedo == 0.9f ? FitRole::HeldOut : FitRole::Unused;
    return albedo == 0.9f ? FitRole::Unused : FitRole::Training;
  }
  return std::strcmp(light.Name, "front") == 0 || albedo == 0.7f ? FitRole::Unused
                                                                 : FitRole::HeldOut;
}

// A case set: its fields, and the cases on each (a field's index, a light, an albedo, a role).
struct FitCaseSpec
{
  std::size_t Field = 0;
  FitLight Light;
  float Albedo = 1.0f;
  bool HeldOut = false;
};
struct FitCaseSet
{
  std::vector<FitField> Fields;
  std::vector<FitCaseSpec> Cases;
};

// The set above ("standard"): the fit's 46 cases.
FitCaseSet StandardCases(const Options& options)
{
  FitCaseSet set;
  set.Fields = FitFields(options.FitSplit, options.FitDimensions);
  for (std::size_t f = 0; f < set.Fields.size(); ++f)
    for (const FitLight& light : FitLights)
      for (float albedo : FitAlbedos)
      {
        const FitRole role = RoleOf(set.Fields[f], light, albedo);
        if (role != FitRole::Unused)
          set.Cases.push_back({ f, light, albedo, role == FitRole::HeldOut });
      }
  return set;
}

// The real regime of issue 38 ("real"): optically thick clouds at albedos near 1, of the kinds
// the scenes ship, with the two lobes (the droplets' references are out of reach: docs/
// lighting.md, "How fast it converges on thick clouds"), no ambient.
//   Fields: the shipped cumulus at optical diameters near 20, 100 (as shipped) and 500 (its
//   unit distance 0.25, 0.05, 0.01); the stratocumulus deck, the cumulonimbus and the cloudscape
//   seen from above, in their physical units (droplet extinction from their liquid water); and a
//   synthetic one, sphere.json 100 times denser (optical diameter near 50, smooth).
//   Lights (world directions; the cameras look along -z, but the cloudscape's looks down): from
//   above, the side, behind, and a low sun (15 degrees high, from the side and a little behind).
//   The split, chosen before anything was fitted or measured on it: the cumulonimbus and the
//   cloudscape are held-out fields (every light, albedos 1 and 0.999); on the training fields the
//   training cases are above, side and behind at albedos 1 and 0.99, and the low sun at albedo
//   0.999 is held out (a light and an albedo no training case has).
FitCaseSet RealCases(const Options& options)
{
  const std::string cumulus = "data/scenes/cumulus.json";
  const struct
  {
    const char* Name;
    std::string Path;
    std::vector<std::string> Assignments;
    bool HeldOut;
  } variants[] = {
    { "cumulus-od20", cumulus, { "transfer_function.unit_distance=0.25" }, false },
    { "cumulus-od100", cumulus, {}, false },
    { "cumulus-od500", cumulus, { "transfer_function.unit_distance=0.01" }, false },
    { "stratocumulus", "data/scenes/stratocumulus.json", {}, false },
    { "dense-sphere",
      "data/scenes/sphere.json",
      { "field.density_scale=100", "transfer_function.opacity=[[0, 0], [100, 0.4]]" },
      false },
    { "cumulonimbus", "data/scenes/cumulonimbus.json", {}, true },
    { "cloudscape", "data/scenes/cloudscape-above.json", {}, true },
  };
  FitCaseSet set;
  for (const auto& variant : variants)
  {
    std::vector<std::string> assignments = variant.Assignments;
    assignments.push_back("ambient.strength=0");
    assignments.push_back("render.march.phase=two_lobe");
    if (options.FitDimensions > 0)
      assignments.push_back("field.dimensions=" + std::to_string(options.FitDimensions));
    set.Fields.push_back({ ReadBenchScene(variant.Path, assignments), variant.HeldOut });
    set.Fields.back().Scene.Name = variant.Name;
  }
  const FitLight above = { "above", { 0.0f, 1.0f, 0.0f } };
  const FitLight side = { "side", { 1.0f, 0.0f, 0.0f } };
  const FitLight behind = { "behind", glm::normalize(glm::vec3(0.2f, 0.3f, -1.0f)) };
  const FitLight low = { "low sun", glm::normalize(glm::vec3(0.9f, 0.27f, -0.35f)) };
  for (std::size_t f = 0; f < set.Fields.size(); ++f)
  {
    if (set.Fields[f].HeldOut)
    {
      for (const FitLight& light : { above, side, behind, low })
        for (float albedo : { 1.0f, 0.999f })
          set.Cases.push_back({ f, light, albedo, true });
      continue;
    }
    for (const FitLight& light : { above, side, behind })
      for (float albedo : { 1.0f, 0.99f })
        set.Cases.push_back({ f, light, albedo, false });
    set.Cases.push_back({ f, low, 0.999f, true });
  }
  return set;
}

// An albedo as the case names print it: one decimal where that is exact (the standard set's
// names, which the reference cache's file names repeat), else three digits.
std::string AlbedoLabel(float albedo)
{
  char label[16];
  std::snprintf(label, sizeof(label), "%.1f", double(albedo));
  if (float(std::atof(label)) != albedo)
    std::snprintf(label, sizeof(label), "%.3g", double(albedo));
  return label;
}

// The march of one case with its light volumes computed once: the octaves (N, a, b, c) change
// only how the optical depth toward the light becomes scattered light, not the optical depth, so
// a fit that changes nothing else need not recompute the volumes at each evaluation (nor does the
// GPU: docs/lighting.md, "Light volumes"). It marches each pixel as vtkCloudReferenceRenderer
// does (Fit checks that the two images are identical at the defaults).
struct PreparedMarch
{
  TransferTable Table;
  MarchUniforms Uniforms;
  LightVolumes Volumes;
  glm::dmat4 DeviceToLocal;
  int Width = 0, Height = 0;

  PreparedMarch(vtkCloudReferenceRenderer* renderer, vtkImageData* field)
  {
    std::string tableProblem;
    this->Table =
      TransferTableOf(renderer->GetVolumeProperty(), renderer->GetExtinctionScale(), tableProblem);
    if (!tableProblem.empty())
      Fail(tableProblem);
    const MarchSetup setup = MakeMarchSetup(field,
      renderer->GetVolumeMatrix(),
      DensityTexelsOf(field->GetPointData()->GetScalars()),
      &this->Table,
      renderer->GetSampleDistance(),
      renderer->GetTerminationTransmittance(),
      renderer->GetLightingProperty()->GetParameters(),
      renderer->GetLightList());
    LocalFrame frame;
    const MarchProblem problem = SetUpMarch(setup, this->Uniforms, &frame);
    if (problem)
      Fail("the field cannot be marched: " + problem.Message);
    if (this->Uniforms.Lighting.Transmittance != LightTransmittance::Volumes)
      Fail("a prepared march reads light volumes");
    ComputeLightVolumes(this->Uniforms, this->Volumes);
    this->Uniforms.LightDepths = &this->Volumes;
    glm::dmat4 viewToDevice;
    glm::dmat3 worldToView;
    glm::dvec3 eye;
    if (!renderer->GetCamera(viewToDevice, worldToView, eye))
      Fail("unusable camera");
    this->DeviceToLocal = cloudvis::DeviceToLocal(frame, viewToDevice, worldToView, eye);
    const int* size = renderer->GetImageSize();
    this->Width = size[0];
    this->Height = size[1];
  }

  // The image with the multiple-scattering volume instead of the octaves, and the seconds its
  // computation took.
  std::vector<float> RenderWithVolume(const ScatteringSolve& solve, double& seconds)
  {
    const double start = vtkTimerLog::GetUniversalTime();
    ComputeScatteringVolume(this->Uniforms, this->Scattering, solve);
    seconds = vtkTimerLog::GetUniversalTime() - start;
    this->Uniforms.MultipleScattering = &this->Scattering;
    std::vector<float> image = this->Render(this->Uniforms.Lighting);
    this->Uniforms.MultipleScattering = nullptr;
    return image;
  }
  ScatteringGrid Scattering;

  // The image with these octaves (the other lighting parameters as prepared).
  std::vector<float> Render(const LightingParameters& octaves)
  {
    // The octaves whatever the default multiple scattering: they are what is fitted.
    this->Uniforms.Lighting.MultipleScattering = MultipleScatteringModel::Octaves;
    this->Uniforms.Lighting.MultipleScatteringOctaves = octaves.MultipleScatteringOctaves;
    this->Uniforms.Lighting.ScatteringFalloff = octaves.ScatteringFalloff;
    this->Uniforms.Lighting.ExtinctionFalloff = octaves.ExtinctionFalloff;
    this->Uniforms.Lighting.EccentricityFalloff = octaves.EccentricityFalloff;
    std::vector<float> rgba(std::size_t(this->Width) * this->Height * 4);
    vtkSMPTools::For(0,
      this->Height,
      [&](int begin, int end)
      {
        for (int j = begin; j < end; ++j)
          for (int i = 0; i < this->Width; ++i)
          {
            glm::dvec3 nearPoint, farPoint;
            vtkCloudReferenceRenderer::PixelRay(
              this->DeviceToLocal, i, j, this->Width, this->Height, nearPoint, farPoint);
            const glm::vec4 color =
              MarchRay(this->Uniforms, glm::vec3(nearPoint), glm::vec3(farPoint));
            std::copy(&color.r, &color.r + 4, &rgba[(std::size_t(j) * this->Width + i) * 4]);
          }
      });
    return rgba;
  }
};

struct FitCase
{
  std::string Name;
  bool HeldOut = false;
  Rendered Reference;
  vtkSmartPointer<vtkCloudReferenceRenderer> March; // its lighting is set per evaluation
  std::unique_ptr<PreparedMarch> Octaves;           // the same march, for the octaves' fit
  double ReferenceSeconds = 0.0;
  double VoxelEdge = 0.0; // the field's smallest voxel edge, world units
};

// The errors of the march with these lighting parameters on each case (of one set only when
// `only` is given: the objective renders the training cases alone). With `octavesOnly` the
// prepared marches render, with `lighting`'s octaves and the rest as prepared.
std::vector<ImageError> FitErrors(std::vector<FitCase>& cases,
  const std::function<LightingParameters(const FitCase&)>& lightingOf,
  bool octavesOnly = false,
  std::optional<bool> onlyHeldOut = std::nullopt)
{
  std::vector<ImageError> errors(cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i)
  {
    FitCase& c = cases[i];
    if (onlyHeldOut && c.HeldOut != *onlyHeldOut)
      continue;
    const LightingParameters lighting = lightingOf(c);
    std::vector<float> image;
    if (octavesOnly)
      image = c.Octaves->Render(lighting);
    else
    {
      c.March->GetLightingProperty()->SetParameters(lighting);
      image = Run(c.March).RGBA;
    }
    errors[i] = CompareWithReference(
      image.data(), c.Reference.RGBA.data(), c.Reference.Variance.data(), image.size() / 4);
  }
  return errors;
}

// The same lighting for every case.
std::vector<ImageError> FitErrors(std::vector<FitCase>& cases,
  const LightingParameters& lighting,
  bool octavesOnly = false,
  std::optional<bool> onlyHeldOut = std::nullopt)
{
  return FitErrors(
    cases, [&lighting](const FitCase&) { return lighting; }, octavesOnly, onlyHeldOut);
}

// The objective: the mean over the training cases of the noise-corrected relative RMSE (each
// case counts the same, whatever its brightness; the reference's noise, which no parameter can
// explain, is taken out).
double MeanError(const std::vector<FitCase>& cases,
  const std::vector<ImageError>& errors,
  bool heldOut)
{
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (cases[i].HeldOut == heldOut)
    {
      sum += errors[i].NoiseCorrectedRelativeRMSE;
      ++n;
    }
  return n ? sum / n : 0.0;
}

// Nelder-Mead in a box: points are clamped into [lower, upper] before they are evaluated, the
// simplex starts at `start` with edges of `step`, and stops when its values differ by less than
// `tolerance` or after `maxEvaluations`.
template<std::size_t D>
std::pair<std::array<double, D>, double> NelderMead(
  const std::function<double(const std::array<double, D>&)>& f,
  std::array<double, D> start,
  const std::array<double, D>& step,
  const std::array<double, D>& lower,
  const std::array<double, D>& upper,
  double tolerance,
  int maxEvaluations)
{
  using Point = std::array<double, D>;
  const auto clamp = [&](Point p)
  {
    for (std::size_t i = 0; i < D; ++i)
      p[i] = std::clamp(p[i], lower[i], upper[i]);
    return p;
  };
  int evaluations = 0;
  const auto value = [&](const Point& p)
  {
    ++evaluations;
    return f(p);
  };
  std::vector<std::pair<Point, double>> simplex;
  start = clamp(start);
  simplex.push_back({ start, value(start) });
  for (std::size_t i = 0; i < D; ++i)
  {
    Point p = start;
    p[i] += (p[i] + step[i] <= upper[i]) ? step[i] : -step[i];
    p = clamp(p);
    simplex.push_back({ p, value(p) });
  }
  const auto combine = [&](const Point& centroid, const Point& p, double t)
  {
    Point q;
    for (std::size_t i = 0; i < D; ++i)
      q[i] = centroid[i] + t * (p[i] - centroid[i]);
    return clamp(q);
  };
  while (evaluations < maxEvaluations)
  {
    std::sort(simplex.begin(),
      simplex.end(),
      [](const auto& x, const auto& y) { return x.second < y.second; });
    if (simplex.back().second - simplex.front().second < tolerance)
      break;
    Point centroid{};
    for (std::size_t k = 0; k < D; ++k)
      for (std::size_t i = 0; i < D; ++i)
        centroid[i] += simplex[k].first[i] / double(D);
    auto& worst = simplex.back();
    const Point reflected = combine(centroid, worst.first, -1.0);
    const double fr = value(reflected);
    if (fr < simplex.front().second)
    {
      const Point expanded = combine(centroid, worst.first, -2.0);
      const double fe = value(expanded);
      worst = fe < fr ? std::make_pair(expanded, fe) : std::make_pair(reflected, fr);
    }
    else if (fr < simplex[D - 1].second)
      worst = { reflected, fr };
    else
    {
      const Point contracted = combine(centroid, worst.first, fr < worst.second ? -0.5 : 0.5);
      const double fc = value(contracted);
      if (fc < std::min(fr, worst.second))
        worst = { contracted, fc };
      else // shrink toward the best
        for (std::size_t k = 1; k <= D; ++k)
        {
          simplex[k].first = combine(simplex[0].first, simplex[k].first, 0.5);
          simplex[k].second = value(simplex[k].first);
        }
    }
  }
  std::sort(simplex.begin(),
    simplex.end(),
    [](const auto& x, const auto& y) { return x.second < y.second; });
  return { simplex.front().first, simplex.front().second };
}

// Golden-section search of a unimodal f on [a, b], to a bracket of `tolerance`.
std::pair<double, double> GoldenSection(const std::function<double(double)>& f,
  double a,
  double b,
  double tolerance)
{
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - r * (b - a), x2 = a + r * (b - a);
  double f1 = f(x1), f2 = f(x2);
  while (b - a > tolerance)
  {
    if (f1 < f2)
    {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - r * (b - a);
      f1 = f(x1);
    }
    else
    {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + r * (b - a);
      f2 = f(x2);
    }
  }
  return f1 < f2 ? std::make_pair(x1, f1) : std::make_pair(x2, f2);
}

// A case's name as a file name: "dense, side, albedo 1.0" -> "dense,_side,_albedo_1.0".
std::string FileLabel(std::string name)
{
  std::replace(name.begin(), name.end(), ' ', '_');
  return name;
}

// The per-case table of two settings' errors, and the aggregates of each set.
void PrintBeforeAfter(const char* title,
  const std::vector<FitCase>& cases,
  const std::vector<ImageError>& before,
  const std::vector<ImageError>& after)
{
  std::printf("\n%s\n\n| case | set | relative RMSE before | after | noise-corrected before | "
              "after | bias before | after | reference's standard error |\n"
              "|---|---|---|---|---|---|---|---|---|\n",
    title);
  for (bool heldOut : { false, true })
    for (std::size_t i = 0; i < cases.size(); ++i)
      if (cases[i].HeldOut == heldOut)
        std::printf("| %s | %s | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.3f | %.3f | %.2f%% |\n",
          cases[i].Name.c_str(),
          heldOut ? "held out" : "training",
          100.0 * before[i].RelativeRMSE,
          100.0 * after[i].RelativeRMSE,
          100.0 * before[i].NoiseCorrectedRelativeRMSE,
          100.0 * after[i].NoiseCorrectedRelativeRMSE,
          before[i].BiasRatio,
          after[i].BiasRatio,
          100.0 * before[i].ReferenceRelativeStandardError);
  for (bool heldOut : { false, true })
  {
    double worstBefore = 0.0, worstAfter = 0.0;
    for (std::size_t i = 0; i < cases.size(); ++i)
      if (cases[i].HeldOut == heldOut)
      {
        worstBefore = std::max(worstBefore, before[i].NoiseCorrectedRelativeRMSE);
        worstAfter = std::max(worstAfter, after[i].NoiseCorrectedRelativeRMSE);
      }
    std::printf("| **mean, %s** | | | | %.1f%% | %.1f%% | | | |\n"
                "| **worst, %s** | | | | %.1f%% | %.1f%% | | | |\n",
      heldOut ? "held out" : "training",
      100.0 * MeanError(cases, before, heldOut),
      100.0 * MeanError(cases, after, heldOut),
      heldOut ? "held out" : "training",
      100.0 * worstBefore,
      100.0 * worstAfter);
  }
  std::fflush(stdout);
}

// A case's reference, read from options.ReferenceCache when an earlier run with the same
// options left it there, else rendered (and left there).
Rendered CachedReference(const Options& options,
  const std::string& name,
  const std::function<Rendered()>& render)
{
  if (options.ReferenceCache.empty())
    return render();
  char key[160];
  std::snprintf(key,
    sizeof(key),
    "/%s-%dx%d-%dspp-%db-s%u-v%d.bin",
    FileLabel(name).c_str(),
    options.Width,
    options.Height,
    options.Samples,
    options.Bounces,
    options.Seed,
    options.FitDimensions);
  const std::string path = options.ReferenceCache + key;
  const std::size_t values = std::size_t(options.Width) * options.Height * 4;
  Rendered r;
  std::ifstream in(path, std::ios::binary);
  if (in)
  {
    r.RGBA.resize(values);
    r.Variance.resize(values);
    in.read(reinterpret_cast<char*>(r.RGBA.data()), std::streamsize(values * sizeof(float)));
    in.read(reinterpret_cast<char*>(r.Variance.data()), std::streamsize(values * sizeof(float)));
    if (in)
      return r;
  }
  r = render();
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(r.RGBA.data()), std::streamsize(values * sizeof(float)));
  out.write(
    reinterpret_cast<const char*>(r.Variance.data()), std::streamsize(values * sizeof(float)));
  return r;
}

// The multiple-scattering volume against the octaves on every case, with the shipped settings.
int MeasureVolume(std::vector<FitCase>& cases, const Options& options)
{
  LightingParameters shipped;
  shipped.Model = LightingModel::March;
  const std::vector<ImageError> octaves = FitErrors(cases, shipped, true);
  std::vector<ImageError> volume(cases.size());
  double seconds = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i)
  {
    double s = 0.0;
    const std::vector<float> image = cases[i].Octaves->RenderWithVolume(ScatteringSolve(), s);
    seconds += s;
    volume[i] = CompareWithReference(image.data(),
      cases[i].Reference.RGBA.data(),
      cases[i].Reference.Variance.data(),
      image.size() / 4);
    WritePng(
      options.PngDirectory, FileLabel(cases[i].Name) + "-volume", image, options.Width, options.Height);
  }
  PrintBeforeAfter("march: octaves (before), multiple-scattering volume (after)", cases, octaves, volume);
  std::printf("volume computations: %.3f s per case\n", seconds / double(cases.size()));
  return 0;
}

} // namespace

int Fit(const Options& options)
{
  const double fitStart = vtkTimerLog::GetUniversalTime();
  std::printf("%d x %d, path tracer %d paths per pixel, bounce cap %d, seed %u; fields on %s "
              "voxels; cases %s, split %s\n",
    options.Width,
    options.Height,
    options.Samples,
    options.Bounces,
    options.Seed,
    options.FitDimensions > 0 ? std::to_string(options.FitDimensions).append("^3").c_str()
                              : "their own",
    options.FitCases.c_str(),
    options.FitCases == "real" ? "the set's own" : options.FitSplit.c_str());
  // The references, once per case.
  std::vector<FitCase> cases;
  std::vector<vtkSmartPointer<vtkImageData>> fields; // kept alive for the marches
  const FitCaseSet set = options.FitCases == "real" ? RealCases(options) : StandardCases(options);
  for (std::size_t f = 0; f < set.Fields.size(); ++f)
  {
    const FitField& fitField = set.Fields[f];
    const Scene& scene = fitField.Scene.Spec;
    fields.push_back(FieldOf(scene));
    vtkImageData* field = fields.back();
    for (const FitCaseSpec& spec : set.Cases)
      if (spec.Field == f)
      {
        const Scene gray = Relit(scene, { LightToward(spec.Light.TowardLight) }, spec.Albedo);
        FitCase c;
        c.Name =
          fitField.Scene.Name + ", " + spec.Light.Name + ", albedo " + AlbedoLabel(spec.Albedo);
        c.HeldOut = spec.HeldOut;
        c.Reference = CachedReference(options, c.Name, [&]()
          { return Run(NewTracer(gray, field, options.Bounces, options)); });
        c.ReferenceSeconds = c.Reference.Seconds;
        const double* spacing = field->GetSpacing();
        c.VoxelEdge = std::min({ spacing[0], spacing[1], spacing[2] });
        LightingParameters lighting = gray.Render.Lighting;
        lighting.Model = LightingModel::March;
        c.March = NewMarch(gray, field, lighting, options);
        c.Octaves = std::make_unique<PreparedMarch>(c.March, field);
        if (options.MultipleScattering != "volume" &&
          Run(c.March).RGBA != c.Octaves->Render(lighting))
          Fail(c.Name + ": the prepared march differs from vtkCloudReferenceRenderer's");
        WritePng(options.PngDirectory,
          FileLabel(c.Name) + "-pathtrace",
          c.Reference.RGBA,
          options.Width,
          options.Height);
        cases.push_back(std::move(c));
      }
  }
  double referenceSeconds = 0.0;
  for (const FitCase& c : cases)
    referenceSeconds += c.ReferenceSeconds;
  std::printf("%zu cases (%d held out); the references took %.0f s\n",
    cases.size(),
    int(std::count_if(cases.begin(), cases.end(), [](const FitCase& c) { return c.HeldOut; })),
    referenceSeconds);

  if (options.MultipleScattering == "volume")
    return MeasureVolume(cases, options);

  // The octaves: for each N, Nelder-Mead over (a, b, c) in [0, 1]^3 from the old defaults.
  // "Before": the octaves' values until this fit (the rest: the shipped defaults, light volumes).
  LightingParameters base;
  base.Model = LightingModel::March;
  base.MultipleScatteringOctaves = 3;
  base.ScatteringFalloff = base.ExtinctionFalloff = base.EccentricityFalloff = 0.5f;
  const std::vector<ImageError> before = FitErrors(cases, base);
  std::printf("\nbefore the fit (N %d, a %.3f, b %.3f, c %.3f): training %.2f%%, held out "
              "%.2f%%\n",
    base.MultipleScatteringOctaves,
    double(base.ScatteringFalloff),
    double(base.ExtinctionFalloff),
    double(base.EccentricityFalloff),
    100.0 * MeanError(cases, before, false),
    100.0 * MeanError(cases, before, true));
  std::printf("\nOctave counts 1 to %d: the best of a 4^3 grid over (a, b, c) starts Nelder-Mead "
              "(at most %d evaluations after it), bounded to [0, 1]^3.\n",
    options.FitMaxOctaves,
    options.FitEvaluations);
  std::printf("\n| octaves N | a | b | c | training mean | held-out mean | evaluations | time |\n"
              "|---|---|---|---|---|---|---|---|\n");
  std::vector<std::pair<LightingParameters, double>> fits; // per N, with its training mean
  for (int octaves = 1; octaves <= options.FitMaxOctaves; ++octaves)
  {
    const double nStart = vtkTimerLog::GetUniversalTime();
    int evaluations = 0;
    const auto withParameters = [&](const std::array<double, 3>& x)
    {
      LightingParameters p = base;
      p.MultipleScatteringOctaves = octaves;
      p.ScatteringFalloff = float(x[0]);
      p.ExtinctionFalloff = float(x[1]);
      p.EccentricityFalloff = float(x[2]);
      return p;
    };
    const auto objective = [&](const std::array<double, 3>& x)
    {
      ++evaluations;
      return MeanError(cases, FitErrors(cases, withParameters(x), true, false), false);
    };
    // Coarse to fine: the best of a 4^3 grid over the box starts the simplex (the objective
    // has more than one valley: less scattering can be traded against less extinction).
    std::array<double, 3> start{ 0.5, 0.5, 0.5 };
    double startValue = objective(start);
    for (double a : { 0.2, 0.4, 0.6, 0.8 })
      for (double b : { 0.2, 0.4, 0.6, 0.8 })
        for (double c : { 0.2, 0.4, 0.6, 0.8 })
        {
          const double value = objective({ a, b, c });
          if (value < startValue)
          {
            startValue = value;
            start = { a, b, c };
          }
        }
    const auto [x, training] = NelderMead<3>(objective,
      start,
      { 0.1, 0.1, 0.1 },
      { 0.0, 0.0, 0.0 },
      { 1.0, 1.0, 1.0 },
      1e-4,
      options.FitEvaluations);
    const LightingParameters fitted = withParameters(x);
    const double heldOut = MeanError(cases, FitErrors(cases, fitted, true, true), true);
    std::printf("| %d | %.3f | %.3f | %.3f | %.2f%% | %.2f%% | %d | %.0f s |\n",
      octaves,
      x[0],
      x[1],
      x[2],
      100.0 * training,
      100.0 * heldOut,
      evaluations,
      vtkTimerLog::GetUniversalTime() - nStart);
    std::fflush(stdout);
    fits.push_back({ fitted, training });
  }
  // The fewest octaves within half a point of the best training mean: each octave costs the
  // march two phase evaluations and an exponential per light at every sample, and beyond 3
  // octaves the training mean falls by tenths of a point, less than it moves between splits.
  double bestTraining = 1e30;
  for (const auto& fit : fits)
    bestTraining = std::min(bestTraining, fit.second);
  LightingParameters best = base;
  for (const auto& fit : fits)
    if (fit.second <= bestTraining + 0.005)
    {
      best = fit.first;
      break;
    }
  // Rounded to two decimals, as the defaults are written.
  for (float* f : { &best.ScatteringFalloff, &best.ExtinctionFalloff, &best.EccentricityFalloff })
    *f = std::round(*f * 100.0f) / 100.0f;
  std::printf("\nchosen (the fewest octaves within 0.5 points of the best training mean, "
              "rounded): N %d, a %.2f, b %.2f, c %.2f\n",
    best.MultipleScatteringOctaves,
    double(best.ScatteringFalloff),
    double(best.ExtinctionFalloff),
    double(best.EccentricityFalloff));
  const LightingParameters shipped;
  std::printf(
    "the shipped defaults (filters/CloudLighting.h) are N %d, a %.2f, b %.2f, c %.2f: %s\n",
    shipped.MultipleScatteringOctaves,
    double(shipped.ScatteringFalloff),
    double(shipped.ExtinctionFalloff),
    double(shipped.EccentricityFalloff),
    shipped.MultipleScatteringOctaves == best.MultipleScatteringOctaves &&
        shipped.ScatteringFalloff == best.ScatteringFalloff &&
        shipped.ExtinctionFalloff == best.ExtinctionFalloff &&
        shipped.EccentricityFalloff == best.EccentricityFalloff
      ? "the fit's"
      : "not the fit's");
  const std::vector<ImageError> after = FitErrors(cases, best);
  PrintBeforeAfter(
    "march, light volumes (the default): before the fit, and fitted", cases, before, after);
  if (!options.PngDirectory.empty())
    for (FitCase& c : cases)
      for (const auto& [lighting, suffix] :
        { std::make_pair(best, "-march-fitted"), std::make_pair(base, "-march-before") })
      {
        c.March->GetLightingProperty()->SetParameters(lighting);
        WritePng(options.PngDirectory,
          FileLabel(c.Name) + suffix,
          Run(c.March).RGBA,
          options.Width,
          options.Height);
      }

  // The check with the nested light march.
  LightingParameters baseNested = base, bestNested = best;
  baseNested.Transmittance = bestNested.Transmittance = LightTransmittance::Nested;
  PrintBeforeAfter("march, nested light march: before the fit, and fitted",
    cases,
    FitErrors(cases, baseNested),
    FitErrors(cases, bestNested));

  // The derivative model: h in voxel spacings of each field (as its default, 4, is stated),
  // golden-section search of log2(h) over [1/2, 64] voxels: its one length; the model has no
  // other constant a fit could set (its slope scale is 1 / (h rho_unit)).
  const auto derivativeAt = [](double log2Voxels)
  {
    return [log2Voxels](const FitCase& c)
    {
      LightingParameters p;
      p.Model = LightingModel::Derivative;
      p.DerivativeDistance = float(std::exp2(log2Voxels) * c.VoxelEdge);
      return p;
    };
  };
  const std::vector<ImageError> derivativeBefore = FitErrors(cases, derivativeAt(2.0));
  const auto [log2h, derivativeTraining] = GoldenSection([&](double x)
    { return MeanError(cases, FitErrors(cases, derivativeAt(x), false, false), false); },
    -1.0,
    6.0,
    0.05);
  std::printf("\nderivative: h = %.2f voxels gives training %.2f%% (4 voxels: %.2f%%)\n",
    std::exp2(log2h),
    100.0 * derivativeTraining,
    100.0 * MeanError(cases, derivativeBefore, false));
  PrintBeforeAfter("derivative: h = 4 voxels before, fitted after",
    cases,
    derivativeBefore,
    FitErrors(cases, derivativeAt(log2h)));

  std::printf("\nthe whole fit took %.0f s (references %.0f s)\n",
    vtkTimerLog::GetUniversalTime() - fitStart,
    referenceSeconds);
  return 0;
}

} // namespace bench
} // namespace cloudvis
