"""Certified intersection points: the Krawczyk test on each point's normal-plane system, in interval arithmetic.

For a point p near the intersection curve of surfaces a and b, with tangent t, the 3 x 3 system

    G(x) = (F_a(x), F_b(x), t . (x - p))

(F the polynomial implicit functions of spatialkin.kernels.geometry.interval.implicit_jet, read in each surface's
local coordinates q = R^T (x - o)) has as zeros the points of a ∩ b in the plane through p normal to t. For the box
X = p + [-r, r]^3 the Krawczyk operator

    K(X) = p - Y G(p) + (I - Y J(X)) (X - p),    Y the float inverse of the Jacobian at p,

evaluated with outward rounding, lying strictly inside X proves that X holds exactly one zero of G: a true point
of both (untrimmed) surfaces within max-norm distance r of p.

References
----------
R. Krawczyk, "Newton-Algorithmen zur Bestimmung von Nullstellen mit Fehlerschranken", Computing 4 (1969) 187-201.
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, sec. 8.2 and 8.4.
"""
import math

import numpy as np

from ..._lib.jit import jit
from ..geometry.interval import EPS, iadd, implicit_jet, imul, iscale, isub, mag, point, up
from ..geometry.surfaces import ORIGIN, ROT

#: The first box half-width is this many times the max-norm of the Newton step Y G(p) (its enclosure).
NEWTON_STEP_FACTOR = 2.0
#: Factor by which the half-width grows after a failed test.
INFLATION = 2.0
#: Smallest half-width, in ulps of max(|p|, size).
FLOOR_ULPS = 2.0


@jit(forceinline=True)
def _implicit_global(data, X):
    """(F, grad F in global coordinates (3 intervals)) of the surface's implicit function over the interval
    point X (3 intervals, global)."""
    d0 = isub(X[0], point(data[ORIGIN]))
    d1 = isub(X[1], point(data[ORIGIN + 1]))
    d2 = isub(X[2], point(data[ORIGIN + 2]))
    # q_i = sum_k R[k, i] d_k  (R row-major in data[ROT:ROT + 9])
    q0 = iadd(iadd(iscale(d0, data[ROT]), iscale(d1, data[ROT + 3])), iscale(d2, data[ROT + 6]))
    q1 = iadd(iadd(iscale(d0, data[ROT + 1]), iscale(d1, data[ROT + 4])), iscale(d2, data[ROT + 7]))
    q2 = iadd(iadd(iscale(d0, data[ROT + 2]), iscale(d1, data[ROT + 5])), iscale(d2, data[ROT + 8]))
    f, g, _ = implicit_jet(data, (q0, q1, q2))
    # (grad_x F)_i = sum_k R[i, k] (grad_q F)_k
    gx0 = iadd(iadd(iscale(g[0], data[ROT]), iscale(g[1], data[ROT + 1])), iscale(g[2], data[ROT + 2]))
    gx1 = iadd(iadd(iscale(g[0], data[ROT + 3]), iscale(g[1], data[ROT + 4])), iscale(g[2], data[ROT + 5]))
    gx2 = iadd(iadd(iscale(g[0], data[ROT + 6]), iscale(g[1], data[ROT + 7])), iscale(g[2], data[ROT + 8]))
    return f, (gx0, gx1, gx2)


@jit(forceinline=True)
def _mid(x):
    return 0.5 * (x[0] + x[1])


@jit
def _inverse(j, out):
    """out = j^-1 (3 x 3, float, by cofactors); False when j is singular or the inverse not finite."""
    c00 = j[1, 1] * j[2, 2] - j[1, 2] * j[2, 1]
    c01 = j[1, 2] * j[2, 0] - j[1, 0] * j[2, 2]
    c02 = j[1, 0] * j[2, 1] - j[1, 1] * j[2, 0]
    det = j[0, 0] * c00 + j[0, 1] * c01 + j[0, 2] * c02
    if det == 0.0 or not math.isfinite(det):
        return False
    out[0, 0] = c00 / det
    out[1, 0] = c01 / det
    out[2, 0] = c02 / det
    out[0, 1] = (j[0, 2] * j[2, 1] - j[0, 1] * j[2, 2]) / det
    out[1, 1] = (j[0, 0] * j[2, 2] - j[0, 2] * j[2, 0]) / det
    out[2, 1] = (j[0, 1] * j[2, 0] - j[0, 0] * j[2, 1]) / det
    out[0, 2] = (j[0, 1] * j[1, 2] - j[0, 2] * j[1, 1]) / det
    out[1, 2] = (j[0, 2] * j[1, 0] - j[0, 0] * j[1, 2]) / det
    out[2, 2] = (j[0, 0] * j[1, 1] - j[0, 1] * j[1, 0]) / det
    for i in range(3):
        for k in range(3):
            if not math.isfinite(out[i, k]):
                return False
    return True


