"""De-duplication of starts and the traced curve's distance queries: near_curve, within and covered
(spatialkin.tracing.components), and a traced curve's closest and foot points and its compiled tables
(spatialkin.kernels.curve.near on spatialkin.tracing.curve.packed).

Oracle: the distance of a point to the curve measured apart from the library's foot-point Newton: the nearest
of 20000 dense samples of the curve (a k-d tree), a bounded scalar minimisation of |p - curve(s)| over the
samples' neighbourhoods (scipy.optimize.minimize_scalar), the smallest of four candidates, and the distance to the
curve's tangent line there (a central difference). The dense output it
samples is checked against the surfaces' exact distances elsewhere (test_curve_result, test_intersect).
"""
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.optimize import minimize_scalar
from scipy.spatial import cKDTree

import spatialkin as sk
import spatialkin.tracing.components as intersect_module
from spatialkin.bench.kinds import pair_kind_cases
from spatialkin.kernels.curve import near as kn
from spatialkin.tracing.components import SAME_COMPONENT, covered, near_curve, within
from spatialkin.tracing.curve.dense import CLOSEST_NEWTON_STEPS, TracedSolution
from spatialkin.tracing.curve.result import point_gaps
from spatialkin.tracing.march.trace import DEFAULT_SINGULAR_TOL
from tests.oracles.closed_forms import torus_sphere_critical_radii

#: Pair kinds whose curves cover the tables: closed and open, one span and several (a sphere re-charted), the
#: compiled method's steps and DOP853's (handed over at a trim edge), two curves in one scene.
KINDS = ("torus-torus", "sphere-cylinder", "plane-plane", "cylinder-cone", "cone-cone", "sphere-torus")
#: Relative distance from the radius of the points placed just inside and just outside it (the curve's
#: curvature moves the true distance of an offset point by about offset^2 x curvature, far below this).
RADIUS_EPS = 1e-3
CASES = {name: (a, b) for name, a, b in pair_kind_cases()}
#: The figure-eight of a torus and a sphere at a saddle radius: traced through its node (a jump span).
BIG, SMALL, CENTRE = 3.0, 1.0, np.array([1.0, 0.5, 0.7])


#: Dense samples of the oracle, its candidates, and the relative tolerance of its minimisation.
ORACLE_SAMPLES = 20000
ORACLE_CANDIDATES = 4
ORACLE_XTOL = 1e-14
#: Step of the central difference giving the tangent at the minimiser's arc length (relative to the length).
TANGENT_STEP = 1e-6
#: A decision against the radius is checked only outside this relative band round it (the oracle's and the
#: library's distances agree far closer, but a point within round-off of the radius may go either way).
DECIDED_BAND = 1e-4


def oracle_distance(curve, points):
    """(distance (M,), arc length (M,)) of each point to the curve, measured apart (see the module docstring)."""
    s_grid = np.linspace(0.0, curve.length, ORACLE_SAMPLES)
    dense = curve.sol(s_grid)
    step = s_grid[1] - s_grid[0]
    _, nearest = cKDTree(dense).query(points, k=ORACLE_CANDIDATES)
    dist, at = np.full(len(points), np.inf), np.zeros(len(points))
    for m, p in enumerate(points):
        for j in np.atleast_1d(nearest[m]):
            lo, hi = max(0.0, s_grid[j] - step), min(curve.length, s_grid[j] + step)
            res = minimize_scalar(lambda x: np.linalg.norm(p - curve.sol(x)), bounds=(lo, hi), method="bounded",
                                  options={"xatol": ORACLE_XTOL * max(curve.length, 1.0)})
            if res.fun < dist[m]:
                dist[m], at[m] = res.fun, res.x
        # the minimiser's s is good to about sqrt(eps) of s only: the distance to the curve's tangent line there
        # (a central difference of the dense output) is exact to curvature x (that error)^2
        h = TANGENT_STEP * max(curve.length, 1.0)
        lo, hi = max(0.0, at[m] - h), min(curve.length, at[m] + h)
        chord = curve.sol(hi) - curve.sol(lo)
        tangent = chord / np.linalg.norm(chord)
        off = p - curve.sol(at[m])
        along = off @ tangent
        dist[m] = np.linalg.norm(off - along * tangent)
        at[m] = at[m] + along
    return dist, at


