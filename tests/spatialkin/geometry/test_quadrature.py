"""spatialkin.geometry.quadrature.gauss_legendre against closed-form integrals: exact (to round-off) for a polynomial
of degree 2 nodes - 1, converged for a smooth speed, NaN on a panel with a failed evaluation."""
import math

import numpy as np

from spatialkin.geometry.quadrature import gauss_legendre, legendre_rule

#: Relative round-off of a few panels' sums.
ROUNDOFF = 1e-14


def test_polynomial_of_degree_2n_minus_1_is_exact():
    """Oracle: the antiderivative of t^(2n - 1) + t^2, n the nodes, over uneven panels."""
    for nodes in (4, 8, 16):
        edges = np.array([-1.3, -0.2, 0.05, 0.9, 2.0])
        degree = 2 * nodes - 1
        got = gauss_legendre(lambda t: t ** degree + t * t, edges[:-1], edges[1:], nodes)

        def primitive(t):
            return t ** (degree + 1) / (degree + 1) + t ** 3 / 3.0
        want = primitive(edges[1:]) - primitive(edges[:-1])
        np.testing.assert_allclose(got, want, rtol=ROUNDOFF, atol=ROUNDOFF)


def test_smooth_speed_over_panels():
    """Oracle: the arc length of the ellipse (cos t, 2 sin t) over a quarter turn, 2 E(t | 3/4) (scipy's
    ellipeinc), panel by panel."""
    from scipy.special import ellipeinc
    edges = np.linspace(0.0, 0.5 * math.pi, 9)
    got = gauss_legendre(lambda t: np.hypot(np.sin(t), 2.0 * np.cos(t)), edges[:-1], edges[1:], 16)
    want = 2.0 * (ellipeinc(edges[1:], 0.75) - ellipeinc(edges[:-1], 0.75))
    np.testing.assert_allclose(got, want, rtol=ROUNDOFF)


def test_a_nan_speed_spoils_only_its_panel():
    """Oracle: a unit speed (integral 1) on the panels around the one where it is NaN."""
    def speed(t):
        return np.where((t > 1.0) & (t < 2.0), np.nan, 1.0)
    got = gauss_legendre(speed, np.array([0.0, 1.0, 2.0]), np.array([1.0, 2.0, 3.0]), 8)
    assert np.isnan(got[1]) and np.all(np.abs(got[[0, 2]] - 1.0) <= ROUNDOFF)


def test_rule_is_numpys_and_read_only():
    """Oracle: numpy's leggauss; the cached arrays cannot be changed by a caller."""
    x, w = legendre_rule(8)
    want_x, want_w = np.polynomial.legendre.leggauss(8)
    assert np.array_equal(x, want_x) and np.array_equal(w, want_w)
    assert not x.flags.writeable and not w.flags.writeable
