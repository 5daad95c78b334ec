"""An oracle for surface–surface intersection topology, written from the surfaces' parametrisations alone.

Nothing here imports spatialkin's kernels or tracer: the surfaces are read through their public attributes
(``frame``, radii, ``half_angle``, ``u_range``, ``v_range``) and every formula is re-derived from the
parametrisations documented in the public API:

    Plane     (u, v, 0)                                        trimmed by u_range, v_range
    Sphere    (R cos v cos u, R cos v sin u, R sin v)          v in [-pi/2, pi/2]
    Cylinder  (r cos u, r sin u, v)                            trimmed by v_range
    Cone      (v tan a cos u, v tan a sin u, v)                double cone, apex at the origin, trimmed by v_range
    Torus     ((R + r cos v) cos u, (R + r cos v) sin u, r sin v)

What it offers
--------------
* implicit functions (signed, in length units) and exact distances to every kind, and a signed trim margin;
* ``refine(a, b, x)``: Newton (minimum-norm Gauss–Newton on the two implicit functions) onto both surfaces;
* ``brute_force(a, b)``: the number of connected components of the intersection of the TRIMMED surfaces, and
  points on it, from a root search on a fine parameter grid of one bounded surface (marching squares on the
  other surface's implicit function h, connectivity by a graph over the sign-changing grid edges with the
  periodic seams identified and sphere poles / cone apexes collapsed to one point). Sub-grid structure is
  resolved by Newton on the critical points of h: extrema whose value has the other sign (loops smaller than
  a cell) or is zero (isolated contacts, tangency along a curve) become components of their own, and a saddle
  near the zero level decides how the four branches around it connect (its sign, or a node if zero);
* ``oracle(a, b, truth=None)``: closed-form truth when the caller has it, else the brute force;
* ``curve_components(curves, scale)``: connected components of the union of returned curves.

Tolerances: "zero" for a critical value or grid value is ``ZERO_ULPS`` units in the last place of the local
coordinates' magnitude, i.e. round-off, far below the 1e-9 x scale gaps the stress cases use.

Limits (see also the stress test's docstring): a component that enters the other surface's trim for less
than one grid cell, two components closer than a cell that are not separated by a saddle Newton can find,
or a tangency along a curve that runs obliquely across the grid and is sampled too sparsely can be
miscounted. The self-check (``python -m tests.oracles.ssi_cases``) measures this against every closed-form case.
"""
import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

KINDS = ("plane", "sphere", "cylinder", "cone", "torus")
GRID = 600                  # grid nodes per parameter direction of the brute force
ZERO_ULPS = 64              # |value| below this many ulp of the local coordinates' magnitude counts as zero
PHASE = 0.3183098861837907  # fraction of a cell the periodic grids are shifted by (keeps seams, equators,
                            # symmetry planes off the grid nodes)
NEWTON_STEPS = 14           # Newton iterations for critical points of h (in grid-cell units)
REFINE_STEPS = 8            # Gauss–Newton iterations onto both surfaces
MAX_CANDIDATES = 6000       # extremum candidates kept (evenly thinned beyond this)
COINCIDENT_FRACTION = 2e-3  # fraction of grid nodes on the other surface that makes the pair 'coincident'
TWO_PI = 2.0 * np.pi


# ----------------------------------------------------------------------------------------------------------
# surfaces through their public attributes
# ----------------------------------------------------------------------------------------------------------
def kind(surface):
    """'plane', 'sphere', 'cylinder', 'cone' or 'torus'."""
    name = type(surface).__name__.lower()
    if name not in KINDS:
        raise TypeError(f"unknown surface type {type(surface).__name__}")
    return name


def frame_of(surface):
    """(origin (3,), rotation (3, 3)); rotation columns are the local axes in global coordinates."""
    return (np.asarray(surface.frame.origin, dtype=float).reshape(3),
            np.asarray(surface.frame.rotation, dtype=float).reshape(3, 3))


def _range(surface, name):
    r = getattr(surface, name, None)
    if r is None:
        return (-np.inf, np.inf)
    lo, hi = float(r[0]), float(r[1])
    return (lo, hi)


def trims(surface):
    """(u_range, v_range) that trim the surface (infinite where it is not trimmed)."""
    k = kind(surface)
    if k == "plane":
        return _range(surface, "u_range"), _range(surface, "v_range")
    if k in ("cylinder", "cone"):
        return (-np.inf, np.inf), _range(surface, "v_range")
    return (-np.inf, np.inf), (-np.inf, np.inf)


def shape_params(surface):
    """The numbers of the local equation of the surface."""
    k = kind(surface)
    if k == "sphere":
        return dict(R=float(surface.radius))
    if k == "cylinder":
        return dict(r=float(surface.radius))
    if k == "cone":
        a = float(surface.half_angle)
        return dict(a=a, t=np.tan(a), c=np.cos(a), s=np.sin(a))
    if k == "torus":
        return dict(R=float(surface.major_radius), r=float(surface.minor_radius))
    return {}


def is_bounded(surface):
    k = kind(surface)
    ur, vr = trims(surface)
    if k in ("sphere", "torus"):
        return True
    if k in ("cylinder", "cone"):
        return bool(np.all(np.isfinite(vr)))
    return bool(np.all(np.isfinite(ur)) and np.all(np.isfinite(vr)))


def size(surface):
    """A characteristic length of the (trimmed) surface; inf if unbounded."""
    k, q = kind(surface), shape_params(surface)
    ur, vr = trims(surface)
    if k == "sphere":
        return q["R"]
    if k == "torus":
        return q["R"] + q["r"]
    if not is_bounded(surface):
        return np.inf
    if k == "cylinder":
        return max(q["r"], 0.5 * (vr[1] - vr[0]))
    if k == "cone":
        vmax = max(abs(vr[0]), abs(vr[1]))
        return vmax * max(1.0, q["t"])
    return 0.5 * np.hypot(ur[1] - ur[0], vr[1] - vr[0])


def scene_scale(a, b):
    """Scale of a pair: the smaller finite size (the bounded surfaces decide it)."""
    sizes = [s for s in (size(a), size(b)) if np.isfinite(s)]
    return min(sizes) if sizes else 1.0


def to_local(surface, x):
    o, rot = frame_of(surface)
    return (np.asarray(x, dtype=float) - o) @ rot


def to_global(surface, p):
    o, rot = frame_of(surface)
    return o + np.asarray(p, dtype=float) @ rot.T