def assert_decides_as_the_oracle(mask, distance, radius):
    """mask True where the oracle's distance is below radius (1 - DECIDED_BAND), False where above radius
    (1 + DECIDED_BAND)."""
    assert mask[distance < radius * (1 - DECIDED_BAND)].all()
    assert not mask[distance > radius * (1 + DECIDED_BAND)].any()


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
def test_near_curve_decides_as_the_distance_oracle(kind):
    """On every curve of the scene, near_curve says near where the oracle's distance is below the radius and far
    where it is above, on points on, just inside, just outside, a few steps off and far; the points on the curve and
    just inside are near, those just outside and far not."""
    rng = np.random.default_rng(19)
    curves, radius = results(*CASES[kind])
    for curve in curves:
        assert curve.sol.table is not None
        points, group = probe_points(curve, radius, rng)
        mask = near_curve(curve, points, radius)
        assert_decides_as_the_oracle(mask, oracle_distance(curve, points)[0], radius)
        assert mask[np.isin(group, ("stored", "dense", "inside"))].all()
        assert not mask[group == "outside"].any()


@pytest.mark.parametrize("kind", KINDS)
def test_foot_and_closest_points_are_the_oracles(kind):
    """A traced curve's closest point (compiled) is the oracle's: its distance within 1e-10 x scale for points within a
    few radii of the curve (never nearer, and within 1e-4 relative, for points a few steps off: its few Newton steps
    serve the de-duplication's radius); the foot point from the oracle's own arc length stays there (the same
    distance) and the chord from it to the point is normal to the curve's tangent."""
    rng = np.random.default_rng(7)
    curves, radius = results(*CASES[kind])
    for curve in curves:
        scale = float(np.ptp(curve.points, axis=0).max())
        points, group = probe_points(curve, radius, rng, n=20)
        points, group = points[np.isin(group, ("inside", "outside", "steps"))], group[np.isin(group, ("inside",
                                                                                                   "outside", "steps"))]
        want, at = oracle_distance(curve, points)
        s, dist = curve.sol.closest(points)
        close = group != "steps"                  # within a few radii: exact; a few steps off: never too near
        np.testing.assert_allclose(dist[close], want[close], rtol=0, atol=1e-10 * scale)
        assert np.all(dist >= want - 1e-10 * scale) and np.all(dist <= want * (1 + 1e-4) + 1e-10 * scale)
        s_foot, d_foot = curve.sol.foot_points(points, at, CLOSEST_NEWTON_STEPS)
        np.testing.assert_allclose(d_foot, want, rtol=0, atol=1e-10 * scale)
        chord = points - curve.sol(s_foot)
        along = np.einsum("ij,ij->i", chord, curve.sol.tangent(s_foot))
        assert np.all(np.abs(along) <= 1e-8 * scale)


@pytest.mark.parametrize("kind, traced", [(kind, True) for kind in KINDS] + [("plane-sphere", False),
                                                                              ("plane-cone", False)])
