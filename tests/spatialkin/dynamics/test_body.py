"""Mass properties (spatialkin.dynamics.Body): the helpers against the textbook moments of inertia written out
here (slender rod m L^2 / 12, thin disc m r^2 / 2 and m r^2 / 4, point mass), and bad input named."""
import numpy as np
import pytest

from spatialkin.dynamics import Body


def test_rod_disc_and_point_against_the_textbook():
    rod = Body.rod(0.3, 40.0, axis=(0.0, 0.0, 2.0), start=(1.0, 2.0, 3.0))
    np.testing.assert_allclose(rod.com, [1.0, 2.0, 23.0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(rod.inertia, np.diag([0.3 * 1600 / 12, 0.3 * 1600 / 12, 0.0]), rtol=1e-15, atol=1e-12)
    disc = Body.disc(2.0, 5.0, axis=(1.0, 0.0, 0.0))
    np.testing.assert_allclose(disc.inertia, np.diag([25.0, 12.5, 12.5]), rtol=1e-15)
    point = Body.point(0.5, (1.0, 0.0, 0.0))
    assert point.mass == 0.5 and not point.inertia.any() and point.com.tolist() == [1.0, 0.0, 0.0]
    tilted = Body.rod(1.0, 1.0, axis=(1.0, 1.0, 0.0))
    a = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)
    assert abs(a @ tilted.inertia @ a) < 1e-15                    # nothing about the rod's own axis
    n = np.array([1.0, -1.0, 0.0]) / np.sqrt(2.0)
    assert abs(n @ tilted.inertia @ n - 1.0 / 12.0) < 1e-15


@pytest.mark.parametrize("args, key", [((-1.0,), "mass"), ((np.nan,), "mass"), (("x",), "mass"),
                                       ((10 ** 400,), "mass must be a finite number >= 0 \\(kg\\), got an integer too"),
                                       ((1.0, (0.0, np.inf, 0.0)), "com"), ((1.0, (0.0, 1.0)), "com"),
                                       ((1.0, (0, 0, 0), [[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
                                        "symmetric"),
                                       ((1.0, (0, 0, 0), np.diag([1.0, -1.0, 1.0])), "positive semi-definite"),
                                       ((1.0, (0, 0, 0), np.eye(2)), "3 x 3"),
                                       ((1.0, (0, 0, 0), np.diag([1.0, np.nan, 1.0])), "finite")])
def test_bad_mass_properties_are_named(args, key):
    with pytest.raises(ValueError, match=key):
        Body(*args)


def test_combined_bodies_obey_the_parallel_axis_theorem():
    """Two point masses 4 apart on x: total 3 kg at their mass centre, m1 m2 / (m1 + m2) d^2 about y and z; a rod
    plus a point mass at its end: the rod's m L^2 / 12 shifted to the common centre, written out."""
    from spatialkin.dynamics import combined
    pair = combined(Body.point(1.0, (0.0, 0.0, 0.0)), Body.point(2.0, (4.0, 0.0, 0.0)))
    assert pair.mass == 3.0
    np.testing.assert_allclose(pair.com, [8.0 / 3.0, 0.0, 0.0], rtol=1e-15)
    np.testing.assert_allclose(pair.inertia, np.diag([0.0, 32.0 / 3.0, 32.0 / 3.0]), rtol=1e-14, atol=1e-14)
    both = combined(Body.rod(1.0, 2.0), Body.point(1.0, (2.0, 0.0, 0.0)))
    # centre at x = 1.5: the rod's 1/3 + 1 x 0.5^2, the point's 1 x 0.5^2, about y and z
    np.testing.assert_allclose(both.inertia, np.diag([0.0, 1 / 3 + 0.25 + 0.25, 1 / 3 + 0.25 + 0.25]), rtol=1e-14,
                               atol=1e-15)
