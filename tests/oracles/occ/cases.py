"""OpenCascade's own surface-surface intersection tests, translated into spatialkin cases with independent truths.

Each ``Case`` names the OCCT test script it comes from (a path in github.com/Open-Cascade-SAS/OCCT), builds the two
surfaces in OpenCascade's conventions (``draw.Geo``: the DRAW command's own arguments) and in spatialkin's
(``draw.to_sk``), and carries the truth: the connected components of the intersection (their lengths, whether
each is closed, its free ends) and the isolated contact points, computed without spatialkin or OpenCascade
(``truth``: closed forms, or an exact sweep measured at 60 digits whose results are stored in ``STORED`` near
the end of this file by ``python -m tests.oracles.occ.truth``). ``method`` says which. ``XFAIL`` (written by ``python
compare.py --xfail``) names the runs spatialkin fails, by failure class.

The truth is the intersection of the two faces as the script builds them; it is never OpenCascade's output
(OpenCascade splits closed loops at its seams, so its curve counts are not component counts).

Conventions of the translation (tests/oracles/occ/draw.py): DRAW's ``cone`` radius is the radius at the placement's origin, not
at the apex; a placement given by its normal only takes OpenCascade's X direction (gp_Ax3); a left-handed
placement (after ``tmirror``) is flipped into a proper rotation with the same surface; a ``mkface``/``trim``
bound is mapped to spatialkin's range (a cone's v along the generatrix becomes the axial distance from the apex).
An angular trim (``trimu``, a ``pcylinder``'s or ``ptorus``'s angle) is spatialkin's u_range; a disc or an
annulus (a primitive's cap, a revolved segment normal to the axis, a ``mkface`` of a circle) is a plane's radius
and inner_radius; a face spatialkin has no form for (an elliptic cylinder) or an unbounded intersection makes the
script ``NOT_EXPRESSIBLE``. spatialkin needs one bounded surface: when both are unbounded and the intersection is
bounded, one is trimmed along its axis to a range that contains the whole intersection with margin (``bound``; the
truth has no end on it).

References
----------
Open CASCADE Technology test scripts, tests/lowalgos/intss, tests/boolean/bsection, tests/boolean/bopsection,
tests/bugs/modalg_*; github.com/Open-Cascade-SAS/OCCT.
"""
import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from . import draw as D
from . import truth as T

#: Where the scripts are.
OCCT = "github.com/Open-Cascade-SAS/OCCT"

METHOD_CLOSED = "closed form"
METHOD_MERIDIAN = ("exact sweep by the generators of the first surface (quadratic roots in closed form), "
                   "lengths by tanh-sinh quadrature at 60 digits")
METHOD_PARALLEL = ("exact sweep by planes normal to the parallel axes (circle-circle intersections in closed "
                   "form), lengths by tanh-sinh quadrature at 60 digits")
METHOD_REVOLUTIONS = ("exact sweep by the spheres about the point where the two axes of revolution meet (each "
                      "sphere cuts each face in a parallel; two parallels meet in closed form), lengths by tanh-sinh "
                      "quadrature at 60 digits")
METHOD_TORUS_PLANES = ("closed-form reduction to torus sections by central planes, each parametrised by the tube "
                       "angle; lengths by tanh-sinh quadrature at 60 digits")


# --- the truth ------------------------------------------------------------------------------------------------------
class Component:
    """One connected component of the truth: its length, whether it is closed, its free ends, and a way to draw it
    (polylines(tol) -> list of (n, 3) arrays whose chords stay within tol of the curve)."""

    def __init__(self, length, closed, polylines, ends=(), nodes=(), label="", distance=None):
        self.length = float(length)
        self.distance = distance             # exact distance from a point, for closed forms joined to sweeps
        self.closed = bool(closed)
        self._polylines = polylines
        self.ends = [np.asarray(e, dtype=float) for e in ends]
        self.nodes = [np.asarray(e, dtype=float) for e in nodes]
        self.label = label

    def polylines(self, tol):
        return self._polylines(tol)

    def __repr__(self):
        return f"Component({self.label or ''} length={self.length:.12g}, closed={self.closed})"


class Truth:
    def __init__(self, components=(), points=(), coincident=False):
        self.components = list(components)
        self.points = [np.asarray(p, dtype=float) for p in points]
        self.coincident = coincident

    @property
    def count(self):
        return len(self.components) + len(self.points)

    @property
    def total_length(self):
        return sum(c.length for c in self.components)


def _count(length, step, minimum=16):
    return max(minimum, int(math.ceil(length / step)) + 1)


def _arc_step(radius, tol):
    """The chord length whose sag on a circle of this radius is tol."""
    return math.sqrt(8.0 * radius * tol) if tol < radius else radius


def circle(centre, normal, radius, arc=None, label="circle"):
    """A circle, or the arc between angles arc[0] < arc[1] (from the fixed in-plane axis of
    truth.circle_points)."""
    span = 2 * math.pi if arc is None else arc[1] - arc[0]
    length = radius * span
    pts = T.circle_points(centre, normal, radius, 3, arc)
    ends = () if arc is None else (pts[0], pts[-1])
    c, n = np.asarray(centre, dtype=float), np.asarray(normal, dtype=float) / np.linalg.norm(normal)

    def distance(p):                         # to the whole circle
        q = np.asarray(p, dtype=float) - c
        h = q @ n
        return math.hypot(np.linalg.norm(q - h * n) - radius, h)
    return Component(length, arc is None,
                     lambda tol: [T.circle_points(centre, normal, radius, _count(length, _arc_step(radius, tol)), arc)],
                     ends, label=label, distance=distance if arc is None else None)


def segment(p0, p1, label="segment"):
    p0, p1 = np.asarray(p0, dtype=float), np.asarray(p1, dtype=float)
    length = float(np.linalg.norm(p1 - p0))
    d = p1 - p0

    def distance(p):
        t = min(1.0, max(0.0, float((np.asarray(p, dtype=float) - p0) @ d / (d @ d))))
        return float(np.linalg.norm(p0 + t * d - p))
    return Component(length, False, lambda tol: [T.segment_points(p0, p1, 2)], (p0, p1), label=label,
                     distance=distance)


# --- truth specifications --------------------------------------------------------------------------------------------
@dataclass
class Closed:
    """A closed-form truth: components and isolated points."""
    components: list = field(default_factory=list)
    points: list = field(default_factory=list)

    def truth(self, case):
        return Truth(self.components, self.points)


@dataclass
class Coincident:
    """The two faces share a piece of surface: spatialkin must raise CoincidentSurfacesError."""
    where: str = ""

    def truth(self, case):
        return Truth(coincident=True)


@dataclass
class Swept:
    """A truth measured by truth.analyse over these sweeps; its results are STORED[case.id]."""
    sweeps: list
    extra_t: dict = None
    curves: list = field(default_factory=list)      # closed-form curves joining the swept pieces (Component)
    zoom: dict = None                               # {sweep: [(t0, t1)]} scanned on a finer grid too

    def analyse(self, case):
        a, b = case.geos()
        return T.analyse(self.sweeps, T.trims_of([("a", a), ("b", b)]), case.scale, self.extra_t,
                         curves=[(c.length, c.distance, c.label, [] if c.closed else c.ends) for c in self.curves],
                         surfaces=(a, b), zoom=self.zoom)

    def truth(self, case):
        stored = STORED.get(case.id)
        if stored is None:
            raise LookupError(f"{case.id}: no stored truth (run python -m tests.oracles.occ.truth)")
        comps = []
        for c in stored["components"]:
            def polylines(tol, c=c):
                out = []
                for piece in c["pieces"]:
                    if piece[0] == "curve":
                        out += self.curves[piece[1]].polylines(tol)
                        continue
                    s, k, t0, t1 = piece
                    k = tuple(k) if isinstance(k, list) else k
                    out.append(T.sample_piece(self.sweeps[s], k, t0, t1, tol))
                return out
            comps.append(Component(c["length"], c["closed"], polylines, c["ends"], c["nodes"]))
        return Truth(comps, [p["point"] for p in stored["points"]])


# --- the cases -------------------------------------------------------------------------------------------------------
@dataclass
class Case:
    id: str
    source: str                 # path of the OCCT script
    make: object                # () -> (Geo a, Geo b, truth specification)
    method: str
    note: str = ""
    xfail: dict = field(default_factory=dict)      # {"ab"/"ba": failure class} of the runs spatialkin fails
    _built: tuple = None

    def _build(self):
        if self._built is None:
            self._built = self.make()
        return self._built

    def geos(self):
        a, b, _ = self._build()
        return a, b

    def spec(self):
        return self._build()[2]

    def surfaces(self):
        a, b = self.geos()
        return D.to_sk(a), D.to_sk(b)

    @property
    def scale(self):
        """spatialkin's scene scale: the smaller characteristic length of the two surfaces (draw.scale)."""
        found = [s for s in (D.scale(g) for g in self.geos()) if s is not None]
        return min(found) if found else 1.0

    def truth(self):
        return self.spec().truth(self)


CASES = []
NOT_EXPRESSIBLE = []            # (script, what, why)


def case(id, source, method, note="", xfail=None):
    def deco(make):
        CASES.append(Case(id, source, make, method, note, dict(xfail or {})))
        return make
    return deco


def not_expressible(source, what, why):
    NOT_EXPRESSIBLE.append((source, what, why))


def bound_cylinder(g, lo, hi):
    """An unbounded cylinder trimmed to v in [lo, hi], a range containing the whole intersection (see module)."""
    return g.with_ranges(g.u_range, (lo, hi), bound="v")


def bound_cone(g, lo, hi):
    """An unbounded cone trimmed to the axial range [lo, hi] from its apex (spatialkin's v), as OCC's v range."""
    a, big_r = g.params["angle"], g.params["radius"]
    vs = sorted((h * math.tan(abs(a)) - big_r) / math.sin(a) for h in (lo, hi))
    return g.with_ranges(g.u_range, tuple(vs), bound="v")


def rects(*geos):
    """(o, x, y, u_range, v_range) of planar faces, for truth.clip_segment_to_rectangles."""
    out = []
    for g in geos:
        o, x, y, _ = g.axes
        out.append((o, x, y, g.u_range, g.v_range))
    return out


def discs(*geos):
    """(o, x, y, radius, inner_radius) of the planar faces bounded by a circle, for truth.clip_line_to_discs."""
    out = []
    for g in geos:
        if g.kind == "plane" and "radius" in g.params:
            o, x, y, _ = g.axes
            out.append((o, x, y, g.params["radius"], g.params.get("inner_radius")))
    return out


# --- closed forms shared by several cases -----------------------------------------------------------------------------
def plane_plane(a, b, label=""):
    """Two planar faces (rectangles, strips): the exact segment, point, coincidence or nothing."""
    oa, xa, ya, za = a.axes
    ob, xb, yb, zb = b.axes
    scale = max(1.0, float(np.abs(np.concatenate([oa, ob])).max()))
    eps = 1e-12 * scale
    d = np.cross(za, zb)
    if np.linalg.norm(d) < 1e-14:
        if abs((ob - oa) @ za) > eps:
            return Closed()
        return _coplanar(a, b, eps)
    d /= np.linalg.norm(d)
    # a point on both planes: least norm solution of [za; zb] p = [za.oa; zb.ob]
    m = np.vstack([za, zb])
    p = np.linalg.lstsq(m, np.array([za @ oa, zb @ ob]), rcond=None)[0]
    span = T.clip_segment_to_rectangles(p, d, rects(a, b))
    if span is None:
        return Closed()
    return segments_in_discs(p, d, [span], discs(a, b), eps, label)


def segments_in_discs(p, d, spans, circles, eps, label=""):
    """The pieces s in spans of the line p + s d (unit d) inside the discs and annuli (truth.clip_line_to_discs):
    segments, or points where a piece is shorter than eps."""
    out = Closed()
    for lo, hi in spans:
        for s0, s1 in T.clip_line_to_discs(p, d, circles, lo, hi) if circles else [(lo, hi)]:
            if not (math.isfinite(s0) and math.isfinite(s1)):
                raise ValueError("unbounded line")
            if s1 - s0 <= eps:
                out.points.append(p + 0.5 * (s0 + s1) * d)
            else:
                out.components.append(segment(p + s0 * d, p + s1 * d, label))
    return out


def _coplanar(a, b, eps):
    """Coplanar faces: an overlap of positive area is a coincidence; an edge or a corner in common is a segment or a
    point (exact clipping of b's rectangle by a's, in a's coordinates)."""
    oa, xa, ya, _ = a.axes
    ob, xb, yb, _ = b.axes

    def corners(g):
        o, x, y, _ = g.axes
        (u0, u1), (v0, v1) = g.u_range, g.v_range
        return [o + u * x + v * y for u, v in ((u0, v0), (u1, v0), (u1, v1), (u0, v1))]
    poly = [np.array([(p - oa) @ xa, (p - oa) @ ya]) for p in corners(b)]
    (u0, u1), (v0, v1) = a.u_range, a.v_range
    for axis, lo, hi in ((0, u0, u1), (1, v0, v1)):
        for bound, sign in ((lo, 1), (hi, -1)):
            out = []
            for i in range(len(poly)):
                p, q = poly[i], poly[(i + 1) % len(poly)]
                fp, fq = sign * (p[axis] - bound), sign * (q[axis] - bound)
                if fp >= -eps:
                    out.append(p)
                if (fp < -eps < fq) or (fq < -eps < fp):
                    out.append(p + (q - p) * (fp / (fp - fq)))
            poly = out
            if not poly:
                return Closed()
    pts = np.array(poly)
    area = 0.5 * abs(sum(p[0] * q[1] - q[0] * p[1] for p, q in zip(pts, np.roll(pts, -1, axis=0))))
    if area > eps * eps * 1e6:
        return Coincident("coplanar faces overlapping in an area")
    dist = np.linalg.norm(pts[:, None] - pts[None], axis=2)
    i, j = np.unravel_index(np.argmax(dist), dist.shape)
    g = lambda uv: oa + uv[0] * xa + uv[1] * ya
    if dist[i, j] <= eps:
        return Closed(points=[g(pts[0])])
    return Closed([segment(g(pts[i]), g(pts[j]), "common edge")])


