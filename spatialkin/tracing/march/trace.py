"""The march of one component from a point on it (trace_from: both directions, then the corrected, re-measured
curve), and the settings of a march (options checked, lengths scaled by the scene).

References
----------
"Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines of the
light industry" (in Ukrainian; [Looper]): Dragilev's method, the intersection line parametrised by arc length as
the solution of a Cauchy problem.
E. Hairer, S. P. Nørsett, G. Wanner, Solving Ordinary Differential Equations I, 2nd ed., Springer, 1993: the
Dormand-Prince pairs (DOP853), dense output and step-size control.
"""
import dataclasses
import functools
import math
import time

import numpy as np

from ...kernels.march import curve as kc
from ...kernels.curve import stored as kst
from ...kernels.geometry import surfaces as ks
from .arclength import remeasure_branch
from .ivp import NODE_SUSPECT, integrate_branch, may_be_off, node_distance, steadiest
from ...ode.solvers import COMPILED, COMPILED_SOLVERS
from .segments import NEWTON_MAX_ITER, Settings, charts_at
from ..curve.dense import CLOSEST_CANDIDATES, CLOSEST_NEWTON_STEPS, Span, TracedSolution
from ..curve.result import CurveResult, TracingError, DUPLICATE_SPACING
from .start import locate_on_curve, scale_of, scene_reading
from ..curve.status import CLOSED, FAILED, MAX_LENGTH, SINGULAR, open_outcome, outcome
from ..._lib import stages
from ..._lib.validation import check_choice, check_nonnegative, check_positive

# --- defaults -----------------------------------------------------------------------------------------
#: Relative tolerance of solve_ivp on (u1, v1, u2, v2): sets how far a step may stray before the Newton
#: correction; positions are corrected onto both surfaces independently of it.
DEFAULT_RTOL = 1e-10
#: The branch stops where sin(angle between the normals) falls below this (a singular point).
DEFAULT_SINGULAR_TOL = 1e-7
#: Pull-back rate times the curve scale: the gap decays like exp(-PULLBACK * s / scale).
DEFAULT_PULLBACK = 1.0
#: The integrator: solve_ivp with the compiled Dormand–Prince 8(5,3) (spatialkin.ode.solvers.COMPILED), or a
#: solve_ivp method.
DEFAULT_METHOD = COMPILED
#: Longest solver step, in scene scales. DOP853's error estimate (its 5th- and 3rd-order estimates combined) can
#: be optimistic on long steps: on a circle of radius 0.93 (the aligned plane-torus stress case) it accepts steps
#: of 0.75 with 40 times the tolerance's local error, and the loop's length comes out 4.8e-9 (relative) off. With
#: steps at most 0.2 the 319 traced stress cases' lengths lie within 1.8e-10 x scale of a reference (RK45 at
#: rtol 1e-13) in 99% of cases, closer than RK45's steps (7.2e-10), for about 2% more time.
MAX_STEP = 0.2
#: Without a max_length, a branch may run this many times 2 pi times the larger surface extent.
MAX_LENGTH_TURNS = 32
#: Points of an open curve traced from a start beside a singular point or possibly off the curve (may_be_off) tested
#: for running over the curve's own path (over_itself), evenly in arc length, both ends included.
OVERLAP_SAMPLES = 5
#: An open curve whose two ends stop at singular points runs over itself where an end lies within OVER_ITSELF x
#: scale of its own path farther than ITSELF_CLEAR x scale (in arc length) from that end: a jump across a singular
#: point landed on a branch the curve had followed already (a loop through the point shorter than the jump).
OVER_ITSELF, ITSELF_CLEAR = 1e-6, 1e-2
#: A start closer than APEX_CLEAR x scale to an apex of the surfaces is first carried along the curve by twice
#: that: a curve passing a cone's apex at a distance d turns from near one ruling to near another within about d,
#: so that its tangent at such a start is not the one it comes back with, and the loop would not close.
APEX_CLEAR = 1e-3
#: Newton's target for |M1 - M2|, as a fraction of the requested tolerance ...
GAP_FRACTION = 1e-2
#: ... but never below this many ulps of the coordinates' magnitude (round-off floor).
ROUNDOFF_ULPS = 64
#: The ulp of 1.0 (np.float64).
EPS = np.finfo(float).eps
#: Smallest rtol, singular_tol and atol (atol per unit of each parameter: 1 for an angle, the scene scale for a
#: length): about 45 ulps of 1. Below it the tolerances ask for less than the round-off of the error estimates and
#: the normals' sine, and the steps shrink until the budget runs out.
TOLERANCE_MIN = 1e-14
#: singular_tol lies below this: the integrator hands over to the fine events at HANDOFF_MARGIN (2) times it, a
#: sine that must stay below 1 (sin 30 degrees; a branch stopped there is no longer near a singular point).
SINGULAR_TOL_MAX = 0.5
#: Largest pullback. Above about 10 the pull-back term's stiffness sets the solver's steps, and their number grows in
#: proportion to it with no accuracy gained (Newton puts every stored point on both surfaces), until a segment's
#: budget of evaluations runs out.
PULLBACK_MAX = 100.0
#: solve_ivp's methods, "compiled": solve_ivp with spatialkin.ode.solvers.CompiledDOP853 (scipy's DOP853 steps,
#: many per solver step in compiled code), and "compiled-rk45" (CompiledRK45: scipy's RK45 steps), both handing hard
#: cases to the compiled DOP853 with the fine events (spatialkin.tracing.march.ivp.FALLBACK_METHOD).
METHODS = ("DOP853", "RK45", "RK23", "Radau", "BDF", "LSODA", *COMPILED_SOLVERS)


