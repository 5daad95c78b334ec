"""Planar curves proven in closed form: two spheres, a plane and a sphere, or a plane and a cylinder, meet in exactly
one circle or ellipse (or in nothing), enclosed in outward-rounded intervals; a returned curve
X(t) = c + P cos t + Q sin t (a circle or an ellipse in closed form) is proven within a distance of it.

The surfaces are the sets |x - o|^2 = r^2 (a sphere), (x - o) . n = 0 (a plane, n its frame's third column as
stored) and |x - o|^2 - ((x - o) . a)^2 = r^2 (a cylinder, a its unit axis: the frame's third column normalised).

The true curve is held as (m, a, n, r) (``truth``, (10, 2) intervals: m rows 0-2, a rows 3-5, n rows 6-8, r row
9): the points m + r cos t (b1 - k1 a) + r sin t (b2 - k2 a), k_i = (n . b_i) / (n . a), for any orthonormal b1, b2
normal to a (b2 = a x b1), m on the axis a and on the plane normal to n:

- two spheres: their radical plane, (x - o_a) . d = (|d|^2 + r_a^2 - r_b^2) / 2, d = o_b - o_a, cuts either in the
  circle of centre m = o_a + k d, k = (|d|^2 + r_a^2 - r_b^2) / (2 |d|^2), a = n = d / |d| and r^2 = r_a^2 -
  k^2 |d|^2;
- a plane at signed distance delta = (o - c) . n / |n| from a sphere's centre c: m = c + delta n / |n|, a = n =
  n / |n|, r^2 = R^2 - delta^2;
- a plane and a cylinder (n . a not 0): m = o_c + lambda a, lambda = n . (o_p - o_c) / (n . a), and r the
  cylinder's radius (an ellipse of semi-axes r and r / |cos(n, a)|).

r^2 > 0 proven: one curve, crossed transversally; r^2 < 0 proven: no common point.

The distance bound chooses, of the true curve's parametrisations, the one nearest the returned curve's: b1 along P's
component normal to a, b2 turned to Q's side. Then |X(t) - true(t)| <= |c - m| + |P - r (b1 - k1 a)| + |Q -
r (b2 - k2 a)| at every t: every point of the returned curve lies within that of the true curve, and every point of
the true curve within it of the returned curve (a Hausdorff bound for the whole dense output, not only its stored
points). The returned curve's own evaluation in floating point (its cosine, sine and sums) adds at most EVAL_ULPS
ulps of |c| + |P| + |Q|.

References
----------
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, ch. 5-6 (interval
arithmetic with outward rounding).
"""
import math

import numpy as np

from ..._lib.jit import jit
from ..geometry.interval import EPS, down, iadd, imul, isqr, iscale, isub, mag, point, up

#: The outcomes: a curve proven, no common point proven, neither.
CURVE, EMPTY, UNDECIDED = 0, 1, 2
#: Ulps of |c| + |P| + |Q| allowed for the floating-point evaluation of a returned point.
EVAL_ULPS = 8.0
#: Rows of a truth (10, 2).
M, A, N, R = 0, 3, 6, 9


@jit
def _isqrt(a):
    """sqrt of an interval with a[0] >= 0."""
    return (max(down(math.sqrt(a[0])), 0.0), up(math.sqrt(a[1])))


@jit
def _idiv(a, b):
    """a / b for an interval b that does not hold 0."""
    q1, q2, q3, q4 = a[0] / b[0], a[0] / b[1], a[1] / b[0], a[1] / b[1]
    return (down(min(min(q1, q2), min(q3, q4))), up(max(max(q1, q2), max(q3, q4))))


@jit
def _row(truth, i):
    return (truth[i, 0], truth[i, 1])


@jit
def _set(truth, i, x):
    truth[i, 0], truth[i, 1] = x


@jit
def _dot(x, y):
    """x . y for interval 3-vectors (tuples of intervals)."""
    return iadd(iadd(imul(x[0], y[0]), imul(x[1], y[1])), imul(x[2], y[2]))


