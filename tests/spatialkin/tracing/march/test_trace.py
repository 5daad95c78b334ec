"""sk.trace: start points, closure, dense evaluation, drift, singular points and edges, against oracles.

[Looper]: "Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines
of the light industry" (in Ukrainian): the looper drive as torus ∩ sphere, started from the sphere's equator.
"""
import numpy as np
import pytest
from scipy.integrate import quad

import spatialkin as sk
from spatialkin.mechanisms.looper import reference

TOL = 1e-10


@pytest.fixture(scope="module")
def looper_pair():
    """The looper drive's reference geometry (mm; assumed: the [Looper] paper gives no dimensions)."""
    return reference.looper_pair()


def test_auxiliary_start_is_on_both_surfaces(looper_pair):
    """The start of [Looper]: the sphere's equator cut by the torus; oracle: exact distances and v2 = 0."""
    torus, sphere = looper_pair
    starts = sk.auxiliary_starts(torus, sphere)
    assert len(starts) >= 2
    assert np.all(starts[:, 3] == 0.0)
    pts = torus.point(starts[:, 0], starts[:, 1])
    np.testing.assert_allclose(pts, sphere.point(starts[:, 2], starts[:, 3]), atol=TOL * 30)
    assert np.max(torus.distance(pts)) < TOL * 30 and np.max(sphere.distance(pts)) < TOL * 30


@pytest.mark.parametrize("kwargs, error, words", [
    (dict(tol=0.0), ValueError, "tol must be a positive finite number"),
    (dict(tol=-1.0), ValueError, "tol must be a positive finite number"),
    (dict(tol=float("nan")), ValueError, "tol must be a positive finite number"),
    (dict(tol=1.0), ValueError, r"tol must lie in \(0, 1\)"),
    (dict(samples=2.7), ValueError, "samples must be an integer >= 2"),
    (dict(samples=0), ValueError, "samples must be an integer >= 2"),
    (dict(samples=10 ** 9), ValueError, "at most 10000000"),
    (dict(v=None), TypeError, "v must be a real number"),
    (dict(v=float("inf")), ValueError, "v must be finite"),
])
def test_auxiliary_starts_name_a_bad_argument(looper_pair, kwargs, error, words):
    """Options out of range are refused, naming them (a zero or NaN tol gave fewer starts, or none, silently)."""
    with pytest.raises(error, match=words):
        sk.auxiliary_starts(*looper_pair, **kwargs)
    with pytest.raises(TypeError, match="a must be a spatialkin surface"):
        sk.auxiliary_starts("a", looper_pair[1])


def test_looper_curve_closes_with_reference_length(looper_pair):
    """From the equator start at v1 ≈ 110° the ball-centre path is a closed loop 59.7 mm long (the reference
    geometry's path, measured by an independent script)."""
    torus, sphere = looper_pair
    starts = sk.auxiliary_starts(torus, sphere)
    start = starts[np.argmin(np.abs(starts[:, 1] - np.radians(110)))]
    curve = sk.trace(torus, sphere, start)
    assert curve.closed and curve.status == "closed"
    assert abs(curve.length - 59.7) < 0.05
    assert curve.max_distance < TOL * 30
    # the parameters reproduce the points on each surface (to 1e-9 mm)
    np.testing.assert_allclose(torus.point(curve.params[:, 0], curve.params[:, 1]), curve.points, atol=1e-9)
    np.testing.assert_allclose(sphere.point(curve.params[:, 2], curve.params[:, 3]), curve.points, atol=1e-9)
    # v1 stays in about 107°-114° (reference, measured independently)
    v1 = np.degrees(np.mod(curve.params[:, 1], 2 * np.pi))
    assert 106 < v1.min() and v1.max() < 115


def test_start_forms_give_the_same_curve(looper_pair):
    torus, sphere = looper_pair
    start = sk.auxiliary_starts(torus, sphere)[-1]
    by_params = sk.trace(torus, sphere, start)
    point = torus.point(start[0], start[1]) + np.array([0.3, -0.2, 0.1])   # near the curve, off it
    by_point = sk.trace(torus, sphere, point)
    assert by_params.closed and by_point.closed
    assert abs(by_params.length - by_point.length) < 1e-8 * by_params.length
    assert np.max(by_params.closest(by_point.points)[1]) < 1e-9


