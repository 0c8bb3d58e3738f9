// The models are timed one at a time in the full window (the others hidden), so a panel's time is
// what `render --benchmark` would report for that model at render.size, plus the clearing of the
// other viewports; the picture itself is rendered with every panel visible, after the timing, so
// the labels can carry the times.
#include "Compare.h"

#include "Background.h"
#include "CpuReference.h"
#include "Display.h"
#include "Errors.h"
#include "ExportRender.h"
#include "FieldCoarsening.h"
#include "SceneLighting.h"
#include "VtkMessageCapture.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkImageActor.h>
#include <vtkImageData.h>
#include <vtkImageMapper3D.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

namespace cloudvis
{
namespace
{

struct Panel
{
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkCloudVolumeMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkTextActor> Label;
};

// A label in the top-left corner of its viewport, readable on any background.
void PlaceLabel(vtkTextActor* label, vtkRenderer* renderer, int height)
{
  const int fontSize = std::max(10, std::min(24, height / 20));
  vtkTextProperty* text = label->GetTextProperty();
  text->SetFontSize(fontSize);
  text->SetColor(1.0, 1.0, 1.0);
  text->ShadowOn();
  text->SetVerticalJustificationToTop();
  label->SetPosition(0.5 * fontSize, height - 0.5 * fontSize);
  renderer->AddActor2D(label);
}

std::string FormatMilliseconds(double ms)
{
  char text[32];
  std::snprintf(text, sizeof(text), ms < 10.0 ? "%.2f ms" : ms < 100.0 ? "%.1f ms" : "%.0f ms", ms);
  return text;
}

// The ramp of the difference panel: t in [0, 1] (clamped) to RGB in [0, 1].
std::array<double, 3> DifferenceColor(double t)
{
  // Dark where the models agree, bright where they differ; monotonic in lightness.
  static const double stops[][3] = { { 0.0, 0.0, 0.0 },
    { 0.27, 0.05, 0.45 },
    { 0.80, 0.20, 0.30 },
    { 1.0, 0.62, 0.10 },
    { 1.0, 1.0, 0.75 } };
  const int last = int(sizeof(stops) / sizeof(stops[0])) - 1;
  const double x = std::min(1.0, std::max(0.0, std::isfinite(t) ? t : 0.0)) * last;
  const int i = std::min(last - 1, int(x));
  const double f = x - i;
  return { stops[i][0] + f * (stops[i + 1][0] - stops[i][0]),
    stops[i][1] + f * (stops[i + 1][1] - stops[i][1]),
    stops[i][2] + f * (stops[i + 1][2] - stops[i][2]) };
}

// The difference image of two float radiances (premultiplied RGBA, same size): per pixel the
// largest |A - B| over r, g, b, colored through DifferenceColor scaled to the largest difference.
vtkSmartPointer<vtkImageData> DifferenceImage(const std::vector<float>& a,
  const std::vector<float>& b, int width, int height, double& largest)
{
  const size_t pixels = size_t(width) * size_t(height);
  std::vector<double> difference(pixels, 0.0);
  largest = 0.0;
  for (size_t i = 0; i < pixels; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      difference[i] = std::max(difference[i], double(std::abs(a[4 * i + c] - b[4 * i + c])));
    }
    largest = std::max(largest, difference[i]);
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* rgb = static_cast<unsigned char*>(image->GetScalarPointer());
  for (size_t i = 0; i < pixels; ++i)
  {
    const std::array<double, 3> color = DifferenceColor(largest > 0.0 ? difference[i] / largest : 0.0);
    for (int c = 0; c < 3; ++c)
    {
      rgb[3 * i + c] = static_cast<unsigned char>(std::lround(255.0 * color[c]));
    }
  }
  return image;
}

// A panel's float image, and with `variance` the variance of its means (a path-traced panel).
void ReadPanel(Panel& panel,
  const std::string& input,
  std::vector<float>& rgba,
  std::vector<float>* variance,
  int& width,
  int& height)
{
  int varianceWidth = 0, varianceHeight = 0;
  if (!panel.Mapper->ReadImage(panel.Renderer, rgba, width, height) ||
    (variance &&
      (!panel.Mapper->ReadVariance(panel.Renderer, *variance, varianceWidth, varianceHeight) ||
        varianceWidth != width || varianceHeight != height)))
  {
    throw InputError(input + ": could not read the panels' images back to measure their errors");
  }
}

// Each model's error against the reference panel, into `result` and onto the labels.
void MeasureAgainstReference(std::vector<std::unique_ptr<Panel>>& panels,
  size_t referencePanel,
  const std::string& input,
  ComparisonResult& result)
{
  std::vector<float> reference, variance;
  int width = 0, height = 0;
  ReadPanel(*panels[referencePanel], input, reference, &variance, width, height);
  const size_t pixels = size_t(width) * size_t(height);
  result.ReferenceNoise = MeasureImageNoise(reference.data(), variance.data(), pixels);
  result.ReferenceSamples =
    panels[referencePanel]->Mapper->GetNumberOfAccumulatedSamples(panels[referencePanel]->Renderer);
  char target[48] = "";
  if (result.ReferenceTarget)
  {
    std::snprintf(target,
      sizeof(target),
      " (target %.2g%%)",
      100.0 * result.ReferenceTarget->Target.RelativeStandardError);
  }
  char text[200];
  std::snprintf(text,
    sizeof(text),
    "%s  %s\nreference: %d paths/pixel, noise %.2g%%%s",
    result.Names[referencePanel].c_str(),
    FormatMilliseconds(result.Milliseconds[referencePanel]).c_str(),
    result.ReferenceSamples,
    100.0 * result.ReferenceNoise.RelativeStandardError,
    target);
  panels[referencePanel]->Label->SetInput(text);
  for (size_t i = 0; i < referencePanel; ++i)
  {
    std::vector<float> rgba;
    int modelWidth = 0, modelHeight = 0;
    ReadPanel(*panels[i], input, rgba, nullptr, modelWidth, modelHeight);
    if (modelWidth != width || modelHeight != height)
    {
      throw InputError(input + ": the panels' images differ in size");
    }
    const ImageError error =
      CompareWithReference(rgba.data(), reference.data(), variance.data(), pixels);
    result.Errors.push_back(error);
    std::snprintf(text,
      sizeof(text),
      "%s  %s\nrRMSE %.1f%%  bias %.2f  max %.0f%%",
      result.Names[i].c_str(),
      FormatMilliseconds(result.Milliseconds[i]).c_str(),
      100.0 * error.RelativeRMSE,
      error.BiasRatio,
      100.0 * error.MaxErrorOverPeak);
    panels[i]->Label->SetInput(text);
  }
}

} // namespace

bool operator==(const ComparedLighting& a, const ComparedLighting& b)
{
  return a.Model == b.Model && a.MultipleScattering == b.MultipleScattering;
}

LightingParameters PanelLighting(const LightingParameters& scene, const ComparedLighting& panel)
{
  LightingParameters lighting = scene;
  lighting.Model = panel.Model;
  lighting.MultipleScattering = panel.MultipleScattering.value_or(scene.MultipleScattering);
  return lighting;
}

std::string PanelName(const LightingParameters& scene, const ComparedLighting& panel)
{
  const std::string model = LightingModelName(panel.Model);
  return panel.Model == LightingModel::March
    ? model + ":" + MultipleScatteringModelName(PanelLighting(scene, panel).MultipleScattering)
    : model;
}

namespace
{
// The panels' models: the compared ones, then the path tracer's when there is a reference (one
// more panel); the refusals of a comparison that cannot be drawn.
std::vector<ComparedLighting> PanelModels(const Scene& scene,
  const std::string& input,
  const std::vector<ComparedLighting>& comparedModels,
  const std::optional<std::pair<size_t, size_t>>& difference,
  const std::optional<ReferencePaths>& reference)
{
  std::vector<ComparedLighting> models = comparedModels;
  if (reference)
  {
    models.push_back({ LightingModel::PathTrace, std::nullopt });
  }
  const int width = scene.Render.Size[0];
  const int panelCount = int(models.size()) + (difference ? 1 : 0);
  if (comparedModels.empty() ||
    (difference && (difference->first >= models.size() || difference->second >= models.size())))
  {
    throw InputError(input + ": compare: no models, or a difference of models not compared");
  }
  if (double(panelCount) * width > MaximumComparisonWidth)
  {
    throw InputError(input + ": compare: " + std::to_string(panelCount) + " panels of " +
      std::to_string(width) + " pixels make a window " + std::to_string(panelCount * width) +
      " pixels wide; the most is " + std::to_string(MaximumComparisonWidth) +
      ": give a smaller --size");
  }
  return models;
}

// The comparison's window: a panel per model side by side, each with the viewport of a `render`
// of render.size, then the difference's panel when asked; every render is checked.
struct ComparisonWindow
{
  ComparisonWindow(vtkImageData* field, const std::string& input, int panelCount, int height)
    : Field(field)
    , Input(input)
    , PanelCount(panelCount)
    , Height(height)
  {
    this->Window->SetDisplayId(this->Display.Get());
    this->Window->AddObserver(vtkCommand::ExitEvent, this->OnExit); // as RenderOffscreen's
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
  }

