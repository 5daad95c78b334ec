"""sk.Curve as a result built once (spatialkin.tracing.curve.result): a read-only view of a CurveResult record and its
dense output, distances to the surfaces measured lazily; the status table (spatialkin.tracing.curve.status); the
closed-form components (spatialkin.tracing.curve.exact). Oracles: the surfaces' closed-form distances, a circle's and a
point's closed forms."""
import dataclasses

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing.curve import status as st
from spatialkin.tracing.curve.result import RECORD_FIELDS, CurveResult

#: Round-off slack of a closed-form comparison (unit-size scenes).
ROUND_OFF = 1e-14


@pytest.fixture(scope="module")
def looper_curve():
    """A closed loop of a looper-like torus ∩ sphere (a spindle torus R 8, r 50), traced from a point."""
    torus, sphere = sk.Torus(8.0, 50.0), sk.Sphere(30.0, sk.Frame((20.0, 0.0, 40.0)))
    return sk.trace(torus, sphere, (20.0, 0.0, 10.0)), (torus, sphere)


def test_attributes_are_read_only_views_of_the_record(looper_curve):
    curve, _ = looper_curve
    assert isinstance(curve.result, CurveResult)
    for name in RECORD_FIELDS:
        assert getattr(curve, name) is getattr(curve.result, name)
        with pytest.raises(AttributeError):
            setattr(curve, name, None)
    with pytest.raises(dataclasses.FrozenInstanceError):
        curve.result.status = st.FAILED
    with pytest.raises(TypeError, match="CurveResult"):
        sk.Curve(curve.points)
    assert curve.topology is None and curve.certificate is None        # sk.trace: no search, nothing certified


def test_max_distance_is_measured_on_first_access(looper_curve):
    """Not at construction; then the largest closed-form distance of the points and the midpoints to either
    surface (the spindle torus of major radius R < minor radius r: its meridian circles about (+-R, 0) in the
    (rho, z) half-plane, | |(rho -+ R, z)| - r |; sphere: | |p - c| - R |)."""
    curve, (torus, sphere) = looper_curve
    fresh = sk.Curve(curve.result)
    assert "max_distance" not in vars(fresh)
    mid = fresh(0.5 * (fresh.s[1:] + fresh.s[:-1]))
    pts = np.vstack([fresh.points, mid])
    rho = np.hypot(pts[:, 0], pts[:, 1])
    on_torus = np.minimum(*(np.abs(np.hypot(rho + shift, pts[:, 2]) - 50.0) for shift in (-8.0, 8.0)))
    on_sphere = np.abs(np.linalg.norm(pts - (20.0, 0.0, 40.0), axis=1) - 30.0)
    expected = max(on_torus.max(), on_sphere.max())
    assert abs(fresh.max_distance - expected) <= ROUND_OFF * 60.0
    assert "max_distance" in vars(fresh) and fresh.max_distance < fresh.tolerance


def test_every_status_is_in_the_table_and_the_docstring():
    sphere = sk.Sphere(1.0)
    scenes = {
        st.CONTACT: sk.intersect(sphere, sk.Sphere(1.0, sk.Frame((2.0, 0.0, 0.0)))),
        st.TANGENT: sk.intersect(sphere, sk.Cylinder(1.0, v_range=(-2.0, 2.0))),
        st.BOUNDARY: sk.intersect(sphere, sk.Plane(frame=sk.Frame((0.0, 0.0, 0.5)), u_range=(-0.3, 2.0),
                                                   v_range=(-2.0, 2.0))),
        st.CLOSED: sk.intersect(sphere, sk.Cylinder(0.5, v_range=(-2.0, 2.0))),
    }
    for status, curves in scenes.items():
        assert curves and all(c.status == status for c in curves), status
    boundary = scenes[st.BOUNDARY][0]
    assert boundary.message.startswith("start end: ") and "; finish end: " in boundary.message
    contact = scenes[st.CONTACT][0]
    assert contact.message == st.outcome("contact", point=contact.points[0].tolist())[1]
    for status in st.CURVE_STATUSES:
        assert f"``'{status}'``" in sk.Curve.__doc__
    assert set(st.END_PRECEDENCE) <= set(st.CURVE_STATUSES) and set(st.MEANINGS) >= set(st.CURVE_STATUSES)


def test_tracing_errors_carry_a_status_of_the_table():
    with pytest.raises(sk.TracingError) as info:
        sk.trace(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((5.0, 0.0, 0.0))), (2.5, 0.0, 0.0))
    assert info.value.status == st.NO_START and str(info.value).startswith("no intersection point found near")
    with pytest.raises(ValueError, match="unknown status"):
        sk.TracingError("x", status="nonsense")
    record = dataclasses.asdict(sk.intersect(sk.Sphere(1.0), sk.Cylinder(0.5, v_range=(-2.0, 2.0)))[0].result)
    with pytest.raises(ValueError, match="status"):
        CurveResult(**{**record, "status": st.NO_START})           # a TracingError's status, not a curve's


