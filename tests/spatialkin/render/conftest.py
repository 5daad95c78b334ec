"""Rendering tests run off-screen (pyvista is a dependency: these tests do not skip without it)."""
import numpy as np
import pytest
import pyvista

import spatialkin as sk
from spatialkin.mechanisms.looper import reference
from spatialkin.mechanisms import LooperDrive

pyvista.OFF_SCREEN = True

#: The testing theme's window (pixels): small, so images are cheap to render and store.
TEST_WINDOW = (400, 400)


@pytest.fixture
def testing_theme():
    """A small fixed theme: 400 x 400, white background, no multisampling, no anti-aliasing, flat shading
    unless an item asks for smooth."""
    theme = pyvista.themes.DocumentTheme()
    theme.window_size = list(TEST_WINDOW)
    theme.multi_samples = 0
    theme.anti_aliasing = None
    theme.smooth_shading = False
    return theme


@pytest.fixture(scope="session")
def pair():
    """The looper's torus and sphere (reference geometry) and their two closed components."""
    torus, sphere = reference.looper_pair()
    return torus, sphere, sk.intersect(torus, sphere)


@pytest.fixture(scope="session")
def motion():
    """The reference looper drive over a turn in 2 degree steps."""
    return LooperDrive.reference().solve(np.radians(np.arange(0.0, 360.0 + 1e-9, 2.0)))
