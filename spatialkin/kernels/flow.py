"""The seeds' gradient flow to the level g = 0, by the compiled Dormand–Prince 5(4) (spatialkin.kernels.dopri).

Only the common case is decided here: the flow reaches the level (the crossing located on the dense output).
Where it would stall, near an apex, or leave a parameter bound, the kernel says so (HANDOFF) and the caller
runs solve_ivp with its event functions instead.
"""
import numpy as np

from .._jit import jit
from .dopri import A, B, E, ERROR_EXPONENT, MAX_FACTOR, MIN_FACTOR, P, SAFETY, combine, copy_into, locate_crossing
from .level import gradient_flow_rhs, level_value, relative_area_at, surface_gradient_norm

#: Status codes of flow_to_level.
HIT = 1
NO_HIT = 0
HANDOFF = -1
@jit
def _rms(x, atol, rtol, ya, yb):
    acc = 0.0
    for i in range(x.shape[0]):
        q = x[i] / (atol + max(abs(ya[i]), abs(yb[i])) * rtol)
        acc += q * q
    return np.sqrt(acc / x.shape[0])


@jit(inline="always")
def _level_at(t, y, fn, pq):
    return fn(pq[0], pq[1], y[0], y[1])


@jit
def flow_to_level(x0, p, q, sigma, h, saturation, t_bound, max_step, rtol, atol, max_nfev, min_gradient,
                  watch_apex, apex_guard, lo, hi, out):
    """Follow gradient_flow_rhs from x0 (2,) until g changes sign; the crossing is written to out (2,).

    The flow ends without a seed (NO_HIT) where solve_ivp's version does: at the end of the interval, the
    evaluation budget or a step failure, or a terminal event (|grad_S g| falling below min_gradient, the
    relative area element below apex_guard where watch_apex, a parameter leaving [lo, hi]). Where such an
    event and the level crossing fall in one step, returns HANDOFF: the caller runs solve_ivp.
    """
    n = 2
    y = x0.copy()
    f = gradient_flow_rhs(0.0, y, p, q, sigma, h, saturation)
    nfev = 1
    # initial step (scipy's select_initial_step, order 4)
    y_stage = np.empty(n)
    d0 = _rms(y, atol, rtol, y, y)
    d1 = _rms(f, atol, rtol, y, y)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, t_bound)
    f1 = gradient_flow_rhs(0.0, y + h0 * f, p, q, sigma, h, saturation)
    nfev += 1
    d2 = _rms(f1 - f, atol, rtol, y, y) / h0
    h1 = max(1e-6, h0 * 1e-3) if (d1 <= 1e-15 and d2 <= 1e-15) else (0.01 / max(d1, d2)) ** 0.2
    step_h = min(100.0 * h0, h1, t_bound, max_step)
    t = 0.0
    g_old = level_value(p, q, y[0], y[1])
    e_old = np.empty(6)
    e_old[0] = surface_gradient_norm(p, q, y[0], y[1], h) - min_gradient
    e_old[1] = relative_area_at(p, y[0], y[1]) - apex_guard
    for i in range(n):
        e_old[2 + 2 * i] = y[i] - lo[i]
        e_old[3 + 2 * i] = hi[i] - y[i]
    k = np.empty((7, n))
    y_new = np.empty(n)
    err = np.empty(n)
    qm = np.empty((n, 4))
    while t < t_bound:
        min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
        step_h = max(min(step_h, max_step), min_step)
        rejected = False
        while True:
            if nfev > max_nfev or step_h < min_step:
                return NO_HIT          # solve_ivp's budget or step failure: no seed either
            t_new = min(t + step_h, t_bound)
            step = t_new - t
            copy_into(k[0], f)
            for s in range(1, 6):
                combine(y_stage, y, step, A[s], k, s)
                copy_into(k[s], gradient_flow_rhs(0.0, y_stage, p, q, sigma, h, saturation))
            combine(y_new, y, step, B, k, 6)
            f_new = gradient_flow_rhs(0.0, y_new, p, q, sigma, h, saturation)
            copy_into(k[6], f_new)
            nfev += 6
            combine(err, None, step, E, k, 7)
            error_norm = _rms(err, atol, rtol, y, y_new)
            if error_norm < 1.0:
                factor = MAX_FACTOR if error_norm == 0.0 else min(MAX_FACTOR, SAFETY * error_norm ** ERROR_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                step_h = step * factor
                break
            step_h = step * max(MIN_FACTOR, SAFETY * error_norm ** ERROR_EXPONENT)
            rejected = True
        # the other (terminal, downward) events of the solve_ivp version: stalled, apex, edges
        stop = False
        e_new = surface_gradient_norm(p, q, y_new[0], y_new[1], h) - min_gradient
        stop = stop or (e_old[0] >= 0.0 and e_new <= 0.0)
        e_old[0] = e_new
        if watch_apex:
            e_new = relative_area_at(p, y_new[0], y_new[1]) - apex_guard
            stop = stop or (e_old[1] >= 0.0 and e_new <= 0.0)
            e_old[1] = e_new
        for i in range(n):
            e_lo = y_new[i] - lo[i]
            e_hi = hi[i] - y_new[i]
            stop = stop or (e_old[2 + 2 * i] >= 0.0 and e_lo <= 0.0) or (e_old[3 + 2 * i] >= 0.0 and e_hi <= 0.0)
            e_old[2 + 2 * i] = e_lo
            e_old[3 + 2 * i] = e_hi
        g_new = level_value(p, q, y_new[0], y_new[1])
        crossed = (g_old <= 0.0 and g_new >= 0.0) or (g_old >= 0.0 and g_new <= 0.0)
        if stop:
            # another event ends the flow without a seed, unless the level is crossed in the same step
            # (then which comes first is solve_ivp's to decide)
            return HANDOFF if crossed else NO_HIT
        if crossed:
            for m in range(4):                       # this step's dense output
                combine(qm[:, m], None, 1.0, P[:, m], k, 7)
            locate_crossing(_level_at, level_value, (p, q), t, step, y, qm, g_old, g_new, out)
            return HIT
        g_old = g_new
        t = t_new
        copy_into(y, y_new)
        f = f_new
    return NO_HIT
