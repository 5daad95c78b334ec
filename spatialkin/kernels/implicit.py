"""Kernels for following the one-dimensional solution set of F(y) = 0, F: R^(n+1) -> R^n, by arc length.

The curve's unit tangent is the null vector of the n x (n+1) Jacobian J, oriented so that
det([J; t]) has a fixed sign: that orientation is intrinsic, so it carries through turning points of any
coordinate (a mechanism's lock position, where the input angle reverses). Drift is pulled back by the
minimum-norm Gauss-Newton step J^+ F. The system-specific kernels fill F and J; these do the rest.

References
----------
E. L. Allgower, K. Georg, Introduction to Numerical Continuation Methods, SIAM 2003, ch. 2 (the oriented
tangent t(J)) and ch. 3 (the Moore-Penrose corrector).
"""
import numpy as np

from .._jit import jit
from .curve import solve_small

#: Singular values below this fraction of the largest count as zero in the pull-back's pseudo-inverse.
RANK_EPS = 1e-13


@jit
def oriented_tangent(jac, sign, tangent):
    """Unit null vector of jac (n, n+1) into tangent (n+1,), with sign * det([jac; tangent]) > 0.

    Returns the smallest non-zero singular value of jac relative to the largest (0 at a branch point,
    where the tangent is not defined)."""
    n = jac.shape[0]
    u, sv, vt = np.linalg.svd(jac)
    aug = np.empty((n + 1, n + 1))
    aug[:n] = jac
    aug[n] = vt[n]
    flip = 1.0 if sign * np.linalg.det(aug) > 0 else -1.0
    for i in range(n + 1):
        tangent[i] = flip * vt[n, i]
    return sv[n - 1] / sv[0] if sv[0] > 0 else 0.0


@jit
def min_norm_step(jac, f, step):
    """The minimum-norm solution step (n+1,) of jac step = f (the Gauss-Newton corrector, J^+ f)."""
    n = jac.shape[0]
    u, sv, vt = np.linalg.svd(jac)
    step[:] = 0.0
    for i in range(n):
        if sv[i] <= RANK_EPS * sv[0]:
            continue
        c = 0.0
        for k in range(n):
            c += u[k, i] * f[k]
        c /= sv[i]
        for j in range(n + 1):
            step[j] += c * vt[i, j]


@jit
def follow_rhs(jac, f, sign, pullback, out):
    """Right-hand side of the arc-length Cauchy problem: the oriented tangent minus pullback * J^+ F."""
    oriented_tangent(jac, sign, out)
    if pullback != 0.0:
        step = np.empty(out.shape[0])
        min_norm_step(jac, f, step)
        for i in range(out.shape[0]):
            out[i] -= pullback * step[i]


@jit
def second_derivative(jac, tangent, quad, out):
    """y'' of the arc-length curve: J y'' = -quad (quad = F''[y', y']) and y'.y'' = 0. False if singular."""
    n = jac.shape[0]
    m = np.empty((n + 1, n + 1))
    r = np.empty(n + 1)
    m[:n] = jac
    m[n] = tangent
    for i in range(n):
        r[i] = -quad[i]
    r[n] = 0.0
    return solve_small(m, r, out)


@jit
def solve_partial(jac, f, out):
    """Solve J[:, :n] out = f (the Jacobian in the unknowns at a fixed input); False if singular."""
    n = jac.shape[0]
    m = np.empty((n, n))
    r = np.empty(n)
    for i in range(n):
        for j in range(n):
            m[i, j] = jac[i, j]
        r[i] = f[i]
    return solve_small(m, r, out)