def test_closed_form_components():
    """A contact is one point, at s = 0; a tangent circle is the circle, its curvature vector -(p - c) / r^2."""
    contact = sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((2.0, 0.0, 0.0))))[0]
    np.testing.assert_array_equal(contact([0.0, 0.0]), contact.points[[0, 0]])
    np.testing.assert_allclose(contact.points[0], (1.0, 0.0, 0.0), atol=ROUND_OFF)
    s, d = contact.closest([[1.0, 2.0, 0.0]])
    assert s[0] == 0.0 and abs(d[0] - 2.0) <= ROUND_OFF
    np.testing.assert_array_equal(contact.parameters(0.0), contact.params[0])
    circle = sk.intersect(sk.Sphere(1.0), sk.Cylinder(1.0, v_range=(-2.0, 2.0)))[0]
    s = np.linspace(0.0, circle.length, 7)
    points, tangents, bend = circle.derivatives(s)
    np.testing.assert_allclose(np.linalg.norm(points[:, :2], axis=1), 1.0, atol=ROUND_OFF)
    np.testing.assert_allclose(points[:, 2], 0.0, atol=ROUND_OFF)
    np.testing.assert_allclose(np.einsum("ij,ij->i", tangents, points), 0.0, atol=ROUND_OFF)
    np.testing.assert_allclose(bend, -points, atol=ROUND_OFF)
    assert circle.points[-1].tolist() == circle.points[0].tolist() and abs(circle.length - 2 * np.pi) <= ROUND_OFF


def test_arc_lengths_given_as_python_ints_past_int64_are_read_or_named():
    """curve(s) reads ints past numpy's int64 as floats (an array of objects), names an int too large for a float,
    and refuses what is no number; the oracle: the circle of radius 0.8 cut by z = 0.6, closed form."""
    curve, = sk.intersect(sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.6))))
    big = 10 ** 20                                  # (past int64, within a float: wraps around the loop)
    point = curve(big)
    assert abs(np.hypot(point[0], point[1]) - 0.8) < ROUND_OFF and abs(point[2] - 0.6) < ROUND_OFF
    assert np.array_equal(curve([0, big]), curve([0.0, float(big)]))
    for s in (10 ** 400, [0.5, 10 ** 400]):
        with pytest.raises(ValueError, match="^s must be finite, got an integer too large for a float"):
            curve(s)
    for s in ("a", True, None, [None, 1.0]):
        with pytest.raises(TypeError, match="^s must be real numbers"):
            curve(s)


def test_a_contact_point_takes_only_s_0():
    """A contact point (two unit spheres 2 apart touch at (1, 0, 0)) is an open curve of length 0: s = 0 gives the
    point, any other s (NaN, beyond, below) is refused as on any open curve."""
    point, = sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((2.0, 0.0, 0.0))))
    np.testing.assert_allclose(point([0.0, 0.0]), [[1.0, 0.0, 0.0]] * 2, atol=ROUND_OFF)
    with pytest.raises(ValueError, match="s must be finite"):
        point(np.nan)
    for s in (5.0, -1.0):
        with pytest.raises(ValueError, match=r"s must lie in \[0, 0\]"):
            point(s)


def test_far_points_are_named_not_overflowed():
    """Points farther than the supported lengths (1e32) are refused naming `points` by closest, distances and a
    surface's distance and parameters; within them the answer is the closed form's (the circle of radius 0.8 at
    z = 0.6, seen from (1e6, 0, 0): its nearest point (0.8, 0, 0.6), at the distance sqrt((1e6 - 0.8)^2 + 0.36))."""
    circle, = sk.intersect(sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.6))))
    traced = sk.intersect(sk.Torus(1.0, 0.4), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.3))))[0]
    far = [1e160, 0.0, 0.0]
    for call in (circle.closest, traced.closest, traced.distances, sk.Sphere(1.0).distance,
                 sk.Torus(1.0, 0.4).parameters):
        with pytest.raises(ValueError, match="points must have coordinates within 1e\\+32 of 0"):
            call(far)
    s, dist = circle.closest([1e30, 0.0, 0.0])
    assert dist == 1e30                           # (every point of the circle, to the round-off of 1e30)
    s, dist = circle.closest([1e6, 0.0, 0.0])     # (the distance settles the angle to sqrt(ulp(1e6) / 0.4))
    np.testing.assert_allclose(circle(s), [0.8, 0.0, 0.6], atol=1e-4)
    assert abs(dist - np.hypot(1e6 - 0.8, 0.6)) <= 1e-9
    with pytest.raises(TypeError, match="points must be an array of real numbers"):
        traced.distances("abc")


