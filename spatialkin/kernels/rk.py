"""The one compiled Runge–Kutta engine: Dormand–Prince 5(4) with scipy RK45's steps, stopping at events.

Every curve of the library (intersection branches, continuation of mechanisms) is integrated by
``solve_ivp(..., method=spatialkin.tracing.ode.CompiledRK45)``; that OdeSolver calls ``advance`` here, which
takes many RK45 steps inside compiled code and returns at the first step where one of the system's event
functions changes sign in its direction, so that solve_ivp locates the event on the step's dense output as it
does for its own methods. The tableau, error norm, step-size control, initial step and dense output are
scipy's (scipy.integrate._ivp.rk.RK45, common.select_initial_step): the steps are RK45's, to round-off.

A system supplies two jitted functions, bound at compile time by a small jitted wrapper in its own kernel
module (numba caches a kernel only when the functions it calls are globals, not values):

* ``fun(t, y, args, out)``: writes dy/dt (n,) into out;
* ``events(t, y, args, eargs, active, out)``: writes the value of every active event into out (the same
  functions serve solve_ivp's own methods through spatialkin.tracing.ode.Event).

References
----------
Dormand, J. R., Prince, P. J., "A family of embedded Runge-Kutta formulae", J. Comput. Appl. Math. 6 (1980);
scipy.integrate._ivp.rk.RK45 and common.select_initial_step (the coefficients and the control copied here).
"""
import numpy as np

from .._jit import jit

# --- what advance returns ----------------------------------------------------------------------------------
#: Took max_steps steps, or reached t_bound, without an event: call again.
STEPPED = 0
#: An active event changed sign (in its direction) over the last step.
EVENT = 1
#: The step size fell below the round-off floor.
STEP_FAILED = -1
#: The evaluation budget ran out.
BUDGET = -2

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
#: Order of the error estimator (scipy's select_initial_step takes it).
ERROR_ORDER = 4


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
    """RK45 dense output on one step: out = y_old + h Q p(x), x = (t - t_old)/h, p = (x, x^2, x^3, x^4)."""
    x = (t - t_old) / h
    p0 = x
    p1 = x * x
    p2 = p1 * x
    p3 = p2 * x
    for i in range(out.shape[0]):
        out[i] = y_old[i] + h * (q[i, 0] * p0 + q[i, 1] * p1 + q[i, 2] * p2 + q[i, 3] * p3)


@jit
def dense_at(ts, ys, hs, qs, t):
    """The dense state (n,) at one time t (dense_many for a scalar)."""
    out = np.empty(ys.shape[1])
    m = ts.shape[0]
    if m < 2:
        copy_into(out, ys[0])
        return out
    j = min(max(np.searchsorted(ts, t, side="right") - 1, 0), m - 2)
    dense_state(ts[j], hs[j], ys[j], qs[j], t, out)
    return out


@jit
def dense_many(ts, ys, hs, qs, t, out):
    """Dense states out (M, n) at times t (M,) from stored steps ts (m,), ys (m, n), their lengths hs (m - 1,)
    and qs (m - 1, n, 4); outside [ts[0], ts[-1]] the first or last step's polynomial is extended (as scipy's
    OdeSolution)."""
    m = ts.shape[0]
    for k in range(t.shape[0]):
        if m < 2:
            copy_into(out[k], ys[0])
            continue
        j = np.searchsorted(ts, t[k], side="right") - 1
        j = min(max(j, 0), m - 2)
        dense_state(ts[j], hs[j], ys[j], qs[j], t[k], out[k])


@jit(inline="always")
def initial_step(fun, args, t0, y0, f0, t_bound, max_step, rtol, atol):
    """scipy's select_initial_step for an error estimator of order ERROR_ORDER (forward in t)."""
    n = y0.shape[0]
    scale = np.empty(n)
    for i in range(n):
        scale[i] = atol[i] + abs(y0[i]) * rtol
    d0 = rms(y0, scale)
    d1 = rms(f0, scale)
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    h0 = min(h0, t_bound - t0)
    y1 = np.empty(n)
    for i in range(n):
        y1[i] = y0[i] + h0 * f0[i]
    f1 = np.empty(n)
    fun(t0 + h0, y1, args, f1)
    for i in range(n):
        f1[i] -= f0[i]
    d2 = rms(f1, scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (ERROR_ORDER + 1))
    return min(100.0 * h0, h1, t_bound - t0, max_step)


