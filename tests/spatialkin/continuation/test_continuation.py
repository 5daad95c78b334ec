"""trace_cycle with the compiled engine (solve_ivp with spatialkin.ode.solvers.CompiledDOP853, the default, and
CompiledRK45) against closed forms and against scipy's own DOP853 and RK45 with the same jitted events."""
import math

import numpy as np
import pytest
from scipy.special import ellipe

from spatialkin._lib.jit import jit
from spatialkin.kernels.continuation import follow as kf
from spatialkin.kernels.continuation.implicit import follow_rhs
from spatialkin.kernels.ode.rk import advance
from spatialkin.continuation import CurveKernels, trace_cycle

#: Tolerances: lock positions and closure against the closed forms (the trace's rtol is 1e-10); the two
#: integrators against each other: the same method, so the same curve to well within the tolerance (not the
#: same steps to round-off: a first step's error estimate is at round-off level, and the same arithmetic in
#: another order sizes the next step differently).
RTOL = 1e-10
CLOSED_FORM_TOL = 1e-8
SAME_CURVE_TOL = 1e-9


@jit
def ellipse_rhs(s, y, a, sign, pullback):
    """F(q, phi) = q^2 + (phi / a)^2 - 1: the input reverses at phi = +-a (q = 0)."""
    jac = np.array([[2.0 * y[0], 2.0 * y[1] / (a * a)]])
    f = np.array([y[0] ** 2 + (y[1] / a) ** 2 - 1.0])
    out = np.empty(2)
    follow_rhs(jac, f, sign, pullback, out)
    return out


@jit
def wave_rhs(s, y, a, sign, pullback):
    """F(q, phi) = q - a sin(phi): a full turn of the input."""
    jac = np.array([[1.0, -a * math.cos(y[1])]])
    f = np.array([y[0] - a * math.sin(y[1])])
    out = np.empty(2)
    follow_rhs(jac, f, sign, pullback, out)
    return out


@jit
def ellipse_fun(t, y, args, out):
    kf.follow_fun(ellipse_rhs, t, y, args, out)


@jit
def ellipse_events(t, y, args, eargs, active, out):
    kf.follow_events(ellipse_rhs, t, y, args, eargs, active, out)


@jit
def ellipse_advance(t, y, f, h, fresh, t_bound, rtol, atol, max_step, max_steps, max_nfev, g, active, directions,
                   modes, args, eargs, method):
    return advance(ellipse_fun, ellipse_events, args, eargs, t, y, f, h, fresh, t_bound, rtol, atol, max_step,
                   max_steps, max_nfev, g, active, directions, modes, method)


@jit
def wave_fun(t, y, args, out):
    kf.follow_fun(wave_rhs, t, y, args, out)


@jit
def wave_events(t, y, args, eargs, active, out):
    kf.follow_events(wave_rhs, t, y, args, eargs, active, out)


@jit
def wave_advance(t, y, f, h, fresh, t_bound, rtol, atol, max_step, max_steps, max_nfev, g, active, directions,
                   modes, args, eargs, method):
    return advance(wave_fun, wave_events, args, eargs, t, y, f, h, fresh, t_bound, rtol, atol, max_step,
                   max_steps, max_nfev, g, active, directions, modes, method)


ELLIPSE = CurveKernels(ellipse_rhs, ellipse_events, ellipse_advance)
WAVE = CurveKernels(wave_rhs, wave_events, wave_advance)


@pytest.fixture(params=[("compiled", "DOP853"), ("compiled-rk45", "RK45")], ids=["dop853", "rk45"])
def methods(request):
    """A compiled method and scipy's method of the same steps."""
    return request.param


def traces(kernels, y0, a, period, methods):
    compiled = trace_cycle(kernels, y0, (a,), period, 100.0, rtol=RTOL, method=methods[0])
    reference = trace_cycle(kernels, y0, (a,), period, 100.0, rtol=RTOL, method=methods[1])
    return compiled, reference


def test_locks_of_an_ellipse_match_the_closed_form_and_solve_ivp(methods):
    a = 1.5
    compiled, reference = traces(ELLIPSE, np.array([1.0, 0.0]), a, 2 * np.pi, methods)
    assert len(compiled.locks) == 2 and not compiled.full_turn and compiled.period == 0.0
    for lock, phi in zip(compiled.locks, (a, -a)):                 # met in this order from the start
        assert abs(lock[1] - phi) < CLOSED_FORM_TOL and abs(lock[0]) < math.sqrt(CLOSED_FORM_TOL)
    perimeter = 4 * a * ellipe(1 - 1 / a ** 2)                       # the closed curve, once round
    assert abs(compiled.length - perimeter) < CLOSED_FORM_TOL
    assert len(compiled.pieces) == len(reference.pieces) == 3
    for (s0, s1, sol), (r0, r1, ref) in zip(compiled.pieces, reference.pieces):
        assert abs(s1 - r1) < SAME_CURVE_TOL
        s = np.linspace(s0, s1, 50)
        np.testing.assert_allclose(sol(s), ref(s), rtol=0, atol=SAME_CURVE_TOL)
    inputs, states = compiled.branch_samples()                       # the arc between the locks
    assert inputs.min() > -a - CLOSED_FORM_TOL and inputs.max() < a + CLOSED_FORM_TOL
    assert np.all(states[:, 0] > -CLOSED_FORM_TOL)


def test_full_turn_closes_after_one_period(methods):
    a = 0.5
    compiled, reference = traces(WAVE, np.array([0.0, 0.0]), a, 2 * np.pi, methods)
    assert compiled.full_turn and compiled.period == 2 * np.pi
    length = 4 * math.sqrt(1 + a * a) * ellipe(a * a / (1 + a * a))      # arc length of q = a sin(phi)
    assert abs(compiled.length - length) < CLOSED_FORM_TOL
    assert abs(compiled.length - reference.length) < SAME_CURVE_TOL
    s = np.linspace(0.0, compiled.length, 200)
    y = compiled(s)
    assert np.max(np.abs(y[:, 0] - a * np.sin(y[:, 1]))) < CLOSED_FORM_TOL
    np.testing.assert_allclose(y, reference(s), rtol=0, atol=SAME_CURVE_TOL)


def test_end_of_interval_is_reported():
    with pytest.raises(ValueError, match="did not close"):
        trace_cycle(WAVE, np.array([0.0, 0.0]), (0.5,), 2 * np.pi, 1.0, rtol=RTOL)
