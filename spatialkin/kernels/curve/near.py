"""Distances of points from a traced curve in compiled code: which points lie within a radius of it.

The curve's dense output is read from flat tables (built by spatialkin.tracing.curve.packed from a TracedSolution):

* spans (S): row k of ``spans`` (S, 5) is (lo, flip, shift, sign, compiled): arc length s in [lo, next lo) maps
  to the solver time t = shift + flip s of span k's segment, whose charts are rows k of ``charts_a`` and
  ``charts_b`` and whose direction of travel is sign; compiled is 0 for a span these tables do not hold (a
  jump across a node or an apex, another solve_ivp method): a point whose Newton meets it is left to Python
  (verdict PYTHON); a re-measured segment (spatialkin.tracing.march.arclength.RemappedStates) first maps t to the
  solver's time by remapped_time through ``remap_new[remap_off[k]:remap_off[k + 1]]`` and ``remap_old[...]``
  (an empty range: no re-mapping);
* steps: span k's segment record (spatialkin.ode.record.Steps) has its step ends and states in rows
  ``t_off[k]:t_off[k + 1]`` of ``step_t`` and ``step_y`` and its step lengths and polynomials from row ``p_off[k]``
  of ``step_h`` and ``step_q`` (spatialkin.kernels.ode.rk.dense_into reads them, as the record does).

Every state is then corrected onto both surfaces by Newton (project_to_curve in the plane normal to the tangent):
``curve_states`` is the dense output of a traced curve (spatialkin.tracing.curve.dense.TracedSolution evaluates
through it), and the foot point is found by Newton in s (foot_distance; foot_many and closest_many are
TracedSolution's foot and closest points). near_mask, the test against a radius, stops at the first Newton iterate
within it (a point of the curve too). curve_point and its helpers are inlined into these loops at numba's level, and
the kernels' arrays are borrowed (spatialkin._lib.jit.borrowed): as separate calls, or with reference counts on their
arrays, the counting costs as much as the arithmetic.
"""
import math

import numpy as np

from ..._lib.jit import borrowed, jit, kept
from ..march.curve import curve_frame, project_to_curve
from ..ode.rk import dense_into

#: Halvings of a foot point's Newton step before it is given up (its distance not shrinking).
FOOT_HALVINGS = 60
#: Columns of the spans table.
LO, FLIP, SHIFT, SIGN, COMPILED = 0, 1, 2, 3, 4
#: near_mask's verdicts: farther than the reach from every stored point (far from the curve) ...
FAR = 0
#: ... within the radius of the foot point found from the nearest stored point (near) ...
NEAR = 1
#: ... or neither: only the closest point on the whole curve decides ...
UNDECIDED = 2
#: ... or its Newton met a span the tables do not hold: the Python foot point decides.
PYTHON = 3


@jit(inline="always")
def solver_state(table, k, t, out):
    """The solver's state at its time t on span k into out (4,), as the segment's record gives it
    (spatialkin.ode.record.Steps: rk.dense_into on its steps)."""
    t_off, p_off, step_t, step_y, step_h, step_q = table[3], table[4], table[5], table[6], table[7], table[8]
    lo, hi, p = t_off[k], t_off[k + 1], p_off[k]
    dense_into(step_t[lo:hi], step_y[lo:hi], step_h[p:], step_q[p:], t, out)


