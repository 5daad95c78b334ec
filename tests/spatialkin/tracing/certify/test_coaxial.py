"""Answers proven exactly for surfaces turning about one axis (spatialkin.tracing.certify.coaxial): circles of
tangency and contact points, which no interval method proves, and transversal parallels.

Oracle: the true circles written from the geometry of each case by hand (the common points of the meridians, in
40-digit arithmetic, mpmath), and every point's distance to its true circle measured there: sqrt((rho - rho*)^2 +
(h - h*)^2), rho the point's distance from the axis. The proven bounds must hold for the stored points and for
dense samples between them; an answer that is not the exact one (a curve dropped, moved, of the wrong kind, or the
placement moved by one ulp) must not be proven.
"""
import dataclasses
import math

import mpmath as mp
import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing.certify import coaxial as cx
from spatialkin.tracing.search.exact import exact_points
from spatialkin.tracing.components import intersect as plain_intersect

mp.mp.dps = 40
FLIP = np.diag([1.0, -1.0, -1.0])
SWAP = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])     # local z along global x


def _circles(rho_h):
    return [(mp.mpf(r), mp.mpf(h)) for r, h in rho_h]


def cases():
    """(name, a, b, axis index, the axis line's other two coordinates, true (rho, h) per curve (rho 0: a point),
    tangency)."""
    s = mp.sqrt
    yield ("sphere-cylinder equator", sk.Sphere(1.5), sk.Cylinder(1.5, v_range=(-1, 1)), 2, (0, 0),
           _circles([(1.5, 0)]), True)
    yield ("sphere-torus inner", sk.Sphere(1.5), sk.Torus(2.0, 0.5), 2, (0, 0), _circles([(1.5, 0)]), True)
    yield ("torus-torus stacked", sk.Torus(2.0, 0.5), sk.Torus(2.0, 0.5, sk.Frame((0, 0, 1.0))), 2, (0, 0),
           _circles([(2.0, 0.5)]), True)
    yield ("plane-torus top, flipped", sk.Plane(sk.Frame((0, 0, 0.5), FLIP)), sk.Torus(2.0, 0.5), 2, (0, 0),
           _circles([(2.0, 0.5)]), True)
    yield ("cylinder-torus outer, off the origin", sk.Torus(2.0, 0.5, sk.Frame((3.0, -1.0, 7.0))),
           sk.Cylinder(2.5, sk.Frame((3.0, -1.0, 0.0)), v_range=(-10, 10)), 2, (3.0, -1.0), _circles([(2.5, 7.0)]),
           True)
    yield ("sphere-torus along x", sk.Torus(2.0, 0.5, sk.Frame((0.0, 1.0, 2.0), SWAP)),
           sk.Sphere(2.5, sk.Frame((0.0, 1.0, 2.0))), 0, (1.0, 2.0), _circles([(2.5, 0.0)]), True)
    yield ("plane-sphere pole", sk.Sphere(1.0), sk.Plane(sk.Frame((0, 0, 1.0))), 2, (0, 0), _circles([(0, 1.0)]),
           True)
    yield ("sphere-sphere inside", sk.Sphere(1.0), sk.Sphere(0.5, sk.Frame((0, 0, 0.5))), 2, (0, 0),
           _circles([(0, 1.0)]), True)
    # transversal parallels: a cylinder through a torus's tube; a cylinder and a cone; a sphere and a torus
    half = s(mp.mpf(0.25) - (mp.mpf(2.2) - 2) ** 2)
    yield ("cylinder-torus crossing", sk.Torus(2.0, 0.5), sk.Cylinder(2.2, v_range=(-1, 1)), 2, (0, 0),
           [(mp.mpf(2.2), half), (mp.mpf(2.2), -half)], False)
    yield ("cylinder-cone", sk.Cylinder(0.5, v_range=(-3, 3)), sk.Cone(math.atan(0.25), v_range=(-4, 4)), 2, (0, 0),
           _circles([(0.5, 2.0), (0.5, -2.0)]), False)
    # torus (R 2, r 0.5) and sphere (R 2) at the same centre: rho^2 + h^2 = 4, (rho - 2)^2 + h^2 = 0.25
    rho = (mp.mpf(4) - mp.mpf(0.25) + 4) / 4
    yield ("sphere-torus crossing", sk.Torus(2.0, 0.5), sk.Sphere(2.0), 2, (0, 0),
           [(rho, s(4 - rho * rho)), (rho, -s(4 - rho * rho))], False)


def _meridian_distance(points, axis, line, rho_h):
    """Distance of each point (N, 3) to the true circle (rho*, h*) about the axis (mpmath)."""
    others = [j for j in range(3) if j != axis]
    rho_t, h_t = rho_h
    out = []
    for p in np.asarray(points, dtype=float).reshape(-1, 3):
        d = [mp.mpf(float(p[j])) - mp.mpf(float(c)) for j, c in zip(others, line)]
        rho = mp.sqrt(d[0] ** 2 + d[1] ** 2)
        out.append(float(mp.sqrt((rho - rho_t) ** 2 + (mp.mpf(float(p[axis])) - h_t) ** 2)))
    return np.array(out)