def _check_options(tol, method, rtol, atol, max_length, singular_tol, pullback):
    """(tol, rtol, atol, max_length, singular_tol, pullback) checked (atol and max_length may be None); none
    depends on the surfaces (atol's floor for length parameters: make_settings).

    Raises
    ------
    TypeError
        Naming an option that is not a real number (a str, a bool).
    ValueError
        Naming an option out of its range: tol, max_length > 0; rtol in [TOLERANCE_MIN, 1); atol >= TOLERANCE_MIN;
        singular_tol in [TOLERANCE_MIN, SINGULAR_TOL_MAX); pullback in [0, PULLBACK_MAX]; method one of METHODS.
    """
    tol = check_positive("tol", tol, strict=True)
    rtol = check_positive("rtol", rtol, strict=True)
    if not TOLERANCE_MIN <= rtol < 1.0:
        raise ValueError(f"rtol must lie in [{TOLERANCE_MIN:g}, 1), got {rtol!r}")
    check_choice("method", method, METHODS)
    if atol is not None:
        atol = check_positive("atol", atol, strict=True)
        if atol < TOLERANCE_MIN:
            raise ValueError(f"atol must be at least {TOLERANCE_MIN:g}, got {atol!r}")
    max_length = None if max_length is None else check_positive("max_length", max_length, strict=True)
    singular_tol = check_positive("singular_tol", singular_tol, strict=True)
    if not TOLERANCE_MIN <= singular_tol < SINGULAR_TOL_MAX:
        raise ValueError(f"singular_tol must lie in [{TOLERANCE_MIN:g}, {SINGULAR_TOL_MAX:g}) (a sine of the angle "
                         f"between the normals), got {singular_tol!r}")
    pullback = check_nonnegative("pullback", pullback, strict=True)
    if pullback > PULLBACK_MAX:
        raise ValueError(f"pullback must lie in [0, {PULLBACK_MAX:g}], got {pullback!r}")
    return tol, rtol, atol, max_length, singular_tol, pullback


#: check_options of the options of recent calls (a bad one raises, and is not kept).
_checked_options = functools.lru_cache(maxsize=64, typed=True)(_check_options)


