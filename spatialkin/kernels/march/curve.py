"""Intersection-curve kernels: Dragilev's right-hand side, the pull-back, Newton corrections, event values.

State y = (u1, v1, u2, v2): parameters of the current point on surface a and on surface b. ' = d/ds, s the
arc length of the intersection curve.

References
----------
"Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines of the
light industry" (in Ukrainian; [Looper]): Dragilev's method, n = N1 x N2 / |N1 x N2| and the two Gram systems.
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002:
integrating the tangent alone drifts off the surfaces; the pull-back -lambda (M1 - M2) and Newton projection keep
the gap flat; a corrector in the plane normal to the tangent (pseudo-arclength).
"""
import math

import numpy as np

from ..._lib.jit import borrowed, jit, kept
from ..linalg import PIVOT_EPS, balance_columns, lu_factor, lu_solve, unbalance
from ..geometry.surfaces import frame, second

#: A Newton step longer than this fraction of the previous one has stopped contracting (round-off floor).
STAGNATION = 0.25


@jit
def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@jit
def norm(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


@jit
def cross3(a, b):
    """a x b as a 3-tuple (a, b: 3-tuples or arrays)."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@jit
def unit_tangent(su1, sv1, su2, sv2):
    """(t, sin): the unit tangent N1 x N2 / |N1 x N2| as a 3-tuple and sin of the angle between the normals
    (0, with t zero, where they are parallel)."""
    n1 = cross3(su1, sv1)
    n2 = cross3(su2, sv2)
    t = cross3(n1, n2)
    c = norm(t)
    scale = norm(n1) * norm(n2)
    if c == 0.0 or scale == 0.0:
        return (0.0, 0.0, 0.0), 0.0
    return (t[0] / c, t[1] / c, t[2] / c), c / scale


@jit
def gram(su, sv, w):
    """(du, dv, ok): the parameter velocity whose image su*du + sv*dv is the tangent-plane part of w, from
    [E F; F G] [du; dv] = [w.su; w.sv]; (0, 0, False) where the parametrisation is singular (EG - F^2 = 0)."""
    e = dot(su, su)
    f = dot(su, sv)
    g = dot(sv, sv)
    det = e * g - f * f
    if det <= PIVOT_EPS * (e * g):
        return 0.0, 0.0, False
    bu = dot(w, su)
    bv = dot(w, sv)
    return (g * bu - f * bv) / det, (e * bv - f * bu) / det, True


@jit
def tangent_from_normals(su1, sv1, su2, sv2, t):
    """Unit tangent t = N1 x N2 / |N1 x N2| of the intersection; returns sin of the angle between the
    normals (0 where they are parallel; t is then left as zeros)."""
    tt, c = unit_tangent(su1, sv1, su2, sv2)
    for i in range(3):
        t[i] = tt[i]
    return c


@jit(forceinline=True)
def min_norm_step(su1, sv1, su2, sv2, gap):
    """(step, ok): the minimum-norm Gauss-Newton step (4-tuple) in (u1, v1, u2, v2) that removes the gap
    M1 - M2 to first order, -J^T (J J^T)^-1 gap with J = [su1, sv1, -su2, -sv2], its columns first scaled to
    unit length (so that surfaces of very different sizes are weighed alike); ok False (step zero) where
    J J^T is singular (the two tangent planes coincide)."""
    zero = (0.0, 0.0, 0.0, 0.0)
    w0 = 1.0 / dot(su1, su1) if dot(su1, su1) > 0.0 else 0.0
    w1 = 1.0 / dot(sv1, sv1) if dot(sv1, sv1) > 0.0 else 0.0
    w2 = 1.0 / dot(su2, su2) if dot(su2, su2) > 0.0 else 0.0
    w3 = 1.0 / dot(sv2, sv2) if dot(sv2, sv2) > 0.0 else 0.0
    if w0 == 0.0 or w1 == 0.0 or w2 == 0.0 or w3 == 0.0:
        return zero, False
    m00 = w0 * su1[0] * su1[0] + w1 * sv1[0] * sv1[0] + w2 * su2[0] * su2[0] + w3 * sv2[0] * sv2[0]
    m11 = w0 * su1[1] * su1[1] + w1 * sv1[1] * sv1[1] + w2 * su2[1] * su2[1] + w3 * sv2[1] * sv2[1]
    m22 = w0 * su1[2] * su1[2] + w1 * sv1[2] * sv1[2] + w2 * su2[2] * su2[2] + w3 * sv2[2] * sv2[2]
    m01 = w0 * su1[0] * su1[1] + w1 * sv1[0] * sv1[1] + w2 * su2[0] * su2[1] + w3 * sv2[0] * sv2[1]
    m02 = w0 * su1[0] * su1[2] + w1 * sv1[0] * sv1[2] + w2 * su2[0] * su2[2] + w3 * sv2[0] * sv2[2]
    m12 = w0 * su1[1] * su1[2] + w1 * sv1[1] * sv1[2] + w2 * su2[1] * su2[2] + w3 * sv2[1] * sv2[2]
    # symmetric 3x3 by cofactors
    c00 = m11 * m22 - m12 * m12
    c01 = m12 * m02 - m01 * m22
    c02 = m01 * m12 - m11 * m02
    det = m00 * c00 + m01 * c01 + m02 * c02
    scale = abs(m00) + abs(m11) + abs(m22)
    if scale == 0.0 or abs(det) <= PIVOT_EPS * scale ** 3:
        return zero, False
    c11 = m00 * m22 - m02 * m02
    c12 = m01 * m02 - m00 * m12
    c22 = m00 * m11 - m01 * m01
    w = ((c00 * gap[0] + c01 * gap[1] + c02 * gap[2]) / det,
         (c01 * gap[0] + c11 * gap[1] + c12 * gap[2]) / det,
         (c02 * gap[0] + c12 * gap[1] + c22 * gap[2]) / det)
    return (-dot(su1, w) * w0, -dot(sv1, w) * w1, dot(su2, w) * w2, dot(sv2, w) * w3), True


@jit(inline="always")
def gap_correction(su1, sv1, su2, sv2, gap, out):
    """min_norm_step written to out (4,); returns its ok flag."""
    step, ok = min_norm_step(su1, sv1, su2, sv2, gap)
    for i in range(4):
        out[i] = step[i]
    return ok


@jit
def dragilev_rhs(s, y, a, b, sign, pullback):
    """Right-hand side of the arc-length Cauchy problem, with a pull-back onto both surfaces.

    Parameters
    ----------
    s : float
        Arc length (unused: the system is autonomous).
    y : ndarray (4,)
        (u1, v1, u2, v2).
    a, b : ndarray (DATA_SIZE,)
        Packed surfaces.
    sign : float
        +1 or -1: the direction of travel along N1 x N2.
    pullback : float
        Rate lambda (1/length) of the pull-back: the gap M1 - M2 decays like exp(-lambda s).

    Returns
    -------
    ndarray (4,)
        dy/ds. Zero where the normals are parallel or a parametrisation is singular.
    """
    dy = np.empty(4)
    dragilev_into(y, a, b, sign, pullback, dy)
    return dy


# Inlined at numba's level into the engine's step (with branch_ode.branch_fun), and frame and min_norm_step at
# LLVM's (forceinline): as separate calls, their array arguments' reference counts (atomic operations) and the
# calls themselves cost about as much as the arithmetic. The results are the same bits.
@jit(inline="always")
def dragilev_into(y, a, b, sign, pullback, out):
    """dragilev_rhs written to out (4,), without allocating (the compiled integrator's hot path). Returns (sin of
    the normals' angle, M1) at y, which it computed on the way (as degeneracy and frame give them)."""
    p1, su1, sv1 = frame(a, y[0], y[1])
    p2, su2, sv2 = frame(b, y[2], y[3])
    t, c = unit_tangent(su1, sv1, su2, sv2)
    if c == 0.0:
        for i in range(4):
            out[i] = 0.0
        return c, p1
    t = (sign * t[0], sign * t[1], sign * t[2])
    out[0], out[1], _ = gram(su1, sv1, t)
    out[2], out[3], _ = gram(su2, sv2, t)
    if pullback > 0.0:
        step, ok = min_norm_step(su1, sv1, su2, sv2, (p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2]))
        if ok:
            for i in range(4):
                out[i] += pullback * step[i]
    return c, p1


@jit
def curve_frame(y, a, b, point, tangent):
    """Point M1(y) and unit tangent N1 x N2/|.| at y; returns sin of the normals' angle."""
    return frame_of(frame(a, y[0], y[1]), frame(b, y[2], y[3]), point, tangent)


@jit(inline="always")
def frame_of(f1, f2, point, tangent):
    """curve_frame from the surfaces' frames f1 = frame(a, y[0], y[1]) and f2 = frame(b, y[2], y[3]) at the state
    y, made by the caller."""
    p1, su1, sv1 = f1
    _, su2, sv2 = f2
    for i in range(3):
        point[i] = p1[i]
    return tangent_from_normals(su1, sv1, su2, sv2, tangent)


@jit
def project_to_curve(y, a, b, q, t, gap_tol, max_iter):
    """Newton correction of y onto the curve, in the plane through q normal to t.

    Solves M1(u1, v1) - M2(u2, v2) = 0 and (M1 - q).t = 0 (4 equations, 4 unknowns) in place.
    With t = 0 the plane condition is dropped and minimum-norm Gauss-Newton steps are taken instead.

    Returns
    -------
    int
        Number of iterations used (>= 0) on convergence (|M1 - M2| <= gap_tol and the last step below
        gap_tol, or stopped contracting: near tangency round-off in the gap, amplified by the nearly
        parallel normals, keeps the steps above gap_tol while the point sits on both surfaces, or the tangent
        planes too nearly parallel for a step while it does), or -1 if Newton failed (singular system off the
        curve, or no convergence within max_iter).
    """
    work = newton_work()
    status, _, _, _ = newton_from(y, a, b, q, t, gap_tol, max_iter, frame(a, y[0], y[1]), frame(b, y[2], y[3]),
                                  borrowed(work))
    kept(work)
    return status


@jit
def newton_work():
    """Newton's work arrays for newton_from: (m (4, 4), r, dx, piv, scales (4,))."""
    return np.empty((4, 4)), np.empty(4), np.empty(4), np.empty(4, dtype=np.int64), np.empty(4)


@jit(inline="always")          # (the stored points' correction: inlined as dragilev_into is, with its helpers)
def newton_from(y, a, b, q, t, gap_tol, max_iter, f1, f2, work):
    """project_to_curve from the frames f1 = frame(a, y[0], y[1]) and f2 = frame(b, y[2], y[3]) at the given y
    (made by the caller, who needed them too). Returns (iterations or -1 as project_to_curve, fresh, f1, f2):
    with fresh, f1 and f2 are the frames at the returned y (Newton stopped on its test before a step), else at
    the y before the last step."""
    m, r, dx, piv, scales = work
    use_plane = dot(t, t) > 0.0
    step = np.inf
    prev_step = np.inf
    for it in range(max_iter + 1):
        if it > 0:
            f1 = frame(a, y[0], y[1])
            f2 = frame(b, y[2], y[3])
        p1, su1, sv1 = f1
        p2, su2, sv2 = f2
        gap = (p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2])
        plane = ((p1[0] - q[0]) * t[0] + (p1[1] - q[1]) * t[1] + (p1[2] - q[2]) * t[2]) if use_plane else 0.0
        err = max(norm(gap), abs(plane))
        if it > 0 and err <= gap_tol and (step <= gap_tol or step > STAGNATION * prev_step):
            return it, True, f1, f2
        prev_step = step
        if it == max_iter:
            break
        if use_plane:
            for i in range(3):
                m[i, 0] = su1[i]
                m[i, 1] = sv1[i]
                m[i, 2] = -su2[i]
                m[i, 3] = -sv2[i]
                r[i] = -gap[i]
            m[3, 0] = dot(t, su1)
            m[3, 1] = dot(t, sv1)
            m[3, 2] = 0.0
            m[3, 3] = 0.0
            r[3] = -plane
            balance_columns(m, scales)          # (the pivot test independent of the parameters' units)
            if lu_factor(m, piv):
                lu_solve(m, piv, r, dx)
                unbalance(dx, scales)
            else:
                # a parametrisation degenerates (an apex, a pole): take the minimum-norm step instead
                if not gap_correction(su1, sv1, su2, sv2, gap, dx):
                    return (it if err <= gap_tol else -1), True, f1, f2
        else:
            if not gap_correction(su1, sv1, su2, sv2, gap, dx):
                return (it if err <= gap_tol else -1), True, f1, f2
        for i in range(4):
            y[i] += dx[i]
        # the size of the step in space, measured on both surfaces
        step = max(norm((su1[0] * dx[0] + sv1[0] * dx[1], su1[1] * dx[0] + sv1[1] * dx[1],
                         su1[2] * dx[0] + sv1[2] * dx[1])),
                   norm((su2[0] * dx[2] + sv2[0] * dx[3], su2[1] * dx[2] + sv2[1] * dx[3],
                         su2[2] * dx[2] + sv2[2] * dx[3])))
        if err <= gap_tol and step <= gap_tol:
            return it + 1, False, f1, f2
    return -1, True, f1, f2          # (the loop ends at max_iter before a step: the frames are y's)