@jit
def _vec(truth, row):
    return (_row(truth, row), _row(truth, row + 1), _row(truth, row + 2))


@jit
def _floats(v):
    return (point(v[0]), point(v[1]), point(v[2]))


@jit
def _unit(v):
    """(v / |v|, True), or (v, False) when |v| may be 0."""
    vv = _dot(v, v)
    if vv[0] <= 0.0:
        return v, False
    length = _isqrt(vv)
    return (_idiv(v[0], length), _idiv(v[1], length), _idiv(v[2], length)), True


@jit
def _cross(x, y):
    return (isub(imul(x[1], y[2]), imul(x[2], y[1])), isub(imul(x[2], y[0]), imul(x[0], y[2])),
            isub(imul(x[0], y[1]), imul(x[1], y[0])))


@jit
def _norm_up(v):
    """An upper bound of the length of any vector in the interval vector v."""
    return up(math.sqrt(up(up(mag(v[0]) ** 2 + mag(v[1]) ** 2) + mag(v[2]) ** 2)))


@jit
def _store(truth, m, a, n, r2):
    """Write the truth; CURVE, EMPTY (r^2 < 0) or UNDECIDED (r^2 holding 0)."""
    if r2[1] < 0.0:
        return EMPTY
    if r2[0] <= 0.0:
        return UNDECIDED
    for i in range(3):
        _set(truth, M + i, m[i])
        _set(truth, A + i, a[i])
        _set(truth, N + i, n[i])
    _set(truth, R, _isqrt(r2))
    return CURVE


@jit
def spheres(oa, ra, ob, rb, truth):
    """The circle of two spheres (centres oa, ob (3,), radii ra, rb) into truth (10, 2): CURVE, EMPTY or
    UNDECIDED (also when concentric)."""
    d = (isub(point(ob[0]), point(oa[0])), isub(point(ob[1]), point(oa[1])), isub(point(ob[2]), point(oa[2])))
    dd = _dot(d, d)
    if dd[0] <= 0.0:
        return UNDECIDED
    ra2, rb2 = isqr(point(ra)), isqr(point(rb))
    k = _idiv(isub(iadd(dd, ra2), rb2), iscale(dd, 2.0))
    axis, _ = _unit(d)
    m = (iadd(point(oa[0]), imul(k, d[0])), iadd(point(oa[1]), imul(k, d[1])), iadd(point(oa[2]), imul(k, d[2])))
    return _store(truth, m, axis, axis, isub(ra2, imul(isqr(k), dd)))


@jit
def plane_sphere(o, n, c, r, truth):
    """The circle of the plane through o with normal n (3,) and the sphere of centre c (3,) and radius r."""
    axis, ok = _unit(_floats(n))
    if not ok:
        return UNDECIDED
    delta = _dot((isub(point(o[0]), point(c[0])), isub(point(o[1]), point(c[1])), isub(point(o[2]), point(c[2]))),
                 axis)
    m = (iadd(point(c[0]), imul(delta, axis[0])), iadd(point(c[1]), imul(delta, axis[1])),
         iadd(point(c[2]), imul(delta, axis[2])))
    return _store(truth, m, axis, axis, isub(isqr(point(r)), isqr(delta)))


@jit
def plane_cylinder(o, n, oc, axis, r, truth):
    """The ellipse of the plane through o with normal n (3,) and the cylinder through oc (3,) along axis (3,) of
    radius r: CURVE, or UNDECIDED when n . axis may be 0 (the plane along the axis)."""
    a, ok = _unit(_floats(axis))
    nu, ok_n = _unit(_floats(n))
    if not (ok and ok_n):
        return UNDECIDED
    na = _dot(nu, a)
    if na[0] <= 0.0 <= na[1]:
        return UNDECIDED
    lam = _idiv(_dot((isub(point(o[0]), point(oc[0])), isub(point(o[1]), point(oc[1])),
                      isub(point(o[2]), point(oc[2]))), nu), na)
    m = (iadd(point(oc[0]), imul(lam, a[0])), iadd(point(oc[1]), imul(lam, a[1])),
         iadd(point(oc[2]), imul(lam, a[2])))
    return _store(truth, m, a, nu, isqr(point(r)))