def circle_in_faces(centre, normal, radius, faces):
    """The parts of a circle inside planar faces (closed trims: rectangles, and discs or annuli in the circle's
    plane): arcs, the whole circle, or single touching points."""
    c = np.asarray(centre, dtype=float)
    n = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    pts = T.circle_points(c, n, radius, 5)
    ex = (pts[0] - c) / radius
    ey = np.cross(n, ex)
    cons = []                            # A cos t + B sin t + C >= 0
    rims = []
    for f in faces:                      # discs and annuli, in the circle's plane
        if f.kind == "plane" and "radius" in f.params:
            fo, fx, fy, fz = f.axes
            if np.linalg.norm(np.cross(fz, n)) > 1e-12 or abs((c - fo) @ fz) > 1e-12 * max(1.0, radius):
                raise ValueError("circle_in_faces: a disc's circle must lie in its plane")
            make, hypot_inside = T.disc_limits(fo, fx, fy, f.params["radius"], f.params.get("inner_radius"))
            cons += make(c, ex, ey, radius)
            rims.append(hypot_inside)
    for o, x, y, ur, vr in rects(*faces):
        for axis, rng in ((x, ur), (y, vr)):
            if rng is None:
                continue
            for bound, sign in ((rng[0], 1), (rng[1], -1)):
                if math.isfinite(bound):
                    cons.append((sign * radius * (ex @ axis), sign * radius * (ey @ axis),
                                 sign * ((c - o) @ axis - bound)))
    cuts, touches = [0.0, 2 * math.pi], []
    for a, b, cc in cons:
        r = math.hypot(a, b)
        phase = math.atan2(b, a)            # a cos t + b sin t = r cos(t - phase)
        if r == 0:
            continue
        q = -cc / r
        if abs(abs(q) - 1) <= 1e-13:
            touches.append((phase if q > 0 else phase + math.pi) % (2 * math.pi))
        elif abs(q) < 1:
            w = math.acos(q)
            cuts += [(phase + w) % (2 * math.pi), (phase - w) % (2 * math.pi)]
    cuts = sorted(set(cuts + touches))
    inside = lambda t: (all(a * math.cos(t) + b * math.sin(t) + cc >= -1e-12 * radius for a, b, cc in cons)
                        and all(h(c + radius * (math.cos(t) * ex + math.sin(t) * ey), 1e-12 * radius) for h in rims))
    arcs = [(t0, t1) for t0, t1 in zip(cuts[:-1], cuts[1:]) if t1 - t0 > 1e-15 and inside(0.5 * (t0 + t1))]
    angle = lambda t: tuple(c + radius * (math.cos(t) * ex + math.sin(t) * ey))
    if not arcs:
        on = [t for t in touches if inside(t)]
        return Closed(points=[np.array(angle(t)) for t in on])
    if len(arcs) == len(cuts) - 1:
        return Closed([circle(c, n, radius, label="circle")])
    merged = [arcs[0]]                      # a cut where the circle only touches a trim edge is no end
    for t0, t1 in arcs[1:]:
        if t0 - merged[-1][1] <= 1e-15:
            merged[-1] = (merged[-1][0], t1)
        else:
            merged.append((t0, t1))
    arcs = merged
    if len(arcs) > 1 and arcs[0][0] <= 1e-15 and arcs[-1][1] >= 2 * math.pi - 1e-15:     # across 0 = 2 pi
        first = arcs.pop(0)
        last = arcs.pop()
        arcs.append((last[0], first[1] + 2 * math.pi))
    comps = []
    for t0, t1 in arcs:
        comps.append(_arc(c, ex, ey, n, radius, t0, t1))
    return Closed(comps)


def _arc(c, ex, ey, n, radius, t0, t1):
    length = radius * (t1 - t0)

    def poly(tol):
        t = np.linspace(t0, t1, _count(length, _arc_step(radius, tol)))
        return [c + radius * (np.cos(t)[:, None] * ex + np.sin(t)[:, None] * ey)]
    p0 = c + radius * (math.cos(t0) * ex + math.sin(t0) * ey)
    p1 = c + radius * (math.cos(t1) * ex + math.sin(t1) * ey)
    return Component(length, False, poly, (p0, p1), label="arc")


def sphere_plane(s, p):
    """A sphere and a planar face: the circle (or its arcs inside the face), a touching point, or nothing."""
    c = np.array(s.o)
    o, x, y, z = p.axes
    dist = (c - o) @ z
    r = s.params["r"]
    if abs(dist) > r:
        return Closed()
    centre = c - dist * z
    if abs(dist) == r:
        return Closed(points=[centre])
    rho = math.sqrt(r * r - dist * dist)
    return circle_in_faces(centre, z, rho, [p])


# === tests/lowalgos/intss ============================================================================================
INTSS = "tests/lowalgos/intss/"


@case("intss/bug23177_1", INTSS + "bug23177_1", METHOD_CLOSED)
def _():
    t = D.torus("100 10")
    p = D.plane("0 0 0 0 1 0")
    # the plane y = 0 holds the axis: the two meridian circles of the tube
    return t, p, Closed([circle((100, 0, 0), (0, 1, 0), 10), circle((-100, 0, 0), (0, 1, 0), 10)])


@case("intss/bug23177_2", INTSS + "bug23177_2", METHOD_CLOSED)
def _():
    t = D.torus("100 10")
    p = D.plane("0 0 0 1 0 0")
    return t, p, Closed([circle((0, 100, 0), (1, 0, 0), 10), circle((0, -100, 0), (1, 0, 0), 10)])


@case("intss/bug24648", INTSS + "bug24648", METHOD_CLOSED,
      note="cone 60 0: semi-angle 60 degrees, radius 0 at the origin, so the apex is the torus's centre; coaxial "
           "surfaces meet in parallels: r = sqrt(3)|z| and (r - 30)^2 + z^2 = 400 give 4 z^2 - 60 sqrt(3) z + 500 "
           "= 0 on each nappe")
def _():
    c = D.cone("60 0")
    t = D.torus("30 20")
    comps = []
    for sign in (1, -1):
        disc = math.sqrt(10800.0 - 8000.0)
        for z in ((60 * math.sqrt(3) + disc) / 8, (60 * math.sqrt(3) - disc) / 8):
            comps.append(circle((0, 0, sign * z), (0, 0, 1), math.sqrt(3) * z))
    return c, t, Closed(comps)


def _cone_sphere_21494(face):
    # pcone 15 0 10: semi-angle atan(-15/10), radius 15 at z = 0, apex (0, 0, 10); psphere 10.
    # r = 1.5 (10 - z) and r^2 + z^2 = 100: 3.25 z^2 - 45 z + 125 = 0, z = 10 (the apex) or z = 50/13.
    c = D.pcone_lateral(15, 0, 10)
    if not face:
        c = c.with_ranges(None, None)               # mksurface: the untrimmed conical surface
    s = D.psphere_face(10)
    truth = Closed([circle((0, 0, 50 / 13), (0, 0, 1), 120 / 13)], points=[(0, 0, 10)])
    return c, s, truth


@case("intss/bug21494_1", INTSS + "bug21494_1", METHOD_CLOSED,
      note="faces: the cone's lateral face z in [0, 10] and the whole sphere; the apex (0, 0, 10) lies on the "
           "sphere and is an isolated contact (inside the sphere below it, outside above)")
def _():
    return _cone_sphere_21494(True)


@case("intss/bug21494_2", INTSS + "bug21494_2", METHOD_CLOSED,
      note="mksurface: the untrimmed double cone and the sphere; the apex is an isolated contact point")
def _():
    return _cone_sphere_21494(False)


@case("intss/bug26008", INTSS + "bug26008", METHOD_CLOSED)
def _():
    a = D.sphere("78.4160443343, 8.94293392454, 70.9553808628 6.5")
    b = D.sphere("82.5593917073, 4.52613090823, 76.3299967 3.5")
    ca, cb = np.array(a.o), np.array(b.o)
    d = float(np.linalg.norm(cb - ca))
    h = (d * d + 6.5 ** 2 - 3.5 ** 2) / (2 * d)
    n = (cb - ca) / d
    return a, b, Closed([circle(ca + h * n, n, math.sqrt(6.5 ** 2 - h * h))])


@case("intss/bug370", INTSS + "bug370", METHOD_CLOSED,
      note="plane x = 0 with X = (0, 0, 1), Y = (0, -1, 0) (gp_Ax3's rule), trimmed to u in [0, 1.000001], "
           "v in [-1, 0.000001]: z in [0, 1.000001], y in [-0.000001, 1]; the unit circle's arc from (0, 1, 0) "
           "(a corner of the rectangle, where the circle is tangent to its edge y = 1) to y = -1e-6, length "
           "pi/2 + asin(1e-6)")
def _():
    s = D.sphere("1")
    p = D.trim(D.plane("0 0 0 1 0 0"), 0, 1.000001, -1, 0.000001)
    return s, p, sphere_plane(s, p)


@case("intss/bug26576_4", INTSS + "bug26576_4", METHOD_CLOSED,
      note="revsurf of the half circle (centre (1.5, 3.125, 0), radius 0.25) about its own diameter is the sphere "
           "of that centre and radius; the plane z = 0 holds the centre: a great circle")
def _():
    s = D.sphere("1.5 3.125 0 0.25")
    p = D.plane("3.48352775473762 1.7282347013387 0 0 0 -1 -1 0 0")
    return s, p, Closed([circle((1.5, 3.125, 0), (0, 0, 1), 0.25)])


@case("intss/bug23644", INTSS + "bug23644", METHOD_CLOSED,
      note="lateral faces of pcone 10 0 20 and pcone 20 0 20: coaxial cones of different angles with the same "
           "apex (0, 0, 20), which is all they share")
def _():
    a = D.pcone_lateral(10, 0, 20)
    b = D.pcone_lateral(20, 0, 20)
    return a, b, Closed(points=[(0, 0, 20)])


@case("intss/bug27623", INTSS + "bug27623", METHOD_CLOSED,
      note="s1: z = 0, x, y in [-10, 10]; s2: x = 0 with X = (0, 0, 1), Y = (0, -1, 0), z = 10 + u in "
           "[1e-5, 20]: the faces are 1e-5 apart and do not meet")
def _():
    a = D.trim(D.plane("0 0 0 0 0 1 1 0 0"), -10, 10, -10, 10)
    b = D.trim(D.plane("0 0 10 1 0 0 0 0 1"), -10 + 1.0e-5, 10, -10 + 1.0e-5, 10)
    return a, b, plane_plane(a, b)


@case("intss/bug20766", INTSS + "bug20766", METHOD_CLOSED,
      note="OCC20766 plane 1 0 0 3522.43 is x + 3522.43 = 0, through the apex of the cone (radius 0 at its "
           "origin); the axis is 44.5 degrees from the plane, more than the semi-angle 26.75: only the apex. Both "
           "are unbounded: the cone is bounded to axial [-5000, 5000] around the apex")
def _():
    p = D.plane("-3522.4299999999998 0 0 1 0 0")
    semi = 0.46689346637921703 / 0.017453292519943295
    c = D.cone(f"-3522.4299999999998 2540 -1461.4300000000001 5449.7857099692965 0 5537.6938973109054 "
               f"{semi!r} 0")
    c = bound_cone(c, -5000.0, 5000.0)
    return p, c, Closed(points=[tuple(c.apex)])


@case("intss/bug30082_2", INTSS + "bug30082_2", METHOD_MERIDIAN,
      note="the thin cylinder's far side is tangent to the big one from inside (2.75 + 0.25 = 3): two loops "
           "meeting at one point; s1 is bounded to v in [-30, -10] (the loops span v in [-21.5, -15.5])")
def _():
    s1 = D.cylinder("-106.471129473161 -64.3442185874231 -19.25 1 0 0 0 0 -1 0.25")
    s2 = D.cylinder("-124.971129473161 -67.0942185874231 -20.5 0 0 1 1 0 -0 3")
    s1 = bound_cylinder(s1, -30.0, -10.0)
    return s1, s2, Swept([T.Meridian(s1, s2)])


@case("intss/bug23178", INTSS + "bug23178", METHOD_MERIDIAN,
      note="perpendicular axes 5 apart, radii 10 and 5: the small cylinder touches the big one from inside; s2 is "
           "bounded to v in [-40, 40]")
def _():
    s1 = D.cylinder("4.999999999813, 1.35836143386791, 0.20975890778078 -1, 0, 0 0, 0, 1 10")
    s2 = D.cylinder("9.999999999813, 9.1401960568287, 0.11837300583107 0, -0.75870713028692, 0.651431877061437 "
                    "0, -0.651431877061437, -0.75870713028692 5")
    s2 = bound_cylinder(s2, -40.0, 40.0)
    return s2, s1, Swept([T.Meridian(s2, s1)])


