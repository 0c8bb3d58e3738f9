// `cloudvis-bench-pathtrace defects`: the march's defects measured one by one (docs/lighting.md,
// "What the march gets wrong"): the light march's midpoint sampling and reach against the exact
// optical depth, the octaves per opacity against the path tracer, and the bright isolated pixels
// of a field that touches its box. The light march's transmittance is read at sample points of
// the cloud through the reference march's own functions (CloudReferenceMarch.h), with the
// uniforms the renderers set up for the scene's field and transfer table.
#include "CloudMarchUniforms.h"
#include "CloudReferenceMarch.h"
#include "CloudTransferTable.h"
#include "CloudTransport.h"
#include "OffscreenRender.h"
#include "PathTraceBench.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace cloudvis
{
namespace bench
{

namespace
{
// The table every renderer builds from the scene's transfer function (MakeVolumeProperty).
TransferTable TableOf(const Scene& scene)
{
  std::string problem;
  TransferTable table = TransferTableOf(MakeVolumeProperty(scene.TransferFunction), 1.0, problem);
  if (!problem.empty())
    Fail(problem);
  return table;
}

// The march's uniforms for the field and table with the default lighting, as the renderers set
// them up (SetUpMarch), and the local frame they are in.
MarchUniforms UniformsOf(vtkImageData* field, const TransferTable& table, LocalFrame& frame)
{
  MarchSetup setup;
  setup.Geometry = GeometryOf(field, nullptr);
  setup.Table = &table;
  MarchUniforms u;
  const MarchProblem problem = SetUpMarch(setup, u, &frame);
  if (problem)
    Fail("the field cannot be marched: " + problem.Message);
  u.Density = DensityTexelsOf(field->GetPointData()->GetScalars());
  return u;
}

// The optical depth from index point p along the direction l over [s0, s1] (local units), by
// the midpoint rule with steps of 1/16 of the smallest voxel: the exact integral to 1e-4.
double OpticalDepth(const MarchUniforms& u,
  const LocalFrame& frame,
  glm::vec3 p,
  glm::vec3 l,
  double s0,
  double s1)
{
  const double ds = frame.SmallestVoxelEdge / frame.Unit / 16.0;
  const glm::vec3 indexStep = LocalToIndex(u, l);
  glsl::Transport transport = TransportOf(u); // the march's medium, set up once for the loop
  double tau = 0.0;
  for (double s = s0 + 0.5 * ds; s < s1; s += ds)
  {
    const glm::vec3 q = p + float(s) * indexStep;
    if (transport.InsideVolume(q))
      tau += transport.ExtinctionAt(q) * std::min(ds, s1 - (s - 0.5 * ds));
  }
  return tau;
}

struct Percentiles
{
  std::vector<double> Values;
  std::string Format(const char* unit = "") const
  {
    std::vector<double> v = this->Values;
    if (v.empty())
      return "-";
    std::sort(v.begin(), v.end());
    double mean = 0.0;
    for (double x : v)
      mean += x;
    mean /= double(v.size());
    char text[160];
    std::snprintf(text,
      sizeof(text),
      "mean %.4f%s, 5%% %.4f, median %.4f, 95%% %.4f, max %.4f",
      mean,
      unit,
      v[v.size() / 20],
      v[v.size() / 2],
      v[v.size() * 19 / 20],
      v.back());
    return text;
  }
};

// The light march's transmittance at sample points of the cloud against the exact one over the
// same way (to the volume's exit): what its segments and their quadrature make of the field.
void LightMarchErrors(const char* name, vtkImageData* field, const TransferTable& table)
{
  LocalFrame frame;
  const MarchUniforms u = UniformsOf(field, table, frame);
  const LightingParameters& l = u.Lighting;                  // lengths in local units
  const double voxel = frame.SmallestVoxelEdge / frame.Unit; // local units
  std::printf("\n%s: %d light steps growing %.2f to the volume's exit, the first at least %.4f "
              "(%.1f voxels; the volume's diagonal is %.2f)\n",
    name,
    l.LightSteps,
    double(l.LightStepGrowth),
    l.LightStep * frame.Unit,
    l.LightStep / voxel,
    frame.LongestChord * frame.Unit);
  for (const glm::vec3 toward : { glm::vec3(1, 0, 0), glm::normalize(glm::vec3(0.2f, 0.3f, -1)) })
  {
    Percentiles ratio;
    int samples = 0;
    glsl::Transport transport = TransportOf(u);
    for (int k = 2; k < u.Dimensions.z - 2; k += 3)
      for (int j = 2; j < u.Dimensions.y - 2; j += 3)
        for (int i = 2; i < u.Dimensions.x - 2; i += 3)
        {
          // Off the lattice, as view samples are.
          const glm::vec3 p(i + 0.37f, j + 0.61f, k + 0.23f);
          const float sigma = transport.ExtinctionAt(p);
          if (!(sigma > 0.0f))
            continue;
          ++samples;
          const glm::vec3 indexStep = LocalToIndex(u, toward);
          const float tauMarch = transport.LightOpticalDepth(p, sigma, indexStep, 1e30f);
          const glm::vec2 exit =
            IntersectBox(p, indexStep, glm::vec3(0.0f), glm::vec3(u.Dimensions - 1));
          const double tauExact = OpticalDepth(u, frame, p, toward, 0.0, exit.y);
          ratio.Values.push_back(std::exp(tauExact - tauMarch));
        }
    std::printf("  light toward (%.2f, %.2f, %.2f), %d cloud samples: transmittance / exact to "
                "the exit: %s\n",
      double(toward.x),
      double(toward.y),
      double(toward.z),
      samples,
      ratio.Format().c_str());
  }
}

// Where a model's image is too bright or too dark: the ratio of its mean to the path tracer's
// over pixels binned by the path tracer's opacity (thin edges to dense cores).
void OpacityBins(const char* label, const Rendered& image, const Rendered& reference)
{
  const double edges[] = { 0.01, 0.3, 0.7, 0.95, 0.99, 1.01 };
  std::printf("  %s:", label);
  for (int b = 0; b + 1 < int(sizeof(edges) / sizeof(edges[0])); ++b)
  {
    double sum = 0.0, referenceSum = 0.0;
    int pixels = 0;
    for (std::size_t p = 0; p < image.RGBA.size() / 4; ++p)
    {
      const float alpha = reference.RGBA[4 * p + 3];
      if (alpha >= edges[b] && alpha < edges[b + 1])
      {
        ++pixels;
        for (int c = 0; c < 3; ++c)
        {
          sum += image.RGBA[4 * p + c];
          referenceSum += reference.RGBA[4 * p + c];
        }
      }
    }
    if (pixels > 0)
      std::printf(" opacity [%.2f, %.2f): %.2f (%d px);",
        edges[b],
        std::min(edges[b + 1], 1.0),
        sum / referenceSum,
        pixels);
  }
  std::printf("\n");
}

// Pixels more than `factor` times brighter than the median of their 8 neighbours.
std::vector<int> Outliers(const Rendered& image, int width, int height, double factor)
{
  std::vector<int> outliers;
  const auto luminance = [&](int i, int j)
  {
    const float* p = &image.RGBA[(std::size_t(j) * width + i) * 4];
    return double(p[0] + p[1] + p[2]);
  };
  for (int j = 1; j + 1 < height; ++j)
    for (int i = 1; i + 1 < width; ++i)
    {
      std::vector<double> around;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          if (di || dj)
            around.push_back(luminance(i + di, j + dj));
      std::nth_element(around.begin(), around.begin() + 4, around.end());
      if (luminance(i, j) > factor * around[4] && luminance(i, j) > 1e-3)
        outliers.push_back(j * width + i);
    }
  return outliers;
}

}

int Defects(const Options& options)
{
  std::printf("The march's defects, measured (%d x %d images, path tracer %d paths per pixel).\n",
    options.Width,
    options.Height,
    options.Samples);
  for (const BenchScene& errorField : ErrorFields())
  {
    const Scene& scene = errorField.Spec;
    const vtkSmartPointer<vtkImageData> field = FieldOf(scene);
    LightMarchErrors(errorField.Name.c_str(), field, TableOf(scene));

    // The octaves against the path tracer, per opacity bin, side-lit, albedo 1 and 0.9.
    for (float albedo : { 1.0f, 0.9f })
    {
      const Scene gray = Relit(scene, { LightToward({ 1.0f, 0.0f, 0.0f }) }, albedo);
      const Rendered reference = Run(NewTracer(gray, field, options.Bounces, options));
      LightingParameters lighting = gray.Render.Lighting;
      lighting.Model = LightingModel::March;
      auto march = NewMarch(gray, field, lighting, options);
      char label[120];
      std::snprintf(label,
        sizeof(label),
        "side-lit, albedo %.1f, march (defaults) / path tracer",
        double(albedo));
      OpacityBins(label, Run(march), reference);
      lighting.LightSteps = 12; // twice the segments, over the same way to the exit
      march->GetLightingProperty()->SetParameters(lighting);
      std::snprintf(label,
        sizeof(label),
        "side-lit, albedo %.1f, march with 12 growing light "
        "steps / path tracer",
        double(albedo));
      OpacityBins(label, Run(march), reference);
    }
  }

  // A field that fills its box (the fbm sphere with radius 2.5 in [-2, 2]^3), lit from the side
  // along the box's front face: view rays enter through that face, and their first sample lies
  // on it. Where rounding puts it a hair outside, the light march finds no midpoint inside and
  // the sample is lit unshadowed.
  const Scene filling = Relit(ReadBenchScene("data/scenes/fbm-sphere.json",
                                { "field.shape.radius=2.5", "ambient.strength=0" })
                                .Spec,
    { LightToward({ 1.0f, 0.0f, 0.0f }) },
    1.0f);
  const vtkSmartPointer<vtkImageData> field = FieldOf(filling);
  const TransferTable table = TableOf(filling);
  LocalFrame frame;
  const MarchUniforms u = UniformsOf(field, table, frame);
  std::printf("\nbox-filling field (radius 2.5), side-lit along the front face, albedo 1, "
              "march (defaults), pixels of opacity > 0.5:\n");
  for (double step : { 0.0, 0.005 })
  {
    LightingParameters lighting = filling.Render.Lighting;
    lighting.Model = LightingModel::March;
    auto march = NewMarch(filling, field, lighting, options);
    march->SetSampleDistance(step);
    const Rendered image = Run(march);
    glm::dmat4 viewToDevice;
    glm::dmat3 worldToView;
    glm::dvec3 eye;
    if (!march->GetCamera(viewToDevice, worldToView, eye))
      Fail("unusable camera");
    const glm::dmat4 deviceToLocal = DeviceToLocal(frame, viewToDevice, worldToView, eye);
    // Whether the first sample of a pixel's ray lies outside the volume (InsideVolume false):
    // the ray set-up of MarchRay, repeated to see that sample.
    const auto firstSampleOutside = [&](int pixel)
    {
      glm::dvec3 nearPoint, farPoint;
      vtkCloudReferenceRenderer::PixelRay(deviceToLocal,
        pixel % options.Width,
        pixel / options.Width,
        options.Width,
        options.Height,
        nearPoint,
        farPoint);
      const glm::vec3 toFar = glm::vec3(farPoint) - glm::vec3(nearPoint);
      const glm::vec3 origin = IndexOfLocal(u, glm::vec3(nearPoint));
      const glm::vec3 direction = LocalToIndex(u, toFar / glm::length(toFar));
      const glm::vec2 tBox =
        IntersectBox(origin, direction, glm::vec3(0.0f), glm::vec3(u.Dimensions) - 1.0f);
      return !InsideVolume(u, origin + std::max(tBox.x, 0.0f) * direction);
    };
    std::vector<int> isOutlier(std::size_t(options.Width) * options.Height, 0);
    for (int pixel : Outliers(image, options.Width, options.Height, 3.0))
      isOutlier[pixel] = 1;
    int dense = 0, outside = 0, outliers = 0, outlierOutside = 0;
    double radiance[2] = { 0.0, 0.0 };
    for (int pixel = 0; pixel < options.Width * options.Height; ++pixel)
    {
      if (image.RGBA[4 * pixel + 3] < 0.5f)
        continue;
      const bool out = firstSampleOutside(pixel);
      ++dense;
      outside += out;
      outliers += isOutlier[pixel];
      outlierOutside += isOutlier[pixel] && out;
      radiance[out] += image.RGBA[4 * pixel];
    }
    std::printf("  step %s: %d of %d pixels have their first sample outside by rounding, and are "
                "on average %.1fx brighter than the others; %d pixels are > 3x the median of "
                "their neighbours, %d of them with the first sample outside\n",
      step > 0.0 ? "0.005" : "default (1 voxel)",
      outside,
      dense,
      (radiance[1] / std::max(outside, 1)) / (radiance[0] / std::max(dense - outside, 1)),
      outliers,
      outlierOutside);
  }
  return 0;
}

} // namespace bench
} // namespace cloudvis
