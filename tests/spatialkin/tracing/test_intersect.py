"""sk.intersect: every component, each once, against the closed form and the topology of torus ∩ sphere,
and exact curves of other pairs."""
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from tests.oracles.closed_forms import (random_rotation, sphere_distance, torus_distance, torus_sphere_closed_form,
                     torus_sphere_components, torus_sphere_critical_radii)

import spatialkin as sk
from spatialkin.mechanisms.looper import reference

TOL = 1e-10


def check_torus_sphere(big, small, origin, rot, c_local, rho, sphere_rot):
    """intersect() against the oracles: component count by critical radii, every point and every dense
    evaluation within 1e-10 * scale of both surfaces (independent distance formulas), closed loops, and
    the exact curve (closed form per torus angle) covered to 1e-8 * scale."""
    torus = sk.Torus(big, small, sk.Frame(origin, rot))
    centre = origin + rot @ c_local
    sphere = sk.Sphere(rho, sk.Frame(centre, sphere_rot))
    scale = min(big + small, rho)
    curves = sk.intersect(torus, sphere, tol=TOL)
    assert len(curves) == torus_sphere_components(big, small, c_local, rho)
    for c in curves:
        assert c.closed and c.status == "closed"
        dense = c(np.linspace(0, c.length, 500))
        for pts in (c.points, dense):
            assert torus_distance((pts - origin) @ rot, big, small).max() <= TOL * scale
            assert sphere_distance(pts, centre, rho).max() <= TOL * scale
    phi = np.linspace(-np.pi, np.pi, 181)
    exact, _ = torus_sphere_closed_form(big, small, c_local, rho, phi)
    if len(exact):
        exact = origin + exact.reshape(-1, 3) @ rot.T
        gaps = np.min(np.stack([c.closest(exact)[1] for c in curves]), axis=0)
        assert gaps.max() <= 1e-8 * scale
    return curves


@pytest.mark.parametrize("band", [0, 1, 2])
def test_each_topology_band(band):
    """Ring torus, sphere centre off the axis: one loop, two loops, one loop between the critical radii."""
    big, small, c = 3.0, 1.0, np.array([1.0, 0.5, 0.7])
    radii = torus_sphere_critical_radii(big, small, c)
    rho = 0.5 * (radii[band] + radii[band + 1])
    curves = check_torus_sphere(big, small, np.zeros(3), np.eye(3), c, rho, np.eye(3))
    assert len(curves) == (2 if band == 1 else 1)


def test_outside_the_bands_nothing():
    big, small, c = 3.0, 1.0, np.array([1.0, 0.5, 0.7])
    radii = torus_sphere_critical_radii(big, small, c)
    torus = sk.Torus(big, small)
    for rho in (0.5 * radii[0], radii[3] + 0.5):
        assert sk.intersect(torus, sk.Sphere(rho, sk.Frame(c))) == []


def test_sphere_centred_on_the_axis_gives_two_circles():
    """d(v)^2 = R^2 + r^2 + cz^2 + 2Rr cos v - 2 r cz sin v = rho^2: two circles at heights r sin v of
    radius R + r cos v (a degenerate, Morse-Bott case for the seeding)."""
    big, small, cz, rho = 3.0, 1.0, 0.4, 3.3
    curves = sk.intersect(sk.Torus(big, small), sk.Sphere(rho, sk.Frame((0, 0, cz))))
    amp = np.hypot(2 * big * small, 2 * small * cz)
    base = np.arctan2(-2 * small * cz, 2 * big * small)
    spread = np.arccos((rho ** 2 - big ** 2 - small ** 2 - cz ** 2) / amp)
    expected = sorted(2 * np.pi * (big + small * np.cos(base + k * spread)) for k in (1, -1))
    assert len(curves) == 2
    lengths = sorted(c.length for c in curves)
    np.testing.assert_allclose(lengths, expected, rtol=1e-9)
    for c in curves:
        assert np.ptp(c.points[:, 2]) < 1e-12          # a horizontal circle


