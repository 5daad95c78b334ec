"""The topology stage of sk.intersect: a start on every component of a ∩ b, found by a search that cannot miss one.

One surface, P, keeps its parameters; the other, Q, is read through its polynomial implicit function F_Q, so
that the intersection is the level g = F_Q(P(u, v)) = 0 on P's parameter domain (a rectangle, bounded by Q's
extent where P is not). Every component of that level

- meets an edge of a trimmed domain (P's edges; Q's edges are curves on P, searched on Q as F_P = 0),
- or crosses a seam of a periodic parameter (the loops that wind round a cylinder, cone or torus),
- or passes through a point where P's parametrisation collapses (a sphere's pole, a cone's or spindle torus's
  apex: searched on small rings round it),
- or is a closed loop inside the open rectangle, and then holds a point where its tangent is normal to a fixed
  direction d (where the linear function d . (u, v) is largest along the loop): a root of g = 0,
  d_v g_u - d_u g_v = 0.

The roots on edges and seams and the roots of that 2 x 2 system come from interval subdivision with outward
rounding (spatialkin.kernels.search.topology): a box is dropped only when an enclosure proves that it holds no root,
and kept as one isolated root when the interval Newton or Krawczyk operator proves it; so a loop of any size
down to the round-off of the coordinates is found. Boxes that shrink to round-off without either proof are
singular points of the level (contacts, nodes, tangencies), classified by the Hessian of g.

Special configurations are recognised first (spatialkin.geometry.placement): coincident patches raise
CoincidentSurfacesError; surfaces of revolution about one axis meet in parallels (found on one meridian; a
double root there is a circle of tangency); a cylinder and a surface invariant along its axis meet in lines
along it (found on one cross-section; a double root is a line of tangency).

References
----------
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002
(starts from critical points; small loops that sampling on a grid misses).
H. Hong, An efficient method for analyzing the topology of plane real algebraic curves, Math. Comput. Simul. 42
(1996): the extremes of a coordinate along a curve as its critical points.
"""
import math
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
from scipy.optimize import brentq

from ...kernels.geometry import interval as ki
from ...kernels.geometry import surfaces as ks
from ...kernels.search import topology as kt
from .meridians import BAND, BESIDE, REVOLVED, meridian_circle, meridian_nodes, meridian_segment, tangent_meridians
from ...geometry.asymptotic import unbounded_message
from ...geometry.surfaces.base import distances_at
from ...geometry.placement import bounding_ball, check_not_coincident, common_axis, ruled_along
from ..march.ivp import APEX_ON_CURVE
from ..march.trace import EPS, ROUNDOFF_ULPS
from ...geometry.traits import LENGTH, power_of_two

#: The fixed direction d (an angle in the plane of scaled parameters) whose extremes seed the closed loops;
#: any direction works, a generic one keeps straight pieces of the level from lying along d's normal.
DIRECTION = 0.3091
#: Smallest box width, relative to the coordinates' magnitude in parameter units (a few hundred ulps).
MIN_WIDTH_ULPS = 256.0
#: Points of a searched line probed first: where g is zero within round-off at all of them, the line itself
#: lies on the other surface (it is not searched, it is a piece of the curve).
LINE_PROBES = 9
#: Widths up to this fraction of the searched range stop bisecting where g is within round-off of zero at the
#: midpoint (near a multiple root, round-off hides the rest: about sqrt(eps) of the range).
COARSE = 1e-7
#: Box budget of one search: past it the search stops and the result is not a proof (TopologyError).
MAX_BOXES = 400_000
#: Records kept per search.
MAX_RECORDS = 4096
#: Parameter offsets of the rings searched round a pole or an apex that lies on the other surface, in units of v
#: (step_units: radians for a sphere's pole, about the scene scale for a cone's length v): far enough
#: for a good start (the tracer then passes the apex from a clear incoming chord), and near, for the branches of
#: a loop through the apex smaller than the first ring.
RINGS = (2e-2, 1e-5)
#: Starts closer than this to an apex or pole (relative to the scale) are left to the rings round it.
APEX_CLEARANCE = 1e-7
#: Margin on the bounding ball that limits an unbounded P's domain.
BALL_MARGIN = 1.01
#: Unresolved boxes closer than this (relative to the scale) are one singular point.
CLUSTER = 1e-6
#: A critical point is on the level when g's enclosure there, widened this many times its width, holds zero.
ON_LEVEL = 1.0
#: An extremum of g within its rigorous enclosure of zero is a tiny loop, not a contact, when its floating value
#: (of the loop's sign) exceeds this fraction of the enclosure's width (a 1e-13-deep loop under a torus's quartic:
#: 0.46 of it; true contacts in the stress test: below 0.003) and g changes sign beside it.
LOOP_FLOOR = 0.1
#: Half-width (relative to the searched range) of the interval round an unresolved cluster on a line whose end
#: values tell a simple root (sign change) from a multiple one.
CLUSTER_SIDE = 1e-6
#: Where round-off hides g's sign at an end of that interval, its half-width grows this many times, at most
#: CLUSTER_WIDENINGS times (to CLUSTER_SIDE x 4^4 = 2.6e-4 of the range).
CLUSTER_GROWTH, CLUSTER_WIDENINGS = 4.0, 4
#: Eigenvalues of the Hessian of g below this fraction of the largest are zero (a degenerate singular point).
EIGEN_RATIO = 1e-10
#: Seeds on the arms of a node sit this far (relative to the scale) from it, or closer where the arm bends away
#: from its tangent sooner: halved up to ARM_HALVINGS times until Newton on g settles within ARM_FIT of the offset
#: (arm_point); at most ARM_NEWTON steps, settled at a step below ARM_SETTLED of that (settles).
NODE_OFFSET = 2e-2
ARM_HALVINGS, ARM_FIT = 24, 0.25
ARM_NEWTON, ARM_SETTLED = 8, 1e-6
#: Where the seams of periodic parameters are cut (offsets from -pi, tried in turn): any position proves the
#: same, but a component lying along the seam itself (a meridian plane through a torus axis) must be avoided.
SEAM_OFFSETS = (0.0, 0.7236, 2.2019, 4.0537, 5.3211)
#: Grid (per parameter) on which g's typical size is sampled, and samples of a seam candidate.
SEAM_GRID, SEAM_SAMPLES = 9, 17
#: A seam candidate is rejected when g is below this fraction of its typical size at most of its samples.
SEAM_FLAT = 1e-9
#: No points (an empty list of apexes).
NO_POINTS = np.empty((0, 3))
#: Newton iterations locating a critical point of g from an unresolved box.
CRITICAL_ITER = 40


