"""Singular points of the level g = F_T(S(u, v)) = 0 in S's (scaled) parameter plane: an isolated critical point of
g proven by the Krawczyk operator of grad g = 0, and the ball round it that holds all of the level nearby.

If the box B = c +- h holds exactly one zero c* of grad g (the Krawczyk test with the Hessian's enclosure over B)
and the Hessian is definite over B, g is strictly convex (or concave) on B: |g(x) - g(c*)| >= lambda |x - c*|^2 / 2
with lambda >= det / trace a lower bound of its smallest eigenvalue magnitude, so every zero of g in B lies within
sqrt(2 |g(c*)| / lambda) of c*. When that radius (plus c*'s offset from c) is below h, the level inside B is a point,
a loop inside that ball, or nothing: which one cannot be decided in floating point (g(c*) = 0 is an equality), but
nothing else of the intersection comes near. A Hessian of negative determinant over B makes c* a saddle (a node or
two branches passing close): only its uniqueness is proven here; sign_on_segment proves g free of zeros along a
segment (across a saddle's box: the branches pass close, spatialkin.tracing.certify.nodes).

References
----------
R. Krawczyk, "Newton-Algorithmen zur Bestimmung von Nullstellen mit Fehlerschranken", Computing 4 (1969) 187-201.
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, ch. 8.
"""
import math

from ..._lib.jit import jit
from ..geometry.interval import (box_trig, iadd, imul, intersect, iscale, isub, jet, jet_first, krawczyk_row,
                                 local_first, mag, point, widen)

#: Most pieces sign_on_segment splits a segment into.
SEGMENT_BOXES = 4096

#: Outcomes: no box passed; a unique critical point, a saddle over its box; a unique extremum isolated in its box
#: (the level within the ball); an extremum whose ball reaches the box's edge.
NONE, SADDLE, ISOLATED, EXTREMUM = 0, 1, 2, 3


@jit(forceinline=True)
def _scaled_jet(s_data, t_data, m, c, pad, cpad, su, sv, U, V):
    """(g, g_u, g_v, g_uu, g_uv, g_vv) over the raw box U x V, derivatives in scaled parameters."""
    g, gu, gv, guu, guv, gvv = jet(s_data, t_data, m, c, pad, cpad, U, V)
    return (g, iscale(gu, su), iscale(gv, sv), iscale(guu, su * su), iscale(guv, su * sv), iscale(gvv, sv * sv))


@jit
def critical_ball(s_data, t_data, m, c, pad, cpad, su, sv, cu, cv, h0, cap, out):
    """Try boxes (cu, cv) +- h (scaled; h from h0 growing eightfold up to cap) for a proven critical point of g.
    out (3,) = (h, the radius of the ball round (cu, cv) holding the level within the box (scaled; inf unless
    ISOLATED), an upper bound of |dS/dx| over the box (length per scaled unit)). Returns NONE, SADDLE, ISOLATED or
    EXTREMUM."""
    out[0], out[1], out[2] = math.inf, math.inf, math.inf
    Uc, Vc = (cu * su, cu * su), (cv * sv, cv * sv)
    gc, guc, gvc, guuc, guvc, gvvc = _scaled_jet(s_data, t_data, m, c, pad, cpad, su, sv, Uc, Vc)
    a, b, d = 0.5 * (guuc[0] + guuc[1]), 0.5 * (guvc[0] + guvc[1]), 0.5 * (gvvc[0] + gvvc[1])
    det = a * d - b * b
    if det == 0.0 or not math.isfinite(det):
        return NONE
    y00, y01, y10, y11 = d / det, -b / det, -b / det, a / det
    result = NONE
    h = h0
    while h <= cap:
        B = (-h, h)
        U = iscale(iadd(point(cu), B), su)
        V = iscale(iadd(point(cv), B), sv)
        g, gu, gv, guu, guv, gvv = _scaled_jet(s_data, t_data, m, c, pad, cpad, su, sv, U, V)
        ok = True
        offset = 0.0
        for row in range(2):
            ya, yb = (y00, y01) if row == 0 else (y10, y11)
            k = krawczyk_row(ya, yb, 0.0, guc, gvc, guu, guv, guv, gvv, B, B, row)     # (centred: K - c)
            if not (-h < k[0] and k[1] < h):
                ok = False
            offset = max(offset, mag(k))
        if ok:
            out[0] = h
            _, s_u, s_v, _ = local_first(s_data, U, V, box_trig(s_data, U, V))
            speed = 0.0
            for i in range(3):
                speed += mag(s_u[i]) * mag(s_u[i]) * su * su + mag(s_v[i]) * mag(s_v[i]) * sv * sv
            out[2] = math.sqrt(speed) * (1.0 + 1e-15)
            det_b = isub(imul(guu, gvv), imul(guv, guv))
            if det_b[1] < 0.0:
                return SADDLE
            if det_b[0] <= 0.0 or guu[0] <= 0.0 <= guu[1]:
                return result
            trace = mag(iadd(guu, gvv))
            lam = det_b[0] / trace * (1.0 - 1e-15)
            # g(c*) for c* in the Krawczyk box: g over the box c +- offset
            W = (-offset, offset)
            gk = _scaled_jet(s_data, t_data, m, c, pad, cpad, su, sv, iscale(iadd(point(cu), W), su),
                             iscale(iadd(point(cv), W), sv))[0]
            radius = math.sqrt(2.0 * mag(gk) / lam) * (1.0 + 1e-15) + offset * 1.4143
            if radius < h:
                out[1] = radius
                return ISOLATED
            result = EXTREMUM               # the ball reaches the box's edge: a larger box may hold it
        h *= 8.0
    return result


