// `cloudvis-bench-pathtrace errors` and `bounces`: how far each lighting model of the march is
// from the path tracer (the table of docs/lighting.md), and the light the path tracer's bounce cap
// drops. Both run on the fields of ErrorFields (PathTraceBench.h), lit by one directional light.
#include "CloudImageComparison.h"
#include "PathTraceBench.h"
#include "vtkCloudPathTracer.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkImageData.h>

#include <cmath>
#include <cstdio>

namespace cloudvis
{
namespace bench
{

namespace
{
struct ErrorModel
{
  const char* Name;
  LightingModel Model;
  int Octaves;
  bool UniformLightSteps; // 64 uniform light steps spanning the volume's diagonal
  bool SingleScattering;  // compared with the path tracer restricted to one bounce
  bool AlbedoOneOnly;     // single scattering scales with the albedo: one albedo says it all
  bool Nested;            // the nested light march rather than the light volumes
};

// The mean of r, g, b over the footprint of an image.

}

int Errors(const Options& options)
{
  const ErrorModel models[] = {
    { "march (defaults: light volumes, 3 octaves)",
      LightingModel::March,
      3,
      false,
      false,
      false,
      false },
    { "march, nested light march (6 growing steps), 3 octaves",
      LightingModel::March,
      3,
      false,
      false,
      false,
      true },
    { "march, no octaves", LightingModel::March, 0, false, false, false, false },
    { "derivative", LightingModel::Derivative, 0, false, false, false, false },
    { "single scattering: march, no octaves (light volumes)",
      LightingModel::March,
      0,
      false,
      true,
      true,
      false },
    { "single scattering: march, no octaves, nested light march",
      LightingModel::March,
      0,
      false,
      true,
      true,
      true },
    { "single scattering: march, no octaves, 64 uniform light steps",
      LightingModel::March,
      0,
      true,
      true,
      true,
      true },
  };
  const struct
  {
    const char* Name;
    glm::vec3 TowardLight;
  } lightings[] = { { "side-lit", { 1.0f, 0.0f, 0.0f } },
    { "backlit", glm::normalize(glm::vec3(0.2f, 0.3f, -1.0f)) } };
  std::printf("%d x %d, path tracer %d paths per pixel, bounce cap %d\n\n",
    options.Width,
    options.Height,
    options.Samples,
    options.Bounces);
  std::printf("| field | light | albedo | model | relative RMSE | noise-corrected | bias (ratio "
              "of means) | max error / peak | reference's relative standard error |\n"
              "|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> albedoRatios, settingDifferences;
  for (const BenchScene& errorField : ErrorFields())
  {
    const Scene& scene = errorField.Spec;
    const vtkSmartPointer<vtkImageData> field = FieldOf(scene);
    double bounds[6];
    field->GetBounds(bounds);
    const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
      (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
    for (const auto& lit : lightings)
    {
      const Light light = LightToward(lit.TowardLight);
      double fullMean[2] = { 0.0, 0.0 };
      double marchMean[2] = { 0.0, 0.0 }; // march with its defaults (models[0])
      for (float albedo : { 1.0f, 0.9f })
      {
        const Scene gray = Relit(scene, { light }, albedo);
        const std::string label =
          errorField.Name + "-" + lit.Name + "-albedo" + (albedo == 1.0f ? "1" : "0.9");
        std::vector<Rendered> references(2); // every order of scattering, single scattering
        Rendered volumesImage;               // march with its defaults: the light volumes
        for (const ErrorModel& model : models)
        {
          if (model.AlbedoOneOnly && albedo != 1.0f)
            continue;
          Rendered& reference = references[model.SingleScattering ? 1 : 0];
          if (reference.RGBA.empty())
          {
            reference =
              Run(NewTracer(gray, field, model.SingleScattering ? 1 : options.Bounces, options));
            WritePng(options.PngDirectory,
              label + (model.SingleScattering ? "-pathtrace1" : "-pathtrace"),
              reference.RGBA,
              options.Width,
              options.Height);
          }
          LightingParameters lighting = scene.Render.Lighting;
          lighting.Model = model.Model;
          // The rows name octave counts: the octaves, whatever the default multiple scattering.
          lighting.MultipleScattering = MultipleScatteringModel::Octaves;
          lighting.MultipleScatteringOctaves = model.Octaves;
          lighting.Transmittance =
            model.Nested ? LightTransmittance::Nested : LightTransmittance::Volumes;
          if (model.UniformLightSteps)
          {
            lighting.LightSteps = 64;
            lighting.LightStepGrowth = 1.0f;
            lighting.LightStep = float(diagonal / 64.0);
          }
          const Rendered image = Run(NewMarch(gray, field, lighting, options));
          WritePng(options.PngDirectory,
            label + "-" + (model.Model == LightingModel::Derivative ? "derivative" : "march") +
              std::to_string(model.Octaves) + (model.UniformLightSteps ? "u" : "") +
              (model.Nested ? "n" : ""),
            image.RGBA,
            options.Width,
            options.Height);
          if (&model == &models[0])
          {
            marchMean[albedo == 1.0f ? 0 : 1] = MeanRadiance(image);
            volumesImage = image;
          }
          if (&model == &models[1]) // the two settings against each other, noise-free
          {
            const std::vector<float> exact(image.RGBA.size(), 0.0f);
            const ImageError d = CompareWithReference(volumesImage.RGBA.data(),
              image.RGBA.data(),
              exact.data(),
              std::size_t(options.Width) * options.Height);
            char line[200];
            std::snprintf(line,
              sizeof(line),
              "| %s | %s | %.1f | %.2f%% | %.4f | %.2f%% |",
              errorField.Name.c_str(),
              lit.Name,
              double(albedo),
              100.0 * d.RelativeRMSE,
              d.BiasRatio,
              100.0 * d.MaxErrorOverPeak);
            settingDifferences.push_back(line);
          }
          const ImageError e = CompareWithReference(image.RGBA.data(),
            reference.RGBA.data(),
            reference.Variance.data(),
            std::size_t(options.Width) * options.Height);
          std::printf("| %s | %s | %.1f | %s | %.1f%% | %.1f%% | %.3f | %.1f%% | %.2f%% |\n",
            errorField.Name.c_str(),
            lit.Name,
            double(albedo),
            model.Name,
            100.0 * e.RelativeRMSE,
            100.0 * e.NoiseCorrectedRelativeRMSE,
            e.BiasRatio,
            100.0 * e.MaxErrorOverPeak,
            100.0 * e.ReferenceRelativeStandardError);
          std::fflush(stdout);
        }
        fullMean[albedo == 1.0f ? 0 : 1] = MeanRadiance(references[0]);
      }
      char line[200];
      std::snprintf(line,
        sizeof(line),
        "| %s | %s | %.3f | %.3f |",
        errorField.Name.c_str(),
        lit.Name,
        fullMean[1] / fullMean[0],
        marchMean[1] / marchMean[0]);
      albedoRatios.push_back(line);
    }
  }
  std::printf("\nImage at albedo 0.9 over image at albedo 1 (means over the footprint):\n\n"
              "| field | light | path tracer | march (defaults) |\n|---|---|---|---|\n");
  for (const std::string& line : albedoRatios)
    std::printf("%s\n", line.c_str());
  std::printf("\nmarch (defaults) with light volumes against the nested light march (the "
              "nested image as the reference):\n\n| field | light | albedo | relative RMSE | "
              "bias | max error / peak |\n|---|---|---|---|---|---|\n");
  for (const std::string& line : settingDifferences)
    std::printf("%s\n", line.c_str());
  return 0;
}

// ---- bounces ----

// The light the bounce cap drops: the same paths (same seed) with the cap and with no cap in
// practice (2^24) differ only by the paths that reach the cap, so the difference of the image
// means (of the green channel, over all pixels) is that loss, nearly free of noise.
int Bounces(const Options& options)
{
  std::printf("%d x %d, %d paths per pixel; loss = 1 - mean(cap) / mean(no cap)\n\n",
    options.Width,
    options.Height,
    options.Samples);
  std::printf("| scene | cap | image mean | loss | relative standard error of the image mean | "
              "time |\n"
              "|---|---|---|---|---|---|\n");
  std::vector<BenchScene> fields = ErrorFields();
  fields.push_back(ReadBenchScene("data/scenes/two-lights.json"));
  fields.back().Name = "two-lights";
  for (const BenchScene& errorField : fields)
  {
    // Albedo 1: the longest paths. two-lights.json keeps its lights, the others are side-lit.
    const Scene scene = Relit(errorField.Spec,
      errorField.Name == "two-lights" ? errorField.Spec.Lights
                                      : std::vector<Light>{ LightToward({ 1.0f, 0.0f, 0.0f }) },
      1.0f);
    const vtkSmartPointer<vtkImageData> field = FieldOf(scene);
    double uncapped = 0.0;
    for (int cap : { 1 << 24, 8, 16, 32, 64, 128, 1024 })
    {
      const Rendered image = Run(NewTracer(scene, field, cap, options));
      // The green channel's mean over all pixels, and its standard error (pixels independent).
      double mean = 0.0, variance = 0.0;
      const std::size_t pixels = image.RGBA.size() / 4;
      for (std::size_t p = 0; p < pixels; ++p)
      {
        mean += image.RGBA[4 * p + 1] / double(pixels);
        variance += image.Variance[4 * p + 1] / (double(pixels) * double(pixels));
      }
      if (cap == (1 << 24))
        uncapped = mean;
      std::printf("| %s | %d | %.5f | %.2e | %.2e | %.1f s |\n",
        errorField.Name.c_str(),
        cap,
        mean,
        1.0 - mean / uncapped,
        std::sqrt(variance) / mean,
        image.Seconds);
      std::fflush(stdout);
    }
  }
  return 0;
}

} // namespace bench
} // namespace cloudvis