  // Renders the window, every panel drawing one field: coarsened for all when one panel's
  // textures do not fit. Throws a mapper's error.
  void RenderChecked()
  {
    std::vector<vtkCloudVolumeMapper*> mappers;
    for (const auto& panel : this->Panels)
    {
      mappers.push_back(panel->Mapper);
    }
    this->Coarsening = RenderCoarsenedToFit(
      mappers, this->Field, this->Coarsening, [&] { this->Window->Render(); }, this->Coarsened);
    for (const auto& panel : this->Panels)
    {
      CheckMapper(panel->Mapper, this->Input, this->Messages);
    }
  }

  vtkImageData* Field;
  const std::string& Input;
  const int PanelCount;
  const int Height;
  const DisplayConnection Display{ "cloudvis compare ..." };
  VtkMessageCapture Messages;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCallbackCommand> OnExit; // no abort() without a GL context
  std::vector<std::unique_ptr<Panel>> Panels;
  vtkNew<vtkRenderer> DifferencePanel;
  vtkNew<vtkImageActor> DifferenceActor;
  vtkNew<vtkTextActor> DifferenceLabel;
  int Coarsening = 1;
  std::string Coarsened;
};

// A panel for each model, lit as the scene with the model's lighting and sharing one camera: the
// reference's accumulates its paths (or a noise target's frames), the others render.accumulate
// frames.
void AddPanels(ComparisonWindow& w,
  const Scene& scene,
  const std::vector<ComparedLighting>& models,
  const std::vector<std::string>& names,
  const std::optional<ReferencePaths>& reference)
{
  const vtkSmartPointer<vtkVolumeProperty> property = MakeVolumeProperty(scene.TransferFunction);
  vtkNew<vtkCamera> camera; // one camera for every panel
  const int frames = scene.Render.Jitter ? scene.Render.Accumulate : 1;
  for (size_t i = 0; i < models.size(); ++i)
  {
    w.Panels.push_back(std::make_unique<Panel>());
    Panel& panel = *w.Panels.back();
    panel.Renderer->SetViewport(double(i) / w.PanelCount, 0.0, double(i + 1) / w.PanelCount, 1.0);
    panel.Renderer->SetActiveCamera(camera);
    w.Window->AddRenderer(panel.Renderer);
    Scene lit = scene;
    lit.Render.Lighting = PanelLighting(scene.Render.Lighting, models[i]);
    ConfigureLighting(lit, panel.Mapper);
    ApplyBackground(lit, panel.Renderer);
    panel.Mapper->SetInputData(w.Field);
    const bool referencePanel = reference && i + 1 == models.size();
    if (referencePanel)
    {
      // Its frames: the reference's paths, or frames of a noise target's paths each.
      lit.Render.SamplesPerPixel =
        reference->Target ? NoiseTargetSamplesPerFrame : reference->SamplesPerPixel;
    }
    ConfigureMapper(panel.Mapper, lit.Render);
    if (referencePanel && reference->Target)
    {
      ConfigureNoiseTarget(panel.Mapper);
    }
    else if (!referencePanel)
    {
      panel.Mapper->SetMaximumAccumulatedFrames(frames);
    }
    panel.Volume->SetMapper(panel.Mapper);
    panel.Volume->SetProperty(property);
    panel.Renderer->AddVolume(panel.Volume);
    PlaceLabel(panel.Label, panel.Renderer, w.Height);
    panel.Label->SetInput(names[i].c_str());
  }
  // Every panel has the viewport of a `render` of render.size, so this is render's camera.
  ApplyCamera(scene.Camera, w.Field->GetBounds(), w.Panels[0]->Renderer, scene.Source);
}

// Each panel's frame time, its model alone in the full window (the others hidden), into
// `result` and onto its label; after an untimed render (shader compilation, texture uploads,
// occupancy).
void TimePanels(ComparisonWindow& w, int timingFrames, ComparisonResult& result)
{
  w.RenderChecked();
  std::vector<std::unique_ptr<Panel>>& panels = w.Panels;
  for (size_t i = 0; i < panels.size(); ++i)
  {
    for (size_t j = 0; j < panels.size(); ++j)
    {
      panels[j]->Volume->SetVisibility(i == j);
    }
    double total = 0.0;
    for (int frame = 0; frame < timingFrames; ++frame)
    {
      panels[i]->Mapper->Modified(); // else the mapper shows its converged still without marching
      const auto start = std::chrono::steady_clock::now();
      w.Window->Render();
      w.Window->WaitForCompletion();
      total += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                 .count();
      CheckMapper(panels[i]->Mapper, w.Input, w.Messages);
    }
    result.Milliseconds.push_back(timingFrames > 0 ? total / timingFrames : 0.0);
    panels[i]->Label->SetInput(
      (result.Names[i] + "  " + FormatMilliseconds(result.Milliseconds.back())).c_str());
  }
}

// The picture: every panel accumulated from the same first jitter frame until the one with the
// most frames (the reference's, usually) has them all. A noise target's reference accumulates
// with the models' frames and goes on alone after them (the converged models only composite);
// it then keeps the frames it reached.
void AccumulatePanels(ComparisonWindow& w,
  const std::optional<ReferencePaths>& reference,
  ComparisonResult& result)
{
  for (const auto& panel : w.Panels)
  {
    panel->Volume->SetVisibility(true);
    panel->Mapper->Modified();
  }
  int rendered = 0;
  if (reference && reference->Target)
  {
    Panel& traced = *w.Panels.back();
    result.ReferenceTarget = AccumulateToNoiseTarget(
      *reference->Target,
      w.Window,
      traced.Mapper,
      traced.Renderer,
      [&w] { w.RenderChecked(); },
      w.Input);
    rendered = result.ReferenceTarget->Frames;
  }
  int mostFrames = 0;
  for (const auto& panel : w.Panels)
  {
    mostFrames = std::max(mostFrames, panel->Mapper->GetMaximumAccumulatedFrames());
  }
  for (int frame = rendered; frame < mostFrames; ++frame)
  {
    w.RenderChecked();
  }
  Panel& first = *w.Panels[0];
  result.AccumulatedFrames = first.Mapper->GetNumberOfAccumulatedFrames(first.Renderer);
  if (result.AccumulatedFrames == 0)
  {
    throw InputError(NothingRenderedProblem(first.Renderer, first.Volume, w.Messages, w.Input));
  }
}

// One exposure for every panel, so that their brightness compares: an automatic one is metered
// on all the panels' pixels together, so that the brightest model keeps its highlights too.
// Returns it; `changed` when it differs from the one the panels were drawn with.
double ExposePanels(ComparisonWindow& w, const Scene& scene, bool& changed)
{
  w.Window->MakeCurrent();
  std::vector<float> metered;
  for (const auto& panel : w.Panels)
  {
    const std::vector<float> image =
      ReadCheckedMapperImage(panel->Mapper, panel->Renderer, w.Input);
    metered.insert(metered.end(), image.begin(), image.end());
  }
  CheckFieldShows(metered.data(), metered.size() / 4, w.Field, scene, w.Input);
  const double exposureEV = ResolveExposureEV(scene.Render, metered.data(), metered.size() / 4);
  changed = exposureEV != w.Panels[0]->Mapper->GetExposureEV();
  for (const auto& panel : w.Panels)
  {
    ConfigureDisplay(panel->Mapper, scene.Render, exposureEV);
  }
  return exposureEV;
}

// The difference panel: |A - B| of two panels' radiances, pixel for pixel when the march ran at
// full resolution, labelled with its largest value (into `result`).
void DrawDifference(ComparisonWindow& w,
  const std::pair<size_t, size_t>& difference,
  ComparisonResult& result)
{
  std::vector<float> a, b;
  int widthA = 0, heightA = 0, widthB = 0, heightB = 0;
  w.Window->MakeCurrent();
  Panel& panelA = *w.Panels[difference.first];
  Panel& panelB = *w.Panels[difference.second];
  if (!panelA.Mapper->ReadImage(panelA.Renderer, a, widthA, heightA) ||
    !panelB.Mapper->ReadImage(panelB.Renderer, b, widthB, heightB) || widthA != widthB ||
    heightA != heightB)
  {
    throw InputError(w.Input + ": could not read the models' images back for the difference");
  }
  const vtkSmartPointer<vtkImageData> image =
    DifferenceImage(a, b, widthA, heightA, result.MaxDifference);
  w.DifferenceActor->GetMapper()->SetInputData(image);
  w.DifferenceActor->InterpolateOff();
  w.DifferencePanel->AddActor(w.DifferenceActor);
  // The image's pixel centres are at 0 .. w - 1, so it spans [-0.5, w - 0.5]; a parallel scale
  // of half its height fills the panel, whose aspect is the image's.
  vtkCamera* flat = w.DifferencePanel->GetActiveCamera();
  flat->ParallelProjectionOn();
  flat->SetFocalPoint(0.5 * (widthA - 1), 0.5 * (heightA - 1), 0.0);
  flat->SetPosition(0.5 * (widthA - 1), 0.5 * (heightA - 1), 1.0);
  flat->SetViewUp(0.0, 1.0, 0.0);
  flat->SetParallelScale(0.5 * heightA);
  flat->SetClippingRange(0.5, 1.5);
  PlaceLabel(w.DifferenceLabel, w.DifferencePanel, w.Height);
  char text[96];
  std::snprintf(text,
    sizeof(text),
    "|%s - %s|  max %.4g",
    result.Names[difference.first].c_str(),
    result.Names[difference.second].c_str(),
    result.MaxDifference);
  w.DifferenceLabel->SetInput(text);
}
} // namespace

ComparisonResult RenderComparison(const Scene& scene,
  vtkImageData* field,
  const std::string& input,
  const std::vector<ComparedLighting>& comparedModels,
  const std::optional<std::pair<size_t, size_t>>& difference,
  int timingFrames,
  const std::optional<ReferencePaths>& reference)
{
  const std::vector<ComparedLighting> models =
    PanelModels(scene, input, comparedModels, difference, reference);
  ComparisonResult result;
  Scene checked = scene;
  for (const ComparedLighting& model : models)
  {
    checked.Render.Lighting = PanelLighting(scene.Render.Lighting, model);
    CheckSceneRenderable(checked, field, input);
    result.Names.push_back(PanelName(scene.Render.Lighting, model));
  }

  const int width = scene.Render.Size[0];
  const int height = scene.Render.Size[1];
  const int panelCount = int(models.size()) + (difference ? 1 : 0);
  ComparisonWindow w(field, input, panelCount, height);
  w.Window->SetSize(panelCount * width, height);
  AddPanels(w, scene, models, result.Names, reference);
  if (difference)
  {
    w.DifferencePanel->SetViewport(double(models.size()) / panelCount, 0.0, 1.0, 1.0);
    w.DifferencePanel->SetBackground(0.0, 0.0, 0.0);
    w.Window->AddRenderer(w.DifferencePanel);
  }

  TimePanels(w, timingFrames, result);
  AccumulatePanels(w, reference, result);
  bool exposed = false;
  const double exposureEV = ExposePanels(w, scene, exposed);
  if (reference)
  {
    MeasureAgainstReference(w.Panels, comparedModels.size(), input, result);
  }
  if (difference)
  {
    DrawDifference(w, *difference, result);
  }
  if (difference || reference || exposed)
  {
    // The model panels are converged: this frame shows them again, with the new labels and the
    // chosen exposure.
    w.RenderChecked();
  }
  result.Image = CaptureWindow(w.Window, input, w.Messages);
  result.Image.ExposureEV = exposureEV;
  result.Image.Display = scene.Render.Display;
  result.Image.Coarsened = w.Coarsened;
  return result;
}

} // namespace cloudvis