def check_options(tol, method, rtol, atol, max_length, singular_tol, pullback):
    """The options checked as _check_options checks them (raising as it does), its answer kept for the options of
    recent calls (by value and type: True is not 1; a bad one is not kept); an unhashable option (a 0-d array)
    checked each time."""
    options = (tol, method, rtol, atol, max_length, singular_tol, pullback)
    try:
        hash(options)
    except TypeError:                       # (an unhashable option: a 0-d array)
        return _check_options(*options)
    return _checked_options(*options)


def make_settings(a, b, tol, method, rtol, atol, max_length, singular_tol, pullback, close, anchor, scene=None):
    """Validated numerical settings, absolute lengths scaled by the scene; scene: the checked options and the
    lengths already made for these arguments (spatialkin.tracing.closed.forms.closed_settings' Scene.checked), else
    made here."""
    if scene is None:
        options = check_options(tol, method, rtol, atol, max_length, singular_tol, pullback)
        magnitude = max(abs(x) for x in anchor.tolist())
        scene = options, scene_lengths(a, b, options[0], options[3], magnitude)
    (tol, rtol, atol, _, singular_tol, pullback), (scale, tolerance, gap_tol, max_length) = scene
    if atol is None:
        # angles get rtol, lengths (plane u, v; cylinder and cone v) rtol * scale
        atol = rtol * np.concatenate([a.traits.parameter_units(scale), b.traits.parameter_units(scale)])
    else:
        unit = max(a.traits.parameter_units(scale).max(), b.traits.parameter_units(scale).max())
        if atol < TOLERANCE_MIN * unit:
            raise ValueError(f"atol must be at least {TOLERANCE_MIN:g} x the scale {unit:.6g} of the length "
                             f"parameters, got {atol!r}")
        atol = np.full(4, atol)
    return Settings(method=method, rtol=rtol, atol=atol, gap_tol=gap_tol, scale=scale, tolerance=tolerance,
                    singular_tol=singular_tol, pullback=pullback / scale, max_length=max_length,
                    max_step=MAX_STEP * scale, close=close, apexes=apex_points(a, b))


def apex_points(a, b):
    """(K, 3) the apexes of both surfaces (a cone's, a horn or spindle torus's points on its axis)."""
    rows = []
    for surface in (a, b):
        vs = surface.traits.apexes(surface)
        if vs:
            out = np.empty((len(vs), 3))
            ks.evaluate(surface.data, np.array([(0.0, v) for v in vs], dtype=float), out)
            rows.append(out)
    return np.concatenate(rows) if len(rows) > 1 else rows[0] if rows else np.empty((0, 3))


def scene_lengths(a, b, tol, max_length, magnitude):
    """(scale, tolerance, gap_tol, max_length) of the settings (see make_settings; tol and max_length checked,
    max_length None for the default), magnitude the largest |coordinate| of the surfaces' origins."""
    first, second = scene_reading(a), scene_reading(b)
    scale = scale_of(first, second)
    if max_length is None:
        bound = min(first[2], second[2])
        max_length = MAX_LENGTH_TURNS * 2 * math.pi * (bound if math.isfinite(bound) else 1e3 * scale)
    magnitude = max(scale, magnitude)
    gap_tol = max(GAP_FRACTION * tol * scale, ROUNDOFF_ULPS * EPS * magnitude)
    tolerance = max(tol * scale, ROUNDOFF_ULPS * EPS * magnitude)
    return scale, tolerance, gap_tol, max_length


class OffCurve(TracingError):
    """The march from a start off the curve (within the gap tolerance of both surfaces where they nearly touch) or
    beside a singular point went round a loop without passing the start, or both its branches went round it, running
    over each other. rejoin: (point (3,), state (4,) in the march's charts) on that loop, where the normals are
    farthest from parallel."""

    def __init__(self, message, rejoin):
        super().__init__(message, where=rejoin[0])
        self.rejoin = rejoin


