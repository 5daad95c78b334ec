"""A continuation curve as a system of the Runge–Kutta engine: the events of trace_cycle.

A continuation right-hand side is any jitted ``rhs(s, y, *system_args, sign, pullback)``
(spatialkin.kernels.continuation.implicit.follow_rhs underneath); the engine's ``args`` are
``(*system_args, sign, pullback)``. The events, in order, with ``eargs = (index, target level, start level)``
(a float array):

* LEVEL_TARGET, LEVEL_START: the input y[index] crosses the target or the start level;
* RATE: the input's rate along the curve, rhs(s, y, *system_args, sign, 0)[index] (no pull-back), crosses
  zero (a lock position).

A system's kernel module binds its rhs in three small jitted functions (numba caches a kernel only when the
functions it calls are globals): ``fun = follow_fun(rhs, ...)``, ``events = follow_events(rhs, ...)`` and
``advance = spatialkin.kernels.ode.rk.advance(fun, events, ...)``; see spatialkin.kernels.mechanisms.rssr.
"""
from ..._lib.jit import jit
from ..ode.rk import copy_into

LEVEL_TARGET = 0
LEVEL_START = 1
RATE = 2
COUNT = 3


@jit(inline="always")
def follow_fun(rhs, t, y, args, out):
    """dy/ds of the continuation into out."""
    copy_into(out, rhs(t, y, *args))


@jit(inline="always")
def follow_events(rhs, t, y, args, eargs, active, out):
    """Values of the active events (LEVEL_TARGET, LEVEL_START, RATE) into out (inactive entries: 1)."""
    index = int(eargs[0])
    out[LEVEL_TARGET] = y[index] - eargs[1] if active[LEVEL_TARGET] else 1.0
    out[LEVEL_START] = y[index] - eargs[2] if active[LEVEL_START] else 1.0
    out[RATE] = rhs(t, y, *args[:-1], 0.0)[index] if active[RATE] else 1.0
