"""Drive solve_ivp along one branch of an intersection curve, segment by segment.

A branch is integrated from a point on the curve in one direction (sign = +1 along N1 x N2, -1 against it)
until it closes on its start, reaches a singular point, leaves a bounded surface or reaches max_length.
It is split into segments at events that need Python between two integrations:

* a sphere's chart nears its poles: the sphere is re-charted (its internal pole axis turned so that the
  current point lies on the new equator, moving along it) and integration goes on; the user's (u, v) are
  recovered from the points afterwards;
* a crossing of the start's normal plane that is not the start (a closure candidate rejected);
* with the compiled method: one step before a trim edge (the next segment, started on the curve, ends exactly on
  the edge: segment_events), and a hand-over to the DOP853 steps with the fine events (FALLBACK_METHOD) before a
  singular point or an apex.

At every segment start the state is projected back onto the curve by Newton, and the right-hand side
carries a pull-back term, so the gap between the surfaces stays flat however long the branch is.
"""
import functools
import math

import numpy as np

from ...kernels.march import branch_ode as kb
from ...kernels.march import curve as kc
from ...kernels.geometry import surfaces as ks
from ...kernels.ode import rk
from ...ode.solvers import COMPILED_SOLVERS, BudgetExceeded, Event, System, Watch, integrate
from .segments import (EDGE_NAMES, EDGE_RATE, EDGE_TOL, POLE_GUARD, SEGMENT_MAX_EVALUATIONS, Branch, Segment,
                       area_flag, finite_bounds, newton_fixed, project_state, segment_start)
from ..curve.status import outcome
from .near_tangent import step_cap
from .singular import APEX_GUARD, closes_within_jump, jump_across, jump_past_edge, take_jump
from ..._lib import stages

# --- named limits -------------------------------------------------------------------------------------
#: The closure plane is put this far (relative to the curve scale) behind the start, so that the start
#: itself is never taken for a crossing ...
CLOSURE_OFFSET = 1e-8
#: ... and at least this many ulps of the start's largest coordinate, its round-off (a scene a million scales and more
#: from the origin: the march's first point, the start projected onto the curve, may lie that far on either side).
CLOSURE_OFFSET_ULPS = 64
#: A crossing of the closure plane within this many times that least offset of the start closes the curve too
#: (closure_radius: the crossing lies the offset behind the start, and off it by the round-off of the loop's places).
CLOSURE_OFFSET_RADII = 4.0
#: A crossing of the closure plane closes the curve if it lies within this distance (relative to the
#: curve scale) of the start and moves in the same direction (cosine above CLOSURE_COSINE).
CLOSURE_RADIUS = 1e-5
#: ... or within this many times rtol (relative to the scale), where that is more: a crossing is located on the
#: step's interpolant, whose error grows with rtol (at rtol 1e-4, RK45 places it 5e-5 of the scale along a small
#: loop from its start lap after lap, BDF farther still; at the default rtol the radius is CLOSURE_RADIUS's).
CLOSURE_RTOLS = 10.0
CLOSURE_COSINE = 0.9
#: A segment ends at each local minimum of sin(angle between the normals) along the path; a minimum below
#: this is a singular point: the node itself (where N1 x N2 flips) or, on a path a gap's width beside it,
#: the turn onto the other branch (a branch jump), which is never taken.
NODE_SUSPECT = 1e-4
#: A minimum of the sine below NODE_SUSPECT is a node only within this distance (relative to the scale) of a
#: singular point proven by the topology stage (sk.intersect's, or the search sk.trace runs at its first such
#: minimum).
KNOWN_NODE = 1e-3
#: An apex lies on the other surface, and so on the curve, within this many times the tolerance: the topology stage
#: seeds such apexes, and where its proof is not known only such an apex is a singular point of the curve.
APEX_ON_CURVE = 1e3
#: An apex event away from a proven apex is not watched again until a segment starts with the relative area element
#: above this many times APEX_GUARD.
APEX_REARM = 2.0
#: Where Newton fails with the normals closer to parallel than this (sine), the branch ends at a singular point.
NEWTON_NEAR_SINGULAR = 1e-3
#: A step may pass the start unseen: one that crosses the closure plane beside the start and back at the far side of
#: the loop shows no crossing (a loop the solver integrates exactly, a circle about a common axis whose parameters run
#: linearly in s, has a zero error estimate and steps of most of a lap, and would close a lap late). A branch that
#: closes with a segment whose longest step turns the tangent by more than LAP_TURN (radians: the step's length times
#: the larger curvature at its ends) is integrated again from that segment with steps turning it by at most MAX_TURN.
LAP_TURN = 0.75 * math.pi
MAX_TURN = 0.25 * math.pi
#: Arc-length step (relative to the curve scale) of the difference that gives the slope of that sine.
SLOPE_STEP = 1e-7
#: Minima are watched only where the sine is below this, and counted once its slope (times the scale)
#: rises above SLOPE_FLOOR, so that a constant sine (a circle on a surface of revolution) never triggers.
WATCH_BELOW = 1e-2
SLOPE_FLOOR = 1e-6
#: The minimum event is armed only this far (relative to the scale) into a segment.
MINIMUM_ARM = 1e-9
#: The method the compiled ones (spatialkin.ode.solvers.CompiledDOP853, CompiledRK45) hand hard cases to, with the
#: fine events (singular, apex, minimum, edges as crossings): the compiled DOP853, solve_ivp's DOP853 steps and event
#: location in compiled code (the same steps as solve_ivp's own DOP853, without Python per step).
FALLBACK_METHOD = "compiled"
#: The compiled integrator hands over this many times before a watched threshold (the sine's WATCH_BELOW or the
#: singular tolerance, APEX_GUARD), so that the fine events see the whole approach.
HANDOFF_MARGIN = 2.0
#: At most this many segments in one branch (each ends at an event): bounds the work on pathological input.
MAX_SEGMENTS = 10_000


