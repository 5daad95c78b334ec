"""Certified root isolation for the topology stage: zeros of g = F_T o S on parameter lines (edges and seams),
and the points of the level g = 0 where its tangent is normal to a fixed direction d (extremes of the linear
function d . (u, v) along the level: every closed loop of the level has one).

Both are branch-and-bound subdivisions over boxes of S's parameters. A box is discarded only when an interval
enclosure (spatialkin.kernels.geometry.interval: the natural form, the centred form and, for g in the 2-D search, the
second-order Taylor form) excludes zero, so no root is ever lost; a box is kept as holding exactly one root when
the interval Newton operator (lines) or the Krawczyk operator (the 2 x 2 system) maps it strictly into itself.
Boxes that can be neither discarded nor verified when they reach the minimum width are returned as unresolved
(singular or multiple roots: contacts, nodes, tangencies).

Records are boxes (lo, hi per parameter) with a kind: VERIFIED (exactly one simple root inside) or UNRESOLVED.

The searches read g in stages (spatialkin.kernels.geometry.interval: level, jet_first, jet_second, inlined into them): a
box's second derivatives only when its first-order tests leave it in doubt, those at its midpoint only for the
Krawczyk test; a bisected box's children reuse its sines and cosines on the side not cut; the refining Newton
stops once its iterates cycle bit for bit (its last one is then known). None of this changes a bit of what
they compute.

line_search and extremal_search run a search and reduce its records to points in the same call (the refined
roots, then the unresolved boxes' centres); line_on_level, level_max, flat_fraction and keep_points do the stage's
per-point tests of many points in one call (the same bits as one point at a time: tests/spatialkin/tracing/
test_topology_batched.py keeps the scalar oracle).

References
----------
R. Krawczyk, Newton-Algorithmen zur Bestimmung von Nullstellen mit Fehlerschranken, Computing 4 (1969).
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, ch. 8.
"""

import math

import numpy as np

from ..._lib.jit import jit
from ..geometry.interval import (box_trig, contains_zero, down, iadd, imul, intersect, iscale, isqr, isub, jet, jet_first,
                       jet_second, krawczyk_row, level, mag, point, u_trig, up, v_trig)
from ..geometry.surfaces import evaluate, inverse_local, to_local

VERIFIED, UNRESOLVED = 1, 2
#: Status of a search: completed, or stopped short (the result is then not a proof): at its box budget, with its
#: record of roots and unresolved boxes full, or with its box stack full.
DONE, OVERFLOW, RECORDS_FULL, STACK_FULL = 0, -1, -2, -3
#: Status of a line search that found the whole line on the level (line_search with probes): not searched.
WHOLE_LINE = 1
#: A contracted box is searched again (rather than bisected) when each side shrank to this fraction or less.
CONTRACTION = 0.7
#: Depth of the explicit box stack.
STACK = 4096
#: Below the coarse width a box stops bisecting when g is within round-off of zero at its midpoint and its
#: gradient moves g across the box by less than FLAT times that round-off (a singular point or a multiple
#: root: bisecting cannot separate anything); a regular crossing of the level goes on to a proof.
FLAT = 8.0
#: Boxes are bisected at this fraction of their width, not at the middle: a root at a round number (a symmetric
#: placement's v = 0) would otherwise sit on a bisection point, on the edge of two boxes, and verify in neither.
SPLIT = 0.4860679774997897
#: Newton iterations refining a root inside its verified box.
REFINE_ITER = 30
#: Longest cycle of the refining Newton's iterates looked for: round-off often makes its last bits cycle rather
#: than settle, and an iterate that repeats an earlier one bit for bit fixes the rest of the sequence (the step
#: is a function of the iterate), so its REFINE_ITER-th iterate is known without taking the steps.
CYCLE = 16


@jit(forceinline=True)
def _line_jet(s_data, t_data, m, c, pad, cpad, fixed, value, a, b):
    """(f, f') over [a, b] of f(t) = g on the parameter line (u = t, v = value) if fixed = 1, else (value, t)."""
    if fixed == 1:
        U, V = (a, b), (value, value)
        j = jet_first(s_data, t_data, m, c, pad, cpad, U, V, box_trig(s_data, U, V))[0]
        return j[0], j[1]
    U, V = (value, value), (a, b)
    j = jet_first(s_data, t_data, m, c, pad, cpad, U, V, box_trig(s_data, U, V))[0]
    return j[0], j[2]


