"""Pieces of an integrated branch: segments and their dense output, settings, charts, budgets, Newton.

A branch is integrated segment by segment (see spatialkin.tracing.march.ivp); each segment keeps the charts it
was integrated in (a sphere is re-charted away from its poles) and its dense output.
"""
import functools
import math
from dataclasses import dataclass, field

import numpy as np

from ...kernels.march import curve as kc
from ...kernels.march import restart as kr
from ...kernels.geometry import surfaces as ks
from ...geometry.traits import LENGTH

# --- named limits -------------------------------------------------------------------------------------
#: A re-charting surface (a sphere) is re-charted when |cos(latitude)| falls below this (latitude beyond 60
#: degrees).
POLE_GUARD = 0.5
#: The edges of a trim, in the order of the bounds in a surface's data (finite_bounds rows' j).
EDGE_NAMES = ("u_min", "u_max", "v_min", "v_max")
#: A parameter this close to a bound (relative to the bound, or to its range where that is below the parameter's
#: unit: 1 for an angle, the scene's scale for a length) counts as on the edge.
EDGE_TOL = 1e-12
#: A curve running along an edge drifts across it by round-off: an edge stops the integration only this many
#: ulp (of the parameter's range) past it, and the end is then snapped onto the edge.
EDGE_ULPS = 64
#: A curve on an edge leaves the surface when the edge parameter decreases faster than this (relative to the
#: speed of that surface's parameters, each in its unit); slower is a curve running along the edge.
EDGE_RATE = 1e-9
#: Newton iterations allowed for one projection onto the curve.
NEWTON_MAX_ITER = 12
#: At most this many right-hand-side evaluations in one segment (a stalled integration ends the branch).
SEGMENT_MAX_EVALUATIONS = 200_000


@dataclass
class Segment:
    """One solve_ivp run: branch arc length s in [s0, s1] is solver time t = s - s0."""
    s0: float
    s1: float
    sign: float          # direction of travel along N1 x N2
    sol: object          # scipy OdeSolution over [0, s1 - s0]
    a: np.ndarray        # chart data of surface a used in this segment
    b: np.ndarray
    t: np.ndarray        # solver step points (local t)
    y: np.ndarray        # states at the step points (4, n)
    normal: np.ndarray = field(default_factory=lambda: np.zeros(3))   # fixed correction plane (jumps)
    compiled: bool = False   # integrated by the compiled method (never beside a hard case)
    area: tuple = (0.0, 0.0)  # area_flag of a and b (the relative area element's units; 0.0: not watched)

    @property
    def jump(self):
        """True for a jump across a singular point (its correction plane's normal set), not a solver run."""
        return bool(self.normal.any())


class LinearStates:
    """Dense output of a jump across a singular point: states interpolated linearly over [0, length]; arc (a
    spatialkin.tracing.march.singular.JumpArc, or None) maps arc length to the chords through the node."""

    def __init__(self, y0, y1, length, arc=None):
        self.y0, self.y1, self.length = np.asarray(y0, dtype=float), np.asarray(y1, dtype=float), length
        self.arc = arc

    def __call__(self, t):
        w = np.clip(np.asarray(t, dtype=float) / self.length, 0.0, 1.0)
        return self.y0[:, None] * (1 - w) + self.y1[:, None] * w if np.ndim(t) else self.y0 * (1 - w) + self.y1 * w


@dataclass
class Branch:
    """Result of integrating one direction from a start point."""
    segments: list = field(default_factory=list)
    status: str = "max_length"   # 'closed' or an end status (spatialkin.tracing.curve.status.END_PRECEDENCE)
    message: str = ""
    length: float = 0.0
    nfev: int = 0
    end_state: np.ndarray = None
    nodes: list = field(default_factory=list)      # (s, point) of singular points passed through
    rejoin: tuple = None            # (point, state) on the loop the branch went round without passing its start


@dataclass
class Settings:
    """Numerical settings of one trace (absolute lengths already scaled)."""
    method: str
    rtol: float
    atol: np.ndarray        # (4,), per parameter
    gap_tol: float          # Newton target for |M1 - M2|
    scale: float            # curve length scale
    tolerance: float        # accuracy promised: tol * scale, or the round-off floor of the coordinates
    singular_tol: float     # stop when sin(normals' angle) or a relative area element falls below it
    pullback: float         # lambda, 1/length
    max_length: float
    max_step: float
    close: bool = True
    nodes: np.ndarray = None  # (K, 3) singular points proven by the topology stage, or None when not known
    find_nodes: object = None  # a callable giving nodes (or None) when they are first asked for (sk.trace)
    apexes: np.ndarray = field(default_factory=lambda: np.empty((0, 3)))  # (K, 3) the surfaces' apexes


def area_flag(surface, scale):
    """The unit of the relative area element of this surface's parametrisation when it is watched (its traits'
    area watch: a degenerate parametrisation ends a branch): the length of a unit step of v in a scene of this
    scale (kernels.curve.relative_area); 0.0 when it is not watched."""
    kind = surface.traits
    return (float(scale) if kind.units[1] == LENGTH else 1.0) if kind.area_watch else 0.0


