"""Answers proven in closed form (spatialkin.tracing.certify.closed): two spheres, or a sphere and a plane.

Oracles: the true circle from the surfaces' floats in 60-digit decimal arithmetic. The proven distance bound must
hold both ways: every point of the dense output (also between the stored points) within it of the true circle, and
every point of the true circle within it of the dense output (its nearest point found by a bounded 1-D search).
"""
from decimal import Decimal, getcontext

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing.certify.closed import closed_certificate
from spatialkin.tracing.curve.exact import exact_curve

getcontext().prec = 60


def true_circle(a, b):
    """(centre, unit axis, radius) of the true circle, in Decimal, of two spheres or a plane and a sphere."""
    def d(v):
        return [Decimal(float(x)) for x in v]

    def dot(u, v):
        return sum(x * y for x, y in zip(u, v))
    if isinstance(a, sk.Plane) or isinstance(b, sk.Plane):
        plane, sphere = (a, b) if isinstance(a, sk.Plane) else (b, a)
        o, n, c, r = d(plane.frame.origin), d(plane.frame.rotation[:, 2]), d(sphere.frame.origin), Decimal(sphere.radius)
        length = dot(n, n).sqrt()
        axis = [x / length for x in n]
        delta = dot([x - y for x, y in zip(o, c)], axis)
        return [x + delta * y for x, y in zip(c, axis)], axis, (r * r - delta * delta).sqrt()
    oa, ob, ra, rb = d(a.frame.origin), d(b.frame.origin), Decimal(a.radius), Decimal(b.radius)
    dv = [y - x for x, y in zip(oa, ob)]
    dd = dot(dv, dv)
    k = (dd + ra * ra - rb * rb) / (2 * dd)
    return [x + k * y for x, y in zip(oa, dv)], [y / dd.sqrt() for y in dv], (ra * ra - k * k * dd).sqrt()


def distance_to_circle(points, circle):
    """Distances (float) of points (N, 3) to the true circle, in Decimal."""
    m, n, rho = circle
    out = []
    for p in points:
        v = [Decimal(float(x)) - y for x, y in zip(p, m)]
        h = sum(x * y for x, y in zip(v, n))
        perp = (sum(x * x for x in v) - h * h).sqrt()
        out.append(float((h * h + (perp - rho) ** 2).sqrt()))
    return np.array(out)


def circle_points(circle, count):
    """count points (N, 3) of the true circle (floats)."""
    m, n, rho = circle
    m, n, rho = np.array([float(x) for x in m]), np.array([float(x) for x in n]), float(rho)
    e1 = np.cross(n, np.eye(3)[np.argmin(np.abs(n))])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    t = np.linspace(0.0, 2 * np.pi, count, endpoint=False)
    return m + rho * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)


def pairs():
    rot = sk.rotation_about((1.0, 2.0, -0.5), 0.7)
    for shift, scale in ((0.0, 1.0), (1e4, 1.0), (1e6, 1e-3), (-3e3, 1e3)):
        o = np.array([shift, -0.3 * shift, 0.7 * shift])
        yield (sk.Sphere(scale, sk.Frame(o)), sk.Sphere(0.8 * scale, sk.Frame(o + scale * np.array([0.9, 0.4, 0.1]))))
        yield (sk.Plane(sk.Frame(o + scale * np.array([0.1, 0.2, 0.3]), rot)),
               sk.Sphere(scale, sk.Frame(o + scale * np.array([0.0, 0.1, -0.1]))))


@pytest.mark.parametrize("pair", list(pairs()), ids=lambda p: f"{type(p[0]).__name__}@{p[1].frame.origin[0]:g}")
def test_circles_are_proven_with_a_hausdorff_bound_both_ways(pair):
    for a, b in (pair, pair[::-1]):
        curves = sk.intersect(a, b, certify=True)
        cert = curves.certificate
        assert cert.proven and cert.mode == "closed form" and len(curves) == 1
        curve, truth = curves[0], true_circle(a, b)
        bound = curve.certificate.distance_bound
        size = np.max(np.abs(curve.points)) + curve.length
        assert bound < 1e-13 * size
        s = np.linspace(0.0, curve.length, 2001)
        assert np.all(distance_to_circle(curve(s), truth) <= bound)
        assert np.all(distance_to_circle(curve.points, truth) <= curve.certificate.radii)
        # the other way: each true point within the bound of the dense output (its foot point by Newton on the
        # arc length, the tangent by central differences)
        dense = curve(s)
        h = 1e-6 * curve.length
        for y in circle_points(truth, 60):
            t = s[int(np.argmin(np.linalg.norm(dense - y, axis=1)))]
            for _ in range(6):
                tangent = (curve((t + h) % curve.length) - curve((t - h) % curve.length)) / (2 * h)
                t += np.dot(y - curve(t % curve.length), tangent) / np.dot(tangent, tangent)
            gap = np.linalg.norm(curve(t % curve.length) - y)
            assert gap <= bound + 8 * np.finfo(float).eps * np.max(np.abs(y))


def test_apart_and_nested_spheres_are_proven_empty():
    for b in (sk.Sphere(1.0, sk.Frame((3.0, 0.0, 0.0))), sk.Sphere(0.5, sk.Frame((0.1, 0.2, 0.0)))):
        curves = sk.intersect(sk.Sphere(1.0), b, certify=True)
        assert curves == [] and curves.certificate.proven and curves.certificate.mode == "closed form"


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
    """Touching spheres, a circle crossing a plane's rectangle, and a trimmed sphere are not settled in closed form:
    their certificates come from the search (another mode)."""
    touching = sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((2.0, 0.0, 0.0))), certify=True)
    assert touching.certificate.mode != "closed form" and not touching.certificate.proven
    strip = sk.Plane(sk.Frame((0.0, 0.0, 0.3)), u_range=(-0.5, 0.5), v_range=(-2.0, 2.0))
    cut = sk.intersect(sk.Sphere(1.0), strip, certify=True)
    assert cut.certificate.mode != "closed form" and len(cut) == 2
    assert closed_certificate(sk.Sphere(1.0, u_range=(0.0, 3.0)), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0))),
                              []) is None
