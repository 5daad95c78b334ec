"""spatialkin.geometry.vectors.cross and cross_list are np.cross bit for bit (the oracle), on random and special
3-vectors."""
import numpy as np

from spatialkin.geometry.vectors import cross, cross_list


def test_cross_is_numpys_bit_for_bit():
    rng = np.random.default_rng(3)
    pairs = [(rng.normal(size=3) * 10.0 ** rng.integers(-8, 8), rng.normal(size=3)) for _ in range(2000)]
    pairs += [(np.eye(3)[i], np.eye(3)[j]) for i in range(3) for j in range(3)]
    for x, y in pairs:
        assert np.array_equal(cross(x, y), np.cross(x, y))
        assert np.array_equal(cross(list(x), tuple(y)), np.cross(x, y))
        floats = cross_list(x.tolist(), y.tolist())
        assert all(type(c) is float for c in floats) and np.array_equal(floats, np.cross(x, y))