@case("intss/bug28222_3", INTSS + "bug28222_3", METHOD_MERIDIAN,
      note="the axis of the thin cylinder (radius 0.001) is a tangent line of the big one (x = -9): one small "
           "loop; s1 is bounded to v in [-6, -4] (y in [-1, 1])")
def _():
    s1 = D.cylinder("-9 -5 -2.2058 0 -1 0 0.001")
    s2 = D.cylinder("0 0 -2.2058 0 0 -1 9")
    s1 = bound_cylinder(s1, -6.0, -4.0)
    return s1, s2, Swept([T.Meridian(s1, s2)])


@case("intss/bug28222_2", INTSS + "bug28222_2", METHOD_MERIDIAN,
      note="perpendicular axes 5 apart, radii 11 and 16.5: the thin one enters and leaves the big one, two loops; "
           "s1 is bounded to v in [-100, 100]")
def _():
    s1 = D.cylinder("-35 13.3706576198285 30.5814570420266 0 -0.258819045102521 -0.965925826289068 "
                    "0 0.965925826289068 -0.258819045102521 11")
    s2 = D.cylinder("0 0 0 1 0 0 0 0 -1 16.5")
    s1 = bound_cylinder(s1, -100.0, 100.0)
    return s1, s2, Swept([T.Meridian(s1, s2)])


@case("intss/bug29807_i5002", INTSS + "bug29807_i5002", METHOD_PARALLEL,
      note="two cones with parallel axes (semi-angles 80 and 5 degrees, radii at their origins); one small loop "
           "on each nappe of the flat cone; s2 is bounded to axial [-20, 20] from its apex")
def _():
    s1 = D.cone("11.4307383137554 3.49999999999979 -89.7537975119388 0 0 1 1 0 0 "
                "80.000725670142287835190342147806 9.45659107381736")
    s2 = D.cone("-3.6479413426839 -11.578679656441 -89.9782110643133 0 0 1 0 1 0 5 0.250951325477062")
    s2 = bound_cone(s2, -20.0, 20.0)
    return s1, s2, Swept([T.Parallel(s1, s2, T.axial_range(s1, s2))])


@case("intss/bug29972_3", INTSS + "bug29972_3", METHOD_PARALLEL,
      note="torus and cylinder with parallel axes; the cylinder (radius r = 10) is centred on the torus's tube "
           "circle (distance 23 = R), so at the torus's equator it touches the tube inside and outside")
def _():
    t = D.torus("-127 84 100 0 0 -1 1 0 0 23 10")
    c = D.cylinder("-132 61.5500556793564 131 0 0 -1 1 0 0 10")
    return t, c, Swept([T.Parallel(t, c, T.axial_range(t, c))])


@case("intss/bug24418_2", INTSS + "bug24418_2", METHOD_PARALLEL,
      note="mksurface of the quarter torus (ptorus 25 24 90) then trimu 0 pi/2; the cone (pcone on the plane "
           "(20, 20, 10): radius 10 to 8 over 40) trimmed to its face, v in [0, 40.05]. The torus's u trim cuts "
           "nothing (the cone lies in x, y in [10, 30])")
def _():
    t = D.ptorus_face(25, 24, angle_deg=90.0)
    t = t.with_ranges((0.0, 1.5707963267948966), None)
    c = D.pcone_lateral(10, 8, 40, place=D.place_of(D.plane("20 20 10 0 0 1")))
    c = c.with_ranges(None, (0.0, 40.049968789001575))
    return t, c, Swept([T.Parallel(t, c, T.axial_range(t, c))])


@case("intss/bug23163_1", INTSS + "bug23163_1", METHOD_PARALLEL + "; the circle of tangency in closed form",
      note="two equal tori (20, 5) with parallel axes 40 apart: their tube circles touch at (20, 0, 0), so the "
           "tori are tangent along the whole meridian circle there (centre (20, 0, 0), radius 5, in y = 0), and "
           "cross in two arcs in the plane x = 20 that meet that circle at (20, 0, +-5)")
def _():
    a = D.torus("20 5")
    b = D.torus("40 0 0 20 5")
    sweep = T.Parallel(a, b, T.axial_range(a, b), branches=[(0, 0, 1), (0, 0, -1)])
    tangent = circle((20, 0, 0), (0, 1, 0), 5, label="circle of tangency")
    return a, b, Swept([sweep], curves=[tangent])


@case("intss/bug27227", INTSS + "bug27227", METHOD_TORUS_PLANES,
      note="ptorus 100 20 and its copy turned 90 degrees about x: subtracting the equations leaves "
           "-200 (rho_z - rho_y) = 0, i.e. y = +-z, so the intersection is the first torus cut by the planes "
           "y = z and y = -z: near x = 100 and x = -100 two ovals each, crossing at (+-80, 0, 0) and (+-120, 0, 0)")
def _():
    a = D.ptorus_face(100, 20)
    b = a.rotated((0, 0, 0), (1, 0, 0), 90)
    sweeps = [T.TorusCentralPlane(a, (0, 1, -1)), T.TorusCentralPlane(a, (0, 1, 1))]
    return a, b, Swept(sweeps, extra_t={0: [math.pi], 1: [math.pi]})


def _bug26509(p1_ops, p2_ops):
    """bug26509_*: p1_2 is the inner cylinder (radius 65) of the annulus swept 1000 along y and turned 180 degrees
    about z; p2_1 the lateral face of the disc (radius 50) swept 4000 along z (its placement left-handed, as
    OpenCascade builds it), both full turns with their axial trims."""
    p1 = D.Geo("cylinder", (0.0, 0.0, 0.0), (0.0, 0.0, -1.0), (-1.0, 1.2246467991473532e-16, 0.0),
               (1.2246467991473532e-16, 1.0, 0.0), {"r": 65.0}, u_range=(0.0, 2 * math.pi),
               v_range=(-1000.0, 0.0))
    p2 = D.Geo("cylinder", (50.0, 500.0, -2000.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, -1.0), {"r": 50.0},
               u_range=(0.0, 2 * math.pi), v_range=(-4000.0, 0.0))
    p2 = p2.rotated((0, 500, 0), (1, 0, 0), -77).rotated((0, 0, 0), (0, 0, 1), 180)
    for op in p1_ops:
        p1 = op(p1)
    for op in p2_ops:
        p2 = op(p2)
    return p1, p2, Swept([T.Meridian(p1, p2)])


_R90 = 1.57079632679489655800 * 180 / math.pi
_AX = (1.22464679914735e-16, 1, 0)
_P2_OWN = lambda g: g.rotated((-49.9999999999998, 1448.74012957047, -449.90210868773),
                              (1.19325918102424e-16, 0.974370064785235, -0.224951054343865),
                              -1.26610367277949897868 * 180 / math.pi)
_BUG26509_NOTE = ("the same two trimmed cylinders in every variant (the extra turns are about the cylinders' own "
                  "axes, and the mirror in the mid-plane of p1_2 maps it onto itself; the left-handed placement is "
                  "flipped into a proper rotation); only the seams move. OCC checks a section length of 1881.92")

for _name, _p1, _p2 in (
        ("bug26509_1", [], []),
        ("bug26509_2", [lambda g: g.rotated((0, 0, 0), _AX, -_R90)], []),
        ("bug26509_3", [lambda g: g.rotated((0, 0, 0), _AX, _R90)], []),
        ("bug26509_4", [lambda g: g.rotated((0, 0, 0), _AX, _R90), lambda g: g.mirrored((0, -500, 0), (0, 1, 0))],
         []),
        ("bug26509_5", [], [_P2_OWN]),
        ("bug26509_6", [lambda g: g.rotated((0, 0, 0), _AX, -_R90)], [_P2_OWN])):
    case("intss/" + _name, INTSS + _name, METHOD_MERIDIAN, note=_BUG26509_NOTE)(
        lambda _p1=_p1, _p2=_p2: _bug26509(_p1, _p2))


not_expressible(INTSS + "bug21750", "two cylinders (radius 76.5) with parallel axes 1.54 apart",
                "the intersection is two whole lines (unbounded); spatialkin needs a bounded surface and any trim "
                "would change the answer")
not_expressible(INTSS + "bug25782_2", "two cylinders (radii 5 and 4) with parallel axes",
                "the intersection is two whole lines (unbounded)")
not_expressible(INTSS + "bug25818", "two untrimmed plane faces (z = 0 and x = 0)", "the intersection is a whole line")
not_expressible(INTSS + "bug24313", "extrusion of a circle (a cylinder of radius 100 about z) and the plane x = 0",
                "the plane holds the axis: two whole lines")
not_expressible(INTSS + "bug33244", "two untrimmed cones with parallel axes and equal semi-angles to 3.5e-11",
                "the intersection has unbounded branches")


@case("intss/bug31552", INTSS + "bug31552", METHOD_MERIDIAN,
      note="s1 (radius 347.85 about the vertical through (0, 557.8), u in [3.2385, 6.28319], z in [-39.957, "
           "39.957]) and s2 (radius 88.5 about a horizontal axis, a 10-degree strip u in [6.19592, 6.37045], "
           "v in [0, 10.0002]): two short open curves, where s2's strip crosses s1's face")
def _():
    s1 = D.trim(D.cylinder("0 557.800010681152 0 0 0 1 0 1 0  347.850006103516"), 3.2385, 6.28319, -39.957, 39.957)
    s2 = D.trim(D.cylinder("5.45639675193397 189.209310035068 0 -0.254420004160252 0.96709382248213 0 "
                           "0.96709382248213 0.254420004160252 0 88.5"), 6.19592, 6.37045, 0, 10.0002)
    return s2, s1, Swept([T.Meridian(s2, s1)])


@case("intss/bug32850", INTSS + "bug32850", METHOD_MERIDIAN,
      note="two cylinders of equal radius 408.97 whose axes (along y and along x) meet at z = -373.97: the "
           "untrimmed ones meet in two ellipses crossing at the top point (25.81, 1974.19, 35.00), where the "
           "cylinders are tangent. The narrow strips u in [0, 0.0225] (1.3 degrees, starting 1.7e-6 rad on the "
           "far side of the top) hold the four branches from that point: one 13 long, three about 1e-3 (OCC "
           "expects four curves)")
def _():
    s1 = D.trim(D.cylinder("25.8071575178163 0 -373.974517822281 0 1 0 -1.73024882663956e-06 0 0.999999999998503 "
                           "408.974517822893"), 0, 0.0225015452057227, -146.010003766057, 2146.01000376606)
    s2 = D.trim(D.cylinder("0 1974.19284248218 -373.974517822281 1 0 0 -0 1.73024882663956e-06 0.999999999998503 "
                           "408.974517822893"), 0, 0.0225015452057227, -146.010003766057, 946.010003766057)
    return s1, s2, Swept([T.Meridian(s1, s2, orthonormal=True)], zoom={0: [(0.0, 1e-5)]})
not_expressible(INTSS + "bug27937_2", "extrusion of an ellipse and a cylinder",
                "an elliptic cylinder is no spatialkin surface")
not_expressible(INTSS + "buc60815", "two identical extrusions of a segment along (1, 1, 1)",
                "the faces are a slanted infinite strip (not a rectangle of a plane) given twice, both unbounded")


# === tests/boolean ===================================================================================================
@case("bsection/Q3:lateral", "tests/boolean/bsection/Q3", METHOD_CLOSED,
      note="pcylinder 10 20 and pcylinder 5 20 moved by (5, 0, 10): parallel axes 5 apart, 10 - 5 = 5, so the "
           "lateral faces are tangent along the line (10, 0, z), z in [10, 20]")
def _():
    a = D.pcylinder_lateral(10, 20)
    b = D.pcylinder_lateral(5, 20).translated((5, 0, 10))
    return a, b, Closed([segment((10, 0, 10), (10, 0, 20), "line of tangency")])


@case("bsection/S1:lateral", "tests/boolean/bsection/S1", "coincidence: the same cylinder, axial overlap [50, 100]",
      note="pcylinder 20 100 and its copy moved by 50 along the axis: the lateral faces share z in [50, 100]")
def _():
    a = D.pcylinder_lateral(20, 100)
    b = D.pcylinder_lateral(20, 100).translated((0, 0, 50))
    return a, b, Coincident("lateral faces overlap in z in [50, 100]")


def _a1_faces():
    # prism of the square x = 0, y in [-1, 1], z in [0, 2] along (1, 0, 0): the box [0, 1] x [-1, 1] x [0, 2]
    return {"x=0": D.rectangle((0, -1, 0), (0, 2, 0), (0, 0, 2), "x=0"),
            "x=1": D.rectangle((1, -1, 0), (0, 2, 0), (0, 0, 2), "x=1"),
            "z=0": D.rectangle((0, -1, 0), (1, 0, 0), (0, 2, 0), "z=0"),
            "y=1": D.rectangle((0, 1, 0), (1, 0, 0), (0, 0, 2), "y=1"),
            "z=2": D.rectangle((0, -1, 2), (1, 0, 0), (0, 2, 0), "z=2"),
            "y=-1": D.rectangle((0, -1, 0), (1, 0, 0), (0, 0, 2), "y=-1")}


_A1_TRUTH = {
    "x=0": lambda: Closed([segment((0, -1, 0), (0, -1, 2), "line"), segment((0, 1, 0), (0, 1, 2), "line")]),
    "x=1": lambda: Closed([segment((1, 0, 0), (1, 0, 2), "line of tangency")]),
    "y=1": lambda: Closed([segment((0, 1, 0), (0, 1, 2), "line of tangency on the face's edge")]),
    "y=-1": lambda: Closed([segment((0, -1, 0), (0, -1, 2), "line of tangency on the face's edge")]),
    "z=0": None, "z=2": None}
