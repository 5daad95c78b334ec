"""Face trims in the certificate: an answer cut by the faces' regions, proven from the answer before the cut.

The tracer follows each component on the surfaces as their length trims leave them and cuts it afterwards at the
edges of the regions (angular ranges, a sphere's latitudes, a torus's tube angles, a plane's disc or annulus;
spatialkin.tracing.curve.clip). The certificate takes the same two steps. It proves the uncut answer claim by claim
(the search reads the surfaces without their regions too), then, along each component's chain of proven pieces,
encloses every limit of the regions (spatialkin.geometry.trims.Limit: >= 0 inside, read on its own surface's local
point through the chart's rigorous placement in that surface's frame) over each piece's arc
(kernels.certify.trims.arcs_inside): the arc lies inside the limit, outside it, or the limit may change sign there.
On a run of pieces where limits may change sign, each of them must be monotone along the run (its rate of one sign,
kernels.certify.trims.edge_rate) and of strict signs on the pieces either side: equal signs, it does not vanish
there; opposite ones, it vanishes exactly once on the run's arc (two limits at once where an angular range is a
half turn: its edges lie in one plane). Where the regions' verdict flips across the run, a returned arc must end
there: within ON_EDGE tolerances of those edges, and inside a box around its end proven to hold a crossing of each
of them (the Krawczyk test of the level and the limit, kernels.certify.trims.crossing) lying in the run; its
distance bound counts the surface's diameter over that box. The returned curves must be exactly the arcs inside
both regions, each from one such crossing (or the component's own end) to the next, with the component's own
stored points between, a component inside all along returned whole and one outside all along not at all.

Not proven: a point where a component touches a face edge from outside (clip's single points).

References
----------
R. Krawczyk, "Newton-Algorithmen zur Bestimmung von Nullstellen mit Fehlerschranken", Computing 4 (1969) 187-201.
B. Martin, A. Goldsztejn, L. Granvilliers, C. Jermann, "Certified parallelotope continuation for one-manifolds",
SIAM J. Numer. Anal. 51 (2013) 3373-3401.
"""
import math
from dataclasses import dataclass

import numpy as np

from ...geometry.trims import HEIGHT, RADIUS, TUBE, TURN, Limit
from ...kernels.certify import trims as kr
from ...kernels.geometry import surfaces as ks
from ...kernels.certify import tubes as kt
from ..curve.clip import WindowSolution
from ..curve.status import CONTACT, TANGENT
from .certify_points import certify_points
from ..search.topology import Reader
from .trims import ARC_DEPTH, CROSSING_CAP, CROSSING_FIRST, ON_EDGE, piece_rate

#: The ulp of 1.0 (np.float64).
EPS = np.finfo(float).eps
#: A cut arc's stored ends may lie this many of its component's tolerances from its dense output's.
SAME_END = 1e3


@dataclass(frozen=True)
class FaceLimit:
    """One limit of a face's region as the kernels read it: of surface a (0) or b (1), in group ``group`` of its
    region, e's code (kernels.certify.trims.FACE plus the kind), the placement of the search's chart in that
    surface's frame (face: kernels.certify.trims's face argument), and the side of the face (inside: +1 where e > 0
    inside, -1 where e < 0)."""
    surface: int
    group: int
    limit: Limit
    code: int
    face: tuple
    inside: float

    @property
    def value(self):
        return float(self.limit.value)


def face_limits(chart, a, b):
    """The FaceLimits of both surfaces' regions, each read on its own surface's local point."""
    out = []
    for k, surface in enumerate((a, b)):
        if not surface.region:
            continue
        placing = Reader(chart.p, surface)          # the chart's local point in the surface's frame
        face = (placing.m, placing.c, float(placing.pad), float(placing.cpad), float(surface.data[ks.P0]))
        for g, group in enumerate(surface.region):
            for limit in group:
                kind = {TURN: kr.NAPPES if limit.nappes else kr.TURN, RADIUS: kr.RADIUS, TUBE: kr.TUBE,
                        HEIGHT: kr.HEIGHT + limit.axis}[limit.kind]
                out.append(FaceLimit(k, g, limit, kr.FACE + kind, face, 1.0 if limit.lower else -1.0))
    return out


