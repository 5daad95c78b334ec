"""The plane (optionally trimmed to a rectangle) and its traits."""
import math

import numpy as np

from ...kernels.geometry import surfaces as ks
from ..placement import parallel
from ..traits import LENGTH, NORMAL, SurfaceTraits, register
from .base import Surface, check_length, check_range
from ..trims import RADIUS, level_groups, region_values

#: Coplanar patches with circles (a disc, an annulus) are compared on a grid of this many samples per side of
#: the overlap of their rectangles.
OVERLAP_SAMPLES = 97
#: Infinite trims are cut at this many times the distance from a's origin of the farthest corner of the lines
#: bounding the two rectangles (every corner of their overlap lies within it) ...
OVERLAP_REACH = 2.0
#: ... of those lines that cross at more than this angle (radians): nearer parallel ones count as parallel, so the
#: reach stays within 1e6 of the trims' magnitude.
OVERLAP_ANGLE = 1e-6
#: Two coplanar rectangles share an area when their overlap is wider than this fraction of that reach (the
#: coincidence tolerance, spatialkin.geometry.placement.SAME: round-off of the frames leaves a sliver there
#: where they only meet along an edge).
OVERLAP_WIDTH = 1e-12


class Plane(Surface):
    """Plane through frame.origin spanned by the local x and y axes: M(u, v) = frame(u, v, 0).

    u and v are lengths (the user's unit) along the local x and y axes; u_range and v_range optionally trim the
    plane to a rectangle (or a strip), radius to a disc about frame.origin (a cylinder's cap), inner_radius cuts
    a hole out of it (an annulus). Local z is its normal.

    Parameters
    ----------
    frame : Frame, optional
        Placement: origin on the plane, local z along the normal (default: the global axes, the plane z = 0).
    u_range, v_range : (float, float), optional
        Trims (min, max) of u and v, lengths; either end may be infinite; None (default) leaves it unbounded.
    radius : float, optional
        The face is the disc of this radius about frame.origin (within the rectangle, if one is given too).
    inner_radius : float, optional
        ... less the disc of this radius (0 <= inner_radius < radius): an annulus.

    Attributes
    ----------
    frame : Frame
    u_range, v_range : (float, float)
        The rectangle, (-inf, inf) where unbounded (with a radius: within its bounding square).
    radius, inner_radius : float or None
        The circles, None where there is none.

    Raises
    ------
    ValueError
        Naming `u_range` or `v_range` when it is not a pair min < max (no NaN, finite ends within 1e32 of 0),
        `radius` when not positive and finite or outside the supported lengths [1e-32, 1e32], `inner_radius` when
        not 0 or a length in [1e-32, radius).
    TypeError
        Naming `radius` or `inner_radius` when it is not a real number (a str, a bool); when `frame` is not a
        spatialkin.Frame.

    Examples
    --------
    >>> import numpy as np
    >>> import spatialkin as sk
    >>> plane = sk.Plane(sk.Frame((0.0, 0.0, 0.5)), u_range=(-1.0, 1.0), v_range=(-1.0, 1.0))
    >>> np.allclose(plane.point(0.25, -0.5), (0.25, -0.5, 0.5))
    True
    >>> round(float(plane.distance([3.0, 3.0, 2.0])), 6)       # to the untrimmed plane
    1.5
    >>> sk.Plane(u_range=(1.0, -1.0))
    Traceback (most recent call last):
    ...
    ValueError: u_range must satisfy min < max, got (1.0, -1.0)
    >>> disc = sk.Plane(sk.Frame((0.0, 0.0, 1.0)), radius=0.5)          # the cap of a cylinder
    >>> [round(c.length, 9) for c in sk.intersect(disc, sk.Sphere(2.0))]   # the circle of radius sqrt 3 misses it
    []
    """

    def __init__(self, frame=None, u_range=None, v_range=None, radius=None, inner_radius=None):
        self.radius = None if radius is None else check_length("radius", radius)
        self.inner_radius = (None if inner_radius is None
                             else check_length("inner_radius", inner_radius, allow_zero=True))
        if self.inner_radius is not None and self.radius is not None and not self.inner_radius < self.radius:
            raise ValueError(f"inner_radius must be less than radius, got {self.inner_radius} and {self.radius}")
        u_range = check_range("u_range", u_range, length=True)
        v_range = check_range("v_range", v_range, length=True)
        if self.radius is not None:        # the bounding square: the tracer's edges, the circle cut from the curves
            u_range = (max(u_range[0], -self.radius), min(u_range[1], self.radius))
            v_range = (max(v_range[0], -self.radius), min(v_range[1], self.radius))
            for name, (lo, hi) in (("u_range", u_range), ("v_range", v_range)):
                if not lo < hi:
                    raise ValueError(f"{name} must meet the disc of radius {self.radius}, got ({lo}, {hi})")
        circles = (0.0 if self.inner_radius is None else self.inner_radius,
                   math.inf if self.radius is None else self.radius)
        region = level_groups(("inner rim", "rim"), RADIUS, circles) if self.inner_radius or self.radius else ()
        super().__init__(frame, u_range=u_range, v_range=v_range, region=region)

    def with_frame(self, frame):
        return Plane(frame, self.u_range, self.v_range, self.radius, self.inner_radius)

    def _describe(self):
        return f"u_range={self.u_range}, v_range={self.v_range}" + "".join(
            f", {name}={value}" for name, value in (("radius", self.radius), ("inner_radius", self.inner_radius))
            if value is not None)


