"""sk.intersect of two unbounded surfaces (planes, cylinders, cones without trims) whose intersection is bounded.

Oracles: the perimeters of the ellipses (scipy.special.ellipe), a plane's section of a cone integrated along the
cone's rulings (scipy.integrate.quad), and the same pair with explicit trims far beyond the curves, which takes
the bounded path."""
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import ellipe
from tests.oracles.measure import on_both
from tests.oracles.unbounded import unbounded_pair

import spatialkin as sk

TOL = 1e-10
R = sk.rotation_about


def ellipse_perimeter(a, b):
    """Perimeter of the ellipse of semi-axes a >= b."""
    return 4.0 * a * ellipe(1.0 - (b / a) ** 2)


def cone_section_length(half_angle, height, tilt):
    """Length of the section of the cone about z (apex at 0) by the plane through (0, 0, height) whose normal is z
    turned by tilt about x: the points t(u) d(u), d(u) = (tan a cos u, tan a sin u, 1), t = n.p / n.d."""
    n = np.array([0.0, -math.sin(tilt), math.cos(tilt)])
    k = math.tan(half_angle)

    def speed(u):
        d = np.array([k * math.cos(u), k * math.sin(u), 1.0])
        dd = np.array([-k * math.sin(u), k * math.cos(u), 0.0])
        nd = n @ d
        t = height * n[2] / nd
        dt = -t * (n @ dd) / nd
        return float(np.linalg.norm(dt * d + t * dd))

    return quad(speed, 0.0, 2 * math.pi, epsabs=1e-13, epsrel=1e-13, limit=200)[0]


@pytest.mark.parametrize("tilt", [0.0, 0.5, 1.2])
@pytest.mark.parametrize("order", [0, 1])
def test_a_tilted_plane_cuts_a_cylinder_in_an_ellipse(tilt, order):
    """Semi-axes r / cos(tilt) and r; the curve's surfaces are the ones given, untrimmed."""
    plane, cyl = sk.Plane(sk.Frame((0.3, -0.2, 1.0), R((1, 0, 0), tilt))), sk.Cylinder(0.8)
    a, b = (plane, cyl)[::1 - 2 * order]
    curve, = sk.intersect(a, b, tol=TOL)
    assert curve.status == "closed"
    assert curve.length == pytest.approx(ellipse_perimeter(0.8 / math.cos(tilt), 0.8), rel=1e-12)
    assert curve.surfaces[0] is a and curve.surfaces[1] is b
    assert curve.surfaces[0].v_range == (-math.inf, math.inf)
    assert on_both([curve], a, b) <= curve.tolerance


@pytest.mark.parametrize("tilt", [0.0, 0.4, 0.9])
def test_a_plane_cuts_a_cone_in_an_ellipse(tilt):
    """The section's length against the integral along the rulings (half angle 0.5: ellipses below tilt 1.07)."""
    plane, cone = sk.Plane(sk.Frame((0.0, 0.0, 2.0), R((1, 0, 0), tilt))), sk.Cone(0.5)
    curve, = sk.intersect(plane, cone, tol=TOL)
    assert curve.length == pytest.approx(cone_section_length(0.5, 2.0, tilt), rel=1e-11)
    assert on_both([curve], plane, cone) <= curve.tolerance


def test_two_perpendicular_cylinders_of_one_radius_meet_in_two_ellipses():
    """The Steinmetz curves of two untrimmed pipes: ellipses of semi-axes r sqrt 2 and r, crossing at two nodes."""
    a, b = sk.Cylinder(1.5), sk.Cylinder(1.5, sk.Frame((0, 0, 0), R((1, 0, 0), math.pi / 2)))
    curves = sk.intersect(a, b, tol=TOL)
    assert len(curves) == 2
    for c in curves:
        assert c.length == pytest.approx(ellipse_perimeter(1.5 * math.sqrt(2), 1.5), rel=1e-10)
    assert on_both(curves, a, b) <= curves[0].tolerance


def random_pair(seed):
    """Two unbounded surfaces of random kinds crossing near the origin."""
    return unbounded_pair(seed, 0.5, (0.3, 1.2), (0.15, 1.2))


def trimmed(surface, half):
    """The surface with its length parameters trimmed to [-half, half] about its origin (the bounded path)."""
    if isinstance(surface, sk.Plane):
        return sk.Plane(surface.frame, (-half, half), (-half, half))
    if isinstance(surface, sk.Cylinder):
        return sk.Cylinder(surface.radius, surface.frame, (-half, half))
    return sk.Cone(surface.half_angle, surface.frame, (-half, half))