class TopologyError(RuntimeError):
    """The topology stage could not prove where every component is.

    ``sk.intersect`` raises it rather than return an answer that may miss a component. It happens on a tangency
    along a curve in a placement the stage does not recognise, or surfaces that nearly touch along a stretch: the
    interval search runs out of its box budget, fills its record of roots, or finds starts it can neither place on
    a curve nor trace; or a component is followed to the default max_length without closing (the march crossed
    between branches a hair apart where the surfaces nearly touch).

    Parameters
    ----------
    message : str
        What stopped and where.
    where : str, optional
        The search that stopped: 'interior', 'edge of P', 'meridian', ..., 'starts', or 'march' (a component
        not closed).

    Attributes
    ----------
    where : str or None

    Examples
    --------
    >>> import spatialkin as sk
    >>> def components_or_none(a, b):
    ...     try:
    ...         return sk.intersect(a, b)
    ...     except sk.TopologyError as error:
    ...         print("not resolved by the", error.where, "search")
    ...         return None
    >>> len(components_or_none(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0)))))
    1
    """

    def __init__(self, message, where=None):
        super().__init__(message)
        self.where = where


@dataclass
class Topology:
    """What the topology stage found, in the surfaces' argument order (a, b).

    seeds : list of ndarray (3,)        points on the curve (to round-off), at least one per curve component
    edge_starts : list of (point, index, fixed, value)   points on an edge: surface index (0 a, 1 b), its
                                        parameter `fixed` (0 u, 1 v) held at value
    contacts : list of ndarray (3,)     isolated points where the surfaces touch
    nodes : list of ndarray (3,)        points where branches cross
    apexes : list of ndarray (3,)       apexes and poles of P that lie on Q
    tangent_circles : list of (centre, axis, radius)     circles along which the surfaces touch
    circles : list of (centre, axis, radius)             circles crossed transversally (coaxial placements)
    tangent_segments : list of (p0, p1)                  segments along which the surfaces touch
    root_boxes : list of RootBoxes      every search's boxes: each verified box holds exactly one root of its
                                        search, and every root lies in one of them (the certificate's input)
    whole_lines : list of (reader, fixed, value, t0, t1)   parameter lines found lying on the other surface
    skipped : list of (what, point)     parts of P's domain the interior search left out (their components are
                                        seeded by the rings or bands' edges, but nothing inside them is proven)
    chart : Surface                     P in the chart its searches read
    """
    P: object
    Q: object
    mode: str
    seeds: list = field(default_factory=list)
    edge_starts: list = field(default_factory=list)
    contacts: list = field(default_factory=list)
    nodes: list = field(default_factory=list)
    tangent_circles: list = field(default_factory=list)
    circles: list = field(default_factory=list)
    tangent_segments: list = field(default_factory=list)
    apexes: list = field(default_factory=list)
    searches: list = field(default_factory=list)
    root_boxes: list = field(default_factory=list)
    whole_lines: list = field(default_factory=list)
    skipped: list = field(default_factory=list)
    chart: object = None
    boxes: int = 0
    verified: int = 0
    unresolved: int = 0
    seconds: float = 0.0

    def crossings(self):
        """(K, 3) the singular points a branch may pass across: the nodes, and the apexes and poles on the curve (what
        the march takes for proven nodes, Settings.nodes)."""
        return np.array(self.nodes + self.apexes, dtype=float).reshape(-1, 3)


@dataclass
class RootBoxes:
    """The boxes one search kept: reader (its Reader), kind ('line': g on a parameter line, args (fixed, value,
    t0, t1: the other parameter's range searched); 'extremal': g = 0 and the level's tangent normal to (du, dv),
    args (du, dv)), verified (K, 4) boxes (u lo, u hi, v lo, v hi of reader.s's parameters) each holding exactly
    one root, the refined roots (K, 2) inside them, and the unresolved boxes (L, 4)."""
    reader: object
    kind: str
    args: tuple
    verified: np.ndarray
    roots: np.ndarray
    unresolved: np.ndarray


# --- roles and domains -------------------------------------------------------------------------------------
def choose_roles(a, b, axis, ruled):
    """(P, Q, mode): P parametrised, Q implicit; the same for (a, b) and (b, a). Coaxial: P has parallels."""
    if axis is not None:
        mode = "coaxial"
        cands = [s for s in (a, b) if s.traits.has_parallels]
    elif ruled is not None:
        return ruled, (b if ruled is a else a), "ruled"
    else:
        mode = "general"
        cands = [a, b]
    ranks = [s.traits.rank for s in cands]
    if len(cands) == 2 and ranks[0] != ranks[1]:
        best = cands[0] if ranks[0] < ranks[1] else cands[1]     # (the key's first entry decides)
    else:
        best = min(cands, key=lambda s: (s.traits.rank, -s.size, tuple(s.data)))
    return best, (b if best is a else a), mode


def domain(p, q_ball):
    """(box (4,) = u_lo, u_hi, v_lo, v_hi of P's domain, u periodic, v periodic): P's natural domain, a length
    parameter where it is unbounded limited by Q's bounding ball."""
    kind = p.traits
    ranges = [list(r) for r in kind.natural_domain(p)]
    if q_ball is not None and any(axis is not None for axis in kind.parameter_axes):
        centre = p.frame.local_of(q_ball[0])
        reach = BALL_MARGIN * q_ball[1]
        for j, axis in enumerate(kind.parameter_axes):
            if axis is not None:
                ranges[j] = [max(ranges[j][0], centre[axis] - reach), min(ranges[j][1], centre[axis] + reach)]
    return np.array([*ranges[0], *ranges[1]]), kind.periodic[0], kind.periodic[1]


def limited_range(surface, j, ball):
    """The trims of parameter j of a surface, an unbounded length limited by the other surface's ball."""
    kind = surface.traits
    lo, hi = kind.natural_domain(surface)[j]
    axis = kind.parameter_axes[j]
    if axis is not None and (not math.isfinite(lo) or not math.isfinite(hi)) and ball is not None:
        centre = surface.frame.local_of(ball[0])[axis]
        lo, hi = max(lo, centre - BALL_MARGIN * ball[1]), min(hi, centre + BALL_MARGIN * ball[1])
    return lo, hi


