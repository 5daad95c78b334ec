"""Every curve integrated by solve_ivp: the compiled engine as an OdeSolver, events written once.

``CompiledRK45`` is a ``scipy.integrate.OdeSolver``: ``solve_ivp(fun, span, y0, method=CompiledRK45,
system=system, watch=events, ...)``. One of its steps runs many RK45 steps inside compiled code
(spatialkin.kernels.ode.rk) and stops at the events it watches: each crossing is located on the step's dense output
in compiled code, as solve_ivp locates events for its own methods (to 4 ulp), and the integration ends at a
terminal one; ``integrate`` hands them back as solve_ivp's t_events and y_events. The steps are scipy RK45's.
``CompiledDOP853`` (the library's default, method name COMPILED) is the same with scipy DOP853's steps.

A ``System`` carries a curve's jitted kernels: the right-hand side in solve_ivp's form, the vector of its
event values, and ``advance`` (the engine bound to both). An ``Event`` is one entry of that vector as solve_ivp
wants an event function (``terminal``, ``direction``), so the same jitted event values serve CompiledRK45 and
solve_ivp's own methods (DOP853 for the hard cases).

References
----------
scipy.integrate._ivp.base.OdeSolver and DenseOutput (the interface), ivp.solve_ivp (event location).
"""
import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import DenseOutput, OdeSolver, solve_ivp

from ..kernels.ode import rk
from .record import Steps

#: Most engine steps one CompiledRK45 or CompiledDOP853 step takes (solve_ivp's per-step Python work is paid once
#: per this many).
STEPS_PER_CALL = 256
#: The compiled methods' names in settings and in method= arguments: DOP853's steps (the library's default) and
#: RK45's.
COMPILED = "compiled"
COMPILED_RK45 = "compiled-rk45"
#: Evaluation budget standing for none.
NO_BUDGET = 2 ** 62
#: CompiledRK45's messages when it stops short (solve_ivp status -1).
STEP_FAILED_MESSAGE = "Required step size is less than spacing between numbers."
BUDGET_MESSAGE = "The evaluation budget ran out."


class BudgetExceeded(Exception):
    """An integration used up its right-hand-side evaluations."""


@dataclass(frozen=True)
class System:
    """The jitted kernels of one curve and their parameters.

    Attributes
    ----------
    rhs : callable
        ``rhs(t, y, *args)`` -> dy/dt (n,), for solve_ivp's methods.
    events : callable
        ``events(t, y, args, eargs, active, out)``: the event values (n_events,) into out.
    advance : callable
        spatialkin.kernels.ode.rk.advance bound to the system's kernels:
        ``advance(t, y, f, h, fresh, t_bound, rtol, atol, max_step, max_steps, max_nfev, g, active, directions,
        modes, args, eargs, method)``.
    args, eargs : tuple or ndarray
        Parameters of the right-hand side and of the events.
    n_events : int
    """
    rhs: object
    events: object
    advance: object
    args: tuple
    eargs: object
    n_events: int

    def event_values(self, t, y, active, out=None):
        """The values (n_events,) of the active events at (t, y) (into out when given)."""
        out = np.empty(self.n_events) if out is None else out
        self.events(t, np.ascontiguousarray(y, dtype=float), self.args, self.eargs, active, out)
        return out


