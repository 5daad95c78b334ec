"""The intersection branch as a system of the Runge–Kutta engine: Dragilev's right-hand side and its events.

Every event of a branch segment is one entry of the vector ``branch_events`` writes, in this fixed order; a
segment switches on the ones it watches. The same values serve the compiled engine (spatialkin.kernels.ode.rk)
and solve_ivp's own methods (spatialkin.ode.solvers.Event reads one entry).

The event parameters are one float array ``ep`` laid out by the P_* indices below, plus the chart data of the
two surfaces in ``args = (a, b, sign, pullback, memo)`` (``branch_args``). ``memo`` keeps what the last right-hand
side computed at its state (the normals' sine and M1): the engine evaluates the events at the state of a step's
last stage, so the events read them instead of evaluating both surfaces again (the same values, bit for bit).
"""
import numpy as np

from ..._lib.jit import jit
from ..ode import rk
from .curve import area_degeneracy, degeneracy, degeneracy_slope, dragilev_into, dragilev_rhs, frame, plane_value

# --- events, in order (each value falls or rises through zero) -----------------------------------------------
#: The normals' sine falls below the singular tolerance.
SINGULAR = 0
#: A flagged parametrisation's relative area element falls below the apex guard.
APEX = 1
#: A local minimum of the normals' sine (below the watch level), where its slope rises through the floor.
MINIMUM = 2
#: The compiled method hands over to a solve_ivp method: the sine or the area element nears a hard case.
HANDOFF_SINE = 3
HANDOFF_AREA = 4
#: Parameter bounds: EDGE + 2 * index + (0 lower, 1 upper), index in (u1, v1, u2, v2).
EDGE = 5
#: A sphere's chart nears its pole (surface a, surface b).
POLE_A = 13
POLE_B = 14
#: The closure plane behind the start is crossed upwards (past the arming length).
CLOSURE = 15
#: The normals' sine leaves the band [lo, hi] a segment's step cap was made for (beside a near tangency).
BAND = 16
COUNT = 17

# --- layout of ep ----------------------------------------------------------------------------------------
P_SINGULAR_TOL = 0
P_FLAG_A = 1
P_FLAG_B = 2
P_APEX_GUARD = 3
P_SLOPE_STEP = 4
P_SLOPE_FLOOR = 5
P_MINIMUM_ARM = 6
P_WATCH_BELOW = 7
P_HANDOFF_SINE = 8
P_HANDOFF_AREA = 9
P_BOUND = 10            # 8 entries, as the EDGE events
P_SLACK = 18            # 8 entries
P_POLE_GUARD = 26
P_CLOSURE_ARM = 27
P_CLOSURE_OFFSET = 28
P_START = 29            # 3 entries
P_DIRECTION = 32        # 3 entries
P_AREA_WEIGHT = 35      # the apex and area hand-over events' factor (area_weight)
P_BAND_LO = 36
P_BAND_HI = 37
P_SIZE = 38

# --- layout of memo: the state of the last right-hand side, the normals' sine and M1 there ---------------------
M_STATE = 0             # 4 entries
M_SINE = 4
M_POINT = 5             # 3 entries
M_SIZE = 8


def branch_args(a, b, sign, pullback):
    """The args of the branch's kernels: (a, b, sign, pullback, memo), the memo empty (NaN: matches no state)."""
    memo = np.empty(M_SIZE)
    memo.fill(np.nan)
    return (a, b, float(sign), float(pullback), memo)


@jit
def branch_rhs(s, y, a, b, sign, pullback, memo):
    """dy/ds for solve_ivp's methods (args = branch_args(...)): dragilev_rhs; the memo is not used."""
    return dragilev_rhs(s, y, a, b, sign, pullback)


@jit(inline="always")          # (inlined into the engine: see curve.dragilev_into)
def branch_fun(t, y, args, out):
    """dy/ds of the branch (Dragilev's right-hand side with its pull-back), args = branch_args(...); the state,
    the sine and M1 kept in the memo."""
    a, b, sign, pullback, memo = args
    sine, point = dragilev_into(y, a, b, sign, pullback, out)
    for i in range(4):
        memo[M_STATE + i] = y[i]
    memo[M_SINE] = sine
    for i in range(3):
        memo[M_POINT + i] = point[i]


