"""Proven trim crossings of a curve of the level g = F_T(S(u, v)) = 0, in S's (scaled) parameter plane.

A trim edge is the zero set of e: a parameter of S held at a value (e = u - u0 or v - v0), a local length coordinate
of T (a plane's x or y, a cylinder's or cone's z) held at a value (e = q_axis - value, q = M s + c the point of S in
T's frame, spatialkin.kernels.geometry.interval), or a face's limit (spatialkin.geometry.trims.Limit) read on the
local point of its own surface (S placed in that surface's frame): a half-plane through the local z axis at an
angle, cos(angle) y - sin(angle) x (on a cone's lower nappe, z < 0, its negative), a torus's tube angle, cos(angle)
z - sin(angle) (rho - R), a local coordinate less a value, or the distance rho from the local z axis less a value.
``crossing`` proves, by the Krawczyk operator of the 2 x 2 system (g, e) on a box of S's parameters, that the box
holds exactly one point of the curve on the edge; ``edge_rate`` encloses de/dt along the arc of a tube piece
(spatialkin.kernels.certify.tubes), so that a rate of one sign proves that the arc crosses the edge at most once
there; ``arc_inside`` encloses e along a piece's arc (on stretches of it, with the arc's own enclosure there), to
prove the arc wholly on one side of an edge.

References
----------
R. Krawczyk, "Newton-Algorithmen zur Bestimmung von Nullstellen mit Fehlerschranken", Computing 4 (1969) 187-201.
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, ch. 8.
"""
import math

import numpy as np

from ..._lib.jit import jit
from ..geometry.interval import (box_trig, iadd, idiv, idot, implicit_jet, imul, ineg, intersect, iscale, ishift,
                                 isqr, isqrt, isub, jet, jet_first, krawczyk_row, local_first, placed, point,
                                 transform, up, widen)
from .tubes import H, P, Q, T0, T1, arc_enclosure, frame_hessian, piece_box, stretch_box

#: An edge of S's own parameters: EDGE_U (u = value) or EDGE_V (v = value); 0, 1, 2: T's local coordinate.
EDGE_U, EDGE_V = -1, -2
#: A face limit: FACE plus its kind: TURN (the half-plane through the axis at the angle value), NAPPES (TURN on a
#: double cone), RADIUS, HEIGHT + the local axis (0, 1, 2), or TUBE (a torus's tube angle: the half-plane of its
#: meridian through the tube's centre at the angle value), read on the local point of the face's own surface: the
#: point of S placed by ``face`` = (m, c, pad, cpad, major), the rigorous placement of S in that surface's frame
#: (as T's is, spatialkin.kernels.geometry.interval.placed) and, for TUBE, its major radius. Other edges ignore face.
FACE = 10
TURN, NAPPES, RADIUS, HEIGHT, TUBE = 0, 1, 2, 3, 6
#: The face argument of the edges that are no face limit.
NO_FACE = (np.eye(3), np.zeros(3), 0.0, 0.0, 0.0)
#: Relative widening of cos and sin of a limit's angle: two ulps hold the exact values (math.cos and math.sin
#: are faithful, within one ulp).
TRIG_ULPS = 4.5e-16


