"""Bad parameters given from Python are refused in words, through VTK's ErrorEvent, and leave no
picture and no crash: the Python process carries on and can render again once fixed."""

import numpy as np

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