# --- the searches ------------------------------------------------------------------------------------------
class Reader:
    """g = F_T o S for one ordered pair (S parametrised), with the rigorous placement of S in T's frame."""

    def __init__(self, s, t):
        self.s, self.t = s, t
        self.m = np.empty((3, 3))
        self.c = np.empty(3)
        magnitude = ki.relative_placement(s.data, t.data, self.m, self.c)
        self.pad = ki.PLACEMENT_ULPS * ki.EPS
        self.cpad = ki.PLACEMENT_ULPS * ki.EPS * magnitude
        self.magnitude = magnitude

    def min_width(self, lo, hi):
        """Smallest box width on [lo, hi]: MIN_WIDTH_ULPS ulps of its magnitude."""
        return MIN_WIDTH_ULPS * ki.EPS * max(abs(lo), abs(hi), 1e-300)

    def line(self, fixed, value, t0, t1, topo, name, probe=False, budget=None):
        """Roots of g on the line (parameter `fixed` of S = value, the other in [t0, t1]): (verified (K,),
        unresolved (L,)) of the other parameter; with probe, None where the line lies on T (line_on_level), not
        searched. budget: the most boxes (MAX_BOXES when None; past it TopologyError)."""
        out = np.empty((MAX_RECORDS, 2))
        kinds = np.empty(MAX_RECORDS, dtype=np.int64)
        found = np.empty((MAX_RECORDS, 2))
        width = max(self.min_width(t0, t1), 1e-15 * (t1 - t0))
        n, status, boxes, verified = kt.line_search(self.s.data, self.t.data, self.m, self.c, self.pad, self.cpad,
                                                    int(fixed), float(value), float(t0), float(t1), width,
                                                    COARSE * (t1 - t0), MAX_BOXES if budget is None else budget,
                                                    out, kinds, LINE_PROBES if probe else 0, ON_LEVEL, found)
        if status == kt.WHOLE_LINE:
            topo.whole_lines.append((self, int(fixed), float(value), float(t0), float(t1)))
            return None
        self._account(topo, name, status, boxes, verified, n - verified, budget)
        uv = np.empty((n, 4))
        uv[:, 2 * fixed:2 * fixed + 2] = value
        uv[:, 2 - 2 * fixed:4 - 2 * fixed] = found[:n]
        roots = line_params(fixed, value, out[:verified, 0])
        args = (int(fixed), float(value), float(t0), float(t1))
        topo.root_boxes.append(RootBoxes(self, "line", args, uv[:verified], roots, uv[verified:n]))
        return out[:verified, 0].copy(), out[verified:n, 0].copy()

    def extremal(self, box, unit, topo):
        """Roots of g = 0, d_v g_u - d_u g_v = 0 in the box: (verified (K, 2), unresolved (L, 2))."""
        du, dv = math.cos(DIRECTION) / unit[0], math.sin(DIRECTION) / unit[1]
        out = np.empty((MAX_RECORDS, 4))
        kinds = np.empty(MAX_RECORDS, dtype=np.int64)
        found = np.empty((MAX_RECORDS, 4))
        width = np.array([max(self.min_width(box[0], box[1]), 1e-15 * (box[1] - box[0])),
                          max(self.min_width(box[2], box[3]), 1e-15 * (box[3] - box[2]))])
        n, status, boxes, verified = kt.extremal_search(self.s.data, self.t.data, self.m, self.c, self.pad,
                                                        self.cpad, du, dv, np.ascontiguousarray(box, dtype=float),
                                                        width, COARSE * max((box[1] - box[0]) / width[0],
                                                                            (box[3] - box[2]) / width[1]),
                                                        MAX_BOXES, out, kinds, found)
        self._account(topo, "interior", status, boxes, verified, n - verified)
        topo.root_boxes.append(RootBoxes(self, "extremal", (du, dv), found[:verified].copy(), out[:verified, :2].copy(),
                                         found[verified:n].copy()))
        return out[:verified, :2].copy(), out[verified:n, :2].copy()

    def enclosure(self, uv):
        """(lo, hi): a rigorous enclosure of g at the parameter point uv of S."""
        return kt.level_enclosure(self.s.data, self.t.data, self.m, self.c, self.pad, self.cpad,
                                  float(uv[0]), float(uv[1]))

    def line_points(self, fixed, value, along):
        """Points (N, 3) of S on the line (parameter `fixed` = value) at the other parameter's values along."""
        return points_at(self.s, line_params(fixed, value, along))

    def on_level(self, uv):
        """True when g at uv is zero within its round-off (a rigorous enclosure, widened ON_LEVEL times)."""
        return kt.on_level(self.s.data, self.t.data, self.m, self.c, self.pad, self.cpad, float(uv[0]),
                           float(uv[1]), ON_LEVEL)

    def values(self, uv):
        """(g, g_u, g_v, g_uu, g_uv, g_vv) (N, 6) at parameter points uv (N, 2) of S."""
        uv = np.ascontiguousarray(np.asarray(uv, dtype=float).reshape(-1, 2))
        out = np.empty((len(uv), 6))
        kt.point_values(self.s.data, self.t.data, self.m, self.c, uv, out)
        return out

    @staticmethod
    def _account(topo, name, status, boxes, verified, unresolved, budget=None):
        topo.boxes += int(boxes)
        topo.verified += verified
        topo.unresolved += unresolved
        topo.searches.append((name, int(boxes)))
        if status != kt.DONE:
            budget = MAX_BOXES if budget is None else budget
            what = {kt.OVERFLOW: f"ran out of its budget of {budget} boxes",
                    kt.RECORDS_FULL: f"found more than {MAX_RECORDS} roots and unresolved boxes",
                    kt.STACK_FULL: f"went deeper than its stack of {kt.STACK} boxes"}[status]
            raise TopologyError(f"the {name} search {what}: the intersection could not be resolved there (a "
                                "tangency along a curve, or an elongated contact, in a placement not recognised as "
                                "symmetric?)", where=name)


def line_params(fixed, value, along):
    """Parameter points (N, 2) of the line (parameter `fixed` = value) at the other parameter's values along."""
    uv = np.empty((len(along), 2))
    uv[:, 1 - fixed] = along
    uv[:, fixed] = value
    return uv


def points_at(surface, uv):
    """Points (N, 3) of a surface at parameter points uv (N, 2): Surface.point without its broadcasting."""
    uv = np.ascontiguousarray(uv, dtype=float).reshape(-1, 2)
    out = np.empty((len(uv), 3))
    ks.evaluate(surface.data, uv, out)
    return out


