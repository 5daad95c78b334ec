"""Following a one-parameter family F(y) = 0 along its input coordinate, by arc length (solve_ivp with the
compiled engine, spatialkin.ode.solvers.CompiledDOP853 or CompiledRK45, or any solve_ivp method, with the same
jitted events).

A mechanism's configuration curve: y holds the unknowns and the input (a crank angle). The curve is traced
from an assembled state in the direction where the input grows, over one period of the input (a full
turn: the curve comes back to the start state shifted by the period), or, when the input reverses at lock
positions (turning points of the input along the curve, where the Jacobian in the unknowns is singular),
through them until the closed curve returns to the start. The lock positions are located by events on
the input's rate along the curve.

The right-hand side is any jitted ``rhs(s, y, *args, sign, pullback)`` whose tangent orientation is
intrinsic (``spatialkin.kernels.continuation.implicit``), so the tangent carries through turning points; its events and
the engine bound to it are the system's kernels (``CurveKernels``, spatialkin.kernels.continuation.follow).
"""
import math
from dataclasses import dataclass, field

import numpy as np

from .._lib import warm
from ..kernels.continuation import follow as kf
from ..ode.solvers import COMPILED, BudgetExceeded, Event, System, integrate
from ..tracing.curve.result import TracingError
from ..tracing.curve.status import MAX_LENGTH, SINGULAR

#: Integration tolerance of the traced curve (a predictor: exact states come from Newton at fixed input).
TRACE_RTOL = 1e-10
#: Right-hand-side evaluations allowed for one arc (between two events): every call ends in bounded time.
ARC_MAX_EVALUATIONS = 2_000_000
#: States within this distance (units of y) count as the same configuration when the curve closes.
CLOSE_TOL = 1e-6
#: Rate of the input along the curve below which a start state counts as a lock position.
LOCK_RATE = 1e-9
#: Most lock positions followed on one closed curve; most periods of the input before it closes.
MAX_LOCKS = 16
MAX_PERIODS = 6
#: Samples per unit arc length of the dense representation used for predictions (and at least this many).
SAMPLES_PER_LENGTH = 256
MIN_SAMPLES = 2048


class ContinuationError(TracingError, ValueError):
    """A configuration curve that cannot be traced or solved: a TracingError (``where``: the state, ``status``
    from spatialkin.tracing.curve.status), and a ValueError as the mechanisms raise for input they cannot move."""


@dataclass
class Cycle:
    """The traced closed configuration curve.

    Attributes
    ----------
    pieces : list of (s0, s1, OdeSolution)
        Consecutive arcs; the input is monotonic on each.
    locks : list of ndarray
        States where the input reverses (in the order met from the start).
    period : float
        Input period after which the curve closes (0 when it closes by reversing at locks).
    start : ndarray
        The start state.
    index : int
        Position of the input in y.
    """
    pieces: list
    locks: list
    period: float
    start: np.ndarray
    index: int
    lock_s: list = field(default_factory=list)

    @property
    def length(self):
        return self.pieces[-1][1]

    @property
    def full_turn(self):
        return not self.locks

    def __call__(self, s):
        """States (N, n+1) at arc lengths s (N,) in [0, length] (within round-off of its ends: clamped)."""
        s = np.asarray(s, dtype=float)
        slack = 1e-9 * max(1.0, self.length)
        if np.any(~np.isfinite(s)) or np.any((s < -slack) | (s > self.length + slack)):
            raise ValueError(f"s must lie in [0, {self.length:.12g}]")
        s = np.clip(s, 0.0, self.length)
        out = np.empty((s.size, self.start.size))
        for s0, s1, sol in self.pieces:
            mask = (s >= s0) & (s <= s1)
            if mask.any():
                out[mask] = sol(s[mask]).T
        return out

    def branch_samples(self):
        """(input (M,), states (M, n+1)) along the arc through the start on which the input is monotonic
        increasing: the whole curve for a full turn, else the arc between the two locks around the start."""
        m = max(MIN_SAMPLES, int(SAMPLES_PER_LENGTH * self.length))
        if self.full_turn:
            s = np.linspace(0.0, self.length, m)
        else:
            first, last = self.lock_s[0], self.lock_s[-1]
            span = first + self.length - last
            s = np.mod(last + np.linspace(0.0, span, m), self.length)
        ys = self(s)
        return ys[:, self.index], ys


@dataclass(frozen=True)
class CurveKernels:
    """The jitted kernels of a configuration curve (spatialkin.kernels.continuation.follow): ``rhs(s, y, *args, sign,
    pullback)``, and the events and the compiled engine bound to it (``events``, ``advance``)."""
    rhs: object
    events: object
    advance: object


