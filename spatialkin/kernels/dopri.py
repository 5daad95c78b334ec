"""A compiled Dormand–Prince 5(4) integrator of the Dragilev right-hand side, with the common case's events.

The same tableau, error norm, step-size control, initial step and dense output as scipy's RK45
(scipy.integrate._ivp.rk), so that a segment integrated here takes the steps solve_ivp(method='RK45')
would, without the per-step Python work. Only what the common case needs is decided in the kernel:

* the closure plane crossing near the start (located on the dense output, as solve_ivp locates events);
* a sphere's chart nearing its poles (the segment ends at that step; the caller re-charts);
* the end of the arc-length interval.

Any other condition (normals near parallel, a parametrisation near its apex, a parameter bound) ends the
segment at the last step before it with status HANDOFF, and the caller integrates on with solve_ivp and its
event functions, so hard cases keep their existing handling.

References
----------
Dormand, J. R., Prince, P. J., "A family of embedded Runge-Kutta formulae", J. Comput. Appl. Math. 6 (1980);
scipy.integrate._ivp.rk.RK45 and common.select_initial_step (the coefficients and the control copied here).
"""
import numpy as np

from .._jit import jit
from .curve import area_degeneracy, closure_value, degeneracy, dragilev_into, dragilev_rhs

# --- status codes returned by dopri_segment ---------------------------------------------------------------
#: Reached the end of the interval (max_length).
DONE = 0
#: The step size fell below the round-off floor, or the evaluation budget ran out.
FAILED = -1
BUDGET = -2
#: The closure function crossed zero upwards: the last stored point is the crossing.
CLOSURE = 1
#: A sphere's chart (surface 0 or 1) passed its pole guard at the last stored point.
CHART_A = 2
CHART_B = 3
#: A hard case is near: the last stored point is the last step before it; go on with solve_ivp.
HANDOFF = 4

# --- RK45 (Dormand–Prince) coefficients, as in scipy.integrate._ivp.rk.RK45 ---------------------------------
C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0])
A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [1 / 5, 0.0, 0.0, 0.0, 0.0],
    [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
    [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]])
