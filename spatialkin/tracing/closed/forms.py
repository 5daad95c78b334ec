"""sk.intersect in closed form for the pairs that meet in conics: plane-plane (a line), plane-sphere and
sphere-sphere (a circle), plane-cylinder (an ellipse, or two lines along the axis), plane-cone (an ellipse, a
parabola or a hyperbola; through the apex, two rulings or the apex alone) and a trimmed plane normal to a torus's
axis (two parallels), each clipped by the trims; and the pairs of quadrics whose intersection splits into two
ellipses crossing at nodes (spatialkin.tracing.closed.split: two equal cylinders with crossing axes, the Steinmetz
curves).

A plane cuts a quadric q^T diag(1, 1, mu) q = rho (local coordinates: a sphere, a cylinder, a double cone) in
the conic x^2 + A y^2 + 2 B y + C = 0 of the plane's coordinates along e1 = n x z (normal to the axis) and
e2 = n x e1; its sign of A tells the shape. Every trim (a plane's u or v, a cylinder's or cone's v) is a linear
function of the point, so its crossings with the conic are roots in closed form (R cos(t - phi) = c, a quadratic in
e^t, in t, or a linear equation). The arcs between crossings that lie inside every trim are the components,
oriented as the tracer runs them (along N_a x N_b), sampled as exact points with exact arc lengths
(spatialkin.tracing.closed.conic).

An ellipse that touches a trim edge from inside to round-off (a circle inscribed in a plane's rectangle, a half
circle ending in the corners of the edges it touches) keeps the trim's side: the touch is no crossing, and
crossings of two trims at one point (a corner) are one end. Two spheres, or a sphere and a plane, beside a
tangency meet in a circle whose radius comes from their distance to the tangency (no difference of squares), or
touch in a point where that distance is within its round-off (TANGENCY_ULPS); a plane along a cylinder's axis
beside a ruling cuts two lines whose distance comes likewise. ``closed_form`` declines
(returns None, and sk.intersect runs its general path) on what is degenerate otherwise: another tangency of the
surfaces or a touch of a trim edge from outside (the patch met in one point) or by a hyperbola's or parabola's vertex
within GRAZE x tolerance, a plane through a cone's apex tangent to it along a ruling, coincident surfaces,
near-parallel configurations whose conic would be huge, both surfaces unbounded.
"""
import collections
import functools
import math
import weakref

import numpy as np

from ...kernels.geometry import surfaces as ks
from .conic import ELLIPSE, HYPERBOLA, LINE, PARABOLA, Conic, ConicSolution, basis
from ..curve.exact import SampledResult, contact_point, exact_curve
from ...geometry.placement import SAME
from ...geometry.vectors import cross_list, dot_list as dot
from ..curve.result import in_sk_order
from ..march.segments import EDGE_NAMES
from .split import split_planes
from ..curve.status import BOUNDARY, CLOSED, open_outcome, outcome
from ..search.topology import Topology
from ...geometry.surfaces.base import distances_at
from ..march.start import scene_reading
from ..march.trace import EPS, ROUNDOFF_ULPS, check_options, scene_lengths

#: A curve within this many times the tolerance of touching the other surface (tangency, a plane through an apex)
#: or of a vertex's touch of a trim level is left to the general path (a user's plane's tangency to a sphere or a
#: cylinder, and two spheres', only within TANGENCY_ULPS).
GRAZE = 1e3
#: Distances to a tangency (two spheres': d - |ra - rb| and ra + rb - d; a plane's to a sphere's centre or a
#: cylinder's axis, less the radius) are read to within this many ulps of the largest coordinate, radius or distance:
#: within it the surfaces touch (a contact point; a cylinder's ruling, left to the general path).
TANGENCY_ULPS = 8
#: crossings' answer where an ellipse touches a trim level (a double root: no crossing).
TOUCH = "touch"
#: A conic whose centre or semi-axes exceed this many scales (a plane nearly parallel to a cylinder's axis or to a
#: cone's generatrix) is left to the general path: its points would lose digits.
LARGE = 1e4
#: |A| at most this: the plane is parallel to a cylinder's axis (two lines, as the topology stage recognises it:
#: placement.SAME, squared for the cosine) ...
PARALLEL_A = SAME * SAME
#: ... or to a cone's generatrix (a parabola; a plane placed so has |A| of a few ulps, and the parabola's points
#: are checked on the cone: PARABOLA_CHECK x tolerance).
PARABOLA_A = 1e-13
PARABOLA_CHECK = 0.1
#: A curve longer than this share of settings.max_length is left to the tracer (a branch runs at most max_length
#: each way from its start).
MAX_LENGTH_SHARE = 0.5
#: Topology.mode of the curves found here.
MODE = "closed_form"
#: The quadrics a plane is cut with here.
QUADRICS = ("sphere", "cylinder", "cone")
#: Points per ellipse of a split pair checked on both surfaces (exact distance functions) before it is taken.
SPLIT_CHECKS = 16
#: A split pair's ellipses must lie this close (relative to the scale, or the round-off of the coordinates' magnitude
#: where larger) to both surfaces; farther, the pair is only nearly split (a waist, not a node) and is traced.
SPLIT_FIT = 1e-13
#: A plane through a cone's apex touches it along a ruling when the axis projected on the plane makes the half angle
#: with the axis to within this (in cosine; a plane tangent to the cone within round-off).
RULING_COS = 1e-9
#: An arc through nodes is oriented at the middle of the piece between its nodes (and ends) where the normals'
#: angle is largest, the first of those where the normals' sine (squared) lies within this fraction of the largest:
#: a symmetric pair's probes tie to round-off on both arcs between its nodes, where N_a x N_b runs opposite ways
#: along the curve, and round-off must not choose the direction.
PROBE_TIE = 1e-9
TWO_PI = 2.0 * math.pi
#: The SPLIT_CHECKS angles at which a split pair's ellipses are checked ...
SPLIT_ANGLES = np.linspace(0.0, TWO_PI, SPLIT_CHECKS, endpoint=False)
#: ... and the weights (1, cos t, sin t) of an ellipse's rows (centre, P, Q) there.
SPLIT_WEIGHTS = np.column_stack([np.ones(SPLIT_CHECKS), np.cos(SPLIT_ANGLES), np.sin(SPLIT_ANGLES)])