def charts_at(a_surface, b_surface, point, tangent, y_prev=None, bend=None):
    """Charts for a new segment at point and the state there in them (kernels.march.restart.chart_states).

    Surfaces whose traits re-chart (spheres) are re-charted at point (so it lies on their equator, tangent along
    +u, or the equator through the centre of the small circle the curve bends round, given its curvature vector
    bend); the other surfaces keep their own chart (returned as the user's data itself) and take (u, v) from
    y_prev (continuous u) or, without it, from the foot point.
    """
    point = np.ascontiguousarray(point, dtype=float)
    tangent = np.ascontiguousarray(tangent, dtype=float)
    bend = np.zeros(3) if bend is None else np.ascontiguousarray(bend, dtype=float)
    keep = y_prev is not None
    y_prev = np.ascontiguousarray(y_prev, dtype=float) if keep else np.zeros(4)
    y = np.empty(4)
    charts = []
    for k, surface in enumerate((a_surface, b_surface)):
        user, rechart = surface.data, surface.traits.recharts
        out = np.empty(user.shape)
        kr.chart_states(user, rechart, point, tangent, bend, y_prev, k, out, y, keep)
        charts.append(out if rechart else user)
    return charts[0], charts[1], y


def segment_start(a_user, b_user, recharts, point, direction, y_prev, settings):
    """(a, b, y, point, tangent, ok) at the start of a segment in one compiled call (kernels.restart.segment_start):
    the charts (re-charting the surfaces whose recharts flag is set, along direction, then along the curve's
    curvature vector where it is defined), then project_state. A surface that keeps its chart is returned as the
    user's data itself, a new chart read-only (as every Surface's data)."""
    a_out, b_out = np.empty(a_user.shape), np.empty(b_user.shape)
    y, p, t = np.empty(4), np.empty(3), np.empty(3)
    ok = kr.segment_start(a_user, b_user, recharts[0], recharts[1], np.ascontiguousarray(point, dtype=float),
                          np.ascontiguousarray(direction, dtype=float), np.ascontiguousarray(y_prev, dtype=float),
                          settings.gap_tol, NEWTON_MAX_ITER, a_out, b_out, y, p, t)
    charts = []
    for user, out, rechart in ((a_user, a_out, recharts[0]), (b_user, b_out, recharts[1])):
        if rechart:
            out.flags.writeable = False
        charts.append(out if rechart else user)
    return charts[0], charts[1], y, p, t, bool(ok)


def finite_bounds(*surfaces):
    """((surface index k, bound index j, state index, bound value, is a lower bound, slack, size), ...) of every
    finite bound of the surfaces' data, j in (u_min, u_max, v_min, v_max) order (a tuple: hashable, event_plan's
    cache key). size is the magnitude of the parameter's range (its largest bound or its width), slack EDGE_ULPS
    ulp of it: the round-off by which a curve lying along the edge may cross it."""
    return tuple(row for k, data in enumerate(surfaces)
                 for row in _bounds_of(k, tuple(data[ks.BOUNDS:ks.BOUNDS + 4].tolist())))


@functools.lru_cache(maxsize=256)
def _bounds_of(k, bounds):
    """finite_bounds' rows of surface slot k with these (u_min, u_max, v_min, v_max), made once per slot and trim."""
    rows = []
    for j, bound in enumerate(bounds):
        if math.isfinite(bound):
            pair = [x for x in bounds[2 * (j // 2):2 * (j // 2) + 2] if math.isfinite(x)]
            size = max(max(abs(x) for x in pair), max(pair) - min(pair))
            rows.append((k, j, 2 * k + j // 2, bound, j % 2 == 0, EDGE_ULPS * np.spacing(size), size))
    return tuple(rows)


def newton_fixed(a, b, y, fixed, gap_tol, max_iter=30):
    """Newton on M1(u1, v1) - M2(u2, v2) = 0 for the three parameters other than y[fixed], which is held.

    Returns the solved (4,) state, or None if Newton fails. This cuts one surface with a parameter line of
    the other (an auxiliary curve such as the sphere's equator, the edge of a trimmed surface, a given crank angle).
    """
    ys = np.array(y, dtype=float).reshape(1, 4)
    ok = np.zeros(1, dtype=np.bool_)
    kc.newton_fixed_many(ys, a, b, fixed, gap_tol, max_iter, ok)
    return ys[0] if ok[0] else None


def project_state(y, a, b, settings):
    """Project y onto the curve in the plane normal to the local tangent (kernels.march.restart.project_state);
    returns (y, point, tangent, ok)."""
    y = np.array(y, dtype=float)
    point, tangent = np.empty(3), np.empty(3)
    ok = kr.project_state(y, a, b, settings.gap_tol, NEWTON_MAX_ITER, point, tangent)
    return y, point, tangent, bool(ok)