def topology(a, b, scale, tolerance):
    """Start points on every component of a ∩ b (see the module docstring). Returns a Topology.

    Raises
    ------
    CoincidentSurfacesError
        The patches overlap in a piece of surface.
    ValueError
        Neither surface is bounded (nothing limits the search).
    TopologyError
        A search ran out of its box budget.
    """
    try:
        return search(a, b, scale, tolerance)
    except TopologyError:
        for p, q in ((a, b), (b, a)):                    # a meridian of a surface of revolution along which they touch?
            if p.traits.name in REVOLVED:
                box, _, _ = domain(p, bounding_ball(q))
                if not (math.isfinite(box[2]) and math.isfinite(box[3])):
                    continue
                meridians = tangent_meridians(p, Reader(p, q), box[2:])
                if meridians:
                    return search(a, b, scale, tolerance, (p, q, meridians[0]))
        raise


def search(a, b, scale, tolerance, tangent=None, general=False, chart_of=None):
    """topology() in one configuration; tangent: (torus P, Q, u0) for a pair that touches along the meridian
    u = u0 of the torus (spatialkin.tracing.search.meridians): P is searched less a band round it; general: the
    general search even where the pair has a common axis or direction (the certificate's completeness, which
    cannot rest on a symmetry decided within a tolerance); chart_of: a or b, the surface P of that general search
    (the certificate's, where the other's apex lies on the curve and its chart collapses there)."""
    t0 = time.perf_counter()
    check_not_coincident(a, b, scale)
    p_user, q, mode, p, balls = search_roles(a, b, scale, general, chart_of)
    if tangent is not None:
        p_user, q, mode = tangent[0], tangent[1], "general"
        p = p_user
    topo = Topology(P=p_user, Q=q, mode=mode, chart=p)
    box, u_periodic, v_periodic = domain(p, balls[id(q)])
    if not box[0] < box[1] or not box[2] < box[3]:
        topo.seconds = time.perf_counter() - t0
        return topo                                  # Q's ball misses P's trimmed domain
    pq, qp = Reader(p, q), Reader(q, p)
    collapse = p.traits.collapse_lines(p)
    if mode == "general":
        place_seams(pq, box, u_periodic, v_periodic, collapse)
    if tangent is not None:                          # the band round the meridian of tangency: its edges are the seam
        u0 = tangent[2]
        box[0], box[1] = u0 + BAND, u0 + 2 * math.pi - BAND
        topo.skipped.append(("a band round the meridian along which the surfaces touch", points_at(p, (u0, 0.0))[0]))
        if p.traits.name == "torus":
            topo.tangent_circles.append(meridian_circle(p, u0))
        else:
            segment = meridian_segment(p, q, u0, box[2:])
            topo.tangent_segments += [] if segment is None else [segment]
        crossings = list(meridian_nodes(p, pq, u0, box[2:]))
        topo.nodes += crossings
    index = {id(a): 0, id(b): 1}
    p_index, q_index = index[id(p_user)], index[id(q)]
    apexes = [v + 2 * math.pi * math.ceil((box[2] - v) / (2 * math.pi) - 1e-12) for v in collapse]
    apexes = sorted({v for v in apexes if box[2] <= v <= box[3]})
    loose = []                                      # (surface reader, uv) of unresolved boxes
    apex_points = list(points_at(p, [(0.0, v) for v in apexes])) if mode == "general" else []

    keep = Keeper(a, b, apex_points, scale, tolerance)

    def add_line_roots(reader, fixed, value, t_lo, t_hi, name, surf_index, edge):
        found = reader.line(fixed, value, t_lo, t_hi, topo, name, probe=True)
        if found is None:
            # the whole line lies on the other surface (a patch's edge in the other plane, a rim on it): it
            # is a piece of the intersection itself; starts on it, inside both trims, trace it
            along = np.linspace(t_lo, t_hi, LINE_PROBES)[1:-1]
            topo.seeds += keep.select_on(reader.s, line_params(fixed, value, along))
            return np.empty(0), np.empty(0)
        roots, unresolved = found
        if len(roots):
            pts, kept = keep.on(reader.s, line_params(fixed, value, roots))
            for pt in pts[kept]:
                if edge:
                    topo.edge_starts.append((pt, surf_index, fixed, value))
                else:
                    topo.seeds.append(pt)
        for t in unresolved:
            loose.append((reader, np.array((t, value) if fixed == 1 else (value, t))))
        return roots, unresolved

    if mode == "coaxial":
        coaxial_components(p, q, pq, qp, box, topo, keep, add_line_roots, scale, q_index)
    elif mode == "ruled":
        ruled_components(p, q, pq, box, topo, scale)
    else:
        # edges of P's trim (not the limits set by Q's ball: no root lies there)
        for j, trim in enumerate(p.bounds):
            for bound in trim:
                if math.isfinite(bound):
                    add_line_roots(pq, j, bound, box[2 - 2 * j], box[3 - 2 * j], "edge of P", p_index, True)
        # seams of periodic parameters (the edges of the band round a meridian of tangency)
        if tangent is not None:
            for edge in box[:2]:
                add_line_roots(pq, 0, edge, box[2], box[3], "tangent band", None, False)
        elif u_periodic:
            add_line_roots(pq, 0, box[0], box[2], box[3], "u seam", None, False)
        if v_periodic:
            add_line_roots(pq, 1, box[2], box[0], box[1], "v seam", None, False)
        # rings round poles and apexes on Q
        bands = []
        v_unit = step_units(p, scale)[1]         # RINGS are in units of v (a cone's v is a length)
        for v, apex in zip(apexes, apex_points):
            if distances_at(q, apex)[0] > APEX_ON_CURVE * tolerance:
                continue
            bands.append((v - RINGS[-1] * v_unit, v + RINGS[-1] * v_unit))
            topo.skipped.append(("a thin band round an apex or pole", apex))
            on_q = pq.on_level((0.0, v))
            if on_q:                                  # a point of the curve (else the branches pass beside it)
                topo.apexes.append(apex)
            found = 0
            for ring in [v + sign * r * v_unit for r in RINGS for sign in (-1.0, 1.0)]:
                if box[2] <= ring <= box[3]:
                    roots, unresolved = add_line_roots(pq, 1, ring, box[0], box[1], "apex ring", None, False)
                    found += len(roots) + len(unresolved)
            if not found and on_q and keep.inside_both(apex):
                topo.contacts.append(apex)           # on Q to round-off, with no branch round it
        # Q's own apexes on P: singular points of the curve (known, so that the tracer's jumps pass them exactly;
        # a chart's poles are no points of the curve's kind)
        for v in q.traits.apexes(q):
            apex = points_at(q, (0.0, v))[0]
            if distances_at(p, apex)[0] <= APEX_ON_CURVE * tolerance and qp.on_level((0.0, v)):
                topo.apexes.append(apex)
        # Q's trim edges, as curves on Q where F_P = 0
        q_edges(q, qp, balls[id(p_user)], add_line_roots, q_index)
        # closed loops inside P's open domain
        # (less the thin bands round apexes on Q: a branch through the apex crosses the ring at the band's edge;
        # inside the band g and the extremal condition may vanish all along the apex line)
        for lo, hi in split_range(box[2], box[3], bands):
            roots, unresolved = pq.extremal(np.array([box[0], box[1], lo, hi]), p.traits.parameter_units(scale),
                                            topo)
            topo.seeds += keep.select_on(p, roots)
            loose += [(pq, uv) for uv in unresolved]
    if tangent is not None:                          # unresolved boxes beside the band: g vanishes to second order
        loose = [(reader, uv) for reader, uv in loose           # there (no singular point of another branch)
                 if reader is not pq or abs(math.remainder(uv[0] - tangent[2], 2 * math.pi)) > BESIDE * BAND]
    classify(loose, topo, scale, keep)
    if tangent is not None:                          # the crossings on the meridian are known exactly: boxes that
        exact = topo.nodes[:len(crossings)]          # shrank round them are those nodes again
        topo.nodes = exact + [x for x in topo.nodes[len(crossings):]
                              if all(np.linalg.norm(x - y) > CLUSTER * scale for y in exact)]
    topo.seconds = time.perf_counter() - t0
    return topo



