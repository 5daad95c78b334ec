"""The topology stage's batched helpers against scalar Python versions of the same computations (the oracles): the
results must be the same to the bit, since the stage's seeds and decisions are built from them."""
import math

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.bench.kinds import pair_kind_cases
from spatialkin.kernels.search import topology as kt
from spatialkin.tracing.search import topology as tp
from spatialkin.geometry.traits import traits

TOL = 1e-10


# --- the scalar oracles (the stage's former code) --------------------------------------------------------------
def inside_trims(surface, point, tolerance):
    """True when the surface's foot point of `point` lies within its trims (with a slack of the tolerance)."""
    (u0, u1), (v0, v1) = surface.u_range, surface.v_range
    if not (np.isfinite([u0, u1, v0, v1]).any()):
        return True
    u, v = surface.parameters(point)
    u_slack, v_slack = traits(surface).trim_slack(surface, 10.0 * tolerance)
    if not (u0 - u_slack <= u <= u1 + u_slack):
        return False
    return v0 - v_slack <= v <= v1 + v_slack


def keep(a, b, apex_points, scale, tolerance, point):
    if any(np.linalg.norm(point - x) <= tp.APEX_CLEARANCE * scale for x in apex_points):
        return False
    return inside_trims(a, point, tolerance) and inside_trims(b, point, tolerance)


def line(reader, fixed, value, t0, t1):
    """(verified roots, unresolved midpoints) of g on a parameter line: line_roots, then refine_line per root."""
    out = np.empty((tp.MAX_RECORDS, 2))
    kinds = np.empty(tp.MAX_RECORDS, dtype=np.int64)
    width = max(reader.min_width(t0, t1), 1e-15 * (t1 - t0))
    n, status, boxes = kt.line_roots(reader.s.data, reader.t.data, reader.m, reader.c, reader.pad, reader.cpad,
                                     int(fixed), float(value), float(t0), float(t1), width, tp.COARSE * (t1 - t0),
                                     tp.MAX_BOXES, out, kinds)
    roots = [kt.refine_line(reader.s.data, reader.t.data, reader.m, reader.c, int(fixed), float(value), lo, hi)
             for lo, hi in out[:n][kinds[:n] == kt.VERIFIED]]
    loose = [0.5 * (lo + hi) for lo, hi in out[:n][kinds[:n] == kt.UNRESOLVED]]
    return np.array(roots), np.array(loose), status, boxes


def extremal(reader, box, unit):
    """(verified (K, 2), unresolved (L, 2)) of the interior search: extremal_points, then refine_extremal per root."""
    du, dv = math.cos(tp.DIRECTION) / unit[0], math.sin(tp.DIRECTION) / unit[1]
    out = np.empty((tp.MAX_RECORDS, 4))
    kinds = np.empty(tp.MAX_RECORDS, dtype=np.int64)
    width = np.array([max(reader.min_width(box[0], box[1]), 1e-15 * (box[1] - box[0])),
                      max(reader.min_width(box[2], box[3]), 1e-15 * (box[3] - box[2]))])
    n, status, boxes = kt.extremal_points(reader.s.data, reader.t.data, reader.m, reader.c, reader.pad, reader.cpad,
                                          du, dv, np.ascontiguousarray(box, dtype=float), width,
                                          tp.COARSE * max((box[1] - box[0]) / width[0], (box[3] - box[2]) / width[1]),
                                          tp.MAX_BOXES, out, kinds)
    uv = np.empty(2)
    roots = []
    for rec in out[:n][kinds[:n] == kt.VERIFIED]:
        kt.refine_extremal(reader.s.data, reader.t.data, reader.m, reader.c, du, dv, rec, uv)
        roots.append(uv.copy())
    loose = [[0.5 * (r[0] + r[1]), 0.5 * (r[2] + r[3])] for r in out[:n][kinds[:n] == kt.UNRESOLVED]]
    return np.array(roots).reshape(-1, 2), np.array(loose).reshape(-1, 2), boxes