#: The error estimator's order of solve_ivp's own methods (scipy's select_initial_step takes it; error_order).
SCIPY_ORDERS = {"RK23": 2, "RK45": 4, "DOP853": 7, "Radau": 3, "BDF": 1, "LSODA": 4}
#: Right-hand sides evaluated to choose a segment's first step (kernels.march.branch_ode.branch_first_step).
FIRST_STEP_EVALUATIONS = 2


def error_order(method):
    """The order of the method's error estimator, which shapes its first step (a compiled method's, a solve_ivp
    method's by name or class; 4 where it has none)."""
    solver = COMPILED_SOLVERS.get(method)
    if solver is not None:
        return rk.ERROR_ORDERS[solver.METHOD]
    return SCIPY_ORDERS.get(method, getattr(method, "error_estimator_order", 4))


def proven_nodes(settings):
    """The singular points the topology stage proved (settings.nodes), or None when they are not known. sk.intersect
    gives them; sk.trace asks for them once, at its first suspect point (settings.find_nodes runs the search), and
    gets None where the search cannot run."""
    if settings.nodes is None and settings.find_nodes is not None:
        settings.nodes, settings.find_nodes = settings.find_nodes(), None
    return settings.nodes


def known_node(point, settings):
    """True unless the topology stage has proven where the singular points are and none is near point (then a
    narrow waist between two branches, or a small loop round a critical point off the curve, is not a node: the
    branch goes round it); True wherever they are not known (proven_nodes)."""
    nodes = proven_nodes(settings)
    return nodes is None or node_distance(point, nodes) <= KNOWN_NODE * settings.scale


