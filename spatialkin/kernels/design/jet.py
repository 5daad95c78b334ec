"""Product of truncated Taylor polynomials in R[t, eps]/(t**T, eps_i eps_j) (see spatialkin.design.jet)."""
from ..._lib.jit import jit


@jit
def jet_product(c, d, out):
    """out[m] = c[m] * d[m] for coefficient arrays (M, T, Q): column 0 the plain polynomial in t, columns
    1..Q-1 the first-order parts in eps_1..eps_{Q-1}."""
    n, orders, q = c.shape
    for m in range(n):
        for a in range(orders):
            for i in range(q):
                out[m, a, i] = 0.0
        for a1 in range(orders):
            c0 = c[m, a1, 0]
            for a2 in range(orders - a1):
                d0 = d[m, a2, 0]
                a = a1 + a2
                out[m, a, 0] += c0 * d0
                for i in range(1, q):
                    out[m, a, i] += c0 * d[m, a2, i] + c[m, a1, i] * d0
