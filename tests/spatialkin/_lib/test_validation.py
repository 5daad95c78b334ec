"""spatialkin._lib.validation: every check returns the converted value, and refuses a bad one with a ValueError
naming the argument. Oracles: the inputs themselves (conversions are exact) and the named argument."""
import math

import numpy as np
import pytest

from spatialkin._lib import validation as v


@pytest.mark.parametrize("check, good, want", [
    (lambda x: v.check_real("x", x), "2.5", 2.5),
    (lambda x: v.check_positive("x", x), 3, 3.0),
    (lambda x: v.check_positive("x", x, allow_none=True), None, None),
    (lambda x: v.check_nonnegative("x", x), 0, 0.0),
    (lambda x: v.check_count("x", x, 3), 3, 3),
    (v.check_omega, -2, -2.0),
    (lambda x: v.check_choice("x", x, (1, -1)), -1, -1),
    (lambda x: v.check_choice("branch", x, (0, 1)), 1.0, 1),
    (lambda x: v.check_range("x", x), None, (-math.inf, math.inf)),
    (lambda x: v.check_range("x", x), (0, math.inf), (0.0, math.inf)),
])
def test_good_values_come_back_converted(check, good, want):
    got = check(good)
    assert got == want and type(got) is type(want)


@pytest.mark.parametrize("check, bad, words", [
    (lambda x: v.check_real("tol", x), "a", "tol must be a real number"),
    (lambda x: v.check_real("tol", x, finite=True), math.inf, "tol must be finite"),
    (lambda x: v.check_positive("tol", x), None, "tol must be a real number"),
    (lambda x: v.check_positive("tol", x), 0.0, "tol must be a positive finite number"),
    (lambda x: v.check_positive("tol", x), math.nan, "tol must be a positive finite number"),
    (lambda x: v.check_nonnegative("pullback", x), -1e-300, "pullback must be a finite number >= 0"),
    (lambda x: v.check_count("samples", x, 3), 2, "samples must be an integer >= 3"),
    (lambda x: v.check_count("n", x), 1.0, "n must be a positive integer"),
    (lambda x: v.check_count("processes", x, 0), -1, "processes must be a non-negative integer"),
    (lambda x: v.check_count("workers", x), True, "workers must be a positive integer, got True"),
    (lambda x: v.check_count("samples", x, 2, 10), 11, "samples must be an integer >= 2 and at most 10, got 11"),
    (v.check_omega, 0.0, "omega must be finite and non-zero"),
    (lambda x: v.check_choice("branch", x, (0, 1)), True, "branch must be 0 or 1, got True"),
    (lambda x: v.check_choice("branch", x, (0, 1)), 2, "branch must be 0 or 1, got 2"),
    (lambda x: v.check_choice("kind", x, ("a", "b", "c")), "d", "kind must be one of 'a', 'b', 'c'"),
    (lambda x: v.check_range("u_range", x), (1, 1), "u_range must satisfy min < max"),
    (lambda x: v.check_range("u_range", x), (0, math.nan), "u_range must not contain NaN"),
    (lambda x: v.check_range("u_range", x), 3, "u_range must be a pair"),
    (lambda x: v.check_finite("s", x), [0.0, math.nan], "s must be finite"),
    (lambda x: v.check_vector("origin", x), (0, 0), r"origin must have shape \(3,\)"),
    (lambda x: v.check_vector("origin", x), (0, math.inf, 0), "origin must be finite: entry 1 is inf"),
    (lambda x: v.check_points("points", x), np.empty((0, 3)), r"points must have shape \(N, 3\) with N >= 1"),
    (lambda x: v.check_points("vectors", x, count=2), np.zeros((3, 3)), "vectors must have 2 rows"),
    (lambda x: v.check_points("curve", x), [[0, 0, 0], [0, math.nan, 0]], "curve must be finite: row 1"),
    (lambda x: v.check_angles("crank_angles", x), [], "crank_angles is empty"),
    (lambda x: v.check_angles("crank_angles", x), [[0.0]], "crank_angles must be a finite 1-D array"),
    (lambda x: v.check_frame((0, 0, 0), x), np.diag([1.0, 1.0, -1.0]), "rotation must be right-handed"),
    (lambda x: v.check_frame((0, 0, 0), x), np.diag([1.0, 1.0, 2.0]), "rotation must be orthonormal"),
    (lambda x: v.check_real("max_length", x), 10 ** 400, "max_length must be finite, got an integer too large"),
    (lambda x: v.check_positive("tol", x), -10 ** 400, "tol must be finite, got an integer too large"),
    (v.check_omega, 10 ** 400, "omega must be finite and non-zero, got an integer too large"),
    (lambda x: v.check_range("v_range", x), (0, 10 ** 400), "v_range must have finite or infinite float ends"),
    (lambda x: v.check_angles("crank_angles", x), [0, 10 ** 400], "crank_angles must be a finite 1-D array"),
    (lambda x: v.check_vector("origin", x), (0, 10 ** 400, 0), "origin must be finite, got an integer too large"),
])
def test_bad_values_name_the_argument(check, bad, words):
    with pytest.raises(ValueError, match=words):
        check(bad)


