"""Jitted kernels of planar linkages: loop-closure equations in natural coordinates and their derivatives.

The unknowns are the coordinates of the moving joints, y = (x_0, y_0, x_1, y_1, ..., phi) with the input
angle phi last; fixed joints come from `fixed` (k, 2). A joint code c >= 0 is moving joint c, c < 0 is
fixed joint -c-1. Constraints (rows of ci (m, 6) int: kind, first equation row, three joint codes, crank
index; cf (m, 3) float):

    DIST   (i, j)         |P_j - P_i| = L                                (1 equation, (|d|^2 - L^2)/2L)
    RIGID  (p0, p1, j)    P_j = P_0 + a (P_1 - P_0) + b perp(P_1 - P_0)   (2 equations, linear)
    CRANK  (c, j), k      P_j = P_c + r (cos th, sin th), th = phase + ratio phi   (2 equations)

A binary link is one DIST, a ternary (or larger) link one DIST between its first two joints and one RIGID
per further joint; a driving crank is one CRANK. Every equation is quadratic or linear in the joints, so
F''[v, v] is exact and cheap: |v_j - v_i|^2 / L for DIST, ratio^2 r (cos th, sin th) v_phi^2 for CRANK.

At a fixed input the systems in J_q (Newton steps, derivatives) are solved by block elimination of the
joints a CRANK or RIGID constraint gives explicitly (factor_reduced, solve_reduced): one LU of the Schur
complement on the other joints and the remaining rows (the DIST constraints'; six-link: 4 x 4, not 10 x 10).
"""
import math

import numpy as np

from spatialkin.kernels import jit
from spatialkin.kernels.continuation.follow import follow_events, follow_fun
from spatialkin.kernels.linalg import lu_factor, lu_solve
from spatialkin.kernels.ode.rk import advance
from spatialkin.kernels.continuation.implicit import follow_rhs

DIST, RIGID, CRANK = 0, 1, 2
#: Columns of ci.
KIND, ROW, J0, J1, J2, CRANK_INDEX = 0, 1, 2, 3, 4, 5


@jit
def _xy(y, fixed, code):
    if code >= 0:
        return y[2 * code], y[2 * code + 1]
    return fixed[-code - 1, 0], fixed[-code - 1, 1]


@jit
def _add(jac, row, code, gx, gy):
    """jac[row, joint's x, y] += (gx, gy) for a moving joint; nothing for a fixed one."""
    if code >= 0:
        jac[row, 2 * code] += gx
        jac[row, 2 * code + 1] += gy


@jit
def linkage_system(y, ci, cf, fixed, f, jac, dtheta):
    """F (n,), its Jacobian (n, n+1) (the last column d/dphi) and dF/dtheta_k (n, cranks) at y."""
    n = f.shape[0]
    phi = y[n]
    jac[:] = 0.0
    dtheta[:] = 0.0
    for c in range(ci.shape[0]):
        kind, row = ci[c, KIND], ci[c, ROW]
        if kind == DIST:
            i, j = ci[c, J0], ci[c, J1]
            length = cf[c, 0]
            xi, yi = _xy(y, fixed, i)
            xj, yj = _xy(y, fixed, j)
            dx, dy = xj - xi, yj - yi
            f[row] = 0.5 * (dx * dx + dy * dy - length * length) / length
            _add(jac, row, j, dx / length, dy / length)
            _add(jac, row, i, -dx / length, -dy / length)
        elif kind == RIGID:
            p0, p1, j = ci[c, J0], ci[c, J1], ci[c, J2]
            a, b = cf[c, 0], cf[c, 1]
            x0, y0 = _xy(y, fixed, p0)
            x1, y1 = _xy(y, fixed, p1)
            xj, yj = _xy(y, fixed, j)
            ex, ey = x1 - x0, y1 - y0
            f[row] = xj - x0 - a * ex + b * ey
            f[row + 1] = yj - y0 - a * ey - b * ex
            _add(jac, row, j, 1.0, 0.0)
            _add(jac, row + 1, j, 0.0, 1.0)
            _add(jac, row, p1, -a, b)
            _add(jac, row + 1, p1, -b, -a)
            _add(jac, row, p0, a - 1.0, -b)
            _add(jac, row + 1, p0, b, a - 1.0)
        else:
            pc, j, k = ci[c, J0], ci[c, J1], ci[c, CRANK_INDEX]
            r, ratio, phase = cf[c, 0], cf[c, 1], cf[c, 2]
            th = phase + ratio * phi
            ct, st = math.cos(th), math.sin(th)
            xc, yc = _xy(y, fixed, pc)
            xj, yj = _xy(y, fixed, j)
            f[row] = xj - xc - r * ct
            f[row + 1] = yj - yc - r * st
            _add(jac, row, j, 1.0, 0.0)
            _add(jac, row + 1, j, 0.0, 1.0)
            _add(jac, row, pc, -1.0, 0.0)
            _add(jac, row + 1, pc, 0.0, -1.0)
            dtheta[row, k] += r * st
            dtheta[row + 1, k] -= r * ct
            jac[row, n] += ratio * r * st
            jac[row + 1, n] -= ratio * r * ct


