"""Components cut by trims after tracing: the trims that are not ranges of a length (spatialkin.geometry.trims:
angular ranges, a plane's circle; the tracer follows each component on the surfaces as the other trims leave
them), and, for a component traced again past a grazed edge (spatialkin.tracing.march.graze), the length trims too. This
module keeps the arcs that lie inside both faces, and the points where a curve touches an edge from outside.

Every limit is 1-Lipschitz in the point, so along a curve parametrised by arc length its value f(s) changes by
at most |s' - s| (plus the points' error, ``slack``). Between two samples s_k < s_k+1 a zero of f is possible
only where |f_k| + |f_k+1| <= (s_k+1 - s_k) + 2 slack: those intervals are cut, pass after pass (one evaluation
of the dense output per pass), until they are cleared or shorter than ``FINEST`` x scale, so no crossing, and no
pair of crossings between two samples, is missed: into ``SECTIONS`` equal parts, or, where f changes sign, at knots
growing geometrically away from its root (Brent's method), which the same test clears where the curve crosses the
edge at an angle (a
curve that only touches an edge to within that length is taken as touching: no crossing). Each crossing is then
solved on the dense output by Brent's method, exactly on the edge. The pieces between the crossings that lie
inside both regions (within slack: a curve lying along an edge is kept; a short piece within slack of an edge
between two inside ones is a touch from inside, cut by round-off) are the arcs returned; neighbours are merged,
and a closed component that never leaves is returned whole. Where the curve comes within slack of an edge from
outside without crossing it (a short piece, or an interval the cutting left), the faces meet in one point: the
point of the curve deepest in both faces there, found by bounded Brent minimisation, returned with length 0.

References
----------
R. P. Brent, Algorithms for Minimization without Derivatives, Prentice-Hall, 1973 (the root on each crossing).
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM, 2009 (Lipschitz bounds on a
function's range over an interval).
"""
import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ...geometry.trims import inside_region, limits, region_values
from .dense import CurveSolution
from .exact import contact_point
from .result import CurveResult
from .status import BOUNDARY, CONTACT, TANGENT, open_outcome

#: Intervals that may hide a crossing are cut down to this length (relative to the scale) ...
FINEST = 1e-9
#: ... into this many parts a pass (a crossing's interval is open all the way down: the limit changes slower than
#: the arc length) ...
SECTIONS = 16
#: ... or, holding a sign change, at knots FINEST / 4 x GROWTH^j either side of its root ...
GROWTH = 2.0
#: ... and at most this many intervals are kept while cutting (a curve running along an edge stays unresolved
#: there, which is what it is: on the edge).
MOST_INTERVALS = 200_000
#: A piece between two cuts is tested at this many points (its ends included).
PIECE_SAMPLES = 7
#: A piece within slack of an edge all along is a touch of the edge (from outside: the component meets the face in
#: one point of its edge) when shorter than this many sqrt(slack x scale), the length over which a curve bending
#: at 1 / scale away from a straight edge stays within slack of it; longer, it runs along the edge (kept).
TOUCH_LENGTH = 20.0
#: The slack of the inside test and of the Lipschitz bound, in tolerances (the points' distance to the curve).
SLACK_TOLERANCES = 4.0


def clip_curves(a, b, curves, scale):
    """The CurveResults cut to the regions of a and b (all of them when neither has one)."""
    if not (a.region or b.region):
        return curves
    out = []
    for curve in curves:
        out += clip_curve(a, b, curve, scale)
    return out


def inside_both(a, b, points, slack):
    """(N,) bool: points inside the regions of both surfaces, within slack."""
    return inside_region(a, points, slack) & inside_region(b, points, slack)


