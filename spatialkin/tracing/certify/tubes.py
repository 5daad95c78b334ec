"""Proven tubes along returned curves, in the chart the topology search read (spatialkin.kernels.certify.tubes).

Each curve's points, and dense samples between them, are mapped to the parameters of the search's surface P
(its chart ``topology.chart``) and covered by a linked chain of parallelograms, each proven to hold exactly one
arc of the level g = F_Q(P(u, v)) = 0 that enters and leaves through its opposite ends. The chain proves the arcs
between the samples and that the curve is connected; a closed chain proves a whole closed component. Disjoint
chains are distinct components; a root of the search whose box lies inside a piece is a point of that piece's arc.
"""
import math

import numpy as np

from ...geometry.traits import power_of_two
from ...kernels.certify import tubes as kt
from ...kernels.curve.stored import unwrap_turns
from ..curve.exact import ExactSolution
from ..search.topology import Reader
from . import nodes as nd

#: Dense samples per stored step (the chords between them carry the pieces).
SAMPLES_PER_STEP = 2
#: Refinements of the samples round a failing chord before a tube is given up.
REFINEMENTS = 96
#: Chords refined on each side of a failing one. The window doubles, up to MOST_WINDOW, each time the chain
#: fails beyond the stretch refined the time before (near a tangency it fails chord after chord, and each proof
#: of it starts again); after STUCK_ROUNDS refinements in a row that do not carry it beyond, the tube is given up
#: (a chain that creeps towards a singular end).
WINDOW, MOST_WINDOW, STUCK_ROUNDS = 4, 256, 16
#: The work one chain may take: at most MOST_SAMPLES samples, MOST_PIECES pieces (about 20 MB) and MOST_WORK
#: pieces tried (proven or not) and samples over all its attempts (a few seconds); beyond, its tube is given up as
#: out of budget (not proven). A chain beside another branch a distance d away needs pieces narrower than d: near
#: a tangency the count grows like one over the square root of the tangency's gap.
MOST_SAMPLES, MOST_PIECES, MOST_WORK = 50_000, 250_000, 1_000_000
#: Shortest chord kept, relative to the median chord.
MIN_CHORD = 0.2
#: Pieces allowed per chord, on average, before the chain gives up (BUDGET); a chain that runs out is tried again
#: with twice as many, up to MOST_PIECES_PER_CHORD, before its samples are refined.
PIECES_PER_CHORD, MOST_PIECES_PER_CHORD = 16, 128
#: Smallest half-width of a piece, in ulps of the scaled coordinates' magnitude.
FLOOR_ULPS = 64.0
#: Bisections on the dense output for a run's end inside a node box.
NODE_BISECTIONS = 40
#: Dense samples added in a chord that passes near a node.
PASSAGE_SAMPLES = 32


class Tube:
    """A proven (or failed) chain of pieces along one curve.

    pieces : ndarray (K, kernels.certify.tubes.WIDTH)   the pieces, in scaled parameters of the chart
    status : int             kernels.certify.tubes.PROVEN, PIECE_FAILED, LINK_FAILED or BUDGET
    where : ndarray (3,) or None      the curve's point where the chain failed
    s : ndarray (M,)         arc lengths of the samples the chain was built on (stored points, dense samples
                             and refinements)
    points : ndarray (M, 3)  those samples
    x : ndarray (L, 2)       the scaled parameters of the samples the chain followed (unwrapped)
    radii : ndarray or None  the proven box half-widths of the samples other than the stored points (set by the
                             certificate, spatialkin.tracing.certify.certificate.sample_radii)
    split : bool             made of one open chain per run of the curve between node boxes (their ends
                             reaching into the boxes), not of one chain
    passes : frozenset       the indices (among the search's nodes) of the node boxes the curve passes
    runs : list              where split: per run of the curve between node boxes, in the curve's order,
                             (its pieces (K, WIDTH) in chain order, the NodeBox it comes from, the one it goes to;
                             None at the curve's own end)
    end_boxes : list         an open curve's ends proven on trim edges: the scaled boxes (4,) holding them
                             (spatialkin.tracing.certify.trims.open_curve), else empty
    """

    def __init__(self, pieces, status, where, s, points, x):
        self.pieces, self.status, self.where, self.s, self.points, self.x = pieces, status, where, s, points, x
        self.radii = None
        self.split = False
        self.passes = frozenset()
        self.runs = []
        self.end_boxes = []

    @property
    def proven(self):
        return self.status == kt.PROVEN

    @property
    def reason(self):
        return {kt.PROVEN: "proven", kt.PIECE_FAILED: "no piece of the tube could be proven",
                kt.LINK_FAILED: "two consecutive pieces could not be linked",
                kt.BUDGET: "the tube ran out of its work budget (pieces or samples)"}[self.status]


