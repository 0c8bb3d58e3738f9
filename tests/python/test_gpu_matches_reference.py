"""vtkCloudVolumeMapper in an ordinary VTK Python pipeline (vtkCloudDensitySource -> mapper ->
vtkVolume -> offscreen vtkRenderWindow) draws the cloud, and draws what the CPU reference
renderer (vtkCloudReferenceRenderer) computes from the same objects.

Gates: those of tests/render/TestGpuMatchesCpuReference.cxx for the float images (relative to
the brightest reference radiance, over the pixels where either image has opacity above 1e-4):
on llvmpipe RMS 1e-5 and max 1e-4 (measured here: RMS 0.2e-6 .. 1.9e-6, max 1.6e-6 .. 9.3e-6,
opacity max 4.8e-6), elsewhere 1e-4 and 1e-3 (the sphere's max 0.05: another GPU's rounding may
add or drop a sample at its sharp surface). The window's 8-bit pixels are the float image
rounded: within 1/255 of it (measured 0.5/255, the rounding itself).
"""

import numpy as np
import pytest
import vtk
from vtk.util.numpy_support import vtk_to_numpy

from conftest import SIZE, Scene, cloud_field, ramp_medium, sphere_field

CASES = {
    "cloud-none": (lambda: cloud_field(), 0.6, False, "none"),
    "cloud-march": (lambda: cloud_field(), 0.6, False, "march"),
    "sphere-march": (lambda: sphere_field(1.2, 40, 1.6, 1.0), 0.8, True, "march"),
}


def compare(gpu, cpu):
    """Brightest reference radiance, cloud pixel count, and the RMS and max colour differences
    and max opacity difference over the cloud pixels."""
    cloud = (gpu[:, 3] > 1e-4) | (cpu[:, 3] > 1e-4)
    difference = np.abs(gpu[cloud, :3].astype(np.float64) - cpu[cloud, :3])
    brightest = float(cpu[cloud, :3].max()) if cloud.any() else 0.0
    rms = float(np.sqrt((difference**2).mean())) if cloud.any() else 0.0
    alpha = float(np.abs(gpu[cloud, 3].astype(np.float64) - cpu[cloud, 3]).max()) if cloud.any() else 0.0
    return brightest, int(cloud.sum()), rms, float(difference.max(initial=0.0)), alpha


@pytest.mark.parametrize("case", sorted(CASES))
def test_gpu_image_is_a_cloud_and_matches_the_cpu_reference(case):
    make_field, opacity, parallel, model = CASES[case]
    scene = Scene(make_field(), ramp_medium(1.0, opacity), parallel)
    lighting = scene.mapper.GetLightingProperty()
    lighting.SetAmbientColor(0.6, 0.6, 0.75)
    lighting.SetAmbientStrength(0.2)
    getattr(lighting, "SetModelTo" + model.capitalize())()

    gpu, pixels = scene.render()
    assert scene.mapper.GetLastError() == ""
    assert gpu is not None and gpu.shape == (SIZE * SIZE, 4), "the mapper drew no cloud"
    cpu = scene.reference()
    assert cpu.shape == (SIZE * SIZE, 4), "the reference rendered nothing"

    # Not blank: the cloud covers a good part of the window and is bright, in the window's
    # pixels too.
    brightest, cloud_pixels, rms, largest, alpha = compare(gpu, cpu)
    print(f"{case}: {cloud_pixels} cloud pixels, brightest {brightest}, RMS {rms / brightest}, "
          f"max {largest / brightest} of it, alpha max {alpha}")
    assert cloud_pixels > SIZE * SIZE / 10
    assert brightest > 0.05
    assert (pixels.max(axis=1) > 25).sum() > SIZE * SIZE / 10

    llvmpipe = scene.on_llvmpipe()
    rms_gate = 1e-5 if llvmpipe else 1e-4
    max_gate = 1e-4 if llvmpipe else (0.05 if parallel else 1e-3)
    assert rms < rms_gate * brightest
    assert largest < max_gate * brightest
    assert alpha < max_gate

    # The per-pixel samples and depth reach numpy too: samples were taken and a depth found
    # wherever the cloud is opaque enough to show.
    auxiliary = vtk.vtkImageData()
    assert scene.mapper.ReadAuxiliary(scene.renderer, auxiliary)
    channels = vtk_to_numpy(auxiliary.GetPointData().GetArray("auxiliary"))
    assert channels.shape == (SIZE * SIZE, 4)
    shown_cloud = gpu[:, 3] > 0.1
    assert (channels[shown_cloud, 0] >= 1).all()
    assert np.isfinite(channels[shown_cloud, 2]).all()

    # What the window shows is that image over the black background, rounded to 8 bits.
    shown = np.clip(gpu[:, :3].astype(np.float64), 0.0, 1.0)
    assert np.abs(pixels / 255.0 - shown).max() < 1.0 / 255.0
