"""Starts for a component whose every start was lost (spatialkin.tracing.search.rescue): a thin loop beside a
near-tangency, seeded only at its ill-conditioned ends. Oracles: the loop's closed form (a sphere off a cylinder's
axis), the lines through the middles by hand."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

import spatialkin as sk
from spatialkin.tracing import components as intersect_module
from spatialkin.tracing.search import rescue

RADIUS, OFFSET = 0.7, 1e-8


def off_axis_pair(seed):
    """A sphere of the cylinder's radius, its centre OFFSET off the axis along the frame's x (random frame): they
    meet in the loop z^2 = 2 OFFSET x - OFFSET^2 on the cylinder x = r cos t, y = r sin t, half round it and about
    2e-4 high, whose ends (cos t = OFFSET / 2r) are where the normals are within about 1e-8 of parallel."""
    rng = np.random.default_rng(seed)
    rot = sk.rotation_about(rng.normal(size=3), rng.uniform(0, 6))
    origin = rng.uniform(-1, 1, 3)
    sphere = sk.Sphere(RADIUS, sk.Frame(origin + OFFSET * rot[:, 0], rot))
    cylinder = sk.Cylinder(RADIUS, sk.Frame(origin, rot), v_range=(-2, 2))
    return sphere, cylinder, origin, rot


def loop_points(t, origin, rot, sign):
    """Points of the exact loop at angles t (N,), on its upper (sign 1) or lower arc."""
    z = sign * np.sqrt(2 * OFFSET * RADIUS * np.cos(t) - OFFSET ** 2)
    local = np.stack([RADIUS * np.cos(t), RADIUS * np.sin(t), z], axis=1)
    return origin + local @ rot.T


@pytest.mark.parametrize("seed", [0, 3])
def test_thin_loop_beside_a_near_tangency_is_found(seed):
    """The interior search seeds this loop only at its two ends, where Newton cannot locate it (every placement
    tried); the lines through the middle of the lost starts seed it. Its arcs stop beside the ends (status
    'singular': not passed) and cover the rest: every point of the exact loop away from the ends within 1e-9 of
    them, their lengths the loop's (quadrature of the closed form) less 1.1e-6 (measured), on both surfaces to
    round-off."""
    sphere, cylinder, origin, rot = off_axis_pair(seed)
    end = math.acos(OFFSET / (2 * RADIUS))

    def speed(t):
        z = math.sqrt(2 * OFFSET * RADIUS * math.cos(t) - OFFSET ** 2)
        return math.hypot(RADIUS, OFFSET * RADIUS * math.sin(t) / z)

    exact = 2 * quad(speed, -end, end, limit=200, epsabs=1e-12)[0]
    t = np.linspace(-end + 0.05, end - 0.05, 200)
    truth = np.vstack([loop_points(t, origin, rot, 1.0), loop_points(t, origin, rot, -1.0)])
    for a, b in ((sphere, cylinder), (cylinder, sphere)):
        curves = sk.intersect(a, b)
        assert curves and all(c.status in ("closed", "singular") for c in curves)
        total = sum(c.length for c in curves)
        assert exact - 1e-5 < total <= exact + 1e-9
        assert max(c.max_distance for c in curves) <= 1e-14
        gaps = np.min([c.closest(truth)[1] for c in curves], axis=0)
        assert gaps.max() <= 1e-9


def test_a_lost_component_raises_never_an_empty_list(monkeypatch):
    """Where the lines through the middles seed nothing either, sk.intersect raises TopologyError naming the lost
    starts rather than return a list without the component."""
    monkeypatch.setattr(intersect_module, "crossing_starts", lambda *args: np.empty((0, 3)))
    sphere, cylinder, _, _ = off_axis_pair(0)
    with pytest.raises(sk.TopologyError, match="neither located"):
        sk.intersect(sphere, cylinder)


def test_middle_lines_and_clusters_by_hand():
    """The lines u = middle and v = middle of each pair, a periodic u's also half a turn on (wrapped into the box,
    its seam -pi included); equal coordinates give no line; lost starts within the cluster radius share one
    representative."""
    box = np.array([-math.pi, math.pi, -1.0, 1.0])
    uv = np.array([[-1.0, 0.2], [1.0, 0.2], [3.0, -0.4]])
    lines = rescue.middle_lines(uv, box, (True, False))
    expected = {(0, -math.pi), (0, 0.0), (0, 1.0), (0, 1.0 - math.pi), (0, 2.0), (0, 2.0 - math.pi), (1, -0.1)}
    assert len(lines) == len(expected)
    for (fixed, value), (f2, v2) in zip(lines, sorted(expected)):
        assert fixed == f2 and abs(value - v2) < 1e-15
    points = [np.zeros(3), np.array([1e-4, 0, 0]), np.array([1.0, 0, 0]), np.array([1.0, 5e-4, 0])]
    reps = rescue.representatives(points, 1e-3)
    assert len(reps) == 2 and reps[0] is points[0] and reps[1] is points[2]
