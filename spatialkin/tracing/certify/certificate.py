"""The certificate of ``sk.intersect(a, b, certify=True)``: each claim about the answer, proven or not, and where.

A claim counts as proven only when a proof in outward-rounded arithmetic covers it: interval arithmetic in the
compiled search, the stored points' boxes and the tubes (spatialkin.kernels.geometry.interval,
spatialkin.kernels.certify). Whatever could not be proven is said, claim by claim, with the points where the proof
stopped.
"""
import math
from dataclasses import dataclass

import numpy as np

from ..curve.clip import WindowSolution
from ..curve.status import CONTACT, TANGENT
from ...kernels.certify import tubes as kt
from ...kernels.certify import singular as ks_singular
from ...kernels.search import topology as ks
from .certify_points import certify_points
from ..search.topology import TopologyError, points_at, search
from .trims import Ends, closed_inside, edges, open_curve, outside, q_edge_roots
from .nodes import SHARES, box_radii, in_boxes, linked, node_boxes, passages, typical_chord
from .tubes import Chart, tube
from .faces import cut

PROVEN, NOT_PROVEN = "proven", "not proven"
#: Half-widths (relative to the root's magnitude, at least 1) of the smaller boxes round a search's refined root
#: that are proven to hold it when its verified box is too large to lie inside a tube: 1e-12 to 1e-6 in steps of
#: sqrt(10) (the search's interval test resolves a box around a root of a tiny loop only above some width, which the
#: piece's width must still exceed).
SHRINK = tuple(10.0 ** (-k / 2) for k in range(24, 11, -1))
#: Box budget of those proofs.
SHRINK_BOXES = 200
#: The modes of a topology search (a Topology of another mode comes from a closed form: nothing searched).
SEARCHED = ("general", "coaxial", "ruled")
#: A chart collapses at a point of the curve (an apex or a pole lies there) within this distance, relative to the
#: scale (other_chart).
APEX_SHARED = 1e-6
#: The claims, in the order they are reported.
CLAIMS = ("complete", "one_component", "distinct", "points", "arcs", "singular")


@dataclass(frozen=True)
class Claim:
    """One claim of a certificate: its name (one of CLAIMS), 'proven' or 'not proven', what was found (detail),
    the points (K, 3) where its proof failed (empty when proven), and for each a ball radius (K,): for a singular
    point, a proven radius round it holding all of the intersection nearby (inf where none was proven)."""
    name: str
    status: str
    detail: str
    where: np.ndarray
    radius: np.ndarray = None

    @property
    def proven(self):
        return self.status == PROVEN

    def __repr__(self):
        at = f" at {np.round(self.where[0], 12).tolist()}" if len(self.where) else ""
        return f"Claim({self.name!r}, {self.status!r}: {self.detail}{at})"


def claim(name, failures, proven_text):
    """A Claim from a list of (text, point or None[, ball radius]) failures: proven when there is none."""
    if not failures:
        return Claim(name, PROVEN, proven_text, np.empty((0, 3)), np.empty(0))
    located = [f for f in failures if f[1] is not None]
    where = np.array([f[1] for f in located], dtype=float).reshape(-1, 3)
    radius = np.array([f[2] if len(f) > 2 else math.inf for f in located], dtype=float)
    more = f" (and {len(failures) - 1} more)" if len(failures) > 1 else ""
    return Claim(name, NOT_PROVEN, failures[0][0] + more, where, radius)


def joined(base, failures, proven_text):
    """The claim base extended by failures (as claim reads them): base itself where it failed already, else
    proven saying proven_text, or not proven with the new failures."""
    if not base.proven:
        return base
    return claim(base.name, failures, proven_text)


class CertificationError(RuntimeError):
    """``sk.intersect(..., certify="strict")`` could not prove the whole answer; ``certificate`` says which claims
    failed and where (``certificate.failed``)."""

    def __init__(self, certificate):
        self.certificate = certificate
        lines = "; ".join(f"{c.name}: {c.detail}" for c in certificate.failed)
        super().__init__(f"the intersection could not be proven: {lines}")


