"""OpenCascade's DRAW conventions for analytic surfaces, and their translation into spatialkin surfaces.

A ``Geo`` is a placed analytic surface exactly as OpenCascade defines it (Geom_Plane, Geom_CylindricalSurface,
Geom_ConicalSurface, Geom_SphericalSurface, Geom_ToroidalSurface), with the trims of a DRAW ``trim``/``trimu``/
``trimv``/``mkface`` in OpenCascade's own parameters. The independent truth (tests/oracles/occ/truth.py) reads a ``Geo``;
``to_sk`` turns it into the spatialkin surface, or raises ``NotExpressible`` naming the trim spatialkin has no
form for.

OpenCascade's parametrisations (position O, axes X, Y, Z, which a mirror can make left-handed):

- plane      P(u, v) = O + u X + v Y
- cylinder   P(u, v) = O + r (cos u X + sin u Y) + v Z
- cone       P(u, v) = O + (R + v sin a)(cos u X + sin u Y) + v cos a Z   (R the radius at O, not at the apex;
  a the signed semi-angle, |a| < pi/2; the apex is O - R / tan(a) Z; v runs along the generatrix)
- sphere     P(u, v) = O + r cos v (cos u X + sin u Y) + r sin v Z
- torus      P(u, v) = O + (R + r cos v)(cos u X + sin u Y) + r sin v Z

spatialkin's (spatialkin/geometry/surfaces/*.py): the same for the plane, cylinder, sphere and torus in a right-handed
frame; the cone has its apex at the frame origin, M(u, v) = frame(v tan(a) cos u, v tan(a) sin u, v) with
0 < a < pi/2 and v the axial coordinate. Trims: a plane's rectangle (u_range, v_range) and a disc or annulus
about its origin (radius, inner_radius); a cylinder's or cone's axial v_range and angular u_range; a sphere's
u_range and latitude v_range; a ring torus's u_range and tube angle v_range. The angle u about the axis is
OpenCascade's once the frames agree; a frame made right-handed by flipping Y (a mirrored placement, or a cone
of negative semi-angle, whose spatialkin frame turns Y and Z over) runs u the other way, so [u0, u1] becomes
[-u1, -u0]. On a cone both nappes use the same u, as in OpenCascade.

References
----------
OpenCascade Technology, Geom_ConicalSurface, gp_Ax3 (X direction of a placement given by its normal only) and the
DRAW commands ``plane``, ``cylinder``, ``cone``, ``sphere``, ``torus`` (GeomliteTest_SurfaceCommands.cxx),
``pcylinder``, ``pcone``, ``psphere``, ``ptorus``, ``box`` (BRepTest_PrimitiveCommands.cxx).
"""
import math
import re
from dataclasses import dataclass, replace

import numpy as np

TWO_PI = 2.0 * math.pi
#: A u-range at least this close to a full turn is the full turn (DRAW writes 2 pi as 6.28319 or 6.2831853...).
FULL_TURN_SLACK = 1e-5
KINDS = ("plane", "cylinder", "cone", "sphere", "torus")


class NotExpressible(ValueError):
    """A trim (or a pair) spatialkin has no form for."""


# --- DRAW arguments -------------------------------------------------------------------------------------------------
_TOKEN = re.compile(r"[0-9eE.+\-*/() ]|pi")


def value(text):
    """A DRAW numeric argument: a number or a small expression ('-10+1.0e-5', 'pi/2', '2*pi'); a trailing comma,
    as some scripts write between coordinates, is ignored."""
    text = text.strip().rstrip(",")
    if not text or "".join(_TOKEN.findall(text)) != text:
        raise ValueError(f"not a DRAW number: {text!r}")
    return float(eval(text, {"__builtins__": {}}, {"pi": math.pi}))