@pytest.mark.parametrize("case", list(cases()), ids=lambda c: c[0])
def test_exact_answers_proven_and_bounded(case):
    """Every claim proven (mode 'exact (coaxial)'), a tangency said to be one; each curve matched to one true circle
    or point, its stored points within their radii of it and 200 dense samples within its distance bound."""
    name, a, b, axis, line, truth, tangent = case
    for first, second in ((a, b), (b, a)):
        curves = sk.intersect(first, second, certify=True)
        cert = curves.certificate
        assert cert.proven, (name, cert)
        assert cert.mode == cx.MODE
        assert len(curves) == len(truth)
        assert ("double common point" in cert.claims["singular"].detail) == tangent
        left = list(truth)
        for curve, bound in zip(curves, cert.distance_bounds):
            near = [float(np.max(_meridian_distance(curve.points, axis, line, t))) for t in left]
            j = int(np.argmin(near))
            rho_h = left.pop(j)
            assert near[j] <= bound and np.all(_meridian_distance(curve.points, axis, line, rho_h)
                                               <= curve.certificate.radii)
            assert bound < 1e-12
            if curve.length > 0:
                dense = curve(np.linspace(0.0, curve.length, 200))
                assert np.max(_meridian_distance(dense, axis, line, rho_h)) <= bound


def test_one_ulp_off_is_never_proven_wrongly():
    """The cylinder's radius one ulp above the sphere's: exactly, no common point; one ulp below: two circles about
    2e-8 apart. Whatever the plain answer (a circle of tangency within its tolerance), it is proven only where it is
    the exact one; with another number of curves, the certificate says the exact answer."""
    for r in (math.nextafter(1.5, 2.0), math.nextafter(1.5, 1.0)):
        a, b = sk.Sphere(1.5), sk.Cylinder(r, v_range=(-1, 1))
        axis, points = exact_points(a, b)
        exact = len(points)
        assert exact == (0 if r > 1.5 else 2)
        curves = sk.intersect(a, b, certify=True)
        assert not curves.certificate.proven or len(curves) == exact
        if len(curves) != exact:
            said = curves.certificate.claims["complete"].detail
            assert "not the exact one" in said and ("no point" if exact == 0 else "2 circle(s) crossed") in said


def test_tampered_answers_are_not_proven():
    """The exact answer, then a curve dropped, one added twice (said not to be the exact answer), its points moved
    1e-6, its status changed (left to the search): only the first is proven."""
    a, b = sk.Torus(2.0, 0.5), sk.Sphere(2.0)
    results = [c.result for c in plain_intersect(a, b)]
    assert cx.coaxial_certificate(a, b, results).proven
    radius = float(cx.coaxial_certificate(a, b, results).radii[0][0])
    for wrong in (results[:1], results + results[:1]):
        cert = cx.coaxial_certificate(a, b, wrong)
        assert not cert.proven and all(not c.proven for c in cert.claims.values())
        assert "exactly, the surfaces meet in 2 circle(s) crossed" in cert.claims["complete"].detail
    far = dataclasses.replace(results[0], points=results[0].points + 1e-6)
    assert cx.coaxial_certificate(a, b, [far, results[1]]) is None
    # moved by 10 radii, within the round-off the stored points may keep from the dense output: still proven, with
    # radii that cover the move (checked against the true circle)
    moved = dataclasses.replace(results[0], points=results[0].points + 10 * radius)
    cert = cx.coaxial_certificate(a, b, [moved, results[1]])
    rho = (mp.mpf(4) - mp.mpf(0.25) + 4) / 4
    truth = [(rho, mp.sqrt(4 - rho * rho)), (rho, -mp.sqrt(4 - rho * rho))]
    worst = min(float(np.max(_meridian_distance(moved.points, 2, (0, 0), t))) for t in truth)
    assert cert.proven and worst > 5 * radius and worst <= float(cert.radii[0][0])
    said = dataclasses.replace(results[0], status="tangent")
    assert cx.coaxial_certificate(a, b, [said, results[1]]) is None


def test_cones_are_the_cones_of_their_stored_slope():
    """A cone's slope is its stored double (Cone.slope): atan(0.75) stores 0.75 exactly, and the sphere of radius 3
    five above the apex touches that cone along one circle (rho 2.4 at h 3.2: a 3-4-5 triangle), proven exactly; a
    sphere through the apex meets the cone in the apex and one circle, both proven (the apex a point of both rays,
    found once); the distances measured on the cone of slope 0.75 (mpmath)."""
    cone = sk.Cone(math.atan(0.75))
    assert cone.slope == 0.75
    touching = sk.intersect(cone, sk.Sphere(3.0, sk.Frame((0.0, 0.0, 5.0))), certify=True)
    assert touching.certificate.proven and touching.certificate.mode == cx.MODE
    assert [c.status for c in touching] == ["tangent"]
    assert np.max(_meridian_distance(touching[0].points, 2, (0, 0), (mp.mpf(2.4), mp.mpf(3.2)))) <= \
        touching.certificate.distance_bounds[0]
    through = sk.intersect(cone, sk.Sphere(5.0, sk.Frame((0.0, 0.0, 5.0))), certify=True)
    assert through.certificate.proven and sorted(c.status for c in through) == ["closed", "contact"]
    # rho = 0.75 h on rho^2 + (h - 5)^2 = 25: h = 6.4, rho = 4.8
    circle = next(c for c in through if c.status == "closed")
    assert np.max(_meridian_distance(circle.points, 2, (0, 0), (mp.mpf(4.8), mp.mpf(6.4)))) <= \
        through.certificate.distance_bounds[list(through).index(circle)]


def test_circles_cut_from_a_trimmed_plane_are_proven():
    """A torus and its equatorial plane trimmed to a square holding both equators: the closed forms' ellipses (two
    circles) are proven exactly, each within its bound of the true equator."""
    torus, plane = sk.Torus(2.0, 0.5), sk.Plane(u_range=(-3.0, 3.0), v_range=(-3.0, 3.0))
    curves = sk.intersect(torus, plane, certify=True)
    assert curves.certificate.proven and curves.certificate.mode == cx.MODE
    for curve, bound, rho in zip(curves, curves.certificate.distance_bounds, (2.5, 1.5)):
        assert np.max(_meridian_distance(curve.points, 2, (0, 0), (mp.mpf(rho), mp.mpf(0)))) <= bound
