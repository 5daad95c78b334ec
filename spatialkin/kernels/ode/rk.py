"""The one compiled Runge–Kutta engine: Dormand–Prince 5(4) or 8(5,3) with scipy's steps, stopping at events.

Every curve of the library (intersection branches, continuation of mechanisms) is integrated by
``solve_ivp(..., method=spatialkin.ode.solvers.CompiledRK45)`` (or ``CompiledDOP853``); that OdeSolver calls
``advance`` here, which takes many steps of its method (RK45 or DOP853) inside compiled code and returns after a
step over which one of the system's events crosses zero in its direction (located on the step's dense output as
solve_ivp locates events for its own methods) or reaches a level. The tableaus, error norms, step-size control,
initial step and dense output are scipy's (scipy.integrate._ivp.rk.RK45 and DOP853, common.select_initial_step):
the steps are scipy's, to round-off. Every step's dense output is held as a polynomial in x = (t - t_old) / h,
``y_old + h (q[0] x + q[1] x^2 + ...)``: RK45's own (4 columns), DOP853's (7 columns) rewritten from scipy's
Horner form in x and 1 - x (the same polynomial, to round-off).

A system supplies two jitted functions, bound at compile time by a small jitted wrapper in its own kernel
module (numba caches a kernel only when the functions it calls are globals, not values):

* ``fun(t, y, args, out)``: writes dy/dt (n,) into out;
* ``events(t, y, args, eargs, active, out)``: writes the value of every active event into out (the same
  functions serve solve_ivp's own methods through spatialkin.ode.solvers.Event).

References
----------
Dormand, J. R., Prince, P. J., "A family of embedded Runge-Kutta formulae", J. Comput. Appl. Math. 6 (1980);
Hairer, E., Norsett, S. P., Wanner, G., "Solving Ordinary Differential Equations I", Sec. II.10 (DOP853);
scipy.integrate.RK45, DOP853 and select_initial_step (RK45's coefficients and the control copied here, DOP853's
tableau read from the public class scipy.integrate.DOP853: A, B, C, A_EXTRA, C_EXTRA, E3, E5, D).
"""
import numpy as np
from scipy.integrate import DOP853 as _DOP853      # its tableau, as class attributes

from ..._lib.jit import borrowed, jit, kept

# --- what advance returns ----------------------------------------------------------------------------------
#: Took max_steps steps, or reached t_bound, without an event: call again.
STEPPED = 0
#: An active event changed sign (in its direction) over the last step.
EVENT = 1
#: The step size fell below the round-off floor.
STEP_FAILED = -1
#: The evaluation budget ran out.
BUDGET = -2

# --- how an event ends a call of advance (its entry in `modes`) ----------------------------------------------
#: A zero crossing in the event's direction, located on the step's dense output, recorded; the integration goes on.
CROSSING = 0
#: The same, and the integration ends at the crossing (solve_ivp's terminal event).
TERMINAL = 1
#: A level: the integration ends at the last step before the one whose end reaches it (the value at or past
#: zero in the event's direction), that step dropped (a hard case ahead, handed to another method).
LEVEL_BEFORE = 2
#: A level: the integration ends at the end of the first step that reaches it (the step kept).
LEVEL_AFTER = 3
#: TERMINAL and LEVEL_BEFORE, the event also probed at PROBES[method] interior points of each step's dense output,
#: and between two of them where neither its rate nor its bend excludes a dip to zero (hidden_crossing): a crossing
#: out and back within one step (a curve grazing out of a trim edge for a fraction of a step) is found down to
#: DIP_FLOOR of the step (the bend bound is rigorous for events linear in the state: the trim edges). Only for events
#: 1-Lipschitz in the state's largest component (a parameter against a bound; a relative area element,
#: tests/spatialkin/tracing/march/test_hard_cases.py):
#: a step is probed only where such an event's value at an end is within the step's reach (step_reach: a bound on
#: how far any component of the dense output moves within the step).
TERMINAL_PROBED = 4
LEVEL_BEFORE_PROBED = 5
#: Interior points of a step at which probed events are evaluated (evenly spaced), per method: DOP853's steps are
#: about four times RK45's at the same rtol, so about four times as many probes keep their spacing.
PROBES = (8, 32)
#: Between two evaluated points where a probed event has one sign, it may still dip to zero and back (a curve grazing
#: 1e-7 out of a trim edge for 1e-3 of its length passes between probes 3e-3 apart). hidden_crossing bisects such an
#: interval until the event's rate (step_speed) or its bend (step_bend: for an event linear in the state, a trim
#: edge, a bound on its second derivative) proves it keeps its sign, or down to this fraction of the step (a touch
#: within round-off then counts as no crossing).
DIP_FLOOR = 2.0 ** -40
#: Intervals a hidden_crossing search holds at once (each bisection of the deepest adds one), and the most points it
#: evaluates: a curve running along an edge (the event within round-off of zero all along) cannot be told from a
#: dip anywhere, and is given up after that many (as a touch).
DIP_STACK = 48
DIP_EVALUATIONS = 96

