"""The independent truth of the OCCT cases: closed forms, and exact sweeps measured at 60 digits with mpmath.

Nothing here calls spatialkin or OpenCascade. A sweep parametrises the intersection curve by one parameter t in
which every point is a closed-form root:

``Meridian``
    The first surface is a cylinder or a cone, swept by its straight generators (t = the angle phi about its
    axis); the second is a plane or a quadric, so each generator meets it in the roots of a quadratic
    a(phi) h^2 + b(phi) h + c(phi) = 0 (a linear equation for a plane). A curve point is the generator's point at
    a root; its derivative follows from implicit differentiation, h' = -(a' h^2 + b' h + c') / (2 a h + b).
``Parallel``
    Two surfaces of revolution with parallel axes (cylinder, cone, sphere, torus), cut by the planes normal to
    the axes (t = the axial coordinate z): each surface's section is one or two circles, and the curve points are
    the intersections of two circles, in closed form.
``CoplanarRevolutions``
    Two faces swept by segments of one plane turning about two perpendicular axes of that plane (t = the distance
    rho from the point where the axes meet): the sphere of radius rho cuts each face in a parallel, and two
    parallels meet in closed form.
``TorusCentralPlane``
    A torus and a plane through its centre, parametrised by the angle v around the tube: the longitude is
    u = u_n +- acos(g(v)) in closed form.

Topology comes from the sweep: the curve's branches over t are split at every critical t (a double root, where
two branches join or cross; a root escaping to infinity; a trim crossing of a branch; a touch of a trim edge),
each critical found by a sign change or a near-zero extremum on a float grid and refined by bisection at 60
digits. A piece (one branch between two consecutive critical t) exists if its middle point exists and lies inside
every trim; pieces whose ends coincide in space are one component (union-find), also with the closed-form curves
a case adds (a circle or segment of tangency, which no sweep can follow); a component with no free end is closed.
A branch that exists at a critical t only, on both surfaces and inside the trims, is an isolated contact point.
Each piece's length is the integral of |dP/dt| by tanh-sinh quadrature, which integrates the inverse-square-root
growth of |dP/dt| at a turning point exactly at the interval's end; every component's length is checked against
an inscribed polyline at the same precision (main).

The results (component lengths, closedness, free ends, the pieces' t-ranges) are stored in cases.py by ``python
tests/oracles/occ/truth.py`` (see main); the tests sample the stored pieces in float arithmetic to match curves to components.

References
----------
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002
(intersections of quadrics and tori, the sweep by a pencil of lines or planes).
"""
import math
import re

import mpmath as mp
import numpy as np

#: Working precision of the analysis (decimal digits).
DPS = 60
#: Uniform float grid of the critical-point scan (points per sweep range).
GRID = 4096
#: Bisection steps of a critical point at DPS digits (2^-220 of a grid cell, 1e-69 of it).
BISECT = 220
#: The quadrature skips this fraction of a piece's parameter range at each end: there the roots drown in the
#: round-off of the discriminant (which vanishes at a turning point), and the part skipped weighs at most
#: 4 C CUT^(1/4) for the worst end behaviour met (|dP/dt| ~ C (t - t0)^(-3/4), the top of a torus's tube).
CUT = mp.mpf("1e-52")
#: Golden-section steps locating a near-zero extremum.
GOLDEN = 160
#: An extremum closer to zero than this (relative to the function's scale on the grid) is examined at DPS digits.
NEAR_ZERO = 1e-2
#: A double root (a touch): |f| at its extremum below this, relative to the function's scale.
TOUCH = mp.mpf("1e-28")
#: Ends of pieces closer than this (relative to the scene scale) are one point.
JOIN = 1e-12
#: A point found at a critical t counts (as an isolated point) when it lies this close (x scale) to both surfaces:
#: the surfaces are built in float, the sweep from the script's exact numbers.
ON_SURFACE = 1e-12
#: Two criticals closer than this (in t) around a double root of an existence function, where the derivative
#: vanishes, bound no piece (the round-off at DPS digits can split the double zero into two).
SLIVER = mp.mpf("1e-25")
#: A piece end this far from the origin has escaped to infinity.
ESCAPE = 1e15


class Unbounded(ValueError):
    """A branch escapes to infinity inside every trim: the intersection is unbounded."""


# --- arithmetic generic over floats (math) and mpmath -------------------------------------------------------------
class _Float:
    num = float
    sqrt = staticmethod(math.sqrt)
    cos = staticmethod(math.cos)
    sin = staticmethod(math.sin)
    acos = staticmethod(math.acos)
    atan2 = staticmethod(math.atan2)
    pi = math.pi


class _Mp:
    num = staticmethod(mp.mpf)
    sqrt = staticmethod(mp.sqrt)
    cos = staticmethod(mp.cos)
    sin = staticmethod(mp.sin)
    acos = staticmethod(mp.acos)
    atan2 = staticmethod(mp.atan2)

    @property
    def pi(self):
        return +mp.pi


FL, MP = _Float(), _Mp()


def vec(B, v):
    return tuple(B.num(float(c)) for c in v)


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a, B=FL):
    return B.sqrt(dot(a, a))


def matvec(m, v):
    return (dot(m[0], v), dot(m[1], v), dot(m[2], v))


def axes(B, g, orthonormal=False):
    """(O, X, Y, Z) of g in B's numbers; orthonormal: at DPS digits made orthonormal again (Z and X normalised, X
    made normal to Z, Y = +-Z x X as g's handedness), so that a sweep is exact to the surface the float axes stand
    for (the float vectors are unit and orthogonal only to round-off, 1e-16, which splits a tangential crossing of
    two curves into two turning points)."""
    o, x, y, z = vec(B, g.o), vec(B, g.x), vec(B, g.y), vec(B, g.z)
    if orthonormal and B.num is not float:           # at DPS digits (also from a second copy of this module)
        z = mul(z, 1 / norm(z, B))
        x = sub(x, mul(z, dot(x, z)))
        x = mul(x, 1 / norm(x, B))
        yy = cross(z, x)
        y = yy if dot(yy, y) > 0 else mul(yy, -1)
    return o, x, y, z


# --- implicit forms and trims of a Geo ------------------------------------------------------------------------------
def quadric(B, g):
    """(M, m, mu) with G(P) = P^T M P + 2 m.P + mu = 0 on a plane, cylinder, cone or sphere (global P)."""
    o, x, y, z = axes(B, g)
    one, zero = B.num(1), B.num(0)
    eye = ((one, zero, zero), (zero, one, zero), (zero, zero, one))
    if g.kind == "plane":
        return (((zero,) * 3,) * 3, mul(z, B.num(0.5)), -dot(o, z))
    if g.kind == "sphere":
        r = B.num(g.params["r"])
        return eye, mul(o, -1), dot(o, o) - r * r
    if g.kind == "cylinder":
        r, k, c = B.num(g.params["r"]), one, o
    elif g.kind == "cone":
        a = B.num(g.params["angle"])
        t = B.sin(a) / B.cos(a)
        k = 1 + t * t
        c = sub(o, mul(z, B.num(g.params["radius"]) / t))          # the apex
        r = zero
    else:
        raise ValueError(f"{g.kind} is not a quadric")
    mm = tuple(tuple(eye[i][j] - k * z[i] * z[j] for j in range(3)) for i in range(3))
    mc = matvec(mm, c)
    return mm, mul(mc, -1), dot(c, mc) - r * r


def implicit(B, g, p):
    """G(P), the surface's implicit function (a torus's quartic), for the self-checks."""
    return implicit_and_gradient(B, g, p)[0]