def test_closest_points_from_afar(kind, traced):
    """Points 0.5 to 1e5 times the curve's size away, beyond its radius of curvature (where Gauss-Newton's step
    overshoots by the distance over that radius), on traced curves (compiled) and closed forms (numpy): the
    closest point's distance is the oracle's within 1e-10 of it (relative, and 1e-10 x scale), never below it,
    and the chord from the point is normal to the curve there (to the distance's flatness), unless the foot is an
    end of an open curve. The
    oracle: the bounded minimisation of oracle_distance, without its tangent line (which serves points near the
    curve, with a foot inside it)."""
    rng = np.random.default_rng(11)
    curves = results(*CASES[kind])[0] if traced else [c._result for c in sk.intersect(*CASES[kind])]
    for curve in curves:
        scale = float(np.ptp(curve.points, axis=0).max())
        centre = curve.points.mean(axis=0)
        away = rng.normal(size=(24, 3))
        away *= (scale * np.geomspace(0.5, 1e5, 24) / np.linalg.norm(away, axis=1))[:, None]
        points = centre + away
        s_grid = np.linspace(0.0, curve.length, ORACLE_SAMPLES)
        _, nearest = cKDTree(curve.sol(s_grid)).query(points, k=ORACLE_CANDIDATES)
        want = np.array([min(minimize_scalar(lambda x: np.linalg.norm(p - curve.sol(x)), method="bounded",
                                             bounds=(max(0.0, s_grid[j] - s_grid[1]),
                                                     min(curve.length, s_grid[j] + s_grid[1])),
                                             options={"xatol": ORACLE_XTOL * max(curve.length, 1.0)}).fun
                             for j in row) for p, row in zip(points, nearest)])
        if not curve.closed:                    # (the bounded minimisation keeps off its bounds: the ends apart)
            ends = curve.sol(np.array([0.0, curve.length]))
            want = np.minimum(want, np.linalg.norm(points[:, None, :] - ends[None], axis=2).min(axis=1))
        s, dist = curve.sol.closest(points)
        np.testing.assert_allclose(dist, want, rtol=1e-10, atol=1e-10 * scale)
        assert np.all(dist >= want * (1 - 1e-12) - 1e-12 * scale)
        chord = points - curve.sol(s)
        along = np.einsum("ij,ij->i", chord, curve.sol.tangent(s)) / np.linalg.norm(chord, axis=1)
        inner = (s > 1e-9 * curve.length) & (s < curve.length * (1 - 1e-9)) | curve.closed
        # (the distance is flat at the foot: s, and the chord's angle, are settled to about sqrt(eps x distance))
        assert np.all(np.abs(along[inner]) <= 8.0 * np.sqrt(np.finfo(float).eps * dist[inner] / scale))


@pytest.mark.parametrize("kind", ["plane-plane", "cylinder-cone", "sphere-cylinder"])
def test_solver_states_read_each_span_record(kind):
    """solver_state reads span k's rows of the packed tables: the states of span k's own record (its Steps), at its
    step times and between them (the same arrays read through the table's offsets)."""
    curve = results(*CASES[kind])[0][0]
    table = curve.sol.table
    rng = np.random.default_rng(3)
    for k, span in enumerate(curve.sol.spans):
        ode = span.seg.sol
        t = np.concatenate([ode.t, rng.uniform(ode.t[0], ode.t[-1], 50)])
        out = np.empty(4)
        for tk in t:
            kn.solver_state(table, k, tk, out)
            np.testing.assert_array_equal(out, ode(tk))


def test_spans_without_tables_left_to_python():
    """A circle in closed form has no table; a figure-eight traced through its node has one whose jump spans are
    marked not held (evaluated in Python) and whose re-measured spans beside the node are held. near_curve decides
    as the oracle on both, on points everywhere on and off the curve and beside the node, and the dense output on
    the jump spans lies on both surfaces."""
    rng = np.random.default_rng(5)
    circle, radius = results(*CASES["sphere-sphere"])
    rho = torus_sphere_critical_radii(BIG, SMALL, CENTRE)[1]
    torus, sphere = sk.Torus(BIG, SMALL), sk.Sphere(rho, sk.Frame(CENTRE))
    eight, radius8 = results(torus, sphere)
    curve = eight[0]
    assert circle[0].sol.table is None
    jumps = np.array([span.seg.normal.any() for span in curve.sol.spans])
    assert jumps.any() and isinstance(curve.sol, TracedSolution)
    np.testing.assert_array_equal(curve.sol.table[0][:, kn.COMPILED] == 1.0, ~jumps)
    on_jumps = np.concatenate([np.linspace(span.lo, span.hi, 9) for span, jump in zip(curve.sol.spans, jumps)
                               if jump])
    points = curve.sol(on_jumps)
    assert max(torus.distance(points).max(), sphere.distance(points).max()) <= curve.tolerance
    node = curve.nodes[0]
    beside = node + rng.normal(size=(40, 3)) * rng.uniform(0.0, 1e-2, (40, 1))
    for c, r, extra in ((circle[0], radius, np.empty((0, 3))), (curve, radius8, beside)):
        points = np.vstack([probe_points(c, r, rng, n=15)[0], extra])
        assert_decides_as_the_oracle(near_curve(c, points, r), oracle_distance(c, points)[0], r)


