"""Proven tubes along a curve of the level g = F_T(S(u, v)) = 0 on S's parameter plane.

A tube piece is a parallelogram of S's (scaled) parameters,

    X = { c + t a + w n : t in [t0, t1], w in [-h, h] },   a = (p, q), n = (-q, p),

in the coordinates x = (u / su, v / sv), su and sv powers of two (so that scaling is exact). With
phi(t, w) = g(c + t a + w n), the piece is proven when the parametric Krawczyk operator

    K = -y (phi(tm, 0) + phi_t(X) (T - tm)) + (1 - y phi_w(X)) W,    y = 1 / phi_w(tm, 0),

lies strictly inside W = [-h, h]: then for every t in T the equation phi(t, w) = 0 has exactly one solution w(t)
in W, and it lies in K. phi(tm, 0) + phi_t(X) (T - tm) encloses phi(t, 0) for every t in T (the mean value theorem
along the centre line), and 1 - y phi_w(X) the derivative of w - y phi(t, w), so K is the Krawczyk operator of the
one-variable equation at every t at once. The level inside X is then the graph of a smooth function w(t) (phi_w
keeps its sign on X): one arc, entering through the face t = t0 and leaving through t = t1.

Where this first-order test fails, the same operator is formed to second order (_operator_second: phi on the centre
line by Taylor's theorem with phi_tt over X, phi_w over X by the mean value theorem from its value at the centre),
which near a tangency of the surfaces, where g's gradient is small and its Hessian is not, is far narrower. A piece
along a chord that fails is tried again centred on the arc (arc_frame: a float Newton step to the level and its
tangent, only a frame: the test alone proves), and, once halved NARROWER_DEPTH times, narrower (a branch may run
close beside the arc).

Two pieces are linked when the point where the first one's arc leaves it (t = t1, its w enclosed by the same test
on that single cross-section, with a W inside the piece's: exit_enclosure) lies strictly inside the second: the
first piece's arc passes into the second's, so the union of a linked chain is one connected arc; a chain whose
last piece links to its first (shifted by the loop's period) is a whole closed component.

All enclosures round outward (spatialkin.kernels.geometry.interval), so round-off cannot make a piece pass.

References
----------
R. Krawczyk, "Newton-Algorithmen zur Bestimmung von Nullstellen mit Fehlerschranken", Computing 4 (1969) 187-201.
B. Martin, A. Goldsztejn, L. Granvilliers, C. Jermann, "Certified parallelotope continuation for one-manifolds",
SIAM J. Numer. Anal. 51(6) (2013) 3373-3401: pieces on which the manifold is a graph over the tangent coordinate,
proven by a Krawczyk test with that coordinate as a parameter, and chained by inclusion of their exit faces.
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, ch. 8.
"""
import math

import numpy as np

from ..._lib.jit import jit
from ..geometry.interval import (EPS, box_trig, iadd, idiv, idot, implicit_jet, imul, intersect, iscale, ishift,
                                 isqr, isub, jet, jet_first, local_first, mag, placed, point, widen)

#: Columns of a piece: centre (cu, cv), direction (p, q), T = [t0, t1], h, the enclosure [k0, k1] of w where the
#: arc leaves the piece (at t = t1), and the index of the chord it lies along.
CU, CV, P, Q, T0, T1, H, K0, K1, CHORD = range(10)
WIDTH = 10
#: Overlap of consecutive pieces along a chord, as a fraction of the piece's length.
OVERLAP = 0.125
#: Tries of the half-width h (each from the last K) before the piece is split.
H_TRIES = 4
#: Before a failing piece is split again, it is tried this many times more with its half-width divided by NARROWER
#: each time (down to the floor): a piece as long but narrow enough to leave out a branch close beside the arc (two
#: rulings of a plane nearly tangent to a cylinder), where halving its length would need thousands of pieces ...
NARROWER_TRIES, NARROWER = 3, 64.0
#: ... once it has been halved this many times (a piece that fails only for its length passes before).
NARROWER_DEPTH = 3
#: A failing piece along a chord is tried again centred on the arc (arc_frame: at most ARC_NEWTON float Newton
#: steps, settled when a step is below ARC_SETTLED of the piece's length).
ARC_NEWTON, ARC_SETTLED = 6, 1e-9
#: The exit enclosure's first half-width, as a fraction of the piece's, and its growth.
EXIT_FIRST, EXIT_GROWTH = 1e-6, 16.0
#: Most Krawczyk iterations narrowing an arc's enclosure on a stretch of a piece.
ARC_ITERATIONS = 6
#: Deepest halving of a chord's pieces.
MAX_DEPTH = 24
#: Outcome of a chain: proven, or where it failed.
PROVEN, PIECE_FAILED, LINK_FAILED, BUDGET = 0, 1, 2, 3


