"""Light crosses the ranks' pieces: under `mpirun -np N pvbatch`, the Cloud Volume
representation draws scenes/shadow.json (a dense slab above a cloud, the sun overhead; ParaView
gives the slab and the cloud to different ranks) with the march as one rank draws it, and the
cloud lies in the slab's shadow. With the exchange of optical depth between ranks turned off,
the shadow is gone.

ParaView's compositing of N ranks' translucent images changes pixels at the cloud's edges by
itself, with no lighting at all (and for ParaView's own volume representation too): the test
measures that floor with the lighting model none and asks the march to add at most 1 RMS level
to it (docs/paraview.md has the figures).

Usage: pvbatch MpiShadow.py FIELD.vti SCENE.json REFERENCE
  On one rank it writes REFERENCE-none.png and REFERENCE-march.png; on more it compares with them."""
import sys

from paraview import servermanager, simple

import cloudvis_paraview_testing as testing

field, scene_path, reference = sys.argv[1], sys.argv[2], sys.argv[3]
testing.load_plugin()
scene = testing.read_scene(scene_path)
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
background = scene["background"]

reader = simple.XMLImageDataReader(FileName=[field])
view = testing.render_view(scene)
display = testing.show_cloud(reader, view, scene, "march")


def render(model, path):
    display.CloudLighting = model
    simple.Render(view)
    testing.save(view, path)
    return testing.read_png(path)


def difference_from_one_rank(model):
    """RMS levels between this run's image and the one-rank image, over the cloud's pixels."""
    many = render(model, "%d-ranks-%s.png" % (ranks, model))
    one = testing.read_png("%s-%s.png" % (reference, model))
    cloud = testing.cloud_pixels(one, background) | testing.cloud_pixels(many, background)
    return one, cloud, testing.rms_levels(one, many, cloud)


def compare_with_one_rank():
    _, _, floor = difference_from_one_rank("none")
    one, cloud, rms = difference_from_one_rank("march")
    print("%d ranks against one: none %.3f, march %.3f RMS levels over %d cloud pixels"
          % (ranks, floor, rms, cloud.sum()))
    testing.check(rms <= floor + 1.0, "with the march, %d ranks differ from one rank by %.3f RMS "
                  "levels, more than 1 beyond the %.3f of compositing alone" % (ranks, rms, floor))

    # The lower cloud, on other ranks than the slab: its pixels are the image's lower half.
    display.CloudShadowExchange = 0
    alone = render("march", "no-exchange.png")
    lower = cloud.copy()
    lower[: lower.shape[0] // 2, :] = False
    brighter = float((alone - one)[lower].mean())
    print("without the exchange the lower cloud is %.2f levels brighter on average" % brighter)
    testing.check(brighter > 10.0, "without the exchange the lower cloud is only %.2f levels "
                  "brighter: the slab's shadow is missing from the one-rank image too, or the "
                  "exchange does nothing" % brighter)


# (No sys.exit(0): pvbatch leaving through SystemExit ends with a GLXBadContext X error and
# status 1, so the script ends by running off its end.)
if ranks == 1:
    for model in ("none", "march"):
        render(model, "%s-%s.png" % (reference, model))
    print("wrote the one-rank images %s-*.png" % reference)
else:
    compare_with_one_rank()