class Certificate:
    """What ``sk.intersect(a, b, certify=True)`` proved about its whole answer, claim by claim.

    The claims (``claims``, a dict of Claim by name; ``proven`` is True only when every one is):

    - **complete**: no component missed. The topology search (spatialkin.tracing.search.topology) encloses every
      root of the conditions each component must meet somewhere (a zero of g on an edge, a seam or a ring, a point
      where the level's tangent is normal to a fixed direction) in boxes, each verified to hold exactly one root or
      left unresolved. Proven when there is no unresolved box and every verified box lies inside a proven tube of a
      returned curve (so its root is a point of that curve) or strictly outside the other surface's trims, with no
      distance tolerance involved; the roots found on the other surface's trim edges are counted against the proven
      crossings there and the roots outside the first surface's trims. A pair the search
      read as coaxial or ruled (a symmetry decided within a tolerance) is proven complete only where the symmetry is
      exact whatever the placement (two spheres, a sphere and a plane).
    - **one_component**: a closed curve's tube closes on itself and lies strictly inside every trim, so the curve
      is a whole closed component of the trimmed patches. An open
      curve is one whole piece of its component within the trims when each end is a proven crossing of a trim
      edge inside the tube (the Krawczyk test on g = 0 and the edge), the arc crosses that edge once in the pieces
      that touch it, and every other piece lies strictly inside every trim (spatialkin.tracing.certify.trims, for
      the trims of length parameters). Faces' regions (angular ranges, a sphere's latitudes, a torus's tube angles,
      a plane's disc or annulus) cut the components after tracing: the answer before the cut is proven, then each
      returned arc is proven to run between two proven crossings of face edges along its component's tube, and
      every arc inside both faces to be returned (spatialkin.tracing.certify.faces; a point where a component
      touches a face edge from outside is not proven).
    - **distinct**: the tubes of different curves are proven disjoint: no two returned curves share a point (with
      one_component, no two are pieces of one component).
    - **points**: every stored point has a finite proven radius (``radii``): a box of that half-width round it
      holds a true intersection point (the Krawczyk test on F_a = 0, F_b = 0 and the plane normal to the curve,
      spatialkin.tracing.certify.certify_points).
    - **arcs**: each curve is covered by a chain of linked parallelograms of the search's parameter plane, each
      proven by a parametric Krawczyk test to hold exactly one arc of the intersection, entering and leaving
      through opposite ends (spatialkin.kernels.certify.tubes): the arcs between the points are proven, and
      ``distance_bounds`` bound the distance from each stored point and dense sample (the points the tube was
      built on, each given a proven box) to the intersection.
    - **singular**: points where the surfaces touch or branches cross (contacts, nodes, apexes, circles or segments
      of tangency) are reported, not proven (a tangency is an equality that floating point cannot decide; see
      below for the placements that make it exact), with
      their places and, for a contact, a proven ball (``radius``): the Krawczyk test proves a unique critical
      point of g in a box where its Hessian is definite, so the intersection within the box lies within the ball
      (a point, a small loop or nothing); a node gets a box proven to hold one critical point, a saddle, and
      exactly four branches leaving it, each through a proven tube (spatialkin.tracing.certify.nodes: the tubes
      are chained between node boxes, so the arcs and completeness are proven through nodes). Where the level is
      proven to keep one sign along a segment across the box (two branches passing close, the saddle off the
      level), the box holds no singular point and the branches join two by two in a proven way: a curve through
      it is one component when each passage takes one arc from end to end, and two curves through it by different
      arcs are distinct. Otherwise (a crossing, or branches too close for floating point to tell) which branches
      join is not decided, and neither are one_component and distinct for the curves through it. An apex of a
      cone lying on the other surface gets its ball the same way, in the chart of the surface it is not an apex of
      (where the cone's implicit function has its critical point): isolated, or a saddle where two branches cross.
      Where the search's own chart collapses at such an apex, the whole answer is read in the other surface's
      chart (a general search there, other_chart), where the tubes pass the apex as they pass a node.
      Circles and segments of tangency get no ball.
      The search's boxes inside an isolated contact's box are accounted for by it in the completeness claim.

    An empty answer has a certificate too (``sk.intersect`` returns a list with a ``certificate`` attribute): it is
    proven when the search found no root and no unresolved box, so no point is common to the two trimmed surfaces.

    Two untrimmed spheres, a plane with an untrimmed sphere, a cylinder or a cone, and two planes are proven in
    closed form instead, with no search (mode 'closed form', spatialkin.tracing.certify.closed): interval arithmetic
    proves that they meet in exactly one circle, ellipse or segment inside the trims, or in nothing, and bounds the
    distance between the returned curve's whole dense output and the true curve both ways (``distance_bounds``, a
    Hausdorff bound). Two surfaces turning about one coordinate axis, or running along one, placed by frames that are
    signed permutations, are proven exactly in rational arithmetic on the floats (modes 'exact (coaxial)' and
    'exact (parallel)', spatialkin.tracing.certify.coaxial and .parallel): the common points of their meridians or
    cross-sections, tangencies included, decided exactly, each returned curve bounded likewise.

    Attributes
    ----------
    claims : dict of Claim
    proven : bool
    failed : list of Claim
        The claims not proven.
    components : int
        How many curves were returned.
    mode : str
        The configuration the search recognised ('general', 'coaxial', 'ruled'), or, with no search, 'closed form'
        (spatialkin.tracing.certify.closed), 'exact (coaxial)' or 'exact (parallel)'
        (spatialkin.tracing.certify.coaxial and .parallel).
    boxes, verified_roots, singular_points : int
        The search's boxes, verified roots and unresolved boxes.
    search_seconds : float
    radii : list of ndarray
        Per curve, the proven half-width of the box round each stored point (inf where not proven).
    distance_bounds : list of float
        Per curve, the proven bound of the distance from its stored points and dense samples to the intersection
        (inf where its tube or a sample's box is not proven; a sample with no proven box inside a node's box left
        out, the node's ball bounding it); proven in closed form, a bound of the Hausdorff distance between its
        whole dense output and the true curve.
    tubes : list of Tube or None
        Per curve, its chain of pieces (spatialkin.tracing.certify.tubes.Tube); for an arc cut by the faces, its
        component's.
    topology, chart
        The search behind the answer (spatialkin.tracing.search.topology.Topology, None for a closed form) and the
        chart its tubes are read in (spatialkin.tracing.certify.tubes.Chart, or None).

    Where a face's region cuts the answer, the claims are proven for its components before the cut (their failures
    name those components) and for the cut itself (spatialkin.tracing.certify.faces).

    References
    ----------
    .. [1] R. Krawczyk, "Newton-Algorithmen zur Bestimmung von Nullstellen mit Fehlerschranken", Computing 4 (1969).
    .. [2] R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM, 2009.
    .. [3] B. Martin, A. Goldsztejn, L. Granvilliers, C. Jermann, "Certified parallelotope continuation for
       one-manifolds", SIAM J. Numer. Anal. 51(6), 2013.

    Examples
    --------
    >>> import spatialkin as sk
    >>> torus, sphere = sk.Torus(1.0, 0.4), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.3)))
    >>> curves = sk.intersect(torus, sphere, certify=True)
    >>> cert = curves.certificate
    >>> cert.proven, cert.components, [c.status for c in cert.claims.values()]
    (True, 2, ['proven', 'proven', 'proven', 'proven', 'proven', 'proven'])
    >>> bool(max(cert.distance_bounds) < 1e-12)
    True
    >>> sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((3.0, 0.0, 0.0))), certify=True).certificate.proven
    True
    """

    def __init__(self, claims, topology, radii, tubes, bounds, components, chart=None, mode=None):
        self.claims = {c.name: c for c in claims}
        self.topology = topology
        self.chart = chart
        self.components = int(components)
        self.mode = mode if mode is not None else topology.mode if topology is not None else "closed form"
        self.boxes = topology.boxes if topology is not None else 0
        self.verified_roots = topology.verified if topology is not None else 0
        self.singular_points = topology.unresolved if topology is not None else 0
        self.search_seconds = topology.seconds if topology is not None else 0.0
        self.radii = radii
        self.tubes = tubes
        self.distance_bounds = list(bounds)

    @property
    def proven(self):
        return all(c.proven for c in self.claims.values())

    @property
    def failed(self):
        return [c for c in self.claims.values() if not c.proven]

    def __repr__(self):
        state = "proven" if self.proven else "NOT proven: " + ", ".join(c.name for c in self.failed)
        bound = max(self.distance_bounds, default=0.0)
        return (f"Certificate({state}; components={self.components}, mode={self.mode!r}, boxes={self.boxes}, "
                f"distance <= {bound:.2e})")


