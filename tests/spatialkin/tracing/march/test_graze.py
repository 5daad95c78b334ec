"""Curves touching a rectangular trim edge, on the general path (closed forms off: the topology stage and the
tracer, spatialkin.tracing.march.graze and clip): a torus cut by a plane normal to its axis in the circles of radii
R + r and R - r (closed forms), the plane trimmed so that the outer circle touches an edge from inside, is halved,
or touches an edge from outside; in a rigid placement, both argument orders."""
import math

import numpy as np
import pytest

import spatialkin as sk
import spatialkin.tracing.components as intersect_module

BIG, SMALL = 2.0, 0.5
OUTER, INNER = 2 * math.pi * (BIG + SMALL), 2 * math.pi * (BIG - SMALL)
#: Lengths: within this (relative) of the circles' (the traced length's own accuracy).
LENGTH_RTOL = 1e-9

CASES = [
    # (u_range, v_range) in the plane's frame (its origin the torus's centre), [(status, length)], point or None
    (((-2.5, 3.0), (-3.0, 3.0)), [("closed", OUTER), ("closed", INNER)], None),       # touches u = -2.5 inside
    (((-2.5, 2.5), (-2.5, 2.5)), [("closed", OUTER), ("closed", INNER)], None),       # inscribed in the square
    (((-3.0, 3.0), (0.0, 3.0)), [("boundary", OUTER / 2), ("boundary", INNER / 2)], None),
    (((2.5, 4.0), (-1.0, 1.0)), [("boundary", 0.0)], (2.5, 0.0, 0.0)),                # touches u = 2.5 outside
]


@pytest.mark.parametrize("rect, expected, point", CASES)
def test_general_path_at_a_touched_edge(rect, expected, point, monkeypatch):
    monkeypatch.setattr(intersect_module, "CLOSED_FORMS", False)
    q = np.linalg.qr(np.random.default_rng(3).normal(size=(3, 3)))[0]
    frame = sk.Frame((0.3, -1.2, 0.7), q * np.sign(np.linalg.det(q)))
    torus = sk.Torus(BIG, SMALL, frame)
    plane = sk.Plane(frame, u_range=rect[0], v_range=rect[1])
    for a, b in ((torus, plane), (plane, torus)):
        curves = sk.intersect(a, b)
        got = sorted((c.status, c.length) for c in curves)
        want = sorted(expected)
        assert [s for s, _ in got] == [s for s, _ in want]
        for (_, length), (_, truth) in zip(got, want):
            assert abs(length - truth) <= LENGTH_RTOL * max(truth, 1.0)
        assert all(c.max_distance <= c.tolerance for c in curves)
        if point is not None:
            assert np.allclose(frame.to_local(curves[0].points[0]), point, atol=1e-6)   # a double root