def test_plane_sphere_circle_closes_exactly():
    """Oracle: a circle of radius sqrt(R^2 - d^2) about the foot of the centre on the plane."""
    centre, radius = np.array([0.3, 0.1, 0.2]), 2.0
    normal = np.array([1.0, 1.0, 1.0]) / np.sqrt(3)
    plane = sk.Plane(sk.Frame.from_z_axis((0, 0, 1.0), normal))
    sphere = sk.Sphere(radius, sk.Frame(centre))
    d = (centre - np.array([0, 0, 1.0])) @ normal
    foot = centre - d * normal
    circle_radius = np.sqrt(radius ** 2 - d ** 2)
    curve = sk.trace(sphere, plane, foot + circle_radius * np.array([1, -1, 0]) / np.sqrt(2))
    assert curve.closed
    assert curve.points[-1].tolist() == curve.points[0].tolist()        # closed exactly
    assert curve.s[-1] == curve.length and np.all(np.diff(curve.s) > 0)
    assert abs(curve.length - 2 * np.pi * circle_radius) < 1e-8 * circle_radius   # one lap, no more
    np.testing.assert_allclose(np.linalg.norm(curve.points - foot, axis=1), circle_radius, atol=1e-12)
    np.testing.assert_allclose((curve.points - foot) @ normal, 0.0, atol=1e-12)


def test_dense_evaluation_on_both_surfaces_and_unit_speed(looper_pair):
    torus, sphere = looper_pair
    curve = sk.trace(torus, sphere, sk.auxiliary_starts(torus, sphere)[0])
    s = np.random.default_rng(0).uniform(0, curve.length, 2000)
    pts = curve(s)
    assert pts.shape == (2000, 3)
    assert np.max(curve.distances(pts)) < TOL * 30
    # arc length parametrisation: chord over a short arc equals the arc (curvature <= 1/5 mm here)
    h = 1e-4
    speed = np.linalg.norm(curve(s + h) - curve(s - h), axis=1) / (2 * h)
    np.testing.assert_allclose(speed, 1.0, atol=1e-7)
    # the tangent is the derivative of the position (central difference, h = 1e-4: error ~ 1e-9)
    np.testing.assert_allclose(curve.tangent(s), (curve(s + h) - curve(s - h)) / (2 * h), atol=1e-7)
    # periodic: s and s + length are the same point
    np.testing.assert_allclose(curve(s[:10] + curve.length), curve(s[:10]), atol=1e-9)


def test_drift_stays_flat_over_100_loops():
    """Traced on for 100 laps (each way) without closing: every point within tol of both surfaces, the solver's own
    gap flat from the first lap to the last, and the pull-back term smaller than without it."""
    torus = sk.Torus(3.0, 1.0)
    sphere = sk.Sphere(2.5, sk.Frame((1.0, 0.5, 0.7)))
    loop = sk.intersect(torus, sphere)[0]
    length = loop.length
    gaps = {}
    for pullback in (1.0, 0.0):
        long = sk.trace(torus, sphere, loop.points[0], close=False, max_length=100 * length, pullback=pullback)
        # traced 100 laps each way from the start, which sits at s = 100 * length
        assert long.status == "max_length" and abs(long.length - 200 * length) < 1e-9 * length
        assert long.max_distance < TOL * 2.5
        gap, s = long.solver_gap, long.s
        first = gap[np.abs(s - 100 * length) < length].max()
        last = max(gap[s < length].max(), gap[s > 199 * length].max())
        gaps[pullback] = (first, last)
    first, last = gaps[1.0]
    assert last <= 10 * first + 1e-13
    assert gaps[1.0][1] < gaps[0.0][1]


def test_villarceau_circles_pass_through_their_nodes():
    """A plane through the torus centre tilted by asin(r/R) cuts two Villarceau circles of radius R about
    (0, +-r, 0), crossing at the two points where the plane touches the torus. Each circle is traced as one
    closed curve straight through both nodes, without jumping to the other circle. Its length is 2 pi R to
    5e-10 R in both argument orders: each jump across a node counts the curve's arc, not its chord (the chords
    would make it 1.3e-9 R to 1.8e-9 R short)."""
    big, small = 3.0, 1.0
    theta = np.arcsin(small / big)
    normal = np.array([np.sin(theta), 0.0, np.cos(theta)])
    torus = sk.Torus(big, small)
    plane = sk.Plane(sk.Frame.from_z_axis((0, 0, 0), normal))
    node = big * np.cos(theta) * np.array([np.cos(theta), 0.0, -np.sin(theta)])
    for reverse in (True, False):
        curves = sk.intersect(plane, torus) if reverse else sk.intersect(torus, plane)
        assert len(curves) == 2 and all(abs(c.length - 2 * np.pi * big) < 5e-10 * big for c in curves)
    centres = []
    for c in curves:
        assert c.closed and len(c.nodes) == 2
        for pts in (c.points, c(np.linspace(0, c.length, 3000))):
            d = [np.abs(np.linalg.norm(pts - [0, sgn * small, 0], axis=1) - big) for sgn in (1, -1)]
            k = int(np.argmin([x.max() for x in d]))
            assert d[k].max() < 1e-11 * big                   # all on one circle: no branch jump
        centres.append(k)
        for p in c.nodes:
            assert min(np.linalg.norm(p - node), np.linalg.norm(p + node)) < 1e-5 * big
    assert sorted(centres) == [0, 1]