def limit_signs(chart, limits, pieces):
    """(L, K) int: +1 where the arc of piece k lies strictly inside limit l, -1 strictly outside, 0 undecided."""
    r = chart.reader
    su, sv = float(chart.units[0]), float(chart.units[1])
    out = np.zeros((len(limits), len(pieces)), dtype=int)
    strict = np.empty(len(pieces), dtype=np.bool_)
    for i, fl in enumerate(limits):
        for side in (1.0, -1.0):
            kr.arcs_inside(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, su, sv, fl.code, fl.value, fl.face, side,
                           pieces, ARC_DEPTH, strict)
            out[i, strict] = int(side * fl.inside)
    return out


def verdict(limits, signs):
    """True (inside both regions), False (outside one) or None (undecided) from one piece's signs (L,)."""
    result = True
    for k in (0, 1):
        groups = {}
        for fl, sign in zip(limits, signs):
            if fl.surface == k:
                groups.setdefault(fl.group, []).append(sign)
        for values in groups.values():
            if any(v > 0 for v in values):
                continue
            if all(v < 0 for v in values):
                return False
            result = None
    return result


@dataclass
class Flip:
    """A run of pieces (first, last: chain indices, last < first across the start of a closed chain) on which each
    of the limits (indices) vanishes once, the regions' verdict going from before to after (two limits vanish
    together where an angular range is a half turn: its edges lie in one plane through the axis)."""
    first: int
    last: int
    limits: tuple
    before: bool
    after: bool

    def indices(self, count):
        return run_indices(self.first, self.last, count)


def run_indices(first, last, count):
    """The chain indices of the run of pieces first to last of a chain of count (across its start when last <
    first)."""
    return [k % count for k in range(first, last + 1 + (count if last < first else 0))]


def box_signs(chart, limits, box):
    """(L,) int: the signs of the limits (as limit_signs) over a scaled parameter box (4,) of the chart."""
    r = chart.reader
    raw = np.ascontiguousarray(box * np.repeat(chart.units, 2))
    out = np.zeros(len(limits), dtype=int)
    for i, fl in enumerate(limits):
        lo, hi = kr.box_trim(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, raw, fl.code, fl.value, fl.face)
        out[i] = int(fl.inside) if lo > 0.0 else -int(fl.inside) if hi < 0.0 else 0
    return out