def test_meridian_plane_cuts_two_circles():
    """A plane through the torus axis: two meridian circles of radius r."""
    curves = sk.intersect(sk.Torus(3.0, 1.0), sk.Plane(sk.Frame.from_z_axis((0, 0, 0), (0, 1, 0))))
    assert len(curves) == 2
    for c in curves:
        assert c.closed and abs(c.length - 2 * np.pi) < 1e-8
        centre = np.array([np.sign(c.points[0, 0]) * 3.0, 0, 0])
        np.testing.assert_allclose(np.linalg.norm(c.points - centre, axis=1), 1.0, atol=1e-12)


def test_cone_and_plane_make_an_ellipse():
    """Cone x^2 + y^2 = z^2 tan^2 a cut by a plane not through the apex: a closed conic."""
    alpha = 0.5
    cone = sk.Cone(alpha, v_range=(0.1, 10.0))
    plane = sk.Plane(sk.Frame.from_z_axis((0, 0, 3.0), (0.3, 0.0, 1.0)))
    curves = sk.intersect(cone, plane)
    assert len(curves) == 1 and curves[0].closed
    p = curves[0].points
    np.testing.assert_allclose(p[:, 0] ** 2 + p[:, 1] ** 2, p[:, 2] ** 2 * np.tan(alpha) ** 2, atol=1e-11)
    np.testing.assert_allclose((p - [0, 0, 3.0]) @ np.array([0.3, 0, 1.0]), 0.0, atol=1e-12)


def test_equal_cylinders_cross_in_two_ellipses():
    """Cylinders of equal radius with axes x and y meet in the ellipses x = y and x = -y (semi-axes sqrt(2) r
    and r), which cross at (0, 0, +-r): two closed curves, each through both nodes."""
    r = 1.0
    cx = sk.Cylinder(r, sk.Frame.from_z_axis((0, 0, 0), (1, 0, 0)), v_range=(-3, 3))
    cy = sk.Cylinder(r, sk.Frame.from_z_axis((0, 0, 0), (0, 1, 0)), v_range=(-3, 3))
    curves = sk.intersect(cx, cy)
    perimeter = 4 * np.sqrt(2) * r * 1.3506438810476755   # 4 a E(e), e^2 = 1/2, E(1/sqrt 2) = 1.35064...
    assert len(curves) == 2
    signs = []
    for c in curves:
        assert c.closed and len(c.nodes) == 2 and abs(c.length - perimeter) < 1e-8
        ratio = c.points[:, 0] / np.where(np.abs(c.points[:, 1]) > 1e-3, c.points[:, 1], np.nan)
        signs.append(np.sign(np.nanmean(ratio)))
        np.testing.assert_allclose(np.abs(c.points[:, 0]), np.abs(c.points[:, 1]), atol=1e-11)
        np.testing.assert_allclose(np.abs(c.nodes[:, 2]), r, atol=1e-6)
    assert sorted(signs) == [-1, 1]          # one ellipse in x = y, the other in x = -y


def test_spindle_torus_of_the_looper_has_two_components():
    """The looper drive's spindle torus (R = 8, r = 50) and its rocker sphere: two assembly branches."""
    torus, sphere = reference.looper_pair()
    curves = sk.intersect(torus, sphere)
    assert len(curves) == 2 and all(c.closed for c in curves)
    assert min(abs(c.length - 59.7) for c in curves) < 0.05
    radius = reference.ROCKER_LENGTH
    for c in curves:
        assert torus_distance(c.points, reference.CRANK_RADIUS, reference.COUPLER_LENGTH).max() < TOL * radius
        assert sphere_distance(c.points, sphere.center, radius).max() < TOL * radius


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2 ** 32 - 1), band=st.integers(0, 2), where=st.floats(0.05, 0.95),
       ratio=st.floats(0.1, 0.9), big=st.floats(0.5, 50.0))
def test_random_frames_and_radii(seed, band, where, ratio, big):
    """General position: random frames (torus and sphere charts), ring tori, every band."""
    rng = np.random.default_rng(seed)
    small = ratio * big
    c_local = rng.uniform(-1, 1, 3) * np.array([big + small, big + small, 1.5 * small])
    radii = torus_sphere_critical_radii(big, small, c_local)
    rho = radii[band] + where * (radii[band + 1] - radii[band])
    check_torus_sphere(big, small, rng.uniform(-20, 20, 3), random_rotation(rng), c_local, rho,
                       random_rotation(rng))