def place_seams(reader, box, u_periodic, v_periodic, apexes):
    uu, vv = np.meshgrid(np.linspace(box[0], box[1], 9), np.linspace(box[2], box[3], 9))
    typical = float(np.max(np.abs(reader.values(np.column_stack([uu.ravel(), vv.ravel()]))[:, 0])))
    t = np.linspace(0.0, 1.0, 17)
    for k, periodic in ((0, u_periodic), (1, v_periodic)):
        if not periodic:
            continue
        lo, hi = box[2 - 2 * k], box[3 - 2 * k]
        for offset in tp.SEAM_OFFSETS:
            value = -math.pi + offset
            if k == 1 and any(abs(math.remainder(value - v, 2 * math.pi)) < 1e-9 for v in apexes):
                continue
            other = lo + t * (hi - lo)
            uv = np.column_stack([np.full_like(t, value), other] if k == 0 else [other, np.full_like(t, value)])
            if np.mean(np.abs(reader.values(uv)[:, 0]) <= tp.SEAM_FLAT * typical) < 0.5:
                break
        box[2 * k], box[2 * k + 1] = value, value + 2 * math.pi


# --- the pairs ---------------------------------------------------------------------------------------------------
def pairs():
    """The bench's 15 pair kinds, trimmed planes and cylinders among them, and a few that put lines on the level: a
    plane's edge lying in another plane, a torus cut through its axis (a seam along the level)."""
    out = [(a, b) for _, a, b in pair_kind_cases()]
    out.append((sk.Plane(u_range=(-1, 1), v_range=(-1, 1)),
                sk.Plane(sk.Frame((0, 1, 0), sk.rotation_about((1, 0, 0), 0.9)), u_range=(-2, 2), v_range=(-2, 2))))
    out.append((sk.Torus(2.0, 0.5), sk.Plane(sk.Frame((0, 0, 0), sk.rotation_about((1, 0, 0), math.pi / 2)),
                                             u_range=(-3, 3), v_range=(-3, 3))))
    out.append((sk.Cone(0.5, v_range=(0.5, 2.0)), sk.Sphere(1.2, sk.Frame((0.1, 0.0, 1.0)))))
    return out


def readers(a, b):
    return [tp.Reader(a, b), tp.Reader(b, a)]


# --- the tests ---------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("k", range(len(pairs())))
def test_keeper_matches_the_scalar_trim_test(k):
    """Keeper.many and Keeper.select against inside_trims on both surfaces and the apex clearance, point by point:
    points near both surfaces (half inside the trims, half out), and some on an apex; Keeper.on and select_on
    against Surface.point and Keeper.many."""
    a, b = pairs()[k]
    rng = np.random.default_rng(k)
    pts = []
    for s in (a, b):
        lo = [r if math.isfinite(r) else -3.0 for r in (s.u_range[0], s.v_range[0])]
        hi = [r if math.isfinite(r) else 3.0 for r in (s.u_range[1], s.v_range[1])]
        span = np.subtract(hi, lo)
        uv = rng.uniform(np.subtract(lo, 0.5 * span), np.add(hi, 0.5 * span), size=(60, 2))
        pts.append(s.point(uv[:, 0], uv[:, 1]))
    pts = np.vstack(pts)
    apexes = [pts[3], pts[70] + 1e-9]
    scale = 2.0
    keeper = tp.Keeper(a, b, apexes, scale, TOL)
    expected = [keep(a, b, apexes, scale, TOL, x) for x in pts]
    assert list(keeper.many(pts)) == expected
    assert 0 < sum(expected) < len(expected) or not any(math.isfinite(r) for r in a.u_range + a.v_range + b.u_range
                                                        + b.v_range)
    assert [keeper(x) for x in pts] == expected
    assert np.array_equal(np.array(keeper.select(pts)).reshape(-1, 3), pts[np.array(expected, dtype=bool)])
    assert keeper.select(np.empty((0, 3))) == []
    # Keeper.on and select_on (points and test in one compiled call) against Surface.point and many, to the bit
    for s, rows in ((a, slice(0, 60)), (b, slice(60, 120))):
        uv = s.parameters(pts[rows])
        points, kept = keeper.on(s, uv)
        assert points.tobytes() == s.point(uv[:, 0], uv[:, 1]).tobytes()
        assert np.array_equal(kept, keeper.many(points))
        assert np.array_equal(np.array(keeper.select_on(s, uv)).reshape(-1, 3), points[kept])