class CurveCertificate:
    """A returned curve's view of the answer's Certificate (``curve.certificate``): the answer's claims, and this
    curve's radii, tube and distance bound.

    Attributes
    ----------
    answer : Certificate
    proven : bool
        The whole answer proven (every claim of ``answer``).
    claims : dict of Claim
    radii : ndarray (N,)
        Proven half-width of the box round each stored point (length unit; inf where not proven).
    all_points_proven : bool
    max_distance_bound : float
        The largest proven distance from a stored point to a true intersection point, radii.max() * sqrt(3).
    distance_bound : float
        Proven bound of the distance from every stored point and dense sample to the true curve (tube; inf when
        not proven; as the answer's distance_bounds), or, proven in closed form, of the Hausdorff distance between
        the whole dense output and the true curve.
    components, mode, boxes, verified_roots, singular_points, search_seconds
        As in the answer's certificate.
    """

    def __init__(self, answer, index):
        self.answer = answer
        self.index = index

    radii = property(lambda self: self.answer.radii[self.index])
    tube = property(lambda self: self.answer.tubes[self.index])
    distance_bound = property(lambda self: self.answer.distance_bounds[self.index])
    claims = property(lambda self: self.answer.claims)
    proven = property(lambda self: self.answer.proven)
    components = property(lambda self: self.answer.components)
    mode = property(lambda self: self.answer.mode)
    boxes = property(lambda self: self.answer.boxes)
    verified_roots = property(lambda self: self.answer.verified_roots)
    singular_points = property(lambda self: self.answer.singular_points)
    search_seconds = property(lambda self: self.answer.search_seconds)

    @property
    def all_points_proven(self):
        """True when every stored point has a finite radius."""
        return bool(self.radii.size) and bool(np.all(np.isfinite(self.radii)))

    @property
    def max_distance_bound(self):
        """The largest proven distance (Euclidean) from a stored point to a true intersection point."""
        return float(np.max(self.radii) * math.sqrt(3.0)) if self.radii.size else math.inf

    def __repr__(self):
        proven = int(np.sum(np.isfinite(self.radii)))
        state = "proven" if self.proven else "NOT proven: " + ", ".join(c.name for c in self.answer.failed)
        return (f"Certificate({state}; curve {self.index} of {self.components}, mode={self.mode!r}, "
                f"points proven {proven}/{self.radii.size}, distance <= {self.distance_bound:.2e})")


