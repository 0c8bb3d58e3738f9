"""Fields from numpy arrays and xarray DataArrays: vtkImageData that shares the array's memory
where it can, with the spacing, origin, units and attributes the data states (docs/python.md).

A field's units travel as the image's field data, under the names cloudvis's readers take from a
.vti file (docs/data.md, "Physical units"): the strings "quantity", "length_unit", "up" and
"units" (the values' units as a file states them, "g m-3" or "kg/kg"), and the numbers
"effective_radius", "droplet_number" and "air_density". `cloudvis render` reads them from the
.vti that cloudvis.render writes, and decides from them, with its one set of rules, what the
values are: a liquid water content in kg m-3 becomes g/m^3 there, a mixing ratio with an
"air_density" a liquid water content. The other attributes are kept as field data too, as text
or numbers, so that they survive a round trip through a .vti file.
"""

import math
import numbers

import numpy
import vtk
from vtk.util.numpy_support import numpy_to_vtk

# The values field data may declare, as cloudvis's readers allow them (FieldFormatReaders.cxx).
_ALLOWED_TEXT = {
    "quantity": ("density", "lwc"),
    "length_unit": ("none", "m", "km"),
    "up": ("x", "y", "z"),
}

# Coordinate units that are lengths, and the length unit each is (as LengthUnitFromText in
# app/fields/FieldUnits.cxx reads a NetCDF coordinate's units; other units declare none).
_LENGTH_UNITS = {
    "m": "m", "metre": "m", "metres": "m", "meter": "m", "meters": "m",
    "km": "km", "kilometre": "km", "kilometres": "km", "kilometer": "km", "kilometers": "km",
}

# How uniform a coordinate's steps must be to be read as a lattice: relative to the mean step.
_UNIFORM_TOLERANCE = 1e-4


def field_from_numpy(values, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0), *,
                     name="density", order="zyx", missing="refuse", units=None,
                     quantity=None, length_unit=None, up=None, effective_radius=None,
                     droplet_number=None, air_density=None, attributes=None):
    """A vtkImageData of the 3-D array `values`.

    `order` says how the array is indexed: "zyx" (values[k, j, i], as NetCDF and xarray hold
    LES output; the default) or "xyz" (values[i, j, k]). `spacing` and `origin` are (x, y, z),
    in world units. The image's point array `name` (the active scalars) is float32; it shares
    the array's memory when the array is float32 and its x axis is the fastest in memory (a
    C-ordered "zyx" array, a Fortran-ordered "xyz" one), and is a copy otherwise.

    Values that are NaN or infinite are refused (ValueError, with their count) unless `missing`
    is "empty": then they are read as density 0 (a copy), as field.missing "empty" reads a
    NetCDF file's missing values.

    `units` (the values' units: "g m-3", "kg m-3", "kg/kg"...), `quantity` ("density" or
    "lwc"), `length_unit` ("none", "m", "km"), `up` ("x", "y", "z"), and the numbers
    `effective_radius` (micrometres), `droplet_number` (per cm^3) and `air_density` (kg/m^3, for
    a mixing ratio) are stored as field data, which `cloudvis.render` and `cloudvis render` of a
    saved .vti read (docs/data.md). `attributes` (a mapping of names to text or numbers) are
    kept as field data as well.
    """
    array = numpy.asarray(values)
    if array.ndim != 3:
        raise ValueError(f"values: a field is a 3-D array, got {array.ndim}-D of shape "
                         f"{array.shape}")
    if 0 in array.shape:
        raise ValueError(f"values: the array of shape {array.shape} holds no values")
    if order not in ("zyx", "xyz"):
        raise ValueError(f'order: "zyx" (values[k, j, i]) or "xyz" (values[i, j, k]), got {order!r}')
    if missing not in ("refuse", "empty"):
        raise ValueError(f'missing: "refuse" or "empty", got {missing!r}')
    if not numpy.issubdtype(array.dtype, numpy.number) or numpy.iscomplexobj(array):
        raise ValueError(f"values: a field holds real numbers, got an array of {array.dtype}")
    spacing = _three_numbers("spacing", spacing)
    origin = _three_numbers("origin", origin)
    if not all(s > 0.0 for s in spacing):
        raise ValueError(f"spacing: each step is a length above 0, got {spacing}")

    # x fastest in memory: the layout of VTK's point arrays.
    zyx = array if order == "zyx" else array.transpose(2, 1, 0)
    finite = numpy.isfinite(zyx)
    if not finite.all():
        bad = int(zyx.size - numpy.count_nonzero(finite))
        if missing == "refuse":
            raise ValueError(
                f"values: {bad} of {zyx.size} values are not finite (NaN or infinity); "
                'missing="empty" reads them as density 0')
        zyx = numpy.where(finite, zyx, 0.0)
    flat = numpy.ascontiguousarray(zyx, dtype=numpy.float32).reshape(-1)

    image = vtk.vtkImageData()
    image.SetDimensions(zyx.shape[2], zyx.shape[1], zyx.shape[0])
    image.SetSpacing(spacing)
    image.SetOrigin(origin)
    # deep=False: the VTK array points into `flat` and keeps a reference to it.
    point_array = numpy_to_vtk(flat, deep=False)
    point_array.SetName(name)
    image.GetPointData().SetScalars(point_array)

    fields = image.GetFieldData()
    for key, value in (attributes or {}).items():
        _add_field_data(fields, str(key), value)
    for key, value in (("quantity", quantity), ("length_unit", length_unit), ("up", up)):
        if value is not None:
            if value not in _ALLOWED_TEXT[key]:
                allowed = ", ".join(f'"{a}"' for a in _ALLOWED_TEXT[key])
                raise ValueError(f"{key}: one of {allowed}, got {value!r}")
            _add_field_data(fields, key, value)
    if units is not None:
        _add_field_data(fields, "units", str(units))
    for key, value in (("effective_radius", effective_radius),
                       ("droplet_number", droplet_number), ("air_density", air_density)):
        if value is not None:
            if not isinstance(value, numbers.Real) or not math.isfinite(value):
                raise ValueError(f"{key}: a finite number, got {value!r}")
            _add_field_data(fields, key, float(value))
    return image