def implicit_and_gradient(B, g, p):
    """(G(P), grad G(P)) of the surface's implicit function (a torus's quartic)."""
    if g.kind == "torus":
        o, x, y, z = axes(B, g)
        q = sub(p, o)
        big, small = B.num(g.params["R"]), B.num(g.params["r"])
        s = dot(q, q) + big * big - small * small
        qz = dot(q, z)
        return (s * s - 4 * big * big * (dot(q, q) - qz * qz),
                sub(mul(q, 4 * s), mul(sub(q, mul(z, qz)), 8 * big * big)))
    mm, m, mu = quadric(B, g)
    return dot(p, matvec(mm, p)) + 2 * dot(m, p) + mu, mul(add(matvec(mm, p), m), 2)


def distance_estimate(B, g, p):
    """|G(P)| / |grad G(P)|: the distance from P to g to first order (for the truth's own checks)."""
    value, grad = implicit_and_gradient(B, g, p)
    gn = norm(grad, B)
    return abs(value) / gn if gn != 0 else abs(value)


def _angle_inside(B, lo, hi):
    mid, half = (lo + hi) / 2, (hi - lo) / 2

    def inside(angle):
        d = angle - mid
        d = d - 2 * B.pi * math.floor(float((d + B.pi) / (2 * B.pi)))      # into [-pi, pi)
        return half - abs(d)
    return inside


def constraints(B, g, name):
    """[(label, f)] with f(P) >= 0 inside each trim of g (its own OpenCascade parameters)."""
    o, x, y, z = axes(B, g)
    out = []

    def span(label, coord, rng):
        lo, hi = B.num(rng[0]), B.num(rng[1])
        if math.isfinite(float(lo)):
            out.append((f"{label}>={float(lo):.6g}", lambda p, c=coord, lo=lo: c(p) - lo))
        if math.isfinite(float(hi)):
            out.append((f"{label}<={float(hi):.6g}", lambda p, c=coord, hi=hi: hi - c(p)))

    tag = {r: ("bound:" if r in g.bound else "") + name for r in "uv"}    # an added range is named as such
    if g.kind == "plane":
        if g.u_range is not None:
            span(f"{tag['u']}.u", lambda p: dot(sub(p, o), x), g.u_range)
        if g.v_range is not None:
            span(f"{tag['v']}.v", lambda p: dot(sub(p, o), y), g.v_range)
        if "radius" in g.params or "inner_radius" in g.params:        # a disc or an annulus about o
            def rho(p):
                q = sub(p, o)
                return B.sqrt(dot(q, x) ** 2 + dot(q, y) ** 2)
            if "radius" in g.params:
                big = B.num(g.params["radius"])
                out.append((f"{name}.rim", lambda p: big - rho(p)))
            if "inner_radius" in g.params:
                small = B.num(g.params["inner_radius"])
                out.append((f"{name}.inner_rim", lambda p: rho(p) - small))
        return out
    if g.u_range is not None and g.kind in ("cylinder", "cone", "sphere", "torus") and \
            (g.u_range[1] - g.u_range[0]) < 2 * math.pi - 1e-5:
        inside = _angle_inside(B, B.num(g.u_range[0]), B.num(g.u_range[1]))
        if g.kind == "cone":                 # u of a point of the nappe where R + v sin(a) < 0: its angle + pi
            tan_a = B.sin(B.num(g.params["angle"])) / B.cos(B.num(g.params["angle"]))
            big = B.num(g.params["radius"])

            def angle(p):
                q = sub(p, o)
                a = B.atan2(dot(q, y), dot(q, x))
                return a + B.pi if big + dot(q, z) * tan_a < 0 else a
        else:
            def angle(p):
                q = sub(p, o)
                return B.atan2(dot(q, y), dot(q, x))
        out.append((f"{name}.u", lambda p: inside(angle(p))))
    if g.v_range is not None and g.kind in ("cylinder", "cone"):
        if g.kind == "cylinder":
            span(f"{tag['v']}.v", lambda p: dot(sub(p, o), z), g.v_range)
        else:
            cosa = B.cos(B.num(g.params["angle"]))
            span(f"{tag['v']}.v", lambda p: dot(sub(p, o), z) / cosa, g.v_range)
    if g.v_range is not None and g.kind == "sphere" and g.v_range[1] - g.v_range[0] < math.pi - 1e-9:
        def latitude(p):
            q = sub(p, o)
            return B.atan2(dot(q, z), B.sqrt(dot(q, x) ** 2 + dot(q, y) ** 2))
        span(f"{name}.v", latitude, g.v_range)
    if g.v_range is not None and g.kind == "torus" and (g.v_range[1] - g.v_range[0]) < 2 * math.pi - 1e-5:
        inside_v = _angle_inside(B, B.num(g.v_range[0]), B.num(g.v_range[1]))
        big = B.num(g.params["R"])

        def tube(p):                         # the angle of (rho - R, z) in the meridian half-plane
            q = sub(p, o)
            return B.atan2(dot(q, z), B.sqrt(dot(q, x) ** 2 + dot(q, y) ** 2) - big)
        out.append((f"{name}.v", lambda p: inside_v(tube(p))))
    return out


# --- sweeps ---------------------------------------------------------------------------------------------------------
class Meridian:
    """A cylinder or cone (a) swept by its generators against a plane or quadric (b); t = phi in [0, 2 pi)."""

    periodic = True

    def __init__(self, a, b, orthonormal=False):
        if a.kind not in ("cylinder", "cone") or b.kind not in ("plane", "cylinder", "cone", "sphere"):
            raise ValueError("Meridian sweeps a cylinder or cone against a plane or quadric")
        self.a, self.b = a, b
        self.orthonormal = orthonormal          # the generators from a's axes made orthonormal at DPS digits
        self.t_range = (0.0, 2 * math.pi)
        self.linear = b.kind == "plane"
        self.branches = (0,) if self.linear else (1, -1)
        self._cache = {}

    def name(self):
        return f"Meridian({self.a.kind} generators x {self.b.kind})"

    def _data(self, B):
        key = id(B)
        if key not in self._cache:
            o, x, y, z = axes(B, self.a, self.orthonormal)
            if self.a.kind == "cone":
                ang = B.num(self.a.params["angle"])
                t = abs(B.sin(ang) / B.cos(ang))
                sgn = 1 if self.a.params["angle"] > 0 else -1
                apex = sub(o, mul(z, B.num(self.a.params["radius"]) * B.cos(ang) / B.sin(ang)))
                extra = (apex, t, mul(z, sgn))
            else:
                extra = (o, B.num(self.a.params["r"]), z)
            self._cache[key] = (x, y, extra, quadric(B, self.b))
        return self._cache[key]

    def coefficients(self, B, phi):
        x, y, (p0, s, zz), (mm, m, mu) = self._data(B)
        c, sn = B.cos(phi), B.sin(phi)
        e = add(mul(x, c), mul(y, sn))
        de = add(mul(x, -sn), mul(y, c))
        if self.a.kind == "cone":
            base, dbase = p0, (0, 0, 0)
            d, dd = add(mul(e, s), zz), mul(de, s)
        else:
            base, dbase = add(p0, mul(e, s)), mul(de, s)
            d, dd = zz, (0, 0, 0)
        md, mb = matvec(mm, d), matvec(mm, base)
        a = dot(d, md)
        b = 2 * (dot(base, md) + dot(m, d))
        cc = dot(base, mb) + 2 * dot(m, base) + mu
        da = 2 * dot(dd, md)
        db = 2 * (dot(dbase, md) + dot(mb, dd) + dot(m, dd))
        dc = 2 * dot(dbase, mb) + 2 * dot(m, dbase)
        return base, dbase, d, dd, a, b, cc, da, db, dc

    def existence(self, B):
        """Functions of t whose zeros may end or join branches: the discriminant and a (quadratic), b (linear)."""
        if self.linear:
            return [("b", lambda t: self.coefficients(B, t)[5])]
        return [("disc", lambda t: self._disc(B, t)), ("a", lambda t: self.coefficients(B, t)[4])]

    def _disc(self, B, t):
        k = self.coefficients(B, t)
        return k[5] * k[5] - 4 * k[4] * k[6]

    def root(self, B, k, t, clamp=False):
        base, dbase, d, dd, a, b, c, da, db, dc = self.coefficients(B, t)
        if self.linear:
            if b == 0:
                return None
            h = -c / b
            dh = -(db * h + dc) / b
        else:
            disc = b * b - 4 * a * c
            if disc < 0:
                if not clamp:
                    return None
                disc = disc * 0
            sq = B.sqrt(disc)
            if k == 1:
                den = (-b - sq) if b >= 0 else 2 * a
                num = 2 * c if b >= 0 else (-b + sq)
            else:
                den = (-b + sq) if b <= 0 else 2 * a
                num = 2 * c if b <= 0 else (-b - sq)
            if den == 0:
                return None
            h = num / den
            slope = 2 * a * h + b
            dh = -(da * h * h + db * h + dc) / slope if slope != 0 else None
        p = add(base, mul(d, h))
        dp = None if dh is None else add(add(dbase, mul(d, dh)), mul(dd, h))
        return p, dp

    def touch_point(self, B, fname, t):
        if fname != "disc":
            return None
        base, _, d, _, a, b, _, _, _, _ = self.coefficients(B, t)
        return add(base, mul(d, -b / (2 * a)))


