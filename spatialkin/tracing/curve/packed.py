"""A traced curve's dense output as flat tables, for the compiled distance kernels (spatialkin.kernels.curve.near).

``pack(spans)`` reads a TracedSolution's spans, their segments' charts and the records of their steps
(spatialkin.ode.record.Steps: step ends, states, lengths and polynomials, as the engine wrote them) into the tables
kernels.curve.near documents (TracedSolution.table makes them once per curve). A traced curve none of whose spans
the tables can hold has none (None); a span they cannot hold (a jump across a node or an apex, a solve_ivp method
without polynomial steps) is marked so, and a point on it is evaluated by the dense output's Python path.
"""
import numpy as np

from ...ode.record import Steps
from ..march.arclength import RemappedStates


def pack(spans):
    """The tables of kernels.curve.near for a traced curve's spans (a tuple of 12 arrays), or None when they hold
    none of them (see the module docstring)."""
    records, held, remap_off, remap_new, remap_old = [], [], [0], [], []
    for span in spans:
        ode = span.seg.sol
        if isinstance(ode, RemappedStates):     # a re-measured segment: arc length -> solver time first
            remap_new.append(ode.t_new)
            remap_old.append(ode.t_old)
            ode = ode.sol
        remap_off.append(remap_off[-1] + (len(remap_new[-1]) if ode is not span.seg.sol else 0))
        # (a jump across a node or an apex, a solve_ivp method without polynomial steps: not held, left to Python)
        own = isinstance(ode, Steps) and ode.compiled and len(ode.t) >= 2 and not span.seg.jump
        held.append(own)
        if own:
            records.append(ode)
    if not records:
        return None
    charts_a = np.array([span.seg.a for span in spans], dtype=float)
    charts_b = np.array([span.seg.b for span in spans], dtype=float)
    if charts_a.ndim != 2 or charts_b.ndim != 2:
        return None          # charts of different layouts (never met: one surface keeps its kind)
    t_off, p_off = [0], [0]
    for own, span in zip(held, spans):
        m = len(_record(span.seg.sol).t) if own else 0
        t_off.append(t_off[-1] + m)
        p_off.append(p_off[-1] + max(m - 1, 0))
    numbers = np.array([x for span, own in zip(spans, held)
                        for x in (span.lo, span.flip, span.shift, span.seg.sign, own)], dtype=float)
    return (numbers.reshape(len(spans), 5), charts_a, charts_b, np.array(t_off, dtype=np.int64),
            np.array(p_off, dtype=np.int64), _joined([r.t for r in records], (0,)),
            _joined([r.y for r in records], (0, 4)), _joined([r.h[:len(r.t) - 1] for r in records], (0,)),
            _joined(_widened([r.q[:len(r.t) - 1] for r in records]), (0, 4, 4)),
            np.array(remap_off, dtype=np.int64), _joined(remap_new, (0,)), _joined(remap_old, (0,)))


def _record(ode):
    """The Steps under a segment's dense output (a re-measured segment's RemappedStates reads one)."""
    return ode.sol if isinstance(ode, RemappedStates) else ode


def _widened(qs):
    """Dense-output coefficient arrays (m, n, c) of the compiled methods, padded with zero columns to the widest c
    (RK45's 4 beside DOP853's 7 where a compiled-rk45 branch handed over to the compiled DOP853): a zero coefficient
    adds nothing to spatialkin.kernels.ode.rk.dense_state's sum, so the states are the same to the bit."""
    width = max((q.shape[2] for q in qs), default=0)
    return [q if q.shape[2] == width else np.concatenate([q, np.zeros(q.shape[:2] + (width - q.shape[2],))], axis=2)
            for q in qs]


def _joined(arrays, empty):
    """The arrays concatenated (C-contiguous floats; one such array itself, not copied), or an empty array of shape
    `empty` when there are none."""
    if len(arrays) == 1 and arrays[0].dtype == np.float64 and arrays[0].flags.c_contiguous:
        return arrays[0]
    return np.ascontiguousarray(np.concatenate(arrays), dtype=float) if arrays else np.empty(empty)
