"""Ellipses and segments proven in closed form: a plane meets a sphere, a cylinder or a cone, and two spheres meet
(their radical plane meets either), in exactly one ellipse or circle (or in nothing), and two trimmed planes in one
segment (or nothing), enclosed in outward-rounded intervals; a returned curve X(t) = c + P cos t + Q sin t (a circle
or an ellipse in closed form), or a returned segment, is proven within a distance of it (plane_plane and
segment_bound: the segment's ends enclosed, the distance between two segments paired end to end at most the larger
of their ends' distances).

The surfaces are the sets the floats define: a plane (x - p) . n = 0 (n its frame's third column as stored), and the
quadrics (x - o)^T (I - g a a^T) (x - o) = k, a the unit axis (the frame's third column normalised): a sphere
(g = 0, k = r^2), a cylinder (g = 1, k = r^2), a double cone (g = 1 + tan^2, k = 0, tan its stored tangent of the
half angle). Two spheres meet where their radical plane, through m = o_a + k d with k = (|d|^2 + r_a^2 - r_b^2) /
(2 |d|^2) and normal d = o_b - o_a, meets either.

On the plane, x = p + u f1 + v f2 (f1, f2 an orthonormal basis normal to n), the quadric is the conic
z^T A2 z + 2 b . z + c0 = 0, z = (u, v), A2_ij = f_i^T G f_j, b_i = f_i^T G (p - o), c0 = (p - o)^T G (p - o) - k.
A2 definite and c1 = c0 + b . z0 of the opposite sign at the centre z0 = -A2^-1 b: one ellipse,
(z - z0)^T A (z - z0) = 1 with A = A2 / (-c1), a nonsingular conic (the plane crosses the quadric transversally all
along it); c1 of A2's sign: no common point. ``truth`` (12, 2) holds the intervals of the ellipse's centre in space
(rows 0-2), f1 (3-5), f2 (6-8) and A11, A12, A22 (9-11).

The distance bound takes, of the true ellipse's parametrisations by conjugate semi-diameters, the one nearest the
returned curve's: P' the point of the true ellipse along P's projection on the plane, Q' its conjugate on Q's side
(Q' along A P' turned a quarter, so that P'^T A Q' = 0 and X'(t) = z0 + P' cos t + Q' sin t runs on the ellipse).
Then |X(t) - X'(t)| <= |c - z0| + |P - P'| + |Q - Q'| at every t: every point of the returned curve lies within
that of the true ellipse and every point of the true ellipse within it of the returned curve (a Hausdorff bound
for the whole dense output, not only its stored points). The returned curve's own evaluation in floating point (its
cosine, sine and sums) adds at most EVAL_ULPS ulps of |c| + |P| + |Q|.

References
----------
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, ch. 5-6 (interval
arithmetic with outward rounding).
"""
import math

from ..._lib.jit import jit
from ..geometry.interval import (EPS, contains_zero, down, iadd, idiv, idot, imul, isqr, iscale, isqrt, isub, mag,
                                 point, up)

#: The outcomes: a curve proven, no common point proven, neither.
CURVE, EMPTY, UNDECIDED = 0, 1, 2
#: Ulps of |c| + |P| + |Q| allowed for the floating-point evaluation of a returned point.
EVAL_ULPS = 8.0
#: Rows of a truth (12, 2).
Z0, F1, F2, A11, A12, A22 = 0, 3, 6, 9, 10, 11
ROWS = 12


@jit
def _row(truth, i):
    return (truth[i, 0], truth[i, 1])


@jit
def _set(truth, i, x):
    truth[i, 0], truth[i, 1] = x


@jit
def _vec(truth, row):
    return (_row(truth, row), _row(truth, row + 1), _row(truth, row + 2))


@jit
def _floats(v):
    return (point(v[0]), point(v[1]), point(v[2]))


@jit
def _sub(x, y):
    return (isub(x[0], y[0]), isub(x[1], y[1]), isub(x[2], y[2]))


@jit
def _axpy(s, x, y):
    """s x + y for an interval s and interval 3-vectors."""
    return (iadd(imul(s, x[0]), y[0]), iadd(imul(s, x[1]), y[1]), iadd(imul(s, x[2]), y[2]))


@jit
def _cross(x, y):
    return (isub(imul(x[1], y[2]), imul(x[2], y[1])), isub(imul(x[2], y[0]), imul(x[0], y[2])),
            isub(imul(x[0], y[1]), imul(x[1], y[0])))