class Parallel:
    """Two surfaces of revolution with parallel axes cut by the planes normal to them; t = the axial coordinate
    along the first surface's z, in t_range."""

    periodic = False

    def __init__(self, a, b, t_range, branches=None):
        for g in (a, b):
            if g.kind not in ("cylinder", "cone", "sphere", "torus"):
                raise ValueError("Parallel needs surfaces of revolution")
        za, zb = np.array(a.z), np.array(b.z)
        if np.linalg.norm(np.cross(za, zb)) > 1e-12:
            raise ValueError("Parallel needs parallel axes")
        self.a, self.b = a, b
        self.t_range = tuple(map(float, t_range))
        self.branches = tuple((i, j, s) for i in range(len(self._radii_names(a)))
                              for j in range(len(self._radii_names(b))) for s in (1, -1))
        if branches is not None:                 # a subset (the others handled in closed form)
            self.branches = tuple(tuple(k) for k in branches)
        self._cache = {}

    def name(self):
        return f"Parallel({self.a.kind} x {self.b.kind}, axial slices)"

    @staticmethod
    def _radii_names(g):
        return ("outer", "inner") if g.kind == "torus" else ("circle",)

    def _frame(self, B):
        key = id(B)
        if key not in self._cache:
            w = vec(B, self.a.z)
            w = mul(w, 1 / norm(w, B))
            centres, heights = [], []
            for g in (self.a, self.b):
                o = vec(B, g.o)
                if g.kind == "cone":
                    ang = B.num(g.params["angle"])
                    o = sub(o, mul(vec(B, g.z), B.num(g.params["radius"]) * B.cos(ang) / B.sin(ang)))
                h = dot(o, w)
                centres.append(sub(o, mul(w, h)))
                heights.append(h)
            delta = sub(centres[1], centres[0])
            dist = norm(delta, B)
            if dist == 0:
                raise ValueError("coaxial surfaces: use the closed form")
            ea = mul(delta, 1 / dist)
            en = cross(w, ea)
            self._cache[key] = (w, centres, heights, dist, ea, en)
        return self._cache[key]

    def _radii(self, B, g, h0, z, clamp=False):
        """[(rho, rho')] of the section circles at height z, None where a circle does not exist (clamp: a circle
        just beyond the surface's extent, by round-off, is its limit)."""
        p = g.params
        u = z - h0
        if g.kind == "cylinder":
            return [(B.num(p["r"]), 0)]
        if g.kind == "cone":
            ang = B.num(p["angle"])
            t = abs(B.sin(ang) / B.cos(ang))
            return [(t * abs(u), t if u >= 0 else -t)]
        r = B.num(p["r"])
        s2 = r * r - u * u
        if s2 < 0 and clamp and s2 > -r * r * B.num(10) ** (-20):
            s2 = s2 * 0
        if s2 < 0:
            return [None] if g.kind == "sphere" else [None, None]
        w = B.sqrt(s2)
        dw = -u / w if w != 0 else None
        if g.kind == "sphere":
            return [(w, dw)]
        big = B.num(p["R"])
        return [(big + w, dw), (big - w, None if dw is None else -dw)]

    def existence(self, B):
        out = []
        w, centres, heights, dist, ea, en = self._frame(B)
        for g, h0, tag in ((self.a, heights[0], "a"), (self.b, heights[1], "b")):
            if g.kind in ("sphere", "torus"):
                r = B.num(g.params["r"])
                out.append((f"{tag}.extent", lambda t, r=r, h0=h0: r * r - (t - h0) ** 2))
            if g.kind == "cone":
                out.append((f"{tag}.apex", lambda t, h0=h0: t - h0))
        for i, j in sorted({(k[0], k[1]) for k in self.branches}):
            out.append((f"hh{i}{j}", lambda t, i=i, j=j: self._hh(B, i, j, t)))
        return out

    def _hh(self, B, i, j, t, clamp=False):
        w, centres, heights, dist, ea, en = self._frame(B)
        ra = self._radii(B, self.a, heights[0], t)[i]
        rb = self._radii(B, self.b, heights[1], t)[j]
        if ra is None or rb is None:
            return B.num(-1) * dist * dist           # the circle does not exist: no point (a negative value)
        aa = (dist * dist + ra[0] * ra[0] - rb[0] * rb[0]) / (2 * dist)
        return ra[0] * ra[0] - aa * aa

    def root(self, B, k, t, clamp=False):
        i, j, s = k
        w, centres, heights, dist, ea, en = self._frame(B)
        ra = self._radii(B, self.a, heights[0], t, clamp)[i]
        rb = self._radii(B, self.b, heights[1], t, clamp)[j]
        if ra is None or rb is None:
            return None
        aa = (dist * dist + ra[0] * ra[0] - rb[0] * rb[0]) / (2 * dist)
        hh = ra[0] * ra[0] - aa * aa
        if hh < 0:
            if not clamp:
                return None
            hh = hh * 0
        sq = B.sqrt(hh)
        p = add(add(add(centres[0], mul(w, t)), mul(ea, aa)), mul(en, s * sq))
        if ra[1] is None or rb[1] is None or sq == 0:
            return p, None
        da = (ra[0] * ra[1] - rb[0] * rb[1]) / dist
        dsq = (ra[0] * ra[1] - aa * da) / sq
        return p, add(add(mul(ea, da), mul(en, s * dsq)), w)

    def touch_point(self, B, fname, t):
        if not fname.startswith("hh"):
            return None
        i, j = int(fname[2]), int(fname[3])
        w, centres, heights, dist, ea, en = self._frame(B)
        ra = self._radii(B, self.a, heights[0], t)[i]
        rb = self._radii(B, self.b, heights[1], t)[j]
        if ra is None or rb is None:
            return None
        aa = (dist * dist + ra[0] * ra[0] - rb[0] * rb[0]) / (2 * dist)
        return add(add(centres[0], mul(w, t)), mul(ea, aa))


