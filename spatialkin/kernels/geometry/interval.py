"""Interval arithmetic with outward rounding, and interval jets of g = F_T(S(u, v)) over parameter boxes.

An interval is a 2-tuple (lo, hi) of floats. Every operation rounds outward: the exact result of the operation
on any reals in its arguments lies in the returned interval. numba exposes no rounding modes, so each bound is
moved one ulp outward after the round-to-nearest operation (its error is at most half an ulp); sin and cos
(within one ulp in glibc) are widened by two.

S is a surface given by its packed data (spatialkin.kernels.geometry.surfaces; the branches below are by its geometry
code), T another one read through a
polynomial implicit function F_T in T's local coordinates (smooth everywhere, unlike a signed distance):

    PLANE     z
    SPHERE    x^2 + y^2 + z^2 - R^2
    CYLINDER  x^2 + y^2 - r^2
    CONE      x^2 + y^2 - tan(a)^2 z^2            (the double cone)
    TORUS     (|q|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2)   (both parts of a horn or spindle torus)

A point of S in T's local coordinates is q = M s(u, v) + c, with s the local point of S, M = R_T^T R_S and
c = R_T^T (o_S - o_T) (``relative_placement``); their own rounding is covered by a pad added to every q.
``jet`` returns enclosures of g, g_u, g_v, g_uu, g_uv, g_vv over a box; a box of zero width gives a
rigorous enclosure of the values at a point. The searches take it in stages, each to the bit what ``jet`` gives:
``level`` (g alone), ``jet_first`` (g and its gradient) and ``jet_second`` (the second derivatives, only for the
boxes whose first-order tests leave them in doubt).

The jets' helpers are compiled with ``forceinline`` (LLVM's alwaysinline) into the kernels that call them: their
tuples of intervals then stay in registers rather than pass through memory at every call, and the parts a caller
does not read are dropped, which speeds up spatialkin.kernels.search.topology's searches (floating-point operations are
not reordered or fused, so their results are the same bits).

References
----------
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009 (outward rounding,
natural and centred forms).
"""
import math


from ..._lib.jit import jit
from .surfaces import CONE, CYLINDER, GEOMETRY, ORIGIN, P0, P1, PLANE, ROT, SPHERE, TORUS

#: Unit round-off of float64 (one ulp of 1.0).
EPS = 2.220446049250313e-16
#: Absolute pad of every outward rounding: covers a result's round-off below the normal range (at most 2^-1075,
#: half the smallest subnormal; any larger pad is as rigorous). Not the smallest subnormal itself: an exact zero
#: (a cylinder's zero cone slope, a zero component of a tangent) padded by it turns into subnormal bounds, and
#: every operation on a subnormal costs a microcode assist on Intel CPUs (about 100 cycles): the searches of the
#: pairs with a cylinder or a cone as the parametrised surface would run several times slower for it. Nor the
#: smallest normal number: its products with numbers below 1 are subnormal again. A pad of 1e-250 keeps such
#: products normal and lies far below any g the searches read (a torus's quartic at scale 1e-30 is about 1e-120):
#: over the stress cases every box decision is the one the pad 2^-1075 gives.
TINY = 1e-250
#: ulps by which sin and cos results are widened (glibc's are within one ulp).
TRIG_ULPS = 2.0
#: Relative pad on the transformed point q for the rounding of M and c: each entry of M is a sum of three
#: products of entries at most 1 (error below 3 ulps), c a rotated difference of origins (likewise).
PLACEMENT_ULPS = 4.0
TWO_PI = 2.0 * math.pi
HALF_PI = 0.5 * math.pi
#: |HALF_PI - pi/2| is below 1e-16 (pi/2 rounded to a double); twice that covers the subtraction too.
HALF_PI_ERROR = 2e-16


@jit
def down(x):
    return x - (abs(x) * EPS + TINY)


@jit
def up(x):
    return x + (abs(x) * EPS + TINY)


@jit
def point(x):
    return (x, x)