@jit
def project_many(ys, a, b, normal, gap_tol, max_iter, points, tangents, status):
    """Project each row of ys (N, 4) onto the curve in the plane through M1(y) normal to the tangent there,
    or normal to the fixed vector `normal` where it is non-zero (beside a singular point, where the tangent
    is ill-defined). Writes the corrected rows in place, their points (N, 3) and tangents (N, 3);
    status[k] = iterations used or -1."""
    q = np.empty(3)
    t = np.empty(3)
    work = newton_work()
    fixed = dot(normal, normal) > 0.0
    for k in range(ys.shape[0]):
        status[k] = _project_row(ys[k], a, b, normal, fixed, gap_tol, max_iter, q, t, points[k], tangents[k], work)


@jit
def project_through(ys, a, b, normal, targets, gap_tol, max_iter, points, tangents, status):
    """project_many in the planes normal to the fixed vector `normal` (non-zero) through the points targets (N, 3),
    not through M1(y): each corrected point lies where its target says along `normal` (a jump's points, placed by
    arc length on its chords)."""
    for k in range(ys.shape[0]):
        status[k] = project_to_curve(ys[k], a, b, targets[k], normal, gap_tol, max_iter)
        frame_along(ys[k], a, b, normal, True, points[k], tangents[k])


@jit
def corrected_many(ys, a, b, normal, gap_tol, max_iter, points, gaps):
    """project_many for the stored states of a traced segment: the rows of ys (N, 4) projected in place, their
    points (N, 3), and gaps[k] = |M1 - M2| of each row before its projection (the solver's own gap)."""
    ys, a, b, normal, points, gaps = borrowed((ys, a, b, normal, points, gaps))     # (see borrowed)
    vectors, newton = np.empty((3, 3)), newton_work()
    q, t, tangent = borrowed((vectors[0], vectors[1], vectors[2]))
    fixed = dot(normal, normal) > 0.0
    for k in range(ys.shape[0]):
        f1 = frame(a, ys[k, 0], ys[k, 1])
        f2 = frame(b, ys[k, 2], ys[k, 3])
        p1, p2 = f1[0], f2[0]
        gaps[k] = math.sqrt((p1[0] - p2[0]) ** 2 + (p1[1] - p2[1]) ** 2 + (p1[2] - p2[2]) ** 2)
        _project_frames(ys[k], a, b, normal, fixed, gap_tol, max_iter, q, t, points[k], tangent, f1, f2,
                        borrowed(newton))
    kept(vectors, newton)


