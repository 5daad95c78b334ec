"""sk.intersect in closed form for the pairs that meet in conics: plane-plane (a line), plane-sphere and
sphere-sphere (a circle), plane-cylinder (an ellipse, or two lines along the axis) and plane-cone (an ellipse, a
parabola or a hyperbola), each clipped by the trims.

A plane cuts a quadric q^T diag(1, 1, mu) q = rho (local coordinates: a sphere, a cylinder, a double cone) in
the conic x^2 + A y^2 + 2 B y + C = 0 of the plane's coordinates along e1 = n x z (normal to the axis) and
e2 = n x e1; its sign of A tells the shape. Every trim (a plane's u or v, a cylinder's or cone's v) is a linear
function of the point, so its crossings with the conic are roots in closed form (R cos(t - phi) = c, a quadratic in
e^t, in t, or a linear equation). The arcs between crossings that lie inside every trim are the components,
oriented as the tracer runs them (along N_a x N_b), sampled as exact points with exact arc lengths
(spatialkin.tracing.conic).

``closed_form`` declines (returns None, and sk.intersect runs its general path) on everything degenerate: a
tangency or a touch of a trim edge or corner within GRAZE x tolerance, a plane through a cone's apex, coincident
surfaces, near-parallel configurations whose conic would be huge, both surfaces unbounded.
"""
import math

import numpy as np

from ..kernels import surfaces as ks
from .conic import ELLIPSE, HYPERBOLA, LINE, PARABOLA, Conic, ConicSolution
from .exact import exact_curve
from .placement import SAME
from .result import CurveResult
from .status import BOUNDARY, open_outcome, outcome
from .topology import Topology
from .traits import traits

#: A curve within this many times the tolerance of touching a trim level, a corner, or the other surface
#: (tangency, a plane through an apex) is left to the general path.
GRAZE = 1e3
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
#: The edges of a trim, in the order of the bounds in a surface's data.
EDGES = ("u_min", "u_max", "v_min", "v_max")
#: The quadrics a plane is cut with here.
QUADRICS = ("sphere", "cylinder", "cone")
TWO_PI = 2.0 * math.pi


def closed_form(a, b, settings):
    """The components of a ∩ b (CurveResults, longest first, as sk.intersect sorts them), or None when the pair
    or its placement is not handled here (see the module docstring)."""
    names = (traits(a).name, traits(b).name)
    if not (math.isfinite(traits(a).extent(a)) or math.isfinite(traits(b).extent(b))):
        return None
    graze = GRAZE * settings.tolerance
    topo = Topology(P=a, Q=b, mode=MODE)
    if names == ("sphere", "sphere"):
        circle = sphere_circle(a, b, graze, settings.scale)
        if not circle:
            return None if circle is None else []
        return [exact_curve((a, b), settings.tolerance, circle=circle, event="axis_circle", topology=topo)]
    if names == ("plane", "plane"):
        conics = plane_line(a, b, graze, settings.scale)
    elif "plane" in names and (names[0] in QUADRICS or names[1] in QUADRICS):
        plane, quadric = (a, b) if names[0] == "plane" else (b, a)
        found = plane_conics(plane, quadric, graze, settings.scale)
        if isinstance(found, tuple):                        # a circle about a common axis: as the general path
            return [] if found == () else [exact_curve((a, b), settings.tolerance, circle=found,
                                                       event="axis_circle", topology=topo)]
        conics = found
    else:
        return None
    if conics is None:
        return None
    trims = linear_trims((a, b))
    if trims is None:
        return None
    curves = []
    for shape, centre, P, Q in conics:
        arcs = clip(shape, centre, P, Q, trims, graze)
        if arcs is None:
            return None
        for t_lo, t_hi, ends in arcs:
            curve = component((a, b), shape, centre, P, Q, t_lo, t_hi, ends, settings, topo)
            if curve is None or curve.length > MAX_LENGTH_SHARE * settings.max_length:
                return None                                  # (the tracer would stop at max_length)
            curves.append(curve)
    curves.sort(key=lambda c: (-c.length, tuple(np.round(c.points[0], 9))))
    return curves


