"""The one Runge–Kutta engine (spatialkin.kernels.ode.rk) as solve_ivp's methods CompiledRK45 and CompiledDOP853
(spatialkin.ode.solvers).

Oracle: scipy's own RK45 and DOP853 on the same jitted right-hand side (the looper pair's Dragilev system): the same
steps to round-off, the same dense output, the same located events; the budget and bad options raise typed errors.
"""
import numpy as np
import pytest
from scipy.integrate import DOP853, RK45, solve_ivp

import spatialkin as sk
from spatialkin.bench.cases import looper_pair
from spatialkin.kernels.march import branch_ode as kb
from spatialkin.kernels.march import curve as kc
from spatialkin.ode.solvers import COMPILED, COMPILED_RK45
from spatialkin.ode.record import Steps
from spatialkin.ode.solvers import BudgetExceeded, CompiledRK45, Event, System, integrate

#: States, dense output and event times: the same polynomials on (nearly) the same steps.
SAME_DENSE_TOL = 1e-9
RTOL = 1e-9


def looper_system():
    """The looper pair's branch system from a point on the curve (state y0, no events watched)."""
    torus, sphere = looper_pair()
    curve = sk.intersect(torus, sphere)[0]
    y0 = np.ascontiguousarray(curve.params[0], dtype=float)
    ep = np.zeros(kb.P_SIZE)
    return System(kb.branch_rhs, kb.branch_events, kb.branch_advance, kb.branch_args(torus.data, sphere.data, 1.0, 0.0),
                  ep, kb.COUNT), y0, curve.length


#: Each compiled method and scipy's method whose steps it takes.
PAIRS = pytest.mark.parametrize("compiled, method", [(COMPILED_RK45, "RK45"), (COMPILED, "DOP853")],
                                ids=["rk45", "dop853"])


#: Unit round-off of binary64.
UNIT_ROUNDOFF = np.finfo(float).eps / 2
#: scipy's step-size control (Hairer, Norsett & Wanner I, sec. II.4): after an accepted step of error norm err the
#: next step is h * clip(SAFETY * err**(-1/(q+1)), MIN_FACTOR, MAX_FACTOR), q the error estimator's order.
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
#: Relative change of h that measures how the next step follows this one (d ln err / d ln h, by a second step).
PROBE = 1e-3
#: The compared runs start from half scipy's median step: an accepted first step whose error estimate stands well
#: above round-off (from scipy's own tiny initial step the estimate of the next steps is round-off itself, and the
#: step sizes it gives are not determined by the arithmetic to any useful relative accuracy).
FIRST_STEP_SHARE = 0.5
#: The bound must still say something: the steps agree to this (relative) or the comparison is vacuous.
MEANINGFUL_BOUND = 1e-2
SCIPY_METHODS = {"RK45": RK45, "DOP853": DOP853}


def rms(x):
    return np.sqrt(np.mean(x * x))


def error_norm(cls, solver, h, y_old, rtol, atol):
    """scipy's scaled error norm of the step just taken (RK45: h E.K; DOP853: its 5th/3rd order blend), and the
    weights |E| with which each stage's own error enters it (DOP853: |d g / d err5| <= 2, |d g / d err3| <= 1 for
    g = err5^2 / hypot(err5, 0.1 err3))."""
    K = solver.K
    scale = atol + rtol * np.maximum(np.abs(y_old), np.abs(solver.y))
    if cls is RK45:
        return rms(h * (K.T @ cls.E) / scale), np.abs(cls.E), scale
    e5, e3 = K.T @ cls.E5, K.T @ cls.E3
    blend = np.hypot(e5, 0.1 * e3)
    share = np.divide(np.abs(e5), blend, out=np.zeros_like(blend), where=blend > 0)
    return rms(h * e5 * share / scale), 2 * np.abs(cls.E5) + 0.1 * np.abs(cls.E3), scale


def step_factor(cls, err):
    q = cls.error_estimator_order
    return MAX_FACTOR if err <= 0 else min(MAX_FACTOR, max(MIN_FACTOR, SAFETY * err ** (-1 / (q + 1))))


