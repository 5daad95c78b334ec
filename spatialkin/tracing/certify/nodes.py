"""Nodes in the certificate: where two branches of the level g = F_Q(P(u, v)) = 0 cross, or pass too close for
floating point to tell.

A node's box N (a square of the search chart's scaled parameters around it) is proven to hold exactly one critical
point of g, a saddle (the Krawczyk test of grad g = 0 with a Hessian of negative determinant over N,
spatialkin.kernels.certify.singular), and g is proven to vanish at exactly four points of N's edges (simple roots
isolated by the interval line search of the topology stage, none at a corner). Then the level inside N is two arcs
joining those four points, crossing at the saddle or not: a closed loop of the level in N, or a lobe closing on
itself, would bound a disc where g has an extremum, a critical point other than the saddle. Each of the four points
must lie in a proven piece of a returned curve's tube (the tubes are chained on either side of N, their ends
reaching into it): every branch leaving the node then runs on through proven tubes.

Which of the four points the two arcs join is decided where g is proven to keep one sign along a segment across N
between two opposite stretches of N's edge (the stretches between consecutive crossings; joined): the arcs then do
not cross (at a crossing, each of the four stretches lies in a region of its own), and of the three regions they
cut N into, only the middle one meets two stretches, so the arcs join the ends of the other two: two branches
passing close, no singular point. A curve through such a node is one component where each of its passages enters
and leaves by the two ends of one arc (passages), and two curves passing it by different arcs are distinct. Where
it is not decided (a crossing, or branches too close for floating point to tell), a curve through the node is not
proven one component.
"""
import math
from dataclasses import dataclass

import numpy as np

from ...kernels.certify import singular as ks_singular
from ...kernels.certify import trims as kr
from ...kernels.certify import tubes as kt
from ...kernels.search import topology as ks

#: Half-widths tried for a node's box, as shares of the median chord of the samples (the smallest that passes: a
#: small ball, the tubes reaching into it).
SHARES = (0.1, 0.25, 0.5, 1.0, 2.0)
#: Box budget of the line search on each edge of a node's box.
EDGE_BOXES = 4000
#: First half-width of a crossing's narrowed box, relative to max(1, |x|) in scaled parameters.
CROSSING_FIRST = 1e-12
#: Pieces the proof of g's sign along a segment across a node's box may try (each direction).
SEGMENT_BOXES = 4096


@dataclass
class NodeBox:
    """A node's proven box: its index among the search's nodes, its point (3,), the scaled centre x (2,) and
    half-width h of N, the scaled boxes (4,) of the four proven roots of g on N's edges, the largest speed of P
    over N (length per scaled unit), and the two pairs of crossings (indices into crossings, each a frozenset) the
    level's arcs in N join where that is proven (joined), else None."""
    index: int
    point: np.ndarray
    x: np.ndarray
    h: float
    crossings: list
    speed: float
    pairs: tuple = None

    @property
    def radius(self):
        """A ball around the node's point holding its box (length unit): the box's half-diagonal times the largest
        speed of P over it."""
        return math.sqrt(2.0) * self.h * self.speed

    @property
    def box(self):
        """N as a scaled box (u lo, u hi, v lo, v hi)."""
        return np.array([self.x[0] - self.h, self.x[0] + self.h, self.x[1] - self.h, self.x[1] + self.h])


def node_boxes(chart, nodes, chord, shares=SHARES):
    """The NodeBox of each node point (3,) in the chart for which one is proven: the smallest box of shares x chord
    that passes (module docstring; shares: SHARES, or its larger ones); the others are left out (the chain through
    them fails)."""
    boxes = []
    for index, point in enumerate(nodes):
        point = np.asarray(point, dtype=float)
        x = chart.scaled(point[None])[0]
        for share in shares:
            h = share * chord
            speed = saddle_box(chart, x, h) if h > 0.0 else None
            if speed is not None:
                crossings = edge_crossings(chart, x, h)
                if crossings is not None and len(crossings) == 4:
                    node = NodeBox(index, point, x, h, crossings, speed)
                    node.pairs = joined(chart, node)
                    boxes.append(node)
                    break
    return boxes


