// What the viewer saves: the screenshot of its layout (s), the scene as the window shows it (w,
// --save-scene-on-exit; with its "view" section, which the viewer applies when it opens the scene
// again) and the window's pixels (--window-image).
//
// A screenshot is what ParaView's "Save Screenshot" of a layout gives: every view of the layout
// (the 3D view alone, or the four views) with what is drawn in them (slices, crosshairs,
// captions, outline, orientation marker) and the color legends, at a chosen resolution, without
// the application around the views (here the transfer-function editor and the viewer's own texts:
// message, hint, help, readout). It is rendered off screen at its own size, as VTK's
// vtkResizingWindowToImageFilter does: with UseOffScreenBuffers on and buffers not swapped, VTK
// renders into its own framebuffer at the size vtkRenderWindow::SetSize gave it (without the X
// window's resize), and the screen keeps the window's size and picture.
#include "ViewerInternals.h"

#include "AtomicFile.h"
#include "Errors.h"
#include "ExportRender.h"
#include "ImageWriters.h"
#include "SceneJson.h"
#include "ViewerFiles.h"

#include <vtkCamera.h>

#include <algorithm>
#include <cmath>

namespace cloudvis
{

std::array<int, 2> Viewer::Internals::ScreenshotSize() const
{
  if (this->Options.ScreenshotSize[0] > 0 && this->Options.ScreenshotSize[1] > 0)
  {
    return this->Options.ScreenshotSize;
  }
  const int* size = const_cast<vtkRenderWindow*>(this->Window.Get())->GetSize();
  return { { size[0], size[1] - this->PixelViewport(this->Editor)[3] } };
}

ScreenshotImages Viewer::Internals::CaptureLayout(const std::array<int, 2>& size, bool floatImage)
{
  vtkRenderWindow* window = this->Window;
  const int* shown = window->GetSize();
  const std::array<int, 2> windowSize{ { shown[0], shown[1] } };
  // Texts scale with the picture, as ParaView scales fonts with a screenshot's resolution.
  const double fontScale =
    double(size[1]) / double(std::max(1, windowSize[1] - this->PixelViewport(this->Editor)[3]));

  // Everything put back however the capture ends.
  struct Restore
  {
    Internals& In;
    vtkRenderWindow* Window;
    std::array<int, 2> Size;
    StatusOverlay::Visibility Texts;
    double ScatteringSeconds;
    ~Restore()
    {
      this->In.Mapper->SetScatteringVolumeSecondsPerFrame(this->ScatteringSeconds);
      this->Window->vtkRenderWindow::SetSize(this->Size[0], this->Size[1]);
      this->Window->SetUseOffScreenBuffers(false);
      this->Window->SwapBuffersOn();
      this->In.Exporting = false;
      SetColorBarFontScale(this->In.Legend, 1.0);
      SetColorBarFontScale(this->In.Colors->GetColorBar(), 1.0);
      this->In.ApplyLayout();
      this->In.Status->Restore(this->Texts);
      this->In.Request(); // the window's own frame again
    }
  } restore{ *this,
    window,
    windowSize,
    this->Status->HideAll(),
    this->Mapper->GetScatteringVolumeSecondsPerFrame() };

  // A multiple-scattering volume still converging (ScatteringVolumeSecondsPerFrame) is finished
  // in the capture's first frame: the picture saved is the converged one.
  this->Mapper->SetScatteringVolumeSecondsPerFrame(0.0);

  this->Exporting = true;
  window->SetUseOffScreenBuffers(true);
  window->SwapBuffersOff();
  window->vtkRenderWindow::SetSize(size[0], size[1]);
  SetColorBarFontScale(this->Legend, fontScale);
  SetColorBarFontScale(this->Colors->GetColorBar(), fontScale);
  this->ApplyLayout();
  window->SetDesiredUpdateRate(this->Interactor->GetStillUpdateRate());
  const int frames = this->FramesToConverge();
  window->Render();
  for (int i = 0; i < frames + 1 && this->Mapper->GetNumberOfAccumulatedFrames(this->View) < frames;
       ++i)
  {
    window->Render();
  }
  if (!this->Mapper->GetLastError().empty())
  {
    throw InputError("screenshot: " + this->Mapper->GetLastError());
  }
  // The window's exposure, so that the picture is the window's. An automatic one the window has
  // not metered yet (its still had not converged) is metered on the capture's converged still,
  // as the window's will be.
  if (this->Current.Render.AutoExposure && !this->ExposureMetered && this->MeterExposure())
  {
    window->Render();
  }
  ScreenshotImages images;
  try
  {
    images.Layout = GrabWindow(window);
    if (floatImage)
    {
      double viewport[4];
      this->View->GetViewport(viewport);
      images.Cloud = GrabWindow(window, viewport);
    }
  }
  catch (const InputError&)
  {
    throw InputError("screenshot: could not read the " + std::to_string(size[0]) + " x " +
      std::to_string(size[1]) + " image back from the window");
  }
  if (images.Layout.Width != size[0] || images.Layout.Height != size[1])
  {
    throw InputError("screenshot: the window gave " + std::to_string(images.Layout.Width) + " x " +
      std::to_string(images.Layout.Height) + " pixels, not the " + std::to_string(size[0]) + " x " +
      std::to_string(size[1]) + " asked for");
  }
  if (floatImage)
  {
    window->MakeCurrent();
    ReadFloatImage(this->Mapper, this->View, images.Cloud, "screenshot");
  }
  // What the PNG's pixels went through, and what the EXR records (its radiance stays linear).
  for (RenderedImage* image : { &images.Layout, &images.Cloud })
  {
    image->ExposureEV = this->Mapper->GetExposureEV();
    image->Display = this->Current.Render.Display;
  }
  return images;
}

ViewSpec Viewer::Internals::CurrentView() const
{
  ViewSpec view;
  view.Layout = this->FourViews ? ViewLayout::Four : ViewLayout::ThreeD;
  std::array<double, 3> position;
  for (int axis = 0; axis < 3; ++axis)
  {
    view.Slices[size_t(axis)] = this->Slices->GetSliceVisible(axis);
    position[size_t(axis)] = this->Slices->GetSlicePosition(axis);
  }
  view.SlicePosition = position;
  view.Oblique.Visible = this->Slices->GetObliqueVisible();
  view.Oblique.Origin = this->Slices->GetObliqueOrigin();
  view.Oblique.Normal = this->Slices->GetObliqueNormal();
  view.WindowLevel = this->Colors->GetWindowLevel();
  view.SliceColors = int(this->Colors->GetColormapIndex());
  view.Legends = this->LegendsVisible;
  return view;
}

void Viewer::Internals::ApplyView(const ViewSpec& view)
{
  this->FourViews = view.Layout == ViewLayout::Four;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (view.SlicePosition)
    {
      this->Slices->SetSlicePosition(axis, (*view.SlicePosition)[size_t(axis)]);
    }
    this->Slices->SetSliceVisible(axis, view.Slices[size_t(axis)]);
  }
  this->Slices->SetObliquePlane(
    view.Oblique.Origin.value_or(this->Slices->GetObliqueOrigin()), view.Oblique.Normal);
  this->Slices->SetObliqueVisible(view.Oblique.Visible);
  if (view.WindowLevel)
  {
    this->Colors->SetWindowLevel((*view.WindowLevel)[0], (*view.WindowLevel)[1]);
  }
  this->Colors->SetColormap(size_t(view.SliceColors));
  this->LegendsVisible = view.Legends;
  this->Views2D->Update();
  this->ApplyLayout(); // places the legends too
}

