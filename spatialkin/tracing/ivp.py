"""Drive solve_ivp along one branch of an intersection curve, segment by segment.

A branch is integrated from a point on the curve in one direction (sign = +1 along N1 x N2, -1 against it)
until it closes on its start, reaches a singular point, leaves a bounded surface or reaches max_length.
It is split into segments at events that need Python between two integrations:

* a sphere's chart nears its poles: the sphere is re-charted (its internal pole axis turned so that the
  current point lies on the new equator, moving along it) and integration goes on; the user's (u, v) are
  recovered from the points afterwards;
* a crossing of the start's normal plane that is not the start (a closure candidate rejected).

At every segment start the state is projected back onto the curve by Newton, and the right-hand side
carries a pull-back term, so the gap between the surfaces stays flat however long the branch is.
"""
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from ..kernels import curve as kc
from ..kernels import surfaces as ks

# --- named limits -------------------------------------------------------------------------------------
#: A sphere is re-charted when |cos(latitude)| falls below this (latitude beyond 60 degrees).
POLE_GUARD = 0.5
#: The closure plane is put this far (relative to the curve scale) behind the start, so that the start
#: itself is never taken for a crossing.
CLOSURE_OFFSET = 1e-8
#: A crossing of the closure plane closes the curve if it lies within this distance (relative to the
#: curve scale) of the start and moves in the same direction (cosine above CLOSURE_COSINE).
CLOSURE_RADIUS = 1e-5
CLOSURE_COSINE = 0.9
#: A segment ends at each local minimum of sin(angle between the normals) along the path; a minimum below
#: this is a singular point: the node itself (where N1 x N2 flips) or, on a path a gap's width beside it,
#: the turn onto the other branch (a branch jump), which is never taken.
NODE_SUSPECT = 1e-5
#: Where Newton fails with the normals closer to parallel than this (sine), the branch ends at a singular point.
NEWTON_NEAR_SINGULAR = 1e-3
#: A singular point (a node where branches cross, the apex of a spindle or horn torus or a cone) is
#: passed by a jump of this length (relative to the curve scale) along the incoming direction, then Newton
#: in the plane normal to it; the jump's dense output is corrected in that plane.
JUMP_LENGTH = 1e-3
#: Longest jump (relative to the curve scale), reached by doubling where the landing is still beside an apex.
MAX_JUMP = 0.1
#: The relative area element of a parametrisation below which its apex is jumped (not a pole: spheres are
#: re-charted well before).
APEX_GUARD = 2e-4
#: After a jump the point must lie within this fraction of the jump of the straight continuation.
JUMP_STRAIGHTNESS = 0.1
#: Arc-length step (relative to the curve scale) of the difference that gives the slope of that sine.
SLOPE_STEP = 1e-7
#: Minima are watched only where the sine is below this, and counted once its slope (times the scale)
#: rises above SLOPE_FLOOR, so that a constant sine (a circle on a surface of revolution) never triggers.
WATCH_BELOW = 1e-2
SLOPE_FLOOR = 1e-6
#: A parameter this close to a bound (relative) counts as on the edge.
EDGE_TOL = 1e-12
#: Newton iterations allowed for one projection onto the curve.
NEWTON_MAX_ITER = 12
#: At most this many right-hand-side evaluations in one segment (a stalled integration ends the branch).
SEGMENT_MAX_EVALUATIONS = 200_000
#: At most this many segments in one branch (each ends at an event): bounds the work on pathological input.
MAX_SEGMENTS = 10_000


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


class LinearStates:
    """Dense output of a jump across a singular point: states interpolated linearly over [0, length]."""

    def __init__(self, y0, y1, length):
        self.y0, self.y1, self.length = np.asarray(y0, dtype=float), np.asarray(y1, dtype=float), length

    def __call__(self, t):
        w = np.clip(np.asarray(t, dtype=float) / self.length, 0.0, 1.0)
        return self.y0[:, None] * (1 - w) + self.y1[:, None] * w if np.ndim(t) else self.y0 * (1 - w) + self.y1 * w


@dataclass
class Branch:
    """Result of integrating one direction from a start point."""
    sign: float
    segments: list = field(default_factory=list)
    status: str = "max_length"   # 'closed', 'singular', 'boundary', 'max_length', 'failed'
    message: str = ""
    length: float = 0.0
    nfev: int = 0
    end_state: np.ndarray = None
    nodes: list = field(default_factory=list)      # (s, point) of singular points passed through