@jit(forceinline=True)
def _face(p, pu, pv, kind, value, major):
    """(e, e_u, e_v) of a face limit of kind at value over the interval local point p (3 intervals) and its
    derivatives (major: a torus's major radius, for TUBE); infinite where the limit is not one smooth function over
    the box (a cone's apex plane, the axis for a radius or a tube angle)."""
    whole = (-math.inf, math.inf)
    c0, s0 = math.cos(value), math.sin(value)
    c = widen(point(c0), TRIG_ULPS * abs(c0) + 1e-300)
    s = widen(point(s0), TRIG_ULPS * abs(s0) + 1e-300)
    if kind == RADIUS or kind == TUBE:
        r2 = iadd(isqr(p[0]), isqr(p[1]))
        if not r2[0] > 0.0:
            return whole, whole, whole
        r = isqrt(r2)
        ru = idiv(iadd(imul(p[0], pu[0]), imul(p[1], pu[1])), r)
        rv = idiv(iadd(imul(p[0], pv[0]), imul(p[1], pv[1])), r)
        if kind == RADIUS:
            return ishift(r, -value), ru, rv
        # cos(value) z - sin(value) (rho - R): the tube angle's half-plane, as spatialkin.geometry.trims.Limit reads it
        e = isub(imul(c, p[2]), imul(s, ishift(r, -major)))
        return e, isub(imul(c, pu[2]), imul(s, ru)), isub(imul(c, pv[2]), imul(s, rv))
    if kind == TURN or kind == NAPPES:
        e = isub(imul(c, p[1]), imul(s, p[0]))
        eu = isub(imul(c, pu[1]), imul(s, pu[0]))
        ev = isub(imul(c, pv[1]), imul(s, pv[0]))
        if kind == NAPPES:
            if p[2][1] < 0.0:
                return ineg(e), ineg(eu), ineg(ev)
            if not p[2][0] > 0.0:
                return whole, whole, whole
        return e, eu, ev
    axis = kind - HEIGHT
    return ishift(p[axis], -value), pu[axis], pv[axis]


@jit(forceinline=True)
def _system(s_data, t_data, m, c, pad, cpad, U, V, edge, value, face):
    """((g, g_u, g_v), (e, e_u, e_v)) over the raw parameter box U x V."""
    x, xu, xv, _ = local_first(s_data, U, V, box_trig(s_data, U, V))
    q = placed(m, c, x, pad, cpad)
    qu = transform(m, xu, pad)
    qv = transform(m, xv, pad)
    f, grad, _ = implicit_jet(t_data, q)
    g = (f, idot(grad, qu), idot(grad, qv))
    if edge == EDGE_U:
        e = (ishift(U, -value), (1.0, 1.0), (0.0, 0.0))
    elif edge == EDGE_V:
        e = (ishift(V, -value), (0.0, 0.0), (1.0, 1.0))
    elif edge >= FACE:
        fm, fc, fpad, fcpad, major = face
        e = _face(placed(fm, fc, x, fpad, fcpad), transform(fm, xu, fpad), transform(fm, xv, fpad), edge - FACE, value,
                  major)
    else:
        e = (ishift(q[edge], -value), qu[edge], qv[edge])
    return g, e


@jit
def crossing(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, cu, cv, h):
    """True when the box (cu, cv) +- h (scaled parameters; su, sv the power-of-two units) holds exactly one solution
    of g = 0, e = 0 (the Krawczyk test)."""
    Uc = (cu * su, cu * su)
    Vc = (cv * sv, cv * sv)
    gc, ec = _system(s_data, t_data, m, c, pad, cpad, Uc, Vc, edge, value, face)
    # the Jacobian at the centre, in scaled parameters, and its float inverse
    j00 = 0.5 * (gc[1][0] + gc[1][1]) * su
    j01 = 0.5 * (gc[2][0] + gc[2][1]) * sv
    j10 = 0.5 * (ec[1][0] + ec[1][1]) * su
    j11 = 0.5 * (ec[2][0] + ec[2][1]) * sv
    det = j00 * j11 - j01 * j10
    if det == 0.0 or not math.isfinite(det):
        return False
    y00, y01, y10, y11 = j11 / det, -j01 / det, -j10 / det, j00 / det
    B = (-h, h)
    U = iscale(iadd(point(cu), B), su)
    V = iscale(iadd(point(cv), B), sv)
    g, e = _system(s_data, t_data, m, c, pad, cpad, U, V, edge, value, face)
    gu, gv = iscale(g[1], su), iscale(g[2], sv)
    eu, ev = iscale(e[1], su), iscale(e[2], sv)
    for row in range(2):
        ya, yb = (y00, y01) if row == 0 else (y10, y11)
        k = krawczyk_row(ya, yb, 0.0, gc[0], ec[0], gu, gv, eu, ev, B, B, row)     # (centred: K - c)
        if not (-h < k[0] and k[1] < h):
            return False
    return True