@jit
def _unit(v):
    """(v / |v|, True), or (v, False) when |v| may be 0."""
    vv = idot(v, v)
    if vv[0] <= 0.0:
        return v, False
    length = isqrt(vv)
    return (idiv(v[0], length), idiv(v[1], length), idiv(v[2], length)), True


@jit
def _norm_up(v):
    """An upper bound of the length of any vector in the interval vector v."""
    return up(math.sqrt(up(up(mag(v[0]) ** 2 + mag(v[1]) ** 2) + mag(v[2]) ** 2)))


@jit
def _form(a, g, x, y):
    """x^T (I - g a a^T) y for interval 3-vectors (a unit)."""
    return isub(idot(x, y), imul(g, imul(idot(a, x), idot(a, y))))


@jit
def _plane_quadric(p, n, o, a, g, k, truth):
    """The conic of the plane through p with normal n and the quadric (o, unit axis a, g, k) (interval vectors and
    intervals) into truth: CURVE, EMPTY or UNDECIDED (A2 not proven definite, c1 holding 0)."""
    nu, ok = _unit(n)
    if not ok:
        return UNDECIDED
    j = 0                                             # f1 = nu x e_j, e_j the axis least along n
    if abs(n[1][0] + n[1][1]) < abs(n[j][0] + n[j][1]):
        j = 1
    if abs(n[2][0] + n[2][1]) < abs(n[j][0] + n[j][1]):
        j = 2
    e = (point(1.0 if j == 0 else 0.0), point(1.0 if j == 1 else 0.0), point(1.0 if j == 2 else 0.0))
    f1, ok = _unit(_cross(nu, e))
    if not ok:
        return UNDECIDED
    f2 = _cross(nu, f1)
    d = _sub(p, o)
    a11, a12, a22 = _form(a, g, f1, f1), _form(a, g, f1, f2), _form(a, g, f2, f2)
    b1, b2 = _form(a, g, f1, d), _form(a, g, f2, d)
    c0 = isub(_form(a, g, d, d), k)
    det = isub(imul(a11, a22), isqr(a12))
    if det[0] <= 0.0 or contains_zero(a11):
        return UNDECIDED                              # not proven an ellipse (a hyperbola, a parabola, lines)
    z1 = idiv(isub(imul(a12, b2), imul(a22, b1)), det)
    z2 = idiv(isub(imul(a12, b1), imul(a11, b2)), det)
    c1 = iadd(c0, iadd(imul(b1, z1), imul(b2, z2)))
    if contains_zero(c1):
        return UNDECIDED
    if (c1[0] > 0.0) == (a11[0] > 0.0):
        return EMPTY
    minus = (-c1[1], -c1[0])
    centre = _axpy(z2, f2, _axpy(z1, f1, p))
    for i in range(3):
        _set(truth, Z0 + i, centre[i])
        _set(truth, F1 + i, f1[i])
        _set(truth, F2 + i, f2[i])
    _set(truth, A11, idiv(a11, minus))
    _set(truth, A12, idiv(a12, minus))
    _set(truth, A22, idiv(a22, minus))
    return CURVE


@jit
def plane_quadric(p, n, o, axis, g, radius, truth):
    """The ellipse of the plane through p with normal n (3,) and the sphere (g = 0) or cylinder (g = 1) through o
    (3,) about axis (3,) of the given radius (k = radius^2, enclosed)."""
    a, ok = _unit(_floats(axis))
    if not ok:
        return UNDECIDED
    return _plane_quadric(_floats(p), _floats(n), _floats(o), a, point(g), isqr(point(radius)), truth)


@jit
def cone_quadric(p, n, o, axis, tangent, truth):
    """plane_quadric for the double cone of apex o, axis and tangent of the half angle: g = 1 + tangent^2
    enclosed."""
    a, ok = _unit(_floats(axis))
    if not ok:
        return UNDECIDED
    g = iadd(point(1.0), isqr(point(tangent)))
    return _plane_quadric(_floats(p), _floats(n), _floats(o), a, g, point(0.0), truth)


@jit
def spheres(oa, ra, ob, rb, truth):
    """The circle of two spheres (centres oa, ob (3,), radii ra, rb): the radical plane's with the first (CURVE,
    EMPTY or UNDECIDED, also when concentric)."""
    d = _sub(_floats(ob), _floats(oa))
    dd = idot(d, d)
    if dd[0] <= 0.0:
        return UNDECIDED
    ra2 = isqr(point(ra))
    k = idiv(isub(iadd(dd, ra2), isqr(point(rb))), iscale(dd, 2.0))
    m = _axpy(k, d, _floats(oa))
    return _plane_quadric(m, d, _floats(oa), (point(0.0), point(0.0), point(1.0)), point(0.0), ra2, truth)