@jit(inline="always")
def remapped_time(x, xp, fp):
    """The solver time of arc length x on a re-measured segment (knots xp ascending, solver times fp): np.interp(x,
    xp, fp) between the knots, operation for operation as numpy computes it (arr_interp in
    numpy/_core/src/multiarray/compiled_base.c: the knots and the NaN guard included); beyond either end, along the
    end step's line (a loop's closure found past the last step extends that step)."""
    n = xp.shape[0]
    if n == 1:
        return fp[0]
    if math.isnan(x):
        return x
    if x < xp[0]:
        return fp[0] + (x - xp[0]) * ((fp[1] - fp[0]) / (xp[1] - xp[0]))
    if x > xp[n - 1]:
        return fp[n - 1] + (x - xp[n - 1]) * ((fp[n - 1] - fp[n - 2]) / (xp[n - 1] - xp[n - 2]))
    j = np.searchsorted(xp, x, side="right") - 1          # xp[j] <= x < xp[j + 1], or j = n - 1 at the end
    if j == n - 1 or xp[j] == x:
        return fp[j]
    slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j])
    value = slope * (x - xp[j]) + fp[j]
    if math.isnan(value):
        value = slope * (x - xp[j + 1]) + fp[j + 1]
        if math.isnan(value) and fp[j] == fp[j + 1]:
            value = fp[j]
    return value


@jit
def remapped_times(x, xp, fp, out):
    """remapped_time of every x (M,) into out (M,)."""
    for i in range(x.shape[0]):
        out[i] = remapped_time(x[i], xp, fp)


@jit(inline="always")
def span_at(spans, s):
    """The span k holding arc length s (already wrapped): searchsorted(lo, s, 'right') - 1, clipped to the spans
    (lo ascending)."""
    k = 0
    for j in range(1, spans.shape[0]):
        if spans[j, LO] <= s:
            k = j
    return k


@jit(inline="always")
def curve_point(table, closed, length, gap_tol, max_iter, s, y, q, point, tangent):
    """Point (3,) and unit tangent (3,) (towards increasing s) of the curve at arc length s, the state corrected
    onto both surfaces into y (4,) (q (3,): work space); returns s wrapped into [0, length) for a closed curve, or
    NaN (nothing written) on a span the tables do not hold."""
    spans, charts_a, charts_b = table[0], table[1], table[2]
    if closed and length > 0.0:
        s = s % length
    k = span_at(spans, s)
    if spans[k, COMPILED] == 0.0:
        return np.nan
    flip = spans[k, FLIP]
    t = spans[k, SHIFT] + flip * s
    remap_off, remap_new, remap_old = table[9], table[10], table[11]
    if remap_off[k + 1] > remap_off[k]:
        t = remapped_time(t, remap_new[remap_off[k]:remap_off[k + 1]], remap_old[remap_off[k]:remap_off[k + 1]])
    solver_state(table, k, t, y)
    a, b = charts_a[k], charts_b[k]
    curve_frame(y, a, b, q, tangent)
    project_to_curve(y, a, b, q, tangent, gap_tol, max_iter)
    curve_frame(y, a, b, point, tangent)
    for i in range(3):
        tangent[i] = tangent[i] * flip * spans[k, SIGN]
    return s


@jit
def curve_states(table, closed, length, gap_tol, max_iter, s, ys, points, tangents, index):
    """The curve at arc lengths s (M,) (wrapped already): corrected states ys (M, 4), points (M, 3) and unit tangents
    (M, 3) (curve_point for each), and the span of each into index (M,), -1 where the tables do not hold it (its
    rows then unwritten)."""
    table, s, ys, points, tangents, index = borrowed((table, s, ys, points, tangents, index))
    work = np.empty(3)
    q = borrowed(work)
    spans = table[0]
    for m in range(s.shape[0]):
        k = span_at(spans, s[m])
        if spans[k, COMPILED] == 0.0:
            index[m] = -1
            continue
        curve_point(table, closed, length, gap_tol, max_iter, s[m], ys[m], q, points[m], tangents[m])
        index[m] = k
    kept(work)


