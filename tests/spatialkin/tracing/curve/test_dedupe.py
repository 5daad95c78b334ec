"""De-duplication of starts: the compiled near_curve (spatialkin.kernels.curve.near on spatialkin.tracing.curve.packed)
against a plain Python one on the curve's dense output (the oracle), and its dense output against scipy's."""
from types import SimpleNamespace

import numpy as np
import pytest
from tests.oracles.closed_forms import torus_sphere_critical_radii
from scipy.spatial import cKDTree

import spatialkin as sk
import spatialkin.tracing.components as intersect_module
from spatialkin.bench.kinds import pair_kind_cases
from spatialkin.kernels.curve import near as kn
from spatialkin.tracing.curve.dense import CLOSEST_NEWTON_STEPS, TracedSolution
from spatialkin.tracing.components import SAME_COMPONENT, covered, near_curve, within
from spatialkin.tracing.curve.packed import packed, packed_grid
from spatialkin.tracing.march.segments import NEWTON_MAX_ITER

#: Pair kinds whose curves cover the tables: closed and open, one span and several (a sphere re-charted), the
#: compiled method's steps and DOP853's (handed over at a trim edge), two curves in one scene.
KINDS = ("torus-torus", "sphere-cylinder", "plane-plane", "cylinder-cone", "cone-cone", "sphere-torus")
#: Relative distance from the radius of the points placed just inside and just outside it (the curve's
#: curvature moves the true distance of an offset point by about offset^2 x curvature, far below this).
RADIUS_EPS = 1e-3
CASES = {name: (a, b) for name, a, b in pair_kind_cases()}
#: The figure-eight of a torus and a sphere at a saddle radius: traced through its node (a jump span).
BIG, SMALL, CENTRE = 3.0, 1.0, np.array([1.0, 0.5, 0.7])


