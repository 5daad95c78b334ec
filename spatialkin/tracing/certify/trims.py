"""Trims in the certificate: proven crossings where open curves end, and roots proven outside a trimmed patch.

The trims proven are those of length parameters (a plane's u and v, a cylinder's or cone's v): in the search's
chart of P they are lines of P's parameters, and Q's are levels of a local coordinate of Q at P(u, v)
(spatialkin.kernels.certify.trims). The trims of a P searched in another chart than its own are not proven. The
face trims (angular ranges, a sphere's latitudes, a plane's disc or annulus) are proven apart, along the components
before they cut them (spatialkin.tracing.certify.faces).
"""
import math
from dataclasses import dataclass

import numpy as np

from ...geometry.traits import LENGTH
from ...kernels.certify import trims as kr
from ...kernels.certify import tubes as kt

#: First and largest half-width of a crossing's box, relative to max(1, |x|) in scaled parameters.
CROSSING_FIRST, CROSSING_CAP = 1e-12, 1e-4
#: An end lies on an edge when |e| there is below this many times the curve's tolerance.
ON_EDGE = 1e3
#: Deepest halving of a piece's length when its arc is proven on one side of an edge.
ARC_DEPTH = 8
#: Stretches of a piece over which an edge's rate along its arc is enclosed again, where the whole parallelogram
#: gives no sign.
RATE_STRETCHES = 16


@dataclass(frozen=True)
class Edge:
    """A trim edge: of P or Q (owner), its parameter held (fixed: 0 u, 1 v) at value, e's code in the kernels
    (kernels.certify.trims: EDGE_U, EDGE_V for P's own parameters, Q's local axis otherwise; for Q's roots read
    on Q, P's local axis: p_axis), and the side of the patch (inside: +1 where e > 0 inside, -1 where e < 0)."""
    owner: str
    fixed: int
    value: float
    code: int
    inside: float


def edges(topology, chart, regions=True):
    """(edges, unsupported): the trim edges of P and Q that can be proven (Edge), and the reasons the others
    cannot (regions False: the faces' regions left out, spatialkin.tracing.certify.faces proves them)."""
    out, unsupported = [], []
    for owner, surface in (("P", topology.P), ("Q", topology.Q)):
        kind = surface.traits
        if regions and surface.region:
            unsupported.append(f"the face trims of {owner} (angular ranges, a disc) are not proven")
        for j, (lo, hi) in enumerate(surface.bounds):
            for bound, inside in ((lo, 1.0), (hi, -1.0)):
                if not math.isfinite(bound):
                    continue
                axis = kind.parameter_axes[j]
                if kind.units[j] != LENGTH or axis is None:
                    unsupported.append(f"an angular trim of {owner} ({'uv'[j]} = {bound:g}) is not proven")
                elif owner == "P" and chart.p is not surface:
                    unsupported.append("P's trims in the chart of its search are not proven")
                else:
                    code = (kr.EDGE_U, kr.EDGE_V)[j] if owner == "P" else axis
                    out.append(Edge(owner, j, float(bound), code, inside))
    return out, unsupported


def trim_value(reader, box, edge):
    """(lo, hi): e of the edge over the raw parameter box (4,) of reader.s (reader: P read against Q, so that a
    Q edge's code is Q's local axis)."""
    return kr.box_trim(reader.s.data, reader.t.data, reader.m, reader.c, reader.pad, reader.cpad,
                       np.ascontiguousarray(box, dtype=float), edge.code, edge.value, kr.NO_FACE)


def outside(reader, box, trims):
    """True when the raw box of reader.s lies strictly outside one of the edges' patches."""
    for edge in trims:
        lo, hi = trim_value(reader, box, edge)
        if (edge.inside > 0 and hi < 0.0) or (edge.inside < 0 and lo > 0.0):
            return True
    return False


def strictly_inside(reader, box, trims):
    """True when the raw box of reader.s lies strictly inside every edge's patch."""
    for edge in trims:
        lo, hi = trim_value(reader, box, edge)
        if not ((edge.inside > 0 and lo > 0.0) or (edge.inside < 0 and hi < 0.0)):
            return False
    return True


class Ends:
    """The proven crossings of every open curve's ends: crossings[(owner, fixed, value)] lists the scaled boxes
    (4,) of the crossings on that edge; failures lists (reason, point) for the open curves not proven."""

    def __init__(self):
        self.crossings = {}
        self.failures = []