# --- the conics ------------------------------------------------------------------------------------------------
def sphere_circle(a, b, graze, scale):
    """(centre, axis, radius) of the circle of two spheres, the axis from a's centre to b's (as the topology
    stage's common axis); () when they do not meet; None near tangency or coincidence."""
    d = b.frame.origin - a.frame.origin
    dist = float(np.linalg.norm(d))
    ra, rb = a.radius, b.radius
    if dist <= SAME * scale:
        return None if abs(ra - rb) <= graze else ()
    if min(abs(dist - ra - rb), abs(dist - abs(ra - rb))) <= graze:
        return None
    if dist > ra + rb or dist < abs(ra - rb):
        return ()
    axis = d / dist
    x = 0.5 * (dist * dist + ra * ra - rb * rb) / dist
    return a.frame.origin + x * axis, axis, math.sqrt(ra * ra - x * x)


def plane_line(a, b, graze, scale):
    """[(LINE, point, 0, unit direction)] of two planes; [] for parallel planes apart; None for (nearly) coplanar
    ones or a line farther than LARGE x scale."""
    n1, n2 = a.frame.rotation[:, 2], b.frame.rotation[:, 2]
    cross = cross3(n1, n2)
    sin = math.sqrt(cross @ cross)
    gap = float(n2 @ (b.frame.origin - a.frame.origin))
    if sin <= SAME:
        return None if abs(gap) <= graze else []
    offset = (gap / (sin * sin)) * cross3(cross, n1)      # a's origin to its foot on the line
    if abs(gap) > LARGE * scale * sin:
        return None
    return [(LINE, a.frame.origin + offset, np.zeros(3), cross / sin)]


def quadric_form(quadric):
    """(mu, rho): the quadric is x^2 + y^2 + mu z^2 = rho in its local coordinates."""
    name = traits(quadric).name
    if name == "sphere":
        return 1.0, quadric.radius ** 2
    if name == "cylinder":
        return 0.0, quadric.radius ** 2
    tan = quadric.data[ks.P1]
    return -tan * tan, 0.0


def plane_conics(plane, quadric, graze, scale):
    """[(shape, centre, P, Q)] (global) of the plane and the quadric; a tuple (centre, axis, radius) for the
    circle of an untrimmed plane about the quadric's axis (or a sphere's), () when nothing is there; None where
    declined."""
    rot, origin = quadric.frame.rotation, quadric.frame.origin
    normal = plane.frame.rotation[:, 2]
    n = rot.T @ normal
    d = float(normal @ (plane.frame.origin - origin))       # the plane: n . q = d (local)
    mu, rho = quadric_form(quadric)
    name = traits(quadric).name
    if name == "sphere" and abs(abs(d) - math.sqrt(rho)) <= graze:
        return None                                          # tangent
    if name == "cone" and abs(d) <= graze:
        return None                                          # through the apex
    e1 = np.array([n[1], -n[0], 0.0])                        # n x z
    sin = math.hypot(n[0], n[1])
    if sin <= SAME:
        e1, sin = np.array([1.0, 0.0, 0.0]), 0.0
    e1 /= math.sqrt(e1 @ e1)
    e2 = cross3(n, e1)
    q0 = d * n
    weights = np.array([1.0, 1.0, mu])
    A = float(weights @ (e2 * e2))
    B = float(weights @ (e2 * q0))
    C = float(weights @ (q0 * q0)) - rho
    coaxial = name == "sphere" or sin <= SAME
    trimmed = np.isfinite(plane.data[ks.BOUNDS:ks.BOUNDS + 4]).any()
    local = []
    if abs(A) <= (PARABOLA_A if name == "cone" else PARALLEL_A):
        if name == "cylinder":                               # parallel to the axis: two lines x = +-sqrt(-C)
            if abs(math.sqrt(rho) - abs(d)) <= graze:
                return None
            if C > 0:
                return []
            x = math.sqrt(-C)
            local = [(LINE, q0 + x * e1, np.zeros(3), e2), (LINE, q0 - x * e1, np.zeros(3), e2)]
        elif name == "cone" and B != 0.0:                    # parallel to a generatrix: y = -(x^2 + C) / (2 B)
            local = [(PARABOLA, q0 - C / (2.0 * B) * e2, -e2 / (2.0 * B), e1)]
        else:
            return None
    else:
        y0 = -B / A
        K = A * y0 * y0 - C
        if A > 0 and K <= 0:
            return []
        if max(abs(y0), math.sqrt(abs(K)), math.sqrt(abs(K / A))) > LARGE * scale or K == 0:
            return None
        centre = q0 + y0 * e2
        if A > 0:
            major, minor = math.sqrt(K / A), math.sqrt(K)
            if coaxial and not trimmed:
                if not inside_axial(quadric, centre[2], graze):
                    return None if inside_axial(quadric, centre[2], -graze) else ()
                axis = normal if name == "sphere" else rot[:, 2]
                return origin + rot @ centre, axis, minor
            P, Q = (minor * e1, major * e2) if minor <= major else (major * e2, -minor * e1)
            local = [(ELLIPSE, centre, P, Q)]
        elif K < 0:
            local = [(HYPERBOLA, centre, sign * math.sqrt(K / A) * e2, math.sqrt(-K) * e1) for sign in (1.0, -1.0)]
        else:
            local = [(HYPERBOLA, centre, sign * math.sqrt(K) * e1, math.sqrt(-K / A) * e2) for sign in (1.0, -1.0)]
    return [(shape, origin + rot @ c, rot @ P, rot @ Q) for shape, c, P, Q in local]