#: What the closed forms read of the settings (a trace Settings has these fields too; closed_form takes either).
#: What the closed forms read of sk.intersect's options; ``checked`` is the options and lengths make_settings
#: reuses when the general path goes on (spatialkin.tracing.march.trace.make_settings's scene).
Scene = collections.namedtuple("Scene", "scale tolerance singular_tol max_length checked")


def closed_settings(a, b, tol, method, rtol, atol, max_length, singular_tol, pullback):
    """The Scene of sk.intersect's options (named as there), checked as make_settings checks them (ValueError
    naming a bad one), its lengths those make_settings gives (spatialkin.tracing.march.trace.scene_lengths)."""
    options = check_options(tol, method, rtol, atol, max_length, singular_tol, pullback)
    reach = max(a.memo("placed", Placed).reach, b.memo("placed", Placed).reach)
    lengths = scene_lengths(a, b, options[0], options[3], reach)
    scale, tolerance, _, max_length = lengths
    return Scene(scale, tolerance, options[4], max_length, (options, lengths))


class Placed:
    """A surface as the closed forms read it, once per surface (kept in its memo): its traits and name, and its
    frame's origin (3 floats), rotation (9 floats, row by row: its local axis j is rot[j::3]) and local z axis (a
    plane's normal), trims (u_min, u_max, v_min, v_max) as floats, read from its packed data; a quadric's (mu, rho)
    (quadric_form; None for a plane); reach, the largest |coordinate| of its origin."""

    __slots__ = ("_surface", "kind", "name", "origin", "rot", "z", "bounds", "form", "reach")

    def __init__(self, surface):
        data = surface.floats
        kind = surface.traits
        self._surface = weakref.ref(surface)        # (kept in the surface's memo: no cycle holding it)
        self.kind = kind
        self.name = kind.name
        self.origin = data[ks.ORIGIN:ks.ORIGIN + 3]
        self.rot = rot = data[ks.ROT:ks.ROT + 9]
        self.z = rot[2::3]
        self.bounds = data[ks.BOUNDS:ks.BOUNDS + 4]
        self.reach = max(map(abs, self.origin))
        self.form = quadric_form(self) if self.name in QUADRICS else (
            (data[ks.P0], data[ks.P1]) if self.name == "torus" else None)

    @property
    def surface(self):
        """The surface read (alive while the call that reads it runs)."""
        return self._surface()


def closed_form(a, b, settings):
    """The components of a ∩ b (CurveResults, longest first, as sk.intersect sorts them), or None when the pair
    or its placement is not handled here (see the module docstring). settings: a Scene or a trace Settings."""
    kinds = (a.traits, b.traits)
    names = (kinds[0].name, kinds[1].name)
    if not (kinds[0].compact or kinds[1].compact or math.isfinite(scene_reading(a)[2])
            or math.isfinite(scene_reading(b)[2])):
        return None                                          # (a compact kind is bounded)
    graze = GRAZE * settings.tolerance
    topo = Topology(P=a, Q=b, mode=MODE)
    if names == ("sphere", "sphere"):
        circle = sphere_circle(a, b, graze, settings.scale)
        if not circle:
            return None if circle is None else []
        if len(circle) == 1:
            return [contact_point((a, b), circle[0], settings.tolerance)]
        return [exact_curve((a, b), settings.tolerance, circle=circle, event="axis_circle", topology=topo)]
    placed = (a.memo("placed", Placed), b.memo("placed", Placed))
    gap = roundoff(placed, settings.scale)
    if names == ("plane", "plane"):
        conics = plane_line(*placed, graze, settings.scale)
        if conics is None:
            return coplanar_faces((a, b), placed, gap, settings, topo)
    elif "plane" in names and (names[0] in QUADRICS or names[1] in QUADRICS):
        plane, quadric = placed if names[0] == "plane" else placed[::-1]
        if quadric.name == "cone" and abs(dot(plane.z, [quadric.origin[k] - plane.origin[k] for k in range(3)])) <= gap:
            return apex_components((a, b), placed, plane, quadric, graze, gap, settings, topo)
        touch = plane_sphere_touch(plane, quadric) if quadric.name == "sphere" else None
        if touch is not None:
            return [contact_point((a, b), touch, settings.tolerance)]
        conics = plane_conics(plane, quadric, graze, settings.scale, gap)
        if isinstance(conics, tuple):                       # a circle about a common axis: as the general path
            return [] if not conics else [exact_curve((a, b), settings.tolerance, circle=along_normals(placed, conics),
                                                      event="axis_circle", topology=topo)]
    elif names[0] in QUADRICS and names[1] in QUADRICS:
        return split_conics(placed, graze, gap, settings, topo)
    elif sorted(names) == ["plane", "torus"]:
        plane, torus = placed if names[0] == "plane" else placed[::-1]
        conics = torus_parallels(plane, torus, graze)
    else:
        return None
    if not conics:
        return conics                                        # None (declined) or [] (nothing)
    trims = linear_trims(placed)
    if not trims:
        return None
    return components(placed, conics, trims, graze, gap, settings, topo)


def roundoff(placed, scale):
    """The round-off of the pair's (Placed) coordinates: ROUNDOFF_ULPS ulps of the larger of the scale and their
    origins' largest coordinate (the floor trace.scene_lengths puts under the tolerance)."""
    return ROUNDOFF_ULPS * EPS * max(scale, placed[0].reach, placed[1].reach)


def components(placed, conics, trims, graze, touch, settings, topo, nodes=()):
    """The CurveResults (in sk.intersect's order) of the conics ([(shape, rows)]) on the surfaces (Placed), clipped by
    the trims (touch: the pair's roundoff, see clip); nodes (K, 3) where two of them cross, each given to the arcs it
    lies on. None where declined."""
    curves = []
    for shape, rows in conics:
        arcs = clip(shape, rows, trims, graze, touch)
        if arcs is None:
            return None
        for t_lo, t_hi, ends in arcs:
            if t_lo == t_hi:
                point = combine(rows, *basis(shape, t_lo, 0, math))
                curves.append(contact_point((placed[0].surface, placed[1].surface), point, settings.tolerance,
                                            event="edge_point"))
                continue
            on = [x for x in nodes if on_arc(shape, rows, t_lo, t_hi, ends, x, settings.tolerance)]
            curve = component(placed, shape, rows, t_lo, t_hi, ends, settings, topo, on)
            if curve is None or curve.length > MAX_LENGTH_SHARE * settings.max_length:
                return None                                  # (the tracer would stop at max_length)
            curves.append(curve)
    return in_sk_order(curves)


