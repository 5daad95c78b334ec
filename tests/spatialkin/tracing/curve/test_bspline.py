"""B-splines of curves: exact Hermite interpolation, and a tolerance measured against the true curve.
Oracles: a helix and circles in closed form; the exact distance functions of the surfaces; Curve.closest."""
import math

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.mechanisms.looper import reference
from spatialkin.tracing.curve.bspline import SplineToleranceError, fit, hermite_bspline
from spatialkin.tracing.curve.curvature import curvature_vectors, implicit_jets


def helix(t):
    """Points, first and second derivatives of (cos t, sin t, 0.3 t)."""
    t = np.asarray(t, dtype=float)
    return (np.stack([np.cos(t), np.sin(t), 0.3 * t], 1), np.stack([-np.sin(t), np.cos(t), 0.3 + 0 * t], 1),
            np.stack([-np.cos(t), -np.sin(t), 0 * t], 1))


def test_hermite_bspline_interpolates_values_and_two_derivatives():
    """At every knot the spline's value, first and second derivative equal the data (1e-13), and it is a
    degree-5 B-spline with triple interior knots (3 (n + 1) control points)."""
    x = np.array([0.0, 0.4, 1.1, 1.5, 2.6, 3.0])
    data = helix(x)
    sp = hermite_bspline(x, *data)
    assert sp.k == 5 and len(sp.c) == 3 * len(x)
    for nu in range(3):
        np.testing.assert_allclose(sp(x, nu), data[nu], rtol=0, atol=1e-13)


@pytest.mark.parametrize("tol", [1e-4, 1e-8, 1e-12])
def test_fit_reaches_the_tolerance_on_a_helix(tol):
    """The measured deviation is below tol, and so is the true one on 200 001 points (closed form)."""
    sp = fit(helix, 0.0, 2 * math.pi, tol)
    t = np.linspace(0, 2 * math.pi, 200_001)
    assert sp.deviation <= tol and np.max(np.linalg.norm(sp(t) - helix(t)[0], axis=1)) <= tol


def sharp_bend(x, eps=1e-3):
    """(x, sqrt(x^2 + eps^2)): a hyperbola with a bend of radius eps at x = 0, its exact first and second
    derivatives."""
    r = np.sqrt(x * x + eps * eps)
    return (np.stack([x, r], 1), np.stack([np.ones_like(x), x / r], 1),
            np.stack([np.zeros_like(x), eps * eps / r ** 3], 1))


