"""Components cut by CAD-face trims (spatialkin.tracing.curve.clip): the arcs against closed forms, the statuses at
edges touched from inside and outside or run along, the arcs' dense output, and the general path against the
untrimmed intersection clipped by an inside test written apart (tests.oracles.ssi.face_margin: atan2 angles)."""
import math

import numpy as np
import pytest

from tests.oracles.ssi import face_margin, to_local, trim_margin

import spatialkin as sk
from spatialkin.tracing.curve.result import TracingError
from spatialkin.geometry.placement import CoincidentSurfacesError

#: Arc ends and lengths of closed forms: within this many ulp of the coordinates (the ends are Brent roots on
#: the dense output, each point corrected onto both surfaces).
ENDS = 1e-14


def both_orders(a, b, **kw):
    return sk.intersect(a, b, **kw), sk.intersect(b, a, **kw)


def test_half_cylinder_cut_by_a_plane_is_a_half_circle():
    """The trimmed cylinder u in [0, pi] meets z = 2 in the half circle y >= 0 from (1, 0, 2) to (-1, 0, 2)."""
    half = sk.Cylinder(1.0, v_range=(0.0, 4.0), u_range=(0.0, math.pi))
    for curves in both_orders(half, sk.Plane(sk.Frame((0.0, 0.0, 2.0)))):
        arc, = curves
        assert arc.status == "boundary" and not arc.closed
        assert abs(arc.length - math.pi) <= ENDS
        ends = sorted(arc.points[[0, -1]].tolist())
        assert np.allclose(ends, [[-1.0, 0.0, 2.0], [1.0, 0.0, 2.0]], atol=ENDS)
        assert np.all(arc.points[:, 1] >= -ENDS)
        assert "trim edge u_m" in arc.message


def test_lower_nappe_of_a_cone_face_lies_opposite():
    """On the nappe z < 0 the points of u in [0, pi/2] lie at angles [pi, 3 pi / 2]: a quarter circle there."""
    cone = sk.Cone(math.pi / 4, v_range=(-2.0, 2.0), u_range=(0.0, math.pi / 2))
    for curves in both_orders(cone, sk.Plane(sk.Frame((0.0, 0.0, -1.0)))):
        arc, = curves
        assert abs(arc.length - math.pi / 2) <= ENDS
        assert np.all(arc.points[:, :2] <= ENDS)


def test_annulus_and_a_circle_touching_its_rim():
    """A circle of radius 0.5 about (0.5, 0) touches the unit disc's rim from inside at (1, 0): one arc between
    its crossings of the inner rim (radius 0.2), of length acos(-0.92), not cut at the touch. About (1.5, 0) it
    touches the rim from outside: the face holds one point of it, (1, 0, 0), returned as a point of length 0."""
    annulus = sk.Plane(radius=1.0, inner_radius=0.2)
    inside = sk.Cylinder(0.5, sk.Frame((0.5, 0.0, 0.0)), v_range=(-1.0, 1.0))
    for curves in both_orders(annulus, inside):
        arc, = curves
        assert arc.status == "boundary"
        assert abs(arc.length - math.acos(-0.92)) <= 4 * ENDS
        assert np.allclose(np.hypot(*arc.points[[0, -1], :2].T), 0.2, atol=ENDS)
    disc = sk.Plane(radius=1.0)
    for curves in both_orders(disc, inside):
        loop, = curves
        assert loop.closed and loop.status == "closed" and abs(loop.length - math.pi) <= 4 * ENDS
    outside = sk.Cylinder(0.5, sk.Frame((1.5, 0.0, 0.0)), v_range=(-1.0, 1.0))
    for curves in both_orders(disc, outside):
        point, = curves
        assert point.length == 0 and point.status == "boundary" and "one point" in point.message
        assert np.allclose(point.points, [[1.0, 0.0, 0.0]], atol=1e-6)      # a double root: sqrt(round-off)


def test_contact_segment_on_an_angular_edge_is_kept():
    """The plane x = 1 touches the cylinder along the ruling u = 0, the edge u_min of the face u in [0, pi/2]:
    the segment of tangency (length 2) lies on the face's edge and is returned."""
    face = sk.Cylinder(1.0, v_range=(0.0, 2.0), u_range=(0.0, math.pi / 2))
    wall = sk.Plane(sk.Frame((1.0, 0.0, 0.0), np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])))
    for curves in both_orders(face, wall):
        segment, = curves
        assert segment.status == "tangent" and abs(segment.length - 2.0) <= ENDS


