"""The start of one segment of a branch in one compiled call: the charts, the state in them, and the projection.

A branch is integrated segment by segment (spatialkin.tracing.march.ivp); at each segment start the tracer
re-charts the surfaces that re-chart (a sphere: spatialkin.kernels.geometry.surfaces.recharted_sphere, at the
point, the equator along the direction of travel, then along the curve's curvature vector there when it is
known), reads the state in the new charts, and projects it back onto the curve in the plane normal to its
tangent (Newton, minimum-norm steps where that plane is ill-posed). ``segment_start`` does these steps in one
call; ``chart_states`` and ``project_state`` are its parts, which the tracer also calls alone
(spatialkin.tracing.march.segments).

References
----------
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002
(marching: a corrector in the plane normal to the tangent, as in pseudo-arclength continuation).
"""
import math

import numpy as np

from ..._lib.jit import jit
from .curve import curve_derivatives, curve_frame, project_to_curve
from ..geometry.interval import EPS
from ..geometry.surfaces import frame, inverse, recharted_sphere

#: settle's most steps, and the move (in ulps of the point's coordinates) below which it stops.
SETTLE_STEPS = 60
SETTLE_ULPS = 4.0


@jit
def foot_parameters(data, point, y, k):
    """y[2k:2k + 2] = the (u, v) of point's foot point on the surface data (spatialkin.kernels.geometry.surfaces.inverse)."""
    uv = np.empty((1, 2))
    inverse(data, point.reshape((1, 3)), uv)
    y[2 * k] = uv[0, 0]
    y[2 * k + 1] = uv[0, 1]


@jit
def chart_states(user, rechart, point, direction, bend, y_prev, k, out, y, keep=True):
    """Surface k's chart into out (user re-charted at point along direction, bend the curvature vector or zero,
    when rechart; else a copy of user) and its (u, v) into y[2k:2k + 2] (the foot point's in a new chart or
    without keep, else y_prev's)."""
    if rechart:
        recharted_sphere(user, point, direction, bend, out)
    else:
        for i in range(out.shape[0]):
            out[i] = user[i]
    if rechart or not keep:
        foot_parameters(out, point, y, k)
    else:
        y[2 * k] = y_prev[2 * k]
        y[2 * k + 1] = y_prev[2 * k + 1]


@jit
def segment_start(a_user, b_user, rechart_a, rechart_b, point, direction, y_prev, gap_tol, max_iter,
                  a_out, b_out, y, point_out, tangent_out):
    """A segment's charts (into a_out, b_out: re-charted where rechart_a, rechart_b, else copies of the user's data),
    its state y (4,) projected onto the curve, and the curve's point and unit tangent there (point_out,
    tangent_out). Returns True when the projection converged.

    point (3,) and direction (3,) are where the segment starts and the direction of travel; y_prev (4,) the state
    of the surfaces that keep their chart. A re-charting surface is re-charted along direction, then (when the
    curve's curvature vector is defined there) along the curvature vector in the first charts."""
    zero = np.zeros(3)
    chart_states(a_user, rechart_a, point, direction, zero, y_prev, 0, a_out, y)
    chart_states(b_user, rechart_b, point, direction, zero, y_prev, 1, b_out, y)
    if rechart_a or rechart_b:
        dy, ddy, d1, bend = np.empty(4), np.empty(4), np.empty(3), np.empty(3)
        if curve_derivatives(y, a_out, b_out, 1.0, dy, ddy, d1, bend):
            first = y.copy()
            chart_states(a_user, rechart_a, point, direction, bend, first, 0, a_out, y)
            chart_states(b_user, rechart_b, point, direction, bend, first, 1, b_out, y)
    return project_state(y, a_out, b_out, gap_tol, max_iter, point_out, tangent_out)