@jit
def _recip(d):
    """1 / d for an interval d not containing zero."""
    lo = 1.0 / d[1]
    hi = 1.0 / d[0]
    return down(lo), up(hi)


@jit
def line_roots(s_data, t_data, m, c, pad, cpad, fixed, value, t0, t1, min_width, coarse, max_boxes, out, kinds):
    """Isolate the zeros of g on a parameter line of S over [t0, t1].

    A box narrower than min_width, or narrower than coarse where g at its midpoint is within round-off of zero
    and g' moves it by less than FLAT times that round-off across the box (a multiple root: bisecting cannot
    separate anything), is returned unresolved.

    Returns (number of records written to out (K, 2) and kinds (K,), status (DONE, or the reason it stopped
    short), boxes visited).
    """
    stack = np.empty((STACK, 2))
    top = 0
    stack[0, 0] = t0
    stack[0, 1] = t1
    top = 1
    count = 0
    boxes = 0
    while top > 0:
        top -= 1
        a = stack[top, 0]
        b = stack[top, 1]
        boxes += 1
        if boxes > max_boxes:
            return count, OVERFLOW, boxes
        f_x, d_x = _line_jet(s_data, t_data, m, c, pad, cpad, fixed, value, a, b)
        if not contains_zero(f_x):
            continue
        mid = 0.5 * (a + b)
        f_m, d_m = _line_jet(s_data, t_data, m, c, pad, cpad, fixed, value, mid, mid)
        f_c = iadd(f_m, imul(d_x, isub((a, b), point(mid))))
        if not contains_zero(intersect(f_x, f_c)):
            continue
        if not contains_zero(d_x):
            n = isub(point(mid), imul(f_m, _recip(d_x)))
            if n[0] > a and n[1] < b:
                if count >= out.shape[0]:
                    return count, RECORDS_FULL, boxes
                out[count, 0] = n[0]
                out[count, 1] = n[1]
                kinds[count] = VERIFIED
                count += 1
                continue
            lo = max(n[0], a)
            hi = min(n[1], b)
            if lo > hi:
                continue
            if hi - lo <= CONTRACTION * (b - a):
                if top >= STACK:
                    return count, STACK_FULL, boxes
                stack[top, 0] = lo
                stack[top, 1] = hi
                top += 1
                continue
        flat = contains_zero(f_m) and abs(_mid(d_m)) * (b - a) <= FLAT * (f_m[1] - f_m[0])
        if b - a <= min_width or (b - a <= coarse and flat):
            if count >= out.shape[0]:
                return count, RECORDS_FULL, boxes
            out[count, 0] = a
            out[count, 1] = b
            kinds[count] = UNRESOLVED
            count += 1
            continue
        if top + 2 > STACK:
            return count, STACK_FULL, boxes
        cut = a + SPLIT * (b - a)
        stack[top, 0] = a
        stack[top, 1] = cut
        stack[top + 1, 0] = cut
        stack[top + 1, 1] = b
        top += 2
    return count, DONE, boxes


@jit
def _put(arr, row, U, V, first=0):
    """arr[row, first:first + 4] = (U lo, U hi, V lo, V hi)."""
    arr[row, first] = U[0]
    arr[row, first + 1] = U[1]
    arr[row, first + 2] = V[0]
    arr[row, first + 3] = V[1]


@jit
def _record(out, kinds, count, U, V, kind):
    """Write record `count` (the box U x V and its kind); False when out is full."""
    if count >= out.shape[0]:
        return False
    _put(out, count, U, V)
    kinds[count] = kind
    return True


@jit
def _mid(x):
    return 0.5 * (x[0] + x[1])