def certify(a, b, curves, topology, scale, tolerance=None, failure=None, wholes=None):
    """The Certificate of an answer (CurveResults, the curves sk.intersect returns, in order) and the search that
    found it (scale and tolerance: the scene's, spatialkin.tracing.march.trace.scene_lengths). A search that read
    the pair as coaxial or ruled, a symmetry decided within a tolerance, is run again as a general search, whose
    roots the completeness claim then places (except for two spheres, or a sphere and a plane, symmetric exactly
    whatever their placement). failure: why no search stands behind the answer (topology None). wholes: the
    components before the faces' regions cut them (spatialkin.tracing.curve.clip), when a surface has a region:
    proven first, then the cut (spatialkin.tracing.certify.faces)."""
    if wholes is None or not (a.region or b.region):
        return uncut(a, b, curves, topology, scale, tolerance, failure)
    base = uncut(a, b, wholes, topology, scale, tolerance, failure, regions=False, arcs=cut_arcs(curves, wholes))
    failures, radii, tubes, bounds = cut(base, a, b, curves, wholes)
    c = base.claims
    claims = [joined(c["complete"], failures, "every root of the search lies on a component traced before the faces "
                     "cut it, and every arc of a component inside both faces is returned (the crossings of their "
                     "edges proven along its tube)"),
              joined(c["one_component"], failures, "every arc cut by the faces runs between two proven crossings of "
                     "face edges (or its component's own ends), a component inside both faces all along is returned "
                     "whole"),
              joined(c["distinct"], failures, "the components' tubes are pairwise disjoint, and the arcs cut from one "
                     "component are parted by stretches of it outside the faces"),
              claim("points", unproven_points(radii, curves), "every stored point has a proven radius"),
              c["arcs"], c["singular"]]
    return Certificate(claims, base.topology, radii, tubes, bounds, len(curves), base.chart)


def cut_arcs(curves, wholes):
    """{index of a whole: [(s0, s1)]}: the arcs the returned curves (a face's cut) take from each whole, in its arc
    length (s1 may pass a closed whole's length)."""
    out = {}
    for curve in curves:
        if isinstance(curve.sol, WindowSolution) and curve.length > 0:
            j = next((j for j, w in enumerate(wholes) if w.sol is curve.sol.whole), None)
            if j is not None:
                out.setdefault(j, []).append((curve.sol.start, curve.sol.start + curve.length))
    return out


def unproven_points(radii, curves):
    """(text, point) of each curve with a stored point of no proven radius (radii: (N,) per curve)."""
    out = []
    for i, (r, curve) in enumerate(zip(radii, curves)):
        bad = ~np.isfinite(r)
        if bad.any():
            out.append((f"curve {i}: {int(bad.sum())} of {bad.size} stored points have no proven radius",
                        curve.points[int(np.argmax(bad))]))
    return out


def regular(curve):
    """True for a curve with a tube: of positive length, neither a contact point nor a curve of tangency."""
    return curve.length > 0 and curve.status not in (TANGENT, CONTACT)


def node_tubes(chart, charted, curves, arcs):
    """(the node boxes, the Tube of each curve (None for a contact, a curve of tangency or without a chart)): the
    boxes of the search's nodes the smallest that pass (nodes.node_boxes), each curve's tube reaching into them.
    Where a tube that passes a node box fails, the boxes are tried again each the next size up (SHARES): close
    beside a node, where two branches pass near each other, a run's end inside a small box may lie nearer the other
    branch than a piece can be narrow."""
    if chart is None:
        return [], [None] * len(curves)
    chord = typical_chord(chart, curves)
    for first in range(len(SHARES)):
        nodes = node_boxes(chart, charted.nodes, chord, SHARES[first:])
        tubes = [tube(chart, curve, nodes, (arcs or {}).get(i, ())) if regular(curve) else None
                 for i, curve in enumerate(curves)]
        if not any(t is not None and t.split and not t.proven for t in tubes):
            break
    return nodes, tubes


