#!/usr/bin/env python3
"""Render a procedural cloud with cloudvis from Python (docs/python.md).

    PYTHONPATH=$(make -s python-path) /usr/bin/python3 docs/examples/render_cloud.py cloud.png

Generates the article's cloud (a sphere plus fBm noise) with vtkCloudDensitySource, looks at its
densities through numpy, draws it with vtkCloudVolumeMapper and the march lighting model in an
ordinary VTK scene, and writes the picture to a PNG file. tests/python/test_example.py runs it.
"""

import os
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

import cloudvis


def main(output="cloud.png", size=256):
    # The density field: 96^3 voxels over [-1.6, 1.6]^3, noise drifting with the wind over time.
    source = cloudvis.vtkCloudDensitySource()
    source.SetDimensions(96, 96, 96)
    source.SetBounds(-1.6, 1.6, -1.6, 1.6, -1.6, 1.6)
    source.SetNoiseType(cloudvis.vtkCloudDensitySource.PerlinNoise)
    source.SetNoiseOctaves(5)
    source.SetTime(2.0)
    source.Update()
    density = vtk_to_numpy(source.GetOutput().GetPointData().GetArray("density"))
    print(f"density: {density.size} voxels, {np.count_nonzero(density)} in the cloud, "
          f"max {density.max():.3f}")

    # The medium: opacity per unit length rising with density, a white albedo.
    medium = vtk.vtkVolumeProperty()
    albedo = vtk.vtkColorTransferFunction()
    albedo.AddRGBPoint(0.0, 1.0, 1.0, 1.0)
    opacity = vtk.vtkPiecewiseFunction()
    opacity.AddPoint(0.0, 0.0)
    opacity.AddPoint(float(density.max()), 0.9)
    medium.SetColor(albedo)
    medium.SetScalarOpacity(opacity)
    medium.SetScalarOpacityUnitDistance(0.3)

    # The mapper, lit by a light march toward the sun, with some sky light.
    mapper = cloudvis.vtkCloudVolumeMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    lighting = mapper.GetLightingProperty()
    lighting.SetModelToMarch()
    lighting.SetAmbientColor(0.55, 0.65, 0.9)
    lighting.SetAmbientStrength(0.3)

    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(medium)
    renderer = vtk.vtkRenderer()
    renderer.AddVolume(volume)
    renderer.SetBackground(0.25, 0.4, 0.65)
    sun = vtk.vtkLight()
    sun.SetLightTypeToSceneLight()
    sun.SetPositional(False)
    sun.SetPosition(4.0, 6.0, 3.0)
    sun.SetFocalPoint(0.0, 0.0, 0.0)
    sun.SetIntensity(1.2)
    renderer.AddLight(sun)
    renderer.GetActiveCamera().SetPosition(0.0, 0.4, 6.5)
    renderer.ResetCameraClippingRange()

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)  # the cloud mapper refuses multisampled windows (docs/python.md)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    window.Render()
    if mapper.GetLastError():
        print(f"render_cloud.py: the cloud was not drawn: {mapper.GetLastError()}", file=sys.stderr)
        return 1

    # The picture, written to a temporary file and renamed, so a failed write leaves no file.
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    writer = vtk.vtkPNGWriter()
    writer.SetInputConnection(grab.GetOutputPort())
    partial = output + ".partial.png"
    writer.SetFileName(partial)
    writer.Write()
    if writer.GetErrorCode() != 0 or not os.path.exists(partial):
        print(f"render_cloud.py: could not write {output}", file=sys.stderr)
        return 1
    os.replace(partial, output)
    print(f"wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:2]))
