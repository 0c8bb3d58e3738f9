"""Bad parameters given from Python are refused in words, through VTK's ErrorEvent, and leave no
picture and no crash: the Python process carries on and can render again once fixed."""

import numpy as np
import pytest
import vtk

import cloudvis
from conftest import SIZE, Scene, cloud_field, ramp_medium, sphere_field


def test_mapper_refuses_a_negative_step_and_draws_nothing(errors):
    scene = Scene(cloud_field(24), ramp_medium())
    errors.watch(scene.mapper)
    scene.mapper.SetSampleDistance(-0.05)
    gpu, pixels = scene.render()

    assert "the step (sample distance) -0.05 must be a finite number >= 0" in scene.mapper.GetLastError()
    assert any("sample distance" in message for message in errors.messages)
    assert gpu is None, "a refused frame must leave no cloud image"
    assert pixels.max() == 0, "the refused volume must not be drawn"

    # Fixed, the same objects render the cloud.
    scene.mapper.SetSampleDistance(0.05)
    gpu, pixels = scene.render()
    assert scene.mapper.GetLastError() == ""
    assert gpu is not None and gpu[:, 3].max() > 0.5
    assert pixels.max() > 25


def test_reference_renderer_refuses_a_negative_step_and_outputs_no_image(errors):
    scene = Scene(cloud_field(24), ramp_medium())
    scene.mapper.SetSampleDistance(-1.0)
    reference = cloudvis.vtkCloudReferenceRenderer()
    errors.watch(reference)
    reference.SetInputConnection(scene.mapper.GetInputConnection(0, 0))
    reference.SetImageSize(SIZE, SIZE)
    reference.SetVolumeProperty(scene.volume.GetProperty())
    reference.SetSampleDistance(-1.0)
    reference.Update()

    assert any("the step (sample distance) -1 must be a finite number >= 0" in message
               for message in errors.messages)
    assert reference.GetOutput().GetNumberOfPoints() == 0


def test_density_source_refuses_an_empty_lattice_and_a_nan_scale(errors):
    source = errors.watch(sphere_field())
    source.SetDimensions(0, 21, 21)
    source.Update()
    assert any("dimensions must be at least 1 along each axis, got 0 along x" in message
               for message in errors.messages)
    assert source.GetOutput().GetNumberOfPoints() == 0

    source.SetDimensions(21, 21, 21)
    source.SetDensityScale(float("nan"))
    errors.messages.clear()
    source.Update()
    assert errors.messages, "a NaN density scale must be refused"
    scalars = source.GetOutput().GetPointData().GetScalars()
    assert scalars is None or not np.isnan(
        np.frombuffer(memoryview(scalars), dtype=np.float32)).any()


def test_mapper_refuses_a_multisampled_window_rather_than_drawing_nothing(errors):
    # vtkRenderWindow's default: multisampling where the driver has it (llvmpipe does). The
    # mapper cannot copy the scene's depth from such a framebuffer; it must say so, not show an
    # empty sky.
    scene = Scene(cloud_field(24), ramp_medium())
    errors.watch(scene.mapper)
    scene.window.SetMultiSamples(8)
    gpu, pixels = scene.render()
    error = scene.mapper.GetLastError()
    if error:
        assert "the render window is multisampled" in error
        assert "SetMultiSamples(0)" in error
        assert any("multisampled" in message for message in errors.messages)
        assert pixels.max() == 0
    else:  # a driver without multisampling: the window is single-sampled after all
        assert gpu is not None and pixels.max() > 25


# Dimensions the source refuses, each once per axis: VTK still asks the source for data when a
# render updates the mapper (vtkVolume does, whatever RequestInformation said), and the source
# used to fill an extent nobody had set, aborting the interpreter (std::bad_alloc, length_error)
# in most runs.
EMPTY_LATTICES = [(0, 21, 21), (21, -3, 21), (21, 21, -1)]


@pytest.mark.parametrize("dimensions", EMPTY_LATTICES)
def test_mapper_fed_an_empty_lattice_draws_nothing_and_says_why(errors, dimensions):
    source = errors.watch(cloud_field(24))
    source.SetDimensions(*dimensions)
    scene = Scene(source, ramp_medium())
    errors.watch(scene.mapper)
    for _ in range(3):
        gpu, pixels = scene.render()
        assert gpu is None, "a refused field must leave no cloud image"
        assert pixels.max() == 0
    assert any("dimensions must be at least 1 along each axis" in message
               for message in errors.messages), errors.messages

    # Fixed, the same objects render the cloud.
    source.SetDimensions(24, 24, 24)
    gpu, pixels = scene.render()
    assert scene.mapper.GetLastError() == ""
    assert gpu is not None and pixels.max() > 25


@pytest.mark.parametrize("renderer", ["vtkCloudReferenceRenderer", "vtkCloudPathTracer"])
@pytest.mark.parametrize("dimensions", EMPTY_LATTICES)
def test_cpu_renderers_fed_an_empty_lattice_output_nothing_and_say_why(errors, renderer, dimensions):
    source = errors.watch(cloud_field(24))
    source.SetDimensions(*dimensions)
    cpu = errors.watch(getattr(cloudvis, renderer)())
    cpu.SetInputConnection(source.GetOutputPort())
    cpu.SetImageSize(8, 8)
    cpu.SetVolumeProperty(ramp_medium())
    cpu.Update()
    assert any("dimensions must be at least 1 along each axis" in message
               for message in errors.messages), errors.messages
    assert cpu.GetOutput().GetNumberOfPoints() == 0


def test_occupancy_filter_fed_an_empty_lattice_outputs_nothing_and_says_why(errors):
    source = errors.watch(cloud_field(24))
    source.SetDimensions(0, 24, 24)
    occupancy = errors.watch(cloudvis.vtkCloudOccupancyFilter())
    occupancy.SetInputConnection(source.GetOutputPort())
    occupancy.SetTransferFunction(ramp_medium())
    occupancy.Update()
    assert any("dimensions must be at least 1 along each axis" in message
               for message in errors.messages), errors.messages
    assert occupancy.GetOutput().GetNumberOfPoints() == 0


def test_mapper_without_a_field_says_so(errors):
    scene = Scene(cloud_field(24), ramp_medium())
    errors.watch(scene.mapper)
    scene.mapper.SetInputData(vtk.vtkImageData())
    gpu, pixels = scene.render()
    assert gpu is None and pixels.max() == 0
    assert "no scalar array" in scene.mapper.GetLastError()