def trace_from(a, b, point, y, settings, t_start, known=None):
    """Trace both directions from a point on the curve: the CurveResult of the component, with its dense
    output. A start off the curve (OffCurve) is moved, once, onto the loop its march went round (located there by
    Newton from the march's state) and the component traced from that point; None where known (a callable of that
    point, or None) says its component is traced already."""
    try:
        return component_from(a, b, point, y, settings, t_start)
    except OffCurve as off:
        rejoin = off.rejoin
    point, y = locate_on_curve(a, b, rejoin[0], settings.gap_tol, rejoin[1])
    if known is not None and known(point):
        return None
    return component_from(a, b, point, y, settings, t_start)


def component_from(a, b, point, y, settings, t_start):
    """trace_from's march from one start."""
    point, y = clear_of_apexes(a, b, point, y, settings)
    tangent = np.empty(3)
    p = np.empty(3)
    a_chart, b_chart, y_chart = charts_at(a, b, point, np.zeros(3), y)
    sin_normals = kc.curve_frame(y_chart, a_chart, b_chart, p, tangent)
    if sin_normals < settings.singular_tol:
        raise TracingError.of("singular_start", where=point, point=point.tolist(), sin=sin_normals)
    forward = measured_branch(a, b, point, tangent, y, 1.0, settings)
    nfev = forward.nfev
    if forward.status == CLOSED:
        branches = [(forward, 1.0, 0.0)]
        closed, length = True, forward.length
        status, message = CLOSED, forward.message
    else:
        backward = measured_branch(a, b, point, tangent, y, -1.0, settings)
        nfev += backward.nfev
        if backward.status == CLOSED:
            branches = [(backward, 1.0, 0.0)]
            closed, length = True, backward.length
            status, message = CLOSED, backward.message
        else:
            branches = [(backward, -1.0, backward.length), (forward, 1.0, backward.length)]
            closed, length = False, backward.length + forward.length
            status, message = open_outcome(backward.status, backward.message, forward.status, forward.message)
    mark = stages.enter("result") if stages.ON else None
    spans, ys, ss, counts = [], [], [], []
    for branch, flip, offset in branches:
        pieces = []
        for seg in branch.segments:
            if flip > 0:
                lo, hi, shift = offset + seg.s0, offset + seg.s1, -(offset + seg.s0)
                s_pts = offset + seg.s0 + seg.t
            else:
                lo, hi, shift = offset - seg.s1, offset - seg.s0, offset - seg.s0
                s_pts = offset - seg.s0 - seg.t
            pieces.append((Span(lo, hi, flip, shift, seg), s_pts, seg.y.T))
        if flip < 0:
            pieces.reverse()
        for span, s_pts, y_pts in pieces:
            s_pts, y_pts = in_order(s_pts, y_pts)
            spans.append(span)
            ss.append(s_pts)
            ys.append(y_pts)
            counts.append(len(s_pts))
    if not ss:
        raise TracingError.of("nothing_traced", where=point, status=status, point=point.tolist(), message=message)
    s_all = np.concatenate(ss)
    y_all = np.ascontiguousarray(np.concatenate(ys))
    span_of = np.arange(len(spans)).repeat(counts)
    keep = np.empty(len(s_all), dtype=bool)
    keep[0] = True
    keep[1:] = s_all[1:] - s_all[:-1] > DUPLICATE_SPACING * settings.scale
    if closed:
        spans[-1].hi = length
        keep &= s_all < length - DUPLICATE_SPACING * settings.scale
    s_all, y_all, span_of = s_all[keep], y_all[keep], span_of[keep]
    inner = stages.enter("correction") if stages.ON else None
    points, params, raw_gap = _corrected(a, b, y_all, span_of, spans, settings)
    if inner is not None:
        stages.leave(inner)
    if closed:
        points = np.concatenate([points, points[:1]])
        params = np.concatenate([params, _closing_params(a, b, params[0], params[-1])[None]])
        s_all = np.concatenate([s_all, [length]])
    nodes = np.array([p for branch, _, _ in branches for _, p in branch.nodes]).reshape(-1, 3)
    sol = TracedSolution(surfaces=(a, b), spans=spans, nodes=nodes, gap_tol=settings.gap_tol, length=length,
                         closed=closed, knots=s_all)
    if not closed and backward.status == SINGULAR and forward.status == SINGULAR:
        overlap = over_itself(sol, settings.scale)
        if overlap is not None:
            end, gap, s_near = overlap
            raise TracingError.of("runs_over_itself", where=end, point=np.round(end, 12).tolist(), gap=gap, s=s_near)
    elif not closed and (sin_normals < NODE_SUSPECT or may_be_off(settings, sin_normals)):
        # a start beside a singular point or off the curve whose two branches went round one loop and stopped at a
        # trim edge (one the loop comes within the gap tolerance of where the surfaces nearly touch): traced again
        # from the loop's point where the normals are farthest from parallel
        overlap = over_itself(sol, settings.scale, np.linspace(0.0, length, OVERLAP_SAMPLES))
        if overlap is not None:
            rejoin = steadiest([seg for branch, _, _ in branches for seg in branch.segments])
            raise OffCurve(outcome("off_curve", point=np.round(point, 12).tolist(),
                                   rejoin=np.round(rejoin[0], 12).tolist())[1], rejoin)
    result = CurveResult(points=points, s=s_all, params=params, closed=closed, length=length, status=status,
                         message=message, tolerance=settings.tolerance, sol=sol, nodes=nodes, solver_gap=raw_gap,
                         nfev=nfev, wall_time=time.perf_counter() - t_start)
    if mark is not None:
        stages.leave(mark)
    return result


