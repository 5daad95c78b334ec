"""A surface kind that lives only in the tests: the spherical zone (the band of a sphere between two latitudes,
poles excluded), declared as a new kind would be in the library (its class, its traits, one registration) and
intersected with the built-in kinds through the public API.

It exercises the registration path: its kind code is new, so tracing and the topology stage read every answer
from its traits (its own chart is never re-charted, it has no poles, its latitude trims are edges to search and
to stop at, it turns only about its own axis). Its geometry is the sphere's: the compiled kernels evaluate it
through data[GEOMETRY] = SPHERE. A kind with a new geometry would need its kernel branches as well
(spatialkin.kernels.geometry.surfaces and spatialkin.kernels.geometry.interval), which a test cannot add.
"""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

import spatialkin as sk
from spatialkin.kernels.geometry import surfaces as ks
from spatialkin.render.geometry import natural_domain
from spatialkin.geometry.surfaces import check_positive, check_range
from spatialkin.geometry.surfaces.sphere import SphereTraits
from spatialkin.geometry.traits import ANGLE, AXIS, SurfaceTraits, register, traits, unregister

#: Kind code of the test kind (any code no registered kind uses).
ZONE_CODE = 100
#: Accuracy asked of sk.intersect and sk.trace (relative to the scene scale).
TOL = 1e-10
#: Closed-form lengths and positions are met to this (relative to the scale): the tracer's tolerance, with
#: margin for the arc-length integration.
CLOSED_FORM = 1e-8


class SphericalZone(sk.Surface):
    """The band of a sphere of the given radius between the latitudes v_range (inside (-pi/2, pi/2)), centred at
    frame.origin about its local z: M(u, v) = frame(R cos v cos u, R cos v sin u, R sin v)."""

    def __init__(self, radius, v_range, frame=None):
        self.radius = check_positive("radius", radius)
        lo, hi = check_range("v_range", v_range)
        if not -0.5 * math.pi < lo < hi < 0.5 * math.pi:
            raise ValueError(f"v_range must lie inside (-pi/2, pi/2) (the poles excluded), got {v_range!r}")
        super().__init__(frame, self.radius, v_range=(lo, hi))

    def with_frame(self, frame):
        return SphericalZone(self.radius, self.v_range, frame)

    def _describe(self):
        return f"radius={self.radius}, v_range={self.v_range}"


class ZoneTraits(SurfaceTraits):
    """The zone's own chart serves the whole band (no pole inside it, no re-chart, no area watch); its latitude
    trims are edges; it turns only about its own axis; its implicit function is the sphere's."""

    code = ZONE_CODE
    geometry = ks.SPHERE
    name = "spherical zone"
    rank = 1
    units = (ANGLE, ANGLE)
    periodic = (True, False)
    parameter_axes = (None, None)
    compact = False
    recharts = False
    area_watch = False
    has_parallels = True

    implicit_jets = SphereTraits.implicit_jets

    def size(self, surface):
        return surface.radius

    def bounding_ball(self, surface):
        return surface.frame.origin.copy(), surface.radius

    def trim_slack(self, surface, slack):
        return slack / surface.radius, slack / surface.radius

    def symmetry(self, surface):
        return AXIS, surface.frame.origin, surface.frame.rotation[:, 2]

    def same_surface(self, a, b, tol, same):
        return np.linalg.norm(a.frame.origin - b.frame.origin) <= tol and abs(a.radius - b.radius) <= tol


@pytest.fixture(scope="module", autouse=True)
def zone_kind():
    """The zone registered for this module's tests only."""
    register(SphericalZone, ZoneTraits())
    yield
    unregister(SphericalZone)


def x_normal_plane(x):
    """The plane x = const (its local z along the global x)."""
    return sk.Plane(sk.Frame.from_z_axis((x, 0.0, 0.0), (1.0, 0.0, 0.0)))