@jit
def iadd(a, b):
    return (down(a[0] + b[0]), up(a[1] + b[1]))


@jit
def isub(a, b):
    return (down(a[0] - b[1]), up(a[1] - b[0]))


@jit
def ineg(a):
    return (-a[1], -a[0])


@jit
def imul(a, b):
    p1 = a[0] * b[0]
    p2 = a[0] * b[1]
    p3 = a[1] * b[0]
    p4 = a[1] * b[1]
    return (down(min(min(p1, p2), min(p3, p4))), up(max(max(p1, p2), max(p3, p4))))


@jit
def isqr(a):
    if a[0] >= 0.0:
        return (down(a[0] * a[0]), up(a[1] * a[1]))
    if a[1] <= 0.0:
        return (down(a[1] * a[1]), up(a[0] * a[0]))
    return (0.0, up(max(a[0] * a[0], a[1] * a[1])))


@jit
def iscale(a, c):
    """c * a for a float c."""
    if c >= 0.0:
        return (down(c * a[0]), up(c * a[1]))
    return (down(c * a[1]), up(c * a[0]))


@jit
def ishift(a, c):
    """a + c for a float c."""
    return (down(a[0] + c), up(a[1] + c))


@jit
def widen(a, r):
    """a widened by r >= 0 on both sides."""
    return (down(a[0] - r), up(a[1] + r))


@jit
def idiv(a, b):
    """a / b for an interval b that does not hold 0."""
    q1, q2, q3, q4 = a[0] / b[0], a[0] / b[1], a[1] / b[0], a[1] / b[1]
    return (down(min(min(q1, q2), min(q3, q4))), up(max(max(q1, q2), max(q3, q4))))


@jit
def isqrt(a):
    """sqrt of an interval with a[0] >= 0."""
    return (max(down(math.sqrt(a[0])), 0.0), up(math.sqrt(a[1])))


@jit
def contains_zero(a):
    return a[0] <= 0.0 <= a[1]


@jit
def mag(a):
    """max |x| over a."""
    return max(abs(a[0]), abs(a[1]))


@jit
def intersect(a, b):
    """a ∩ b; lo > hi when empty."""
    return (max(a[0], b[0]), min(a[1], b[1]))


@jit(forceinline=True)
def _has_multiple(lo, hi, offset):
    """True if some offset + 2 k pi lies in [lo, hi] (conservatively: also when within round-off of it)."""
    slack = 4.0 * EPS * (abs(lo) + abs(hi) + 1.0)
    k = math.ceil((lo - offset - slack) / TWO_PI)
    return offset + k * TWO_PI <= hi + slack


@jit(forceinline=True)
def icos(a):
    lo, hi = a
    if hi - lo >= TWO_PI:
        return (-1.0, 1.0)
    c0 = math.cos(lo)
    c1 = c0 if hi == lo else math.cos(hi)       # (a point: one evaluation)
    r0 = min(c0, c1)
    r1 = max(c0, c1)
    r0 -= TRIG_ULPS * EPS * abs(r0) + TINY
    r1 += TRIG_ULPS * EPS * abs(r1) + TINY
    if _has_multiple(lo, hi, 0.0):
        r1 = 1.0
    if _has_multiple(lo, hi, math.pi):
        r0 = -1.0
    return (max(r0, -1.0), min(r1, 1.0))


@jit(forceinline=True)
def isin(a):
    """sin over a as cos over a - pi/2 (the float pi/2 is within 1e-16 of the true one, and cos is
    1-Lipschitz: the shifted interval is widened by that)."""
    return icos(widen((a[0] - HALF_PI, a[1] - HALF_PI), HALF_PI_ERROR))


ZERO = (0.0, 0.0)


@jit(forceinline=True)
def u_trig(data, U):
    """(cos, sin) enclosures over U, as local_first reads them (zeros for a plane, which reads none)."""
    if int(data[GEOMETRY]) == PLANE:
        return ZERO, ZERO
    return icos(U), isin(U)


