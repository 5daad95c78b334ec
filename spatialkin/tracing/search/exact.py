"""Exact common points of two surfaces about one axis, or along one, in rational arithmetic on the floats: the solvers
behind the exact certificates (spatialkin.tracing.certify.coaxial, .parallel).

A sphere, a torus (R > r), a cylinder, a cone and a plane normal to the axis, each placed by a frame whose rotation
is a signed permutation (entries -1, 0, 1: exactly orthogonal), are exactly surfaces of revolution about the line of
their frame's z axis. Where both lines are one line (the same coordinate axis, the same other two coordinates of the
origins; a sphere's centre on the other's line), a point lies on both surfaces exactly when its radius rho from the
axis and its coordinate h along it lie on both meridians: curves of the (rho, h) half-plane rho >= 0, each a circle
a (rho^2 + h^2) + b rho + c h + d = 0 or a line (a = 0) with rational coefficients (a sphere's and a torus's circle,
a cylinder's line rho = r, a plane's h = p, a cone's two rays rho = +-slope (h - apex), the slope its stored double
Cone.slope). Two of them meet where a quadratic with rational coefficients vanishes, solved exactly: its roots are
p + q sqrt(D) with rationals p, q, D, and every sign they are tested by (rho >= 0, a ray's side of the apex, a trim)
is decided exactly. A double root (D = 0) is a tangency of the meridians, so of the surfaces: a circle of tangency,
or, on the axis, a contact point. The intersection is then exactly one parallel circle per common point with rho > 0
and one point per common point on the axis, those inside the trims.

Likewise a cylinder and a plane so placed are exactly invariant along their frame's z axis (the cylinder) or an
in-plane axis (the plane); where both run along one coordinate axis e_k, a point lies on both exactly when its other
two coordinates lie on both cross-sections (a circle or a line, met as the meridians are: crossings), each common
point a line along e_k, cut by the trims along it into one segment (exact_segments).

Pairs outside this (a rotation that is not a signed permutation, trims that cut a circle into arcs, angular trims,
a horn or spindle torus, a circle or a segment on a trim edge) are not decided here (None).
"""
import math
from fractions import Fraction

import numpy as np

from ...geometry.surfaces import Cone, Cylinder, Plane, Sphere, Torus
from ...kernels.geometry import surfaces as ks


class Surd:
    """p + q sqrt(d) with rationals p, q and d >= 0 (d = 0 or q = 0: the rational p), exact."""

    __slots__ = ("p", "q", "d")

    def __init__(self, p, q=Fraction(0), d=Fraction(0)):
        self.p, self.q, self.d = Fraction(p), Fraction(q), Fraction(d)
        root = _rational_root(self.d)
        if root is not None:                                # (a square: one rational, so that equal values compare
            self.p, self.q, self.d = self.p + self.q * root, Fraction(0), Fraction(0)     # equal as keys)
        if self.q == 0 or self.d == 0:
            self.q, self.d = Fraction(0), Fraction(0)

    def __sub__(self, x):
        """self - x for a rational x."""
        return Surd(self.p - Fraction(x), self.q, self.d)

    def sign(self):
        """-1, 0 or 1: the exact sign (p and q sqrt(d) compared through their squares where their signs differ)."""
        sp, sq = _sign(self.p), _sign(self.q)
        if sq == 0 or sp == sq:
            return sp if sp else sq
        if sp == 0:
            return sq
        diff = self.p * self.p - self.q * self.q * self.d           # |p| vs |q| sqrt(d)
        return sp if diff > 0 else sq if diff < 0 else 0

    def key(self):
        return (self.p, self.q, self.d)

    def enclosure(self):
        """(lo, hi) floats holding the value."""
        p, q = enclose(self.p), enclose(self.q)
        if self.q == 0:
            return p
        d = enclose(self.d)
        root = (float_below(math.sqrt(max(d[0], 0.0))), float_above(math.sqrt(d[1])))
        products = [x * y for x in q for y in root]
        return float_below(p[0] + float_below(min(products))), float_above(p[1] + float_above(max(products)))


def _rational_root(d):
    """sqrt(d) for a rational d >= 0 that is the square of a rational, else None."""
    n, m = d.numerator, d.denominator
    rn, rm = math.isqrt(n), math.isqrt(m)
    return Fraction(rn, rm) if rn * rn == n and rm * rm == m else None


def _sign(x):
    return (x > 0) - (x < 0)


def float_below(x):
    """The float next below x."""
    return math.nextafter(x, -math.inf)