# --- the methods (advance's `method`) -----------------------------------------------------------------------
#: Dormand–Prince 5(4), scipy's RK45.
RK45 = 0
#: Dormand–Prince 8(5,3), scipy's DOP853.
DOP853 = 1
#: Columns of a step's dense-output polynomial (q), per method.
DENSE_COLUMNS = (4, 7)
#: Order of each method's error estimator (scipy's error_estimator_order: select_initial_step takes it, and the step
#: control's exponent is -1 / (order + 1)).
ERROR_ORDERS = (4, 7)
#: Rows of the stage array k, per method (RK45's 7; DOP853's 16, its dense output's three stages included) ...
STAGE_ROWS = (7, 16)
#: ... and the row holding f at the step's end (the next step's first stage).
END_ROWS = (6, 12)

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

# --- DOP853 coefficients, scipy's (scipy.integrate.DOP853) -------------------------------------------------------
#: Stages of a step (the 13th, f at the step's end, is the next step's first), and the extended tableau's rows
#: (three more stages for the dense output).
DOP853_STAGES = END_ROWS[1]
DOP853_EXTENDED = STAGE_ROWS[1]
#: The extended tableau (16, 16): the 12 stages, f at the step's end (row 12: the weights B), and the dense output's
#: three stages (rows 13-15).
A8 = np.zeros((DOP853_EXTENDED, DOP853_EXTENDED))
A8[:DOP853_STAGES, :DOP853_STAGES] = _DOP853.A
A8[DOP853_STAGES, :DOP853_STAGES] = _DOP853.B
A8[DOP853_STAGES + 1:] = _DOP853.A_EXTRA
C8 = np.concatenate([_DOP853.C, [1.0], _DOP853.C_EXTRA]).astype(float)        # (16,)
B8 = np.ascontiguousarray(_DOP853.B, dtype=float)           # (12,)
E3 = np.ascontiguousarray(_DOP853.E3, dtype=float)          # (13,)
E5 = np.ascontiguousarray(_DOP853.E5, dtype=float)          # (13,)
D8 = np.ascontiguousarray(_DOP853.D, dtype=float)           # (4, 16)
#: scipy's Dop853DenseOutput is y_old + x (F0 + (1-x)(F1 + x (F2 + (1-x)(F3 + x (F4 + (1-x)(F5 + x F6)))))); row
#: m of this matrix gives the coefficient of x^(m+1) of that polynomial from F0..F6 (integers, exact).
DOP853_POWERS = np.array([
    [1, 1, 0, 0, 0, 0, 0],
    [0, -1, 1, 1, 0, 0, 0],
    [0, 0, -1, -2, 1, 1, 0],
    [0, 0, 0, 1, -2, -3, 1],
    [0, 0, 0, 0, 1, 3, -3],
    [0, 0, 0, 0, 0, -1, 3],
    [0, 0, 0, 0, 0, 0, -1]], dtype=float)


@jit
def rms(x, scale):
    """sqrt(mean((x / scale)^2)), scipy's norm of a scaled error."""
    acc = 0.0
    for i in range(x.shape[0]):
        q = x[i] / scale[i]
        acc += q * q
    return np.sqrt(acc / x.shape[0])


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


@jit
def dense_state(t_old, h, y_old, q, t, out):
    """A step's dense output: out = y_old + h Q p(x), x = (t - t_old)/h, p = (x, x^2, ..., x^c), Q (n, c)."""
    x = (t - t_old) / h
    for i in range(out.shape[0]):
        p = x
        acc = q[i, 0] * p
        for m in range(1, q.shape[1]):
            p *= x
            acc += q[i, m] * p
        out[i] = y_old[i] + h * acc