@jit
def extremal_points(s_data, t_data, m, c, pad, cpad, du, dv, box, min_width, coarse, max_boxes, out, kinds):
    """Isolate the solutions of g = 0, phi = dv g_u - du g_v = 0 (the level's tangent normal to (du, dv)) in the
    box (u_lo, u_hi, v_lo, v_hi) of S's parameters.

    min_width (2,) is the smallest width per parameter; boxes are bisected along the parameter that spreads g or
    phi most over the box (_cut_u: the smear), among those still wider than min_width; a box within coarse times
    min_width where g at its midpoint is within round-off of zero and its gradient moves g by less than FLAT times
    that across the box is unresolved at once (round-off: bisecting further cannot separate anything). Returns
    (records in out (K, 4) and kinds (K,), status (DONE, or why it stopped short), boxes visited).
    """
    stack = np.empty((STACK, 4))
    # the trig enclosures of a box's U and V (cos lo, hi, sin lo, hi: U's in columns 0-3, V's in 4-7), where
    # known (bit 1: U's, bit 2: V's): a bisected box's children share the side not cut, and its trig
    trig = np.empty((STACK, 8))
    known = np.empty(STACK, dtype=np.int64)
    for i in range(4):
        stack[0, i] = box[i]
    known[0] = 0
    top = 1
    count = 0
    boxes = 0
    while top > 0:
        top -= 1
        U = (stack[top, 0], stack[top, 1])
        V = (stack[top, 2], stack[top, 3])
        boxes += 1
        if boxes > max_boxes:
            return count, OVERFLOW, boxes
        if known[top] & 1:
            cu, su = (trig[top, 0], trig[top, 1]), (trig[top, 2], trig[top, 3])
        else:
            cu, su = u_trig(s_data, U)
        if known[top] & 2:
            cv, sv = (trig[top, 4], trig[top, 5]), (trig[top, 6], trig[top, 7])
        else:
            cv, sv = v_trig(s_data, V)
        # the jets in two stages: the second derivatives only for the boxes the first-order tests keep (over
        # the box), and that reach the Krawczyk test (at the midpoint)
        (g, gu, gv), box_state = jet_first(s_data, t_data, m, c, pad, cpad, U, V, (cu, su, cv, sv))
        if not contains_zero(g):
            continue
        phi = isub(iscale(gu, dv), iscale(gv, du))
        if not contains_zero(phi):
            continue
        mu = _mid(U)
        mv = _mid(V)
        (gm, gum, gvm), mid_state = jet_first(s_data, t_data, m, c, pad, cpad, point(mu), point(mv),
                                              box_trig(s_data, point(mu), point(mv)))
        dU = isub(U, point(mu))
        dV = isub(V, point(mv))
        if not contains_zero(intersect(g, iadd(gm, iadd(imul(gu, dU), imul(gv, dV))))):
            continue
        guu, guv, gvv = jet_second(s_data, t_data, m, pad, box_state)
        if not contains_zero(_second_order(gm, gum, gvm, guu, guv, gvv, dU, dV)):
            continue
        j10 = isub(iscale(guu, dv), iscale(guv, du))
        j11 = isub(iscale(guv, dv), iscale(gvv, du))
        phim = isub(iscale(gum, dv), iscale(gvm, du))
        if not contains_zero(intersect(phi, iadd(phim, iadd(imul(j10, dU), imul(j11, dV))))):
            continue
        # Krawczyk: K = m - Y Phi(m) + (I - Y J(X)) (X - m), Y the inverse of the midpoint Jacobian
        guum, guvm, gvvm = jet_second(s_data, t_data, m, pad, mid_state)
        a00 = _mid(gum)
        a01 = _mid(gvm)
        a10 = dv * _mid(guum) - du * _mid(guvm)
        a11 = dv * _mid(guvm) - du * _mid(gvvm)
        det = a00 * a11 - a01 * a10
        scale = abs(a00 * a11) + abs(a01 * a10)
        contracted = False
        if scale > 0.0 and abs(det) > 1e-12 * scale:
            y00 = a11 / det
            y01 = -a01 / det
            y10 = -a10 / det
            y11 = a00 / det
            k = krawczyk_row(y00, y01, mu, gm, phim, gu, gv, j10, j11, dU, dV, 0)
            l = krawczyk_row(y10, y11, mv, gm, phim, gu, gv, j10, j11, dU, dV, 1)
            if k[0] > U[0] and k[1] < U[1] and l[0] > V[0] and l[1] < V[1]:
                if not _record(out, kinds, count, k, l, VERIFIED):
                    return count, RECORDS_FULL, boxes
                count += 1
                continue
            ku = intersect(k, U)
            kv = intersect(l, V)
            if ku[0] > ku[1] or kv[0] > kv[1]:
                continue
            if (ku[1] - ku[0] <= CONTRACTION * (U[1] - U[0]) and kv[1] - kv[0] <= CONTRACTION * (V[1] - V[0])):
                U = ku
                V = kv
                contracted = True
        if contracted:
            if top >= STACK:
                return count, STACK_FULL, boxes
            _put(stack, top, U, V)
            known[top] = 0
            top += 1
            continue
        ru = (U[1] - U[0]) / min_width[0]
        rv = (V[1] - V[0]) / min_width[1]
        tiny = (ru <= coarse and rv <= coarse and contains_zero(gm)
                and abs(a00) * (U[1] - U[0]) + abs(a01) * (V[1] - V[0]) <= FLAT * (gm[1] - gm[0]))
        if (ru <= 1.0 and rv <= 1.0) or tiny:
            if not _record(out, kinds, count, U, V, UNRESOLVED):
                return count, RECORDS_FULL, boxes
            count += 1
            continue
        if top + 2 > STACK:
            return count, STACK_FULL, boxes
        _put(stack, top, U, V)
        _put(stack, top + 1, U, V)
        if _cut_u(ru, rv, gu, gv, j10, j11, U[1] - U[0], V[1] - V[0]):
            cut = U[0] + SPLIT * (U[1] - U[0])
            stack[top, 1] = cut
            stack[top + 1, 0] = cut
            _put(trig, top, cv, sv, 4)
            _put(trig, top + 1, cv, sv, 4)
            known[top] = known[top + 1] = 2
        else:
            cut = V[0] + SPLIT * (V[1] - V[0])
            stack[top, 3] = cut
            stack[top + 1, 2] = cut
            _put(trig, top, cu, su, 0)
            _put(trig, top + 1, cu, su, 0)
            known[top] = known[top + 1] = 1
        top += 2
    return count, DONE, boxes


