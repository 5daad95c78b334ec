"""Closed forms of sk.intersect (spatialkin.tracing.closed.forms) against independent oracles: the general traced path
of the library on random placements of each pair kind (both argument orders, trimmed or not), scipy's quad for the
arc length, the surfaces' exact distance functions for the points; degenerate placements must be declined."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

import spatialkin as sk
import spatialkin.tracing.components as intersect_module
from spatialkin.geometry.frame import rotation_about
from spatialkin.tracing.closed.forms import closed_form
from spatialkin.tracing.closed.conic import ELLIPSE, HYPERBOLA, LINE, PARABOLA
from spatialkin.geometry.placement import CoincidentSurfacesError
from spatialkin.tracing.march.trace import (DEFAULT_METHOD, DEFAULT_PULLBACK, DEFAULT_RTOL, DEFAULT_SINGULAR_TOL,
                                      make_settings)

#: Random placements per pair kind (each in both argument orders).
CASES = 12
#: Lengths agree to this (relative): the traced length itself is off by up to about 1e-9 relative (seen: 1.1e-9
#: on a short hyperbola arc), the closed form's by round-off (test_arc_length_and_points: scipy quad to 1e-12) ...
LENGTH_TOL = 5e-9
#: ... and the points of one curve lie within this x scale of the other.
POINT_TOL = 1e-9
#: Stored points lie on both surfaces within this x the coordinates' magnitude (round-off).
ON_SURFACE = 1e-14
#: Arc length against scipy quad (relative).
QUAD_TOL = 1e-12


def frame(rng, spread=0.3):
    rot = rotation_about(rng.normal(size=3), rng.uniform(0.0, math.pi))
    return sk.Frame(rng.uniform(-spread, spread, 3), rot)


def plane_through(rng, near, trimmed, half=(0.6, 2.5)):
    """A plane through a point near `near`, trimmed to a random rectangle round it or not."""
    f = frame(rng)
    f = sk.Frame(near + rng.uniform(-0.3, 0.3, 3), f.rotation)
    if not trimmed:
        return sk.Plane(f)
    u0, v0 = rng.uniform(-0.5, 0.5, 2)
    hu, hv = rng.uniform(*half, 2)
    return sk.Plane(f, (u0 - hu, u0 + hu), (v0 - hv, v0 + hv))


def make_pair(kind, rng, k):
    """A random placement of the pair kind; k alternates the trims."""
    if kind == "plane-plane":
        return plane_through(rng, np.zeros(3), True), plane_through(rng, np.zeros(3), k % 3 != 0)
    if kind == "plane-sphere":
        sphere = sk.Sphere(rng.uniform(0.7, 1.3), frame(rng))
        return plane_through(rng, sphere.frame.origin, k % 2 == 0, half=(0.3, 1.5)), sphere
    if kind == "sphere-sphere":
        return sk.Sphere(rng.uniform(0.7, 1.3), frame(rng, 0.8)), sk.Sphere(rng.uniform(0.7, 1.3), frame(rng, 0.8))
    if kind == "plane-cylinder":
        cyl = sk.Cylinder(rng.uniform(0.5, 1.0), frame(rng), (-rng.uniform(1, 2), rng.uniform(1, 2)))
        return plane_through(rng, cyl.frame.origin, k % 2 == 0), cyl
    if kind == "plane-cone":
        trims = ((0.3, 3.0), (-2.0, 2.5), (-3.0, -0.5))[k % 3]
        cone = sk.Cone(rng.uniform(0.3, 0.8), frame(rng), trims)
        centre = cone.frame.to_global([0.0, 0.0, 0.5 * sum(trims)])
        return plane_through(rng, centre, k % 2 == 1), cone
    raise ValueError(kind)


KINDS = ("plane-plane", "plane-sphere", "sphere-sphere", "plane-cylinder", "plane-cone")


def general(a, b, monkeypatch):
    """sk.intersect by the general path (topology stage and tracing)."""
    with monkeypatch.context() as m:
        m.setattr(intersect_module, "CLOSED_FORMS", False)
        return sk.intersect(a, b)


def settings_of(a, b):
    anchor = np.concatenate([a.frame.origin, b.frame.origin])
    return make_settings(a, b, 1e-10, DEFAULT_METHOD, DEFAULT_RTOL, None, None, DEFAULT_SINGULAR_TOL,
                         DEFAULT_PULLBACK, True, anchor)


def compare(ours, theirs, scale):
    """The two lists describe the same components (see the module docstring)."""
    assert [(c.status, c.closed) for c in ours] == [(c.status, c.closed) for c in theirs]
    for c in ours:
        # curves of one length (to round-off) come in either order: the one lying on c
        ties = [g for g in theirs if abs(g.length - c.length) <= LENGTH_TOL * c.length]
        g = min(ties, key=lambda g: np.max(g.closest(c.points[::8])[1]))
        assert c.length == pytest.approx(g.length, rel=LENGTH_TOL)
        assert np.max(g.closest(c.points)[1]) <= POINT_TOL * scale
        assert np.max(c.closest(g.points)[1]) <= POINT_TOL * scale
        s = np.linspace(0.0, c.length, 23)
        points, tangents, bends = c.derivatives(s)
        assert np.allclose(points, c(s), rtol=0, atol=1e-13 * scale)
        s_g, gap = g.closest(points)
        assert np.max(gap) <= POINT_TOL * scale
        assert np.min(np.sum(tangents * g.tangent(s_g), axis=1)) >= 1 - 1e-9
        bend_g = g.derivatives(s_g)[2]
        assert np.max(np.linalg.norm(bends - bend_g, axis=1)) <= 1e-6 * max(1.0, np.max(np.linalg.norm(bend_g, axis=1)))
        # parameters: the same surface points (periodic ones up to whole turns), continuous along the curve
        params = c.parameters(s)
        for k, surf in enumerate(c.surfaces):
            assert np.allclose(surf.point(params[:, 2 * k], params[:, 2 * k + 1]), points, atol=1e-12 * scale)
            assert np.allclose(surf.point(c.params[:, 2 * k], c.params[:, 2 * k + 1]), c.points, atol=1e-12 * scale)
        if hasattr(c.result.sol, "conic"):     # (an axis circle, spatialkin.tracing.curve.exact: wrapped, as there)
            assert np.max(np.abs(np.diff(c.params, axis=0))) <= math.pi       # periodic ones unwrapped
        if c.closed:
            assert np.array_equal(c.points[0], c.points[-1])


@pytest.mark.parametrize("kind", KINDS)
def test_against_general_path(kind, monkeypatch):
    """Random placements, both orders: the closed form (it must handle most of them) gives what the traced path
    gives: statuses, closed flags, lengths (1e-9 rel), points within 1e-9 x scale of each other's curve, dense
    output (points, tangents, curvature vectors, parameters)."""
    rng = np.random.default_rng(sum(map(ord, kind)))
    handled = 0
    for k in range(CASES):
        a, b = make_pair(kind, rng, k)
        for pair in ((a, b), (b, a)):
            scale = settings_of(*pair).scale
            ours = sk.intersect(*pair)
            if ours and ours[0].topology.mode == "closed_form":
                handled += 1
            compare(ours, general(*pair, monkeypatch), scale)
    assert handled >= CASES          # most placements are transversal: handled in closed form


@pytest.mark.parametrize("kind", KINDS)
def test_arc_length_and_points(kind):
    """Arc lengths of the stored points against scipy quad of |C'(t)|; points on both surfaces to round-off."""
    rng = np.random.default_rng(7 + len(kind))
    for k in range(CASES):
        a, b = make_pair(kind, rng, k)
        found = closed_form(a, b, settings_of(a, b))
        for c in found or ():
            sol = c.sol
            magnitude = max(1.0, np.max(np.abs(c.points)))
            assert np.max([surf.distance(c.points) for surf in (a, b)]) <= ON_SURFACE * magnitude
            if not hasattr(sol, "conic"):
                continue                            # a circle about a common axis (spatialkin.tracing.curve.exact)
            conic = sol.conic
            t = sol.t_knots
            for i in (len(t) // 3, len(t) - 1):
                exact = quad(lambda x: conic.speed(np.array([x]))[0], t[0], t[i], epsabs=0, epsrel=1e-13,
                             limit=200)[0]
                assert c.s[i] == pytest.approx(exact, rel=QUAD_TOL, abs=1e-14 * c.length)
            s = np.linspace(0.0, c.length, 17, endpoint=not c.closed)     # s -> t by Newton: the arc length of the point reached is s
            back = [quad(lambda x: conic.speed(np.array([x]))[0], t[0], tt, epsabs=0, epsrel=1e-13, limit=200)[0]
                    for tt in sol.t_of(sol.wrap(s))]
            assert np.allclose(back, s, rtol=0, atol=1e-12 * c.length)


def test_each_conic_shape(monkeypatch):
    """Lines (two planes; a plane along a cylinder's axis), ellipses, both branches of a hyperbola (a plane
    steeper than the generatrix across a two-nappe cone), a parabola (a plane parallel to a generatrix): each
    against the general path."""
    cyl = sk.Cylinder(0.8, sk.Frame((0.1, 0.0, 0.0), rotation_about((1.0, 0.2, 0.0), 0.4)), (-2.0, 2.0))
    rot = cyl.frame.rotation                                           # a plane along the axis, 0.3 from it
    along = sk.Plane(sk.Frame(cyl.frame.origin + 0.3 * rot[:, 1], np.column_stack([rot[:, 2], rot[:, 0], rot[:, 1]])),
                     (-3, 3), (-3, 3))
    alpha = 0.5
    cone = sk.Cone(alpha, sk.Frame((0.0, 0.0, 0.0), np.eye(3)), (-2.0, 2.5))
    steep = sk.Plane(sk.Frame((0.3, 0.0, 0.0), rotation_about((0.0, 1.0, 0.0), math.pi / 2 - 0.2)))
    n = np.array([math.cos(alpha), 0.0, math.sin(alpha)])             # normal to a generatrix: parabola
    x = np.cross([0.0, 1.0, 0.0], n)
    tilted = sk.Plane(sk.Frame(0.6 * n, np.column_stack([x / np.linalg.norm(x), [0.0, 1.0, 0.0], n])))
    shapes = {}
    for a, b, shape, count in ((along, cyl, LINE, 2), (steep, cone, HYPERBOLA, 2), (tilted, cone, PARABOLA, 1)):
        ours = sk.intersect(a, b)
        assert len(ours) == count and ours[0].topology.mode == "closed_form"
        shapes[shape] = {c.result.sol.shape for c in ours}
        scale = settings_of(a, b).scale
        compare(ours, general(a, b, monkeypatch), scale)
        assert ours[0].to_bspline(1e-8).deviation <= 1e-8 * scale          # the dense output's C'' in use
    assert shapes == {LINE: {LINE}, HYPERBOLA: {HYPERBOLA}, PARABOLA: {PARABOLA}}
    ellipse = sk.intersect(sk.Plane(sk.Frame((0, 0, 0.5), rotation_about((1, 0, 0), 0.3))), cyl)
    assert ellipse[0].result.sol.shape == ELLIPSE


def declined(a, b):
    return closed_form(a, b, settings_of(a, b)) is None


def test_degenerate_placements_decline(monkeypatch):
    """Tangency along a cone's ruling through its apex or a cylinder's, coincidence, both surfaces unbounded:
    declined, and sk.intersect answers as its general path does (a line of tangency, an error). A plane touching a
    sphere is answered: the contact point (exactly here); so is a touch of a trim edge from outside: the point."""
    sphere = sk.Sphere(1.0)
    tangent = sk.Plane(sk.Frame((0.0, 0.0, 1.0), np.eye(3)), (-1, 1), (-1, 1))
    touch, = closed_form(tangent, sphere, settings_of(tangent, sphere))
    assert touch.status == "contact" and np.array_equal(touch.points, [[0.0, 0.0, 1.0]])
    assert [c.status for c in sk.intersect(tangent, sphere)] == ["contact"]
    cone = sk.Cone(0.5, sk.Frame(), (-1.0, 2.0))
    along = sk.Plane(sk.Frame((0.0, 0.0, 0.0), rotation_about((1.0, 0.0, 0.0), math.pi / 2 - 0.5)), (-3, 3), (-3, 3))
    assert declined(along, cone)                          # through the apex, tangent along a ruling
    assert [c.status for c in sk.intersect(along, cone)] == [c.status for c in general(along, cone, monkeypatch)]
    cyl = sk.Cylinder(0.8, sk.Frame(), (-1.0, 1.0))
    along = sk.Plane(sk.Frame((0.8, 0.0, 0.0), rotation_about((0.0, 1.0, 0.0), math.pi / 2)), (-2, 2), (-2, 2))
    assert declined(along, cyl)
    # a circle touching the rectangle from outside (the sphere's circle in z = 0.6 has radius 0.8: edge u = 0.8):
    # the patches meet in one point
    edge = sk.Plane(sk.Frame((0.0, 0.0, 0.6), np.eye(3)), (0.8, 2.0), (-2.0, 2.0))
    point, = closed_form(edge, sphere, settings_of(edge, sphere))
    assert point.length == 0 and np.allclose(point.points, [[0.8, 0.0, 0.6]], atol=1e-15)
    # coincident: the general path raises
    for a, b in ((sphere, sk.Sphere(1.0)), (tangent, sk.Plane(sk.Frame((0.5, 0.0, 1.0), np.eye(3)), (-1, 1), (-1, 1)))):
        assert declined(a, b)
        with pytest.raises(CoincidentSurfacesError):
            sk.intersect(a, b)
    with pytest.raises(ValueError, match="bounded pair"):              # the plane along the cylinder's axis
        sk.intersect(sk.Plane(sk.Frame((0.0, 0.0, 0.0), rotation_about((1.0, 0.0, 0.0), math.pi / 2))),
                     sk.Cylinder(1.0))


def moved(rotation, shift, origin, local=np.eye(3)):
    """The frame at `origin` with axes `local`, moved by the rigid motion x -> rotation x + shift."""
    return sk.Frame(rotation @ np.asarray(origin, float) + shift, rotation @ local)


#: Circles touching a plane's rectangle from inside, at edges or corners, each with its oracle: (name, the pair
#: from a rigid motion, the length, closed). The cylinder's circle in z = 2 has radius 1; the sphere's in z = 0.6
#: has radius 0.8; the cylinder's rims are the circles in z = 0 and z = 4.
TOUCHING = (
    ("inscribed in a square", lambda R, t: (sk.Cylinder(1.0, moved(R, t, (0, 0, 0)), (0.0, 4.0)),
                                            sk.Plane(moved(R, t, (0, 0, 2)), (-1.0, 1.0), (-1.0, 1.0))),
     2 * math.pi, True),
    ("touching three edges", lambda R, t: (sk.Cylinder(1.0, moved(R, t, (0, 0, 0)), (0.0, 4.0)),
                                           sk.Plane(moved(R, t, (0, 0, 2)), (-1.0, 2.0), (-1.0, 1.0))),
     2 * math.pi, True),
    ("half, ending in two corners", lambda R, t: (sk.Cylinder(1.0, moved(R, t, (0, 0, 0)), (0.0, 4.0)),
                                                  sk.Plane(moved(R, t, (0, 0, 2)), (0.0, 1.0), (-1.0, 1.0))),
     math.pi, False),
    ("quarter, between a corner and an edge", lambda R, t: (
        sk.Cylinder(1.0, moved(R, t, (0, 0, 0)), (0.0, 4.0)), sk.Plane(moved(R, t, (0, 0, 2)), (0.0, 1.0), (0.0, 3.0))),
     0.5 * math.pi, False),
    ("sphere's circle touching one edge", lambda R, t: (
        sk.Sphere(1.0, moved(R, t, (0, 0, 0))), sk.Plane(moved(R, t, (0, 0, 0.6)), (-2.0, 0.8), (-2.0, 2.0))),
     2 * math.pi * 0.8, True),
    ("on a cylinder's rim", lambda R, t: (sk.Cylinder(1.0, moved(R, t, (0, 0, 0)), (0.0, 4.0)),
                                          sk.Plane(moved(R, t, (0, 0, 4)))), 2 * math.pi, True),
)


@pytest.mark.parametrize("name, pair, length, closed", TOUCHING, ids=[c[0] for c in TOUCHING])
def test_circles_touching_trim_edges_from_inside(name, pair, length, closed):
    """A circle touching a trim edge from inside stays whole there, and one ending in a corner ends there once:
    one curve of the oracle's length (exact: 2 pi r, its half or quarter), closed or not, in both orders and in
    placements moved by random rigid motions, its points within round-off of both trimmed patches."""
    rng = np.random.default_rng(7)
    motions = [(np.eye(3), np.zeros(3))] + [(rotation_about(rng.normal(size=3), rng.uniform(0.0, math.pi)),
                                              rng.uniform(-3.0, 3.0, 3)) for _ in range(3)]
    for rotation, shift in motions:
        a, b = pair(rotation, shift)
        for first, second in ((a, b), (b, a)):
            curves = sk.intersect(first, second)
            assert len(curves) == 1, (name, [(c.status, c.length) for c in curves])
            curve = curves[0]
            assert abs(curve.length - length) <= 1e-12 * length
            assert curve.closed == closed and curve.status == ("closed" if closed else "boundary")
            for surface in (a, b):
                assert np.max(surface.distance(curve.points)) <= 1e-14 * 8


def test_a_line_of_tangency_along_a_trim_edge_is_kept():
    """A plane tangent to a cylinder along a ruling that is the plane's trim edge: the segment on the edge, length
    2 (the plane's trim along the axis), status 'tangent', on either side of the edge and in both orders."""
    cylinder = sk.Cylinder(1.0, sk.Frame(), (0.0, 4.0))
    turn = rotation_about((0.0, 1.0, 0.0), math.pi / 2)      # the plane's local z along x, its v along y
    for v_range in ((0.0, 1.0), (-1.0, 0.0), (-1.0, 1.0)):
        plane = sk.Plane(sk.Frame((1.0, 0.0, 0.0), turn), (-3.0, -1.0), v_range)
        for pair in ((cylinder, plane), (plane, cylinder)):
            curves = sk.intersect(*pair)
            assert [(c.status, c.closed) for c in curves] == [("tangent", False)], v_range
            assert abs(curves[0].length - 2.0) <= 1e-12


def test_nothing_and_orders():
    """Apart surfaces give nothing in closed form; parallel planes apart give nothing."""
    apart = sk.Plane(sk.Frame((0.0, 0.0, 3.0), np.eye(3)), (-1, 1), (-1, 1))
    assert closed_form(apart, sk.Sphere(1.0), settings_of(apart, sk.Sphere(1.0))) == []
    other = sk.Plane(sk.Frame((0.0, 0.0, 1.0), np.eye(3)), (-1, 1), (-1, 1))
    assert closed_form(apart, other, settings_of(apart, other)) == []
    assert sk.intersect(sk.Sphere(1.0), sk.Sphere(0.5, sk.Frame((3.0, 0.0, 0.0), np.eye(3)))) == []


def test_short_max_length_left_to_tracer(monkeypatch):
    """A max_length shorter than the curve: declined, the tracer stops there as before."""
    plane = sk.Plane(sk.Frame((0.0, 0.0, 0.2), np.eye(3)), (-2, 2), (-2, 2))
    ours = sk.intersect(plane, sk.Sphere(1.0), max_length=1.0)
    assert ours[0].topology.mode != "closed_form"
    assert sk.intersect(plane, sk.Sphere(1.0))[0].topology.mode == "closed_form"



@pytest.mark.parametrize("offset", [1e-7, -1e-7, 1e-9])
def test_a_plane_beside_a_cone_apex_cuts_a_small_ellipse(offset):
    """A plane `offset` from a double cone's apex, tilted 0.3 (less than the half angle 0.5): a small ellipse on one
    nappe. The closed form declines only a plane through the apex to round-off: the general path's search does not
    look so close to an apex on the other surface (a wider margin, such as 1e3 tolerances, would return [] in some
    placements, the loop in others). Oracle: the rulings' crossings with the plane, apex + t(u) d(u)
    with t = offset / (n . d(u)) for the nappe the plane meets, their chord sums of 4096 and 8192 points
    Richardson-extrapolated; lengths to 1e-9 (relative) plus the coordinates' round-off (1e-15: the 3.8e-9 ellipse
    at 1e-9 is fixed to 2.7e-8 of itself), points on both surfaces to 1e-15, in both orders and three placements."""
    half, tilt = 0.5, 0.3
    for seed in range(3):
        rng = np.random.default_rng(seed)
        rot = rotation_about(rng.normal(size=3), rng.uniform(0, 6))
        apex = rng.uniform(-1, 1, 3)
        cone = sk.Cone(half, sk.Frame(apex, rot), v_range=(-1.0, 1.0))
        plane_rot = rotation_about(rot[:, 0], tilt) @ rot
        normal = plane_rot[:, 2]
        plane = sk.Plane(sk.Frame(apex + offset * normal, plane_rot), (-2, 2), (-2, 2))

        def length(n):
            u = np.linspace(0.0, 2 * np.pi, n + 1)
            d = np.stack([math.sin(half) * np.cos(u), math.sin(half) * np.sin(u),
                          np.full_like(u, math.cos(half))], axis=1) @ rot.T
            t = offset / (d @ normal)                   # one sign all round: the nappe the plane meets
            pts = apex + t[:, None] * d
            return np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()

        exact = (4 * length(8192) - length(4096)) / 3
        for a, b in ((plane, cone), (cone, plane)):
            curves = sk.intersect(a, b)
            assert [c.status for c in curves] == ["closed"]
            assert abs(curves[0].length - exact) <= 1e-9 * exact + 1e-15
            assert curves[0].max_distance <= 1e-15


@pytest.mark.parametrize("tilt", [0.0, 0.3, 0.5, 0.6, 1.2, math.pi / 2])
def test_a_plane_through_a_cones_apex(tilt):
    """A plane through the apex of a double cone (half angle 30 deg, trimmed to |z| <= 2), at the angle `tilt` to
    the axis. Oracle: below the half angle it holds two rulings, each through the apex from rim to rim, of length
    4 / cos(30 deg) whatever their direction, crossing at the apex (each curve's node); above it, the apex alone
    (a contact point). Both orders, random rigid placements; points on both surfaces to round-off."""
    alpha = math.pi / 6
    rng = np.random.default_rng(11)
    for _ in range(3):
        rotation, shift = rotation_about(rng.normal(size=3), rng.uniform(0.0, math.pi)), rng.uniform(-3.0, 3.0, 3)
        cone = sk.Cone(alpha, sk.Frame(shift, rotation), (-2.0, 2.0))
        plane = sk.Plane(sk.Frame(shift, rotation @ rotation_about((0.0, 1.0, 0.0), math.pi / 2 - tilt)),
                         (-5.0, 5.0), (-5.0, 5.0))
        for pair in ((cone, plane), (plane, cone)):
            curves = sk.intersect(*pair)
            if tilt < alpha:
                assert [(c.status, c.closed) for c in curves] == [("boundary", False)] * 2
                for c in curves:
                    assert abs(c.length - 4.0 / math.cos(alpha)) <= 1e-12
                    np.testing.assert_allclose(c.result.nodes, [shift], rtol=0, atol=1e-14 * 8)
            else:
                assert [c.status for c in curves] == ["contact"]
                np.testing.assert_allclose(curves[0].points, [shift], rtol=0, atol=1e-14 * 8)
            for c in curves:
                for surface in pair:
                    assert np.max(surface.distance(c.points)) <= 1e-14 * 8


def test_a_cones_apex_outside_the_planes_patch_is_no_contact():
    cone = sk.Cone(math.pi / 6, sk.Frame(), (-2.0, 2.0))
    plane = sk.Plane(sk.Frame(), (0.5, 1.0), (0.5, 1.0))     # through the apex, the axis its normal
    assert sk.intersect(cone, plane) == [] and sk.intersect(plane, cone) == []


@pytest.mark.parametrize("height, rect", [(0.0, (-2.5, 2.5, -2.5, 2.5)), (0.3, (-2.0, 2.5, -3.0, 3.0)),
                                          (0.3, (0.0, 3.0, -3.0, 3.0)), (-0.45, (-1.0, 3.0, -3.0, 1.0))])
def test_a_trimmed_plane_normal_to_a_torus_axis(height, rect, monkeypatch):
    """Torus(2, 0.5) and a plane normal to its axis at `height`, trimmed to a rectangle: its parallels of radius
    2 +- sqrt(0.25 - height^2), in closed form, clipped by the rectangle (the outer one touching all four edges at
    height 0 stays whole). Oracles: the exact lengths of the whole circles and the total, and the general path,
    on random rigid placements in both orders."""
    rng = np.random.default_rng(13)
    half = math.sqrt(0.25 - height * height)
    for _ in range(2):
        rotation, shift = rotation_about(rng.normal(size=3), rng.uniform(0.0, math.pi)), rng.uniform(-3.0, 3.0, 3)
        torus = sk.Torus(2.0, 0.5, sk.Frame(shift, rotation))
        plane = sk.Plane(sk.Frame(shift + height * rotation[:, 2], rotation), rect[:2], rect[2:])
        for a, b in ((torus, plane), (plane, torus)):
            ours = sk.intersect(a, b)
            assert all(c.topology.mode == "closed_form" for c in ours)
            for c in ours:
                if c.closed:
                    assert min(abs(c.length - 2 * math.pi * (2.0 + s * half)) for s in (1, -1)) <= 1e-12 * c.length
            if height == 0.0:        # (the general path ends the touching circle at an edge: not an oracle here)
                assert [c.closed for c in ours] == [True, True]
                assert abs(sum(c.length for c in ours) - 2 * math.pi * 4.0) <= 1e-12 * 8 * math.pi
            else:
                compare(ours, general(a, b, monkeypatch), settings_of(a, b).scale)


def both(a, b):
    return sk.intersect(a, b), sk.intersect(b, a)


def test_faces_meeting_in_one_point_of_their_edges():
    """A rectangle whose edge touches a circle of the cylinder from outside meets it in that point; two
    perpendicular rectangles through a common corner meet in the corner: one point of length 0 (status
    'boundary'), exactly there, in both orders."""
    strip = sk.Plane(u_range=(-1.0, 1.0), v_range=(-1.0, 1.0))
    beside = sk.Cylinder(0.5, sk.Frame((1.5, 0.0, 0.0)), v_range=(-1.0, 1.0))
    x_wall = sk.Plane(sk.Frame((0.0, 0.0, 0.0), np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]).T),
                      u_range=(0.0, 10.0), v_range=(0.0, 10.0))
    y_wall = sk.Plane(sk.Frame((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]).T),
                      u_range=(-10.0, 0.0), v_range=(-10.0, 0.0))
    for (a, b), where in (((strip, beside), (1.0, 0.0, 0.0)), ((x_wall, y_wall), (0.0, 0.0, 0.0))):
        for curves in both(a, b):
            point, = curves
            assert point.length == 0 and point.status == "boundary" and "one point" in point.message
            assert np.allclose(point.points, [where], atol=1e-15)


