"""The torus (ring, horn or spindle) and its traits."""
import math

import numpy as np

from ...kernels.geometry import surfaces as ks
from ..placement import parallel
from ..traits import ANGLE, SurfaceTraits, register
from .base import Surface, check_length, own_axis, trims_described, trims_given
from ..trims import TUBE, TURN, angle_range, angular_groups


class Torus(Surface):
    """Torus about the local z axis: ring (minor < major), horn (minor = major) or spindle (minor > major).

    M(u, v) = frame((R + r cos v) cos u, (R + r cos v) sin u, r sin v), u round the axis and v round the tube
    (radians). In the looper drive it is the surface of the coupler's ball centre: R the crank radius, r the
    coupler length [1]_.

    Parameters
    ----------
    major_radius : float
        R, distance of the tube's centre circle from the axis (the user's length unit), > 0.
    minor_radius : float
        r, radius of the tube (same unit), > 0.
    frame : Frame, optional
        Placement: origin at the centre, local z along the axis (default: the global axes).
    u_range, v_range : (float, float), optional
        Trims (min, max) of the angles u (round the axis) and v (round the tube), radians, finite, each at most
        a full turn wide (a quarter torus, a CAD face of a torus). Only a ring torus takes trims. None
        (default): the full turn.

    Attributes
    ----------
    major_radius, minor_radius : float
    frame : Frame
    shape : str
        'ring', 'horn' or 'spindle'.
    u_range, v_range : (float, float)
        The trims ((-inf, inf) where there is none).

    Raises
    ------
    ValueError
        Naming `major_radius` or `minor_radius` when it is not a positive finite number or lies outside the
        supported lengths [1e-32, 1e32], `u_range` or `v_range` when not finite or wider than a full turn, or set
        on a horn or spindle torus.
    TypeError
        Naming `major_radius` or `minor_radius` when it is not a real number (a str, a bool, None); when `frame`
        is not a spatialkin.Frame.

    References
    ----------
    .. [1] "Investigation of the trajectories of characteristic points of spatial mechanisms of technological
       machines of the light industry" (in Ukrainian).

    Examples
    --------
    >>> import numpy as np
    >>> import spatialkin as sk
    >>> torus = sk.Torus(2.0, 0.5, sk.Frame((0.0, 0.0, 1.0)))
    >>> torus.shape
    'ring'
    >>> np.allclose(torus.point(np.pi / 2, np.pi / 2), (0.0, 2.0, 1.5))
    True
    >>> round(float(torus.distance([0.0, 0.0, 1.0])), 6)     # the centre lies R - r from the tube
    1.5
    >>> sk.Torus(2.0, -0.5)
    Traceback (most recent call last):
    ...
    ValueError: minor_radius must be a positive finite number, got -0.5
    """

    def __init__(self, major_radius, minor_radius, frame=None, u_range=None, v_range=None):
        self.major_radius = check_length("major_radius", major_radius)
        self.minor_radius = check_length("minor_radius", minor_radius)
        turns = angle_range("u_range", u_range), angle_range("v_range", v_range)
        if turns != (None, None) and self.minor_radius >= self.major_radius:
            name = "u_range" if turns[0] is not None else "v_range"
            raise ValueError(f"{name} trims only a ring torus (minor_radius < major_radius), got major_radius "
                             f"{self.major_radius} and minor_radius {self.minor_radius}")
        region = (angular_groups(("u_min", "u_max"), TURN, turns[0])
                  + angular_groups(("v_min", "v_max"), TUBE, turns[1], major=self.major_radius))
        super().__init__(frame, self.major_radius, self.minor_radius, region=region,
                         shown=None if not region else tuple(t or (-math.inf, math.inf) for t in turns))

    @property
    def shape(self):
        """'ring' (minor < major radius), 'horn' (equal) or 'spindle' (minor > major)."""
        if self.minor_radius < self.major_radius:
            return "ring"
        return "horn" if self.minor_radius == self.major_radius else "spindle"

    def with_frame(self, frame):
        return Torus(self.major_radius, self.minor_radius, frame, *trims_given(self))

    def _describe(self):
        return f"major_radius={self.major_radius}, minor_radius={self.minor_radius}" + trims_described(self)


class TorusTraits(SurfaceTraits):
    """Compact, both parameters periodic angles; a horn or spindle torus collapses to its apexes on the axis
    (the area watch is on for every torus)."""

    code = geometry = ks.TORUS
    name = "torus"
    rank = 0                        # no collapsing chart: the first choice of parametrised surface
    units = (ANGLE, ANGLE)
    periodic = (True, True)
    parameter_axes = (None, None)
    compact = True
    recharts = False
    area_watch = True
    has_parallels = True

    def size(self, surface):
        return surface.major_radius + surface.minor_radius

    def bounding_ball(self, surface):
        return surface.frame.origin.copy(), surface.major_radius + surface.minor_radius

    def apexes(self, surface):
        """The tube's points on the axis (horn, spindle): v = +-acos(-R/r), at pi for the horn."""
        if surface.minor_radius < surface.major_radius:
            return []
        v = math.acos(-surface.major_radius / surface.minor_radius)
        return [v, -v] if v < math.pi else [math.pi, -math.pi]

    def symmetry(self, surface):
        return own_axis(surface)

    def same_surface(self, a, b, tol, same):
        return (abs(a.major_radius - b.major_radius) <= tol and abs(a.minor_radius - b.minor_radius) <= tol
                and parallel(a.frame.rotation[:, 2], b.frame.rotation[:, 2], same)
                and np.linalg.norm(a.frame.origin - b.frame.origin) <= tol)

    def implicit_jets(self, surface, q):
        """F = (|q|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) (both parts of a horn or spindle torus)."""
        r2 = q[:, 0] ** 2 + q[:, 1] ** 2
        big2, small2 = surface.major_radius ** 2, surface.minor_radius ** 2
        s = r2 + q[:, 2] ** 2 + big2 - small2
        value = s * s - 4 * big2 * r2
        grad = 4 * s[:, None] * q
        grad[:, :2] -= 8 * big2 * q[:, :2]
        hess = 4 * s[:, None, None] * np.eye(3) + 8 * q[:, :, None] * q[:, None, :]
        hess[:, 0, 0] -= 8 * big2
        hess[:, 1, 1] -= 8 * big2
        return value, grad, hess


register(Torus, TorusTraits())
