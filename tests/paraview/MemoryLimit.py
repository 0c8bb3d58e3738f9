"""A field too large for one rank renders on four: with the Cloud Volume representation's
per-rank GPU memory limit (CloudMaximumGPUMemory) below what the whole field needs and above what
a quarter needs, one rank refuses it (the mapper's error names the limit; RunPvbatch.cmake checks
the output for it) and draws nothing, and four ranks draw it, the same image as without the limit
(which MpiShadow.py compares with one rank's).

Usage: pvbatch MemoryLimit.py FIELD.vti SCENE.json LIMIT_MIB"""
import sys

from paraview import servermanager, simple

import cloudvis_paraview_testing as testing

field, scene_path, limit = sys.argv[1], sys.argv[2], float(sys.argv[3])
testing.load_plugin()
scene = testing.read_scene(scene_path)
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()

reader = simple.XMLImageDataReader(FileName=[field])
view = testing.render_view(scene)
display = testing.show_cloud(reader, view, scene, scene["render"]["lighting"])
display.CloudMaximumGPUMemory = limit
simple.Render(view)
testing.save(view, "limited.png")
image = testing.read_png("limited.png")
background = scene["background"]
cloud = testing.cloud_pixels(image, background)
if ranks == 1:
    print("one rank under a %g MiB limit draws %d cloud pixels" % (limit, cloud.sum()))
    testing.check(cloud.sum() == 0, "one rank drew the field it cannot hold under a %g MiB limit" % limit)
else:
    display.CloudMaximumGPUMemory = 0
    simple.Render(view)
    testing.save(view, "unlimited.png")
    unlimited = testing.read_png("unlimited.png")
    drawn = testing.cloud_pixels(unlimited, background)
    print("%d ranks under a %g MiB limit each draw %d cloud pixels, without it %d"
          % (ranks, limit, cloud.sum(), drawn.sum()))
    testing.check(drawn.sum() > 0.05 * drawn.size, "%d ranks drew no cloud without the limit" % ranks)
    testing.check(testing.rms_levels(unlimited, image, cloud | drawn) == 0.0,
                  "%d ranks under the limit draw another image than without it" % ranks)