@pytest.mark.parametrize("k", range(len(pairs())))
def test_line_search_and_probes_match_the_scalar_code(k):
    """Reader.line (one compiled line_search) against line_roots and refine_line called root by root, and its
    probe (line_on_level) against on_level at numpy.linspace's probes, on the edges, seams and lines through the
    middle of both surfaces' domains, both ways round."""
    a, b = pairs()[k]
    checked_on_level = 0
    for reader in readers(a, b):
        s = reader.s
        box = []
        for r in (s.u_range, s.v_range):
            lo, hi = (r if all(map(math.isfinite, r)) else (-math.pi, math.pi))
            box += [lo, hi]
        for fixed in (0, 1):
            t0, t1 = box[2 - 2 * fixed], box[3 - 2 * fixed]
            for value in (box[2 * fixed], box[2 * fixed + 1], 0.37 * box[2 * fixed] + 0.63 * box[2 * fixed + 1]):
                probes = np.linspace(t0, t1, tp.LINE_PROBES)
                want = all(reader.on_level((t, value) if fixed == 1 else (value, t)) for t in probes)
                topo = tp.Topology(P=s, Q=reader.t, mode="general")
                found = reader.line(fixed, value, t0, t1, topo, "line", probe=True)
                assert (found is None) == want
                checked_on_level += want
                if not want:                         # (a line on the level is not searched: it has no roots)
                    roots, loose = found
                    want_roots, want_loose, _, boxes = line(reader, fixed, value, t0, t1)
                    assert np.array_equal(roots, want_roots) and np.array_equal(loose, want_loose)
                    assert topo.boxes == boxes and topo.verified == len(roots) and topo.unresolved == len(loose)
                    plain = reader.line(fixed, value, t0, t1, tp.Topology(P=s, Q=reader.t, mode="general"), "line")
                    assert np.array_equal(plain[0], roots) and np.array_equal(plain[1], loose)
                along = probes[1:-1]
                pts = reader.line_points(fixed, value, along)
                assert np.array_equal(pts, np.array([s.point(*((t, value) if fixed == 1 else (value, t)))
                                                     for t in along]))
    if k == len(pairs()) - 3:
        assert checked_on_level > 0                  # the plane's edge lying in the other plane


@pytest.mark.parametrize("k", range(len(pairs())))
def test_place_seams_matches_the_scalar_code(k):
    """place_seams (its grid and first seam in one evaluation) cuts the seams where the former code did."""
    a, b = pairs()[k]
    for p, q in ((a, b), (b, a)):
        kind = traits(p)
        if not (kind.periodic[0] or kind.periodic[1]):
            continue
        p = kind.general_chart(p, q)
        box, u_periodic, v_periodic = tp.domain(p, tp.bounding_ball(q))
        reader = tp.Reader(p, q)
        for apexes in ([], traits(p).collapse_lines(p), [-math.pi]):
            got, want = box.copy(), box.copy()
            tp.place_seams(reader, got, u_periodic, v_periodic, apexes)
            place_seams(reader, want, u_periodic, v_periodic, apexes)
            assert np.array_equal(got, want)


@pytest.mark.parametrize("k", range(len(pairs())))
def test_extremal_search_matches_the_scalar_code(k):
    """Reader.extremal (one compiled extremal_search) against extremal_points and refine_extremal called root by
    root, over P's whole domain and a sub-box of it, for the parametrised surface of a general placement."""
    a, b = pairs()[k]
    for p, q in ((a, b), (b, a)):
        kind = traits(p)
        p = kind.general_chart(p, q)
        box, u_periodic, v_periodic = tp.domain(p, tp.bounding_ball(q))
        if not (box[0] < box[1] and box[2] < box[3]) or not np.all(np.isfinite(box)):
            continue
        reader = tp.Reader(p, q)
        unit = kind.parameter_units(2.0)
        for sub in (box, box * np.array([0.9, 0.4, 0.7, 0.3])):
            topo = tp.Topology(P=p, Q=q, mode="general")
            roots, loose = reader.extremal(sub, unit, topo)
            want_roots, want_loose, boxes = extremal(reader, sub, unit)
            assert np.array_equal(roots, want_roots) and np.array_equal(loose, want_loose)
            assert topo.boxes == boxes and topo.verified == len(roots) and topo.unresolved == len(loose)
