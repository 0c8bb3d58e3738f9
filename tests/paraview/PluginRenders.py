"""The plugin loads in pvbatch, its Cloud Density source makes a field, and the Cloud Volume
representation draws it: a cloud where the field is dense, the plain background elsewhere."""
from paraview import simple

import cloudvis_paraview_testing as testing

testing.load_plugin()
source = simple.CloudDensity(Dimensions=[48, 48, 48])
source.UpdatePipeline()
info = source.GetDataInformation()
testing.check(info.GetNumberOfPoints() == 48 ** 3, "the source made %d points" % info.GetNumberOfPoints())
scene = testing.white_cloud_scene([128, 96], 8)
view = testing.render_view(scene)
testing.show_cloud(source, view, scene, "march")
simple.Render(view)
testing.save(view, "cloud.png")
image = testing.read_png("cloud.png")
cloud = testing.cloud_pixels(image, scene["background"])
height, width = cloud.shape
testing.check(cloud[height // 2, width // 2], "no cloud at the centre of the image")
testing.check(not cloud[0, 0] and not cloud[-1, -1], "the corners are not the background")
print("the cloud covers %d of %d pixels" % (cloud.sum(), cloud.size))
