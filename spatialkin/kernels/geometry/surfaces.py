"""Surface kernels: points, first and second derivatives, implicit values, exact distances, inverse maps.

A placed surface is packed into one float64 array (its *data*), so that one jitted function serves every
kind of surface and every pair of them:

    data[KIND]            kind code: the key of the surface's traits (spatialkin.geometry.traits); the
                          built-in kinds use their geometry codes
    data[P0], data[P1]    shape parameters (see below)
    data[GEOMETRY]        geometry code (PLANE, SPHERE, CYLINDER, CONE, TORUS): the parametrisation and the
                          implicit function these kernels (and spatialkin.kernels.geometry.interval) evaluate
    data[ORIGIN:+3]       frame origin in global coordinates
    data[ROT:+9]          frame rotation, row-major; its columns are the local x, y, z axes
    data[BOUNDS:+4]       u_min, u_max, v_min, v_max (infinite where unbounded)

Local parametrisations (x, y, z in the surface frame):

    PLANE     (u, v, 0)
    SPHERE    (R cos v cos u, R cos v sin u, R sin v)                 P0 = R
    TORUS     ((R + r cos v) cos u, (R + r cos v) sin u, r sin v)     P0 = R (major), P1 = r (minor)
    CYLINDER  (r cos u, r sin u, v)                                   P0 = r
    CONE      (v tan a cos u, v tan a sin u, v)   apex at the origin  P1 = tan a

The sphere is the torus with R = 0, and the cylinder and cone are both the revolution of the line
rho(v) = P0 + P1 v, so three parametrisations cover the five geometries. The geometries are a closed set
compiled here: a surface kind with a new geometry needs its branch in these kernels and in
spatialkin.kernels.geometry.interval; a kind over an existing geometry (another chart, trim or set of traits) needs none.

References
----------
"Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines of the
light industry" (in Ukrainian; [Looper]): the torus and sphere parametrisations and their
first derivatives (decoded from the paper, whose printed formulas are damaged).
"""
import math

import numpy as np

from ..._lib.jit import jit

# --- layout of the data array -------------------------------------------------------------------------
KIND, P0, P1, GEOMETRY, ORIGIN, ROT, BOUNDS = 0, 1, 2, 3, 4, 7, 16
DATA_SIZE = 20

# --- geometry codes (also the kind codes of the built-in kinds) ---------------------------------------------------------------------------------------
PLANE, SPHERE, CYLINDER, CONE, TORUS = 0, 1, 2, 3, 4

# --- rows of the derivative block returned by ``derivatives`` ----------------------------------------
POINT, DU, DV, DUU, DUV, DVV = 0, 1, 2, 3, 4, 5


@jit
def to_global(data, local, out):
    """out = origin + rotation @ local (a point)."""
    for i in range(3):
        out[i] = data[ORIGIN + i] + (data[ROT + 3 * i] * local[0] + data[ROT + 3 * i + 1] * local[1]
                                     + data[ROT + 3 * i + 2] * local[2])


@jit
def rotate(data, local, out):
    """out = rotation @ local (a vector)."""
    for i in range(3):
        out[i] = (data[ROT + 3 * i] * local[0] + data[ROT + 3 * i + 1] * local[1]
                  + data[ROT + 3 * i + 2] * local[2])


@jit
def to_local(data, point, out):
    """out = rotation.T @ (point - origin)."""
    d0 = point[0] - data[ORIGIN]
    d1 = point[1] - data[ORIGIN + 1]
    d2 = point[2] - data[ORIGIN + 2]
    for j in range(3):
        out[j] = data[ROT + j] * d0 + data[ROT + 3 + j] * d1 + data[ROT + 6 + j] * d2