def test_faces_sharing_an_edge():
    """Perpendicular rectangles sharing the edge x = y = 0, z in [0, 6]: that segment (its ends on both faces'
    edges); coplanar rectangles side by side: their common edge, a segment of tangency, or their common corner,
    a contact point; apart: nothing; overlapping: CoincidentSurfacesError."""
    x_wall = sk.Plane(sk.Frame((0.0, 0.0, 0.0), np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]).T),
                      u_range=(0.0, 10.0), v_range=(0.0, 10.0))
    y_wall = sk.Plane(sk.Frame((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]).T),
                      u_range=(-10.0, 0.0), v_range=(-4.0, 6.0))
    for curves in both(x_wall, y_wall):
        edge, = curves
        assert edge.status == "boundary" and edge.length == pytest.approx(6.0, abs=1e-14)
        assert sorted(edge.points[[0, -1]].tolist()) == [[0.0, 0.0, 0.0], [0.0, 0.0, 6.0]]
    square = sk.Plane(u_range=(0.0, 10.0), v_range=(0.0, 10.0))
    for origin, status, length in (((10.0, 3.0, 0.0), "tangent", 7.0), ((10.0, 10.0, 0.0), "contact", 0.0)):
        other = sk.Plane(sk.Frame(origin), u_range=(0.0, 10.0), v_range=(0.0, 10.0))
        for curves in both(square, other):
            common, = curves
            assert common.status == status and common.length == pytest.approx(length, abs=1e-14)
    assert all(c == [] for c in both(square, sk.Plane(sk.Frame((11.0, 3.0, 0.0)), u_range=(0.0, 10.0),
                                                      v_range=(0.0, 10.0))))
    with pytest.raises(CoincidentSurfacesError):
        sk.intersect(square, sk.Plane(sk.Frame((5.0, 3.0, 0.0)), u_range=(0.0, 10.0), v_range=(0.0, 10.0)))