def uncut(a, b, curves, topology, scale, tolerance=None, failure=None, regions=True, arcs=None):
    """The Certificate of an answer as certify makes it where no region cuts it (regions False: the faces'
    regions left out, as the search leaves them; arcs: {curve index: the arcs a face cuts from it}, whose tubes
    get samples in and beside them, cut_arcs)."""
    general = topology
    tolerance = scale * 1e-10 if tolerance is None else tolerance
    if topology is not None and topology.mode in ("coaxial", "ruled") and not exactly_symmetric(topology.P,
                                                                                                 topology.Q):
        try:
            general = search(a, b, scale, tolerance, general=True)
        except TopologyError as err:
            general = None
            failure = f"the general search (the pair was read as {topology.mode}) stopped: {err}"
    charted = topology if general is None else general
    other = other_chart(a, b, charted, scale, tolerance)
    if other is not None:
        general = charted = other
        failure = None
    chart = Chart(charted, scale) if charted is not None and charted.chart is not None else None
    trims, unsupported = edges(charted, chart, regions) if chart is not None else ([], [])
    nodes, tubes = node_tubes(chart, charted, curves, arcs)
    uses = {}                   # {curve index: {node index: the arcs (pairs) its passages take}}
    ends = Ends()
    radii, bounds = [], []
    arcs_failed, whole_failed = [], []
    for i, curve in enumerate(curves):
        t = tubes[i]
        if not regular(curve):
            radii.append(np.full(len(curve.points), math.inf))
        elif t is None:
            radii.append(certify_points(a, b, curve.points, curve.sol.tangent(curve.s)))
        else:
            radii.append(sample_radii(a, b, curve, t))
            if t.split:
                box_radii(chart, nodes, curve.points, radii[-1])
        bounds.append(math.inf if t is None or not t.proven else distance_bound(chart, nodes, curve, t, radii[-1]))
        if not regular(curve):
            continue
        if t is None or not t.proven:
            arcs_failed.append((f"curve {i}: {t.reason if t is not None else 'no search chart'}",
                                None if t is None else t.where))
            whole_failed.append((f"curve {i}: its tube is not proven", None if t is None else t.where))
        elif t.split:
            through = passages(nodes, t.runs, chart.periods) if curve.closed and not (trims or unsupported) else None
            if through is None:
                node = next((n for n in nodes if n.index in t.passes and n.pairs is None), None)
                whole_failed.append((f"curve {i} passes a node: which of the branches there join is not decided"
                                     if node is not None else f"curve {i} does not pass its nodes along the arcs "
                                     "that join there", t.points[0] if node is None else node.point))
            else:
                uses[i] = through
        elif not curve.closed and not open_curve(chart, trims, unsupported, t, curve, ends, i):
            whole_failed.append(ends.failures[-1])
        elif curve.closed and not closed_inside(chart, trims, unsupported, t, i, ends):
            whole_failed.append(ends.failures[-1])
    nodes, unlinked = linked(chart, nodes, tubes) if nodes else ([], [])
    arcs_failed += unlinked
    singular = singular_places(charted, chart, curves, scale, nodes)
    if topology is None:
        singular.append(("no search stands behind the answer: its singular points were not looked for", None))
    isolated = [place[3] for place in singular if len(place) > 3] + [node.box for node in nodes]
    complete = (claim("complete", [(failure, None)], "") if failure is not None else
                complete_claim(general, chart, tubes, curves, trims, unsupported, ends, isolated))
    claims = [complete,
              claim("one_component", whole_failed, "every closed curve's tube closes on itself, every open "
                    "curve runs between two proven crossings of trim edges"),
              distinct_claim(chart, tubes, contact_boxes(curves, singular), nodes, uses),
              claim("points", unproven_points(radii, curves), "every stored point has a proven radius"),
              claim("arcs", arcs_failed, "every curve lies in a chain of proven pieces" +
                    (", outside the node boxes (whose branches leave through them)" if nodes else "")),
              claim("singular", [place[:3] for place in singular],
                    "no singular point (contact, node, apex, tangency) was found")]
    return Certificate(claims, topology, radii, tubes, bounds, len(curves), chart)


def contact_boxes(curves, singular):
    """{index of a contact curve: the isolation box of its singular place (scaled)}, where one was proven."""
    out = {}
    for i, curve in enumerate(curves):
        if curve.status != CONTACT:
            continue
        for place in singular:
            if len(place) > 3 and np.array_equal(place[1], curve.points[0]):
                out[i] = place[3]
    return out


