"""Surface kernels against oracles: closed-form points, finite-difference derivatives, exact distances.

[Looper]: "Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines
of the light industry" (in Ukrainian): the torus and sphere parametrisations.
"""
import numpy as np
import pytest
from tests.oracles.closed_forms import random_rotation, sphere_distance, torus_distance

import spatialkin as sk


def placed(kind, rng):
    frame = sk.Frame(rng.uniform(-3, 3, 3), random_rotation(rng))
    return {
        "ring": lambda: sk.Torus(3.0, 1.2, frame),
        "horn": lambda: sk.Torus(2.0, 2.0, frame),
        "spindle": lambda: sk.Torus(1.0, 2.5, frame),
        "sphere": lambda: sk.Sphere(2.2, frame),
        "plane": lambda: sk.Plane(frame),
        "cylinder": lambda: sk.Cylinder(1.7, frame),
        "cone": lambda: sk.Cone(0.6, frame),
    }[kind]()


KINDS = ["ring", "horn", "spindle", "sphere", "plane", "cylinder", "cone"]


@pytest.mark.parametrize("kind", KINDS)
def test_derivatives_match_finite_differences(kind):
    """First and second derivatives against central differences of point(); tolerance 1e-7 (h = 1e-5)."""
    rng = np.random.default_rng(1)
    surf = placed(kind, rng)
    h = 1e-5
    for u, v in rng.uniform(-2.5, 2.5, (5, 2)):
        d = surf.derivatives(u, v)
        np.testing.assert_allclose(d[0], surf.point(u, v), atol=1e-14)
        fd_u = (surf.point(u + h, v) - surf.point(u - h, v)) / (2 * h)
        fd_v = (surf.point(u, v + h) - surf.point(u, v - h)) / (2 * h)
        np.testing.assert_allclose(d[1], fd_u, atol=1e-7)
        np.testing.assert_allclose(d[2], fd_v, atol=1e-7)
        du = lambda uu, vv: surf.derivatives(uu, vv)[1]
        dv = lambda uu, vv: surf.derivatives(uu, vv)[2]
        np.testing.assert_allclose(d[3], (du(u + h, v) - du(u - h, v)) / (2 * h), atol=1e-7)
        np.testing.assert_allclose(d[4], (du(u, v + h) - du(u, v - h)) / (2 * h), atol=1e-7)
        np.testing.assert_allclose(d[5], (dv(u, v + h) - dv(u, v - h)) / (2 * h), atol=1e-7)


def test_closed_form_points():
    """The torus and sphere formulas of [Looper], frame applied by hand."""
    rng = np.random.default_rng(2)
    rot = random_rotation(rng)
    origin = np.array([1.0, -2.0, 0.5])
    torus = sk.Torus(8.0, 50.0, sk.Frame(origin, rot))
    sphere = sk.Sphere(30.0, sk.Frame(origin, rot))
    u, v = rng.uniform(-np.pi, np.pi, (2, 50))
    w = 8 + 50 * np.cos(v)
    np.testing.assert_allclose(torus.point(u, v), origin + np.stack([w * np.cos(u), w * np.sin(u), 50 * np.sin(v)], -1) @ rot.T, atol=1e-12)
    np.testing.assert_allclose(sphere.point(u, v), origin + 30 * np.stack([np.cos(v) * np.cos(u), np.cos(v) * np.sin(u), np.sin(v)], -1) @ rot.T, atol=1e-12)
    assert torus.point(u.reshape(5, 10), v.reshape(5, 10)).shape == (5, 10, 3)


@pytest.mark.parametrize("kind", KINDS)
def test_distance_along_normal_is_exact(kind):
    """A point moved by delta along the unit normal is at distance |delta| (delta below every curvature
    radius), to 1e-12."""
    rng = np.random.default_rng(3)
    surf = placed(kind, rng)
    for u, v in rng.uniform(-2.5, 2.5, (20, 2)):
        if kind == "cone" and abs(v) < 0.5:
            continue
        if kind in ("horn", "spindle"):
            w = surf.major_radius + surf.minor_radius * np.cos(v)
            if abs(w) < 0.5:
                continue
        n = surf.normal(u, v)
        p = surf.point(u, v)
        for delta in (0.0, 1e-3, -2e-2, 0.1):
            assert abs(surf.distance(p + delta * n) - abs(delta)) <= 1e-12


def test_torus_and_sphere_distance_match_independent_formula():
    rng = np.random.default_rng(4)
    rot = random_rotation(rng)
    frame = sk.Frame((0.5, 0.1, -0.3), rot)
    pts = rng.uniform(-6, 6, (500, 3))
    local = (pts - frame.origin) @ rot
    for big, small in ((3.0, 1.0), (1.0, 2.5)):
        np.testing.assert_allclose(sk.Torus(big, small, frame).distance(pts), torus_distance(local, big, small), atol=1e-13)
    np.testing.assert_allclose(sk.Sphere(2.0, frame).distance(pts), sphere_distance(pts, frame.origin, 2.0), atol=1e-13)