@jit
def _span(cu, cv, p, q, T, W):
    """(xu, xv): the scaled parameter intervals of the parallelogram c + T a + W n."""
    xu = iadd(iadd(point(cu), iscale(T, p)), iscale(W, -q))
    xv = iadd(iadd(point(cv), iscale(T, q)), iscale(W, p))
    return xu, xv


@jit(forceinline=True)
def _hull(cu, cv, p, q, T, W, su, sv):
    """(U, V): the raw parameter intervals of the parallelogram c + T a + W n (scaled by su, sv)."""
    xu, xv = _span(cu, cv, p, q, T, W)
    return iscale(xu, su), iscale(xv, sv)


@jit(forceinline=True)
def piece_span(piece):
    """(xu, xv): the scaled parameter intervals of the piece's parallelogram."""
    return _span(piece[CU], piece[CV], piece[P], piece[Q], (piece[T0], piece[T1]), (-piece[H], piece[H]))


@jit
def piece_box(piece, su, sv):
    """(U, V): the raw parameter intervals of the piece's parallelogram (scaled by su, sv)."""
    return stretch_box(piece, piece[T0], piece[T1], (-piece[H], piece[H]), su, sv)


@jit
def stretch_box(piece, t0, t1, W, su, sv):
    """(U, V): the raw parameter intervals of the parallelogram c + [t0, t1] a + W n of the piece's frame."""
    return _hull(piece[CU], piece[CV], piece[P], piece[Q], (t0, t1), W, su, sv)


@jit(forceinline=True)
def _in_frame(piece, xu, xv):
    """(t, w): enclosures of the coordinates in the piece's frame (c + t a + w n) of the scaled point intervals."""
    ru = ishift(xu, -piece[CU])
    rv = ishift(xv, -piece[CV])
    p2, q2 = piece[P], piece[Q]
    norm = iadd(imul(point(p2), point(p2)), imul(point(q2), point(q2)))
    t = idiv(iadd(iscale(ru, p2), iscale(rv, q2)), norm)
    w = idiv(iadd(iscale(ru, -q2), iscale(rv, p2)), norm)
    return t, w


@jit(forceinline=True)
def _strictly_in(piece, t, w):
    """True when the frame coordinates (t, w) lie strictly inside the piece (t in T, w in W)."""
    return piece[T0] < t[0] and t[1] < piece[T1] and -piece[H] < w[0] and w[1] < piece[H]


@jit(forceinline=True)
def _operator(s_data, t_data, m, c, pad, cpad, su, sv, cu, cv, p, q, T, tm, gc, y, h):
    """(K, |1 - y phi_w(X)|): the Krawczyk operator of the piece with W = [-h, h]."""
    return _operator_on(s_data, t_data, m, c, pad, cpad, su, sv, cu, cv, p, q, T, tm, gc, y, (-h, h), 0.0)