def distance_bound(chart, nodes, curve, t, radii):
    """The proven bound of the distance from the curve's stored points (radii: their box half-widths) and the
    tube's other samples to the intersection: sqrt(3) x the largest half-width; a sample with no proven box inside a
    node's box (where the 3 x 3 test meets the node's singular system) is left out, the node's ball bounding it."""
    every = np.full(len(t.s), np.nan)
    stored = np.searchsorted(t.s, curve.s)
    others = np.ones(len(t.s), dtype=bool)
    others[stored] = False
    every[stored], every[others] = radii, t.radii
    if t.split:
        every = every[np.isfinite(every) | ~in_boxes(chart, nodes, t.points)]
    return float(np.max(every, initial=0.0) * math.sqrt(3.0))


def sample_radii(a, b, curve, t):
    """The proven box half-widths (certify_points) of the curve's stored points, returned; those of the tube's
    other samples (its dense samples and refinements) kept on the tube as t.radii. The normal planes are across the
    samples' chords (any plane through the point transversal to the curve serves)."""
    tangents = np.gradient(t.points, axis=0)
    every = certify_points(a, b, t.points, tangents)
    stored = np.searchsorted(t.s, curve.s)
    t.radii = np.delete(every, stored)
    return every[stored]


def singular_places(topology, chart, curves, scale, nodes=()):
    """(text, point, ball radius) of each singular place: the contacts and nodes the search recorded, and the
    returned contact points, with the ball of kernels.certify.singular where it is proven; apexes likewise, in the
    chart of the surface the apex is not on (where the other's implicit function has a critical point); tangencies
    along curves with none."""
    out = []
    if topology is not None:
        out += [(f"a node: its ball of {node.radius:.1e} holds one critical point of the level, a saddle, and four "
                 "branches leaving it through proven tubes; which of them join there (a crossing, or two branches "
                 "passing close) is not decided", node.point, node.radius) for node in nodes if node.pairs is None]
        boxed = {node.index for node in nodes}
        points = [(p, "node") for k, p in enumerate(topology.nodes) if k not in boxed]
        points += [(p, "contact") for p in topology.contacts]
        points += [(c.points[0], "contact") for c in curves if c.status == CONTACT and
                   not any(np.array_equal(c.points[0], p) for p in topology.contacts)]
        points += [(p, "apex") for p in topology.apexes]
        other = Chart(topology, scale, other=True) if points and chart is not None else None
        out += [either_ball(chart, other, p, what) for p, what in points]
        out += [("a circle of tangency (not proven)", np.asarray(c[0], dtype=float), math.inf)
                for c in topology.tangent_circles]
        out += [("a segment of tangency (not proven)", np.asarray(seg[0], dtype=float), math.inf)
                for seg in topology.tangent_segments]
    out += [(f"curve {i} is a {c.status} along which the surfaces touch (not proven)", c.points[0], math.inf)
            for i, c in enumerate(curves) if c.status == TANGENT]
    return out


def either_ball(chart, other, point, what):
    """(text, point, ball radius[, its box]) of a singular point: singular_ball in the search's chart, else in Q's
    (other: where P's chart collapses, at an apex or a pole of P, F_P(Q(u, v)) has the critical point; no box then,
    the box being in Q's parameters)."""
    found = singular_ball(chart, point, what)
    if math.isfinite(found[2]) or other is None:
        return found
    return singular_ball(other, point, what)[:3]


def singular_ball(chart, point, what):
    """(text, point, ball radius[, its box]) of a contact, a node or an apex (kernels.certify.singular.critical_ball
    in the chart); the scaled box (4,) of an isolated one holds nothing of the intersection but its ball."""
    what = ("an " if what[0] in "aeiou" else "a ") + what
    if chart is None:
        return (f"{what} (not proven)", point, math.inf)
    x = chart.scaled(np.asarray(point, dtype=float)[None])[0]
    r = chart.reader
    size = max(1.0, float(np.max(np.abs(x))))
    out = np.empty(3)
    kind = ks_singular.critical_ball(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, float(chart.units[0]),
                                     float(chart.units[1]), float(x[0]), float(x[1]), 1e-9 * size, 1e-3 * size, out)
    if kind == ks_singular.ISOLATED:
        ball = float(out[1] * out[2])
        return (f"{what}: within {out[0] * out[2]:.1e} of it the intersection lies within {ball:.1e} of it (a "
                "point, a small loop or nothing; not decided)", point, ball,
                np.array([x[0] - out[0], x[0] + out[0], x[1] - out[0], x[1] + out[0]]))
    if kind == ks_singular.SADDLE:
        ball = float(out[0] * out[2])
        return (f"{what}: the only critical point of the level within {ball:.1e} of it is a saddle (a node, or "
                "two branches passing close); the branches there are not proven", point, ball)
    return (f"{what} (not proven)", point, math.inf)