def over_itself(sol, scale, at=None):
    """(end (3,), gap, s) where an end of the open curve (its dense output sol; or a point at one of the arc lengths
    `at`) lies within OVER_ITSELF x scale of the curve's own path at an arc length s more than ITSELF_CLEAR x scale
    from it (the nearest of the CLOSEST_CANDIDATES grid points there, refined by Newton in s); None where none
    does."""
    grid_s, grid = sol.grid()
    clear = ITSELF_CLEAR * scale
    for s_end in ((0.0, sol.length) if at is None else at):
        end = np.asarray(sol(s_end), dtype=float).reshape(3)
        far = np.nonzero(np.abs(grid_s - s_end) > clear)[0]
        if not len(far):
            continue
        near = far[np.argsort(np.linalg.norm(grid[far] - end, axis=1))[:CLOSEST_CANDIDATES]]
        s, gap = sol.foot_points(np.repeat(end[None], len(near), axis=0), grid_s[near], CLOSEST_NEWTON_STEPS)
        hit = np.nonzero((np.abs(s - s_end) > clear) & (gap <= OVER_ITSELF * scale))[0]
        if len(hit):
            return end, float(gap[hit[0]]), float(s[hit[0]])
    return None


def in_order(s, y):
    """(s (m,), y (m, 4)) sorted by s (np.argsort's order): as given where s strictly increases, reversed where it
    strictly decreases (the order every sort gives distinct keys), else by np.argsort."""
    if len(s) < 2 or (s[1:] > s[:-1]).all():
        return s, y
    if (s[1:] < s[:-1]).all():
        return s[::-1], y[::-1]
    order = np.argsort(s)
    return s[order], y[order]


def clear_of_apexes(a, b, point, y, settings):
    """(point, y) the start itself, or, where it lies within APEX_CLEAR x scale of an apex of the surfaces, the
    point twice that far along the curve (forward; the start itself where the curve ends before, or where the way
    there crosses a singular point)."""
    if not len(settings.apexes):
        return point, y
    clear = APEX_CLEAR * settings.scale
    if node_distance(point, settings.apexes) >= clear:
        return point, y
    tangent = np.empty(3)
    a_chart, b_chart, y_chart = charts_at(a, b, point, np.zeros(3), y)
    if kc.curve_frame(y_chart, a_chart, b_chart, np.empty(3), tangent) < settings.singular_tol:
        return point, y
    short = dataclasses.replace(settings, max_length=2.0 * clear)
    branch = integrate_branch(a, b, point, tangent, y, 1.0, short)
    if branch.status != MAX_LENGTH or not branch.segments or branch.nodes:
        return point, y             # (it ended, or it jumped across the apex: a loop through it may be shorter)
    try:
        return locate_on_curve(a, b, branch_end(branch, point), settings.gap_tol)
    except TracingError:
        return point, y