@pytest.mark.parametrize("kind", KINDS)
def test_parameters_invert_point(kind):
    """parameters(point(u, v)) gives back the same surface point (to 1e-12)."""
    rng = np.random.default_rng(5)
    surf = placed(kind, rng)
    uv = rng.uniform(-3, 3, (40, 2))
    if kind == "sphere":
        uv[:, 1] = rng.uniform(-1.5, 1.5, 40)
    pts = surf.point(uv[:, 0], uv[:, 1])
    back = surf.parameters(pts)
    np.testing.assert_allclose(surf.point(back[:, 0], back[:, 1]), pts, atol=1e-12)


@pytest.mark.parametrize("make, name, reason", [
    (lambda: sk.Torus(-1, 1), "major_radius", "positive"),
    (lambda: sk.Torus(1, 0), "minor_radius", "positive"),
    (lambda: sk.Torus(np.nan, 1), "major_radius", "finite"),
    (lambda: sk.Sphere(np.inf), "radius", "finite"),
    (lambda: sk.Sphere(1e-320), "radius", "supported lengths"),
    (lambda: sk.Cylinder(1, v_range=(2, 1)), "v_range", "min < max"),
    (lambda: sk.Cone(2.0), "half_angle", "pi/2"),
    (lambda: sk.Plane(u_range=(0, np.nan)), "u_range", "NaN"),
])
def test_bad_surface_arguments(make, name, reason):
    with pytest.raises(ValueError, match=reason) as info:
        make()
    assert name in str(info.value)


def test_frame_must_be_a_frame():
    with pytest.raises(TypeError, match="frame"):
        sk.Sphere(1.0, frame=np.eye(3))


def test_torus_shape_names():
    assert sk.Torus(3, 1).shape == "ring"
    assert sk.Torus(2, 2).shape == "horn"
    assert sk.Torus(1, 2).shape == "spindle"


def test_a_pickled_surface_comes_back_read_only():
    """A surface sent to a worker process (pickled) keeps its packed data and its frame's arrays read-only, as made
    (the compiled kernels are specialised on that flag: a writable copy would compile them again there), and equal
    to the original's."""
    import pickle
    frame = sk.Frame((1.0, -2.0, 3.0), sk.rotation_about((1.0, 1.0, 0.0), 0.7))
    for surface in (sk.Torus(2.0, 0.5, frame), sk.Sphere(1.5, frame), sk.Plane(frame, (-1.0, 1.0), (0.0, 2.0)),
                    sk.Cylinder(0.8, frame, (-1.0, 1.0)), sk.Cone(0.4, frame, (0.1, 2.0))):
        copy = pickle.loads(pickle.dumps(surface))
        assert not copy.data.flags.writeable
        assert not copy.frame.origin.flags.writeable and not copy.frame.rotation.flags.writeable
        assert np.array_equal(copy.data, surface.data) and type(copy) is type(surface)


def test_a_value_derived_from_a_surface_is_made_once_and_not_carried_to_other_data():
    """Surface.memo makes a derived value on the first request only (None kept as a value too); a copy with other
    packed data (with_data) and a pickled copy make their own: a closed-form intersection read through it (the
    plane's trims) gives, for the copy with wider trims, what a fresh plane with those trims gives."""
    import pickle
    made = []

    def count(surface):
        made.append(surface)
        return None

    plane = sk.Plane(sk.Frame((0.0, 0.0, 0.5)), (-0.5, 0.5), (-2.0, 2.0))
    assert plane.memo("probe", count) is None and plane.memo("probe", count) is None and made == [plane]
    for other in (plane.with_data(plane.data), pickle.loads(pickle.dumps(plane))):
        other.memo("probe", count)
        assert made[-1] is other
    assert len(made) == 3
    sphere = sk.Sphere(1.0)
    cut = sk.intersect(plane, sphere)                       # the circle of radius sqrt(0.75), cut by u = +-0.5
    assert len(cut) == 2 and not cut[0].closed
    wider = plane.with_data(np.concatenate([plane.data[:-4], [-3.0, 3.0, -3.0, 3.0]]))
    whole = sk.intersect(wider, sphere)
    assert len(whole) == 1 and whole[0].closed
    assert abs(whole[0].length - 2.0 * np.pi * np.sqrt(0.75)) < 1e-12
    assert [c.length for c in sk.intersect(plane, sphere)] == [c.length for c in cut]


def test_a_surface_read_by_an_intersection_is_freed_as_soon_as_it_is_dropped():
    """What an intersection keeps in a surface's memo holds no reference back to it: the surface is freed by its
    reference count alone (the cyclic collector off), as one that was never intersected."""
    import gc
    import weakref
    gc.disable()
    try:
        for other in (sk.Sphere(1.0), sk.Cylinder(0.5, sk.Frame((0.0, 0.0, 0.2)), (-2.0, 2.0))):
            plane = sk.Plane(sk.Frame((0.0, 0.0, 0.3)), (-2.0, 2.0), (-2.0, 2.0))
            assert sk.intersect(plane, other) and plane.memo("placed", lambda s: None) is not None
            alive = weakref.ref(plane)
            del plane
            assert alive() is None
    finally:
        gc.enable()