def axial_range(a, b):
    """The range of t = P . w (w = a's axis) covered by both surfaces: a sphere's or torus's extent, a trimmed
    cylinder's or cone's axial trim; ValueError if neither bounds it."""
    w = np.asarray(a.z, dtype=float) / np.linalg.norm(a.z)
    lo, hi = -math.inf, math.inf
    for g in (a, b):
        o, z = np.asarray(g.o, dtype=float), np.asarray(g.z, dtype=float)
        if g.kind in ("sphere", "torus"):
            c, r = float(o @ w), g.params["r"]
            rng = (c - r, c + r)
        elif g.v_range is not None and g.kind == "cylinder":
            rng = sorted(float(o @ w + v * (z @ w)) for v in g.v_range)
        elif g.v_range is not None and g.kind == "cone":
            ang = g.params["angle"]
            rng = sorted(float(o @ w + v * math.cos(ang) * (z @ w)) for v in g.v_range)
        else:
            continue
        lo, hi = max(lo, rng[0]), min(hi, rng[1])
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise Unbounded("neither surface bounds the axial range")
    return _widened(lo, hi)


def _widened(lo, hi):
    """A float range made a little wider (1e-9 of its size): its ends, rounded to float, must not cut a sliver
    off a branch; the existence functions, exact at DPS digits, give the branches' true ends inside it."""
    pad = 1e-9 * max(abs(hi - lo), abs(lo), abs(hi), 1e-300)
    return lo - pad, hi + pad


def _one_minus(v):
    return None if v is None else 1 - v


class CoplanarRevolutions:
    """Two faces swept by segments of one plane turning about two perpendicular axes of that plane which meet at
    Q; t = rho, the distance from Q.

    The sphere |P - Q| = rho cuts each face in parallels: the first face's through the point p1 of its segment at
    distance rho from Q (the circle of the sphere in the plane normal to the first axis through p1), the second's
    likewise through p2. Two such circles meet where P - Q = a1 w1 + a2 w2 +- sqrt(rho^2 - a1^2 - a2^2) n, with
    a1 = (p1 - Q).w1, a2 = (p2 - Q).w2 and n = w1 x w2: a point in closed form. The segments bound the faces, so
    their ends are the trims. Branch (k1, k2, s): the root k1 of p1 on the first segment, k2 of p2, s the side.
    """

    periodic = False

    def __init__(self, q, w1, seg1, w2, seg2, branches=None):
        self.q = tuple(map(float, q))
        self.w1, self.w2 = tuple(map(float, w1)), tuple(map(float, w2))
        self.seg1 = tuple(tuple(map(float, p)) for p in seg1)
        self.seg2 = tuple(tuple(map(float, p)) for p in seg2)
        if abs(float(np.dot(self.w1, self.w2))) > 1e-15:
            raise ValueError("the axes must be perpendicular")
        self.branches = tuple((k1, k2, sg) for k1 in (1, -1) for k2 in (1, -1) for sg in (1, -1))
        if branches is not None:
            self.branches = tuple(tuple(k) for k in branches)
        lo, hi = -math.inf, math.inf
        for a, b in (self.seg1, self.seg2):
            a, b, qq = np.array(a), np.array(b), np.array(self.q)
            d = b - a
            s = min(1.0, max(0.0, float((qq - a) @ d / (d @ d))))
            near = float(np.linalg.norm(a + s * d - qq))
            far = max(float(np.linalg.norm(a - qq)), float(np.linalg.norm(b - qq)))
            lo, hi = max(lo, near), min(hi, far)
        self.t_range = _widened(lo, hi)
        self._cache = {}

    def name(self):
        return "CoplanarRevolutions(faces of revolution about perpendicular axes meeting at Q, by spheres about Q)"

    def _data(self, B):
        key = id(B)
        if key not in self._cache:
            q, w1, w2 = vec(B, self.q), vec(B, self.w1), vec(B, self.w2)
            segs = []
            for a, b in (self.seg1, self.seg2):
                a, b = vec(B, a), vec(B, b)
                d = sub(b, a)
                aq = sub(a, q)
                segs.append((a, d, dot(d, d), dot(aq, d), dot(aq, aq)))
            self._cache[key] = (q, w1, w2, cross(w1, w2), segs)
        return self._cache[key]

    def _seg_root(self, B, which, k, rho, clamp):
        """(s, p, ds/drho) of the point of segment `which` at distance rho from Q (root k), or None."""
        q, w1, w2, n, segs = self._data(B)
        a, d, alpha, beta, gamma = segs[which]
        disc = beta * beta - alpha * (gamma - rho * rho)
        if disc < 0:
            if not clamp:
                return None
            disc = disc * 0
        sq = B.sqrt(disc)
        s = (-beta + k * sq) / alpha
        slack = 1e-12                 # the range ends are float distances: s may pass 0 or 1 by round-off
        if s < -slack or s > 1 + slack:
            return None
        p = add(a, mul(d, s))
        den = dot(sub(p, q), d)
        ds = rho / den if den != 0 else None
        return s, p, ds

    def existence(self, B):
        out = []
        for which in (0, 1):
            out.append((f"seg{which}.disc", lambda t, w=which: self._seg_disc(B, w, t)))
            for k in (1, -1):
                out.append((f"seg{which}.s{k}>=0", lambda t, w=which, k=k: self._seg_s(B, w, k, t)))
                out.append((f"seg{which}.s{k}<=1", lambda t, w=which, k=k: _one_minus(self._seg_s(B, w, k, t))))
        for k1, k2 in sorted({(k[0], k[1]) for k in self.branches}):
            out.append((f"zz{k1}{k2}", lambda t, k1=k1, k2=k2: self._zz(B, k1, k2, t)))
        return out

    def _seg_disc(self, B, which, rho):
        q, w1, w2, n, segs = self._data(B)
        a, d, alpha, beta, gamma = segs[which]
        return beta * beta - alpha * (gamma - rho * rho)

    def _seg_s(self, B, which, k, rho):
        q, w1, w2, n, segs = self._data(B)
        a, d, alpha, beta, gamma = segs[which]
        disc = beta * beta - alpha * (gamma - rho * rho)
        if disc < 0:
            return None
        return (-beta + k * B.sqrt(disc)) / alpha

    def _zz(self, B, k1, k2, rho, clamp=False):
        q, w1, w2, n, segs = self._data(B)
        r1 = self._seg_root(B, 0, k1, rho, clamp)
        r2 = self._seg_root(B, 1, k2, rho, clamp)
        if r1 is None or r2 is None:
            return None
        a1, a2 = dot(sub(r1[1], q), w1), dot(sub(r2[1], q), w2)
        return rho * rho - a1 * a1 - a2 * a2

    def root(self, B, k, t, clamp=False):
        k1, k2, sg = k
        q, w1, w2, n, segs = self._data(B)
        r1 = self._seg_root(B, 0, k1, t, clamp)
        r2 = self._seg_root(B, 1, k2, t, clamp)
        if r1 is None or r2 is None:
            return None
        a1, a2 = dot(sub(r1[1], q), w1), dot(sub(r2[1], q), w2)
        zz = t * t - a1 * a1 - a2 * a2
        if zz < 0:
            if not clamp:
                return None
            zz = zz * 0
        z = sg * B.sqrt(zz)
        p = add(add(add(q, mul(w1, a1)), mul(w2, a2)), mul(n, z))
        if r1[2] is None or r2[2] is None or zz == 0:
            return p, None
        da1 = dot(mul(segs[0][1], r1[2]), w1)
        da2 = dot(mul(segs[1][1], r2[2]), w2)
        dz = sg * (t - a1 * da1 - a2 * da2) / B.sqrt(zz)
        return p, add(add(mul(w1, da1), mul(w2, da2)), mul(n, dz))

    def touch_point(self, B, fname, t):
        m = re.fullmatch(r"zz(-?1)(-?1)", fname)
        if m is None:
            return None
        r = self.root(B, (int(m.group(1)), int(m.group(2)), 1), t, clamp=True)
        return None if r is None else r[0]


