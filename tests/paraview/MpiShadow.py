"""Light crosses the ranks' pieces: under `mpirun -np N pvbatch`, the Cloud Volume
representation draws scenes/shadow.json (a dense slab above a cloud, the sun overhead; ParaView
gives the slab and the cloud to different ranks) as one rank draws it, and the cloud lies in the
slab's shadow. With the exchange of optical depth between ranks turned off, the shadow is gone.

Usage: pvbatch MpiShadow.py FIELD.vti SCENE.json REFERENCE.png
  On one rank it writes REFERENCE.png; on more it compares with it: at most 1 RMS 8-bit level
  over the cloud's pixels with the exchange, and the cloud clearly brighter without it."""
import sys

from paraview import servermanager, simple

import cloudvis_paraview_testing as testing

field, scene_path, reference = sys.argv[1], sys.argv[2], sys.argv[3]
testing.load_plugin()
scene = testing.read_scene(scene_path)
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()

reader = simple.XMLImageDataReader(FileName=[field])
view = testing.render_view(scene)
display = testing.show_cloud(reader, view, scene, scene["render"]["lighting"])
simple.Render(view)

# (No sys.exit(0) below: pvbatch leaves through SystemExit with a GLXBadContext X error and
# status 1, so the script ends by running off its end.)
def compare_with_one_rank():
    testing.save(view, "ranks.png")
    one = testing.read_png(reference)
    many = testing.read_png("ranks.png")
    background = scene["background"]
    cloud = testing.cloud_pixels(one, background) | testing.cloud_pixels(many, background)
    rms = testing.rms_levels(one, many, cloud)
    print("%d ranks: %d cloud pixels, RMS difference from one rank %.3f levels" % (ranks, cloud.sum(), rms))
    testing.check(rms <= 1.0, "%d ranks differ from one rank by %.3f RMS levels (at most 1)" % (ranks, rms))

    # The lower cloud, on other ranks than the slab: its pixels are the image's lower half.
    display.CloudShadowExchange = 0
    simple.Render(view)
    testing.save(view, "no_exchange.png")
    alone = testing.read_png("no_exchange.png")
    lower = cloud.copy()
    lower[: lower.shape[0] // 2, :] = False
    brighter = float((alone - one)[lower].mean())
    print("without the exchange the lower cloud is %.2f levels brighter on average" % brighter)
    testing.check(brighter > 10.0, "without the exchange the lower cloud is only %.2f levels brighter: "
                  "the slab's shadow is missing from the one-rank image too, or the exchange does nothing" % brighter)


if ranks == 1:
    testing.save(view, reference)
    print("wrote the one-rank image %s" % reference)
else:
    compare_with_one_rank()