@jit
def foot_distance(table, closed, length, gap_tol, max_iter, p, s, steps, enough):
    """(s, distance) of the foot point of p (3,) on the curve by `steps` Newton steps in s from s, as
    CurveSolution.foot_points (its dot product summed as numpy's einsum sums three terms: (0 + 2) + 1); or, at
    the first curve point met within `enough` of p, that point's (a negative `enough`: never); (NaN, NaN) when
    Newton meets a span the tables do not hold."""
    table, p = borrowed((table, p))
    work = (np.empty(4), np.empty(3), np.empty(3), np.empty(3))
    y, q, at, tangent = borrowed(work)
    s, dist = _foot(table, closed, length, gap_tol, max_iter, p, s, steps, enough, y, q, at, tangent)
    kept(work)
    return s, dist


@jit(inline="always")
def _foot(table, closed, length, gap_tol, max_iter, p, s, steps, enough, y, q, at, tangent):
    """foot_distance with its work arrays y (4,), q, at, tangent (3,): Newton on g(s) = (p - C(s)) . C'(s), whose
    slope -(1 - (p - C) . C'') is read by the secant through the last two iterates (Gauss-Newton's -1 at the
    first), each step halved (up to FOOT_HALVINGS times) until the distance does not grow: beyond the curve's
    radius of curvature Gauss-Newton overshoots, by the distance over that radius."""
    s_at = curve_point(table, closed, length, gap_tol, max_iter, s, y, q, at, tangent)
    if math.isnan(s_at):
        return np.nan, np.nan
    d0, d1, d2 = p[0] - at[0], p[1] - at[1], p[2] - at[2]
    dist = math.sqrt((d0 * d0 + d1 * d1) + d2 * d2)
    g = (d0 * tangent[0] + d2 * tangent[2]) + d1 * tangent[1]
    s_prev, g_prev = np.nan, np.nan
    for _ in range(steps):
        if dist <= enough:
            return s_at, dist
        slope = (g - g_prev) / (s - s_prev) if s != s_prev else np.nan
        if not slope < 0.0:
            slope = -1.0
        step = -g / slope
        for _ in range(FOOT_HALVINGS + 1):
            trial = s + step
            if not closed:
                trial = min(max(trial, 0.0), length)
            t_at = curve_point(table, closed, length, gap_tol, max_iter, trial, y, q, at, tangent)
            if math.isnan(t_at):
                return np.nan, np.nan
            d0, d1, d2 = p[0] - at[0], p[1] - at[1], p[2] - at[2]
            t_dist = math.sqrt((d0 * d0 + d1 * d1) + d2 * d2)
            if t_dist <= dist:
                break
            step *= 0.5
        if not t_dist <= dist:
            break                                   # no step brings it nearer: s is the foot, to round-off
        s_prev, g_prev = s, g
        s, s_at, dist = trial, t_at, t_dist
        g = (d0 * tangent[0] + d2 * tangent[2]) + d1 * tangent[1]
    return s_at, dist


@jit
def reach_of(s_stored, radius):
    """Radius plus half the longest step between stored points at arc lengths s_stored (N,): a point farther than
    this from every stored point is farther than radius from the curve (each arc between two stored points lies
    within half its length of one of them)."""
    longest = 0.0
    for j in range(s_stored.shape[0] - 1):
        longest = max(longest, s_stored[j + 1] - s_stored[j])
    return radius + 0.5 * longest


@jit
def nearest_stored(p, stored):
    """(distance, index) of the stored point (N, 3) nearest to p (3,) (the first of equals)."""
    best, nearest = np.inf, -1
    for j in range(stored.shape[0]):
        d0, d1, d2 = p[0] - stored[j, 0], p[1] - stored[j, 1], p[2] - stored[j, 2]
        d = (d0 * d0 + d1 * d1) + d2 * d2
        if d < best:
            best, nearest = d, j
    return math.sqrt(best), nearest


@jit
def within_reach(points, stored, s_stored, radius):
    """Whether every point (M, 3) lies within reach_of(s_stored, radius) of one of the stored points (N, 3): False
    proves some point farther than radius from the curve."""
    reach = reach_of(s_stored, radius)
    for m in range(points.shape[0]):
        if not nearest_stored(points[m], stored)[0] < reach:
            return False
    return True


