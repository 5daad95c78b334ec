"""The sphere and its traits."""
import math

import numpy as np

from ..frame import Frame
from ...kernels.geometry import surfaces as ks
from ..traits import ANGLE, FULL_TURN, POINT, SurfaceTraits, register
from .base import Surface, check_length, check_range, quadric_jets, trims_described, trims_given
from ..trims import FULL_TURN_SLACK, HEIGHT, TURN, angle_range, angular_groups, level_groups

#: The latitudes of the poles, where the chart (u longitude, v latitude) collapses.
POLES = (-0.5 * math.pi, 0.5 * math.pi)


class Sphere(Surface):
    """Sphere of the given radius centred at frame.origin; local z is the pole axis of (u, v).

    M(u, v) = frame(R cos v cos u, R cos v sin u, R sin v): u the longitude, v the latitude (radians). In the
    looper drive it is the surface of the ball centre about the rocker centre, R the rocker length [1]_.

    Parameters
    ----------
    radius : float
        R (the user's length unit), > 0.
    frame : Frame, optional
        Placement: origin at the centre, local z the pole axis of (u, v) (default: the global axes).
    u_range : (float, float), optional
        Trim (min, max) of the longitude u, radians, finite, at most a full turn wide. None (default): the full
        turn.
    v_range : (float, float), optional
        Trim (min, max) of the latitude v, radians within [-pi/2, pi/2] (a spherical cap, a zone). None
        (default): pole to pole.

    Attributes
    ----------
    radius : float
    frame : Frame
    center : ndarray, shape (3,)
        The centre, frame.origin.
    u_range, v_range : (float, float)
        The trims ((-inf, inf) where there is none).

    Raises
    ------
    ValueError
        Naming `radius` when it is not a positive finite number or lies outside the supported lengths
        [1e-32, 1e32], `u_range` when not finite or wider than a full turn, `v_range` when not a pair of latitudes
        min < max within [-pi/2, pi/2].
    TypeError
        Naming `radius` when it is not a real number (a str, a bool, None); when `frame` is not a
        spatialkin.Frame.

    References
    ----------
    .. [1] "Investigation of the trajectories of characteristic points of spatial mechanisms of technological
       machines of the light industry" (in Ukrainian).

    Examples
    --------
    >>> import numpy as np
    >>> import spatialkin as sk
    >>> sphere = sk.Sphere(2.0, sk.Frame((1.0, 0.0, 0.0)))
    >>> np.allclose(sphere.point(0.0, np.pi / 2), (1.0, 0.0, 2.0))      # the north pole
    True
    >>> sphere.center.tolist()
    [1.0, 0.0, 0.0]
    >>> round(float(sphere.distance([1.0, 0.0, 5.0])), 6)
    3.0
    """

    def __init__(self, radius, frame=None, u_range=None, v_range=None):
        self.radius = check_length("radius", radius)
        turn, zone = angle_range("u_range", u_range), latitudes(v_range)
        heights = None if zone is None else tuple(self.radius * math.sin(x) if abs(x) < POLES[1] else x * math.inf
                                                  for x in zone)
        region = angular_groups(("u_min", "u_max"), TURN, turn)
        region += () if heights is None else level_groups(("v_min", "v_max"), HEIGHT, heights)
        super().__init__(frame, self.radius, region=region,
                         shown=None if not region else tuple(t or (-math.inf, math.inf) for t in (turn, zone)))

    @property
    def center(self):
        """The centre (3,), frame.origin."""
        return self.frame.origin

    def with_frame(self, frame):
        return Sphere(self.radius, frame, *trims_given(self))

    def _describe(self):
        return f"radius={self.radius}" + trims_described(self)


def latitudes(v_range):
    """(lo, hi) of a sphere's latitude trim, checked (within the poles); None for None or pole to pole."""
    if v_range is None:
        return None
    lo, hi = check_range("v_range", v_range)
    if lo < POLES[0] * (1.0 + FULL_TURN_SLACK) or hi > POLES[1] * (1.0 + FULL_TURN_SLACK):
        raise ValueError(f"v_range must be latitudes within [-pi/2, pi/2], got ({lo}, {hi})")
    lo, hi = max(lo, POLES[0]), min(hi, POLES[1])
    return None if (lo, hi) == POLES else (lo, hi)


class SphereTraits(SurfaceTraits):
    """Compact; u a periodic angle, v the latitude. Its chart collapses at the poles of a smooth surface, so the
    tracer turns the chart at every segment start (``rechart``) and never reaches them; it turns about any line
    through its centre."""

    code = geometry = ks.SPHERE
    name = "sphere"
    rank = 3                        # after the ruled kinds: P = cylinder or cone takes 0.6-0.7x the boxes
    units = (ANGLE, ANGLE)
    periodic = (True, False)
    parameter_axes = (None, None)
    compact = True
    recharts = True
    area_watch = False              # re-charted: its poles are never on a segment
    has_parallels = True

    def size(self, surface):
        return surface.radius

    def bounding_ball(self, surface):
        return surface.frame.origin.copy(), surface.radius

    def natural_domain(self, surface):
        return FULL_TURN, POLES

    def rechart(self, data, point, tangent, bend=None):
        """Sphere data with its chart turned so that point is at (u, v) = (0, 0), the equator along the tangent or,
        given the curvature vector bend (C'') of a curve bending round a small circle, through its centre (see
        spatialkin.kernels.geometry.surfaces.recharted_sphere)."""
        new = np.empty_like(data)
        ks.recharted_sphere(data, np.ascontiguousarray(point, dtype=float),
                            np.ascontiguousarray(tangent, dtype=float),
                            np.zeros(3) if bend is None else np.ascontiguousarray(bend, dtype=float), new)
        new.flags.writeable = False     # read-only as every Surface's data: one compiled specialisation of the kernels
        return new

    def poles(self, surface):
        return list(POLES)

    def general_chart(self, p, q):
        """The sphere with its poles as far from Q as the frame's axes allow (fewer rings round them): of the
        frame's axes, the first whose poles lie farther from Q than every earlier one's (by a relative 1e-9)."""
        axes = p.frame.rotation.T
        poles = (p.frame.origin + np.concatenate([axes, -axes]) * p.radius)
        d = np.minimum(*q.distance(poles).reshape(2, 3)).tolist()
        best, score = 2, -1.0
        for k in range(3):
            if d[k] > score * (1 + 1e-9):
                best, score = k, d[k]
        return p if best == 2 else p.with_frame(Frame.from_z_axis(p.frame.origin, axes[best]))

    def symmetry(self, surface):
        return POINT, surface.frame.origin

    def aligned(self, surface, axis):
        return surface.with_frame(Frame.from_z_axis(surface.frame.origin, axis[1]))

    def same_surface(self, a, b, tol, same):
        return np.linalg.norm(a.frame.origin - b.frame.origin) <= tol and abs(a.radius - b.radius) <= tol

    def implicit_jets(self, surface, q):
        """F = |q|^2 - R^2."""
        value = q[:, 0] ** 2 + q[:, 1] ** 2 + q[:, 2] ** 2 - surface.radius ** 2
        return quadric_jets(q, np.array([2.0, 2.0, 2.0]), value)


register(Sphere, SphereTraits())