@jit(forceinline=True)
def _share(a, b):
    """a / (a + b) (0.5 where both vanish)."""
    total = a + b
    return 0.5 if not total > 0.0 else a / total


@jit(forceinline=True)
def _cut_u(ru, rv, gu, gv, j10, j11, wu, wv):
    """True when a box is bisected along u: the parameter whose share of the spread of g or phi over the box
    (|d/du| wu against |d/dv| wv, their enclosures' magnitudes times the widths: the smear) is largest, among those
    still wider than the smallest width (ru, rv: the widths over it). Along a near-tangency the level g is flat
    along one parameter and bent across it; cutting the relatively wider side there kept halving the flat one to
    no effect (a plane 1e-9 off a cone's tangent plane: 173 349 boxes, 364 by the smear).

    References
    ----------
    R. B. Kearfott, M. Novoa, INTBIS, a portable interval Newton/bisection package, ACM TOMS 16 (1990): the
    maximal-smear rule."""
    if ru <= 1.0:
        return False
    if rv <= 1.0:
        return True
    share = max(_share(mag(gu) * wu, mag(gv) * wv), _share(mag(j10) * wu, mag(j11) * wv))
    other = max(_share(mag(gv) * wv, mag(gu) * wu), _share(mag(j11) * wv, mag(j10) * wu))
    return share >= other


@jit(forceinline=True)
def _second_order(gm, gum, gvm, guu, guv, gvv, dU, dV):
    """The second-order Taylor form of g over the box m + dU x dV: g(m) + grad g(m) . d + d^T H(X) d / 2, with g
    and its gradient enclosed at the midpoint m and the Hessian over the box X (Lagrange's remainder lies in it).
    Its overestimate falls with the square of the width, as the centred form's does, but with a smaller constant
    (0.1-0.4 of it, tests/spatialkin/kernels/geometry/test_interval.py): the 2-D searches of the bench's pairs visit 8-37%
    fewer boxes with it (a torus-torus pair 2877 for 4597)."""
    linear = iadd(imul(gum, dU), imul(gvm, dV))
    half = iadd(iadd(iscale(imul(guu, isqr(dU)), 0.5), imul(guv, imul(dU, dV))), iscale(imul(gvv, isqr(dV)), 0.5))
    return iadd(gm, iadd(linear, half))


