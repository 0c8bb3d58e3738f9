"""vtkCloudDensitySource from Python, read through numpy: a constant sphere has its density at
the voxels inside and 0 at those outside, on the lattice its bounds and dimensions define."""

import os

import numpy as np
import vtkmodules
import vtkmodules.vtkCommonExecutionModel
from vtk.util.numpy_support import vtk_to_numpy

import cloudvis
from conftest import sphere_field


def density_array(source):
    source.Update()
    image = source.GetOutput()
    nx, ny, nz = image.GetDimensions()
    density = vtk_to_numpy(image.GetPointData().GetArray("density"))
    # VTK orders points x fastest: index [z, y, x].
    return image, density.reshape(nz, ny, nx)


def test_constant_sphere_has_its_density_inside_and_none_outside():
    source = sphere_field(radius=0.9, size=21, half_width=2.0, density=2.5)
    image, density = density_array(source)

    assert image.GetDimensions() == (21, 21, 21)
    np.testing.assert_allclose(image.GetOrigin(), (-2.0, -2.0, -2.0))
    np.testing.assert_allclose(image.GetSpacing(), (0.2, 0.2, 0.2))
    assert density.dtype == np.float32

    # Known voxels: the centre and a voxel 0.8 from it along x are inside, one 1.0 away and a
    # corner are outside.
    assert density[10, 10, 10] == 2.5
    assert density[10, 10, 14] == 2.5
    assert density[10, 10, 15] == 0.0
    assert density[0, 0, 0] == 0.0

    # Every voxel: 2.5 exactly where the lattice point lies inside the sphere (no lattice point
    # lies within 1% of its surface), 0 elsewhere.
    axis = np.linspace(-2.0, 2.0, 21)
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    inside = x * x + y * y + z * z < 0.9 * 0.9
    np.testing.assert_array_equal(density, np.where(inside, 2.5, 0.0).astype(np.float32))
    assert inside.sum() == 389


def test_shapes_and_noise_set_from_python_change_the_field():
    source = sphere_field(radius=0.9, size=21, half_width=2.0, density=1.0)
    source.AddBox(1.5, 0.0, 0.0, 0.3, 0.3, 0.3)
    assert source.GetNumberOfShapes() == 2
    _, two_shapes = density_array(source)
    # The box's centre voxel (x = 1.6 is the lattice point nearest 1.5: index 18) is now inside.
    assert two_shapes[10, 10, 18] == 1.0

    source.SetDensityModelToSdfPlusFbm()
    source.SetNoiseType(cloudvis.vtkCloudDensitySource.PerlinNoise)
    source.SetNoiseSeed(7)
    _, noisy = density_array(source)
    # sdf + fBm: inside the sphere the density now varies with the noise.
    assert noisy[8:13, 8:13, 8:13].std() > 0.01
    source.SetNoiseSeed(8)
    _, other_seed = density_array(source)
    assert not np.array_equal(noisy, other_seed)


def test_out_of_range_choices_are_refused_and_leave_the_field_alone(errors):
    source = errors.watch(sphere_field())
    source.SetDensityModel(7)
    source.SetNoiseType(-1)
    source.SetShapeScale(5, 2.0)
    assert source.GetDensityModel() == cloudvis.vtkCloudDensitySource.ConstantModel
    assert source.GetNoiseType() == cloudvis.vtkCloudDensitySource.NoNoise
    assert len(errors.messages) == 3
    assert "density model 7" in errors.messages[0]
    assert "noise type -1" in errors.messages[1]
    assert "shape 5 does not exist" in errors.messages[2]


def test_classes_are_ordinary_vtk_classes_of_debians_vtkmodules():
    # One VTK in the process: Debian's python3-vtk9, whose classes the cloudvis ones derive from
    # and connect to.
    assert vtkmodules.__file__.startswith("/usr/lib/python3/dist-packages/vtkmodules/")
    source = sphere_field()
    assert isinstance(source, vtkmodules.vtkCommonExecutionModel.vtkImageAlgorithm)
    assert isinstance(cloudvis.vtkCloudVolumeMapper().GetLightingProperty(),
                      cloudvis.vtkCloudLightingProperty)
    # The package is the build's (PYTHONPATH as docs/python.md says), not an installed copy.
    assert os.path.basename(os.path.dirname(cloudvis.__file__)) == "cloudvis"
    assert os.path.dirname(os.path.dirname(cloudvis.__file__)) in os.environ["PYTHONPATH"].split(":")