@jit
def _project_row(y, a, b, normal, fixed, gap_tol, max_iter, q, t, point, tangent, work):
    """One row of project_many (q, t: work vectors); returns Newton's iterations or -1."""
    return _project_frames(y, a, b, normal, fixed, gap_tol, max_iter, q, t, point, tangent, frame(a, y[0], y[1]),
                           frame(b, y[2], y[3]), work)


@jit(inline="always")
def _project_frames(y, a, b, normal, fixed, gap_tol, max_iter, q, t, point, tangent, f1, f2, work):
    """_project_row from the frames f1, f2 at y: curve_frame, project_to_curve and frame_along of y, each surface
    evaluated once where two of them evaluate it at the same parameters (the same values: the same kernels)."""
    frame_of(f1, f2, q, t)                              # curve_frame(y, a, b, q, t)
    if fixed:
        for i in range(3):
            t[i] = normal[i]
    status, fresh, f1, f2 = newton_from(y, a, b, q, t, gap_tol, max_iter, f1, f2, work)
    if not fresh:
        f1 = frame(a, y[0], y[1])
        f2 = frame(b, y[2], y[3])
    frame_of(f1, f2, point, tangent)                    # frame_along(y, a, b, normal, fixed, point, tangent)
    turn_along(tangent, normal, fixed)
    return status