@pytest.mark.parametrize("seed", range(4))
def test_spheres_beside_a_tangency_give_their_circle_or_touch(seed):
    """Two spheres 1e-12 to 1e-5 (of the scale) past or short of an inner or outer tangency, up to 1e5 from the
    origin: a circle (status 'closed') whose length is within its conditioning of the 50-digit closed form from the
    stored doubles (1e-12, plus 4 ulps of the coordinates over the distance to tangency, relative), a contact point
    where that distance is within 8 ulps, nothing where they are apart by more; never a circle of tangency (two
    spheres touch along none) and never the general path's answer."""
    import mpmath as mp
    rng = np.random.default_rng(seed)
    for _ in range(25):
        scale = 10 ** rng.uniform(-2, 2)
        offset = 10 ** rng.uniform(0, 5) * rng.normal(size=3) if rng.random() < 0.7 else np.zeros(3)
        ra, rb = scale * rng.uniform(0.5, 2.0), scale * rng.uniform(0.3, 2.0)
        touch = abs(ra - rb) if rng.random() < 0.5 else ra + rb
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        step = scale * 10 ** rng.uniform(-12, -5) * rng.choice([1.0, -1.0])
        a = sk.Sphere(ra, sk.Frame(tuple(offset)))
        b = sk.Sphere(rb, sk.Frame(tuple(offset + (touch + step) * direction)))
        with mp.workdps(50):
            d = mp.sqrt(sum((mp.mpf(float(x)) - mp.mpf(float(y))) ** 2
                            for x, y in zip(a.frame.origin, b.frame.origin)))
            big, small = mp.mpf(ra), mp.mpf(rb)
            inner, outer = d - abs(big - small), big + small - d
            away = float(min(abs(inner), abs(outer)))
            square = inner * (d + abs(big - small)) * outer * (big + small + d) / (4 * d * d)
            exact = float(2 * mp.pi * mp.sqrt(square)) if square > 0 else None
        circle_or_touch(a, b, away, exact, np.spacing(max(np.abs(offset).max(), ra + rb, float(d))))