@jit
def near_mask(points, stored, s_stored, radius, table, closed, length, gap_tol, max_iter, steps, verdict):
    """Verdict (M,) (FAR, NEAR, UNDECIDED or PYTHON) of each point (M, 3) against the curve through its stored points
    (N, 3) at arc lengths s_stored (N,): FAR when farther than radius plus half the longest step from every
    stored point (each arc between two stored points lies within half its length of one of them); NEAR when
    within radius of a curve point met by foot_distance from the nearest stored point (the foot point, or one of
    the Newton iterates before it: each is a point of the curve); PYTHON when that Newton met a span the tables
    do not hold (or gave NaN); UNDECIDED otherwise. Returns the number of UNDECIDED and PYTHON points.
    """
    points, stored, s_stored, table, verdict = borrowed((points, stored, s_stored, table, verdict))
    reach = reach_of(s_stored, radius)
    undecided = 0
    for m in range(points.shape[0]):
        gap, nearest = nearest_stored(points[m], stored)
        # scipy's cKDTree query with distance_upper_bound=reach finds no neighbour at reach or beyond
        if not gap < reach:
            verdict[m] = FAR
            continue
        _, dist = foot_distance(table, closed, length, gap_tol, max_iter, points[m], s_stored[nearest], steps,
                                radius)
        if math.isnan(dist):
            verdict[m] = PYTHON
        else:
            verdict[m] = NEAR if dist <= radius else UNDECIDED
        undecided += verdict[m] != NEAR
    return undecided


@jit
def foot_many(table, closed, length, gap_tol, max_iter, points, s, steps, s_out, d_out):
    """foot_distance (every step taken) of each point (M, 3) from its start s (M,): arc lengths s_out (M,) and
    distances d_out (M,), NaN where Newton met a span the tables do not hold."""
    table, points, s, s_out, d_out = borrowed((table, points, s, s_out, d_out))
    for m in range(points.shape[0]):
        s_out[m], d_out[m] = foot_distance(table, closed, length, gap_tol, max_iter, points[m], s[m], steps, -1.0)


@jit
def closest_many(points, grid_s, grid, table, closed, length, gap_tol, max_iter, steps, candidates, s_out, d_out):
    """The closest curve point to each point (M, 3): foot points (foot_distance, every step taken) from the
    `candidates` grid points (arc lengths grid_s (G,), points grid (G, 3)) nearest to it, the nearest of them (the
    first of equals): its arc length s_out (M,) and distance d_out (M,), NaN where a Newton met a span the tables
    do not hold."""
    points, grid_s, grid, table, s_out, d_out = borrowed((points, grid_s, grid, table, s_out, d_out))
    k = min(candidates, grid.shape[0])
    best_d, best_i = np.empty(k), np.empty(k, dtype=np.int64)
    for m in range(points.shape[0]):
        for c in range(k):
            best_d[c], best_i[c] = np.inf, -1
        for j in range(grid.shape[0]):          # the k nearest grid points, kept in order of distance
            d0, d1, d2 = points[m, 0] - grid[j, 0], points[m, 1] - grid[j, 1], points[m, 2] - grid[j, 2]
            d = (d0 * d0 + d1 * d1) + d2 * d2
            if d < best_d[k - 1]:
                c = k - 1
                while c > 0 and best_d[c - 1] > d:
                    best_d[c], best_i[c] = best_d[c - 1], best_i[c - 1]
                    c -= 1
                best_d[c], best_i[c] = d, j
        s_out[m], d_out[m] = np.inf, np.inf
        for c in range(k):
            s_c, d_c = foot_distance(table, closed, length, gap_tol, max_iter, points[m], grid_s[best_i[c]], steps,
                                     -1.0)
            if math.isnan(d_c):
                s_out[m], d_out[m] = np.nan, np.nan
                break
            if d_c < d_out[m]:
                s_out[m], d_out[m] = s_c, d_c
