"""The exact solver of surfaces about one axis (spatialkin.tracing.search.exact): the placements it leaves to the
search, and its exact numbers against 60-digit arithmetic."""
from fractions import Fraction

import mpmath as mp
import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing.search import exact as ex


@pytest.mark.parametrize("pair", [
    (sk.Sphere(1.5), sk.Cylinder(1.5, sk.Frame((0, 0, 0), sk.rotation_about((1, 0, 0), 1e-3)))),   # turned
    (sk.Sphere(1.5), sk.Cylinder(1.5, sk.Frame((1e-9, 0, 0)))),                                    # moved off
    (sk.Sphere(1.5), sk.Cylinder(1.5, v_range=(0.0, 1.0))),                                        # ends on a trim
    (sk.Sphere(1.5), sk.Cylinder(1.5, u_range=(0.0, 1.0))),                                        # an arc
    (sk.Plane(sk.Frame((0, 0, 0.5)), u_range=(-1, 1), v_range=(-1, 1)), sk.Torus(2.0, 0.5)),       # cut
    (sk.Torus(0.5, 0.5), sk.Plane(sk.Frame((0, 0, 0.2)))),                                         # a horn torus
], ids=["turned", "moved", "trim-edge", "angular", "cut", "horn"])
def test_pairs_left_to_the_search(pair):
    """Placements this module does not decide give no exact points (and the search's certificate decides)."""
    assert ex.exact_points(*pair) is None


def test_surd_signs_against_high_precision():
    """Surd.sign is the sign of p + q sqrt(d) evaluated in 60 digits, on values whose two parts cancel to within
    1e-30, and its enclosure holds the value."""
    rng = np.random.default_rng(7)
    with mp.workdps(60):
        for _ in range(2000):
            d = Fraction(int(rng.integers(1, 10 ** 6)), int(rng.integers(1, 10 ** 3)))
            q = Fraction(int(rng.integers(-50, 51)), int(rng.integers(1, 20)))
            root = mp.sqrt(mp.mpf(d.numerator) / d.denominator)
            value = mp.mpf(q.numerator) / q.denominator * root
            near = Fraction(mp.nstr(-value, 50)) if rng.random() < 0.5 else Fraction(int(rng.integers(-99, 99)), 7)
            surd = ex.Surd(near, q, d)
            exact = mp.mpf(near.numerator) / near.denominator + value
            assert surd.sign() == (exact > 0) - (exact < 0)
            lo, hi = surd.enclosure()
            assert lo <= exact <= hi
