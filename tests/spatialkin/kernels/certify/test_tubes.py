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


def test_pieces_beside_a_close_branch_hold_their_own_line_only():
    """A plane at 1 - eps from a unit cylinder's axis, parallel to it, cuts it in the two rulings u = +-acos(1 - eps),
    2 sqrt(2 eps) apart (eps = 1e-8, below the closed forms' grazing distance: the search and the tubes prove them).
    Both are proven, every stored point within the proven distance bound of its ruling; every piece holds its own
    ruling (its points inside the piece's W wherever they lie in its T) and none of the other one's."""
    eps = 1e-8
    cylinder = sk.Cylinder(1.0, v_range=(-1.0, 1.0))
    plane = sk.Plane(sk.Frame((1.0 - eps, 0.0, 0.0), sk.rotation_about((0.0, 1.0, 0.0), math.pi / 2)))
    curves = sk.intersect(cylinder, plane, certify=True)
    assert curves.certificate.proven, curves.certificate.failed
    assert len(curves) == 2
    u_star = math.acos(1.0 - eps)
    chart = curves.certificate.chart
    assert chart.p is cylinder or type(chart.p) is sk.Cylinder
    v = np.linspace(-1.0, 1.0, 2001)
    for curve, tube in zip(curves, curves.certificate.tubes):
        side = np.sign(curve.points[0, 1])
        own = chart.scaled(np.column_stack([np.full_like(v, np.cos(u_star)), side * np.full_like(v, np.sin(u_star)),
                                            v]))
        other = chart.scaled(np.column_stack([np.full_like(v, np.cos(u_star)), -side * np.full_like(v, np.sin(u_star)),
                                              v]))
        off = np.hypot(curve.points[:, 0] - math.cos(u_star), curve.points[:, 1] - side * math.sin(u_star))
        assert np.all(off <= curve.certificate.distance_bound) and curve.certificate.distance_bound < 1e-9
        for piece in tube.pieces:
            held = 0
            for shift in chart.shifts(np.repeat(piece[[kt.CU, kt.CV]], 2), np.repeat(own[0], 2)):
                t, w = frame_coordinates(piece, own + np.array(shift))
                within = (t > piece[kt.T0]) & (t < piece[kt.T1]) & (np.abs(w) < 1.0)    # (this turn of u)
                held += np.count_nonzero(within)
                assert np.all(np.abs(w[within]) < piece[kt.H])
                t_o, w_o = frame_coordinates(piece, other + np.array(shift))
                within_o = (t_o > piece[kt.T0]) & (t_o < piece[kt.T1])
                assert np.all(np.abs(w_o[within_o]) > piece[kt.H])
            assert held > 0


def test_close_branches_of_nearly_touching_surfaces_are_proven():
    """Stress cases where the surfaces nearly touch and two components run close beside each other (a plane just
    inside a torus's top, two cylinders nearly tangent from outside, and from inside with arcs ending on their rims
    (each crossing its edge once: the arc's slope to second order), a sphere and a cone nearly touching along a
    circle, whose tubes need more pieces than the first budget): proven, with the oracle's two components."""
    from tests.oracles.ssi_cases import all_cases
    names = ("contact/plane-torus/top-in", "contact/cylinder-cylinder/ext-in", "contact/plane-cylinder/in",
             "contact/sphere-cone/circle-out", "contact/cylinder-cylinder/int-out")
    cases = {c.name: c for c in all_cases() if c.name in names}
    assert len(cases) == len(names)
    for name, case in cases.items():
        curves = sk.intersect(case.a, case.b, certify=True)
        assert curves.certificate.proven, (name, curves.certificate.failed)
        assert len(curves) == case.count == 2, name


def chain_pieces(points, h):
    """Pieces (K, WIDTH) along the polyline points (K + 1, 2): each centred on its chord, along it, T its half
    length plus 10%, half-width h."""
    chords = np.diff(points, axis=0)
    length = np.linalg.norm(chords, axis=1)
    pieces = np.zeros((len(chords), kt.WIDTH))
    pieces[:, [kt.CU, kt.CV]] = 0.5 * (points[:-1] + points[1:])
    pieces[:, [kt.P, kt.Q]] = chords / length[:, None]
    pieces[:, kt.T0], pieces[:, kt.T1], pieces[:, kt.H] = -0.55 * length, 0.55 * length, h
    return pieces


