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


def test_fit_goes_on_through_a_sharp_bend_until_the_tolerance():
    """Spans long beside a bend of radius 1e-3 do not halve their error at once (the fit stopped there at 3.3e-3,
    taking it for round-off, as it did on a near-tangent intersection loop); the spline reaches 1e-6, measured
    and against 200 001 exact points (closed form)."""
    sp = fit(sharp_bend, -1.0, 0.93, 1e-6)
    x = np.linspace(-1.0, 0.93, 200_001)
    assert sp.deviation <= 1e-6 and np.max(np.linalg.norm(sp(x) - sharp_bend(x)[0], axis=1)) <= 1e-6


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