class TorusCentralPlane:
    """A torus and the plane through its centre with normal n; t = v (around the tube) in [0, 2 pi)."""

    periodic = True

    def __init__(self, torus, normal):
        self.torus = torus
        self.normal = tuple(np.asarray(normal, dtype=float) / np.linalg.norm(normal))
        self.t_range = (0.0, 2 * math.pi)
        self.branches = (1, -1)
        self._cache = {}

    def name(self):
        return "TorusCentralPlane(torus x plane through its centre, by the tube angle)"

    def _data(self, B):
        key = id(B)
        if key not in self._cache:
            o, x, y, z = axes(B, self.torus)
            n = vec(B, self.normal)
            nx, ny, nz = dot(n, x), dot(n, y), dot(n, z)
            m = B.sqrt(nx * nx + ny * ny)
            self._cache[key] = (o, x, y, z, nz, m, B.atan2(ny, nx), B.num(self.torus.params["R"]),
                                B.num(self.torus.params["r"]))
        return self._cache[key]

    def _g(self, B, v):
        o, x, y, z, nz, m, un, big, r = self._data(B)
        return -r * nz * B.sin(v) / (m * (big + r * B.cos(v)))

    def existence(self, B):
        return [("acos", lambda t: 1 - self._g(B, t) ** 2)]

    def root(self, B, k, t, clamp=False):
        o, x, y, z, nz, m, un, big, r = self._data(B)
        g = self._g(B, t)
        s2 = 1 - g * g
        if s2 < 0:
            if not clamp:
                return None
            s2, g = s2 * 0, (1 if g > 0 else -1) * B.num(1)
        u = un + k * B.acos(max(min(g, 1), -1))
        cv, sv, cu, su = B.cos(t), B.sin(t), B.cos(u), B.sin(u)
        rho = big + r * cv
        e, de = add(mul(x, cu), mul(y, su)), add(mul(x, -su), mul(y, cu))
        p = add(add(o, mul(e, rho)), mul(z, r * sv))
        if s2 == 0:
            return p, None
        dg = -r * nz * (big * cv + r) / (m * rho * rho)
        du = -k * dg / B.sqrt(s2)
        dp = add(add(mul(e, -r * sv), mul(de, rho * du)), mul(z, r * cv))
        return p, dp

    def touch_point(self, B, fname, t):
        return None