@pytest.mark.parametrize("seed", range(4))
def test_a_plane_beside_a_sphere_tangency_gives_its_circle_or_touches(seed):
    """A plane (turned at random) 1e-12 to 1e-5 (of the scale) inside or outside a sphere's tangent plane, up to 1e5
    from the origin: a circle (status 'closed') within its conditioning of the 50-digit closed form from the stored
    doubles (2 pi sqrt(R^2 - h^2), h the centre's distance to the plane; 1e-12 plus 4 ulps of the coordinates over
    |R - h|, relative), a contact point where |R - h| is within 8 ulps, nothing where the plane misses by more; never
    a circle of tangency."""
    import mpmath as mp
    from tests.oracles.closed_forms import random_rotation
    rng = np.random.default_rng(seed)
    for _ in range(25):
        scale = 10 ** rng.uniform(-2, 2)
        offset = 10 ** rng.uniform(0, 5) * rng.normal(size=3) if rng.random() < 0.7 else np.zeros(3)
        radius, turn = scale * rng.uniform(0.5, 2.0), random_rotation(rng)
        step = scale * 10 ** rng.uniform(-12, -5) * rng.choice([1.0, -1.0])
        sphere = sk.Sphere(radius, sk.Frame(tuple(offset)))
        plane = sk.Plane(sk.Frame(tuple(offset + (radius - step) * turn[:, 2]), turn))
        with mp.workdps(50):
            z = [mp.mpf(float(x)) for x in np.asarray(plane.frame.rotation)[:, 2]]
            h = abs(sum((mp.mpf(float(c)) - mp.mpf(float(o))) * w
                        for c, o, w in zip(sphere.frame.origin, plane.frame.origin, z)))
            h /= mp.sqrt(sum(w * w for w in z))
            away = float(abs(mp.mpf(radius) - h))
            square = mp.mpf(radius) ** 2 - h * h
            exact = float(2 * mp.pi * mp.sqrt(square)) if square > 0 else None
        circle_or_touch(sphere, plane, away, exact, np.spacing(max(np.abs(offset).max(), radius)))


