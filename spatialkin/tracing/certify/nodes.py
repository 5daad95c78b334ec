"""Nodes in the certificate: where two branches of the level g = F_Q(P(u, v)) = 0 cross, or pass too close for
floating point to tell.

A node's box N (a square of the search chart's scaled parameters around it) is proven to hold exactly one critical
point of g, a saddle (the Krawczyk test of grad g = 0 with a Hessian of negative determinant over N,
spatialkin.kernels.certify.singular), and g is proven to vanish at exactly four points of N's edges (simple roots
isolated by the interval line search of the topology stage, none at a corner). Then the level inside N is two arcs
joining those four points, crossing at the saddle or not: a closed loop of the level in N, or a lobe closing on
itself, would bound a disc where g has an extremum, a critical point other than the saddle. Each of the four points
must lie in a proven piece of a returned curve's tube (the tubes are chained on either side of N, their ends
reaching into it): every branch leaving the node then runs on through proven tubes. Which of the four points the two
arcs join (a crossing, or two branches passing close, either way) is an equality floating point cannot decide: a
curve through a node is not proven one component.
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


@dataclass
class NodeBox:
    """A node's proven box: its index among the search's nodes, its point (3,), the scaled centre x (2,) and
    half-width h of N, the scaled boxes (4,) of the four proven roots of g on N's edges, and the largest speed of P
    over N (length per scaled unit)."""
    index: int
    point: np.ndarray
    x: np.ndarray
    h: float
    crossings: list
    speed: float

    @property
    def radius(self):
        """A ball around the node's point holding its box (length unit): the box's half-diagonal times the largest
        speed of P over it."""
        return math.sqrt(2.0) * self.h * self.speed

    @property
    def box(self):
        """N as a scaled box (u lo, u hi, v lo, v hi)."""
        return np.array([self.x[0] - self.h, self.x[0] + self.h, self.x[1] - self.h, self.x[1] + self.h])


def node_boxes(chart, nodes, chord):
    """The NodeBox of each node point (3,) in the chart for which one is proven: the smallest box of SHARES x chord
    that passes (module docstring); the others are left out (the chain through them fails)."""
    boxes = []
    for index, point in enumerate(nodes):
        point = np.asarray(point, dtype=float)
        x = chart.scaled(point[None])[0]
        for share in SHARES:
            h = share * chord
            speed = saddle_box(chart, x, h) if h > 0.0 else None
            if speed is not None:
                crossings = edge_crossings(chart, x, h)
                if crossings is not None and len(crossings) == 4:
                    boxes.append(NodeBox(index, point, x, h, crossings, speed))
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


def typical_chord(chart, curves):
    """The median chord between consecutive stored points of the curves of positive length, in the chart's scaled
    parameters (0 when there is none)."""
    chords = [np.hypot(*np.diff(chart.scaled(c.points), axis=0).T) for c in curves
              if c.length > 0 and len(c.points) > 1]
    return float(np.median(np.concatenate(chords))) if chords else 0.0


def linked(chart, boxes, tubes):
    """(the node boxes whose four crossings each lie in a proven piece of a tube, failures [(text, point)] of the
    others)."""
    pieces = [t.pieces for t in tubes if t is not None and t.proven]
    pieces = np.concatenate(pieces) if pieces else np.empty((0, kt.WIDTH))
    good, failures = [], []
    for node in boxes:
        if all(kt.point_in_pieces(pieces, len(pieces), np.ascontiguousarray(box), chart.periods[0],
                                  chart.periods[1]) >= 0 for box in node.crossings):
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