def reference_near_curve(curve, points, radius):
    """near_curve in plain Python (k-d tree candidates, then foot points on the dense output): the oracle."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    out = np.zeros(len(points), dtype=bool)
    ask = np.ones(len(points), dtype=bool)
    if curve.length > 0 and len(curve.points) > 1:
        reach = radius + 0.5 * float(np.max(np.diff(curve.s)))
        gap, nearest = cKDTree(curve.points).query(points, distance_upper_bound=reach)
        ask = gap <= reach
        if ask.any():
            out[ask] = curve.sol.foot_points(points[ask], curve.s[nearest[ask]], CLOSEST_NEWTON_STEPS)[1] <= radius
            ask &= ~out
    if ask.any():
        out[ask] = curve.sol.closest(points[ask])[1] <= radius
    return out


def reference_covered(curve, others, radius):
    """covered in plain Python (every point of the curve within radius of a longer curve): the oracle."""
    if curve.closed or curve.status == "contact":
        return False
    return any(other.length >= curve.length and np.max(other.sol.closest(curve.points)[1]) <= radius
               for other in others)


def results(a, b):
    """The traced CurveResults of a ∩ b (the closed forms off: the plane-quadric kinds are traced too) and the
    radius intersect uses for them."""
    closed_forms, intersect_module.CLOSED_FORMS = intersect_module.CLOSED_FORMS, False
    try:
        curves = sk.intersect(a, b)
    finally:
        intersect_module.CLOSED_FORMS = closed_forms
    scale = max(np.ptp(np.vstack([c.points for c in curves]), axis=0).max(), 1.0)
    return [c._result for c in curves], SAME_COMPONENT * scale


def probe_points(curve, radius, rng, n=60):
    """Points exactly on the curve (stored and dense), at radius (1 -+ RADIUS_EPS) off it along a normal, within
    a few steps of it, and far from it: (points (M, 3), their kind (M,) as strings)."""
    s = rng.uniform(0.0, curve.length, n)
    on = curve.sol(s)
    tangent = curve.sol.tangent(s)
    normal = np.cross(tangent, rng.normal(size=(n, 3)))
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    size = np.ptp(curve.points, axis=0).max()
    groups = {"stored": curve.points[rng.integers(0, len(curve.points), n)], "dense": on,
              "inside": on + normal * radius * (1 - RADIUS_EPS), "outside": on + normal * radius * (1 + RADIUS_EPS),
              "steps": on + normal * rng.uniform(0.0, 0.05 * size, (n, 1)),
              "far": curve.points.mean(axis=0) + rng.uniform(-2.0 * size, 2.0 * size, (n, 3))}
    return np.vstack(list(groups.values())), np.repeat(list(groups), n)


@pytest.mark.parametrize("kind", KINDS)
def test_compiled_mask_equals_the_python_one(kind):
    """On every curve of the scene, the compiled mask equals the oracle's on points on, just inside, just
    outside, near and far; the points on the curve and just inside are near, those just outside and far not."""
    rng = np.random.default_rng(19)
    curves, radius = results(*CASES[kind])
    for curve in curves:
        assert packed(curve.sol) is not None
        points, group = probe_points(curve, radius, rng)
        mask = near_curve(curve, points, radius)
        np.testing.assert_array_equal(mask, reference_near_curve(curve, points, radius))
        assert mask[np.isin(group, ("stored", "dense", "inside"))].all()
        assert not mask[group == "outside"].any()


@pytest.mark.parametrize("kind", KINDS)
def test_foot_points_bit_identical(kind):
    """The compiled foot point (every step taken) equals CurveSolution.foot_points to the bit, in s and distance,
    from arbitrary starts (a closed curve's s past its length included)."""
    rng = np.random.default_rng(7)
    curves, radius = results(*CASES[kind])
    for curve in curves:
        sol, table = curve.sol, packed(curve.sol)
        points = probe_points(curve, radius, rng, n=20)[0]
        start = rng.uniform(0.0, curve.length * (1.5 if curve.closed else 1.0), len(points))
        s, dist = sol.foot_points(points, start, CLOSEST_NEWTON_STEPS)
        got = np.array([kn.foot_distance(table, sol.closed, sol.length, sol.gap_tol, NEWTON_MAX_ITER, p, s0,
                                         CLOSEST_NEWTON_STEPS, -1.0) for p, s0 in zip(points, start)])
        np.testing.assert_array_equal(got[:, 0], s)
        np.testing.assert_array_equal(got[:, 1], dist)


@pytest.mark.parametrize("kind", ["plane-plane", "cylinder-cone", "sphere-cylinder"])
def test_solver_states_read_each_span_record(kind):
    """solver_state reads span k's rows of the packed tables: the states of span k's own record (its Steps), at its
    step times and between them (the same arrays read through the table's offsets)."""
    curve = results(*CASES[kind])[0][0]
    table = packed(curve.sol)
    rng = np.random.default_rng(3)
    for k, span in enumerate(curve.sol.spans):
        ode = span.seg.sol
        t = np.concatenate([ode.t, rng.uniform(ode.t[0], ode.t[-1], 50)])
        out = np.empty(4)
        for tk in t:
            kn.solver_state(table, k, tk, out)
            np.testing.assert_array_equal(out, ode(tk))


def test_spans_without_tables_left_to_python():
    """A circle in closed form has no table; a figure-eight traced through its node has one whose jump spans
    are marked not held (Newton meeting them leaves the point to Python) and whose re-measured spans beside the
    node are held. Both masks are the oracle's, on points everywhere on and off the curve and beside the node."""
    rng = np.random.default_rng(5)
    circle, radius = results(*CASES["sphere-sphere"])
    rho = torus_sphere_critical_radii(BIG, SMALL, CENTRE)[1]
    eight, radius8 = results(sk.Torus(BIG, SMALL), sk.Sphere(rho, sk.Frame(CENTRE)))
    curve = eight[0]
    assert packed(circle[0].sol) is None
    jumps = np.array([span.seg.normal.any() for span in curve.sol.spans])
    assert jumps.any() and isinstance(curve.sol, TracedSolution)
    np.testing.assert_array_equal(packed(curve.sol)[0][:, kn.COMPILED] == 1.0, ~jumps)
    node = curve.nodes[0]
    beside = node + rng.normal(size=(40, 3)) * rng.uniform(0.0, 1e-2, (40, 1))
    for c, r, extra in ((circle[0], radius, np.empty((0, 3))), (curve, radius8, beside)):
        points = np.vstack([probe_points(c, r, rng, n=15)[0], extra])
        np.testing.assert_array_equal(near_curve(c, points, r), reference_near_curve(c, points, r))


@pytest.mark.parametrize("kind", ["plane-plane", "cone-cone", "torus-torus"])
def test_covered_as_the_python_one(kind):
    """A piece of a curve (open, shorter) is covered by it; the same piece moved 10 radii off it, or cut from
    another curve of the scene, is not: as the oracle says."""
    curves, radius = results(*CASES[kind])
    curve = curves[0]
    s = np.linspace(0.2, 0.6, 40) * curve.length
    on = curve.sol(s)
    off = on + 10.0 * radius * np.cross(curve.sol.tangent(s), [0.0, 0.0, 1.0])

    def piece(points):
        return SimpleNamespace(closed=False, status="boundary", points=points, length=0.4 * curve.length)

    pieces = {"on": piece(on), "off": piece(off)}
    if len(curves) > 1:
        pieces["other"] = piece(curves[1].sol(np.linspace(0.0, 0.4, 40) * curves[1].length))
    for name, p in pieces.items():
        assert covered(p, [curve], radius) == reference_covered(p, [curve], radius) == (name == "on"), name


def test_interp_bit_identical_to_numpy():
    """kernels.near.interp equals np.interp to the bit: between knots, at knots, at and beyond both ends, and
    for a single knot."""
    rng = np.random.default_rng(11)
    xp = np.cumsum(rng.uniform(0.1, 1.0, 30))
    fp = np.cumsum(rng.uniform(0.1, 1.0, 30))
    x = np.concatenate([rng.uniform(xp[0] - 1.0, xp[-1] + 1.0, 500), xp, [xp[0], xp[-1]]])
    np.testing.assert_array_equal([kn.interp(v, xp, fp) for v in x], np.interp(x, xp, fp))
    assert kn.interp(0.3, xp[:1], fp[:1]) == np.interp(0.3, xp[:1], fp[:1])


@pytest.mark.parametrize("kind", ["torus-torus", "plane-plane", "sphere-cylinder"])
def test_closest_grid_and_verdicts_as_closest(kind):
    """The compiled grid equals CurveSolution.grid to the bit; `within` says what closest() says of the points
    against radius (points on, just inside, just outside, a few steps off, far)."""
    rng = np.random.default_rng(23)
    curves, radius = results(*CASES[kind])
    curve = curves[0]
    fresh = TracedSolution(surfaces=curve.sol.surfaces, spans=curve.sol.spans, nodes=curve.sol.nodes,
                           gap_tol=curve.sol.gap_tol, length=curve.sol.length, closed=curve.sol.closed,
                           knots=curve.sol.knots)                  # no grid cached by an earlier closest()
    s, points = packed_grid(fresh, packed(fresh))
    np.testing.assert_array_equal(s, fresh.grid()[0])
    np.testing.assert_array_equal(points, fresh.grid()[1])
    probes = probe_points(curve, radius, rng, n=20)[0]
    np.testing.assert_array_equal(within(curve, probes, radius), curve.sol.closest(probes)[1] <= radius)