@jit
def frame_along(y, a, b, normal, fixed, point, tangent):
    """curve_frame of y into point and tangent, the tangent turned along the fixed vector normal (when fixed)."""
    curve_frame(y, a, b, point, tangent)
    turn_along(tangent, normal, fixed)


@jit(inline="always")
def turn_along(tangent, normal, fixed):
    """The tangent (3,) reversed in place when fixed and it points against the vector normal."""
    if fixed and dot(tangent, normal) < 0.0:
        for i in range(3):
            tangent[i] = -tangent[i]


@jit
def degeneracy(y, a, b, area_a, area_b):
    """Smallest of: sin(angle between the normals), and the relative area element (relative_area) of each
    surface whose area unit (area_a, area_b: the length of a unit step of its v, 0.0 for none) is set. Zero at a
    singular point of the curve or of a parametrisation."""
    _, su1, sv1 = frame(a, y[0], y[1])
    _, su2, sv2 = frame(b, y[2], y[3])
    _, value = unit_tangent(su1, sv1, su2, sv2)
    if area_a:
        value = min(value, relative_area(su1, sv1, area_a))
    if area_b:
        value = min(value, relative_area(su2, sv2, area_b))
    return value


@jit
def area_degeneracy(y, a, b, area_a, area_b):
    """Smallest relative area element of the watched surfaces' parametrisations at y (1 if none watched;
    area_a, area_b: the length of a unit step of the surface's v, 0.0 where it is not watched)."""
    value = 1.0
    if area_a:
        _, su, sv = frame(a, y[0], y[1])
        value = min(value, relative_area(su, sv, area_a))
    if area_b:
        _, su, sv = frame(b, y[2], y[3])
        value = min(value, relative_area(su, sv, area_b))
    return value


