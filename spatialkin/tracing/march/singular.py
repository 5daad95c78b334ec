"""Passing singular points of a branch straight through: nodes where branches cross, apexes of a spindle or
horn torus or a cone, a horn torus's cusp.

References
----------
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002
(singular points of intersection curves): a sign flip of N1 x N2 marks a node passed; the corrector in the plane
normal to the direction of travel keeps to the same branch.
"""
import numpy as np
from numpy.polynomial import legendre

from ...kernels.march import curve as kc
from ...kernels.geometry import surfaces as ks
from ...geometry.quadrature import legendre_rule
from ..curve.result import set_states
from .segments import NEWTON_MAX_ITER, LinearStates, Segment, newton_fixed

# --- named limits -------------------------------------------------------------------------------------
#: A singular point (a node where branches cross, the apex of a spindle or horn torus or a cone) is passed by a
#: jump of this length (relative to the curve scale) along the incoming direction, then Newton lands the point
#: in the plane normal to it; the jump's dense output is corrected in that plane.
JUMP_LENGTH = 1e-3
#: Longest jump (relative to the curve scale), reached by doubling where the landing is still beside an apex.
MAX_JUMP = 0.1
#: The relative area element of a parametrisation below which its apex is jumped (not a pole: spheres are
#: re-charted well before).
APEX_GUARD = 2e-4
#: After a jump the point must lie within this fraction of the jump of the straight continuation.
JUMP_STRAIGHTNESS = 0.1
#: A jump must land where the normals' sine exceeds ten times this (clear of the node), else it is doubled.
NODE_CLEARANCE = 1e-6
#: A node located by a jump is the singular point proven by the topology stage within this distance (relative to
#: the scale).
SNAP = 1e-2
#: Gauss-Legendre nodes per side of a jump (start to node, node to end) measuring the curve's arc length over it.
ARC_NODES = 8
#: Newton steps mapping an arc length inside a jump to its chord position (speed within 1e-2 of 1 there: each step
#: squares the error).
ARC_NEWTON = 5
#: A point of that measure is trusted only within this fraction of its distance from the node (else it went to
#: the other branch) and of the side's length (else off through a degenerate chart): the chord stands otherwise.
ARC_STRAY = 0.2

_ARC_X = legendre_rule(ARC_NODES)[0]


def restate(y, from_a, from_b, to_a, to_b):
    """State y given in the charts (from_a, from_b) expressed in (to_a, to_b) (a re-charted sphere's
    parameters come from its point; the other surfaces keep their continuous parameters)."""
    out = np.array(y, dtype=float)
    for k, (old, new) in enumerate(((from_a, to_a), (from_b, to_b))):
        if old is new or np.array_equal(old, new):
            continue
        point = np.empty((1, 3))
        ks.evaluate(old, np.ascontiguousarray(out[2 * k:2 * k + 2].reshape(1, 2)), point)
        uv = np.empty((1, 2))
        ks.inverse(new, point, uv)
        out[2 * k:2 * k + 2] = uv[0]
    return out


def state_before(branch, s_back):
    """(segment index, local time, state in that segment's charts) of the integrated branch at arc length
    s_back, from the last solver segment that reaches back to it; None if there is none."""
    for i in range(len(branch.segments) - 1, -1, -1):
        seg = branch.segments[i]
        if seg.jump:
            return None                      # a jump lies in between: do not jump back across it
        if seg.s0 <= s_back:
            t = s_back - seg.s0
            return i, t, np.asarray(seg.sol(t), dtype=float)
    return None