def float_above(x):
    """The float next above x."""
    return math.nextafter(x, math.inf)


def enclose(x):
    """(lo, hi) floats holding the rational x (float(x) is correctly rounded: one ulp either side holds it)."""
    f = float(x)
    return (f, f) if Fraction(f) == x else (float_below(f), float_above(f))


# --- the surfaces as meridians -----------------------------------------------------------------------------------
class Meridian:
    """A piece of a surface's meridian: a (rho^2 + h^2) + b rho + c h + d = 0 (rationals), valid where side * (h -
    apex) >= 0 (a cone's ray; side 0: everywhere), with the surface's trim along the axis (lo, hi) in h (Fractions,
    or None where untrimmed)."""

    __slots__ = ("a", "b", "c", "d", "side", "apex", "trim")

    def __init__(self, a, b, c, d, side=0, apex=Fraction(0), trim=None):
        self.a, self.b, self.c, self.d = (Fraction(x) for x in (a, b, c, d))
        self.side, self.apex, self.trim = side, Fraction(apex), trim


def signed_axis(rotation):
    """(k, sign) of the frame's z column sign * e_k when the rotation is a signed permutation, else None."""
    r = np.asarray(rotation, dtype=float)
    if not (np.all(np.isin(r, (-1.0, 0.0, 1.0))) and np.all(np.abs(r).sum(axis=0) == 1.0)
            and np.all(np.abs(r).sum(axis=1) == 1.0)):
        return None
    k = int(np.flatnonzero(r[:, 2])[0])
    return k, int(r[k, 2])


def meridians(surface, axis):
    """The Meridian pieces of the surface about axis = (k, other two coordinates (Fractions)), or None where the
    surface is not exactly a surface of revolution about that line (or is trimmed so that it cuts circles into
    arcs)."""
    k, line = axis
    others = [j for j in range(3) if j != k]
    origin = [Fraction(x) for x in surface.frame.origin.tolist()]
    own = signed_axis(surface.frame.rotation)
    if own is None:
        return None
    h0 = origin[k]
    if isinstance(surface, Plane):
        if own[0] != k or surface.region:
            return None
        return [Meridian(0, 0, 1, -h0)]
    if [origin[j] for j in others] != list(line):
        return None
    if isinstance(surface, Sphere):
        if surface.trimmed:
            return None
        r = Fraction(surface.radius)
        return [Meridian(1, 0, -2 * h0, h0 * h0 - r * r)]
    if own[0] != k:
        return None
    if isinstance(surface, Torus):
        big, small = Fraction(surface.major_radius), Fraction(surface.minor_radius)
        if surface.trimmed or not big > small:
            return None
        return [Meridian(1, -2 * big, -2 * h0, big * big + h0 * h0 - small * small)]
    trim = False if surface.region else _range(surface, 1, k, own[1])     # (an angular trim: arcs, not circles)
    if trim is False:
        return None
    if isinstance(surface, Cylinder):
        return [Meridian(0, 1, 0, -Fraction(surface.radius), trim=trim)]
    if isinstance(surface, Cone):
        t = Fraction(surface.floats[ks.P1])             # (the cone of its stored slope: Cone.slope)
        return [Meridian(0, 1, -side * t, side * t * h0, side, h0, trim) for side in (1, -1)]
    return None


def common_axis(a, b):
    """(k, the other two coordinates of the line) of a line both surfaces turn about exactly, or None."""
    axes = [signed_axis(s.frame.rotation) for s in (a, b)]
    if axes[0] is None or axes[1] is None:
        return None
    for s, own in ((a, axes[0]), (b, axes[1])):
        if not isinstance(s, (Sphere, Plane)):
            k = own[0]
            return k, tuple(Fraction(s.frame.origin[j]) for j in range(3) if j != k)
    for s, own in ((a, axes[0]), (b, axes[1])):                # two spheres, or a sphere and a plane
        if isinstance(s, Plane):
            other = b if s is a else a
            k = own[0]
            return k, tuple(Fraction(other.frame.origin[j]) for j in range(3) if j != k)
    diff = [Fraction(x) - Fraction(y) for x, y in zip(a.frame.origin.tolist(), b.frame.origin.tolist())]
    moved = [j for j in range(3) if diff[j] != 0]
    if len(moved) > 1:
        return None                                           # (centres apart along no coordinate axis)
    k = moved[0] if moved else 2
    return k, tuple(Fraction(a.frame.origin[j]) for j in range(3) if j != k)