def values(text):
    return [value(t) for t in text.split()]


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def ax3(origin, normal=None, xdir=None):
    """(O, X, Y, Z) of gp_Ax3(P, N[, Vx]): X = Vx made normal to N, or, without Vx, OpenCascade's rule that zeroes
    the smallest component of N (gp_Ax3.cxx); Y = N x X (right-handed)."""
    o = np.asarray(origin, dtype=float)
    z = np.array([0.0, 0.0, 1.0]) if normal is None else unit(normal)
    if xdir is None:
        a, b, c = z
        aa, ba, ca = abs(a), abs(b), abs(c)
        if ba <= aa and ba <= ca:
            d = (-c, 0.0, a) if aa > ca else (c, 0.0, -a)
        elif aa <= ba and aa <= ca:
            d = (0.0, -c, b) if ba > ca else (0.0, c, -b)
        else:
            d = (-b, a, 0.0) if aa > ba else (b, -a, 0.0)
        xdir = np.array(d)
    x = unit(np.asarray(xdir, dtype=float) - (np.asarray(xdir, dtype=float) @ z) * z)
    return o, x, np.cross(z, x), z


# --- the placed surface ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Geo:
    """A placed OpenCascade analytic surface with optional trims in its own (u, v).

    params: cylinder/sphere ``r``; cone ``angle`` (signed semi-angle, radians) and ``radius`` (at O); torus ``R``
    and ``r``; a plane face bounded by a circle about O: ``radius`` (a disc) and ``inner_radius`` (an annulus).
    ``bound`` names the range ("v") added to an unbounded surface so that spatialkin accepts the pair (it contains
    the whole intersection, with margin).
    """

    kind: str
    o: tuple
    x: tuple
    y: tuple
    z: tuple
    params: dict
    u_range: tuple = None
    v_range: tuple = None
    bound: str = ""
    label: str = ""

    @property
    def axes(self):
        return np.array(self.o), np.array(self.x), np.array(self.y), np.array(self.z)

    @property
    def left_handed(self):
        _, x, y, z = self.axes
        return float(np.cross(x, y) @ z) < 0

    def transformed(self, rotation, translation=(0.0, 0.0, 0.0)):
        """The surface moved by p -> rotation @ p + translation (rotation may be a reflection)."""
        r = np.asarray(rotation, dtype=float)
        t = np.asarray(translation, dtype=float)
        o, x, y, z = self.axes
        return replace(self, o=tuple(r @ o + t), x=tuple(r @ x), y=tuple(r @ y), z=tuple(r @ z))

    def translated(self, v):
        return self.transformed(np.eye(3), v)

    def rotated(self, point, axis, degrees):
        """DRAW ``trotate name x y z dx dy dz angle``: about the line through point along axis, in degrees."""
        r = rotation(axis, math.radians(degrees))
        p = np.asarray(point, dtype=float)
        return self.transformed(r, p - r @ p)

    def mirrored(self, point, normal):
        """DRAW ``tmirror name x y z dx dy dz``: reflection in the plane through point with the given normal."""
        n = unit(normal)
        r = np.eye(3) - 2.0 * np.outer(n, n)
        p = np.asarray(point, dtype=float)
        return self.transformed(r, p - r @ p)

    def with_ranges(self, u_range=None, v_range=None, **kw):
        return replace(self, u_range=u_range, v_range=v_range, **kw)

    # --- cone helpers (OpenCascade's convention) -------------------------------------------------------------
    @property
    def apex(self):
        o, _, _, z = self.axes
        return o - self.params["radius"] / math.tan(self.params["angle"]) * z

    def cone_axial(self, v):
        """spatialkin's axial coordinate (from the apex, along the axis the radius grows on) of OCC's v."""
        a, big_r = self.params["angle"], self.params["radius"]
        return (big_r + v * math.sin(a)) / math.tan(abs(a))

    def describe(self):
        p = ", ".join(f"{k}={v:.15g}" for k, v in self.params.items() if v is not None)
        trims = []
        if self.u_range is not None:
            trims.append(f"u in [{self.u_range[0]:.15g}, {self.u_range[1]:.15g}]")
        if self.v_range is not None:
            trims.append(f"v in [{self.v_range[0]:.15g}, {self.v_range[1]:.15g}]")
        return f"{self.kind}({p}{'; ' if trims else ''}{', '.join(trims)})"


