"""Answers proven in closed form (spatialkin.tracing.certify.closed): two spheres, a plane with a sphere, a
cylinder or a cone, and two trimmed planes.

Oracle: the true curve as the surfaces' floats define it, in 30-digit arithmetic (tests.oracles.mp.foot: the
nearest true point by Newton). The proven distance bound must hold both ways: every point of the dense output
(also between the stored points) within it of the true curve, and every true point (the feet of points between
the samples) within it of the dense output (its nearest point by Newton on the arc length).
"""
import dataclasses

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing.certify.closed import closed_certificate
from spatialkin.tracing.curve.exact import exact_curve
from tests.oracles.mp import foot

EPS = np.finfo(float).eps


def pairs():
    rot = sk.rotation_about((1.0, 2.0, -0.5), 0.7)
    tilt = rot @ sk.rotation_about((0.3, -1.0, 0.2), 0.5)        # the cylinder's axis 0.5 off the plane's normal
    for shift, scale in ((0.0, 1.0), (1e4, 1.0), (1e6, 1e-3), (-3e3, 1e3)):
        o = np.array([shift, -0.3 * shift, 0.7 * shift])
        yield (sk.Sphere(scale, sk.Frame(o)), sk.Sphere(0.8 * scale, sk.Frame(o + scale * np.array([0.9, 0.4, 0.1]))))
        yield (sk.Plane(sk.Frame(o + scale * np.array([0.1, 0.2, 0.3]), rot)),
               sk.Sphere(scale, sk.Frame(o + scale * np.array([0.0, 0.1, -0.1]))))
        yield (sk.Plane(sk.Frame(o + scale * np.array([0.1, 0.2, 0.3]), rot), u_range=(-5 * scale, 5 * scale),
                        v_range=(-5 * scale, 5 * scale)),
               sk.Cylinder(scale, sk.Frame(o, tilt), v_range=(-4 * scale, 4 * scale)))
        yield (sk.Plane(sk.Frame(o + scale * np.array([0.1, 0.2, 0.3]), rot)),
               sk.Cone(0.5, sk.Frame(o - scale * (tilt @ np.array([0.0, 0.0, 1.5])), tilt),
                       v_range=(0.2 * scale, 4 * scale)))
        yield (sk.Plane(sk.Frame(o + scale * np.array([0.1, 0.2, 0.3]), rot), u_range=(-scale, scale),
                        v_range=(-2 * scale, 2 * scale)),
               sk.Plane(sk.Frame(o, rot @ sk.rotation_about((0.3, 1.0, 0.2), 1.1)), u_range=(-3 * scale, 3 * scale),
                        v_range=(-scale, 1.5 * scale)))


def nearest_on(curve, y, s, dense):
    """The distance from y (3,) to the dense output, by Newton on the arc length from the nearest of the samples
    dense (M, 3) at s (M,) (the tangent by central differences; an open curve's s kept in [0, length])."""
    def at(t):
        return curve(t % curve.length if curve.closed else min(max(t, 0.0), curve.length))
    t = s[int(np.argmin(np.linalg.norm(dense - y, axis=1)))]
    h = 1e-6 * curve.length
    for _ in range(6):
        tangent = (at(t + h) - at(t - h)) / (2 * h)
        t += np.dot(y - at(t), tangent) / np.dot(tangent, tangent)
    return np.linalg.norm(at(t) - y)


@pytest.mark.parametrize("pair", list(pairs()), ids=lambda p: f"{type(p[0]).__name__}-{type(p[1]).__name__}@"
                                                               f"{p[1].frame.origin[0]:g}")
def test_proven_with_a_hausdorff_bound_both_ways(pair):
    for a, b in (pair, pair[::-1]):
        curves = sk.intersect(a, b, certify=True)
        cert = curves.certificate
        assert cert.proven and cert.mode == "closed form" and len(curves) == 1
        curve = curves[0]
        bound = curve.certificate.distance_bound
        size = np.max(np.abs(curve.points)) + curve.length
        assert bound < 1e-13 * size
        s = np.linspace(0.0, curve.length, 401)
        dense = curve(s)
        slack = 4 * EPS * np.max(np.abs(dense))          # (the two definitions of the true curve, to round-off)
        mids = curve(s[:-1] + 0.37 * (s[1] - s[0]))
        for x in np.concatenate([dense[::4], mids[::8], curve.points[::8]]):
            assert foot(a, b, x)[0] <= bound + slack
        for x in mids[::10]:
            _, y = foot(a, b, x)
            assert nearest_on(curve, y, s, dense) <= bound + slack