@jit
def dense_into(ts, ys, hs, qs, t, out):
    """The dense state at time t into out (n,), from stored steps ts (m,), ys (m, n), their lengths hs (m - 1,)
    and qs (m - 1, n, c); outside [ts[0], ts[-1]] the first or last step's polynomial is extended (as scipy's
    OdeSolution)."""
    m = ts.shape[0]
    if m < 2:
        copy_into(out, ys[0])
        return
    j = min(max(np.searchsorted(ts, t, side="right") - 1, 0), m - 2)
    dense_state(ts[j], hs[j], ys[j], qs[j], t, out)


@jit
def dense_at(ts, ys, hs, qs, t):
    """The dense state (n,) at one time t (dense_into, allocated)."""
    out = np.empty(ys.shape[1])
    dense_into(ts, ys, hs, qs, t, out)
    return out


@jit
def dense_many(ts, ys, hs, qs, t, out):
    """Dense states out (M, n) at times t (M,) (dense_into for each)."""
    for k in range(t.shape[0]):
        dense_into(ts, ys, hs, qs, t[k], out[k])


#: Iterations of the Illinois root search locating an event on a step's dense output.
ROOT_MAX_ITER = 100
#: Relative width (times 4 ulps, as solve_ivp's brentq call) at which the root search stops.
ROOT_ULPS = 4.0


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


@jit(inline="always")
def locate(events, args, eargs, only, values, index, t_old, step, y_old, q, lo, hi, g_lo, g_hi, out):
    """The time where event `index` crosses zero inside [lo, hi] within the step [t_old, t_old + step] (values
    g_lo, g_hi at lo and hi, of opposite signs), by the Illinois method on the step's dense output (to ROOT_ULPS
    ulp, as solve_ivp's brentq); the state there is written to out. only (n_events,) is a mask with only `index`
    set, values a work array."""
    side = 0
    for _ in range(ROOT_MAX_ITER):
        if hi - lo <= ROOT_ULPS * 2.220446049250313e-16 * max(abs(hi), 1e-300):
            break
        tm = regula_falsi_point(lo, hi, g_lo, g_hi)
        dense_state(t_old, step, y_old, q, tm, out)
        events(tm, out, args, eargs, only, values)
        gm = values[index]
        if gm == 0.0:
            lo = hi = tm
            break
        lo, hi, g_lo, g_hi, side = illinois_update(lo, hi, g_lo, g_hi, side, tm, gm,
                                                   (gm < 0.0) == (g_lo < 0.0) and g_lo != 0.0)
    dense_state(t_old, step, y_old, q, hi, out)
    return hi


@jit
def level_reached(g, active, directions, modes, mode, other=-1):
    """The first active event of the given level mode (or of mode `other`) whose value g has reached zero in its
    direction, or -1."""
    for i in range(g.shape[0]):
        if (active[i] and (modes[i] == mode or modes[i] == other)
                and (g[i] <= 0.0 if directions[i] <= 0.0 else g[i] >= 0.0)):
            return i
    return -1


@jit
def coefficient_bound(q, derivative):
    """max_i sum_m w_m |q[i, m]| over a step's dense-output coefficients, w_m = 1 (derivative False) or m + 1 (the
    weights of the polynomial's derivative in x)."""
    bound = 0.0
    for i in range(q.shape[0]):
        total = abs(q[i, 0])
        for m in range(1, q.shape[1]):
            total += (m + 1) * abs(q[i, m]) if derivative else abs(q[i, m])
        bound = max(bound, total)
    return bound


@jit
def step_reach(step, q):
    """Bound on |y_i(t) - y_i(t_old)| over the step, every component i: |step| x max_i sum_m |q[i, m]|."""
    return abs(step) * coefficient_bound(q, False)


@jit
def within_reach(g_lo, g_hi, reach):
    """True when a 1-Lipschitz event with values g_lo, g_hi at a step's ends may reach zero inside it."""
    return min(abs(g_lo), abs(g_hi)) <= reach


@jit
def crosses(g_lo, g_hi, direction):
    """True when an event's value goes from g_lo to g_hi through zero in its direction (solve_ivp's rule)."""
    up = g_lo <= 0.0 <= g_hi
    down = g_lo >= 0.0 >= g_hi
    return (up and direction >= 0.0) or (down and direction <= 0.0)


@jit
def is_terminal(mode):
    """True for the modes that end the integration at the crossing."""
    return mode == TERMINAL or mode == TERMINAL_PROBED


@jit
def is_level(mode):
    """True for the level modes (reached at a step's end, not located)."""
    return mode == LEVEL_BEFORE or mode == LEVEL_AFTER or mode == LEVEL_BEFORE_PROBED


