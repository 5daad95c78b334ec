"""Bad input to the geometry layer (surfaces, frames, rotations): a TypeError for a wrong type, a ValueError for a
wrong value, each naming the argument; lengths outside the supported range are refused; coplanar patches that
share an area are coincident. Oracles: the named argument in the message, and the geometry of the plane cases
(areas and edges by hand)."""
import math

import numpy as np
import pytest

import spatialkin as sk
from spatialkin._lib.validation import LENGTH_MAX, LENGTH_MIN
from spatialkin.geometry.placement import CoincidentSurfacesError
from spatialkin.geometry.surfaces.plane import rectangles_overlap

NAN = float("nan")


@pytest.mark.parametrize("make, name", [
    (lambda: sk.Torus("8", 50), "major_radius"),
    (lambda: sk.Torus(True, 50), "major_radius"),
    (lambda: sk.Torus(None, 50), "major_radius"),
    (lambda: sk.Torus([8], 50), "major_radius"),
    (lambda: sk.Torus(8, np.bool_(True)), "minor_radius"),
    (lambda: sk.Sphere("1"), "radius"),
    (lambda: sk.Cylinder(False), "radius"),
    (lambda: sk.Cone("0.3"), "half_angle"),
    (lambda: sk.Plane(radius="1"), "radius"),
    (lambda: sk.Plane(radius=1, inner_radius=True), "inner_radius"),
    (lambda: sk.Frame("abc"), "origin"),
    (lambda: sk.Frame(None), "origin"),
    (lambda: sk.Frame(sk.Sphere(1)), "origin"),
    (lambda: sk.Frame((0, 0, 0), sk.Sphere(1)), "rotation"),
    (lambda: sk.rotation_about((0, 0, 1), "1"), "angle"),
    (lambda: sk.rotation_about("z", 1.0), "axis"),
    (lambda: sk.Torus(8, 3).point("a", 0), "u"),
    (lambda: sk.Torus(8, 3).point(0, None), "v"),
    (lambda: sk.Sphere(1).distance("abc"), "points"),
    (lambda: sk.Sphere(1).derivatives("0", 0), "u"),
])
def test_a_wrong_type_is_a_type_error_naming_the_argument(make, name):
    with pytest.raises(TypeError, match=rf"^{name} must"):
        make()


@pytest.mark.parametrize("make, name", [
    (lambda: sk.Sphere(1e-320), "radius"),
    (lambda: sk.Sphere(1e155), "radius"),
    (lambda: sk.Sphere(0.5 * LENGTH_MIN), "radius"),
    (lambda: sk.Sphere(2 * LENGTH_MAX), "radius"),
    (lambda: sk.Torus(8, 1e-40), "minor_radius"),
    (lambda: sk.Cylinder(1e33), "radius"),
    (lambda: sk.Plane(radius=1e-33), "radius"),
    (lambda: sk.Plane(radius=1, inner_radius=1e-300), "inner_radius"),
    (lambda: sk.Plane(u_range=(0, 1e33)), "u_range"),
    (lambda: sk.Plane(v_range=(0, 1e-40)), "v_range"),
    (lambda: sk.Cylinder(1, v_range=(-1e40, 0)), "v_range"),
    (lambda: sk.Cone(0.3, v_range=(0, 1e33)), "v_range"),
    (lambda: sk.Frame((1e33, 0, 0)), "origin"),
    (lambda: sk.Frame((0, 0, -1e300)), "origin"),
])
def test_a_length_out_of_the_supported_range_is_refused(make, name):
    with pytest.raises(ValueError, match=rf"^{name} must"):
        make()


@pytest.mark.parametrize("make, name", [
    (lambda: sk.Sphere(10 ** 400), "radius"),
    (lambda: sk.Torus(8, -10 ** 400), "minor_radius"),
    (lambda: sk.Plane(u_range=(0, 10 ** 400)), "u_range"),
    (lambda: sk.Sphere(1.0, u_range=(0, 10 ** 400)), "u_range"),
    (lambda: sk.Frame((0, 10 ** 400, 0)), "origin"),
    (lambda: sk.Frame((0, 0, 0), [[10 ** 400, 0, 0], [0, 1, 0], [0, 0, 1]]), "rotation"),
])
def test_an_integer_too_large_for_a_float_is_refused_by_name(make, name):
    """An int past the float range is a ValueError naming the argument, not Python's OverflowError."""
    with pytest.raises(ValueError, match=rf"^{name} must .*an integer too large for a float"):
        make()