@dataclass
class Settings:
    """Numerical settings of one trace (absolute lengths already scaled)."""
    method: str
    rtol: float
    atol: float
    gap_tol: float          # Newton target for |M1 - M2|
    scale: float            # curve length scale
    tolerance: float        # accuracy promised: tol * scale, or the round-off floor of the coordinates
    singular_tol: float     # stop when sin(normals' angle) or a relative area element falls below it
    pullback: float         # lambda, 1/length
    max_length: float
    max_step: float
    close: bool = True


def recharted_sphere(data, point, tangent):
    """Sphere data with its chart turned so that point is at (u, v) = (0, 0) and tangent along +u."""
    new = data.copy()
    center = data[ks.ORIGIN:ks.ORIGIN + 3]
    x = point - center
    x /= np.linalg.norm(x)
    z = np.cross(x, tangent)
    nz = np.linalg.norm(z)
    if nz < 1e-12:            # tangent not known (zero): any axis normal to x will do
        z = np.cross(x, np.eye(3)[np.argmin(np.abs(x))])
        nz = np.linalg.norm(z)
    z /= nz
    y = np.cross(z, x)
    new[ks.ROT:ks.ROT + 9] = np.column_stack([x, y, z]).ravel()
    return new


def area_flag(data):
    """Whether a degenerate parametrisation of this surface ends a branch (spheres are re-charted)."""
    return int(data[ks.KIND]) not in (ks.SPHERE, ks.PLANE, ks.CYLINDER)


def charts_at(a_user, b_user, point, tangent, y_prev=None):
    """Charts for a new segment at point and the state there in them.

    Spheres are re-charted at point (so it lies on their equator, tangent along +u); the other surfaces
    keep their own chart and take (u, v) from y_prev (continuous u) or, without it, from the foot point.
    """
    y = np.empty(4)
    charts = []
    for k, user in enumerate((a_user, b_user)):
        uv = np.empty((1, 2))
        if int(user[ks.KIND]) == ks.SPHERE:
            data = recharted_sphere(user, point, tangent)
            ks.inverse(data, point.reshape(1, 3), uv)
        elif y_prev is not None:
            data = user
            uv[0] = y_prev[2 * k:2 * k + 2]
        else:
            data = user
            ks.inverse(data, point.reshape(1, 3), uv)
        y[2 * k:2 * k + 2] = uv[0]
        charts.append(data)
    return charts[0], charts[1], y


class BudgetExceeded(Exception):
    """An integration used up its right-hand-side evaluations."""


def budgeted(rhs, limit=None):
    """rhs wrapped so that it raises BudgetExceeded after `limit` calls (bounded time on any input)."""
    limit = SEGMENT_MAX_EVALUATIONS if limit is None else limit
    calls = [0]

    def wrapped(t, y, *args):
        calls[0] += 1
        if calls[0] > limit:
            raise BudgetExceeded
        return rhs(t, y, *args)
    return wrapped


def finite_bounds(*surfaces):
    """(surface index k, bound index j, state index, bound value, is a lower bound) of every finite bound of
    the surfaces' data, j in (u_min, u_max, v_min, v_max) order."""
    for k, data in enumerate(surfaces):
        for j in range(4):
            bound = data[ks.BOUNDS + j]
            if np.isfinite(bound):
                yield k, j, 2 * k + j // 2, bound, j % 2 == 0


def make_events(a, b, settings, sign, start, direction, s_arm):
    """The event functions of one segment, in a fixed order: singular, minimum, boundaries, poles, closure."""
    events, kinds = [], []
    flag_a, flag_b = area_flag(a), area_flag(b)
    sing_tol = settings.singular_tol

    def singular(s, y, *_):
        return kc.degeneracy(y, a, b, 0, 0) - sing_tol
    singular.terminal, singular.direction = True, -1
    events.append(singular)
    kinds.append(("singular", None))

    if flag_a or flag_b:
        def apex(s, y, *_):
            return kc.area_degeneracy(y, a, b, flag_a, flag_b) - APEX_GUARD
        apex.terminal, apex.direction = True, -1
        events.append(apex)
        kinds.append(("apex", None))

    h = SLOPE_STEP * settings.scale

    floor = SLOPE_FLOOR / settings.scale

    def minimum(s, y, *_):
        if kc.degeneracy(y, a, b, 0, 0) > WATCH_BELOW:
            return -1.0
        return kc.degeneracy_slope(y, a, b, sign, h) - floor
    minimum.terminal, minimum.direction = True, 1
    events.append(minimum)
    kinds.append(("minimum", None))

    for k, j, idx, bound, lower in finite_bounds(a, b):
        def edge(s, y, *_, idx=idx, bound=bound, lower=lower):
            return y[idx] - bound if lower else bound - y[idx]
        edge.terminal, edge.direction = True, -1
        events.append(edge)
        kinds.append(("boundary", (k, j)))

    for k, data in enumerate((a, b)):
        if int(data[ks.KIND]) == ks.SPHERE:
            iv = 2 * k + 1

            def pole(s, y, *_, iv=iv):
                return abs(np.cos(y[iv])) - POLE_GUARD
            pole.terminal, pole.direction = True, -1
            events.append(pole)
            kinds.append(("chart", k))

    if settings.close:
        offset = CLOSURE_OFFSET * settings.scale

        def closure(s, y, *_):
            if s <= s_arm:
                return 1.0
            return kc.closure_value(y, a, start, direction, offset)
        closure.terminal, closure.direction = True, 1
        events.append(closure)
        kinds.append(("closure", None))
    return events, kinds


