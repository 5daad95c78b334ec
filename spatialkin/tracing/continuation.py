"""Following a one-parameter family F(y) = 0 along its input coordinate, by arc length (solve_ivp, or the
compiled Dormand-Prince segment of spatialkin.kernels.follow with the same events).

A mechanism's configuration curve: y holds the unknowns and the input (a crank angle). The curve is traced
from an assembled state in the direction where the input grows, over one period of the input (a full
turn: the curve comes back to the start state shifted by the period), or, when the input reverses at lock
positions (turning points of the input along the curve, where the Jacobian in the unknowns is singular),
through them until the closed curve returns to the start. The lock positions are located by events on
the input's rate along the curve.

The right-hand side is any jitted ``rhs(s, y, *args, sign, pullback)`` whose tangent orientation is
intrinsic (``spatialkin.kernels.implicit``), so the tangent carries through turning points.
"""
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from ..kernels import follow as kf
from .segments import StepStates

#: Integration tolerance of the traced curve (a predictor: exact states come from Newton at fixed input).
TRACE_RTOL = 1e-10
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
        """States (N, n+1) at arc lengths s (N,) in [0, length]; an s a round-off outside is taken at the
        nearer end (it was left uninitialised: np.empty's garbage)."""
        s = np.clip(np.asarray(s, dtype=float), 0.0, self.length)
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


def _event(fun, direction):
    fun.terminal, fun.direction = True, direction
    return fun


def _solve_ivp_piece(rhs, args, y, s, max_length, sign, index, levels, watch, directions, rtol, method):
    """One arc by solve_ivp up to the first event: (end, dense output, end state, outcome as
    spatialkin.kernels.follow's)."""
    funs = [lambda s, y, *_: y[index] - levels[0], lambda s, y, *_: y[index] - levels[1],
            lambda s, y, *_: rhs(s, y, *args, sign, 0.0)[index]]
    events = [_event(fun if on else lambda s, y, *_: -1.0, direction)
              for fun, on, direction in zip(funs, watch, directions)]
    res = solve_ivp(rhs, (s, max_length), y, method=method, rtol=rtol, atol=rtol, dense_output=True,
                    events=events, args=(*args, sign, 1.0))
    if res.status < 0:
        raise ValueError(f"tracing the configuration curve failed: {res.message}")
    fired = [kf.LEVEL_TARGET + e for e in (2, 0, 1) if res.t_events[e].size]     # a lock first
    return res.t[-1], res.sol, res.y[:, -1], fired[0] if fired else kf.REACHED_END


def _compiled_piece(segment, args, y, s, max_length, sign, index, levels, watch, directions, rtol):
    """One arc by a compiled segment (spatialkin.kernels.follow.follow_segment bound to the rhs)."""
    outcome, ts, ys, hs, qs = segment(y, s, max_length, sign, 1.0, rtol, rtol, index, levels, watch,
                                      directions, *args)
    if outcome == kf.STEP_FAILED:
        raise ValueError("tracing the configuration curve failed: the step size fell below the round-off "
                         f"floor at arc length {ts[-1]:.6g}")
    return ts[-1], StepStates(ts, ys, hs, qs), ys[-1], outcome


def trace_cycle(rhs, y0, args, period, max_length, index=-1, rtol=TRACE_RTOL, method="DOP853", segment=None):
    """Trace the closed configuration curve of rhs through y0 (see the module docstring).

    Parameters
    ----------
    rhs : callable
        ``rhs(s, y, *args, sign, pullback)``, jitted.
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
        solve_ivp's method (when no compiled segment is given).
    segment : callable, optional
        spatialkin.kernels.follow.follow_segment bound to rhs in a jitted wrapper,
        ``segment(y, t0, t_bound, sign, pullback, rtol, atol, index, levels, watch, directions, *args)``:
        the arcs are then integrated by that compiled Dormand-Prince 5(4) (scipy RK45's steps) instead of
        solve_ivp, with the same events.

    Returns
    -------
    Cycle

    Raises
    ------
    ValueError
        When y0 is itself a lock position, or the curve does not close within max_length.
    """
    y0 = np.asarray(y0, dtype=float)
    index = index % y0.size
    rate = rhs(0.0, y0, *args, 1.0, 0.0)[index]
    if abs(rate) < LOCK_RATE:
        raise ValueError("the start state is a lock position (the input cannot move there)")
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
        if segment is None:
            end, sol, y, outcome = _solve_ivp_piece(rhs, args, y, s, max_length, sign, index, levels, watch,
                                                    directions, rtol, method)
        else:
            end, sol, y, outcome = _compiled_piece(segment, args, y, s, max_length, sign, index, levels, watch,
                                                   directions, rtol)
        pieces.append((s, end, sol))
        if outcome == kf.REACHED_END:
            raise ValueError(f"the configuration curve did not close within arc length {max_length:.6g}")
        if outcome == kf.RATE:
            locks.append(y)
            lock_s.append(end)
            if len(locks) > MAX_LOCKS:
                raise ValueError(f"more than {MAX_LOCKS} lock positions on one configuration curve")
            lock_direction = -lock_direction
        elif outcome == kf.LEVEL_TARGET:
            if np.max(np.abs(y - y0 - turns * shift)) <= CLOSE_TOL:
                return Cycle(pieces, locks, turns * period, y0, index, lock_s)
            turns += 1
            if turns > MAX_PERIODS:
                raise ValueError(f"the configuration curve did not close within {MAX_PERIODS} input periods")
        elif np.max(np.abs(y - y0)) <= CLOSE_TOL:
            return Cycle(pieces, locks, 0.0, y0, index, lock_s)
        else:
            skip_back = True
        s = end
        if not math.isfinite(s) or s >= max_length:
            raise ValueError(f"the configuration curve did not close within arc length {max_length:.6g}")