@jit
def _inverse(truth):
    """(i11, i12, i22, True): A^-1; (.., False) when det A is not proven positive (no enclosure then)."""
    a11, a12, a22 = _row(truth, A11), _row(truth, A12), _row(truth, A22)
    det = isub(imul(a11, a22), isqr(a12))
    if det[0] <= 0.0:
        return a11, a12, a22, False
    return idiv(a22, det), idiv((-a12[1], -a12[0]), det), idiv(a11, det), True


@jit
def within_band(truth, o, e, lo, hi):
    """True when lo < (x - o) . e < hi at every point x of the true ellipse (e (3,) any vector: a plane's frame
    column, a cylinder's or cone's axis): (z0 - o) . e +- sqrt(h^T A^-1 h), h = (e . f1, e . f2)."""
    ev = _floats(e)
    h1, h2 = idot(ev, _vec(truth, F1)), idot(ev, _vec(truth, F2))
    i11, i12, i22, ok = _inverse(truth)
    if not ok:
        return False
    spread = iadd(iadd(imul(i11, isqr(h1)), iscale(imul(i12, imul(h1, h2)), 2.0)), imul(i22, isqr(h2)))
    reach = isqrt((max(spread[0], 0.0), spread[1]))
    at = idot(_sub(_vec(truth, Z0), _floats(o)), ev)
    return lo < down(at[0] - reach[1]) and up(at[1] + reach[1]) < hi


@jit
def _quad(truth, x1, x2):
    """x^T A x."""
    a11, a12, a22 = _row(truth, A11), _row(truth, A12), _row(truth, A22)
    return iadd(iadd(imul(a11, isqr(x1)), iscale(imul(a12, imul(x1, x2)), 2.0)), imul(a22, isqr(x2)))


@jit
def distance_bound(truth, c, P, Q):
    """An upper bound of sup_t |X(t) - X'(t)| for the returned X(t) = c + P cos t + Q sin t (c, P, Q (3,)) and the
    true ellipse's X'(t) (module docstring), with the evaluation's round-off; inf when P's projection on the plane
    may vanish or Q's side is not decided."""
    f1, f2 = _vec(truth, F1), _vec(truth, F2)
    Pv, Qv = _floats(P), _floats(Q)
    p1, p2 = idot(f1, Pv), idot(f2, Pv)
    lam2 = _quad(truth, p1, p2)
    if lam2[0] <= 0.0:
        return math.inf
    lam = isqrt(lam2)
    u1, u2 = idiv(p1, lam), idiv(p2, lam)              # P' on the true ellipse
    ap1 = iadd(imul(_row(truth, A11), u1), imul(_row(truth, A12), u2))
    ap2 = iadd(imul(_row(truth, A12), u1), imul(_row(truth, A22), u2))
    d1, d2 = (-ap2[1], -ap2[0]), ap1                     # A P' turned a quarter: conjugate to P'
    mu2 = _quad(truth, d1, d2)
    if mu2[0] <= 0.0:
        return math.inf
    side = iadd(imul(d1, idot(f1, Qv)), imul(d2, idot(f2, Qv)))
    if contains_zero(side):
        return math.inf
    mu = isqrt(mu2)
    if side[1] < 0.0:
        mu = (-mu[1], -mu[0])
    w1, w2 = idiv(d1, mu), idiv(d2, mu)                # Q' on Q's side
    p_true = _axpy(u2, f2, _axpy(u1, f1, (point(0.0), point(0.0), point(0.0))))
    q_true = _axpy(w2, f2, _axpy(w1, f1, (point(0.0), point(0.0), point(0.0))))
    bound = up(up(_norm_up(_sub(_floats(c), _vec(truth, Z0))) + _norm_up(_sub(Pv, p_true)))
               + _norm_up(_sub(Qv, q_true)))
    size = (math.sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) + math.sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2])
            + math.sqrt(Q[0] * Q[0] + Q[1] * Q[1] + Q[2] * Q[2]))
    return up(bound + up(EVAL_ULPS * EPS * size))


