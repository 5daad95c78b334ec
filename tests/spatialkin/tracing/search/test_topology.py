"""The topology stage of sk.intersect on cases where components are easily lost, and its special configurations.
Oracles: closed-form circles, lines and lengths; exact distance functions (tests/oracles/closed_forms.py)."""
import math
import warnings

import numpy as np
import pytest
from tests.oracles.closed_forms import random_rotation
from tests.oracles.measure import on_both

import spatialkin as sk
from spatialkin.tracing.search import topology as tp

TOL = 1e-10


def lengths(curves):
    return sorted(round(c.length, 6) for c in curves)


def test_shaft_through_a_ball():
    """Sphere(10) and Cylinder(5) about one axis: two circles of radius 5 (length 10 pi), in either order, with
    the axis moved, tilted, or the sphere off-centre along it."""
    for frame in (sk.Frame(), sk.Frame((1.0, 2.0, 3.0)), sk.Frame((0, 0, 0), sk.rotation_about((1, 1, 0), 0.7))):
        sphere = sk.Sphere(10.0, sk.Frame(frame.to_global([0, 0, 1.5])))
        cylinder = sk.Cylinder(5.0, frame, v_range=(-12, 12))
        for a, b in ((sphere, cylinder), (cylinder, sphere)):
            curves = sk.intersect(a, b, TOL)
            assert lengths(curves) == [round(10 * math.pi, 6)] * 2
            assert all(c.closed for c in curves) and on_both(curves, a, b) < 1e-13


def test_sphere_plane_and_cone_sphere():
    """Plane z = 3 cuts Sphere(10) in a circle of radius sqrt(91); a 30-degree cone cuts Sphere(5) in a circle of
    radius 2.5."""
    curves = sk.intersect(sk.Sphere(10.0), sk.Plane(sk.Frame((0, 0, 3))))
    assert lengths(curves) == [round(2 * math.pi * math.sqrt(91), 6)]
    curves = sk.intersect(sk.Cone(np.radians(30), v_range=(0, 10)), sk.Sphere(5.0))
    assert lengths(curves) == [round(2 * math.pi * 2.5, 6)]


def test_sphere_cut_round_its_own_pole_axis():
    """Plane z = 0.3 on Sphere(1) and two equal spheres one above the other: one circle each, whatever the
    sphere's frame (tilted by 1e-8 or not)."""
    for tilt in (0.0, 1e-8, 0.4):
        sphere = sk.Sphere(1.0, sk.Frame((0, 0, 0), sk.rotation_about((1, 0, 0), tilt)))
        assert lengths(sk.intersect(sphere, sk.Plane(sk.Frame((0, 0, 0.3))))) == \
            [round(2 * math.pi * math.sqrt(1 - 0.09), 6)]
        other = sk.Sphere(1.0, sk.Frame((0, 0, 1.2)))
        assert lengths(sk.intersect(sphere, other)) == [round(2 * math.pi * math.sqrt(1 - 0.36), 6)]


def test_coincident_patches_raise():
    """The same sphere twice, the same torus twice, coaxial equal cylinders, coplanar overlapping planes: a typed
    error; coplanar planes whose rectangles do not overlap meet nowhere."""
    tilt = sk.Frame((1, 2, 3), sk.rotation_about((1, 0, 0), 0.3))
    pairs = [(sk.Sphere(1.0), sk.Sphere(1.0)), (sk.Torus(2, 0.5, tilt), sk.Torus(2, 0.5, tilt)),
             (sk.Cylinder(1.0, v_range=(0, 2)), sk.Cylinder(1.0, v_range=(1, 3))),
             (sk.Plane(u_range=(0, 1), v_range=(0, 1)), sk.Plane(u_range=(0.5, 2), v_range=(0.5, 2)))]
    for a, b in pairs:
        with pytest.raises(sk.CoincidentSurfacesError, match="same"):
            sk.intersect(a, b)
    assert sk.intersect(sk.Plane(u_range=(0, 1), v_range=(0, 1)), sk.Plane(u_range=(2, 3), v_range=(0, 1))) == []