B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
P = np.array([
    [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
    [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423]])
#: Step-size control (scipy's values).
SAFETY = 0.9
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
ERROR_EXPONENT = -1.0 / 5.0
#: Stored steps allocated at first; the arrays double when full.
INITIAL_CAPACITY = 64
#: Iterations of the Illinois root search locating the closure crossing on the dense output.
ROOT_MAX_ITER = 100
#: Relative width (times 4 ulps, as scipy's brentq call) at which the root search stops.
ROOT_ULPS = 4.0


@jit
def _rms(x, scale):
    acc = 0.0
    for i in range(x.shape[0]):
        q = x[i] / scale[i]
        acc += q * q
    return np.sqrt(acc / x.shape[0])


@jit
def _initial_step(y0, f0, a, b, sign, pullback, t_bound, max_step, rtol, atol):
    """scipy's select_initial_step for an error estimator of order 4."""
    n = y0.shape[0]
    scale = np.empty(n)
    for i in range(n):
        scale[i] = atol[i] + abs(y0[i]) * rtol
    d0 = _rms(y0, scale)
    d1 = _rms(f0, scale)
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    h0 = min(h0, t_bound)
    y1 = np.empty(n)
    for i in range(n):
        y1[i] = y0[i] + h0 * f0[i]
    f1 = dragilev_rhs(0.0, y1, a, b, sign, pullback)
    for i in range(n):
        f1[i] -= f0[i]
    d2 = _rms(f1, scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 5.0)
    return min(100.0 * h0, h1, t_bound, max_step)


@jit
def regula_falsi_point(lo, hi, g_lo, g_hi):
    """The secant root of g on [lo, hi] (the midpoint where the secant leaves the bracket or is flat)."""
    tm = (lo * g_hi - hi * g_lo) / (g_hi - g_lo) if g_hi != g_lo else 0.5 * (lo + hi)
    return tm if lo < tm < hi else 0.5 * (lo + hi)


@jit
def illinois_update(lo, hi, g_lo, g_hi, side, tm, gm, to_lo):
    """One Illinois update of the bracket: tm (value gm) replaces lo when to_lo, else hi; when the same end
    moves twice running, the other end's value is halved. Returns (lo, hi, g_lo, g_hi, side)."""
    if to_lo:
        if side == -1:
            g_hi *= 0.5
        return tm, hi, gm, g_hi, -1
    if side == 1:
        g_lo *= 0.5
    return lo, tm, g_lo, gm, 1


@jit
def dense_state(t_old, h, y_old, q, t, out):
    """RK45 dense output on one step: out = y_old + h Q p(x), x = (t - t_old)/h, p = (x, x^2, x^3, x^4)."""
    x = (t - t_old) / h
    p0 = x
    p1 = x * x
    p2 = p1 * x
    p3 = p2 * x
    for i in range(out.shape[0]):
        out[i] = y_old[i] + h * (q[i, 0] * p0 + q[i, 1] * p1 + q[i, 2] * p2 + q[i, 3] * p3)


@jit
def combine(out, y, h, weights, k, stages):
    """out = y + h * sum_j weights[j] k[j] over the first `stages` rows of k (y None: from zero)."""
    for i in range(out.shape[0]):
        acc = 0.0
        for j in range(stages):
            acc += weights[j] * k[j, i]
        out[i] = h * acc if y is None else y[i] + h * acc


@jit
def copy_into(out, x):
    """out[i] = x[i] for 1-D arrays (an element loop: numba's array-to-array slice assignment compiles its
    shape-mismatch message, string formatting and all, into every kernel that uses it)."""
    for i in range(out.shape[0]):
        out[i] = x[i]


@jit(inline="always")
def locate_crossing(value, fn, vargs, t_old, step, y_old, q, g_lo, g_hi, out):
    """The time where value(t, y(t), fn, vargs) crosses zero inside the step [t_old, t_old + step] (values g_lo,
    g_hi at its ends, of opposite signs), by the Illinois method on the step's dense output (dense_state);
    the state there is written to out. Inlined, so that a caller binds its own event function (value, and
    the jitted fn it may call, passed apart from the tuple vargs) and stays cacheable."""
    lo, hi = t_old, t_old + step
    side = 0
    for _ in range(ROOT_MAX_ITER):
        if hi - lo <= ROOT_ULPS * 2.220446049250313e-16 * max(abs(hi), 1e-300):
            break
        tm = regula_falsi_point(lo, hi, g_lo, g_hi)
        dense_state(t_old, step, y_old, q, tm, out)
        gm = value(tm, out, fn, vargs)
        if gm == 0.0:
            lo = hi = tm
            break
        lo, hi, g_lo, g_hi, side = illinois_update(lo, hi, g_lo, g_hi, side, tm, gm,
                                                   (gm < 0.0) == (g_lo < 0.0) and g_lo != 0.0)
    dense_state(t_old, step, y_old, q, hi, out)
    return hi


@jit
def dense_many(ts, ys, hs, qs, t, out):
    """Dense states out (M, 4) at times t (M,) from stored steps ts (n,), ys (n, 4), their lengths hs (n - 1,)
    (the last may reach past ts[-1], a located event) and qs (n - 1, 4, 4); outside [ts[0], ts[-1]] the first
    or last step's polynomial is extended (as scipy's OdeSolution)."""
    n = ts.shape[0]
    for k in range(t.shape[0]):
        if n < 2:
            copy_into(out[k], ys[0])
            continue
        j = np.searchsorted(ts, t[k], side="right") - 1
        j = min(max(j, 0), n - 2)
        dense_state(ts[j], hs[j], ys[j], qs[j], t[k], out[k])


@jit(inline="always")
def _closure_at(t, y, fn, vargs):
    s_arm, a, start, direction, offset = vargs
    return fn(t, y, s_arm, a, start, direction, offset)


@jit
def _closure_g(t, y, s_arm, a, start, direction, offset):
    if t <= s_arm:
        return 1.0
    return closure_value(y, a, start, direction, offset)


@jit
def dopri_segment(y0, a, b, sign, pullback, t_bound, rtol, atol, max_step, max_nfev,
                  close, start, direction, offset, s_arm, watch_below, area_a, area_b, apex_watch,
                  bounds_lo, bounds_hi, pole_a, pole_b, pole_guard):
    """Integrate dy/ds = dragilev_rhs from s = 0 (state y0) towards t_bound, stopping at the first event.

    Parameters
    ----------
    y0 : ndarray (4,)
    a, b : ndarray
        Packed surfaces (charts of this segment).
    sign, pullback : float
        As in dragilev_rhs.
    t_bound, rtol, max_step : float
    atol : ndarray (4,)
    max_nfev : int
        Evaluation budget (status BUDGET past it).
    close : bool
        Watch the closure plane: crossing upwards of closure_value(y, a, start, direction, offset) at s > s_arm.
    watch_below : float
        HANDOFF where sin(angle between the normals) falls below this.
    area_a, area_b : int
        Flags: watch the relative area element of a, b; HANDOFF where it falls below apex_watch.
    bounds_lo, bounds_hi : ndarray (4,)
        Parameter bounds (+-inf where none); HANDOFF before a step that leaves them.
    pole_a, pole_b : bool
        Whether a, b is a sphere; the segment ends (CHART_A / CHART_B) at the first step where
        |cos v| < pole_guard.

    Returns
    -------
    status : int
    ts : ndarray (n,)
    ys : ndarray (n, 4)
    hs : ndarray (n - 1,)
        Length of each step's polynomial (the last one may reach past ts[-1], a located event).
    qs : ndarray (n - 1, 4, 4)
        Dense-output coefficients of each step.
    nfev : int
    """
    n = y0.shape[0]
    cap = INITIAL_CAPACITY
    ts = np.empty(cap)
    ys = np.empty((cap, n))
    qs = np.empty((cap, n, 4))
    hs = np.empty(cap)
    ts[0] = 0.0
    copy_into(ys[0], y0)
    count = 1
    y = y0.copy()
    f = dragilev_rhs(0.0, y, a, b, sign, pullback)
    nfev = 1
    t = 0.0
    h = _initial_step(y, f, a, b, sign, pullback, t_bound, max_step, rtol, atol)
    nfev += 1
    k = np.empty((7, n))
    y_new = np.empty(n)
    y_stage = np.empty(n)
    err = np.empty(n)
    scale = np.empty(n)
    q = np.empty((n, 4))
    g_old = _closure_g(0.0, y, s_arm, a, start, direction, offset) if close else 1.0
    status = DONE
    while t < t_bound:
        if nfev > max_nfev:
            status = BUDGET
            break
        min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
        h = min(h, max_step)
        if h < min_step:
            h = min_step
        rejected = False
        accepted = False
        while not accepted:
            if h < min_step:
                status = FAILED
                break
            t_new = t + h
            if t_new - t_bound > 0:
                t_new = t_bound
            step = t_new - t
            # stages
            copy_into(k[0], f)
            for s in range(1, 6):
                combine(y_stage, y, step, A[s], k, s)
                dragilev_into(y_stage, a, b, sign, pullback, k[s])
            combine(y_new, y, step, B, k, 6)
            dragilev_into(y_new, a, b, sign, pullback, k[6])
            f_new = k[6]
            nfev += 6
            combine(err, None, step, E, k, 7)
            for i in range(n):
                scale[i] = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
            error_norm = _rms(err, scale)
            if error_norm < 1.0:
                if error_norm == 0.0:
                    factor = MAX_FACTOR
                else:
                    factor = min(MAX_FACTOR, SAFETY * error_norm ** ERROR_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                h = step * factor
                accepted = True
            else:
                h = step * max(MIN_FACTOR, SAFETY * error_norm ** ERROR_EXPONENT)
                rejected = True
                if nfev > max_nfev:
                    break
        if not accepted:
            if status == DONE:
                status = BUDGET
            break
        # --- hard cases ahead: stop at the last step (this one is dropped) ---
        leave = degeneracy(y_new, a, b, 0, 0) < watch_below
        if not leave and (area_a or area_b):
            leave = area_degeneracy(y_new, a, b, area_a, area_b) < apex_watch
        if not leave:
            for i in range(n):
                if y_new[i] < bounds_lo[i] or y_new[i] > bounds_hi[i]:
                    leave = True
        if leave:
            status = HANDOFF
            break
        # --- store the step ---
        for m in range(4):                       # this step's dense output
            combine(q[:, m], None, 1.0, P[:, m], k, 7)
        if count == cap:
            cap *= 2
            ts2 = np.empty(cap)
            ys2 = np.empty((cap, n))
            qs2 = np.empty((cap, n, 4))
            hs2 = np.empty(cap)
            for j in range(count):
                ts2[j] = ts[j]
                copy_into(ys2[j], ys[j])
                if j < count - 1:
                    hs2[j] = hs[j]
                    for i in range(n):
                        copy_into(qs2[j, i], qs[j, i])
            ts, ys, qs, hs = ts2, ys2, qs2, hs2
        for i in range(n):
            copy_into(qs[count - 1, i], q[i])
        hs[count - 1] = step
        # --- closure crossing (upwards) within this step ---
        if close:
            g_new = _closure_g(t_new, y_new, s_arm, a, start, direction, offset)
            if g_old <= 0.0 and g_new >= 0.0:
                y_mid = np.empty(n)
                t_e = locate_crossing(_closure_at, _closure_g, (s_arm, a, start, direction, offset), t, step, y, q,
                                      g_old, g_new, y_mid)
                ts[count] = t_e
                copy_into(ys[count], y_mid)
                count += 1
                status = CLOSURE
                break
            g_old = g_new
        ts[count] = t_new
        copy_into(ys[count], y_new)
        count += 1
        t = t_new
        copy_into(y, y_new)
        copy_into(f, f_new)
        if pole_a and abs(np.cos(y[1])) < pole_guard:
            status = CHART_A
            break
        if pole_b and abs(np.cos(y[3])) < pole_guard:
            status = CHART_B
            break
    m = max(count - 1, 0)
    return status, ts[:count].copy(), ys[:count].copy(), hs[:m].copy(), qs[:m].copy(), nfev