def at_outer_edge(a, b, y, sign):
    """True where y lies on (or past) an edge of a trimmed surface and the direction of travel leaves it."""
    dy = kc.dragilev_rhs(0.0, y, a, b, sign, 0.0)
    for _, _, idx, bound, lower in finite_bounds(a, b):
        inside = y[idx] - bound if lower else bound - y[idx]
        rate = dy[idx] if lower else -dy[idx]
        if inside <= EDGE_TOL * max(1.0, abs(bound)) and rate < 0:
            return True
    return False


def newton_fixed(a, b, y, fixed, gap_tol, max_iter=30):
    """Newton on M1(u1, v1) - M2(u2, v2) = 0 for the three parameters other than y[fixed], which is held.

    Returns the solved (4,) state, or None if Newton fails. This cuts one surface with a parameter line of
    the other (the seed's auxiliary curve, the edge of a trimmed surface, a given crank angle).
    """
    ys = np.array(y, dtype=float).reshape(1, 4)
    ok = np.zeros(1, dtype=np.bool_)
    kc.newton_fixed_many(ys, a, b, fixed, gap_tol, max_iter, ok)
    return ys[0] if ok[0] else None


def project_state(y, a, b, settings, tangent_hint=None):
    """Project y onto the curve in the plane normal to the local tangent; returns (y, point, tangent, ok)."""
    y = np.array(y, dtype=float)
    point = np.empty(3)
    tangent = np.empty(3)
    kc.curve_frame(y, a, b, point, tangent)
    if tangent_hint is None:
        tangent_hint = tangent.copy()
    iters = kc.project_to_curve(y, a, b, point.copy(), tangent_hint, settings.gap_tol, NEWTON_MAX_ITER)
    kc.curve_frame(y, a, b, point, tangent)
    return y, point, tangent, iters >= 0


def jump_across(seg, t_event, y_event, settings):
    """Pass a singular point reached at solver time t_event of seg (state y_event, on or beside it).

    The jump starts a jump length before the event, where the solver's path is still on the incoming
    branch, and goes on along the incoming chord to as far beyond the event; there the curve is found by
    Newton in the plane normal to the chord (the nearest branch: the same one, straight through). The jump
    is lengthened (up to MAX_JUMP) until it lands clear of an apex's degenerate zone.

    Returns (solver time where the jump starts, state there, state after, unit direction, length), or None
    if no point of the same branch is found.
    """
    a, b = seg.a, seg.b
    flags = (area_flag(a), area_flag(b))
    h = JUMP_LENGTH * settings.scale
    while h <= MAX_JUMP * settings.scale:
        back = max(t_event - h, 0.0)
        if t_event - back <= 0.0:
            return None
        y_back = seg.sol(back)
        p_event, p_back, t = np.empty(3), np.empty(3), np.empty(3)
        kc.curve_frame(y_event, a, b, p_event, t)
        kc.curve_frame(y_back, a, b, p_back, t)
        d = p_event - p_back
        span = np.linalg.norm(d)
        if span == 0.0:
            return None
        d /= span
        reach = h + span
        y = y_back + (y_event - y_back) * (reach / (t_event - back))
        target = p_back + reach * d
        if kc.project_to_curve(y, a, b, target, d, settings.gap_tol, NEWTON_MAX_ITER) < 0:
            return None
        p_after = np.empty(3)
        kc.curve_frame(y, a, b, p_after, t)
        if np.linalg.norm(p_after - target) > JUMP_STRAIGHTNESS * reach:
            return None
        if kc.area_degeneracy(y, a, b, *flags) < 2 * APEX_GUARD:
            h *= 2                      # still beside an apex (a horn torus's cusp): jump further
            continue
        if kc.degeneracy(y, a, b, 0, 0) < 10 * settings.singular_tol:
            return None
        return back, y_back, y, d, float(np.linalg.norm(p_after - p_back))
    return None