@jit
def step_speed(q):
    """Bound on |dy_i/dt| over the step, every component i: the dense output's derivative is
    sum_m (m + 1) q[i, m] x^m with 0 <= x <= 1 (dense_state), so max_i sum_m (m + 1) |q[i, m]|, widened by 1e-12
    (relative) over its round-off."""
    return coefficient_bound(q, True) * (1.0 + 1e-12)


@jit
def step_bend(step, q):
    """Bound on |d^2 y_i/dt^2| over the step, every component i: the dense output's second derivative is
    sum_m (m + 1) m q[i, m] x^(m-1) / step, so max_i sum_m (m + 1) m |q[i, m]| / |step|, widened by 1e-12
    (relative) over its round-off."""
    bound = 0.0
    for i in range(q.shape[0]):
        total = 0.0
        for m in range(1, q.shape[1]):
            total += (m + 1) * m * abs(q[i, m])
        bound = max(bound, total)
    return bound / abs(step) * (1.0 + 1e-12)


@jit
def may_dip(g_a, g_b, width, speed, bend):
    """True when an event with values g_a, g_b of one sign at the ends of an interval of the given width may reach
    zero inside it: neither its rate (speed: a zero needs |g_a| + |g_b| <= speed x width) nor its bend (bend: the
    event lies above the chord less bend x width^2 / 8) excludes it."""
    low = min(abs(g_a), abs(g_b))
    return abs(g_a) + abs(g_b) <= speed * width and low <= 0.125 * bend * width * width


@jit(inline="always")
def hidden_crossing(events, args, eargs, mask, values, index, t_old, step, y_old, q, t_a, t_b, g_a, g_b, direction,
                    speed, bend, out):
    """(lo, hi, g_lo, g_hi) of the first piece of [t_a, t_b] (event `index`, values g_a, g_b there, not crossing
    between them) over which the event crosses zero in its direction, found by bisecting, first half first, every
    piece where may_dip cannot exclude a dip to zero, down to DIP_FLOOR of the step and for at most DIP_EVALUATIONS
    points; lo > hi when there is none.
    Evaluates the events of `mask` (into values) on the step's dense output."""
    stack = np.empty((DIP_STACK, 4))
    stack[0, 0], stack[0, 1], stack[0, 2], stack[0, 3] = t_a, t_b, g_a, g_b
    top = 1
    floor = DIP_FLOOR * abs(step)
    evaluations = 0
    while top > 0:
        top -= 1
        a, b, ga, gb = stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3]
        if crosses(ga, gb, direction):
            return a, b, ga, gb
        if abs(b - a) <= floor or not may_dip(ga, gb, abs(b - a), speed, bend) or top + 2 > DIP_STACK:
            continue
        if evaluations == DIP_EVALUATIONS:
            break
        evaluations += 1
        m = a + 0.5 * (b - a)
        dense_state(t_old, step, y_old, q, m, out)
        events(m, out, args, eargs, mask, values)
        gm = values[index]
        stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3] = m, b, gm, gb          # (second half last)
        stack[top + 1, 0], stack[top + 1, 1], stack[top + 1, 2], stack[top + 1, 3] = a, m, ga, gm
        top += 2
    return 1.0, 0.0, 0.0, 0.0


@jit
def keeps_sign(g, t_from, t, speed):
    """True when an event of value g at t_from, 1-Lipschitz in the state's largest component (its rate at most
    speed, step_speed), cannot be zero between t_from and t: it keeps g's sign there."""
    return speed * abs(t - t_from) < abs(g)


