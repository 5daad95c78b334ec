"""The circular double cone (optionally trimmed along its axis) and its traits."""
import math

import numpy as np

from ...kernels.geometry import surfaces as ks
from ..placement import parallel
from ..traits import ANGLE, LENGTH, SCALING, SurfaceTraits, register
from .base import Surface, check_positive, check_range, own_axis, quadric_jets
from ..trims import TURN, angle_range, angular_groups
from .cylinder import axial_trims_overlap


class Cone(Surface):
    """Circular double cone with its apex at frame.origin about the local z axis.

    M(u, v) = frame(v tan(a) cos u, v tan(a) sin u, v), a the half angle: u the angle round the axis (radians),
    v the height along it (the user's length unit; v < 0 is the other nappe). The apex (v = 0) is a singular
    point of the surface. v_range optionally trims it along the axis, u_range round it. tan(a) is the double
    ``slope = math.tan(a)`` (within an ulp of the true tangent, which no double holds for a != 0): every point,
    distance and certificate is of the cone of that slope (``sk.Cone(math.atan(0.75))`` has slope 0.75 exactly).

    Parameters
    ----------
    half_angle : float
        a, the angle between the axis and the generatrices, radians in (0, pi/2).
    frame : Frame, optional
        Placement: origin at the apex, local z along the axis (default: the global axes).
    v_range : (float, float), optional
        Trim (min, max) of v, either end possibly infinite; None (default): both nappes, unbounded.
    u_range : (float, float), optional
        Trim (min, max) of the angle u, radians, finite, at most a full turn wide; on both nappes the same u
        (the lower nappe's points then lie opposite, at the angle u + pi). None (default): the full turn.

    Attributes
    ----------
    half_angle : float
    slope : float
        math.tan(half_angle): the cone's radius per unit of height, as every computation reads it.
    frame : Frame
    u_range, v_range : (float, float)
        The trims ((-inf, inf) where there is none).

    Raises
    ------
    ValueError
        Naming `half_angle` (not in (0, pi/2)), `v_range` (not a pair min < max within the supported lengths,
        1e32 of 0) or `u_range` (not finite, or wider than a full turn).
    TypeError
        Naming `half_angle` when it is not a real number (a str, a bool, None); when `frame` is not a
        spatialkin.Frame.

    Examples
    --------
    >>> import numpy as np
    >>> import spatialkin as sk
    >>> cone = sk.Cone(np.pi / 4, v_range=(0.0, 2.0))
    >>> np.allclose(cone.point(0.0, 1.0), (1.0, 0.0, 1.0))
    True
    >>> round(float(cone.distance([0.0, 0.0, 1.0])), 6)     # on the axis at height 1: sin(a) from the cone
    0.707107
    >>> sk.Cone(2.0)
    Traceback (most recent call last):
    ...
    ValueError: half_angle must lie in (0, pi/2), got 2.0
    """

    def __init__(self, half_angle, frame=None, v_range=None, u_range=None):
        a = check_positive("half_angle", half_angle, strict=True)
        if a >= math.pi / 2:
            raise ValueError(f"half_angle must lie in (0, pi/2), got {a}")
        self.half_angle = a
        self.slope = math.tan(a)
        turn = angle_range("u_range", u_range)
        super().__init__(frame, 0.0, self.slope, v_range=v_range,
                         region=angular_groups(("u_min", "u_max"), TURN, turn, nappes=True),
                         shown=None if turn is None else (turn, tuple(check_range("v_range", v_range, length=True))))

    def with_frame(self, frame):
        return Cone(self.half_angle, frame, self.v_range, self.u_range if self.region else None)

    def _describe(self):
        return f"half_angle={self.half_angle}, v_range={self.v_range}" + (f", u_range={self.u_range}"
                                                                          if self.region else "")


class ConeTraits(SurfaceTraits):
    """u a periodic angle, v the length along the local z axis; the chart collapses at the apex (v = 0), a
    singular point of the surface (the area watch is on); its length comes only from its trims; made of straight
    lines through the apex."""

    code = geometry = ks.CONE
    name = "cone"
    rank = 2                        # ruled, as the cylinder
    units = (ANGLE, LENGTH)
    periodic = (True, False)
    parameter_axes = (None, 2)
    compact = False
    recharts = False
    area_watch = True
    has_parallels = True

    def size(self, surface):
        """The slant length to the farther rim when trimmed on both sides, else 1."""
        lo, hi = surface.v_range
        if math.isfinite(lo) and math.isfinite(hi):
            return max(abs(lo), abs(hi)) * math.sqrt(1.0 + surface.data[ks.P1] * surface.data[ks.P1])
        return 1.0

    def scale_length(self, surface):
        lo, hi = surface.v_range
        return float(self.size(surface)) if math.isfinite(lo) and math.isfinite(hi) else None

    def extent(self, surface):
        v0, v1 = surface.v_range
        return max(abs(v0), abs(v1)) * math.sqrt(1.0 + surface.data[ks.P1] ** 2)

    def bounding_ball(self, surface):
        v0, v1 = surface.v_range
        if not (math.isfinite(v0) and math.isfinite(v1)):
            return None
        half = 0.5 * (v1 - v0)
        t = math.tan(surface.half_angle)
        return surface.frame.global_of([0.0, 0.0, 0.5 * (v0 + v1)]), math.hypot(t * max(abs(v0), abs(v1)), half)

    def asymptote(self, surface):
        if self.bounding_ball(surface) is not None:
            return None
        return surface.frame.rotation[:, 2], surface.half_angle, 0.0, surface.frame.origin

    def trim_slack(self, surface, slack):
        return slack, slack * math.cos(surface.half_angle)

    def apexes(self, surface):
        return [0.0]

    def symmetry(self, surface):
        return own_axis(surface)

    def ruling(self, surface):
        return SCALING, surface.frame.origin

    def cross_section(self, v_lo, v_hi):
        """Halfway along the longer side of the apex."""
        return 0.5 * max(v_lo, v_hi, key=abs)

    def same_surface(self, a, b, tol, same):
        return (abs(a.half_angle - b.half_angle) <= same
                and parallel(a.frame.rotation[:, 2], b.frame.rotation[:, 2], same)
                and np.linalg.norm(a.frame.origin - b.frame.origin) <= tol)

    def trims_overlap(self, a, b):
        return axial_trims_overlap(a, b)

    def implicit_jets(self, surface, q):
        """F = x^2 + y^2 - tan(a)^2 z^2 (the double cone)."""
        t2 = math.tan(surface.half_angle) ** 2
        value = q[:, 0] ** 2 + q[:, 1] ** 2 - t2 * q[:, 2] ** 2
        return quadric_jets(q, np.array([2.0, 2.0, -2.0 * t2]), value)


register(Cone, ConeTraits())