@jit(forceinline=True)
def _operator_on(s_data, t_data, m, c, pad, cpad, su, sv, cu, cv, p, q, T, tm, gc, y, W, wm):
    """(K, |1 - y phi_w(X)|): the Krawczyk operator of the parallelogram X = c + T a + W n centred on (tm, wm) in
    W (gc = phi(tm, wm)): K = wm - y (phi(tm, wm) + phi_t(X) (T - tm)) + (1 - y phi_w(X)) (W - wm)."""
    U, V = _hull(cu, cv, p, q, T, W, su, sv)
    g, gu, gv = jet_first(s_data, t_data, m, c, pad, cpad, U, V, box_trig(s_data, U, V))[0]
    d_t = iadd(iscale(gu, p * su), iscale(gv, q * sv))
    d_w = iadd(iscale(gu, -q * su), iscale(gv, p * sv))
    value = iadd(gc, imul(d_t, isub(T, point(tm))))
    contraction = isub((1.0, 1.0), iscale(d_w, y))
    K = iadd(iscale(value, -y), imul(contraction, isub(W, point(wm))))
    return ishift(K, wm), mag(contraction)


@jit(forceinline=True)
def frame_hessian(guu, guv, gvv, p, q, su, sv):
    """(phi_tt, phi_tw, phi_ww): g's second derivatives (raw parameters) along a = (p, q) and n = (-q, p) of a
    piece's frame in scaled parameters, each product made one factor at a time (p su, q sv are exact: su and sv
    are powers of two; their products would round)."""
    au, av, nu, nv = p * su, q * sv, -q * su, p * sv
    d_tt = iadd(iadd(iscale(iscale(guu, au), au), iscale(iscale(guv, au), 2.0 * av)), iscale(iscale(gvv, av), av))
    d_tw = iadd(iadd(iscale(iscale(guu, au), nu), iadd(iscale(iscale(guv, au), nv), iscale(iscale(guv, av), nu))),
                iscale(iscale(gvv, av), nv))
    d_ww = iadd(iadd(iscale(iscale(guu, nu), nu), iscale(iscale(guv, nu), 2.0 * nv)), iscale(iscale(gvv, nv), nv))
    return d_tt, d_tw, d_ww


@jit
def _operator_second(s_data, t_data, m, c, pad, cpad, su, sv, cu, cv, p, q, T, tm, gc, y, h):
    """(K, |1 - y phi_w(X)|) as _operator (W = [-h, h], centred on (tm, 0)), its enclosures of phi over the centre
    line and of phi_w over X taken to second order where that is narrower: phi(t, 0) in phi(tm, 0) + phi_t(tm, 0)
    (t - tm) + phi_tt(X) (t - tm)^2 / 2, and phi_w(X) in phi_w(tm, 0) + phi_tw(X) (T - tm) + phi_ww(X) W (the mean
    value theorem; each met with the first-order enclosure). Along a level whose gradient is small beside a close
    branch (surfaces nearly touching), the first-order enclosures grow with the width of g's Hessian over X times the
    piece's length, far beyond the gradient itself; these only with its variation along the arc."""
    W = (-h, h)
    U, V = _hull(cu, cv, p, q, T, W, su, sv)
    g, gu, gv, guu, guv, gvv = jet(s_data, t_data, m, c, pad, cpad, U, V)
    Uc, Vc = _hull(cu, cv, p, q, point(tm), (0.0, 0.0), su, sv)
    _, cu_, cv_ = jet_first(s_data, t_data, m, c, pad, cpad, Uc, Vc, box_trig(s_data, Uc, Vc))[0]
    au, av, nu, nv = p * su, q * sv, -q * su, p * sv          # d/dt and d/dw in raw parameters
    d_t = iadd(iscale(gu, au), iscale(gv, av))
    d_w = iadd(iscale(gu, nu), iscale(gv, nv))
    dc_t = iadd(iscale(cu_, au), iscale(cv_, av))
    dc_w = iadd(iscale(cu_, nu), iscale(cv_, nv))
    d_tt, d_tw, d_ww = frame_hessian(guu, guv, gvv, p, q, su, sv)
    dT = isub(T, point(tm))
    first = iadd(gc, imul(d_t, dT))
    second = iadd(iadd(gc, imul(dc_t, dT)), iscale(imul(d_tt, isqr(dT)), 0.5))
    value = intersect(first, second)
    slope = intersect(d_w, iadd(iadd(dc_w, imul(d_tw, dT)), imul(d_ww, W)))
    contraction = isub((1.0, 1.0), iscale(slope, y))
    return iadd(iscale(value, -y), imul(contraction, W)), mag(contraction)