#: An untrimmed plane's bounds.
UNBOUNDED = (-math.inf, math.inf, -math.inf, math.inf)


class Cut:
    """An untrimmed plane as plane_conics reads it (a Placed plane's origin, z and bounds), from its unit normal and
    a point on it (3 floats each)."""

    __slots__ = ("origin", "z", "bounds")

    def __init__(self, normal, point):
        self.origin, self.z, self.bounds = point, normal, UNBOUNDED


def split_conics(placed, graze, gap, settings, topo):
    """The components of two quadrics (Placed) whose intersection splits into two ellipses (split.split_planes), cut
    from the first by the two planes, checked on the second (SPLIT_CHECKS points of each within SPLIT_FIT x scale,
    or the coordinates' round-off) and clipped by both trims, the nodes given to the arcs through them; a plane
    tangent to a cone along a ruling that lies on the other surface too (a cone touching a cylinder or a cone all
    along a line) gives that ruling, clipped, as a segment of tangency (status 'tangent', checked on both). None
    where declined (the pair does not split, or a conic is not an ellipse or that ruling, a circle about the axis,
    or off a surface)."""
    a, b = placed
    found = split_planes(((a.name, a.origin, a.rot, a.form), (b.name, b.origin, b.rot, b.form)), settings.scale)
    trims = linear_trims(placed)
    if found is None or trims is None:
        return None
    cuts, nodes = found
    conics, rulings = [], []
    for normal, point in cuts:
        cut = plane_conics(Cut(normal, point), placed[0], graze, settings.scale)
        if cut is None:
            ruling = tangent_ruling(placed, normal, point, graze)
            if ruling is None:
                return None
            rulings.append(ruling)
            continue
        if isinstance(cut, tuple) or any(shape != ELLIPSE for shape, _ in cut):
            return None
        conics += cut
    fit = max(SPLIT_FIT * settings.scale, gap)
    if conics and float(np.max(distances_at(placed[1].surface, (SPLIT_WEIGHTS @ np.array(
            [rows for _, rows in conics])).reshape(-1, 3)))) > fit:
        return None                                          # (cut from the first: on it to round-off)
    segments = []
    for apex, direction in rulings:
        span = line_span(trims, apex, direction)
        if span is None:
            return None
        if span:
            ends = (apex + span[0] * direction, apex + span[1] * direction)
            segments.append(ends)
            points = np.linspace(*ends, SPLIT_CHECKS)
            if max(float(np.max(distances_at(surf.surface, points))) for surf in placed) > fit:
                return None
    curves = components(placed, conics, trims, graze, gap, settings, topo, nodes) if conics else []
    if curves is None:
        return None
    surfaces = (placed[0].surface, placed[1].surface)
    curves += [exact_curve(surfaces, settings.tolerance, segment=ends, topology=topo) for ends in segments]
    return in_sk_order(curves)


def tangent_ruling(placed, normal, point, graze):
    """(apex (3,), unit direction (3,)) of the ruling along which the plane (unit normal and a point on it, 3 floats
    each) touches a cone of the pair (Placed): the plane passes through the cone's apex (within graze) and holds
    exactly one of its rulings (the axis projected on the plane, at the half angle to the axis); None otherwise."""
    normal, point = np.array(normal), np.array(point)
    for quadric in placed:
        if quadric.name != "cone":
            continue
        apex = np.array(quadric.origin)
        if abs(float(normal @ (apex - point))) > graze:
            continue
        axis = np.array(quadric.z)
        along = axis - float(axis @ normal) * normal
        size = float(np.linalg.norm(along))
        if size == 0.0:
            continue
        along /= size
        cos_half = 1.0 / math.sqrt(1.0 - quadric.form[0])            # (mu = -tan^2 of the half angle)
        if abs(float(along @ axis) - cos_half) <= RULING_COS:
            return apex, along
    return None


def line_span(trims, origin, direction):
    """(t_lo, t_hi) of the line origin + t direction (arrays) inside every trim (linear_trims' rows), () where it
    misses them, None where it is unbounded."""
    lo, hi = -math.inf, math.inf
    for w, bound, side, _ in trims:
        a0 = dot(w, origin) - bound                                 # the trim's value at t, times side: <= 0 inside
        a1 = dot(w, direction)
        if a1 == 0.0:
            if a0 * side > 0.0:
                return ()
            continue
        cut = -a0 / a1
        if side * a1 > 0.0:
            hi = min(hi, cut)
        else:
            lo = max(lo, cut)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return None
    return (lo, hi) if lo < hi else ()


def on_arc(shape, rows, t_lo, t_hi, ends, x, near=0.0):
    """True when the point x (3,) of the conic (an ellipse, rows = centre, P, Q with P normal to Q, or a line,
    centre + t Q) lies on its arc [t_lo, t_hi] (ends None: the whole ellipse)."""
    if ends is None:
        return True
    for t in (t_lo, t_hi):                                   # a node at an end of the arc (a trim through it)
        if math.dist(combine(rows, *basis(shape, t, 0, math)), x) <= near:
            return True
    t = parameter_at(shape, rows, x)
    if shape == LINE:
        return t_lo <= t <= t_hi
    t %= TWO_PI
    return t_lo <= t <= t_hi or t_lo <= t + TWO_PI <= t_hi


def parameter_at(shape, rows, x):
    """The parameter t of the point x (3,) of a conic: an ellipse's angle in (-pi, pi] (rows = centre, P, Q with P
    normal to Q), or a line's t (centre + t Q)."""
    c, p, q = rows
    d = [x[0] - c[0], x[1] - c[1], x[2] - c[2]]
    if shape == LINE:
        return dot(d, q) / dot(q, q)
    return math.atan2(dot(d, q) / dot(q, q), dot(d, p) / dot(p, p))


# --- small vectors as lists of floats (numpy costs more than the arithmetic on them) ---------------------------
# (their dot and cross products are spatialkin.geometry.vectors.dot_list, imported as dot, and cross_list)
def combine(rows, f, g):
    """rows[0] + f rows[1] + g rows[2] (3-lists)."""
    c, p, q = rows
    return [c[0] + f * p[0] + g * q[0], c[1] + f * p[1] + g * q[1], c[2] + f * p[2] + g * q[2]]


# (f, g) of spatialkin.tracing.closed.conic at one float t, or their derivatives, are basis(shape, t, order, math): its
# arguments passed by position (a functools.partial with lib=math as a keyword costs three times the call).


