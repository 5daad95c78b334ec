"""A torus and a second surface touching along a whole meridian circle, with another curve crossing it
(spatialkin.tracing.search.meridians): the circle of tangency in closed form and the other curve against its length by
quadrature of an independent parametrisation, in both argument orders."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

import spatialkin as sk

#: Lengths by quadrature: within this (relative) of spatialkin's.
LENGTH_RTOL = 1e-9
#: The curve crossing the circle passes its crossings within this (relative to the scale).
NODE_GAP = 1e-6


def quarter_length(speed):
    """4 x the integral of speed over [0, pi/2], as t = pi/2 - w^2 (the square-root end made smooth)."""
    value, error = quad(lambda w: speed(math.pi / 2 - w * w) * 2 * w, 0.0, math.sqrt(math.pi / 2), epsabs=1e-13,
                        epsrel=1e-13, limit=200)
    assert error < 1e-10
    return 4 * value


def apart_oval():
    """Torus(20, 5) and the same 40 apart along x: the mirror plane x = 20 cuts each in the oval
    sqrt(400 + y^2) - 20 = 5 cos t, z = 5 sin t."""
    def speed(t):
        f = (20 + 5 * np.cos(t)) ** 2 - 400
        dy = -(20 + 5 * np.cos(t)) * 5 * np.sin(t) / np.sqrt(f)
        return math.hypot(dy, 5 * np.cos(t))
    return quarter_length(speed)


def inner_curve():
    """Torus(20, 5) and Torus(10, 5) about (10, 0, 0): rho_a + rho_b = 30 (an ellipse in plan, foci at the two
    centres, rho_a = 15 + 5 cos t) at the height z = 5 sqrt(2 cos t - cos^2 t)."""
    b = math.sqrt(200.0)

    def speed(t):
        c, s = math.cos(t), math.sin(t)
        dz = 5 * (c - 1) * s / math.sqrt(2 * c - c * c)
        return math.sqrt((15 * s) ** 2 + (b * c) ** 2 + dz * dz)
    return quarter_length(speed)


PAIRS = {
    "apart": (sk.Torus(20.0, 5.0), sk.Torus(20.0, 5.0, sk.Frame((40.0, 0.0, 0.0))), apart_oval),
    "inner": (sk.Torus(20.0, 5.0), sk.Torus(10.0, 5.0, sk.Frame((10.0, 0.0, 0.0))), inner_curve),
}


@pytest.mark.parametrize("name", sorted(PAIRS))
@pytest.mark.parametrize("swap", [False, True])
def test_tori_touching_along_a_meridian(name, swap):
    a, b, truth = PAIRS[name]
    if swap:
        a, b = b, a
    curves = sk.intersect(a, b)
    tangent = [c for c in curves if c.status == "tangent"]
    other = [c for c in curves if c.status != "tangent"]
    circle, = tangent
    assert circle.closed and abs(circle.length - 10 * math.pi) <= 1e-12 * 10 * math.pi
    assert np.allclose(np.hypot(circle.points[:, 0] - 20.0, circle.points[:, 2]), 5.0, atol=1e-12)
    assert np.allclose(circle.points[:, 1], 0.0, atol=1e-12)
    loop, = other
    assert loop.closed and loop.status == "closed"
    assert abs(loop.length - truth()) <= LENGTH_RTOL * loop.length
    assert loop.max_distance <= loop.tolerance
    # it crosses the circle at (20, 0, +-5): the dense output passes a node along the chords of its jump
    # (spatialkin.tracing.curve.dense), within about jump^2 x curvature of it
    _, gap = loop.closest(np.array([[20.0, 0.0, -5.0], [20.0, 0.0, 5.0]]))
    assert gap.max() <= NODE_GAP * 20.0


def test_tilted_tori_and_an_inscribed_ball():
    """Tori of equal tubes whose axes cross in the plane of a shared meridian, both orders agreeing; a ball
    inscribed in the tube touches along the meridian only."""
    phi = 0.4
    axis, out = np.array([math.sin(phi), 0.0, math.cos(phi)]), np.array([math.cos(phi), 0.0, -math.sin(phi)])
    rotation = np.column_stack([out, np.cross(axis, out), axis])
    a = sk.Torus(20.0, 5.0)
    b = sk.Torus(15.0, 5.0, sk.Frame(np.array([20.0, 0.0, 0.0]) - 15.0 * out, rotation))
    ab, ba = sk.intersect(a, b), sk.intersect(b, a)
    assert sorted(c.status for c in ab) == sorted(c.status for c in ba) == ["closed", "tangent"]
    assert sorted(c.length for c in ab) == pytest.approx(sorted(c.length for c in ba), rel=1e-9)
    assert all(c.max_distance <= c.tolerance for c in ab + ba)
    ball = sk.Sphere(5.0, sk.Frame((20.0, 0.0, 0.0)))
    for curves in (sk.intersect(a, ball), sk.intersect(ball, a)):
        circle, = curves
        assert circle.status == "tangent" and abs(circle.length - 10 * math.pi) <= 1e-12 * 10 * math.pi


def test_cones_holding_one_generator():
    """Two cones whose axes lie in one plane with a common generator touch all along it (both normals lie in
    that plane, normal to the line): the segment of tangency is the generator over both axial trims (closed form
    along the line t d: t in [0.5, 3] / cos 0.5 on the first, 4 - t in [0.5, 3] / cos 0.3 on the second), in both
    orders, the other curves on both surfaces and alike in both orders."""
    alpha, beta, apex_at = 0.5, 0.3, 4.0
    d = np.array([math.sin(alpha), 0.0, math.cos(alpha)])
    turn = np.array([[math.cos(beta), 0.0, math.sin(beta)], [0.0, 1.0, 0.0], [-math.sin(beta), 0.0, math.cos(beta)]])
    axis = -(turn @ d)
    x = np.cross([0.0, 1.0, 0.0], axis)
    x /= np.linalg.norm(x)
    a = sk.Cone(alpha, v_range=(0.5, 3.0))
    b = sk.Cone(beta, sk.Frame(apex_at * d, np.column_stack([x, np.cross(axis, x), axis])), v_range=(0.5, 3.0))
    lo, hi = max(0.5 / math.cos(alpha), apex_at - 3.0 / math.cos(beta)), min(3.0 / math.cos(alpha),
                                                                           apex_at - 0.5 / math.cos(beta))
    answers = [sk.intersect(a, b), sk.intersect(b, a)]
    for curves in answers:
        segment, = [c for c in curves if c.status == "tangent"]
        assert abs(segment.length - (hi - lo)) <= 1e-12 * hi
        assert np.allclose(sorted(segment.points[[0, -1]].tolist()), [(lo * d).tolist(), (hi * d).tolist()],
                           atol=1e-12)
        assert all(c.max_distance <= c.tolerance for c in curves)
    lengths = [sorted(c.length for c in curves) for curves in answers]
    assert lengths[0] == pytest.approx(lengths[1], rel=1e-9, abs=1e-12)