@jit
def centred_level(s_data, t_data, m, c, pad, cpad, U, V):
    """An enclosure of g over a (near-)point box U x V in the centred form F_T(q~) + grad F_T(Q) . (Q - q~), Q
    the enclosure of the point in T's frame and q~ its midpoint: near a tangency, where g is a small difference of
    large terms, it is several times narrower than F_T(Q) (the width of Q times |grad F_T| instead of the spread
    of every term)."""
    x = local_first(s_data, U, V, box_trig(s_data, U, V))[0]
    q = placed(m, c, x, pad, cpad)
    mid = (point(0.5 * (q[0][0] + q[0][1])), point(0.5 * (q[1][0] + q[1][1])), point(0.5 * (q[2][0] + q[2][1])))
    f_mid = implicit_jet(t_data, mid)[0]
    naive, grad, _ = implicit_jet(t_data, q)
    centred = iadd(f_mid, idot(grad, (isub(q[0], mid[0]), isub(q[1], mid[1]), isub(q[2], mid[2]))))
    return max(naive[0], centred[0]), min(naive[1], centred[1])


@jit(forceinline=True)
def _passes(K, h):
    return K[0] > -h and K[1] < h and math.isfinite(K[0]) and math.isfinite(K[1])


@jit
def prove_piece(s_data, t_data, m, c, pad, cpad, su, sv, cu, cv, p, q, t0, t1, h, out):
    """Krawczyk test of one piece (see the module docstring), trying up to H_TRIES half-widths from h; True with
    the piece written to out (WIDTH,) when one passes."""
    T = (t0, t1)
    tm = 0.5 * (t0 + t1)
    # phi at the centre of the piece, and the preconditioner y from its w-derivative there
    Uc, Vc = _hull(cu, cv, p, q, point(tm), (0.0, 0.0), su, sv)
    _, gcu, gcv = jet_first(s_data, t_data, m, c, pad, cpad, Uc, Vc, box_trig(s_data, Uc, Vc))[0]
    gc = centred_level(s_data, t_data, m, c, pad, cpad, Uc, Vc)
    dw_mid = 0.5 * (gcu[0] + gcu[1]) * (-q * su) + 0.5 * (gcv[0] + gcv[1]) * (p * sv)
    if not (dw_mid != 0.0 and math.isfinite(dw_mid)):
        return False
    y = 1.0 / dw_mid
    for _ in range(H_TRIES):
        K, contraction = _operator(s_data, t_data, m, c, pad, cpad, su, sv, cu, cv, p, q, T, tm, gc, y, h)
        if not _passes(K, h):
            K2, contraction2 = _operator_second(s_data, t_data, m, c, pad, cpad, su, sv, cu, cv, p, q, T, tm, gc, y,
                                                h)
            if _passes(K2, h) or max(abs(K2[0]), abs(K2[1])) < max(abs(K[0]), abs(K[1])):
                K, contraction = K2, contraction2
        if _passes(K, h):
            out[CU], out[CV], out[P], out[Q] = cu, cv, p, q
            out[T0], out[T1], out[H], out[K0], out[K1] = t0, t1, h, K[0], K[1]
            return True
        spread = max(abs(K[0]), abs(K[1]))
        if not (math.isfinite(spread) and contraction < 1.0):
            return False
        h = 2.0 * spread if spread > 0.5 * h else h
    return False


