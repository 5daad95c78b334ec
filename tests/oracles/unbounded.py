"""Random pairs of unbounded surfaces (untrimmed planes, cylinders and cones), reproducible by seed."""
import numpy as np

import spatialkin as sk
from tests.oracles.closed_forms import random_rotation


def unbounded_pair(seed, spread, radii, half_angles):
    """(a, b): kinds from the seed (plane, cylinder, cone: seed % 3 and seed // 3 % 3), origins uniform in
    [-spread, spread]^3, random axes, radii and half angles uniform in the given (low, high) ranges."""
    rng = np.random.default_rng(seed)
    makers = [lambda f: sk.Plane(f), lambda f: sk.Cylinder(rng.uniform(*radii), f),
              lambda f: sk.Cone(rng.uniform(*half_angles), f)]
    a = makers[seed % 3](sk.Frame(rng.uniform(-spread, spread, 3), random_rotation(rng)))
    b = makers[(seed // 3) % 3](sk.Frame(rng.uniform(-spread, spread, 3), random_rotation(rng)))
    return a, b