@jit
def semi_minor_squared(truth):
    """A lower bound of the true ellipse's smaller semi-axis squared, 1 / (the largest eigenvalue of A)."""
    a11, a12, a22 = _row(truth, A11), _row(truth, A12), _row(truth, A22)
    trace = iadd(a11, a22)
    det = isub(imul(a11, a22), isqr(a12))
    disc = isub(isqr(trace), iscale(det, 4.0))
    top = iscale(iadd(trace, isqrt((max(disc[0], 0.0), disc[1]))), 0.5)
    return down(1.0 / top[1])


@jit
def plane_plane(o1, n1, o2, n2, bands, ends):
    """The segment where the planes through o1, o2 with normals n1, n2 (3,) meet inside the bands (K, 8) (rows
    (o (3), e (3), lo, hi): lo < (x - o) . e < hi, the planes' trims): its ends into ends (6, 2) (intervals of A,
    rows 0-2, and B, rows 3-5; A first along n1 x n2); CURVE, EMPTY (the line misses the bands' common part) or
    UNDECIDED (the planes parallel to round-off, a band along the line, an end not decided).

    The line is p0 + t d, d = n1 x n2, p0 = ((h1 |n2|^2 - h2 n1.n2) n1 + (h2 |n1|^2 - h1 n1.n2) n2) / |d|^2 with
    h_i = n_i . o_i; a band holds it for t between (lo - a) / b and (hi - a) / b, a = e . (p0 - o), b = e . d; the
    segment runs from the largest of the lower ends to the smallest of the upper ones."""
    a1, a2 = _floats(n1), _floats(n2)
    d = _cross(a1, a2)
    dd = idot(d, d)
    if dd[0] <= 0.0:
        return UNDECIDED
    h1, h2 = idot(a1, _floats(o1)), idot(a2, _floats(o2))
    n11, n22, n12 = idot(a1, a1), idot(a2, a2), idot(a1, a2)
    k1 = idiv(isub(imul(h1, n22), imul(h2, n12)), dd)
    k2 = idiv(isub(imul(h2, n11), imul(h1, n12)), dd)
    p0 = _axpy(k2, a2, _axpy(k1, a1, (point(0.0), point(0.0), point(0.0))))
    t_lo, t_hi = (-math.inf, -math.inf), (math.inf, math.inf)
    for k in range(bands.shape[0]):
        o, e = (point(bands[k, 0]), point(bands[k, 1]), point(bands[k, 2])), _floats(bands[k, 3:6])
        a = idot(_sub(p0, o), e)
        b = idot(d, e)
        if contains_zero(b):
            return UNDECIDED
        first = idiv(isub(point(bands[k, 6]), a), b) if math.isfinite(bands[k, 6]) else (-math.inf, math.inf)
        last = idiv(isub(point(bands[k, 7]), a), b) if math.isfinite(bands[k, 7]) else (-math.inf, math.inf)
        if b[0] > 0.0:
            lower, upper = ((-math.inf, -math.inf) if not math.isfinite(bands[k, 6]) else first,
                            (math.inf, math.inf) if not math.isfinite(bands[k, 7]) else last)
        else:
            lower, upper = ((-math.inf, -math.inf) if not math.isfinite(bands[k, 7]) else last,
                            (math.inf, math.inf) if not math.isfinite(bands[k, 6]) else first)
        t_lo = (max(t_lo[0], lower[0]), max(t_lo[1], lower[1]))
        t_hi = (min(t_hi[0], upper[0]), min(t_hi[1], upper[1]))
    if not (math.isfinite(t_lo[0]) and math.isfinite(t_hi[1])):
        return UNDECIDED
    if t_lo[0] > t_hi[1]:
        return EMPTY
    if not t_lo[1] < t_hi[0]:
        return UNDECIDED
    A, B = _axpy(t_lo, d, p0), _axpy(t_hi, d, p0)
    for i in range(3):
        _set(ends, i, A[i])
        _set(ends, 3 + i, B[i])
    return CURVE


@jit
def segment_bound(ends, a, b):
    """An upper bound of sup_tau |X(tau) - X'(tau)| for the returned segment X from a to b (3,) and the true one X'
    between the ends (6, 2), paired with a and b the nearer way (both affine in tau: the larger end distance),
    with the evaluation's round-off."""
    A, B = _vec(ends, 0), _vec(ends, 3)
    av, bv = _floats(a), _floats(b)
    straight = max(_norm_up(_sub(av, A)), _norm_up(_sub(bv, B)))
    crossed = max(_norm_up(_sub(av, B)), _norm_up(_sub(bv, A)))
    size = math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) + math.sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2])
    return up(min(straight, crossed) + up(EVAL_ULPS * EPS * size))