def oracle_pieces(curves, a, b, n=40000):
    """(count, total length) of the pieces of the untrimmed curves inside both faces by the oracle's margins, on
    n samples per curve: the arc lengths between samples inside, and of each sample step crossing an edge the part
    inside by linear interpolation of the margin (within its square, about 1e-9 here)."""
    count, total = 0, 0.0
    for c in curves:
        s = np.linspace(0.0, c.length, n)
        p = c(s)
        m = np.minimum(trim_margin(a, p), trim_margin(b, p))
        inside = m >= 0
        step = np.diff(s)
        both, one = inside[1:] & inside[:-1], inside[1:] != inside[:-1]
        m0, m1 = m[:-1][one], m[1:][one]
        m_in = np.where(m0 >= 0, m0, m1)
        total += float(step[both].sum() + (step[one] * m_in / np.abs(m1 - m0)).sum())
        rises = np.count_nonzero(inside & ~np.roll(inside, 1)) if c.closed else \
            np.count_nonzero(inside[1:] & ~inside[:-1]) + int(inside[0])
        count += int(rises) if not inside.all() else 1
    return count, total


FACE_PAIRS = [
    (dict(u_range=(0.0, math.pi / 2)), (1.0, 0.0, 0.3), 1.0),
    (dict(u_range=(-0.3, 0.3)), (1.0, 0.0, 0.3), 1.0),                    # cuts both loops
    (dict(u_range=(-2.0, 2.5), v_range=(0.5, 4.0)), (1.0, 0.2, 0.3), 1.0),
    (dict(v_range=(-1.0, 1.0)), (0.9, 0.4, -0.2), 0.8),
]


@pytest.mark.parametrize("trims, centre, radius", FACE_PAIRS)
def test_torus_face_and_sphere_on_the_general_path(trims, centre, radius):
    """A torus face against a sphere (topology stage and tracer): the arcs are the untrimmed loops clipped by the
    oracle (count; total length within the polyline's chord error), in both orders; every point on both
    surfaces, inside both faces, the ends on an edge; the arcs' dense output consistent with their points."""
    torus, sphere = sk.Torus(1.0, 0.4, **trims), sk.Sphere(radius, sk.Frame(centre))
    whole = sk.intersect(sk.Torus(1.0, 0.4), sphere)
    count, total = oracle_pieces(whole, torus, sphere)
    for curves in both_orders(torus, sphere):
        assert len(curves) == count
        assert abs(sum(c.length for c in curves) - total) <= 1e-7
        for c in curves:
            assert c.max_distance <= c.tolerance
            margin = face_margin(torus, to_local(torus, c.points))
            assert margin.min() >= -1e-12
            if not c.closed:
                assert np.abs(margin[[0, -1]]).max() <= 1e-12
            assert np.allclose(c(c.s), c.points, atol=1e-12)
            for k, surface in enumerate(c.surfaces):
                assert np.allclose(surface.point(c.params[:, 2 * k], c.params[:, 2 * k + 1]), c.points, atol=1e-12)
            s, dist = c.closest(c(0.37 * c.length))
            assert abs(s - 0.37 * c.length) <= 1e-9 and dist <= 1e-12
            if not c.closed:
                with pytest.raises(ValueError, match="s must lie in"):
                    c(c.length * 1.01)


#: Narrow angular faces (surface, sphere radius, widths): a cylinder of radius 1 meets the sphere in the circles at
#: z = +-sqrt(R^2 - 1) of radius 1, a torus (2, 1) in circles of radius 2 +- ..., a double cone on both nappes.
NARROW = [(lambda u: sk.Cylinder(1.0, u_range=u), 1.5), (lambda u: sk.Torus(2.0, 1.0, u_range=u), 2.5),
          (lambda u: sk.Cone(0.5, v_range=(-2.0, 2.0), u_range=u), 1.5)]


@pytest.mark.parametrize("face, radius", NARROW)
@pytest.mark.parametrize("lo, width, tol", [(0.3, 5e-3, 1e-3), (0.3, 5e-3, 1e-10), (-1.0, 1e-4, 1e-10),
                                            (2.0, 3e-11, 1e-10), (0.0, 1e-11, 1e-10),
                                            (0.3, 5e-3, 1e-2)])