def other_chart(a, b, topology, scale, tolerance):
    """The general search with the other surface as its chart, where an apex or a pole of the search's chart P lies
    on the curve (among topology.apexes): there P's chart collapses and no tube passes, while in the other chart the
    apex is a point of the level like any node, whose runs the tubes prove on either side. None where there is no
    such apex, the other chart's search stops, or its chart collapses at one of those apexes too (two cones
    sharing their apex)."""
    if topology is None or topology.chart is None or not collapses_at(topology.chart, topology.apexes, scale):
        return None
    try:
        other = search(a, b, scale, tolerance, general=True, chart_of=topology.Q)
    except (TopologyError, ValueError):
        return None
    if other.chart is None or collapses_at(other.chart, topology.apexes, scale):
        return None
    return other


def collapses_at(chart, points, scale):
    """True when the chart (a Surface in the chart searched) collapses within APEX_SHARED x scale of one of the
    points (3,): its apex, or a pole."""
    collapsed = points_at(chart, [(0.0, v) for v in chart.traits.collapse_lines(chart)])
    return any(np.linalg.norm(x - np.asarray(p)) <= APEX_SHARED * scale for x in collapsed for p in points)


def complete_claim(topology, chart, tubes, curves, trims, unsupported, ends, isolated=()):
    """No component missed: every verified root box of the searches inside a proven piece, inside the box of an
    isolated singular point (isolated: scaled boxes (4,) holding nothing of the intersection but that point's
    ball, which the singular claim reports) or proven outside Q's trims, the roots on Q's trim edges counted against
    the proven crossings there (trims.q_edge_roots), and no unresolved box outside those isolated boxes."""
    if topology is None or topology.mode not in SEARCHED:
        return claim("complete", [("no search was run (closed form)", None)], "")
    failures = []
    if topology.mode != "general" and not exactly_symmetric(topology.P, topology.Q):
        failures.append((f"the search read the pair as {topology.mode} (a common axis or direction decided within a "
                         "tolerance): its completeness holds for an exact symmetry only", None))
    proven = [t for t in tubes if t is not None and t.proven]
    pieces = np.concatenate([t.pieces for t in proven]) if proven else np.empty((0, kt.WIDTH))
    q_trims = [e for e in trims if e.owner == "Q"]
    for found in topology.root_boxes:
        reader = found.reader
        for box in found.unresolved:
            if reader.s is chart.p and within_isolated(chart, box, isolated):
                continue
            failures.append(("the search left a box it could neither exclude nor verify (a singular point)",
                             reader.s.point(0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3]))))
        if not len(found.verified):
            continue
        if reader.s is not chart.p:
            failures += q_edge_roots(chart, topology, found, trims, unsupported, ends, candidate_boxes)
            continue
        for i, raw in enumerate(found.verified):
            if not any(kt.point_in_pieces(pieces, len(pieces), chart.scaled_boxes(box), chart.periods[0],
                                          chart.periods[1]) >= 0 or outside(chart.reader, box, q_trims)
                       or within_isolated(chart, box, isolated) for box in candidate_boxes(found, i)):
                failures.append(("a root of the search lies in no proven tube",
                                 chart.p.point(0.5 * (raw[0] + raw[1]), 0.5 * (raw[2] + raw[3]))))
    for what, where in topology.skipped:
        failures.append((f"the search left out {what}", where))
    for reader, fixed, value, t0, t1 in topology.whole_lines:
        failures.append(("a parameter line lies on the other surface (not proven)", None))
    text = ("the search found no root: the trimmed surfaces have no common point" if not curves else
            "every root of the search lies on a returned curve")
    if isolated:
        text += " or in the ball of an isolated singular point (see the singular claim)"
    return claim("complete", failures, text)


def candidate_boxes(found, i):
    """Boxes that hold root i of a search (RootBoxes): its verified box, then smaller ones round its refined root,
    each inside the verified box and proven by the search's own kernel to hold exactly one root and nothing
    unresolved (so the verified box's only root is in it)."""
    box = found.verified[i]
    yield box
    r = found.reader
    root = found.roots[i]
    out = np.empty((16, 4))
    kinds = np.empty(16, dtype=np.int64)
    for rel in SHRINK:
        if found.kind == "line":
            fixed, value = found.args[:2]
            j = 1 - fixed
            eps = rel * max(1.0, abs(root[j]))
            lo, hi = max(box[2 * j], root[j] - eps), min(box[2 * j + 1], root[j] + eps)
            if not lo < hi:
                return
            n, status, _ = ks.line_roots(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, fixed, value, lo, hi,
                                         1e-6 * (hi - lo), 0.0, SHRINK_BOXES, out, kinds)
            small = box.copy()
            small[2 * j], small[2 * j + 1] = lo, hi
        else:
            du, dv = found.args
            small = box.copy()
            for j in range(2):
                eps = rel * max(1.0, abs(root[j]))
                small[2 * j], small[2 * j + 1] = max(box[2 * j], root[j] - eps), min(box[2 * j + 1], root[j] + eps)
            if not (small[0] < small[1] and small[2] < small[3]):
                return
            width = 1e-6 * np.array([small[1] - small[0], small[3] - small[2]])
            n, status, _ = ks.extremal_points(r.s.data, r.t.data, r.m, r.c, r.pad, r.cpad, du, dv, small, width,
                                              0.0, SHRINK_BOXES, out, kinds)
        if status == ks.DONE and n == 1 and kinds[0] == ks.VERIFIED:
            yield small