# ----------------------------------------------------------------------------------------------------------
# parametrisations, implicit functions, distances, trims (all derived from the documented parametrisations)
# ----------------------------------------------------------------------------------------------------------
def local_point(k, q, u, v, derivs=False):
    """Local point (and its u, v derivatives) of the parametrisation of kind k."""
    u = np.asarray(u, dtype=float)
    v = np.asarray(v, dtype=float)
    u, v = np.broadcast_arrays(u, v)
    cu, su, cv, sv = np.cos(u), np.sin(u), np.cos(v), np.sin(v)
    zero, one = np.zeros_like(u), np.ones_like(u)
    if k == "plane":
        p, pu, pv = (u, v, zero), (one, zero, zero), (zero, one, zero)
    elif k == "sphere":
        R = q["R"]
        p = (R * cv * cu, R * cv * su, R * sv)
        pu = (-R * cv * su, R * cv * cu, zero)
        pv = (-R * sv * cu, -R * sv * su, R * cv)
    elif k == "cylinder":
        r = q["r"]
        p, pu, pv = (r * cu, r * su, v), (-r * su, r * cu, zero), (zero, zero, one)
    elif k == "cone":
        t = q["t"]
        p = (v * t * cu, v * t * su, v)
        pu = (-v * t * su, v * t * cu, zero)
        pv = (t * cu, t * su, one)
    elif k == "torus":
        R, r = q["R"], q["r"]
        w = R + r * cv
        p = (w * cu, w * su, r * sv)
        pu = (-w * su, w * cu, zero)
        pv = (-r * sv * cu, -r * sv * su, r * cv)
    else:
        raise ValueError(k)
    p = np.stack(p, axis=-1)
    if not derivs:
        return p
    return p, np.stack(pu, axis=-1), np.stack(pv, axis=-1)


def implicit(k, q, p, grad=False):
    """Signed implicit function of kind k at local points p (length units, |f| = distance near the
    surface; negative inside sphere, cylinder, torus tube and the solid double cone), and its gradient."""
    p = np.asarray(p, dtype=float)
    x, y, z = p[..., 0], p[..., 1], p[..., 2]
    if k == "plane":
        f = z.copy()
        g = np.stack(np.broadcast_arrays(0.0 * z, 0.0 * z, 1.0 + 0.0 * z), axis=-1) if grad else None
    elif k == "sphere":
        n = np.sqrt(x * x + y * y + z * z)
        f = n - q["R"]
        if grad:
            nn = np.where(n > 0, n, 1.0)
            g = p / nn[..., None]
    else:
        rho = np.hypot(x, y)
        rr = np.where(rho > 0, rho, 1.0)
        ex, ey = x / rr, y / rr
        if k == "cylinder":
            f = rho - q["r"]
            if grad:
                g = np.stack([ex, ey, 0.0 * z], axis=-1)
        elif k == "cone":
            c, s = q["c"], q["s"]
            f = rho * c - np.abs(z) * s
            if grad:
                g = np.stack([c * ex, c * ey, -np.sign(z) * s], axis=-1)
        elif k == "torus":
            d = rho - q["R"]
            qd = np.hypot(d, z)
            f = qd - q["r"]
            if grad:
                qq = np.where(qd > 0, qd, 1.0)
                g = np.stack([d / qq * ex, d / qq * ey, z / qq], axis=-1)
        else:
            raise ValueError(k)
    return (f, g) if grad else f


def distance(surface, x):
    """Exact unsigned distance from global points x to the untrimmed surface."""
    k, q = kind(surface), shape_params(surface)
    p = to_local(surface, x)
    px, py, pz = p[..., 0], p[..., 1], p[..., 2]
    if k == "plane":
        return np.abs(pz)
    if k == "sphere":
        return np.abs(np.sqrt(px * px + py * py + pz * pz) - q["R"])
    rho = np.hypot(px, py)
    if k == "cylinder":
        return np.abs(rho - q["r"])
    if k == "cone":
        # the closest point lies in the meridian plane, which meets the double cone in two full lines
        return np.minimum(np.abs(rho * q["c"] - pz * q["s"]), np.abs(rho * q["c"] + pz * q["s"]))
    return np.minimum(np.abs(np.hypot(rho - q["R"], pz) - q["r"]), np.abs(np.hypot(rho + q["R"], pz) - q["r"]))


def trim_margin(surface, x):
    """Signed margin of global points x inside the trim of the surface (>= 0 inside; parameters read from
    the local coordinates, which are the parameters of points on the surface); +inf when untrimmed."""
    k = kind(surface)
    p = to_local(surface, x)
    margin = np.full(p.shape[:-1], np.inf)
    ur, vr = trims(surface)
    coords = []
    if k == "plane":
        coords = [(p[..., 0], ur), (p[..., 1], vr)]
    elif k in ("cylinder", "cone"):
        coords = [(p[..., 2], vr)]
    for c, (lo, hi) in coords:
        if np.isfinite(lo):
            margin = np.minimum(margin, c - lo)
        if np.isfinite(hi):
            margin = np.minimum(margin, hi - c)
    return np.minimum(margin, face_margin(surface, p))


def angle_margin(theta, lo, hi):
    """Signed margin (radians) of angles theta inside [lo, hi] taken modulo 2 pi: the angle to the nearer end,
    negative outside."""
    t = lo + np.mod(theta - lo, TWO_PI)                  # in [lo, lo + 2 pi)
    inside = t <= hi
    return np.where(inside, np.minimum(t - lo, hi - t), -np.minimum(t - hi, lo + TWO_PI - t))


def face_margin(surface, p):
    """Signed margin (a length, >= 0 inside) of local points p on the surface inside its CAD-face trims: the
    angle u round the axis (a cylinder, cone, sphere or torus; on a cone's lower nappe the point lies at u + pi),
    a torus's tube angle or a sphere's latitude v, a plane's circles; read from the angles of the point
    (atan2), each margin times the radius it turns on. +inf where the surface has none."""
    k = kind(surface)
    margin = np.full(p.shape[:-1], np.inf)
    rho = np.hypot(p[..., 0], p[..., 1])
    if k == "plane":
        outer, inner = getattr(surface, "radius", None), getattr(surface, "inner_radius", None)
        if outer is not None:
            margin = np.minimum(margin, outer - rho)
        if inner is not None:
            margin = np.minimum(margin, rho - inner)
        return margin
    ur, vr = surface.u_range, surface.v_range
    if np.isfinite(ur[0]):
        theta = np.arctan2(p[..., 1], p[..., 0])
        if k == "cone":
            theta = np.where(p[..., 2] < 0, theta + np.pi, theta)
        margin = np.minimum(margin, angle_margin(theta, ur[0], ur[1]) * rho)
    if k == "torus" and np.isfinite(vr[0]):
        r = float(surface.minor_radius)
        phi = np.arctan2(p[..., 2], rho - float(surface.major_radius))
        margin = np.minimum(margin, angle_margin(phi, vr[0], vr[1]) * r)
    if k == "sphere" and np.isfinite(vr[0]):
        lat = np.arctan2(p[..., 2], rho)
        margin = np.minimum(margin, np.minimum(lat - vr[0], vr[1] - lat) * float(surface.radius))
    return margin


def _global_implicit(surface, x):
    k, q = kind(surface), shape_params(surface)
    _, rot = frame_of(surface)
    f, g = implicit(k, q, to_local(surface, x), grad=True)
    return f, g @ rot.T


