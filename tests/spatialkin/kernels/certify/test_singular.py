"""The sign of the level g along a segment of the search chart (spatialkin.kernels.certify.singular.sign_on_segment)
against a closed form.

Oracle: a unit cylinder along z and a sphere of radius 1.5 centred off its axis by d meet in two loops; a point of
the chart's surface lies inside the other surface or outside it (its distance to the cylinder's axis against 1, or
to the sphere's centre against 1.5), so g keeps one sign where that side does not change, and changes sign on a
segment whose samples lie on both sides.
"""
import numpy as np

import spatialkin as sk
from spatialkin.kernels.certify import singular as ksg
from spatialkin.tracing.certify.tubes import Chart

D = 0.05
#: Samples of a segment the oracle reads, and the least |side| (of the surfaces' scale) a proven segment keeps.
SAMPLES, MARGIN = 2001, 1e-3


def side(surface, x):
    """> 0 outside, < 0 inside the other surface of the pair, for points x (N, 3)."""
    if isinstance(surface, sk.Cylinder):
        return np.linalg.norm(x - [D, 0.0, 0.0], axis=1) - 1.5
    return np.hypot(x[:, 0], x[:, 1]) - 1.0


def pair_chart():
    """(the loops, the search's chart, its Reader, its units) of the unit cylinder and the sphere."""
    cylinder, sphere = sk.Cylinder(1.0, v_range=(-3.0, 3.0)), sk.Sphere(1.5, sk.Frame((D, 0.0, 0.0)))
    curves = sk.intersect(cylinder, sphere)
    chart = Chart(curves[0].topology, 1.0)
    return curves, chart, chart.reader, float(chart.units[0]), float(chart.units[1])


def test_sign_along_segments_follows_the_side_of_the_other_surface():
    curves, chart, r, su, sv = pair_chart()
    x = chart.scaled(np.concatenate([c.points for c in curves]))
    lo, hi = x.min(axis=0) - 0.3 * np.ptp(x, axis=0), x.max(axis=0) + 0.3 * np.ptp(x, axis=0)
    rng = np.random.default_rng(7)
    seen, agree = {"proven": 0, "crossing": 0}, set()
    for _ in range(400):
        a = rng.uniform(lo, hi)
        b = a + rng.normal(size=2) * 0.05 * np.ptp(x, axis=0)
        t = np.linspace(0.0, 1.0, SAMPLES)[:, None]
        raw = (a + t * (b - a)) * chart.units
        sides = side(chart.p, chart.p.point(raw[:, 0], raw[:, 1]))
        sign = ksg.sign_on_segment(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, su, sv, a[0], a[1], b[0], b[1],
                                   ksg.SEGMENT_BOXES)
        if sides.min() < 0.0 < sides.max():
            assert sign == 0
            seen["crossing"] += 1
        elif np.abs(sides).min() > MARGIN:
            assert sign != 0
            agree.add(sign * np.sign(sides[0]))        # (g's sign against the side: one convention throughout)
            seen["proven"] += 1
    assert len(agree) == 1 and seen["proven"] > 50 and seen["crossing"] > 20, seen


def test_a_segment_beyond_its_budget_is_not_proven():
    """A chord of one loop (g vanishes at its ends) is never proven; a short segment between the loops is, but not
    with no piece allowed."""
    curves, chart, r, su, sv = pair_chart()
    x = chart.scaled(curves[0].points)
    a, b = x[0], x[len(x) // 2]           # (two points of one loop: g vanishes at both ends)
    assert ksg.sign_on_segment(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, su, sv, a[0], a[1], b[0], b[1],
                               ksg.SEGMENT_BOXES) == 0
    mid = 0.5 * (x.mean(axis=0) + chart.scaled(curves[1].points).mean(axis=0))
    ends = mid - 1e-3, mid + 1e-3
    args = (r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, su, sv, ends[0][0], ends[0][1], ends[1][0], ends[1][1])
    assert ksg.sign_on_segment(*args, ksg.SEGMENT_BOXES) != 0
    assert ksg.sign_on_segment(*args, 0) == 0