def search_roles(a, b, scale, general=False, chart_of=None):
    """(P as given, Q, mode, P in the chart searched, {id: bounding ball}) of a pair that is not coincident: the roles
    and chart of topology()'s searches (ValueError for an unbounded pair); general: no symmetric configuration;
    chart_of: P of the general search (a or b), else choose_roles'."""
    balls = {id(a): bounding_ball(a), id(b): bounding_ball(b)}
    if balls[id(a)] is None and balls[id(b)] is None:
        raise ValueError(unbounded_message(a, b))
    axis = None if general else common_axis(a, b, scale)
    ruled = ruled_along(a, b, scale) if axis is None and not general else None
    if general and chart_of is not None:
        p_user, q, mode = chart_of, (b if chart_of is a else a), "general"
    else:
        p_user, q, mode = choose_roles(a, b, axis, ruled)
    if mode == "ruled" and balls[id(p_user)] is None and balls[id(q)] is None:
        raise ValueError("intersect needs a bounded pair")
    p = p_user.traits.aligned(p_user, axis) if mode == "coaxial" else p_user
    if mode == "general":
        p = p.traits.general_chart(p, q)
    return p_user, q, mode, p, balls


def place_seams(reader, box, u_periodic, v_periodic, apexes):
    """Cut the periodic parameters' seams (box is changed in place) where g does not vanish all along them: not
    where g is below SEAM_FLAT of its typical size (its largest on a SEAM_GRID x SEAM_GRID grid over the box) at
    half or more of SEAM_SAMPLES points along the seam."""
    if not (u_periodic or v_periodic):
        return
    args = (reader.s.data, reader.t.data, reader.m, reader.c)
    floor = SEAM_FLAT * kt.level_max(*args, box, SEAM_GRID)
    for k, periodic in ((0, u_periodic), (1, v_periodic)):
        if not periodic:
            continue
        lo, hi = box[2 - 2 * k], box[3 - 2 * k]
        for offset in SEAM_OFFSETS:
            value = -math.pi + offset
            if k == 1 and any(abs(math.remainder(value - v, 2 * math.pi)) < 1e-9 for v in apexes):
                continue
            if kt.flat_fraction(*args, k, value, lo, hi, SEAM_SAMPLES, floor) < 0.5:
                break
        box[2 * k], box[2 * k + 1] = value, value + 2 * math.pi


def q_edges(q, qp, p_ball, add_line_roots, q_index):
    """Roots of F_P on the trim edges of Q (a trimmed plane's sides, a cylinder's or cone's rims), each edge over
    the other parameter's range (limited by P's ball where it is an unbounded length)."""
    for j, trim in enumerate(q.bounds):
        if not (math.isfinite(trim[0]) or math.isfinite(trim[1])):
            continue
        lo, hi = limited_range(q, 1 - j, p_ball)
        for bound in trim:
            if math.isfinite(bound) and lo < hi:
                add_line_roots(qp, j, bound, lo, hi, "edge of Q", q_index, True)


def coaxial_components(p, q, pq, qp, box, topo, keep, add_line_roots, scale, q_index):
    """Surfaces of revolution about one axis (P's z) meet in parallels v = const of P: the roots of g on one
    meridian. A simple root is a circle crossed transversally (traced); a multiple root where g keeps its sign
    is a circle of tangency; a root where the parallel collapses (a pole, an apex) is a contact point."""
    roots, unresolved = pq.line(0, -math.pi, box[2], box[3], topo, "meridian")
    apexes = p.traits.collapse_lines(p)
    v_unit = step_units(p, scale)[1]                 # (a cone's or cylinder's v is a length)
    q_rim = q.traits.trim_breaks_revolution(q)
    found = [(v, True) for v in roots]
    # v runs on past a trim (a cylinder's or cone's rim), or round a periodic v's seam (a torus's inner equator)
    beyond = p.traits.units[1] == LENGTH or p.traits.periodic[1]
    clusters = merge_values(unresolved, 4 * COARSE * (box[3] - box[2]))
    for v in clusters:
        # a cluster across which g changes sign is a simple root blurred by round-off (a tiny parallel near a
        # pole, or a parallel the surfaces cross at a small angle); one across which it keeps its sign is a multiple
        # root (a tangency); at a rim or a seam, g is read past it
        bracket = cluster_bracket(pq, v, box, beyond, [w for w in (*roots, *clusters) if w != v])
        if bracket is not None:
            lo, hi = bracket
            found.append((brentq(lambda x: pq.values([-math.pi, x])[0, 0], lo, hi, xtol=1e-15 * v_unit), True))
        else:
            found.append((double_root(pq, 0, -math.pi, v, v_unit), False))
    for v, simple in found:
        pt = p.point(0.0, v)
        radius = math.hypot(*p.frame.local_of(pt)[:2])
        if radius <= 1e-9 * scale or any(abs(v - w) < 1e-12 * v_unit for w in apexes):
            # (a point on the axis is met once per side of a periodic meridian: a horn torus's centre at v = +-pi)
            if keep(pt) and not any(np.linalg.norm(pt - c) <= 1e-9 * scale for c in topo.contacts):
                topo.contacts.append(pt)
            continue
        if not simple:
            if not q_rim:
                centre = p.frame.global_of([0.0, 0.0, p.frame.local_of(pt)[2]])
                if keep(pt) and not any(np.linalg.norm(centre - c) <= 1e-9 * scale and abs(radius - r) <= 1e-9 * scale
                                        for c, _, r in topo.tangent_circles):
                    topo.tangent_circles.append((centre, p.frame.rotation[:, 2].copy(), radius))
                continue
        if not q_rim:
            # a parallel crossed transversally, in closed form (traced, its parameters would move linearly in
            # s, and the solver's error estimate, zero, would let one step lap a small circle)
            centre = p.frame.global_of([0.0, 0.0, p.frame.local_of(pt)[2]])
            if keep(pt) and not any(np.linalg.norm(centre - c) <= 1e-9 * scale and abs(radius - r) <= 1e-9 * scale
                                    for c, _, r in topo.circles):       # (once: a seam's two ends are one circle)
                topo.circles.append((centre, p.frame.rotation[:, 2].copy(), radius))
            continue
        # an arc of a circle cut by a trimmed plane: seed it at a point inside both trims
        ring = p.point(np.linspace(-math.pi, math.pi, 64, endpoint=False), np.full(64, v))
        inside = keep.select(ring)
        if inside:
            topo.seeds.append(inside[0])
    if q_rim:
        q_edges(q, qp, bounding_ball(p), add_line_roots, q_index)