@jit
def arc_enclosure(s_data, t_data, m, c, pad, cpad, su, sv, piece, t0, t1):
    """(lo, hi): an enclosure of w(t) for t in [t0, t1] (inside the piece's T), w(t) the proven piece's arc: the
    Krawczyk operator on that stretch, first with the piece's W, then with its last value met with the last W (the
    operator holds every zero in the interval it is given; each is centred on its interval's midpoint), while that
    halves the width, up to ARC_ITERATIONS times."""
    tm = 0.5 * (t0 + t1)
    h = piece[H]
    Uc, Vc = _hull(piece[CU], piece[CV], piece[P], piece[Q], point(tm), (0.0, 0.0), su, sv)
    _, gcu, gcv = jet_first(s_data, t_data, m, c, pad, cpad, Uc, Vc, box_trig(s_data, Uc, Vc))[0]
    dw_mid = 0.5 * (gcu[0] + gcu[1]) * (-piece[Q] * su) + 0.5 * (gcv[0] + gcv[1]) * (piece[P] * sv)
    if not (dw_mid != 0.0 and math.isfinite(dw_mid)):
        return -h, h
    lo, hi = -h, h
    for _ in range(ARC_ITERATIONS):
        wm = 0.5 * (lo + hi)
        Um, Vm = _hull(piece[CU], piece[CV], piece[P], piece[Q], point(tm), point(wm), su, sv)
        gm = centred_level(s_data, t_data, m, c, pad, cpad, Um, Vm)
        K, _ = _operator_on(s_data, t_data, m, c, pad, cpad, su, sv, piece[CU], piece[CV], piece[P], piece[Q],
                            (t0, t1), tm, gm, 1.0 / dw_mid, (lo, hi), wm)
        if not (math.isfinite(K[0]) and math.isfinite(K[1])):
            break
        narrower = max(K[0], lo), min(K[1], hi)
        shrunk = (narrower[1] - narrower[0]) < 0.5 * (hi - lo)
        lo, hi = narrower
        if not shrunk:
            break
    return lo, hi


@jit
def exit_enclosure(s_data, t_data, m, c, pad, cpad, su, sv, piece):
    """Narrow the piece's [k0, k1] to an enclosure of w where its arc leaves it (t = t1): the Krawczyk test on the
    single cross-section t = t1 with W from EXIT_FIRST of the piece's h, growing, inside the piece's W (so the zero
    it proves is the arc's, unique there); False when none passes."""
    h_piece = piece[H]
    h = EXIT_FIRST * h_piece
    scratch = np.empty(WIDTH)
    while h < h_piece:
        if prove_piece(s_data, t_data, m, c, pad, cpad, su, sv, piece[CU], piece[CV], piece[P], piece[Q], piece[T1],
                       piece[T1], h, scratch) and scratch[H] < h_piece:
            piece[K0], piece[K1] = scratch[K0], scratch[K1]
            return True
        h *= EXIT_GROWTH
    return False


@jit
def _shifted(x, shift):
    """x + shift for a float period shift (a multiple of the float 2 pi / unit), widened for the float period's
    own error (2 pi rounds to within 2.5e-16 of the true one)."""
    if shift == 0.0:
        return x
    return widen(ishift(x, shift), 4.0 * EPS * abs(shift))


@jit
def linked(first, second, shift_u, shift_v):
    """True when the exit of piece `first` (t = t1, w in [k0, k1]), shifted by (shift_u, shift_v) (scaled
    coordinates: a period of the loop, or zero), lies strictly inside piece `second`."""
    eu, ev = _span(first[CU], first[CV], first[P], first[Q], point(first[T1]), (first[K0], first[K1]))
    t, w = _in_frame(second, _shifted(eu, shift_u), _shifted(ev, shift_v))
    return _strictly_in(second, t, w)