def flips(chart, limits, signs, pieces, closed, end_boxes=()):
    """(flips in chain order, the verdict of every piece (K,): True, False, or None inside a flip's run; a reason
    when the verdicts along the chain cannot be settled, else None). signs (L, K): limit_signs of the pieces (a
    limit proven not to vanish on a run gets its sign there). end_boxes: an open chain's proven end boxes (scaled),
    whose signs stand beside its first and last pieces."""
    count = pieces.shape[0]
    if not closed and len(end_boxes) == 2:          # the ends as pieces -1 and count: one more column each side
        signs = np.column_stack([box_signs(chart, limits, end_boxes[0]), signs,
                                 box_signs(chart, limits, end_boxes[1])])
        pieces = np.vstack([pieces[:1], pieces, pieces[-1:]])
        found, verdicts, reason = flips(chart, limits, signs, pieces, False)
        if reason is not None:
            return found, verdicts, reason
        for flip in found:
            flip.first, flip.last = max(flip.first - 1, 0), min(flip.last - 1, count - 1)
        return found, verdicts[1:-1], None
    verdicts = [verdict(limits, signs[:, k]) for k in range(count)]
    undecided = [v is None for v in verdicts]
    if not any(undecided):
        return [], verdicts, None
    if all(undecided):
        return None, None, "no piece of its tube is proven inside or outside the faces"
    start = next(k for k in range(count) if not undecided[k]) if closed else 0
    runs, prev = [], None
    for k in ((start + i) % count for i in range(count)):
        if undecided[k]:
            if prev is not None and undecided[prev]:
                runs[-1][1] = k
            else:
                runs.append([k, k])
        prev = k
    out = []
    for first, last in runs:
        if not closed and (first == 0 or last == count - 1):
            return None, None, "a face edge comes near an end of the component"
        run = run_indices(first, last, count)
        zero = sorted({int(i) for k in run for i in np.flatnonzero(signs[:, k] == 0)})
        before, after = (first - 1) % count, (last + 1) % count
        crossing = []
        for l in zero:
            fl = limits[l]
            if signs[l, before] == 0 or signs[l, after] == 0:
                return None, None, f"the face edge {fl.limit.name} is not proven apart from a run of its tube"
            rates = np.array([piece_rate(chart, fl.code, fl.value, fl.face, pieces[k]) for k in run])
            if not (np.all(rates[:, 0] > 0.0) or np.all(rates[:, 1] < 0.0)):
                return None, None, f"the arc is not proven to cross the face edge {fl.limit.name} once"
            if signs[l, before] == signs[l, after]:       # monotone, of one sign either side: it does not vanish
                signs[l, run] = signs[l, before]
            else:
                crossing.append(l)
        for k in run:
            verdicts[k] = verdict(limits, signs[:, k])
        if not crossing:
            continue
        names = ", ".join(limits[l].limit.name for l in crossing)
        if verdicts[before] is None or verdicts[after] is None:
            return None, None, f"the faces' verdict is not settled across the edge {names}"
        for k in run:          # each side of the crossings, every piece of the run gives its neighbour's verdict
            for side in (before, after):
                trial = signs[:, k].copy()
                trial[crossing] = signs[crossing, side]
                if verdict(limits, trial) != verdicts[side]:
                    return None, None, f"the faces' verdict is not settled across the edge {names}"
        if verdicts[before] != verdicts[after]:
            out.append(Flip(first, last, tuple(crossing), verdicts[before], verdicts[after]))
    inside_flips = {k for flip in out for k in flip.indices(count)}
    if any(verdicts[k] is None for k in range(count) if k not in inside_flips):
        return None, None, "the faces' verdict is not settled along its tube"
    out.sort(key=lambda flip: (flip.first - start) % count)
    return out, verdicts, None


def end_flip(chart, limits, pieces, count, found, x, tolerance):
    """(index in found (Flips), distance bound) of the run holding a proven crossing of each of its limits around the
    scaled parameters x (2,) (a cut arc's end, where each of those limits is within ON_EDGE tolerances of 0), or
    None. The regions' verdict changes only where one of those limits vanishes, once each on the run's arc, inside
    its box: the edge the arc crosses lies within those boxes, and the end within the bound (the diameter of the
    surface over the largest box) of that crossing."""
    r = chart.reader
    su, sv = float(chart.units[0]), float(chart.units[1])
    size = max(1.0, float(np.max(np.abs(x))))
    at = np.ascontiguousarray(np.repeat(x * chart.units, 2))
    for i, flip in enumerate(found):
        run = np.ascontiguousarray(pieces[flip.indices(count)])
        widest = 0.0
        for l in flip.limits:
            fl = limits[l]
            lo, hi = kr.box_trim(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, at, fl.code, fl.value, fl.face)
            if max(abs(lo), abs(hi)) > ON_EDGE * tolerance:
                break
            h = kr.crossing_radius(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, su, sv, fl.code, fl.value, fl.face,
                                   float(x[0]), float(x[1]), CROSSING_FIRST * size, CROSSING_CAP * size)
            box = np.array([x[0] - h, x[0] + h, x[1] - h, x[1] + h])
            if not math.isfinite(h) or kt.point_in_pieces(run, len(run), box, chart.periods[0],
                                                          chart.periods[1]) < 0:
                break
            widest = max(widest, h)
        else:
            raw = np.array([x[0] - widest, x[0] + widest, x[1] - widest, x[1] + widest]) * np.repeat(chart.units, 2)
            return i, kr.box_diameter(chart.p.data, raw)
    return None