def ruled_components(p, q, pq, box, topo, scale):
    """A ruled P (a cylinder or cone) and a surface that respects its rulings meet in rulings u = const of P
    (straight segments, through the apex for a cone): the roots of g on one cross-section (P's traits choose it:
    off a cone's apex, through which all its rulings pass). Each line is clipped to both trims; a simple root is
    traced, a multiple root where g keeps its sign is a line of tangency."""
    v_mid = p.traits.cross_section(box[2], box[3])
    roots, unresolved = pq.line(1, v_mid, -math.pi, math.pi, topo, "cross-section")
    for u, simple in [(u, True) for u in roots] + [(u, False) for u in merge_values(unresolved, 8 * COARSE * math.pi)]:
        if not simple:
            u = double_root(pq, 1, v_mid, u)       # (before the clip: a line of tangency may run along Q's edge)
        lo, hi = clip_line(p, u, box[2], box[3], q, scale)
        if not lo < hi:
            continue
        if not simple:
            h = 1e-6
            side = pq.values([[u - h, v_mid], [u + h, v_mid]])[:, 0]
            if side[0] * side[1] > 0:
                ends = (p.point(u, lo), p.point(u, hi))          # a straight segment (through a cone's apex)
                if not any(np.linalg.norm(ends[0] - e[0]) <= 1e-9 * scale for e in topo.tangent_segments):
                    topo.tangent_segments.append(ends)
                continue
        # a start off the apex, where the ruling is regular
        topo.seeds.append(p.point(u, v_mid if lo < v_mid < hi else 0.5 * (lo + hi)))


def step_units(surface, scale):
    """(2,) the length of a unit step of (u, v) of the surface (traits' parameter_units: 1 for an angle, the scale
    for a length) rounded to a power of two (power_of_two): the units of the stops and moves of the Newton and
    root-finder iterations here, so that they do not depend on the scene's scale."""
    return np.array([power_of_two(x) for x in surface.traits.parameter_units(scale)])


def double_root(reader, fixed, value, t, unit=1.0):
    """A multiple root of g on a parameter line, refined from t as the zero of its derivative along the line
    (Newton); t itself where that does not settle within 1e-5 of it. unit: the length of a unit step of the line's
    parameter (step_units; the tests are in units of it)."""
    x = t
    for _ in range(CRITICAL_ITER):
        g = reader.values([x, value] if fixed == 1 else [value, x])[0]
        d1, d2 = (g[1], g[3]) if fixed == 1 else (g[2], g[5])
        if d2 == 0.0:
            break
        step = d1 / d2
        x -= step
        if abs(step) <= 1e-15 * max(unit, abs(x)):
            break
    return x if abs(x - t) <= 1e-5 * max(unit, abs(t)) else t


def clip_line(p, u, v_lo, v_hi, q, scale):
    """The v-interval of the line u = const of the ruled P within [v_lo, v_hi] that lies inside Q's trim (the
    trims of Q's length parameters, each along its local axis). A line along a trim edge to round-off (ROUNDOFF_ULPS
    of the coordinates' magnitude) lies on it, inside the closed trim."""
    ends = p.point(np.array([u, u]), np.array([v_lo, v_hi]))
    lo, hi = 0.0, 1.0
    local = q.frame.local_of(ends)
    slack = ROUNDOFF_ULPS * EPS * max(scale, float(np.max(np.abs(ends))), float(np.max(np.abs(q.frame.origin))))
    limits = [(axis, *trim) for axis, trim in zip(q.traits.parameter_axes, q.bounds)
              if axis is not None]
    for k, a, b in limits:
        x0, x1 = local[0, k], local[1, k]
        if abs(x1 - x0) <= slack:
            if not a - slack <= 0.5 * (x0 + x1) <= b + slack:
                return 0.0, -1.0
            continue
        t_a, t_b = (a - x0) / (x1 - x0), (b - x0) / (x1 - x0)
        lo, hi = max(lo, min(t_a, t_b)), min(hi, max(t_a, t_b))
    return v_lo + lo * (v_hi - v_lo), v_lo + hi * (v_hi - v_lo)


def split_range(lo, hi, bands):
    """[lo, hi] less the open bands (lo_k, hi_k): a list of (lo, hi)."""
    pieces = [(lo, hi)]
    for b_lo, b_hi in bands:
        pieces = [q for a, b in pieces for q in ((a, min(b, b_lo)), (max(a, b_hi), b)) if q[0] < q[1]]
    return pieces