@jit(forceinline=True)
def v_trig(data, V):
    """(cos, sin) enclosures over V, as local_first reads them (zeros but for a sphere or a torus)."""
    geometry = int(data[GEOMETRY])
    if geometry == SPHERE or geometry == TORUS:
        return icos(V), isin(V)
    return ZERO, ZERO


@jit(forceinline=True)
def box_trig(data, U, V):
    """(cos U, sin U, cos V, sin V): the enclosures local_first reads over the box U x V (u_trig, v_trig)."""
    cu, su = u_trig(data, U)
    cv, sv = v_trig(data, V)
    return cu, su, cv, sv


@jit(forceinline=True)
def local_first(data, U, V, trig):
    """Interval local point and first derivatives of S over the box U x V: (s, s_u, s_v, parts), each of s, s_u,
    s_v a 3-tuple of intervals, parts (6 intervals) what local_second reads (its products of sines and cosines);
    trig is box_trig of the box (a search hands a box the half its parent shares with it)."""
    geometry = int(data[GEOMETRY])
    z = (0.0, 0.0)
    one = (1.0, 1.0)
    if geometry == PLANE:
        return (U, V, z), (one, z, z), (z, one, z), (z, z, z, z, z, z)
    cu, su, cv, sv = trig
    if geometry == SPHERE or geometry == TORUS:
        big = 0.0 if geometry == SPHERE else data[P0]
        small = data[P0] if geometry == SPHERE else data[P1]
        w = ishift(iscale(cv, small), big)
        ssv = iscale(sv, small)
        scv = iscale(cv, small)
        wcu = imul(w, cu)
        wsu = imul(w, su)
        return ((wcu, wsu, ssv), (ineg(wsu), wcu, z), (ineg(imul(ssv, cu)), ineg(imul(ssv, su)), scv),
                (wcu, wsu, ssv, scv, cu, su))
    b = data[P1]
    rho = ishift(iscale(V, b), data[P0])
    rcu = imul(rho, cu)
    rsu = imul(rho, su)
    bcu = iscale(cu, b)
    bsu = iscale(su, b)
    return (rcu, rsu, V), (ineg(rsu), rcu, z), (bcu, bsu, one), (rcu, rsu, bcu, bsu, z, z)


@jit(forceinline=True)
def local_second(data, parts):
    """Interval second derivatives (s_uu, s_uv, s_vv) of S over the box whose local_first gave parts."""
    geometry = int(data[GEOMETRY])
    z = (0.0, 0.0)
    zero3 = (z, z, z)
    if geometry == PLANE:
        return zero3, zero3, zero3
    if geometry == SPHERE or geometry == TORUS:
        wcu, wsu, ssv, scv, cu, su = parts
        return ((ineg(wcu), ineg(wsu), z), (imul(ssv, su), ineg(imul(ssv, cu)), z),
                (ineg(imul(scv, cu)), ineg(imul(scv, su)), ineg(ssv)))
    rcu, rsu, bcu, bsu, _, _ = parts
    return (ineg(rcu), ineg(rsu), z), (ineg(bsu), bcu, z), zero3


@jit
def relative_placement(s_data, t_data, m, c):
    """M = R_T^T R_S (3, 3) and c = R_T^T (o_S - o_T) (3,) into m and c; returns the pad scale (the magnitude of
    the translation, for the rounding pad of q)."""
    for i in range(3):
        for j in range(3):
            acc = 0.0
            for k in range(3):
                acc += t_data[ROT + 3 * k + i] * s_data[ROT + 3 * k + j]
            m[i, j] = acc
    mag_o = 0.0
    for i in range(3):
        acc = 0.0
        for k in range(3):
            d = s_data[ORIGIN + k] - t_data[ORIGIN + k]
            acc += t_data[ROT + 3 * k + i] * d
            mag_o += abs(s_data[ORIGIN + k]) + abs(t_data[ORIGIN + k])
        c[i] = acc
    return mag_o