_A1_NOTE = {
    "x=0": "the plane of the axis cuts the cylinder in the lines y = +-1, which are the face's edges",
    "x=1": "a tangent plane: the line of tangency (1, 0, z) crosses the face",
    "y=1": "a tangent plane whose line of tangency (0, 1, z) is the face's edge x = 0",
    "y=-1": "a tangent plane whose line of tangency (0, -1, z) is the face's edge x = 0",
    "z=0": "the cylinder's rim circle z = 0: the half x >= 0 lies in the face, tangent to its edge x = 1",
    "z=2": "the half circle x >= 0 at z = 2, tangent to the face's edge x = 1, ending at its corners"}

for _f in ("x=0", "x=1", "y=1", "y=-1", "z=0", "z=2"):
    def _mk(f=_f):
        cyl = D.pcylinder_lateral(1, 4)
        face = _a1_faces()[f]
        truth = _A1_TRUTH[f]() if _A1_TRUTH[f] else circle_in_faces((0, 0, float(f[2:])), (0, 0, 1), 1.0, [face])
        return cyl, face, truth
    case(f"bopsection/A1:lateral*{_f}", "tests/boolean/bopsection/A1", METHOD_CLOSED, note=_A1_NOTE[_f])(_mk)

_Z = (0.0, 0.0, 1.0)


@case("bsection/Q3:c1.top*c2.lateral", "tests/boolean/bsection/Q3", METHOD_CLOSED,
      note="c1's top disc (z = 20, radius 10 about the axis) against c2's lateral face (radius 5 about (5, 0), z "
           "in [10, 30]): the whole circle of radius 5 at z = 20, inside the disc, touching its rim at (10, 0, 20) "
           "(with the line of tangency of the lateral faces it makes OCC's 41.4159; the other pairs of faces are "
           "parallel planes or apart)")
def _():
    disc = D.disc((0, 0, 20), _Z, 10, label="c1.top")
    b = D.pcylinder_lateral(5, 20).translated((5, 0, 10))
    return disc, b, circle_in_faces((5, 0, 20), _Z, 5.0, [disc])


@case("bsection/Q3:c1.lateral*c2.bottom", "tests/boolean/bsection/Q3", METHOD_CLOSED,
      note="c1's lateral face (radius 10) against c2's bottom disc (z = 10, radius 5 about (5, 0)): the plane "
           "cuts the cylinder in the circle of radius 10, which touches the disc's rim at (10, 0, 10) only")
def _():
    a = D.pcylinder_lateral(10, 20)
    disc = D.disc((5, 0, 10), _Z, 5, label="c2.bottom")
    return a, disc, circle_in_faces((0, 0, 10), _Z, 10.0, [disc])


@case("bsection/S1:c1.lateral*c2.bottom", "tests/boolean/bsection/S1", METHOD_CLOSED,
      note="c2's bottom disc (z = 50, radius 20) against c1's lateral face (radius 20, z in [0, 100]): the "
           "circle of radius 20 at z = 50, the disc's rim")
def _():
    a = D.pcylinder_lateral(20, 100)
    disc = D.disc((0, 0, 50), _Z, 20, label="c2.bottom")
    return a, disc, circle_in_faces((0, 0, 50), _Z, 20.0, [disc])


@case("bsection/S1:c1.top*c2.lateral", "tests/boolean/bsection/S1", METHOD_CLOSED,
      note="c1's top disc (z = 100, radius 20) against c2's lateral face (z in [50, 150]): the disc's rim")
def _():
    disc = D.disc((0, 0, 100), _Z, 20, label="c1.top")
    b = D.pcylinder_lateral(20, 100).translated((0, 0, 50))
    return disc, b, circle_in_faces((0, 0, 100), _Z, 20.0, [disc])


_A1_BOTTOM_NOTE = {
    "x=0": "the cylinder's bottom disc (z = 0, radius 1) against the face x = 0 (y in [-1, 1], z in [0, 2]): the "
           "disc's diameter along y, which is the face's edge z = 0",
    "x=1": "the bottom disc against the face x = 1: the line x = 1, z = 0 (the face's edge) touches the disc's rim "
           "at (1, 0, 0)",
    "y=1": "the bottom disc against the face y = 1: the face's edge z = 0 touches the rim at its corner (0, 1, 0)",
    "y=-1": "the bottom disc against the face y = -1: the face's edge z = 0 touches the rim at its corner "
            "(0, -1, 0)"}
for _f in ("x=0", "x=1", "y=1", "y=-1"):
    def _mk(f=_f):
        disc = D.disc((0, 0, 0), _Z, 1.0, label="bottom")
        face = _a1_faces()[f]
        return disc, face, plane_plane(disc, face)
    case(f"bopsection/A1:bottom*{_f}", "tests/boolean/bopsection/A1", METHOD_CLOSED, note=_A1_BOTTOM_NOTE[_f])(_mk)


@case("bopsection/A1:bottom*z=0", "tests/boolean/bopsection/A1",
      "coincidence: the half disc x >= 0 of the cylinder's bottom lies in the box's face z = 0",
      note="the bottom disc (z = 0, radius 1) and the box's face z = 0 ([0, 1] x [-1, 1]) overlap in the half "
           "disc x >= 0 (the top disc, z = 4, is above the box)")
def _():
    return D.disc((0, 0, 0), _Z, 1.0, label="bottom"), _a1_faces()["z=0"], Coincident("the half disc x >= 0")


@case("bsection/P9", "tests/boolean/bsection/P9", METHOD_CLOSED,
      note="the square z = 0, [-1, 1]^2 (mkface fa pl -1 1 -1 1) and the disc of radius 0.5 about (0.5, 0.5, 0) "
           "in the plane of normal (sin 80 sin 20, sin 80 cos 20, cos 80) (degrees; mkface of the circle): the "
           "disc's diameter along the planes' common line, inside the square; OCC checks a length of 1")
def _():
    az, dip = math.radians(20.0), math.radians(80.0)
    n = (math.sin(dip) * math.sin(az), math.sin(dip) * math.cos(az), math.cos(dip))
    a = D.trim(D.plane("0 0 0 0 0 1"), -1, 1, -1, 1)
    b = D.disc((0.5, 0.5, 0.0), n, 0.5, label="fb")
    return a, b, plane_plane(a, b)


# === tests/bugs/modalg_* ============================================================================================
BUGS = "tests/bugs/"


def _psphere_plane_x2():
    s = D.psphere_face(10)
    p = D.trim(D.plane("2 0 0 1 0 0"), -100, 100, -100, 100)
    return s, p, sphere_plane(s, p)


case("bugs/bug28094", BUGS + "modalg_6/bug28094", METHOD_CLOSED,
     note="psphere 10 and the face x = 2, [-100, 100]^2: the circle of radius sqrt(96)")(_psphere_plane_x2)
case("bugs/bug22990", BUGS + "modalg_2/bug22990", METHOD_CLOSED,
     note="the same geometry as bug28094")(_psphere_plane_x2)


for _name, _apex2, _len in (("bug28626_2", "-23 -20 10", 88.9692), ("bug28626_3", "-22 -20 10", 94.3164)):
    def _mk(apex2=_apex2):
        # trimv 0 42.4264068711929 on 45-degree cones with radius 0 at the origin: axial [0, 30] from the apex
        a = D.cone("0 0 0  0 -1 0  45  0").with_ranges(None, (0.0, 42.4264068711929))
        b = D.cone(f"{apex2}  1 0 0  45  0").with_ranges(None, (0.0, 42.4264068711929))
        return a, b, Swept([T.Meridian(a, b)])
    case("bugs/" + _name, BUGS + "modalg_6/" + _name, METHOD_MERIDIAN,
         note=f"two one-nappe cone faces (45 degrees, axial length 30) with perpendicular axes; OCC checks a "
              f"section length of {_len}")(_mk)


def _coaxial_cones(args1, args2):
    """mkface c 0 2pi 0 1e6 of two cones with radius 0 at their origins on one axis (to 1e-13): one circle where
    tan(a1) (s - s1) = tan(a2) (s - s2) along the common axis."""
    a = D.cone(args1).with_ranges((0.0, 2 * math.pi), (0.0, 1e6))
    b = D.cone(args2).with_ranges((0.0, 2 * math.pi), (0.0, 1e6))
    pa, pb = np.array(a.o), np.array(b.o)
    z = np.array(a.z) / np.linalg.norm(a.z)
    ta, tb = math.tan(a.params["angle"]), math.tan(b.params["angle"])
    sb = float((pb - pa) @ z)                    # b's apex along a's axis
    s = -tb * sb / (ta - tb)                     # ta s = tb (s - sb)
    return a, b, Closed([circle(pa + s * z, z, ta * s)])


case("bugs/bug29807_svm01", BUGS + "modalg_7/bug29807_svm01", METHOD_CLOSED,
     note="coaxial cones (axis (0, -1, 1.1e-16), apexes 959 apart along it to 1e-13), one nappe each: one "
          "circle; OCC checks 2202.91")(
    lambda: _coaxial_cones("0 518.47000000000003 0 0 -1 1.1102230246251565e-016 14.999999999912038 0",
                           "0 -440.74363604000001 0 0 -1 1.1102230246251565e-016 45.110284878807235 0"))
case("bugs/bug29807_svm02", BUGS + "modalg_7/bug29807_svm02", METHOD_CLOSED,
     note="coaxial cones, one nappe each: one circle; OCC checks 1993.34")(
    lambda: _coaxial_cones("0 -60.919306349999999 0 0 -1 1.1102230246251565e-016 28.800000000062262 0",
                           "0 -309.47272469000001 0 0 -1 1.1102230246251565e-016 43.999999999485127 0"))


def _revolved_cone(axis_point, axis_dir, p, q, label):
    """The face swept by the segment p-q turning about an axis (p, q in a plane of the axis): the cone through
    them, trimmed to the segment (radius 0 at the placement's origin: the apex)."""
    o = np.asarray(axis_point, dtype=float)
    w = np.asarray(axis_dir, dtype=float) / np.linalg.norm(axis_dir)
    p, q = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    zp, zq = (p - o) @ w, (q - o) @ w
    rp, rq = np.linalg.norm((p - o) - zp * w), np.linalg.norm((q - o) - zq * w)
    if rq < rp:
        p, q, zp, zq, rp, rq = q, p, zq, zp, rq, rp
    slope = (rq - rp) / (zq - zp)                 # dr/dz along w
    zapex = zp - rp / slope
    axis = w if slope > 0 else -w
    apex = o + zapex * w
    ang = math.atan(abs(slope))
    h0, h1 = sorted((abs(zp - zapex), abs(zq - zapex)))
    _, x, y, z = D.ax3(apex, axis)
    g = D.Geo("cone", tuple(apex), tuple(x), tuple(y), tuple(z), {"angle": ang, "radius": 0.0},
              v_range=(h0 / math.cos(ang), h1 / math.cos(ang)), label=label)
    return g


def _bug13211_faces():
    pts = [(136.06, 187.51), (136.06, 143.01), (128.08, 143.01), (127.88, 164.75), (116.11, 176.00)]
    edges = [(pts[i], pts[(i + 1) % 5]) for i in range(5)]
    r1 = {f"e{i + 1}": _revolved_cone((153.08, 143.01, 0), (1, 0, 0), (*e[0], 0), (*e[1], 0), f"r1.e{i + 1}")
          for i, e in enumerate(edges) if i in (2, 3, 4)}
    r2 = {f"e{i + 1}": _revolved_cone((136.06, 68.01, 0), (0, 1, 0), (*e[0], 0), (*e[1], 0), f"r2.e{i + 1}")
          for i, e in enumerate(edges) if i in (2, 3, 4)}
    return r1, r2


_PENTAGON = [(136.06, 187.51, 0.0), (136.06, 143.01, 0.0), (128.08, 143.01, 0.0), (127.88, 164.75, 0.0),
             (116.11, 176.00, 0.0)]
_Q13211 = (136.06, 143.01, 0.0)                  # where the two axes (y = 143.01 and x = 136.06 in z = 0) meet

for _i in ("e3", "e4", "e5"):
    for _j in ("e3", "e4", "e5"):
        def _mk(i=_i, j=_j):
            r1, r2 = _bug13211_faces()
            ki, kj = int(i[1]) - 1, int(j[1]) - 1
            seg_i = (_PENTAGON[ki], _PENTAGON[(ki + 1) % 5])
            seg_j = (_PENTAGON[kj], _PENTAGON[(kj + 1) % 5])
            if i == j:          # the common edge: both faces contain it and are tangent along it
                same = [(k1, k2, s) for k1 in (1, -1) for k2 in (1, -1) for s in (1, -1) if k1 != k2]
                sweep = T.CoplanarRevolutions(_Q13211, (1, 0, 0), seg_i, (0, 1, 0), seg_j, branches=same)
                return r1[i], r2[j], Swept([sweep], curves=[segment(*seg_i, label="common edge (tangency)")])
            sweep = T.CoplanarRevolutions(_Q13211, (1, 0, 0), seg_i, (0, 1, 0), seg_j)
            return r1[i], r2[j], Swept([sweep])
        case(f"bugs/bug13211_6:r1.{_i}*r2.{_j}", BUGS + "modalg_1/bug13211_6", METHOD_REVOLUTIONS,
             note="a pentagon of the plane z = 0 revolved about x (r1) and about y (r2), the axes meeting at "
                  "(136.06, 143.01, 0): the faces swept by its edges e3, e4, e5 are cone faces (e1 of r1 and e2 of "
                  "r2 sweep discs; e2 of r1 and e1 of r2 lie on the axes)"
                  + ("; both faces hold the edge itself and are tangent along it" if _i == _j else ""))(_mk)


