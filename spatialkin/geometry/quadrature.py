"""Gauss-Legendre quadrature of a curve's speed over panels: the arc length of a conic's hyperbola branch
(spatialkin.tracing.closed.conic) and of a traced curve over a solver step (spatialkin.tracing.march.arclength).

References
----------
Abramowitz and Stegun, Handbook of Mathematical Functions, 25.4.29 (Gauss-Legendre).
"""
import functools

import numpy as np


@functools.lru_cache(maxsize=8)
def legendre_rule(nodes):
    """(x, w): the Gauss-Legendre nodes on [-1, 1] and their weights, (nodes,) each (read-only, made once)."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    x.flags.writeable = False
    w.flags.writeable = False
    return x, w


def gauss_legendre(speed, lo, hi, nodes):
    """The integral of speed over each panel [lo, hi] by the Gauss-Legendre rule of the given number of nodes.

    Parameters
    ----------
    speed : callable
        speed(t) (K,) at parameters t (K,): the panels' nodes, panel by panel (K = M x nodes). A value that is
        NaN (a failed evaluation) makes its panel's integral NaN.
    lo, hi : ndarray (M,)
        The panels' ends.
    nodes : int
        Nodes per panel (exact for polynomials of degree 2 nodes - 1).

    Returns
    -------
    ndarray (M,)
        The integral over each panel, 0.5 (hi - lo) sum_i w_i speed(mid + 0.5 (hi - lo) x_i).
    """
    x, w = legendre_rule(nodes)
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    half = 0.5 * (hi - lo)
    at = (0.5 * (hi + lo))[..., None] + half[..., None] * x
    return half * (speed(at.ravel()).reshape(at.shape) @ w)