@jit
def crossing_radius(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, cu, cv, h0, cap):
    """The smallest half-width h (from h0, growing eightfold up to cap) whose box round (cu, cv) passes crossing;
    inf when none does."""
    h = h0
    while h <= cap:
        if crossing(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, cu, cv, h):
            return h
        h *= 8.0
    return math.inf


@jit(forceinline=True)
def _rate(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, piece, U, V):
    """(lo, hi): an enclosure of de/dt along the arc of the piece over the raw box U x V holding that arc."""
    g, e = _system(s_data, t_data, m, c, pad, cpad, U, V, edge, value, face)
    p, q = piece[P], piece[Q]
    gu, gv = iscale(g[1], su), iscale(g[2], sv)            # derivatives in scaled parameters
    return _arc_rate(e, p, q, su, sv, iadd(iscale(gu, p), iscale(gv, q)), iadd(iscale(gu, -q), iscale(gv, p)))


@jit(forceinline=True)
def _arc_rate(e, p, q, su, sv, phi_t, phi_w):
    """(lo, hi): de/dt along the arc of a piece with direction (p, q), from the enclosures of e's jet (raw
    parameters) and of phi_t, phi_w (g's derivatives along the piece's a and n)."""
    eu, ev = iscale(e[1], su), iscale(e[2], sv)
    if phi_w[0] <= 0.0 <= phi_w[1]:
        return -math.inf, math.inf
    dw = ineg(idiv(phi_t, phi_w))
    du = iadd(point(p), iscale(dw, -q))
    dv = iadd(point(q), iscale(dw, p))
    rate = iadd(imul(eu, du), imul(ev, dv))
    return rate[0], rate[1]


@jit
def _rate_second(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, piece, t0, t1, W):
    """(lo, hi): _rate over the stretch [t0, t1] x W of the piece with phi_t and phi_w enclosed to second order too
    (the mean value theorem from the stretch's centre, g's Hessian over it; each met with the first-order
    enclosure): near a tangency, where g's gradient is small and its Hessian is not, the first-order phi_w holds 0
    over all but the shortest stretches."""
    U, V = stretch_box(piece, t0, t1, W, su, sv)
    _, e = _system(s_data, t_data, m, c, pad, cpad, U, V, edge, value, face)
    _, gu, gv, guu, guv, gvv = jet(s_data, t_data, m, c, pad, cpad, U, V)
    tm, wm = 0.5 * (t0 + t1), 0.5 * (W[0] + W[1])
    Uc, Vc = stretch_box(piece, tm, tm, (wm, wm), su, sv)
    _, cu_, cv_ = jet_first(s_data, t_data, m, c, pad, cpad, Uc, Vc, box_trig(s_data, Uc, Vc))[0]
    p, q = piece[P], piece[Q]
    au, av, nu, nv = p * su, q * sv, -q * su, p * sv
    d_tt, d_tw, d_ww = frame_hessian(guu, guv, gvv, p, q, su, sv)
    dT, dW = isub((t0, t1), point(tm)), isub(W, point(wm))
    phi_t = intersect(iadd(iscale(gu, au), iscale(gv, av)),
                      iadd(iadd(iadd(iscale(cu_, au), iscale(cv_, av)), imul(d_tt, dT)), imul(d_tw, dW)))
    phi_w = intersect(iadd(iscale(gu, nu), iscale(gv, nv)),
                      iadd(iadd(iadd(iscale(cu_, nu), iscale(cv_, nv)), imul(d_tw, dT)), imul(d_ww, dW)))
    return _arc_rate(e, p, q, su, sv, phi_t, phi_w)


