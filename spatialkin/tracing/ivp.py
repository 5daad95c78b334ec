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
import numpy as np
from scipy.integrate import solve_ivp

from ..kernels import curve as kc
from ..kernels import dopri as kd
from ..kernels import surfaces as ks
from .segments import (EDGE_RATE, EDGE_TOL, POLE_GUARD, SEGMENT_MAX_EVALUATIONS, Branch, BudgetExceeded, Segment, StepStates,
                       area_flag, budgeted, charts_at, finite_bounds, newton_fixed, project_state)
from .singular import APEX_GUARD, closes_within_jump, jump_across, take_jump
from .traits import traits

# --- named limits -------------------------------------------------------------------------------------
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
NODE_SUSPECT = 1e-4
#: A minimum of the sine below NODE_SUSPECT is a node only within this distance (relative to the scale) of a
#: singular point proven by the topology stage (when the trace comes from sk.intersect).
KNOWN_NODE = 1e-3
#: Where Newton fails with the normals closer to parallel than this (sine), the branch ends at a singular point.
NEWTON_NEAR_SINGULAR = 1e-3
#: A singular point (a node where branches cross, the apex of a spindle or horn torus or a cone) is
#: passed by a jump of this length (relative to the curve scale) along the incoming direction, then Newton
#: The relative area element of a parametrisation below which its apex is jumped (not a pole: spheres are
#: Arc-length step (relative to the curve scale) of the difference that gives the slope of that sine.
SLOPE_STEP = 1e-7
#: Minima are watched only where the sine is below this, and counted once its slope (times the scale)
#: rises above SLOPE_FLOOR, so that a constant sine (a circle on a surface of revolution) never triggers.
WATCH_BELOW = 1e-2
SLOPE_FLOOR = 1e-6
#: The minimum event is armed only this far (relative to the scale) into a segment.
MINIMUM_ARM = 1e-9
#: settings.method of the compiled integrator (spatialkin.kernels.dopri), and the solve_ivp method it hands
#: hard cases to.
COMPILED = "compiled"
FALLBACK_METHOD = "DOP853"
#: The compiled integrator hands over to solve_ivp this many times before a watched threshold (the sine's
#: WATCH_BELOW or the singular tolerance, APEX_GUARD), so that solve_ivp's events see the whole approach.
HANDOFF_MARGIN = 2.0
#: At most this many segments in one branch (each ends at an event): bounds the work on pathological input.
MAX_SEGMENTS = 10_000


def known_node(point, settings):
    """True unless the topology stage has proven where the singular points are and none is near point (then a
    narrow waist between two branches is not a node: the branch goes round it)."""
    if settings.nodes is None:
        return True
    nodes = np.asarray(settings.nodes).reshape(-1, 3)
    return bool(len(nodes)) and float(np.min(np.linalg.norm(nodes - point, axis=1))) <= KNOWN_NODE * settings.scale


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

    arm = MINIMUM_ARM * settings.scale

    def minimum(s, y, *_):
        if s <= arm:
            return 1.0          # not at the segment's start, which may be the minimum just found
        if kc.degeneracy(y, a, b, 0, 0) > WATCH_BELOW:
            return -1.0
        return kc.degeneracy_slope(y, a, b, sign, h) - floor
    minimum.terminal, minimum.direction = True, 1
    events.append(minimum)
    kinds.append(("minimum", None))

    for k, j, idx, bound, lower, slack in finite_bounds(a, b):
        def edge(s, y, *_, idx=idx, bound=bound, lower=lower, slack=slack):
            return (y[idx] - bound if lower else bound - y[idx]) + slack
        edge.terminal, edge.direction = True, -1
        events.append(edge)
        kinds.append(("boundary", (k, j)))

    for k, data in enumerate((a, b)):
        if traits(data).recharts:
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


def compiled_segment(a, b, y, sign, settings, start, direction, s_arm, t_bound):
    """One segment by the compiled integrator over local arc length [0, t_bound], the closure armed past s_arm:
    (status, ts, ys (n, 4), hs, qs, nfev), see kd.dopri_segment."""
    lo, hi = np.full(4, -np.inf), np.full(4, np.inf)
    for _, _, idx, bound, lower, slack in finite_bounds(a, b):
        if lower:
            lo[idx] = max(lo[idx], bound - slack)
        else:
            hi[idx] = min(hi[idx], bound + slack)
    atol = settings.atol
    watch = HANDOFF_MARGIN * max(WATCH_BELOW, settings.singular_tol)
    return kd.dopri_segment(np.ascontiguousarray(y, dtype=float), a, b, float(sign), settings.pullback,
                            float(t_bound),
                            settings.rtol, atol, settings.max_step, SEGMENT_MAX_EVALUATIONS, settings.close, start,
                            direction, CLOSURE_OFFSET * settings.scale, s_arm, watch, area_flag(a), area_flag(b),
                            HANDOFF_MARGIN * APEX_GUARD, lo, hi, traits(a).recharts,
                            traits(b).recharts, POLE_GUARD)