@jit
def relative_area(su, sv, unit):
    """|su x sv'| / max(|su|, |sv'|)^2 with sv' = unit sv, the derivative along a step of v of length unit
    (1 for an angle, the scene's scale for a length such as a cone's v; u is an angle on every watched surface):
    zero where the parametrisation degenerates (a derivative vanishes or they become parallel), and the same
    number for the same scene at any scale (a cone's is its distance from the axis over the scale, near the apex).
    A unit of 1 leaves every bit as without it."""
    svu = (unit * sv[0], unit * sv[1], unit * sv[2])
    big = max(dot(su, su), dot(svu, svu))
    if big == 0.0:
        return 0.0
    return norm(cross3(su, svu)) / big


@jit
def degeneracy_slope(y, a, b, sign, h):
    """d/ds of sin(angle between the normals) along the direction of travel, by a central difference of
    arc-length step h. It changes sign from - to + where the path passes a minimum: at a node where branches
    cross this minimum is (near) zero and the slope jumps."""
    dy = dragilev_rhs(0.0, y, a, b, sign, 0.0)
    yp = y + h * dy
    ym = y - h * dy
    return (degeneracy(yp, a, b, 0.0, 0.0) - degeneracy(ym, a, b, 0.0, 0.0)) / (2.0 * h)


@jit
def plane_value(p, start, direction, offset):
    """Signed distance of the point p (3-tuple) past the plane through start normal to direction, plus offset."""
    return (p[0] - start[0]) * direction[0] + (p[1] - start[1]) * direction[1] + (p[2] - start[2]) * direction[2] \
        + offset