def test_the_zone_is_registered_under_its_code_and_packs_the_sphere_geometry():
    """The registry answers for the class, the instance, the packed data and the code alike."""
    zone = SphericalZone(2.0, (-0.5, 0.5))
    kind = traits(zone)
    assert isinstance(kind, ZoneTraits)
    assert traits(SphericalZone) is kind and traits(zone.data) is kind and traits(ZONE_CODE) is kind
    assert zone.kind == ZONE_CODE and int(zone.data[ks.GEOMETRY]) == ks.SPHERE
    assert zone.size == 2.0 and not zone.compact and not zone.periodic_v
    assert natural_domain(zone) == ((-math.pi, math.pi), (-0.5, 0.5))
    # its points are the sphere's (the kernels evaluate the geometry code): closed form, to round-off
    u, v = 0.3, -0.2
    assert np.allclose(zone.point(u, v), 2.0 * np.array([math.cos(v) * math.cos(u), math.cos(v) * math.sin(u),
                                                         math.sin(v)]), rtol=0, atol=1e-15)


def test_zone_and_plane_meet_in_two_arcs_cut_by_the_band():
    """Zone R = 1, latitudes (-0.6, 0.9), and the plane x = 0.5: the circle y^2 + z^2 = 3/4 of that plane cut by
    the band into two arcs (y > 0 and y < 0) from z = sin(-0.6) to z = sin(0.9), each of length
    r (asin(z_hi / r) - asin(z_lo / r)), r = sqrt(3)/2. Oracle: that closed form, to CLOSED_FORM."""
    lo, hi = -0.6, 0.9
    zone, plane = SphericalZone(1.0, (lo, hi)), x_normal_plane(0.5)
    r = math.sqrt(0.75)
    length = r * (math.asin(math.sin(hi) / r) - math.asin(math.sin(lo) / r))
    curves = sk.intersect(zone, plane, tol=TOL)
    assert len(curves) == 2
    sides = []
    for c in curves:
        assert c.status == "boundary" and not c.closed
        assert c.length == pytest.approx(length, rel=CLOSED_FORM)
        p = c.points
        assert np.max(np.abs(p[:, 0] - 0.5)) <= CLOSED_FORM
        assert np.max(np.abs(np.hypot(p[:, 1], p[:, 2]) - r)) <= CLOSED_FORM
        assert sorted([p[0, 2], p[-1, 2]]) == pytest.approx([math.sin(lo), math.sin(hi)], abs=CLOSED_FORM)
        sides.append(np.sign(np.mean(p[:, 1])))
    assert sorted(sides) == [-1.0, 1.0]
    # the same arc by sk.trace from a point near it
    arc = sk.trace(zone, plane, (0.5, 0.8, 0.1), tol=TOL)
    assert arc.status == "boundary" and arc.length == pytest.approx(length, rel=CLOSED_FORM)
    assert np.all(arc.points[:, 1] > 0)


def test_zone_and_coaxial_cylinder_meet_in_one_circle_of_the_band():
    """Zone R = 1, latitudes (-0.6, 0.9), and the coaxial cylinder r = 0.8: the parallels z = +-0.6, of which
    only z = 0.6 (latitude asin 0.6 = 0.64) lies in the band. Oracle: that closed form (a circle of radius 0.8)."""
    zone, cylinder = SphericalZone(1.0, (-0.6, 0.9)), sk.Cylinder(0.8)
    for a, b in ((zone, cylinder), (cylinder, zone)):
        curves = sk.intersect(a, b, tol=TOL)
        assert len(curves) == 1
        c = curves[0]
        assert c.closed and c.length == pytest.approx(2 * math.pi * 0.8, rel=CLOSED_FORM)
        assert np.max(np.abs(c.points[:, 2] - 0.6)) <= CLOSED_FORM
        assert np.max(np.abs(np.hypot(c.points[:, 0], c.points[:, 1]) - 0.8)) <= CLOSED_FORM