def to_global(rot, x):
    """rot x (the local vector x in global coordinates; rot: 9 floats, row by row): dot(row, x) for each row."""
    r00, r01, r02, r10, r11, r12, r20, r21, r22 = rot
    return [r00 * x[0] + r01 * x[1] + r02 * x[2], r10 * x[0] + r11 * x[1] + r12 * x[2],
            r20 * x[0] + r21 * x[1] + r22 * x[2]]


def to_local(rot, x):
    """rot^T x."""
    r00, r01, r02, r10, r11, r12, r20, r21, r22 = rot
    return [r00 * x[0] + r10 * x[1] + r20 * x[2], r01 * x[0] + r11 * x[1] + r21 * x[2],
            r02 * x[0] + r12 * x[1] + r22 * x[2]]


# --- the conics: (shape, [centre, P, Q]) in global coordinates ------------------------------------------------
def sphere_circle(a, b, graze, scale):
    """(centre, axis, radius) of the circle of two spheres (centre and axis 3 floats each), the axis from a's centre
    to b's (as the topology stage's common axis); (point,) where they touch within the round-off of their centres'
    distance (TANGENCY_ULPS); () when they do not meet; None when they (nearly) share their centre. The radius
    comes from the distances to both tangencies, d - |ra - rb| and ra + rb - d, each read once (no difference of
    squares), so that a circle just past a tangency keeps its relative accuracy."""
    (a0, a1, a2), (b0, b1, b2) = a.frame.origin.tolist(), b.frame.origin.tolist()
    d = [b0 - a0, b1 - a1, b2 - a2]
    dist = math.sqrt(dot(d, d))
    ra, rb = a.radius, b.radius
    if dist <= SAME * scale:
        return None if abs(ra - rb) <= graze else ()
    floor = TANGENCY_ULPS * EPS * max(abs(x) for x in (a0, a1, a2, b0, b1, b2, ra, rb, dist))
    inner, outer = dist - abs(ra - rb), ra + rb - dist
    if inner < -floor or outer < -floor:
        return ()
    axis = [d[0] / dist, d[1] / dist, d[2] / dist]
    if min(abs(inner), abs(outer)) <= floor:          # touching: on the axis, on b's side of a unless b holds a
        side = -ra if abs(inner) <= floor and rb > ra else ra
        return ([a0 + side * axis[0], a1 + side * axis[1], a2 + side * axis[2]],)
    x = 0.5 * (dist * dist + ra * ra - rb * rb) / dist
    radius = math.sqrt(inner * (dist + abs(ra - rb)) * outer * (ra + rb + dist)) / (2.0 * dist)
    return [a0 + x * axis[0], a1 + x * axis[1], a2 + x * axis[2]], axis, radius


def plane_line(a, b, graze, scale):
    """[(LINE, rows)] of two planes (Placed); [] for parallel planes apart; None for (nearly) coplanar ones or a
    line farther than LARGE x scale."""
    (o0, o1, o2), (p0, p1, p2) = a.origin, b.origin
    (m0, m1, m2), (n0, n1, n2) = a.z, b.z
    l0, l1, l2 = m1 * n2 - m2 * n1, m2 * n0 - m0 * n2, m0 * n1 - m1 * n0      # (along = cross(a.z, b.z))
    sin = math.sqrt(l0 * l0 + l1 * l1 + l2 * l2)
    gap = n0 * (p0 - o0) + n1 * (p1 - o1) + n2 * (p2 - o2)
    if sin <= SAME:
        return None if abs(gap) <= graze else []
    if abs(gap) > LARGE * scale * sin:
        return None
    k = gap / (sin * sin)                           # a's origin to its foot on the line: k cross(along, a.z)
    foot = [o0 + k * (l1 * m2 - l2 * m1), o1 + k * (l2 * m0 - l0 * m2), o2 + k * (l0 * m1 - l1 * m0)]
    return [(LINE, [foot, [0.0, 0.0, 0.0], [l0 / sin, l1 / sin, l2 / sin]])]


def coplanar_faces(surfaces, placed, touch, settings, topo):
    """The common edge (a segment of tangency) or corner (a contact point) of two coplanar rectangles (Placed) that
    share no area, [] where they are apart; None (declined) where they overlap in an area (the topology stage then
    says so), where a rectangle is unbounded or has a circle, or where the planes are only nearly the same (farther
    apart than touch). B's rectangle is clipped by A's (Sutherland-Hodgman, closed within touch) in A's plane."""
    a, b = placed
    if surfaces[0].region or surfaces[1].region or not all(map(math.isfinite, [*a.bounds, *b.bounds])):
        return None
    if abs(dot(a.z, [b.origin[i] - a.origin[i] for i in range(3)])) > touch:
        return None
    xa, ya = a.rot[0::3], a.rot[1::3]
    xb, yb = b.rot[0::3], b.rot[1::3]
    shift = [b.origin[i] - a.origin[i] for i in range(3)]
    u0, u1, v0, v1 = b.bounds
    poly = []
    for u, v in ((u0, v0), (u1, v0), (u1, v1), (u0, v1)):
        p = [shift[i] + u * xb[i] + v * yb[i] for i in range(3)]
        poly.append((dot(p, xa), dot(p, ya)))
    for axis, bound, sign in ((0, a.bounds[0], 1.0), (0, a.bounds[1], -1.0), (1, a.bounds[2], 1.0),
                              (1, a.bounds[3], -1.0)):
        out = []
        for p, q in zip(poly, poly[1:] + poly[:1]):
            fp, fq = sign * (p[axis] - bound), sign * (q[axis] - bound)
            if fp >= -touch:
                out.append(p)
            if (fp < -touch < fq) or (fq < -touch < fp):
                w = fp / (fp - fq)
                out.append((p[0] + w * (q[0] - p[0]), p[1] + w * (q[1] - p[1])))
        poly = out
        if not poly:
            return []
    far = max(((p, q) for p in poly for q in poly), key=lambda pq: math.dist(*pq))
    width = max(abs((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])) for p, q in [far] for r in poly)
    if width > touch * max(math.dist(*far), touch):
        return None                                          # an area in common
    ends = [[a.origin[i] + p[0] * xa[i] + p[1] * ya[i] for i in range(3)] for p in far]
    if math.dist(*far) <= touch:
        return [contact_point(surfaces, ends[0], settings.tolerance)]
    return [exact_curve(surfaces, settings.tolerance, segment=(np.array(ends[0]), np.array(ends[1])), topology=topo)]