def saddle_box(chart, x, h):
    """The largest speed of P over the box x +- h (scaled: length per scaled unit) when the box holds exactly one
    critical point of g, a saddle over the whole box; else None."""
    r = chart.reader
    out = np.empty(3)
    kind = ks_singular.critical_ball(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, float(chart.units[0]),
                                     float(chart.units[1]), float(x[0]), float(x[1]), h, h, out)
    return float(out[2]) if kind == ks_singular.SADDLE and out[0] == h else None


def joined(chart, node):
    """The two pairs of the node's crossings (frozensets of indices into node.crossings) that the level's two arcs
    in its box join, where g is proven to keep one sign along a segment across the box between two opposite
    stretches of its edge (module docstring); None where no such segment is found. The segments tried run through
    the box's centre along the eigenvectors of g's Hessian there: through a saddle where g is d != 0, g keeps the
    sign of d along the eigenvector whose eigenvalue has that sign."""
    r = chart.reader
    su, sv = float(chart.units[0]), float(chart.units[1])
    values = np.empty((1, 6))
    ks.point_values(r.s.data, r.t.data, r.m, r.c, (node.x * chart.units)[None], values)
    _, _, _, guu, guv, gvv = values[0]
    hessian = np.array([[guu * su * su, guv * su * sv], [guv * su * sv, gvv * sv * sv]])
    if not np.all(np.isfinite(hessian)):
        return None
    order = perimeter_order(node)
    if order is None:
        return None
    for e in np.linalg.eigh(hessian)[1].T:
        (ea, a), (eb, b) = across(node, e)
        if not ks_singular.sign_on_segment(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, su, sv, a[0], a[1], b[0],
                                           b[1], SEGMENT_BOXES):
            continue
        ka, kb = stretch(order, ea, a), stretch(order, eb, b)
        if ka is None or kb is None or (ka - kb) % 4 != 2:
            continue
        ends = [order[(ka + k) % 4][2] for k in range(4)]      # (c_ka, c_ka+1, c_ka+2, c_ka+3)
        return frozenset(ends[:2]), frozenset(ends[2:])
    return None


#: The edges of a node's box, counterclockwise from its lower left corner: (the coordinate fixed on it, its side,
#: the sign of the other coordinate's run along it).
EDGES = ((1, -1, 1.0), (0, 1, 1.0), (1, 1, -1.0), (0, -1, -1.0))


def perimeter(edge, along):
    """A sort key of the point of the box's edge `edge` (index into EDGES) where the other coordinate is `along`:
    counterclockwise from the lower left corner (exact: no arithmetic on the coordinates)."""
    return edge, EDGES[edge][2] * along


def perimeter_order(node):
    """[(lo, hi, index)] of the node's crossings in counterclockwise order round the box's edge (lo, hi: perimeter
    keys of the stretch of the edge each crossing's box covers); None where a box lies on no single edge or reaches
    a corner, or where two of them overlap."""
    spans = []
    for i, box in enumerate(node.crossings):
        on = [e for e, (fixed, side, _) in enumerate(EDGES)
              if box[2 * fixed] <= node.x[fixed] + side * node.h <= box[2 * fixed + 1]]
        if len(on) != 1:
            return None
        fixed = EDGES[on[0]][0]
        lo, hi = box[2 * (1 - fixed)], box[2 * (1 - fixed) + 1]
        if not (node.x[1 - fixed] - node.h < lo and hi < node.x[1 - fixed] + node.h):
            return None
        spans.append(tuple(sorted((perimeter(on[0], lo), perimeter(on[0], hi)))) + (i,))
    spans.sort()
    return None if any(spans[k][1] >= spans[k + 1][0] for k in range(len(spans) - 1)) else spans