Scene Viewer::CurrentScene() const
{
  const Internals& in = *this->Internal;
  Scene scene = in.Current;
  scene.TransferFunction = TransferFunctionOf(in.Property);
  scene.Render.Size = in.ViewSize();
  vtkCamera* camera = const_cast<vtkRenderer*>(in.View.Get())->GetActiveCamera();
  std::array<double, 3> position, focal, up;
  camera->GetPosition(position.data());
  camera->GetFocalPoint(focal.data());
  camera->GetViewUp(up.data());
  scene.Camera.Position = position;
  scene.Camera.FocalPoint = focal;
  scene.Camera.ViewUp = up;
  scene.Camera.Orbit.reset();
  scene.Camera.ViewAngle = camera->GetViewAngle();
  scene.View = in.CurrentView();
  return scene;
}

nlohmann::json Viewer::CurrentSceneJson() const
{
  const Scene scene = this->CurrentScene();
  ResolvedCamera camera;
  camera.Position = *scene.Camera.Position;
  camera.FocalPoint = *scene.Camera.FocalPoint;
  camera.ViewUp = scene.Camera.ViewUp;
  return SceneToJson(scene, camera);
}

void Viewer::SaveScene(const std::string& path) const
{
  WriteTextFile(path, this->CurrentSceneJson().dump(2) + "\n", "the scene");
}

void Viewer::SaveScreenshot()
{
  Internals& in = *this->Internal;
  // The capture renders render.accumulate frames of every view (seconds for a large picture):
  // say so on screen, and in the state, before the work starts.
  in.Show("saving a screenshot ...", false);
  in.RenderFrame();
  this->WriteStateFile();
  try
  {
    const bool floatImage = in.Current.Render.ResolutionScale >= 1.0;
    const std::array<int, 2> size = in.ScreenshotSize();
    const std::vector<std::string> paths = WriteScreenshot(
      in.Options.OutputDirectory,
      floatImage,
      [&] { return in.CaptureLayout(size, floatImage); },
      this->CurrentSceneJson().dump(-1, ' ', true),
      in.Options.CommandLine);
    in.SavedFiles.insert(in.SavedFiles.end(), paths.begin(), paths.end());
    const std::string pixels = std::to_string(size[0]) + " x " + std::to_string(size[1]);
    if (!floatImage)
    {
      in.Show("saved " + paths[0] + " (" + pixels +
          "); no EXR: the float image needs resolution scale 1 (press ])",
        true);
      return;
    }
    in.Show("saved " + paths[0] + " (" + pixels + ") and " + paths[1] + " (the 3D view)", false);
  }
  catch (const std::exception& e)
  {
    in.Show(e.what(), true);
  }
}

void Viewer::SaveWindowImage(const std::string& path)
{
  Internals& in = *this->Internal;
  in.RenderFrame();
  const RenderedImage image = GrabWindow(in.Window);
  WriteImage(image, path);
}

void Viewer::SaveSceneFile()
{
  Internals& in = *this->Internal;
  try
  {
    const std::string path =
      NextFreeBase(in.Options.OutputDirectory, "cloudvis-view-", { ".json" }) + ".json";
    CheckOutputTarget(path);
    this->SaveScene(path);
    in.SavedEdits = in.EditsOf(*this);
    in.SavedFiles.push_back(path);
    in.Show("saved " + path + " (cloudvis render " + path + " -o IMAGE.png)", false);
  }
  catch (const std::exception& e)
  {
    in.Show(e.what(), true);
  }
}

} // namespace cloudvis