def touching(plane, quadric):
    """The round-off (TANGENCY_ULPS) of the distance from a plane to a sphere's centre or a cylinder's axis
    (both Placed), within which the plane touches the sphere (or the cylinder along a ruling)."""
    return TANGENCY_ULPS * EPS * max(*map(abs, plane.origin), *map(abs, quadric.origin), quadric.surface.radius)


def plane_sphere_touch(plane, sphere):
    """The point where the plane touches the sphere (both Placed), their distance within its round-off (touching) of
    the radius; None otherwise."""
    offset = [plane.origin[i] - sphere.origin[i] for i in range(3)]
    d = dot(plane.z, offset)
    radius = sphere.surface.radius
    if abs(abs(d) - radius) > touching(plane, sphere):
        return None
    side = radius if d > 0 else -radius
    return [sphere.origin[i] + side * plane.z[i] for i in range(3)]


def quadric_form(quadric):
    """(mu, rho): the quadric (Placed) is x^2 + y^2 + mu z^2 = rho in its local coordinates."""
    name, surface = quadric.name, quadric.surface
    if name == "sphere":
        return 1.0, surface.radius ** 2
    if name == "cylinder":
        return 0.0, surface.radius ** 2
    tan = float(surface.data[ks.P1])
    return -tan * tan, 0.0


def plane_conics(plane, quadric, graze, scale, apex_gap=None):
    """[(shape, rows)] (global) of the plane and the quadric (Placed); a tuple (centre, axis, radius) for the circle
    of an untrimmed plane about the quadric's axis (or a sphere's), () when nothing is there; None where
    declined. A plane within apex_gap of a cone's apex passes through it (declined; graze when None: the split
    pairs' planes, known to about that, which graze a sphere within graze too; a user's plane touches it within the
    round-off of their distance): a user's plane farther from it cuts a conic of its own, however small
    (a plane 1e-7 from the apex, tilted less than the half angle: an ellipse 3.6e-7 long, which the general path's
    search does not look for so close to an apex on the plane)."""
    origin, rot = quadric.origin, quadric.rot
    (o0, o1, o2), (p0, p1, p2) = origin, plane.origin
    normal = plane.z
    n = to_local(rot, normal)
    d = dot(normal, (p0 - o0, p1 - o1, p2 - o2))            # the plane: n . q = d (local)
    mu, rho = quadric.form
    name = quadric.name
    if name == "sphere" and abs(abs(d) - math.sqrt(rho)) <= (graze if apex_gap is None else touching(plane, quadric)):
        return None                                          # tangent (a user's plane: plane_sphere_touch)
    if name == "cone" and abs(d) <= (graze if apex_gap is None else apex_gap):
        return None                                          # through the apex
    n0, n1, n2 = n
    sin = math.hypot(n0, n1)
    e1 = [n1 / sin, -n0 / sin, 0.0] if sin > SAME else [1.0, 0.0, 0.0]    # n x z, normal to the axis
    e2 = cross_list(n, e1)
    q0 = [d * n0, d * n1, d * n2]
    (a0, a1, a2), (b0, b1, b2) = e2, q0
    A = a0 * a0 + a1 * a1 + mu * a2 * a2
    B = a0 * b0 + a1 * b1 + mu * a2 * b2
    C = b0 * b0 + b1 * b1 + mu * b2 * b2 - rho
    zero = [0.0, 0.0, 0.0]
    if abs(A) <= (PARABOLA_A if name == "cone" else PARALLEL_A):
        if name == "cylinder":                               # parallel to the axis: two lines x = +-sqrt(-C)
            away = math.sqrt(rho) - abs(d)                   # (-C as (r - |d|)(r + |d|), as a sphere's K below)
            if abs(away) <= (graze if apex_gap is None else touching(plane, quadric)):
                return None                                  # along a ruling: a segment of tangency
            if away < 0:
                return []
            x = math.sqrt(away * (math.sqrt(rho) + abs(d)))
            local = [(LINE, [[q0[i] + s * x * e1[i] for i in range(3)], zero, e2]) for s in (1.0, -1.0)]
        elif name == "cone" and B != 0.0:                    # parallel to a generatrix: y = -(x^2 + C) / (2 B)
            local = [(PARABOLA, [[q0[i] - C / (2.0 * B) * e2[i] for i in range(3)], [-x / (2.0 * B) for x in e2],
                                 e1])]
        else:
            return None
    else:
        y0 = -B / A
        # (a sphere's: R^2 - d^2 as (R - |d|)(R + |d|), which keeps its relative accuracy beside a tangency)
        K = (math.sqrt(rho) - abs(d)) * (math.sqrt(rho) + abs(d)) if name == "sphere" else A * y0 * y0 - C
        if A > 0 and K <= 0:
            return []
        if K == 0 or max(abs(y0), math.sqrt(abs(K)), math.sqrt(abs(K / A))) > LARGE * scale:
            return None
        centre = [b0 + y0 * a0, b1 + y0 * a1, b2 + y0 * a2]
        if A > 0:
            major, minor = math.sqrt(K / A), math.sqrt(K)
            if (name == "sphere" or sin <= SAME) and not any(map(math.isfinite, plane.bounds)):
                if not inside_axial(quadric, centre[2], graze):
                    return None if inside_axial(quadric, centre[2], -graze) else ()
                axis = normal if name == "sphere" else quadric.z
                return np.array(combine([origin, to_global(rot, centre), zero], 1.0, 0.0)), np.array(axis), minor
            if minor <= major:
                local = [(ELLIPSE, [centre, [minor * e1[0], minor * e1[1], minor * e1[2]],
                                    [major * a0, major * a1, major * a2]])]
            else:
                local = [(ELLIPSE, [centre, [major * a0, major * a1, major * a2],
                                    [-minor * e1[0], -minor * e1[1], -minor * e1[2]]])]
        else:                                                # a hyperbola's two branches
            u, v = (e2, e1) if K < 0 else (e1, e2)
            ku, kv = (math.sqrt(K / A), math.sqrt(-K)) if K < 0 else (math.sqrt(K), math.sqrt(-K / A))
            local = [(HYPERBOLA, [centre, [s * ku * x for x in u], [kv * x for x in v]]) for s in (1.0, -1.0)]
    out = []
    for shape, (c, P, Q) in local:
        c0, c1, c2 = to_global(rot, c)
        out.append((shape, [[o0 + c0, o1 + c1, o2 + c2], to_global(rot, P), to_global(rot, Q)]))
    return out