def inside_axial(quadric, z, margin):
    """True when the local height z lies inside the quadric's v trim by more than margin (a sphere: always)."""
    lo, hi = quadric.data[ks.BOUNDS + 2:ks.BOUNDS + 4]
    return lo + margin < z < hi - margin


# --- clipping ----------------------------------------------------------------------------------------------------
class Trims:
    """The finite trims of two surfaces as linear functions of the point x: trim i holds x . w[i] - bound[i] on
    the inside side (side[i] (x . w[i] - bound[i]) <= 0); edges[i] is (surface index, edge index)."""

    def __init__(self, w, bound, side, edges):
        self.w, self.bound, self.side, self.edges = w, bound, side, edges


def linear_trims(surfaces):
    """The Trims of both surfaces (a trimmed parameter is a length along a local axis: x . w - w . origin); None
    if a finite trim is not such a length."""
    rows, bounds, edges = [], [], []
    for k, surf in enumerate(surfaces):
        axes = traits(surf).parameter_axes
        for j, value in enumerate(surf.data[ks.BOUNDS:ks.BOUNDS + 4].tolist()):
            if math.isfinite(value):
                axis = axes[j // 2]
                if axis is None:
                    return None
                w = surf.frame.rotation[:, axis]
                rows.append(w)
                bounds.append(value + float(w @ surf.frame.origin))
                edges.append((k, j))
    w = np.array(rows).reshape(-1, 3)
    return Trims(w, np.array(bounds), np.array([1.0 if j % 2 else -1.0 for _, j in edges]), edges)


def crossings(shape, beta, gamma, level, graze):
    """The t where beta f(t) + gamma g(t) = level (see spatialkin.tracing.conic for f, g); None where the conic
    touches the level within graze (its extremum there, or a line along it)."""
    if shape == ELLIPSE:
        amp = math.hypot(beta, gamma)
        if abs(amp - abs(level)) <= graze:
            return None
        if abs(level) > amp:
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
    if gamma == 0.0 or abs(gamma) <= SAME:
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


def clip(shape, centre, P, Q, trims, graze):
    """[(t_lo, t_hi, ends)] of the arcs of the conic inside every trim; ends is None for a whole ellipse, else
    ((surface, edge) at t_lo, at t_hi); None where declined (a touch, a corner, an unbounded arc)."""
    conic = Conic(shape, centre, P, Q)
    events = []
    for beta, gamma, level, (k, j) in zip((trims.w @ P).tolist(), (trims.w @ Q).tolist(),
                                          (trims.bound - trims.w @ centre).tolist(), trims.edges):
        roots = crossings(shape, beta, gamma, level, graze)
        if roots is None:
            return None
        events += [(t, (k, j)) for t in roots]
    events.sort()
    periodic = shape == ELLIPSE
    if not events:
        if inside(conic, trims, np.zeros(1))[0]:
            return [(0.0, TWO_PI, None)] if periodic else None
        return []
    ts = np.array([t for t, _ in events])
    if periodic:
        ts = np.append(ts, ts[0] + TWO_PI)
        events.append((ts[-1], events[0][1]))
    elif inside(conic, trims, np.array([ts[0] - 1.0, ts[-1] + 1.0])).any():
        return None                                          # an unbounded arc
    pts = conic.at(ts)
    if len(ts) > 1 and np.min(np.linalg.norm(np.diff(pts, axis=0), axis=1)) <= graze:
        return None                                          # a corner, or two trims crossed at one point
    keep = inside(conic, trims, 0.5 * (ts[1:] + ts[:-1]))
    return [(events[i][0], events[i + 1][0], (events[i][1], events[i + 1][1])) for i in np.flatnonzero(keep)]


def inside(conic, trims, t):
    """Mask (M,): the conic's points at t (M,) lie inside every trim."""
    excess = (conic.at(t) @ trims.w.T - trims.bound) * trims.side      # <= 0 inside
    return np.all(excess <= 0.0, axis=1)


# --- the components ----------------------------------------------------------------------------------------------
def normal(surf, point):
    """The surface's normal (3,) at a point on it: a positive multiple of S_u x S_v (the gradient of its implicit
    function: q diag(1, 1, mu) for a quadric, local z for a plane)."""
    rot = surf.frame.rotation
    if traits(surf).name == "plane":
        return rot[:, 2]
    q = (point - surf.frame.origin) @ rot
    q[2] *= quadric_form(surf)[0]
    return rot @ q


def cross3(x, y):
    """x x y of two 3-vectors (np.cross costs more than the product on such small arrays)."""
    return np.array([x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]])