@pytest.mark.parametrize("seed", range(18))
def test_random_unbounded_pairs_match_the_same_pair_trimmed_far_out(seed):
    """Either the pair is refused (its directions to infinity too close: the message says so), or its answer is
    that of the same surfaces trimmed at 4 times the distance of its farthest point (count, statuses, lengths to
    1e-9), none of its curves ends on a cut, and every point lies on both surfaces."""
    a, b = random_pair(seed)
    try:
        curves = sk.intersect(a, b, tol=TOL)
    except ValueError as err:
        assert "direction" in str(err)
        return
    assert all(c.status in ("closed", "contact") or c.nodes.size for c in curves)
    if not curves:
        return
    far = max(float(np.max(np.linalg.norm(c.points - o, axis=1))) for c in curves
              for o in (a.frame.origin, b.frame.origin))
    reference = sk.intersect(trimmed(a, 4 * far + 1), trimmed(b, 4 * far + 1), tol=TOL)
    assert sorted(c.status for c in curves) == sorted(c.status for c in reference)
    assert sorted(c.length for c in curves) == pytest.approx(sorted(c.length for c in reference), rel=1e-9, abs=1e-12)
    assert on_both(curves, a, b) <= max(c.tolerance for c in curves)


@pytest.mark.parametrize("scale, shift", [(1e-20, 0.0), (1e-3, 0.0), (1e3, 0.0), (1e20, 0.0), (1.0, 1e6)])
def test_the_answer_does_not_depend_on_scale_or_place(scale, shift):
    """A cylinder and a cone, untrimmed: the same lengths scaled and moved (relative 1e-9)."""
    def pair(k, t):
        return (sk.Cylinder(0.5 * k, sk.Frame(k * np.array([0.2, 0.0, 3.0]) + t)),
                sk.Cone(0.6, sk.Frame(np.zeros(3) + t, R((0, 1, 0), 0.2))))
    base = sorted(c.length for c in sk.intersect(*pair(1.0, 0.0), tol=TOL))
    moved = sorted(c.length / scale for c in sk.intersect(*pair(scale, shift), tol=TOL))
    assert len(base) == 2 and moved == pytest.approx(base, rel=1e-9)


def test_planes_and_cones_through_one_point_share_it_alone():
    """A cone and a plane through its apex tilted beyond its half angle, and two cones on one apex whose rulings
    point apart: the apex, a contact point (no length in the scene: at the origin and 1e6 from it)."""
    for o in (np.zeros(3), np.array([1e6, -2e6, 5e5])):
        plane = sk.Plane(sk.Frame(o, R((1, 0, 0), 0.2)))
        for a, b in ((plane, sk.Cone(0.3, sk.Frame(o))),
                     (sk.Cone(0.3, sk.Frame(o)), sk.Cone(0.3, sk.Frame(o, R((1, 0, 0), 1.4))))):
            point, = sk.intersect(a, b, tol=TOL)
            assert point.status == "contact" and np.allclose(point.points[0], o, rtol=0, atol=1e-9 * (1 + abs(o).max()))


def test_certify_proves_the_answer_of_an_unbounded_pair():
    plane, cyl = sk.Plane(sk.Frame((0.0, 0.0, 1.0), R((1, 0, 0), 0.5))), sk.Cylinder(1.0)
    curves = sk.intersect(plane, cyl, certify=True)
    assert curves.certificate.proven and curves[0].surfaces == (plane, cyl)
    cone = sk.Cone(0.6, sk.Frame((0.0, 0.0, 0.0), R((0, 1, 0), 0.2)))
    curves = sk.intersect(sk.Cylinder(0.5, sk.Frame((0.2, 0.0, 3.0))), cone, certify=True)
    assert len(curves) == 2 and curves.certificate.proven


def test_a_half_infinite_trim_is_kept():
    """A cylinder trimmed to v >= 0 and a plane through its origin tilted 0.5: half the ellipse, ending on the rim;
    trimmed to v >= 100 (beyond every common point): nothing."""
    plane = sk.Plane(sk.Frame((0.0, 0.0, 0.0), R((1, 0, 0), 0.5)))
    half, = sk.intersect(sk.Cylinder(1.0, v_range=(0.0, math.inf)), plane, tol=TOL)
    assert half.status == "boundary"
    assert half.length == pytest.approx(0.5 * ellipse_perimeter(1.0 / math.cos(0.5), 1.0), rel=1e-12)
    assert sk.intersect(sk.Cylinder(1.0, v_range=(100.0, math.inf)), plane, tol=TOL) == []


@pytest.mark.parametrize("a, b, why", [
    (sk.Plane(sk.Frame((0, 0, 0), R((1, 0, 0), math.pi / 2))), sk.Cylinder(1.0, sk.Frame((0, 3, 0))),
     "share a direction"),                                 # the axis parallel to the plane
    (sk.Cylinder(1.0), sk.Cylinder(0.5, sk.Frame((0.2, 0, 0), R((1, 0, 0), 5e-4))), "only 0.0005 rad apart"),
    (sk.Plane(sk.Frame((0, 0, 0), R((1, 0, 0), 1.3))), sk.Cone(0.3), "share a direction"),   # two rulings
    (sk.Plane(), sk.Plane(sk.Frame((0, 0, 0), R((1, 0, 0), 0.5))), "share a direction"),     # a line
])
def test_pairs_that_may_meet_far_out_are_refused(a, b, why):
    with pytest.raises(ValueError, match=f"both unbounded and .*{why}"):
        sk.intersect(a, b)
