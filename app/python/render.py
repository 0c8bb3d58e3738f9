"""cloudvis.render: a field drawn by `cloudvis render`, as a numpy image (docs/python.md).

The picture is the command line's own: the same default transfer function fitted to the
field, camera, lighting, exposure and refusals, because it is the `cloudvis` program that draws
it. The field goes to it as a .vti file in a temporary folder (its units as field data,
fields.py), the scene as JSON, and the PNG comes back as an `Image`: a numpy array of
(height, width, channels) with the PNG's bytes, which notebooks show (`_repr_png_`).
"""

import json
import os
import shutil
import subprocess
import tempfile

import numpy
import vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy

from .fields import field_from_xarray


class RenderError(RuntimeError):
    """`cloudvis render` refused the field, the scene or a setting; the message is its own."""


class Image(numpy.ndarray):
    """A rendered picture: uint8 (or uint16, with png_bits 16) values of shape
    (height, width, channels), top row first, as PIL and matplotlib take them. `png` holds the
    PNG `cloudvis render` wrote (with its metadata: scene, lighting, transfer function), and
    `report` the lines it printed. A notebook shows it as that PNG."""

    def __new__(cls, pixels, png=None, report=""):
        image = numpy.asarray(pixels).view(cls)
        image.png = png
        image.report = report
        return image

    def __array_finalize__(self, parent):
        # A slice or a computed array is another picture: its PNG is made from its values.
        self.png = None
        self.report = getattr(parent, "report", "")

    def _repr_png_(self):
        if self.png is not None:
            return self.png
        return _encode_png(numpy.asarray(self))


def render(field=None, scene=None, *, size=(480, 360), lighting=None, settings=None,
           executable=None, timeout=None):
    """The picture `cloudvis render` makes of `field`, as an Image (a numpy array).

    - `field`: a vtkImageData (field_from_numpy, field_from_xarray, a VTK source or reader), an
      xarray DataArray (read by field_from_xarray), or None when `scene` names its own field.
    - `scene`: None (the defaults `cloudvis render FIELD` uses), a dict in the scene format
      (docs/scene-format.md), or the path of a scene file. Given a field too, the field
      replaces the scene's `field.file`; other `field` keys (field.quantity...) still apply.
    - `size`: (width, height) in pixels; `lighting`: "none", "derivative", "march" or
      "pathtrace"; `settings`: a mapping of dotted scene keys to values, each a `--set`
      ({"render.exposure": "auto"}).
    - `executable`: the `cloudvis` program; by default $CLOUDVIS_EXECUTABLE, else the one built
      beside this package, else `cloudvis` on PATH. Without an X display it runs under
      `xvfb-run -a` where that is installed.

    Raises RenderError with cloudvis's message when it refuses (a bad scene, a blank picture,
    no display), TypeError or ValueError for arguments of the wrong kind.
    """
    if field is not None and not isinstance(field, vtk.vtkImageData):
        if hasattr(field, "dims") and hasattr(field, "attrs"):
            field = field_from_xarray(field)
        else:
            raise TypeError(
                "field: a vtkImageData (cloudvis.field_from_numpy, cloudvis.field_from_xarray) "
                f"or an xarray DataArray, got {type(field).__name__}")
    if field is None and scene is None:
        raise ValueError("render: give a field, a scene, or both")
    try:
        width, height = (int(v) for v in size)
    except (TypeError, ValueError):
        raise ValueError(f"size: (width, height) in pixels, got {size!r}") from None

    with tempfile.TemporaryDirectory(prefix="cloudvis-render-") as folder:
        command = [_executable(executable), "render"]
        field_path = scene_path = None
        if field is not None:
            field_path = os.path.join(folder, "field.vti")
            _write_vti(field, field_path)
        if isinstance(scene, dict):
            document = json.loads(json.dumps(scene))  # a copy, and JSON or refused here
            if field_path:
                document.setdefault("field", {})
                if not isinstance(document["field"], dict):
                    raise ValueError("scene: its \"field\" is an object of keys")
                document["field"]["file"] = field_path
            scene_path = os.path.join(folder, "scene.json")
            with open(scene_path, "w", encoding="utf-8") as out:
                json.dump(document, out)
            command.append(scene_path)
        elif scene is not None:
            command.append(os.fspath(scene))
            if field_path:
                command += ["--set", "field.file=" + field_path]
        else:
            command.append(field_path)
        picture = os.path.join(folder, "picture.png")
        command += ["-o", picture, "--size", f"{width}x{height}"]
        if lighting is not None:
            command += ["--lighting", str(lighting)]
        for key, value in (settings or {}).items():
            command += ["--set", f"{key}={json.dumps(value)}"]
        if not os.environ.get("DISPLAY") and shutil.which("xvfb-run"):
            command = ["xvfb-run", "-a"] + command
        run = subprocess.run(command, capture_output=True, text=True, timeout=timeout,
                             check=False)
        if run.returncode != 0:
            message = run.stderr.strip() or run.stdout.strip() or f"exit status {run.returncode}"
            # The files it names are gone once this returns: say what they were.
            if field_path:
                message = message.replace(field_path, "the field")
            if scene_path:
                message = message.replace(scene_path, "the scene")
            raise RenderError(message.replace("cloudvis: error: ", ""))
        with open(picture, "rb") as png:
            data = png.read()
        return Image(_decode_png(picture), png=data, report=run.stdout)


def _executable(given):
    if given:
        return os.fspath(given)
    if os.environ.get("CLOUDVIS_EXECUTABLE"):
        return os.environ["CLOUDVIS_EXECUTABLE"]
    try:
        from ._build import CLOUDVIS_EXECUTABLE
        if os.access(CLOUDVIS_EXECUTABLE, os.X_OK):
            return CLOUDVIS_EXECUTABLE
    except ImportError:
        pass
    found = shutil.which("cloudvis")
    if not found:
        raise RenderError("the cloudvis program was not found: build it (make build), or name "
                          "it with $CLOUDVIS_EXECUTABLE")
    return found


def _write_vti(field, path):
    """The field as a .vti of raw appended data: the quickest for VTK to write and read."""
    writer = vtk.vtkXMLImageDataWriter()
    writer.SetInputData(field)
    writer.SetFileName(path)
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    writer.SetCompressorTypeToNone()
    if not writer.Write():
        raise RenderError(f"{path}: the field could not be written for cloudvis render")


def _decode_png(path):
    reader = vtk.vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    pixels = vtk_to_numpy(scalars).reshape(height, width, scalars.GetNumberOfComponents())
    return pixels[::-1].copy()  # VTK's first row is the bottom one


def _encode_png(pixels):
    if pixels.ndim == 2:
        pixels = pixels[:, :, None]
    if pixels.ndim != 3 or pixels.shape[2] not in (1, 2, 3, 4):
        raise ValueError(f"an image of (height, width, channels), got shape {pixels.shape}")
    image = vtk.vtkImageData()
    image.SetDimensions(pixels.shape[1], pixels.shape[0], 1)
    flat = numpy.ascontiguousarray(pixels[::-1]).reshape(-1, pixels.shape[2])
    image.GetPointData().SetScalars(numpy_to_vtk(flat, deep=True))
    writer = vtk.vtkPNGWriter()
    writer.SetInputData(image)
    writer.WriteToMemoryOn()
    writer.Write()
    return bytes(memoryview(vtk_to_numpy(writer.GetResult())))