def test_narrow_angular_face(face, radius, lo, width, tol):
    """A face of an angular range narrower than the slack of the inside test (4 tolerances, at a radius of 1-3):
    two arcs, inside the face by the oracle's atan2 margin, of the face's width times the radius each (measured
    from the points: the arc length of a circle about the axis), or, where the width is below the tolerance, two
    points inside the face; never a point in the opposite wedge, where both edges' half-planes are within the
    slack of zero."""
    surface = face((lo, lo + width))
    sphere = sk.Sphere(radius)
    for curves in both_orders(surface, sphere, tol=tol):
        assert len(curves) == 2
        for c in curves:
            local = to_local(surface, c.points)
            rho = np.hypot(local[:, 0], local[:, 1])
            assert face_margin(surface, local).min() >= -c.tolerance
            assert c.max_distance <= c.tolerance
            if width * rho.max() > c.tolerance:
                assert c.status == "boundary" and not c.closed
                assert abs(c.length - width * rho[0]) <= 1e-9 * width + 4 * c.tolerance
            else:
                assert c.length == 0.0 and c.status == "boundary"


def test_arc_across_the_start_of_a_closed_component():
    """A face that keeps the piece of a closed circle across its s = 0: one arc, its parameters continuous."""
    sphere = sk.Sphere(1.0, u_range=(-0.5, 0.5))
    whole, = sk.intersect(sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.3))))
    arc, = sk.intersect(sphere, sk.Plane(sk.Frame((0.0, 0.0, 0.3))))
    assert abs(arc.length - math.sqrt(1 - 0.09)) <= ENDS           # radius sqrt(0.91) times the angle 1
    assert np.abs(np.diff(arc.params, axis=0)).max() < 0.1
    assert np.all(arc.points[:, 0] > 0.8)


def test_trace_returns_the_arc_through_the_start():
    half = sk.Cylinder(1.0, v_range=(0.0, 4.0), u_range=(0.0, math.pi))
    plane = sk.Plane(sk.Frame((0.0, 0.0, 2.0)))
    arc = sk.trace(half, plane, (0.0, 1.0, 2.0))
    assert arc.status == "boundary" and abs(arc.length - math.pi) <= 1e-9
    quarter = sk.Cylinder(1.0, v_range=(0.0, 4.0), u_range=(0.0, 0.5))
    with pytest.raises(TracingError, match="outside the trims"):      # a loop round (-1, 0, 2), at u = pi
        sk.trace(quarter, sk.Sphere(0.3, sk.Frame((-1.0, 0.0, 2.0))), (-1.0, 0.0, 2.3))


def test_patches_of_one_surface():
    with pytest.raises(CoincidentSurfacesError, match="share no area"):
        sk.intersect(sk.Sphere(1.0, u_range=(0.0, 1.0)), sk.Sphere(1.0, u_range=(2.0, 3.0)))
    with pytest.raises(CoincidentSurfacesError, match="overlap"):
        sk.intersect(sk.Sphere(1.0, u_range=(0.0, 1.0)), sk.Sphere(1.0, u_range=(0.5, 3.0)))
    # patches along a cylinder's or a cone's axis that abut or lie apart, in both orders and certified
    for a, b in ((sk.Cylinder(1.0, v_range=(0.0, 1.0)), sk.Cylinder(1.0, v_range=(1.0, 2.0))),
                 (sk.Cone(0.5, v_range=(0.0, 1.0)), sk.Cone(0.5, v_range=(-1.0, 0.0))),
                 (sk.Cylinder(1.0, v_range=(0.0, 1.0)), sk.Cylinder(1.0, v_range=(2.0, 3.0)))):
        for pair in ((a, b), (b, a)):
            for certify in (False, True):
                with pytest.raises(CoincidentSurfacesError, match="share no area"):
                    sk.intersect(*pair, certify=certify)


def test_many_pairs_with_faces_on_workers():
    face = sk.Torus(1.0, 0.4, u_range=(0.0, math.pi / 2))
    sphere = sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.3)))
    here = sk.intersect(face, sphere)
    there, = sk.intersect_many([(face, sphere)], workers=2)
    assert [c.length for c in there] == pytest.approx([c.length for c in here], abs=1e-12)
