"""cloudvis.field_from_numpy, cloudvis.field_from_xarray and cloudvis.render (docs/python.md):
fields made from arrays as Python users hold them, with their coordinates and units, drawn by
`cloudvis render` into numpy images. The xarray data comes from a NetCDF file laid out as
DALES writes a field dump (ql in kg/kg on time, zt, yt, xt), written with netCDF4 and opened
with xarray, as a user would open one."""

import os
import tempfile

import numpy as np
import pytest
import vtk
import xarray
from netCDF4 import Dataset
from vtk.util.numpy_support import vtk_to_numpy

import cloudvis

NX, NY, NZ = 24, 20, 16
DX, DZ = 50.0, 25.0  # metres


def dales_file(path, steps=1, stretched=False):
    """ql in kg/kg on (time, zt, yt, xt): a cumulus-sized blob up to 1.2e-3 kg/kg."""
    with Dataset(path, "w") as nc:
        nc.createDimension("time", None)
        for name, size in (("zt", NZ), ("yt", NY), ("xt", NX)):
            nc.createDimension(name, size)
        time = nc.createVariable("time", "f8", ("time",))
        time.units = "seconds since 2020-01-01 00:00:00"
        time[:] = np.arange(steps) * 60.0
        xt = nc.createVariable("xt", "f4", ("xt",))
        xt.units = "m"
        xt[:] = DX / 2 + DX * np.arange(NX)
        yt = nc.createVariable("yt", "f4", ("yt",))
        yt.units = "m"
        yt[:] = DX / 2 + DX * np.arange(NY)
        zt = nc.createVariable("zt", "f4", ("zt",))
        zt.units = "m"
        zt.positive = "up"
        levels = 500.0 + DZ * np.arange(NZ)
        if stretched:
            levels = 500.0 + DZ * np.arange(NZ) ** 1.3
        zt[:] = levels
        ql = nc.createVariable("ql", "f4", ("time", "zt", "yt", "xt"))
        ql.units = "kg/kg"
        ql.long_name = "Liquid water mixing ratio"
        z, y, x = np.meshgrid(np.arange(NZ), np.arange(NY), np.arange(NX), indexing="ij")
        r2 = ((x - NX / 2) / 7.0) ** 2 + ((y - NY / 2) / 6.0) ** 2 + ((z - NZ / 2) / 5.0) ** 2
        blob = np.clip(1.0 - r2, 0.0, None).astype(np.float32) * 1.2e-3
        for step in range(steps):
            ql[step] = blob
    return path


# ---- field_from_numpy ---------------------------------------------------------------------------


def test_numpy_field_shares_the_arrays_memory_and_keeps_its_layout():
    values = np.random.default_rng(1).random((4, 5, 6), dtype=np.float32)  # (z, y, x)
    field = cloudvis.field_from_numpy(values, spacing=(2.0, 3.0, 4.0), origin=(1.0, 0.0, -1.0))
    assert field.GetDimensions() == (6, 5, 4)
    assert field.GetSpacing() == (2.0, 3.0, 4.0)
    assert field.GetOrigin() == (1.0, 0.0, -1.0)
    stored = vtk_to_numpy(field.GetPointData().GetScalars())
    assert field.GetPointData().GetScalars().GetName() == "density"
    assert np.shares_memory(stored, values), "a float32 (z, y, x) array is not copied"
    # Voxel (i, j, k) is values[k, j, i], and a change to the array is a change to the field.
    assert field.GetScalarComponentAsDouble(5, 1, 2, 0) == pytest.approx(values[2, 1, 5])
    values[3, 4, 0] = 7.0
    assert field.GetScalarComponentAsDouble(0, 4, 3, 0) == 7.0


def test_numpy_field_copies_what_it_must():
    values = np.arange(24, dtype=np.float64).reshape(2, 3, 4)
    field = cloudvis.field_from_numpy(values)
    stored = vtk_to_numpy(field.GetPointData().GetScalars())
    assert stored.dtype == np.float32 and not np.shares_memory(stored, values)
    assert np.array_equal(stored, values.reshape(-1))
    # An (x, y, z) array in Fortran order is x fastest too: shared.
    xyz = np.asfortranarray(np.ones((4, 3, 2), dtype=np.float32))
    field = cloudvis.field_from_numpy(xyz, order="xyz")
    assert field.GetDimensions() == (4, 3, 2)
    assert np.shares_memory(vtk_to_numpy(field.GetPointData().GetScalars()), xyz)