def step_time_bounds(method, system, y0, t_bound, rtol, atol, first_step):
    """scipy's step times t (m,) of `method` and a bound (m,) on |t_k - t'_k| for any implementation of the same
    method that rounds differently: the error analysis of the error estimate, step by step on scipy's own stages.

    Each stage k_j carries a round-off of at most (s+1) u (|k_j| + L |y + h sum a_jl k_l|) (its own evaluation, and
    the rounded stage argument through the Lipschitz constant L of the right-hand side, measured by central
    differences), so the scaled error norm err moves by at most dE = h (s+1) u rms(sum_j |E_j| dk_j / scale). The
    next step's factor moves within [factor(err + dE), factor(err - dE)] (the clip included); that relative change
    of h is carried into the steps after it by d ln h' / d ln h = 1 - p/(q+1), with p = d ln err / d ln h measured
    by a second step of size h (1 + PROBE) (0: the controller restores the step size; 1: it keeps the change). A
    step time is the sum of the steps before it, so its bound is the sum of h_i times the carried change."""
    cls = SCIPY_METHODS[method]
    q, s, n = cls.error_estimator_order, cls.n_stages, len(y0)
    a = np.zeros((s + 1, s + 1))
    a[:cls.A.shape[0], :cls.A.shape[1]] = np.abs(cls.A)
    a[s, :s] = np.abs(cls.B)                         # the last stage is f at the new state

    def rhs(t, y):
        return system.rhs(t, y, *system.args)

    def lipschitz(y):
        columns = [(rhs(0.0, y + 1e-6 * e) - rhs(0.0, y - 1e-6 * e)) / 2e-6 for e in np.eye(n)]
        return np.abs(np.array(columns)).sum(axis=0)

    solver = cls(rhs, 0.0, y0, t_bound, rtol=rtol, atol=atol, first_step=first_step)
    ts, fresh, carried = [0.0], [], []
    while solver.status == "running":
        t_old, y_old = solver.t, solver.y.copy()
        solver.step()
        h = solver.t - t_old
        ts.append(solver.t)
        err, weights, scale = error_norm(cls, solver, h, y_old, rtol, atol)
        stage_args = np.abs(y_old)[None, :] + h * (a @ np.abs(solver.K))
        dk = np.abs(solver.K) + lipschitz(y_old)[None, :] * stage_args
        d_err = h * (s + 1) * UNIT_ROUNDOFF * rms((weights @ dk) / scale)
        fresh.append(np.log(step_factor(cls, max(err - d_err, 0.0)) / step_factor(cls, err + d_err)))
        probe = cls(rhs, t_old, y_old, t_old + 2 * h, rtol=rtol, atol=atol, first_step=h * (1 + PROBE))
        probe.step()
        err_probe = error_norm(cls, probe, probe.t - t_old, y_old, rtol, atol)[0]
        clipped = step_factor(cls, err) in (MIN_FACTOR, MAX_FACTOR) or err == 0 or err_probe == 0
        p = 0.0 if clipped else np.log(err_probe / err) / np.log((probe.t - t_old) / h)
        carried.append(0.0 if clipped else abs(1 - p / (q + 1)))
    ts = np.array(ts)
    change = [0.0]                                  # relative change of each step from the round-off before it
    for f, c in zip(fresh[:-1], carried[:-1]):
        change.append(f + c * change[-1])
    bound = np.concatenate([[0.0], np.cumsum(np.diff(ts) * np.array(change))]) + 4 * UNIT_ROUNDOFF * np.abs(ts)
    return ts, bound