def test_tangency_along_a_circle_and_a_line():
    """Torus(2, 0.5) with the plane z = 0.5 touches along the circle of radius 2; Sphere(1.5) with Cylinder(1.5)
    along the equator; Cylinder(1) with the plane x = 1 along a segment of the trimmed length. Each is one
    component with status 'tangent', on both surfaces to round-off."""
    cases = [(sk.Torus(2.0, 0.5), sk.Plane(sk.Frame((0, 0, 0.5))), 4 * math.pi, True),
             (sk.Sphere(1.5), sk.Cylinder(1.5, v_range=(-2, 2)), 3 * math.pi, True),
             (sk.Cylinder(1.0, v_range=(-2, 2)),
              sk.Plane(sk.Frame((1, 0, 0), sk.rotation_about((0, 1, 0), math.pi / 2))), 4.0, False)]
    for a, b, length, closed in cases:
        for x, y in ((a, b), (b, a)):
            curves = sk.intersect(x, y)
            assert len(curves) == 1 and curves[0].status == "tangent" and curves[0].closed == closed
            assert abs(curves[0].length - length) < 1e-12 and on_both(curves, x, y) < 1e-14


@pytest.mark.parametrize("turn", [None, (1.0, 2.0, 0.5)])
def test_a_torus_and_its_equatorial_plane_cross_along_both_equators(turn):
    """A plane through a torus's centre normal to its axis meets it in the outer and inner equators, crossing it
    (the torus's normal lies in the plane) along both: two closed circles of radii R + r and R - r (their lengths in
    closed form), neither said to be a tangency, the inner one lying on the seam of the torus's tube angle; placed
    by the identity or turned, in both argument orders."""
    big, small = 1.3394697620205813, 0.5656870850124908
    rotation = np.eye(3) if turn is None else sk.rotation_about(turn, 0.7)
    torus = sk.Torus(big, small, sk.Frame((0.3, -0.2, 0.1), rotation))
    plane = sk.Plane(sk.Frame((0.3, -0.2, 0.1), rotation))
    for x, y in ((torus, plane), (plane, torus)):
        curves = sk.intersect(x, y)
        assert [c.status for c in curves] == ["closed", "closed"]
        assert abs(curves[0].length - 2 * math.pi * (big + small)) < 1e-12
        assert abs(curves[1].length - 2 * math.pi * (big - small)) < 1e-12
        assert on_both(curves, x, y) < 1e-14


def test_trim_of_either_surface_is_respected():
    """A torus and a small plane patch far from it meet nowhere; a patch cutting one tube gives open curves
    that end exactly on the patch's edges and lie on the patch."""
    torus = sk.Torus(2.0, 0.5)
    assert sk.intersect(torus, sk.Plane(u_range=(5, 6), v_range=(5, 6))) == []
    patch = sk.Plane(u_range=(1.0, 3.0), v_range=(-0.2, 0.2))               # cuts the tube at u ~ 0 only
    for a, b in ((torus, patch), (patch, torus)):
        curves = sk.intersect(a, b, TOL)
        assert len(curves) == 2 and all(c.status == "boundary" for c in curves)
        for c in curves:
            local = c.points
            assert np.all(np.abs(local[:, 1]) <= 0.2 + 1e-12) and np.all((local[:, 0] > 1.0) & (local[:, 0] < 3.0))
            assert abs(abs(local[0, 1]) - 0.2) < 1e-12 and abs(abs(local[-1, 1]) - 0.2) < 1e-12


def test_curve_running_along_a_patch_edge_is_traced_whole():
    """A unit square patch standing on a plane along its edge u = 1 (turned about that edge): the intersection
    is the whole edge, length 1 exactly, in either order (the edge event of the square does not stop a curve
    that runs along the edge; round-off carries it across by ~1e-17)."""
    turn = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])   # about y, through x = 1
    rot = random_rotation(np.random.default_rng(5))
    square = sk.Plane(sk.Frame(rot @ np.array([1.0, 0.0, 1.0]), rot @ turn), u_range=(0.0, 1.0), v_range=(0.0, 1.0))
    floor = sk.Plane(sk.Frame(np.zeros(3), rot), u_range=(-1.0, 3.0), v_range=(-1.0, 2.0))
    for a, b in ((square, floor), (floor, square)):
        curves = sk.intersect(a, b, TOL)
        assert len(curves) == 1 and curves[0].status == "boundary"
        assert abs(curves[0].length - 1.0) < 1e-12
        ends = np.sort((curves[0].points[[0, -1]] @ rot)[:, 1])          # local y of the ends: 0 and 1
        assert np.allclose(ends, [0.0, 1.0], atol=1e-12)


