"""Starts for a component whose every start was lost (spatialkin.tracing.search.rescue): a thin loop beside a
near-tangency, seeded only at its ill-conditioned ends. Oracles: the loop's closed form (a sphere off a cylinder's
axis), the lines through the middles by hand."""
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

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



# --- cones whose apex lies on the other surface, a loop through the apex on one nappe ---------------------------
def apex_on_cylinder_pair():
    """A cone (half angle 0.364) whose apex lies on a cylinder (radius 0.934), its axis 69 degrees from the
    cylinder's normal there (a random placement of such pairs): the two branches through the apex cross at about
    3 degrees; on one nappe they run into a loop about 3.18 long, on the other they close within about 1.2e-3 of the
    apex, a sliver about 2e-5 wide."""
    cylinder = sk.Cylinder(0.9341446625800867, sk.Frame(
        [-0.30355982334655573, -0.4194247738109601, 0.4834425496553042],
        [[0.07370763159234561, 0.7051904549682373, 0.7051762951679086],
         [-0.9971725438944314, 0.0624887588786347, 0.04173814462713854],
         [-0.014632250276534364, -0.706258859934159, 0.7078024583288381]]), v_range=(-2.0, 2.0))
    cone = sk.Cone(0.36375903960281497, sk.Frame(
        [-0.8047387312904223, -1.0654297320354131, 0.9389473880600965],
        [[-0.5405673284665435, -0.7835612018608719, -0.3062985575102988],
         [0.04047944442958851, -0.38788017329548197, 0.9208204959398647],
         [-0.8403263520640154, 0.48536668004984923, 0.24139347117138754]]), v_range=(-1.5, 1.5))
    return cone, cylinder, lambda q: q[:, 0] ** 2 + q[:, 1] ** 2 - cylinder.radius ** 2


def apex_on_torus_pair():
    """A cone (half angle 0.600) whose apex lies on a torus (R 1.19, r 0.304), a random placement of such pairs: on
    one nappe the branches through the apex close within 1e-2 to 3e-2 of it, on the other they run into a loop."""
    torus = sk.Torus(1.188061906589534, 0.3044131156735492, sk.Frame(
        [0.03717085121410224, 0.3202678035179438, -0.22406174243482646],
        [[0.8520334491980986, -0.4704075611269035, -0.22968615082810181],
         [-0.4372631439607437, -0.8807668748338255, 0.18179839143683652],
         [-0.28781929119007443, -0.05446502207925649, -0.95613472742535]]))
    cone = sk.Cone(0.5997541924255974, sk.Frame(
        [-1.3238028711578245, 0.7279907980942535, 0.22516841045585873],
        [[0.33394159812722746, -0.9383381509666041, -0.0894680025529114],
         [0.8317487711084829, 0.2486835123258413, 0.4963370754404828],
         [-0.4434827965093592, -0.24016249735930373, 0.8635073734846627]]), v_range=(-1.5, 1.5))
    big, small = torus.major_radius, torus.minor_radius

    def implicit(q):
        square = np.sum(q * q, axis=1)
        return (square + big ** 2 - small ** 2) ** 2 - 4 * big ** 2 * (q[:, 0] ** 2 + q[:, 1] ** 2)
    return cone, torus, implicit


def nappe_points(cone, other, implicit, rho, nappe, samples=20001):
    """The points where the intersection crosses the circle of the cone's nappe (1 or -1) at distance rho from the
    apex: sign changes of the other surface's implicit function (in its local frame) round that circle, each
    bisected to round-off (closed forms of both surfaces)."""
    rot, apex = np.array(cone.frame.rotation), np.array(cone.frame.origin)
    tan = math.tan(cone.half_angle)

    def at(phi):
        w = np.stack([tan * np.cos(phi), tan * np.sin(phi), np.full_like(phi, float(nappe))], axis=-1)
        return apex + rho * (w / np.linalg.norm(w, axis=-1)[..., None]) @ rot.T

    def level(phi):
        q = (at(np.atleast_1d(phi)) - np.array(other.frame.origin)) @ np.array(other.frame.rotation)
        return implicit(q)

    phi = np.linspace(0.0, 2 * math.pi, samples)
    f = level(phi)
    roots = [brentq(lambda t: float(level(t)[0]), phi[k], phi[k + 1], xtol=1e-15)
             for k in np.nonzero(np.sign(f[1:]) != np.sign(f[:-1]))[0]]
    return at(np.array(roots)).reshape(-1, 3)


def test_a_loop_through_an_apex_within_the_arm_seeds_offset_is_traced():
    """The search seeds a node's arms 2e-2 of the scale from it; here the branches on one nappe close between 1e-2 and
    3e-2 from the apex (closed forms: two crossings of that nappe's circles up to 1e-2, none from 3e-2), so the
    seeds are moved closer, where Newton settles on them. The answer, in both argument orders, is one closed curve
    through the apex twice: every crossing of the nappes' circles from 1e-4 to 1.4 (200 of them, bisected) lies
    within 1e-12 of it, and it lies on both surfaces within 1e-14."""
    cone, torus, implicit = apex_on_torus_pair()
    assert torus.distance(np.array(cone.frame.origin)) <= 1e-15
    counts = {rho: len(nappe_points(cone, torus, implicit, rho, 1)) for rho in (1e-3, 1e-2, 3e-2, 1e-1)}
    assert counts == {1e-3: 2, 1e-2: 2, 3e-2: 0, 1e-1: 0}
    truth = np.vstack([nappe_points(cone, torus, implicit, rho, nappe, 4001)
                       for nappe in (1, -1) for rho in np.geomspace(1e-4, 1.4, 50)])
    assert len(truth) >= 150
    for a, b in ((cone, torus), (torus, cone)):
        curves = sk.intersect(a, b)
        assert [c.status for c in curves] == ["closed"]
        assert curves[0].max_distance <= 1e-14
        assert curves[0].closest(truth)[1].max() <= 1e-12


def test_a_loop_through_an_apex_shorter_than_the_jump_is_refused():
    """On the far nappe here the branches through the apex close within about 1.2e-3 of it (closed forms: two
    crossings of that nappe's circle at 1e-3, none at 1.9e-2, two on the other nappe at both), shorter than the
    tracer's jump across the apex. From a start on that sliver, sk.trace jumps across, runs round the other
    nappe's loop and lands on it again: it raises TracingError (the curve runs over itself) instead of returning
    that loop twice. sk.intersect refuses in both argument orders, with that reason (a known limit), naming an end
    within 1e-3 of the apex (the cone's origin, on the cylinder within 1e-15)."""
    cone, cylinder, implicit = apex_on_cylinder_pair()
    apex = np.array(cone.frame.origin)
    assert cylinder.distance(apex) <= 1e-15
    assert [len(nappe_points(cone, cylinder, implicit, rho, -1)) for rho in (1e-3, 1.9e-2)] == [2, 0]
    assert [len(nappe_points(cone, cylinder, implicit, rho, 1)) for rho in (1e-3, 1.9e-2)] == [2, 2]
    sliver = nappe_points(cone, cylinder, implicit, 8e-4, -1)[0]
    with pytest.raises(sk.TracingError, match="runs over itself"):
        sk.trace(cone, cylinder, sliver)
    for a, b in ((cone, cylinder), (cylinder, cone)):
        with pytest.raises(sk.TopologyError) as refused:
            sk.intersect(a, b)
        message = str(refused.value)
        assert "runs over itself" in message
        end = np.array([float(x) for x in message.split("its end [")[1].split("]")[0].split(",")])
        assert np.linalg.norm(end - apex) <= 1e-3