def measured_branch(a, b, point, tangent, y, sign, settings):
    """One direction integrated from point (integrate_branch) with its arc length re-measured on the curve
    (remeasure_branch, timed as correction)."""
    branch = integrate_branch(a, b, point, tangent, y, sign, settings)
    if branch.rejoin is not None:
        raise OffCurve(outcome("off_curve", point=np.round(point, 12).tolist(),
                               rejoin=np.round(branch.rejoin[0], 12).tolist())[1], branch.rejoin)
    if branch.status == FAILED:
        end = branch_end(branch, point)
        raise TracingError.of("branch_failed", where=end, point=np.round(end, 12).tolist(), message=branch.message)
    mark = stages.enter("correction") if stages.ON else None
    branch = remeasure_branch(branch, settings.pullback, settings.gap_tol)
    if mark is not None:
        stages.leave(mark)
    return branch


def branch_end(branch, start):
    """The point (3,) where a branch stopped: its last state on its last segment's chart of a (start if it has
    no segment)."""
    if not branch.segments:
        return np.asarray(start, dtype=float)
    seg = branch.segments[-1]
    end = np.empty((1, 3))
    ks.evaluate(seg.a, np.ascontiguousarray(seg.y[:2, -1:].T), end)
    return end[0]


def _corrected(a, b, y_all, span_of, spans, settings):
    """Project the solver's step states onto the curve (each in its segment's charts); user parameters.
    span_of is non-decreasing (the states come span by span): one compiled call for all spans
    (kernels.stored.corrected_spans: per span, corrected_many and user_params' foot points where the span's chart
    is not the user's; then unwrap_turns of a re-charting surface's u)."""
    n = len(y_all)
    points, params, raw_gap = np.empty((n, 3)), np.empty((n, 4)), np.empty(n)
    breaks = (span_of[1:] != span_of[:-1]).nonzero()[0]
    cuts = np.empty(len(breaks) + 2, dtype=np.int64)
    cuts[0], cuts[1:-1], cuts[-1] = 0, breaks + 1, n
    segs = [spans[k].seg for k in span_of[cuts[:-1]].tolist()]
    recharts = bool(a.traits.recharts), bool(b.traits.recharts)
    # (a surface that re-charts has a chart of its own in every segment: segment_start makes one at each start)
    own = [np.zeros(len(segs), dtype=bool) | flag for flag in recharts]
    kst.corrected_spans(np.ascontiguousarray(y_all, dtype=float), cuts, np.array([seg.a for seg in segs]),
                        np.array([seg.b for seg in segs]), np.array([seg.normal for seg in segs], dtype=float),
                        a.data, b.data, own[0], own[1], recharts[0], recharts[1], settings.gap_tol, NEWTON_MAX_ITER,
                        points, params, raw_gap)
    return points, params, raw_gap


def _closing_params(a, b, first, last):
    """The parameters of the closing point: the first point's, shifted by whole turns in periodic u (and v)
    so that they continue the last point's."""
    out = first.copy()
    firsts, lasts = first.tolist(), last.tolist()
    for k, surface in enumerate((a, b)):
        for j, periodic in enumerate(surface.traits.periodic):
            if periodic:       # (round: to the nearest whole turn, half to even as np.rint)
                i = 2 * k + j
                out[i] = firsts[i] + 2 * math.pi * round((lasts[i] - firsts[i]) / (2 * math.pi))
    return out