def test_viviani_figure_eight_is_one_curve_through_its_node():
    """Viviani's curve (sphere radius 2a ∩ cylinder radius a through the centre): x = a(1 + cos t),
    y = a sin t, z = 2a sin(t/2), a figure-eight through its node (2a, 0, 0), passed twice."""
    a = 1.0
    curves = sk.intersect(sk.Sphere(2 * a), sk.Cylinder(a, sk.Frame((a, 0, 0))))
    length = 2 * a * quad(lambda w: np.sqrt(1 + np.cos(w) ** 2), 0, 2 * np.pi)[0]
    assert len(curves) == 1
    c = curves[0]
    assert c.closed and abs(c.length - length) < 1e-9
    for p in (c.points, c(np.linspace(0, c.length, 3000))):
        np.testing.assert_allclose((p[:, 0] - a) ** 2 + p[:, 1] ** 2, a ** 2, atol=1e-12)
        np.testing.assert_allclose(np.linalg.norm(p, axis=1), 2 * a, atol=1e-12)
    assert len(c.nodes) == 2
    np.testing.assert_allclose(c.nodes, [[2 * a, 0, 0]] * 2, atol=1e-6)


def test_edges_of_a_trimmed_cylinder():
    """Plane z = -x through a cylinder trimmed to |z| <= 0.5: two arcs of the ellipse x = cos u, y = sin u,
    z = -cos u, for |cos u| <= 1/2, ending exactly on the rims."""
    cylinder = sk.Cylinder(1.0, v_range=(-0.5, 0.5))
    plane = sk.Plane(sk.Frame.from_z_axis((0, 0, 0), (1, 0, 1)))
    curves = sk.intersect(cylinder, plane)
    arc = quad(lambda u: np.sqrt(1 + np.sin(u) ** 2), np.pi / 3, 2 * np.pi / 3)[0]
    assert len(curves) == 2
    for c in curves:
        assert c.status == "boundary" and not c.closed
        np.testing.assert_allclose(np.abs(c.points[[0, -1], 2]), 0.5, atol=1e-12)
        assert np.all(np.abs(c.points[:, 2]) <= 0.5 + 1e-12)
        assert abs(c.length - arc) < 1e-8
    # the untrimmed cylinder gives the whole ellipse (perimeter of semi-axes sqrt(2) and 1)
    whole = sk.intersect(sk.Cylinder(1.0, v_range=(-2, 2)), plane)
    assert len(whole) == 1 and whole[0].closed
    assert abs(whole[0].length - 4 * arc * 1.5 / 1.5 * 0 - quad(lambda u: np.sqrt(1 + np.sin(u) ** 2), 0, 2 * np.pi)[0]) < 1e-8


def test_no_intersection_is_an_error_for_trace_and_empty_for_intersect():
    torus = sk.Torus(3.0, 1.0)
    far = sk.Sphere(1.0, sk.Frame((20.0, 0, 0)))
    assert sk.intersect(torus, far) == []
    with pytest.raises(sk.TracingError, match="no intersection point"):
        sk.trace(torus, far, (15.0, 0, 0))


@pytest.mark.parametrize("kwargs, name", [
    ({"tol": 0.0}, "tol"), ({"tol": -1e-10}, "tol"), ({"tol": np.nan}, "tol"), ({"rtol": -1.0}, "rtol"),
    ({"method": "Euler"}, "method"), ({"max_length": 0.0}, "max_length"), ({"singular_tol": 0}, "singular_tol"),
])
def test_bad_arguments_are_named(kwargs, name, looper_pair):
    torus, sphere = looper_pair
    start = sk.auxiliary_starts(torus, sphere)[0]
    with pytest.raises(ValueError, match=name):
        sk.trace(torus, sphere, start, **kwargs)


def test_bad_start_and_surfaces(looper_pair):
    torus, sphere = looper_pair
    with pytest.raises(ValueError, match="start"):
        sk.trace(torus, sphere, (1.0, 2.0))
    with pytest.raises(ValueError, match="start"):
        sk.trace(torus, sphere, (np.nan, 0, 0))
    with pytest.raises(TypeError, match="b must be"):
        sk.trace(torus, "sphere", (0, 0, 0))
    with pytest.raises(ValueError, match="tol"):
        sk.intersect(torus, sphere, tol=0)


def test_open_curve_evaluation_outside_is_an_error():
    cylinder = sk.Cylinder(1.0, v_range=(-0.5, 0.5))
    plane = sk.Plane(sk.Frame.from_z_axis((0, 0, 0), (1, 0, 1)))
    c = sk.intersect(cylinder, plane)[0]
    with pytest.raises(ValueError, match="s must lie"):
        c(c.length + 1.0)