@jit
def point_radius(a_data, b_data, p, t, cap, floor, radius0):
    """The half-width r of a box p + [-r, r]^3 that passes the Krawczyk test (see the module docstring), from
    radius0 (or NEWTON_STEP_FACTOR times the Newton step when radius0 <= 0) growing by INFLATION up to cap; inf
    when none passes (a singular point: parallel normals, a node, an apex; or a point too far off)."""
    P = (point(p[0]), point(p[1]), point(p[2]))
    fa, ga = _implicit_global(a_data, P)
    fb, gb = _implicit_global(b_data, P)
    jac = np.empty((3, 3))
    y = np.empty((3, 3))
    for k in range(3):
        jac[0, k] = _mid(ga[k])
        jac[1, k] = _mid(gb[k])
        jac[2, k] = t[k]
    if not _inverse(jac, y):
        return math.inf
    # Y G(p), G(p) = (F_a(p), F_b(p), 0) (the third row vanishes exactly at p)
    steps = np.empty((3, 2))
    largest = 0.0
    for i in range(3):
        s = iadd(iscale(fa, y[i, 0]), iscale(fb, y[i, 1]))
        steps[i, 0], steps[i, 1] = s[0], s[1]
        largest = max(largest, mag(s))
    r = radius0 if radius0 > 0.0 else max(NEWTON_STEP_FACTOR * largest, floor)
    magnitude = max(abs(p[0]), max(abs(p[1]), abs(p[2])))
    while r <= cap:
        X = ((p[0] - r, p[0] + r), (p[1] - r, p[1] + r), (p[2] - r, p[2] + r))
        X = ((X[0][0] - (abs(X[0][0]) * EPS), X[0][1] + abs(X[0][1]) * EPS),
             (X[1][0] - (abs(X[1][0]) * EPS), X[1][1] + abs(X[1][1]) * EPS),
             (X[2][0] - (abs(X[2][0]) * EPS), X[2][1] + abs(X[2][1]) * EPS))
        _, ja = _implicit_global(a_data, X)
        _, jb = _implicit_global(b_data, X)
        ok = True
        fills = False
        for i in range(3):
            # row i of (I - Y J(X)) (X - p) (X holds p +- r: its bounds were moved outward)
            acc = (0.0, 0.0)
            for k in range(3):
                jy = iadd(iadd(iscale(ja[k], y[i, 0]), iscale(jb[k], y[i, 1])), point(y[i, 2] * t[k]))
                jy = (jy[0] - abs(jy[0]) * EPS, jy[1] + abs(jy[1]) * EPS)      # (y[i, 2] * t[k] rounded)
                m = isub(point(1.0 if i == k else 0.0), jy)
                acc = iadd(acc, imul(m, isub(X[k], point(p[k]))))
            k_i = isub(acc, (steps[i, 0], steps[i, 1]))
            if not (mag(k_i) < r):
                ok = False
            if 0.5 * (acc[1] - acc[0]) >= r:
                fills = True
        if ok:
            return up(r + 4.0 * EPS * (magnitude + r))     # (X's bounds lie within two ulps beyond p +- r)
        if fills:           # the contraction term alone fills the box: larger boxes only widen J(X)
            return math.inf
        r *= INFLATION
    return math.inf


@jit
def point_radii(a_data, b_data, points, tangents, cap, size, radius0, out):
    """point_radius of every point (N, 3) with its tangent (N, 3), into out (N,)."""
    for i in range(points.shape[0]):
        p = points[i]
        floor = FLOOR_ULPS * EPS * max(max(abs(p[0]), max(abs(p[1]), abs(p[2]))), size)
        out[i] = point_radius(a_data, b_data, p, tangents[i], cap, floor, radius0)


@jit
def implicit_box(data, box, out):
    """Enclosures of the surface's implicit function and its global gradient over the box (3, 2) (lo, hi per
    coordinate): out (4, 2) = F, dF/dx, dF/dy, dF/dz."""
    f, g = _implicit_global(data, ((box[0, 0], box[0, 1]), (box[1, 0], box[1, 1]), (box[2, 0], box[2, 1])))
    out[0, 0], out[0, 1] = f[0], f[1]
    for k in range(3):
        out[k + 1, 0], out[k + 1, 1] = g[k][0], g[k][1]