@PAIRS
def test_compiled_methods_take_scipys_steps(compiled, method):
    """The same steps as scipy's method: as many, the same evaluations (DOP853's three dense-output stages counted
    as scipy counts them), the step times within the round-off bound of step_time_bounds (not bit for bit: the
    error estimate h sum E_j k_j cancels to about 1e-5 of its terms, so summing in numpy's order or ours moves it
    in a late digit on some CPUs and the controller carries that), and the dense output (DOP853's polynomial
    rewritten in powers of x) to SAME_DENSE_TOL everywhere."""
    system, y0, length = looper_system()
    atol = np.full(4, RTOL)
    first = FIRST_STEP_SHARE * float(np.median(np.diff(integrate(system, (0.0, length), y0, method, [], RTOL,
                                                                 atol).t)))
    ours = integrate(system, (0.0, length), y0, compiled, [], RTOL, atol, first_step=first)
    scipy = solve_ivp(system.rhs, (0.0, length), y0, method=method, rtol=RTOL, atol=atol, args=system.args,
                      first_step=first, dense_output=True)
    t, y = ours.sol.t, ours.sol.y.T
    assert ours.status == scipy.status == 0
    assert len(ours.t) < len(t) == len(scipy.t) > 10          # many RK steps per solver step, the same steps
    scipy_t, bound = step_time_bounds(method, system, y0, length, RTOL, atol, first)
    np.testing.assert_array_equal(scipy_t, scipy.t)           # the bound is computed on scipy's very steps
    assert np.max(bound[1:] / scipy_t[1:]) < MEANINGFUL_BOUND
    excess = np.abs(t - scipy.t) - bound
    assert np.all(excess <= 0), f"step {np.argmax(excess)}: {t[np.argmax(excess)]!r} against {scipy.t[np.argmax(excess)]!r}"
    np.testing.assert_allclose(y[:, 0], scipy.y[:, 0], rtol=0, atol=0)
    np.testing.assert_allclose(ours.sol(scipy.t), scipy.y, rtol=0, atol=SAME_DENSE_TOL)
    s = np.linspace(0.0, length, 997)
    np.testing.assert_allclose(ours.sol(s), scipy.sol(s), rtol=0, atol=SAME_DENSE_TOL)
    assert ours.nfev == scipy.nfev


@PAIRS
def test_compiled_methods_choose_scipys_first_step(compiled, method):
    """Without first_step, the initial step is scipy's (Hairer, Norsett & Wanner I, sec. II.4): h from the norms of
    y0, f(y0) and (f(y0 + h0 f(y0)) - f(y0)) / h0, whose difference cancels; bound: the round-off of that difference
    relative to it, through the exponent 1/(q+1), plus a few units of round-off of the step."""
    system, y0, length = looper_system()
    atol = np.full(4, RTOL)
    ours = integrate(system, (0.0, length), y0, compiled, [], RTOL, atol)
    scipy = integrate(system, (0.0, length), y0, method, [], RTOL, atol)
    cls = SCIPY_METHODS[method]
    f0 = system.rhs(0.0, y0, *system.args)
    scale = atol + RTOL * np.abs(y0)
    h0 = 0.01 * rms(y0 / scale) / rms(f0 / scale)
    f1 = system.rhs(0.0, y0 + h0 * f0, *system.args)
    cancel = rms(4 * UNIT_ROUNDOFF * (np.abs(f0) + np.abs(f1)) / scale) / rms((f1 - f0) / scale)
    h = ours.sol.t[1]
    assert abs(h - scipy.t[1]) <= (cancel / (cls.error_estimator_order + 1) + 4 * UNIT_ROUNDOFF) * scipy.t[1]


@PAIRS
def test_events_are_located_as_solve_ivp_locates_them(compiled, method):
    """A terminal event (a pole guard of the sphere's chart, v2 leaving |cos v2| > 0.9) and a non-terminal one
    (the closure plane, armed at once): the same times as scipy's method with the same Event objects."""
    system, y0, length = looper_system()
    ep = system.eargs.copy()
    ep[kb.P_POLE_GUARD] = 0.9
    ep[kb.P_START:kb.P_START + 3] = looper_pair()[0].point(y0[0], y0[1])
    tangent, point = np.empty(3), np.empty(3)
    kc.curve_frame(y0, system.args[0], system.args[1], point, tangent)
    ep[kb.P_DIRECTION:kb.P_DIRECTION + 3] = tangent
    ep[kb.P_CLOSURE_ARM] = -1.0
    ep[kb.P_CLOSURE_OFFSET] = 1e-3
    system = System(system.rhs, system.events, system.advance, system.args, ep, system.n_events)
    results = []
    for name in (compiled, method):
        events = [Event(system, kb.POLE_B, -1), Event(system, kb.CLOSURE, 1, terminal=False)]
        results.append(integrate(system, (0.0, 2 * length), y0, name, events, RTOL, np.full(4, RTOL)))
    ours, scipy = results
    assert [te.size for te in ours.t_events] == [te.size for te in scipy.t_events]
    assert sum(te.size for te in ours.t_events) >= 1
    for a, b in zip(ours.t_events, scipy.t_events):
        np.testing.assert_allclose(a, b, rtol=0, atol=SAME_DENSE_TOL)
    assert ours.status == scipy.status