class Chart:
    """The search's surface P read against Q (or Q against P): its Reader (the rigorous placement), the
    power-of-two units of its parameters, and their periods in those units (0 where not periodic)."""

    def __init__(self, topology, scale, other=False):
        """other: Q's chart (Q read against the search's P) instead."""
        self.p, q = (topology.Q, topology.chart) if other else (topology.chart, topology.Q)
        self.reader = Reader(self.p, q)
        kind = self.p.traits
        self.units = np.array([power_of_two(x) for x in kind.parameter_units(scale)])
        self.periodic = tuple(bool(x) for x in kind.periodic)
        self.periods = np.array([2.0 * math.pi / self.units[j] if self.periodic[j] else 0.0 for j in range(2)])

    def scaled(self, points):
        """(N, 2) scaled parameters of points (N, 3) on P, periodic ones unwrapped along the sequence."""
        uv = self.p.parameters(np.asarray(points, dtype=float).reshape(-1, 3))
        for j in range(2):
            if self.periodic[j]:
                column = np.ascontiguousarray(uv[:, j])
                unwrap_turns(column)
                uv[:, j] = column
        return uv / self.units

    def shifts(self, a, b):
        """The whole-period shifts (su, sv) of scaled box b (4,) that may bring it onto box a: the turns nearest
        to the difference of their centres, and one either side (a single (0, 0) where nothing is periodic)."""
        out = []
        for j in range(2):
            period = self.periods[j]
            if not period:
                out.append((0.0,))
                continue
            n = round((a[2 * j] + a[2 * j + 1] - b[2 * j] - b[2 * j + 1]) / (2.0 * period))
            out.append(tuple((n + k) * period for k in (-1, 0, 1)))
        return [(su, sv) for su in out[0] for sv in out[1]]

    def scaled_boxes(self, boxes):
        """Raw parameter boxes (K, 4) of P as scaled boxes (exact: the units are powers of two)."""
        return np.ascontiguousarray(boxes / np.repeat(self.units, 2))


def curve_samples(curve, arcs=()):
    """(points (M, 3), s (M,), the arc lengths of the arcs' samples among s): the curve's stored points with
    SAMPLES_PER_STEP - 1 dense samples between each two (the dense output's points, Newton-corrected onto both
    surfaces); a closed form's stored points alone (its dense output is exact, its points evenly spread); and, for
    each arc (s0, s1) of it that a face cuts out (arcs), the samples arc_samples puts in and beside it."""
    s = np.asarray(curve.s, dtype=float)
    if len(s) < 2 or not curve.length > 0:
        return np.asarray(curve.points, dtype=float), s, np.empty(0)
    if isinstance(curve.sol, ExactSolution):
        points = np.asarray(curve.points, dtype=float)
    else:
        fractions = np.arange(SAMPLES_PER_STEP) / SAMPLES_PER_STEP
        dense = (s[:-1, None] + np.diff(s)[:, None] * fractions[None, :]).ravel()
        dense = np.append(dense, s[-1])
        points = np.asarray(curve.sol(dense), dtype=float).reshape(-1, 3)
        points[np.arange(0, len(dense), SAMPLES_PER_STEP)] = curve.points     # the stored points, not re-evaluated
        s = dense
    extra = arc_samples(curve, arcs, float(np.median(np.diff(s))), s)
    if not len(extra):
        return points, s, extra
    every = np.concatenate([s, extra])
    order = np.argsort(every, kind="stable")
    points = np.concatenate([points, np.asarray(curve.sol(extra), dtype=float).reshape(-1, 3)])[order]
    return points, every[order], extra


