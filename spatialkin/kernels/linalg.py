"""Small dense linear systems in jitted code: LU with partial pivoting, in place (no allocation).

Used by the curve kernels' 3 x 3 and 4 x 4 Newton systems and by planar linkages' Schur complements. Each is
inlined into spatialkin's kernels at numba's level (the inline cost model _into_spatialkin): as a separate call, the
reference counting of its array arguments (atomic operations) costs about as much as the elimination of a 4 x 4
system.
"""
import math

from .._lib.jit import jit

__all__ = ["PIVOT_EPS", "lu_factor", "lu_solve", "balance_columns", "unbalance"]

#: Below this, a pivot is treated as zero (relative to the largest entry of the matrix).
PIVOT_EPS = 1e-14


def _into_spatialkin(expr, caller, callee):
    """numba's inline cost model of these solvers: inlined into spatialkin's kernels (Newton's 4 x 4 systems, solved
    point after point), called from the others (planar's linkages: one solve a step, where inlining costs only
    compile time)."""
    return caller.func_id.modname.partition(".")[0] == "spatialkin"


@jit(inline=_into_spatialkin)
def lu_factor(m, piv):
    """LU factorisation with partial pivoting of the square m, in place; False if a pivot vanishes
    relative to the largest entry (a singular matrix)."""
    n = m.shape[0]
    big = 0.0
    for i in range(n):
        for j in range(n):
            big = max(big, abs(m[i, j]))
    if big == 0.0:
        return False
    for col in range(n):
        p = col
        for i in range(col + 1, n):
            if abs(m[i, col]) > abs(m[p, col]):
                p = i
        piv[col] = p
        if abs(m[p, col]) <= PIVOT_EPS * big:
            return False
        if p != col:
            for j in range(n):
                tmp = m[col, j]
                m[col, j] = m[p, j]
                m[p, j] = tmp
        for i in range(col + 1, n):
            m[i, col] /= m[col, col]
            for j in range(col + 1, n):
                m[i, j] -= m[i, col] * m[col, j]
    return True


@jit(inline=_into_spatialkin)
def lu_solve(m, piv, r, x):
    """x = m^-1 r from lu_factor's m, piv (r is left untouched)."""
    n = m.shape[0]
    for i in range(n):
        x[i] = r[i]
    for i in range(n):
        p = piv[i]
        if p != i:
            tmp = x[i]
            x[i] = x[p]
            x[p] = tmp
        for j in range(i):
            x[i] -= m[i, j] * x[j]
    for i in range(n - 1, -1, -1):
        for j in range(i + 1, n):
            x[i] -= m[i, j] * x[j]
        x[i] /= m[i, i]


@jit(inline=_into_spatialkin)
def balance_columns(m, scales):
    """Scale each column of m in place by a power of two (into scales, (n,)) that puts its largest entry in
    [0.5, 1): exact, so lu_factor of the balanced m gives the same numbers up to those powers, but its pivot test
    (relative to the largest entry) does not depend on the units of the unknowns. A Newton system of
    surface parameters mixes columns of lengths (an angle's derivative, a radius) and of numbers (a length
    parameter's): unbalanced, scaling the scene by 2^k moves the test by 2^k. A zero column keeps scale 1."""
    n = m.shape[1]
    for j in range(n):
        big = 0.0
        for i in range(m.shape[0]):
            big = max(big, abs(m[i, j]))
        scales[j] = 1.0
        if big > 0.0 and math.isfinite(big):
            _, e = math.frexp(big)
            scales[j] = math.ldexp(1.0, -e)
            for i in range(m.shape[0]):
                m[i, j] *= scales[j]


@jit(inline=_into_spatialkin)
def unbalance(x, scales):
    """The solution of the original system from that of the balanced one (balance_columns), in place."""
    for j in range(x.shape[0]):
        x[j] *= scales[j]