@jit
def local_rows(data, u, v):
    """Local point and derivatives (point, S_u, S_v, S_uu, S_uv, S_vv), each a 3-tuple: no allocation (the hot
    path; the rows a caller does not use cost a few multiplications, the trigonometry is shared)."""
    geometry = int(data[GEOMETRY])
    zero = (0.0, 0.0, 0.0)
    if geometry == PLANE:
        return (u, v, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), zero, zero, zero
    cu = math.cos(u)
    su = math.sin(u)
    if geometry == SPHERE or geometry == TORUS:
        big = 0.0 if geometry == SPHERE else data[P0]
        small = data[P0] if geometry == SPHERE else data[P1]
        cv = math.cos(v)
        sv = math.sin(v)
        w = big + small * cv
        return ((w * cu, w * su, small * sv), (-w * su, w * cu, 0.0), (-small * sv * cu, -small * sv * su, small * cv),
                (-w * cu, -w * su, 0.0), (small * sv * su, -small * sv * cu, 0.0),
                (-small * cv * cu, -small * cv * su, -small * sv))
    # CYLINDER, CONE: revolution of rho(v) = P0 + P1 v
    rho = data[P0] + data[P1] * v
    b = data[P1]
    return ((rho * cu, rho * su, v), (-rho * su, rho * cu, 0.0), (b * cu, b * su, 1.0),
            (-rho * cu, -rho * su, 0.0), (-b * su, b * cu, 0.0), zero)


@jit
def rotated(data, x):
    """rotation @ x for a 3-tuple x, as a 3-tuple."""
    return (data[ROT] * x[0] + data[ROT + 1] * x[1] + data[ROT + 2] * x[2],
            data[ROT + 3] * x[0] + data[ROT + 4] * x[1] + data[ROT + 5] * x[2],
            data[ROT + 6] * x[0] + data[ROT + 7] * x[1] + data[ROT + 8] * x[2])


@jit(forceinline=True)          # (the right-hand side's hot path: spatialkin.kernels.march.curve.dragilev_into)
def frame(data, u, v):
    """Global point and first derivatives (point, S_u, S_v), each a 3-tuple (no allocation)."""
    rows = local_rows(data, u, v)
    r = rotated(data, rows[0])
    return (data[ORIGIN] + r[0], data[ORIGIN + 1] + r[1], data[ORIGIN + 2] + r[2]), rotated(data, rows[1]), rotated(data, rows[2])


@jit
def second(data, u, v):
    """Global second derivatives (S_uu, S_uv, S_vv), each a 3-tuple."""
    rows = local_rows(data, u, v)
    return rotated(data, rows[3]), rotated(data, rows[4]), rotated(data, rows[5])


@jit
def local_derivatives(data, u, v, loc):
    """Local point and derivatives (6, 3): rows POINT, DU, DV, DUU, DUV, DVV."""
    rows = local_rows(data, u, v)
    for i in range(6):
        for j in range(3):
            loc[i, j] = rows[i][j]


@jit
def derivatives(data, u, v, out):
    """Global point and its first and second derivatives in (u, v), written to out (6, 3)."""
    rows = frame(data, u, v) + second(data, u, v)
    for i in range(6):
        for j in range(3):
            out[i, j] = rows[i][j]


@jit
def implicit_local(data, q):
    """A signed implicit value of the surface at the local point q, zero exactly on the surface.

    It is the signed distance for the plane, sphere, cylinder, cone and ring torus (positive outside);
    for a horn or spindle torus it is the product of the signed distances to the two circles of the
    meridian plane, which vanishes on both the outer (apple) and inner (lemon) parts.
    """
    geometry = int(data[GEOMETRY])
    if geometry == PLANE:
        return q[2]
    if geometry == SPHERE:
        return math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - data[P0]
    rho = math.sqrt(q[0] * q[0] + q[1] * q[1])
    if geometry == TORUS:
        big = data[P0]
        small = data[P1]
        outer = math.sqrt((rho - big) ** 2 + q[2] * q[2]) - small
        if small < big:
            return outer
        inner = math.sqrt((rho + big) ** 2 + q[2] * q[2]) - small
        return outer * inner / small
    # revolution of the line rho = a + b z: signed distance to the nearer generator of the meridian plane
    a = data[P0]
    b = data[P1]
    norm = math.sqrt(1.0 + b * b)
    d_same = (rho - a - b * q[2]) / norm
    d_opposite = (-rho - a - b * q[2]) / norm
    if abs(d_same) <= abs(d_opposite):
        return d_same
    return -d_opposite