@jit(inline="always")
def probe_level(events, args, eargs, probed, values, t_old, step, y_old, q, directions, modes, probes, g_lo, g_hi,
                last, now, speed, bend, out):
    """The first probed level event (LEVEL_BEFORE_PROBED, mask `probed`; values g_lo, g_hi at the step's ends, not
    reached at its end) reached at one of `probes` evenly spaced interior points of the step, or between two of
    them (hidden_crossing), or -1. A point is evaluated only where some probed event may have changed sign since
    the last point evaluated and may still change it before the end (keeps_sign): elsewhere each keeps the sign of
    one of those values, reached at neither, so the answer is that of evaluating every point. last, now
    (n_events,) are work arrays."""
    t_last = t_old
    t_end = t_old + step
    for i in range(g_lo.shape[0]):
        last[i] = g_lo[i]
    for k in range(1, probes + 1):
        tk = t_old + step * k / (probes + 1)
        unsettled = False
        due = False
        for i in range(g_lo.shape[0]):
            if probed[i] and not keeps_sign(g_hi[i], t_end, tk, speed):
                unsettled = True
                due = due or not keeps_sign(last[i], t_last, tk, speed)
        if not unsettled:
            break
        if not due:
            continue
        dense_state(t_old, step, y_old, q, tk, out)
        events(tk, out, args, eargs, probed, values)
        i = level_reached(values, probed, directions, modes, LEVEL_BEFORE_PROBED)
        if i >= 0:
            return i
        for i in range(g_lo.shape[0]):
            now[i] = values[i]
        i = dipped_level(events, args, eargs, probed, values, t_old, step, y_old, q, directions, t_last, tk, last,
                         now, speed, bend, out)
        if i >= 0:
            return i
        t_last = tk
        for i in range(g_lo.shape[0]):
            last[i] = now[i]
    return dipped_level(events, args, eargs, probed, values, t_old, step, y_old, q, directions, t_last, t_end, last,
                        g_hi, speed, bend, out)


@jit(inline="always")
def dipped_level(events, args, eargs, probed, values, t_old, step, y_old, q, directions, t_a, t_b, g_a, g_b, speed,
                 bend, out):
    """The first probed level event (mask `probed`, values g_a, g_b at t_a, t_b, reached at neither) that
    hidden_crossing finds reached between t_a and t_b, or -1."""
    for i in range(g_a.shape[0]):
        if probed[i]:
            lo, hi, _, _ = hidden_crossing(events, args, eargs, probed, values, i, t_old, step, y_old, q, t_a, t_b,
                                           g_a[i], g_b[i], directions[i], speed, bend, out)
            if lo <= hi:
                return i
    return -1


@jit(inline="always")
def probe_crossing(events, args, eargs, only, values, index, t_old, step, y_old, q, g_lo, g_hi, direction, probes,
                   speed, bend, out):
    """(lo, hi, g_lo, g_hi) of the first interval between `probes` evenly spaced interior points of the step (and
    its ends) over which event `index` (values g_lo, g_hi at the step's ends) crosses zero in its direction, or
    between two of them where it dips to zero and back (hidden_crossing: the piece of the first crossing), or
    lo > hi when none does. Points where the event provably keeps the sign of the last value evaluated are
    skipped (keeps_sign); from the first point where it provably keeps g_hi's sign to the end, the last interval
    runs to the step's end."""
    t_lo = t_old
    t_end = t_old + step
    for k in range(1, probes + 1):
        tk = t_old + step * k / (probes + 1)
        if keeps_sign(g_hi, t_end, tk, speed):
            break
        if keeps_sign(g_lo, t_lo, tk, speed):
            continue
        dense_state(t_old, step, y_old, q, tk, out)
        events(tk, out, args, eargs, only, values)
        g_k = values[index]
        lo, hi, g_a, g_b = hidden_crossing(events, args, eargs, only, values, index, t_old, step, y_old, q, t_lo, tk,
                                           g_lo, g_k, direction, speed, bend, out)
        if lo <= hi:
            return lo, hi, g_a, g_b
        t_lo, g_lo = tk, g_k
    return hidden_crossing(events, args, eargs, only, values, index, t_old, step, y_old, q, t_lo, t_end, g_lo, g_hi,
                           direction, speed, bend, out)


@jit(inline="always")
def initial_step(fun, args, t0, y0, f0, t_bound, max_step, rtol, atol, order, unit):
    """scipy's select_initial_step for an error estimator of the given order (forward in t), read in units of
    `unit` of t: scipy's own step for unit 1; else the step scipy's rule gives the problem in t / unit, times unit.
    The rule's floors and its root of the derivatives' norms do not scale with t: a problem stretched in t by a
    factor gets its first step stretched by that factor only where unit is stretched with it."""
    n = y0.shape[0]
    scale = np.empty(n)
    for i in range(n):
        scale[i] = atol[i] + abs(y0[i]) * rtol
    d0 = rms(y0, scale)
    d1 = rms(f0, scale) * unit
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6 * unit
    else:
        h0 = 0.01 * d0 / d1 * unit
    h0 = min(h0, t_bound - t0)
    y1 = np.empty(n)
    for i in range(n):
        y1[i] = y0[i] + h0 * f0[i]
    f1 = np.empty(n)
    fun(t0 + h0, y1, args, f1)
    for i in range(n):
        f1[i] -= f0[i]
    d2 = rms(f1, scale) / h0 * unit * unit
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6 * unit, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (order + 1)) * unit
    return min(100.0 * h0, h1, t_bound - t0, max_step)