# --- common points of two meridians --------------------------------------------------------------------------------
def _quadratic(a2, a1, a0):
    """[(root, double)] of a2 x^2 + a1 x + a0 = 0 (a2 != 0) as Surds; [] for no real root."""
    disc = a1 * a1 - 4 * a2 * a0
    if disc < 0:
        return []
    if disc == 0:
        return [(Surd(-a1 / (2 * a2)), True)]
    return [(Surd(-a1 / (2 * a2), s / (2 * a2), disc), False) for s in (1, -1)]


def _on_line(b, c, d, x, solve_h):
    """The other coordinate (a Surd) on the line b rho + c h + d = 0 at x (a Surd of rho, or of h when solve_h is
    False): rationals combine with x's own sqrt(d)."""
    if solve_h:                                          # h = -(b rho + d) / c
        return Surd(-(b * x.p + d) / c, -b * x.q / c, x.d)
    return Surd(-(c * x.p + d) / b, -c * x.q / b, x.d)


def crossings(m, n):
    """[(rho, h, double)] (Surds) where the meridian pieces m and n meet (before their validity and trims), or None
    where they share a whole piece (the same surface)."""
    if m.a == 0 and n.a != 0:
        m, n = n, m
    if m.a != 0 and n.a != 0:                            # two circles: their radical line, then either circle
        b, c, d = n.a * m.b - m.a * n.b, n.a * m.c - m.a * n.c, n.a * m.d - m.a * n.d
        if b == 0 and c == 0:
            return None if d == 0 else []
        line = (b, c, d)
    elif m.a != 0:
        line = (n.b, n.c, n.d)
    else:                                                # two lines
        det = m.b * n.c - n.b * m.c
        if det == 0:
            return None if m.b * n.d == n.b * m.d and m.c * n.d == n.c * m.d else []
        rho = (m.c * n.d - n.c * m.d) / det
        h = (n.b * m.d - m.b * n.d) / det
        return [(Surd(rho), Surd(h), False)]
    b, c, d = line
    if c != 0:         # h = -(b rho + d) / c into m: a rho^2 + a h^2 + mb rho + mc h + md = 0
        k1, k0 = -b / c, -d / c
        a2 = m.a * (1 + k1 * k1)
        a1 = 2 * m.a * k1 * k0 + m.b + m.c * k1
        a0 = m.a * k0 * k0 + m.c * k0 + m.d
        return [(rho, _on_line(b, c, d, rho, True), double) for rho, double in _quadratic(a2, a1, a0)]
    k0 = -d / b        # rho = -d / b
    a2 = m.a
    a1 = m.c
    a0 = m.a * k0 * k0 + m.b * k0 + m.d
    return [(Surd(k0), h, double) for h, double in _quadratic(a2, a1, a0)]


def _valid(piece, rho, h):
    """1 where the point lies on the piece's valid part and strictly inside its trim, 0 where strictly outside
    either, None where it lies on the edge of one (a ray's end at an apex counts as on the ray)."""
    if piece.side and piece.side * (h - piece.apex).sign() < 0:
        return 0
    if piece.trim is None:
        return 1
    lo, hi = (h - piece.trim[0]).sign(), (h - piece.trim[1]).sign()
    if lo == 0 or hi == 0:
        return None
    return 1 if lo > 0 > hi else 0


def _plane_holds(plane, axis, rho):
    """1 where the circle of radius rho (a Surd; 0: the point) about the axis, in the plane, lies strictly inside
    the plane's rectangle (or the plane is untrimmed), None otherwise (a circle the trims cut, touch or miss is left
    to the search)."""
    bounds = [x for pair in plane.bounds for x in pair]
    if all(math.isinf(x) for x in bounds):
        return 1
    if not all(math.isfinite(x) for x in bounds):
        return None
    k, line = axis
    centre = dict(zip([j for j in range(3) if j != k], line))
    rot = plane.frame.rotation
    for col, (lo, hi) in enumerate(plane.bounds):
        j = int(np.flatnonzero(rot[:, col])[0])
        c = (centre[j] - Fraction(plane.frame.origin[j])) * int(rot[j, col])      # the centre's plane coordinate
        for gap in (c - Fraction(lo), Fraction(hi) - c):                       # to each edge: beyond rho
            if not (rho - gap).sign() < 0:
                return None
    return 1