def apex_components(surfaces, placed, plane, cone, graze, gap, settings, topo):
    """a ∩ b for a plane through a cone's apex (to round-off): the double cone's rulings w = (tan cos phi,
    tan sin phi, 1) (local) in the plane, n . w = 0. Tilted from the axis by more than the half angle, the plane
    meets the cone in the apex alone (a contact point, where the apex lies inside both trims); by less, in two
    rulings crossing at the apex (each clipped by the trims, the apex their node). None (declined) where the plane
    is within graze of tangent to the cone along a ruling, or a ruling is unbounded."""
    n0, n1, n2 = to_local(cone.rot, plane.z)
    tan = math.sqrt(-cone.form[0])
    reach = tan * math.hypot(n0, n1)                # n . w = n2 + reach cos(phi - psi): zero for two phi, one, none
    if abs(reach - abs(n2)) <= graze / settings.scale:
        return None                                          # tangent along a ruling (or nearly)
    trims = linear_trims(placed)
    if trims is None:
        return None
    apex = cone.origin
    if reach < abs(n2):
        inside = all((dot(w, apex) - bound) * side <= gap for w, bound, side, _ in trims)
        return [contact_point(surfaces, apex, settings.tolerance)] if inside else []
    psi, half = math.atan2(n1, n0), math.acos(-n2 / reach)
    lines = []
    for phi in (psi - half, psi + half):
        w = [tan * math.cos(phi), tan * math.sin(phi), 1.0]
        size = math.sqrt(dot(w, w))
        lines.append((LINE, [list(apex), [0.0, 0.0, 0.0], to_global(cone.rot, [x / size for x in w])]))
    return components(placed, lines, trims, graze, gap, settings, topo, nodes=[list(apex)])


def torus_parallels(plane, torus, graze):
    """[(ELLIPSE, rows)] (global) of a trimmed plane normal to a torus's axis: the parallels of radius
    R +- sqrt(r^2 - d^2) at the plane's height d, [] where it misses the tube; None (declined) where the plane is
    not normal to the axis, within graze of touching the tube, or where the inner parallel nearly collapses (a
    spindle or horn torus near its axis points). An untrimmed plane is left to the coaxial search (its circles are
    whole)."""
    if not any(map(math.isfinite, plane.bounds)):
        return None
    axis = torus.z
    if dot(cross_list(plane.z, axis), cross_list(plane.z, axis)) > PARALLEL_A:
        return None
    (o0, o1, o2), (p0, p1, p2) = torus.origin, plane.origin
    d = dot(axis, (p0 - o0, p1 - o1, p2 - o2))
    big, small = torus.form
    if abs(abs(d) - small) <= graze:
        return None                                          # touching the tube along a circle
    if abs(d) > small:
        return []
    half = math.sqrt(small * small - d * d)
    if big - half <= graze:
        return None
    centre = [o0 + d * axis[0], o1 + d * axis[1], o2 + d * axis[2]]
    e1, e2 = torus.rot[0::3], torus.rot[1::3]
    return [(ELLIPSE, [centre, [rho * x for x in e1], [rho * x for x in e2]]) for rho in (big + half, big - half)]


def inside_axial(quadric, z, margin):
    """True when the local height z lies inside the quadric's (Placed) v trim by more than margin (a sphere:
    always)."""
    lo, hi = quadric.bounds[2:]
    return lo + margin < z < hi - margin


# --- clipping ----------------------------------------------------------------------------------------------------
def linear_trims(surfaces):
    """[(w (3,), bound, side, (surface index, edge index))] of every finite trim of the surfaces (Placed):
    x . w - bound <= 0 inside when side is 1 (an upper bound), >= 0 when it is -1 (a trimmed parameter is a length
    along a local axis: x . w - w . origin); None if a finite trim is not such a length."""
    first = surfaces[0].surface.memo("linear_trims_a", own_trims_a)
    second = surfaces[1].surface.memo("linear_trims_b", own_trims_b)
    return None if first is None or second is None else first + second