def cone_in_axial_plane(cone, plane):
    """A cone face (radius 0 at its origin, v in [v0, v1] along the generatrix from the apex, full turn) and a
    planar face whose plane holds the cone's axis: the two generators in the plane, clipped by the planar face's
    rectangle and discs (occ_truth); generators meeting at the apex (v0 = 0) are one component."""
    apex, w = np.array(cone.o), np.array(cone.z)
    n = np.array(plane.axes[3])
    if abs(n @ w) > 1e-12 or abs((apex - np.array(plane.o)) @ n) > 1e-9:
        raise ValueError("the plane must hold the cone's axis")
    e = np.cross(n, w)
    e /= np.linalg.norm(e)
    ang = cone.params["angle"]
    v0, v1 = cone.v_range
    eps = 1e-12 * max(1.0, float(np.abs(apex).max()))
    pieces, points = [], []
    for side in (1.0, -1.0):
        d = math.cos(ang) * w + side * math.sin(ang) * e
        span = T.clip_segment_to_rectangles(apex, d, rects(plane), v0, v1)
        got = segments_in_discs(apex, d, [] if span is None else [span], discs(plane), eps)
        pieces += got.components
        points += got.points
    at_apex = [c for c in pieces if min(np.linalg.norm(p - apex) for p in c.ends) <= eps]
    if len(at_apex) == 2:                     # the two generators from the apex: one open polyline
        far = [max(c.ends, key=lambda p: np.linalg.norm(p - apex)) for c in at_apex]
        line = np.array([far[0], apex, far[1]])
        pieces = [c for c in pieces if c not in at_apex] + [
            Component(sum(c.length for c in at_apex), False, lambda tol, line=line: [line], far,
                      label="two generators meeting at the apex")]
    unique = []
    for p in points:
        if all(np.linalg.norm(p - q) > eps for q in unique) and \
                all(min(np.linalg.norm(p - q) for q in c.ends) > eps for c in pieces):
            unique.append(p)
    return Closed(pieces, unique)


def _bug13211_discs():
    """r1.e1, the disc e1 sweeps about x (plane x = 136.06, radius 44.5 about Q), and r2.e2, the disc e2 sweeps
    about y (plane y = 143.01, radius 7.98 about Q)."""
    q = np.array(_Q13211)
    return (D.disc(q, (1, 0, 0), _PENTAGON[0][1] - _Q13211[1], label="r1.e1"),
            D.disc(q, (0, 1, 0), _Q13211[0] - _PENTAGON[2][0], label="r2.e2"))


_BUG13211_DISC_NOTE = {
    "r1.e1*r2.e2": "the two discs, in the planes x = 136.06 and y = 143.01 through Q: the segment of their common "
                   "line within the smaller one, z in [-7.98, 7.98]",
    "r1.e1*r2.e3": "the plane of r1's disc holds r2's axis: it cuts r2's cone face e3 in two generators, both "
                   "inside the disc",
    "r1.e1*r2.e4": "two generators of r2's cone face e4, inside r1's disc",
    "r1.e1*r2.e5": "two generators of r2's cone face e5 meeting at its apex (136.06, 187.51, 0), the vertex where "
                   "the disc's rim and the cone face meet: one open curve",
    "r1.e3*r2.e2": "the plane of r2's disc holds r1's axis: r1's cone face e3 meets it in two generators from its "
                   "apex (128.08, 143.01, 0), which lies on the disc's rim; both leave the disc at once: that point",
    "r1.e4*r2.e2": "the generators of r1's cone face e4 in the plane y = 143.01 lie outside r2's disc",
    "r1.e5*r2.e2": "the generators of r1's cone face e5 in the plane y = 143.01 lie outside r2's disc"}

for _pair in _BUG13211_DISC_NOTE:
    def _mk(pair=_pair):
        r1, r2 = _bug13211_faces()
        d1, d2 = _bug13211_discs()
        i, j = (k.split(".")[1] for k in pair.split("*"))
        if i == "e1" and j == "e2":
            return d1, d2, plane_plane(d1, d2)
        if i == "e1":
            return d1, r2[j], cone_in_axial_plane(r2[j], d1)
        return r1[i], d2, cone_in_axial_plane(r1[i], d2)
    case(f"bugs/bug13211_6:{_pair}", BUGS + "modalg_1/bug13211_6", METHOD_CLOSED,
         note="the pentagon's edge e1 sweeps a disc about x (r1.e1: plane x = 136.06, radius 44.5 about "
              "(136.06, 143.01, 0)) and e2 a disc about y (r2.e2: plane y = 143.01, radius 7.98 about the same "
              "point); " + _BUG13211_DISC_NOTE[_pair])(_mk)


def _buc60899_polyline():
    n, dx, sx, sz = 2, 4, 1, 10
    x, y, z = 0.0, -50.0, 0.0
    pts = [(x, y, z)]
    for _ in range(n):
        for ddx, ddz in ((dx, 0), (sx, sz), (dx, 0), (sx, -sz)):
            x, z = x + ddx, z + ddz
            pts.append((x, y, z))
    return pts


def _buc60899_crg(k, extent):
    """Face k (1..8) of the prism of the polyline along y ('inf': unbounded), bounded to y in extent."""
    pts = _buc60899_polyline()
    p0, p1 = np.array(pts[k - 1]), np.array(pts[k])
    g = D.strip(p0, p1, (0, 1, 0), f"crg.s{k}")
    # v along y from the polyline at y = -50
    return g.with_ranges(g.u_range, (extent[0] + 50.0, extent[1] + 50.0), bound="v", label=g.label)


for _k in range(1, 9):
    def _mk(k=_k):
        # circle (10, 0, -30) radius 9, prism along z 'inf': the unbounded cylinder about x = 10, y = 0
        cyl = D.cylinder("10 0 -30 9")
        face = _buc60899_crg(k, (-20.0, 20.0))
        return face, cyl, Swept([T.Meridian(cyl, face)]) if k != 8 else Closed(points=[(19.0, 0.0, 10.0)])
    case(f"bugs/buc60899_1:crg.s{_k}*cyl", BUGS + "modalg_1/buc60899_1", METHOD_MERIDIAN if _k != 8 else
         METHOD_CLOSED,
         note="the zigzag polyline (0..20 in x, 0..10 in z at y = -50) swept along y, unbounded, against the "
              "cylinder of radius 9 about x = 10, y = 0; the strips are bounded to y in [-20, 20]"
              + ("; the face x in [19, 20] touches the cylinder only at its corner edge point (19, 0, 10)"
                 if _k == 8 else ""))(_mk)


def _buc60899_2_faces():
    xc, r, zc = 10.0, 9.0, -30.0
    ring = [(xc - r, -r * 2, zc), (xc + r, -r * 2, zc), (xc + r, r * 2, zc), (xc - r, r * 2, zc)]
    names = ["y=-18", "x=19", "y=18", "x=1"]
    tube = {}
    for i, nm in enumerate(names):
        g = D.strip(ring[i], ring[(i + 1) % 4], (0, 0, 1), f"cyl.{nm}")
        tube[nm] = g.with_ranges(g.u_range, (-10.0, 70.0), bound="v", label=g.label)   # z in [-40, 40]
    return tube


for _nm in ("x=1", "x=19", "y=-18", "y=18"):
    for _k in range(1, 9):
        def _mk(nm=_nm, k=_k):
            a = _buc60899_2_faces()[nm]
            b = _buc60899_crg(k, (-50.0, 50.0))
            return a, b, plane_plane(a, b)
        _a, _b, _t = _mk()
        if _t.components or _t.points:
            case(f"bugs/buc60899_2:{_nm}*crg.s{_k}", BUGS + "modalg_1/buc60899_2", METHOD_CLOSED,
                 note="the rectangle [1, 19] x [-18, 18] swept along z against the zigzag strips swept along y "
                      "(both unbounded; bounded to z in [-40, 40] and y in [-50, 50])")(_mk)


@case("bugs/bug28795", BUGS + "modalg_6/bug28795", METHOD_CLOSED,
      note="ab_2, the face x = 2 of box 0 -1 -1 2 2 2, against pryz_1, the side face y = -0.5 of the semi-infinite "
           "prism of the unit box's face x = -0.5 along x (OpenCascade's face: u in [0, 1], v in [-1e100, 0], an "
           "unbounded v here): the segment x = 2, y = -0.5, z in [-0.5, 0.5]")
def _():
    a = D.Geo("plane", (2.0, -1.0, -1.0), (0.0, 0.0, 1.0), (0.0, -1.0, 0.0), (1.0, 0.0, 0.0), {},
              u_range=(0.0, 2.0), v_range=(-2.0, 0.0), label="ab_2")
    b = D.Geo("plane", (-0.5, -0.5, -0.5), (0.0, 0.0, 1.0), (-1.0, 0.0, 0.0), (0.0, -1.0, 0.0), {},
              u_range=(0.0, 1.0), v_range=(-math.inf, 0.0), label="pryz_1")
    return a, b, plane_plane(a, b)


@case("bugs/bug23881:f1*pl", BUGS + "modalg_5/bug23881", METHOD_CLOSED,
      note="the unit square z = 0, x, y in [0, 1] and the whole plane y = 1: the square's edge y = 1")
def _():
    a = D.rectangle((0, 0, 0), (1, 0, 0), (0, 1, 0), "f1")
    b = D.plane("0 1 0 0 1 0")
    return a, b, Closed([segment((0, 1, 0), (1, 1, 0), "edge")])


@case("bugs/bug23881:f2*pl", BUGS + "modalg_5/bug23881", METHOD_CLOSED,
      note="the square z = 0, x in [0, 1], y in [1, 2] and the plane y = 1: the square's edge y = 1")
def _():
    a = D.rectangle((0, 1, 0), (1, 0, 0), (0, 1, 0), "f2")
    b = D.plane("0 1 0 0 1 0")
    return a, b, Closed([segment((0, 1, 0), (1, 1, 0), "edge")])


@case("bugs/bug21564:1", BUGS + "modalg_5/bug21564", METHOD_CLOSED,
      note="the first face is a B-spline conversion of the plane z = 0 trimmed to [-10, 10]^2 (the same "
           "rectangle); the second x = 0 (X = (0, 0, 1), Y = (0, -1, 0)), [-10, 10]^2")
def _():
    a = D.trim(D.plane("0 0 0 0 0 1"), -10, 10, -10, 10)
    b = D.trim(D.plane("0 0 0 1 0 0"), -10, 10, -10, 10)
    return a, b, plane_plane(a, b)


@case("bugs/bug21564:2", BUGS + "modalg_5/bug21564", METHOD_CLOSED,
      note="the B-spline square z = 0, [-10, 10]^2, and the plane of normal (1, 2, 0), [-15, 15]^2 "
           "(X = (2, -1, 0)/sqrt 5 by gp_Ax3's rule)")
def _():
    a = D.trim(D.plane("0 0 0 0 0 1"), -10, 10, -10, 10)
    b = D.trim(D.plane("0 0 0 1 2 0"), -15, 15, -15, 15)
    return a, b, plane_plane(a, b)


def _box_cases(name, source, b1, b2, note):
    """Every pair of faces of two boxes (b1, b2: lists of six Geo) whose exact section is not empty."""
    for fa in b1:
        for fb in b2:
            truth = plane_plane(fa, fb)
            if isinstance(truth, Closed) and not truth.components and not truth.points:
                continue
            case(f"bugs/{name}:b1.{fa.label}*b2.{fb.label}", source, METHOD_CLOSED, note=note)(
                lambda fa=fa, fb=fb, truth=truth: (fa, fb, truth))


def _box(x0, y0, z0, dx, dy, dz, ops=()):
    faces = D.box_faces(x0, y0, z0, dx, dy, dz)
    for op in ops:
        faces = [op(f) for f in faces]
    return faces


_BOX = lambda: _box(0, 0, 0, 10, 10, 10)
_box_cases("bug25354_32", BUGS + "modalg_5/bug25354_32", _BOX(), _box(-10, -10, -10, 10, 10, 10),
           "b2 moved by (-10, -10, -10): the boxes share the corner (0, 0, 0)")
_box_cases("bug25354_33", BUGS + "modalg_5/bug25354_33", _BOX(),
           _box(5, -10, -10, 10, 10, 10, [lambda g: g.rotated((5, 0, 0), (0, 0, 1), -45)]),
           "b2 moved by (5, -10, -10) and turned -45 degrees about the vertical through (5, 0, 0): its edge "
           "touches b1's face y = 0 at (5, 0, 0)")
_box_cases("bug25354_34", BUGS + "modalg_5/bug25354_34", _BOX(),
           _box(5, -10, -4, 10, 10, 10, [lambda g: g.rotated((5, 0, 0), (0, 0, 1), -45),
                                         lambda g: g.rotated((5, 0, 0), (1, 0, 0), 45)]),
           "b2 moved by (5, -10, -4), turned -45 degrees about z then 45 about x through (5, 0, 0): a corner "
           "contact")
_box_cases("bug25354_35", BUGS + "modalg_5/bug25354_35", _BOX(), _box(-10, -10, -4, 10, 10, 10),
           "b2 moved by (-10, -10, -4): the boxes share the edge x = y = 0, z in [0, 6]")
_box_cases("bug25354_36", BUGS + "modalg_5/bug25354_36", _BOX(),
           _box(5, -10, -4, 10, 10, 10, [lambda g: g.rotated((5, 0, 0), (0, 0, 1), -45)]),
           "b2 moved by (5, -10, -4) and turned -45 degrees about the vertical through (5, 0, 0): its edge lies on "
           "b1's face y = 0 for z in [0, 6]")