@pytest.mark.parametrize("check", [lambda x: v.check_vector("origin", x), lambda x: v.check_finite("origin", x),
                                   lambda x: v.check_points("origin", x), lambda x: v.check_angles("origin", x)])
@pytest.mark.parametrize("bad, kind", [(np.array([1 + 1j, 0, 0]), "complex values"), ([0, 1j, 0], "complex values"),
                                       ([True, False, True], "bool values"), (np.array([1.0, 2.0], dtype=complex),
                                                                              "complex values"),
                                       (np.array(["1", "2"]), "str values"), (1 + 0j, "complex"),
                                       (np.bool_(True), "bool")])
def test_values_that_are_not_real_are_refused(check, bad, kind):
    """Complex, bool and str values raise TypeError naming the argument (numpy would cast them: dropping the
    imaginary part with a warning, reading True as 1)."""
    with pytest.raises(TypeError, match=f"origin must be an array of real numbers, got {kind}"):
        check(bad)


def test_points_may_be_empty_when_allowed():
    assert v.check_points("points", np.empty((0, 3)), allow_empty=True).shape == (0, 3)


#: Symmetric perturbations E of a rotation Q (R = Q (I + E)): their largest entry.
PERTURBATION = 1e-6
#: Round-off of a polar factor by LAPACK's SVD, and of forming R (seen: 12 eps off orthonormal, 22 eps from Q, over
#: 5000 draws).
ROUNDOFF = 32 * np.finfo(float).eps


def rotations(count, seed):
    """Proper rotations (count, 3, 3) from scipy's uniform sampler (independent of spatialkin)."""
    from scipy.spatial.transform import Rotation
    return Rotation.random(count, random_state=seed).as_matrix()


def test_orthonormalised_returns_the_polar_factor():
    """R = Q (I + E), E symmetric and small: its polar factor is Q exactly (I + E is symmetric positive definite).
    Oracle: Q; the result is orthonormal and has det +1 to ROUNDOFF, and moves R by no more than the perturbation."""
    rng = np.random.default_rng(7)
    for q in rotations(200, 7):
        e = rng.uniform(-PERTURBATION, PERTURBATION, (3, 3))
        e = 0.5 * (e + e.T)
        r = q @ (np.eye(3) + e)
        got = v.orthonormalised("r", r, 1e-5)
        assert np.max(np.abs(got.T @ got - np.eye(3))) <= ROUNDOFF
        assert abs(np.linalg.det(got) - 1.0) <= ROUNDOFF
        assert np.max(np.abs(got - q)) <= ROUNDOFF
        assert np.max(np.abs(got - r)) <= np.max(np.abs(q @ e)) + ROUNDOFF


def test_orthonormalised_keeps_a_rotation_orthonormal_to_roundoff():
    """A rotation already orthonormal to round-off comes back as given (its own entries)."""
    for q in rotations(50, 11):
        assert np.max(np.abs(q.T @ q - np.eye(3))) <= v.ROUNDOFF_DEVIATION
        assert np.array_equal(v.orthonormalised("q", q, v.ORTHONORMAL_TOL), q)


@pytest.mark.parametrize("rotation, tol, words", [
    (np.diag([1.0, 1.0, 1.002]), 1e-5, r"mirror must be orthonormal: max \|R\^T R - I\| = 0.004 > 1e-05 \(advice\)"),
    (np.diag([1.0, 1.0, -1.0]) + 1e-7, 1e-5, r"mirror must be right-handed \(det = \+1\), got a reflection"),
    (np.diag([1.0, 1.0, 1.0 + 1e-8]), v.ORTHONORMAL_TOL, r"mirror must be orthonormal: max \|R\^T R - I\| = 2e-08"),
    (np.eye(2), 1e-5, r"mirror must have shape \(3, 3\)"),
    (np.full((3, 3), np.nan), 1e-5, "mirror must be finite"),
])
def test_orthonormalised_refuses_naming_the_argument(rotation, tol, words):
    """Too far from orthonormal (the measured deviation in the message), a reflection, a bad shape or entry."""
    with pytest.raises(ValueError, match=words):
        v.orthonormalised("mirror", rotation, tol, advice=" (advice)")


@pytest.mark.parametrize("bad", ["3", True, None, [3.0]])
def test_omega_of_no_real_type_is_a_type_error(bad):
    with pytest.raises(TypeError, match="omega must be a real number"):
        v.check_omega(bad)