def own_trims(surface, k):
    """linear_trims' rows of one surface, its index k in the pair."""
    surf = surface.memo("placed", Placed)
    trims = []
    axes = surf.kind.parameter_axes
    o0, o1, o2 = surf.origin
    for j, value in enumerate(surf.bounds):
        if math.isfinite(value):
            axis = axes[j // 2]
            if axis is None:
                return None
            w = surf.rot[axis::3]
            trims.append((w, value + (w[0] * o0 + w[1] * o1 + w[2] * o2), 1.0 if j % 2 else -1.0, (k, j)))
    return trims


own_trims_a = functools.partial(own_trims, k=0)
own_trims_b = functools.partial(own_trims, k=1)


def crossings(shape, beta, gamma, level, graze, touch):
    """The t where beta f(t) + gamma g(t) = level (see spatialkin.tracing.closed.conic for f, g); TOUCH where an
    ellipse's extremum meets the level within touch (the round-off of the coordinates: a double root, no crossing); None
    where a hyperbola's or parabola's vertex touches the level within graze, or a line runs along it."""
    if shape == ELLIPSE:
        amp = math.hypot(beta, gamma)
        if abs(amp - abs(level)) <= touch:
            return TOUCH
        if abs(level) >= amp:
            return []
        phi, half = math.atan2(gamma, beta), math.acos(level / amp)
        return [(phi - half) % TWO_PI, (phi + half) % TWO_PI]
    if shape == HYPERBOLA:
        if abs(beta) > abs(gamma) and abs(level - math.copysign(math.sqrt(beta * beta - gamma * gamma), beta)) <= graze:
            return None
        return [math.log(z) for z in quadratic(beta + gamma, -2.0 * level, beta - gamma) if z > 0]  # z = e^t
    if shape == PARABOLA:
        if beta != 0.0 and abs(level + gamma * gamma / (4.0 * beta)) <= graze:
            return None
        return quadratic(beta, gamma, -level)
    if abs(gamma) <= SAME:
        return None if abs(level) <= graze else []
    return [level / gamma]


def quadratic(a2, a1, a0):
    """Real roots of a2 x^2 + a1 x + a0 = 0 (stable form; linear where a2 = 0)."""
    if a2 == 0.0:
        return [] if a1 == 0.0 else [-a0 / a1]
    disc = a1 * a1 - 4.0 * a2 * a0
    if disc < 0.0:
        return []
    q = -0.5 * (a1 + math.copysign(math.sqrt(disc), a1))
    return [q / a2] if q == 0.0 else [q / a2, a0 / q]


def clip(shape, rows, trims, graze, touch):
    """[(t_lo, t_hi, ends)] of the arcs of the conic inside every trim; ends is None for a whole ellipse, else
    ((surface, edge) at t_lo, at t_hi); t_lo == t_hi for a single point (a line through a corner, an ellipse
    touching an edge from outside); None where declined (a vertex's touch, an unbounded arc). An ellipse touching
    an edge from inside (within touch) is not cut there; crossings within touch of each other (a corner) are one
    end; a line along an edge is inside it or outside whole."""
    if shape == LINE:
        arc = line_arc(rows, trims, touch)
        if arc is not None:
            return arc
    (c0, c1, c2), (p0, p1, p2), (q0, q1, q2) = rows
    linear = []                                     # (alpha, beta, gamma, side): the trim's alpha + beta f + gamma g
    events = []
    only = None                                     # (t, edge): an ellipse outside a trim but for its touch point
    for (w0, w1, w2), bound, side, edge in trims:
        alpha = w0 * c0 + w1 * c1 + w2 * c2 - bound         # (dot(w, rows[k]) written out)
        beta = w0 * p0 + w1 * p1 + w2 * p2
        gamma = w0 * q0 + w1 * q1 + w2 * q2
        if shape == LINE and abs(gamma) <= SAME:             # a line along the trim's level: all in or all out
            if alpha * side > touch:
                return []
            continue                                         # inside (on the edge within round-off): not cut
        roots = crossings(shape, beta, gamma, -alpha, graze, touch)
        if roots is TOUCH:        # the ellipse's far extremum tells its side of the level it touches
            far = math.atan2(gamma, beta) + (math.pi if -alpha > 0.0 else 0.0)
            f, g = basis(shape, far, 0, math)
            if (alpha + beta * f + gamma * g) * side > touch:
                only = ((far + math.pi) % TWO_PI, edge)     # outside but for the touch point
            continue                                         # inside: not cut, and not tested again
        if roots is None:
            return None
        linear.append((alpha, beta, gamma, side))
        for t in roots:
            events.append((t, edge))
    if only is not None:                            # that point, where it lies inside the other trims
        return [(only[0], only[0], (only[1], only[1]))] if within(linear, shape, only[0], touch) else []
    events.sort()
    periodic = shape == ELLIPSE

    def inside(t):
        f, g = basis(shape, t, 0, math)
        for alpha, beta, gamma, side in linear:
            if not (alpha + beta * f + gamma * g) * side <= 0.0:
                return False
        return True

    if not events:
        if inside(0.0):
            return [(0.0, TWO_PI, None)] if periodic else None
        return []
    if periodic:
        events.append((events[0][0] + TWO_PI, events[0][1]))
    elif inside(events[0][0] - 1.0) or inside(events[-1][0] + 1.0):
        return None                                          # an unbounded arc
    kept, last = [], None
    for t, edge in events:
        f, g = basis(shape, t, 0, math)
        point = (c0 + f * p0 + g * q0, c1 + f * p1 + g * q1, c2 + f * p2 + g * q2)      # (combine(rows, f, g))
        if last is None or math.dist(last, point) > touch:
            kept.append((t, edge))
        last = point                     # (a corner: two trims crossed at one point, kept once)
    arcs = [(t0, t1, (e0, e1)) for (t0, e0), (t1, e1) in zip(kept, kept[1:]) if inside(0.5 * (t0 + t1))]
    if shape == LINE:                    # a line that meets the faces in one point of their edges (a corner)
        ends = {t for t0, t1, _ in arcs for t in (t0, t1)}
        arcs += [(t, t, (edge, edge)) for t, edge in kept if t not in ends and within(linear, shape, t, touch)]
    return arcs


def line_arc(rows, trims, touch):
    """clip's answer for a line in the plain case, in one pass (the line inside every trim runs from its largest
    lower bound to its smallest upper one): [(t_lo, t_hi, ends)] when both bounds exist, the line runs along no
    trim, and every other crossing violates the trim of the bound beyond it by more than twice touch (so no two
    crossings make a corner and none is a touch point: clip's events give this one arc, at the same t); else None
    (clip's general path decides)."""
    (c0, c1, c2), _, (q0, q1, q2) = rows
    lows, highs = [], []                            # (t, |gamma|, edge) of the lower and the upper bounds
    for (w0, w1, w2), bound, side, edge in trims:
        alpha = w0 * c0 + w1 * c1 + w2 * c2 - bound         # (as clip computes it)
        gamma = w0 * q0 + w1 * q1 + w2 * q2
        if abs(gamma) <= SAME:
            return None                                      # (along the trim's level)
        (highs if gamma * side > 0.0 else lows).append((-alpha / gamma, abs(gamma), edge))
    if not lows or not highs:
        return None
    t_lo, g_lo, e_lo = max(lows)                    # (a tie in t is a corner: declined below)
    t_hi, g_hi, e_hi = min(highs)
    margin = 2.0 * touch
    if not (t_hi - t_lo) * min(g_lo, g_hi) > margin:
        return None
    for t, _, edge in lows:
        if edge != e_lo and not (t_lo - t) * g_lo > margin:
            return None
    for t, _, edge in highs:
        if edge != e_hi and not (t - t_hi) * g_hi > margin:
            return None
    return [(t_lo, t_hi, (e_lo, e_hi))]


def within(linear, shape, t, touch):
    """True when the point at t of the conic lies inside every trim (linear: clip's rows) within touch."""
    f, g = basis(shape, t, 0, math)
    return all((alpha + beta * f + gamma * g) * side <= touch for alpha, beta, gamma, side in linear)


# --- the components ----------------------------------------------------------------------------------------------
def normal(surf, point):
    """The surface's (Placed) normal at a point on it: a positive multiple of S_u x S_v (the gradient of its
    implicit function: diag(1, 1, mu) q for a quadric, q - R (x, y, 0) / |(x, y)| for a torus, local z for a
    plane)."""
    if surf.form is None:
        return surf.z
    (o0, o1, o2), (r00, r01, r02, r10, r11, r12, r20, r21, r22) = surf.origin, surf.rot
    x0, x1, x2 = point[0] - o0, point[1] - o1, point[2] - o2
    q0, q1, q2 = (r00 * x0 + r10 * x1 + r20 * x2, r01 * x0 + r11 * x1 + r21 * x2,
                  r02 * x0 + r12 * x1 + r22 * x2)                                      # (to_local)
    if surf.name == "torus":
        ring = surf.form[0] / math.hypot(q0, q1)             # q less its nearest point of the core circle
        q0, q1 = q0 - ring * q0, q1 - ring * q1
    else:
        q2 *= surf.form[0]
    return [r00 * q0 + r01 * q1 + r02 * q2, r10 * q0 + r11 * q1 + r12 * q2,
            r20 * q0 + r21 * q1 + r22 * q2]                                             # (to_global)


def along_normals(placed, circle):
    """The circle (centre, unit axis, radius) that the surfaces (Placed) cross, its axis turned where need be so that
    it runs along N_a x N_b, as a traced curve and every conic here do (CircleSolution runs counterclockwise about its
    axis): N_a x N_b keeps its sense all round such a circle, read at one point of it. A circle of two spheres, whose
    axis runs from a's centre to b's, runs that way already (N_a x N_b = (c_b - c_a) x (x - c_a))."""
    centre, axis, radius = circle
    w0, w1, w2 = axis
    least = min(range(3), key=lambda k: abs(axis[k]))          # (a coordinate axis least aligned with it)
    e = cross_list(axis, [1.0 if k == least else 0.0 for k in range(3)])
    size = radius / math.sqrt(dot(e, e))
    point = [centre[0] + size * e[0], centre[1] + size * e[1], centre[2] + size * e[2]]
    along = cross_list(normal(placed[0], point), normal(placed[1], point))
    if dot(along, cross_list(axis, e)) < 0.0:
        return centre, [-w0, -w1, -w2], radius
    return circle


def normals_at(placed, point):
    """(sine, N_a, N_b, N_a x N_b) of the surfaces (Placed) at a point on both: their normals (normal), their cross
    product, and the sine of their angle squared (0 where a normal vanishes, at a cone's apex)."""
    na, nb = normal(placed[0], point), normal(placed[1], point)
    along = cross_list(na, nb)
    sizes = dot(na, na) * dot(nb, nb)
    return (dot(along, along) / sizes if sizes > 0.0 else 0.0), na, nb, along


def component(placed, shape, rows, t_lo, t_hi, ends, settings, topo, nodes=()):
    """The CurveResult of the arc t in [t_lo, t_hi] (ends None: the whole closed conic) of the surfaces (Placed),
    run along N_a x N_b at its middle; None where the surfaces are nearly tangent there. nodes: the points (3,) on
    the arc where it crosses another conic of the pair (its nodes; with nodes the arc is run along N_a x N_b at the
    middle of the piece between two nodes, or a node and an end, where the normals' angle is largest, the first of
    those that tie (PROBE_TIE): N_a x N_b vanishes at the nodes and turns round along the curve there)."""
    if len(nodes):
        read = [(t, normals_at(placed, combine(rows, *basis(shape, t, 0, math))))
                for t in piece_middles(shape, rows, t_lo, t_hi, ends is None, nodes)]
        top = (1.0 - PROBE_TIE) * max(sine for _, (sine, _, _, _) in read)
        t_mid, (_, na, nb, along) = next(probe for probe in read if probe[1][0] >= top)   # (the first that ties)
    else:
        t_mid = 0.5 * (t_lo + t_hi)
        _, na, nb, along = normals_at(placed, combine(rows, *basis(shape, t_mid, 0, math)))
    centre, P, Q = rows
    tangent = Q if shape == LINE else combine([[0.0] * 3, P, Q], *basis(shape, t_mid, 1, math))
    if dot(along, along) < settings.singular_tol ** 2 * dot(na, na) * dot(nb, nb):
        return None
    if dot(along, tangent) < 0:
        Q, t_lo, t_hi = [-x for x in Q], -t_hi, -t_lo       # run it backwards: C(-t), g odd
        ends = None if ends is None else ends[::-1]
    closed = ends is None
    surfaces = (placed[0].surface, placed[1].surface)
    conic = Conic(shape, centre, P, Q, t_lo, t_hi)
    sol = ConicSolution(surfaces, conic, t_lo, t_hi, closed)    # (its points and parameters made on first use)
    if shape == PARABOLA and max(float(np.max(surf.distance(sol.samples()[0]))) for surf in surfaces) > (
            PARABOLA_CHECK * settings.tolerance):
        return None                                          # not quite parallel to the generatrix
    length = sol.length
    status = CLOSED if closed else BOUNDARY                 # (arc_message's: closed, or both ends on an edge)
    extra = {"nodes": np.array(nodes, dtype=float).reshape(-1, 3)} if len(nodes) else {}
    return SampledResult(closed=closed, length=length, status=status, tolerance=settings.tolerance, sol=sol,
                         topology=topo, message_of=functools.partial(arc_message, ends, length), **extra)


def piece_middles(shape, rows, t_lo, t_hi, closed, nodes):
    """The parameters t of the middles of the pieces into which the nodes (points (3,) on it) cut the arc
    [t_lo, t_hi] of an ellipse (rows = centre, P, Q with P normal to Q) or a line (centre + t Q), in order along it
    (a node at an end, a line's apex, leaves no piece there); closed: the whole ellipse, whose pieces run round from
    the last node to the first."""
    if shape == LINE:
        cuts = sorted(min(max(parameter_at(shape, rows, x), t_lo), t_hi) for x in nodes)
    else:                                                   # (each one's turn within [t_lo, t_lo + 2 pi))
        cuts = sorted(min(max(t_lo + (parameter_at(shape, rows, x) - t_lo) % TWO_PI, t_lo), t_hi) for x in nodes)
    pairs = zip(cuts, cuts[1:] + [cuts[0] + TWO_PI]) if closed else zip([t_lo] + cuts, cuts + [t_hi])
    return [0.5 * (t0 + t1) for t0, t1 in pairs if t1 > t0] or [0.5 * (t_lo + t_hi)]


def arc_message(ends, length):
    """The message of a component of the given length: closed (ends None), or open from the edge ends[0]
    ((surface index, edge index)) at s = 0 to the edge ends[1] at s = length (SampledResult makes it on first
    access)."""
    if ends is None:
        return outcome("closed", s=length)[1]
    (k0, j0), (k1, j1) = ends
    return open_outcome(BOUNDARY, outcome("edge", edge=EDGE_NAMES[j0], surface="ab"[k0], s=0.0)[1],
                        BOUNDARY, outcome("edge", edge=EDGE_NAMES[j1], surface="ab"[k1], s=length)[1])[1]
