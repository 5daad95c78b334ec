"""The step cap beside a near tangency (spatialkin.tracing.march.near_tangent) on Viviani's curve, whose normals'
sine vanishes at its node (1, 0, 0) (a sphere of radius 1 and a cylinder of radius 1/2 through its centre)."""
import math

import numpy as np

import spatialkin as sk
from spatialkin.tracing.march import near_tangent as nt
from spatialkin.tracing.march.ivp import node_distance

SPHERE, CYLINDER = sk.Sphere(1.0), sk.Cylinder(0.5, sk.Frame((0.5, 0.0, 0.0)))
NODE = np.array([1.0, 0.0, 0.0])


def viviani(t):
    """Viviani's point (3,) at angle t round the cylinder's axis (t = 0: the node)."""
    x, y = 0.5 + 0.5 * math.cos(t), 0.5 * math.sin(t)
    return np.array([x, y, math.sqrt(max(1.0 - x * x - y * y, 0.0))])


def cap_at(point, previous=math.inf, nodes=None):
    """step_cap at the point of both surfaces (their own charts), travelling either way, the search's nodes ((K, 3)
    or None) at node_distance."""
    y = np.concatenate([SPHERE.parameters(point), CYLINDER.parameters(point)])
    return nt.step_cap(y, SPHERE.data, CYLINDER.data, 1.0, 1e-7, previous, node_distance(point, nodes), 1.0)


def test_far_from_the_touching_point_no_cap_until_the_sine_falls():
    """At the top of the curve (0, 0, 1) the sine is 1/2: no cap, the segment ends where it falls below
    CAP_BELOW / BAND_RATIO."""
    cap, band = cap_at(viviani(math.pi))
    assert cap == math.inf and band == (nt.CAP_BELOW / nt.BAND_RATIO, math.inf)


def test_on_the_way_in_the_cap_is_a_share_of_the_distance_to_the_node():
    """At 1e-3 to 1e-6 from the node (by the closed form) the sine vanishes at about that distance: the cap is
    STEP_PER_SINE of it within a factor two, at most GROWTH times the previous cap, and the band is the sine's
    factor of two each way."""
    for t in (1e-3, 1e-4, 1e-5, 1e-6):
        point = viviani(t)
        distance = float(np.linalg.norm(point - NODE))
        cap, (lo, hi) = cap_at(point)
        assert 0.5 * nt.STEP_PER_SINE * distance <= cap <= 2.0 * nt.STEP_PER_SINE * distance
        assert math.isclose(hi / lo, nt.BAND_RATIO ** 2) and lo < nt.CAP_BELOW
        assert cap_at(point, previous=1e-3 * cap)[0] == nt.GROWTH * 1e-3 * cap


def test_no_cap_beside_a_node_the_search_proved():
    """Within NODE_CLEAR of a proven node the march passes it by a jump: no cap and no band."""
    assert cap_at(viviani(1e-4), nodes=NODE[None, :]) is None
    assert cap_at(viviani(1e-4), nodes=NODE[None, :] + 1.0) is not None