def field_from_xarray(data_array, *, missing="refuse", air_density=None, name=None):
    """A vtkImageData of an xarray DataArray of three dimensions (others of length 1 are
    dropped), ordered as CF recommends and LES codes write: (z, y, x), the last fastest, as
    DALES's ql(time, zt, yt, xt) or WRF's QCLOUD(Time, bottom_top, south_north, west_east).

    - Coordinates: a dimension's 1-D coordinate gives the spacing (its step, which must be
      uniform: a stretched axis is refused, naming it) and the origin (its first value); a
      decreasing coordinate is flipped. A dimension without a coordinate has step 1 from 0.
    - Units: the coordinates' shared length unit ("m", "km") becomes "length_unit", and z is up
      when the vertical coordinate is a length (a pressure axis, or positive="down", declares
      nothing). The array's `units` attribute becomes "units"; `cloudvis render` decides from it
      whether the values are a liquid water content (g m-3, kg m-3).
    - A mixing ratio (kg/kg, g/kg) becomes a liquid water content with `air_density`, one number
      in kg/m^3; for a profile, multiply in xarray first (ql * rho * 1000, units "g m-3").
    - Every attribute of the array is kept as field data (text or numbers).
    - Missing values (NaN where xarray decoded a _FillValue) are refused unless `missing` is
      "empty" (see field_from_numpy).

    The image shares the DataArray's memory where field_from_numpy can (float32, the dimensions
    already in (z, y, x) order, no coordinate flipped).
    """
    try:
        dims = tuple(data_array.dims)
        attrs = dict(data_array.attrs)
    except AttributeError:
        raise TypeError(f"data_array: an xarray DataArray, got {type(data_array).__name__}") \
            from None
    extra = [d for d in dims if data_array.sizes[d] != 1]
    if len(extra) > 3:
        # A fourth dimension of more than one step, time most often: choose one.
        other = extra[0]
        raise ValueError(
            f'data_array: {data_array.name or "the array"} has {len(extra)} dimensions of more '
            f"than one step {tuple(extra)}; a field has three: choose one "
            f'"{other}" with data_array.isel({other}=0)')
    if len(extra) < 3:
        raise ValueError(
            f"data_array: a field has three dimensions of more than one step, got {tuple(extra)}")
    squeezed = data_array.squeeze([d for d in dims if d not in extra], drop=True)
    z_dim, y_dim, x_dim = squeezed.dims

    spacing, origin, lengths, flips = [], [], [], []
    for dim in (x_dim, y_dim, z_dim):
        step, first, unit, flip = _axis_of(squeezed, dim)
        spacing.append(step)
        origin.append(first)
        lengths.append(unit)
        flips.append(flip)
    values = squeezed.values
    if any(flips):
        values = values[tuple(slice(None, None, -1) if f else slice(None)
                              for f in reversed(flips))]
    shared = lengths[0] if len(set(lengths)) == 1 else None
    length_unit = _LENGTH_UNITS.get(shared) if shared else None
    up = None
    if length_unit and str(squeezed[z_dim].attrs.get("positive", "up")).lower() != "down":
        up = "z"

    # The attributes as they are ("units", and "effective_radius" or "droplet_number" where the
    # file declares them, are among them), then what the coordinates say.
    return field_from_numpy(
        values, spacing, origin, name=name or str(data_array.name or "density"),
        missing=missing, length_unit=length_unit, up=up, attributes=attrs,
        air_density=air_density)