_box_cases("bug25354_37", BUGS + "modalg_5/bug25354_37", _BOX(), _box(10, 3, 4, 10, 10, 10),
           "b2 moved by (10, 3, 4): the boxes touch on the face x = 10 (a coplanar overlap)")
_box_cases("bug25354_38", BUGS + "modalg_5/bug25354_38", _BOX(), _box(5, 3, 4, 10, 10, 10),
           "b2 moved by (5, 3, 4): overlapping boxes")
_box_cases("bug21264", BUGS + "modalg_7/bug21264", _BOX(), _box(5, 5, 5, 10, 10, 10),
           "boxes [0, 10]^3 and [5, 15]^3 (modalg_7/bug30206 and modalg_7/bug29973_2 section the same two boxes)")

#: Scripts whose geometry is that of cases already listed: (script, the cases' script).
SAME_AS = [(BUGS + "modalg_7/bug30206", BUGS + "modalg_7/bug21264"),
           (BUGS + "modalg_7/bug29973_2", BUGS + "modalg_7/bug21264"),
           (BUGS + "modalg_7/bug31858_2", BUGS + "modalg_7/bug31858_1")]


def _bug25354_49_face(family, j):
    """Face b_1 (x = 0), b_3 (y = 0) or b_5 (z = 0) of box 100 moved by 10 j along its normal."""
    faces = D.box_faces(0, 0, 0, 100, 100, 100)
    g = {"x": faces[0], "y": faces[2], "z": faces[4]}[family]
    shift = {"x": (10.0 * j, 0, 0), "y": (0, 10.0 * j, 0), "z": (0, 0, 10.0 * j)}[family]
    return dataclasses.replace(g.translated(shift), label=f"f{family}{j}")


for _j in range(1, 6):
    for _i in range(1, 11):
        def _mk(i=_i, j=_j):
            f = _bug25354_49_face("x", j)
            s = D.sphere(f"50 50 50 {5.0 * i}")
            return f, s, sphere_plane(s, f)
        case(f"bugs/bug25354_49:x{_j}*s{_i}", BUGS + "modalg_5/bug25354_49", METHOD_CLOSED,
             note="square faces x = 10 j ([0, 100]^2) against spheres of radius 5 i about (50, 50, 50); the pairs "
                  "j = 1..5 against every sphere cover every distinct plane-sphere configuration of the script "
                  "(the y and z faces and j = 6..9 repeat them by symmetry); tangent when 5 i = |10 j - 50|")(_mk)
for _fa, _fb in (("x", "y"), ("x", "z"), ("y", "z")):
    def _mk(fa=_fa, fb=_fb):
        a, b = _bug25354_49_face(fa, 3), _bug25354_49_face(fb, 6)
        return a, b, plane_plane(a, b)
    case(f"bugs/bug25354_49:{_fa}3*{_fb}6", BUGS + "modalg_5/bug25354_49", METHOD_CLOSED,
         note="two perpendicular square faces crossing along a whole side (every such pair of the script is "
              "congruent to one of these three)")(_mk)
case("bugs/bug25354_49:s3*s7", BUGS + "modalg_5/bug25354_49", METHOD_CLOSED,
     note="concentric spheres (radii 15 and 35): nothing")(
    lambda: (D.sphere("50 50 50 15"), D.sphere("50 50 50 35"), Closed()))


@case("bugs/bug31836:lateral*torus", BUGS + "modalg_7/bug31836", METHOD_CLOSED,
      note="pcone 282.84 100 300 moved by (100, 0, 0) and ptorus 80.25 19.75 moved by (100, 0, 300): coaxial; the "
           "torus's outer equator (radius R + r = 100 at z = 300) is the cone face's top rim, where the two cross; "
           "their other common parallel (z = 317.5) lies above the face (the top disc: bug31836:top*torus)")
def _():
    c = D.pcone_lateral(282.842712474619, 100, 300).translated((100, 0, 0))
    t = D.ptorus_face(80.2535587508467, 19.7464412491533).translated((100, 0, 300))
    rim = 80.2535587508467 + 19.7464412491533
    return c, t, Closed([circle((100, 0, 300), (0, 0, 1), rim, label="rim circle")])


def _bug31858():
    """pcylinder 500 200 and ptorus on the plane through (-2.3e-15, -4.5e-15, 200): R + r exceeds 500 by
    about 4e-13 as the floats add, so the torus's outer equator pokes through the cylinder and the two cross in two
    parallels at z = 200 +- sqrt(r^2 - (500 - R)^2) (6.4e-6 from the equator): the one below z = 200 lies on the
    lateral face. The axes are 5e-15 apart: the curve is that circle to 1e-14."""
    import mpmath as mp
    c = D.pcylinder_lateral(500, 200)
    t = D.ptorus_face(449.367136080235, 50.6328639197654,
                      place=D.place_of(D.plane("-2.31895142368858e-15 -4.49296838339662e-15 200 0 0 1")))
    with mp.workdps(40):
        big, small = mp.mpf(449.367136080235), mp.mpf(50.6328639197654)
        dz = mp.sqrt(small ** 2 - (500 - big) ** 2)
        z = float(200 - dz)
    return c, t, Closed([circle((0, 0, z), (0, 0, 1), 500.0, label="parallel just below the equator")])


case("bugs/bug31858_1", BUGS + "modalg_7/bug31858_1", METHOD_CLOSED,
     note=_bug31858.__doc__.split(":", 1)[1].strip() + " (modalg_7/bug31858_2 builds the same shapes)")(_bug31858)


@case("bugs/bug31858_1:top*torus", BUGS + "modalg_7/bug31858_1", METHOD_CLOSED,
      note="the cylinder's top disc (z = 200, radius 500) holds the torus's central plane: the inner equator "
           "(radius R - r = 398.734) lies in the disc; the outer one (R + r = 500 + 4e-13 as the floats add) "
           "lies on the disc's rim to 1e-12 of the radius, the truth's tolerance for a touch, and counts as in it")
def _():
    big, small = 449.367136080235, 50.6328639197654
    place = D.place_of(D.plane("-2.31895142368858e-15 -4.49296838339662e-15 200 0 0 1"))
    disc = D.disc((0, 0, 200), _Z, 500, label="top")
    t = D.ptorus_face(big, small, place=place)
    comps = circle_in_faces(place[0], _Z, big + small, [disc]).components
    comps += circle_in_faces(place[0], _Z, big - small, [disc]).components
    return disc, t, Closed(comps)


@case("bugs/bug29910_1", BUGS + "modalg_7/bug29910_1", METHOD_PARALLEL,
      note="ptorus 100 10 and its copy moved by (100, 0, 0): equal tori with parallel axes whose tube circles cross "
           "at (50, +-86.6, 0)")
def _():
    a = D.ptorus_face(100, 10)
    b = D.ptorus_face(100, 10).translated((100, 0, 0))
    return a, b, Swept([T.Parallel(a, b, T.axial_range(a, b))])


for _name, _r in (("outer", 75.0), ("inner", 65.0)):
    def _mk(r=_r):
        p1 = D.Geo("cylinder", (0.0, 0.0, 0.0), (0.0, 0.0, -1.0), (-1.0, 1.2246467991473532e-16, 0.0),
                   (1.2246467991473532e-16, 1.0, 0.0), {"r": r}, u_range=(0.0, 2 * math.pi), v_range=(-1000.0, 0.0))
        p2 = D.Geo("cylinder", (50.0, 500.0, -2000.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, -1.0),
                   {"r": 50.0}, u_range=(0.0, 2 * math.pi), v_range=(-4000.0, 0.0))
        p2 = p2.rotated((0, 500, 0), (1, 0, 0), -77).rotated((0, 0, 0), (0, 0, 1), 180)
        return p1, p2, Swept([T.Meridian(p1, p2)])
    case(f"bugs/bug24905:p1.{_name}*p2", BUGS + "modalg_7/bug24905", METHOD_MERIDIAN,
         note=f"the shapes of bug26509 as whole solids: the annulus's {_name} cylinder (radius {_r:g}) against the "
              "tilted cylinder (the annuli: bug24905:p1.annulus*)")(_mk)


def _bug24905_p2():
    p2 = D.Geo("cylinder", (50.0, 500.0, -2000.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, -1.0),
               {"r": 50.0}, u_range=(0.0, 2 * math.pi), v_range=(-4000.0, 0.0))
    return p2.rotated((0, 500, 0), (1, 0, 0), -77).rotated((0, 0, 0), (0, 0, 1), 180)


for _name, _y in (("y=0", 0.0), ("y=-1000", -1000.0)):
    def _mk(y=_y):
        annulus = D.disc((0.0, y, 0.0), (0, 1, 0), 75.0, inner_radius=65.0, label=f"p1.annulus {y:g}")
        p2 = _bug24905_p2()
        return annulus, p2, Swept([T.Meridian(p2, annulus)])
    case(f"bugs/bug24905:p1.annulus{_name}*p2", BUGS + "modalg_7/bug24905", METHOD_MERIDIAN,
         note=f"p1's annulus at {_name} (radii 65 and 75 about the y axis) against p2's lateral face: the arc of "
              "the ellipse the plane cuts from the tilted cylinder between two crossings of the outer rim (it "
              "stays outside the inner one); p2's discs lie 450 and more from p1")(_mk)


@case("bugs/bug31836:top*torus", BUGS + "modalg_7/bug31836", METHOD_CLOSED,
      note="the cone's top disc (z = 300, radius 100 about (100, 0)) holds the torus's central plane: the torus's "
           "two equators, radius R + r = 100 (the disc's rim) and R - r = 60.507, both in the disc (with the rim "
           "circle of the lateral face they make OCC's 1008.5; the bottom disc is 280 below the torus)")
def _():
    big, small = 80.2535587508467, 19.7464412491533
    disc = D.disc((100, 0, 300), _Z, 100, label="top")
    t = D.ptorus_face(big, small).translated((100, 0, 300))
    comps = circle_in_faces((100, 0, 300), _Z, big + small, [disc]).components
    comps += circle_in_faces((100, 0, 300), _Z, big - small, [disc]).components
    return disc, t, Closed(comps)


def _bug25354_50(i):
    face = D.box_faces(-5, -5, -5, 10, 10, 10)[5]               # the face z = 5 of the box [-5, 5]^3
    s = D.sphere(f"0 0 0 {i * 0.1 + 5.0!r}")
    return face, s, sphere_plane(s, face)


for _i in range(41):
    case(f"bugs/bug25354_50:Zmax*s{_i}", BUGS + "modalg_5/bug25354_50", METHOD_CLOSED,
         note="the face z = 5 of the box [-5, 5]^3 against spheres of radius 5 + 0.1 i about its centre (the other "
              "five faces are congruent): a touching point (i = 0), whole circles, circles cut into four arcs by "
              "the square's edges, then nothing")(lambda i=_i: _bug25354_50(i))


def _bug25614(which):
    # pcylinder 6 10 moved by (10, 10, -5) against the box b_1_1 = [10, 20] x [10, 20] x [-2, 2] of the grid
    cyl = D.pcylinder_lateral(6, 10).translated((10, 10, -5))
    box = {f.label: f for f in D.box_faces(10, 10, -2, 10, 10, 4)}
    face = box[which]
    if which in ("Zmin", "Zmax"):
        z = -2.0 if which == "Zmin" else 2.0
        return cyl, face, circle_in_faces((10, 10, z), (0, 0, 1), 6.0, [face])
    if which == "Xmin":
        return cyl, face, Closed([segment((10, 16, -2), (10, 16, 2), "line")])
    return cyl, face, Closed([segment((16, 10, -2), (16, 10, 2), "line")])


for _w in ("Xmin", "Ymin", "Zmin", "Zmax"):
    case(f"bugs/bug25614_section:cyl*b_1_1.{_w}", BUGS + "modalg_5/bug25614_section", METHOD_CLOSED,
         note="a grid of boxes 10 x 10 x 4 and a grid of cylinders (radius 6) about their common corners: each "
              "cylinder against the faces of one box next to it (every other pair repeats these by symmetry, or is "
              "empty); the planes x = 10 and y = 10 hold the axis, z = +-2 cut quarter circles")(
        lambda w=_w: _bug25614(w))


def _bug23932(r1, r2):
    """Two half cylinders (trimu 0 pi, mkface: unbounded along their axes) with perpendicular axes 102.51 apart:
    the thin one passes through the thick one, the untrimmed cylinders meet in two loops, and s1's half z >= 183.375
    cuts each in an open arc (s2's half z >= 80.865 holds all of s1). s1 is bounded to v in [-400, 150] (the loops
    span v in [-294, 62])."""
    pi = 3.1415926535897932
    s1 = D.cylinder(f"538.57646417050069, 347.77316708315834, 183.37500000000000 0 -1 0 1 0 0 {r1}")
    s1 = bound_cylinder(s1.with_ranges((0.0, pi), None), -400.0, 150.0)
    s2 = D.cylinder(f"859.00000000000011 463.75990629028450 80.865093709715211 -1 0 0 0 -1 0 {r2}")
    s2 = s2.with_ranges((0.0, pi), None)
    return s1, s2, Swept([T.Meridian(s1, s2)])


case("bugs/bug23932_1", BUGS + "modalg_5/bug23932_1", METHOD_MERIDIAN,
     note=_bug23932.__doc__.split(":", 1)[1].strip() + "; OCC checks 326.401")(
    lambda: _bug23932("44.194173824159222", "186.78835506149036"))