@jit
def linkage_quadratic(y, v, ci, cf, fixed, out):
    """F''[v, v] (n,) at y along the direction v (n+1,)."""
    n = out.shape[0]
    out[:] = 0.0
    for c in range(ci.shape[0]):
        kind, row = ci[c, KIND], ci[c, ROW]
        if kind == DIST:
            vix, viy = _velocity(v, ci[c, J0])
            vjx, vjy = _velocity(v, ci[c, J1])
            out[row] = ((vjx - vix) ** 2 + (vjy - viy) ** 2) / cf[c, 0]
        elif kind == CRANK:
            r, ratio, phase = cf[c, 0], cf[c, 1], cf[c, 2]
            th = phase + ratio * y[n]
            w2 = (ratio * v[n]) ** 2
            out[row] = r * math.cos(th) * w2
            out[row + 1] = r * math.sin(th) * w2


@jit
def _velocity(v, code):
    if code >= 0:
        return v[2 * code], v[2 * code + 1]
    return 0.0, 0.0


@jit
def linkage_rhs(s, y, ci, cf, fixed, cranks, sign, pullback):
    """Arc-length Cauchy problem of the linkage's configuration curve (with the drift pull-back)."""
    n = y.shape[0] - 1
    f = np.empty(n)
    jac = np.empty((n, n + 1))
    dtheta = np.empty((n, cranks))
    linkage_system(y, ci, cf, fixed, f, jac, dtheta)
    out = np.empty(n + 1)
    follow_rhs(jac, f, sign, pullback, out)
    return out


@jit
def linkage_fun(t, y, args, out):
    """linkage_rhs for the Runge-Kutta engine (spatialkin.kernels.continuation.follow)."""
    follow_fun(linkage_rhs, t, y, args, out)


@jit
def linkage_events(t, y, args, eargs, active, out):
    """The continuation events of linkage_rhs (spatialkin.kernels.continuation.follow)."""
    follow_events(linkage_rhs, t, y, args, eargs, active, out)


@jit
def linkage_advance(t, y, f, h, fresh, t_bound, rtol, atol, max_step, max_steps, max_nfev, g, active, directions,
                   modes, args, eargs, method):
    """spatialkin.kernels.ode.rk.advance bound to linkage_fun and linkage_events."""
    return advance(linkage_fun, linkage_events, args, eargs, t, y, f, h, fresh, t_bound, rtol, atol, max_step,
                   max_steps, max_nfev, g, active, directions, modes, method)


