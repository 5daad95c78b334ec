"""Kernels for g(u, v) = f_Q(P(u, v)): the implicit value of surface Q read on the parametrised surface P.

The intersection P ∩ Q is the zero level set of g. Its critical points and gradient flow find every
component (see spatialkin.tracing.seeds).
"""
import math

import numpy as np

from .._jit import jit
from .curve import relative_area, solve_small
from .surfaces import frame, implicit_value

#: Parameter step of the central differences, for a parameter of unit scale (angles).
FD_STEP_GRAD = 1e-6
FD_STEP_HESS = 1e-4


@jit
def level_value(p, q, u, v):
    point, _, _ = frame(p, u, v)
    return implicit_value(q, point)


@jit
def level_gradient(p, q, u, v, h, grad):
    """Central-difference gradient of g in (u, v) with step h[0], h[1]; returns g."""
    grad[0] = (level_value(p, q, u + h[0], v) - level_value(p, q, u - h[0], v)) / (2 * h[0])
    grad[1] = (level_value(p, q, u, v + h[1]) - level_value(p, q, u, v - h[1])) / (2 * h[1])
    return level_value(p, q, u, v)


@jit
def level_hessian(p, q, u, v, h, hess):
    """Central-difference Hessian of g in (u, v) with steps h (2,)."""
    g0 = level_value(p, q, u, v)
    hess[0, 0] = (level_value(p, q, u + h[0], v) - 2 * g0 + level_value(p, q, u - h[0], v)) / h[0] ** 2
    hess[1, 1] = (level_value(p, q, u, v + h[1]) - 2 * g0 + level_value(p, q, u, v - h[1])) / h[1] ** 2
    hess[0, 1] = (level_value(p, q, u + h[0], v + h[1]) - level_value(p, q, u + h[0], v - h[1])
                  - level_value(p, q, u - h[0], v + h[1]) + level_value(p, q, u - h[0], v - h[1])) / (4 * h[0] * h[1])
    hess[1, 0] = hess[0, 1]


@jit
def critical_newton(p, q, starts, param_scale, max_iter, out, status):
    """Newton on grad g = 0 from each start (N, 2); out (N, 2) the critical points, status 1 if converged.

    param_scale (2,) is the length of a unit step in u and v (1 for angles), setting the difference steps.
    Steps are capped at 0.5 parameter units so that Newton stays near its start.
    """
    hg = np.empty(2)
    hh = np.empty(2)
    for i in range(2):
        hg[i] = FD_STEP_GRAD * param_scale[i]
        hh[i] = FD_STEP_HESS * param_scale[i]
    grad = np.empty(2)
    hess = np.empty((2, 2))
    dx = np.empty(2)
    for k in range(starts.shape[0]):
        u = starts[k, 0]
        v = starts[k, 1]
        status[k] = 0
        for _ in range(max_iter):
            level_gradient(p, q, u, v, hg, grad)
            level_hessian(p, q, u, v, hh, hess)
            r = -grad
            if not solve_small(hess, r, dx):
                break
            step = math.sqrt((dx[0] / param_scale[0]) ** 2 + (dx[1] / param_scale[1]) ** 2)
            if step > 0.5:
                dx *= 0.5 / step
            u += dx[0]
            v += dx[1]
            if step < 1e-10:
                status[k] = 1
                break
        out[k, 0] = u
        out[k, 1] = v


@jit
def steepest(p, q, u, v, h):
    """(du, dv, speed2): G^-1 grad g at (u, v), the parameter velocity of steepest ascent, and |grad_S g|^2
    (the squared rate of change of g per unit length on P); speed2 = -1 where P's metric degenerates."""
    _, su, sv = frame(p, u, v)
    e = su[0] * su[0] + su[1] * su[1] + su[2] * su[2]
    f = su[0] * sv[0] + su[1] * sv[1] + su[2] * sv[2]
    g = sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]
    det = e * g - f * f
    if det <= 0.0:
        return 0.0, 0.0, -1.0
    g_u = (level_value(p, q, u + h[0], v) - level_value(p, q, u - h[0], v)) / (2 * h[0])
    g_v = (level_value(p, q, u, v + h[1]) - level_value(p, q, u, v - h[1])) / (2 * h[1])
    du = (g * g_u - f * g_v) / det
    dv = (e * g_v - f * g_u) / det
    return du, dv, du * g_u + dv * g_v


@jit
def gradient_flow_rhs(t, x, p, q, sigma, h, saturation):
    """d(u, v)/dtau of the gradient flow of g on P, sigma * G^-1 grad g / max(|grad_S g|, saturation):
    unit speed in space where the gradient is steep, slowing smoothly into an extremum (no chattering)."""
    out = np.zeros(2)
    du, dv, speed2 = steepest(p, q, x[0], x[1], h)
    if speed2 <= 0.0:
        return out
    speed = max(math.sqrt(speed2), saturation)
    out[0] = sigma * du / speed
    out[1] = sigma * dv / speed
    return out


@jit
def surface_gradient_norm(p, q, u, v, h):
    """|grad_S g| at (u, v): the rate of change of g per unit length on P along its steepest direction."""
    return math.sqrt(max(steepest(p, q, u, v, h)[2], 0.0))


@jit
def relative_area_at(p, u, v):
    """|S_u x S_v| / max(|S_u|^2, |S_v|^2) of P at (u, v): zero where its parametrisation collapses."""
    _, su, sv = frame(p, u, v)
    return relative_area(su, sv)