@jit
def implicit_value(data, point):
    """Signed implicit value at a global point (see ``implicit_local``)."""
    d0 = point[0] - data[ORIGIN]
    d1 = point[1] - data[ORIGIN + 1]
    d2 = point[2] - data[ORIGIN + 2]
    return implicit_local(data, (data[ROT] * d0 + data[ROT + 3] * d1 + data[ROT + 6] * d2,
                                 data[ROT + 1] * d0 + data[ROT + 4] * d1 + data[ROT + 7] * d2,
                                 data[ROT + 2] * d0 + data[ROT + 5] * d1 + data[ROT + 8] * d2))


@jit
def distance_local(data, q):
    """Exact unsigned distance from the local point q to the (untrimmed) surface."""
    geometry = int(data[GEOMETRY])
    if geometry == PLANE:
        return abs(q[2])
    if geometry == SPHERE:
        return abs(math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - data[P0])
    rho = math.sqrt(q[0] * q[0] + q[1] * q[1])
    if geometry == TORUS:
        big = data[P0]
        small = data[P1]
        d_outer = abs(math.sqrt((rho - big) ** 2 + q[2] * q[2]) - small)
        d_inner = abs(math.sqrt((rho + big) ** 2 + q[2] * q[2]) - small)
        return min(d_outer, d_inner)
    a = data[P0]
    b = data[P1]
    norm = math.sqrt(1.0 + b * b)
    d_same = abs(rho - a - b * q[2]) / norm
    d_opposite = abs(-rho - a - b * q[2]) / norm
    return min(d_same, d_opposite)


@jit
def distances(data, points, out):
    """Exact unsigned distances of points (N, 3) to the surface, written to out (N,)."""
    q = np.empty(3)
    for k in range(points.shape[0]):
        to_local(data, points[k], q)
        out[k] = distance_local(data, q)


@jit
def farther_distances(a_data, b_data, points, cap, roundoff, out):
    """out (N,): each point's (N, 3) distance to the farther of the surfaces a and b, at most cap, plus roundoff
    times its largest |coordinate| (a point's gap to a curve's surfaces; cap inf and roundoff 0: the larger of its
    two distances)."""
    q = np.empty(3)
    for k in range(points.shape[0]):
        to_local(a_data, points[k], q)
        gap = distance_local(a_data, q)
        to_local(b_data, points[k], q)
        gap = max(gap, distance_local(b_data, q))
        gap = min(gap, cap)
        out[k] = gap + roundoff * max(abs(points[k, 0]), abs(points[k, 1]), abs(points[k, 2]))


@jit
def inverse_local(data, q, uv):
    """Parameters (u, v) of the surface point nearest to the local point q, written to uv.

    Exact foot point for every kind; u is in (-pi, pi].
    """
    geometry = int(data[GEOMETRY])
    if geometry == PLANE:
        uv[0] = q[0]
        uv[1] = q[1]
        return
    theta = math.atan2(q[1], q[0])
    rho = math.sqrt(q[0] * q[0] + q[1] * q[1])
    if geometry == SPHERE:
        uv[0] = theta
        uv[1] = math.atan2(q[2], rho)
        return
    if geometry == TORUS:
        big = data[P0]
        small = data[P1]
        d_outer = abs(math.sqrt((rho - big) ** 2 + q[2] * q[2]) - small)
        d_inner = abs(math.sqrt((rho + big) ** 2 + q[2] * q[2]) - small)
        if d_outer <= d_inner:
            uv[0] = theta
            uv[1] = math.atan2(q[2], rho - big)
        else:
            uv[0] = theta + math.pi if theta <= 0.0 else theta - math.pi
            uv[1] = math.atan2(q[2], -rho - big)
        return
    a = data[P0]
    b = data[P1]
    v_same = (b * (rho - a) + q[2]) / (1.0 + b * b)
    v_opposite = (b * (-rho - a) + q[2]) / (1.0 + b * b)
    d_same = (a + b * v_same - rho) ** 2 + (v_same - q[2]) ** 2
    d_opposite = (a + b * v_opposite + rho) ** 2 + (v_opposite - q[2]) ** 2
    if d_same <= d_opposite:
        uv[0] = theta
        uv[1] = v_same
    else:
        uv[0] = theta + math.pi if theta <= 0.0 else theta - math.pi
        uv[1] = v_opposite