case("bugs/bug23932_2", BUGS + "modalg_5/bug23932_2", METHOD_MERIDIAN,
     note="as bug23932_1 with both radii 0.625 larger; OCC checks 330.903")(
    lambda: _bug23932("44.819173824159222", "187.41335506149036"))

for _src, _what, _why in (
        (BUGS + "modalg_1/buc60901", "a circle swept along a direction oblique to its plane",
         "an elliptic cylinder is no spatialkin surface"),
        (BUGS + "modalg_1/bug17194_1", "a half circle swept along an oblique direction",
         "an elliptic cylinder is no spatialkin surface"),
        (BUGS + "modalg_1/bug17194_2", "a half circle swept along an oblique direction",
         "an elliptic cylinder is no spatialkin surface"),
):
    not_expressible(_src, _what, _why)


#: Scripts with no data file that were read and set aside, and why (not a pair of analytic surfaces).
SET_ASIDE = [
    (INTSS + "begin", "helper procedures only"),
    (BUGS + "modalg_7/begin", "helper procedures only"),
    (BUGS + "modalg_6/bug27773", "an offset circle against a segment (curves, no surfaces)"),
    (BUGS + "modalg_6/bug8040", "circles against a segment (curves)"),
    (BUGS + "modalg_5/bug25354_39", "vertex against vertex"),
    (BUGS + "modalg_5/bug25354_40", "vertex against edge"),
    (BUGS + "modalg_5/bug25354_41", "vertex against edge"),
    (BUGS + "modalg_5/bug25354_45", "vertex against box"),
    (BUGS + "modalg_5/bug25354_46", "vertex against box"),
    (BUGS + "modalg_5/bug25354_47", "vertex against box"),
    (BUGS + "modalg_5/bug25354_48", "vertex against box"),
    (BUGS + "modalg_5/bug24758_2", "a swept (pipe) shell against a plane"),
    (BUGS + "modalg_5/bug23706_8", "a B-spline curve against a pipe surface"),
    (BUGS + "modalg_7/bug29530", "a line against a torus (a curve, not a surface)"),
]