def component(surfaces, shape, centre, P, Q, t_lo, t_hi, ends, settings, topo):
    """The CurveResult of the arc t in [t_lo, t_hi] (ends None: the whole closed conic), run along N_a x N_b; None
    where the surfaces are nearly tangent on it."""
    probe = Conic(shape, centre, P, Q)
    t_mid = np.array([0.5 * (t_lo + t_hi)])
    point = probe.at(t_mid)[0]
    na, nb = normal(surfaces[0], point), normal(surfaces[1], point)
    along = cross3(na, nb)
    sin = math.sqrt((along @ along) / ((na @ na) * (nb @ nb)))
    if sin < settings.singular_tol:
        return None
    if along @ probe.at(t_mid, 1)[0] < 0:                    # run it backwards: C(-t), g odd
        Q, t_lo, t_hi = -Q, -t_hi, -t_lo
        ends = None if ends is None else ends[::-1]
    closed = ends is None
    conic = Conic(shape, centre, P, Q, t_lo, t_hi)
    sol = ConicSolution(surfaces, conic, t_lo, t_hi, closed)
    points = conic.at(sol.t_knots)
    if closed:
        points[-1] = points[0]
    params = np.concatenate([surf.parameters(points) for surf in surfaces], axis=1)
    for k, surf in enumerate(surfaces):
        if traits(surf).periodic[0]:                         # unwrapped along the curve, as the tracer's
            u = params[:, 2 * k]
            u[1:] -= TWO_PI * np.cumsum(np.round(np.diff(u) / TWO_PI))
    sol.params = params
    if shape == PARABOLA and max(float(np.max(surf.distance(points))) for surf in surfaces) > (
            PARABOLA_CHECK * settings.tolerance):
        return None                                          # not quite parallel to the generatrix
    length = sol.length
    if closed:
        status, message = outcome("closed", s=length)
    else:
        (k0, j0), (k1, j1) = ends
        status, message = open_outcome(
            BOUNDARY, outcome("edge", edge=EDGES[j0], surface="ab"[k0], s=0.0)[1],
            BOUNDARY, outcome("edge", edge=EDGES[j1], surface="ab"[k1], s=length)[1])
    return CurveResult(points=points, s=sol.knots, params=params, closed=closed, length=length, status=status,
                       message=message, tolerance=settings.tolerance, sol=sol, topology=topo)
