"""The cloud model and the cellular noises from Python (issue 22): the setters exist and
generate what they say, a coverage map made with numpy leaves its empty half empty, a tiled noise
repeats across a field one period wide, and a bad layer or map is refused in words."""

import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy

import cloudvis

Source = cloudvis.vtkCloudDensitySource


def density_of(source):
    source.Modified()
    source.Update()
    image = source.GetOutput()
    nx, ny, nz = image.GetDimensions()
    # VTK orders points x fastest: index [z, y, x].
    return vtk_to_numpy(image.GetPointData().GetArray("density")).reshape(nz, ny, nx)


def cloudscape(nx=41, ny=26, nz=30):
    """A cumulus layer from -0.5 to 1 under a procedural weather map, over [-2, 2] x [-1, 1.5] x
    [-2, 2]: y spacing 0.1, so the base and the top fall on voxels 5 and 20."""
    source = Source()
    source.SetDimensions(nx, ny, nz)
    source.SetBounds(-2.0, 2.0, -1.0, 1.5, -2.0, 2.0)
    source.SetDensityModelToCloud()
    source.SetCloudType(Source.Cumulus)
    source.SetCloudAltitudes(-0.5, 1.0)
    source.SetCloudCoverage(0.6)
    source.SetCoverageSource(Source.NoiseCoverage)
    source.SetWeatherMap(2.0, 6, 0.6)
    source.SetCloudNoiseScales(1.5, 0.6)
    source.SetCloudErosion(0.4)
    source.SetCloudCurl(0.3)
    source.SetCloudShear(0.2, 0.0)
    source.SetNoiseSeed(7)
    return source


def half_map(full=1.0):
    """A 16 x 16 map over x (first axis) and z: 0 in the columns i < 8, `full` in the others."""
    values = np.zeros((16, 16), dtype=np.float32)
    values[:, 8:] = full
    image = vtk.vtkImageData()
    image.SetDimensions(16, 1, 16)
    array = numpy_to_vtk(values.ravel(), deep=True)
    image.GetPointData().SetScalars(array)
    return image


def test_cloud_setters_read_back_and_the_layer_holds_cloud_only_between_base_and_top():
    source = cloudscape()
    assert source.GetDensityModel() == Source.CloudModel
    assert source.GetCloudType() == Source.Cumulus
    assert (source.GetCloudBase(), source.GetCloudTop()) == (-0.5, 1.0)
    assert source.GetCloudCoverage() == 0.6
    assert source.GetCoverageSource() == Source.NoiseCoverage
    assert source.Validate() == ""

    density = density_of(source)
    assert (density > 0).sum() > 1000, "the layer must hold cloud"
    assert density[:, :5, :].max() == 0.0, "no cloud below the base"
    assert density[:, 21:, :].max() == 0.0, "no cloud above the top"
    assert density.max() <= source.GetDensityScale()

    source.SetCloudCoverage(0.0)
    assert density_of(source).max() == 0.0, "coverage 0 is an empty sky"


def test_a_coverage_map_from_numpy_leaves_its_empty_half_empty():
    source = cloudscape(nx=61)
    source.SetCloudShear(0.0, 0.0)
    source.SetWind(0.0, 0.0, 0.0)
    source.SetCloudCoverage(1.0)
    source.SetCoverageMap(half_map())
    assert source.GetCoverageSource() == Source.MapCoverage
    density = density_of(source)
    # Voxel i lies at x = -2 + i / 15; the map's last 0 (column 7) at x = -2 + 7 / 15 * 4.
    assert density[:, :, :29].max() == 0.0
    assert (density[:, :, 29:] > 0).sum() > 1000


def test_every_cellular_noise_generates_and_a_tiled_one_repeats_across_one_period():
    for noise in (Source.WorleyNoise, Source.InvertedWorleyNoise, Source.PerlinWorleyNoise):
        source = Source()
        source.SetDimensions(33, 33, 33)
        source.SetBounds(-1.0, 3.0, 0.0, 4.0, -2.0, 2.0)  # spacing 1/8: every voxel exact
        source.SetDensityModelToFbmFalloff()
        source.RemoveAllShapes()
        source.AddBox(0.0, 0.0, 0.0, 100.0, 100.0, 100.0)
        source.SetNoiseType(noise)
        source.SetNoiseOctaves(3)
        source.SetNoiseFrequency(0.75)
        source.SetNoiseLacunarity(2.0)
        source.SetNoiseLacunarityIncrement(0.0)
        source.SetNoiseAmplitude(1.0)
        source.SetNoisePeriod(3)  # 3 / 0.75 = 4 world units: the field's width on every axis
        source.SetWind(0.0, 0.0, 0.0)
        assert source.GetNoisePeriod() == 3
        assert source.Validate() == ""
        density = density_of(source)
        assert (density > 0).sum() > 1000, noise
        np.testing.assert_array_equal(density[:, :, 0], density[:, :, -1])
        np.testing.assert_array_equal(density[:, 0, :], density[:, -1, :])
        np.testing.assert_array_equal(density[0, :, :], density[-1, :, :])


def test_a_bad_layer_or_map_is_refused_in_words(errors):
    source = errors.watch(cloudscape())
    cube = vtk.vtkImageData()
    cube.SetDimensions(4, 4, 4)
    cube.AllocateScalars(vtk.VTK_FLOAT, 1)
    source.SetCoverageMap(cube)
    assert any("a coverage map must be a 2-D image, got 4 x 4 x 4 points" in m
               for m in errors.messages)
    source.SetCoverageMap(half_map(1.5))
    assert any("is outside [0, 1]" in m for m in errors.messages)
    assert source.GetCoverageSource() == Source.NoiseCoverage, "a refused map changes nothing"

    errors.messages.clear()
    source.SetCloudAltitudes(1.0, 0.5)
    assert "the cloud base (1) must lie below the top (0.5)" in source.Validate()
    source.Update()
    assert any("must lie below the top" in m for m in errors.messages)
    assert source.GetOutput().GetNumberOfPoints() == 0

    # Fixed, the same source generates.
    source.SetCloudAltitudes(-0.5, 1.0)
    assert (density_of(source) > 0).sum() > 1000

    # A noise period with a fractional lacunarity cannot repeat: refused.
    source.SetNoisePeriod(4)
    source.SetNoiseLacunarity(2.02)
    assert "whole-number lacunarity" in source.Validate()