def locate_node(a, b, y_from, y_to, d, y_event):
    """The singular point passed by a jump from y_from to y_to (direction d), to about the chord's sagitta:
    the sine of the normals' angle (at a node) or the relative area element (at an apex) grows like
    |s - s_node| on either side, so its values at a quarter and three quarters of the jump (corrected onto
    the curve in planes normal to d) place the point between them. Falls back to the event point."""
    pts, sines = [], []
    for w in (0.25, 0.75):
        y = y_from + w * (y_to - y_from)
        p, t = np.empty(3), np.empty(3)
        kc.curve_frame(y, a, b, p, t)
        kc.project_to_curve(y, a, b, p.copy(), d, 0.0, NEWTON_MAX_ITER)
        kc.curve_frame(y, a, b, p, t)
        pts.append(p)
        sines.append(kc.degeneracy(y, a, b, area_flag(a), area_flag(b)))
    total = sines[0] + sines[1]
    if total == 0.0 or float(np.dot(pts[1] - pts[0], d)) <= 0.0:
        p, t = np.empty(3), np.empty(3)
        kc.curve_frame(y_event, a, b, p, t)
        return p
    w = sines[0] / total
    return pts[0] + w * (pts[1] - pts[0])


def take_jump(branch, seg, y_event, jump):
    """Record a jump across a singular point: cut seg where the jump starts, add the jump segment, and
    return the new (sign, state, point, tangent) to go on from."""
    back, y_back, y_after, d, length = jump
    keep = seg.t <= back
    seg.t, seg.y = np.append(seg.t[keep], back), np.column_stack([seg.y[:, keep], y_back])
    seg.s1 = seg.s0 + back
    point, tangent = np.empty(3), np.empty(3)
    branch.nodes.append((seg.s1, locate_node(seg.a, seg.b, y_back, y_after, d, y_event)))
    branch.segments.append(Segment(s0=seg.s1, s1=seg.s1 + length, sign=1.0,
                                   sol=LinearStates(y_back, y_after, length), a=seg.a, b=seg.b,
                                   t=np.array([0.0, length]), y=np.column_stack([y_back, y_after]), normal=d))
    kc.curve_frame(y_after, seg.a, seg.b, point, tangent)
    sign = 1.0 if float(np.dot(tangent, d)) > 0 else -1.0
    return sign, y_after.copy(), point, tangent


def closes_within_jump(jump, start, direction):
    """Arc length at which the curve returns to its start inside a jump segment, or None."""
    p_from, t = np.empty(3), np.empty(3)
    kc.curve_frame(jump.y[:, 0], jump.a, jump.b, p_from, t)
    d = jump.normal
    along = float(np.dot(start - p_from, d))
    length = jump.s1 - jump.s0
    lateral = np.linalg.norm(start - p_from - along * d)
    if 0.0 < along <= length and lateral <= JUMP_STRAIGHTNESS * length and float(np.dot(d, direction)) >= CLOSURE_COSINE:
        return jump.s0 + along
    return None