def rotation(axis, angle):
    k = unit(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * (kx @ kx)


#: Every analytic surface made from DRAW arguments, and every primitive face: (command, arguments, Geo), for the
#: check of the translation against OpenCascade itself (test_occ_cases.py).
MADE = []


def _make(kind, args, nparams, **kw):
    """A DRAW analytic surface command's arguments after the name: [x y z [dx dy dz [ux uy uz]]] params."""
    nums = values(args) if isinstance(args, str) else [float(a) for a in args]
    place, par = nums[:len(nums) - nparams], nums[len(nums) - nparams:]
    if len(place) == 0:
        o, x, y, z = ax3((0, 0, 0), (0, 0, 1), (1, 0, 0))
    elif len(place) == 3:
        o, x, y, z = ax3(place, (0, 0, 1), (1, 0, 0))
    elif len(place) == 6:
        o, x, y, z = ax3(place[:3], place[3:6])
    elif len(place) == 9:
        o, x, y, z = ax3(place[:3], place[3:6], place[6:9])
    else:
        raise ValueError(f"bad DRAW {kind} arguments: {args!r}")
    return o, x, y, z, par


def _made(command, args, g):
    MADE.append((command, args, g))
    return g


def _geo(kind, o, x, y, z, params, **kw):
    return Geo(kind, tuple(o), tuple(x), tuple(y), tuple(z), params, **kw)


def plane(args="", **kw):
    """DRAW ``plane name [x y z [dx dy dz [ux uy uz]]]``."""
    o, x, y, z, _ = _make("plane", args, 0)
    return _made("plane", args, _geo("plane", o, x, y, z, {}, **kw))


def cylinder(args, **kw):
    """DRAW ``cylinder name [x y z [dx dy dz [ux uy uz]]] radius``."""
    o, x, y, z, (r,) = _make("cylinder", args, 1)
    return _made("cylinder", args, _geo("cylinder", o, x, y, z, {"r": r}, **kw))


def cone(args, **kw):
    """DRAW ``cone name [x y z [dx dy dz [ux uy uz]]] semi-angle(degrees) radius``: radius at the origin."""
    o, x, y, z, (deg, radius) = _make("cone", args, 2)
    return _made("cone", args, _geo("cone", o, x, y, z, {"angle": math.radians(deg), "radius": radius}, **kw))


def sphere(args, **kw):
    """DRAW ``sphere name [x y z [dx dy dz [ux uy uz]]] radius``."""
    o, x, y, z, (r,) = _make("sphere", args, 1)
    return _made("sphere", args, _geo("sphere", o, x, y, z, {"r": r}, **kw))


def torus(args, **kw):
    """DRAW ``torus name [x y z [dx dy dz [ux uy uz]]] major minor``."""
    o, x, y, z, (big, small) = _make("torus", args, 2)
    return _made("torus", args, _geo("torus", o, x, y, z, {"R": big, "r": small}, **kw))


def trim(g, u0, u1, v0, v1):
    """DRAW ``trim`` / ``mkface f s u0 u1 v0 v1``."""
    return g.with_ranges((u0, u1), (v0, v1))


def place_of(plane_geo):
    """The gp_Ax2 a primitive takes from a DRAW plane argument (``pcone name plane ...``)."""
    return plane_geo.axes


# --- faces of DRAW primitives (their lateral faces, in OpenCascade's parametrisation) -------------------------------
def pcylinder_lateral(r, h, place=None, angle_deg=360.0):
    """Lateral face of ``pcylinder [plane] r h [angle]``: u in [0, angle], v in [0, h]."""
    o, x, y, z = place if place is not None else ax3((0, 0, 0), (0, 0, 1), (1, 0, 0))
    return _made("pcylinder", (r, h, place), _geo("cylinder", o, x, y, z, {"r": r},
                                                  u_range=(0.0, math.radians(angle_deg)), v_range=(0.0, h)))


def pcone_lateral(r1, r2, h, place=None, angle_deg=360.0):
    """Lateral face of ``pcone [plane] r1 r2 h``: BRepPrim_Cone, semi-angle atan((r2 - r1) / h), radius r1 at the
    base, v in [0, sqrt(h^2 + (r2 - r1)^2)]."""
    o, x, y, z = place if place is not None else ax3((0, 0, 0), (0, 0, 1), (1, 0, 0))
    return _made("pcone", (r1, r2, h, place),
                 _geo("cone", o, x, y, z, {"angle": math.atan((r2 - r1) / h), "radius": r1},
                      u_range=(0.0, math.radians(angle_deg)), v_range=(0.0, math.hypot(h, r2 - r1))))


def psphere_face(r, place=None):
    o, x, y, z = place if place is not None else ax3((0, 0, 0), (0, 0, 1), (1, 0, 0))
    return _made("psphere", (r, place), _geo("sphere", o, x, y, z, {"r": r}))


def ptorus_face(big, small, place=None, angle_deg=360.0):
    o, x, y, z = place if place is not None else ax3((0, 0, 0), (0, 0, 1), (1, 0, 0))
    full = angle_deg >= 360.0
    return _made("ptorus", (big, small, place), _geo("torus", o, x, y, z, {"R": big, "r": small},
                                                     u_range=None if full else (0.0, math.radians(angle_deg))))


def rectangle(corner, edge_u, edge_v, label=""):
    """A planar rectangular face: corner + s edge_u + t edge_v, s, t in [0, 1] (edges orthogonal)."""
    c = np.asarray(corner, dtype=float)
    eu, ev = np.asarray(edge_u, dtype=float), np.asarray(edge_v, dtype=float)
    lu, lv = np.linalg.norm(eu), np.linalg.norm(ev)
    if abs(eu @ ev) > 1e-12 * lu * lv:
        raise ValueError("rectangle edges must be orthogonal")
    x, y = eu / lu, ev / lv
    return _geo("plane", c, x, y, np.cross(x, y), {}, u_range=(0.0, lu), v_range=(0.0, lv), label=label)


def disc(centre, normal, radius, inner_radius=None, label=""):
    """A planar face bounded by the circle of this radius about centre in the plane of this normal (a
    ``pcylinder``'s or ``pcone``'s cap, a ``mkface`` of a circle, a revolved segment normal to the axis), less the
    disc of inner_radius (an annulus); the in-plane axes by gp_Ax3's rule (a disc has no preferred one)."""
    o, x, y, z = ax3(centre, normal)
    params = {"radius": float(radius)}
    if inner_radius is not None:
        params["inner_radius"] = float(inner_radius)
    return _geo("plane", o, x, y, z, params, label=label)


def strip(p0, p1, direction, label="", extent=None):
    """The face swept by the segment p0-p1 along a direction orthogonal to it (a prism's face): a plane with
    u along the segment in [0, |p1 - p0|] and v along the direction, unbounded or in extent."""
    p0 = np.asarray(p0, dtype=float)
    e = np.asarray(p1, dtype=float) - p0
    d = np.asarray(direction, dtype=float)
    if abs(e @ d) > 1e-12 * np.linalg.norm(e) * np.linalg.norm(d):
        raise ValueError("strip direction must be orthogonal to its segment")
    x, y = unit(e), unit(d)
    return _geo("plane", p0, x, y, np.cross(x, y), {}, u_range=(0.0, float(np.linalg.norm(e))),
                v_range=extent, label=label)


def box_faces(x0, y0, z0, dx, dy, dz):
    """The six faces of ``box [x0 y0 z0] dx dy dz`` in DRAW's explode order (Xmin, Xmax, Ymin, Ymax, Zmin, Zmax),
    each as the rectangle it is."""
    c = np.array([x0, y0, z0], dtype=float)
    ex, ey, ez = np.array([dx, 0, 0.0]), np.array([0, dy, 0.0]), np.array([0, 0, dz * 1.0])
    return [rectangle(c, ey, ez, "Xmin"), rectangle(c + ex, ey, ez, "Xmax"),
            rectangle(c, ez, ex, "Ymin"), rectangle(c + ey, ez, ex, "Ymax"),
            rectangle(c, ex, ey, "Zmin"), rectangle(c + ez, ex, ey, "Zmax")]


# --- to spatialkin --------------------------------------------------------------------------------------------------
def full_turn(r):
    return r is None or (r[1] - r[0]) >= TWO_PI - FULL_TURN_SLACK


def _frame(sk, o, x, y, z, left_handed):
    if left_handed:
        y = -np.asarray(y)
    return sk.Frame(o, np.column_stack([x, y, z]))


def _turn(g, sigma):
    """spatialkin's u_range of g's u trim (None for a full turn), sigma = -1 where the frame runs u the other way."""
    if full_turn(g.u_range):
        return None
    lo, hi = sigma * g.u_range[0], sigma * g.u_range[1]
    return (min(lo, hi), max(lo, hi))


def to_sk(g):
    """The spatialkin surface of a Geo, or NotExpressible naming what spatialkin cannot express."""
    import spatialkin as sk
    o, x, y, z = g.axes
    lh = g.left_handed
    p = g.params
    sigma = -1.0 if lh else 1.0

    if g.kind == "plane":
        if lh:                      # keep (u, v): turn the normal instead of an in-plane axis
            z = -z
        return sk.Plane(sk.Frame(o, np.column_stack([x, y, z])), g.u_range, g.v_range, radius=p.get("radius"),
                        inner_radius=p.get("inner_radius"))
    if g.kind == "cylinder":
        return sk.Cylinder(p["r"], _frame(sk, o, x, y, z, lh), g.v_range, u_range=_turn(g, sigma))
    if g.kind == "cone":
        s = 1.0 if p["angle"] > 0 else -1.0
        frame = _frame(sk, g.apex, x, s * y, s * z, lh)
        vr = None
        if g.v_range is not None:
            a, b = g.cone_axial(g.v_range[0]), g.cone_axial(g.v_range[1])
            vr = (min(a, b), max(a, b))
        return sk.Cone(abs(p["angle"]), frame, vr, u_range=_turn(g, s * sigma))
    if g.kind == "sphere":
        vr = g.v_range
        if vr is not None and vr[1] - vr[0] >= math.pi - 1e-9:
            vr = None
        return sk.Sphere(p["r"], _frame(sk, o, x, y, z, lh), u_range=_turn(g, sigma), v_range=vr)
    if g.kind == "torus":
        vr = g.v_range
        if vr is not None and vr[1] - vr[0] >= TWO_PI - FULL_TURN_SLACK:
            vr = None
        return sk.Torus(p["R"], p["r"], _frame(sk, o, x, y, z, lh), u_range=_turn(g, sigma), v_range=vr)
    raise NotExpressible(f"no spatialkin surface for {g.kind}")


def scale(g):
    """A characteristic length, as spatialkin states its tolerance: a radius, R + r, a trimmed cone's slant length,
    a trimmed plane's half-diagonal (a disc's: that of its bounding square) (None when it has none)."""
    p = g.params
    if g.kind in ("cylinder", "sphere"):
        return p["r"]
    if g.kind == "torus":
        return p["R"] + p["r"]
    if g.kind == "cone":
        if g.v_range is None:
            return None
        a, b = g.cone_axial(g.v_range[0]), g.cone_axial(g.v_range[1])
        return max(abs(a), abs(b)) / math.cos(p["angle"])
    if g.kind == "plane":
        ur, vr = g.u_range or (-math.inf, math.inf), g.v_range or (-math.inf, math.inf)
        if "radius" in p:               # spatialkin's bounds of a disc: the rectangle within its bounding square
            ur = (max(ur[0], -p["radius"]), min(ur[1], p["radius"]))
            vr = (max(vr[0], -p["radius"]), min(vr[1], p["radius"]))
        if not all(map(math.isfinite, (*ur, *vr))):
            return None
        return 0.5 * math.hypot(ur[1] - ur[0], vr[1] - vr[0])
    return None