@jit
def branch_first_step(y, args, t_bound, max_step, rtol, atol, order, unit):
    """The first step of a segment from (0, y): spatialkin.kernels.ode.rk.initial_step of branch_fun in units of
    `unit` of the arc length (the scene's scale), so that a scene scaled by a factor is marched with every step
    scaled by it."""
    f0 = np.empty(y.shape[0])
    branch_fun(0.0, y, args, f0)
    return rk.initial_step(branch_fun, args, 0.0, y, f0, t_bound, max_step, rtol, atol, order, unit)


@jit
def remembered(y, memo):
    """True when the memo holds the state y (exactly)."""
    for i in range(4):
        if memo[M_STATE + i] != y[i]:
            return False
    return True


@jit
def sine_at(y, a, b, memo):
    """sin of the normals' angle at y (degeneracy without flags), from the memo when it holds y."""
    return memo[M_SINE] if remembered(y, memo) else degeneracy(y, a, b, 0.0, 0.0)


@jit
def branch_event(i, t, y, args, ep):
    """Value of event i at (t, y)."""
    a, b, sign, _, memo = args
    if i == SINGULAR:
        return sine_at(y, a, b, memo) - ep[P_SINGULAR_TOL]
    if i == APEX or i == HANDOFF_AREA:
        guard = ep[P_APEX_GUARD] if i == APEX else ep[P_HANDOFF_AREA]
        return (area_degeneracy(y, a, b, ep[P_FLAG_A], ep[P_FLAG_B]) - guard) * ep[P_AREA_WEIGHT]
    if i == MINIMUM:
        if t <= ep[P_MINIMUM_ARM]:
            return 1.0          # not at the segment's start, which may be the minimum just found
        if sine_at(y, a, b, memo) > ep[P_WATCH_BELOW]:
            return -1.0
        return degeneracy_slope(y, a, b, sign, ep[P_SLOPE_STEP]) - ep[P_SLOPE_FLOOR]
    if i == HANDOFF_SINE:
        return sine_at(y, a, b, memo) - ep[P_HANDOFF_SINE]
    if i == BAND:
        sine = sine_at(y, a, b, memo)
        return min(sine - ep[P_BAND_LO], ep[P_BAND_HI] - sine)
    if EDGE <= i < EDGE + 8:
        j = i - EDGE
        idx = j // 2
        inside = y[idx] - ep[P_BOUND + j] if j % 2 == 0 else ep[P_BOUND + j] - y[idx]
        return inside + ep[P_SLACK + j]
    if i == POLE_A:
        return abs(np.cos(y[1])) - ep[P_POLE_GUARD]
    if i == POLE_B:
        return abs(np.cos(y[3])) - ep[P_POLE_GUARD]
    if i == CLOSURE:
        if t <= ep[P_CLOSURE_ARM]:
            return 1.0
        if remembered(y, memo):
            point = (memo[M_POINT], memo[M_POINT + 1], memo[M_POINT + 2])
        else:
            point, _, _ = frame(a, y[0], y[1])
        return plane_value(point, ep[P_START:P_START + 3], ep[P_DIRECTION:P_DIRECTION + 3], ep[P_CLOSURE_OFFSET])
    return 1.0


@jit
def branch_events(t, y, args, ep, active, out):
    """Values of the active events at (t, y) into out (COUNT,) (inactive entries: 1)."""
    for i in range(out.shape[0]):
        out[i] = branch_event(i, t, y, args, ep) if active[i] else 1.0


@jit
def branch_advance(t, y, f, h, fresh, t_bound, rtol, atol, max_step, max_steps, max_nfev, g, active, directions,
                   modes, args, ep, method):
    """spatialkin.kernels.ode.rk.advance bound to branch_fun and branch_events."""
    return rk.advance(branch_fun, branch_events, args, ep, t, y, f, h, fresh, t_bound, rtol, atol, max_step,
                      max_steps, max_nfev, g, active, directions, modes, method)
