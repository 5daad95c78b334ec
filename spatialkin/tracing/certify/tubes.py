"""Proven tubes along returned curves, in the chart the topology search read (spatialkin.kernels.certify.tubes).

Each curve's points, and dense samples between them, are mapped to the parameters of the search's surface P
(its chart ``topology.chart``) and covered by a linked chain of parallelograms, each proven to hold exactly one
arc of the level g = F_Q(P(u, v)) = 0 that enters and leaves through its opposite ends. The chain proves the arcs
between the samples and that the curve is connected; a closed chain proves a whole closed component. Disjoint
chains are distinct components; a root of the search whose box lies inside a piece is a point of that piece's arc.
"""
import math

import numpy as np

from ...geometry.traits import power_of_two, traits
from ...kernels.certify import tubes as kt
from ...kernels.curve.stored import unwrap_turns
from ..curve.exact import ExactSolution
from ..search.topology import Reader

#: Dense samples per stored step (the chords between them carry the pieces).
SAMPLES_PER_STEP = 2
#: Refinements of the samples round a failing chord before a tube is given up.
REFINEMENTS = 96
#: Chords refined on each side of a failing one.
WINDOW = 4
#: Shortest chord kept, relative to the median chord.
MIN_CHORD = 0.2
#: Pieces allowed per chord, on average, before the chain gives up (BUDGET).
PIECES_PER_CHORD = 16
#: Smallest half-width of a piece, in ulps of the scaled coordinates' magnitude.
FLOOR_ULPS = 64.0


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
    """

    def __init__(self, pieces, status, where, s, points, x):
        self.pieces, self.status, self.where, self.s, self.points, self.x = pieces, status, where, s, points, x
        self.radii = None

    @property
    def proven(self):
        return self.status == kt.PROVEN

    @property
    def reason(self):
        return {kt.PROVEN: "proven", kt.PIECE_FAILED: "no piece of the tube could be proven",
                kt.LINK_FAILED: "two consecutive pieces could not be linked",
                kt.BUDGET: "the tube ran out of pieces"}[self.status]


class Chart:
    """The search's surface P read against Q (or Q against P): its Reader (the rigorous placement), the
    power-of-two units of its parameters, and their periods in those units (0 where not periodic)."""

    def __init__(self, topology, scale, other=False):
        """other: Q's chart (Q read against the search's P) instead."""
        self.p, q = (topology.Q, topology.chart) if other else (topology.chart, topology.Q)
        self.reader = Reader(self.p, q)
        kind = traits(self.p)
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


def curve_samples(curve):
    """(points (M, 3), s (M,)): the curve's stored points with SAMPLES_PER_STEP - 1 dense samples between each
    two (the dense output's points, Newton-corrected onto both surfaces); a closed form's stored points alone (its
    dense output is exact, its points evenly spread)."""
    s = np.asarray(curve.s, dtype=float)
    if len(s) < 2 or not curve.length > 0 or isinstance(curve.sol, ExactSolution):
        return np.asarray(curve.points, dtype=float), s
    fractions = np.arange(SAMPLES_PER_STEP) / SAMPLES_PER_STEP
    dense = (s[:-1, None] + np.diff(s)[:, None] * fractions[None, :]).ravel()
    dense = np.append(dense, s[-1])
    points = np.asarray(curve.sol(dense), dtype=float).reshape(-1, 3)
    stored = np.arange(0, len(dense), SAMPLES_PER_STEP)
    points[stored] = curve.points                  # the stored points themselves, not their re-evaluation
    return points, dense


def tube(chart, curve):
    """The Tube of one curve (a CurveResult of positive length) in the chart: where the chain fails, the samples
    round the failing chord are refined (dense output at the midpoints) and the chain is proven again, up to
    REFINEMENTS times."""
    points, s = curve_samples(curve)
    for _ in range(REFINEMENTS):
        x, kept = chain_samples(chart, curve, points)
        pieces, status, chord = chain(chart, x, curve.closed, x[-1] - x[0] if curve.closed else np.zeros(2))
        if status == kt.PROVEN:
            return Tube(pieces, status, None, s, points, x)
        at = kept[min(max(chord, 0), len(kept) - 2)]
        lo, hi = max(at - WINDOW, 0), min(at + WINDOW + 1, len(s) - 1)
        mids = 0.5 * (s[lo:hi] + s[lo + 1:hi + 1])
        s = np.sort(np.concatenate([s, mids]))
        points = merged(points, s, mids, np.asarray(curve.sol(mids), dtype=float).reshape(-1, 3))
    return Tube(pieces, status, points[kept][min(max(chord, 0), len(kept) - 1)], s, points, x)


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


def chain_samples(chart, curve, points):
    """(x (M, 2) scaled parameters of the kept samples, their indices): unwrapped, the closing point of a closed
    curve put exactly a whole number of turns from the first, too-close samples dropped (spaced)."""
    x = np.ascontiguousarray(chart.scaled(points))
    if curve.closed:
        shift = np.zeros(2)
        for j in range(2):
            if chart.periodic[j]:
                shift[j] = round((x[-1, j] - x[0, j]) / chart.periods[j]) * chart.periods[j]
        x[-1] = x[0] + shift                   # the closing point is the first one, a whole number of turns on
    keep = spaced(x)
    return np.ascontiguousarray(x[keep]), keep


def chain(chart, x, closed, shift):
    """(pieces (K, WIDTH), status, failing chord) of kernels.certify.tubes.tube_chain along x."""
    floor = FLOOR_ULPS * np.finfo(float).eps * max(float(np.max(np.abs(x))), 1.0)
    pieces = np.empty((PIECES_PER_CHORD * len(x) + 8, kt.WIDTH))
    r = chart.reader
    count, status, chord = kt.tube_chain(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, float(chart.units[0]),
                                         float(chart.units[1]), x, bool(closed), float(shift[0]), float(shift[1]),
                                         floor, len(pieces), pieces)
    return pieces[:count].copy(), status, chord


def spaced(x):
    """Indices of the rows of x (M, 2) kept as the chain's samples (kernels.certify.tubes.spaced): a sample closer
    than MIN_CHORD times the median chord to the last kept one is dropped (a piece along a very short chord cannot
    hold the longer one before it), the last row always kept."""
    keep = np.empty(len(x), dtype=np.int64)
    return keep[:kt.spaced(x, MIN_CHORD, keep)]
