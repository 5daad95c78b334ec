"""A compiled Dormand–Prince 5(4) segment of a continuation curve, ending at the events of trace_cycle.

Integrates dy/ds = rhs(s, y, *args, sign, pullback) for any jitted continuation right-hand side
(spatialkin.kernels.implicit) with scipy RK45's steps, error control and dense output (the tableau and the
dense-output and root-bracketing helpers of spatialkin.kernels.dopri), and stops at the first of the
events spatialkin.tracing.continuation.trace_cycle gives solve_ivp, located on the dense output as
solve_ivp locates them:

* LEVEL_TARGET, LEVEL_START: the input y[index] crosses levels[0] or levels[1] upwards;
* RATE: the input's rate along the curve, rhs(s, y, *args, sign, 0)[index] (no pull-back), crosses zero
  in the given direction (a lock position).

follow_segment takes the right-hand side as an argument and is inlined into its caller, so that a system's
kernel module binds its own rhs in a small jitted wrapper that numba can cache (a kernel that receives a
jitted function as a value cannot be cached).

References
----------
scipy.integrate._ivp.rk.RK45, common.select_initial_step and ivp.solve_ivp's event handling (the step
control, initial step and event location reproduced here).
"""
import numpy as np

from .._jit import jit
from .dopri import (A, B, C, E, ERROR_EXPONENT, INITIAL_CAPACITY, MAX_FACTOR, MIN_FACTOR, P,
                    SAFETY, _rms, combine, locate_crossing)

# --- outcome of follow_segment ------------------------------------------------------------------------------
#: Reached t_bound without an event.
REACHED_END = 0
#: The step size fell below the round-off floor.
STEP_FAILED = -1
#: Which event ended the segment (its state is the last stored point).
LEVEL_TARGET = 1
LEVEL_START = 2
RATE = 3


@jit(inline="always")
def _event_at(t, y, rhs, vargs):
    """_event_value with its arguments but rhs as one tuple (for locate_crossing)."""
    args, sign, index, levels, which = vargs
    return _event_value(t, y, rhs, args, sign, index, levels, which)


@jit(inline="always")
def _event_value(t, y, rhs, args, sign, index, levels, which):
    """Value at (t, y) of event LEVEL_TARGET, LEVEL_START or RATE."""
    if which == RATE:
        return rhs(t, y, *args, sign, 0.0)[index]
    return y[index] - levels[which - LEVEL_TARGET]