def cluster_bracket(pq, v, box, beyond, others):
    """(lo, hi) round the cluster v of unresolved roots on P's meridian u = -pi across which g changes sign (a simple
    root), or None (a multiple root: g keeps its sign, or round-off hides it at every width). The interval's
    half-width starts at CLUSTER_SIDE of the range and grows CLUSTER_GROWTH-fold, at most CLUSTER_WIDENINGS times,
    while g is within round-off of zero at an end (a root crossed at a small angle is blurred over round-off / slope),
    never taking in another root or cluster (others); beyond: g is read past the range's ends (else clipped)."""
    h = CLUSTER_SIDE * (box[3] - box[2])
    for _ in range(CLUSTER_WIDENINGS + 1):
        lo, hi = (v - h, v + h) if beyond else (max(v - h, box[2]), min(v + h, box[3]))
        if any(lo <= w <= hi for w in others):
            return None
        if not pq.on_level((-math.pi, lo)) and not pq.on_level((-math.pi, hi)):
            side = pq.values([[-math.pi, lo], [-math.pi, hi]])[:, 0]
            return (lo, hi) if side[0] * side[1] < 0 else None
        h *= CLUSTER_GROWTH
    return None


def merge_values(values, gap):
    """Sorted values with runs closer than gap replaced by their mean."""
    values = np.sort(np.asarray(values, dtype=float))
    out, run = [], []
    for x in values:
        if run and x - run[-1] > gap:
            out.append(float(np.mean(run)))
            run = []
        run.append(x)
    if run:
        out.append(float(np.mean(run)))
    return out


def trim_bounds(surface, tolerance):
    """(u_lo, u_hi, v_lo, v_hi) (4,): the trims of a surface widened by a slack of 10 tolerances (as parameter
    slacks at the trims); all NaN when it has no trim."""
    (u0, u1), (v0, v1) = surface.bounds
    if not (math.isfinite(u0) or math.isfinite(u1) or math.isfinite(v0) or math.isfinite(v1)):
        return np.full(4, np.nan)
    u_slack, v_slack = surface.traits.trim_slack(surface, 10.0 * tolerance)
    return np.array([u0 - u_slack, u1 + u_slack, v0 - v_slack, v1 + v_slack])


class Keeper:
    """Which starts are kept: inside both trims (their foot points' parameters, with trim_bounds' slack of 10
    tolerances) and off the apexes of P (the rings round them seed their branches); set up once per call, each test
    of many points one compiled call (spatialkin.kernels.search.topology.keep_points)."""

    def __init__(self, a, b, apex_points, scale, tolerance):
        self.data = (a.data, b.data)
        self.bounds = (trim_bounds(a, tolerance), trim_bounds(b, tolerance))
        self.apexes = np.array(apex_points, dtype=float).reshape(-1, 3)
        self.clearance = APEX_CLEARANCE * scale

    def many(self, points, apexes=None):
        """(N,) bool for points (N, 3); apexes (K, 3) in place of P's."""
        points = np.ascontiguousarray(points, dtype=float).reshape(-1, 3)
        out = np.empty(len(points), dtype=bool)
        kt.keep_points(self.data[0], self.bounds[0], self.data[1], self.bounds[1],
                       self.apexes if apexes is None else apexes, self.clearance, points, out)
        return out

    def __call__(self, point):
        """True when the start point (3,) is kept."""
        return bool(self.many(point)[0])

    def inside_both(self, point):
        """True when the point (3,) is inside both trims (wherever it is relative to the apexes)."""
        return bool(self.many(point, NO_POINTS)[0])

    def select(self, points):
        """The kept rows of points (N, 3), as a list of (3,) arrays."""
        points = np.asarray(points, dtype=float).reshape(-1, 3)
        return list(points[self.many(points)]) if len(points) else []

    def on(self, surface, uv):
        """(points (N, 3) of the surface at parameter points uv (N, 2), (N,) bool: which are kept): points_at and
        many in one compiled call (spatialkin.kernels.search.topology.keep_surface_points)."""
        uv = np.ascontiguousarray(uv, dtype=float).reshape(-1, 2)
        points = np.empty((len(uv), 3))
        out = np.empty(len(uv), dtype=bool)
        kt.keep_surface_points(surface.data, uv, self.data[0], self.bounds[0], self.data[1], self.bounds[1],
                               self.apexes, self.clearance, points, out)
        return points, out

    def select_on(self, surface, uv):
        """The kept points of the surface at parameter points uv (N, 2), as a list of (3,) arrays (select of
        points_at, in one compiled call)."""
        points, kept = self.on(surface, uv)
        return list(points[kept])


def classify(loose, topo, scale, keep):
    """Unresolved boxes: each cluster is a singular point of the level (a contact, a node, a degenerate point)
    or a double root on a line; contacts are kept, nodes seed their four arms, the rest seed where they are."""
    clusters, done = [], []
    units = {}
    firsts = np.empty((len(loose), 3))                     # the clusters' first points, as rows
    for reader, uv in loose:
        pt = reader.s.point(*uv)
        if clusters and np.min(np.sum((firsts[:len(clusters)] - pt) ** 2, axis=1)) <= (CLUSTER * scale) ** 2:
            continue
        firsts[len(clusters)] = pt
        clusters.append((reader, uv, pt))
    for reader, uv, pt in clusters:
        unit = units.setdefault(id(reader), step_units(reader.s, scale))
        crit = critical_point(reader, uv, unit)
        if crit is None:
            if keep(pt):
                topo.seeds.append(pt)
            continue
        at = reader.s.point(*crit)
        if any(np.linalg.norm(at - x) <= CLUSTER * scale for x in done):
            continue                                 # the same singular point, reached from another box
        done.append(at)
        if not reader.on_level(crit):
            # a critical point off the level (a tiny loop's centre, a waist): the extremal roots seed what is
            # there; this box's centre is a start too, and so is each side of a waist (the extremal roots of two
            # branches passing it closely may be left unresolved with it, in one cluster)
            for start in [pt] + waist_starts(reader, crit, unit):
                if keep(start):
                    topo.seeds.append(start)
            continue
        lam, vec = hessian_eigen(reader, crit, unit)
        if lam is None:
            if keep(at):
                topo.seeds.append(at)
            continue
        big = max(abs(lam[0]), abs(lam[1]), 1e-300)
        nonzero = np.abs(lam) > EIGEN_RATIO * big
        inside = keep(at)
        if np.all(nonzero) and lam[0] * lam[1] > 0:
            if not inside:
                continue
            start = tiny_loop_start(reader, crit, lam, vec)
            if start is not None:
                topo.seeds.append(start)
            else:
                topo.contacts.append(at)
        elif np.all(nonzero):
            # a node: its arms seed the branches, each where it lies inside the trims (the node itself may lie
            # just outside an edge that the branches cross beside it)
            if inside:
                topo.nodes.append(at)
            ratio = math.sqrt(-lam[0] / lam[1])
            d = reader.s.derivatives(*crit)
            jacobian = np.column_stack([d[1], d[2]])
            for w in (vec[:, 0] + ratio * vec[:, 1], vec[:, 0] - ratio * vec[:, 1]):
                step = NODE_OFFSET * scale / max(np.linalg.norm(d[1] * w[0] + d[2] * w[1]), 1e-300)
                for sense in (1.0, -1.0):
                    arm = reader.s.point(*arm_point(reader, crit, sense * step * w, jacobian))
                    if keep(arm):
                        topo.seeds.append(arm)
        elif inside:
            topo.seeds.append(at)