@jit
def error_scale(scale, y, y_new, rtol, atol):
    """scale = atol + max(|y|, |y_new|) rtol, the step's error scale (scipy's, both methods)."""
    for i in range(y.shape[0]):
        scale[i] = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol


@jit(inline="always")
def rk45_attempt(fun, args, t, t_new, step, y, k, y_new, stage, err, scale, rtol, atol):
    """One RK45 step of length step from (t, y), k[0] = f there: the stages into k, the new state into y_new (f
    there into k[6]); returns scipy RK45's scaled error norm."""
    for s in range(1, 6):                                   # the Dormand–Prince stages
        combine(stage, y, step, A[s], k, s)
        fun(t + C[s] * step, stage, args, k[s])
    combine(y_new, y, step, B, k, 6)
    fun(t_new, y_new, args, k[6])
    combine(err, None, step, E, k, 7)
    error_scale(scale, y, y_new, rtol, atol)
    return rms(err, scale)


@jit(inline="always")
def dop853_attempt(fun, args, t, t_new, step, y, k, y_new, stage, scale, rtol, atol):
    """One DOP853 step of length step from (t, y), k[0] = f there: the stages into k, the new state into y_new (f
    there into k[DOP853_STAGES]); returns scipy DOP853's error norm (its 5th- and 3rd-order estimates)."""
    for s in range(1, DOP853_STAGES):
        combine(stage, y, step, A8[s], k, s)
        fun(t + C8[s] * step, stage, args, k[s])
    combine(y_new, y, step, B8, k, DOP853_STAGES)
    fun(t_new, y_new, args, k[DOP853_STAGES])
    n = y.shape[0]
    error_scale(scale, y, y_new, rtol, atol)
    err5 = 0.0
    err3 = 0.0
    for i in range(n):
        e5 = 0.0
        e3 = 0.0
        for j in range(DOP853_STAGES + 1):
            e5 += E5[j] * k[j, i]
            e3 += E3[j] * k[j, i]
        e5 /= scale[i]
        e3 /= scale[i]
        err5 += e5 * e5
        err3 += e3 * e3
    if err5 == 0.0 and err3 == 0.0:
        return 0.0
    return abs(step) * err5 / np.sqrt((err5 + 0.01 * err3) * n)


@jit(inline="always")
def dop853_dense(fun, args, t, step, y, y_new, k, stage, f, q):
    """A DOP853 step's dense output into q (n, 7) (dense_state's form): its three extra stages into k, then scipy's
    coefficients F (Dop853DenseOutput; f a work array (7,)) rewritten in powers of x."""
    for s in range(DOP853_STAGES + 1, DOP853_EXTENDED):
        combine(stage, y, step, A8[s], k, s)
        fun(t + C8[s] * step, stage, args, k[s])
    for i in range(y.shape[0]):
        delta = y_new[i] - y[i]
        f[0] = delta
        f[1] = step * k[0, i] - delta
        f[2] = 2.0 * delta - step * (k[DOP853_STAGES, i] + k[0, i])
        for r in range(4):
            acc = 0.0
            for j in range(DOP853_EXTENDED):
                acc += D8[r, j] * k[j, i]
            f[3 + r] = step * acc
        for m in range(7):
            acc = 0.0
            for r in range(7):
                acc += DOP853_POWERS[m, r] * f[r]
            q[i, m] = acc / step


