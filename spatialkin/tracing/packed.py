"""A traced curve's dense output packed into flat arrays, for the compiled distance kernels (spatialkin.kernels.near).

``packed(sol)`` reads a TracedSolution's spans, their segments' charts and scipy OdeSolutions, and each step's
dense output (CompiledRK45's StepsDense, or solve_ivp's DOP853 where the compiled method handed over) into the
tables kernels.near documents, once per curve (a curve does not change). A curve that is not a plain traced one
(a closed form, a jump across a node or an apex, a re-measured segment, another solve_ivp method) has no table:
None, and the callers use the dense output's Python methods.
"""
import weakref

import numpy as np
from scipy.integrate import OdeSolution
from scipy.integrate._ivp.rk import Dop853DenseOutput   # scipy's DOP853 step polynomial (no public name)

from ..kernels import near as kn
from .dense import TracedSolution
from .ode import StepsDense

#: The tables made so far, per dense output (dropped with it).
_TABLES = weakref.WeakKeyDictionary()
#: What _TABLES holds for a curve without a table (None would read as "not packed yet").
_NO_TABLE = ()


def packed(sol):
    """The tables of kernels.near for the dense output sol (a tuple of 15 arrays), made once per curve, or None
    when sol is not a plain traced curve (see the module docstring)."""
    if not isinstance(sol, TracedSolution):
        return None
    table = _TABLES.get(sol)
    if table is None:
        table = _TABLES[sol] = _pack(sol) or _NO_TABLE
    return table or None


def _pack(sol):
    """The tables for a TracedSolution, or None (see packed)."""
    spans = sol.spans
    if any(np.any(span.seg.normal) for span in spans):
        return None                        # a jump across a node or an apex: straight chords, not a solver
    charts = [[np.asarray(getattr(span.seg, side), dtype=float) for span in spans] for side in ("a", "b")]
    if any(len({len(c) for c in side}) > 1 for side in charts):
        return None                        # charts of different layouts (never met: one surface, one kind)
    ode_t, ode_off, ode_first, kinds, pieces = [], [0], [], [], []
    for span in spans:
        ode = span.seg.sol
        if not isinstance(ode, OdeSolution) or not ode.ascending or ode.side != "left":
            return None                    # re-measured (RemappedStates), or a method other than ours and DOP853
        ode_first.append(len(kinds))
        for dense in ode.interpolants:
            piece = _piece(dense)
            if piece is None:
                return None
            kinds.append(piece[0])
            pieces.append(piece[1:])
        ode_t.append(np.asarray(ode.ts, dtype=float))
        ode_off.append(ode_off[-1] + len(ode.ts))
    pt_off = np.cumsum([0] + [len(piece[0]) for piece in pieces])
    pt, ph, py, pc = (np.concatenate(parts) for parts in zip(*pieces))
    lo, flip, shift, sign = (np.array(x, dtype=float) for x in zip(*((span.lo, span.flip, span.shift, span.seg.sign)
                                                                     for span in spans)))
    return (lo, flip, shift, sign, np.stack(charts[0]), np.stack(charts[1]), np.concatenate(ode_t),
            np.array(ode_off, dtype=np.int64), np.array(ode_first, dtype=np.int64), np.array(kinds, dtype=np.int64),
            pt_off.astype(np.int64), pt, ph, py, pc)


def _piece(dense):
    """(kind, start times (m,), lengths (m,), start states (m, 4), coefficients (m, 4, 7)) of one step's dense
    output (the last row of each a filler: m times bound m - 1 polynomials), or None for another kind."""
    if isinstance(dense, StepsDense) and len(dense.ts) >= 2:
        m = len(dense.ts)
        coef = np.zeros((m, 4, kn.DOP853_POWER))
        coef[:m - 1, :, :4] = dense.qs
        return (kn.RK45_STEPS, np.asarray(dense.ts, dtype=float), np.append(dense.hs[:m - 1], 0.0),
                np.asarray(dense.ys, dtype=float), coef)
    if isinstance(dense, Dop853DenseOutput) and dense.F.shape == (kn.DOP853_POWER, 4):
        coef = np.zeros((2, 4, kn.DOP853_POWER))
        coef[0] = dense.F.T
        return (kn.DOP853, np.array([dense.t_old, dense.t], dtype=float), np.array([dense.h, 0.0]),
                np.stack([dense.y_old, np.zeros(4)]), coef)
    return None
