import numpy as np
import pytest

import spatialkin as sk


def test_frame_defaults_and_maps():
    f = sk.Frame((1, 2, 3), sk.rotation_about((0, 0, 1), np.pi / 2))
    # oracle: a quarter turn about z maps local x to global y
    np.testing.assert_allclose(f.to_global([1, 0, 0]), [1, 3, 3], atol=1e-15)
    np.testing.assert_allclose(f.to_local(f.to_global([[0.3, -0.2, 5.0]])), [[0.3, -0.2, 5.0]], atol=1e-14)


@pytest.mark.parametrize("rotation, fragment", [
    (np.diag([1.0, 1.0, 2.0]), "orthonormal"),
    (np.diag([1.0, 1.0, -1.0]), "right-handed"),
    (np.full((3, 3), np.nan), "finite"),
    (np.eye(2), "shape"),
])
def test_frame_rejects_bad_rotation(rotation, fragment):
    with pytest.raises(ValueError, match=fragment) as info:
        sk.Frame((0, 0, 0), rotation)
    assert "rotation" in str(info.value)


def test_frame_rejects_bad_origin():
    with pytest.raises(ValueError, match="origin"):
        sk.Frame((0, np.inf, 0))
    with pytest.raises(ValueError, match="origin"):
        sk.Frame((0, 0))


def test_rotation_about_is_proper_and_exact():
    r = sk.rotation_about((1, 1, 0), 0.7)
    np.testing.assert_allclose(r.T @ r, np.eye(3), atol=1e-15)
    assert np.isclose(np.linalg.det(r), 1.0)
    # the axis is fixed
    np.testing.assert_allclose(r @ np.array([1, 1, 0]), [1, 1, 0], atol=1e-15)
    z = sk.rotation_to_z((0.0, 3.0, 4.0))
    np.testing.assert_allclose(z[:, 2], [0, 0.6, 0.8], atol=1e-15)
    np.testing.assert_allclose(z.T @ z, np.eye(3), atol=1e-15)