def exact_points(a, b):
    """(axis, [(rho, h, double)]): every common point of the two surfaces' meridians in the half-plane rho >= 0
    inside both trims (exact Surds; double: a tangency), or None where the pair is not one this module decides."""
    axis = common_axis(a, b)
    if axis is None:
        return None
    ma, mb = meridians(a, axis), meridians(b, axis)
    if ma is None or mb is None:
        return None
    found = {}
    for m in ma:
        for n in mb:
            points = crossings(m, n)
            if points is None:
                return None                                   # (a shared piece: the same surface)
            for rho, h, double in points:
                if rho.sign() < 0:
                    continue
                held = [_valid(m, rho, h), _valid(n, rho, h)]
                held += [_plane_holds(s, axis, rho) for s in (a, b) if isinstance(s, Plane)]
                if None in held:
                    return None                               # (on a trim edge, or a circle the trims cut)
                if all(held):
                    key = (rho.key(), h.key())
                    found[key] = (rho, h, double or (key in found and found[key][2]))
    return axis, list(found.values())


# --- surfaces along one coordinate axis: their cross-sections -------------------------------------------------
def _range(surface, col, k, sign):
    """The surface's trim of parameter col (0: u, 1: v) as a range of coordinate k (Fractions, sorted), None when
    untrimmed, False when half-open."""
    lo, hi = surface.bounds[col]
    if math.isinf(lo) and math.isinf(hi):
        return None
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return False
    o = Fraction(surface.frame.origin[k])
    return tuple(sorted((o + sign * Fraction(lo), o + sign * Fraction(hi))))


def section(surface, k, others):
    """(its cross-section normal to e_k as a Meridian in the coordinates others, its range along e_k, its range
    across (coordinate index among others, range) or None), or None where the surface does not run along e_k
    exactly or is trimmed otherwise."""
    rot = np.asarray(surface.frame.rotation, dtype=float)
    if signed_axis(rot) is None or surface.region:
        return None
    origin = [Fraction(surface.frame.origin[j]) for j in range(3)]
    axes = [int(np.flatnonzero(rot[:, col])[0]) for col in range(3)]
    signs = [int(rot[axes[col], col]) for col in range(3)]
    if isinstance(surface, Cylinder):
        if axes[2] != k or not all(math.isinf(x) for x in surface.bounds[0]):
            return None
        a, b, r = origin[others[0]], origin[others[1]], Fraction(surface.radius)
        along = _range(surface, 1, k, signs[2])
        return None if along is False else (Meridian(1, -2 * a, -2 * b, a * a + b * b - r * r), along, None)
    if not isinstance(surface, Plane) or k not in axes[:2]:
        return None
    normal = others.index(axes[2])
    p = origin[axes[2]]
    line = Meridian(0, 1, 0, -p) if normal == 0 else Meridian(0, 0, 1, -p)
    col_along = axes.index(k)
    col_across = 1 - col_along
    along = _range(surface, col_along, k, signs[col_along])
    across = _range(surface, col_across, axes[col_across], signs[col_across])
    if along is False or across is False:
        return None
    return line, along, None if across is None else (others.index(axes[col_across]), across)


def exact_segments(a, b):
    """(k, others, [(x0, x1, lo, hi, double)]): the segments along e_k where the surfaces meet, each at the common
    point (x0, x1) (Surds) of their sections, from lo to hi (Fractions) along e_k; or None where the pair is not one
    this module decides."""
    if not (isinstance(a, Cylinder) or isinstance(b, Cylinder)):
        return None
    cylinder = a if isinstance(a, Cylinder) else b
    own = signed_axis(cylinder.frame.rotation)
    if own is None:
        return None
    k = own[0]
    others = [j for j in range(3) if j != k]
    sections = [section(s, k, others) for s in (a, b)]
    if sections[0] is None or sections[1] is None:
        return None
    points = crossings(sections[0][0], sections[1][0])
    if points is None:
        return None
    lows = [s[1][0] for s in sections if s[1] is not None]
    highs = [s[1][1] for s in sections if s[1] is not None]
    if not lows:
        return None                                             # (unbounded along e_k)
    lo, hi = max(lows), min(highs)
    out = []
    for x0, x1, double in points:
        inside = True
        for _, _, across in sections:
            if across is None:
                continue
            index, (near, far) = across
            x = (x0, x1)[index]
            signs = ((x - near).sign(), (x - far).sign())
            if 0 in signs:
                return None                                     # (on the plane's edge across)
            inside = inside and signs[0] > 0 > signs[1]
        if not inside or lo > hi:
            continue
        if lo == hi:
            return None                                         # (a single point of the trims' edges)
        out.append((x0, x1, lo, hi, double))
    return k, others, out
