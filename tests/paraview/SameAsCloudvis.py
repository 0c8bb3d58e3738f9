"""pvbatch on one rank draws what `cloudvis render` draws: the same field (a .vti that cloudvis
generates from the scene), camera, transfer function and lights, rendered by the Cloud Volume
representation and by cloudvis, differ by at most 1 RMS 8-bit level over the cloud's pixels.

Usage: pvbatch SameAsCloudvis.py SCENE.json MODEL"""
import sys

from paraview import simple

import cloudvis_paraview_testing as testing

scene_path, model = sys.argv[1], sys.argv[2]
testing.load_plugin()
scene = testing.read_scene(scene_path)
testing.run_cloudvis("generate", scene_path, "-o", "field.vti")
testing.run_cloudvis("render", scene_path, "--lighting", model, "-o", "cloudvis.png", "-q")

reader = simple.XMLImageDataReader(FileName=["field.vti"])
view = testing.render_view(scene)
testing.show_cloud(reader, view, scene, model)
simple.Render(view)
testing.save(view, "paraview.png")

cloudvis = testing.read_png("cloudvis.png")
paraview = testing.read_png("paraview.png")
background = scene["background"]
cloud = testing.cloud_pixels(cloudvis, background) | testing.cloud_pixels(paraview, background)
testing.check(cloud.sum() > 0.05 * cloud.size, "%s: the cloud covers only %d pixels" % (model, cloud.sum()))
rms = testing.rms_levels(cloudvis, paraview, cloud)
print("%s: %d cloud pixels, RMS difference %.3f levels" % (model, cloud.sum(), rms))
testing.check(rms <= 1.0, "%s: ParaView's image differs from cloudvis's by %.3f RMS levels (at most 1)" % (model, rms))