def refine(a, b, x, steps=REFINE_STEPS):
    """Move points x (..., 3) onto both surfaces: minimum-norm Gauss–Newton steps on (f_a, f_b), regularised
    where the normals are parallel (tangency). Returns (points, residual = max(|f_a|, |f_b|))."""
    x = np.array(x, dtype=float, copy=True)
    shape = x.shape
    x = x.reshape(-1, 3)
    if len(x) == 0:
        return x.reshape(shape), np.zeros(shape[:-1])
    for _ in range(steps):
        fa, ga = _global_implicit(a, x)
        fb, gb = _global_implicit(b, x)
        J = np.stack([ga, gb], axis=1)                       # (N, 2, 3)
        F = np.stack([fa, fb], axis=1)                       # (N, 2)
        JJ = J @ np.transpose(J, (0, 2, 1))
        mu = 1e-13 * np.trace(JJ, axis1=1, axis2=2)
        JJ = JJ + mu[:, None, None] * np.eye(2)
        lam = np.linalg.solve(JJ, F[..., None])[..., 0]
        x = x - np.einsum("nij,ni->nj", J, lam)
    fa = _global_implicit(a, x)[0]
    fb = _global_implicit(b, x)[0]
    res = np.maximum(np.abs(fa), np.abs(fb))
    return x.reshape(shape), res.reshape(shape[:-1])