@jit(inline="always")
def advance(fun, events, args, eargs, t, y, f, h, fresh, t_bound, rtol, atol, max_step, max_steps, max_nfev,
            g, active, directions, modes, method):
    """Steps of `method` (RK45 or DOP853) from (t, y, f = fun(t, y)) with proposed step h towards t_bound,
    stopping at events.

    Returns at t_bound, after max_steps steps, after a step over which active events cross zero in their
    directions (each crossing located on the step's dense output, as solve_ivp locates events; at a terminal
    one the step is cut there; TERMINAL_PROBED also at PROBES[method] interior points of a step within reach), where a
    level event is reached (modes: LEVEL_BEFORE, LEVEL_AFTER; LEVEL_BEFORE_PROBED probed likewise), when the step
    size falls below the round-off floor, or when more than max_nfev evaluations were spent. With fresh, f is
    computed first, and h <= 0 asks for scipy's initial step.

    Parameters
    ----------
    fun, events : jitted callables
        ``fun(t, y, args, out)``, ``events(t, y, args, eargs, active, out)`` (module docstring).
    args, eargs : tuple or ndarray
        The system's and its events' parameters.
    y, f : ndarray (n,)
        State and its derivative at t; overwritten with those at the returned time.
    g : ndarray (n_events,)
        Event values at (t, y); overwritten with those at the returned time.
    active : ndarray (n_events,) of bool
    directions : ndarray (n_events,)
        +1: crossings upwards count, -1 downwards, 0 both (solve_ivp's event.direction); for a level, the
        direction in which it is reached.
    modes : ndarray (n_events,) of int
        CROSSING, TERMINAL, LEVEL_BEFORE, LEVEL_AFTER, TERMINAL_PROBED or LEVEL_BEFORE_PROBED.
    method : int
        RK45 or DOP853.

    Returns
    -------
    status : int
        STEPPED, EVENT, STEP_FAILED or BUDGET.
    t : float
        Time reached (a terminal event's time, or where a level event stopped it).
    h : float
        The next step size proposed.
    nfev : int
        Evaluations of fun spent.
    ts : ndarray (m,)
        Step points, ts[0] the start (the last one a terminal event's time).
    ys : ndarray (m, n)
    hs, qs : ndarray (m - 1,), (m - 1, n, DENSE_COLUMNS[method])
        Each step's length and dense-output coefficients (dense_state; the last step's polynomial may reach
        past a terminal event).
    hits : ndarray (k,) of int
        The events crossed over the last step, in time order, up to the first terminal one (or the level event
        that stopped it).
    hit_ts : ndarray (k,)
    hit_ys : ndarray (k, n)
    """
    # the arguments (their caller holds them) and the arrays made here are used through borrowed views: no atomic
    # reference counts in the loops (the arrays made here are kept alive to the end)
    args, eargs, y, f, atol, g, active, directions, modes = borrowed((args, eargs, y, f, atol, g, active, directions,
                                                                      modes))
    n = y.shape[0]
    ne = g.shape[0]
    records = (np.empty(max_steps + 1), np.empty((max_steps + 1, n)), np.empty(max_steps),
               np.empty((max_steps, n, DENSE_COLUMNS[method])), np.empty(ne, dtype=np.int64), np.empty(ne),
               np.empty((ne, n)), np.zeros(ne, dtype=np.bool_), np.empty(ne))
    ts, ys, hs, qs, hits, hit_ts, hit_ys, only, values = borrowed(records)
    n_hits = 0
    ts[0] = t
    copy_into(ys[0], y)
    count = 1
    nfev = 0
    if fresh:
        fun(t, y, args, f)
        nfev += 1
        if h <= 0.0:
            h = initial_step(fun, args, t, y, f, t_bound, max_step, rtol, atol, ERROR_ORDERS[method], 1.0)
            nfev += 1
    last = END_ROWS[method]
    exponent = -1.0 / (ERROR_ORDERS[method] + 1)
    work = (np.empty((STAGE_ROWS[method], n)), np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(7),
            np.empty(ne), np.empty(ne), np.empty(ne), np.zeros(ne, dtype=np.bool_))
    # probed: the probed level events
    k, y_new, stage, err, scale, coefficients, g_new, g_last, g_now, probed = borrowed(work)
    any_probed = False
    for i in range(ne):
        probed[i] = active[i] and modes[i] == LEVEL_BEFORE_PROBED
        any_probed = any_probed or probed[i]
    status = STEPPED
    while t < t_bound and count <= max_steps:
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
                status = STEP_FAILED
                break
            t_new = t + h
            if t_new - t_bound > 0:
                t_new = t_bound
            step = t_new - t
            copy_into(k[0], f)
            if method == DOP853:
                error_norm = dop853_attempt(fun, args, t, t_new, step, y, k, y_new, stage, scale, rtol, atol)
                nfev += DOP853_STAGES
            else:
                error_norm = rk45_attempt(fun, args, t, t_new, step, y, k, y_new, stage, err, scale, rtol, atol)
                nfev += 6
            if error_norm < 1.0:
                if error_norm == 0.0:
                    factor = MAX_FACTOR
                else:
                    factor = min(MAX_FACTOR, SAFETY * error_norm ** exponent)
                if rejected:
                    factor = min(1.0, factor)
                h = step * factor
                accepted = True
            else:
                h = step * max(MIN_FACTOR, SAFETY * error_norm ** exponent)
                rejected = True
                if nfev > max_nfev:
                    status = BUDGET
                    break
        if not accepted:
            break
        events(t_new, y_new, args, eargs, active, g_new)        # (first: a system may reuse the last evaluation)
        if method == DOP853:                                     # this step's dense output
            dop853_dense(fun, args, t, step, y, y_new, k, stage, coefficients, qs[count - 1])
            nfev += DOP853_EXTENDED - DOP853_STAGES - 1
        else:
            for m in range(4):
                combine(qs[count - 1, :, m], None, 1.0, P[:, m], k, 7)
        before = level_reached(g_new, active, directions, modes, LEVEL_BEFORE, LEVEL_BEFORE_PROBED)
        reach = step_reach(step, qs[count - 1])
        speed = -1.0                                             # (made when first needed, with bend)
        bend = -1.0
        if before < 0 and any_probed:
            near = False
            for i in range(ne):
                near = near or (probed[i] and within_reach(g[i], g_new[i], reach))
            if near:
                speed = step_speed(qs[count - 1])
                bend = step_bend(step, qs[count - 1])
                before = probe_level(events, args, eargs, probed, values, t, step, y, qs[count - 1], directions,
                                     modes, PROBES[method], g, g_new, g_last, g_now, speed, bend, stage)
        if before >= 0:                                          # a hard case ahead: this step is dropped
            hits[0] = before
            hit_ts[0] = t
            copy_into(hit_ys[0], y)
            n_hits = 1
            status = EVENT
            break
        hs[count - 1] = step
        # events crossed over this step, located, in time order (insertion), up to the first terminal one
        for i in range(ne):
            if not active[i] or is_level(modes[i]):
                continue
            lo, hi, g_lo, g_hi = t, t_new, g[i], g_new[i]
            if not crosses(g_lo, g_hi, directions[i]):
                if modes[i] != TERMINAL_PROBED or not within_reach(g_lo, g_hi, reach):
                    continue
                only[i] = True
                if speed < 0.0:
                    speed = step_speed(qs[count - 1])
                    bend = step_bend(step, qs[count - 1])
                lo, hi, g_lo, g_hi = probe_crossing(events, args, eargs, only, values, i, t, step, y,
                                                    qs[count - 1], g_lo, g_hi, directions[i], PROBES[method], speed,
                                                    bend, stage)
                if lo > hi:
                    only[i] = False
                    continue
            only[i] = True
            t_e = locate(events, args, eargs, only, values, i, t, step, y, qs[count - 1], lo, hi, g_lo, g_hi, stage)
            only[i] = False
            j = n_hits
            while j > 0 and hit_ts[j - 1] > t_e:
                hits[j] = hits[j - 1]
                hit_ts[j] = hit_ts[j - 1]
                copy_into(hit_ys[j], hit_ys[j - 1])
                j -= 1
            hits[j] = i
            hit_ts[j] = t_e
            copy_into(hit_ys[j], stage)
            n_hits += 1
        first = -1
        for j in range(n_hits):
            if is_terminal(modes[hits[j]]):
                first = j
                n_hits = j + 1
                break
        if first >= 0:                                           # cut at the terminal event
            ts[count] = hit_ts[first]
            copy_into(ys[count], hit_ys[first])
            count += 1
            t = hit_ts[first]
            copy_into(y, hit_ys[first])               # the integration ends here: f and g stay the step's
            status = EVENT
            break
        ts[count] = t_new
        copy_into(ys[count], y_new)
        count += 1
        t = t_new
        copy_into(y, y_new)
        copy_into(f, k[last])
        for i in range(ne):
            g[i] = g_new[i]
        after = level_reached(g_new, active, directions, modes, LEVEL_AFTER)
        if after >= 0:                                           # the step is kept, the integration ends here
            hits[n_hits] = after
            hit_ts[n_hits] = t
            copy_into(hit_ys[n_hits], y)
            n_hits += 1
        if n_hits:
            status = EVENT
            break
    result = (status, t, h, nfev, ts[:count].copy(), ys[:count].copy(), hs[:count - 1].copy(),
              qs[:count - 1].copy(), hits[:n_hits].copy(), hit_ts[:n_hits].copy(), hit_ys[:n_hits].copy())
    kept(records, work)
    return result