def test_budget_and_bad_options_are_reported():
    system, y0, length = looper_system()
    res = integrate(system, (0.0, length), y0, COMPILED_RK45, [], RTOL, np.full(4, RTOL), max_nfev=50)
    assert res.status == -1 and res.sol.budget_exceeded and 0 < res.t[-1] < length     # the steps taken are kept
    with pytest.raises(BudgetExceeded):
        integrate(system, (0.0, length), y0, "DOP853", [], RTOL, np.full(4, RTOL), max_nfev=50)
    with pytest.raises(TypeError, match="system"):
        solve_ivp(system.rhs, (0.0, 1.0), y0, method=CompiledRK45, args=system.args)
    with pytest.raises(ValueError, match="forward"):
        solve_ivp(system.rhs, (1.0, 0.0), y0, method=CompiledRK45, args=system.args, system=system)


def test_compiled_rk45_base_state_is_odesolvers():
    """CompiledRK45 sets OdeSolver.__init__'s state itself (its y0 checks on the few floats): oracle OdeSolver.__init__
    on the same arguments, every attribute it sets equal (the same y0 values, t, t_bound, direction, n, status,
    counters; the functions callable and counting nfev), and the same errors for a complex, two-dimensional or
    non-finite y0."""
    from scipy.integrate import OdeSolver
    system, y0, length = looper_system()
    rhs = lambda t, y: system.rhs(t, y, *system.args)      # noqa: E731 (as solve_ivp wraps it with args)
    ours = CompiledRK45(rhs, 0.0, list(y0), length, system=system)
    theirs = OdeSolver(rhs, 0.0, list(y0), length, False)
    assert set(vars(theirs)) <= set(vars(ours))
    for name, value in vars(theirs).items():
        if callable(value):
            assert callable(getattr(ours, name)) or name == "fun_vectorized"
        elif isinstance(value, np.ndarray):
            assert getattr(ours, name).dtype == value.dtype
            np.testing.assert_array_equal(getattr(ours, name), value)
        else:
            assert getattr(ours, name) == value and type(getattr(ours, name)) is type(value), name
    np.testing.assert_array_equal(ours.fun(0.0, y0), theirs.fun(0.0, y0))
    assert ours.nfev == theirs.nfev == 1
    for bad in (y0.astype(complex), y0[None], np.where(np.arange(4) == 1, np.nan, y0)):
        with pytest.raises(ValueError) as want:
            OdeSolver(system.rhs, 0.0, bad, length, False)
        with pytest.raises(ValueError) as got:
            CompiledRK45(system.rhs, 0.0, bad, length, system=system)
        assert str(got.value) == str(want.value)


def test_integrate_records_the_steps_solve_ivp_gives_and_reads_its_watch():
    """integrate's dense output is the record of the engine's steps (spatialkin.ode.record.Steps): oracle solve_ivp's
    own OdeSolution of the same run (dense_output=True: the solver's StepsDense per solver step), the same steps (the
    record's ends are every engine step's, the solver's ends among them) and values to SAME_DENSE_TOL (at a solver
    step's end the OdeSolution takes the earlier polynomial at its end, the record the next one at its start);
    a Watch made once gives the same run as the list of its Events."""
    from spatialkin.ode.solvers import STEPS_PER_CALL, Watch
    system, y0, length = looper_system()
    atol = np.full(4, RTOL)
    options = dict(rtol=RTOL, atol=atol, args=system.args, system=system)
    for steps_per_call in (5, STEPS_PER_CALL):     # several engine calls per record, and integrate's own
        theirs = solve_ivp(system.rhs, (0.0, length), y0, method=CompiledRK45, dense_output=True,
                           steps_per_call=steps_per_call, **options)
        record = Steps()
        ours = solve_ivp(system.rhs, (0.0, length), y0, method=CompiledRK45, record=record,
                         steps_per_call=steps_per_call, **options)
        record.close(0.0, y0)
        assert len(theirs.t) > (10 if steps_per_call == 5 else 1)
        assert len(record.t) == len(record.y) == len(record.h) + 1 == len(record.q) + 1 > len(theirs.t)
        assert np.all(np.diff(record.t) > 0) and np.isin(theirs.t, record.t).all()
        np.testing.assert_array_equal(ours.t, theirs.t)
        np.testing.assert_array_equal(record.y[np.isin(record.t, theirs.t)], theirs.y.T)
        s = np.concatenate([np.linspace(0.0, length, 301), theirs.t])
        np.testing.assert_allclose(record(s), theirs.sol(s), rtol=0, atol=SAME_DENSE_TOL)
        for t in theirs.t:
            np.testing.assert_allclose(record(t), theirs.sol(t), rtol=0, atol=SAME_DENSE_TOL)
    events = [Event(system, kb.POLE_B, -1), Event(system, kb.CLOSURE, 1, terminal=False)]
    watch = Watch(events, system.n_events)
    assert list(watch) == events and watch.modes[kb.POLE_B] == events[0].mode and watch.active.sum() == 2
    one = integrate(system, (0.0, length), y0, COMPILED_RK45, events, RTOL, atol)
    two = integrate(system, (0.0, length), y0, COMPILED_RK45, watch, RTOL, atol)
    assert one.status == two.status and one.nfev == two.nfev
    for a, b in zip(one.t_events + one.y_events, two.t_events + two.y_events):
        np.testing.assert_array_equal(a, b)
    with pytest.raises(ValueError, match="twice"):
        Watch([events[0], events[0]], system.n_events)