def test_apart_and_nested_spheres_are_proven_empty():
    """Spheres apart or nested are proven empty: in closed form, or exactly where the centres lie on a line along a
    coordinate axis."""
    for b, mode in ((sk.Sphere(1.0, sk.Frame((1.8, 2.4, 0.0))), "closed form"),
                    (sk.Sphere(0.5, sk.Frame((0.1, 0.2, 0.0))), "closed form"),
                    (sk.Sphere(1.0, sk.Frame((3.0, 0.0, 0.0))), "exact (coaxial)")):
        curves = sk.intersect(sk.Sphere(1.0), b, certify=True)
        assert curves == [] and curves.certificate.proven and curves.certificate.mode == mode


def test_a_circle_moved_off_gets_a_bound_that_covers_the_move():
    """The true circle's answer with its radius made 1e-9 larger: the closed-form certificate's bound covers the
    move (never a bound below the 1e-9 the points are off)."""
    a, b = sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0)))
    curve = sk.intersect(a, b)[0].result
    sol = curve.sol
    off = exact_curve((a, b), curve.tolerance, circle=(sol.centre, sol.axis, sol.radius * (1 + 1e-9)))
    cert = closed_certificate(a, b, [off])
    assert cert is not None and cert.distance_bounds[0] >= 1e-9 * sol.radius


def test_what_the_algebra_leaves_goes_to_the_search():
    """Touching spheres, a circle crossing a plane's rectangle, an ellipse crossing a cylinder's rim, a hyperbola on
    a cone and a trimmed sphere are not settled in closed form: their certificates come from elsewhere (another
    mode: touching spheres whose centres differ along a coordinate axis are exactly coaxial, proven in rational
    arithmetic; the rest from the search)."""
    touching = sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((2.0, 0.0, 0.0))), certify=True)
    assert touching.certificate.mode == "exact (coaxial)" and touching.certificate.proven
    strip = sk.Plane(sk.Frame((0.0, 0.0, 0.3)), u_range=(-0.5, 0.5), v_range=(-2.0, 2.0))
    cut = sk.intersect(sk.Sphere(1.0), strip, certify=True)
    assert cut.certificate.mode != "closed form" and len(cut) == 2
    slanted = sk.Plane(sk.Frame((0.0, 0.0, 0.0), sk.rotation_about((1.0, 0.0, 0.0), 0.8)))
    rim = sk.intersect(slanted, sk.Cylinder(1.0, v_range=(-0.5, 3.0)), certify=True)
    assert rim.certificate.mode != "closed form" and all(not c.closed for c in rim)
    hyperbola = sk.intersect(sk.Plane(sk.Frame((0.0, 0.0, 0.0), sk.rotation_about((1.0, 0.0, 0.0), 1.4))),
                             sk.Cone(0.5, sk.Frame((0.0, 0.0, -1.0)), v_range=(0.1, 3.0)), certify=True)
    assert hyperbola.certificate.mode != "closed form"
    assert closed_certificate(sk.Sphere(1.0, u_range=(0.0, 3.0)), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0))),
                              []) is None