@jit(forceinline=True)
def _segment_enclosure(s_data, t_data, m, c, pad, cpad, su, sv, au, av, bu, bv, t0, t1):
    """Enclosure of g over the box hull (raw parameters) of the points a + t (b - a), t in [t0, t1], of the
    scaled segment from a to b: the natural enclosure met with the mean-value form about the hull's centre."""
    pu0, pu1 = au + t0 * (bu - au), au + t1 * (bu - au)
    pv0, pv1 = av + t0 * (bv - av), av + t1 * (bv - av)
    slack_u = 4e-16 * (abs(au) + abs(bu - au)) + 1e-300
    slack_v = 4e-16 * (abs(av) + abs(bv - av)) + 1e-300
    U = iscale(widen((min(pu0, pu1), max(pu0, pu1)), slack_u), su)
    V = iscale(widen((min(pv0, pv1), max(pv0, pv1)), slack_v), sv)
    g, gu, gv = jet_first(s_data, t_data, m, c, pad, cpad, U, V, box_trig(s_data, U, V))[0]
    um, vm = 0.5 * (U[0] + U[1]), 0.5 * (V[0] + V[1])
    Um, Vm = (um, um), (vm, vm)
    gm = jet_first(s_data, t_data, m, c, pad, cpad, Um, Vm, box_trig(s_data, Um, Vm))[0][0]
    form = iadd(gm, iadd(imul(gu, isub(U, Um)), imul(gv, isub(V, Vm))))
    both = intersect(g, form)
    return both if both[0] <= both[1] else g


@jit
def sign_on_segment(s_data, t_data, m, c, pad, cpad, su, sv, au, av, bu, bv, max_boxes):
    """+1 or -1 when g is proven to keep that sign along the whole segment from a = (au, av) to b = (bu, bv) in
    scaled parameters (every point a + t (b - a), t in [0, 1], in exact arithmetic), else 0. The segment is split
    into pieces (bisection of t, from a on) until each piece's enclosure of g (_segment_enclosure) excludes 0; 0 as
    soon as a piece can be split no further or max_boxes pieces have been tried."""
    stack = [(0.0, 1.0)]
    sign = 0
    tried = 0
    while len(stack):
        t0, t1 = stack.pop()
        tried += 1
        if tried > max_boxes:
            return 0
        g = _segment_enclosure(s_data, t_data, m, c, pad, cpad, su, sv, au, av, bu, bv, t0, t1)
        if g[0] > 0.0 or g[1] < 0.0:
            here = 1 if g[0] > 0.0 else -1
            if sign != 0 and here != sign:
                return 0
            sign = here
            continue
        mid = 0.5 * (t0 + t1)
        if not (t0 < mid < t1):
            return 0
        stack.append((mid, t1))
        stack.append((t0, mid))
    return sign