@pytest.mark.parametrize("kind", ["plane-plane", "cone-cone", "torus-torus"])
def test_covered(kind):
    """A piece of a curve (open, shorter) is covered by it; the same piece moved 10 radii off it, or cut from
    another curve of the scene, is not."""
    curves, radius = results(*CASES[kind])
    curve = curves[0]
    s = np.linspace(0.2, 0.6, 40) * curve.length
    on = curve.sol(s)
    off = on + 10.0 * radius * np.cross(curve.sol.tangent(s), [0.0, 0.0, 1.0])

    def piece(points):
        gaps = point_gaps(*curve.sol.surfaces, points, curve.tolerance)
        return SimpleNamespace(closed=False, status="boundary", points=points, length=0.4 * curve.length,
                               sol=SimpleNamespace(surfaces=curve.sol.surfaces), gaps=gaps, largest_gap=gaps.max())

    pieces = {"on": piece(on), "off": piece(off)}
    limits = SimpleNamespace(singular_tol=DEFAULT_SINGULAR_TOL, tolerance=curve.tolerance)
    if len(curves) > 1:
        pieces["other"] = piece(curves[1].sol(np.linspace(0.0, 0.4, 40) * curves[1].length))
    for name, p in pieces.items():
        assert covered(p, [curve], radius, limits) == (name == "on"), name


def test_remapped_time_is_numpys_interp_and_extends_the_end_steps():
    """kernels.curve.near.remapped_time equals np.interp (to 1 ulp) between the knots and at them, and beyond either
    end the line through the two end knots (to 1e-15 relative), for a single knot the knot's value."""
    rng = np.random.default_rng(11)
    xp = np.cumsum(rng.uniform(0.1, 1.0, 30))
    fp = np.cumsum(rng.uniform(0.1, 1.0, 30))
    inside = np.concatenate([rng.uniform(xp[0], xp[-1], 500), xp])
    got = np.array([kn.remapped_time(v, xp, fp) for v in inside])
    np.testing.assert_array_max_ulp(got, np.interp(inside, xp, fp), maxulp=1)
    for x, (i, j) in ((xp[0] - 0.7, (0, 1)), (xp[-1] + 0.4, (-2, -1))):
        line = fp[i] + (x - xp[i]) * (fp[j] - fp[i]) / (xp[j] - xp[i])
        assert abs(kn.remapped_time(x, xp, fp) - line) <= 1e-15 * abs(line)
    assert kn.remapped_time(0.3, xp[:1], fp[:1]) == fp[0]


@pytest.mark.parametrize("kind", ["torus-torus", "plane-plane", "sphere-cylinder"])
def test_within_decides_as_the_oracle(kind):
    """`within` (the closest point against radius) decides as the oracle's distance, on points on, just inside,
    just outside, a few steps off and far."""
    rng = np.random.default_rng(23)
    curves, radius = results(*CASES[kind])
    curve = curves[0]
    probes = probe_points(curve, radius, rng, n=20)[0]
    assert_decides_as_the_oracle(within(curve, probes, radius), oracle_distance(curve, probes)[0], radius)