def arm_point(reader, crit, offset, jacobian):
    """The parameters of a seed on a node's arm: crit + offset, the offset halved (up to ARM_HALVINGS times) until
    Newton on g from there settles on the level within ARM_FIT of the offset's length (settles): the branch may
    bend away from its tangent at the node within the first offset (a loop through the node smaller than
    NODE_OFFSET, such as one through a cone's apex lying on the other surface); the first offset where none
    settles. jacobian (3, 2): S's derivatives at the node, which measure parameter steps as lengths."""
    first = offset
    for _ in range(ARM_HALVINGS):
        if settles(reader, crit + offset, jacobian, ARM_FIT * float(np.linalg.norm(jacobian @ offset))):
            return crit + offset
        offset = 0.5 * offset
    return crit + first


def settles(reader, uv, jacobian, reach):
    """True when Newton on g from uv (least-norm steps along grad g, at most ARM_NEWTON) converges (a step below
    ARM_SETTLED of reach) without moving farther than reach from uv (lengths through jacobian)."""
    x = np.array(uv, dtype=float)
    for _ in range(ARM_NEWTON):
        g = reader.values(x)[0]
        size = g[1] * g[1] + g[2] * g[2]
        if not size > 0.0:
            return False
        step = -g[0] / size * g[1:3]
        x = x + step
        if not np.linalg.norm(jacobian @ (x - uv)) <= reach:
            return False
        if np.linalg.norm(jacobian @ step) <= ARM_SETTLED * reach:
            return True
    return False


def waist_starts(reader, crit, units):
    """Points of the level on both sides of a saddle of g off the level (a waist between two branches passing it
    closely): the roots of g along the Hessian's eigen-direction whose curvature has the sign opposite to g there,
    each bracketed round the quadratic prediction (brentq); [] where crit is no saddle or a side has no root."""
    lam, vec = hessian_eigen(reader, crit, units)
    if lam is None or lam[0] * lam[1] >= 0.0:
        return []
    g0 = float(reader.values(crit)[0][0])
    k = 0 if lam[0] * g0 < 0.0 else 1
    guess = math.sqrt(2.0 * abs(g0) / abs(lam[k]))
    sides = (level_root(reader, crit, sense * vec[:, k], g0, guess) for sense in (1.0, -1.0))
    return [point for point in sides if point is not None]


def level_root(reader, crit, w, g0, guess):
    """The point of the level g = 0 on the ray crit + t w (t > 0) from a critical point where g = g0, bracketed
    round the quadratic prediction t = guess (brentq); None if g keeps its sign out to 16 guesses."""
    def along(t):
        return float(reader.values(crit + t * w)[0][0])
    inside = 0.0
    for t in guess * np.geomspace(0.25, 16.0, 13):
        if along(t) * g0 <= 0.0:
            return reader.s.point(*(crit + brentq(along, inside, t, xtol=1e-300, rtol=4 * np.finfo(float).eps) * w))
        inside = t
    return None


def tiny_loop_start(reader, crit, lam, vec):
    """A point of the loop round an extremum of g whose value is within g's rigorous enclosure of zero but, in
    floating point, of the sign that puts a loop round it (a minimum below zero, a maximum above), by more than
    LOOP_FLOOR of the enclosure's width (which overestimates round-off; a true contact's g is a few ulp): the
    root of g on the flattest eigen-direction, bracketed round the quadratic prediction (brentq). None if
    g does not change sign there (then it is a contact)."""
    g0 = float(reader.values(crit)[0][0])
    lo, hi = reader.enclosure(crit)
    if g0 * lam[0] >= 0.0 or abs(g0) < LOOP_FLOOR * (hi - lo):
        return None
    k = int(np.argmin(np.abs(lam)))
    return level_root(reader, crit, vec[:, k], g0, math.sqrt(2.0 * abs(g0) / abs(lam[k])))


def critical_point(reader, uv, units):
    """Newton on grad g = 0 from uv; the critical point (2,), or None if Newton does not settle nearby. units (2,):
    the length of a unit step of (u, v) (step_units: 1 for an angle, about the scene scale for a length); the
    convergence and the move allowed are measured in the scaled parameters uv / units, so that a length
    parameter's tests do not depend on the scene's scale."""
    units = np.asarray(units, dtype=float)
    x = np.array(uv, dtype=float)
    for _ in range(CRITICAL_ITER):
        g = reader.values(x)[0]
        hess = np.array([[g[3], g[4]], [g[4], g[5]]])
        try:
            step = np.linalg.solve(hess, -g[1:3])
        except np.linalg.LinAlgError:
            return x
        if not np.all(np.isfinite(step)):
            return x
        x = x + step
        if np.max(np.abs(step / units)) <= 1e-15 * max(1.0, np.max(np.abs(x / units))):
            break
    if np.max(np.abs((x - uv) / units)) > 1e-3 * max(1.0, np.max(np.abs(uv / units))):
        return None
    return x


def hessian_eigen(reader, uv, units):
    """Eigenvalues and vectors of the Hessian of g in the metric of S at uv, or (None, None) where the metric
    degenerates (a pole or an apex). units (2,) as in critical_point: the degeneracy is judged on the metric of
    the scaled parameters uv / units (whose entries are all lengths squared), not on a mix of lengths and angles
    (a cylinder's diag(r^2, 1) would read as degenerate for r below 1e-7 in the user's unit)."""
    g = reader.values(uv)[0]
    hess = np.array([[g[3], g[4]], [g[4], g[5]]])
    d = reader.s.derivatives(*uv)
    metric = np.array([[d[1] @ d[1], d[1] @ d[2]], [d[1] @ d[2], d[2] @ d[2]]])
    scaled = metric * np.outer(units, units)
    if np.linalg.det(scaled) <= 1e-14 * np.trace(scaled) ** 2:
        return None, None
    return scipy.linalg.eigh(hess, metric)