@jit
def arc_frame(s_data, t_data, m, c, pad, cpad, su, sv, xu, xv, p, q, span):
    """(found, cu, cv, p, q): the point of the level g = 0 on the line through (xu, xv) along n = (-q, p) (float
    Newton from it, at most ARC_NEWTON steps, within span of it) and the unit tangent of the level there, turned
    towards (p, q); found False where Newton does not settle. Only a frame for a piece to be proven: nothing here
    is a proof."""
    w = 0.0
    for _ in range(ARC_NEWTON):
        cu, cv = xu - w * q, xv + w * p
        U, V = point(cu * su), point(cv * sv)
        g, gu, gv = jet_first(s_data, t_data, m, c, pad, cpad, U, V, box_trig(s_data, U, V))[0]
        du, dv = 0.5 * (gu[0] + gu[1]) * su, 0.5 * (gv[0] + gv[1]) * sv        # (the gradient, scaled)
        d_w = -q * du + p * dv
        if not (d_w != 0.0 and math.isfinite(d_w)):
            return False, xu, xv, p, q
        step = 0.5 * (g[0] + g[1]) / d_w
        w -= step
        if not (abs(w) < span):
            return False, xu, xv, p, q
        if abs(step) <= ARC_SETTLED * span:
            norm = math.hypot(du, dv)
            tp, tq = dv / norm, -du / norm
            if tp * p + tq * q < 0.0:
                tp, tq = -tp, -tq
            return True, xu - w * q, xv + w * p, tp, tq
    return False, xu, xv, p, q


@jit
def tube_chain(s_data, t_data, m, c, pad, cpad, su, sv, x, closed, shift_u, shift_v, h_floor, max_pieces, pieces):
    """Prove a chain of linked pieces along the polyline x (N, 2) of scaled parameters (consecutive points of one
    curve; for a closed curve the last point is the first shifted by (shift_u, shift_v)), each chord covered by
    one piece or by halves of it (down to MAX_DEPTH), consecutive pieces overlapping by OVERLAP of their length.

    Returns (pieces written to pieces (max_pieces, WIDTH), status (PROVEN, PIECE_FAILED, LINK_FAILED, BUDGET), the
    index of the chord where it failed (-1 when proven), the pieces tried (proven or not: the work done)).
    """
    n = x.shape[0]
    count = 0
    tries = 0
    stack = np.empty((MAX_DEPTH + 2, 2))
    for k in range(n - 1):
        du = x[k + 1, 0] - x[k, 0]
        dv = x[k + 1, 1] - x[k, 1]
        length = math.sqrt(du * du + dv * dv)
        if length == 0.0:
            continue
        p, q = du / length, dv / length
        stack[0, 0], stack[0, 1] = length, 0.0
        top = 1
        start = 0.0
        while top > 0:
            top -= 1
            end = stack[top, 0]
            depth = stack[top, 1]
            span = end - start
            pad_t = OVERLAP * span
            if count >= max_pieces:
                return count, BUDGET, k, tries
            h = max(h_floor, 0.25 * span)
            tries += 1
            ok = prove_piece(s_data, t_data, m, c, pad, cpad, su, sv, x[k, 0], x[k, 1], p, q, start - pad_t,
                             end + pad_t, h, pieces[count])
            if not ok:      # the same stretch on the arc itself: centred on it, along its tangent
                tm = 0.5 * (start + end)
                found, ac_u, ac_v, ap, aq = arc_frame(s_data, t_data, m, c, pad, cpad, su, sv, x[k, 0] + tm * p,
                                                      x[k, 1] + tm * q, p, q, span)
                half = 0.5 * span + pad_t
                if found:
                    tries += 1
                    ok = prove_piece(s_data, t_data, m, c, pad, cpad, su, sv, ac_u, ac_v, ap, aq, -half, half, h,
                                     pieces[count])
                for _ in range(NARROWER_TRIES if found and depth >= NARROWER_DEPTH else 0):
                    if ok or h <= h_floor:      # (narrower, as long: another branch may run close beside this one)
                        break
                    h = max(h_floor, h / NARROWER)
                    tries += 1
                    ok = prove_piece(s_data, t_data, m, c, pad, cpad, su, sv, ac_u, ac_v, ap, aq, -half, half, h,
                                     pieces[count])
            if not ok:
                if depth >= MAX_DEPTH:
                    return count, PIECE_FAILED, k, tries
                mid = 0.5 * (start + end)
                stack[top, 0], stack[top, 1] = end, depth + 1
                stack[top + 1, 0], stack[top + 1, 1] = mid, depth + 1
                top += 2
                continue
            if not exit_enclosure(s_data, t_data, m, c, pad, cpad, su, sv, pieces[count]):
                return count, PIECE_FAILED, k, tries
            if count > 0 and not linked(pieces[count - 1], pieces[count], 0.0, 0.0):
                return count, LINK_FAILED, k, tries
            pieces[count, CHORD] = k
            count += 1
            start = end
    if count == 0:
        return 0, PIECE_FAILED, 0, tries
    if closed and not linked(pieces[count - 1], pieces[0], -shift_u, -shift_v):
        return count, LINK_FAILED, n - 2, tries
    return count, PROVEN, -1, tries


