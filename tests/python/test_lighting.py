"""A vtkCloudLightingProperty set from Python changes what the mapper draws: switching the
mapper's property from none to march after a first render re-renders the cloud lit (the mapper
watches its property), and the lit image is the CPU reference's march, not just any change; the
march's multiple-scattering setting is reached by name."""

import numpy as np

import cloudvis
from conftest import Scene, cloud_field, ramp_medium


def test_switching_to_march_lights_the_cloud_as_the_reference_does():
    scene = Scene(cloud_field(), ramp_medium(1.0, 0.6))
    lighting = scene.mapper.GetLightingProperty()
    lighting.SetModelToNone()
    unlit, unlit_pixels = scene.render()

    lighting.SetModelToMarch()
    lighting.SetAmbientStrength(0.1)
    lit, lit_pixels = scene.render()
    assert lighting.GetModelAsString() == "march"

    cloud = unlit[:, 3] > 1e-4
    brightest = float(unlit[cloud, :3].max())
    change = np.sqrt(((lit[cloud, :3].astype(np.float64) - unlit[cloud, :3]) ** 2).mean())
    print(f"none -> march: RMS change {change / brightest} of the brightest")
    largest_pixel_change = np.abs(lit_pixels.astype(int) - unlit_pixels).max()
    print(f"largest pixel change {largest_pixel_change} / 255")
    # Measured on llvmpipe: an RMS change of 0.099 of the brightest radiance and 60 / 255 at the
    # most changed pixel; 0 when the property change does not reach the mapper. The opacity does
    # not depend on the lighting model.
    assert change > 0.03 * brightest
    assert largest_pixel_change > 20
    np.testing.assert_allclose(lit[:, 3], unlit[:, 3], atol=1e-5)

    # The change is the march model's light, as the CPU reference computes it with the same
    # property (the gates of test_gpu_matches_reference.py).
    reference = scene.reference()
    gate = 1e-4 if scene.on_llvmpipe() else 1e-3
    assert np.abs(lit[:, :3].astype(np.float64) - reference[:, :3]).max() < gate * brightest


def test_multiple_scattering_is_chosen_by_name_on_the_property():
    """The march's choice between the multiple-scattering volume and the octaves, from Python: the
    setters reach the one LightingParameters (its name is the scene file's), a change marks the
    property modified, and the octave count stays a setting of its own."""
    lighting = cloudvis.vtkCloudLightingProperty()
    lighting.SetMultipleScatteringOctaves(5)
    lighting.SetMultipleScatteringToVolume()
    assert lighting.GetMultipleScattering() == cloudvis.vtkCloudLightingProperty.ScatteringVolume
    assert lighting.GetMultipleScatteringAsString() == "volume"
    before = lighting.GetMTime()
    lighting.SetMultipleScatteringToOctaves()
    assert lighting.GetMultipleScattering() == cloudvis.vtkCloudLightingProperty.ScatteringOctaves
    assert lighting.GetMultipleScatteringAsString() == "octaves"
    assert lighting.GetMTime() > before
    assert lighting.GetMultipleScatteringOctaves() == 5