def clip_curve(a, b, curve, scale):
    """The arcs (CurveResults) of one component inside both regions."""
    slack = SLACK_TOLERANCES * curve.tolerance
    if curve.length == 0.0:
        return [curve] if inside_both(a, b, curve.points[:1], slack)[0] else []
    cuts, touches = [], []
    for k, surface in enumerate((a, b)):
        for limit in limits(surface):
            more_cuts, more_touches = crossings(curve, surface, limit, k, slack, scale)
            cuts += more_cuts
            touches += more_touches
    cuts.sort(key=lambda cut: cut[0])
    length = curve.length
    if curve.closed and cuts:
        ends = cuts + [(cuts[0][0] + length, *cuts[0][1:])]
    else:
        ends = [(0.0, None, None)] + cuts + [(length, None, None)]
    pieces = list(zip(ends[:-1], ends[1:]))
    touch = TOUCH_LENGTH * np.sqrt(slack * scale)    # the longest a touch stays within slack of an edge
    verdicts = [piece_verdict(a, b, curve, lo[0], hi[0], slack, touch, across(lo, hi)) for lo, hi in pieces]
    n = len(verdicts)
    for i, verdict in enumerate(verdicts):         # a touch from inside, cut by round-off on both sides: inside
        inner = curve.closed or 0 < i < n - 1
        if verdict == TOUCHED and inner and verdicts[i - 1] == verdicts[(i + 1) % n] == INSIDE:
            verdicts[i] = INSIDE
    touches += [(lo[0], hi[0]) for (lo, hi), verdict in zip(pieces, verdicts) if verdict == TOUCHED]
    arcs = merged([piece for piece, verdict in zip(pieces, verdicts) if verdict == INSIDE], curve.closed, length)
    if len(arcs) == 1 and curve.closed and arcs[0][1][0] - arcs[0][0][0] >= length:
        return [curve]                               # whole: every touch lies on it
    ends = [end[0] for arc in arcs for end in arc if end[1] is not None]           # the crossings kept
    points = touch_points(a, b, curve, touches, ends, arcs, slack, scale, touch)
    return [window(curve, lo, hi) if hi[0] - lo[0] > curve.tolerance else short_arc(curve, lo[0], hi[0])
            for lo, hi in arcs] + points


def short_arc(curve, s0, s1):
    """An arc [s0, s1] no longer than the tolerance (a face narrower than that): the faces meet there in one point
    to that accuracy, its middle (face_point)."""
    s = 0.5 * (s0 + s1)
    return face_point(curve, curve.sol(np.array([s % curve.length if curve.closed else s]))[0])


def face_point(curve, point):
    """A point (3,) of the component where the faces meet alone: a CurveResult of length 0, status 'boundary', or
    'contact' on a curve of tangency."""
    event = "contact" if curve.status in (TANGENT, CONTACT) else "edge_point"
    return contact_point(curve.sol.surfaces, point, curve.tolerance, event=event)


INSIDE, OUTSIDE, TOUCHED = "inside", "outside", "touched"


def across(lo, hi):
    """True when a piece runs between the cuts (s, limit, surface) lo and hi of two different edges: a curve that
    comes within slack of an edge and leaves again cuts that one edge twice, or not at all."""
    return lo[1] is not None and hi[1] is not None and (lo[1] is not hi[1] or lo[2] != hi[2])


def piece_verdict(a, b, curve, s0, s1, slack, touch, crossing=False):
    """INSIDE when the piece [s0, s1] of the curve between two cuts lies inside both regions: a sample of it
    inside by more than slack, or, within slack of an edge all along, longer than a touch (touch, a length: a curve
    lying along the edge) or running from one edge to another (crossing: a face narrower than twice the slack);
    TOUCHED when neither (a curve touching an edge from outside); else OUTSIDE."""
    s = np.linspace(s0, s1, PIECE_SAMPLES)[1:-1]
    points = curve.sol(s % curve.length if curve.closed else s)
    if not inside_both(a, b, points, slack).all():
        return OUTSIDE
    if crossing or inside_both(a, b, points, -slack).any() or s1 - s0 > touch:
        return INSIDE
    return TOUCHED


