"""A field file opens in ParaView through the plugin's reader as cloudvis reads it, and a bad one
gives an error naming the file, no data and no crash.

The file field.EXTENSION is made from SOURCE: a scene, which `cloudvis generate` writes as the
file (.vdb) and as .vti, or a CDL text, which ncgen writes as a NetCDF file (.nc4, .cdf: NetCDF
names ParaView 5.11 does not offer). `cloudvis generate FILE` writes what cloudvis reads of the
file as .vti. ParaView's own OpenDataFile must pick the plugin's reader for the file, whose output
must equal what cloudvis reads (extent, origin, spacing, direction, density: bit for bit); a
generated field must also be found on its lattice with its values (an OpenVDB file holds the
active voxels' box: every non-empty voxel, at its place).

Then broken copies of the file (truncated, garbage, empty, missing) are opened: each must leave
the reader's output empty and its LastError naming the file, and the same reader must read the
good file again afterwards; so must too small a MaximumVoxels and an ArrayName the file does not
hold. A reader that crashed would end pvbatch with a non-zero status; one
that returned data for a broken file, or an error without the file's name, fails the checks.

Usage: pvbatch ReadFieldFile.py SOURCE.json|SOURCE.cdl EXTENSION"""
import os
import subprocess
import sys

import numpy
from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import cloudvis_paraview_testing as testing

source_path, extension = sys.argv[1], sys.argv[2]
testing.load_plugin()
path = os.path.abspath("field." + extension)
generated = None
if source_path.endswith(".cdl"):
    # ncgen's kind: 1 (classic) for .cdf, 3 (netCDF-4 on HDF5) for .nc4.
    kind = "3" if extension == "nc4" else "1"
    result = subprocess.run(["ncgen", "-k", kind, "-o", path, source_path], capture_output=True, text=True)
    testing.check(result.returncode == 0, "ncgen failed: %s" % result.stderr)
else:
    testing.run_cloudvis("generate", source_path, "-o", path)
    testing.run_cloudvis("generate", source_path, "-o", "generated.vti")
testing.run_cloudvis("generate", path, "-o", "cloudvis.vti")


def read_vti(name):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(name)
    reader.Update()
    return reader.GetOutput()


expected = read_vti("cloudvis.vti")
if not source_path.endswith(".cdl"):
    generated = read_vti("generated.vti")


def density(image):
    array = image.GetPointData().GetArray("density")
    testing.check(array is not None and array.GetDataTypeAsString() == "float",
                  "no float point array \"density\"")
    return vtk_to_numpy(array)


def last_error(reader):
    reader.UpdatePropertyInformation()
    return reader.GetProperty("LastError").GetData() or ""


def on_generated_lattice(output, got, what):
    """The output's voxels are the generated field's voxels at the same places, and hold all of
    its non-empty ones."""
    spacing = numpy.array(generated.GetSpacing())
    testing.check(numpy.allclose(output.GetSpacing(), spacing, rtol=1e-12, atol=0),
                  "%s: spacing %s, generated %s" % (what, output.GetSpacing(), spacing))
    first = numpy.array(output.GetPoint(0))
    offset = (first - numpy.array(generated.GetOrigin())) / spacing
    testing.check(numpy.allclose(offset, numpy.round(offset), rtol=0, atol=1e-6),
                  "%s: the first voxel %s is off the generated lattice" % (what, first))
    i, j, k = (int(v) for v in numpy.round(offset))
    nx, ny, nz = output.GetDimensions()
    gx, gy, gz = generated.GetDimensions()
    whole = density(generated).reshape(gz, gy, gx)
    box = whole[k:k + nz, j:j + ny, i:i + nx]
    testing.check(box.shape == (nz, ny, nx) and numpy.array_equal(box.ravel(), got),
                  "%s: the values differ from the generated field's at their places" % what)
    testing.check(numpy.count_nonzero(box) == numpy.count_nonzero(whole),
                  "%s: non-empty voxels of the generated field are missing" % what)


def check_same_as_cloudvis(reader, what):
    reader.UpdatePipeline()
    output = servermanager.Fetch(reader)
    testing.check(last_error(reader) == "", "%s: error %r" % (what, last_error(reader)))
    testing.check(output.GetExtent() == expected.GetExtent(),
                  "%s: extent %s, cloudvis's %s" % (what, output.GetExtent(), expected.GetExtent()))
    for name in ("GetOrigin", "GetSpacing"):
        got, want = getattr(output, name)(), getattr(expected, name)()
        testing.check(got == want, "%s: %s %s, cloudvis's %s" % (what, name[3:], got, want))
    direction = [output.GetDirectionMatrix().GetElement(i, j) for i in range(3) for j in range(3)]
    testing.check(direction == [1, 0, 0, 0, 1, 0, 0, 0, 1], "%s: direction %s" % (what, direction))
    got, want = density(output), density(expected)
    testing.check(numpy.count_nonzero(want) > 0.01 * want.size, "cloudvis's field is almost empty")
    different = int(numpy.count_nonzero(got != want))
    print("%s: %d voxels, %d differ from cloudvis's" % (what, want.size, different))
    testing.check(different == 0, "%s: %d of %d voxels differ from cloudvis's" % (what, different, want.size))
    if generated is not None:
        on_generated_lattice(output, got, what)


reader = simple.OpenDataFile(path)
testing.check(reader is not None and reader.GetXMLName() == "CloudFieldReader",
              "ParaView opens %s with %s, not the plugin's reader" % (
                  path, reader.GetXMLName() if reader else "nothing"))
check_same_as_cloudvis(reader, path)

with open(path, "rb") as f:
    good = f.read()
broken = {
    "truncated": good[: len(good) // 2],
    "garbage": b"this is not a field file\n" * 40,
    "empty": b"",
}
for name, content in broken.items():
    with open("%s.%s" % (name, extension), "wb") as f:
        f.write(content)
for name in list(broken) + ["missing"]:
    bad = os.path.abspath("%s.%s" % (name, extension))
    reader.FileName = bad
    reader.UpdatePipeline()
    output = servermanager.Fetch(reader)
    message = last_error(reader)
    print("%s: %s" % (name, message))
    testing.check(output.GetNumberOfPoints() == 0,
                  "%s: %d points read from a broken file" % (name, output.GetNumberOfPoints()))
    testing.check(bad in message, "%s: the error %r does not name the file" % (name, message))

# The reader's options reach cloudvis's reader: a field larger than MaximumVoxels and an array the
# file does not hold are refused, naming the file.
reader.FileName = path
for option, value, default in (("MaximumVoxels", 100, reader.MaximumVoxels),
                               ("ArrayName", "no_such_array", "")):
    setattr(reader, option, value)
    reader.UpdatePipeline()
    output = servermanager.Fetch(reader)
    message = last_error(reader)
    print("%s %s: %s" % (option, value, message))
    testing.check(output.GetNumberOfPoints() == 0 and path in message,
                  "%s %s: %d points, error %r" % (option, value, output.GetNumberOfPoints(), message))
    setattr(reader, option, default)

check_same_as_cloudvis(reader, path + " after the broken files and options")