def jump_across(branch, seg, t_event, y_event, settings):
    """Pass a singular point reached at solver time t_event of seg (state y_event, on or beside it).

    The jump starts a jump length before the event (in seg or a segment before it), where the solver's
    path is still on the incoming branch, and goes on along the incoming chord to as far beyond the event;
    there the curve is found by Newton in the plane normal to the chord (the nearest branch: the same one,
    straight through). The jump is lengthened (up to MAX_JUMP) until it lands clear of the singular point
    (an apex's degenerate zone, the narrow wedge between branches crossing at a shallow angle).

    Returns (segment index, its local time, state there in its charts, the same in seg's charts, state
    after, unit direction, length, node, arc): length the curve's arc over the jump (arc, a JumpArc) or, where
    that cannot be measured (arc None), the chord's; node the singular point passed (snapped onto the proven
    one). None if no point of the same branch is found.
    """
    a, b = seg.a, seg.b
    flags = seg.area
    s_event = seg.s0 + t_event
    h = JUMP_LENGTH * settings.scale
    p_event, p_back, t = np.empty(3), np.empty(3), np.empty(3)
    kc.curve_frame(y_event, a, b, p_event, t)
    while h <= MAX_JUMP * settings.scale:
        found = state_before(branch, max(s_event - h, 0.0))
        if found is None:
            return None
        index, t_back, y_own = found
        owner = branch.segments[index]
        y_back = restate(y_own, owner.a, owner.b, a, b)
        kc.curve_frame(y_back, a, b, p_back, t)
        d = p_event - p_back
        span = np.linalg.norm(d)
        if span == 0.0:
            return None
        d /= span
        reach = h + span
        y = y_back + (y_event - y_back) * (reach / span)
        target = p_back + reach * d
        if kc.project_to_curve(y, a, b, target, d, settings.gap_tol, NEWTON_MAX_ITER) < 0:
            h *= 2
            continue
        p_after = np.empty(3)
        kc.curve_frame(y, a, b, p_after, t)
        if np.linalg.norm(p_after - target) > JUMP_STRAIGHTNESS * reach:
            return None
        if (kc.area_degeneracy(y, a, b, *flags) < 2 * APEX_GUARD
                or kc.degeneracy(y, a, b, 0.0, 0.0) < 10 * NODE_CLEARANCE):
            h *= 2                      # still beside the singular point (a cusp, a shallow crossing)
            continue
        node = snapped_node(locate_node(a, b, y_back, y, d, y_event, flags), settings)
        arc = jump_arc(a, b, (p_back, node, p_after), (y_back, y), settings)
        length = arc.length if arc is not None else float(np.linalg.norm(p_after - p_back))
        return index, t_back, y_own, y_back, y, d, length, node, arc
    return None


def snapped_node(node, settings):
    """The node located by a jump (to about the jump's accuracy; at a horn torus's cusp, where the area element
    grows with the square of the distance, 0.01 x the scale off), replaced by the singular point the topology stage
    proved there (Newton on grad g, or an apex; settings.nodes, when known) if one lies within SNAP x scale."""
    if settings.nodes is None or not len(settings.nodes):
        return node
    known = np.asarray(settings.nodes).reshape(-1, 3)
    d = np.linalg.norm(known - node, axis=1)
    return known[np.argmin(d)] if d.min() <= SNAP * settings.scale else node


class JumpArc:
    """The curve's arc length over a jump through (start, node, end): on each side, the speed 1 / (T . chord) of the
    curve point in the plane normal to the side's chord, interpolated at the Gauss-Legendre nodes by a Legendre
    series and integrated exactly (the Gauss-Legendre sum), so that an arc length inside the jump maps to its point
    on the chords (chord_position: Newton on the integral), not in proportion to the chords' length."""

    def __init__(self, lengths, speeds, points=None):
        """lengths (2,): the sides' chords; speeds (2, ARC_NODES): the speed at each side's Gauss-Legendre nodes
        (0.5 x length x (1 + x_i), x_i the nodes on [-1, 1]); points (3, 3): the jump's start, node and end (the
        chords' ends), when known."""
        self.points = points
        self.sides = []                                     # per side: (chord length, speed series, its integral)
        for length, speed in zip(lengths, speeds):
            series = legendre.legfit(_ARC_X, speed, ARC_NODES - 1)
            self.sides.append((float(length), series, legendre.legint(series, lbnd=-1.0)))
        self.arcs = [0.5 * length * float(legendre.legval(1.0, integral)) for length, _, integral in self.sides]
        self.length = float(sum(self.arcs))

    def chord_position(self, t):
        """Distance along the chords (start to node, node to end) (M,) at arc lengths t (M,) from the start."""
        t = np.clip(np.asarray(t, dtype=float), 0.0, self.length)
        out = np.empty_like(t)
        first = t <= self.arcs[0]
        offset = 0.0
        for k, rows in enumerate((first, ~first)):
            length, series, integral = self.sides[k]
            target = t[rows] - (self.arcs[0] if k else 0.0)
            tau = target * (length / self.arcs[k]) if self.arcs[k] > 0 else np.zeros_like(target)
            for _ in range(ARC_NEWTON):
                xi = 2.0 * tau / length - 1.0
                tau = np.clip(tau - (0.5 * length * legendre.legval(xi, integral) - target)
                              / legendre.legval(xi, series), 0.0, length)
            out[rows] = offset + tau
            offset += length
        return out

    def arc_of_point(self, p):
        """Arc length from the start of the curve's point nearest to p (3,), read on the chords: p's projection on
        the first chord while it lies within it, on the second past the node."""
        start, node, end = self.points
        first, second = self.sides[0][0], self.sides[1][0]
        along = float(np.dot(p - start, node - start)) / first
        if along > first:
            along = first + float(np.dot(p - node, end - node)) / second
        return self.arc_position(along)

    def arc_position(self, d):
        """Arc length from the start at distance d along the chords (a float)."""
        first = self.sides[0][0]
        k, tau = (0, d) if d <= first else (1, d - first)
        length, _, integral = self.sides[k]
        tau = min(max(tau, 0.0), length)
        return (self.arcs[0] if k else 0.0) + 0.5 * length * float(legendre.legval(2.0 * tau / length - 1.0, integral))