@jit(inline="always")
def follow_segment(rhs, args, y0, t0, t_bound, sign, pullback, rtol, atol, index, levels, watch, directions):
    """Integrate from s = t0 (state y0) towards t_bound, stopping at the first event.

    Parameters
    ----------
    rhs : jitted callable
        ``rhs(s, y, *args, sign, pullback)`` (n + 1,).
    args : tuple
        The system's parameters.
    y0 : ndarray (n + 1,)
    t0, t_bound : float
        Start and end of the arc-length interval.
    sign, pullback : float
        As in spatialkin.kernels.implicit.follow_rhs.
    rtol, atol : float
        Tolerances (atol the same for every component).
    index : int
        Position of the input in y.
    levels : ndarray (2,)
        Levels of LEVEL_TARGET and LEVEL_START.
    watch : ndarray (3,) of bool
        Which of LEVEL_TARGET, LEVEL_START, RATE are watched.
    directions : ndarray (3,)
        Their crossing directions (+1 upwards, -1 downwards, as solve_ivp's event.direction).

    Returns
    -------
    outcome : int
        REACHED_END, STEP_FAILED, or the event that ended the segment.
    ts : ndarray (m,)
    ys : ndarray (m, n + 1)
        The stored points (the last one the event's, located on the dense output).
    hs : ndarray (m - 1,)
        Length of each step's polynomial (the last one may reach past ts[-1]).
    qs : ndarray (m - 1, n + 1, 4)
        Dense-output coefficients of each step (spatialkin.kernels.dopri.dense_state).
    """
    n = y0.shape[0]
    cap = INITIAL_CAPACITY
    ts, ys, hs, qs = np.empty(cap), np.empty((cap, n)), np.empty(cap), np.empty((cap, n, 4))
    ts[0] = t0
    ys[0] = y0
    count = 1
    y = y0.copy()
    f = rhs(t0, y, *args, sign, pullback)
    # initial step: scipy's select_initial_step for an error estimator of order 4
    scale = atol + np.abs(y) * rtol
    d0, d1 = _rms(y, scale), _rms(f, scale)
    h0 = min(1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1, t_bound - t0)
    d2 = _rms(rhs(t0 + h0, y + h0 * f, *args, sign, pullback) - f, scale) / h0
    h1 = max(1e-6, h0 * 1e-3) if max(d1, d2) <= 1e-15 else (0.01 / max(d1, d2)) ** (1.0 / 5.0)
    h = min(100.0 * h0, h1, t_bound - t0)
    g_old = np.empty(3)
    g_new = np.empty(3)
    for e in range(3):
        if watch[e]:
            g_old[e] = _event_value(t0, y, rhs, args, sign, index, levels, LEVEL_TARGET + e)
    k = np.empty((7, n))
    stage, y_new, err, q, y_event = np.empty(n), np.empty(n), np.empty(n), np.empty((n, 4)), np.empty(n)
    t = t0
    while t < t_bound:
        min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
        h = max(h, min_step)
        rejected = False
        while True:
            if h < min_step:
                return STEP_FAILED, ts[:count].copy(), ys[:count].copy(), hs[:count - 1].copy(), qs[:count - 1].copy()
            t_new = min(t + h, t_bound)
            step = t_new - t
            k[0] = f
            for s in range(1, 6):                               # the Dormand-Prince stages
                combine(stage, y, step, A[s], k, s)
                k[s] = rhs(t + C[s] * step, stage, *args, sign, pullback)
            combine(y_new, y, step, B, k, 6)
            k[6] = rhs(t_new, y_new, *args, sign, pullback)
            combine(err, None, step, E, k, 7)
            error = _rms(err, atol + np.maximum(np.abs(y), np.abs(y_new)) * rtol)
            if error < 1.0:
                factor = MAX_FACTOR if error == 0.0 else min(MAX_FACTOR, SAFETY * error ** ERROR_EXPONENT)
                h = step * (min(1.0, factor) if rejected else factor)
                break
            h = step * max(MIN_FACTOR, SAFETY * error ** ERROR_EXPONENT)
            rejected = True
        for m in range(4):                                       # this step's dense output
            combine(q[:, m], None, 1.0, P[:, m], k, 7)
        if count == cap:
            cap *= 2
            ts, ys = np.concatenate((ts, np.empty(cap - count))), np.concatenate((ys, np.empty((cap - count, n))))
            hs = np.concatenate((hs, np.empty(cap - count)))
            qs = np.concatenate((qs, np.empty((cap - count, n, 4))))
        qs[count - 1] = q
        hs[count - 1] = step
        # events at the step's end: the earliest crossing in its direction ends the segment
        first, t_first = 0, np.inf
        for e in range(3):
            if not watch[e]:
                continue
            g_new[e] = _event_value(t_new, y_new, rhs, args, sign, index, levels, LEVEL_TARGET + e)
            up = g_old[e] <= 0.0 <= g_new[e]
            down = g_old[e] >= 0.0 >= g_new[e]
            if (up and directions[e] >= 0) or (down and directions[e] <= 0):
                t_e = locate_crossing(_event_at, rhs, (args, sign, index, levels, LEVEL_TARGET + e), t, step, y,
                                      q, g_old[e], g_new[e], stage)
                if t_e < t_first:
                    first, t_first = LEVEL_TARGET + e, t_e
                    y_event[:] = stage
        if first:
            ts[count] = t_first
            ys[count] = y_event
            count += 1
            return first, ts[:count].copy(), ys[:count].copy(), hs[:count - 1].copy(), qs[:count - 1].copy()
        ts[count] = t_new
        ys[count] = y_new
        count += 1
        t = t_new
        y[:] = y_new
        f = k[6].copy()
        g_old[:] = g_new
    return REACHED_END, ts[:count].copy(), ys[:count].copy(), hs[:count - 1].copy(), qs[:count - 1].copy()
