"""Circles proven in closed form: two spheres, or a plane and a sphere, meet in exactly one circle (or in nothing),
its centre, unit axis and radius enclosed in outward-rounded intervals, and a returned curve
X(t) = c + P cos t + Q sin t (a circle or an ellipse in closed form) proven within a distance of it.

The surfaces are the sets |x - o|^2 = r^2 (a sphere) and (x - o) . n = 0 (a plane, n its frame's third column as
stored). Two spheres meet where their radical plane, (x - o_a) . d = (|d|^2 + r_a^2 - r_b^2) / 2 with d = o_b - o_a,
cuts either: the circle of centre m = o_a + k d, k = (|d|^2 + r_a^2 - r_b^2) / (2 |d|^2), axis d / |d| and radius
rho, rho^2 = r_a^2 - k^2 |d|^2; a plane at signed distance delta = (o - c) . n / |n| from a sphere's centre c cuts
it in the circle of centre c + delta n / |n|, axis n / |n| and rho^2 = r^2 - delta^2. rho^2 > 0 proven: one
circle, crossed transversally; rho^2 < 0 proven: no common point.

The distance bound chooses, of the true circle's parametrisations m + rho (e1 cos t + e2 sin t), the one nearest
the returned curve's: e1 along P minus its component along the axis, e2 = axis x e1 turned to Q's side. Then
|X(t) - true(t)| <= |c - m| + |P - rho e1| + |Q - rho e2| at every t: every point of the returned curve lies within
that of the true circle, and every point of the true circle within it of the returned curve (a Hausdorff bound for
the whole dense output, not only its stored points). The returned curve's own evaluation in floating point (its
cosine, sine and sums) adds at most EVAL_ULPS ulps of |c| + |P| + |Q|.

References
----------
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, ch. 5-6 (interval
arithmetic with outward rounding).
"""
import math

from ..._lib.jit import jit
from ..geometry.interval import EPS, down, iadd, imul, isqr, iscale, isub, mag, point, up

#: The outcomes: a circle proven, no common point proven, neither.
CIRCLE, EMPTY, UNDECIDED = 0, 1, 2
#: Ulps of |c| + |P| + |Q| allowed for the floating-point evaluation of a returned point.
EVAL_ULPS = 8.0


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
def _dot(a0, a1, a2, b0, b1, b2):
    return iadd(iadd(imul(a0, b0), imul(a1, b1)), imul(a2, b2))


@jit
def _norm_up(x0, x1, x2):
    """An upper bound of the length of any vector in the interval vector (x0, x1, x2)."""
    return up(math.sqrt(up(up(mag(x0) ** 2 + mag(x1) ** 2) + mag(x2) ** 2)))


@jit
def spheres(oa, ra, ob, rb, out):
    """The circle of two spheres (centres oa, ob (3,), radii ra, rb): CIRCLE with out (7, 2) = the intervals of its
    centre (rows 0-2), unit axis (3-5) and radius (6); EMPTY; or UNDECIDED (concentric, or rho^2 holding 0)."""
    d0 = isub(point(ob[0]), point(oa[0]))
    d1 = isub(point(ob[1]), point(oa[1]))
    d2 = isub(point(ob[2]), point(oa[2]))
    dd = iadd(iadd(isqr(d0), isqr(d1)), isqr(d2))
    if dd[0] <= 0.0:
        return UNDECIDED
    ra2, rb2 = isqr(point(ra)), isqr(point(rb))
    num = isub(iadd(dd, ra2), rb2)
    k = _idiv(num, iscale(dd, 2.0))
    rho2 = isub(ra2, imul(isqr(k), dd))
    if rho2[1] < 0.0:
        return EMPTY
    if rho2[0] <= 0.0:
        return UNDECIDED
    length = _isqrt(dd)
    for i, di in enumerate((d0, d1, d2)):
        out[i, 0], out[i, 1] = iadd(point(oa[i]), imul(k, di))
        out[3 + i, 0], out[3 + i, 1] = _idiv(di, length)
    out[6, 0], out[6, 1] = _isqrt(rho2)
    return CIRCLE