def test_zone_and_sphere_off_its_axis_meet_in_a_closed_circle():
    """Zone R = 1, latitudes (-0.9, 0.9), and the sphere of radius 0.5 about (0.9, 0, 0) (off the zone's axis: a
    general placement, the zone's own chart searched and traced, the sphere re-charted): the circle in the plane
    x = d = (1 - 0.25 + 0.81) / 1.8 of radius sqrt(1 - d^2), all inside the band. Oracle: that closed form."""
    zone, sphere = SphericalZone(1.0, (-0.9, 0.9)), sk.Sphere(0.5, sk.Frame((0.9, 0.0, 0.0)))
    d = (1.0 - 0.25 + 0.81) / 1.8
    rho = math.sqrt(1.0 - d * d)
    curves = sk.intersect(zone, sphere, tol=TOL)
    assert [c.topology.mode for c in curves] == ["general"]
    c = curves[0]
    assert c.closed and c.length == pytest.approx(2 * math.pi * rho, rel=CLOSED_FORM)
    assert np.max(np.abs(c.points[:, 0] - d)) <= CLOSED_FORM
    assert np.max(np.abs(np.hypot(c.points[:, 1], c.points[:, 2]) - rho)) <= CLOSED_FORM
    # the zone's parameters along it are its own chart's (never re-charted): latitude sin v = z
    assert np.max(np.abs(np.sin(c.params[:, 1]) - c.points[:, 2])) <= CLOSED_FORM


def band_length(curve, latitude, lo, hi, samples=4001):
    """Arc length of the curve where latitude(points) lies in (lo, hi): the crossings of lo and hi bracketed on
    `samples` points and refined by brentq on the curve's dense output."""
    s = np.linspace(0.0, curve.length, samples)
    lat = latitude(curve(s))
    cuts = [0.0]
    for bound in (lo, hi):
        f = lat - bound
        for i in np.nonzero(f[:-1] * f[1:] < 0)[0]:
            cuts.append(brentq(lambda x: latitude(curve(x)) - bound, s[i], s[i + 1], xtol=1e-14))
    cuts = np.sort(np.append(cuts, curve.length))
    mid = latitude(curve(0.5 * (cuts[:-1] + cuts[1:])))
    return float(np.sum(np.diff(cuts)[(mid > lo) & (mid < hi)]))


def test_zone_as_implicit_surface_cut_from_the_sphere_curves():
    """A ring torus (R = 1.2, r = 0.5) and the zone of the unit sphere about (0.3, 0, 0.2) between latitudes
    (-0.3, 0.25): the torus is the parametrised surface and the zone the implicit one, whose latitude edges are
    searched on it. Oracle: the intersection with the whole sphere (traced by the built-in kind), cut to the band
    at its latitude crossings: the same total length, and every arc ending on the band's edges (to CLOSED_FORM)."""
    centre = np.array([0.3, 0.0, 0.2])
    lo, hi = -0.3, 0.25
    torus = sk.Torus(1.2, 0.5)
    zone = SphericalZone(1.0, (lo, hi), sk.Frame(centre))
    arcs = sk.intersect(torus, zone, tol=TOL)
    whole = sk.intersect(torus, sk.Sphere(1.0, sk.Frame(centre)), tol=TOL)
    assert arcs and all(c.status == "boundary" for c in arcs)

    def latitude(points):
        return np.arcsin(np.clip(points[..., 2] - centre[2], -1.0, 1.0))

    for c in arcs:
        ends = latitude(c.points[[0, -1]])
        assert np.min(np.abs(ends[:, None] - np.array([lo, hi])[None, :]), axis=1) == pytest.approx(
            [0.0, 0.0], abs=CLOSED_FORM)
    cut = sum(band_length(c, latitude, lo, hi) for c in whole)
    assert sum(c.length for c in arcs) == pytest.approx(cut, rel=CLOSED_FORM)
