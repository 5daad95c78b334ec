"""The independent oracles of tests/oracles checked against their own definitions (no spatialkin internals)."""
import numpy as np
import pytest

from tests.oracles.ssi import inverse_param, local_point

SHAPES = {"plane": {}, "sphere": {"R": 1.3}, "cylinder": {"r": 0.7}, "cone": {"t": np.tan(0.6)},
          "torus": {"R": 1.2, "r": 0.45}}
V_RANGES = {"plane": (-2.0, 2.0), "sphere": (-1.4, 1.4), "cylinder": (-2.0, 2.0), "cone": (-2.0, 2.0),
            "torus": (-3.0, 3.0)}


@pytest.mark.parametrize("k", sorted(SHAPES))
def test_inverse_param_gives_back_the_point(k):
    """inverse_param(local_point(u, v)) is a parameter point of the same surface point (to 1e-12), on both nappes of
    a cone and both sides of every seam: the oracle's windows and loop samples start from it."""
    rng = np.random.default_rng(7)
    u = rng.uniform(-np.pi, np.pi, 400)
    v = rng.uniform(*V_RANGES[k], 400)
    if k == "plane":
        u = rng.uniform(-2.0, 2.0, 400)
    p = local_point(k, SHAPES[k], u, v)
    back = local_point(k, SHAPES[k], *inverse_param(k, SHAPES[k], p))
    assert np.max(np.linalg.norm(back - p, axis=-1)) <= 1e-12