def node_distance(point, nodes):
    """Distance of the point (3,) to the nearest of the nodes ((K, 3) or None: singular points, or apexes); inf where
    there are none."""
    nodes = np.empty((0, 3)) if nodes is None else np.asarray(nodes, dtype=float).reshape(-1, 3)
    return float(np.min(np.linalg.norm(nodes - point, axis=1))) if len(nodes) else math.inf


def known_apex(point, settings, surfaces):
    """True where the apex of the surfaces (Settings.apexes: a cone's, a horn or spindle torus's points on its axis)
    nearest to point is a singular point of the curve: one the topology stage proved (known_node), or, where that
    is not known, one lying within APEX_ON_CURVE x the tolerance of both surfaces (else the curve passes beside it,
    and the branch goes round it). An apex event fires where a relative area element falls to APEX_GUARD, which lies
    farther from the apex than KNOWN_NODE where the element grows with the square of the distance (a horn torus's
    cusp: 0.02 x its minor radius), so the apex itself is tested, not the point of the event."""
    if not len(settings.apexes):
        return known_node(point, settings)
    apex = settings.apexes[np.argmin(np.linalg.norm(settings.apexes - point, axis=1))]
    if proven_nodes(settings) is None:
        return max(float(surf.distance(apex)) for surf in surfaces) <= APEX_ON_CURVE * settings.tolerance
    return known_node(apex, settings)


def area_weight(area_a, area_b):
    """Factor of the apex and area hand-over events: the relative area element grows by 1 / unit per unit of a
    length v (a cone's, unit the scene's scale), so below a unit of 1 it is weighted by the unit, keeping the
    events 1-Lipschitz in the state (kernels.rk.within_reach probes a step on that bound); 1 otherwise (their
    zeros are the same)."""
    units = [u for u in (area_a, area_b) if u > 0.0]
    return min([1.0] + units)


def branch_event_params(a, b, settings, start, direction):
    """The event parameters (kb.P_SIZE,) every segment of a branch shares (charts of the surfaces a, b,
    the closure plane through start normal to direction): all but the bounds and the closure's arm, which
    segment_system sets."""
    ep = np.zeros(kb.P_SIZE)
    ep[kb.P_SINGULAR_TOL] = settings.singular_tol
    ep[kb.P_FLAG_A], ep[kb.P_FLAG_B] = area_flag(a, settings.scale), area_flag(b, settings.scale)
    ep[kb.P_AREA_WEIGHT] = area_weight(ep[kb.P_FLAG_A], ep[kb.P_FLAG_B])
    ep[kb.P_APEX_GUARD] = APEX_GUARD
    ep[kb.P_SLOPE_STEP] = SLOPE_STEP * settings.scale
    ep[kb.P_SLOPE_FLOOR] = SLOPE_FLOOR / settings.scale
    ep[kb.P_MINIMUM_ARM] = MINIMUM_ARM * settings.scale
    ep[kb.P_WATCH_BELOW] = WATCH_BELOW
    ep[kb.P_HANDOFF_SINE] = HANDOFF_MARGIN * max(WATCH_BELOW, settings.singular_tol)
    ep[kb.P_HANDOFF_AREA] = HANDOFF_MARGIN * APEX_GUARD
    ep[kb.P_POLE_GUARD] = POLE_GUARD
    ep[kb.P_CLOSURE_OFFSET] = max(CLOSURE_OFFSET * settings.scale, closure_offset_floor(start))
    ep[kb.P_START:kb.P_START + 3] = start
    ep[kb.P_DIRECTION:kb.P_DIRECTION + 3] = direction
    return ep


def segment_system(a, b, settings, sign, s_arm, shared, bounds):
    """The System of one segment (charts a, b with their finite_bounds rows `bounds`; the closure armed past
    s_arm) with its event parameters: the branch's shared ones (branch_event_params) completed."""
    ep = shared.copy()
    for _, _, idx, bound, lower, slack, _ in bounds:
        j = 2 * idx + (0 if lower else 1)
        ep[kb.P_BOUND + j], ep[kb.P_SLACK + j] = bound, slack
    ep[kb.P_CLOSURE_ARM] = s_arm
    return System(kb.branch_rhs, kb.branch_events, kb.branch_advance, kb.branch_args(a, b, sign, settings.pullback),
                  ep, kb.COUNT)