def touch_points(a, b, curve, touches, cuts, arcs, slack, scale, reach):
    """Single points (CurveResults of length 0) where the curve touches an edge of the faces from outside: the
    intervals of touches ((s0, s1) within slack of an edge) joined where they lie within a touch's length (reach)
    of each other, less those as close to a crossing (cuts: the arc lengths of the arcs' ends on an edge), each
    point where the curve comes deepest into both regions there (bounded Brent on the dense output), kept when
    inside both within slack and on no arc kept. Status 'boundary' (the faces meet in
    one point of their edges), or 'contact' on a curve of tangency."""
    if not touches:
        return []
    length = curve.length
    spans = []
    for lo, hi in sorted(touches):
        if spans and lo <= spans[-1][1] + reach:
            spans[-1][1] = max(spans[-1][1], hi)
        else:
            spans.append([lo, hi])
    turns = (-length, 0.0, length) if curve.closed else (0.0,)
    out = []
    for lo, hi in spans:
        if any(lo - reach <= cut + turn <= hi + reach for cut in cuts for turn in turns):
            continue                                          # beside a crossing: no touch
        depth = lambda s: -float(np.min(np.concatenate(                 # noqa: E731 - the two regions' depth at s
            [region_values(x, curve.sol(np.array([s]))) for x in (a, b)], axis=1), initial=np.inf))
        s = minimize_scalar(depth, bounds=(lo, hi), method="bounded", options={"xatol": 1e-14 * scale}).x
        if any(lo_arc[0] - slack <= s + turn <= hi_arc[0] + slack for lo_arc, hi_arc in arcs
               for turn in ((0.0, length) if curve.closed else (0.0,))):
            continue
        point = curve.sol(np.array([s]))
        if inside_both(a, b, point, slack)[0] and all(np.linalg.norm(point[0] - q.points[0]) > reach for q in out):
            out.append(face_point(curve, point[0]))
    return out


def merged(pieces, closed, length):
    """Neighbouring pieces (lo end, hi end) joined (a cut between two kept pieces is no end); on a closed curve
    the last joins the first across s = length."""
    out = []
    for lo, hi in pieces:
        if out and out[-1][1][0] == lo[0]:
            out[-1] = (out[-1][0], hi)
        else:
            out.append((lo, hi))
    if closed and len(out) > 1 and out[-1][1][0] == out[0][0][0] + length:
        out[0] = (out[-1][0], (out[0][1][0] + length, *out[0][1][1:]))
        out.pop()
    return out


def crossings(curve, surface, limit, k, slack, scale):
    """([(s, limit, surface index k)] where the curve crosses the limit's edge (from inside to outside or back),
    [(s0, s1)] intervals where it lies within slack of the edge without crossing it)."""
    sol, length = curve.sol, curve.length
    frame = surface.frame

    def value(s):
        return limit(frame.local_of(sol(np.atleast_1d(s)).reshape(-1, 3)))

    s = np.unique(np.concatenate([curve.s, [0.0, length]]))
    f = value(s)
    lo_s, hi_s, lo_f, hi_f = s[:-1], s[1:], f[:-1], f[1:]
    finest = FINEST * scale
    xtol = 1e-15 * max(scale, length)
    done_s, done_f, known = [], [], []
    while len(lo_s):
        width = hi_s - lo_s
        open_ = np.abs(lo_f) + np.abs(hi_f) <= width + 2.0 * slack
        on_edge = (np.abs(lo_f) <= slack) & (np.abs(hi_f) <= slack)
        split = open_ & ~on_edge & (width > finest)
        settled = ~split
        done_s.append(np.stack([lo_s[settled], hi_s[settled]], axis=1))
        done_f.append(np.stack([lo_f[settled], hi_f[settled]], axis=1))
        lo_s, hi_s, lo_f, hi_f = lo_s[split], hi_s[split], lo_f[split], hi_f[split]
        if not len(lo_s) or len(lo_s) * SECTIONS > MOST_INTERVALS:
            if len(lo_s):
                done_s.append(np.stack([lo_s, hi_s], axis=1))
                done_f.append(np.stack([lo_f, hi_f], axis=1))
            break
        lo_s, hi_s, lo_f, hi_f = next_round(value, lo_s, hi_s, lo_f, hi_f, finest, xtol, known)
    ss, ff = np.concatenate(done_s), np.concatenate(done_f)
    change = (ff[:, 0] < 0.0) != (ff[:, 1] < 0.0)
    near = ~change & (np.abs(ff).max(axis=1) <= slack)
    touches = [tuple(pair) for pair in ss[near].tolist()]
    cuts = []
    known = np.array(known)
    for (s0, s1), (f0, f1) in zip(ss[change], ff[change]):
        found = known[(known >= s0) & (known <= s1)]
        root = float(found[0]) if len(found) == 1 else brentq(lambda x: float(value(x)[0]), s0, s1, xtol=xtol,
                                                                  rtol=1e-15)
        if not curve.closed and (root <= curve.tolerance or root >= length - curve.tolerance):
            continue                                       # the curve ends on this edge already
        if not limit.on_edge_side(frame.local_of(sol(np.array([root])).reshape(1, 3)))[0]:
            continue                 # the line of a half-plane through the axis, beyond it: not this edge
        cuts.append((float(root), limit, k))
    return cuts, touches