def expected_arcs(found, verdicts, closed, count):
    """[(start, end)] of the stretches inside both regions, each end a flip's index or 'start' / 'end' (an open
    chain's own ends); 'whole' for a closed chain inside all along."""
    if not found:
        inside = verdicts[0]
        return (["whole"] if closed else [("start", "end")]) if inside else []
    out = []
    if not closed and found[0].before:
        out.append(("start", 0))
    for i, flip in enumerate(found):
        if flip.after:
            nxt = i + 1
            out.append((i, nxt % len(found) if closed else (nxt if nxt < len(found) else "end")))
    return out


def own_points(whole, curve, slack):
    """The indices among the component's stored points of the cut arc's stored points between its ends, when they
    are the component's own, in order, at their arc lengths (the arc's s plus its start, across s = 0 of a closed
    component a turn less, within slack) and its s runs from 0 to its length; else None."""
    s = np.asarray(curve.s, dtype=float)
    if len(s) < 2 or s[0] != 0.0 or s[-1] != curve.length or not np.all(np.diff(s) > 0.0):
        return None
    inner = s[1:-1] + curve.sol.start
    if whole.closed:
        inner = np.mod(inner, whole.length)
    knots = np.asarray(whole.s, dtype=float)
    at = np.clip(np.searchsorted(knots, inner), 1, len(knots) - 1)
    at = np.where(np.abs(knots[at - 1] - inner) < np.abs(knots[at] - inner), at - 1, at)
    if np.all(np.abs(knots[at] - inner) <= slack) and np.array_equal(whole.points[at], curve.points[1:-1]):
        return at
    return None


def component_arcs(chart, limits, whole, t, returned):
    """(failures (text, point), {id of a returned arc: (proven distance of its ends from the face edges' crossings,
    the indices of its inner stored points among the component's, its ends (2, 3) and their tangents (2, 3))}) of
    one component (whole, its proven Tube t) against the returned curves cut from it (returned: [CurveResult])."""
    if t is None or not t.proven or t.split:
        return [("a component cut by the faces has no proven tube of one chain", whole.points[0])], {}
    pieces = t.pieces
    count = len(pieces)
    signs = limit_signs(chart, limits, pieces)
    found, verdicts, reason = flips(chart, limits, signs, pieces, whole.closed, t.end_boxes)
    if reason is not None:
        return [(f"a component cut by the faces: {reason}", whole.points[0])], {}
    want = expected_arcs(found, verdicts, whole.closed, count)
    if want == ["whole"]:
        if len(returned) == 1 and returned[0] is whole:
            return [], {}
        return [("a component inside both faces all along is not returned whole", whole.points[0])], {}
    got, reach = [], {}
    slack = 64.0 * EPS * max(whole.length, 1.0)
    for curve in returned:
        if curve is whole or not isinstance(curve.sol, WindowSolution) or curve.closed:
            return [("a returned curve is not an arc of its component between proven face edges",
                     curve.points[0])], {}
        start, length = curve.sol.start, curve.length
        longest = whole.length if whole.closed else whole.length + slack
        if not (0.0 < length < longest) or curve.sol.length != length:
            return [("a returned arc is longer than its component", curve.points[0])], {}
        _, at_ends, end_tangents, _ = curve.sol.evaluate(np.array([0.0, length]), with_params=False)
        if np.max(np.abs(at_ends - curve.points[[0, -1]])) > SAME_END * whole.tolerance:
            return [("a returned arc's stored ends are not its dense output's", curve.points[0])], {}
        rows = own_points(whole, curve, slack)
        if rows is None:
            return [("a returned arc's stored points are not its component's, at their arc lengths",
                     curve.points[0])], {}
        ends, bound = [], 0.0
        for s, point, own in ((start, at_ends[0], 0.0), (start + length, at_ends[1], whole.length)):
            if not whole.closed and abs(s - own) <= slack:
                ends.append("start" if own == 0.0 else "end")        # the component's own end (proven before)
                continue
            match = end_flip(chart, limits, pieces, count, found, chart.scaled(point)[0], whole.tolerance)
            if match is None:
                return [("an end of a returned arc is not a proven crossing of a face edge", point)], {}
            ends.append(match[0])
            bound = max(bound, match[1] + 64.0 * EPS * max(1.0, float(np.max(np.abs(point)))))
        got.append(tuple(ends))
        reach[id(curve)] = (bound, rows, curve.points[[0, -1]], end_tangents)
    if sorted(map(str, got)) != sorted(map(str, want)):
        return [(f"the arcs of a component inside both faces are {len(want)} between proven crossings, "
                 f"{len(got)} returned", whole.points[0])], {}
    return [], reach


