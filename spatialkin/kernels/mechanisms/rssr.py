"""Kernels of the spatial four-link crank-rocker RSSR: F(phi, psi) = |C(psi) - B(phi)|^2 - L^2 = 0.

B(phi) = O1 + T1 (a cos phi, a sin phi, 0) is the crank pin, C(psi) = O2 + T2 (c cos psi, c sin psi, 0)
the rocker's ball centre, L the coupler length; params packs O1 (3), T1 (9, row-major), a, O2, T2, c, L.

References
----------
"Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines of the
light industry" (in Ukrainian; [Looper]): the classic RSSR solved as sphere ∩ sphere ∩ circle.
"""
import math

import numpy as np

from ..._lib.jit import jit
from ..continuation.follow import follow_events, follow_fun
from ..continuation.implicit import follow_rhs
from ..ode.rk import advance

O1, T1, A, O2, T2, C, L = 0, 3, 12, 13, 16, 25, 26
PARAMS_SIZE = 27


@jit
def rssr_points(params, phi, psi, b, c):
    """Crank pin B(phi) and ball centre C(psi) with their first and second derivatives, rows 0, 1, 2."""
    cp, sp = math.cos(phi), math.sin(phi)
    cq, sq = math.cos(psi), math.sin(psi)
    a = params[A]
    r = params[C]
    local_b = ((a * cp, a * sp), (-a * sp, a * cp), (-a * cp, -a * sp))
    local_c = ((r * cq, r * sq), (-r * sq, r * cq), (-r * cq, -r * sq))
    for k in range(3):
        for i in range(3):
            b[k, i] = params[T1 + 3 * i] * local_b[k][0] + params[T1 + 3 * i + 1] * local_b[k][1]
            c[k, i] = params[T2 + 3 * i] * local_c[k][0] + params[T2 + 3 * i + 1] * local_c[k][1]
    for i in range(3):
        b[0, i] += params[O1 + i]
        c[0, i] += params[O2 + i]


@jit
def rssr_residual(params, x, grad, hess):
    """F at x = (phi, psi), its gradient (2,) and Hessian (2, 2)."""
    b = np.empty((3, 3))
    c = np.empty((3, 3))
    rssr_points(params, x[0], x[1], b, c)
    d = c[0] - b[0]
    dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
    grad[0] = -2.0 * (d[0] * b[1, 0] + d[1] * b[1, 1] + d[2] * b[1, 2])
    grad[1] = 2.0 * (d[0] * c[1, 0] + d[1] * c[1, 1] + d[2] * c[1, 2])
    bb = b[1, 0] ** 2 + b[1, 1] ** 2 + b[1, 2] ** 2
    cc = c[1, 0] ** 2 + c[1, 1] ** 2 + c[1, 2] ** 2
    hess[0, 0] = 2.0 * bb - 2.0 * (d[0] * b[2, 0] + d[1] * b[2, 1] + d[2] * b[2, 2])
    hess[1, 1] = 2.0 * cc + 2.0 * (d[0] * c[2, 0] + d[1] * c[2, 1] + d[2] * c[2, 2])
    hess[0, 1] = -2.0 * (b[1, 0] * c[1, 0] + b[1, 1] * c[1, 1] + b[1, 2] * c[1, 2])
    hess[1, 0] = hess[0, 1]
    return dd - params[L] * params[L]


@jit
def implicit_curve_rhs(s, x, params, sign, pullback):
    """Arc-length Cauchy problem of the planar implicit curve F(x) = 0 (spatialkin.kernels.continuation.implicit.follow_rhs
    with J = grad F): x' = sign (-F_2, F_1)/|grad F|, minus the pull-back pullback F grad F/|grad F|^2."""
    grad = np.empty(2)
    hess = np.empty((2, 2))
    f = np.array([rssr_residual(params, x, grad, hess)])
    jac = np.empty((1, 2))
    jac[0, 0], jac[0, 1] = grad[0], grad[1]
    out = np.zeros(2)
    follow_rhs(jac, f, sign, pullback, out)
    return out


@jit
def rssr_fun(t, y, args, out):
    """implicit_curve_rhs for the Runge-Kutta engine (spatialkin.kernels.continuation.follow)."""
    follow_fun(implicit_curve_rhs, t, y, args, out)


@jit
def rssr_events(t, y, args, eargs, active, out):
    """The continuation events of implicit_curve_rhs (spatialkin.kernels.continuation.follow)."""
    follow_events(implicit_curve_rhs, t, y, args, eargs, active, out)


@jit
def rssr_advance(t, y, f, h, fresh, t_bound, rtol, atol, max_step, max_steps, max_nfev, g, active, directions,
                   modes, args, eargs, method):
    """spatialkin.kernels.ode.rk.advance bound to rssr_fun and rssr_events."""
    return advance(rssr_fun, rssr_events, args, eargs, t, y, f, h, fresh, t_bound, rtol, atol, max_step,
                   max_steps, max_nfev, g, active, directions, modes, method)


@jit
def implicit_curve_derivatives(params, xs, sign, d1, d2, ok):
    """x' (unit tangent) and x'' = -(t.H.t)/|grad F|^2 grad F at points xs (N, 2) of F = 0."""
    grad = np.empty(2)
    hess = np.empty((2, 2))
    for k in range(xs.shape[0]):
        rssr_residual(params, xs[k], grad, hess)
        g2 = grad[0] * grad[0] + grad[1] * grad[1]
        if g2 == 0.0:
            ok[k] = False
            continue
        ok[k] = True
        g = math.sqrt(g2)
        t0 = -sign * grad[1] / g
        t1 = sign * grad[0] / g
        d1[k, 0] = t0
        d1[k, 1] = t1
        curv = (hess[0, 0] * t0 * t0 + 2.0 * hess[0, 1] * t0 * t1 + hess[1, 1] * t1 * t1) / g2
        d2[k, 0] = -curv * grad[0]
        d2[k, 1] = -curv * grad[1]


@jit
def newton_psi(params, xs, tol, max_iter, ok):
    """Newton on F(phi, psi) = 0 in psi at fixed phi, in place for each row of xs (N, 2)."""
    grad = np.empty(2)
    hess = np.empty((2, 2))
    for k in range(xs.shape[0]):
        ok[k] = False
        for _ in range(max_iter):
            f = rssr_residual(params, xs[k], grad, hess)
            if abs(f) <= tol:
                if ok[k]:
                    break
                ok[k] = True
            if grad[1] == 0.0:
                ok[k] = False
                break
            xs[k, 1] -= f / grad[1]