def at_outer_edge(a, b, y, sign):
    """True where y lies on (or past) an edge of a trimmed surface and the direction of travel leaves it (a curve
    running along the edge does not leave it)."""
    dy = kc.dragilev_rhs(0.0, y, a, b, sign, 0.0)
    for k, _, idx, bound, lower, _ in finite_bounds(a, b):
        inside = y[idx] - bound if lower else bound - y[idx]
        rate = dy[idx] if lower else -dy[idx]
        if inside <= EDGE_TOL * max(1.0, abs(bound)) and rate < -EDGE_RATE * np.hypot(dy[2 * k], dy[2 * k + 1]):
            return True
    return False


def curvature_vector(y, a, b):
    """C'' (3,) of the curve at the state y (charts a, b), or None at a singular point."""
    dy, ddy, d1, d2 = np.empty(4), np.empty(4), np.empty(3), np.empty(3)
    return d2 if kc.curve_derivatives(np.ascontiguousarray(y, dtype=float), a, b, 1.0, dy, ddy, d1, d2) else None


def integrate_branch(a_user, b_user, point, tangent, y_start, sign, settings):
    """Integrate one direction from point (on the curve, unit tangent N1 x N2/|.| there).

    y_start holds the non-sphere parameters at point (a sphere's come from its chart). Singular points on
    the way (nodes where branches cross, apexes) are passed straight through. Returns a Branch whose
    segments cover [0, branch.length] in arc length.
    """
    branch = Branch()
    point = np.array(point, dtype=float)
    tangent = np.array(tangent, dtype=float)
    y = np.asarray(y_start, dtype=float)
    start, direction = point.copy(), sign * tangent
    s, s_arm = 0.0, 0.0
    radius = CLOSURE_RADIUS * settings.scale
    compiled = settings.method == COMPILED
    for _ in range(MAX_SEGMENTS):
        y_prev = y
        a, b, y = charts_at(a_user, b_user, point, sign * tangent, y)
        if traits(a_user).recharts or traits(b_user).recharts:
            bend = curvature_vector(y, a, b)
            if bend is not None:
                a, b, y = charts_at(a_user, b_user, point, sign * tangent, y, bend)
        y, point, tangent, ok = project_state(y, a, b, settings)
        if not ok and branch.segments and not np.any(branch.segments[-1].normal):
            # a restart beside a singular point: pass it from the last integrated segment instead
            last = branch.segments[-1]
            jump = jump_across(branch, last, last.s1 - last.s0, y_prev, settings)
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
        if compiled:
            status, ts, ys, hs, qs, nfev = compiled_segment(a, b, y, sign, settings, start, direction, s_arm - s,
                                                             settings.max_length - s)
            branch.nfev += nfev
            seg = Segment(s0=s, s1=s + ts[-1], sign=sign, sol=StepStates(ts, ys, hs, qs), a=a, b=b, t=ts,
                          y=np.ascontiguousarray(ys.T))
            if ts[-1] > 0:
                branch.segments.append(seg)
            s = seg.s1
            y = ys[-1].copy()
            kc.curve_frame(y, a, b, point, tangent)
            if status == kd.BUDGET:
                branch.status = "failed"
                branch.message = (f"integration stalled after s = {s:.6g} ({SEGMENT_MAX_EVALUATIONS} right-hand-side "
                                  f"evaluations in one segment), near point {point.tolist()}")
                break
            if status == kd.DONE:
                branch.status = "max_length"
                branch.message = f"stopped at max_length = {settings.max_length:.6g} without closing"
                break
            if status in (kd.HANDOFF, kd.FAILED):
                compiled = False         # a hard case ahead: solve_ivp and its event functions from here on
                continue
            if status in (kd.CHART_A, kd.CHART_B):
                continue
            kind, info = "closure", None
        else:
            events, kinds = make_events(a, b, settings, sign, start, direction, s_arm - s)
            try:
                method = FALLBACK_METHOD if settings.method == COMPILED else settings.method
                res = solve_ivp(budgeted(kc.dragilev_rhs), (0.0, settings.max_length - s), y, method=method,
                                rtol=settings.rtol, atol=settings.atol, dense_output=True, events=events,
                                args=(a, b, sign, settings.pullback), max_step=settings.max_step)
            except BudgetExceeded:
                branch.status = "failed"
                branch.message = (f"integration stalled after s = {s:.6g} ({SEGMENT_MAX_EVALUATIONS} "
                                  f"right-hand-side evaluations in one segment), near point {point.tolist()}")
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
            singular = kind == "singular" or (kind == "apex" and known_node(point, settings)) or (
                kind in ("minimum", "chart") and kc.degeneracy(y, a, b, 0, 0) < NODE_SUSPECT
                and known_node(point, settings))
            if singular:
                jump = jump_across(branch, seg, res.t_events[hit][0], y, settings)
                if jump is None:
                    branch.status = "singular"
                    what = ("a parametrisation degenerates (apex of a cone or axis point of a horn/spindle torus)"
                            if kind == "apex" else "singular point (branches cross or the surfaces touch)")
                    branch.message = (f"{what}, not passed, at s = {s:.6g}, point {point.tolist()}, sin of the "
                                      "normals' "
                                      f"angle {kc.degeneracy(y, a, b, 0, 0):.2g}")
                    break
                sign, y, point, tangent = take_jump(branch, seg, y, jump)
                s = branch.segments[-1].s1
                closing = closes_within_jump(branch.segments[-1], start, direction, CLOSURE_COSINE)
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
