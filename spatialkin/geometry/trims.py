"""The trims of CAD faces that are not a range of a length: an angular range about a surface's axis (u of a
cylinder, cone, sphere or torus), a torus's tube angle v, a sphere's latitude v, and a plane bounded by a circle
or an annulus.

Each trim edge is one *limit*: a function of the point that is >= 0 on the trim's side of the edge, 0 on the
edge, and 1-Lipschitz in the point (its gradient has norm <= 1), so that along a curve parametrised by arc
length it changes by at most the arc length travelled. An angular range [lo, hi] of width <= pi is the
intersection of two half-planes through the axis (u >= lo within a half turn, u <= hi within a half turn); a
wider one is their union. A surface's ``region`` is a tuple of groups of limits: a point is inside when, in
every group, at least one limit is >= 0.

The limits of an angle about the local z axis: lo <= u holds within a half turn where
cos(lo) y - sin(lo) x >= 0, and u <= hi where sin(hi) x - cos(hi) y >= 0 (the local coordinates of the point).
A cone's lower nappe (z < 0) sees its angle u at the point's angle plus pi: the limits are multiplied by the
sign of z there. A torus's tube angle v is the angle of (rho - R, z) in the meridian half-plane (rho the distance
from the axis); a sphere's latitude v lies in [lo, hi] where R sin(lo) <= z <= R sin(hi).

The tracer follows the untrimmed curve (trims that are ranges of a length, a plane's rectangle and a
cylinder's or cone's axial range, are its own events); spatialkin.tracing.curve.clip then cuts each component at the
crossings of these limits.
"""
import dataclasses
import math

import numpy as np

from .._lib.validation import TOO_LARGE

#: A range of an angle at least this close to a full turn (relative) is no trim.
FULL_TURN_SLACK = 1e-12
#: An angular range at most this wide (radians) is also bounded by the half-plane about its middle.
NARROW = 0.5 * math.pi

TURN, TUBE, HEIGHT, RADIUS = "turn", "tube", "height", "radius"


@dataclasses.dataclass(frozen=True)
class Limit:
    """One trim edge as a 1-Lipschitz function of the point, >= 0 on the inside.

    kind is TURN (an angle about the local z axis), TUBE (a torus's tube angle), HEIGHT (a local coordinate, z
    unless axis says) or RADIUS (the distance from the local z axis); value the angle or the length of the edge;
    lower True when the inside is above it. name: the edge as a user names it ('u_min', 'u_max', 'v_min', 'v_max',
    'rim', 'inner rim').
    """

    name: str
    kind: str
    value: float
    lower: bool
    nappes: bool = False            # TURN on a cone: the angle of the lower nappe's points is u + pi
    major: float = 0.0              # TUBE: the torus's major radius
    axis: int = 2                   # HEIGHT: the local axis it is read on (0 x, 1 y, 2 z)

    def __call__(self, local):
        """Values (N,) at local points (N, 3)."""
        x, y, z = local[:, 0], local[:, 1], local[:, 2]
        if self.kind == TURN:
            c, s = math.cos(self.value), math.sin(self.value)
            out = c * y - s * x if self.lower else s * x - c * y
            return out * np.where(z < 0.0, -1.0, 1.0) if self.nappes else out
        if self.kind == TUBE:
            c, s = math.cos(self.value), math.sin(self.value)
            a = np.hypot(x, y) - self.major
            return c * z - s * a if self.lower else s * a - c * z
        level = local[:, self.axis] if self.kind == HEIGHT else np.hypot(x, y)
        return level - self.value if self.lower else self.value - level

    def on_edge_side(self, local):
        """(N,) bool: local points (N, 3) on the side of the edge itself where the limit's zero set is a line
        through the axis (TURN) or the tube's centre (TUBE): the ray at its angle, not the opposite one (where the
        other limit's edge, or no edge, lies); True for the other kinds."""
        x, y, z = local[:, 0], local[:, 1], local[:, 2]
        c, s = math.cos(self.value), math.sin(self.value)
        if self.kind == TURN:
            along = c * x + s * y
            return (along * np.where(z < 0.0, -1.0, 1.0) if self.nappes else along) >= 0.0
        if self.kind == TUBE:
            return c * (np.hypot(x, y) - self.major) + s * z >= 0.0
        return np.ones(len(local), dtype=bool)


def angle_range(name, value):
    """(lo, hi) of an angular trim, checked: finite, lo < hi, at most a full turn; None for None or a full
    turn. ValueError naming the argument otherwise."""
    if value is None:
        return None
    try:
        lo, hi = (float(x) for x in value)
    except OverflowError:
        raise ValueError(f"{name} must be finite angles in radians, got {TOO_LARGE}") from None
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (min, max) of angles in radians, got {value!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise ValueError(f"{name} must be finite angles in radians, got ({lo}, {hi})")
    if not lo < hi:
        raise ValueError(f"{name} must satisfy min < max, got ({lo}, {hi})")
    width = hi - lo
    if width > 2.0 * math.pi * (1.0 + FULL_TURN_SLACK):
        raise ValueError(f"{name} must span at most a full turn (2 pi), got a width of {width!r}")
    return None if width >= 2.0 * math.pi * (1.0 - FULL_TURN_SLACK) else (lo, hi)


def angular_groups(names, kind, lo_hi, **extra):
    """The groups of limits of an angle in [lo, hi] (kind TURN or TUBE): two groups of one limit each for a
    width of at most a half turn (both half-planes), one group of both (either) for a wider range. A range of at
    most a quarter turn gets a third group, the half-plane of the angles within a quarter turn of its middle
    (named ``<u or v>_range``): the two edges' half-planes also hold the opposite wedge, where they fall below
    zero only by about the distance from the axis times the sine of half the width, within any slack for a
    narrow range; that half-plane is below zero there by at least the distance times the cosine."""
    if lo_hi is None:
        return ()
    lo, hi = lo_hi
    low = Limit(names[0], kind, lo, True, **extra)
    high = Limit(names[1], kind, hi, False, **extra)
    if hi - lo > math.pi:
        return ((low, high),)
    if hi - lo > NARROW:
        return ((low,), (high,))
    side = Limit(names[0][0] + "_range", kind, 0.5 * (lo + hi) - 0.5 * math.pi, True, **extra)
    return ((low,), (high,), (side,))


def level_groups(names, kind, lo_hi, axis=2):
    """The groups of a range of a level (kind HEIGHT on a local axis, or RADIUS), each finite end one group of one
    limit."""
    lo, hi = lo_hi
    groups = []
    if math.isfinite(lo):
        groups.append((Limit(names[0], kind, lo, True, axis=axis),))
    if math.isfinite(hi):
        groups.append((Limit(names[1], kind, hi, False, axis=axis),))
    return tuple(groups)


def region_values(surface, points):
    """(N, G): each group's value (its largest limit) at global points (N, 3); inside where all are >= 0."""
    local = surface.frame.local_of(np.asarray(points, dtype=float).reshape(-1, 3))
    region = surface.region
    if not region:
        return np.zeros((len(local), 0))
    return np.stack([np.max([limit(local) for limit in group], axis=0) for group in region], axis=1)


def limits(surface):
    """Every limit of the surface's region, once each."""
    return tuple(limit for group in surface.region for limit in group)


def inside_region(surface, points, slack=0.0):
    """(N,) bool: global points (N, 3) inside the surface's region (within slack, a length)."""
    values = region_values(surface, points)
    return np.all(values >= -slack, axis=1)
