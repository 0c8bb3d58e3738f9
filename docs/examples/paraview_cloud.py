"""cloudvis in ParaView from Python (docs/paraview.md): make a cloud with the Cloud Density
source, draw it with the Cloud Volume representation under a low sun, and save a screenshot.

    pvpython docs/examples/paraview_cloud.py PLUGIN OUTPUT.png
    mpirun -np 4 pvbatch docs/examples/paraview_cloud.py PLUGIN OUTPUT.png

PLUGIN is the plugin's CloudVis.so (build/paraview/lib/paraview-5.11/plugins/CloudVis/CloudVis.so
after `make`); pvpython and pvbatch need PYTHONPATH=build/paraview-prefix/python/usr/lib/python3/dist-packages.
"""
import sys

from paraview import simple

plugin, output = sys.argv[1], sys.argv[2]
simple.LoadPlugin(plugin, remote=False, ns=vars(simple))

# The field: the default cloud (a unit sphere plus value-noise fBm) over [-2, 2]^3.
cloud = simple.CloudDensity(Dimensions=[128, 128, 128])

view = simple.CreateView("RenderView")
view.ViewSize = [640, 480]
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [0.32, 0.45, 0.65]

display = simple.Show(cloud, view)
display.SetRepresentationType("Cloud Volume")
simple.ColorBy(display, ("POINTS", "density"))

# The transfer function, as in ParaView's editor: white cloud, opacity per 0.1 world units.
color = simple.GetColorTransferFunction("density")
color.AutomaticRescaleRangeMode = "Never"
color.RGBPoints = [0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]
opacity = simple.GetOpacityTransferFunction("density")
opacity.Points = [0.0, 0.0, 0.5, 0.0, 0.05, 0.0, 0.5, 0.0, 0.5, 0.95, 0.5, 0.0]
display.ScalarOpacityUnitDistance = 0.1

# The light march under a warm, low sun and a blue sky's ambient light.
display.CloudLighting = "march"
display.CloudSunDirection = [-4, 2, 3]
display.CloudSunColor = [1.0, 0.85, 0.7]
display.CloudSunIntensity = 0.4
display.CloudAmbientColor = [0.55, 0.65, 0.85]
display.CloudAmbientStrength = 0.2
display.CloudAccumulatedFrames = 8

# The first render fits the camera to the data; then it is placed.
simple.Render(view)
view.CameraPosition = [0.0, 0.6, 5.0]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 1.0, 0.0]
simple.Render(view)
simple.SaveScreenshot(output, view, ImageResolution=[640, 480])
print("wrote %s" % output)
