"""Image regression of the 3-D pictures against stored baselines (tests/spatialkin/render/baseline).

The comparison is tolerant: the root-mean-square difference of the RGB values in [0, 1] over the pixels
that are not background in either image must stay below IMAGE_RMS_TOLERANCE. Measured here: 0 between
runs (the same Mesa llvmpipe); the tolerance leaves room for other Mesa / VTK versions (anti-aliasing of
edges, text), while turning the crank by 10 degrees or dropping the surfaces exceeds it several times over
(test_the_comparison_can_fail). Set SPATIALKIN_UPDATE_BASELINES=1 to rewrite the baselines after a wanted
change, then look at them.
"""
import os

import numpy as np
import pytest
from PIL import Image

from spatialkin.render import Scene, looper_scene

BASELINE = os.path.join(os.path.dirname(__file__), "baseline")
#: RMS difference (RGB in [0, 1], over the pixels not background in either image) allowed.
IMAGE_RMS_TOLERANCE = 0.08
#: Fixed cameras: position, focal point, view up (mm); the scene is then fitted along that direction and
#: zoomed. The curves are seen from above the sphere through both surfaces.
CURVES_CAMERA, CURVES_ZOOM = [(60.0, -90.0, 180.0), (3.0, 0.0, 50.0), (0.0, 0.0, 1.0)], 1.8
CAMERA = [(180.0, -160.0, 140.0), (3.0, 0.0, 45.0), (0.0, 0.0, 1.0)]


def rms_difference(actual, expected):
    """RMS of the RGB difference (values in [0, 1]) over the pixels where either image is not white."""
    a = np.asarray(actual, dtype=float)[..., :3] / 255.0
    e = np.asarray(expected, dtype=float)[..., :3] / 255.0
    assert a.shape == e.shape, f"image size {a.shape} differs from the baseline's {e.shape}"
    drawn = (a < 1.0).any(axis=-1) | (e < 1.0).any(axis=-1)
    if not drawn.any():
        return 0.0
    return float(np.sqrt(np.mean((a[drawn] - e[drawn]) ** 2)))


def check_image(image, name):
    path = os.path.join(BASELINE, name)
    if os.environ.get("SPATIALKIN_UPDATE_BASELINES") == "1":
        Image.fromarray(image).save(path)
    expected = np.asarray(Image.open(path).convert("RGB"))
    rms = rms_difference(image, expected)
    if rms >= IMAGE_RMS_TOLERANCE:
        out = os.path.join(BASELINE, "..", f"_actual_{name}")
        Image.fromarray(image).save(out)
        pytest.fail(f"{name}: RMS difference {rms:.4f} >= {IMAGE_RMS_TOLERANCE} (actual image kept at {out})")


def curves_scene(pair, theme):
    torus, sphere, curves = pair
    scene = Scene(theme=theme, camera_position=CURVES_CAMERA, zoom=CURVES_ZOOM)
    scene.add_surface(torus, name="torus", color="#9ecae1", resolution=(64, 32))
    scene.add_surface(sphere, name="sphere", color="#fdae6b", resolution=(48, 24))
    for k, curve in enumerate(curves):
        scene.add_curve(curve, name=f"curve{k}", color_by="s", radius=0.8, scalar_bar=False)
    return scene


def mechanism_scene(motion, theme, crank_angle_deg=60.0):
    index = int(np.argmin(np.abs(np.degrees(motion.crank_angle) - crank_angle_deg)))
    return looper_scene(motion, index, velocities=8, theme=theme, camera_position=CAMERA)


def test_image_curves_on_translucent_surfaces(pair, testing_theme):
    check_image(curves_scene(pair, testing_theme).image(), "curves_torus_sphere.png")


def test_image_looper_mechanism(motion, testing_theme):
    check_image(mechanism_scene(motion, testing_theme).image(), "looper_mechanism.png")


def test_the_comparison_can_fail(pair, motion, testing_theme):
    """Changes a person would see exceed the tolerance: the crank turned by 10 degrees, the surfaces
    left out."""
    turned = mechanism_scene(motion, testing_theme, crank_angle_deg=70.0).image()
    expected = np.asarray(Image.open(os.path.join(BASELINE, "looper_mechanism.png")).convert("RGB"))
    assert rms_difference(turned, expected) > IMAGE_RMS_TOLERANCE
    torus, sphere, curves = pair
    bare = Scene(theme=testing_theme, camera_position=CURVES_CAMERA, zoom=CURVES_ZOOM)
    for k, curve in enumerate(curves):
        bare.add_curve(curve, name=f"curve{k}", color_by="s", radius=0.8, scalar_bar=False)
    expected = np.asarray(Image.open(os.path.join(BASELINE, "curves_torus_sphere.png")).convert("RGB"))
    assert rms_difference(bare.image(), expected) > IMAGE_RMS_TOLERANCE
