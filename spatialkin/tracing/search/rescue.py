"""Starts for a component whose every start from the topology stage was lost: the parameter lines of P through the
middles of its lost starts.

The interior search seeds a closed loop at its extremes in a fixed direction d (spatialkin.tracing.search.topology). On
a thin loop along a near-tangency (a sphere 1e-8 of its radius off a cylinder's axis: the loop runs half round the
cylinder, 2e-4 high) those extremes are the loop's two ends, where the surfaces' normals are within about 1e-8 of
parallel: Newton cannot locate the curve there, and every start of the loop is lost. Its middle is well conditioned.
Both arcs of a loop run from one end to the other, so each crosses the parameter line u = (u_A + u_B) / 2 of P, and v =
(v_A + v_B) / 2, between two ends A and B (the intermediate value theorem; round a periodic u the arcs may run the other
way, so that line + pi too): the topology stage's rigorous line search finds those crossings, and they start the loop.

References
----------
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002
(surface-surface intersection by marching: finding a start on every component; loops near a tangency).
"""
import itertools
import math

import numpy as np

from .topology import Keeper, Reader, Topology, TopologyError, domain, line_params, search_roles

#: A start that could be neither located nor traced is lost when it lies farther than this (relative to the scale)
#: from every component traced (the starts beside the end of a branch that stopped at a near-singular point lie
#: within 2e-5 of it, measured; a missed loop's have no component near them).
LOST_RADIUS = 1e-3
#: Lost starts within this (relative to the scale) of one kept as a cluster's representative belong to its cluster;
#: at most MAX_CLUSTERS representatives are paired (each pair costs two or four line searches; a thin loop has
#: two clusters, one at each end).
CLUSTER_RADIUS = 1e-3
MAX_CLUSTERS = 6
#: Box budget of one rescue line: a line that runs along the thin loop (g within its depth of zero all along) may
#: not resolve; it is skipped, and the line across the loop seeds it.
RESCUE_BOXES = 20_000


def representatives(points, radius):
    """The first point of each cluster of points (a list of (3,)): a point farther than radius from every
    representative so far starts a new one; at most MAX_CLUSTERS."""
    reps = []
    for x in points:
        if all(math.dist(x, r) > radius for r in reps):
            reps.append(x)
            if len(reps) == MAX_CLUSTERS:
                break
    return reps


def middle_lines(uv, box, periodic):
    """(fixed, value) of the parameter lines u = middle and v = middle between each pair of parameter points uv
    (K, 2), a periodic parameter's also half a turn on, each value wrapped into the box (u_lo, u_hi, v_lo, v_hi)."""
    lines = set()
    for i, j in itertools.combinations(range(len(uv)), 2):
        for fixed in (0, 1):
            if uv[i, fixed] == uv[j, fixed]:
                continue
            middle = 0.5 * (uv[i, fixed] + uv[j, fixed])
            for value in ((middle, middle + math.pi) if periodic[fixed] else (middle,)):
                lo, hi = box[2 * fixed], box[2 * fixed + 1]
                if periodic[fixed]:
                    value = lo + math.fmod(value - lo, hi - lo) % (hi - lo)
                if lo < value < hi or (periodic[fixed] and value == lo):
                    lines.add((fixed, float(value)))
    return sorted(lines)


def crossing_starts(a, b, scale, tolerance, lost):
    """Points (N, 3), inside both trims, where the parameter lines of P through the middles of pairs of the lost
    starts (a list of (3,)) cross the level g = 0 (verified roots and unresolved boxes' middles alike: each is
    located on the curve before it is traced); empty when the search is not the general one (coaxial and ruled
    placements are solved on one meridian or cross-section)."""
    p_user, q, mode, p, balls = search_roles(a, b, scale)
    reps = representatives(lost, CLUSTER_RADIUS * scale)
    if mode != "general" or len(reps) < 2:
        return np.empty((0, 3))
    box, u_periodic, v_periodic = domain(p, balls[id(q)])
    if not box[0] < box[1] or not box[2] < box[3]:
        return np.empty((0, 3))
    reader = Reader(p, q)
    keep = Keeper(a, b, [], scale, tolerance)
    scratch = Topology(P=p_user, Q=q, mode=mode)            # (the line searches' counts; not reported)
    starts = []
    for fixed, value in middle_lines(p.parameters(np.array(reps)), box, (u_periodic, v_periodic)):
        try:
            roots, unresolved = reader.line(fixed, value, box[2 - 2 * fixed], box[3 - 2 * fixed], scratch, "rescue",
                                            budget=RESCUE_BOXES)
        except TopologyError:
            continue
        points, kept = keep.on(p, line_params(fixed, value, np.concatenate([roots, unresolved])))
        starts.append(points[kept])
    return np.concatenate(starts) if starts else np.empty((0, 3))