class PlaneTraits(SurfaceTraits):
    """u and v lengths along the local x and y axes, never periodic; no size of its own (it has no length in its
    shape); a surface of revolution about any line along its normal, and invariant under scaling about any of its
    points and translation along it."""

    code = geometry = ks.PLANE
    name = "plane"
    rank = 4                        # read linearly as the implicit surface Q: the last choice of P
    units = (LENGTH, LENGTH)
    periodic = (False, False)
    parameter_axes = (0, 1)
    compact = False
    recharts = False
    area_watch = False
    has_parallels = False

    def size(self, surface):
        return 1.0

    def scale_length(self, surface):
        return None

    def extent(self, surface):
        (u0, u1), (v0, v1) = surface.u_range, surface.v_range
        return math.hypot(u1 - u0, v1 - v0)

    def bounding_ball(self, surface):
        (u0, u1), (v0, v1) = surface.u_range, surface.v_range
        if not all(math.isfinite(x) for x in (u0, u1, v0, v1)):
            return None
        return surface.frame.global_of([0.5 * (u0 + u1), 0.5 * (v0 + v1), 0.0]), 0.5 * math.hypot(u1 - u0, v1 - v0)

    def asymptote(self, surface):
        if self.bounding_ball(surface) is not None:
            return None
        return surface.frame.rotation[:, 2], 0.5 * math.pi, 0.0, surface.frame.origin

    def symmetry(self, surface):
        return NORMAL, surface.frame.rotation[:, 2]

    def trim_breaks_revolution(self, surface):
        return bool(np.isfinite(surface.u_range).any() or np.isfinite(surface.v_range).any())

    def keeps_translation(self, surface, direction, same):
        return abs(surface.frame.rotation[:, 2] @ direction) <= same

    def keeps_scaling(self, surface, centre, tol):
        return abs((centre - surface.frame.origin) @ surface.frame.rotation[:, 2]) <= tol

    def same_surface(self, a, b, tol, same):
        za = a.frame.rotation[:, 2]
        return (parallel(za, b.frame.rotation[:, 2], same)
                and abs((b.frame.origin - a.frame.origin) @ za) <= tol)

    def trims_overlap(self, a, b):
        """The rectangles share an area (their circles aside: regions_overlap)."""
        return rectangles_overlap(a, b) is not None

    def regions_overlap(self, a, b):
        """The patches share an area: a grid of their rectangles' overlap has a point strictly inside both
        rectangles and both regions (discs, annuli)."""
        box = rectangles_overlap(a, b)
        if box is None:
            return False
        (u0, v0), (u1, v1) = box
        uu, vv = np.meshgrid(np.linspace(u0, u1, OVERLAP_SAMPLES)[1:-1], np.linspace(v0, v1, OVERLAP_SAMPLES)[1:-1])
        points = a.frame.global_of(np.stack([uu.ravel(), vv.ravel(), np.zeros(uu.size)], axis=1))
        inside = np.all(region_values(a, points) > 0.0, axis=1) & np.all(region_values(b, points) > 0.0, axis=1)
        local = b.frame.local_of(points)
        (bu0, bu1), (bv0, bv1) = b.u_range, b.v_range
        inside &= (local[:, 0] > bu0) & (local[:, 0] < bu1) & (local[:, 1] > bv0) & (local[:, 1] < bv1)
        inside &= (uu.ravel() > a.u_range[0]) & (uu.ravel() < a.u_range[1])
        inside &= (vv.ravel() > a.v_range[0]) & (vv.ravel() < a.v_range[1])
        return bool(inside.any())

    def implicit_jets(self, surface, q):
        """F = q_z."""
        grad = np.zeros((len(q), 3))
        grad[:, 2] = 1.0
        return q[:, 2], grad, np.zeros((len(q), 3, 3))