def segment_events(system, settings, compiled, near_edge, bounds, recharts, watch_apex=True, band=False):
    """(Events as a Watch, kinds) of one segment, in a fixed order: singular, apex, minimum, boundaries, poles,
    closure (the apex unless watch_apex is False), and the sine's band where the segment's steps are capped beside a
    near tangency (band; near_tangent.step_cap).

    The compiled method watches levels instead of the first three: where the sine or the area element nears a hard case,
    the segment ends at the last step before (that step dropped) and the hand-over (FALLBACK_METHOD) goes on with the
    fine events; a sphere's chart ends the segment at the end of the step that passes its pole guard. A bound is a level
    too, until the branch is near_edge: then the next segment, started on the curve (projected) at most a step from the
    bound, ends exactly at the crossing, so that the curve's end on the edge has one step's accuracy, not the whole
    branch's drift. The compiled method probes the bounds inside each step too (spatialkin.kernels.ode.rk.PROBES), so that a
    curve grazing out of a trim and back within one step ends there, and the area hand-over likewise, so that no step
    passes over an apex (a horn torus's cusp, whose guarded zone a step can span). bounds: the charts' finite_bounds
    rows, recharts: whether each surface re-charts."""
    ep = system.eargs
    flagged = bool(ep[kb.P_FLAG_A] or ep[kb.P_FLAG_B]) and watch_apex
    plan, kinds = event_plan(compiled, near_edge, flagged, bounds, recharts, settings.close, band)
    return Watch([Event(system, i, d, level=level, probed=probed) for i, d, level, probed in plan],
                 system.n_events), list(kinds)


@functools.lru_cache(maxsize=256)
def event_plan(compiled, near_edge, flagged, bounds, recharts, close, band=False):
    """segment_events' plan: ((event index, direction, level, probed), ...) and the kinds
    (what integrate_branch does at each), for the method (compiled or not), near_edge, whether an area element is
    watched (flagged), the finite_bounds rows, whether each surface re-charts, whether closure is watched and whether
    the sine's band is (all hashable: made once per combination)."""
    handoff = ("handoff", None)
    if compiled:
        plan = [(kb.HANDOFF_SINE, -1, handoff, "before")] + (
            [(kb.HANDOFF_AREA, -1, handoff, "before")] if flagged else [])
    else:
        plan = [(kb.SINGULAR, -1, ("singular", None), None)] + (
            [(kb.APEX, -1, ("apex", None), None)] if flagged else []) + [(kb.MINIMUM, 1, ("minimum", None), None)]
    for k, j, idx, _, lower, _, _ in bounds:
        edge = kb.EDGE + 2 * idx + (0 if lower else 1)
        plan.append((edge, -1, ("near_edge", None), "before") if compiled and not near_edge
                    else (edge, -1, ("boundary", (k, j)), None))
    for k, rechart in enumerate(recharts):
        if rechart:
            plan.append((kb.POLE_A + k, -1, ("chart", k), "after" if compiled else None))
    if close:
        plan.append((kb.CLOSURE, 1, ("closure", None), None))
    if band and not compiled:
        plan.append((kb.BAND, -1, ("band", None), None))
    edges = range(kb.EDGE, kb.EDGE + 8)
    return (tuple((i, d, level, compiled and (i in edges or i == kb.HANDOFF_AREA)) for i, d, _, level in plan),
            tuple(kind for _, _, kind, _ in plan))


