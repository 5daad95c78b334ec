"""A traced curve's dense output packed into flat arrays, for the compiled distance kernels (spatialkin.kernels.curve.near).

``packed(sol)`` reads a TracedSolution's spans, their segments' charts and scipy OdeSolutions, and each step's
dense output (the compiled methods' StepsDense, or solve_ivp's DOP853 where a solve_ivp method integrated) into the
tables kernels.near documents, once per curve (a curve does not change). A closed form has no table (None), nor a traced
curve none of whose spans the tables can hold; a span they cannot hold (a jump across a node or an apex,
another solve_ivp method) is marked so, and a point whose Newton meets it is left to the
dense output's Python methods.
"""
import weakref

import numpy as np
from scipy.integrate import OdeSolution
from scipy.integrate._ivp.rk import Dop853DenseOutput   # scipy's DOP853 step polynomial (no public name)

from ...kernels.curve import near as kn
from ..march.arclength import RemappedStates
from .dense import TracedSolution
from ...ode.solvers import StepsDense
from ..march.segments import NEWTON_MAX_ITER

#: The tables made so far, per dense output (dropped with it).
_TABLES = weakref.WeakKeyDictionary()
#: The grids of closest() (CurveSolution.grid) made so far, per dense output.
_GRIDS = weakref.WeakKeyDictionary()
#: What _TABLES holds for a curve without a table (None would read as "not packed yet").
_NO_TABLE = ()


def packed(sol):
    """The tables of kernels.near for the dense output sol (a tuple of 20 arrays), made once per curve, or None
    when sol is not a plain traced curve (see the module docstring)."""
    if not isinstance(sol, TracedSolution):
        return None
    table = _TABLES.get(sol)
    if table is None:
        table = _TABLES[sol] = _pack(sol) or _NO_TABLE
    return table or None


def packed_grid(sol, table):
    """(arc lengths (G,), points (G, 3)) of the grid CurveSolution.closest starts from, the same to the bit: by
    kernels.near.curve_points on the tables of sol when they hold every span, else sol.grid(). Made once."""
    grid = _GRIDS.get(sol)
    if grid is None:
        s = sol.grid_s()
        points = np.empty((len(s), 3))
        grid = _GRIDS[sol] = ((s, points) if kn.curve_points(table, sol.closed, sol.length, float(sol.gap_tol),
                                                               NEWTON_MAX_ITER, s, points) else sol.grid())
    return grid


def _pack(sol):
    """The tables for a TracedSolution, or None (see packed)."""
    spans = sol.spans
    ode_t, ode_off, ode_first, kinds, dense_outputs, compiled = [], [0], [], [], [], []
    remap_off, remap_new, remap_old = [0], [], []
    for span in spans:
        ode = span.seg.sol
        if isinstance(ode, RemappedStates):     # a re-measured segment: arc length -> solver time first
            remap_new.append(ode.t_new)
            remap_old.append(ode.t_old)
            ode = ode.sol
        remap_off.append(remap_off[-1] + (len(remap_new[-1]) if ode is not span.seg.sol else 0))
        own = _kinds(ode) if not any(span.seg.normal.tolist()) else None
        compiled.append(own is not None)       # a jump across a node or an apex, another solve_ivp method: not
        ode_first.append(len(kinds))           # held (its points left to Python)
        if own is not None:
            kinds += own
            dense_outputs += ode.interpolants
            ode_t.append(ode.ts)
        ode_off.append(ode_off[-1] + (len(ode.ts) if own is not None else 0))
    if not any(compiled):
        return None
    charts_a = np.array([span.seg.a for span in spans], dtype=float)
    charts_b = np.array([span.seg.b for span in spans], dtype=float)
    if charts_a.ndim != 2 or charts_b.ndim != 2:
        return None          # charts of different layouts (never met: one surface keeps its kind)
    steps = [dense for dense in dense_outputs if isinstance(dense, StepsDense)]
    dop = [dense for dense in dense_outputs if not isinstance(dense, StepsDense)]
    pt_off, poly_first, n_times, n_polys, n_dop = [0], [], 0, 0, 0
    for dense in dense_outputs:
        if isinstance(dense, StepsDense):
            poly_first.append(n_polys)
            n_times += len(dense.ts)
            n_polys += len(dense.ts) - 1
        else:
            poly_first.append(n_dop)
            n_dop += 1
        pt_off.append(n_times)
    numbers = np.array([x for span, held in zip(spans, compiled)
                        for x in (span.lo, span.flip, span.shift, span.seg.sign, held)], dtype=float)
    ints = (np.array(x, dtype=np.int64) for x in (ode_off, ode_first, kinds, pt_off, poly_first))
    return (numbers.reshape(len(spans), 5), charts_a, charts_b, _joined(ode_t, (0,)), *ints,
            _joined([d.ts for d in steps], (0,)), _joined([d.hs[:len(d.ts) - 1] for d in steps], (0,)),
            _joined([d.ys[:len(d.ts) - 1] for d in steps], (0, 4)), _joined(_widened([d.qs[:len(d.ts) - 1]
                                                                                      for d in steps]), (0, 4, 4)),
            np.array([d.t_old for d in dop], dtype=float), np.array([d.h for d in dop], dtype=float),  # (D,) each
            _joined([d.y_old[None] for d in dop], (0, 4)), _joined([d.F[None] for d in dop], (0, kn.DOP853_POWER, 4)),
            np.array(remap_off, dtype=np.int64), _joined(remap_new, (0,)), _joined(remap_old, (0,)))


def _kinds(ode):
    """The kinds (kernels.near) of the dense outputs of a segment's solution, or None when the tables cannot hold
    it (not scipy's OdeSolution ascending in time, or a dense output neither the compiled methods' nor DOP853's)."""
    if not isinstance(ode, OdeSolution) or not ode.ascending or ode.side != "left":
        return None
    kinds = []
    for dense in ode.interpolants:
        if isinstance(dense, StepsDense) and len(dense.ts) >= 2:
            kinds.append(kn.RK45_STEPS)
        elif isinstance(dense, Dop853DenseOutput) and dense.F.shape == (kn.DOP853_POWER, 4):
            kinds.append(kn.DOP853)
        else:
            return None
    return kinds


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