def _axis_of(data_array, dim):
    """The step, first value, units and whether to flip one dimension, from its coordinate."""
    if dim not in data_array.coords:
        return 1.0, 0.0, None, False
    coordinate = data_array.coords[dim]
    points = numpy.asarray(coordinate.values, dtype=numpy.float64)
    if points.ndim != 1 or not numpy.isfinite(points).all():
        raise ValueError(f'coordinate "{dim}": a field\'s axis is a 1-D coordinate of finite '
                         "numbers")
    units = coordinate.attrs.get("units")
    units = str(units).strip().lower() if units is not None else None
    if points.size == 1:
        return 1.0, float(points[0]), units, False
    steps = numpy.diff(points)
    mean = float(steps.mean())
    if mean == 0.0 or (steps * numpy.sign(mean) <= 0.0).any():
        raise ValueError(f'coordinate "{dim}": its values are not strictly monotonic')
    if (numpy.abs(steps - mean) > _UNIFORM_TOLERANCE * abs(mean)).any():
        raise ValueError(
            f'coordinate "{dim}" is stretched (steps {abs(steps).min():g} to '
            f"{abs(steps).max():g}): a field is a uniform lattice; resample it with "
            f"data_array.interp({dim}=...), or write it with to_netcdf and open the file with "
            "cloudvis, which resamples a stretched axis (docs/data.md)")
    flip = mean < 0.0
    return abs(mean), float(points.min() if flip else points[0]), units, flip


def _three_numbers(what, value):
    try:
        numbers_ = [float(v) for v in value]
    except (TypeError, ValueError):
        raise ValueError(f"{what}: three numbers (x, y, z), got {value!r}") from None
    if len(numbers_) != 3 or not all(math.isfinite(v) for v in numbers_):
        raise ValueError(f"{what}: three finite numbers (x, y, z), got {value!r}")
    return tuple(numbers_)


def _add_field_data(fields, key, value):
    """One field data entry: text as a vtkStringArray, a number (or numbers) as a
    vtkDoubleArray; other values as their text."""
    if isinstance(value, (numbers.Real, numpy.number)) and not isinstance(value, bool):
        entry = vtk.vtkDoubleArray()
        entry.InsertNextValue(float(value))
    elif isinstance(value, (list, tuple, numpy.ndarray)) and len(value) > 0 and all(
            isinstance(v, (numbers.Real, numpy.number)) for v in value):
        entry = vtk.vtkDoubleArray()
        for v in value:
            entry.InsertNextValue(float(v))
    else:
        entry = vtk.vtkStringArray()
        entry.InsertNextValue(str(value))
    entry.SetName(key)
    fields.RemoveArray(key)
    fields.AddArray(entry)