# --- stored results of the sweeps (written by ``python -m tests.oracles.occ.truth``; do not edit by hand) ------------------------
# BEGIN STORED
STORED = {
 'bugs/buc60899_1:crg.s1*cyl': {
  'components': [
   {'length': 15.139236070222745, 'closed': False, 'end_trims': ['a.u<=4'],
    'ends': [
     (4.0, 6.708203932499369, 0.0),
     (4.0, -6.708203932499369, 0.0),],
    'nodes': [],
    'pieces': [
     (0, 0, '2.30052398302186298268611835145', '3.98266132415772349423916841511'),
    ]},
  ],
  'points': []},
 'bugs/buc60899_1:crg.s2*cyl': {
  'components': [
   {'length': 10.079931145634424, 'closed': False, 'end_trims': ['a.u<=10.0499', 'a.u>=0'],
    'ends': [
     (5.0, 7.483314773547883, 10.0),
     (4.0, 6.708203932499369, -7.46761833343337e-60),],
    'nodes': [],
    'pieces': [
     (0, 0, '2.15982729701117050794388360458', '2.30052398302186298268611835145'),
    ]},
   {'length': 10.079931145634424, 'closed': False, 'end_trims': ['a.u<=10.0499', 'a.u>=0'],
    'ends': [
     (4.0, -6.708203932499369, -1.9913648889155653e-59),
     (5.0, -7.483314773547883, 10.0),],
    'nodes': [],
    'pieces': [
     (0, 0, '3.98266132415772349423916841511', '4.12335801016841596898140316198'),
    ]},
  ],
  'points': []},
 'bugs/buc60899_1:crg.s3*cyl': {
  'components': [
   {'length': 4.29920960287779, 'closed': False, 'end_trims': ['a.u<=4', 'a.u>=0'],
    'ends': [
     (9.0, 8.94427190999916, 10.0),
     (5.0, 7.483314773547883, 10.0),],
    'nodes': [],
    'pieces': [
     (0, 0, '1.68213734113586051155305006365', '2.15982729701117050130082562077'),
    ]},
   {'length': 4.29920960287779, 'closed': False, 'end_trims': ['a.u<=4', 'a.u>=0'],
    'ends': [
     (5.0, -7.483314773547883, 10.0),
     (9.0, -8.94427190999916, 10.0),],
    'nodes': [],
    'pieces': [
     (0, 0, '4.12335801016841597562446114579', '4.60104796604372596537223670291'),
    ]},
  ],
  'points': []},
 'bugs/buc60899_1:crg.s4*cyl': {
  'components': [
   {'length': 10.050081887559903, 'closed': False, 'end_trims': ['a.u<=10.0499', 'a.u>=0'],
    'ends': [
     (10.0, 9.0, 4.971209395182531e-16),
     (9.0, 8.94427190999916, 10.0),],
    'nodes': [],
    'pieces': [
     (0, 0, '1.57079632679489662475488768629', '1.68213734113586051155305006365'),
    ]},
   {'length': 10.050081887559903, 'closed': False, 'end_trims': ['a.u<=10.0499', 'a.u>=0'],
    'ends': [
     (9.0, -8.94427190999916, 10.0),
     (10.0, -9.0, 4.971209395182531e-16),],
    'nodes': [],
    'pieces': [
     (0, 0, '4.60104796604372596537223670291', '4.71238898038468985217039908027'),
    ]},
  ],
  'points': []},
 'bugs/buc60899_1:crg.s5*cyl': {
  'components': [
   {'length': 4.144985925131902, 'closed': False, 'end_trims': ['a.u<=4', 'a.u>=0'],
    'ends': [
     (14.0, 8.06225774829855, 0.0),
     (10.0, 9.0, 0.0),],
    'nodes': [],
    'pieces': [
     (0, 0, '1.11024233511357421655055291769', '1.57079632679489661923132169164'),
    ]},
   {'length': 4.144985925131902, 'closed': False, 'end_trims': ['a.u<=4', 'a.u>=0'],
    'ends': [
     (10.0, -9.0, 0.0),
     (14.0, -8.06225774829855, 0.0),],
    'nodes': [],
    'pieces': [
     (0, 0, '4.71238898038468985769396507492', '5.17294297206601226037473384887'),
    ]},
  ],
  'points': []},
 'bugs/buc60899_1:crg.s6*cyl': {
  'components': [
   {'length': 10.06665901200082, 'closed': False, 'end_trims': ['a.u<=10.0499', 'a.u>=0'],
    'ends': [
     (15.0, 7.483314773547883, 10.0),
     (14.0, 8.06225774829855, 0.0),],
    'nodes': [],
    'pieces': [
     (0, 0, '0.98176535657862274380487574633', '1.11024233511357421655055291769'),
    ]},
   {'length': 10.06665901200082, 'closed': False, 'end_trims': ['a.u<=10.0499', 'a.u>=0'],
    'ends': [
     (14.0, -8.06225774829855, -4.978412222288913e-59),
     (15.0, -7.483314773547883, 10.0),],
    'nodes': [],
    'pieces': [
     (0, 0, '5.17294297206601226037473384887', '5.30141995060096373312041102023'),
    ]},
  ],
  'points': []},
 'bugs/buc60899_1:crg.s7*cyl': {
  'components': [
   {'length': 17.67177641841521, 'closed': False, 'end_trims': ['a.u>=0'],
    'ends': [
     (15.0, 7.483314773547883, 10.0),
     (15.0, -7.483314773547883, 10.0),],
    'nodes': [],
    'pieces': [
     (0, 0, '0.0', '0.981765356578622737161817762514'),
     (0, 0, '5.30141995060096373976346900405', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'bugs/bug13211_6:r1.e3*r2.e3': {
  'components': [
   {'length': 21.740919943737442, 'closed': False, 'end_trims': ['curve'],
    'ends': [
     (128.08, 143.01, 0.0),
     (127.88, 164.75, 0.0),],
    'nodes': [],
    'pieces': [
     ('curve', 0),
    ]},
  ],
  'points': []},
 'bugs/bug13211_6:r1.e3*r2.e4': {
  'components': [
  ],
  'points': [{'point': (127.88, 164.75, 0.0)}]},
 'bugs/bug13211_6:r1.e3*r2.e5': {
  'components': [
  ],
  'points': []},
 'bugs/bug13211_6:r1.e4*r2.e3': {
  'components': [
  ],
  'points': [{'point': (127.88, 164.75, 0.0)}]},
 'bugs/bug13211_6:r1.e4*r2.e4': {
  'components': [
   {'length': 16.281750520137567, 'closed': False, 'end_trims': ['curve'],
    'ends': [
     (127.88, 164.75, 0.0),
     (116.11, 176.0, 0.0),],
    'nodes': [],
    'pieces': [
     ('curve', 0),
    ]},
  ],
  'points': []},
 'bugs/bug13211_6:r1.e4*r2.e5': {
  'components': [
  ],
  'points': [{'point': (116.11, 176.0, 0.0)}]},
 'bugs/bug13211_6:r1.e5*r2.e3': {
  'components': [
  ],
  'points': []},
 'bugs/bug13211_6:r1.e5*r2.e4': {
  'components': [
   {'length': 14.900593246346359, 'closed': False, 'end_trims': ['?'],
    'ends': [
     (117.48549325840284, 176.0, 7.279436743757158),
     (117.48549325840284, 176.0, -7.279436743757158),],
    'nodes': [],
    'pieces': [
     (0, [1, 1, 1], '38.5449369196856758144846450208', '38.5531140117111773818072540317'),
     (0, [1, 1, -1], '38.5449369196856758144846450208', '38.5531140117111773818072540317'),
     (0, [-1, 1, 1], '38.5449369196856758144846450208', '38.5531140117111773818072540317'),
     (0, [-1, 1, -1], '38.5449369196856758144846450208', '38.5531140117111773818072540317'),
    ]},
  ],
  'points': []},
 'bugs/bug13211_6:r1.e5*r2.e5': {
  'components': [
   {'length': 37.70574451650612, 'closed': False, 'end_trims': ['b.v<=23.0322', 'curve'],
    'ends': [
     (117.48549325840284, 176.0, 7.279436743757158),
     (117.48549325840284, 176.0, -7.279436743757158),
     (116.11, 176.0, 0.0),
     (136.06, 187.51, 0.0),],
    'nodes': [
     (116.79774662920143, 176.3967901605067, 3.2207805861153286e-14),],
    'pieces': [
     (0, [1, -1, 1], '38.5449369196856758144846450208', '38.5531140117111773818072540317'),
     (0, [1, -1, -1], '38.5449369196856758144846450208', '38.5531140117111773818072540317'),
     ('curve', 0),
    ]},
  ],
  'points': []},
 'bugs/bug23932_1': {
  'components': [
   {'length': 163.20030970505505, 'closed': False, 'end_trims': ['a.u'],
    'ends': [
     (582.7706379946599, 307.61379298952244, 183.375),
     (494.38229034634145, 307.61379298952244, 183.375),],
    'nodes': [],
    'pieces': [
     (0, 1, '0.0', '3.14159265358979311599796346854'),
    ]},
   {'length': 163.20030970505505, 'closed': False, 'end_trims': ['a.u'],
    'ends': [
     (582.7706379946599, 619.9060195910465, 183.375),
     (494.38229034634145, 619.9060195910465, 183.375),],
    'nodes': [],
    'pieces': [
     (0, -1, '0.0', '3.14159265358979311599796346854'),
    ]},
  ],
  'points': []},
 'bugs/bug23932_2': {
  'components': [
   {'length': 165.45157899685086, 'closed': False, 'end_trims': ['a.u'],
    'ends': [
     (583.3956379946599, 306.8666790057351, 183.375),
     (493.75729034634145, 306.8666790057351, 183.375),],
    'nodes': [],
    'pieces': [
     (0, 1, '0.0', '3.14159265358979311599796346854'),
    ]},
   {'length': 165.45157899685086, 'closed': False, 'end_trims': ['a.u'],
    'ends': [
     (583.3956379946599, 620.653133574834, 183.375),
     (493.75729034634145, 620.653133574834, 183.375),],
    'nodes': [],
    'pieces': [
     (0, -1, '0.0', '3.14159265358979311599796346854'),
    ]},
  ],
  'points': []},
 'bugs/bug24905:p1.annulusy=-1000*p2': {
  'components': [
   {'length': 8.573933645686527, 'closed': False, 'end_trims': ['a.rim'],
    'ends': [
     (-34.200939529986414, -1000.0, 66.74800173238307),
     (-26.369473514970057, -1000.0, 70.21147247098078),],
    'nodes': [],
    'pieces': [
     (0, 0, '1.89228699895156780644464945674', '2.06304699122562007702467968069'),
    ]},
  ],
  'points': []},
 'bugs/bug24905:p1.annulusy=0*p2': {
  'components': [
   {'length': 8.573933645686877, 'closed': False, 'end_trims': ['a.rim'],
    'ends': [
     (-26.369473514969823, 0.0, -70.21147247098088),
     (-34.2009395299865, 0.0, -66.74800173238302),],
    'nodes': [],
    'pieces': [
     (0, 0, '4.22013831595396390565002680365', '4.39089830822802317004722108973'),
    ]},
  ],
  'points': []},
 'bugs/bug24905:p1.inner*p2': {
  'components': [
   {'length': 1881.9207699122053, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, 1, '1.18045026902229906755646547589e-14', '3.14159265358977211084930957582'),
     (0, -1, '1.18045026902229906755646547589e-14', '3.14159265358977211084930957582'),
    ]},
  ],
  'points': []},
 'bugs/bug24905:p1.outer*p2': {
  'components': [
   {'length': 1033.0007767238533, 'closed': False, 'end_trims': ['a.v<=0', 'a.v>=-1000'],
    'ends': [
     (-26.369473514973738, 3.2293291335313494e-15, -70.2114724709794),
     (-34.20093952997638, -1000.0, 66.74800173238827),],
    'nodes': [],
    'pieces': [
     (0, 1, '9.70573343587391685811231190637e-15', '0.359272184907664184431368472071'),
     (0, -1, '9.70573343587391685811231190637e-15', '0.359272184907664184431368472071'),
     (0, -1, '0.359272184907664184431368472071', '0.473509587876225912805307386001'),
     (0, -1, '0.473509587876225912805307386001', '2.6680830657136649040086983575'),
    ]},
   {'length': 1033.0007767238524, 'closed': False, 'end_trims': ['a.v<=0', 'a.v>=-1000'],
    'ends': [
     (-34.20093952998277, 4.188407112322558e-15, -66.74800173238494),
     (-26.369473514980726, -1000.0, 70.21147247097683),],
    'nodes': [],
    'pieces': [
     (0, 1, '0.473509587876225912805307386001', '2.6680830657136649040086983575'),
     (0, 1, '2.6680830657136649040086983575', '2.78232046868203127131243529086'),
     (0, 1, '2.78232046868203127131243529086', '3.14159265358977420961856392489'),
     (0, -1, '2.78232046868203127131243529086', '3.14159265358977420961856392489'),
    ]},
  ],
  'points': []},
 'bugs/bug28626_2': {
  'components': [
   {'length': 88.96917862903281, 'closed': False, 'end_trims': ['a.v<=42.4264', 'b.v<=42.4264'],
    'ends': [
     (7.000000000000037, -21.168147308012188, -19.977248570654144),
     (-0.6455327113022831, -30.000000000000036, 29.99305398785927),],
    'nodes': [],
    'pieces': [
     (0, 1, '0.0', '0.337029878542172668392547687248'),
     (0, 1, '3.16311207148259479599714000095', '4.3958808312674283785748132462'),
     (0, 1, '4.3958808312674283785748132462', '5.49184554172062381107910326159'),
     (0, 1, '5.49184554172062381107910326159', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'bugs/bug28626_3': {
  'components': [
   {'length': 94.31640754459883, 'closed': False, 'end_trims': ['a.v<=42.4264', 'b.v<=42.4264'],
    'ends': [
     (8.000000000000037, -21.505564993996334, -19.962197416892757),
     (0.35876103928407477, -30.000000000000036, 29.997854765244362),],
    'nodes': [],
    'pieces': [
     (0, 1, '0.0', '0.381159209433177503741229508799'),
     (0, -1, '0.0', '0.381159209433177503741229508799'),
     (0, -1, '0.381159209433177503741229508799', '0.532111734654724171059078523778'),
     (0, -1, '0.532111734654724171059078523778', '2.91855175109735077051959566319'),
     (0, -1, '2.91855175109735077051959566319', '3.12963366722526303491433754629'),
     (0, 1, '3.12963366722526303491433754629', '4.4379815642842850635109817032'),
     (0, -1, '3.12963366722526303491433754629', '4.4379815642842850635109817032'),
     (0, 1, '6.06763539702626341300189898003', '6.28318530717958647692528676656'),
     (0, -1, '6.06763539702626341300189898003', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'bugs/bug29910_1': {
  'components': [
   {'length': 165.0480621991573, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [
     (50.0, 86.60254037844386, -10.0),
     (50.0, 86.60254037844386, 10.0),],
    'pieces': [
     (0, [0, 0, 1], '-10.0', '10.0'),
     (0, [0, 1, 1], '-10.0', '10.0'),
     (0, [1, 0, 1], '-10.0', '10.0'),
     (0, [1, 1, 1], '-10.0', '10.0'),
    ]},
   {'length': 165.0480621991573, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [
     (50.0, -86.60254037844386, -10.0),
     (50.0, -86.60254037844386, 10.0),],
    'pieces': [
     (0, [0, 0, -1], '-10.0', '10.0'),
     (0, [0, 1, -1], '-10.0', '10.0'),
     (0, [1, 0, -1], '-10.0', '10.0'),
     (0, [1, 1, -1], '-10.0', '10.0'),
    ]},
  ],
  'points': []},
 'intss/bug23163_1': {
  'components': [
   {'length': 100.28540627141737, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [
     (20.0, 0.0, -5.0),
     (20.0, 0.0, 5.0),],
    'pieces': [
     (0, [0, 0, 1], '-5.0', '5.0'),
     (0, [0, 0, -1], '-5.0', '5.0'),
     ('curve', 0),
    ]},
  ],
  'points': []},
 'intss/bug23178': {
  'components': [
   {'length': 79.42778988020216, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, 1, '0.0', '3.14159247483048199658001991899'),
     (0, -1, '0.0', '3.14159247483048199658001991899'),
     (0, 1, '3.14159283234910448034526684757', '6.28318530717958647692528676656'),
     (0, -1, '3.14159283234910448034526684757', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'intss/bug24418_2': {
  'components': [
   {'length': 59.76571444083901, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, [0, 0, 1], '20.3217490024190607788879842443', '23.2237492617871756605153700413'),
     (0, [0, 0, -1], '20.3217490024190607788879842443', '23.2237492617871756605153700413'),
     (0, [0, 0, 1], '23.2237492617871756605153700413', '24.0'),
     (0, [0, 0, -1], '23.2237492617871756605153700413', '24.0'),
     (0, [1, 0, 1], '23.2237492617871756605153700413', '24.0'),
     (0, [1, 0, -1], '23.2237492617871756605153700413', '24.0'),
    ]},
  ],
  'points': []},
 'intss/bug26509_1': {
  'components': [
   {'length': 1881.9207699122053, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, 1, '1.18045026902229906755646547589e-14', '3.14159265358977211084930957582'),
     (0, -1, '1.18045026902229906755646547589e-14', '3.14159265358977211084930957582'),
    ]},
  ],
  'points': []},
 'intss/bug26509_2': {
  'components': [
   {'length': 1881.9207699122053, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, 1, '1.57079632679490831271170945212', '4.71238898038466861905832880494'),
     (0, -1, '1.57079632679490831271170945212', '4.71238898038466861905832880494'),
    ]},
  ],
  'points': []},
 'intss/bug26509_3': {
  'components': [
   {'length': 1881.9207699122053, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, 1, '0.0', '1.57079632679487560264029034669'),
     (0, -1, '0.0', '1.57079632679487560264029034669'),
     (0, 1, '4.71238898038470177321895776043', '6.28318530717958647692528676656'),
     (0, -1, '4.71238898038470177321895776043', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'intss/bug26509_4': {
  'components': [
   {'length': 1881.9207699122053, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, 1, '0.0', '1.57079632679487454173467734148'),
     (0, -1, '0.0', '1.57079632679487454173467734148'),
     (0, 1, '4.71238898038470071231334475521', '6.28318530717958647692528676656'),
     (0, -1, '4.71238898038470071231334475521', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'intss/bug26509_5': {
  'components': [
   {'length': 1881.9207699122683, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, 1, '0.0', '3.14159265358983340538959640806'),
     (0, -1, '0.0', '3.14159265358983340538959640806'),
     (0, 1, '6.28318530717956521246627668064', '6.28318530717958647692528676656'),
     (0, -1, '6.28318530717956521246627668064', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'intss/bug26509_6': {
  'components': [
   {'length': 1881.9207699122683, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, 1, '1.57079632679487524375000914321', '4.71238898038472991359861563718'),
     (0, -1, '1.57079632679487524375000914321', '4.71238898038472991359861563718'),
    ]},
  ],
  'points': []},
 'intss/bug27227': {
  'components': [
   {'length': 306.695734960788, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [
     (-120.0, 1.3703924393098437e-59, 0.0),
     (-80.0, 2.4492935982947065e-15, 2.4492935982947065e-15),],
    'pieces': [
     (0, 1, '0.0', '3.14159265358979311599796346854'),
     (0, 1, '3.14159265358979311599796346854', '6.28318530717958647692528676656'),
     (1, 1, '0.0', '3.14159265358979311599796346854'),
     (1, 1, '3.14159265358979311599796346854', '6.28318530717958647692528676656'),
    ]},
   {'length': 306.695734960788, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [
     (120.0, 0.0, 0.0),
     (80.0, 2.4492935982947065e-15, 2.4492935982947065e-15),],
    'pieces': [
     (0, -1, '0.0', '3.14159265358979311599796346854'),
     (0, -1, '3.14159265358979311599796346854', '6.28318530717958647692528676656'),
     (1, -1, '0.0', '3.14159265358979311599796346854'),
     (1, -1, '3.14159265358979311599796346854', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'intss/bug28222_2': {
  'components': [
   {'length': 77.09069520559275, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, 1, '0.0', '6.28318530717958647692528676656'),
    ]},
   {'length': 77.09069520559275, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, -1, '0.0', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'intss/bug28222_3': {
  'components': [
   {'length': 0.5368099716533702, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, 1, '0.0', '3.14159265358979323846264338328'),
     (0, -1, '0.0', '3.14159265358979323846264338328'),
    ]},
  ],
  'points': []},
 'intss/bug29807_i5002': {
  'components': [
   {'length': 2.8731558799692145, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, [0, 0, 1], '-87.7400948652556983003614041851', '-87.5800862468282585705840682517'),
     (0, [0, 0, -1], '-87.7400948652556983003614041851', '-87.5800862468282585705840682517'),
    ]},
   {'length': 1.2933926946856855, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, [0, 0, 1], '-95.217499956616696766753874428', '-95.1454665497963481910007114919'),
     (0, [0, 0, -1], '-95.217499956616696766753874428', '-95.1454665497963481910007114919'),
    ]},
  ],
  'points': []},
 'intss/bug29972_3': {
  'components': [
   {'length': 153.5247851725941, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [],
    'pieces': [
     (0, [0, 0, 1], '-110.0', '-100.000000943846251216295209679'),
     (0, [0, 0, -1], '-110.0', '-100.000000943846251216295209679'),
     (0, [1, 0, 1], '-110.0', '-100.000000943846251216295209679'),
     (0, [1, 0, -1], '-110.0', '-100.000000943846251216295209679'),
     (0, [1, 0, 1], '-100.000000943846251216295209679', '-99.9999990561537487837047903211'),
     (0, [1, 0, -1], '-100.000000943846251216295209679', '-99.9999990561537487837047903211'),
     (0, [0, 0, 1], '-99.9999990561537487837047903211', '-90.0'),
     (0, [0, 0, -1], '-99.9999990561537487837047903211', '-90.0'),
     (0, [1, 0, 1], '-99.9999990561537487837047903211', '-90.0'),
     (0, [1, 0, -1], '-99.9999990561537487837047903211', '-90.0'),
    ]},
  ],
  'points': []},
 'intss/bug30082_2': {
  'components': [
   {'length': 7.578540703796088, 'closed': True, 'end_trims': [],
    'ends': [],
    'nodes': [
     (-124.971129473161, -64.0942185874231, -19.25),],
    'pieces': [
     (0, 1, '0.0', '1.57079632679489661923132169165'),
     (0, -1, '0.0', '1.57079632679489661923132169165'),
     (0, 1, '1.57079632679489661923132169165', '6.28318530717958647692528676656'),
     (0, -1, '1.57079632679489661923132169165', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'intss/bug31552': {
  'components': [
   {'length': 15.445905007861072, 'closed': False, 'end_trims': ['a.u'],
    'ends': [
     (88.17428429792234, 221.31089891857906, -7.713127203694547),
     (88.17427971403886, 221.31089771740903, 7.713181367591022),],
    'nodes': [],
    'pieces': [
     (0, -1, '0.0', '0.0872646928204134583323249683669'),
     (0, -1, '6.19592000000000010481707341213', '6.28318530717958647692528676656'),
    ]},
  ],
  'points': []},
 'intss/bug32850': {
  'components': [
   {'length': 13.015835696779138, 'closed': False, 'end_trims': ['a.u', 'b.u'],
    'ends': [
     (25.80644989013671, 1974.1935501098594, 34.999999999999844),
     (25.80644989013671, 1974.1921348545004, 34.999999999999844),
     (25.80786514549589, 1974.1935501098594, 34.999999999999844),
     (35.008232117163715, 1964.9917678828324, 34.89648439563747),],
    'nodes': [
     (25.8071575178163, 1974.19284248218, 35.00000000061203),],
    'pieces': [
     (0, 1, '0.0', '0.00000173024882664042351886064003968'),
     (0, -1, '0.0', '0.00000173024882664042351886064003968'),
     (0, 1, '0.00000173024882664042351886064003968', '0.0000034604976532808470377212780672'),
     (0, -1, '0.00000173024882664042351886064003968', '0.0000034604976532808470377212780672'),
     (0, -1, '0.0000034604976532808470377212780672', '0.0225015452057227005600026359389'),
    ]},
  ],
  'points': []},
}
# END STORED


# --- the runs spatialkin fails, by failure class (written by ``python -m tests.spatialkin.tracing.occ.compare --xfail``) ------------------
# BEGIN XFAIL
XFAIL = {}
# END XFAIL

for _c in CASES:
    _c.xfail.update(XFAIL.get(_c.id, {}))


def by_id(case_id):
    for c in CASES:
        if c.id == case_id:
            return c
    raise KeyError(case_id)