#: Event of spatialkin.kernels.continuation.follow that ends an arc, checked in this order (a lock first).
OUTCOME_ORDER = (kf.RATE, kf.LEVEL_TARGET, kf.LEVEL_START)
#: No event: the arc reached max_length.
REACHED_END = -1


def _arc(kernels, args, y, s, max_length, sign, index, levels, watch, directions, rtol, method):
    """One arc by solve_ivp up to the first event: (end, dense output, end state, the event or REACHED_END)."""
    system = System(kernels.rhs, kernels.events, kernels.advance, (*args, sign, 1.0),
                    np.array([index, levels[0], levels[1]], dtype=float), kf.COUNT)
    events = [Event(system, e, directions[e]) for e in range(kf.COUNT) if watch[e]]
    try:
        res = integrate(system, (s, max_length), y, method, events, rtol, rtol, max_nfev=ARC_MAX_EVALUATIONS)
    except BudgetExceeded as err:
        raise ContinuationError(f"tracing the configuration curve stalled after arc length {s:.6g}: {err}", y) from None
    if res.status < 0:
        raise ContinuationError(f"tracing the configuration curve failed after arc length {res.t[-1]:.6g}: "
                                f"{res.message}", res.y[:, -1])
    fired = {event.index for event, te in zip(events, res.t_events) if te.size}
    outcome = next((e for e in OUTCOME_ORDER if e in fired), REACHED_END)
    return res.t[-1], res.sol, res.y[:, -1], outcome


def trace_cycle(kernels, y0, args, period, max_length, index=-1, rtol=TRACE_RTOL, method=COMPILED):
    """Trace the closed configuration curve of rhs through y0 (see the module docstring).

    Parameters
    ----------
    kernels : CurveKernels
        ``rhs(s, y, *args, sign, pullback)`` and the events and engine bound to it, jitted.
    y0 : ndarray (n+1,)
        A state on the curve.
    args : tuple
        The system's parameters.
    period : float
        Period of the input (2 pi for one crank turn; larger when geared inputs need more turns).
    max_length : float
        Arc length after which tracing stops with an error (the curve is bounded, so this is a budget).
    index : int
        Position of the input in y.
    rtol : float
        Relative and absolute tolerance of the integration.
    method : str
        'compiled' (spatialkin.ode.solvers.CompiledDOP853: scipy DOP853's steps in compiled code), 'compiled-rk45'
        (CompiledRK45: RK45's) or a solve_ivp method.

    Returns
    -------
    Cycle

    Raises
    ------
    ContinuationError
        When y0 is itself a lock position, or the curve does not close within max_length.
    """
    warm.refresh()
    y0 = np.asarray(y0, dtype=float)
    index = index % y0.size
    rate = kernels.rhs(0.0, y0, *args, 1.0, 0.0)[index]
    if abs(rate) < LOCK_RATE:
        raise ContinuationError("the start state is a lock position (the input cannot move there)", y0, SINGULAR)
    sign = 1.0 if rate > 0 else -1.0
    shift = np.zeros_like(y0)
    shift[index] = period

    pieces, locks, lock_s = [], [], []
    s, y, lock_direction, turns, skip_back = 0.0, y0, -1.0, 1, True
    while True:
        levels = np.array([y0[index] + turns * period, y0[index]])
        # returning to the start needs a lock first; never re-fire where it fired
        watch = np.array([True, not skip_back, True])
        directions = np.array([1.0, 1.0, lock_direction])
        skip_back = False
        end, sol, y, outcome = _arc(kernels, args, y, s, max_length, sign, index, levels, watch, directions,
                                    rtol, method)
        pieces.append((s, end, sol))
        if outcome == REACHED_END:
            raise ContinuationError(f"the configuration curve did not close within arc length {max_length:.6g}",
                                    y, MAX_LENGTH)
        if outcome == kf.RATE:
            locks.append(y)
            lock_s.append(end)
            if len(locks) > MAX_LOCKS:
                raise ContinuationError(f"more than {MAX_LOCKS} lock positions on one configuration curve", y)
            lock_direction = -lock_direction
        elif outcome == kf.LEVEL_TARGET:
            if np.max(np.abs(y - y0 - turns * shift)) <= CLOSE_TOL:
                return Cycle(pieces, locks, turns * period, y0, index, lock_s)
            turns += 1
            if turns > MAX_PERIODS:
                raise ContinuationError(f"the configuration curve did not close within {MAX_PERIODS} input periods", y,
                                        MAX_LENGTH)
        elif np.max(np.abs(y - y0)) <= CLOSE_TOL:
            return Cycle(pieces, locks, 0.0, y0, index, lock_s)
        else:
            skip_back = True
        s = end
        if not math.isfinite(s) or s >= max_length:
            raise ContinuationError(f"the configuration curve did not close within arc length {max_length:.6g}",
                                    y, MAX_LENGTH)
