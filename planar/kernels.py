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
"""
import math

import numpy as np

from spatialkin._jit import jit
from spatialkin.kernels.curve import lu_factor, lu_solve
from spatialkin.kernels.implicit import follow_rhs

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
def solve_configurations(ys, ci, cf, fixed, tol, max_iter, d1, d2, parts, status):
    """At each row's fixed input angle: Newton in the joints from the prediction in ys (N, n+1) until the
    residual is below tol, then, with the same Jacobian and its LU, the derivatives along the
    configuration curve parametrised by the input, y' = (dq/dphi, 1) and y'' = (d2q/dphi2, 0) (N, n+1)
    from J_q q' = -F_phi, J_q q'' = -F''[y', y'], and the joints' rates per unit rate of each crank,
    parts (N, cranks, n) = -J_q^-1 dF/dtheta_k.

    status[k]: 0 solved, 1 Newton did not converge, 2 J_q singular (a lock position)."""
    n = ys.shape[1] - 1
    cranks = parts.shape[1]
    f = np.empty(n)
    jac = np.empty((n, n + 1))
    dtheta = np.empty((n, cranks))
    m = np.empty((n, n))
    piv = np.empty(n, dtype=np.int64)
    rhs = np.empty(n)
    step = np.empty(n)
    quad = np.empty(n)
    for k in range(ys.shape[0]):
        status[k] = 1
        for _ in range(max_iter + 1):
            linkage_system(ys[k], ci, cf, fixed, f, jac, dtheta)
            m[:, :] = jac[:, :n]
            if not lu_factor(m, piv):
                status[k] = 2
                break
            big = 0.0
            for i in range(n):
                big = max(big, abs(f[i]))
            if big <= tol:
                status[k] = 0
                break
            lu_solve(m, piv, f, step)
            for i in range(n):
                ys[k, i] -= step[i]
        if status[k] != 0:
            continue
        for i in range(n):
            rhs[i] = -jac[i, n]
        lu_solve(m, piv, rhs, d1[k])
        d1[k, n] = 1.0
        linkage_quadratic(ys[k], d1[k], ci, cf, fixed, quad)
        for i in range(n):
            rhs[i] = -quad[i]
        lu_solve(m, piv, rhs, d2[k])
        d2[k, n] = 0.0
        for c in range(cranks):
            for i in range(n):
                rhs[i] = -dtheta[i, c]
            lu_solve(m, piv, rhs, parts[k, c])