@jit
def _semi_diameters(truth, b1, sign):
    """(P, Q): the true curve's r (b1 - k1 a) and r (b2 - k2 a), b2 = sign a x b1 (b1 a unit interval vector normal
    to a)."""
    a, n, r = _vec(truth, A), _vec(truth, N), _row(truth, R)
    b2 = _cross(a, b1)
    if sign < 0.0:
        b2 = (iscale(b2[0], -1.0), iscale(b2[1], -1.0), iscale(b2[2], -1.0))
    na = _dot(n, a)
    k1, k2 = _idiv(_dot(n, b1), na), _idiv(_dot(n, b2), na)
    P = (imul(r, isub(b1[0], imul(k1, a[0]))), imul(r, isub(b1[1], imul(k1, a[1]))),
         imul(r, isub(b1[2], imul(k1, a[2]))))
    Q = (imul(r, isub(b2[0], imul(k2, a[0]))), imul(r, isub(b2[1], imul(k2, a[1]))),
         imul(r, isub(b2[2], imul(k2, a[2]))))
    return P, Q


@jit
def within_band(truth, o, e, lo, hi):
    """True when lo < (x - o) . e < hi at every point x of the true curve (e (3,) any vector: a plane's frame
    column, a cylinder's axis): (m - o) . e +- sqrt((e . P)^2 + (e . Q)^2), for any b1 (the root does not depend
    on it)."""
    a = _vec(truth, A)
    k = int(np.argmin(np.abs(np.array([truth[A, 0], truth[A + 1, 0], truth[A + 2, 0]]))))
    w = (point(1.0 if k == 0 else 0.0), point(1.0 if k == 1 else 0.0), point(1.0 if k == 2 else 0.0))
    b1, ok = _unit(_cross(a, w))
    if not ok:
        return False
    P, Q = _semi_diameters(truth, b1, 1.0)
    ev = _floats(e)
    m = _vec(truth, M)
    at = _dot((isub(m[0], point(o[0])), isub(m[1], point(o[1])), isub(m[2], point(o[2]))), ev)
    reach = _isqrt(iadd(isqr(_dot(ev, P)), isqr(_dot(ev, Q))))
    return lo < down(at[0] - reach[1]) and up(at[1] + reach[1]) < hi


@jit
def distance_bound(truth, c, P, Q):
    """An upper bound of sup_t |X(t) - true(t)| for the returned X(t) = c + P cos t + Q sin t (c, P, Q (3,)) and
    the true curve parametrised as in the module docstring, with the evaluation's round-off; inf when P lies along
    the axis or Q's side is not decided (no parametrisation to compare with)."""
    a = _vec(truth, A)
    Pv, Qv = _floats(P), _floats(Q)
    along = _dot(Pv, a)
    b1, ok = _unit((isub(Pv[0], imul(along, a[0])), isub(Pv[1], imul(along, a[1])), isub(Pv[2], imul(along, a[2]))))
    if not ok:
        return math.inf
    side = _dot(_cross(a, b1), Qv)
    if side[0] <= 0.0 <= side[1]:
        return math.inf
    tp, tq = _semi_diameters(truth, b1, 1.0 if side[0] > 0.0 else -1.0)
    m = _vec(truth, M)
    dc = (isub(point(c[0]), m[0]), isub(point(c[1]), m[1]), isub(point(c[2]), m[2]))
    dp = (isub(Pv[0], tp[0]), isub(Pv[1], tp[1]), isub(Pv[2], tp[2]))
    dq = (isub(Qv[0], tq[0]), isub(Qv[1], tq[1]), isub(Qv[2], tq[2]))
    bound = up(up(_norm_up(dc) + _norm_up(dp)) + _norm_up(dq))
    size = (math.sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) + math.sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2])
            + math.sqrt(Q[0] * Q[0] + Q[1] * Q[1] + Q[2] * Q[2]))
    return up(bound + up(EVAL_ULPS * EPS * size))
