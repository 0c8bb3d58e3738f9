"""A field too large for one rank renders on four: with the Cloud Volume representation's
per-rank GPU memory limit (CloudMaximumGPUMemory) below what the whole field needs and above what
a quarter needs, one rank refuses it (the mapper's error names the limit; RunPvbatch.cmake checks
the output for it) and draws nothing, and four ranks draw it as one rank draws it without the
limit.

Usage: pvbatch MemoryLimit.py FIELD.vti SCENE.json LIMIT_MIB REFERENCE.png"""
import sys

from paraview import servermanager, simple

import cloudvis_paraview_testing as testing

field, scene_path, limit, reference = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
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
    one = testing.read_png(reference)
    cloud |= testing.cloud_pixels(one, background)
    rms = testing.rms_levels(one, image, cloud)
    print("%d ranks under a %g MiB limit each: RMS difference from one rank without it %.3f levels"
          % (ranks, limit, rms))
    testing.check(rms <= 1.0, "%d ranks under the limit differ from one rank by %.3f RMS levels" % (ranks, rms))