@jit(inline="always")
def advance(fun, events, args, eargs, t, y, f, h, fresh, t_bound, rtol, atol, max_step, max_steps, max_nfev,
            g, active):
    """RK45 steps from (t, y, f = fun(t, y)) with proposed step h towards t_bound.

    Returns at t_bound, after max_steps steps, at the first step over which an active event changes sign (in
    either direction, so that each event changes sign at most once over what one call covers and solve_ivp's
    root search on its dense output finds that crossing), when the step size falls below the round-off floor,
    or when more than max_nfev evaluations were spent. With fresh, f is computed first, and h <= 0 asks for
    scipy's initial step.

    Parameters
    ----------
    fun, events : jitted callables
        ``fun(t, y, args, out)``, ``events(t, y, args, eargs, active, out)`` (module docstring).
    args, eargs : tuple
        The system's and its events' parameters.
    y, f : ndarray (n,)
        State and its derivative at t; overwritten with those at the returned time.
    g : ndarray (n_events,)
        Event values at (t, y); overwritten with those at the returned time.
    active : ndarray (n_events,) of bool

    Returns
    -------
    status : int
        STEPPED, EVENT, STEP_FAILED or BUDGET.
    t : float
        Time reached.
    h : float
        The next step size proposed.
    nfev : int
        Evaluations of fun spent.
    ts : ndarray (m,)
        Step points, ts[0] the start.
    ys : ndarray (m, n)
    qs : ndarray (m - 1, n, 4)
        Dense-output coefficients of each step (dense_state; the step length is ts[j + 1] - ts[j]).
    """
    n = y.shape[0]
    ts = np.empty(max_steps + 1)
    ys = np.empty((max_steps + 1, n))
    qs = np.empty((max_steps, n, 4))
    ts[0] = t
    copy_into(ys[0], y)
    count = 1
    nfev = 0
    if fresh:
        fun(t, y, args, f)
        nfev += 1
        if h <= 0.0:
            h = initial_step(fun, args, t, y, f, t_bound, max_step, rtol, atol)
            nfev += 1
    k = np.empty((7, n))
    y_new = np.empty(n)
    stage = np.empty(n)
    err = np.empty(n)
    scale = np.empty(n)
    g_new = np.empty(g.shape[0])
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
            for s in range(1, 6):                               # the Dormand–Prince stages
                combine(stage, y, step, A[s], k, s)
                fun(t + C[s] * step, stage, args, k[s])
            combine(y_new, y, step, B, k, 6)
            fun(t_new, y_new, args, k[6])
            nfev += 6
            combine(err, None, step, E, k, 7)
            for i in range(n):
                scale[i] = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
            error_norm = rms(err, scale)
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
                    status = BUDGET
                    break
        if not accepted:
            break
        for m in range(4):                                       # this step's dense output
            combine(qs[count - 1, :, m], None, 1.0, P[:, m], k, 7)
        ts[count] = t_new
        copy_into(ys[count], y_new)
        count += 1
        t = t_new
        copy_into(y, y_new)
        copy_into(f, k[6])
        events(t, y, args, eargs, active, g_new)
        crossed = False                  # any sign change, in either direction: one per step returned
        for i in range(g.shape[0]):
            if active[i] and ((g[i] <= 0.0 <= g_new[i]) or (g[i] >= 0.0 >= g_new[i])):
                crossed = True
            g[i] = g_new[i]
        if crossed:
            status = EVENT
            break
    return status, t, h, nfev, ts[:count].copy(), ys[:count].copy(), qs[:count - 1].copy()