@jit
def inverse(data, points, out):
    """Foot-point parameters (N, 2) of global points (N, 3)."""
    q = np.empty(3)
    for k in range(points.shape[0]):
        to_local(data, points[k], q)
        inverse_local(data, q, out[k])


@jit
def evaluate(data, uv, out):
    """Global points (N, 3) at parameters uv (N, 2)."""
    loc = np.empty((6, 3))
    for k in range(uv.shape[0]):
        local_derivatives(data, uv[k, 0], uv[k, 1], loc)
        to_global(data, loc[POINT], out[k])


#: Below this sine of their angle two directions are parallel (recharted_sphere's cross products).
UNIT_CROSS_FLOOR = 1e-12


@jit
def recharted_sphere(data, point, tangent, bend, out):
    """out = sphere data with its chart turned so that point is at (u, v) = (0, 0).

    The equator runs along the tangent; but where the curve's curvature vector `bend` (C'', zero if not
    known) shows it bending round a small circle of angular radius below 60 degrees, the equator runs
    through that circle's centre instead, so that a loop close to the circle stays within 60 degrees of the
    equator (no re-charting on the way round). A zero tangent takes any axis normal to the radius.
    """
    for i in range(out.shape[0]):
        out[i] = data[i]
    x = np.empty(3)
    for i in range(3):
        x[i] = point[i] - data[ORIGIN + i]
    nx = math.sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2])
    for i in range(3):
        x[i] /= nx
    z = np.empty(3)
    z[:] = 0.0
    k2 = bend[0] * bend[0] + bend[1] * bend[1] + bend[2] * bend[2]
    if k2 > 0.0:
        # the osculating circle lies on the sphere: its centre point + C''/|C''|^2 gives the circle's axis
        c = np.empty(3)
        for i in range(3):
            c[i] = point[i] + bend[i] / k2 - data[ORIGIN + i]
        nc = math.sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2])
        if nc > 0.0 and (x[0] * c[0] + x[1] * c[1] + x[2] * c[2]) > 0.5 * nc:
            _unit_cross(x, c, z, UNIT_CROSS_FLOOR * nc)     # (c is a length: the floor relative to it)
    if z[0] == 0.0 and z[1] == 0.0 and z[2] == 0.0:
        _unit_cross(x, tangent, z, UNIT_CROSS_FLOOR)
    if z[0] == 0.0 and z[1] == 0.0 and z[2] == 0.0:
        axis = np.zeros(3)
        smallest = 0                           # the first axis where |x| is least (as np.argmin)
        for i in range(1, 3):
            if abs(x[i]) < abs(x[smallest]):
                smallest = i
        axis[smallest] = 1.0
        _unit_cross(x, axis, z, UNIT_CROSS_FLOOR)
    y = np.empty(3)
    _unit_cross(z, x, y, UNIT_CROSS_FLOOR)
    for i in range(3):
        out[ROT + 3 * i] = x[i]
        out[ROT + 3 * i + 1] = y[i]
        out[ROT + 3 * i + 2] = z[i]


@jit
def _unit_cross(a, b, out, floor):
    """out = a x b normalised, or zeros where |a x b| < floor (UNIT_CROSS_FLOOR times |a| |b|: a a unit
    vector, b a unit vector or a length)."""
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]
    n = math.sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2])
    for i in range(3):
        out[i] = out[i] / n if n >= floor else 0.0