@jit
def pieces_overlap(first, second, shift_u, shift_v):
    """False when the two pieces (the second shifted by (shift_u, shift_v)) are proven disjoint: a corner-free
    separating axis (one of the four edge normals) parts their parallelograms, in interval arithmetic."""
    for which in range(2):
        ref = first if which == 0 else second
        for axis in range(2):
            # the separating axis: ref's a (axis 0) or n (axis 1)
            if axis == 0:
                ax_u, ax_v = ref[P], ref[Q]
            else:
                ax_u, ax_v = -ref[Q], ref[P]
            ours = (0.0, 0.0)
            theirs = (0.0, 0.0)
            for side in range(2):
                piece = first if side == 0 else second
                su_ = 0.0 if side == 0 else shift_u
                sv_ = 0.0 if side == 0 else shift_v
                xu, xv = piece_span(piece)
                proj = iadd(iscale(_shifted(xu, su_), ax_u), iscale(_shifted(xv, sv_), ax_v))
                if side == 0:
                    ours = proj
                else:
                    theirs = proj
            if ours[1] < theirs[0] or theirs[1] < ours[0]:
                return False
    return True


@jit
def _turns(delta, period):
    """The whole number of periods nearest to delta (0 when not periodic)."""
    return 0.0 if period == 0.0 else float(round(delta / period))


@jit
def point_in_pieces(pieces, count, box, shift_u, shift_v):
    """Index of a piece that holds the scaled parameter box (u_lo, u_hi, v_lo, v_hi), shifted by whole periods
    (shift_u, shift_v: the periods of u and v, 0 when not periodic; the turns nearest to the piece, and one either
    side), strictly inside (t in T, w in W: a zero of g in the box is then a point of the piece's arc), or -1."""
    for i in range(count):
        piece = pieces[i]
        nu = _turns(piece[CU] - 0.5 * (box[0] + box[1]), shift_u)
        nv = _turns(piece[CV] - 0.5 * (box[2] + box[3]), shift_v)
        for ku in range(-1, 2):
            if shift_u == 0.0 and ku != 0:
                continue
            for kv in range(-1, 2):
                if shift_v == 0.0 and kv != 0:
                    continue
                t, w = _in_frame(piece, _shifted((box[0], box[1]), (nu + ku) * shift_u),
                                 _shifted((box[2], box[3]), (nv + kv) * shift_v))
                if _strictly_in(piece, t, w):
                    return i
    return -1


@jit
def spaced(x, share, keep):
    """Indices (into keep (M,), returning how many) of the rows of x (M, 2) kept as a chain's samples: a row
    closer than share times the median chord to the last kept one is dropped, the last row always kept (in place of
    the one before it when that one is too close)."""
    n = x.shape[0]
    floor = 0.0
    if n > 1:
        chords = np.empty(n - 1)
        for i in range(n - 1):
            chords[i] = math.hypot(x[i + 1, 0] - x[i, 0], x[i + 1, 1] - x[i, 1])
        floor = share * np.median(chords)
    keep[0] = 0
    count = 1
    for i in range(1, n):
        j = keep[count - 1]
        du = x[i, 0] - x[j, 0]
        dv = x[i, 1] - x[j, 1]
        if math.sqrt(du * du + dv * dv) >= floor:
            keep[count] = i
            count += 1
    if keep[count - 1] != n - 1:
        if count > 1:
            keep[count - 1] = n - 1
        else:
            keep[count] = n - 1
            count += 1
    return count


