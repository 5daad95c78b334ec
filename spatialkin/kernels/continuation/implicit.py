"""Kernels for following the one-dimensional solution set of F(y) = 0, F: R^(n+1) -> R^n, by arc length.

The curve's unit tangent is the null vector of the n x (n+1) Jacobian J, oriented so that
det([J; t]) has a fixed sign: that orientation is intrinsic, so it carries through turning points of any
coordinate (a mechanism's lock position, where the input angle reverses). Drift is pulled back by the
minimum-norm Gauss-Newton step J^+ F. The system-specific kernels fill F and J; these do the rest.

References
----------
E. L. Allgower, K. Georg, Introduction to Numerical Continuation Methods, SIAM 2003, ch. 2 (the oriented
tangent t(J)), ch. 3 (the Moore-Penrose corrector) and ch. 4 (both from one QR factorisation of J^T).
"""
import numpy as np

from ..._lib.jit import jit

#: Diagonal entries of R below this fraction of the largest count as zero (rank loss: a branch point).
RANK_EPS = 1e-13


@jit
def householder(jac, a, beta):
    """QR of jac^T (n+1, n) by Householder reflections, in place in a (n+1, n): R in its upper triangle,
    the reflection vectors v_k (v_k[k] = 1 implied) below it, beta (n,) their factors (H = I - beta v v^T).
    Returns the number of non-trivial reflections (each has determinant -1)."""
    n = jac.shape[0]
    for i in range(n + 1):
        for j in range(n):
            a[i, j] = jac[j, i]
    flips = 0
    for k in range(n):
        norm2 = 0.0
        for i in range(k, n + 1):
            norm2 += a[i, k] * a[i, k]
        if norm2 == 0.0:
            beta[k] = 0.0
            continue
        alpha = -np.sign(a[k, k]) * np.sqrt(norm2) if a[k, k] != 0.0 else -np.sqrt(norm2)
        v0 = a[k, k] - alpha
        vnorm2 = v0 * v0 + norm2 - a[k, k] * a[k, k]
        if vnorm2 == 0.0:
            beta[k] = 0.0
            continue
        for i in range(k + 1, n + 1):
            a[i, k] /= v0
        beta[k] = 2.0 * v0 * v0 / vnorm2
        flips += 1
        for j in range(k + 1, n):                       # apply H_k to the remaining columns
            dot = a[k, j]
            for i in range(k + 1, n + 1):
                dot += a[i, k] * a[i, j]
            dot *= beta[k]
            a[k, j] -= dot
            for i in range(k + 1, n + 1):
                a[i, j] -= dot * a[i, k]
        a[k, k] = alpha
    return flips


@jit
def _apply_q(a, beta, x):
    """x <- Q x = H_0 H_1 ... H_{n-1} x, in place."""
    n = a.shape[1]
    for k in range(n - 1, -1, -1):
        if beta[k] == 0.0:
            continue
        dot = x[k]
        for i in range(k + 1, n + 1):
            dot += a[i, k] * x[i]
        dot *= beta[k]
        x[k] -= dot
        for i in range(k + 1, n + 1):
            x[i] -= dot * a[i, k]


@jit
def follow_rhs(jac, f, sign, pullback, out):
    """Right-hand side of the arc-length Cauchy problem: the oriented unit tangent (sign * det([J; t]) > 0)
    minus pullback * J^+ F (the minimum-norm Gauss-Newton step). Returns False at a rank loss."""
    n = jac.shape[0]
    a = np.empty((n + 1, n))
    beta = np.empty(n)
    flips = householder(jac, a, beta)
    big, det_sign = 0.0, 1.0 if flips % 2 == 0 else -1.0
    for k in range(n):
        big = max(big, abs(a[k, k]))
        det_sign *= 1.0 if a[k, k] > 0 else -1.0
    for k in range(n):
        if abs(a[k, k]) <= RANK_EPS * big:
            out[:] = 0.0
            return False
    # the tangent t = Q e_n: det([J; t]) = det(Q) det(R) since [J^T t] = Q diag(R, 1)
    out[:] = 0.0
    out[n] = 1.0 if sign * det_sign > 0 else -1.0
    if pullback != 0.0:           # J = R^T Q^T: the minimum-norm solution of J x = f is Q (R^-T f, 0)
        for k in range(n):
            acc = f[k]
            for i in range(k):
                acc -= a[i, k] * out[i]
            out[k] = acc / a[k, k]
        for k in range(n):
            out[k] *= -pullback
    _apply_q(a, beta, out)
    return True


@jit
def oriented_tangent(jac, sign, tangent):
    """Unit null vector of jac (n, n+1) into tangent (n+1,), with sign * det([jac; tangent]) > 0.
    False at a rank loss (a branch point, where the tangent is not defined)."""
    return follow_rhs(jac, jac[:, 0], sign, 0.0, tangent)