def cut(base, a, b, curves, wholes):
    """(failures, radii, tubes, bounds) of the cut answer (curves, the CurveResults returned) from base, the
    Certificate of the answer before the cut (wholes): why the cut is not proven ((text, point) each; none when it
    is), and each returned curve's stored points' proven radii, tube (its component's) and distance bound (its
    component's, its ends' radii, and their distance from the crossings of the face edges)."""
    chart = base.chart
    failures = []
    limits = face_limits(chart, a, b) if chart is not None else []
    unsupported = [] if chart is not None else ["no search chart"]
    owner = {}
    for i, curve in enumerate(curves):
        parent = curve.sol.whole if isinstance(curve.sol, WindowSolution) else curve.sol
        j = next((j for j, w in enumerate(wholes) if w.sol is parent), None)
        if j is None:
            failures.append(("a point where a component touches a face edge (not proven)" if curve.length == 0 else
                             "a returned curve comes from no traced component", curve.points[0]))
        owner[i] = j
    reach = {}
    if unsupported:
        failures.append((unsupported[0], None))
    else:
        for j, whole in enumerate(wholes):
            if whole.length > 0 and whole.status not in (TANGENT, CONTACT):
                more, ends = component_arcs(chart, limits, whole, base.tubes[j], [c for i, c in enumerate(curves)
                                                                                  if owner[i] == j])
                failures += more
                reach.update(ends)
            else:
                failures.append(("a singular component or a single point, cut by the faces or not (not proven)",
                                 whole.points[0]))
    radii, tubes, bounds = [], [], []
    for i, curve in enumerate(curves):
        j = owner[i]
        if j is not None and curve is wholes[j]:
            radii.append(base.radii[j])
            bounds.append(base.distance_bounds[j])
        elif id(curve) in reach:       # a proven arc: its inner points are its component's, with their radii
            bound, rows, ends, end_tangents = reach[id(curve)]
            end_radii = certify_points(a, b, ends, end_tangents)
            radii.append(np.concatenate([end_radii[:1], base.radii[j][rows], end_radii[1:]]))
            bounds.append(max(base.distance_bounds[j], float(np.max(end_radii)) * math.sqrt(3.0), bound))
        else:
            points = np.asarray(curve.points, dtype=float)
            tangents = np.gradient(points, axis=0) if len(points) > 1 else np.zeros((len(points), 3))
            radii.append(certify_points(a, b, points, tangents) if len(points) > 1 else np.full(len(points),
                                                                                                  math.inf))
            bounds.append(math.inf)
        tubes.append(base.tubes[j] if j is not None else None)
    return failures, radii, tubes, bounds