def test_lengths_at_the_ends_of_the_range_are_accepted():
    """The ends themselves, a zero inner radius and infinite trims are valid."""
    assert sk.Sphere(LENGTH_MIN).radius == LENGTH_MIN and sk.Sphere(LENGTH_MAX).radius == LENGTH_MAX
    assert sk.Plane(radius=1, inner_radius=0).inner_radius == 0.0
    assert sk.Cylinder(1, v_range=(-math.inf, LENGTH_MAX)).v_range[1] == LENGTH_MAX
    assert sk.Frame((LENGTH_MAX, -LENGTH_MAX, 1e-300)).origin[0] == LENGTH_MAX
    assert sk.Sphere(np.float32(2.0)).radius == 2.0 and sk.Torus(np.int64(8), np.array(3.0)).minor_radius == 3.0


@pytest.mark.parametrize("scale", [1e-32, 1.0, 3e31])
def test_spheres_at_the_ends_of_the_range_meet_in_their_circle(scale):
    """Two spheres of radius R, centres R apart, meet in a circle of radius R sqrt(3)/2 (oracle: its length)."""
    curve, = sk.intersect(sk.Sphere(scale), sk.Sphere(scale, sk.Frame((scale, 0.0, 0.0))))
    assert abs(curve.length / scale - math.pi * math.sqrt(3.0)) <= 1e-9


@pytest.mark.parametrize("call, name", [
    (lambda t: t.point(NAN, 0.0), "u"),
    (lambda t: t.point(0.0, [0.0, math.inf]), "v"),
    (lambda t: t.distance((NAN, 0.0, 0.0)), "points"),
    (lambda t: t.parameters([[0.0, 0.0, 0.0], [0.0, -math.inf, 0.0]]), "points"),
    (lambda t: t.derivatives(0.0, NAN), "v"),
    (lambda t: t.normal(NAN, 0.0), "u"),
])
@pytest.mark.parametrize("surface", [sk.Torus(8, 3), sk.Sphere(2.0), sk.Plane(), sk.Cylinder(1.0), sk.Cone(0.3)],
                         ids=lambda s: type(s).__name__)
def test_no_nan_leaks_from_point_or_distance(surface, call, name):
    with pytest.raises(ValueError, match=rf"^{name} must be finite"):
        call(surface)


def test_empty_points_still_give_empty_distances():
    assert sk.Sphere(1).distance(np.zeros((0, 3))).shape == (0,)


@pytest.mark.parametrize("a, b", [
    (sk.Plane(), sk.Plane()),                                                     # two untrimmed planes
    (sk.Plane(radius=1), sk.Plane()),                                             # a disc in its plane
    (sk.Plane(), sk.Plane(radius=1)),
    (sk.Plane(), sk.Plane(sk.Frame((1e3 + 0.37, 5.1, 0.0)), radius=0.01)),        # a small disc far out
    (sk.Plane(radius=1), sk.Plane(sk.Frame((0, 0, 0), sk.rotation_about((1, 0, 0), math.pi)))),  # normal turned
    (sk.Plane(radius=1), sk.Plane(sk.Frame((1.99, 0.0, 0.0)), radius=1)),         # a lens 0.01 wide
    (sk.Plane(u_range=(0, 1)), sk.Plane(sk.Frame((0, 0, 0), sk.rotation_about((0, 0, 1), 0.3)), v_range=(5, 6))),
])
def test_coplanar_patches_sharing_an_area_are_coincident(a, b):
    with pytest.raises(CoincidentSurfacesError, match="the same plane and their patches overlap"):
        sk.intersect(a, b)


def test_coplanar_rectangles_meeting_along_an_edge_share_no_area():
    """Oracle: the overlap's area by hand (0 along an edge; a strip 0.1 wide where one half-plane, turned a half
    turn, reaches 0.1 past the other's edge)."""
    turned = sk.Frame((0, 0, 0), sk.rotation_about((0, 0, 1), math.pi))
    assert rectangles_overlap(sk.Plane(u_range=(0, 1)), sk.Plane(u_range=(1, 2))) is None
    assert rectangles_overlap(sk.Plane(u_range=(-math.inf, 0)), sk.Plane(turned, u_range=(-math.inf, 0))) is None
    lo, hi = rectangles_overlap(sk.Plane(u_range=(-math.inf, 0)), sk.Plane(turned, u_range=(-math.inf, 0.1)))
    assert abs(lo[0] + 0.1) <= 1e-15 and abs(hi[0]) <= 1e-15
    edge, = sk.intersect(sk.Plane(u_range=(0, 1), v_range=(0, 1)), sk.Plane(u_range=(1, 2), v_range=(0, 1)))
    assert abs(edge.length - 1.0) <= 1e-12