class Event:
    """Event `index` of a System as a solve_ivp event function (terminal by default).

    ``level`` ('before' or 'after', the compiled method only) makes it a level instead of a crossing: the
    integration ends at the last step before the one whose end reaches zero in the event's direction (that
    step dropped), or at the end of the first such step (spatialkin.kernels.ode.rk.LEVEL_BEFORE, LEVEL_AFTER).
    ``probed`` (the compiled method; solve_ivp's methods check step ends only) also evaluates a terminal crossing
    or a level 'before' at interior points of each step (rk.TERMINAL_PROBED, LEVEL_BEFORE_PROBED). ``system`` may be
    pointed at another System of the same events between two integrations (a branch's segments reuse their
    Events)."""

    def __init__(self, system, index, direction, terminal=True, level=None, probed=False):
        if level not in (None, "before", "after"):
            raise ValueError(f"level must be None, 'before' or 'after', got {level!r}")
        if probed and (level == "after" or (level is None and not terminal)):
            raise ValueError("probed is for a terminal crossing or a level 'before'")
        self.system, self.index, self.direction = system, int(index), float(direction)
        self.terminal = bool(terminal or level)
        self.level = level
        self.probed = bool(probed)
        # its entry in spatialkin.kernels.ode.rk.advance's modes
        if level is not None:
            self.mode = rk.LEVEL_AFTER if level == "after" else (rk.LEVEL_BEFORE_PROBED if probed else rk.LEVEL_BEFORE)
        else:
            self.mode = rk.TERMINAL_PROBED if probed else (rk.TERMINAL if self.terminal else rk.CROSSING)
        self._only = self._out = None        # work arrays, made at the first call (solve_ivp's methods only)

    def __call__(self, t, y, *_):
        system = self.system
        if self._only is None:
            self._only = np.zeros(system.n_events, dtype=np.bool_)
            self._only[self.index] = True
            self._out = np.empty(system.n_events)
        system.events(t, y, system.args, system.eargs, self._only, self._out)
        return self._out[self.index]


class Watch(tuple):
    """The Events a CompiledRK45 watches (a tuple of them, in order) with the arrays rk.advance takes for them:
    made once for Events that several integrations share (a branch's segments), so that each CompiledRK45 reads
    them instead of filling its own.

    Attributes
    ----------
    active : ndarray (n_events,) of bool
        The watched entries of the System's event vector.
    directions : ndarray (n_events,)
        Each watched event's direction (0 elsewhere).
    modes : ndarray (n_events,) of int64
        Each watched event's mode (Event.mode; 0 elsewhere).
    position : dict
        Event index -> position in the tuple.

    The arrays are read, never written, by the engine; ValueError for an event index given twice.
    """

    def __new__(cls, events, n_events):
        self = super().__new__(cls, events)
        self.active = np.zeros(n_events, dtype=np.bool_)
        self.directions = np.zeros(n_events)
        self.modes = np.zeros(n_events, dtype=np.int64)
        self.position = {}
        for k, event in enumerate(self):
            if event.index in self.position:
                raise ValueError(f"event {event.index} given twice")
            self.position[event.index] = k
            self.active[event.index] = True
            self.directions[event.index] = event.direction
            self.modes[event.index] = event.mode
        return self

    def __getnewargs__(self):
        return tuple(self), len(self.active)


class StepsDense(DenseOutput):
    """Dense output of one CompiledRK45 or CompiledDOP853 step (OdeSolver.dense_output's, for solve_ivp called with
    dense_output=True): the polynomials of each of its engine steps (spatialkin.kernels.ode.rk.dense_state; step
    lengths hs: the last polynomial may reach past a terminal event's time ts[-1])."""

    def __init__(self, ts, ys, hs, qs):
        super().__init__(ts[0], ts[-1])
        self.ts, self.ys, self.hs, self.qs = ts, ys, hs, qs

    def _call_impl(self, t):
        if np.ndim(t) == 0:
            return rk.dense_at(self.ts, self.ys, self.hs, self.qs, float(t))
        tt = np.atleast_1d(np.asarray(t, dtype=float)).ravel()
        out = np.empty((tt.size, self.ys.shape[1]))
        rk.dense_many(self.ts, self.ys, self.hs, self.qs, tt, out)
        return out.T