def across(node, e):
    """The two ends of the segment through the node box's centre along the direction e (2,), each (edge index,
    point (2,)): the coordinate fixed on its edge set to the edge's own value (that of the crossings' search)."""
    k = 0 if abs(e[0]) >= abs(e[1]) else 1
    t = node.h / abs(e[k])
    lo, hi = node.x[1 - k] - node.h, node.x[1 - k] + node.h
    out = []
    for side in (-1.0, 1.0):
        towards = 1 if side * e[k] > 0 else -1
        p = node.x + side * t * e
        p[k] = node.x[k] + towards * node.h
        p[1 - k] = min(max(p[1 - k], lo), hi)
        out.append((EDGES.index(next(edge for edge in EDGES if edge[:2] == (k, towards))), p))
    return out


def stretch(order, edge, p):
    """The index k of the stretch of the box's edge (between crossings order[k - 1] and order[k], k mod 4) holding
    the point p (2,) of the edge `edge`, or None where p lies in a crossing's box."""
    at = perimeter(edge, p[1 - EDGES[edge][0]])
    k = 0
    for lo, hi, _ in order:
        if lo <= at <= hi:
            return None
        if hi < at:
            k += 1
    return k % 4


def passages(nodes, runs, periods):
    """{node index: [the pair (frozenset of crossing indices) of each passage]} of a closed curve whose tube is made
    of runs (Tube.runs: (pieces, the NodeBox it comes from, the one it goes to), in the curve's order) through
    node boxes (nodes: NodeBox), when every node it passes has its pairs decided and each passage enters and leaves
    the node by the two ends of one of its arcs; else None. A run must hold (in a piece of its chain) exactly two
    crossings of the nodes' edges: the earlier in the chain's order one of the node it comes from (where it leaves
    that node), the later one of the node it goes to (where it enters it)."""
    ends = []
    for pieces, before, after in runs:
        if before is None or after is None or before.pairs is None or after.pairs is None:
            return None
        held = {}
        for node in nodes:
            for i, box in enumerate(node.crossings):
                k = piece_holding(pieces, box, periods)
                if k >= 0:
                    held[(node.index, i)] = k
        if len(held) != 2:
            return None
        (first, k0), (last, k1) = sorted(held.items(), key=lambda item: item[1])
        if k0 == k1 or first[0] != before.index or last[0] != after.index:
            return None
        ends.append((first, last))
    pairs = {node.index: node.pairs for node in nodes}
    out = {}
    for k, (_, (node, entered)) in enumerate(ends):
        left_node, left = ends[(k + 1) % len(ends)][0]
        pair = frozenset((entered, left))
        if left_node != node or pair not in pairs[node]:
            return None
        out.setdefault(node, []).append(pair)
    return out


def typical_chord(chart, curves):
    """The median chord between consecutive stored points of the curves of positive length, in the chart's scaled
    parameters (0 when there is none)."""
    chords = [np.hypot(*np.diff(chart.scaled(c.points), axis=0).T) for c in curves
              if c.length > 0 and len(c.points) > 1]
    return float(np.median(np.concatenate(chords))) if chords else 0.0


def piece_holding(pieces, box, periods):
    """Index of a piece (kernels.certify.tubes.point_in_pieces, whole periods (2,) of the chart) holding the scaled
    box (4,) strictly inside, or -1."""
    return kt.point_in_pieces(pieces, len(pieces), np.ascontiguousarray(box), periods[0], periods[1])


def linked(chart, boxes, tubes):
    """(the node boxes whose four crossings each lie in a proven piece of a tube, failures [(text, point)] of the
    others)."""
    pieces = [t.pieces for t in tubes if t is not None and t.proven]
    pieces = np.concatenate(pieces) if pieces else np.empty((0, kt.WIDTH))
    good, failures = [], []
    for node in boxes:
        if all(piece_holding(pieces, box, chart.periods) >= 0 for box in node.crossings):
            good.append(node)
        else:
            failures.append(("a branch leaving a node lies in no proven tube", node.point))
    return good, failures