def jump_arc(a, b, points, states, settings):
    """The JumpArc of a jump through points = (start, node, end), states = (at start, at end): the curve's points
    found by Newton in the planes normal to each side's chord at its Gauss-Legendre nodes (where the point moves
    along the chord with speed 1 / (T . chord)), so that a long jump (past a horn torus's cusp, 0.2 x the scale)
    counts the curve, not the chord. None (the chords stand) where a side's point cannot be trusted (ARC_STRAY).

    References
    ----------
    Abramowitz and Stegun, Handbook of Mathematical Functions, 25.4.29 (Gauss-Legendre).
    """
    lengths, speeds = [], []
    for side in (0, 1):
        start, end = points[side], points[side + 1]
        length = float(np.linalg.norm(end - start))
        if length == 0.0:
            return None
        direction = (end - start) / length
        taus = 0.5 * length * (1.0 + _ARC_X)
        targets = start + taus[:, None] * direction
        ys = set_states(np.repeat(np.asarray(states[side], dtype=float)[None], ARC_NODES, axis=0), targets, a, b)
        found, tangents, status = np.empty((ARC_NODES, 3)), np.empty((ARC_NODES, 3)), np.empty(ARC_NODES, np.int64)
        kc.project_through(ys, a, b, direction, targets, settings.gap_tol, NEWTON_MAX_ITER, found, tangents, status)
        along = tangents @ direction
        node_distance = length - taus if side == 0 else taus
        if (np.any(status < 0) or np.any(along <= 0.0)
                or np.any(np.linalg.norm(found - targets, axis=1) > ARC_STRAY * np.minimum(node_distance, length))):
            return None
        lengths.append(length)
        speeds.append(1.0 / along)
    return JumpArc(lengths, speeds, np.array(points, dtype=float))


def locate_node(a, b, y_from, y_to, d, y_event, flags):
    """The singular point passed by a jump from y_from to y_to (direction d), to about the chord's sagitta:
    the sine of the normals' angle (at a node) or the relative area element (at an apex) grows like
    |s - s_node| on either side, so its values at a quarter and three quarters of the jump (corrected onto
    the curve in planes normal to d) place the point between them (flags: the surfaces' area_flag). Falls back
    to the event point."""
    pts, sines = [], []
    for w in (0.25, 0.75):
        y = y_from + w * (y_to - y_from)
        p, t = np.empty(3), np.empty(3)
        kc.curve_frame(y, a, b, p, t)
        kc.project_to_curve(y, a, b, p.copy(), d, 0.0, NEWTON_MAX_ITER)
        kc.curve_frame(y, a, b, p, t)
        pts.append(p)
        sines.append(kc.degeneracy(y, a, b, *flags))
    total = sines[0] + sines[1]
    if total == 0.0 or float(np.dot(pts[1] - pts[0], d)) <= 0.0:
        p, t = np.empty(3), np.empty(3)
        kc.curve_frame(y_event, a, b, p, t)
        return p
    w = sines[0] / total
    return pts[0] + w * (pts[1] - pts[0])


