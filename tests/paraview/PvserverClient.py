"""The client half of paraview.pvserver.two_ranks (pvserver_client.py starts the server): pvpython
connects to `mpirun -np 2 pvserver`, loads the plugin on both sides, makes a Cloud Density source
on the server, draws it as a Cloud Volume with the march and saves a screenshot, which must show
the cloud.

Usage: pvpython PvserverClient.py PORT OUTPUT.png"""
import sys

from paraview import servermanager, simple

import cloudvis_paraview_testing as testing

port, output = int(sys.argv[1]), sys.argv[2]
simple.Connect("localhost", port)
# The client builds the proxies and the panel, the server's ranks run the classes: both load it.
simple.LoadPlugin(testing.PLUGIN, remote=False, ns=vars(simple))
simple.LoadPlugin(testing.PLUGIN, remote=True, ns=vars(simple))
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
testing.check(ranks == 2, "the server has %d ranks, not 2" % ranks)

source = simple.CloudDensity(Dimensions=[48, 48, 48])
scene = testing.white_cloud_scene([160, 120], 7)
view = testing.render_view(scene)
testing.show_cloud(source, view, scene, "march")
simple.Render(view)
testing.save(view, output)
cloud = testing.cloud_pixels(testing.read_png(output), scene["background"])
print("%d server ranks drew %d cloud pixels" % (ranks, cloud.sum()))
testing.check(cloud.sum() > 0.05 * cloud.size, "the server's ranks drew no cloud")
simple.Disconnect()