@jit
def edge_rate(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, piece, stretches):
    """(lo, hi): an enclosure of de/dt along the arc of the piece (t its parameter along a): the arc's direction
    (du/dt, dv/dt) = a + n dw/dt, dw/dt = -phi_t / phi_w, over the piece's parallelogram (stretches 0), or the hull
    of its enclosures over that many equal stretches of T, each with its arc's enclosure (tubes.arc_enclosure)."""
    if stretches == 0:
        U, V = piece_box(piece, su, sv)
        return _rate(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, piece, U, V)
    lo, hi = math.inf, -math.inf
    t0, t1 = piece[T0], piece[T1]
    for k in range(stretches):
        a = t0 + (t1 - t0) * k / stretches
        b = t1 if k == stretches - 1 else t0 + (t1 - t0) * (k + 1) / stretches
        W = arc_enclosure(s_data, t_data, m, c, pad, cpad, su, sv, piece, a, b)
        U, V = stretch_box(piece, a, b, W, su, sv)
        r = _rate(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, piece, U, V)
        if not (r[0] > 0.0 or r[1] < 0.0):
            r2 = _rate_second(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, piece, a, b, W)
            r = (max(r[0], r2[0]), min(r[1], r2[1]))
        lo, hi = min(lo, r[0]), max(hi, r[1])
    return lo, hi


@jit
def arc_inside(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, inside, piece, depth):
    """True when the arc of the proven piece lies strictly on the inside of the edge (e > 0 for inside = +1, e < 0
    for inside = -1): e's enclosure over the parallelogram of each stretch of T and its arc's enclosure there
    (tubes.arc_enclosure) is of that sign, the stretch halved where it is not, at most depth - 1 times."""
    stack = np.empty((depth + 2, 3))
    stack[0, 0], stack[0, 1], stack[0, 2] = piece[T0], piece[T1], 0.0
    top = 1
    for _ in range(1 << (depth + 1)):
        if top == 0:
            return True
        top -= 1
        t0, t1, level = stack[top, 0], stack[top, 1], stack[top, 2]
        # the whole parallelogram first (most pieces lie well inside), then the arc's enclosure on each stretch
        W = (-piece[H], piece[H]) if level == 0.0 else arc_enclosure(s_data, t_data, m, c, pad, cpad, su, sv,
                                                                      piece, t0, t1)
        U, V = stretch_box(piece, t0, t1, W, su, sv)
        _, e = _system(s_data, t_data, m, c, pad, cpad, U, V, edge, value, face)
        if (inside > 0.0 and e[0][0] > 0.0) or (inside < 0.0 and e[0][1] < 0.0):
            continue
        if level >= depth or not (inside > 0.0 and e[0][1] > 0.0 or inside < 0.0 and e[0][0] < 0.0):
            return False                      # too deep, or the whole stretch on the edge's other side
        if level == 0.0:
            stack[0, 2] = 1.0                 # the same stretch again, with its arc's enclosure
            top = 1
            continue
        mid = 0.5 * (t0 + t1)
        stack[top, 0], stack[top, 1], stack[top, 2] = t0, mid, level + 1
        stack[top + 1, 0], stack[top + 1, 1], stack[top + 1, 2] = mid, t1, level + 1
        top += 2
    return top == 0


@jit
def arcs_inside(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, inside, pieces, depth, out):
    """arc_inside of every piece (K, WIDTH), into out (K,) bool."""
    for i in range(pieces.shape[0]):
        out[i] = arc_inside(s_data, t_data, m, c, pad, cpad, su, sv, edge, value, face, inside, pieces[i], depth)



@jit
def box_trim(s_data, t_data, m, c, pad, cpad, box, edge, value, face):
    """(lo, hi): an enclosure of e over the raw parameter box (u lo, u hi, v lo, v hi) of S."""
    _, e = _system(s_data, t_data, m, c, pad, cpad, (box[0], box[1]), (box[2], box[3]), edge, value, face)
    return e[0][0], e[0][1]


@jit
def box_diameter(s_data, box):
    """An upper bound of the diameter of S over the raw parameter box (u lo, u hi, v lo, v hi): the diagonal of its
    local point's enclosure."""
    U, V = (box[0], box[1]), (box[2], box[3])
    x, _, _, _ = local_first(s_data, U, V, box_trig(s_data, U, V))
    total = 0.0
    for k in range(3):
        width = up(x[k][1] - x[k][0])
        total = up(total + up(width * width))
    return up(math.sqrt(total))
