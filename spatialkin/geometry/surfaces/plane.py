"""The plane (optionally trimmed to a rectangle) and its traits."""
import math

import numpy as np

from ...kernels.geometry import surfaces as ks
from ..placement import parallel
from ..traits import LENGTH, NORMAL, SurfaceTraits, register
from .base import Surface, check_positive, check_range
from ..trims import RADIUS, level_groups
from ..._lib.validation import check_nonnegative

#: Coplanar rectangles are compared on a grid of this many samples per side of one of them.
OVERLAP_SAMPLES = 64
#: Infinite trims are clipped at this many times the other rectangle's magnitude for that grid.
OVERLAP_REACH = 1e6


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
        Naming `u_range` or `v_range` when it is not a pair min < max (no NaN), `radius` when not positive and
        finite, `inner_radius` when not in [0, radius).
    TypeError
        When `frame` is not a spatialkin.Frame.

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
        self.radius = None if radius is None else check_positive("radius", radius)
        self.inner_radius = None if inner_radius is None else check_nonnegative("inner_radius", inner_radius)
        if self.inner_radius is not None and self.radius is not None and not self.inner_radius < self.radius:
            raise ValueError(f"inner_radius must be less than radius, got {self.inner_radius} and {self.radius}")
        u_range, v_range = check_range("u_range", u_range), check_range("v_range", v_range)
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
        return surface.frame.to_global([0.5 * (u0 + u1), 0.5 * (v0 + v1), 0.0]), 0.5 * math.hypot(u1 - u0, v1 - v0)

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
        """b's rectangle, turned in a's plane: its bounding box first, then a grid of its inside."""
        corners = []
        (u0, u1), (v0, v1) = b.u_range, b.v_range
        big = 1e300
        for u in (max(u0, -big), min(u1, big)):
            for v in (max(v0, -big), min(v1, big)):
                corners.append(b.frame.to_global([u, v, 0.0]))
        local = a.frame.to_local(np.array(corners))[:, :2]
        lo, hi = local.min(axis=0), local.max(axis=0)
        if (lo[0] >= a.u_range[1] or hi[0] <= a.u_range[0] or lo[1] >= a.v_range[1] or hi[1] <= a.v_range[0]):
            return False
        return rectangles_overlap(a, b)

    def implicit_jets(self, surface, q):
        """F = q_z."""
        grad = np.zeros((len(q), 3))
        grad[:, 2] = 1.0
        return q[:, 2], grad, np.zeros((len(q), 3, 3))


def rectangles_overlap(a, b, samples=OVERLAP_SAMPLES):
    """Two coplanar trimmed rectangles share an area: a grid of b's rectangle has a point strictly inside a's."""
    (u0, u1), (v0, v1) = b.u_range, b.v_range
    big = OVERLAP_REACH * max(1.0, *[abs(x) for x in (*a.u_range, *a.v_range) if np.isfinite(x)])
    u0, u1, v0, v1 = max(u0, -big), min(u1, big), max(v0, -big), min(v1, big)
    uu, vv = np.meshgrid(np.linspace(u0, u1, samples)[1:-1], np.linspace(v0, v1, samples)[1:-1])
    pts = b.frame.to_global(np.stack([uu.ravel(), vv.ravel(), np.zeros(uu.size)], axis=1))
    loc = a.frame.to_local(pts)
    inside = ((loc[:, 0] > a.u_range[0]) & (loc[:, 0] < a.u_range[1]) & (loc[:, 1] > a.v_range[0])
              & (loc[:, 1] < a.v_range[1]))
    return bool(inside.any())


register(Plane, PlaneTraits())
