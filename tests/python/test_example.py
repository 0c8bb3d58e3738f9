"""docs/examples/render_cloud.py, the example docs/python.md shows, runs as a user runs it (a
separate python3, PYTHONPATH from the build) and writes a PNG of a lit cloud over the sky."""

import os
import subprocess
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

EXAMPLE = os.path.join(os.path.dirname(__file__), "..", "..", "docs", "examples", "render_cloud.py")
SKY = np.array([0.25, 0.4, 0.65]) * 255  # the example's background


def test_example_writes_a_picture_of_the_cloud(tmp_path):
    output = tmp_path / "cloud.png"
    run = subprocess.run([sys.executable, EXAMPLE, str(output)], capture_output=True, text=True,
                         timeout=240)
    assert run.returncode == 0, run.stderr
    assert "wrote" in run.stdout
    assert [p.name for p in tmp_path.iterdir()] == ["cloud.png"], "no partial file left behind"

    reader = vtk.vtkPNGReader()
    reader.SetFileName(str(output))
    reader.Update()
    assert reader.GetOutput().GetDimensions()[:2] == (256, 256)
    rgb = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(float)
    # The corners are sky; the cloud (white, lit) covers a good part of the picture.
    assert np.abs(rgb[0] - SKY).max() <= 1.0
    cloud = np.abs(rgb - SKY).max(axis=1) > 30
    print(f"cloud covers {cloud.mean():.2f} of the picture, brightest {rgb.max()}")
    assert cloud.mean() > 0.1
    assert rgb[cloud].mean() > SKY.mean() + 40