def test_numpy_field_keeps_units_and_attributes_as_field_data():
    field = cloudvis.field_from_numpy(np.zeros((2, 2, 2)), units="g m-3", length_unit="m",
                                      up="z", droplet_number=70,
                                      attributes={"long_name": "liquid water", "step": 3})
    data = field.GetFieldData()
    assert data.GetAbstractArray("units").GetValue(0) == "g m-3"
    assert data.GetAbstractArray("length_unit").GetValue(0) == "m"
    assert data.GetAbstractArray("up").GetValue(0) == "z"
    assert data.GetAbstractArray("long_name").GetValue(0) == "liquid water"
    assert data.GetArray("step").GetTuple1(0) == 3.0
    assert data.GetArray("droplet_number").GetTuple1(0) == 70.0


@pytest.mark.parametrize("call, message", [
    (lambda: cloudvis.field_from_numpy(np.zeros((3, 3))), "values: a field is a 3-D array"),
    (lambda: cloudvis.field_from_numpy(np.zeros((0, 3, 3))), "holds no values"),
    (lambda: cloudvis.field_from_numpy(np.zeros((2, 2, 2)), spacing=(1, 0, 1)),
     "spacing: each step is a length above 0"),
    (lambda: cloudvis.field_from_numpy(np.zeros((2, 2, 2)), origin=(0, 0)),
     "origin: three finite numbers"),
    (lambda: cloudvis.field_from_numpy(np.full((2, 2, 2), np.nan)),
     "values: 8 of 8 values are not finite"),
    (lambda: cloudvis.field_from_numpy(np.zeros((2, 2, 2)), up="w"),
     "up: one of \"x\", \"y\", \"z\""),
    (lambda: cloudvis.field_from_numpy(np.array([[["a"]]])), "a field holds real numbers"),
])
def test_numpy_field_refuses_bad_input(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_missing_values_read_as_empty_when_asked():
    values = np.ones((2, 2, 2), dtype=np.float32)
    values[0, 0, 0] = np.nan
    field = cloudvis.field_from_numpy(values, missing="empty")
    stored = vtk_to_numpy(field.GetPointData().GetScalars())
    assert stored[0] == 0.0 and stored[1:].min() == 1.0
    assert np.isnan(values[0, 0, 0]), "the caller's array is left as it was"


# ---- field_from_xarray --------------------------------------------------------------------------


def test_xarray_field_takes_coordinates_units_and_attributes(tmp_path):
    with xarray.open_dataset(dales_file(tmp_path / "fielddump.001.nc")) as dataset:
        ql = dataset["ql"].load()
    field = cloudvis.field_from_xarray(ql)
    assert field.GetDimensions() == (NX, NY, NZ)
    assert field.GetSpacing() == pytest.approx((DX, DX, DZ))
    assert field.GetOrigin() == pytest.approx((DX / 2, DX / 2, 500.0))
    stored = vtk_to_numpy(field.GetPointData().GetArray("ql"))
    assert np.shares_memory(stored, ql.values), "the DataArray's values are not copied"
    data = field.GetFieldData()
    assert data.GetAbstractArray("units").GetValue(0) == "kg/kg"
    assert data.GetAbstractArray("long_name").GetValue(0) == "Liquid water mixing ratio"
    assert data.GetAbstractArray("length_unit").GetValue(0) == "m"
    assert data.GetAbstractArray("up").GetValue(0) == "z"


def test_xarray_field_flips_a_decreasing_coordinate():
    values = np.arange(24, dtype=np.float32).reshape(2, 3, 4)
    array = xarray.DataArray(values, dims=("z", "y", "x"),
                             coords={"x": [30.0, 20.0, 10.0, 0.0]})
    field = cloudvis.field_from_xarray(array)
    assert field.GetOrigin()[0] == 0.0 and field.GetSpacing()[0] == 10.0
    # x = 0 is the array's last column.
    assert field.GetScalarComponentAsDouble(0, 0, 0, 0) == values[0, 0, 3]


def test_xarray_field_refuses_what_is_not_one_uniform_3d_field(tmp_path):
    with xarray.open_dataset(dales_file(tmp_path / "series.nc", steps=3)) as dataset:
        with pytest.raises(ValueError, match=r'choose one "time" with data_array.isel\(time=0\)'):
            cloudvis.field_from_xarray(dataset["ql"])
        cloudvis.field_from_xarray(dataset["ql"].isel(time=2))
    with xarray.open_dataset(dales_file(tmp_path / "stretched.nc", stretched=True)) as dataset:
        with pytest.raises(ValueError, match='coordinate "zt" is stretched'):
            cloudvis.field_from_xarray(dataset["ql"])
    with pytest.raises(TypeError, match="an xarray DataArray"):
        cloudvis.field_from_xarray(np.zeros((2, 2, 2)))


# ---- render -------------------------------------------------------------------------------------


def cloud_pixels(image):
    """The pixels that differ from the background (the top left corner)."""
    rgb = np.asarray(image)[:, :, :3].astype(float)
    return np.abs(rgb - rgb[0, 0]).max(axis=2) > 20


def test_render_draws_a_mixing_ratio_as_liquid_water(tmp_path):
    with xarray.open_dataset(dales_file(tmp_path / "fielddump.001.nc")) as dataset:
        ql = dataset["ql"].isel(time=0)
        field = cloudvis.field_from_xarray(ql, air_density=1.1)
    # Droplet extinction needs a liquid water content in metres: units from the DataArray.
    scene = {"transfer_function": {"extinction": "droplets"}, "field": {"droplet_number": 70}}
    image = cloudvis.render(field, scene, size=(96, 72))
    assert isinstance(image, np.ndarray) and image.dtype == np.uint8
    assert image.shape[:2] == (72, 96)
    cloud = cloud_pixels(image)
    print(f"cloud covers {cloud.mean():.2f} of the picture")
    assert 0.02 < cloud.mean() < 0.5  # a 700 m x 250 m cloud in a domain 1200 m wide
    assert (image[cloud][:, :3] < 255).any(axis=1).mean() > 0.95, "the cloud is not clipped"
    assert "wrote" in image.report
    # Without the air's density the values stay a mixing ratio, which has no droplets.
    with pytest.raises(cloudvis.RenderError, match="field.quantity"):
        cloudvis.render(cloudvis.field_from_xarray(ql), scene, size=(96, 72))


def test_render_takes_a_data_array_and_gives_a_notebook_png(tmp_path):
    with xarray.open_dataset(dales_file(tmp_path / "fielddump.001.nc")) as dataset:
        image = cloudvis.render(dataset["ql"].isel(time=0), size=(64, 48), lighting="none")
    assert cloud_pixels(image).mean() > 0.02
    png = image._repr_png_()
    assert png.startswith(b"\x89PNG\r\n\x1a\n") and png == image.png
    # A part of the picture is a picture of its own.
    part = image[10:30, 5:45]
    assert part.png is None
    decoded = vtk.vtkPNGReader()
    decoded.SetMemoryBuffer(part._repr_png_())
    decoded.SetMemoryBufferLength(len(part._repr_png_()))
    decoded.Update()
    assert decoded.GetOutput().GetDimensions()[:2] == (40, 20)
    rows = vtk_to_numpy(decoded.GetOutput().GetPointData().GetScalars())
    assert np.array_equal(rows.reshape(20, 40, -1)[::-1], np.asarray(part))


def test_render_says_what_cloudvis_refused():
    before = set(os.listdir(tempfile.gettempdir()))
    field = cloudvis.field_from_numpy(np.ones((4, 4, 4), dtype=np.float32))
    with pytest.raises(cloudvis.RenderError, match=r"size"):
        cloudvis.render(field, size=(8, 8))
    with pytest.raises(cloudvis.RenderError, match=r"render\.lighting|--lighting"):
        cloudvis.render(field, lighting="phong", size=(32, 32))
    with pytest.raises(TypeError, match="a vtkImageData"):
        cloudvis.render(np.ones((4, 4, 4)))
    left = {n for n in set(os.listdir(tempfile.gettempdir())) - before
            if n.startswith("cloudvis-render-")}
    assert not left, "the temporary folders are removed"