def exactly_symmetric(p, q):
    """True for a pair whose symmetry holds exactly whatever the placement: two spheres (about the line through
    their centres) or a sphere and a plane (about the normal through the centre)."""
    kinds = sorted(type(s).__name__ for s in (p, q))
    return kinds in (["Sphere", "Sphere"], ["Plane", "Sphere"])


def within_isolated(chart, raw, isolated):
    """True when the raw parameter box (4,) of the chart lies strictly inside one of the isolated boxes (scaled),
    also shifted by whole periods."""
    box = chart.scaled_boxes(raw)
    for iso in isolated:
        for su, sv in chart.shifts(iso, box):
            slack = 1e-12 * (1.0 + abs(su) + abs(sv) + float(np.max(np.abs(iso))))
            if (iso[0] + slack < box[0] + su and box[1] + su < iso[1] - slack and
                    iso[2] + slack < box[2] + sv and box[3] + sv < iso[3] - slack):
                return True
    return False


def distinct_claim(chart, tubes, boxes=None, nodes=(), uses=None):
    """The curves' tubes pairwise disjoint (pieces_overlap, with whole periods of the chart); a contact point's
    isolation box (boxes: {curve index: scaled box (4,)}) stands for its tube, and the boxes of the nodes a curve
    passes (nodes: NodeBox) belong to its tube. Two curves through one node are distinct where both are proven one
    component each passing the node by its arcs (uses: {curve index: {node index: [pairs]}}, from
    spatialkin.tracing.certify.nodes.passages) and, at some node they share, by different arcs: a whole component
    meets the node's box in the arcs its passages take, and the two arcs are disjoint; else not proven."""
    uses = uses or {}
    boxes = boxes or {}
    pieces = [t.pieces if t is not None and t.proven else box_piece(boxes[i]) if i in boxes else None
              for i, t in enumerate(tubes)]
    for i, t in enumerate(tubes):
        if t is not None and t.proven and t.passes:
            pieces[i] = np.concatenate([t.pieces] + [box_piece(n.box) for n in nodes if n.index in t.passes])
    failures = []
    for i in range(len(tubes)):
        for j in range(i + 1, len(tubes)):
            if pieces[i] is None or pieces[j] is None:
                failures.append((f"curves {i} and {j}: a tube is not proven", None))
                continue
            shared = tubes[i].passes & tubes[j].passes if tubes[i] is not None and tubes[j] is not None else ()
            if shared:
                apart = i in uses and j in uses and any(not set(uses[i].get(n, ())) & set(uses[j].get(n, ()))
                                                        for n in shared)
                if not apart:
                    failures.append((f"curves {i} and {j} meet at a node, where which branches join is not decided",
                                     None))
                continue
            hit = overlapping(chart, pieces[i], pieces[j])
            if hit is not None:
                failures.append((f"the tubes of curves {i} and {j} overlap", hit))
    return claim("distinct", failures, "the curves' tubes are pairwise disjoint")


def box_piece(box):
    """A scaled box (4,) as a piece (1, WIDTH): the parallelogram along u, T its u half-width, W its v half-width."""
    piece = np.zeros((1, kt.WIDTH))
    piece[0, kt.CU], piece[0, kt.CV] = 0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3])
    piece[0, kt.P], piece[0, kt.Q] = 1.0, 0.0
    half_u, half_v = 0.5 * (box[1] - box[0]), 0.5 * (box[3] - box[2])
    piece[0, kt.T0], piece[0, kt.T1], piece[0, kt.H] = -half_u * (1 + 1e-15), half_u * (1 + 1e-15), half_v * (1 + 1e-15)
    return piece


def overlapping(chart, first, second):
    """A point (3,) where a piece of first may overlap one of second (shifted by whole periods), or None."""
    i, _ = kt.tubes_disjoint(first, second, chart.periods)
    if i < 0:
        return None
    raw = first[i, [kt.CU, kt.CV]] * chart.units
    return chart.p.point(raw[0], raw[1])