# --- J_q by block elimination of the explicit joints -----------------------------------------------------------
# A crank's pin and a rigid link's further joint are explicit: their two rows read P_j - g(other joints) = 0,
# a unit block in P_j's columns. Ordered so that each depends only on implicit and earlier explicit joints,
# they make J_q's explicit block unit lower triangular, and J_q x = b reduces to the Schur complement S on
# the implicit joints' columns (the rows of the distance constraints): x_E = a + G x_R, S x_R = b_I - J_IE a,
# with G, S (and S's LU) from the Jacobian alone. det J_q = det S, so S is singular exactly where J_q is.
# layout = (pattern, slot, rows, cols, ne) from model._block_layout: rows (n,) the explicit joints' unit rows in
# order, then the implicit rows; cols (n,) the matching explicit columns, then the implicit ones; ne the
# number of explicit columns; pattern (n, 6) the columns each row couples (its own explicit joint's left out,
# -1 padded); slot (n,) a column's position in cols (explicit) or -1 - its position among the implicit ones.
# G (negated) and S are stacked in gs (n, n - ne): rows [0, ne) G, rows [ne, n) S.


@jit(inline="always")
def factor_reduced(jac, layout, gs, piv):
    """G and S of J_q = jac[:, :n] into gs, S's LU in place (with piv); False where S (so J_q) is
    singular."""
    pattern, slot, rows, _, ne = layout
    nr = gs.shape[1]
    for k in range(rows.shape[0]):
        r = rows[k]
        for j in range(nr):
            gs[k, j] = 0.0
        for q in range(pattern.shape[1]):           # row r's coefficients on x_R
            p = pattern[r, q]
            if p < 0:
                break
            coef, u = jac[r, p], slot[p]
            if u < 0:
                gs[k, -u - 1] += coef
            else:
                for j in range(nr):
                    gs[k, j] += coef * gs[u, j]
        if k < ne:                                  # x_E = a - (row's coefficients) x_R
            for j in range(nr):
                gs[k, j] = -gs[k, j]
    return nr == 0 or lu_factor(gs[ne:], piv)           # nr = 0: all joints explicit (cranks alone)


@jit(inline="always")
def solve_reduced(jac, layout, gs, piv, b, x, a, z):
    """x = J_q^-1 b from factor_reduced's gs, piv (workspace a (n,), z (n - ne,))."""
    pattern, slot, rows, cols, ne = layout
    for k in range(rows.shape[0]):                  # the part of each row's unknowns known from b alone
        r = rows[k]
        acc = b[r]
        for q in range(pattern.shape[1]):
            p = pattern[r, q]
            if p < 0:
                break
            if slot[p] >= 0:
                acc -= jac[r, p] * a[slot[p]]
        a[k] = acc
    lu_solve(gs[ne:], piv, a[ne:], z)
    for k in range(rows.shape[0]):
        if k >= ne:
            x[cols[k]] = z[k - ne]
        else:
            acc = a[k]
            for j in range(z.shape[0]):
                acc += gs[k, j] * z[j]
            x[cols[k]] = acc


@jit
def workspace(n, cranks, layout):
    """Arrays of the fixed-input solves: f, jac, dtheta, gs, piv, a, z, x."""
    nr = n - layout[4]
    return (np.empty(n), np.empty((n, n + 1)), np.empty((n, cranks)), np.empty((n, nr)), np.empty(nr, dtype=np.int64),
            np.empty(n), np.empty(nr), np.empty(n))


@jit(inline="always")
def _solve(ws, layout, b, x):
    """x = J_q^-1 b at the point of the last _correct."""
    _, jac, _, gs, piv, a, z, _ = ws
    solve_reduced(jac, layout, gs, piv, b, x, a, z)


@jit(inline="always")
def _correct(y, ci, cf, fixed, layout, tol, max_iter, ws):
    """Newton in the joints at y's input, in place. Returns 0 when the residual is below tol (the workspace
    then holds the system at y and J_q's factors), 1 when it is not within max_iter steps, 2 when J_q is
    singular (a lock position)."""
    f, jac, dtheta, gs, piv, _, _, step = ws
    n = f.shape[0]
    for _ in range(max_iter + 1):
        linkage_system(y, ci, cf, fixed, f, jac, dtheta)
        if not factor_reduced(jac, layout, gs, piv):
            return 2
        big = 0.0
        for i in range(n):
            big = max(big, abs(f[i]))
        if big <= tol:
            return 0
        _solve(ws, layout, f, step)
        for i in range(n):
            y[i] -= step[i]
    return 1