def distance_to_sharp_bend(q, x, eps):
    """Distances of points q (M, 2) to the hyperbola sharp_bend(., eps): Newton's method on the foot point's
    parameter, from x (M,)."""
    for _ in range(40):
        p, d1, d2 = sharp_bend(x, eps)
        r = p - q
        x = x - np.einsum("ij,ij->i", r, d1) / (np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", r, d2))
    return np.linalg.norm(sharp_bend(x, eps)[0] - q, axis=1)


@pytest.mark.parametrize("eps, tol", [(1e-3, 1e-6), (1e-5, 1e-9), (1e-7, 1e-12)])
def test_fit_goes_on_through_a_sharp_bend_until_the_tolerance(eps, tol):
    """Spans long beside a bend of radius eps do not halve their error at once, and that is not round-off: the
    spline reaches tol, measured and as the distance of 220 001 of its points (20 001 across the bend) to the
    hyperbola (closed form, foot points by Newton's method)."""
    sp = fit(lambda x: sharp_bend(x, eps), -1.0, 0.93, tol)
    x = np.r_[np.linspace(-1.0, 0.93, 200_001), np.linspace(-100 * eps, 100 * eps, 20_001)]
    assert sp.deviation <= tol and distance_to_sharp_bend(sp(x), x, eps).max() <= tol


def test_fit_stops_soon_where_the_curve_points_are_noisy():
    """A helix 1e-5 across whose exact points carry an error of 5e-11 (5e-6 of its extent, as the points of a
    tiny near-tangent intersection loop do): a tolerance of 1e-12 is refused after about 1000 evaluations of the
    curve, not after the most knots allowed; 5e-10 is reached."""
    def noisy(t):
        p, d1, d2 = helix(t)
        return 1e-5 * p + 5e-11 * np.sin(1.2345e7 * np.asarray(t) + 0.3)[:, None], 1e-5 * d1, 1e-5 * d2
    calls = []
    def counted(t):
        calls.append(len(t))
        return noisy(t)
    with pytest.raises(SplineToleranceError, match="round-off"):
        fit(counted, 0.0, 2 * math.pi, 1e-12)
    assert sum(calls) < 5000
    assert fit(noisy, 0.0, 2 * math.pi, 5e-10).deviation <= 5e-10


def test_to_bspline_of_a_tiny_near_tangent_loop_stops_at_its_round_off():
    """Two cylinders meeting in a loop 4.6e-5 long near tangency: 1e-9 is reached (checked against the two
    surfaces' exact distance functions); 1e-11, below the error of the loop's points (about 5e-11), is refused
    with fewer than 1000 knots."""
    a = sk.Cylinder(0.312087037011044, frame=sk.Frame(
        (-0.19761942178565717, -0.4186685260360638, 0.19185862875746637),
        [(0.8968106550716552, 0.28835864185784765, -0.3355293468772087),
         (-0.32424852462623444, 0.944368460820828, -0.055055467345309014),
         (0.3009876130801049, 0.15816922542896167, 0.9404195621633694)]), v_range=(-1.9111662495240034, 1.132528154787801))
    b = sk.Cylinder(0.776997434836475, frame=sk.Frame(
        (-0.2941694093027249, 0.6700151961861531, -0.273959162060577),
        [(0.4324020335184729, 0.03377221666492862, -0.9010482333319492),
         (-0.6259645926928467, 0.7305014265158073, -0.27301281023653257),
         (0.6489967720289277, 0.6820755846971124, 0.3370105141625771)]), v_range=(-1.7713937414029344, 2.011938987033233))
    loop, = sk.intersect(a, b)
    assert loop.closed and loop.length < 1e-4
    sp = loop.to_bspline(1e-9)
    pts = sp(np.linspace(0, loop.length, 5001))
    assert max(a.distance(pts).max(), b.distance(pts).max()) <= 1e-9
    with pytest.raises(SplineToleranceError, match=r"with (\d{1,3}) knots"):
        loop.to_bspline(1e-11)


def test_implicit_jets_match_differences():
    """Gradient and Hessian of every kind's implicit function against central differences (1e-7 relative)."""
    rng = np.random.default_rng(4)
    frame = sk.Frame(rng.normal(size=3), sk.rotation_about(rng.normal(size=3), 0.8))
    for surf in (sk.Torus(2, 0.7, frame), sk.Sphere(1.5, frame), sk.Plane(frame), sk.Cylinder(0.8, frame),
                 sk.Cone(0.6, frame)):
        x = rng.normal(size=(6, 3))
        _, grad, hess = implicit_jets(surf, x)
        h = 1e-6
        g_fd = np.stack([(implicit_jets(surf, x + h * e)[0] - implicit_jets(surf, x - h * e)[0]) / (2 * h)
                         for e in np.eye(3)], 1)
        h_fd = np.stack([(implicit_jets(surf, x + h * e)[1] - implicit_jets(surf, x - h * e)[1]) / (2 * h)
                         for e in np.eye(3)], 2)
        assert np.max(np.abs(grad - g_fd)) <= 1e-7 * max(1.0, np.max(np.abs(grad)))
        assert np.max(np.abs(hess - h_fd)) <= 1e-7 * max(1.0, np.max(np.abs(hess)))


def test_curvature_vector_of_a_circle():
    """On a sphere ∩ plane circle of radius r the curvature vector points to its centre with length 1/r."""
    sphere = sk.Sphere(2.0, sk.Frame((0.3, -0.2, 0.1)))
    plane = sk.Plane(sk.Frame((0.3, -0.2, 1.1)))
    curve = sk.intersect(sphere, plane)[0]
    s = np.linspace(0, curve.length, 9)
    pts, tangents = curve(s), curve.tangent(s)
    bend = curvature_vectors(sphere, plane, pts, tangents)
    centre, radius = np.array([0.3, -0.2, 1.1]), math.sqrt(3.0)
    np.testing.assert_allclose(bend, (centre - pts) / radius ** 2, atol=1e-12)


@pytest.mark.parametrize("tol", [1e-6, 1e-10])
def test_curve_to_bspline_within_tolerance_of_the_true_curve(tol):
    """The looper's two loops: every spline sample lies within tol x scale of the curve (Curve.closest, a foot
    point by Newton on the corrected curve) and of both surfaces; closed loops give periodic splines."""
    torus, sphere = reference.looper_pair()
    scale = reference.ROCKER_LENGTH
    for curve in sk.intersect(torus, sphere):
        sp = curve.to_bspline(tol)
        assert sp.deviation <= tol * scale and sp.extrapolate == "periodic"
        s = np.linspace(0, curve.length, 1500)
        pts = sp(s)
        assert np.max(curve.closest(pts)[1]) <= tol * scale
        assert max(torus.distance(pts).max(), sphere.distance(pts).max()) <= tol * scale
        np.testing.assert_allclose(sp(s[:10] + curve.length), sp(s[:10]), atol=1e-12 * scale)


def test_tangency_circle_spline_and_bad_input():
    """A tangency circle (closed form) gives a spline on the circle to 1e-9 of the scale; tol <= 0 and a
    contact point are refused by name; a tolerance below round-off raises SplineToleranceError."""
    torus, plane = sk.Torus(2.0, 0.5), sk.Plane(sk.Frame((0, 0, 0.5)))
    circle = sk.intersect(torus, plane)[0]
    sp = circle.to_bspline(1e-9)
    pts = sp(np.linspace(0, circle.length, 2001))
    assert np.max(np.abs(np.hypot(pts[:, 0], pts[:, 1]) - 2.0)) <= 0.5e-9 and np.max(np.abs(pts[:, 2] - 0.5)) < 1e-15
    with pytest.raises(ValueError, match="tol"):
        circle.to_bspline(0.0)
    contact = sk.intersect(sk.Sphere(1.0), sk.Plane(sk.Frame((0, 0, 1.0))))[0]
    with pytest.raises(ValueError, match="contact"):
        contact.to_bspline(1e-6)
    with pytest.raises(SplineToleranceError, match="round-off"):
        fit(lambda t: tuple(x + 1e-9 * np.sin(1e9 * t)[:, None] * (k == 0) for k, x in enumerate(helix(t))),
            0.0, 1.0, 1e-15)
