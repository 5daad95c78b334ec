"""Continuation kernels (spatialkin.kernels.continuation.implicit) and the LU kernels against numpy's linear algebra."""
import numpy as np
import pytest

from spatialkin.kernels.march import curve as kc

from spatialkin.kernels.continuation import implicit as ki

TOL = 1e-13


@pytest.mark.parametrize("n", [1, 2, 5, 10])
def test_oriented_tangent_is_the_unit_null_vector_with_the_asked_orientation(n):
    rng = np.random.default_rng(n)
    for _ in range(20):
        jac = rng.normal(size=(n, n + 1))
        for sign in (1.0, -1.0):
            t = np.empty(n + 1)
            assert ki.oriented_tangent(jac, sign, t)
            assert np.max(np.abs(jac @ t)) < TOL * np.abs(jac).max() * n
            assert abs(np.linalg.norm(t) - 1) < TOL
            assert sign * np.linalg.det(np.vstack([jac, t])) > 0


def test_pullback_is_the_minimum_norm_gauss_newton_step():
    rng = np.random.default_rng(1)
    n = 6
    for _ in range(20):
        jac, f = rng.normal(size=(n, n + 1)), rng.normal(size=n)
        t, out = np.empty(n + 1), np.empty(n + 1)
        ki.oriented_tangent(jac, 1.0, t)
        ki.follow_rhs(jac, f, 1.0, 0.5, out)
        step = np.linalg.lstsq(jac, f, rcond=None)[0]          # minimum-norm solution
        assert np.allclose(out, t - 0.5 * step, atol=1e-12)


def test_rank_loss_is_reported():
    jac = np.array([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0]])
    assert not ki.oriented_tangent(jac, 1.0, np.empty(3))


def test_lu_solve_matches_numpy():
    rng = np.random.default_rng(2)
    for n in (1, 3, 10):
        m, r = rng.normal(size=(n, n)), rng.normal(size=n)
        lu, piv, x = m.copy(), np.empty(n, dtype=np.int64), np.empty(n)
        assert kc.lu_factor(lu, piv)
        kc.lu_solve(lu, piv, r, x)
        assert np.allclose(x, np.linalg.solve(m, r), rtol=1e-12, atol=1e-12)
    assert not kc.lu_factor(np.ones((3, 3)), np.empty(3, dtype=np.int64))