def take_jump(branch, seg, y_event, jump):
    """Record a jump across a singular point: cut the branch where the jump starts, add the jump segment
    (in seg's charts), and return the new (sign, state, point, tangent) to go on from."""
    index, t_back, y_own, y_back, y_after, d, length, node, arc = jump
    owner = branch.segments[index]
    keep = owner.t <= t_back
    # (states as every segment holds them: (4, m), each state's column contiguous, the transpose of the record's)
    owner.t, owner.y = np.append(owner.t[keep], t_back), np.concatenate([owner.y[:, keep].T, y_own[None]]).T
    owner.s1 = owner.s0 + t_back
    del branch.segments[index + 1:]
    point, tangent = np.empty(3), np.empty(3)
    branch.nodes.append((owner.s1, node))
    branch.segments.append(Segment(s0=owner.s1, s1=owner.s1 + length, sign=1.0,
                                   sol=LinearStates(y_back, y_after, length, arc), a=seg.a, b=seg.b,
                                   t=np.array([0.0, length]), y=np.array([y_back, y_after]).T, normal=d,
                                   area=seg.area))
    kc.curve_frame(y_after, seg.a, seg.b, point, tangent)
    sign = 1.0 if float(np.dot(tangent, d)) > 0 else -1.0
    return sign, y_after.copy(), point, tangent


#: An edge crossed this close to the node inside a jump (a fraction of the jump's length) is taken to pass through it
#: (jump_past_edge).
EDGE_AT_NODE = 1e-3


def jump_past_edge(jump, a, b, bounds, gap_tol, near=EDGE_AT_NODE):
    """The jump (jump_across's tuple) ended where the curve leaves a trimmed surface inside it, when it lands past
    an edge (bounds: finite_bounds rows, in the charts a, b; past by more than the edge's slack): the landing state
    is the curve's point on that edge (Newton with the edge parameter held, from the states' linear interpolation at
    the edge), or, where that Newton fails (the edge through the node itself, where the surfaces touch), that
    interpolated state; the jump's length is the arc to that point (its JumpArc's, through the node), or, where that
    point lies within `near` x the jump's length of the node (an edge through or beside the node, where Newton
    cannot tell the branches apart), the arc to the node: the end is then off the edge by at most the edge's
    distance from the node. Returns (the shortened jump, (surface index, bound index)), or None when the jump lands
    inside every trim."""
    index, t_back, y_own, y_back, y_after, d, length, node, arc = jump
    for k, j, idx, bound, lower, slack, _ in bounds:
        past = (bound - y_after[idx]) if lower else (y_after[idx] - bound)
        if not past > slack:
            continue
        run = y_after[idx] - y_back[idx]
        if run == 0.0:
            continue
        w = min(max((bound - y_back[idx]) / run, 0.0), 1.0)
        guess = y_back + w * (y_after - y_back)
        guess[idx] = bound
        snapped = newton_fixed(a, b, guess, idx, gap_tol)
        y_edge = guess if snapped is None else snapped
        p_edge, t = np.empty(3), np.empty(3)
        kc.curve_frame(y_edge, a, b, p_edge, t)
        if arc is not None and float(np.linalg.norm(p_edge - node)) <= near * length:
            reach = arc.arcs[0]                       # the edge through the node: the arc to the node
        elif arc is not None and arc.points is not None:
            reach = arc.arc_of_point(p_edge)
        else:
            reach = w * length
        reach = min(max(reach, 0.0), length)
        return (index, t_back, y_own, y_back, y_edge, d, reach, node, arc), (k, j)
    return None


def closes_within_jump(jump, start, direction, min_cosine):
    """Arc length at which the curve returns to its start inside a jump segment, or None."""
    p_from, t = np.empty(3), np.empty(3)
    kc.curve_frame(jump.y[:, 0], jump.a, jump.b, p_from, t)
    d = jump.normal
    along = float(np.dot(start - p_from, d))
    length = jump.s1 - jump.s0
    lateral = np.linalg.norm(start - p_from - along * d)
    travelled = jump.s0 + along > 2.0 * length         # not the start's own neighbourhood
    if (0.0 < along <= length and travelled and lateral <= JUMP_STRAIGHTNESS * length
            and float(np.dot(d, direction)) >= min_cosine):
        return jump.s0 + (along if jump.sol.arc is None else jump.sol.arc.arc_of_point(start))
    return None