def viviani_bend(points, a, origin):
    """Curvature vectors (N, 3) of Viviani's curve x = a (1 + cos t), y = a sin t, z = 2 a sin(t / 2) (moved to
    origin) at its points (N, 3): (r'' - (r'' . T) T) / |r'|^2, t read from the point (the branch by z's sign)."""
    q = points - origin
    t = np.arctan2(q[:, 1], q[:, 0] - a)
    t = np.where(np.sign(q[:, 2]) == np.sign(np.sin(t / 2)), t, t + 2 * np.pi)
    d1 = np.stack([-a * np.sin(t), a * np.cos(t), a * np.cos(t / 2)], axis=1)
    d2 = np.stack([-a * np.cos(t), -a * np.sin(t), -0.5 * a * np.sin(t / 2)], axis=1)
    speed2 = np.einsum("ij,ij->i", d1, d1)
    tangent = d1 / np.sqrt(speed2)[:, None]
    return (d2 - np.einsum("ij,ij->i", d2, tangent)[:, None] * tangent) / speed2[:, None]


@pytest.mark.parametrize("offset, far_from, far_error", [(0.0, 1e-3, 1e-5), (1e4, 1e-2, 1e-4)])
def test_curvature_beside_a_node_is_nan_or_right(offset, far_from, far_error):
    """Viviani's curve (a sphere of radius 2 and a cylinder of radius 1 through its centre), at the origin and 1e4
    from it, passes its node twice. Beside the node C'' is NaN or within 1e-2 of the closed form's curvature vector
    (relative to its size), and 1e-5 of it from 1e-3 away (1e-4 from 1e-2 away at 1e4); at the node NaN (it was
    1.5e9 for a curvature of 0.5).
    The B-spline through the node stays within its tolerance of the curve (the distance of its points from the
    curve, measured by closest)."""
    origin = np.array([offset, 0.0, 0.0])
    curve, = sk.intersect(sk.Sphere(2.0, sk.Frame(origin)),
                          sk.Cylinder(1.0, sk.Frame(origin + (1.0, 0.0, 0.0)), v_range=(-3.0, 3.0)))
    node = curve.closest(curve.nodes[0])[0]
    offsets = np.concatenate([[0.0], np.geomspace(1e-12, 1e-1, 45)])
    for side in (1.0, -1.0):
        s = (node + side * offsets) % curve.length
        points, _, bend = curve.derivatives(s)
        true = viviani_bend(points, 1.0, origin)
        error = np.linalg.norm(bend - true, axis=1) / np.linalg.norm(true, axis=1)
        assert np.isnan(error[0])
        known = ~np.isnan(error)
        assert np.all(error[known] <= 1e-2)
        far = offsets >= far_from                  # (1e4 out, the coordinates' round-off is 2e-12)
        assert known[far].all() and np.all(error[far] <= far_error)
    spline = curve.to_bspline(1e-8)
    _, dist = curve.closest(spline(np.linspace(0.0, curve.length, 20001)))
    assert spline.deviation <= 1e-8 and dist.max() <= 1e-8 * 2.0


@pytest.mark.parametrize("kind", ["plane-torus", "sphere-cone", "cylinder-torus", "cone-cone"])
def test_point_gaps_are_the_farther_surfaces_distance_capped_plus_round_off(kind):
    """point_gaps (one compiled call: kernels.geometry.surfaces.farther_distances) at points scattered round each
    surface of a pair and far from it: the larger of the two distances by the oracle's own distance functions
    (tests.oracles.ssi.distance, from the parametrisations), at most the tolerance, plus GAP_ROUNDOFF_ULPS ulps of the
    point's largest coordinate; within 1e-12 of the scale plus 8 ulps of the coordinates (two ways of rounding)."""
    from spatialkin.bench.kinds import pair_kind_cases
    from spatialkin.tracing.curve.result import EPS, GAP_ROUNDOFF_ULPS, point_gaps
    from tests.oracles.ssi import distance
    a, b = {k: (x, y) for k, x, y in pair_kind_cases()}[kind]
    rng = np.random.default_rng(5)
    near = [np.asarray(s.point(rng.uniform(-3, 3, 50), rng.uniform(0.5, 1.5, 50)), dtype=float) for s in (a, b)]
    points = np.concatenate(near + [rng.normal(size=(50, 3))])
    points += rng.normal(size=points.shape) * 10.0 ** rng.uniform(-12, 0, (len(points), 1))
    for cap in (1e-6, np.inf):
        got = point_gaps(a, b, points, cap)
        want = np.minimum(np.maximum(distance(a, points), distance(b, points)), cap)
        want += GAP_ROUNDOFF_ULPS * EPS * np.abs(points).max(axis=1)
        assert np.all(np.abs(got - want) <= 1e-12 + 8 * EPS * np.abs(points).max(axis=1)), kind