class CompiledRK45(OdeSolver):
    """scipy's RK45 run in compiled code, many steps per solver step, stopping at the events it is given.

    Options (through solve_ivp): ``system`` (System, required); ``watch``: the Events to watch (a sequence, or a
    Watch made once for them; given to this solver, not as solve_ivp's events: each crossing is located in compiled
    code on the step's dense output, as solve_ivp locates events, and recorded in the record; at a terminal one the
    integration ends there); ``record``: the Steps (spatialkin.ode.record) the engine's steps and located events are
    written to; ``rtol``, ``atol``, ``max_step``, ``first_step``, ``max_nfev`` (past it the steps taken are kept and
    the next solver step fails with BUDGET_MESSAGE, record.budget_exceeded set), ``steps_per_call``. Forward in t
    only. ``integrate`` reads solve_ivp's t_events and y_events and its dense output from the record.
    """
    #: The engine's method (spatialkin.kernels.ode.rk.RK45 or DOP853).
    METHOD = rk.RK45

    def __init__(self, fun, t0, y0, t_bound, vectorized=False, system=None, watch=(), record=None, rtol=1e-3,
                 atol=1e-6, max_step=np.inf, first_step=None, max_nfev=None, steps_per_call=STEPS_PER_CALL,
                 **extraneous):
        if extraneous:
            raise TypeError(f"CompiledRK45 got unexpected options {sorted(extraneous)}")
        if not isinstance(system, System):
            raise TypeError("CompiledRK45 needs system=spatialkin.ode.solvers.System(...)")
        self._base_state(fun, t0, y0, t_bound, vectorized)
        if self.direction < 0:
            raise ValueError("CompiledRK45 integrates forward in t only (t_bound < t0)")
        if not (max_step > 0):
            raise ValueError(f"max_step must be positive, got {max_step!r}")
        self.system = system
        self.rtol = float(rtol)
        self.atol = (atol if isinstance(atol, np.ndarray) and atol.shape == (self.n,) and atol.dtype == float
                     else np.full(self.n, atol, dtype=float))
        self.max_step = float(max_step)
        self.max_nfev = NO_BUDGET if max_nfev is None else int(max_nfev)
        self.steps_per_call = int(steps_per_call)
        self.record = Steps() if record is None else record
        plan = watch if isinstance(watch, Watch) else Watch(watch, system.n_events)
        self.active, self.directions, self.modes, self.position = plan.active, plan.directions, plan.modes, \
            plan.position
        self.y = np.array(self.y, dtype=float)
        self.f = np.empty(self.n)
        self.g = system.event_values(self.t, self.y, self.active)
        self.h = 0.0 if first_step is None else float(first_step)
        self.fresh = True
        self.failed = None
        self._dense = None

    def _base_state(self, fun, t0, y0, t_bound, vectorized):
        """OdeSolver.__init__'s state (its attributes, the same values; a test compares them), with its checks of
        y0 (real, one-dimensional, finite) made on a real vector's few floats instead of by numpy's generic
        dtype tests: OdeSolver.__init__ costs a few microseconds per segment. fun is never called by this method
        (the compiled kernels evaluate the right-hand side): fun and fun_single count nfev, fun_vectorized is None
        and vectorized is recorded but not used (unlike OdeSolver, which wraps fun both ways)."""
        if not (type(y0) is np.ndarray and y0.dtype == np.float64):      # (a float array is used as it is)
            y0 = np.asarray(y0)
            if y0.dtype.kind == "c":
                raise ValueError("`y0` is complex, but the chosen solver does not support integration in a complex "
                                 "domain.")
            y0 = y0.astype(float, copy=False)
        if y0.ndim != 1:
            raise ValueError("`y0` must be 1-dimensional.")
        for value in y0.tolist():
            if not math.isfinite(value):
                raise ValueError("All components of the initial state `y0` must be finite.")

        def fun_counted(t, y):
            self.nfev += 1
            return np.asarray(fun(t, y), dtype=float)

        self.t_old = None
        self.t = t0
        self._fun, self.y = fun, y0
        self.t_bound = t_bound
        self.vectorized = vectorized
        self.fun = self.fun_single = fun_counted
        self.fun_vectorized = None
        self.direction = np.sign(t_bound - t0) if t_bound != t0 else 1
        self.n = self.y.size
        self.status = "running"
        self.nfev = self.njev = self.nlu = 0

    def _step_impl(self):
        if self.failed is not None:
            return False, self.failed
        y = self.y.copy()
        status, t, h, nfev, ts, ys, hs, qs, hits, hit_ts, hit_ys = self.system.advance(
            self.t, y, self.f, self.h, self.fresh, self.t_bound, self.rtol, self.atol, self.max_step,
            self.steps_per_call, self.max_nfev - self.nfev, self.g, self.active, self.directions, self.modes,
            self.system.args, self.system.eargs, self.METHOD)
        self.fresh = False
        self.nfev += nfev
        record = self.record
        if status in (rk.STEP_FAILED, rk.BUDGET):
            self.failed = STEP_FAILED_MESSAGE if status == rk.STEP_FAILED else BUDGET_MESSAGE
            record.budget_exceeded = status == rk.BUDGET
            if len(ts) < 2:
                return False, self.failed
        for index, t_e, y_e in zip(hits.tolist(), hit_ts.tolist(), hit_ys):
            record.events.append((self.position[index], t_e, y_e))
            if self.modes[index] != rk.CROSSING:
                self.t_bound = t_e           # the integration ends at a terminal event (solve_ivp: 'finished')
        self.t_old, self.t, self.y, self.h = self.t, t, y, h
        record.add(ts, ys, hs, qs)
        self._dense = (ts, ys, hs, qs)
        return True, None

    def _dense_output_impl(self):
        return StepsDense(*self._dense)