def next_round(value, lo_s, hi_s, lo_f, hi_f, finest, xtol, known):
    """The intervals (lo_s, hi_s, lo_f, hi_f) that replace the open ones given, with one evaluation of f (value)
    for them all. An interval where f changes sign: its root (Brent's method, appended to known), then knots at
    finest / 4 x GROWTH^j either side of it (near a crossing at an angle the limit changes nearly as fast as the arc
    length, so those intervals are cleared by the same test, where equal parts would stay open down to finest); any
    other: SECTIONS equal parts."""
    change = (lo_f < 0.0) != (hi_f < 0.0)
    knots = []
    for a, b in zip(lo_s[change].tolist(), hi_s[change].tolist()):
        root = brentq(lambda x: float(value(x)[0]), a, b, xtol=xtol, rtol=1e-15)
        known.append(root)
        steps = 0.25 * finest * GROWTH ** np.arange(int(np.log(max(b - a, finest) / finest) / np.log(GROWTH)) + 3)
        knots.append(np.concatenate([[a], (root - steps[root - steps > a])[::-1], root + steps[root + steps < b],
                                     [b]]))
    inner = lo_s[~change, None] + (hi_s - lo_s)[~change, None] * (np.arange(1, SECTIONS) / SECTIONS)[None, :]
    fresh = np.concatenate([inner.ravel()] + [k[1:-1] for k in knots])
    f_fresh = value(fresh) if len(fresh) else fresh
    rows_s = np.concatenate([lo_s[~change, None], inner, hi_s[~change, None]], axis=1)
    rows_f = np.concatenate([lo_f[~change, None], f_fresh[:inner.size].reshape(inner.shape), hi_f[~change, None]],
                            axis=1)
    out_s, out_f = [rows_s], [rows_f]
    at = inner.size
    for k_s, a_f, b_f in zip(knots, lo_f[change].tolist(), hi_f[change].tolist()):
        count = len(k_s) - 2
        out_s.append(k_s[None, :])
        out_f.append(np.concatenate([[a_f], f_fresh[at:at + count], [b_f]])[None, :])
        at += count
    return (np.concatenate([r[:, :-1].ravel() for r in out_s]), np.concatenate([r[:, 1:].ravel() for r in out_s]),
            np.concatenate([r[:, :-1].ravel() for r in out_f]), np.concatenate([r[:, 1:].ravel() for r in out_f]))