def integrate_branch(a_user, b_user, point, tangent, y_start, sign, settings):
    """Integrate one direction from point (on the curve, unit tangent N1 x N2/|.| there).

    y_start holds the non-sphere parameters at point (a sphere's come from its chart). Singular points on
    the way (nodes where branches cross, apexes) are passed straight through. Returns a Branch whose
    segments cover [0, branch.length] in arc length.
    """
    branch = Branch(sign=sign)
    point = np.array(point, dtype=float)
    tangent = np.array(tangent, dtype=float)
    y = np.asarray(y_start, dtype=float)
    start, direction = point.copy(), sign * tangent
    s, s_arm = 0.0, 0.0
    radius = CLOSURE_RADIUS * settings.scale
    for _ in range(MAX_SEGMENTS):
        y_prev = y
        a, b, y = charts_at(a_user, b_user, point, sign * tangent, y)
        y, point, tangent, ok = project_state(y, a, b, settings)
        if not ok and branch.segments and not np.any(branch.segments[-1].normal):
            # a restart beside a singular point: pass it from the last integrated segment instead
            last = branch.segments[-1]
            jump = jump_across(last, last.s1 - last.s0, y_prev, settings)
            if jump is not None:
                sign, y, point, tangent = take_jump(branch, last, y_prev, jump)
                s = branch.segments[-1].s1
                continue
        if not ok:
            sin_normals = kc.degeneracy(y, a, b, 0, 0)
            if sin_normals < NEWTON_NEAR_SINGULAR:
                branch.status = "singular"
                branch.message = (f"singular point (normals nearly parallel, sin = {sin_normals:.2g}; Newton "
                                  f"cannot separate the branches) at s = {s:.6g}, point {point.tolist()}")
            else:
                branch.status, branch.message = "failed", f"Newton correction failed at s = {s:.6g}"
            break
        if at_outer_edge(a, b, y, sign):
            branch.status, branch.message = "boundary", f"starts on an edge, leaving the surface, at s = {s:.6g}"
            break
        events, kinds = make_events(a, b, settings, sign, start, direction, s_arm - s)
        try:
            res = solve_ivp(budgeted(kc.dragilev_rhs), (0.0, settings.max_length - s), y, method=settings.method,
                            rtol=settings.rtol, atol=settings.atol, dense_output=True, events=events,
                            args=(a, b, sign, settings.pullback), max_step=settings.max_step)
        except BudgetExceeded:
            branch.status = "failed"
            branch.message = (f"integration stalled after s = {s:.6g} ({SEGMENT_MAX_EVALUATIONS} right-hand-side "
                              f"evaluations in one segment), near point {point.tolist()}")
            break
        branch.nfev += res.nfev
        seg = Segment(s0=s, s1=s + (res.t[-1] if res.t.size else 0.0), sign=sign, sol=res.sol, a=a, b=b,
                      t=res.t, y=res.y)
        if res.t.size and res.t[-1] > 0:
            branch.segments.append(seg)
        s = seg.s1
        y = res.y[:, -1].copy() if res.t.size else y
        if res.status == -1:
            if kc.degeneracy(y, a, b, 0, 0) < NODE_SUSPECT:
                branch.status = "singular"
                branch.message = f"singular point (normals parallel) near s = {s:.6g}"
            else:
                branch.status, branch.message = "failed", f"solve_ivp failed at s = {s:.6g}: {res.message}"
            break
        if res.status == 0:
            branch.status = "max_length"
            branch.message = f"stopped at max_length = {settings.max_length:.6g} without closing"
            break
        hit = next(i for i, te in enumerate(res.t_events) if te.size)
        kind, info = kinds[hit]
        y = res.y_events[hit][0].copy()
        kc.curve_frame(y, a, b, point, tangent)
        singular = kind in ("singular", "apex") or (
            kind in ("minimum", "chart") and kc.degeneracy(y, a, b, 0, 0) < NODE_SUSPECT)
        if singular:
            jump = jump_across(seg, res.t_events[hit][0], y, settings)
            if jump is None:
                branch.status = "singular"
                what = ("a parametrisation degenerates (apex of a cone or axis point of a horn/spindle torus)"
                        if kind == "apex" else "singular point (branches cross or the surfaces touch)")
                branch.message = (f"{what}, not passed, at s = {s:.6g}, point {point.tolist()}, sin of the normals' "
                                  f"angle {kc.degeneracy(y, a, b, 0, 0):.2g}")
                break
            sign, y, point, tangent = take_jump(branch, seg, y, jump)
            s = branch.segments[-1].s1
            closing = closes_within_jump(branch.segments[-1], start, direction)
            if closing is not None:
                branch.status = "closed"
                branch.message = f"closed on its start, within a jump, after s = {closing:.12g}"
                branch.length = closing
                branch.end_state = y
                return branch
            continue
        if kind in ("minimum", "chart"):
            continue
        if kind == "closure":
            yp, p_e, t_e, _ = project_state(y, a, b, settings)
            close_enough = np.linalg.norm(p_e - start) <= radius
            if close_enough and float(np.dot(sign * t_e, direction)) >= CLOSURE_COSINE:
                remaining = float(np.dot(start - p_e, sign * t_e))
                branch.status = "closed"
                branch.message = f"closed on its start after s = {s + remaining:.12g}"
                branch.length = s + remaining
                branch.end_state = yp
                return branch
            s_arm = s          # a crossing elsewhere: go on, re-armed past it
            continue
        if kind == "boundary":
            k, j = info
            name = "ab"[k]
            which = ("u_min", "u_max", "v_min", "v_max")[j]
            branch.status = "boundary"
            branch.message = f"reached the edge {which} of surface {name} at s = {s:.6g}"
            edge_state = y.copy()
            edge_state[2 * k + j // 2] = (a, b)[k][ks.BOUNDS + j]
            snapped = newton_fixed(a, b, edge_state, 2 * k + j // 2, settings.gap_tol)
            if snapped is not None:      # end exactly on the edge
                y = snapped
                seg.y[:, -1] = y
            break
    else:
        branch.status, branch.message = "failed", f"more than {MAX_SEGMENTS} segments"
    branch.length = s
    branch.end_state = y
    return branch