@jit
def _apply(m, x, i):
    """Row i of M times the interval 3-vector x."""
    acc = iscale(x[0], m[i, 0])
    acc = iadd(acc, iscale(x[1], m[i, 1]))
    return iadd(acc, iscale(x[2], m[i, 2]))


@jit(forceinline=True)
def transform(m, x, pad):
    """M x (a vector: no translation), each component widened by pad * (|x|_1 + 1e-300)."""
    size = mag(x[0]) + mag(x[1]) + mag(x[2])
    r = pad * size
    return (widen(_apply(m, x, 0), r), widen(_apply(m, x, 1), r), widen(_apply(m, x, 2), r))


@jit
def idot(a, b):
    return iadd(iadd(imul(a[0], b[0]), imul(a[1], b[1])), imul(a[2], b[2]))


@jit(forceinline=True)
def krawczyk_row(y0, y1, m_i, gm, phim, gu, gv, j10, j11, dU, dV, i):
    """Row i of the Krawczyk operator of a 2 x 2 system Phi = (g, phi): m_i - (Y Phi(m))_i + sum_j (delta_ij -
    (Y J)_ij) (X_j - m_j), with (y0, y1) row i of the float preconditioner Y, (gm, phim) Phi's enclosures at the
    midpoint m, J = ((gu, gv), (j10, j11)) the Jacobian's over the box X, dU, dV = X - m."""
    yphi = iadd(iscale(gm, y0), iscale(phim, y1))
    a0 = iadd(iscale(gu, y0), iscale(j10, y1))        # (Y J)_i0
    a1 = iadd(iscale(gv, y0), iscale(j11, y1))        # (Y J)_i1
    if i == 0:
        a0 = isub((1.0, 1.0), a0)
        a1 = isub((0.0, 0.0), a1)
    else:
        a0 = isub((0.0, 0.0), a0)
        a1 = isub((1.0, 1.0), a1)
    return iadd(isub(point(m_i), yphi), iadd(imul(a0, dU), imul(a1, dV)))


@jit(forceinline=True)
def _square(x):
    """x^2 of a float constant, as an interval (its rounding enclosed)."""
    return isqr((x, x))


@jit(forceinline=True)
def implicit_jet(t_data, q):
    """(F, grad F (3 intervals), s) of T's polynomial implicit function at the interval local point q; s is the
    torus's |q|^2 + R^2 - r^2 (unused otherwise). The constants (R^2, r^2, tan^2) are enclosed too."""
    geometry = int(t_data[GEOMETRY])
    z = (0.0, 0.0)
    if geometry == PLANE:
        return q[2], (z, z, (1.0, 1.0)), z
    x2 = isqr(q[0])
    y2 = isqr(q[1])
    z2 = isqr(q[2])
    rho2 = iadd(x2, y2)
    if geometry == SPHERE:
        f = isub(iadd(rho2, z2), _square(t_data[P0]))
        return f, (iscale(q[0], 2.0), iscale(q[1], 2.0), iscale(q[2], 2.0)), z
    if geometry == CYLINDER:
        return isub(rho2, _square(t_data[P0])), (iscale(q[0], 2.0), iscale(q[1], 2.0), z), z
    if geometry == CONE:
        t2 = _square(t_data[P1])
        return (isub(rho2, imul(z2, t2)), (iscale(q[0], 2.0), iscale(q[1], 2.0), imul(q[2], iscale(t2, -2.0))), z)
    big2 = _square(t_data[P0])
    s = iadd(iadd(rho2, z2), isub(big2, _square(t_data[P1])))
    f = isub(isqr(s), imul(rho2, iscale(big2, 4.0)))
    s4 = iscale(s, 4.0)
    b8 = iscale(big2, 8.0)
    g0 = isub(imul(s4, q[0]), imul(q[0], b8))
    g1 = isub(imul(s4, q[1]), imul(q[1], b8))
    return f, (g0, g1, imul(s4, q[2])), s