def test_dense_points_pass_exactly_through_a_node():
    """Oblique Steinmetz curve (equal cylinders, axes crossing at 50 degrees): the two ellipses lie in the planes
    normal to e1 - e2 and e1 + e2; dense evaluations within 1e-5 of a node stay on their own ellipse's plane
    (within 1e-9; the other branch passes within 4e-6 there)."""
    rot = random_rotation(np.random.default_rng(11))
    e1 = rot[:, 2]
    tilt = rot @ np.array([[1.0, 0.0, 0.0], [0.0, math.cos(0.87), -math.sin(0.87)], [0.0, math.sin(0.87), math.cos(0.87)]])
    o = np.array([0.3, -0.2, 0.5])
    c1, c2 = sk.Cylinder(1.0, sk.Frame(o, rot), v_range=(-4, 4)), sk.Cylinder(1.0, sk.Frame(o, tilt), v_range=(-4, 4))
    e2 = tilt[:, 2]
    normals = [(e1 - e2) / np.linalg.norm(e1 - e2), (e1 + e2) / np.linalg.norm(e1 + e2)]
    curves = sk.intersect(c1, c2, TOL)
    assert len(curves) == 2
    for c in curves:
        assert len(c.nodes) == 2
        plane = min(normals, key=lambda n: np.abs((c(np.linspace(0, c.length, 50)) - o) @ n).max())
        s = np.linspace(0, c.length, 20001)
        p = c(s)
        for node in c.nodes:
            near = s[np.argmin(np.linalg.norm(p - node, axis=1))]
            fine = near + np.linspace(-1e-3, 1e-3, 20001)
            at = fine[np.argmin(np.linalg.norm(c(fine) - node, axis=1))]       # within 5e-8 of the node
            local = c(at + np.concatenate([-np.geomspace(1e-5, 1e-12, 30), [0.0], np.geomspace(1e-12, 1e-5, 30)]))
            assert np.abs((local - o) @ plane).max() < 1e-9


