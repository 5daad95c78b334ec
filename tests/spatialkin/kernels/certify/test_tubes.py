"""The arc enclosures of proven tube pieces (spatialkin.kernels.certify.tubes.arc_enclosure) against a closed form.

Oracle: a unit cylinder along z and a sphere of radius 1.5 centred off its axis by d meet in the loops
z = +-sqrt(2.25 - (1 + d^2 - 2 d cos theta)); their points, mapped into each piece's frame, must lie in the
enclosure of the piece's arc over any stretch of T that holds them.
"""
import math

import numpy as np

import spatialkin as sk
from spatialkin.kernels.certify import tubes as kt
from spatialkin.tracing.certify.tubes import Chart

D = 0.05


def true_points(theta, sign):
    z = sign * np.sqrt(2.25 - (1 + D * D - 2 * D * np.cos(theta)))
    return np.column_stack([np.cos(theta), np.sin(theta), z])


def frame_coordinates(piece, x):
    """(t, w) of the scaled parameter points x (N, 2) in the piece's frame c + t a + w n."""
    r = x - piece[[kt.CU, kt.CV]]
    a = piece[[kt.P, kt.Q]]
    n = np.array([-a[1], a[0]])
    norm = a @ a
    return r @ a / norm, r @ n / norm


def test_arc_enclosures_hold_the_true_curve_and_narrow_on_short_stretches():
    cylinder, sphere = sk.Cylinder(1.0, v_range=(-3.0, 3.0)), sk.Sphere(1.5, sk.Frame((D, 0.0, 0.0)))
    curves = sk.intersect(cylinder, sphere, certify=True)
    assert curves.certificate.proven
    chart = Chart(curves[0].topology, 1.0)
    r = chart.reader
    su, sv = float(chart.units[0]), float(chart.units[1])
    theta = np.linspace(0.0, 2.0 * math.pi, 4001)
    checked = 0
    for curve, tube in zip(curves, curves.certificate.tubes):
        truth = chart.scaled(true_points(theta, np.sign(curve.points[0, 2])))
        for piece in tube.pieces[::7]:
            for shift in chart.shifts(np.repeat(piece[[kt.CU, kt.CV]], 2), np.repeat(truth[0], 2)):
                t, w = frame_coordinates(piece, truth + np.array(shift))
                inside = (t > piece[kt.T0]) & (t < piece[kt.T1]) & (np.abs(w) < piece[kt.H])
                for k in np.flatnonzero(inside)[::5]:
                    half = 1e-3 * (piece[kt.T1] - piece[kt.T0])
                    t0, t1 = max(t[k] - half, piece[kt.T0]), min(t[k] + half, piece[kt.T1])
                    lo, hi = kt.arc_enclosure(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, su, sv, piece, t0, t1)
                    slack = 1e-13 * max(1.0, abs(piece[kt.CU]), abs(piece[kt.CV]))
                    assert lo - slack <= w[k] <= hi + slack
                    assert hi - lo < 1e-4 * piece[kt.H] + 1e-12       # a short stretch's enclosure is narrow
                    whole = kt.arc_enclosure(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, su, sv, piece,
                                             piece[kt.T0], piece[kt.T1])
                    assert -piece[kt.H] <= whole[0] <= w[k] + slack and w[k] - slack <= whole[1] <= piece[kt.H]
                    checked += 1
    assert checked > 50