@jit
def _piece_hull(piece):
    """(u lo, u hi, v lo, v hi): an enclosure of the piece's parallelogram (scaled parameters)."""
    xu, xv = piece_span(piece)
    return xu[0], xu[1], xv[0], xv[1]


#: Consecutive pieces of a chain grouped under one hull in tubes_disjoint (a chain's pieces lie along it, so a
#: group's hull is tight and pairs of groups far apart are dismissed without looking at their pieces).
GROUP = 32


@jit
def _group_hulls(pieces):
    """(G, 4): the hulls (u lo, u hi, v lo, v hi) of the pieces' hulls, GROUP consecutive pieces each; and
    (P, 4) the pieces' own hulls."""
    n = pieces.shape[0]
    own = np.empty((n, 4))
    groups = np.empty(((n + GROUP - 1) // GROUP, 4))
    for i in range(n):
        own[i, 0], own[i, 1], own[i, 2], own[i, 3] = _piece_hull(pieces[i])
        g = i // GROUP
        if i % GROUP == 0:
            groups[g] = own[i]
        else:
            groups[g, 0], groups[g, 2] = min(groups[g, 0], own[i, 0]), min(groups[g, 2], own[i, 2])
            groups[g, 1], groups[g, 3] = max(groups[g, 1], own[i, 1]), max(groups[g, 3], own[i, 3])
    return groups, own


@jit
def _turn_range(lo, hi, other_lo, other_hi, period):
    """(first, last) whole numbers of periods k for which [other_lo, other_hi] + k period may meet [lo, hi], one
    more either side (the division's rounding; _apart then decides each); (0, 0) when not periodic."""
    if period == 0.0:
        return 0, 0
    return int(math.ceil((lo - other_hi) / period)) - 1, int(math.floor((hi - other_lo) / period)) + 1


@jit
def _apart(a, b, su, sv):
    """True when the hull a (4,) and the hull b (4,) shifted by (su, sv) are apart (with the shifted bounds'
    rounding, far below any gap that matters)."""
    slack_u = 8.0 * EPS * (abs(su) + abs(a[0]) + abs(a[1])) + 1e-300
    slack_v = 8.0 * EPS * (abs(sv) + abs(a[2]) + abs(a[3])) + 1e-300
    return (b[1] + su + slack_u < a[0] or a[1] < b[0] + su - slack_u or
            b[3] + sv + slack_v < a[2] or a[3] < b[2] + sv - slack_v)


@jit
def tubes_disjoint(first, second, periods):
    """(-1, -1) when every piece of first (K, WIDTH) is proven disjoint from every piece of second (L, WIDTH),
    the second shifted by any whole number of periods (periods (2,): of u and v, 0 when not periodic); else the
    indices of a pair that may overlap. Groups of GROUP consecutive pieces whose hulls are apart under a shift
    are disjoint under it; within groups that may meet, pairs whose hulls are apart are disjoint, and the rest
    are decided by pieces_overlap. Every shift under which two groups' hulls may meet is tried."""
    groups_a, own_a = _group_hulls(first)
    groups_b, own_b = _group_hulls(second)
    for ga in range(groups_a.shape[0]):
        a = groups_a[ga]
        for gb in range(groups_b.shape[0]):
            b = groups_b[gb]
            ku0, ku1 = _turn_range(a[0], a[1], b[0], b[1], periods[0])
            kv0, kv1 = _turn_range(a[2], a[3], b[2], b[3], periods[1])
            for ku in range(ku0, ku1 + 1):
                su = ku * periods[0]
                for kv in range(kv0, kv1 + 1):
                    sv = kv * periods[1]
                    if _apart(a, b, su, sv):
                        continue
                    for i in range(ga * GROUP, min((ga + 1) * GROUP, first.shape[0])):
                        for j in range(gb * GROUP, min((gb + 1) * GROUP, second.shape[0])):
                            if not _apart(own_a[i], own_b[j], su, sv) and pieces_overlap(first[i], second[j],
                                                                                          su, sv):
                                return i, j
    return -1, -1