def circle_or_touch(a, b, away, exact, ulp):
    """In both argument orders: a contact point or nothing where the distance to tangency, away, is within 8 ulps
    (or the circle, where there is one); nothing where there is no circle (exact None); else one circle, status
    'closed', its length within 1e-12 + 4 ulp / away (relative) of exact."""
    for x, y in ((a, b), (b, a)):
        curves = sk.intersect(x, y)
        statuses = [c.status for c in curves]
        if away <= 8 * ulp:
            assert statuses in (["contact"], []) or statuses == ["closed"] and exact is not None
        elif exact is None:
            assert curves == []
        else:
            assert statuses == ["closed"], (statuses, away)
            bound = exact * (1e-12 + 4 * ulp / away)
            assert abs(curves[0].length - exact) <= bound, (curves[0].length, exact, bound)


@pytest.mark.parametrize("seed", range(3))
def test_a_plane_beside_a_cylinder_ruling_gives_two_lines_or_the_ruling(seed):
    """A plane parallel to a trimmed cylinder's axis, 1e-12 to 1e-5 (of the scale) inside or outside the tangent
    plane along a ruling, up to 1e5 from the origin: two lines (each 'boundary' at both rims), 2 sqrt(r^2 - h^2)
    apart within their conditioning of the 50-digit closed form from the stored doubles (h the axis's distance to
    the plane; 1e-12 plus 4 ulps of the coordinates over |r - h|, relative), nothing where the plane misses by more
    than 16 ulps; within 8 ulps, the ruling as a segment of tangency (the general path's answer)."""
    import mpmath as mp
    from tests.oracles.closed_forms import random_rotation
    rng = np.random.default_rng(seed)
    for _ in range(20):
        scale = 10 ** rng.uniform(-2, 2)
        offset = 10 ** rng.uniform(0, 5) * rng.normal(size=3) if rng.random() < 0.7 else np.zeros(3)
        radius, turn = scale * rng.uniform(0.5, 2.0), random_rotation(rng)
        step = scale * 10 ** rng.uniform(-12, -5) * rng.choice([1.0, -1.0])
        cylinder = sk.Cylinder(radius, sk.Frame(tuple(offset), turn), v_range=(-2.0 * scale, 2.0 * scale))
        facing = np.column_stack([turn[:, 2], -turn[:, 1], turn[:, 0]])        # normal along the cylinder's x
        plane = sk.Plane(sk.Frame(tuple(offset + (radius - step) * turn[:, 0]), facing))
        with mp.workdps(50):
            z = [mp.mpf(float(x)) for x in np.asarray(plane.frame.rotation)[:, 2]]
            h = abs(sum((mp.mpf(float(c)) - mp.mpf(float(o))) * w
                        for c, o, w in zip(cylinder.frame.origin, plane.frame.origin, z)))
            h /= mp.sqrt(sum(w * w for w in z))
            away = float(abs(mp.mpf(radius) - h))
            square = mp.mpf(radius) ** 2 - h * h
            exact = float(2 * mp.sqrt(square)) if square > 0 else None
        ulp = np.spacing(max(np.abs(offset).max(), radius))
        for x, y in ((cylinder, plane), (plane, cylinder)):
            curves = sk.intersect(x, y)
            statuses = [c.status for c in curves]
            if away <= 16 * ulp:
                assert statuses in (["tangent"], ["boundary", "boundary"], [])
            elif exact is None:
                assert curves == []
            else:
                assert statuses == ["boundary", "boundary"], (statuses, step / scale)
                middles = [np.asarray(c.points, dtype=float).mean(axis=0) for c in curves]
                apart = np.linalg.norm(np.cross(middles[0] - middles[1], turn[:, 2]))
                assert abs(apart - exact) <= exact * (1e-12 + 4 * ulp / away) + 4 * ulp, (apart, exact)