def samples_near(a, b, centre, radius, n=16):
    """Points of the intersection near `centre` (e.g. a tiny loop or a contact point of known centre and
    approximate radius): a ring of starts in the tangent plane of `a`, refined onto both surfaces."""
    centre = np.asarray(centre, dtype=float)
    _, ga = _global_implicit(a, centre[None])
    nrm = ga[0] / np.linalg.norm(ga[0])
    e1 = np.cross(nrm, [1.0, 0.0, 0.0])
    if np.linalg.norm(e1) < 0.5:
        e1 = np.cross(nrm, [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(nrm, e1)
    th = np.linspace(0.0, TWO_PI, n, endpoint=False)
    starts = centre + radius * (np.cos(th)[:, None] * e1 + np.sin(th)[:, None] * e2)
    starts = np.vstack([centre[None], starts])
    pts, res = refine(a, b, starts, steps=30)
    return pts[res <= 1e-9 * max(radius, 1e-300) + 1e-12 * np.abs(centre).max() + 1e-300]


def inverse_param(k, q, p):
    """(u, v) of local points p on (or near) a surface of kind k (the parameters of the nearby surface point; on a
    cone's lower nappe, v < 0, the point (v tan a cos u, v tan a sin u, v) lies opposite u, at angle u + pi)."""
    p = np.asarray(p, dtype=float)
    x, y, z = p[..., 0], p[..., 1], p[..., 2]
    if k == "plane":
        return x, y
    if k == "cone":
        flip = np.where(z < 0, -1.0, 1.0)
        return np.arctan2(flip * y, flip * x), z
    u = np.arctan2(y, x)
    if k == "sphere":
        return u, np.arctan2(z, np.hypot(x, y))
    if k == "cylinder":
        return u, z
    return u, np.arctan2(z, np.hypot(x, y) - q["R"])


def window_regions(a, b, centre, du, dv, n=2001):
    """(regions where b's implicit function is negative, regions where it is positive, whether the window's border
    meets both signs) over the window u0 +- du, v0 +- dv of a's parameters round the point centre (3,), on an n x n
    grid of a's points (connected by edges, scipy.ndimage.label). Where the border keeps one sign, the intersection
    inside the window is made of (negative regions + positive regions - 1) closed loops: each loop bounds one region,
    nested or not. A loop or a bridge narrower than a cell is not seen."""
    from scipy import ndimage
    ka, qa = kind(a), shape_params(a)
    kb, qb = kind(b), shape_params(b)
    u0, v0 = inverse_param(ka, qa, to_local(a, np.asarray(centre, dtype=float)))
    uu, vv = np.meshgrid(u0 + np.linspace(-du, du, n), v0 + np.linspace(-dv, dv, n), indexing="ij")
    h = implicit(kb, qb, to_local(b, to_global(a, local_point(ka, qa, uu, vv))))
    border = np.concatenate([h[0], h[-1], h[:, 0], h[:, -1]])
    return ndimage.label(h < 0)[1], ndimage.label(h > 0)[1], bool((border < 0).any() and (border > 0).any())


def ray_roots(A, B, u0, v0, du, dv, scale, doublings=90, bisections=200):
    """Zeros of h = (implicit of B) on A along the parameter rays (u0, v0) + t (du, dv), t > 0, nearest to the
    start: the first sign change found by doubling t from 1e-13 x scale, then bisection to the last bit.
    Well conditioned where the rays cross the curve transversally, so it places points on tiny loops to
    round-off (Newton onto both surfaces cannot: near a tangency a tiny residual does not fix the position).
    Returns global points (N, 3) of the rays that found a sign change."""
    kA, qA = kind(A), shape_params(A)
    kB, qB = kind(B), shape_params(B)
    oA, RA = frame_of(A)
    oB, RB = frame_of(B)
    M, t0 = RB.T @ RA, RB.T @ (oA - oB)

    def h(t):
        return implicit(kB, qB, t0 + local_point(kA, qA, u0 + t * du, v0 + t * dv) @ M.T)

    du, dv = np.asarray(du, dtype=float), np.asarray(dv, dtype=float)
    h0 = h(np.zeros_like(du))
    lo = np.zeros_like(du)
    hi = np.full_like(du, 1e-13 * scale)
    found = np.zeros(du.shape, dtype=bool)
    for _ in range(doublings):
        s = (h(hi) > 0) != (h0 > 0)
        found |= s
        lo = np.where(found, lo, hi)
        hi = np.where(found, hi, 2 * hi)
        if found.all():
            break
    for _ in range(bisections):
        mid = 0.5 * (lo + hi)
        s = (h(mid) > 0) != (h0 > 0)
        hi = np.where(s, mid, hi)
        lo = np.where(s, lo, mid)
    t = 0.5 * (lo + hi)
    return to_global(A, local_point(kA, qA, u0 + t * du, v0 + t * dv))[found]


def loop_samples(a, b, centre, n=32):
    """Points of a small loop (or the point of a contact) round `centre`, a point on one of the surfaces
    inside the loop: rays in that surface's parameter domain, in n tangent directions, bisected to h = 0."""
    centre = np.asarray(centre, dtype=float)
    A, B = (a, b) if distance(a, centre[None])[0] <= distance(b, centre[None])[0] else (b, a)
    kA, qA = kind(A), shape_params(A)
    u0, v0 = inverse_param(kA, qA, to_local(A, centre))
    _, pu, pv = local_point(kA, qA, u0, v0, derivs=True)
    J = np.stack([pu, pv], axis=1)                      # (3, 2)
    e1 = pu / np.linalg.norm(pu)
    e2 = pv - (pv @ e1) * e1
    e2 /= np.linalg.norm(e2)
    th = np.linspace(0, 2 * np.pi, n, endpoint=False)
    d3 = np.cos(th)[:, None] * e1 + np.sin(th)[:, None] * e2
    duv = np.linalg.lstsq(J, d3.T, rcond=None)[0]       # (2, n)
    scale = max(size(A) if np.isfinite(size(A)) else 0.0, size(B) if np.isfinite(size(B)) else 0.0, 1e-300)
    return ray_roots(A, B, np.full(n, float(u0)), np.full(n, float(v0)), duv[0], duv[1], scale)


# ----------------------------------------------------------------------------------------------------------
# brute force
# ----------------------------------------------------------------------------------------------------------
def grid_roles(a, b):
    """(A, B): the surface whose parameter grid is searched, and the one whose implicit function is read on
    it. None when neither is bounded. A cone whose apex lies in its trim is gridded (its apex row is then
    one collapsed point); otherwise a trimmed surface is preferred to a closed one of comparable size (its
    trim is then the exact edge of the grid), otherwise the smaller one."""
    ba, bb = is_bounded(a), is_bounded(b)
    if not ba and not bb:
        return None
    if ba != bb:
        return (a, b) if ba else (b, a)

    def apex_inside(s):
        return kind(s) == "cone" and trims(s)[1][0] <= 0.0 <= trims(s)[1][1]

    if apex_inside(a) != apex_inside(b):
        return (a, b) if apex_inside(a) else (b, a)

    def trimmed(s):
        return kind(s) in ("plane", "cylinder", "cone")

    sa, sb = size(a), size(b)
    if trimmed(a) != trimmed(b):
        t, c = (a, b) if trimmed(a) else (b, a)
        if size(t) <= 20.0 * size(c):
            return t, c
    if sa != sb:
        return (a, b) if sa < sb else (b, a)
    order = {"torus": 0, "sphere": 1, "cylinder": 2, "cone": 3, "plane": 4}
    return (a, b) if order[kind(a)] <= order[kind(b)] else (b, a)


class _Grid:
    """Parameter grid of surface A with B's implicit function read on it."""

    def __init__(self, A, B, n):
        self.A, self.B = A, B
        self.kA, self.qA = kind(A), shape_params(A)
        self.kB, self.qB = kind(B), shape_params(B)
        oA, RA = frame_of(A)
        oB, RB = frame_of(B)
        self.M = RB.T @ RA                      # A-local -> B-local rotation
        self.t = RB.T @ (oA - oB)               # origin difference first: exact for nearby far origins
        ur, vr = trims(A)
        k = self.kA
        self.per_u = k != "plane"
        self.per_v = k == "torus"
        self.collapsed = []
        if self.per_u:
            self.u = (PHASE + np.arange(n)) * (TWO_PI / n)
        else:
            self.u = np.linspace(ur[0], ur[1], n)
        if k == "sphere":
            nv = n + (n % 2)                    # even: the equator is not a grid row
            self.v = np.linspace(-np.pi / 2, np.pi / 2, nv)
            self.collapsed = [0, nv - 1]
        elif k == "torus":
            self.v = (PHASE + np.arange(n)) * (TWO_PI / n)
        elif k == "cone" and vr[0] < 0.0 < vr[1]:
            n1 = int(np.clip(round(n * (-vr[0]) / (vr[1] - vr[0])), 4, n - 4))
            n2 = max(4, n - n1 + 1)
            self.v = np.concatenate([np.linspace(vr[0], 0.0, n1)[:-1], np.linspace(0.0, vr[1], n2)])
            self.v[n1 - 1] = 0.0
            self.collapsed = [n1 - 1]
        else:
            self.v = np.linspace(vr[0], vr[1], n)
            if k == "cone":
                if vr[0] == 0.0:
                    self.collapsed = [0]
                elif vr[1] == 0.0:
                    self.collapsed = [len(self.v) - 1]
        self.nu, self.nv = len(self.u), len(self.v)
        self.cu = self.nu if self.per_u else self.nu - 1
        self.cv = self.nv if self.per_v else self.nv - 1
        self.ip = (np.arange(self.cu) + 1) % self.nu
        self.jp = (np.arange(self.cv) + 1) % self.nv
        self.du = (self.u[self.ip] - self.u[: self.cu]) % TWO_PI if self.per_u else np.diff(self.u)
        self.dv = (self.v[self.jp] - self.v[: self.cv]) % TWO_PI if self.per_v else np.diff(self.v)
        self.su = float(np.mean(self.du))       # cell units for Newton
        self.sv = float(np.mean(self.dv))
        U, V = np.meshgrid(self.u, self.v, indexing="ij")
        pA = local_point(self.kA, self.qA, U, V)
        pB = self.t + pA @ self.M.T
        for row in self.collapsed:
            pB[:, row] = pB[0, row]
            pA[:, row] = pA[0, row]
        self.pA = pA
        self.h = implicit(self.kB, self.qB, pB)
        mag = max(float(np.abs(pB).max()), float(np.abs(pA).max()), 1e-300)
        self.zero_tol = ZERO_ULPS * np.spacing(mag)

    # --- evaluation off the grid ---
    def h_grad(self, u, v):
        p, pu, pv = local_point(self.kA, self.qA, u, v, derivs=True)
        f, g = implicit(self.kB, self.qB, self.t + p @ self.M.T, grad=True)
        gu = np.sum(g * (pu @ self.M.T), axis=-1) * self.su
        gv = np.sum(g * (pv @ self.M.T), axis=-1) * self.sv
        return f, gu, gv

    def global_point(self, u, v):
        return to_global(self.A, local_point(self.kA, self.qA, u, v))

    def canonical(self, u, v):
        """Wrap parameters into the grid's domain (sphere: over the pole)."""
        u = np.array(u, dtype=float)
        v = np.array(v, dtype=float)
        if self.kA == "sphere":
            v = np.mod(v + np.pi / 2, TWO_PI) - np.pi / 2
            over = v > np.pi / 2
            v[over] = np.pi - v[over]
            u[over] += np.pi
        if self.per_u:
            u = self.u[0] + np.mod(u - self.u[0], TWO_PI)
        if self.per_v:
            v = self.v[0] + np.mod(v - self.v[0], TWO_PI)
        return u, v

    def inside(self, u, v, slack=1e-9):
        ok = np.ones(np.shape(u), dtype=bool)
        if not self.per_u:
            w = self.u[-1] - self.u[0]
            ok &= (u >= self.u[0] - slack * w) & (u <= self.u[-1] + slack * w)
        if not self.per_v:
            w = self.v[-1] - self.v[0]
            ok &= (v >= self.v[0] - slack * w) & (v <= self.v[-1] + slack * w)
        return ok

    def cell_of(self, u, v):
        if self.per_u:
            i = np.floor((u - self.u[0]) / (TWO_PI / self.nu)).astype(int) % self.nu
        else:
            i = np.clip(np.searchsorted(self.u, u) - 1, 0, self.cu - 1)
        if self.per_v:
            j = np.floor((v - self.v[0]) / (TWO_PI / self.nv)).astype(int) % self.nv
        else:
            j = np.clip(np.searchsorted(self.v, v) - 1, 0, self.cv - 1)
        return i, j

    def critical_points(self, u, v, max_move):
        """Newton on grad h = 0 from (u, v) (cell units internally, FD Hessian of the analytic gradient,
        pseudo-inverse for degenerate critical sets). Returns u, v, h, det(H)/|H|^2, converged."""
        x = np.asarray(u, dtype=float) / self.su
        y = np.asarray(v, dtype=float) / self.sv
        x0, y0 = x.copy(), y.copy()
        d = 1e-5
        ok = np.ones(x.shape, dtype=bool)
        last = np.full(x.shape, np.inf)
        H = np.zeros(x.shape + (2, 2))
        for _ in range(NEWTON_STEPS):
            uu, vv = x * self.su, y * self.sv
            _, gu, gv = self.h_grad(uu, vv)
            _, gu_p, gv_p = self.h_grad(uu + d * self.su, vv)
            _, gu_m, gv_m = self.h_grad(uu - d * self.su, vv)
            _, gu_q, gv_q = self.h_grad(uu, vv + d * self.sv)
            _, gu_n, gv_n = self.h_grad(uu, vv - d * self.sv)
            huu = (gu_p - gu_m) / (2 * d)
            hvv = (gv_q - gv_n) / (2 * d)
            huv = 0.5 * ((gv_p - gv_m) + (gu_q - gu_n)) / (2 * d)
            H = np.stack([np.stack([huu, huv], -1), np.stack([huv, hvv], -1)], -2)
            bad = ~np.all(np.isfinite(H), axis=(-1, -2))
            H[bad] = np.eye(2)
            step = -np.einsum("nij,nj->ni", np.linalg.pinv(H, rcond=1e-9), np.stack([gu, gv], -1))
            norm = np.linalg.norm(step, axis=-1)
            cap = np.minimum(1.0, 1.0 / np.maximum(norm, 1e-300))
            step *= cap[:, None]
            x += step[:, 0]
            y += step[:, 1]
            last = norm
            ok &= ~bad
        moved = np.hypot(x - x0, y - y0)
        uu, vv = x * self.su, y * self.sv
        f, gu, gv = self.h_grad(uu, vv)
        nrm2 = np.sum(H * H, axis=(-1, -2))
        small_gradient = np.hypot(gu, gv) <= 1e-7 * np.sqrt(nrm2)      # within ~1e-7 cell of the critical set
        conv = ok & ((last < 1e-7) | small_gradient) & (moved <= max_move)
        det = np.linalg.det(H) / np.where(nrm2 > 0, nrm2, 1.0)
        return uu, vv, f, det, conv, H


def _neighbour_extrema(h, per_u, per_v, tol=0.0):
    """Non-strict discrete minima and maxima over the 8 neighbours (periodic where the grid is); values within
    tol count as ties (round-off along a ridge of equal values)."""
    is_min = np.ones(h.shape, dtype=bool)
    is_max = np.ones(h.shape, dtype=bool)
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            if di == 0 and dj == 0:
                continue
            for fill, target, op in ((np.inf, is_min, lambda x, y: x <= y + tol),
                                     (-np.inf, is_max, lambda x, y: x >= y - tol)):
                s = np.roll(h, (di, dj), axis=(0, 1))
                if not per_u and di != 0:
                    if di > 0:
                        s[:di, :] = fill
                    else:
                        s[di:, :] = fill
                if not per_v and dj != 0:
                    if dj > 0:
                        s[:, :dj] = fill
                    else:
                        s[:, dj:] = fill
                target &= op(h, s)
    return is_min, is_max


def _block(g, ci, cj, half, eu, ev):
    """The (2 half + 1)^2 block of cells round cell (ci, cj): (cell indices, ring edge ids in cyclic order,
    sign of h at the ring nodes, interior edge ids), or None where it leaves a non-periodic grid or touches
    a collapsed row."""
    cu, cv, nu, nv = g.cu, g.cv, g.nu, g.nv
    bi = list(range(ci - half, ci + half + 1))
    bj = list(range(cj - half, cj + half + 1))
    if g.per_u:
        bi = [x % cu for x in bi]
    elif bi[0] < 0 or bi[-1] >= cu:
        return None
    if g.per_v:
        bj = [x % cv for x in bj]
    elif bj[0] < 0 or bj[-1] >= cv:
        return None
    if any((r in g.collapsed) or ((r + 1) % nv in g.collapsed) for r in bj):
        return None
    m = len(bi)
    ni = bi + [(bi[-1] + 1) % nu]
    nj = bj + [(bj[-1] + 1) % nv]
    ring = [(ni[k], nj[0]) for k in range(m + 1)] + [(ni[m], nj[k]) for k in range(1, m + 1)] + \
           [(ni[k], nj[m]) for k in range(m - 1, -1, -1)] + [(ni[0], nj[k]) for k in range(m - 1, 0, -1)]
    ring_edges = []
    for k in range(len(ring)):
        (i0, j0), (i1, j1) = ring[k], ring[(k + 1) % len(ring)]
        if j0 == j1:
            ring_edges.append(eu(i0 if (i0 + 1) % nu == i1 else i1, j0))
        else:
            ring_edges.append(ev(i0, j0 if (j0 + 1) % nv == j1 else j1))
    pos = g.h > 0
    ring_pos = [bool(pos[i, j]) for i, j in ring]
    cells = [x * cv + y for x in bi for y in bj]
    edges = set()
    for x in bi:
        for y in bj:
            edges.update([eu(x, y), eu(x, (y + 1) % nv), ev(x, y), ev((x + 1) % nu, y)])
    return cells, ring_edges, ring_pos, edges - set(ring_edges)


def brute_force(a, b, n=GRID, roles=None, with_labels=False):
    """Components of the intersection of the trimmed surfaces by a grid root search (see module doc).

    Returns dict(count, samples (M, 3), kind, roles, labels?) with kind one of 'generic', 'contact'
    (an isolated zero-valued extremum was found), 'tangent' (zero-valued extrema along a curve),
    'coincident', 'unbounded'."""
    if roles is None:
        roles = grid_roles(a, b)
    if roles is None:
        return dict(count=None, samples=np.zeros((0, 3)), kind="unbounded", roles=None)
    A, B = roles
    g = _Grid(A, B, n)
    h, zt = g.h, g.zero_tol
    scale = scene_scale(a, b)
    nu, nv, cu, cv, ip, jp = g.nu, g.nv, g.cu, g.cv, g.ip, g.jp

    # coincident: a whole area of A lies on B (inside B's trim)
    near0 = np.abs(h) <= max(zt, 1e-12 * scale)
    for row in g.collapsed:
        near0[:, row] = False
    if near0.mean() > COINCIDENT_FRACTION:
        inside = trim_margin(B, to_global(A, g.pA[near0])) >= -1e-12 * scale
        if inside.mean() > 0.5 and near0.sum() * inside.mean() > COINCIDENT_FRACTION * h.size:
            return dict(count=None, samples=np.zeros((0, 3)), kind="coincident", roles=(A, B))

    pos = h > 0
    cross_u = pos[:cu, :] != pos[ip, :]                 # edge (i, j)-(i+1, j)
    cross_v = pos[:, :cv] != pos[:, jp]                 # edge (i, j)-(i, j+1)
    n_eu = cu * nv
    n_ev = nu * cv
    n_edges = n_eu + n_ev

    def eu(i, j):
        return i * nv + j

    def ev(i, j):
        return n_eu + i * cv + j

    # crossing points (linear interpolation), refined onto both surfaces
    iu, ju = np.nonzero(cross_u)
    iv, jv = np.nonzero(cross_v)
    h0 = h[iu, ju]
    tt = h0 / (h0 - h[ip[iu], ju])
    cu_u = g.u[iu] + tt * g.du[iu]
    cu_v = g.v[ju]
    h0 = h[iv, jv]
    tt = h0 / (h0 - h[iv, jp[jv]])
    cv_u = g.u[iv]
    cv_v = g.v[jv] + tt * g.dv[jv]
    ids = np.concatenate([eu(iu, ju), ev(iv, jv)])
    cp = g.global_point(np.concatenate([cu_u, cv_u]), np.concatenate([cu_v, cv_v]))
    cp_ref, res = refine(A, B, cp)
    good = res <= 1e-8 * scale
    cp = np.where(good[:, None], cp_ref, cp)
    active = np.zeros(n_edges, dtype=bool)
    active[ids] = trim_margin(B, cp) >= 0.0
    edge_pts = np.full((n_edges, 3), np.nan)
    edge_pts[ids] = cp

    pairs = []
    # cells
    I, J = np.meshgrid(np.arange(cu), np.arange(cv), indexing="ij")
    I, J = I.ravel(), J.ravel()
    e_b, e_t = eu(I, J), eu(I, jp[J])
    e_l, e_r = ev(I, J), ev(ip[I], J)
    f_b, f_t = cross_u[I, J], cross_u[I, jp[J]]
    f_l, f_r = cross_v[I, J], cross_v[ip[I], J]
    ncross = f_b.astype(int) + f_t + f_l + f_r
    overridden = np.zeros(cu * cv, dtype=bool)           # cell index I * cv + J
    dropped = np.zeros(n_edges, dtype=bool)

    # saddles near the zero level decide the connections in the 3x3 block of cells around them
    sad = np.nonzero(ncross > 0)[0]
    node_pairs = []
    n_saddles = 0
    if len(sad):
        uc = g.u[I[sad]] + 0.5 * g.du[I[sad]]
        vc = g.v[J[sad]] + 0.5 * g.dv[J[sad]]
        su_, sv_, sh_, sdet, sconv, _ = g.critical_points(uc, vc, max_move=3.5)
        keep = sconv & (sdet < -1e-10)
        su_, sv_ = g.canonical(su_[keep], sv_[keep])
        sh_ = sh_[keep]
        keep2 = g.inside(su_, sv_)
        su_, sv_, sh_ = su_[keep2], sv_[keep2], sh_[keep2]
        si, sj = g.cell_of(su_, sv_)
        seen = set()
        used = np.zeros(cu * cv, dtype=bool)
        for ci, cj, hs in zip(si, sj, sh_):
            if (ci, cj) in seen:
                continue
            seen.add((ci, cj))
            for half in (1, 2, 3):
                blk = _block(g, ci, cj, half, eu, ev)
                if blk is None:
                    break
                cells, ring_edges, ring_pos, interior = blk
                crossings = [k for k in range(len(ring_pos)) if ring_pos[k] != ring_pos[(k + 1) % len(ring_pos)]]
                if len(crossings) == 4:
                    break
            else:
                continue
            if blk is None or len(crossings) != 4 or used[cells].any():
                continue
            used[cells] = True
            overridden[cells] = True
            n_saddles += 1
            dropped[list(interior)] = True
            ce = [ring_edges[k] for k in crossings]
            if abs(hs) <= zt:
                node_pairs += [(ce[0], ce[1]), (ce[0], ce[2]), (ce[0], ce[3])]
            else:
                s_pos = hs > 0
                nr = len(ring_pos)
                for m in range(4):
                    k0, k1 = crossings[m], crossings[(m + 1) % 4]
                    if ring_pos[(k0 + 1) % nr] != s_pos:
                        node_pairs.append((ring_edges[k0], ring_edges[k1]))
    pairs += node_pairs

    cell_ok = ~overridden
    two = cell_ok & (ncross == 2)
    E = np.stack([e_b, e_t, e_l, e_r], axis=1)[two]
    Fm = np.stack([f_b, f_t, f_l, f_r], axis=1)[two]
    pairs += list(E[Fm].reshape(-1, 2))
    four = np.nonzero(cell_ok & (ncross == 4))[0]
    if len(four):
        i4, j4 = I[four], J[four]
        h00, h10, h01, h11 = h[i4, j4], h[ip[i4], j4], h[i4, jp[j4]], h[ip[i4], jp[j4]]
        den = h00 + h11 - h10 - h01
        sval = np.where(den != 0, (h00 * h11 - h10 * h01) / np.where(den != 0, den, 1), 0.25 * (h00 + h11 + h10 + h01))
        join_00_11 = (sval > 0) == (h00 > 0)
        for k, q in enumerate(four):
            if join_00_11[k]:
                pairs += [(e_b[q], e_r[q]), (e_l[q], e_t[q])]
            else:
                pairs += [(e_b[q], e_l[q]), (e_t[q], e_r[q])]

    # vertices: grid nodes where h is zero (and the collapsed pole / apex rows) join the crossings around them
    extra_pts = []
    extra_active = []
    extra_pairs = []
    n_extra = 0

    def new_node(point, is_active):
        nonlocal n_extra
        extra_pts.append(point)
        extra_active.append(is_active)
        n_extra += 1
        return n_edges + n_extra - 1

    def cell_edges(ci, cj):
        return [eu(ci, cj), eu(ci, jp[cj]), ev(ci, cj), ev(ip[ci], cj)]

    zero_nodes = np.argwhere(np.abs(h) <= zt)
    row_vertex = {}
    vertex_id = {}
    for i, j in zero_nodes:
        if j in g.collapsed:
            if j in row_vertex:
                continue
            x = to_global(A, g.pA[0, j])
            vid = new_node(x, bool(trim_margin(B, x[None])[0] >= 0))
            row_vertex[j] = vid
            cells = [(ci, cj) for cj in (j - 1, j) if 0 <= cj < cv for ci in range(cu)]
        else:
            x = to_global(A, g.pA[i, j])
            vid = new_node(x, bool(trim_margin(B, x[None])[0] >= 0))
            vertex_id[(i, j)] = vid
            ci_list = [i - 1, i] if g.per_u else [c for c in (i - 1, i) if 0 <= c < cu]
            cj_list = [j - 1, j] if g.per_v else [c for c in (j - 1, j) if 0 <= c < cv]
            cells = [(ci % cu, cj % cv) for ci in ci_list for cj in cj_list]
        for ci, cj in cells:
            for e in cell_edges(ci, cj):
                if active[e]:
                    extra_pairs.append((vid, e))
    for (i, j), vid in vertex_id.items():
        for di, dj in ((1, 0), (0, 1)):
            other = ((i + di) % nu, (j + dj) % nv)
            if other in vertex_id:
                extra_pairs.append((vid, vertex_id[other]))

    # extrema: sub-grid loops (critical value of the other sign) and contacts / tangency (zero value)
    is_min, is_max = _neighbour_extrema(h, g.per_u, g.per_v, tol=zt)
    cand = is_min | is_max
    for row in g.collapsed:
        cand[:, row] = False
    ci_, cj_ = np.nonzero(cand)
    stride = 1
    if len(ci_) > MAX_CANDIDATES:
        stride = int(np.ceil(len(ci_) / MAX_CANDIDATES))
        ci_, cj_ = ci_[::stride], cj_[::stride]
    features = []                       # (point, sample points, zero?, degenerate?)
    if len(ci_):
        fu, fv, fh, fdet, fconv, fH = g.critical_points(g.u[ci_], g.v[cj_], max_move=3.0)
        node_val = h[ci_, cj_]
        fu, fv = g.canonical(fu, fv)
        is_zero = np.abs(fh) <= zt
        other_sign = ((fh > 0) != (node_val > 0)) & ~is_zero
        degenerate = np.abs(fdet) < 1e-6
        keep = fconv & g.inside(fu, fv) & (is_zero | (other_sign & ((fdet > 1e-10) | degenerate)))
        if keep.any():
            fu, fv, fh, fH = fu[keep], fv[keep], fh[keep], fH[keep]
            is_zero, degenerate = is_zero[keep], degenerate[keep]
            fx = g.global_point(fu, fv)
            ok = trim_margin(B, fx) >= 0.0
            for k in np.nonzero(ok)[0]:
                pts = [fx[k]]
                if not is_zero[k]:
                    # points on the loop / band: parameter rays from the critical point, bisected to h = 0
                    th = np.linspace(0, 2 * np.pi, 12, endpoint=False)
                    found = ray_roots(A, B, np.full(12, fu[k]), np.full(12, fv[k]), np.cos(th) * g.su,
                                      np.sin(th) * g.sv, scale, bisections=120)
                    pts = list(found) or pts
                features.append((fx[k], pts, bool(is_zero[k]), bool(degenerate[k])))
    zero_vertices = [(vid, extra_pts[vid - n_edges]) for vid in list(vertex_id.values()) + list(row_vertex.values())
                     if extra_active[vid - n_edges]]
    feature_samples = []
    n_zero_groups = 0
    if features:
        cell3d = _cell_size_3d(g)
        radius = 4.0 * stride * cell3d + 1e-9 * scale
        fpts = np.array([f[0] for f in features])
        nf = len(features)
        tree = cKDTree(fpts)
        fp = np.array(list(tree.query_pairs(radius)), dtype=np.int64).reshape(-1, 2)
        fg = coo_matrix((np.ones(len(fp)), (fp[:, 0], fp[:, 1])), shape=(nf, nf))
        _, flab = connected_components(fg, directed=False)
        vtree = cKDTree(np.array([p for _, p in zero_vertices])) if zero_vertices else None
        for grp in np.unique(flab):
            members = np.nonzero(flab == grp)[0]
            pts = [p for k in members for p in features[k][1]]
            feature_samples += pts
            zero = any(features[k][2] for k in members)
            gp = fpts[members]
            extent = float(np.linalg.norm(gp.max(axis=0) - gp.min(axis=0)))
            ridge = np.mean([features[k][3] for k in members]) > 0.5 and extent > 3.0 * cell3d
            if zero:
                n_zero_groups += 1
                nid = new_node(gp[0], True)
                if vtree is not None:
                    for hits in vtree.query_ball_point(gp, radius):
                        for hidx in hits:
                            extra_pairs.append((nid, zero_vertices[hidx][0]))
            else:
                new_node(gp[0], True)
                if ridge:
                    new_node(gp[-1], True)        # a thin band round a ridge: its two edges
    # components
    N = n_edges + n_extra
    act = np.concatenate([active & ~dropped, np.array(extra_active, dtype=bool)])
    P = np.array(pairs + extra_pairs, dtype=np.int64).reshape(-1, 2)
    if len(P):
        P = P[act[P[:, 0]] & act[P[:, 1]]]
    graph = coo_matrix((np.ones(len(P)), (P[:, 0], P[:, 1])), shape=(N, N))
    _, labels = connected_components(graph, directed=False)
    act_ids = np.nonzero(act)[0]
    count = len(np.unique(labels[act_ids]))

    samp = [edge_pts[active]]
    if feature_samples:
        samp.append(np.array(feature_samples))
    vertex_pts = [extra_pts[k] for k in range(len(extra_pts)) if extra_active[k]]
    if vertex_pts:
        samp.append(np.array(vertex_pts))
    samples = np.vstack(samp) if samp else np.zeros((0, 3))
    if len(samples):
        # Newton may push a crossing on the grid's own trim edge a hair outside it: keep points inside both trims
        inside = np.minimum(trim_margin(A, samples), trim_margin(B, samples)) >= -1e-12 * scale
        samples = samples[inside]
    kind_ = "generic"
    if n_zero_groups:
        kind_ = "tangent" if sum(f[2] for f in features) > 2 else "contact"
    out = dict(count=count, samples=samples, kind=kind_, roles=(A, B), saddles=n_saddles,
               features=len(features))
    if with_labels:
        out["labels"] = labels
    return out


def _cell_size_3d(g):
    """Largest 3D edge length of the grid cells (away from collapsed rows)."""
    pa = g.pA
    d1 = np.linalg.norm(pa[g.ip] - pa[: g.cu], axis=-1).max()
    d2 = np.linalg.norm(pa[:, g.jp] - pa[:, : g.cv], axis=-1).max()
    return float(max(d1, d2))


def oracle(a, b, truth=None, n=GRID):
    """dict(count, samples (M, 3), kind) for the trimmed pair: the closed-form `truth` (a dict with count,
    samples and optionally kind) when given, else the brute force."""
    if truth is not None and (truth.get("count") is not None or truth.get("kind") in ("coincident", "unbounded")):
        samples = np.asarray(truth.get("samples", np.zeros((0, 3))), dtype=float).reshape(-1, 3)
        return dict(count=truth.get("count"), samples=samples, kind=truth.get("kind") or "generic",
                    sample_tol=truth.get("sample_tol", 0.0))
    return brute_force(a, b, n=n)


# ----------------------------------------------------------------------------------------------------------
# returned curves: dense points, components
# ----------------------------------------------------------------------------------------------------------
def dense_points(curve, scale, spacing=1e-3, max_points=100000, sag=5e-8, rounds=4, split=64):
    """Dense evaluations of a returned curve (its own points for a contact point): uniform in arc length,
    then refined (a few rounds, each splitting an interval at most `split` times) where the polyline turns,
    so that chords stay within about sag x scale of the arc, kinks at nodes included (the polyline stands
    for the curve in the distance checks)."""
    length = float(curve.length)
    pts = np.asarray(curve.points, dtype=float).reshape(-1, 3)
    if length <= 0 or curve.status == "contact":
        return pts[:1] if len(pts) else pts
    m = int(np.clip(length / (spacing * scale), 200, 40000))
    s = np.linspace(0.0, length, m)
    x = np.asarray(curve(s), dtype=float).reshape(-1, 3)
    for _ in range(rounds):
        step = np.linalg.norm(np.diff(x, axis=0), axis=1)
        t = np.diff(x, axis=0) / np.maximum(step, 1e-300)[:, None]
        turn = np.arccos(np.clip(np.sum(t[1:] * t[:-1], axis=1), -1.0, 1.0))
        k_mid = turn / np.maximum(0.5 * (step[1:] + step[:-1]), 1e-300)
        kappa = np.zeros(len(step))
        kappa[1:] = np.maximum(kappa[1:], k_mid)
        kappa[:-1] = np.maximum(kappa[:-1], k_mid)
        h_needed = np.sqrt(8.0 * sag * scale / np.maximum(kappa, 1e-300))
        extra = np.clip(np.ceil(step / h_needed).astype(int) - 1, 0, split)
        extra[step <= 1e-3 * sag * scale] = 0
        budget = max_points - len(s)
        if extra.sum() == 0 or budget <= 0:
            break
        if extra.sum() > budget:
            extra = np.floor(extra * budget / extra.sum()).astype(int)
        idx = np.repeat(np.arange(len(extra)), extra)                  # interval of each new point
        first = np.cumsum(extra) - extra
        k = np.arange(len(idx)) - np.repeat(first, extra) + 1          # 1..extra[i] within interval i
        more = s[idx] + (s[idx + 1] - s[idx]) * k / (extra[idx] + 1)
        if len(more) == 0:
            break
        xm = np.asarray(curve(more), dtype=float).reshape(-1, 3)
        s = np.concatenate([s, more])
        x = np.vstack([x, xm])
        order = np.argsort(s, kind="stable")
        s, x = s[order], x[order]
    return x


def segment_distances(P0, P1, Q0, Q1):
    """Distances between segments P0P1 and Q0Q1 (arrays (N, 3)), clamped closest points."""
    d1, d2, r = P1 - P0, Q1 - Q0, P0 - Q0
    a = np.sum(d1 * d1, -1)
    e = np.sum(d2 * d2, -1)
    f = np.sum(d2 * r, -1)
    c = np.sum(d1 * r, -1)
    b = np.sum(d1 * d2, -1)
    den = a * e - b * b
    a_ = np.where(a > 0, a, 1.0)
    e_ = np.where(e > 0, e, 1.0)
    s = np.where(den > 1e-300, np.clip((b * f - c * e) / np.where(den > 1e-300, den, 1.0), 0, 1), 0.0)
    t = (b * s + f) / e_
    t = np.where(e > 0, t, 0.0)
    s = np.where(t < 0, np.clip(-c / a_, 0, 1), np.where(t > 1, np.clip((b - c) / a_, 0, 1), s))
    s = np.where(a > 0, s, 0.0)
    t = np.clip(t, 0, 1)
    diff = (P0 + s[:, None] * d1) - (Q0 + t[:, None] * d2)
    return np.linalg.norm(diff, axis=-1)


def _segment_pairs_distance(P, Q, i, j):
    """min distance between the segments of P incident to vertices i and those of Q incident to j."""
    best = np.full(len(i), np.inf)
    for a in (-1, 0):
        ii = np.clip(i + a, 0, len(P) - 2)
        for b in (-1, 0):
            jj = np.clip(j + b, 0, len(Q) - 2)
            best = np.minimum(best, segment_distances(P[ii], P[ii + 1], Q[jj], Q[jj + 1]))
    return best


def polyline_distance(P, Q, radius):
    """min distance between polylines P and Q when it is below `radius` (else a value above it)."""
    if len(P) == 1 or len(Q) == 1:
        if len(P) == 1 and len(Q) == 1:
            return float(np.linalg.norm(P[0] - Q[0]))
        pt, poly = (P[0], Q) if len(P) == 1 else (Q[0], P)
        return float(point_polyline_distance(pt[None], poly)[0])
    hp = np.linalg.norm(np.diff(P, axis=0), axis=1).max()
    hq = np.linalg.norm(np.diff(Q, axis=0), axis=1).max()
    d, j = cKDTree(Q).query(P, k=1, distance_upper_bound=hp + hq + radius)
    i = np.nonzero(np.isfinite(d))[0]
    if len(i) == 0:
        return np.inf
    return float(_segment_pairs_distance(P, Q, i, j[i]).min())


def point_polyline_distance(points, poly, tree=None, bound=np.inf):
    """Distance from each point to the polyline `poly` (segments incident to the nearest vertices); with a
    finite bound, points farther than about bound from every vertex get inf (a KD-tree query for far points
    is slow, and the checks only need to know they are far)."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    if len(poly) == 1:
        return np.linalg.norm(points - poly[0], axis=-1)
    tree = cKDTree(poly) if tree is None else tree
    h = float(np.linalg.norm(np.diff(poly, axis=0), axis=1).max())
    k = min(3, len(poly))
    d, idx = tree.query(points, k=k, distance_upper_bound=bound + h)
    d = np.asarray(d).reshape(len(points), -1)
    idx = np.asarray(idx).reshape(len(points), -1)
    best = np.full(len(points), np.inf)
    for col in range(idx.shape[1]):
        ok = np.isfinite(d[:, col])
        if not ok.any():
            continue
        for off in (-1, 0):
            i0 = np.clip(idx[ok, col] + off, 0, len(poly) - 2)
            best[ok] = np.minimum(best[ok], segment_distances(points[ok], points[ok], poly[i0], poly[i0 + 1]))
    return best


def curve_components(curves, scale, join_tol=2e-6, dense=None):
    """Number of connected components of the union of returned curves, and the component of each curve.
    Curves within join_tol x scale of each other (polyline distance of dense evaluations) or sharing a node
    are one component; a 'contact' point curve is a component of its own."""
    n = len(curves)
    if dense is None:
        dense = [dense_points(c, scale) for c in curves]
    parent = list(range(n))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    tol = join_tol * scale
    for i in range(n):
        if curves[i].status == "contact":
            continue
        for j in range(i + 1, n):
            if curves[j].status == "contact" or find(i) == find(j):
                continue
            joined = polyline_distance(dense[i], dense[j], tol) <= tol
            if not joined:
                for ni in (np.asarray(getattr(curves[i], "nodes", np.zeros((0, 3)))).reshape(-1, 3),):
                    for nj in (np.asarray(getattr(curves[j], "nodes", np.zeros((0, 3)))).reshape(-1, 3),):
                        if len(ni) and len(nj):
                            dd = np.linalg.norm(ni[:, None] - nj[None], axis=-1)
                            joined = bool((dd <= tol).any())
            if joined:
                parent[find(i)] = find(j)
    roots = [find(i) for i in range(n)]
    return len(set(roots)), roots