def arc_samples(curve, arcs, chord, s):
    """Arc lengths (K,) inside (0, length) of the samples added for the arcs (s0, s1) a face cuts from the curve
    (its samples at s, their typical chord: chord): a quarter, a half and three quarters along each arc shorter
    than 4 chords, and beside its ends at a quarter of its length times 2, 4, 8, ... up to the chord, each no
    nearer to a sample than a tenth of that quarter (a narrow face crossed within one chord would leave both
    crossings of its edges in one run of the tube's pieces; the chords grow by no more than twice from one to the
    next, and the chain keeps these samples however close: chain_samples)."""
    out = []
    for s0, s1 in arcs:
        step = 0.25 * (s1 - s0)
        if not 0.0 < step < chord:
            continue
        grades = step * 2.0 ** np.arange(int(math.log2(chord / step)) + 1)
        more = np.concatenate([s0 + step * np.arange(1.0, 4.0), s0 - grades, s1 + grades])
        more = np.mod(more, curve.length) if curve.closed else more
        more = more[(more > 0.0) & (more < curve.length)]
        gap = np.min(np.abs(more[:, None] - s[None, :]), axis=1)
        out.append(more[gap >= 0.1 * step])
    return np.unique(np.concatenate(out)) if out else np.empty(0)


def tube(chart, curve, nodes=(), arcs=()):
    """The Tube of one curve (a CurveResult of positive length) in the chart: one chain along its samples (and those
    of the arcs (s0, s1) a face cuts from it: curve_samples), or, where it passes the boxes of nodes
    (spatialkin.tracing.certify.nodes.NodeBox), one open chain along each run of samples between them, each run's
    ends inside the node boxes it leaves and enters (node_runs)."""
    points, s, forced = curve_samples(curve, arcs)
    runs, passed = node_runs(chart, curve, points, s, nodes) if len(nodes) else (None, ())
    if runs is None:
        return chained(chart, curve, points, s, curve.closed, forced)
    if not runs:
        failed = Tube(np.empty((0, kt.WIDTH)), kt.PIECE_FAILED, points[0], s, points, chart.scaled(points))
        failed.split = True
        failed.passes = frozenset(nodes[j].index for j in passed)
        return failed
    parts = [chained(chart, curve, run_points, run_s, False, forced) for run_points, run_s, _, _ in runs]
    failed = next((t for t in parts if not t.proven), None)
    every_s = np.concatenate([s] + [t.s for t in parts])     # (a closed curve's runs may pass s = 0)
    every_s = np.where((every_s < 0.0) | (every_s > curve.length), np.mod(every_s, curve.length), every_s)
    every_s, first = np.unique(every_s, return_index=True)
    every_points = np.concatenate([points] + [t.points for t in parts])[first]
    whole = Tube(np.concatenate([t.pieces for t in parts]), kt.PROVEN if failed is None else failed.status,
                 None if failed is None else failed.where, every_s, every_points,
                 np.concatenate([t.x for t in parts]))
    whole.split = True
    whole.passes = frozenset(nodes[j].index for j in passed)
    whole.runs = [(t.pieces, nodes[before] if before >= 0 else None, nodes[after] if after >= 0 else None)
                  for t, (_, _, before, after) in zip(parts, runs)]
    return whole