def window(curve, lo, hi):
    """The CurveResult of the arc [lo[0], hi[0]] of a component (hi past its length: across s = 0 of a closed
    one); lo and hi are (s, limit or None, surface index or None): a limit ends the arc on its edge."""
    s0, s1 = lo[0], hi[0]
    length = curve.length
    period = period_shift(curve)
    knots = curve.s
    inner = [(knots + turn * length, turn) for turn in ((0, 1) if curve.closed else (0,))]
    gap = curve.tolerance
    s_in, rows, turns = [], [], []
    for shifted, turn in inner:
        mask = (shifted > s0 + gap) & (shifted < s1 - gap)
        if curve.closed and turn == 0:
            mask &= knots < length           # the last point of a closed curve is its first, once
        idx = np.nonzero(mask)[0]
        s_in.append(shifted[idx])
        rows.append(idx)
        turns.append(np.full(len(idx), turn))
    s_in, rows, turns = np.concatenate(s_in), np.concatenate(rows), np.concatenate(turns)
    sol = WindowSolution(curve.sol, s0, s1 - s0, period)
    ends_at = np.array([0.0, s1 - s0])
    _, end_points, _, end_params = sol.evaluate(ends_at)
    points = np.vstack([end_points[:1], curve.points[rows], end_points[1:]])
    params = np.vstack([end_params[:1], curve.params[rows] + turns[:, None] * period, end_params[1:]])
    align_angles(params, curve.sol.surfaces)
    status, message = window_outcome(curve, lo, hi)
    sol.knots = np.concatenate([[0.0], s_in - s0, [s1 - s0]])
    return CurveResult(points=points, s=sol.knots, params=params, closed=False,
                       length=s1 - s0, status=status, message=message, tolerance=curve.tolerance, sol=sol,
                       nodes=nodes_within(curve, s0, s1), solver_gap=curve.solver_gap, nfev=curve.nfev,
                       wall_time=curve.wall_time)


def period_shift(curve):
    """(4,): how far the parameters move over one period of a closed curve (whole turns of its angles; 0 for an
    open one)."""
    if not curve.closed or len(curve.params) < 2:
        return np.zeros(4)
    return curve.params[-1] - curve.params[0]


def align_angles(params, surfaces):
    """The angular columns of params (M, 4) made continuous (each row within pi of the one before), in place."""
    for k, surface in enumerate(surfaces):
        for j, angle in enumerate(surface.traits.angular):
            if angle:
                params[:, 2 * k + j] = np.unwrap(params[:, 2 * k + j])


def window_outcome(curve, lo, hi):
    """(status, message) of an arc: its ends on a trim edge ('boundary'), or the component's own ends."""
    if curve.status in (TANGENT, CONTACT):
        return curve.status, f"{curve.message}; cut by the trims"
    ends = []
    for end in (lo, hi):
        s, limit, k = end
        if limit is None:
            ends.append((curve.status, curve.message))
        else:
            ends.append((BOUNDARY, f"reached the trim edge {limit.name} of surface {'ab'[k]}"))
    return open_outcome(ends[0][0], ends[0][1], ends[1][0], ends[1][1])


def nodes_within(curve, s0, s1):
    """The component's nodes (K, 3) that lie on the arc [s0, s1]."""
    nodes = np.asarray(curve.nodes, dtype=float).reshape(-1, 3)
    if not len(nodes):
        return nodes
    s, _ = curve.sol.closest(nodes)
    s = np.where(curve.closed & (s < s0), s + curve.length, s)
    return nodes[(s >= s0) & (s <= s1)]


class WindowSolution(CurveSolution):
    """Dense output of the arc [start, start + length] of a component (across s = 0 of a closed one): the
    component's own, its parameters moved by a period's shift past s = 0."""

    def __init__(self, whole, start, length, period):
        super().__init__(whole.surfaces, length, False, None)
        self.whole, self.start, self.period = whole, float(start), np.asarray(period, dtype=float)

    def evaluate(self, s, with_params=True):
        s = self.wrap(np.ravel(s))
        at = self.start + s
        _, points, tangents, params = self.whole.evaluate(at, with_params)
        if params is not None and self.whole.closed:
            params = params + np.floor_divide(at, self.whole.length)[:, None] * self.period
        return s, points, tangents, params

    def predicted_parameters(self, s):
        shape = np.shape(s)
        s = self.wrap(np.ravel(s))
        at = self.start + s
        params = self.whole.predicted_parameters(at).reshape(-1, 4)
        if self.whole.closed:
            params = params + np.floor_divide(at, self.whole.length)[:, None] * self.period
        return params.reshape(shape + (4,))