@jit
def curve_derivatives(y, a, b, sign, dy, ddy, d1, d2):
    """Analytic first and second derivatives in arc length at a point y on the curve.

    Writes dy = y' (4,), ddy = y'' (4,), d1 = C' (3,) (the unit tangent, sign * N1 x N2/|.|) and
    d2 = C'' (3,) (the curvature vector). C'' follows from the surfaces' second derivatives:
    N_i . C'' = N_i . Q_i with Q_i = S_uu u'^2 + 2 S_uv u'v' + S_vv v'^2, and t . C'' = 0 (unit speed);
    then S_u u'' + S_v v'' = C'' - Q_i is solved in each surface's Gram system. Returns False at a
    singular point.
    """
    p1, su1, sv1 = frame(a, y[0], y[1])
    p2, su2, sv2 = frame(b, y[2], y[3])
    t, c = unit_tangent(su1, sv1, su2, sv2)
    if c == 0.0:
        return False
    for i in range(3):
        d1[i] = sign * t[i]
    dy[0], dy[1], _ = gram(su1, sv1, d1)
    dy[2], dy[3], _ = gram(su2, sv2, d1)
    q1 = _quadratic(second(a, y[0], y[1]), dy[0], dy[1])
    q2 = _quadratic(second(b, y[2], y[3]), dy[2], dy[3])
    n1 = cross3(su1, sv1)
    n2 = cross3(su2, sv2)
    # rows n1, n2, t: C'' = (r1 (n2 x t) + r2 (t x n1)) / det with r1 = n1.q1, r2 = n2.q2 (t.C'' = 0)
    c12 = cross3(n2, d1)
    c20 = cross3(d1, n1)
    det = dot(n1, c12)
    if abs(det) <= PIVOT_EPS * norm(n1) * norm(n2):
        return False
    r1 = dot(n1, q1) / det
    r2 = dot(n2, q2) / det
    for i in range(3):
        d2[i] = r1 * c12[i] + r2 * c20[i]
    ddy[0], ddy[1], _ = gram(su1, sv1, (d2[0] - q1[0], d2[1] - q1[1], d2[2] - q1[2]))
    ddy[2], ddy[3], _ = gram(su2, sv2, (d2[0] - q2[0], d2[1] - q2[1], d2[2] - q2[2]))
    return True


@jit
def longest_step_bend(t, y, a, b):
    """(length of the longest step of a segment, the larger curvature |C''| at that step's ends (0 at a singular
    point)): t (m >= 2,) its step points, y (4, m) the states there, a, b its charts."""
    j = 0
    for i in range(1, t.shape[0] - 1):
        if t[i + 1] - t[i] > t[j + 1] - t[j]:
            j = i
    state, dy, ddy, d1, d2 = np.empty(4), np.empty(4), np.empty(4), np.empty(3), np.empty(3)
    bend = 0.0
    for i in (j, j + 1):
        for c in range(4):
            state[c] = y[c, i]
        if curve_derivatives(state, a, b, 1.0, dy, ddy, d1, d2):
            bend = max(bend, math.sqrt(d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2]))
    return t[j + 1] - t[j], bend


@jit
def _quadratic(sec, du, dv):
    """S_uu du^2 + 2 S_uv du dv + S_vv dv^2 (a 3-tuple) from sec = (S_uu, S_uv, S_vv)."""
    return (sec[0][0] * du * du + 2.0 * sec[1][0] * du * dv + sec[2][0] * dv * dv,
            sec[0][1] * du * du + 2.0 * sec[1][1] * du * dv + sec[2][1] * dv * dv,
            sec[0][2] * du * du + 2.0 * sec[1][2] * du * dv + sec[2][2] * dv * dv)


@jit
def curve_derivatives_many(ys, a, b, sign, dy, ddy, d1, d2, ok):
    """curve_derivatives for each row of ys (N, 4); ok[k] False at singular points."""
    for k in range(ys.shape[0]):
        ok[k] = curve_derivatives(ys[k], a, b, sign, dy[k], ddy[k], d1[k], d2[k])


@jit
def curve_speed_many(ys, a, b, sign, pullback, gap_tol, max_iter, speed):
    """Speed along the curve, per unit solver time, of the curve point C beside M1(y) for each state row of ys
    (N, 4) the integrator passes (off the curve by its round-off, far more beside a near-node waist, where the
    two surfaces nearly touch and a tiny gap lets M1 slide along the curve's normal).

    C is the Newton projection of y in the plane through M1 normal to the tangent there; its speed is
    (T . M1') / (1 - K . (M1 - C)), T and K the unit tangent and curvature vector at C, M1' the integrated
    velocity (the right-hand side with its pull-back): the foot point of a point beside a curve moves at that
    rate. speed[k] = -1 where Newton fails or C is singular."""
    dy = np.empty(4)
    yc = np.empty(4)
    q = np.empty(3)
    t = np.empty(3)
    d1y = np.empty(4)
    d2y = np.empty(4)
    d1 = np.empty(3)
    d2 = np.empty(3)
    for k in range(ys.shape[0]):
        y = ys[k]
        dragilev_into(y, a, b, sign, pullback, dy)
        m, su, sv = frame(a, y[0], y[1])
        curve_frame(y, a, b, q, t)
        for i in range(4):
            yc[i] = y[i]
        if project_to_curve(yc, a, b, q, t, gap_tol, max_iter) < 0 or \
                not curve_derivatives(yc, a, b, sign, d1y, d2y, d1, d2):
            speed[k] = -1.0
            continue
        c, _, _ = frame(a, yc[0], yc[1])
        along = 0.0
        bend = 0.0
        for i in range(3):
            along += d1[i] * (su[i] * dy[0] + sv[i] * dy[1])
            bend += d2[i] * (m[i] - c[i])
        speed[k] = abs(along) / (1.0 - bend) if bend < 0.5 else -1.0