def rectangles_overlap(a, b):
    """The bounding box ((u0, v0), (u1, v1)), in a's (u, v), of the overlap of two coplanar trimmed rectangles
    (strips, half-planes, the whole plane), or None when they share no area (they meet along an edge at most).

    b's rectangle, mapped into a's plane, is clipped by a's (Sutherland-Hodgman), both cut at a reach that holds
    every corner of the lines bounding them (OVERLAP_REACH, OVERLAP_ANGLE); the overlap shares an area when its
    area exceeds its diameter times OVERLAP_WIDTH x the reach.
    """
    rot = a.frame.rotation.T @ b.frame.rotation                 # b's local axes in a's coordinates
    axes = (rot[:2, 0], rot[:2, 1])
    offset = a.frame.local_of(b.frame.origin)[:2]
    ranges_a, ranges_b = (a.u_range, a.v_range), (b.u_range, b.v_range)
    lines = []                                                  # (normal, level): normal . x = level, in a's (u, v)
    for j in range(2):
        normal = np.eye(2)[j]
        lines += [(normal, x) for x in ranges_a[j] if math.isfinite(x)]
        lines += [(axes[j], x + axes[j] @ offset) for x in ranges_b[j] if math.isfinite(x)]
    far = max([1.0] + [abs(level) for _, level in lines])
    for i, (n1, c1) in enumerate(lines):
        for n2, c2 in lines[i + 1:]:
            det = n1[0] * n2[1] - n1[1] * n2[0]
            if abs(det) > OVERLAP_ANGLE:
                corner = np.array([c1 * n2[1] - c2 * n1[1], n1[0] * c2 - n2[0] * c1]) / det
                far = max(far, float(np.abs(corner).max()))
    reach = OVERLAP_REACH * far
    reach_b = reach + float(np.abs(offset).max())
    (bu0, bu1), (bv0, bv1) = ((max(lo, -2 * reach_b), min(hi, 2 * reach_b)) for lo, hi in ranges_b)
    polygon = [offset + u * axes[0] + v * axes[1] for u, v in ((bu0, bv0), (bu1, bv0), (bu1, bv1), (bu0, bv1))]
    for j in range(2):
        lo, hi = max(ranges_a[j][0], -reach), min(ranges_a[j][1], reach)
        polygon = clipped(polygon, j, lo, 1.0)
        polygon = clipped(polygon, j, hi, -1.0)
        if len(polygon) < 3:
            return None
    pts = np.array(polygon)
    x, y = pts[:, 0], pts[:, 1]
    area = 0.5 * abs(float(x @ np.roll(y, -1) - y @ np.roll(x, -1)))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    if not area > OVERLAP_WIDTH * reach * float(np.linalg.norm(hi - lo)):
        return None
    return lo, hi


def clipped(polygon, axis, level, side):
    """The convex polygon (a list of points (2,)) clipped to side * (x[axis] - level) >= 0 (Sutherland-Hodgman)."""
    out = []
    for k, p in enumerate(polygon):
        q = polygon[k - 1]
        dp, dq = side * (p[axis] - level), side * (q[axis] - level)
        if (dp >= 0) != (dq >= 0):
            out.append(q + (p - q) * (dq / (dq - dp)))
        if dp >= 0:
            out.append(p)
    return out


register(Plane, PlaneTraits())
