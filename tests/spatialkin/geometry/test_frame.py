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


@pytest.mark.parametrize("size", [1e-300, 1e-170, 1.0, 1e160, 1e300])
def test_axes_of_any_length(size):
    """An axis is a direction whatever its length: the rotations from (1, 2, 2) x size equal those from (1, 2, 2)
    (the unit axis (1, 2, 2) / 3, by Rodrigues' formula written apart), and the frame's z follows it."""
    axis = np.array([1.0, 2.0, 2.0])
    unit = axis / 3.0
    k = np.array([[0, -unit[2], unit[1]], [unit[2], 0, -unit[0]], [-unit[1], unit[0], 0]])
    rodrigues = np.eye(3) + np.sin(0.9) * k + (1 - np.cos(0.9)) * (k @ k)
    np.testing.assert_allclose(sk.rotation_about(axis * size, 0.9), rodrigues, atol=1e-15)
    z = sk.rotation_to_z(axis * size)
    np.testing.assert_allclose(z[:, 2], unit, atol=1e-15)
    np.testing.assert_allclose(z.T @ z, np.eye(3), atol=1e-15)
    frame = sk.Frame.from_z_axis((0.0, 0.0, 0.0), axis * size)
    np.testing.assert_allclose(frame.rotation[:, 2], unit, atol=1e-15)


@pytest.mark.parametrize("bad, kind", [(np.array([1 + 1j, 0, 0]), "complex"), ([True, False, False], "bool"),
                                       (np.array(["1", "0", "0"]), "str")])
def test_frames_refuse_values_that_are_not_real(bad, kind):
    """Complex, bool or str values are refused, naming the argument (numpy would drop imaginary parts, read True
    as 1 or parse the strings)."""
    with pytest.raises(TypeError, match=f"origin must be an array of real numbers, got {kind}"):
        sk.Frame(bad)
    with pytest.raises(TypeError, match="rotation must be an array of real numbers, got complex"):
        sk.Frame(rotation=np.eye(3) + 0j)
    with pytest.raises(TypeError, match="axis must be an array of real numbers"):
        sk.rotation_about(bad, 1.0)


@pytest.mark.parametrize("method, name", [("to_global", "local_points"), ("to_local", "points")])
@pytest.mark.parametrize("bad, error, fragment", [
    ([np.nan, 0.0, 0.0], ValueError, "must be finite"),
    ([[0.0, 0.0, 0.0], [1.0, np.inf, 0.0]], ValueError, "must be finite"),
    ([1.0, 2.0], ValueError, r"must have shape \(\.\.\., 3\), got \(2,\)"),
    ("abc", TypeError, "must be an array of real numbers"),
    ([1j, 0.0, 0.0], TypeError, "must be an array of real numbers"),
])
def test_frame_maps_refuse_bad_points(method, name, bad, error, fragment):
    frame = sk.Frame((1.0, 2.0, 3.0), sk.rotation_about((0.0, 0.0, 1.0), 0.5))
    with pytest.raises(error, match=f"^{name} {fragment}"):
        getattr(frame, method)(bad)


def test_frame_maps_keep_any_leading_shape():
    """Oracle: origin + R p point by point; an empty set of points maps to an empty set."""
    frame = sk.Frame((1.0, 2.0, 3.0), sk.rotation_about((1.0, 1.0, 0.0), 0.7))
    pts = np.random.default_rng(0).normal(size=(4, 5, 3))
    out = frame.to_global(pts)
    assert out.shape == (4, 5, 3)
    assert np.allclose(out[2, 3], frame.origin + frame.rotation @ pts[2, 3], rtol=0, atol=1e-14)
    assert np.allclose(frame.to_local(out), pts, rtol=0, atol=1e-14)
    assert frame.to_global(np.zeros((0, 3))).shape == (0, 3)