def chained(chart, curve, points, s, closed, forced=()):
    """The Tube of one chain along the samples points (M, 3) at arc lengths s (M,) of the curve (closed: the last
    sample is the first one, a whole loop on): where the chain fails, the samples around the failing chord are
    refined (dense output at the midpoints) and the chain is proven again, up to REFINEMENTS times; where it runs
    out of pieces, it is given more (up to MOST_PIECES_PER_CHORD per chord), then every chord is halved."""
    per_chord, window, beyond, stuck, work = PIECES_PER_CHORD, WINDOW, None, 0, 0
    for _ in range(REFINEMENTS):
        x, kept = chain_samples(chart, points, closed, np.isin(s, forced))
        per_chord = min(per_chord, max(MOST_PIECES // len(x), 1))
        pieces, status, chord, tries = chain(chart, x, closed, x[-1] - x[0] if closed else np.zeros(2), per_chord)
        if status == kt.PROVEN:
            return Tube(pieces, status, None, s, points, x)
        work += tries + len(x)
        if work > MOST_WORK:
            status = kt.BUDGET
            break
        if status == kt.BUDGET:
            if 2 * per_chord * len(x) > MOST_PIECES:
                break                   # (out of the whole budget of pieces: more samples would not give more)
            if per_chord < MOST_PIECES_PER_CHORD:
                per_chord *= 2          # (pieces short all along, near a tangency: more of them, the same samples)
                continue
        at = kept[min(max(chord, 0), len(kept) - 2)]
        if status == kt.BUDGET:
            lo, hi = 0, len(s) - 1          # (out of pieces all along: every chord halved)
        else:
            if beyond is None or s[at] >= beyond:
                window = WINDOW if beyond is None else min(2 * window, MOST_WINDOW)
                stuck = 0
            else:
                stuck += 1
                if stuck >= STUCK_ROUNDS:
                    break
            lo, hi = max(at - window, 0), min(at + window + 1, len(s) - 1)
            beyond = s[hi]
        mids = 0.5 * (s[lo:hi] + s[lo + 1:hi + 1])
        mids = mids[(mids > s[lo:hi]) & (mids < s[lo + 1:hi + 1])]      # (none between neighbouring floats)
        if not len(mids) or len(s) + len(mids) > MOST_SAMPLES:
            if len(mids):
                status = kt.BUDGET
            break
        s = np.sort(np.concatenate([s, mids]))
        points = merged(points, s, mids, np.asarray(curve.sol(mids), dtype=float).reshape(-1, 3))
    return Tube(pieces, status, points[kept][min(max(chord, 0), len(kept) - 1)], s, points, x)


def node_runs(chart, curve, points, s, nodes):
    """(runs, the indices into nodes of the boxes passed): the runs of the curve's samples outside the node boxes,
    in the curve's order, each (points (K, 3), s (K,), the index into nodes of the box it comes from, of the box it
    goes to; -1 at the curve's own end) beginning and ending at a point of the curve inside the box it comes from
    or goes to (at half its half-width from the node, found by bisection on the dense output), or at the curve's
    own ends; runs None when the curve passes no node box, [] when it lies wholly inside them."""
    points, s = node_passages(chart, curve, points, s, nodes)
    x = chart.scaled(points)
    where = np.full(len(x), -1)
    for j, node in enumerate(nodes):
        where[nd.inside(chart, node, x)] = j
    if not (where >= 0).any():
        return None, ()
    passed = set(where[where >= 0].tolist())
    count = len(x) - 1 if curve.closed else len(x)       # (a closed curve's last sample is its first)
    if (where[:count] >= 0).all():
        return [], passed
    order = np.arange(count)
    if curve.closed:                 # start where the curve leaves a node box
        start = next(k for k in range(count) if where[(k - 1) % count] >= 0 and where[k] < 0)
        order = np.roll(order, -start)
    flat_s = s[order] + np.where(order < order[0], curve.length, 0.0) if curve.closed else s[order]
    runs, k = [], 0
    while k < count:
        if where[order[k]] >= 0:
            k += 1
            continue
        first = k
        while k < count and where[order[k]] < 0:
            k += 1
        idx = order[first:k]
        run_points, run_s = list(points[idx]), list(flat_s[first:k])
        before = order[first - 1] if first > 0 else (order[-1] if curve.closed else -1)
        after = order[k] if k < count else (order[0] if curve.closed else -1)
        if before >= 0 and where[before] >= 0:
            s_in = flat_s[first - 1] if first > 0 else flat_s[-1] - curve.length
            p, at = node_end(chart, curve, nodes[where[before]], s_in, flat_s[first])
            run_points.insert(0, p)
            run_s.insert(0, at)
        if after >= 0 and where[after] >= 0:
            s_in = flat_s[k] if k < count else flat_s[0] + curve.length
            p, at = node_end(chart, curve, nodes[where[after]], s_in, flat_s[k - 1])
            run_points.append(p)
            run_s.append(at)
        runs.append((np.array(run_points), np.array(run_s), int(where[before]) if before >= 0 else -1,
                     int(where[after]) if after >= 0 else -1))
    return runs, passed


def node_passages(chart, curve, points, s, nodes):
    """(points, s): the samples with PASSAGE_SAMPLES dense ones added in each chord that comes within twice a
    node box's half-width of the node (a passage whose samples straddle the box gets samples inside it)."""
    x = chart.scaled(points)
    near = np.zeros(len(x) - 1, dtype=bool)
    for node in nodes:
        ends = nd.shifted_into(chart, node, x) - node.x
        lo, hi = np.minimum(ends[:-1], ends[1:]), np.maximum(ends[:-1], ends[1:])
        near |= np.all((lo < 2.0 * node.h) & (hi > -2.0 * node.h), axis=1)
    if not near.any():
        return points, s
    fractions = np.arange(1, PASSAGE_SAMPLES + 1) / (PASSAGE_SAMPLES + 1)
    extra = (s[:-1][near, None] + np.diff(s)[near, None] * fractions[None, :]).ravel()
    every = np.concatenate([s, extra])
    order = np.argsort(every, kind="stable")
    fresh = np.asarray(curve.sol(extra), dtype=float).reshape(-1, 3)
    return np.concatenate([points, fresh])[order], every[order]


def node_end(chart, curve, node, s_in, s_out):
    """(point (3,), s) of the curve inside the node's box at about half its half-width from the node (in the
    chart's scaled parameters, max norm), between the sample inside at s_in and the one outside at s_out
    (bisection on the dense output); the inside sample itself when it is that far already."""
    def reach(at):
        p = np.asarray(curve.sol(at), dtype=float).reshape(3)
        x = nd.shifted_into(chart, node, chart.scaled(p[None])[0])
        return p, float(np.max(np.abs(x - node.x))) / node.h
    p, r = reach(s_in)
    if r >= 0.5:
        return p, s_in
    lo, hi = s_in, s_out
    for _ in range(NODE_BISECTIONS):
        mid = 0.5 * (lo + hi)
        p, r = reach(mid)
        if abs(r - 0.5) < 0.1:
            return p, mid
        lo, hi = (mid, hi) if r < 0.5 else (lo, mid)
    return reach(0.5 * (lo + hi))[0], 0.5 * (lo + hi)


def merged(points, s_new, mids, fresh):
    """The sample points in the order of the sorted s_new (the old samples' s and mids, whose points are
    fresh)."""
    out = np.empty((len(s_new), 3))
    where = np.searchsorted(s_new, mids)
    mask = np.ones(len(s_new), dtype=bool)
    mask[where] = False
    out[where] = fresh
    out[mask] = points
    return out


def chain_samples(chart, points, closed, forced=None):
    """(x (M, 2) scaled parameters of the kept samples, their indices): unwrapped, the closing point of a closed
    chain put exactly a whole number of turns from the first, too-close samples dropped (spaced) but those marked
    forced (M,) (arc_samples: graded, so that no chord is shorter than half the one before it)."""
    x = np.ascontiguousarray(chart.scaled(points))
    if closed:
        shift = np.zeros(2)
        for j in range(2):
            if chart.periodic[j]:
                shift[j] = round((x[-1, j] - x[0, j]) / chart.periods[j]) * chart.periods[j]
        x[-1] = x[0] + shift                   # the closing point is the first one, a whole number of turns on
    keep = spaced(x)
    if forced is not None and forced.any():
        keep = np.union1d(keep, np.flatnonzero(forced))
    return np.ascontiguousarray(x[keep]), keep


def chain(chart, x, closed, shift, per_chord=PIECES_PER_CHORD):
    """(pieces (K, WIDTH), status, failing chord, pieces tried) of kernels.certify.tubes.tube_chain along x, with
    per_chord pieces per chord on average at most."""
    floor = FLOOR_ULPS * np.finfo(float).eps * max(float(np.max(np.abs(x))), 1.0)
    pieces = np.empty((per_chord * len(x) + 8, kt.WIDTH))
    r = chart.reader
    count, status, chord, tries = kt.tube_chain(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, float(chart.units[0]),
                                                float(chart.units[1]), x, bool(closed), float(shift[0]),
                                                float(shift[1]), floor, len(pieces), pieces)
    return pieces[:count].copy(), status, chord, tries


def spaced(x):
    """Indices of the rows of x (M, 2) kept as the chain's samples (kernels.certify.tubes.spaced): a sample closer
    than MIN_CHORD times the median chord to the last kept one is dropped (a piece along a very short chord cannot
    hold the longer one before it), the last row always kept."""
    keep = np.empty(len(x), dtype=np.int64)
    return keep[:kt.spaced(x, MIN_CHORD, keep)]