@jit
def correct_configuration(y, ci, cf, fixed, layout, tol, max_iter):
    """Newton in the joints at the input y[-1], in place (status as _correct)."""
    return _correct(y, ci, cf, fixed, layout, tol, max_iter, workspace(y.shape[0] - 1, crank_count(ci), layout))


@jit
def crank_count(ci):
    """Number of CRANK constraints in ci."""
    count = 0
    for c in range(ci.shape[0]):
        if ci[c, KIND] == CRANK:
            count += 1
    return count


@jit
def solve_configurations(guess, order, reach, jump, ci, cf, fixed, layout, tol, max_iter, ys, d1, d2, parts,
                         status):
    """At each row's fixed input angle: Newton in the joints until the residual is below tol, then, with the
    last Jacobian's LU, the joints' rates per unit rate of each crank, parts (N, cranks, n) =
    -J_q^-1 dF/dtheta_k, and the derivatives along the configuration curve parametrised by the input,
    y' = (dq/dphi, 1) = (sum_k ratio_k parts_k, 1) (as F_phi = sum_k ratio_k dF/dtheta_k) and
    y'' = (d2q/dphi2, 0) from J_q q'' = -F''[y', y'] (N, n+1).

    The rows are solved in `order` (by input along the branch). A row within `reach` of the input of the row
    solved before it starts from that row's second-order expansion q + q' h + q'' h^2 / 2 (one Newton step
    then reaches round-off); any other row, or one whose Newton fails from there or lands further than
    `jump` from its prediction guess (N, n+1) (the traced curve), starts from guess. Solved states go to ys.

    status[k]: 0 solved, 1 Newton did not converge, 2 J_q singular (a lock position)."""
    n = guess.shape[1] - 1
    cranks = parts.shape[1]
    ratios = np.empty(cranks)
    for c in range(ci.shape[0]):
        if ci[c, KIND] == CRANK:
            ratios[ci[c, CRANK_INDEX]] = cf[c, 1]
    ws = workspace(n, cranks, layout)
    dtheta = ws[2]
    rhs = np.empty(n)
    quad = np.empty(n)
    prev = -1
    for k in order:
        status[k] = 1
        if prev >= 0 and abs(guess[k, n] - ys[prev, n]) <= reach:
            h = guess[k, n] - ys[prev, n]
            for i in range(n):
                ys[k, i] = ys[prev, i] + h * (d1[prev, i] + 0.5 * h * d2[prev, i])
            ys[k, n] = guess[k, n]
            status[k] = _correct(ys[k], ci, cf, fixed, layout, tol, max_iter, ws)
            if status[k] == 0:
                for i in range(n):
                    if abs(ys[k, i] - guess[k, i]) > jump:
                        status[k] = 1
        if status[k] != 0:
            ys[k] = guess[k]
            status[k] = _correct(ys[k], ci, cf, fixed, layout, tol, max_iter, ws)
        if status[k] != 0:
            continue
        prev = k
        for c in range(cranks):
            for i in range(n):
                rhs[i] = -dtheta[i, c]
            _solve(ws, layout, rhs, parts[k, c])
        for i in range(n):
            acc = 0.0
            for c in range(cranks):
                acc += ratios[c] * parts[k, c, i]
            d1[k, i] = acc
        d1[k, n] = 1.0
        linkage_quadratic(ys[k], d1[k], ci, cf, fixed, quad)
        for i in range(n):
            rhs[i] = -quad[i]
        _solve(ws, layout, rhs, d2[k])
        d2[k, n] = 0.0