def open_curve(chart, trims, unsupported, tube, curve, ends, index):
    """Prove that an open curve (its tube proven) is one whole piece of its component within the trims: each end a
    proven crossing of a trim edge lying in the tube, the arc crossing that edge once in every piece that touches it
    (each such piece holding the crossing), and every other piece strictly inside every trim. Records the crossings
    in ends; returns True when proven, else appends the reason to ends.failures."""
    if unsupported:
        ends.failures.append((f"curve {index}: {unsupported[0]}", curve.points[0]))
        return False
    pieces = tube.pieces
    found = []
    for end, x in ((curve.points[0], tube.x[0]), (curve.points[-1], tube.x[-1])):
        crossing = end_crossing(chart, trims, curve, x)
        if crossing is None:
            ends.failures.append((f"curve {index}: an end is not a proven crossing of a trim edge", end))
            return False
        found.append(crossing)
    for edge in trims:
        inner = inner_pieces(chart, edge, pieces)
        reason = touching_runs(chart, edge, pieces, inner, found)
        if reason is not None:
            k = int(np.flatnonzero(~inner)[0]) if (~inner).any() else 0
            raw = pieces[k, [kt.CU, kt.CV]] * chart.units
            ends.failures.append((f"curve {index}: {reason} ({edge.owner}'s {'uv'[edge.fixed]} = {edge.value:g})",
                                  chart.p.point(raw[0], raw[1])))
            return False
    for edge, box in found:
        ends.crossings.setdefault((edge.owner, edge.fixed, edge.value), []).append(box)
    tube.end_boxes = [box for _, box in found]
    return True


def inner_pieces(chart, edge, pieces):
    """(K,) bool: which pieces' arcs lie strictly inside the edge's patch (kernels.certify.trims.arc_inside, the
    piece's length halved up to ARC_DEPTH - 1 times where e's enclosure is not of one sign)."""
    r = chart.reader
    out = np.empty(len(pieces), dtype=np.bool_)
    kr.arcs_inside(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, float(chart.units[0]), float(chart.units[1]),
                   edge.code, edge.value, kr.NO_FACE, edge.inside, pieces, ARC_DEPTH, out)
    return out


def touching_runs(chart, edge, pieces, inner, found):
    """None when the pieces not strictly inside the edge's patch (inner False) form a run at the start and one at
    the end of the chain, each holding that end's proven crossing of this edge and crossing the edge in one
    direction (de/dt of one sign over every piece of the run: e is then monotone along the run's arc, which meets
    the edge once, at the crossing); else why not."""
    touching = np.flatnonzero(~inner)
    if not len(touching):
        return None
    count = len(pieces)
    head = 0
    while head < count and not inner[head]:
        head += 1
    tail = count
    while tail > 0 and not inner[tail - 1]:
        tail -= 1
    if head >= tail or np.any((touching >= head) & (touching < tail)):
        return "its tube comes near a trim edge away from its ends"
    for run, (end_edge, box) in ((range(0, head), found[0]), (range(tail, count), found[1])):
        if not len(run):
            continue
        if end_edge != edge:
            return "an end of its tube comes near a trim edge other than the one it crosses"
        if not any(kt.point_in_pieces(pieces[k:k + 1], 1, box, chart.periods[0], chart.periods[1]) == 0
                   for k in run):
            return "the crossing at an end lies in no piece of the tube that touches the edge"
        rates = np.array([piece_rate(chart, edge.code, edge.value, kr.NO_FACE, pieces[k]) for k in run])
        if not (np.all(rates[:, 0] > 0.0) or np.all(rates[:, 1] < 0.0)):
            return "its arc is not proven to cross the trim edge once"
    return None


def piece_rate(chart, code, value, face, piece):
    """(lo, hi): an enclosure of an edge's rate along the arc of a proven piece (kernels.certify.trims.edge_rate),
    over its parallelogram, or, where that holds 0, the hull over RATE_STRETCHES stretches of the arc."""
    r = chart.reader
    su, sv = float(chart.units[0]), float(chart.units[1])
    for stretches in (0, RATE_STRETCHES):
        lo, hi = kr.edge_rate(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, su, sv, code, value, face, piece, stretches)
        if lo > 0.0 or hi < 0.0:
            break
    return lo, hi


def closed_inside(chart, trims, unsupported, tube, index, ends):
    """True when every piece of a closed curve's tube lies strictly inside every trim (so the loop is inside the
    trimmed patches, not a loop the trims should have cut); else appends the reason to ends.failures."""
    if unsupported:
        ends.failures.append((f"curve {index}: {unsupported[0]}", tube.points[0]))
        return False
    for edge in trims:
        inner = inner_pieces(chart, edge, tube.pieces)
        if not inner.all():
            k = int(np.flatnonzero(~inner)[0])
            raw = tube.pieces[k, [kt.CU, kt.CV]] * chart.units
            ends.failures.append((f"curve {index}: its closed tube is not proven inside a trim ({edge.owner}'s "
                                  f"{'uv'[edge.fixed]} = {edge.value:g})", chart.p.point(raw[0], raw[1])))
            return False
    return True