@jit(forceinline=True)
def _point_jet(s_data, t_data, m, c, u, v):
    """(g, g_u, g_v, g_uu, g_uv, g_vv) at the point (u, v): the midpoints of jet's enclosures, unpadded."""
    j = jet(s_data, t_data, m, c, 0.0, 0.0, (u, u), (v, v))
    return (_mid(j[0]), _mid(j[1]), _mid(j[2]), _mid(j[3]), _mid(j[4]), _mid(j[5]))


@jit(forceinline=True)
def _point_first(s_data, t_data, m, c, u, v):
    """(g, g_u, g_v) at the point (u, v): _point_jet's first three, to the bit."""
    j = jet_first(s_data, t_data, m, c, 0.0, 0.0, (u, u), (v, v), box_trig(s_data, (u, u), (v, v)))[0]
    return (_mid(j[0]), _mid(j[1]), _mid(j[2]))


@jit(forceinline=True)
def _point_level(s_data, t_data, m, c, u, v):
    """g at the point (u, v): _point_jet's first, to the bit."""
    return _mid(level(s_data, t_data, m, c, 0.0, 0.0, (u, u), (v, v)))


@jit
def _cycle_end(iterates, k, n):
    """Row of iterates (rows 0..k the iterates so far) that is iterate n of the sequence when iterate k repeats one
    of the CYCLE before it bit for bit (then they cycle: iterate n is that of its phase); -1 otherwise."""
    for j in range(k - 1, max(k - CYCLE, 0) - 1, -1):
        same = True
        for i in range(iterates.shape[1]):
            x = iterates[k, i]
            y = iterates[j, i]
            if not (x == y and math.copysign(1.0, x) == math.copysign(1.0, y)):
                same = False
                break
        if same:
            return j + (n - j) % (k - j)
    return -1


@jit
def refine_extremal(s_data, t_data, m, c, du, dv, box, uv):
    """Newton on (g, phi) from the box centre, kept inside the box, for REFINE_ITER steps or until it settles (or
    cycles: _cycle_end); the root into uv (2,)."""
    u = 0.5 * (box[0] + box[1])
    v = 0.5 * (box[2] + box[3])
    iterates = np.empty((REFINE_ITER + 1, 2))
    iterates[0, 0] = u
    iterates[0, 1] = v
    for it in range(REFINE_ITER):
        g, gu, gv, guu, guv, gvv = _point_jet(s_data, t_data, m, c, u, v)
        phi = dv * gu - du * gv
        a10 = dv * guu - du * guv
        a11 = dv * guv - du * gvv
        det = gu * a11 - gv * a10
        if det == 0.0:
            break
        su = (a11 * g - gv * phi) / det
        sv = (gu * phi - a10 * g) / det
        nu = min(max(u - su, box[0]), box[1])
        nv = min(max(v - sv, box[2]), box[3])
        done = nu == u and nv == v
        u = nu
        v = nv
        if done:
            break
        iterates[it + 1, 0] = u
        iterates[it + 1, 1] = v
        end = _cycle_end(iterates, it + 1, REFINE_ITER)
        if end >= 0:
            u = iterates[end, 0]
            v = iterates[end, 1]
            break
    uv[0] = u
    uv[1] = v


@jit
def refine_line(s_data, t_data, m, c, fixed, value, a, b):
    """Newton on g along the parameter line inside [a, b], for REFINE_ITER steps or until it settles (or cycles:
    _cycle_end); returns the root."""
    t = 0.5 * (a + b)
    iterates = np.empty((REFINE_ITER + 1, 1))
    iterates[0, 0] = t
    for it in range(REFINE_ITER):
        if fixed == 1:
            j = _point_first(s_data, t_data, m, c, t, value)
            f, d = j[0], j[1]
        else:
            j = _point_first(s_data, t_data, m, c, value, t)
            f, d = j[0], j[2]
        if d == 0.0:
            break
        nt = min(max(t - f / d, a), b)
        if nt == t:
            break
        t = nt
        iterates[it + 1, 0] = t
        end = _cycle_end(iterates, it + 1, REFINE_ITER)
        if end >= 0:
            return iterates[end, 0]
    return t