def test_curve_speed_of_a_point_beside_the_curve():
    """kernels.curve.curve_speed_many on the plane z = 0 and the unit sphere (the unit circle), with M1 on the
    plane at radius 1 + d beside the circle and M2 on the equator: the integrated velocity is the unit tangent
    (no pull-back), and the foot point on the circle moves at 1 / (1 + d) (similar arcs). Oracle: that closed
    form, to 1e-13."""
    from spatialkin.kernels.march import curve as kc
    from spatialkin.kernels.geometry import surfaces as ks
    plane, sphere = sk.Plane(), sk.Sphere(1.0)
    for d in (0.0, 1e-7, 1e-3, -2e-2):
        for angle in (0.3, 2.0):
            on_circle = np.array([[np.cos(angle), np.sin(angle), 0.0]])
            uv_plane, uv_sphere = np.empty((1, 2)), np.empty((1, 2))
            ks.inverse(plane.data, (1.0 + d) * on_circle, uv_plane)
            ks.inverse(sphere.data, on_circle, uv_sphere)
            y = np.ascontiguousarray(np.hstack([uv_plane, uv_sphere]))
            speed = np.empty(1)
            kc.curve_speed_many(y, plane.data, sphere.data, 1.0, 0.0, 1e-14, 30, speed)
            assert speed[0] == pytest.approx(1.0 / (1.0 + d), rel=1e-13, abs=0.0)


def test_a_circle_the_solver_integrates_exactly_closes_after_one_lap():
    """Two coaxial cones meet in two circles about their axis; along each, the parameters run linearly in s, so the
    solver's error estimate is zero and its steps grow to most of a lap. Traced from 40 starts round the smaller
    circle (radius 0.045, the scene's scale 1.1), each trace closes after one lap: its length is 2 pi r, r the
    points' distance from the common axis (oracle: the frames' axis line), to 1e-9 relative; and it runs round it
    once (its parameter u on the second cone changes by 2 pi)."""
    rot = sk.rotation_about((0.3, -1.0, 0.4), 0.9)
    axis = rot[:, 2]
    a = sk.Cone(0.3605483438618241, sk.Frame(np.zeros(3), rot), v_range=(-0.8194389152712889, 1.1021087906142555))
    b = sk.Cone(0.48856714563997855, sk.Frame(-0.2 * axis, rot), v_range=(-1.8180393555929746, 1.6812331229361444))
    small = min(sk.intersect(a, b), key=lambda c: c.length)
    starts = small(np.linspace(0.0, small.length, 40, endpoint=False))
    for start in starts:
        loop = sk.trace(a, b, start)
        offset = loop.points - a.frame.origin
        radius = np.linalg.norm(offset - np.outer(offset @ axis, axis), axis=1)
        assert loop.closed and np.ptp(radius) < 1e-12
        assert abs(loop.length - 2 * np.pi * radius.mean()) <= 1e-9 * loop.length
        assert abs(abs(loop.params[-1, 2] - loop.params[0, 2]) - 2 * np.pi) < 1e-9


def test_a_branch_beside_an_apex_goes_round_it():
    """Two cones with perpendicular axes, the apex of the first 2.2e-4 off the second (its scale about 1): the curves
    on its two nappes pass 2.4e-4 and 1.2e-3 from the apex without meeting. sk.trace, without the topology stage's
    proof of where the singular points are, goes round the apex (an apex is a singular point of the curve only on
    both surfaces): traced from four points of each of the two curves near it, every dense sample lies on both
    surfaces (oracle: their exact distance functions, 1e-9), and the trace ends where sk.intersect's curve does."""
    a = sk.Cone(0.7067288711463966, sk.Frame((0.465, 0.234, 0.265), [[0.0, -1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]]),
                v_range=(-1.5216902476354528, 1.4586651536584672))
    b = sk.Cone(0.8283762795582951, sk.Frame((0.0, -0.128, -0.276), [[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]]),
                v_range=(0.350452639852212, 2.217356357903618))
    apex = a.frame.origin
    assert 1e-4 < b.distance(apex) < 1e-3
    near = [c for c in sk.intersect(a, b) if c.closest(apex)[1] < 1e-2]
    assert len(near) == 2
    for curve in near:
        ends = {tuple(np.round(curve.points[0], 9)), tuple(np.round(curve.points[-1], 9))}
        for s in np.linspace(0.0, curve.length, 6)[1:-1]:
            loop = sk.trace(a, b, curve(np.array([s]))[0])
            samples = loop.sample(2000)
            assert max(float(np.max(a.distance(samples))), float(np.max(b.distance(samples)))) < 1e-9
            assert {tuple(np.round(loop.points[0], 9)), tuple(np.round(loop.points[-1], 9))} == ends
