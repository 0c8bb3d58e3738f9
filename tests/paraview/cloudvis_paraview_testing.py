"""What the ParaView plugin's tests share: loading the plugin, showing a field as a scene file
describes it (transfer function, camera, lights, background), and comparing images.

The scripts run under pvbatch (tests/paraview/RunPvbatch.cmake), which puts the plugin's path,
the cloudvis binary and the source tree in the environment."""
import json
import os
import subprocess
import sys

import numpy
from paraview import simple
from paraview.modules.vtkRemotingCore import vtkProcessModule
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

PLUGIN = os.environ["CLOUDVIS_PARAVIEW_PLUGIN"]
CLOUDVIS = os.environ.get("CLOUDVIS", "")
SOURCE_DIR = os.environ.get("CLOUDVIS_SOURCE_DIR", "")

LIGHTING_MODELS = ["none", "derivative", "march", "pathtrace"]


def load_plugin():
    """Loads the plugin into this process (pvbatch: every rank) and adds its proxies
    (CloudDensity, ...) to paraview.simple."""
    simple.LoadPlugin(PLUGIN, remote=False, ns=vars(simple))


def rank():
    return vtkProcessModule.GetProcessModule().GetPartitionId()


def ranks():
    return vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()


def fail(message):
    """Ends the test: the message on stderr, status 1 (on every rank, so mpirun ends)."""
    sys.stderr.write("FAIL: %s\n" % message)
    sys.stderr.flush()
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)


def run_cloudvis(*args):
    """Runs the cloudvis binary; its failure fails the test with its output."""
    result = subprocess.run([CLOUDVIS, *args], capture_output=True, text=True)
    if result.returncode != 0:
        fail("cloudvis %s exited %d:\n%s%s" % (" ".join(args), result.returncode, result.stdout,
                                              result.stderr))
    return result


def read_scene(path):
    with open(path) as f:
        return json.load(f)


def white_cloud_scene(size, distance):
    """A plain scene for the tests that only need a cloud on the screen: a white cloud, opaque
    at density 1 per 0.1 world units, the default sun, a black background, the camera on +z at
    `distance`, one unjittered frame of `size` pixels."""
    return {
        "render": {"size": size, "jitter": False, "accumulate": 1},
        "camera": {"position": [0, 0, distance]},
        "background": [0, 0, 0],
        "transfer_function": {"opacity": [[0, 0], [1, 1]], "color": [[0, 1, 1, 1], [1, 1, 1, 1]],
                              "unit_distance": 0.1},
        "lights": [{"position": [6, 8, 4]}],
    }


def render_view(scene):
    """A render view as the scene's render, camera and background sections say."""
    view = simple.CreateView("RenderView")
    width, height = scene["render"]["size"]
    view.ViewSize = [width, height]
    view.OrientationAxesVisibility = 0
    set_view(view, scene)
    return view


def set_view(view, scene):
    """The scene's background and camera on a view (pvbatch's, or the GUI's own, whose size is
    the window's)."""
    view.UseColorPaletteForBackground = 0
    view.Background = scene.get("background", [0, 0, 0])
    # The camera is the scene's, not the one ParaView's first render would fit to the data.
    simple._DisableFirstRenderCameraReset()
    camera = scene["camera"]
    view.CameraPosition = camera["position"]
    view.CameraFocalPoint = camera.get("focal_point", [0, 0, 0])
    view.CameraViewUp = camera.get("view_up", [0, 1, 0])
    view.CameraViewAngle = camera.get("view_angle", 30)
    view.CameraParallelProjection = 0


def show_cloud(source, view, scene, lighting):
    """Shows `source` as a Cloud Volume with the scene's transfer function, sun, ambient light
    and render settings, lit by `lighting`."""
    display = simple.Show(source, view)
    display.SetRepresentationType("Cloud Volume")
    simple.ColorBy(display, ("POINTS", "density"))
    transfer = scene["transfer_function"]
    lut = simple.GetColorTransferFunction("density")
    lut.AutomaticRescaleRangeMode = "Never"
    lut.ColorSpace = "RGB"
    lut.Discretize = 0
    lut.RGBPoints = [value for point in transfer["color"] for value in point]
    opacity = simple.GetOpacityTransferFunction("density")
    opacity.Points = [value for x, a in transfer["opacity"] for value in (x, a, 0.5, 0.0)]
    display.ScalarOpacityUnitDistance = transfer.get("unit_distance", 1.0)

    display.CloudLighting = lighting
    lights = scene.get("lights", [])
    if lights:
        sun = lights[0]
        focal = sun.get("focal_point", [0, 0, 0])
        display.CloudSunDirection = [p - f for p, f in zip(sun["position"], focal)]
        display.CloudSunColor = sun.get("color", [1, 1, 1])
        display.CloudSunIntensity = sun.get("intensity", 1)
    ambient = scene.get("ambient", {})
    display.CloudAmbientColor = ambient.get("color", [1, 1, 1])
    display.CloudAmbientStrength = ambient.get("strength", 0)
    render = scene.get("render", {})
    march = render.get("march", {})
    display.CloudLightSteps = march.get("light_steps", 6)
    display.CloudTransmittance = march.get("transmittance", "volumes")
    display.CloudPhaseG1 = march.get("g1", 0.6)
    display.CloudPhaseG2 = march.get("g2", -0.3)
    display.CloudPhaseLobeWeight = march.get("lobe_weight", 0.8)
    display.CloudPhase = march.get("phase", "two_lobe")
    display.CloudDropletEffectiveRadius = march.get("effective_radius", 10)
    display.CloudDropletEffectiveVariance = march.get("effective_variance", 0.1)
    display.CloudMultipleScattering = march.get("multiple_scattering", "volume")
    display.CloudOctaves = march.get("octaves", 3)
    display.CloudSampleDistance = render.get("step", 0)
    display.CloudJitter = 1 if render.get("jitter", True) else 0
    display.CloudAccumulatedFrames = render.get("accumulate", 1)
    return display


def save(view, path):
    width, height = view.ViewSize
    simple.SaveScreenshot(path, view, ImageResolution=[width, height])


def read_png(path):
    """An image file as a height x width x 3 float array of 8-bit levels, top row first."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).astype(numpy.float64)
    pixels = pixels.reshape(height, width, -1)[::-1, :, :3]
    return pixels


def cloud_pixels(image, background, margin=2.0):
    """The pixels where the image is not the plain background (by more than `margin` levels in
    some channel)."""
    levels = numpy.asarray(background, dtype=numpy.float64) * 255.0
    return numpy.abs(image - levels).max(axis=2) > margin


def rms_levels(a, b, mask):
    """Root mean square difference over the masked pixels, in 8-bit levels per channel."""
    difference = (a - b)[mask]
    return float(numpy.sqrt(numpy.mean(difference * difference)))