@pytest.mark.parametrize("gap", [1e-4, 1e-8, 1e-10, 1e-12])
def test_tiny_circles_of_nearly_touching_spheres_are_proven_or_said_not_to_be(gap):
    """Two unit spheres whose centres are 2 - gap apart (moved 1e3 off, along (0.6, 0.8, 0): no coordinate axis, so
    not an exact placement) meet in one circle of radius about sqrt(gap). Returned as a circle, it is proven in
    closed form, every stored point within its proven radius of the true circle (30-digit oracle), the bound within
    1% of the radius or 64 ulps of the coordinates over the normals' sine (about the radius: the circle's
    conditioning); returned as a contact point (the gap within the coordinates' round-off), it is not proven. Along
    x the placement is exact: a circle returned (or, at gap 0, the contact point) is proven in rational arithmetic,
    within its bound of the true one; a contact returned there is not proven (exactly, the spheres meet in a
    circle)."""
    o = np.array([1e3, -2e3, 5e2])
    a, b = sk.Sphere(1.0, sk.Frame(o)), sk.Sphere(1.0, sk.Frame(o + (2.0 - gap) * np.array([0.6, 0.8, 0.0])))
    curves = sk.intersect(a, b, certify=True)
    assert len(curves) == 1
    curve = curves[0]
    if curve.status == "contact":
        assert not curves.certificate.proven
    else:
        assert curves.certificate.proven and curves.certificate.mode == "closed form"
        radius = np.sqrt(1.0 - (1.0 - gap / 2) ** 2)
        assert abs(curve.length - 2 * np.pi * radius) < 1e-2 * curve.length
        ulp = np.spacing(np.abs(o).max())
        assert curve.certificate.distance_bound < max(1e-2 * radius, 64 * ulp / radius)
        for x, r in zip(curve.points[::4], curve.certificate.radii[::4]):
            assert foot(a, b, x)[0] <= r
    aligned = sk.Sphere(1.0, sk.Frame(o + [2.0 - gap, 0.0, 0.0]))
    exact = sk.intersect(a, aligned, certify=True)
    if exact[0].status == "contact":                # (the search's answer within round-off; exactly, a circle)
        assert not exact.certificate.proven
    else:
        assert exact.certificate.proven and exact.certificate.mode == "exact (coaxial)"
        for x, r in zip(exact[0].points[::8], exact[0].certificate.radii[::8]):
            assert foot(a, aligned, x)[0] <= r
    touching = sk.intersect(a, sk.Sphere(1.0, sk.Frame(o + [2.0, 0.0, 0.0])), certify=True)
    assert touching.certificate.proven and touching.certificate.mode == "exact (coaxial)"
    assert len(touching) == 1 and touching[0].status == "contact"
    assert np.linalg.norm(touching[0].points[0] - (o + [1.0, 0.0, 0.0])) <= touching.certificate.distance_bounds[0]


def test_answers_not_faithful_to_their_closed_form_are_left_to_the_search():
    """The closed-form proof bounds the returned closed form's dense output: an answer whose stored points, length or
    parameter range are not that whole closed form (half the circle's length, points moved by 0.3, a sixth of an
    ellipse marked closed) is not proven in closed form (None: the search's certificate decides)."""
    from spatialkin.tracing.closed.conic import ConicSolution
    from spatialkin.tracing.curve.result import CurveResult
    a, b = sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0)))
    c = sk.intersect(a, b)[0].result
    assert closed_certificate(a, b, [c]).proven
    k = len(c.points) // 2 + 1
    half = CurveResult(points=c.points[:k], s=c.s[:k], params=c.params[:k], closed=True, length=c.length / 2,
                       status=c.status, message=c.message, tolerance=c.tolerance, sol=c.sol)
    moved = dataclasses.replace(c, points=c.points + 0.3)
    assert closed_certificate(a, b, [half]) is None and closed_certificate(a, b, [moved]) is None
    plane = sk.Plane(sk.Frame((0.1, 0.2, 0.3)), u_range=(-5, 5), v_range=(-5, 5))
    cylinder = sk.Cylinder(1.0, sk.Frame((0.0, 0.0, 0.0), sk.rotation_about((0.3, -1.0, 0.2), 0.5)), v_range=(-4, 4))
    e = sk.intersect(plane, cylinder)[0].result
    assert closed_certificate(plane, cylinder, [e]).proven
    arc = ConicSolution(e.sol.surfaces, e.sol.conic, 0.0, np.pi / 3, False)
    k = len(e.points) // 6
    sixth = dataclasses.replace(e, sol=arc, length=arc.length, points=e.points[:k], s=e.s[:k], params=e.params[:k])
    assert closed_certificate(plane, cylinder, [sixth]) is None