def edge_crossings(chart, x, h):
    """The scaled boxes (4,) of the roots of g on the four edges of the box x +- h, each verified simple and away
    from the corners, then narrowed to a small box proven to hold it (kernels.certify.trims.crossing_radius, inside
    the verified interval along the edge); None when an edge's search leaves a box unresolved or a root near a
    corner."""
    r = chart.reader
    su, sv = float(chart.units[0]), float(chart.units[1])
    out = np.empty((64, 2))
    kinds = np.empty(64, dtype=np.int64)
    found = []
    for fixed in (0, 1):
        unit, other = (su, sv) if fixed == 0 else (sv, su)
        lo, hi = (x[1 - fixed] - h) * other, (x[1 - fixed] + h) * other
        for side in (-1.0, 1.0):
            value = (x[fixed] + side * h) * unit
            n, status, _ = ks.line_roots(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, fixed, value, lo, hi,
                                         1e-9 * (hi - lo), 0.0, EDGE_BOXES, out, kinds)
            if status != ks.DONE or np.any(kinds[:n] != ks.VERIFIED):
                return None
            for a, b in out[:n]:
                if not (lo < a and b < hi):
                    return None
                # narrowed: the 2 x 2 Krawczyk test of g = 0 and the edge around the root refined by Newton, in a
                # box within the verified interval along the edge (so the root it holds is that interval's)
                root = ks.refine_line(r.s.data, r.t.data, r.m, r.c, fixed, value, a, b)
                mid = root / other
                cu, cv = (value / unit, mid) if fixed == 0 else (mid, value / unit)
                size = max(1.0, abs(cu), abs(cv))
                room = 0.999 * min(root - a, b - root) / other
                radius = kr.crossing_radius(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, su, sv,
                                            (kr.EDGE_U, kr.EDGE_V)[fixed], value, kr.NO_FACE, cu, cv,
                                            min(CROSSING_FIRST * size, room), room)
                if not (math.isfinite(radius) and radius < room):
                    return None
                found.append(np.array([cu - radius, cu + radius, cv - radius, cv + radius]))
    return found


def inside(chart, node, x):
    """(M,) bool: which scaled points x (M, 2) lie strictly inside the node's box (each shifted by the whole periods
    that bring it nearest the node: shifted_into)."""
    return np.all(np.abs(shifted_into(chart, node, x) - node.x) < node.h, axis=1)


def in_boxes(chart, nodes, points):
    """(M,) bool: which points (M, 3) lie inside one of the node boxes."""
    x = chart.scaled(points)
    out = np.zeros(len(x), dtype=bool)
    for node in nodes:
        out |= inside(chart, node, x)
    return out


def box_radii(chart, nodes, points, radii):
    """Give the points (M, 3) inside a node box that have no proven radius (radii (M,), changed in place) one from
    the boxes: within the largest box's diameter of a crossing on its edge (a true point), plus the point's distance
    from the chart's surface."""
    inside = in_boxes(chart, nodes, points) & ~np.isfinite(radii) if nodes else np.zeros(len(points), dtype=bool)
    if inside.any():
        feet = chart.p.point(*chart.p.parameters(points[inside]).T)
        off = np.linalg.norm(points[inside] - feet, axis=1) * (1.0 + 1e-9) + 1e-300
        radii[inside] = (2.0 * max(node.radius for node in nodes) + off) * (1.0 + 1e-15)


def shifted_into(chart, node, x):
    """The scaled points x (M, 2) (or one, (2,)), each shifted by the whole periods that bring it nearest the
    node's centre (periodic parameters only)."""
    turns = np.where(chart.periods > 0.0, np.round((node.x - x) / np.where(chart.periods > 0.0, chart.periods, 1.0)),
                     0.0)
    return x + turns * chart.periods
