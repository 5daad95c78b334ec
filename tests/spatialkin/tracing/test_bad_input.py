"""Bad input to sk.intersect, sk.trace and a Curve: a TypeError for a wrong type, a ValueError for a value out of
its range, each naming the argument, before any numerics run. Oracles: the named argument in the message; the
defaults and the values the tests and notebooks use stay valid."""
import math

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing.march.trace import (DEFAULT_PULLBACK, DEFAULT_RTOL, DEFAULT_SINGULAR_TOL, PULLBACK_MAX,
                                            TOLERANCE_MIN, check_options)

TORUS = sk.Torus(8.0, 50.0)
SPHERE = sk.Sphere(30.0, sk.Frame((6, 0, 75), sk.rotation_about((1, 0, 0), -np.pi / 2)))
ON_CURVE = (12.3374, 0.0, 45.677)


@pytest.fixture(scope="module")
def curve():
    return sk.intersect(TORUS, SPHERE)[0]


@pytest.mark.parametrize("options, name", [
    (dict(atol=1e-300), "atol"),
    (dict(atol=1e-200), "atol"),
    (dict(atol=0.5 * TOLERANCE_MIN), "atol"),
    (dict(rtol=1e-300), "rtol"),
    (dict(rtol=0.5 * TOLERANCE_MIN), "rtol"),
    (dict(rtol=1.0), "rtol"),
    (dict(singular_tol=10.0), "singular_tol"),
    (dict(singular_tol=0.5), "singular_tol"),
    (dict(singular_tol=1e-300), "singular_tol"),
    (dict(pullback=1e6), "pullback"),
    (dict(pullback=2 * PULLBACK_MAX), "pullback"),
])
@pytest.mark.parametrize("run", [lambda o: sk.intersect(TORUS, SPHERE, **o),
                                 lambda o: sk.trace(TORUS, SPHERE, ON_CURVE, **o),
                                 lambda o: sk.intersect(sk.Plane(sk.Frame((0, 0, 0.6))), sk.Sphere(1.0), **o)],
                         ids=["intersect", "trace", "closed-form"])
def test_options_out_of_range_are_refused(run, options, name):
    with pytest.raises(ValueError, match=rf"^{name} must"):
        run(options)


def test_atol_below_the_scale_of_length_parameters_is_refused():
    """A plane's (u, v) are lengths: atol is at least TOLERANCE_MIN x the scale (1000 here). Oracle for the good
    atol: the great circle's length 2 pi 1000."""
    plane = sk.Plane(sk.Frame((0, 0, 0), sk.rotation_about((1, 0, 0), 0.5)), u_range=(-2e3, 2e3), v_range=(-2e3, 2e3))
    with pytest.raises(ValueError, match="^atol must be at least 1e-14 x the scale 1000"):
        sk.trace(plane, sk.Sphere(1e3), (1e3, 0.0, 0.0), atol=1e-13)
    circle = sk.trace(plane, sk.Sphere(1e3), (1e3, 0.0, 0.0), atol=1e-9)
    assert circle.closed and abs(circle.length - 2e3 * math.pi) <= 1e-6


@pytest.mark.parametrize("options, name", [
    (dict(tol="1e-10"), "tol"),
    (dict(tol=True), "tol"),
    (dict(rtol="1e-10"), "rtol"),
    (dict(atol=np.array(["1"])), "atol"),
    (dict(max_length="10"), "max_length"),
    (dict(singular_tol=None), "singular_tol"),
    (dict(pullback=[1.0]), "pullback"),
])
def test_options_of_a_wrong_type_are_type_errors(options, name):
    with pytest.raises(TypeError, match=rf"^{name} must be a real number"):
        sk.intersect(TORUS, SPHERE, **options)


def test_defaults_and_the_values_in_use_stay_valid():
    """The defaults, and the option values the tests, notebooks and bench pass (grep), are accepted."""
    check_options(1e-10, "compiled", DEFAULT_RTOL, None, None, DEFAULT_SINGULAR_TOL, DEFAULT_PULLBACK)
    for rtol in (1e-4, 1e-5, 1e-6, 1e-8, 1e-10, 1e-12, 1e-13, TOLERANCE_MIN):
        check_options(1e-10, "RK45", rtol, None, None, DEFAULT_SINGULAR_TOL, DEFAULT_PULLBACK)
    check_options(1e-10, "compiled", DEFAULT_RTOL, TOLERANCE_MIN, 1e7, 0.1, 0.0)
    check_options(1e-10, "compiled", np.float64(1e-10), np.float32(1e-9), np.int64(10), 1e-7, PULLBACK_MAX)


def test_options_checked_once_still_refuse_what_compares_equal():
    """Options kept from an earlier call are matched by type too: a bool equal to an accepted int, or an unhashable
    0-d array, is checked anew (the bool refused, the array read as its float)."""
    def options(**given):
        values = dict(tol=1e-10, method="compiled", rtol=DEFAULT_RTOL, atol=None, max_length=None,
                      singular_tol=DEFAULT_SINGULAR_TOL, pullback=DEFAULT_PULLBACK)
        values.update(given)
        return check_options(**values)

    assert options(pullback=1) == options(pullback=1) == options(pullback=1.0)
    with pytest.raises(TypeError, match="^pullback must be a real number") as refused:
        options(pullback=True)
    assert refused.value.__context__ is None                 # (raised once, not chained to a second check)
    assert options(tol=np.array(1e-9)) == options(tol=1e-9)
    with pytest.raises(ValueError, match="^tol must be"):
        options(tol=np.array(-1e-9))
    with pytest.raises(ValueError, match="^tol must be"):
        options(tol=float("nan"))


@pytest.mark.parametrize("close", [None, "no", 1, 0.0])
def test_close_must_be_a_bool(close):
    with pytest.raises(TypeError, match="^close must be a bool"):
        sk.trace(TORUS, SPHERE, ON_CURVE, close=close)


@pytest.mark.parametrize("start", ["abc", None, sk.Frame(), object()])
def test_a_start_that_is_no_array_of_numbers_is_a_type_error(start):
    with pytest.raises(TypeError, match="^start must be an array of real numbers"):
        sk.trace(TORUS, SPHERE, start)


def test_certify_takes_only_its_three_values():
    with pytest.raises(ValueError, match="^certify must be False, True or 'strict'"):
        sk.intersect(TORUS, SPHERE, certify=1)


@pytest.mark.parametrize("call, error, name", [
    (lambda c: c("1.0"), TypeError, "s"),
    (lambda c: c(None), TypeError, "s"),
    (lambda c: c.tangent(True), TypeError, "s"),
    (lambda c: c.closest((0, 0)), ValueError, "points"),
    (lambda c: c.closest((math.nan, 0, 0)), ValueError, "points"),
    (lambda c: c.closest("abc"), TypeError, "points"),
    (lambda c: c.sample(-5), ValueError, "n"),
    (lambda c: c.sample(2.5), ValueError, "n"),
])
def test_curve_arguments_are_checked(curve, call, error, name):
    with pytest.raises(error, match=rf"^{name} must"):
        call(curve)


def test_curve_good_arguments_still_work(curve):
    """Oracles: the stored points (s = 0 is the first), the empty cases' shapes."""
    assert np.allclose(curve(np.int64(0)), curve.points[0], rtol=0, atol=1e-9)
    assert curve(np.array([])).shape == (0, 3) and curve.sample(0).shape == (0, 3)
    s, d = curve.closest(curve.points[:3])
    assert s.shape == (3,) and float(d.max()) <= 1e-9
