"""Answers proven exactly for surfaces along one coordinate axis (spatialkin.tracing.certify.parallel): segments of
tangency of parallel cylinders and of a plane on a cylinder, and the two lines of a plane parallel to a cylinder's
axis.

Oracle: the true segments written from each case's geometry by hand (the common points of the cross-sections and
the trims' common range along the axis, 40-digit mpmath), every point's distance to its true line measured there.
"""
import dataclasses
import math

import mpmath as mp
import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing.certify import parallel as px
from spatialkin.tracing.search.exact import exact_segments
from spatialkin.tracing.components import intersect as plain_intersect

mp.mp.dps = 40
ALONG_Z = np.column_stack([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])    # u along y, v along z, normal x


def cases():
    """(name, a, b, true (x, y) per segment, its range along z, tangency)."""
    yield ("plane on a cylinder", sk.Cylinder(1.0, v_range=(-2, 2)), sk.Plane(sk.Frame((1.0, 0, 0), ALONG_Z)),
           [(1, 0)], (-2, 2), True)
    yield ("trimmed plane on a cylinder", sk.Plane(sk.Frame((1.0, 0, 0), ALONG_Z), u_range=(-3, 3),
                                                   v_range=(-0.5, 0.7)),
           sk.Cylinder(1.0, v_range=(-2, 2)), [(1, 0)], (-0.5, 0.7), True)
    yield ("cylinders outside", sk.Cylinder(0.5, v_range=(-1, 1)),
           sk.Cylinder(0.75, sk.Frame((1.25, 0, 0)), v_range=(-0.5, 1.5)), [(0.5, 0)], (-0.5, 1), True)
    yield ("cylinders inside, off the origin", sk.Cylinder(0.5, sk.Frame((3.0, -2.0, 5.0)), v_range=(-1, 1)),
           sk.Cylinder(1.25, sk.Frame((3.75, -2.0, 4.0)), v_range=(-0.5, 1.5)), [(2.5, -2)], (4.0, 5.5), True)
    r = mp.sqrt(1 - mp.mpf(0.6) ** 2)
    yield ("plane through a cylinder", sk.Cylinder(1.0, v_range=(-2, 2)), sk.Plane(sk.Frame((0.6, 0, 0), ALONG_Z)),
           [(mp.mpf(0.6), r), (mp.mpf(0.6), -r)], (-2, 2), False)


def _line_distance(points, xy):
    x, y = (mp.mpf(v) for v in xy)
    return np.array([float(mp.sqrt((mp.mpf(float(p[0])) - x) ** 2 + (mp.mpf(float(p[1])) - y) ** 2))
                     for p in np.asarray(points, dtype=float).reshape(-1, 3)])


@pytest.mark.parametrize("case", list(cases()), ids=lambda c: c[0])
def test_exact_segments_proven_and_bounded(case):
    """Every claim proven (mode 'exact (parallel)'); each curve matched to one true segment: its stored points and
    100 dense samples within the bound of the true line, its ends within it of the true ends."""
    name, a, b, truth, (lo, hi), tangent = case
    for first, second in ((a, b), (b, a)):
        curves = sk.intersect(first, second, certify=True)
        cert = curves.certificate
        assert cert.proven and cert.mode == px.MODE, (name, cert)
        assert len(curves) == len(truth)
        assert ("segment(s) of tangency" in cert.claims["singular"].detail) == tangent
        left = list(truth)
        for curve, bound in zip(curves, cert.distance_bounds):
            j = int(np.argmin([np.max(_line_distance(curve.points, t)) for t in left]))
            xy = left.pop(j)
            dense = curve(np.linspace(0.0, curve.length, 100))
            assert np.max(_line_distance(np.vstack([curve.points, dense]), xy)) <= bound < 1e-12
            z = sorted(float(p[2]) for p in curve(np.array([0.0, curve.length])))
            assert abs(z[0] - lo) <= bound and abs(z[1] - hi) <= bound


def test_one_ulp_off_is_never_proven_wrongly():
    """The plane one ulp outside the cylinder (no common point, exactly) or inside (two lines 3e-8 apart): an
    answer is proven only where it is the exact one."""
    for p in (math.nextafter(1.0, 2.0), math.nextafter(1.0, 0.0)):
        a, b = sk.Cylinder(1.0, v_range=(-2, 2)), sk.Plane(sk.Frame((p, 0, 0), ALONG_Z))
        _, _, segments = exact_segments(a, b)
        assert len(segments) == (0 if p > 1.0 else 2)
        curves = sk.intersect(a, b, certify=True)
        assert not curves.certificate.proven or len(curves) == len(segments)


def test_tampered_answers_are_not_proven():
    """The plane's two lines through the cylinder, then one dropped (said not to be the exact answer), one moved
    1e-6, one said tangent (left to the search): only the first is proven."""
    a, b = sk.Cylinder(1.0, v_range=(-2, 2)), sk.Plane(sk.Frame((0.6, 0, 0), ALONG_Z))
    results = [c.result for c in plain_intersect(a, b)]
    assert px.parallel_certificate(a, b, results).proven
    dropped = px.parallel_certificate(a, b, results[:1])
    assert not dropped.proven and "exactly, the surfaces meet in 2 segment(s) crossed" in dropped.failed[0].detail
    moved = dataclasses.replace(results[0], points=results[0].points + 1e-6)
    assert px.parallel_certificate(a, b, [moved, results[1]]) is None
    said = dataclasses.replace(results[0], status="tangent")
    assert px.parallel_certificate(a, b, [said, results[1]]) is None


@pytest.mark.parametrize("pair", [
    (sk.Cylinder(1.0, v_range=(-1, 1)), sk.Cylinder(1.0, sk.Frame((1.5, 0, 0)), v_range=(-0.5, 2))),  # traced
    (sk.Cylinder(1.0, v_range=(-2, 2)),
     sk.Plane(sk.Frame((1.0, 0, 0), ALONG_Z @ sk.rotation_about((1, 0, 0), 1e-3)))),                     # turned
    (sk.Cylinder(1.0, v_range=(-2, 2)), sk.Plane(sk.Frame((1.0, 0, 0), ALONG_Z), u_range=(0, 3))),     # edge across
    (sk.Cylinder(1.0, v_range=(-2, 2)), sk.Plane(sk.Frame((1.0, 0, 0), ALONG_Z), v_range=(2, 3))),     # one point
], ids=["traced", "turned", "edge-across", "one-point"])
def test_pairs_left_to_the_search(pair):
    """A traced answer, a turned plane, a line on the plane's edge across it and a segment shrunk to one point of
    the trims get no certificate here."""
    assert px.parallel_certificate(*pair, [c.result for c in plain_intersect(*pair)]) is None