@jit
def newton_fixed_many(ys, a, b, fixed, gap_tol, max_iter, ok):
    """Newton on M1(u1, v1) - M2(u2, v2) = 0 for the three parameters other than ys[k, fixed], in place
    for each row of ys (N, 4); ok[k] True once |M1 - M2| <= gap_tol (then one more step is taken)."""
    for k in range(ys.shape[0]):
        ok[k] = newton_fixed_row(ys[k], a, b, fixed, gap_tol, max_iter)


@jit
def newton_fixed_row(y, a, b, fixed, gap_tol, max_iter):
    """newton_fixed_many for one state y (4,), in place; True once |M1 - M2| <= gap_tol."""
    m = np.empty((3, 3))
    r = np.empty(3)
    dx = np.empty(3)
    piv = np.empty(3, dtype=np.int64)
    scales = np.empty(3)
    done = False
    for _ in range(max_iter):
        p1, su1, sv1 = frame(a, y[0], y[1])
        p2, su2, sv2 = frame(b, y[2], y[3])
        gap = (p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2])
        if norm(gap) <= gap_tol:
            if done:
                break
            done = True      # converged: one more step polishes to round-off
        columns = (su1, sv1, su2, sv2)
        col = 0
        for i in range(4):
            if i == fixed:
                continue
            for j in range(3):
                m[j, col] = columns[i][j] if i < 2 else -columns[i][j]
            col += 1
        for j in range(3):
            r[j] = -gap[j]
        balance_columns(m, scales)              # (the pivot test independent of the parameters' units)
        if not lu_factor(m, piv):
            break
        lu_solve(m, piv, r, dx)
        unbalance(dx, scales)
        col = 0
        for i in range(4):
            if i == fixed:
                continue
            y[i] += dx[col]
            col += 1
    return done


@jit
def fixed_parameter_path(ys, targets, a, b, fixed, reach, gap_tol, max_iter, dy, ddy, d1, d2, status):
    """States on the curve at the values targets (N,) of the parameter `fixed`, visited in the given order,
    with their arc-length derivatives (as curve_derivatives with sign +1).

    Row k starts from a second-order Taylor prediction in the fixed parameter off the row before when the step
    between their targets is at most reach, else (or where Newton fails from the prediction) from the guess
    ys[k] (a nearby curve state); then Newton at the fixed value (newton_fixed_row). Continuation keeps each
    row on the branch of the one before. status[k]: 0 solved, 1 Newton failed, 2 a singular point
    (derivatives undefined).
    """
    guess = np.empty(4)
    for k in range(ys.shape[0]):
        for i in range(4):
            guess[i] = ys[k, i]
        guess[fixed] = targets[k]
        predicted = k > 0 and status[k - 1] == 0 and abs(targets[k] - targets[k - 1]) <= reach \
            and abs(dy[k - 1, fixed]) > 0.0
        if predicted:
            h = targets[k] - targets[k - 1]
            rate = dy[k - 1, fixed]
            for i in range(4):
                first = dy[k - 1, i] / rate
                second = (ddy[k - 1, i] * rate - dy[k - 1, i] * ddy[k - 1, fixed]) / (rate * rate * rate)
                ys[k, i] = ys[k - 1, i] + h * first + 0.5 * h * h * second
        ys[k, fixed] = targets[k]
        ok = newton_fixed_row(ys[k], a, b, fixed, gap_tol, max_iter)
        if not ok and predicted:
            for i in range(4):
                ys[k, i] = guess[i]
            ok = newton_fixed_row(ys[k], a, b, fixed, gap_tol, max_iter)
        if not ok:
            status[k] = 1
        elif not curve_derivatives(ys[k], a, b, 1.0, dy[k], ddy[k], d1[k], d2[k]):
            status[k] = 2
        else:
            status[k] = 0