@jit
def point_values(s_data, t_data, m, c, uv, out):
    """(g, g_u, g_v, g_uu, g_uv, g_vv) (N, 6) at parameter points uv (N, 2) of S (float evaluation)."""
    for k in range(uv.shape[0]):
        j = _point_jet(s_data, t_data, m, c, uv[k, 0], uv[k, 1])
        for i in range(6):
            out[k, i] = j[i]


@jit
def level_enclosure(s_data, t_data, m, c, pad, cpad, u, v):
    """(lo, hi): a rigorous enclosure of g at the point (u, v) (its round-off and the placement's)."""
    return level(s_data, t_data, m, c, pad, cpad, (u, u), (v, v))


@jit
def on_level(s_data, t_data, m, c, pad, cpad, u, v, widen):
    """True when g at (u, v) is zero within its round-off: its rigorous enclosure (level_enclosure), widened
    `widen` times its width on each side, holds zero."""
    lo, hi = level_enclosure(s_data, t_data, m, c, pad, cpad, u, v)
    width = hi - lo
    return lo - widen * width <= 0.0 <= hi + widen * width


@jit
def spaced(lo, hi, n, i):
    """Point i of n evenly spaced over [lo, hi], ends included, to the bit as numpy.linspace(lo, hi, n)[i]."""
    if i == n - 1:
        return hi
    return i * ((hi - lo) / (n - 1)) + lo


@jit
def _on_line(fixed, value, t):
    """(u, v) of the point t of the parameter line (parameter `fixed` = value)."""
    if fixed == 1:
        return t, value
    return value, t


@jit
def line_on_level(s_data, t_data, m, c, pad, cpad, fixed, value, t0, t1, probes, widen):
    """True when g is zero within its round-off at every one of `probes` evenly spaced points of the parameter line
    (parameter `fixed` of S = value, the other over [t0, t1]: spaced()): its rigorous enclosure, widened `widen`
    times its width on each side, holds zero. Stops at the first probe off the level."""
    for i in range(probes):
        u, v = _on_line(fixed, value, spaced(t0, t1, probes, i))
        if not on_level(s_data, t_data, m, c, pad, cpad, u, v, widen):
            return False
    return True


@jit
def level_max(s_data, t_data, m, c, box, n):
    """Largest |g| (float evaluation) on the n x n grid of spaced() points over box (u_lo, u_hi, v_lo, v_hi)."""
    top = 0.0
    for j in range(n):
        v = spaced(box[2], box[3], n, j)
        for i in range(n):
            top = max(top, abs(_point_level(s_data, t_data, m, c, spaced(box[0], box[1], n, i), v)))
    return top


@jit
def flat_fraction(s_data, t_data, m, c, fixed, value, lo, hi, n, floor):
    """Fraction of n spaced() points of the parameter line (parameter `fixed` = value, the other over [lo, hi])
    where |g| (float evaluation) is at most floor."""
    flat = 0
    for i in range(n):
        u, v = _on_line(fixed, value, lo + spaced(0.0, 1.0, n, i) * (hi - lo))
        if abs(_point_level(s_data, t_data, m, c, u, v)) <= floor:
            flat += 1
    return flat / n


@jit
def _inside(data, bounds, point, q, uv):
    """True when the foot point's parameters of point lie in bounds (u_lo, u_hi, v_lo, v_hi); NaN bounds: no trim."""
    if bounds[0] != bounds[0]:
        return True
    to_local(data, point, q)
    inverse_local(data, q, uv)
    return bounds[0] <= uv[0] <= bounds[1] and bounds[2] <= uv[1] <= bounds[3]


@jit
def keep_points(a_data, a_bounds, b_data, b_bounds, apexes, clearance, points, out):
    """out[k] = True where points[k] (N, 3) has its foot points on both surfaces within their trims (a_bounds,
    b_bounds: u_lo, u_hi, v_lo, v_hi with the slack included; NaN: untrimmed) and lies farther than clearance
    from every apex (K, 3)."""
    q = np.empty(3)
    uv = np.empty(2)
    for k in range(points.shape[0]):
        kept = _inside(a_data, a_bounds, points[k], q, uv) and _inside(b_data, b_bounds, points[k], q, uv)
        for j in range(apexes.shape[0]):
            d0 = points[k, 0] - apexes[j, 0]
            d1 = points[k, 1] - apexes[j, 1]
            d2 = points[k, 2] - apexes[j, 2]
            if np.sqrt(d0 * d0 + d1 * d1 + d2 * d2) <= clearance:
                kept = False
        out[k] = kept


