"""The Cloud Density source in ParaView makes the field `cloudvis generate` makes of the same
scene, voxel for voxel: every key of the scene's field section is set as the property
docs/paraview.md maps it to (the table FIELD_KEYS below, which fails the test on a key it does not
know), the source's output is fetched, and its geometry and "density" array must equal those of
the .vti cloudvis writes, bit for bit. The drop-downs are set by the scene's own names, so a name
that differs between the panel and the scene fails too.

Usage: pvbatch SourceSameAsCloudvis.py SCENE.json"""
import json
import os
import sys

import numpy
from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import cloudvis_paraview_testing as testing


def as_vector(value, count):
    return list(value) if isinstance(value, list) else [value] * count


def set_shape(source, value):
    if value == "morph":
        source.Morph = 1
    else:
        source.Shapes = json.dumps(value)


def set_coverage_map(source, value):
    if value in ("shapes", "noise"):
        source.CoverageSource = value
    else:
        # A scene's path is relative to the scene's folder.
        source.CoverageMapFile = os.path.join(os.path.dirname(os.path.abspath(scene_path)), value)
        source.CoverageSource = "map"


# Scene key -> how it sets the source (docs/paraview.md, "The Cloud Density source").
FIELD_KEYS = {
    "dimensions": lambda s, v: setattr(s, "Dimensions", as_vector(v, 3)),
    "bounds": lambda s, v: setattr(s, "Bounds", v),
    "density_model": lambda s, v: setattr(s, "DensityModel", v),
    "density_scale": lambda s, v: setattr(s, "DensityScale", v),
    "falloff_width": lambda s, v: setattr(s, "FalloffWidth", v),
    "shape": set_shape,
    "blend": lambda s, v: setattr(s, "ShapeBlend", v),
    "blend_radius": lambda s, v: setattr(s, "BlendRadius", v),
    "noise": lambda s, v: setattr(s, "NoiseType", v),
    "octaves": lambda s, v: setattr(s, "NoiseOctaves", v),
    "frequency": lambda s, v: setattr(s, "NoiseFrequency", v),
    "lacunarity": lambda s, v: setattr(s, "NoiseLacunarity", v),
    "lacunarity_increment": lambda s, v: setattr(s, "NoiseLacunarityIncrement", v),
    "gain": lambda s, v: setattr(s, "NoiseGain", v),
    "amplitude": lambda s, v: setattr(s, "NoiseAmplitude", v),
    "seed": lambda s, v: setattr(s, "NoiseSeed", v),
    "noise_period": lambda s, v: setattr(s, "NoisePeriod", v),
    "wind": lambda s, v: setattr(s, "Wind", v),
    # ParaView's time wins over the Time property: the field is updated at the scene's time.
    "time": lambda s, v: setattr(s, "Time", v),
}
CLOUD_KEYS = {
    "type": lambda s, v: setattr(s, "CloudType", v),
    "base": lambda s, v: setattr(s, "CloudAltitudes", [v, s.CloudAltitudes[1]]),
    "top": lambda s, v: setattr(s, "CloudAltitudes", [s.CloudAltitudes[0], v]),
    "coverage": lambda s, v: setattr(s, "CloudCoverage", v),
    "coverage_map": set_coverage_map,
    "map_scale": lambda s, v: setattr(s, "WeatherMapScale", v),
    "map_octaves": lambda s, v: setattr(s, "WeatherMapOctaves", v),
    "map_gain": lambda s, v: setattr(s, "WeatherMapGain", v),
    "shape_scale": lambda s, v: setattr(s, "CloudNoiseScales", [v, s.CloudNoiseScales[1]]),
    "detail_scale": lambda s, v: setattr(s, "CloudNoiseScales", [s.CloudNoiseScales[0], v]),
    "erosion": lambda s, v: setattr(s, "CloudErosion", v),
    "curl": lambda s, v: setattr(s, "CloudCurl", v),
    "anvil": lambda s, v: setattr(s, "CloudAnvil", v),
    "shear": lambda s, v: setattr(s, "CloudShear", v),
}


def configure(source, field):
    for key, value in field.items():
        if key == "cloud":
            for cloud_key, cloud_value in value.items():
                testing.check(cloud_key in CLOUD_KEYS, "field.cloud.%s has no property" % cloud_key)
                CLOUD_KEYS[cloud_key](source, cloud_value)
        else:
            testing.check(key in FIELD_KEYS, "field.%s has no property" % key)
            FIELD_KEYS[key](source, value)


def read_vti(path):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


scene_path = sys.argv[1]
testing.load_plugin()
field = testing.read_scene(scene_path)["field"]
testing.run_cloudvis("generate", scene_path, "-o", "cloudvis.vti")
expected = read_vti("cloudvis.vti")

source = simple.CloudDensity()
configure(source, field)
time = field.get("time", 0.0)
source.UpdatePipeline(time)


def check_same_as_cloudvis(what):
    output = servermanager.Fetch(source)
    testing.check(output.GetExtent() == expected.GetExtent(),
                  "%s: extent %s, cloudvis's %s" % (what, output.GetExtent(), expected.GetExtent()))
    for name in ("GetOrigin", "GetSpacing"):
        got, want = getattr(output, name)(), getattr(expected, name)()
        testing.check(numpy.allclose(got, want, rtol=0, atol=1e-12),
                      "%s: %s %s, cloudvis's %s" % (what, name[3:], got, want))
    array = output.GetPointData().GetArray("density")
    testing.check(array is not None and array.GetDataTypeAsString() == "float",
                  "%s: the source's output has no float array \"density\"" % what)
    got = vtk_to_numpy(array)
    want = vtk_to_numpy(expected.GetPointData().GetArray("density"))
    # A field that is empty, or the same whatever the keys, would prove nothing.
    testing.check(numpy.count_nonzero(want) > 0.01 * want.size, "cloudvis's field is almost empty")
    different = int(numpy.count_nonzero(got != want))
    print("%s: %d voxels, %d non-empty, %d differ (largest difference %g)" % (
        what, want.size, numpy.count_nonzero(want), different, float(numpy.abs(got - want).max())))
    testing.check(different == 0, "%s: %d of %d voxels differ from cloudvis generate's" % (what, different, want.size))


check_same_as_cloudvis(scene_path)
# A shape list the scene reader refuses leaves the source's shapes as they were.
if not source.Morph:
    source.Shapes = '[{"type": "box", "radius": 1}]'
    source.UpdatePipeline(time)
    check_same_as_cloudvis(scene_path + " after a refused shape list")
