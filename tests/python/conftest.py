"""Shared by the Python tests (tests/python, run by ctest as python.*): what they build their
scenes from, so each test file states only what it checks.

The tests run /usr/bin/python3 -m pytest with PYTHONPATH set to the build's package folder
(tests/python/CMakeLists.txt), as docs/python.md tells users to.
"""

import pytest
import vtk
from vtk.util.numpy_support import vtk_to_numpy

import cloudvis


class ErrorLog:
    """Collects the vtkErrorMacro messages of the objects it watches (VTK's ErrorEvent), so a
    test can assert that a refusal was reported, and in which words."""

    def __init__(self):
        self.messages = []

    def watch(self, obj):
        obj.AddObserver(vtk.vtkCommand.ErrorEvent, self._on_error)
        return obj

    def _on_error(self, caller, event, message=None):
        self.messages.append(str(message))

    _on_error.CallDataType = vtk.VTK_STRING


@pytest.fixture
def errors():
    return ErrorLog()


def sphere_field(radius=0.9, size=21, half_width=2.0, density=2.5):
    """A constant sphere of `density` centred at the origin, sampled on size^3 voxels over
    [-half_width, half_width] on each axis."""
    source = cloudvis.vtkCloudDensitySource()
    source.SetDimensions(size, size, size)
    source.SetBounds(-half_width, half_width, -half_width, half_width, -half_width, half_width)
    source.SetDensityModelToConstant()
    source.SetNoiseType(cloudvis.vtkCloudDensitySource.NoNoise)
    source.RemoveAllShapes()
    source.AddSphere(0.0, 0.0, 0.0, radius)
    source.SetDensityScale(density)
    return source


def cloud_field(size=40):
    """The article's cloud (a unit sphere plus 6 octaves of value noise) on size^3 voxels over
    [-1.6, 1.6]: soft edges, so GPU and CPU differ only by arithmetic."""
    source = cloudvis.vtkCloudDensitySource()
    source.SetDimensions(size, size, size)
    source.SetBounds(-1.6, 1.6, -1.6, 1.6, -1.6, 1.6)
    return source


def ramp_medium(full_density=1.0, opacity=0.6):
    """A vtkVolumeProperty whose opacity per unit length rises linearly with density, with a
    slightly blue albedo."""
    prop = vtk.vtkVolumeProperty()
    color = vtk.vtkColorTransferFunction()
    color.AddRGBPoint(0.0, 0.9, 0.92, 1.0)
    color.AddRGBPoint(full_density, 0.9, 0.92, 1.0)
    opacity_function = vtk.vtkPiecewiseFunction()
    opacity_function.AddPoint(0.0, 0.0)
    opacity_function.AddPoint(full_density, opacity)
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity_function)
    prop.SetScalarOpacityUnitDistance(0.5)
    return prop


def sun(renderer_or_collection):
    """One white-ish directional scene light from the upper right, added to a renderer or a
    vtkLightCollection."""
    light = vtk.vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(False)
    light.SetPosition(6.0, 8.0, 4.0)
    light.SetFocalPoint(0.0, 0.0, 0.0)
    light.SetDiffuseColor(1.0, 0.9, 0.8)
    light.SetIntensity(0.8)
    if isinstance(renderer_or_collection, vtk.vtkRenderer):
        renderer_or_collection.AddLight(light)
    else:
        renderer_or_collection.AddItem(light)
    return light


SIZE = 64  # test images are SIZE x SIZE pixels, as the C++ GPU-vs-CPU tests


class Scene:
    """A vtkCloudVolumeMapper in an ordinary offscreen VTK scene (render window, renderer,
    vtkVolume, vtkVolumeProperty), the camera looking down -z at the field's centre, and the CPU
    reference renderer given the very objects the mapper renders with, as a user would."""

    def __init__(self, field, medium, parallel=False):
        self.mapper = cloudvis.vtkCloudVolumeMapper()
        self.mapper.SetInputConnection(field.GetOutputPort())
        self.mapper.SetSampleDistance(0.05)
        self.mapper.JitterOff()
        self.volume = vtk.vtkVolume()
        self.volume.SetMapper(self.mapper)
        self.volume.SetProperty(medium)
        self.renderer = vtk.vtkRenderer()
        self.renderer.SetBackground(0.0, 0.0, 0.0)
        self.renderer.AddVolume(self.volume)
        self.renderer.AutomaticLightCreationOff()
        sun(self.renderer)
        self.window = vtk.vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.SetMultiSamples(0)
        self.window.SetSize(SIZE, SIZE)
        self.window.AddRenderer(self.renderer)
        camera = self.renderer.GetActiveCamera()
        camera.SetFocalPoint(0.0, 0.0, 0.0)
        camera.SetPosition(0.0, 0.0, 6.0)
        camera.SetViewUp(0.0, 1.0, 0.0)
        camera.SetViewAngle(30.0)
        camera.SetParallelProjection(parallel)
        camera.SetParallelScale(1.6)
        camera.SetClippingRange(0.1, 22.0)

    def render(self):
        """Renders the window; returns the mapper's float image (premultiplied RGBA, SIZE^2 x 4)
        and the window's 8-bit RGB pixels (SIZE^2 x 3)."""
        self.window.Render()
        image = vtk.vtkImageData()
        rgba = None
        if self.mapper.ReadImage(self.renderer, image):
            rgba = vtk_to_numpy(image.GetPointData().GetScalars()).copy()
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.ReadFrontBufferOff()
        grab.Update()
        pixels = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).copy()
        return rgba, pixels

    def reference(self):
        """The CPU reference of the same scene: SIZE^2 x 4 premultiplied RGBA floats."""
        camera = self.renderer.GetActiveCamera()
        reference = cloudvis.vtkCloudReferenceRenderer()
        reference.SetInputConnection(self.mapper.GetInputConnection(0, 0))
        reference.SetImageSize(SIZE, SIZE)
        reference.SetCameraPosition(camera.GetPosition())
        reference.SetCameraFocalPoint(camera.GetFocalPoint())
        reference.SetCameraViewUp(camera.GetViewUp())
        reference.SetViewAngle(camera.GetViewAngle())
        reference.SetParallelProjection(bool(camera.GetParallelProjection()))
        reference.SetParallelScale(camera.GetParallelScale())
        reference.SetClippingRange(camera.GetClippingRange())
        reference.SetVolumeMatrix(self.volume.GetMatrix())
        reference.SetVolumeProperty(self.volume.GetProperty())
        reference.SetExtinctionScale(self.mapper.GetExtinctionScale())
        reference.SetLightingProperty(self.mapper.GetLightingProperty())
        reference.SetLights(self.renderer.GetLights())
        reference.SetSampleDistance(self.mapper.GetSampleDistance())
        reference.Update()
        return vtk_to_numpy(reference.GetOutput().GetPointData().GetScalars()).copy()

    def on_llvmpipe(self):
        return "llvmpipe" in self.window.ReportCapabilities()