class CompiledDOP853(CompiledRK45):
    """CompiledRK45 with scipy DOP853's steps (its tableau, error norm, step control and dense output; the same
    options, events and log): fewer, longer steps at the same rtol."""
    METHOD = rk.DOP853


#: The OdeSolver of each compiled method's name.
COMPILED_SOLVERS = {COMPILED: CompiledDOP853, COMPILED_RK45: CompiledRK45}


def integrate(system, t_span, y0, method, events, rtol, atol, max_step=np.inf, max_nfev=None, first_step=None):
    """solve_ivp on a System with the given Events, its dense output ``res.sol`` the record of its steps (Steps):
    by CompiledDOP853 (method COMPILED) or CompiledRK45 (COMPILED_RK45), which write the record as they step, their
    located events returned as solve_ivp returns its own (t_events, y_events, status 1 at a terminal one; past
    max_nfev evaluations status -1 with the steps taken and res.sol.budget_exceeded), or by a solve_ivp method
    (dense_output=True, its result converted once: Steps.of_solution) whose right-hand side raises BudgetExceeded
    past max_nfev evaluations (level events are the compiled methods')."""
    solver = COMPILED_SOLVERS.get(method)
    if solver is None:
        if any(event.level for event in events):
            raise ValueError(f"level events need the compiled method, not {method!r}")
        res = solve_ivp(budgeted(system.rhs, max_nfev), t_span, y0, method=method, rtol=rtol, atol=atol,
                        dense_output=True, events=events, args=system.args, max_step=max_step, first_step=first_step)
        res.sol = Steps.of_solution(res, method)
        return res
    record = Steps()
    res = solve_ivp(system.rhs, t_span, y0, method=solver, rtol=rtol, atol=atol, args=system.args,
                    max_step=max_step, first_step=first_step, system=system, watch=events, record=record,
                    max_nfev=max_nfev)
    res["sol"] = record.close(t_span[0], y0)
    n = len(y0)
    no_t, no_y = np.empty(0), np.empty((0, n))        # the events not met share these (empty: nothing to change)
    t_events, y_events = [no_t] * len(events), [no_y] * len(events)
    if record.events:
        met = {}
        for k, t_e, y_e in record.events:
            met.setdefault(k, []).append((t_e, y_e))
        for k, hits in met.items():
            t_events[k] = np.array([t_e for t_e, _ in hits])
            y_events[k] = np.array([y_e for _, y_e in hits]).reshape(len(hits), n)
        if res["status"] == 0 and events[record.events[-1][0]].terminal:
            res["status"], res["message"] = 1, "A termination event occurred."
    res["t_events"], res["y_events"] = t_events, y_events
    return res


def budgeted(rhs, limit=None):
    """rhs wrapped so that it raises BudgetExceeded after `limit` calls (None: no limit)."""
    if limit is None:
        return rhs
    calls = [0]

    def wrapped(t, y, *args):
        calls[0] += 1
        if calls[0] > limit:
            raise BudgetExceeded(f"{limit} right-hand-side evaluations")
        return rhs(t, y, *args)
    return wrapped