def test_a_record_keeps_no_call_that_ends_where_the_last_one_did():
    """An engine call without a step, or ending where the last kept one ended, adds nothing (solve_ivp keeps no
    interpolant for such a solver step); the rest join end to start. Oracle: the rule written out on made-up
    steps of y = t (polynomial q = 1 in x, h the step)."""
    def call(ts):
        ts = np.array(ts, dtype=float)
        return ts, ts[:, None] * np.ones((1, 4)), np.diff(ts), np.ones((len(ts) - 1, 4, 1))
    record = Steps()
    for ts in ([0.0, 0.5, 1.0], [1.0], [0.5, 1.0], [1.0, 2.0], [2.0, 3.0, 4.0]):
        record.add(*call(ts))
    record.close(0.0, np.zeros(4))
    np.testing.assert_array_equal(record.t, [0.0, 0.5, 1.0, 2.0, 3.0, 4.0])
    np.testing.assert_array_equal(record.h, [0.5, 0.5, 1.0, 1.0, 1.0])
    np.testing.assert_allclose(record(np.array([0.25, 1.5, 3.75])), np.array([[0.25, 1.5, 3.75]] * 4), rtol=1e-15)
    empty = Steps().close(2.0, np.arange(4.0))
    np.testing.assert_array_equal(empty(7.0), np.arange(4.0))


@pytest.mark.parametrize("method", ["RK23", "RK45", "DOP853", "Radau"])
def test_a_solve_ivp_result_converted_once_evaluates_as_its_dense_output(method):
    """Steps.of_solution: the record of a solve_ivp method's run evaluates as its OdeSolution (RK23's and RK45's Q as
    they are, DOP853's F rewritten in powers of x: to SAME_DENSE_TOL; Radau's kept as it is: the same values)."""
    system, y0, length = looper_system()
    res = solve_ivp(system.rhs, (0.0, length), y0, method=method, rtol=RTOL, atol=RTOL, args=system.args,
                    dense_output=True)
    record = Steps.of_solution(res, method)
    assert record.compiled == (method != "Radau")
    np.testing.assert_array_equal(record.t, res.t)
    s = np.linspace(0.0, length, 503)
    np.testing.assert_allclose(record(s), res.sol(s), rtol=0, atol=SAME_DENSE_TOL)


def test_integrate_over_an_empty_span_is_solve_ivps():
    """An empty span (t0 = t_bound: no step of the method): integrate's res.t and res.y are solve_ivp's, and its
    record holds the start alone (its dense output is y0 at every time, as solve_ivp's ConstantDenseOutput)."""
    system, y0, _ = looper_system()
    atol = np.full(4, RTOL)
    ours = integrate(system, (0.0, 0.0), y0, COMPILED_RK45, [], RTOL, atol)
    theirs = solve_ivp(system.rhs, (0.0, 0.0), y0, method=CompiledRK45, rtol=RTOL, atol=atol, args=system.args,
                       system=system, dense_output=True)
    np.testing.assert_array_equal(ours.t, theirs.t)
    np.testing.assert_array_equal(ours.y, theirs.y)
    np.testing.assert_array_equal(ours.sol(0.0), theirs.sol(0.0))
    np.testing.assert_array_equal(ours.sol(0.0), y0)