def lapping(branch, max_step):
    """(index of the first segment of the branch whose longest step turns the tangent by more than LAP_TURN, the
    largest step that turns it by MAX_TURN where that step bends most, at most max_step), or None. A step that hides
    a pass by the start turns the tangent by more than half a turn: on a loop integrated exactly (a circle) every
    step turns it alike, and the longest most. Jumps across singular points are not steps."""
    for k, seg in enumerate(branch.segments):
        if len(seg.t) < 2 or seg.jump:
            continue
        step, bend = kc.longest_step_bend(seg.t, seg.y, seg.a, seg.b)
        if step * bend > LAP_TURN:
            return k, min(max_step, MAX_TURN / bend)
    return None


def lapped(branch, passed, point, direction, radius, s):
    """True, with the branch ended (status failed; rejoin: a point of the loop and its state), where the branch passes
    again a geometric event it passed already (within radius, moving the same way: cosine at least CLOSURE_COSINE)
    without having closed on its start: it went round a loop that does not pass the start, which lies off the curve
    (within the gap tolerance of both surfaces where they nearly touch, yet farther from the curve than the closure's
    radius; asked only where the start's sine allows that: from a start on the curve, such a lap crossed between
    branches, and the branch runs on to max_length, which sk.intersect refuses). The rejoin point is the last
    segment's stored state where the normals are farthest from parallel (a loop's events sit where they are closest:
    minima of the sine). Else the event is added to passed (a list of (point, direction))."""
    for seen, heading in passed:
        if passes_again(point, direction, seen, heading, radius):
            branch.rejoin = steadiest(branch.segments[-1:])
            branch.status, branch.message = outcome("lapped", s=s, point=branch.rejoin[0].tolist())
            return True
    passed.append((point.copy(), direction.copy()))
    return False


def steadiest(segments):
    """(point (3,), state (4,) in its segment's charts) of the segments' stored state where the normals are farthest
    from parallel."""
    best, where = -1.0, None
    for seg in segments:
        for k in range(seg.y.shape[1]):
            sine = kc.degeneracy(seg.y[:, k], seg.a, seg.b, 0.0, 0.0)
            if sine > best:
                best, where = sine, (seg, k)
    seg, k = where
    y = seg.y[:, k].copy()
    point = np.empty(3)
    kc.curve_frame(y, seg.a, seg.b, point, np.empty(3))
    return point, y


def may_be_off(settings, sine):
    """True where a start with this sine of the normals' angle may lie farther than the closure's radius from the
    curve: its gap (at most the gap tolerance) over the sine, to first order."""
    return settings.gap_tol > closure_radius(settings) * sine


def closure_radius(settings, start=None):
    """The distance from its start within which a crossing of the closure plane closes a branch (CLOSURE_RADIUS,
    CLOSURE_RTOLS), a length; given the start (3,), at least CLOSURE_OFFSET_RADII times the closure plane's offset's
    round-off floor there (branch_event_params: the crossing lies that far behind the start)."""
    radius = max(CLOSURE_RADIUS, CLOSURE_RTOLS * settings.rtol) * settings.scale
    if start is None:
        return radius
    return max(radius, CLOSURE_OFFSET_RADII * closure_offset_floor(start))


def closure_offset_floor(start):
    """CLOSURE_OFFSET_ULPS ulps of the start's (3,) largest coordinate: the least offset of the closure plane."""
    return CLOSURE_OFFSET_ULPS * np.spacing(float(np.max(np.abs(start))))


def passes_again(point, heading, place, direction, radius):
    """True where point lies within radius of place and heading (the unit direction of travel at point) has a cosine
    of at least CLOSURE_COSINE with direction (place's): the branch passes place again, the same way."""
    gap = point - place
    return math.sqrt(gap.dot(gap)) <= radius and float(heading.dot(direction)) >= CLOSURE_COSINE


