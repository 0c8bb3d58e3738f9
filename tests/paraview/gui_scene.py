"""Runs inside ParaView's GUI (`paraview --script=gui_scene.py`, started by paraview_gui.py), in
the GUI's own Python: what a user does by hand, in the same proxies the GUI's panels show. It
loads the plugin, makes a Cloud Density source, shows it in the render view as a Cloud Volume lit
by the light march, and writes the file named by CLOUDVIS_GUI_READY when done.

CLOUDVIS_GUI_SCENE picks the scene: `check` (the test's: a yellow cloud on pure blue, no
orientation axes, so that paraview_gui.py can find it on the screen) or `picture` (the docs')."""
import os

from paraview import simple

import cloudvis_paraview_testing as testing

SCENES = {
    "check": {
        "source": {"Dimensions": [48, 48, 48]},
        "render": {"jitter": False, "accumulate": 1},
        "camera": {"position": [0, 0, 8]},
        "background": [0, 0, 1],
        "transfer_function": {"opacity": [[0, 0], [1, 1]],
                              "color": [[0, 1, 1, 0], [1, 1, 1, 0]], "unit_distance": 0.1},
        "lights": [{"position": [6, 8, 4]}],
        "orientation_axes": False,
    },
    "picture": {
        "source": {"Dimensions": [128, 128, 128]},
        "render": {"jitter": True, "accumulate": 16},
        "camera": {"position": [3.8, 1.7, 6.6], "focal_point": [0, -0.05, 0], "view_angle": 30},
        "background": [0.36, 0.52, 0.74],
        "transfer_function": {"opacity": [[0, 0], [0.05, 0], [1, 1]],
                              "color": [[0, 0.95, 0.95, 0.95], [1, 0.95, 0.95, 0.95]],
                              "unit_distance": 0.07},
        "lights": [{"position": [4, 6, 2], "color": [1, 0.96, 0.9], "intensity": 0.9}],
        "ambient": {"color": [0.6, 0.75, 1], "strength": 0.25},
        "orientation_axes": True,
    },
}

scene = SCENES[os.environ["CLOUDVIS_GUI_SCENE"]]
testing.load_plugin()
source = simple.CloudDensity(**scene["source"])
simple.RenameSource("Cloud Density", source)
view = simple.GetActiveViewOrCreate("RenderView")
testing.set_view(view, scene)
view.OrientationAxesVisibility = 1 if scene["orientation_axes"] else 0
testing.show_cloud(source, view, scene, "march")
# The Properties panel shows the active source and its display in the active view.
simple.SetActiveView(view)
simple.SetActiveSource(source)
simple.Render(view)
with open(os.environ["CLOUDVIS_GUI_READY"], "w") as ready:
    ready.write("shown\n")