def test_arc_length_through_a_near_node_waist():
    """Two perpendicular cylinders of radii 1 and 1 - 1e-8 (axes crossing): two loops, each passing twice
    through a waist 1e-8 wide beside the Steinmetz nodes. Closed form of a loop, psi in [0, 2 pi):
    (sqrt(r^2 - r2^2 sin^2 psi), r2 sin psi, r2 cos psi); its length by adaptive quadrature (scipy.quad).
    Every loop, in either order, has that length to 1e-10 relative (the solver's time alone overshoots it by up to
    6e-8 through the waists; the curve's speed is measured there: tracing/arclength.py)."""
    from scipy.integrate import quad
    r, r2 = 1.0, 1.0 - 1e-8

    def speed(psi):
        s, c = math.sin(psi), math.cos(psi)
        return math.hypot(r2 * r2 * s * c / math.sqrt(r * r - r2 * r2 * s * s), r2)
    quarters = np.linspace(0.0, 2.0 * math.pi, 5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")          # quad's round-off notice at the waists
        exact = sum(quad(speed, lo, hi, epsabs=1e-15, epsrel=1e-14, limit=500)[0]
                    for lo, hi in zip(quarters[:-1], quarters[1:]))
    c1 = sk.Cylinder(r, v_range=(-2, 2))
    c2 = sk.Cylinder(r2, sk.Frame((0, 0, 0), [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]), v_range=(-2, 2))
    for a, b in ((c1, c2), (c2, c1)):
        curves = sk.intersect(a, b, TOL)
        assert len(curves) == 2 and all(c.status == "closed" for c in curves)
        for c in curves:
            assert abs(c.length - exact) < 1e-10 * exact
            assert abs(c.s[-1] - c.length) < 1e-12 * exact


def test_bounded_pair_accepted_in_either_order():
    """An untrimmed cone with a cylinder about its axis, trimmed or not: two circles, in either order; two
    unbounded cylinders along one direction: a ValueError naming the need for bounds."""
    r = 0.5
    for cylinder in (sk.Cylinder(r, v_range=(-3, 3)), sk.Cylinder(r)):
        for a, b in ((sk.Cone(1.0), cylinder), (cylinder, sk.Cone(1.0))):
            assert lengths(sk.intersect(a, b)) == [round(2 * math.pi * r, 6)] * 2
    with pytest.raises(ValueError, match="bounded"):
        sk.intersect(sk.Cylinder(1.0), sk.Cylinder(0.5, sk.Frame((0.7, 0.0, 0.0))))


@pytest.mark.parametrize("seed", range(4))
def test_invariant_under_order_translation_and_scale(seed):
    """A general torus–cylinder scene: the same component lengths in either order and scaled by 1e-4 and 1e4
    (relative 1e-9), and moved 1e5 from the origin (relative 1e-6: the integrated arc length there carries the
    round-off of coordinates of size 1e5 in every step)."""
    rng = np.random.default_rng(seed)
    rot, rot2 = random_rotation(rng), random_rotation(rng)
    base = None
    for scale, shift in ((1.0, 0.0), (1.0, 1e5), (1e-4, 0.0), (1e4, 0.0), (1e-4, 1e5)):
        torus = sk.Torus(2.0 * scale, 0.6 * scale, sk.Frame(np.full(3, shift), rot))
        cyl = sk.Cylinder(0.5 * scale, sk.Frame(shift + scale * np.array([2.0, 0.3, 0.1]), rot2),
                          v_range=(-4 * scale, 4 * scale))
        for a, b in ((torus, cyl), (cyl, torus)):
            found = sorted(c.length / scale for c in sk.intersect(a, b))
            if base is None:
                base = found
                assert found
            assert len(found) == len(base)
            np.testing.assert_allclose(found, base, rtol=1e-6 if shift else 1e-9)


def _extreme_scene(kind, scale):
    """A tilted torus or sphere with a plane trimmed to a square or a cone trimmed along its axis (one nappe),
    all lengths times scale."""
    rot, rot2 = sk.rotation_about((1.0, 2.0, 0.5), 0.4), sk.rotation_about((-0.6, 0.3, 1.0), 1.1)
    origin = scale * np.array([0.31, -0.22, 0.27])
    if kind == "plane-torus":
        return (sk.Torus(1.2 * scale, 0.5 * scale, sk.Frame((0.0, 0.0, 0.0), rot)),
                sk.Plane(sk.Frame(origin, rot2), (-2 * scale, 2 * scale), (-2 * scale, 2 * scale)))
    return (sk.Sphere(scale, sk.Frame((0.0, 0.0, 0.0), rot)),
            sk.Cone(0.5, sk.Frame(origin - 1.5 * scale * rot2[:, 2], rot2), (0.4 * scale, 3.0 * scale)))


@pytest.mark.parametrize("kind, count", [("plane-torus", 2), ("sphere-cone", 1)])
def test_extreme_scales(kind, count):
    """The same curves (lengths relative 1e-9) with the scene scaled by 1e-14, 1e-20 and 1e20 (and 1e-30, 1e30 for
    the cone). A plane's or cone's length parameters are then tiny or huge: an edge test of a start with an absolute
    margin (1e-12 for ranges below 1) would count every start of the plane scene as on the edge, and its loops
    would be lost without an error; a cone's apex watch in the scene's units (a v of 1e-12 is near the apex) would
    run the sphere-cone loop on to max_length instead of closing it. Both are relative to the scale."""
    base = None
    for scale in (1.0, 1e-14, 1e-20, 1e20) + ((1e-30, 1e30) if kind == "sphere-cone" else ()):
        a, b = _extreme_scene(kind, scale)
        for first, second in ((a, b), (b, a)):
            found = sorted(c.length / scale for c in sk.intersect(first, second))
            if base is None:
                base = found
                assert len(found) == count
            assert len(found) == len(base), scale
            np.testing.assert_allclose(found, base, rtol=1e-9)


def test_tiny_loop_and_contact_near_one():
    """A plane 1e-12 (relative) below the top of a sphere cuts a loop of radius sqrt(2e-12); at the top itself it
    touches in one contact point; a little above, nothing."""
    sphere = sk.Sphere(1.0, sk.Frame((0, 0, 0), sk.rotation_about((1, 1, 1), 0.5)))
    for dz, expect in ((-1e-12, "closed"), (0.0, "contact"), (1e-9, None)):
        plane = sk.Plane(sk.Frame((0.3, 0.1, 1.0 + dz)))
        curves = sk.intersect(sphere, plane)
        if expect is None:
            assert curves == []
            continue
        assert len(curves) == 1 and curves[0].status == expect
        if expect == "closed":
            z = 1.0 + dz                                # as stored: 1 - z is exact, z itself rounded
            radius = math.sqrt((1.0 - z) * (1.0 + z))
            # a near-tangent circle is fixed by both surfaces only to round-off / sin(angle of the normals)
            assert abs(curves[0].length - 2 * math.pi * radius) < 2 * math.pi * 1e-15 / radius
            # on both surfaces to round-off; along the plane only to round-off / sin(angle of the normals)
            assert curves[0].max_distance < 1e-15
            spread = np.linalg.norm(curves[0].points - plane.frame.origin * [0, 0, 1], axis=1) - radius
            assert np.max(np.abs(spread)) < 1e-15 / radius


def test_tiny_loop_under_a_quartic_is_a_loop():
    """Two coplanar tori whose outer equators overlap by 2e-13 (x their tube radius): a loop of ~2.5e-6 where
    the torus's quartic implicit function is only 1e-12 deep (within its rigorous enclosure of zero, which used
    to make it a contact). Truth: the loop through the two equators' crossing, length by the 40-digit oracle of
    the stress test; agreement within its conditioning, 2 pi x 4 ulp / sin(normals' angle) (~1e-3 relative)."""
    from tests.oracles.mp import loop_length
    b1, s1, b2, s2, depth = 1.2, 0.4, 1.0, 0.35, 2.5e-13
    rot = random_rotation(np.random.default_rng(3))
    t1 = sk.Torus(b1, s1, sk.Frame(np.zeros(3), rot))
    t2 = sk.Torus(b2, s2, sk.Frame(rot @ np.array([b1 + s1 + b2 + s2 - depth, 0.0, 0.0]), rot))
    touch = rot @ np.array([b1 + s1, 0.0, 0.0])
    ring = touch + 1.2e-6 * np.stack([rot @ np.array([0.0, math.cos(a), math.sin(a)])
                                      for a in np.linspace(0, 2 * math.pi, 12, endpoint=False)])
    exact, _, sine = loop_length(t1, t2, ring)
    bound = 2 * math.pi * 4 * np.finfo(float).eps * np.abs(ring).max() / sine
    for a, b in ((t1, t2), (t2, t1)):
        curves = sk.intersect(a, b, TOL)
        assert len(curves) == 1 and curves[0].status == "closed"
        assert abs(curves[0].length - exact) < bound
        assert np.linalg.norm(curves[0].points - touch, axis=1).max() < 3e-6


def test_loops_winding_round_a_cylinder_and_a_torus():
    """A tilted plane through a cylinder: one ellipse winding round it; a plane through the torus axis: two
    meridian circles (one lies along the default seam u = pi)."""
    cyl = sk.Cylinder(1.0, v_range=(-5, 5))
    plane = sk.Plane(sk.Frame((0, 0, 0.5), sk.rotation_about((1, 0, 0), 0.6)))
    curves = sk.intersect(cyl, plane)
    assert len(curves) == 1 and curves[0].closed
    a, b = 1.0 / math.cos(0.6), 1.0                   # ellipse semi-axes
    h = ((a - b) / (a + b)) ** 2
    ramanujan = math.pi * (a + b) * (1 + 3 * h / (10 + math.sqrt(4 - 3 * h)))
    assert abs(curves[0].length - ramanujan) < 1e-8 * ramanujan
    curves = sk.intersect(sk.Torus(3.0, 1.0), sk.Plane(sk.Frame.from_z_axis((0, 0, 0), (0, 1, 0))))
    assert lengths(curves) == [round(2 * math.pi, 6)] * 2


def test_certificate_radii_hold_the_true_points():
    """certify=True: every stored point of sphere ∩ plane has a finite radius, and the true circle (closed form)
    passes within radius * sqrt(3) of it; the certificate counts the components."""
    sphere = sk.Sphere(2.0, sk.Frame((1.0, -1.0, 0.5)))
    plane = sk.Plane(sk.Frame((0, 0, 1.2), sk.rotation_about((0, 1, 0), 0.3)))
    curves = sk.intersect(sphere, plane, certify=True)
    assert len(curves) == 1
    cert = curves[0].certificate
    assert cert.components == 1 and cert.all_points_proven and cert.max_distance_bound < 1e-12
    n = plane.frame.rotation[:, 2]
    d = (sphere.center - plane.frame.origin) @ n
    centre, radius = sphere.center - d * n, math.sqrt(4.0 - d * d)
    pts = curves[0].points
    off = pts - centre
    dist = np.hypot(off @ n, np.linalg.norm(off - np.outer(off @ n, n), axis=1) - radius)
    assert np.all(dist <= cert.radii * math.sqrt(3) + 1e-15)
    assert cert.proven and all(c.proven for c in cert.claims.values())


def test_search_budget_is_a_typed_error(monkeypatch):
    """A search that runs out of boxes, or of room for its roots and unresolved boxes, raises TopologyError naming
    the search and which limit, never a partial answer."""
    pair = (sk.Torus(2.0, 0.5), sk.Cylinder(0.4, sk.Frame((2.0, 0.1, 0.0)), v_range=(-2, 2)))
    monkeypatch.setattr(tp, "MAX_BOXES", 5)
    with pytest.raises(sk.TopologyError, match="budget of 5 boxes"):
        sk.intersect(*pair)
    monkeypatch.setattr(tp, "MAX_BOXES", 400_000)
    monkeypatch.setattr(tp, "MAX_RECORDS", 1)
    with pytest.raises(sk.TopologyError, match="search found more than 1 roots and unresolved boxes"):
        sk.intersect(*pair)


@pytest.mark.parametrize("offset", [-1e-9, 1e-9])
def test_plane_nearly_tangent_to_a_cone_along_a_ruling(offset):
    """A plane offset by 1e-9 from a cone's tangent plane along a ruling (one nappe, v in [0, h]): inside, a
    parabola hugging the ruling from the trim edge to the trim edge; outside, nothing (it cuts the nappe trimmed
    away). The level g is within 1e-9 of zero along the whole ruling, so the search has to cut across the ruling
    (its bisection follows the smear |dg/du| wu against |dg/dv| wv); cutting the relatively wider side instead
    took 173 349 and 95 369 boxes. Oracle: the parabola w -> offset n + s(w) e1 + w e2 with s(w) =
    (w^2 + offset^2 cos 2a / cos^2 a) / (2 |offset| tan a), its length 2 [w/2 sqrt(1 + (w/c)^2) + c/2 asinh(w/c)]
    at the trim edge w = W (c = |offset| tan a)."""
    a, h = 0.6, 1.5
    rot = random_rotation(np.random.default_rng(11))
    origin = np.array([0.2, -0.1, 0.3])
    cone = sk.Cone(a, sk.Frame(origin, rot), v_range=(0.0, h))
    e1, e2 = np.array([math.sin(a), 0.0, math.cos(a)]), np.array([0.0, 1.0, 0.0])
    normal = np.array([math.cos(a), 0.0, -math.sin(a)])         # outward, normal to the ruling u = 0
    plane = sk.Plane(sk.Frame(origin + rot @ (offset * normal), rot @ np.column_stack([e2, e1, normal])))
    for p, q in ((cone, plane), (plane, cone)):
        curves = sk.intersect(p, q, TOL)
        scale = 1.0
        topo = tp.topology(p, q, scale, TOL * scale)
        assert topo.boxes < 1000
        if offset > 0:
            assert curves == []
            continue
        assert len(curves) == 1 and curves[0].status == "boundary"
        c = abs(offset) * math.tan(a)
        s_edge = (h + offset * math.sin(a)) / math.cos(a)            # the point's height s cos a - offset sin a
        w_edge = math.sqrt(2.0 * c * s_edge - offset ** 2 * math.cos(2 * a) / math.cos(a) ** 2)
        exact = 2.0 * (0.5 * w_edge * math.hypot(1.0, w_edge / c) + 0.5 * c * math.asinh(w_edge / c))
        assert abs(curves[0].length - exact) < 1e-9 * exact
        assert on_both(curves, p, q) < 1e-14


@pytest.mark.parametrize("seed", [0, 1])
def test_elongated_contacts_of_two_stacked_tori(seed):
    """Two equal tori (R 1, r 0.3) on parallel axes, one 0.6 up its axis and 1e-3 aside: their tube circles meet
    where the two centre circles cross, so the tori touch at exactly two points, each a contact whose Hessian of g
    has eigenvalues 4e-6 and 16 (the tubes part slowly along the circles): a degeneracy test at 1e-6 of the
    largest eigenvalue would take them for degenerate points, whose starts cannot be located. Oracle: the contacts
    (eps/2, +-sqrt(1 - eps^2/4), 0.3) in the first torus's frame, within 1e-9 (along the flat direction the contact
    is fixed only to the gradient's round-off over the small eigenvalue, about 1e-15 / 4e-6; measured 1.3e-10); on
    both surfaces to round-off."""
    eps = 1e-3
    rot = random_rotation(np.random.default_rng(seed))
    origin = np.random.default_rng(seed + 10).uniform(-1, 1, 3)
    a = sk.Torus(1.0, 0.3, sk.Frame(origin, rot))
    b = sk.Torus(1.0, 0.3, sk.Frame(origin + rot @ np.array([eps, 0.0, 0.6]), rot))
    truth = np.array([origin + rot @ np.array([eps / 2, s * math.sqrt(1 - eps * eps / 4), 0.3]) for s in (1, -1)])
    for p, q in ((a, b), (b, a)):
        curves = sk.intersect(p, q, TOL)
        assert [c.status for c in curves] == ["contact", "contact"]
        got = np.array([c.points[0] for c in curves])
        assert np.min(np.linalg.norm(got[:, None] - truth[None], axis=2), axis=1).max() < 1e-9
        assert on_both(curves, p, q) < 1e-15


@pytest.mark.parametrize("seed", [1, 2])
def test_two_nappes_beside_an_apex_are_two_components(seed):
    """A double cone whose apex lies 1e-7 inside a unit sphere, its axis tangent to the sphere there: each nappe
    leaves the sphere in a loop round the axis, and the two loops pass 2e-7 apart beside the apex, so a start of
    the second lies within 1e-6 of the first and must not be dropped as a point of it. Starts on a nappe that a
    curve never visits are not its. Oracle: each loop is the rulings' exits from the sphere,
    apex + t(u) d(u) with t(u) the positive root of |apex + t d - centre|^2 = 1; its length by chord sums of 4096
    and 8192 exact points, Richardson-extrapolated (to 1e-9); each traced loop on one nappe, on both surfaces to the
    tolerance asked (its points beside the apex, where the cone's parametrisation degenerates, 3e-12 off)."""
    rng = np.random.default_rng(seed)
    rot, origin = sk.rotation_about(rng.normal(size=3), rng.uniform(0, 6)), rng.uniform(-1, 1, 3)
    half, depth = 0.4, 1e-7
    sphere = sk.Sphere(1.0, sk.Frame(origin, rot))
    apex = origin + (1.0 - depth) * rot[:, 0]
    cone = sk.Cone(half, sk.Frame(apex, rot), v_range=(-1.0, 1.0))

    def loop_length(sign, n):
        u = np.linspace(0.0, 2 * np.pi, n + 1)
        d = sign * np.stack([math.sin(half) * np.cos(u), math.sin(half) * np.sin(u),
                             np.full_like(u, math.cos(half))], axis=1) @ rot.T
        w = apex - origin
        bw = d @ w
        t = -bw + np.sqrt(bw * bw + 1.0 - w @ w)
        pts = apex + t[:, None] * d
        return np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()

    exact = [(4 * loop_length(s, 8192) - loop_length(s, 4096)) / 3 for s in (1.0, -1.0)]
    for p, q in ((sphere, cone), (cone, sphere)):
        curves = sk.intersect(p, q, TOL)
        assert [c.status for c in curves] == ["closed", "closed"]
        heights = [cone.frame.to_local(c.points)[:, 2] for c in curves]
        assert sorted(np.sign(h[0]) for h in heights) == [-1.0, 1.0]
        assert all(np.all(np.sign(h) == np.sign(h[0])) for h in heights)
        for c, h in zip(curves, heights):
            assert abs(c.length - exact[0 if h[0] > 0 else 1]) < 1e-9
        assert on_both(curves, p, q) < TOL


#: Each loop of Viviani's pair opened by 1e-9 (sphere radius 2 (1 + 1e-9), centre 1 from the cylinder's axis):
#: the integral of sqrt(1 + sin^2 t / (R^2 - 2 + 2 cos t)) over a turn, mpmath quad at 30 digits.
OPENED_VIVIANI_LOOP = 7.640288416955098


@pytest.mark.parametrize("shift, scale", [(0.0, 1.0), (1e5, 1.0), (1e5, 1e4), (1e9, 1e4)])
def test_two_loops_beside_a_waist_far_from_the_origin(shift, scale):
    """Viviani's pair with the sphere 1e-9 larger: two loops passing 1.8e-4 apart (relative) at a waist of g.
    Moved far from the origin, the search leaves the loops' critical points unresolved in one cluster round the
    waist; both sides of the waist still seed a loop: two loops, each of the quadrature's length (within the
    coordinates' round-off carried by s: 1e-7 relative far away), in both orders."""
    origin = np.array([shift, 0.0, 0.0])
    cylinder = sk.Cylinder(scale, sk.Frame(origin), (-3.0 * scale, 3.0 * scale))
    sphere = sk.Sphere(2.0 * scale * (1 + 1e-9), sk.Frame(origin + np.array([scale, 0.0, 0.0])))
    for pair in ((cylinder, sphere), (sphere, cylinder)):
        curves = sk.intersect(*pair)
        assert [c.closed for c in curves] == [True, True]
        for c in curves:
            assert abs(c.length / scale - OPENED_VIVIANI_LOOP) <= (1e-9 if shift == 0.0 else 1e-7) * OPENED_VIVIANI_LOOP


@pytest.mark.parametrize("offset", [0.0, 2.6e5])
@pytest.mark.parametrize("overlap", [1e-6, 1e-7, 4e-8])
def test_spheres_crossing_at_a_small_angle_give_their_circle_not_a_tangency(overlap, offset):
    """Two spheres (radii 2.50 and 2.31) whose centres lie `overlap` farther apart than the radii's difference
    (11 to 272 times the tolerance at 2.6e5 from the origin): they cross at a sine of 2.6e-4 to 5.2e-5 along a circle.
    Round-off blurs g's root on the common meridian over the narrowest interval; the circle is still read as
    crossed (status 'closed', both orders), not as one the spheres touch along, its length within 1e-8 (relative)
    of the 50-digit closed form: r^2 = R1^2 - ((d^2 + R1^2 - R2^2) / 2d)^2, the centres' distance d taken from the
    stored doubles."""
    import mpmath as mp
    big, small = 2.5025682306252945, 2.3091309474524637
    direction = np.array([0.7395177, -0.40175899, -0.54009558])
    direction /= np.linalg.norm(direction)
    centre = np.full(3, offset) + np.array([0.3, 0.1, -0.2])
    other = centre + (big - small + overlap) * direction
    a, b = sk.Sphere(big, sk.Frame(tuple(centre))), sk.Sphere(small, sk.Frame(tuple(other)))
    with mp.workdps(50):
        d = mp.sqrt(sum((mp.mpf(float(x)) - mp.mpf(float(y))) ** 2
                        for x, y in zip(a.frame.origin, b.frame.origin)))
        h = (d * d + mp.mpf(big) ** 2 - mp.mpf(small) ** 2) / (2 * d)
        exact = float(2 * mp.pi * mp.sqrt(mp.mpf(big) ** 2 - h * h))
    for x, y in ((a, b), (b, a)):
        curves = sk.intersect(x, y)
        assert len(curves) == 1 and curves[0].status == "closed", curves[0].message
        assert abs(curves[0].length - exact) <= 1e-8 * exact, (curves[0].length, exact)
