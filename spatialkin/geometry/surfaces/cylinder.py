"""The circular cylinder (optionally trimmed along its axis) and its traits."""
import math

import numpy as np

from ...kernels.geometry import surfaces as ks
from ..placement import on_line, parallel
from ..traits import ANGLE, LENGTH, TRANSLATION, SurfaceTraits, register
from .base import Surface, check_length, check_range, own_axis, quadric_jets
from ..trims import TURN, angle_range, angular_groups


class Cylinder(Surface):
    """Circular cylinder of the given radius about the local z axis: M(u, v) = frame(r cos u, r sin u, v).

    u is the angle round the axis (radians), v the length along it (the user's unit); v_range optionally trims
    the cylinder along its axis, u_range round it (a half cylinder, a strip of a CAD face).

    Parameters
    ----------
    radius : float
        r (the user's length unit), > 0.
    frame : Frame, optional
        Placement: origin on the axis, local z along it (default: the global axes).
    v_range : (float, float), optional
        Trim (min, max) of v, either end possibly infinite; None (default): unbounded.
    u_range : (float, float), optional
        Trim (min, max) of the angle u, radians, finite, at most a full turn wide (any start: (-1, 1) and
        (2 pi - 1, 2 pi + 1) are the same strip); None (default): the full turn.

    Attributes
    ----------
    radius : float
    frame : Frame
    u_range, v_range : (float, float)
        The trims ((-inf, inf) where there is none).

    Raises
    ------
    ValueError
        Naming `radius` (not a positive finite number, or outside the supported lengths [1e-32, 1e32]),
        `v_range` (not a pair min < max within them) or `u_range` (not finite, or wider than a full turn).
    TypeError
        Naming `radius` when it is not a real number (a str, a bool, None); when `frame` is not a
        spatialkin.Frame.

    Examples
    --------
    >>> import numpy as np
    >>> import spatialkin as sk
    >>> cylinder = sk.Cylinder(0.5, sk.Frame((1.0, 0.0, 0.0)), v_range=(-2.0, 2.0))
    >>> np.allclose(cylinder.point(np.pi / 2, 1.0), (1.0, 0.5, 1.0))
    True
    >>> round(float(cylinder.distance([1.0, 0.0, 7.0])), 6)    # on the axis: r from the (untrimmed) surface
    0.5
    >>> half = sk.Cylinder(1.0, v_range=(0.0, 4.0), u_range=(0.0, np.pi))      # the half y >= 0
    >>> curve, = sk.intersect(half, sk.Plane(sk.Frame((0.0, 0.0, 2.0))))
    >>> curve.status, round(curve.length, 9)
    ('boundary', 3.141592654)
    """

    def __init__(self, radius, frame=None, v_range=None, u_range=None):
        self.radius = check_length("radius", radius)
        turn = angle_range("u_range", u_range)
        super().__init__(frame, self.radius, 0.0, v_range=v_range,
                         region=angular_groups(("u_min", "u_max"), TURN, turn),
                         shown=None if turn is None else (turn, tuple(check_range("v_range", v_range, length=True))))

    def with_frame(self, frame):
        return Cylinder(self.radius, frame, self.v_range, self.u_range if self.region else None)

    def _describe(self):
        return f"radius={self.radius}, v_range={self.v_range}" + (f", u_range={self.u_range}" if self.region else "")


class CylinderTraits(SurfaceTraits):
    """u a periodic angle, v the length along the local z axis (trimmed or unbounded); a surface of revolution
    about its axis made of straight lines along it."""

    code = geometry = ks.CYLINDER
    name = "cylinder"
    rank = 1                        # ruled: g is quadratic along its lines, the search prunes best (below)
    units = (ANGLE, LENGTH)
    periodic = (True, False)
    parameter_axes = (None, 2)
    compact = False
    recharts = False
    area_watch = False
    has_parallels = True

    def size(self, surface):
        return surface.radius

    def extent(self, surface):
        v0, v1 = surface.v_range
        return max(surface.size, v1 - v0)

    def bounding_ball(self, surface):
        v0, v1 = surface.v_range
        if not (math.isfinite(v0) and math.isfinite(v1)):
            return None
        half = 0.5 * (v1 - v0)
        return surface.frame.global_of([0.0, 0.0, 0.5 * (v0 + v1)]), math.hypot(surface.radius, half)

    def asymptote(self, surface):
        if self.bounding_ball(surface) is not None:
            return None
        return surface.frame.rotation[:, 2], 0.0, surface.radius, surface.frame.origin

    def symmetry(self, surface):
        return own_axis(surface)

    def ruling(self, surface):
        return TRANSLATION, surface.frame.rotation[:, 2]

    def keeps_translation(self, surface, direction, same):
        return parallel(direction, surface.frame.rotation[:, 2], same)

    def same_surface(self, a, b, tol, same):
        za = a.frame.rotation[:, 2]
        return (abs(a.radius - b.radius) <= tol and parallel(za, b.frame.rotation[:, 2], same)
                and on_line(b.frame.origin, a.frame.origin, za, tol))

    def trims_overlap(self, a, b):
        return axial_trims_overlap(a, b)

    def implicit_jets(self, surface, q):
        """F = x^2 + y^2 - r^2."""
        value = q[:, 0] ** 2 + q[:, 1] ** 2 - surface.radius ** 2
        return quadric_jets(q, np.array([2.0, 2.0, 0.0]), value)


def axial_trims_overlap(a, b):
    """For one cylinder or cone given twice: the axial trims overlap (b's rim mapped to a's axial coordinate)."""
    flip = float(a.frame.rotation[:, 2] @ b.frame.rotation[:, 2]) < 0
    lo_b, hi_b = b.v_range
    shift = float(a.frame.local_of(b.frame.origin)[2])
    lo_b, hi_b = (shift - hi_b, shift - lo_b) if flip else (shift + lo_b, shift + hi_b)
    return max(lo_b, a.v_range[0]) < min(hi_b, a.v_range[1])


register(Cylinder, CylinderTraits())