# --- the analysis ---------------------------------------------------------------------------------------------------
def _bisect(f, lo, hi, flo):
    for _ in range(BISECT):
        mid = (lo + hi) / 2
        fm = f(mid)
        if fm is None:
            return mid
        if (fm < 0) == (flo < 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return (lo + hi) / 2


def _golden(f, lo, hi, sign):
    """The t in [lo, hi] minimising sign * f(t) (f unimodal there)."""
    g = (mp.sqrt(5) - 1) / 2
    a, b = lo, hi
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = sign * f(c), sign * f(d)
    for _ in range(GOLDEN):
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = sign * f(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = sign * f(d)
    return (a + b) / 2


def _zeros(f_fl, f_mp, grid, label, found, touches):
    """Zeros of f on the float grid: sign changes (bisected at DPS digits) and near-zero extrema (a touch, or two
    close zeros, both refined). f returns None where undefined; those cells are skipped."""
    vals = [f_fl(t) for t in grid]
    finite = [abs(v) for v in vals if v is not None]
    fscale = max(finite) if finite else 0.0
    if fscale == 0.0:
        return
    exact = {}

    def at(j):                                       # f at grid point j, at DPS digits (cached)
        if j not in exact:
            exact[j] = f_mp(mp.mpf(grid[j]))
        return exact[j]
    done = set()
    for i in range(len(grid) - 1):
        v0, v1 = vals[i], vals[i + 1]
        if v0 is None or v1 is None:
            continue
        if (v0 < 0) != (v1 < 0) or v0 == 0 or v1 == 0:      # a sign change, or a zero in float: look at DPS digits
            for j in range(max(i - 2, 0), min(i + 3, len(grid) - 1)):    # in float the change may sit a cell off
                if j in done:
                    continue
                m0, m1 = at(j), at(j + 1)
                if m0 is None or m1 is None:
                    continue
                if m0 == 0:
                    found.append((mp.mpf(grid[j]), label))
                    done.add(j)
                elif m1 != 0 and (m0 < 0) != (m1 < 0):
                    found.append((_bisect(f_mp, mp.mpf(grid[j]), mp.mpf(grid[j + 1]), m0), label))
                    done.add(j)
    for i in range(1, len(grid) - 1):
        v0, v1, v2 = vals[i - 1], vals[i], vals[i + 1]
        if v0 is None or v1 is None or v2 is None:
            continue
        if abs(v1) <= abs(v0) and abs(v1) <= abs(v2) and abs(v1) < NEAR_ZERO * fscale \
                and (not (v0 < 0) == (v1 < 0) == (v2 < 0) or 0.0 in (v0, v1, v2)):
            # the signs differ, or vanish, in float only (round-off at a double zero): the extremum at DPS digits
            m = [at(j) for j in (i - 1, i, i + 1)]
            if any(x is None for x in m) or not (m[0] < 0) == (m[1] < 0) == (m[2] < 0) or \
                    abs(m[1]) > abs(m[0]) or abs(m[1]) > abs(m[2]):
                continue
            v0, v1, v2 = (float(x) for x in m)
        if abs(v1) <= abs(v0) and abs(v1) <= abs(v2) and (v0 < 0) == (v1 < 0) == (v2 < 0) \
                and abs(v1) < NEAR_ZERO * fscale:
            side = v0 + v2
            sign = 1 if side > 0 else -1            # minimise |f| = sign * f (the side values give the sign)
            tm = _golden(lambda t: f_mp(t) if f_mp(t) is not None else mp.mpf(fscale) * sign,
                         mp.mpf(grid[i - 1]), mp.mpf(grid[i + 1]), sign)
            fm = f_mp(tm)
            if fm is None:
                continue
            if abs(fm) <= TOUCH * fscale:
                touches.append((tm, label, sign))
            elif (fm < 0) != (v1 < 0):
                f0 = f_mp(mp.mpf(grid[i - 1]))
                found.append((_bisect(f_mp, mp.mpf(grid[i - 1]), tm, f0), label))
                found.append((_bisect(f_mp, tm, mp.mpf(grid[i + 1]), fm), label))


class Piece:
    def __init__(self, sweep, branch, t0, t1, p0, p1, end0, end1, sweep_obj=None):
        self.sweep, self.branch, self.t0, self.t1 = sweep, branch, t0, t1
        self.sweep_obj = sweep_obj
        self.p0, self.p1, self.end0, self.end1 = p0, p1, end0, end1
        self.length = None


def analyse(sweeps, trims, scale, extra_t=None, lengths=True, curves=(), surfaces=None, zoom=None):
    """Components of the union of the sweeps' curves inside the trims.

    sweeps : list of sweeps; trims : list of (label, f(B) -> f(P) >= 0 inside) constructors, as
    ``[(label, lambda B: f)]``; scale : the scene's length scale; extra_t : {sweep index: [t]} extra split
    points (where curves of different sweeps cross); curves : closed-form curves (length, distance(p), label, ends) that
    belong to the intersection too (a piece ending on one joins it); zoom : {sweep index: [(t0, t1)]} ranges scanned
    on a grid of their own as well (criticals closer together than the sweep's grid cell). Returns a dict of
    components (length, closed, free ends, nodes where three or more pieces meet, pieces) and isolated points.
    """
    with mp.workdps(DPS):
        pieces, points = [], []
        for si, sw in enumerate(sweeps):
            pcs, pts = _analyse_one(si, sw, trims, (extra_t or {}).get(si, ()), surfaces, scale,
                                    (zoom or {}).get(si, ()))
            pieces += pcs
            points += pts
        if lengths:
            for pc in pieces:
                sw = sweeps[pc.sweep]

                lo, hi = pc.t0 + CUT * (pc.t1 - pc.t0), pc.t1 - CUT * (pc.t1 - pc.t0)

                def speed(t, sw=sw, pc=pc, lo=lo, hi=hi):
                    if not lo < t < hi:
                        return mp.mpf(0)
                    r = sw.root(MP, pc.branch, t, clamp=True)
                    if r is None or r[1] is None:
                        return mp.mpf(0)
                    return mp.sqrt(dot(r[1], r[1]))
                val, err = mp.quad(speed, [pc.t0, pc.t1], error=True, maxdegree=10)
                pc.length = val
                pc.error = err
        return _components(pieces, points, scale, curves)


def _analyse_one(si, sw, trims, extra, surfaces=None, scale=1.0, zoom=()):
    t0, t1 = sw.t_range
    if t0 > t1:                                      # the sweep's range is empty: nothing
        return [], []
    grid = list(np.linspace(t0, t1, GRID + 1))
    if zoom:
        fine = {float(t) for z0, z1 in zoom for t in np.linspace(z0, z1, GRID + 1)}
        grid = sorted(set(grid) | {t for t in fine if t0 <= t <= t1})
    found, touches = [], []
    cons_fl = [(lab, mk(FL)) for lab, mk in trims]
    cons_mp = [(lab, mk(MP)) for lab, mk in trims]
    for (label, f_fl), (_, f_mp) in zip(sw.existence(FL), sw.existence(MP)):
        _zeros(_safe(f_fl), _safe(f_mp), grid, label, found, touches)
    crit = sorted({float(t) for t, _ in found} | {float(t) for t, _, _ in touches})
    # the constraints along each branch, on the grid refined by the existence criticals
    scan = sorted(set(grid) | {c + d for c in crit for d in (-1e-9, 1e-9)})
    scan = [t for t in scan if t0 <= t <= t1]
    for k in sw.branches:
        for (lab, c_fl), (_, c_mp) in zip(cons_fl, cons_mp):
            def g_fl(t, k=k, c=c_fl):
                r = sw.root(FL, k, t)
                return None if r is None else c(r[0])

            def g_mp(t, k=k, c=c_mp):
                r = sw.root(MP, k, t)
                return None if r is None else c(r[0])
            _zeros(_safe(g_fl), _safe(g_mp), scan, f"{lab}@{k}", found, touches)
    lo = mp.mpf(t0)
    hi = lo + 2 * mp.pi if sw.periodic else mp.mpf(t1)      # a period ends exactly where it starts
    ts = [lo] + [t for t, _ in found] + [t for t, _, _ in touches] + [mp.mpf(t) for t in extra] + [hi]
    ts = sorted(t for t in ts if lo <= t <= hi)
    crit = [ts[0]]
    for t in ts[1:]:
        if t - crit[-1] > mp.mpf(10) ** (-DPS + 8):
            crit.append(t)
    delta = mp.mpf(10) ** (-DPS + 6)

    def inside(p):
        bad = [lab for lab, c in cons_mp if c(p) < 0]
        return not bad

    def end_reason(p):
        vals = [(abs(c(p)), lab) for lab, c in cons_mp]
        small = [lab for v, lab in vals if v < mp.mpf(10) ** (-15)]
        return small[0] if small else None

    pieces = []
    for a, b in zip(crit[:-1], crit[1:]):
        mid = (a + b) / 2
        for k in sw.branches:
            r = sw.root(MP, k, mid)
            if r is None or not inside(r[0]):
                continue
            if r[1] is None and b - a < SLIVER:        # between two roots of one double zero, found apart
                continue
            if r[1] is None:
                raise Unbounded(f"{sw.name()}: branch {k} has no derivative at t = {float(mid)} "
                                f"(piece [{mp.nstr(a, 20)}, {mp.nstr(b, 20)}])")
            pa = sw.root(MP, k, a, clamp=True) or sw.root(MP, k, a + delta, clamp=True)
            pb = sw.root(MP, k, b, clamp=True) or sw.root(MP, k, b - delta, clamp=True)
            if pa is None or pb is None or max(norm(pa[0], MP), norm(pb[0], MP)) > ESCAPE:
                raise Unbounded(f"{sw.name()}: branch {k} escapes near [{float(a)}, {float(b)}] inside the trims")
            pieces.append(Piece(si, k, a, b, pa[0], pb[0], end_reason(pa[0]), end_reason(pb[0]), sw))
    points = []
    slack = mp.mpf(10) ** (-25)
    for t, label, sign in touches:
        if sign > 0:                                 # touching zero from above: a split point, not a point
            continue
        if "@" in label:                             # a trim's function touching zero from below along a branch
            k = _branch_of(label.split("@", 1)[1])
            r = sw.root(MP, k, t)
            p = None if r is None else r[0]
        else:                                        # an existence function touching zero from below
            p = sw.touch_point(MP, label, t)
        if p is not None and all(c(p) >= -slack for _, c in cons_mp):
            points.append((si, t, p))
    if surfaces is not None:                         # at every critical t: a point that exists there only
        for t in crit:
            for k in sw.branches:
                r = sw.root(MP, k, t, clamp=True)
                if r is None or not all(c(r[0]) >= -ON_SURFACE * scale for _, c in cons_mp):
                    continue
                if max(distance_estimate(MP, g, r[0]) for g in surfaces) <= ON_SURFACE * scale:
                    points.append((si, t, r[0]))
    return pieces, points


def _branch_of(text):
    text = text.strip()
    if text.startswith("("):
        return tuple(int(v) for v in text.strip("()").split(","))
    return int(text)


def _safe(f):
    def g(t):
        try:
            return f(t)
        except (ZeroDivisionError, ValueError):
            return None
    return g


def _components(pieces, points, scale, curves=()):
    """Union-find of the pieces (and closed-form curves) by coinciding ends, and of pieces ending on a curve."""
    n = len(pieces)
    ends = []                                        # (node, end 0/1, point): pieces, then open curves' ends
    for i, pc in enumerate(pieces):
        ends.append((i, 0, pc.p0))
        ends.append((i, 1, pc.p1))
    for k, (_, _, _, cends) in enumerate(curves):
        for e, p in enumerate(cends):
            ends.append((n + k, e, vec(MP, p)))
    tol = JOIN * scale
    clusters = []                                    # [representative point, [(node, end)]]
    for i, e, p in ends:
        for cl in clusters:
            if norm(sub(cl[0], p), MP) <= tol:
                cl[1].append((i, e))
                break
        else:
            clusters.append([p, [(i, e)]])
    parent = list(range(n + len(curves)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i
    for _, members in clusters:
        for (i, _), (j, _) in zip(members[:-1], members[1:]):
            parent[find(i)] = find(j)
    passing = []                                     # per cluster: curves it lies on (not at their own ends)
    for cl in clusters:
        own = {i for i, _ in cl[1]}
        hits = [k for k, (_, dist, _, _) in enumerate(curves)
                if n + k not in own and dist(tuple(float(c) for c in cl[0])) <= tol]
        for k in hits:
            parent[find(cl[1][0][0])] = find(n + k)
        passing.append(len(hits))
    groups = {}
    for i in range(n + len(curves)):
        groups.setdefault(find(i), []).append(i)
    comps = []
    for members in groups.values():
        mset = set(members)
        mine = [(cl, hits) for cl, hits in zip(clusters, passing) if any(i in mset for i, _ in cl[1])]
        degree = [(cl[0], len(cl[1]) + 2 * hits) for cl, hits in mine]
        free = [p for p, d in degree if d == 1]
        nodes = [p for p, d in degree if d >= 3]
        reasons = sorted({((pieces[i].end0 if e == 0 else pieces[i].end1) if i < n else "curve") or "?"
                          for cl, hits in mine for i, e in cl[1] if len(cl[1]) == 1 and not hits})
        pcs = [i for i in members if i < n]
        crv = [i - n for i in members if i >= n]
        measured = all(pieces[i].length is not None for i in pcs)
        comps.append(dict(
            length=float(sum(pieces[i].length for i in pcs) + sum(curves[k][0] for k in crv)) if measured else None,
            error=float(sum(pieces[i].error for i in pcs)) if measured and pcs else 0.0,
            closed=not free,
            ends=[tuple(float(c) for c in p) for p in free],
            end_trims=reasons if free else [],
            nodes=[tuple(float(c) for c in p) for p in nodes],
            pieces=[(pieces[i].sweep, list(pieces[i].branch) if isinstance(pieces[i].branch, tuple)
                     else pieces[i].branch, mp.nstr(pieces[i].t0, 30), mp.nstr(pieces[i].t1, 30)) for i in pcs]
            + [("curve", k) for k in crv],
        ))
    comps.sort(key=lambda c: -(c["length"] or 0))
    pts = []
    for _, _, p in points:                           # isolated: away from every end, curve and other point
        if any(norm(sub(p, cl[0]), MP) <= tol for cl in clusters):
            continue
        if any(_near_piece(p, pc, tol) for pc in pieces):
            continue
        if any(dist(tuple(float(c) for c in p)) <= tol for _, dist, _, _ in curves):
            continue
        if any(norm(sub(p, vec(MP, q["point"])), MP) <= tol for q in pts):
            continue
        pts.append(dict(point=tuple(float(c) for c in p)))
    return dict(components=comps, points=pts)


def _near_piece(p, pc, tol):
    """p lies on the piece (a point found at a critical t where a branch passes without ending)."""
    return pc.sweep_obj is not None and _on_branch(pc, p, tol)


def _on_branch(pc, p, tol):
    sw = pc.sweep_obj
    for t in (pc.t0, pc.t1):
        r = sw.root(MP, pc.branch, t, clamp=True)
        if r is not None and norm(sub(r[0], p), MP) <= tol:
            return True
    # interior: the nearest of a few samples, refined by a golden-section search on the distance
    ts = [pc.t0 + (pc.t1 - pc.t0) * j / 64 for j in range(65)]
    dist = []
    for t in ts:
        r = sw.root(MP, pc.branch, t, clamp=True)
        dist.append(norm(sub(r[0], p), MP) if r is not None else mp.inf)
    j = min(range(len(ts)), key=lambda i: dist[i])
    a, b = ts[max(j - 1, 0)], ts[min(j + 1, len(ts) - 1)]

    def f(t):
        r = sw.root(MP, pc.branch, t, clamp=True)
        return norm(sub(r[0], p), MP) if r is not None else mp.inf
    return f(_golden(f, a, b, 1)) <= tol


def trims_of(named):
    """[(label, make)] for analyse: every trim of the (name, Geo) pairs; make(B) gives f(P) >= 0 inside."""
    out = []
    for name, g in named:
        for i, (label, _) in enumerate(constraints(FL, g, name)):
            out.append((label, lambda B, g=g, name=name, i=i: constraints(B, g, name)[i][1]))
    return out


# --- sampling (float) -----------------------------------------------------------------------------------------------
def sample_piece(sweep, branch, t0, t1, tol, max_points=400000):
    """Float points of one stored piece (t0, t1: its stored decimal strings), subdivided until every chord's
    middle lies within tol of the curve (the chord of a t-interval against the curve's point at its middle t)."""
    t0, t1 = float(t0), float(t1)

    def at(t):
        r = sweep.root(FL, branch, t, clamp=True)
        return None if r is None else np.array(r[0], dtype=float)
    ts = list(t0 + (t1 - t0) * 0.5 * (1 - np.cos(np.pi * np.linspace(0.0, 1.0, 33))))
    pts = [at(t) for t in ts]
    keep = [(t, p) for t, p in zip(ts, pts) if p is not None]
    out = [keep[0]] if keep else []
    stack = list(reversed(list(zip(keep[:-1], keep[1:]))))
    shortest = 1e-13 * max(abs(t1 - t0), 1e-300)
    while stack and len(out) < max_points:
        (ta, pa), (tb, pb) = stack.pop()
        tm = 0.5 * (ta + tb)
        pm = at(tm)
        if pm is not None and tb - ta > shortest:
            d = pb - pa
            dd = float(d @ d)
            u = 0.0 if dd == 0 else min(1.0, max(0.0, float((pm - pa) @ d) / dd))
            if float(np.linalg.norm(pa + u * d - pm)) > tol:
                stack.append(((tm, pm), (tb, pb)))
                stack.append(((ta, pa), (tm, pm)))
                continue
        out.append((tb, pb))
    return np.array([p for _, p in out], dtype=float).reshape(-1, 3)


# --- closed forms ---------------------------------------------------------------------------------------------------
def circle_points(centre, normal, radius, n, arc=None):
    """n points of the circle (or of the arc from angle arc[0] to arc[1], measured from a fixed in-plane axis)."""
    c = np.asarray(centre, dtype=float)
    nz = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    helper = np.eye(3)[np.argmin(np.abs(nz))]
    ex = np.cross(helper, nz)
    ex /= np.linalg.norm(ex)
    ey = np.cross(nz, ex)
    a0, a1 = arc if arc is not None else (0.0, 2 * np.pi)
    th = np.linspace(a0, a1, n)
    return c + radius * (np.cos(th)[:, None] * ex + np.sin(th)[:, None] * ey)


def segment_points(p0, p1, n):
    p0, p1 = np.asarray(p0, dtype=float), np.asarray(p1, dtype=float)
    s = np.linspace(0.0, 1.0, n)[:, None]
    return p0 + s * (p1 - p0)


def clip_segment_to_rectangles(p, d, rects, lo=-np.inf, hi=np.inf):
    """The parameter interval [s0, s1] of the line p + s d inside every planar rectangle (o, x, y, (u0, u1),
    (v0, v1)) it lies in, or None (exact arithmetic on the given floats up to rounding)."""
    for o, x, y, ur, vr in rects:
        for axis, rng in ((x, ur), (y, vr)):
            if rng is None:
                continue
            a = float(np.dot(p - o, axis))
            b = float(np.dot(d, axis))
            for bound, sign in ((rng[0], 1), (rng[1], -1)):
                if not math.isfinite(bound):
                    continue
                # sign * (a + s b - bound) >= 0
                if b == 0:
                    if sign * (a - bound) < 0:
                        return None
                    continue
                s = (bound - a) / b
                if sign * b > 0:
                    lo = max(lo, s)
                else:
                    hi = min(hi, s)
    if lo > hi:
        return None
    return lo, hi


def clip_line_to_discs(p, d, discs, lo=-np.inf, hi=np.inf):
    """The parameter intervals [s0, s1] of the line p + s d (lying in each disc's plane), s in [lo, hi], inside
    every disc or annulus (o, x, y, radius, inner_radius or None): |P - o| <= radius and >= inner_radius, the
    distance measured in the plane's own axes. The crossings of a circle are the roots of a quadratic in s
    (closed form); each interval is checked at its middle with the distance itself (hypot). A line tangent to a
    rim gives an interval of length 0 (a point). [] when none."""
    spans = [(lo, hi)]
    for o, x, y, radius, inner in discs:
        q = np.asarray(p, dtype=float) - np.asarray(o, dtype=float)
        qx, qy = float(q @ x), float(q @ y)
        dx, dy = float(np.dot(d, x)), float(np.dot(d, y))
        a, b = dx * dx + dy * dy, qx * dx + qy * dy           # |q + s d|^2 = a s^2 + 2 b s + c

        def roots(r):
            c = qx * qx + qy * qy - r * r
            disc = b * b - a * c
            if disc < -1e-13 * max(b * b, a * r * r):
                return None
            w = math.sqrt(max(disc, 0.0))
            s0, s1 = (-b - w) / a, (-b + w) / a
            return s0, s1
        inside = roots(radius)
        if inside is None:
            return []
        spans = [(max(s0, inside[0]), min(s1, inside[1])) for s0, s1 in spans]
        spans = [sp for sp in spans if sp[0] <= sp[1]]
        if inner:
            hole = roots(inner)
            if hole is not None and hole[1] > hole[0]:
                cut = []
                for s0, s1 in spans:
                    if s0 < hole[0]:
                        cut.append((s0, min(s1, hole[0])))
                    if s1 > hole[1]:
                        cut.append((max(s0, hole[1]), s1))
                spans = cut
        for s0, s1 in spans:                                  # the middle, by the distance itself
            m = q + 0.5 * (s0 + s1) * np.asarray(d, dtype=float)
            rho = math.hypot(float(m @ x), float(m @ y))
            slack = 1e-12 * radius
            if rho > radius + slack or (inner and rho < inner - slack):
                raise AssertionError("clip_line_to_discs: an interval's middle lies outside the face")
    return spans


def disc_limits(o, x, y, radius, inner=None):
    """The disc's (or annulus's) constraints on a circle's angle t, as A cos t + B sin t + C >= 0, for a circle
    in its plane: (radius^2 - |P - o|^2) / (2 radius) >= 0 and (|P - o|^2 - inner^2) / (2 inner) >= 0 (the
    distance's first order, exact in sign). Returns make(centre, ex, ey, r) -> [(A, B, C)]."""
    o, x, y = (np.asarray(v, dtype=float) for v in (o, x, y))

    def make(centre, ex, ey, r):
        dvec = np.asarray(centre, dtype=float) - o
        dd = float(dvec @ x) ** 2 + float(dvec @ y) ** 2
        a = 2 * r * (float(dvec @ x) * float(ex @ x) + float(dvec @ y) * float(ex @ y))
        b = 2 * r * (float(dvec @ x) * float(ey @ x) + float(dvec @ y) * float(ey @ y))
        out = [(-a / (2 * radius), -b / (2 * radius), (radius * radius - dd - r * r) / (2 * radius))]
        if inner:
            out.append((a / (2 * inner), b / (2 * inner), (dd + r * r - inner * inner) / (2 * inner)))
        return out

    def hypot_inside(point, slack):
        q = np.asarray(point, dtype=float) - o
        rho = math.hypot(float(q @ x), float(q @ y))
        return rho <= radius + slack and (not inner or rho >= inner - slack)
    return make, hypot_inside


def _polyline_length(sweeps, pieces, n=1200):
    """A check of a component's length independent of the quadrature: inscribed polylines of n and 2n points per
    piece, at DPS digits, clustered at the ends as t - t0 ~ s^4 (so that even a quarter-power end, as at the top
    of a torus's tube, is sampled evenly along the curve), Richardson-extrapolated; None with closed-form parts."""
    if any(p[0] == "curve" for p in pieces):
        return None
    total = []
    with mp.workdps(DPS):
        for m in (n, 2 * n):
            length = mp.mpf(0)
            for s, k, t0, t1 in pieces:
                k = tuple(k) if isinstance(k, list) else k
                t0, t1 = mp.mpf(t0), mp.mpf(t1)
                prev = None
                for j in range(m + 1):
                    u = (1 - mp.cos(mp.pi * j / m)) / 2
                    u = (1 - mp.cos(mp.pi * u)) / 2
                    r = sweeps[s].root(MP, k, t0 + (t1 - t0) * u, clamp=True)
                    if r is None:
                        continue
                    if prev is not None:
                        length += norm(sub(r[0], prev), MP)
                    prev = r[0]
            total.append(length)
        return float(total[1] + (total[1] - total[0]) / 3)


# --- regenerating the stored truths ---------------------------------------------------------------------------------
def main(argv=None):
    """Measure every swept case of cases.py and write the results into its STORED block (``python -m tests.oracles.occ.truth
    [case-id ...]``: only those, the others kept; ``--missing``: those with no stored result)."""
    import os
    import sys
    import time
    from . import cases
    here = os.path.dirname(os.path.abspath(__file__))
    args = list(argv if argv is not None else sys.argv[1:])
    stored = dict(cases.STORED)
    if "--missing" in args:                          # only the swept cases with no stored truth yet
        args = [c.id for c in cases.CASES if hasattr(c.spec(), "analyse") and c.id not in stored]
        if not args:
            return
    want = set(args)
    for c in cases.CASES:
        spec = c.spec()
        if not hasattr(spec, "analyse") or (want and c.id not in want):
            continue
        t = time.time()
        res = spec.analyse(c)
        bounds = [tr for comp in res["components"] for tr in comp["end_trims"] if tr.startswith("bound:")]
        if bounds:
            raise RuntimeError(f"{c.id}: the truth ends on an added bound {bounds}: enlarge it")
        for comp in res["components"]:
            err = comp.pop("error", 0.0) or 0.0
            if err > 1e-14 * max(comp["length"], c.scale):
                raise RuntimeError(f"{c.id}: quadrature error estimate {err:.3g} on length {comp['length']}")
            check = _polyline_length(spec.sweeps, comp["pieces"])
            if check is not None and abs(check - comp["length"]) > 1e-8 * comp["length"]:
                raise RuntimeError(f"{c.id}: a fine polyline measures {check!r}, the quadrature {comp['length']!r}")
        stored[c.id] = res
        _write_stored(here, stored)
        print(f"{c.id}: {len(res['components'])} components "
              f"{[(round(x['length'], 9), x['closed'], len(x['pieces'])) for x in res['components']]}, "
              f"{len(res['points'])} points ({time.time() - t:.1f} s)", flush=True)
    _write_stored(here, stored)


def _literal(stored):
    """The stored results as a Python literal, one piece, end or point a line."""
    lines = ["{"]
    for cid in sorted(stored):
        res = stored[cid]
        lines.append(f" {cid!r}: {{")
        lines.append("  'components': [")
        for comp in res["components"]:
            lines.append(f"   {{'length': {comp['length']!r}, 'closed': {comp['closed']!r}, "
                         f"'end_trims': {comp['end_trims']!r},")
            for key in ("ends", "nodes"):
                lines.append(f"    {key!r}: [" + ("" if comp[key] else "],"))
                if comp[key]:
                    lines += [f"     {tuple(p)!r}," for p in comp[key]]
                    lines[-1] += "],"
            lines.append("    'pieces': [")
            lines += [f"     {tuple(p)!r}," for p in comp["pieces"]]
            lines.append("    ]},")
        lines.append("  ],")
        lines.append("  'points': [" + ", ".join(f"{{'point': {tuple(p['point'])!r}}}" for p in res["points"]) + "]},")
    lines.append("}")
    return "\n".join(lines)


def _write_stored(here, stored):
    import os
    path = os.path.join(here, "cases.py")
    text = open(path).read()
    head, rest = text.split("# BEGIN STORED\n", 1)
    _, tail = rest.split("# END STORED\n", 1)
    body = "STORED = " + _literal(stored) + "\n"
    open(path, "w").write(head + "# BEGIN STORED\n" + body + "# END STORED\n" + tail)


if __name__ == "__main__":
    main()