def at_outer_edge(a, b, y, sign, bounds, units):
    """True where y lies on (or past) an edge of a trimmed surface and the direction of travel leaves it (a curve
    running along the edge does not leave it). bounds: finite_bounds(a, b); units (4,): each state parameter's unit
    (1 for an angle, the scene's scale for a length: SurfaceTraits.parameter_units), in which the rates are
    compared (an angle's and a length's rates otherwise differ by the scale); the direction of travel is evaluated
    only at an edge."""
    dy = None
    for k, _, idx, bound, lower, _, size in bounds:
        inside = y[idx] - bound if lower else bound - y[idx]
        if not inside <= EDGE_TOL * max(min(units[idx], size), abs(bound)):
            continue
        if dy is None:
            dy = kc.dragilev_rhs(0.0, y, a, b, sign, 0.0)
        rate = (dy[idx] if lower else -dy[idx]) / units[idx]
        if rate < -EDGE_RATE * math.hypot(dy[2 * k] / units[2 * k], dy[2 * k + 1] / units[2 * k + 1]):
            return True
    return False


def integrate_branch(a_surface, b_surface, point, tangent, y_start, sign, settings):
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
    radius = closure_radius(settings, start)
    compiled = settings.method in COMPILED_SOLVERS
    near_edge = False
    watch_apex = True
    a_user, b_user = a_surface.data, b_surface.data
    recharts = (a_surface.traits.recharts, b_surface.traits.recharts)
    shared = branch_event_params(a_surface, b_surface, settings, start, direction)
    area = (float(shared[kb.P_FLAG_A]), float(shared[kb.P_FLAG_B]))        # every segment's area_flag
    # a re-chart turns a chart's axes only: every segment's charts have the user's bounds, and for one method and
    # near_edge the same events, made once per branch and pointed at each segment's System
    bounds = finite_bounds(a_user, b_user)
    units = tuple(a_surface.traits.parameter_units(settings.scale).tolist() +
                  b_surface.traits.parameter_units(settings.scale).tolist())
    watched = {}
    max_step = settings.max_step
    passed = []             # (point, direction) of the geometric events passed (minima, charts, crossings elsewhere)
    last_cap = math.inf     # the last segment's step cap beside a near tangency (near_tangent)
    off_start = None        # whether the start may lie off the curve by more than the closure's radius (laps watched)
    for _ in range(MAX_SEGMENTS):
        y_prev = y
        mark = stages.enter("correction") if stages.ON else None
        # the charts (re-charted along the curvature vector), the state and its projection in one compiled call
        a, b, y, point, tangent, ok = segment_start(a_user, b_user, recharts, point, sign * tangent, y, settings)
        if mark is not None:
            stages.leave(mark)
        if not ok and branch.segments and not branch.segments[-1].jump:
            # a restart beside a singular point: pass it from the last integrated segment instead
            last = branch.segments[-1]
            jump = jump_across(branch, last, last.s1 - last.s0, y_prev, settings)
            if jump is not None:
                sign, y, point, tangent = take_jump(branch, last, y_prev, jump)
                s = branch.segments[-1].s1
                last_cap = math.inf      # (landed clear of the singular point: its cap starts afresh)
                continue
        if not ok:
            sin_normals = kc.degeneracy(y, a, b, 0.0, 0.0)
            if sin_normals < NEWTON_NEAR_SINGULAR:
                branch.status, branch.message = outcome("newton_singular", sin=sin_normals, s=s,
                                                        point=point.tolist())
            else:
                branch.status, branch.message = outcome("newton_failed", s=s)
            break
        if off_start is None:
            off_start = may_be_off(settings, kc.degeneracy(y, a, b, 0.0, 0.0))
        if at_outer_edge(a, b, y, sign, bounds, units):
            branch.status, branch.message = outcome("leaves_edge", s=s)
            break
        if not watch_apex and kc.area_degeneracy(y, a, b, area[0], area[1]) > APEX_REARM * APEX_GUARD:
            watch_apex = True            # clear of the apex passed beside: watched again
        # beside a near tangency, steps shorter than the gap two branches may pass each other at (near_tangent)
        cap = None if compiled else step_cap(y, a, b, sign, SLOPE_STEP * settings.scale, last_cap,
                                             node_distance(point, settings.nodes), settings.scale)
        last_cap = math.inf if cap is None else cap[0]
        system = segment_system(a, b, settings, sign, s_arm - s, shared, bounds)
        if cap is not None:
            system.eargs[kb.P_BAND_LO], system.eargs[kb.P_BAND_HI] = cap[1]
        key = (compiled, near_edge, watch_apex, cap is not None)
        if key not in watched:
            watched[key] = segment_events(system, settings, compiled, near_edge, bounds, recharts, watch_apex,
                                          cap is not None)
        events, kinds = watched[key]
        for event in events:
            event.system = system
        method = settings.method if compiled or settings.method not in COMPILED_SOLVERS else FALLBACK_METHOD
        if s >= settings.max_length:         # (a jump across a singular point may land beyond it)
            branch.status, branch.message = outcome("max_length", max_length=settings.max_length)
            break
        mark = stages.enter("integration") if stages.ON else None
        span, longest = settings.max_length - s, max_step if cap is None else min(max_step, cap[0])
        # (the first step in units of the scale: the march of a scaled scene is the same, scaled)
        first = kb.branch_first_step(y, system.args, span, longest, settings.rtol, settings.atol, error_order(method),
                                     settings.scale)
        branch.nfev += FIRST_STEP_EVALUATIONS
        try:
            res = integrate(system, (0.0, span), y, method, events, settings.rtol, settings.atol, longest,
                            SEGMENT_MAX_EVALUATIONS, first)
        except BudgetExceeded:
            branch.status, branch.message = outcome("stalled", s=s, budget=SEGMENT_MAX_EVALUATIONS,
                                                    point=point.tolist())
            break
        finally:
            if mark is not None:
                stages.leave(mark)
        # (solve_ivp's OdeResult read once, as the dict it is)
        status, t_events, y_events, steps = res["status"], res["t_events"], res["y_events"], res["sol"]
        branch.nfev += res["nfev"]           # steps: the record of the segment's steps (spatialkin.ode.record.Steps)
        ts, ys = steps.t, steps.y.T
        seg = Segment(s0=s, s1=s + ts[-1], sign=sign, sol=steps, a=a, b=b, t=ts, y=ys, compiled=compiled,
                      area=area)
        if ts[-1] > 0:
            branch.segments.append(seg)
        s = seg.s1
        y = ys[:, -1].copy()
        if status == -1 and steps.budget_exceeded:
            kc.curve_frame(y, a, b, point, tangent)          # (the point where it ran out, not the segment's start)
            branch.status, branch.message = outcome("stalled", s=s, budget=SEGMENT_MAX_EVALUATIONS,
                                                    point=point.tolist())
            break
        if status == -1:
            if compiled:
                compiled = False         # the step size collapsed: solve_ivp's method from here on
                kc.curve_frame(y, a, b, point, tangent)
                continue
            if kc.degeneracy(y, a, b, 0.0, 0.0) < NODE_SUSPECT:
                branch.status, branch.message = outcome("solver_singular", s=s)
            else:
                branch.status, branch.message = outcome("solver_failed", s=s, message=res["message"])
            break
        if status == 0:
            branch.status, branch.message = outcome("max_length", max_length=settings.max_length)
            break
        hit = 0
        while not t_events[hit].size:       # (the first event that fired)
            hit += 1
        kind, info = kinds[hit]
        y = y_events[hit][0].copy()
        kc.curve_frame(y, a, b, point, tangent)
        if kind == "handoff":
            compiled = False
            continue
        if kind == "near_edge":
            near_edge = True
            continue
        if kind == "band":
            continue
        # (a trim edge met beside a node, where the traced path is off the curve by gap / sine, may be the node's
        # own crossing of the edge: it is taken through the node, and the jump ends on the edge)
        singular = kind == "singular" or (kind == "apex" and known_apex(point, settings, (a_surface, b_surface))) or (
            kind in ("minimum", "chart", "boundary") and kc.degeneracy(y, a, b, 0.0, 0.0) < NODE_SUSPECT
            and known_node(point, settings))
        jump = jump_across(branch, seg, t_events[hit][0], y, settings) if singular else None
        if jump is None and kind == "boundary":
            singular = False                 # (no way through the node: the edge ends the branch, as any edge)
        if singular:
            if jump is None:
                what = ("a parametrisation degenerates (apex of a cone or axis point of a horn/spindle torus)"
                        if kind == "apex" else "singular point (branches cross or the surfaces touch)")
                branch.status, branch.message = outcome("not_passed", what=what, s=s, point=point.tolist(),
                                                        sin=kc.degeneracy(y, a, b, 0.0, 0.0))
                break
            clipped = jump_past_edge(jump, a, b, bounds, settings.gap_tol)
            if clipped is not None:              # the curve leaves a trimmed surface inside the jump: it ends there
                jump, (k, j) = clipped
                sign, y, point, tangent = take_jump(branch, seg, y, jump)
                s = branch.segments[-1].s1
                branch.status, branch.message = outcome("edge", edge=EDGE_NAMES[j], surface="ab"[k], s=s)
                break
            sign, y, point, tangent = take_jump(branch, seg, y, jump)
            s = branch.segments[-1].s1
            last_cap = math.inf
            closing = closes_within_jump(branch.segments[-1], start, direction, CLOSURE_COSINE)
            if closing is not None:
                branch.status, branch.message = outcome("closed_in_jump", s=closing)
                branch.length = closing
                branch.end_state = y
                return branch
            continue
        if kind in ("minimum", "chart"):
            if off_start and lapped(branch, passed, point, sign * tangent, radius, s):
                break
            continue
        if kind == "apex":                   # beside an apex the topology stage proved off the curve: go round it,
            watch_apex = False               # unwatched until clear of it (else its event fires again at each start)
            continue
        if kind == "closure":
            mark = stages.enter("correction") if stages.ON else None
            yp, p_e, t_e, _ = project_state(y, a, b, settings)
            if mark is not None:
                stages.leave(mark)
            if passes_again(p_e, sign * t_e, start, direction, radius):
                redo = lapping(branch, max_step)
                if redo is not None:             # integrated again from that segment, with shorter steps
                    k, max_step = redo
                    passed.clear()       # (passed again on the way)
                    seg = branch.segments[k]
                    del branch.segments[k:]
                    s, sign, a, b, y, compiled = seg.s0, seg.sign, seg.a, seg.b, seg.y[:, 0].copy(), seg.compiled
                    kc.curve_frame(y, a, b, point, tangent)
                    continue
                remaining = float((start - p_e).dot(sign * t_e))
                branch.status, branch.message = outcome("closed", s=s + remaining)
                branch.length = s + remaining
                branch.end_state = yp
                return branch
            s_arm = s          # a crossing elsewhere: go on, re-armed past it
            if off_start and lapped(branch, passed, p_e, sign * t_e, radius, s):
                break
            continue
        if kind == "boundary":
            k, j = info
            name = "ab"[k]
            which = EDGE_NAMES[j]
            branch.status, branch.message = outcome("edge", edge=which, surface=name, s=s)
            edge_state = y.copy()
            edge_state[2 * k + j // 2] = (a, b)[k][ks.BOUNDS + j]
            snapped = newton_fixed(a, b, edge_state, 2 * k + j // 2, settings.gap_tol)
            if snapped is not None:      # end exactly on the edge
                y = snapped
                seg.y[:, -1] = y
            break
    else:
        branch.status, branch.message = outcome("too_many_segments", count=MAX_SEGMENTS)
    branch.length = s
    branch.end_state = y
    return branch