@jit
def plane_sphere(o, n, c, r, out):
    """The circle of the plane through o with normal n (3,) and the sphere of centre c (3,) and radius r: as
    spheres."""
    nn = iadd(iadd(isqr(point(n[0])), isqr(point(n[1]))), isqr(point(n[2])))
    if nn[0] <= 0.0:
        return UNDECIDED
    length = _isqrt(nn)
    g = _dot(isub(point(o[0]), point(c[0])), isub(point(o[1]), point(c[1])), isub(point(o[2]), point(c[2])),
             point(n[0]), point(n[1]), point(n[2]))
    delta = _idiv(g, length)                                   # signed distance of the plane from c along n
    rho2 = isub(isqr(point(r)), isqr(delta))
    if rho2[1] < 0.0:
        return EMPTY
    if rho2[0] <= 0.0:
        return UNDECIDED
    for i in range(3):
        axis = _idiv(point(n[i]), length)
        out[3 + i, 0], out[3 + i, 1] = axis
        out[i, 0], out[i, 1] = iadd(point(c[i]), imul(delta, axis))
    out[6, 0], out[6, 1] = _isqrt(rho2)
    return CIRCLE


@jit
def within_rectangle(circle, o, e1, e2, u0, u1, v0, v1):
    """True when the circle (7, 2) lies strictly inside the rectangle u0 < (x - o) . e1 < u1, v0 < (x - o) . e2
    < v1 (e1, e2 (3,) a plane's first two frame columns): along e, the circle spans (m - o) . e +- rho |e|."""
    rho = (circle[6, 0], circle[6, 1])
    for e, lo, hi in ((e1, u0, u1), (e2, v0, v1)):
        at = _dot(isub((circle[0, 0], circle[0, 1]), point(o[0])), isub((circle[1, 0], circle[1, 1]), point(o[1])),
                  isub((circle[2, 0], circle[2, 1]), point(o[2])), point(e[0]), point(e[1]), point(e[2]))
        reach = imul(rho, _isqrt(iadd(iadd(isqr(point(e[0])), isqr(point(e[1]))), isqr(point(e[2])))))
        if not (lo < down(at[0] - reach[1]) and up(at[1] + reach[1]) < hi):
            return False
    return True


@jit
def distance_bound(circle, c, P, Q):
    """An upper bound of sup_t |X(t) - true(t)| for the returned X(t) = c + P cos t + Q sin t (c, P, Q (3,)) and
    the true circle (7, 2) parametrised as in the module docstring, with the evaluation's round-off; inf when P
    lies along the axis (no parametrisation to compare with)."""
    m = [(circle[i, 0], circle[i, 1]) for i in range(3)]
    a = [(circle[3 + i, 0], circle[3 + i, 1]) for i in range(3)]
    rho = (circle[6, 0], circle[6, 1])
    # e1: P minus its component along the axis, normalised
    along = _dot(point(P[0]), point(P[1]), point(P[2]), a[0], a[1], a[2])
    u = [isub(point(P[i]), imul(along, a[i])) for i in range(3)]
    uu = iadd(iadd(isqr(u[0]), isqr(u[1])), isqr(u[2]))
    if uu[0] <= 0.0:
        return math.inf
    ul = _isqrt(uu)
    e1 = [_idiv(u[i], ul) for i in range(3)]
    # e2 = axis x e1, turned to Q's side
    e2 = [isub(imul(a[1], e1[2]), imul(a[2], e1[1])), isub(imul(a[2], e1[0]), imul(a[0], e1[2])),
          isub(imul(a[0], e1[1]), imul(a[1], e1[0]))]
    side = _dot(e2[0], e2[1], e2[2], point(Q[0]), point(Q[1]), point(Q[2]))
    if side[0] <= 0.0 <= side[1]:
        return math.inf
    sign = 1.0 if side[0] > 0.0 else -1.0
    dc = [isub(point(c[i]), m[i]) for i in range(3)]
    dp = [isub(point(P[i]), imul(rho, e1[i])) for i in range(3)]
    dq = [isub(point(Q[i]), iscale(imul(rho, e2[i]), sign)) for i in range(3)]
    bound = up(up(_norm_up(dc[0], dc[1], dc[2]) + _norm_up(dp[0], dp[1], dp[2])) + _norm_up(dq[0], dq[1], dq[2]))
    size = (math.sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) + math.sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2])
            + math.sqrt(Q[0] * Q[0] + Q[1] * Q[1] + Q[2] * Q[2]))
    return up(bound + up(EVAL_ULPS * EPS * size))