def end_crossing(chart, trims, curve, x):
    """(edge, scaled box (4,)) of a proven crossing at the end whose scaled parameters are x, or None."""
    r = chart.reader
    raw = x * chart.units
    point_box = np.array([raw[0], raw[0], raw[1], raw[1]])
    near = []
    for edge in trims:
        lo, hi = trim_value(r, point_box, edge)
        gap = max(abs(lo), abs(hi))
        if gap <= ON_EDGE * curve.tolerance:
            near.append((gap, edge))
    for _, edge in sorted(near, key=lambda item: item[0]):
        size = max(1.0, float(np.max(np.abs(x))))
        h = kr.crossing_radius(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, float(chart.units[0]),
                               float(chart.units[1]), edge.code, edge.value, kr.NO_FACE, float(x[0]), float(x[1]),
                               CROSSING_FIRST * size, CROSSING_CAP * size)
        if math.isfinite(h):
            return edge, np.array([x[0] - h, x[0] + h, x[1] - h, x[1] + h])
    return None


def q_edge_roots(chart, topology, found, trims, unsupported, ends, candidates):
    """(text, point) failures for the roots of one search on a trim edge of Q (found: RootBoxes read on Q): every
    root must be one of the proven crossings on that edge (within the range searched) or lie strictly outside
    P's trims (its verified box, or a smaller one proven to hold it: candidates(found, i) yields them); counted,
    since the crossings are distinct roots of that search and it holds no other."""
    fixed, value, t0, t1 = found.args
    where = lambda box: found.reader.s.point(0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3]))  # noqa: E731
    if unsupported:
        return [(f"roots on Q's trim edge: {unsupported[0]}", where(found.verified[0]))]
    q_kind = topology.Q.traits
    p_trims = [e for e in trims if e.owner == "P"]
    # P's trims read on Q: P's local axes (the reader of Q against P)
    p_kind = topology.P.traits
    on_q = [Edge("P", e.fixed, e.value, p_kind.parameter_axes[e.fixed], e.inside) for e in p_trims]
    outside_count = sum(any(outside(found.reader, box, on_q) for box in candidates(found, i))
                        for i in range(len(found.verified)))
    crossings = ends.crossings.get(("Q", fixed, value), [])
    other = 1 - fixed
    r = chart.reader
    for box in crossings:
        raw = box * np.repeat(chart.units, 2)
        if not strictly_inside(r, raw, p_trims):
            return [("a crossing of Q's trim edge is not proven inside P's trims", where(found.verified[0]))]
        if q_kind.units[other] == LENGTH:
            span = Edge("Q", other, 0.0, q_kind.parameter_axes[other], 1.0)
            lo, hi = trim_value(r, raw, span)
            if not (t0 < lo and hi < t1):
                return [("a crossing of Q's trim edge is not proven within the range searched",
                         where(found.verified[0]))]
        elif t1 - t0 < 2.0 * math.pi:
            return [("Q's trim edge was searched over part of a turn", where(found.verified[0]))]
    if not pairwise_apart(crossings, chart):
        return [("two crossings of Q's trim edge are not proven distinct", where(found.verified[0]))]
    if outside_count + len(crossings) != len(found.verified):
        return [(f"{len(found.verified)} roots on Q's trim edge, {len(crossings)} proven on returned curves and "
                 f"{outside_count} outside P's trims", where(found.verified[0]))]
    return []


def pairwise_apart(boxes, chart):
    """True when the scaled boxes (4,) are pairwise disjoint, also shifted by any whole number of periods (the
    turns nearest to each pair, and one either side)."""
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            a, b = boxes[i], boxes[j]
            if any(boxes_meet(a, b, su, sv) for su, sv in chart.shifts(a, b)):
                return False
    return True


def boxes_meet(a, b, su, sv):
    """True unless the boxes (4,) a and b shifted by (su, sv) are apart by more than a round-off slack."""
    slack = 1e-12 * (1.0 + abs(su) + abs(sv) + float(np.max(np.abs(a))))
    return not (a[1] + slack < b[0] + su or b[1] + su + slack < a[0] or
                a[3] + slack < b[2] + sv or b[3] + sv + slack < a[2])