@jit(forceinline=True)
def hessian_form(t_data, q, s, a, b):
    """a^T H_F b over intervals, H_F the Hessian of T's implicit function at q."""
    geometry = int(t_data[GEOMETRY])
    if geometry == PLANE:
        return (0.0, 0.0)
    xy = iadd(imul(a[0], b[0]), imul(a[1], b[1]))
    if geometry == SPHERE:
        return iscale(iadd(xy, imul(a[2], b[2])), 2.0)
    if geometry == CYLINDER:
        return iscale(xy, 2.0)
    if geometry == CONE:
        return isub(iscale(xy, 2.0), imul(imul(a[2], b[2]), iscale(_square(t_data[P1]), 2.0)))
    full = iadd(xy, imul(a[2], b[2]))
    term = iadd(imul(iscale(s, 4.0), full), iscale(imul(idot(q, a), idot(q, b)), 8.0))
    return isub(term, imul(xy, iscale(_square(t_data[P0]), 8.0)))


@jit(forceinline=True)
def placed(m, c, x, pad, cpad):
    """The interval point q = M x + c in T's frame, padded for the rounding of M (pad) and of c (cpad)."""
    q0 = transform(m, x, pad)
    r = cpad + pad * (abs(c[0]) + abs(c[1]) + abs(c[2]))
    return (widen(ishift(q0[0], c[0]), r), widen(ishift(q0[1], c[1]), r), widen(ishift(q0[2], c[2]), r))


@jit(forceinline=True)
def level(s_data, t_data, m, c, pad, cpad, U, V):
    """Enclosure of g alone over the box U x V (the first entry of jet, to the bit)."""
    x = local_first(s_data, U, V, box_trig(s_data, U, V))[0]
    return implicit_jet(t_data, placed(m, c, x, pad, cpad))[0]


@jit(forceinline=True)
def jet_first(s_data, t_data, m, c, pad, cpad, U, V, trig):
    """((g, g_u, g_v), state): enclosures of g and its gradient over the box U x V (the first three entries of
    jet, to the bit; trig is box_trig of the box), and what jet_second reads to finish the jet."""
    x, xu, xv, parts = local_first(s_data, U, V, trig)
    q = placed(m, c, x, pad, cpad)
    qu = transform(m, xu, pad)
    qv = transform(m, xv, pad)
    f, grad, s = implicit_jet(t_data, q)
    return (f, idot(grad, qu), idot(grad, qv)), (parts, q, qu, qv, grad, s)


@jit(forceinline=True)
def jet_second(s_data, t_data, m, pad, state):
    """Enclosures (g_uu, g_uv, g_vv) over the box whose jet_first gave state (the last three entries of jet)."""
    parts, q, qu, qv, grad, s = state
    xuu, xuv, xvv = local_second(s_data, parts)
    quu = transform(m, xuu, pad)
    quv = transform(m, xuv, pad)
    qvv = transform(m, xvv, pad)
    guu = iadd(hessian_form(t_data, q, s, qu, qu), idot(grad, quu))
    guv = iadd(hessian_form(t_data, q, s, qu, qv), idot(grad, quv))
    gvv = iadd(hessian_form(t_data, q, s, qv, qv), idot(grad, qvv))
    return guu, guv, gvv


@jit
def jet(s_data, t_data, m, c, pad, cpad, U, V):
    """Enclosures (g, g_u, g_v, g_uu, g_uv, g_vv) of g = F_T(S(u, v)) over the box U x V (intervals); pad is the
    relative rounding pad of M, cpad the absolute one of c. The searches take it in two stages (jet_first, then
    jet_second only for the boxes that need the second derivatives)."""
    first, state = jet_first(s_data, t_data, m, c, pad, cpad, U, V, box_trig(s_data, U, V))
    guu, guv, gvv = jet_second(s_data, t_data, m, pad, state)
    return first[0], first[1], first[2], guu, guv, gvv