def corners(pieces):
    """(K, 4, 2): the corners c +- T a +- h n of the pieces' parallelograms."""
    c, a = pieces[:, [kt.CU, kt.CV]], pieces[:, [kt.P, kt.Q]]
    n = np.column_stack([-a[:, 1], a[:, 0]])
    return np.stack([c + t[:, None] * a + w * pieces[:, kt.H, None] * n
                     for t in (pieces[:, kt.T0], pieces[:, kt.T1]) for w in (-1.0, 1.0)], axis=1)


def parallelogram_gaps(first, second, shift):
    """(K, L): the largest separation (positive: apart) of each pair of parallelograms, the second shifted by
    shift along u, over their four edge normals (exact for convex polygons, in floats)."""
    ca, cb = corners(first), corners(second) + np.array([shift, 0.0])
    gap = np.full((len(first), len(second)), -np.inf)
    for pieces, mine in ((first, True), (second, False)):
        a = pieces[:, [kt.P, kt.Q]]
        for axis in (a, np.column_stack([-a[:, 1], a[:, 0]])):
            if mine:        # (K, 4) projections of first, (K, L, 4) of second on first's axes
                p, q = np.einsum("kcd,kd->kc", ca, axis)[:, None, :], np.einsum("lcd,kd->klc", cb, axis)
            else:
                p, q = np.einsum("kcd,ld->klc", ca, axis), np.einsum("lcd,ld->lc", cb, axis)[None, :, :]
            gap = np.maximum(gap, np.maximum(q.min(-1) - p.max(-1), p.min(-1) - q.max(-1)))
    return gap


def may_overlap(first, second, shift):
    """(K, L) the pair test alone: the pieces' parameter boxes meet (second shifted by shift along u) and
    pieces_overlap does not part them."""
    boxes = [np.array([np.ravel(kt.piece_span(p)) for p in pieces]) for pieces in (first, second)]
    (au0, au1, av0, av1), (bu0, bu1, bv0, bv1) = (b.T[:, :, None] if k == 0 else b.T[:, None, :]
                                                  for k, b in enumerate(boxes))
    meet = ~((bu1 + shift < au0) | (au1 < bu0 + shift) | (bv1 < av0) | (av1 < bv0))
    out = np.zeros_like(meet)
    for i, j in zip(*np.nonzero(meet)):
        out[i, j] = kt.pieces_overlap(first[i], second[j], shift, 0.0)
    return out


def test_tubes_disjoint_agrees_with_every_pair_under_every_shift():
    """Two chains of pieces (30 to 300 each, spiralling over more than a period of u, so that a group of pieces
    spans more than one period) a clear gap apart, alongside or crossing. tubes_disjoint against every pair under
    every whole period from -8 to 8: it reports an overlap whenever two parallelograms overlap (separating axes,
    in floats; pairs within 1e-9 of touching are not drawn), it reports one exactly when the pair test does for
    some pair and period, and the pair it reports is one of those."""
    rng = np.random.default_rng(7)
    period = 2.0 * math.pi
    verdicts = set()
    for case in range(24):
        s = np.linspace(0.0, 1.0, int(rng.integers(30, 300)))
        u0, v0, turns = rng.uniform(-10, 10), rng.uniform(-1, 1), rng.uniform(0.2, 2.5)
        line = np.column_stack([u0 + turns * period * s, v0 + 0.3 * np.sin(7 * s + case)])
        other = line + np.array([rng.uniform(-0.5, 0.5) + period * rng.integers(-3, 4),
                                 rng.choice([rng.uniform(0.02, 0.2), rng.uniform(-0.01, 0.01)])])
        if case % 3 == 0:                       # crossing, not alongside
            other = np.column_stack([other[:, 0], v0 + 4.0 * (s - 0.5) + rng.uniform(-0.1, 0.1)])
        first, second = chain_pieces(line, 0.004), chain_pieces(other[::-1], 0.003)
        shifts = period * np.arange(-8, 9)
        gaps = np.min([parallelogram_gaps(first, second, k) for k in shifts], axis=0)
        if np.min(np.abs(gaps)) < 1e-9:
            continue
        flagged = np.any([may_overlap(first, second, k) for k in shifts], axis=0)
        i, j = kt.tubes_disjoint(first, second, np.array([period, 0.0]))
        assert i >= 0 or gaps.min() > 0
        assert (i >= 0) == flagged.any()
        if i >= 0:
            assert flagged[i, j]
        verdicts.add(bool(gaps.min() > 0))
    assert verdicts == {True, False}