@jit
def project_state(y, a, b, gap_tol, max_iter, point_out, tangent_out):
    """The state y (4,) projected onto the curve in place, by Newton in the plane through its point normal to the
    curve's tangent there (minimum-norm steps where that plane condition is ill-posed: a tiny loop, near
    tangency), and the curve's point and unit tangent at the result (point_out, tangent_out). Returns True when
    the projection converged."""
    curve_frame(y, a, b, point_out, tangent_out)
    start = y.copy()
    iters = project_to_curve(y, a, b, point_out.copy(), tangent_out.copy(), gap_tol, max_iter)
    if iters < 0:
        for i in range(4):
            y[i] = start[i]
        iters = project_to_curve(y, a, b, point_out.copy(), np.zeros(3), gap_tol, max_iter)
    curve_frame(y, a, b, point_out, tangent_out)
    return iters >= 0


@jit
def locate(a_user, b_user, rechart_a, rechart_b, guess, y_guess, keep_guess, gap_tol, max_iter, point, y_user):
    """A point of the curve near guess (3,) by minimum-norm Gauss-Newton on M1 - M2 = 0, in charts made at guess
    (re-charted where rechart_a, rechart_b; the others' (u, v) from y_guess (4,) with keep_guess, else from the
    foot points), then settled onto the curve to round-off (settle): the point into point (3,), its state into
    y_user (4,) with a re-charted surface's (u, v) read in the user's chart. Returns False when Newton fails or the
    point is not finite (spatialkin.tracing.march.start.locate_on_curve)."""
    zero = np.zeros(3)
    a_out, b_out = np.empty(a_user.shape[0]), np.empty(b_user.shape[0])
    y = np.empty(4)
    chart_states(a_user, rechart_a, guess, zero, zero, y_guess, 0, a_out, y, keep_guess)
    chart_states(b_user, rechart_b, guess, zero, zero, y_guess, 1, b_out, y, keep_guess)
    iters = project_to_curve(y, a_out, b_out, guess.copy(), zero, gap_tol, max_iter)
    tangent = np.empty(3)
    curve_frame(y, a_out, b_out, point, tangent)
    if iters < 0 or not (np.isfinite(point[0]) and np.isfinite(point[1]) and np.isfinite(point[2])):
        return False
    settle(y, a_out, b_out)
    curve_frame(y, a_out, b_out, point, tangent)
    for i in range(4):
        y_user[i] = y[i]
    if rechart_a:
        foot_parameters(a_user, point, y_user, 0)
    if rechart_b:
        foot_parameters(b_user, point, y_user, 1)
    return True


@jit
def gap_at(y, a, b):
    """(|M1(u1, v1) - M2(u2, v2)|, M1 (3,)) at the state y (4,)."""
    p1 = frame(a, y[0], y[1])[0]
    p2 = frame(b, y[2], y[3])[0]
    return math.sqrt((p1[0] - p2[0]) ** 2 + (p1[1] - p2[1]) ** 2 + (p1[2] - p2[2]) ** 2), p1


@jit
def settle(y, a, b):
    """Minimum-norm Gauss-Newton steps from y (4,), within the gap tolerance of the curve, on to round-off: y becomes
    the iterate of least gap, the steps stopping where one moves the point by at most SETTLE_ULPS of its coordinates
    (or after SETTLE_STEPS). Where the surfaces nearly touch, a point within the gap tolerance of both lies up to
    gap / sine of the normals' angle off the curve (3e-4 where they are 3e-9 from tangency), and Newton creeps
    there, its gap wavering, which its test takes for stagnation: the points located from the starts of one
    component would scatter farther than its radius, each traced to a loop of its own."""
    zero = np.zeros(3)
    best = y.copy()
    best_gap, before = gap_at(y, a, b)
    trial = y.copy()
    for _ in range(SETTLE_STEPS):
        if not best_gap > 0.0:
            break
        project_to_curve(trial, a, b, zero, zero, 0.0, 1)           # (one step: it cannot meet a zero tolerance)
        gap, after = gap_at(trial, a, b)
        if gap < best_gap:
            best_gap = gap
            for i in range(4):
                best[i] = trial[i]
        moved = math.sqrt((after[0] - before[0]) ** 2 + (after[1] - before[1]) ** 2 + (after[2] - before[2]) ** 2)
        size = max(abs(after[0]), abs(after[1]), abs(after[2]))
        if not moved > SETTLE_ULPS * EPS * size:
            break
        before = after
    for i in range(4):
        y[i] = best[i]