@jit
def keep_surface_points(s_data, uv, a_data, a_bounds, b_data, b_bounds, apexes, clearance, points, out):
    """The points (N, 3) of S at parameter points uv (N, 2) (surfaces.evaluate) into points, and which of them
    keep_points keeps into out (N,): the two in one call."""
    evaluate(s_data, uv, points)
    keep_points(a_data, a_bounds, b_data, b_bounds, apexes, clearance, points, out)


@jit
def line_search(s_data, t_data, m, c, pad, cpad, fixed, value, t0, t1, min_width, coarse, max_boxes, out, kinds,
                probes, widen, boxes):
    """line_roots, its records then reduced to points of the line: the verified roots, refined (refine_line),
    in out[:K, 0], then the unresolved boxes' midpoints in out[K:N, 0] (each in the search's order), and the boxes
    themselves (lo, hi) in the same order in boxes (K, 2) (a verified box holds exactly one root). First,
    when probes > 0, the line is probed (line_on_level with probes, widen): where it lies on the level, it is
    not searched and the status is WHOLE_LINE.

    Returns (N, status, boxes visited, K).
    """
    if probes > 0 and line_on_level(s_data, t_data, m, c, pad, cpad, fixed, value, t0, t1, probes, widen):
        return 0, WHOLE_LINE, 0, 0
    n, status, searched = line_roots(s_data, t_data, m, c, pad, cpad, fixed, value, t0, t1, min_width, coarse,
                                     max_boxes, out, kinds)
    roots = np.empty(n)
    loose = np.empty(n)
    loose_boxes = np.empty((n, 2))
    k = 0
    j = 0
    for i in range(n):
        if kinds[i] == VERIFIED:
            roots[k] = refine_line(s_data, t_data, m, c, fixed, value, out[i, 0], out[i, 1])
            boxes[k, 0] = out[i, 0]
            boxes[k, 1] = out[i, 1]
            k += 1
        else:
            loose[j] = 0.5 * (out[i, 0] + out[i, 1])
            loose_boxes[j, 0] = out[i, 0]
            loose_boxes[j, 1] = out[i, 1]
            j += 1
    for i in range(k):
        out[i, 0] = roots[i]
    for i in range(j):
        out[k + i, 0] = loose[i]
        boxes[k + i, 0] = loose_boxes[i, 0]
        boxes[k + i, 1] = loose_boxes[i, 1]
    return n, status, searched, k


@jit
def extremal_search(s_data, t_data, m, c, pad, cpad, du, dv, box, min_width, coarse, max_boxes, out, kinds, boxes):
    """extremal_points, its records then reduced to parameter points: the verified roots, refined
    (refine_extremal), in out[:K, :2], then the unresolved boxes' centres in out[K:N, :2] (each in the search's
    order), and the boxes themselves (u lo, u hi, v lo, v hi) in the same order in boxes (K, 4) (a verified box
    holds exactly one solution).

    Returns (N, status, boxes visited, K).
    """
    n, status, searched = extremal_points(s_data, t_data, m, c, pad, cpad, du, dv, box, min_width, coarse, max_boxes,
                                          out, kinds)
    points = np.empty((n, 2))
    uv = np.empty(2)
    k = 0
    for i in range(n):
        if kinds[i] == VERIFIED:
            refine_extremal(s_data, t_data, m, c, du, dv, out[i], uv)
            points[k, 0] = uv[0]
            points[k, 1] = uv[1]
            boxes[k, :] = out[i, :]
            k += 1
    j = k
    for i in range(n):
        if kinds[i] != VERIFIED:
            points[j, 0] = 0.5 * (out[i, 0] + out[i, 1])
            points[j, 1] = 0.5 * (out[i, 2] + out[i, 3])
            boxes[j, :] = out[i, :]
            j += 1
    for i in range(n):
        out[i, 0] = points[i, 0]
        out[i, 1] = points[i, 1]
    return n, status, searched, k
